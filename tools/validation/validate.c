/*
 * validate.c -- build/validate: carom against Box2D 2.4.1 and against exact
 * answers, driven by one check table. See validate.h for the
 * pieces and `validate --help` for the use.
 */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "validate.h"

static const char usage_text[] =
    "usage: validate [options]\n"
    "\n"
    "Runs every scene of the scene directory through carom (methods events and\n"
    "discrete) and Box2D 2.4.1 (carom-box2d; also with --bullets where the check\n"
    "table asks), with traces and events, and evaluates the check table on what\n"
    "they wrote: agreement between the engines and errors against exact answers\n"
    "(computed here in double precision, in closed form, from the scene alone).\n"
    "Writes a report with every measured number (regenerated each run) and a\n"
    "gnuplot figure of the restitution drop.\n"
    "\n"
    "options:\n"
    "  --carom PATH     build/carom (default build/carom)\n"
    "  --box2d PATH     build/carom-box2d (default build/carom-box2d)\n"
    "  --scenes DIR     the scenes, every DIR/*.scene (default\n"
    "                   tools/scenes/validation); each must say sleep=off\n"
    "  --checks FILE    the check table (default tools/validation/checks.txt)\n"
    "  --out FILE       the report (default docs/validation.md)\n"
    "  --figure FILE    the figure (default docs/validation-bounce.png)\n"
    "  --no-figure      draw no figure (gnuplot not needed)\n"
    "  --build TEXT     how the engines were built, for the report\n"
    "  --keep DIR       keep the engines' outputs in DIR (default: a temporary\n"
    "                   directory, removed at the end)\n"
    "  --jobs N         engine runs at once (default: the number of CPUs)\n"
    "  -v, --verbose    say what runs\n"
    "  -h, --help       this help\n"
    "\n"
    "The check table has one row per line:\n"
    "  SCENES  ENGINES  QUANTITY  TOLERANCE  REASON...\n"
    "SCENES: comma-separated patterns over scene names (*, ?, [..]); ENGINES:\n"
    "comma-separated, from carom (masses only), events, discrete, box2d,\n"
    "box2d-bullets, or pairs A:B; a check passes when the measured value is at\n"
    "most TOLERANCE (a value that cannot be measured fails). Quantities:\n";

static const char usage_tail[] =
    "\n"
    "exit status: 0 every check within its tolerance, 1 a check failed (or the\n"
    "report could not be written), 2 bad usage, a bad scene or table, or a tool\n"
    "missing (an engine, gnuplot)\n";

typedef struct options {
    run_options run;
    report_info report;
    const char *scene_dir;
    const char *checks;
    const char *keep;
    int figure;
} options;

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "validate: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (try --help)\n");
    return V_EXIT_USAGE;
}

/* Not an exit status: go on. */
#define GO_ON (-1)

/* Returns GO_ON, or an exit status. */
static int parse_options(int argc, char **argv, options *o)
{
    int i;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    memset(o, 0, sizeof *o);
    o->run.carom = "build/carom";
    o->run.box2d = "build/carom-box2d";
    o->run.jobs = cpus > 0 ? (int)cpus : 2;
    o->scene_dir = "tools/scenes/validation";
    o->checks = "tools/validation/checks.txt";
    o->report.out = "docs/validation.md";
    o->report.figure = "docs/validation-bounce.png";
    o->report.build = "not given (--build)";
    o->figure = 1;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char **target = NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(usage_text, stdout);
            checks_print_quantities(stdout);
            fputs(usage_tail, stdout);
            return V_EXIT_PASS;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            o->run.verbose = 1;
            continue;
        } else if (!strcmp(a, "--no-figure")) {
            o->figure = 0;
            continue;
        }
        if (!strcmp(a, "--carom"))
            target = &o->run.carom;
        else if (!strcmp(a, "--box2d"))
            target = &o->run.box2d;
        else if (!strcmp(a, "--scenes"))
            target = &o->scene_dir;
        else if (!strcmp(a, "--checks"))
            target = &o->checks;
        else if (!strcmp(a, "--out"))
            target = &o->report.out;
        else if (!strcmp(a, "--figure"))
            target = &o->report.figure;
        else if (!strcmp(a, "--build"))
            target = &o->report.build;
        else if (!strcmp(a, "--keep"))
            target = &o->keep;
        else if (strcmp(a, "--jobs") != 0)
            return usage_error("unknown argument '%s'", a);
        if (i + 1 >= argc || argv[i + 1][0] == '\0')
            return usage_error("%s needs a value", a);
        if (target) {
            *target = argv[++i];
        } else {
            char *end;
            long j = strtol(argv[++i], &end, 10);
            if (*end || j < 1 || j > 256)
                return usage_error("--jobs: want an integer in [1, 256], got '%s'", argv[i]);
            o->run.jobs = (int)j;
        }
    }
    if (!o->figure)
        o->report.figure = NULL;
    return GO_ON;
}

/* ---- the scenes -------------------------------------------------------------------------- */

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* What carom makes of the scene's bodies: its masses, and the rest speed
 * when the scene says auto. */
static int carom_side(vscene *s)
{
    carom_world *w;
    void *mem;
    char err[512];
    carom_tolerances tol;
    int i, nb = s->sc.body_count > 0 ? s->sc.body_count : 1;
    if (scene_build_world(&s->sc, &w, &mem, err, sizeof err) != 0) {
        fprintf(stderr, "validate: %s: %s\n", s->path, err);
        return -1;
    }
    s->carom_mass = (double *)calloc((size_t)nb, sizeof(double));
    s->carom_inertia = (double *)calloc((size_t)nb, sizeof(double));
    if (!s->carom_mass || !s->carom_inertia) {
        scene_free_world(w, mem);
        fprintf(stderr, "validate: out of memory\n");
        return -1;
    }
    for (i = 0; i < s->sc.body_count; ++i) {
        float m = 0.0f, inertia = 0.0f;
        carom_body_get_mass(w, i, &m, &inertia);
        s->carom_mass[i] = (double)m;
        s->carom_inertia[i] = (double)inertia;
    }
    carom_world_get_tolerances(w, &tol);
    s->rest_speed = s->sc.world.rest_speed == CAROM_AUTO ? (double)tol.rest_speed
                                                          : (double)s->sc.world.rest_speed;
    scene_free_world(w, mem);
    return 0;
}

static int load_scene(vscene *s, const char *dir, const char *file)
{
    char err[512];
    size_t len = strlen(file) - strlen(".scene");
    int i;
    if (len >= sizeof s->name) {
        fprintf(stderr, "validate: %s/%s: name too long\n", dir, file);
        return -1;
    }
    memcpy(s->name, file, len);
    s->name[len] = '\0';
    snprintf(s->path, sizeof s->path, "%s/%s", dir, file);
    for (i = 0; i < ENG_COUNT; ++i)
        s->runs[i].status = -1;
    if (scene_load(s->path, &s->sc, err, sizeof err) != 0) {
        fprintf(stderr, "validate: %s\n", err);
        return -1;
    }
    if (s->sc.world.enable_sleep) {
        fprintf(stderr, "validate: %s: a validation scene must say sleep=off on its world "
                        "line (a sleeping body is not simulated; Box2D's sleeping is off)\n",
                s->path);
        return -1;
    }
    s->gx = (double)s->sc.world.gravity.x;
    s->gy = (double)s->sc.world.gravity.y;
    s->dt = (double)s->sc.world.dt;
    s->steps = s->sc.steps;
    s->exact = (body_props *)calloc((size_t)s->sc.body_count + 1, sizeof *s->exact);
    if (!s->exact) {
        fprintf(stderr, "validate: out of memory\n");
        return -1;
    }
    for (i = 0; i < s->sc.body_count; ++i)
        exact_body_props(&s->sc.bodies[i], &s->exact[i]);
    return carom_side(s);
}

static int load_suite(suite *su, const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char **names = NULL;
    int n = 0, cap = 0, i, rc = 0;
    memset(su, 0, sizeof *su);
    if (!d) {
        fprintf(stderr, "validate: cannot read the scene directory %s: %s\n", dir,
                strerror(errno));
        return -1;
    }
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        if (len <= 6 || strcmp(e->d_name + len - 6, ".scene") != 0)
            continue;
        if (n == cap) {
            char **bigger = (char **)realloc(names, (size_t)(cap = cap ? 2 * cap : 64) *
                                                        sizeof *bigger);
            if (!bigger)
                break;
            names = bigger;
        }
        if (!(names[n] = strdup(e->d_name)))
            break;
        ++n;
    }
    closedir(d);
    if (n == 0) {
        fprintf(stderr, "validate: no scenes in %s\n", dir);
        free(names);
        return -1;
    }
    qsort(names, (size_t)n, sizeof *names, by_name);
    su->scenes = (vscene *)calloc((size_t)n, sizeof *su->scenes);
    for (i = 0; i < n; ++i) {
        if (su->scenes && rc == 0) {
            rc = load_scene(&su->scenes[i], dir, names[i]);
            su->count = i + 1;
        }
        free(names[i]);
    }
    free(names);
    if (!su->scenes) {
        fprintf(stderr, "validate: out of memory\n");
        return -1;
    }
    return rc;
}

static void free_suite(suite *su)
{
    int i, e;
    for (i = 0; i < su->count; ++i) {
        vscene *s = &su->scenes[i];
        for (e = 0; e < ENG_COUNT; ++e)
            run_free(&s->runs[e]);
        scene_free(&s->sc);
        free(s->exact);
        free(s->carom_mass);
        free(s->carom_inertia);
        free(s->b2_mass);
        free(s->b2_inertia);
    }
    free(su->scenes);
    memset(su, 0, sizeof *su);
}

const vscene *suite_find(const suite *su, const char *name)
{
    int i;
    for (i = 0; i < su->count; ++i)
        if (strcmp(su->scenes[i].name, name) == 0)
            return &su->scenes[i];
    return NULL;
}

/* ---- the working directory --------------------------------------------------------------- */

static int make_dirs(const char *path)
{
    char buf[V_PATH_MAX];
    size_t i;
    snprintf(buf, sizeof buf, "%s", path);
    for (i = 1; buf[i]; ++i)
        if (buf[i] == '/') {
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            buf[i] = '/';
        }
    return mkdir(buf, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

/* Remove the temporary directory this run made, and what is in it (the
 * engines' outputs: plain files only). */
static void remove_workdir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[V_PATH_MAX + 256];
    if (!d)
        return;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        unlink(path);
    }
    closedir(d);
    rmdir(dir);
}

static int executable(const char *path, const char *what)
{
    if (access(path, X_OK) == 0)
        return 1;
    fprintf(stderr, "validate: %s '%s' not found or not executable (build it: make all box2d)\n",
            what, path);
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void print_failures(const check_table *t, const suite *su, const char *path)
{
    int i;
    for (i = 0; i < t->result_count; ++i) {
        const check_result *c = &t->results[i];
        const check_row *row = &t->rows[c->row];
        char v[32], eng[64];
        if (c->pass)
            continue;
        format_value(v, sizeof v, c->value);
        snprintf(eng, sizeof eng, "%s%s%s", engine_names[c->a], c->b >= 0 ? ":" : "",
                 c->b >= 0 ? engine_names[c->b] : "");
        fprintf(stderr, "validate: FAIL: %s %s %s = %s > %g (%s:%d)%s%s\n",
                su->scenes[c->scene].name, eng, quantity_name(row->quantity), v, row->tol, path,
                row->line, c->why[0] ? ": " : "", c->why);
    }
}

/* Run the engines and evaluate the table in workdir, then write the report.
 * Returns the exit status. */
static int validate(suite *su, check_table *table, options *o, const char *workdir, double t0)
{
    int drawn = 0, written;
    o->run.workdir = workdir;
    if (runs_execute(su, &o->run) != 0)
        return V_EXIT_USAGE;
    checks_evaluate(table, su);
    o->report.checks_path = o->checks;
    o->report.scene_dir = o->scene_dir;
    o->report.workdir = workdir;
    o->report.carom = o->run.carom;
    written = report_write(su, table, &o->report, &drawn);
    print_failures(table, su, o->checks);
    fprintf(stderr, "validate: %d checks over %d scenes: %s (%.1f s)", table->result_count,
            su->count, table->failed ? "FAILED" : "all within tolerance", now_s() - t0);
    if (written >= 0)
        fprintf(stderr, "; wrote %s%s%s", o->report.out, drawn ? " and " : "",
                drawn ? o->report.figure : "");
    fputc('\n', stderr);
    if (o->report.figure && !drawn)
        fprintf(stderr, "validate: the figure %s was not drawn\n", o->report.figure);
    if (table->failed)
        fprintf(stderr, "validate: %d check(s) failed\n", table->failed);
    return table->failed || written != 0 ? V_EXIT_FAIL : V_EXIT_PASS;
}

int main(int argc, char **argv)
{
    options o;
    suite su;
    check_table table;
    char workdir[V_PATH_MAX], version[128];
    char *gnuplot_argv[] = {(char *)"gnuplot", (char *)"--version", NULL};
    double t0 = now_s();
    int rc = parse_options(argc, argv, &o), e, i;

    if (rc != GO_ON)
        return rc;
    if (!executable(o.run.carom, "carom") || !executable(o.run.box2d, "carom-box2d"))
        return V_EXIT_USAGE;
    if (checks_load(o.checks, &table) != 0)
        return V_EXIT_USAGE;
    if (load_suite(&su, o.scene_dir) != 0) {
        free_suite(&su);
        checks_free(&table);
        return V_EXIT_USAGE;
    }
    /* the report compares the three everywhere; the table may ask for more */
    for (i = 0; i < su.count; ++i)
        for (e = ENG_EVENTS; e <= ENG_BOX2D; ++e)
            su.scenes[i].runs[e].wanted = 1;
    if (checks_expand(&table, &su, o.checks) != 0) {
        free_suite(&su);
        checks_free(&table);
        return V_EXIT_USAGE;
    }

    if (o.keep) {
        snprintf(workdir, sizeof workdir, "%s", o.keep);
        if (make_dirs(workdir) != 0) {
            fprintf(stderr, "validate: cannot make %s: %s\n", workdir, strerror(errno));
            rc = V_EXIT_USAGE;
        }
    } else {
        const char *tmp = getenv("TMPDIR");
        snprintf(workdir, sizeof workdir, "%s/carom-validate.XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(workdir)) {
            fprintf(stderr, "validate: cannot make a temporary directory %s: %s\n", workdir,
                    strerror(errno));
            workdir[0] = '\0';
            rc = V_EXIT_USAGE;
        }
    }
    if (rc == GO_ON && o.figure &&
        capture_line(gnuplot_argv, workdir, version, sizeof version) != 0) {
        fprintf(stderr, "validate: gnuplot not found (Debian: apt-get install gnuplot-nox), "
                        "or give --no-figure\n");
        rc = V_EXIT_USAGE;
    }
    if (rc == GO_ON)
        rc = validate(&su, &table, &o, workdir, t0);
    if (!o.keep && workdir[0])
        remove_workdir(workdir);
    free_suite(&su);
    checks_free(&table);
    return rc;
}
