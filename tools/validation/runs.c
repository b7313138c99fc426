/*
 * runs.c -- the engines as child processes (posix_spawn, no shell), and
 * their CSV outputs read back: --trace, --events and carom-box2d's
 * --masses. Formats: docs/scene-format.md and `carom --help`.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "validate.h"

extern char **environ;

const char *const engine_names[ENG_COUNT] = {"carom", "events", "discrete", "box2d",
                                             "box2d-bullets"};

int engine_from_name(const char *name)
{
    int e;
    for (e = 0; e < ENG_COUNT; ++e)
        if (strcmp(name, engine_names[e]) == 0)
            return e;
    return -1;
}

void run_file(char *buf, size_t n, const char *workdir, const vscene *s, int eng,
              const char *kind)
{
    /* Box2D's mass table is the same for both Box2D runs */
    if (strcmp(kind, "masses") == 0)
        eng = ENG_BOX2D;
    snprintf(buf, n, "%s/%s.%s.%s", workdir, s->name, engine_names[eng], kind);
}

/* ---- child processes --------------------------------------------------------------------- */

static int exit_code(int status)
{
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    if (WIFSIGNALED(status))
        return 128 + WTERMSIG(status);
    return 127;
}

/* Start argv with stdout and stderr redirected; returns the pid, or -1
 * with errno set. */
static pid_t spawn(char *const argv[], const char *out_path, const char *err_path)
{
    posix_spawn_file_actions_t fa;
    pid_t pid;
    int rc;
    if (posix_spawn_file_actions_init(&fa) != 0)
        return -1;
    rc = posix_spawn_file_actions_addopen(&fa, 1, out_path ? out_path : "/dev/null",
                                          O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (rc == 0)
        rc = posix_spawn_file_actions_addopen(&fa, 2, err_path ? err_path : "/dev/null",
                                              O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (rc == 0)
        rc = strchr(argv[0], '/') ? posix_spawn(&pid, argv[0], &fa, NULL, argv, environ)
                                  : posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        errno = rc;
        return -1;
    }
    return pid;
}

int spawn_wait(char *const argv[], const char *out_path, const char *err_path)
{
    int status;
    pid_t pid = spawn(argv, out_path, err_path);
    if (pid < 0)
        return 127;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return 127;
    return exit_code(status);
}

int capture_line(char *const argv[], const char *workdir, char *buf, size_t n)
{
    char path[V_PATH_MAX];
    FILE *f;
    int rc;
    buf[0] = '\0';
    snprintf(path, sizeof path, "%s/capture.txt", workdir);
    rc = spawn_wait(argv, path, NULL);
    f = fopen(path, "r");
    if (f) {
        if (fgets(buf, (int)n, f))
            buf[strcspn(buf, "\r\n")] = '\0';
        fclose(f);
    }
    unlink(path);
    return rc == 0 && buf[0] ? 0 : -1;
}

/* ---- reading CSV ------------------------------------------------------------------------- */

/* The whole file, NUL-terminated, or NULL. */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    size_t cap = 1 << 16, n = 0;
    char *buf;
    if (!f)
        return NULL;
    buf = (char *)malloc(cap + 1);
    while (buf) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
        if (n == cap) {
            char *b = (char *)realloc(buf, 2 * cap + 1);
            if (!b) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = b;
            cap *= 2;
        }
    }
    if (buf && ferror(f)) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        *len = n;
    }
    return buf;
}

/* Parse `want` comma-separated numbers of one line starting at *p; *p moves
 * past the line end. Returns 0, or -1 if the line is not exactly that. */
static int csv_numbers(char **p, double *v, int want)
{
    char *s = *p, *end;
    int i;
    for (i = 0; i < want; ++i) {
        v[i] = strtod(s, &end);
        if (end == s || !isfinite(v[i]))
            return -1;
        s = end;
        if (i + 1 < want) {
            if (*s != ',')
                return -1;
            ++s;
        }
    }
    if (*s == '\r')
        ++s;
    if (*s != '\n' && *s != '\0')
        return -1;
    *p = *s ? s + 1 : s;
    return 0;
}

/* Past the header line, which must be `header`. */
static char *after_header(char *text, const char *header)
{
    size_t n = strlen(header);
    if (strncmp(text, header, n) != 0 || (text[n] != '\n' && text[n] != '\r'))
        return NULL;
    text += n;
    if (*text == '\r')
        ++text;
    return text + 1;
}

static int load_trace(const char *path, const vscene *s, trace *tr, char *why, size_t wn)
{
    size_t len;
    char *text = slurp(path, &len), *p;
    long k, row = 0;
    int b;
    const int nb = s->sc.body_count;
    memset(tr, 0, sizeof *tr);
    if (!text) {
        snprintf(why, wn, "cannot read %s", path);
        return -1;
    }
    p = after_header(text, "step,t,body,x,y,angle,vx,vy,omega");
    tr->bodies = nb;
    tr->samples = s->steps + 1;
    tr->t = (double *)malloc((size_t)tr->samples * sizeof *tr->t);
    tr->st = (double *)malloc((size_t)tr->samples * (size_t)(nb > 0 ? nb : 1) * S_FIELDS *
                              sizeof *tr->st);
    if (!p || !tr->t || !tr->st) {
        snprintf(why, wn, "%s: %s", path, p ? "out of memory" : "not a trace (header)");
        free(text);
        return -1;
    }
    for (k = 0; k < tr->samples; ++k)
        for (b = 0; b < nb; ++b, ++row) {
            double v[9];
            if (*p == '\0' || csv_numbers(&p, v, 9) != 0 || v[0] != (double)k ||
                v[2] != (double)b) {
                snprintf(why, wn, "%s: line %ld: %s (want step %ld, body %d)", path, row + 2,
                         *p ? "malformed row" : "ends early", k, b);
                free(text);
                return -1;
            }
            if (b == 0)
                tr->t[k] = v[1];
            memcpy(TRACE_AT(tr, k, b), v + 3, S_FIELDS * sizeof(double));
        }
    if (*p != '\0') {
        snprintf(why, wn, "%s: more rows than %ld steps of %d bodies", path, s->steps, nb);
        free(text);
        return -1;
    }
    free(text);
    return 0;
}

static int load_events(const char *path, const vscene *s, events *ev, char *why, size_t wn)
{
    size_t len, cap = 64;
    char *text = slurp(path, &len), *p;
    int complete;
    memset(ev, 0, sizeof *ev);
    if (!text) {
        snprintf(why, wn, "cannot read %s", path);
        return -1;
    }
    p = after_header(text, "t,body_a,body_b,nx,ny,impulse,approach_speed");
    ev->rows = (event_row *)malloc(cap * sizeof *ev->rows);
    while (p && ev->rows && *p) {
        double v[7];
        event_row *r;
        if (csv_numbers(&p, v, 7) != 0 || v[1] < 0 || v[2] < 0 || v[1] >= s->sc.body_count ||
            v[2] >= s->sc.body_count) {
            snprintf(why, wn, "%s: line %d: malformed row", path, ev->count + 2);
            free(text);
            return -1;
        }
        if ((size_t)ev->count == cap) {
            event_row *bigger = (event_row *)realloc(ev->rows, 2 * cap * sizeof *bigger);
            if (!bigger)
                break;
            ev->rows = bigger;
            cap *= 2;
        }
        r = &ev->rows[ev->count++];
        r->t = v[0];
        r->a = (int)v[1];
        r->b = (int)v[2];
        r->nx = v[3];
        r->ny = v[4];
        r->impulse = v[5];
        r->approach = v[6];
    }
    complete = p && ev->rows && *p == '\0';
    free(text);
    if (!complete) {
        snprintf(why, wn, "%s: %s", path, p ? "out of memory" : "not an events file (header)");
        return -1;
    }
    return 0;
}

static int load_masses(const char *path, vscene *s, char *why, size_t wn)
{
    size_t len;
    char *text = slurp(path, &len), *p;
    int b, nb = s->sc.body_count, complete;
    if (!text) {
        snprintf(why, wn, "cannot read %s", path);
        return -1;
    }
    p = after_header(text, "body,carom_mass,box2d_mass,carom_inertia,box2d_inertia,cx,cy");
    s->b2_mass = (double *)calloc((size_t)(nb > 0 ? nb : 1), sizeof(double));
    s->b2_inertia = (double *)calloc((size_t)(nb > 0 ? nb : 1), sizeof(double));
    for (b = 0; p && s->b2_mass && s->b2_inertia && b < nb; ++b) {
        double v[7];
        if (csv_numbers(&p, v, 7) != 0 || v[0] != (double)b)
            p = NULL;
        else {
            s->b2_mass[b] = v[2];
            s->b2_inertia[b] = v[4];
        }
    }
    complete = p && *p == '\0' && s->b2_mass && s->b2_inertia;
    free(text);
    if (!complete) {
        snprintf(why, wn, "%s: not a mass table of %d bodies", path, nb);
        free(s->b2_mass);
        free(s->b2_inertia);
        s->b2_mass = s->b2_inertia = NULL;
        return -1;
    }
    return 0;
}

/* The first line of stderr that is not a note (the reason it failed). */
static void first_message(const char *path, char *buf, size_t n)
{
    FILE *f = fopen(path, "r");
    char line[V_NOTE_MAX];
    buf[0] = '\0';
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] && !strstr(line, ": note: ")) {
            snprintf(buf, n, "%s", line);
            break;
        }
    }
    fclose(f);
}

/* ---- running them ------------------------------------------------------------------------ */

typedef struct job {
    vscene *s;
    int eng;
    pid_t pid;
} job;

static pid_t start_job(const job *j, const run_options *o)
{
    char trace[V_PATH_MAX], ev[V_PATH_MAX], out[V_PATH_MAX], err[V_PATH_MAX],
        masses[V_PATH_MAX];
    char *argv[16];
    int n = 0;
    run_file(trace, sizeof trace, o->workdir, j->s, j->eng, "trace");
    run_file(ev, sizeof ev, o->workdir, j->s, j->eng, "events");
    run_file(out, sizeof out, o->workdir, j->s, j->eng, "out");
    run_file(err, sizeof err, o->workdir, j->s, j->eng, "err");
    run_file(masses, sizeof masses, o->workdir, j->s, j->eng, "masses");
    if (j->eng == ENG_EVENTS || j->eng == ENG_DISCRETE) {
        argv[n++] = (char *)o->carom;
        argv[n++] = (char *)"run";
        argv[n++] = j->s->path;
        argv[n++] = (char *)"--method";
        argv[n++] = (char *)engine_names[j->eng];
    } else {
        argv[n++] = (char *)o->box2d;
        argv[n++] = (char *)"run";
        argv[n++] = j->s->path;
        if (j->eng == ENG_BOX2D) {
            argv[n++] = (char *)"--masses";
            argv[n++] = masses;
        } else {
            argv[n++] = (char *)"--bullets";
        }
    }
    argv[n++] = (char *)"--trace";
    argv[n++] = trace;
    argv[n++] = (char *)"--events";
    argv[n++] = ev;
    argv[n] = NULL;
    if (o->verbose)
        fprintf(stderr, "validate: run %s on %s\n", engine_names[j->eng], j->s->name);
    return spawn(argv, out, err);
}

/* Read back a finished run's files; on failure the run is not ok and its
 * message says why. */
static void finish_job(const job *j, int status, const run_options *o)
{
    char path[V_PATH_MAX];
    run *r = &j->s->runs[j->eng];
    r->status = status;
    run_file(path, sizeof path, o->workdir, j->s, j->eng, "err");
    if (status != 0) {
        first_message(path, r->message, sizeof r->message);
        return;
    }
    run_file(path, sizeof path, o->workdir, j->s, j->eng, "trace");
    if (load_trace(path, j->s, &r->tr, r->message, sizeof r->message) != 0)
        return;
    run_file(path, sizeof path, o->workdir, j->s, j->eng, "events");
    if (load_events(path, j->s, &r->ev, r->message, sizeof r->message) != 0)
        return;
    if (j->eng == ENG_BOX2D) {
        run_file(path, sizeof path, o->workdir, j->s, j->eng, "masses");
        if (load_masses(path, j->s, r->message, sizeof r->message) != 0)
            return;
    }
    r->ok = 1;
}

int runs_execute(suite *su, const run_options *o)
{
    job *jobs = NULL, *running;
    int njobs = 0, next = 0, active = 0, i, e, started = 0;
    jobs = (job *)calloc((size_t)su->count * ENG_COUNT + 1, sizeof *jobs);
    running = (job *)calloc((size_t)(o->jobs > 0 ? o->jobs : 1), sizeof *running);
    if (!jobs || !running) {
        fprintf(stderr, "validate: out of memory\n");
        free(jobs);
        free(running);
        return -1;
    }
    for (i = 0; i < su->count; ++i)
        for (e = ENG_EVENTS; e < ENG_COUNT; ++e)
            if (su->scenes[i].runs[e].wanted) {
                jobs[njobs].s = &su->scenes[i];
                jobs[njobs].eng = e;
                ++njobs;
            }
    /* The longest scenes first, so the slots stay busy. */
    for (i = 1; i < njobs; ++i) {
        job j = jobs[i];
        double wj = (double)j.s->steps * j.s->sc.body_count;
        int k = i;
        while (k > 0 && (double)jobs[k - 1].s->steps * jobs[k - 1].s->sc.body_count < wj) {
            jobs[k] = jobs[k - 1];
            --k;
        }
        jobs[k] = j;
    }
    while (next < njobs || active > 0) {
        int status, slot;
        pid_t pid;
        while (next < njobs && active < o->jobs) {
            job *j = &jobs[next++];
            j->pid = start_job(j, o);
            if (j->pid < 0) {
                j->s->runs[j->eng].status = 127;
                snprintf(j->s->runs[j->eng].message, V_NOTE_MAX, "cannot start %s: %s",
                         j->eng <= ENG_DISCRETE ? o->carom : o->box2d, strerror(errno));
                continue;
            }
            running[active++] = *j;
            ++started;
        }
        if (active == 0)
            continue;
        pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR)
                continue;
            fprintf(stderr, "validate: waitpid: %s\n", strerror(errno));
            break;
        }
        for (slot = 0; slot < active && running[slot].pid != pid; ++slot) {}
        if (slot == active)
            continue; /* not one of ours (a capture_line child is waited for there) */
        finish_job(&running[slot], exit_code(status), o);
        running[slot] = running[--active];
    }
    free(jobs);
    free(running);
    if (started == 0 && njobs > 0) {
        fprintf(stderr, "validate: no engine could be started\n");
        return -1;
    }
    return 0;
}

void run_free(run *r)
{
    free(r->tr.t);
    free(r->tr.st);
    free(r->ev.rows);
    memset(&r->tr, 0, sizeof r->tr);
    memset(&r->ev, 0, sizeof r->ev);
}
