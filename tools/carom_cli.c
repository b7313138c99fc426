/*
 * carom_cli.c -- build/carom: run scene files through the library.
 *
 *   carom run SCENE       final state as CSV (and --trace, --events)
 *   carom profile SCENE   operation counts and their weighted cost
 *   carom render SCENE    an animated SVG (and PNG frames with gnuplot)
 *
 * The three commands share one table of options (`options` below) and one
 * simulation loop. Exit status: 0 success, 1 the simulation reported an
 * error (the state reached is still written, marked partial), 2 bad usage
 * or a bad scene.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "carom.h"
#include "render/render.h"
#include "scene.h"

#define EXIT_SIM 1
#define EXIT_USAGE 2

/* Scene files larger than this are refused (as tools/scene.c does). */
#define SCENE_MAX_BYTES (64L << 20)
/* Estimated bytes per --trace row ("step,t,body,x,y,angle,vx,vy,omega"
 * with %.9g numbers: 40 to 140, about 70 for moving bodies). */
#define TRACE_ROW_BYTES 72.0
/* Default of --max-output, MB (10^6 bytes). */
#define DEFAULT_MAX_OUTPUT_MB 300.0
/* render: default and largest --fps, default --size, most impact markers. */
#define DEFAULT_FPS 30.0
#define MAX_FPS 60.0
#define DEFAULT_SIZE 640L
#define MAX_MARKERS 10000L
/* Progress is refreshed at most this often (seconds). */
#define PROGRESS_PERIOD 0.2

/* ---- options: one table for run, profile and render ---------------------- */

enum { CMD_RUN = 1u, CMD_PROFILE = 2u, CMD_RENDER = 4u, CMD_ALL = 7u };

typedef enum opt_id {
    OPT_STEPS, OPT_DT, OPT_METHOD, OPT_TRACE, OPT_EVENTS, OPT_MAX_OUTPUT,
    OPT_FORCE, OPT_PROGRESS, OPT_NO_PROGRESS, OPT_WEIGHTS, OPT_JSON,
    OPT_OUTPUT, OPT_PNG, OPT_FPS, OPT_EVERY, OPT_IMPACTS, OPT_SIZE, OPT_VIEW,
    OPT_HELP
} opt_id;

typedef struct cli_option {
    opt_id id;
    const char *name;  /* --name */
    char short_name;   /* -x, or 0 */
    const char *arg;   /* metavariable, NULL for a flag */
    unsigned cmds;     /* CMD_* that accept it */
    const char *help;  /* lines after the first are indented */
} cli_option;

static const cli_option options[] = {
    {OPT_STEPS, "steps", 0, "N", CMD_ALL,
     "number of steps (overrides the scene's steps=)"},
    {OPT_DT, "dt", 0, "DT", CMD_ALL, "time step in seconds (overrides dt=)"},
    {OPT_METHOD, "method", 0, "NAME", CMD_ALL,
     "events (default), discrete or first-impact\n"
     "(overrides method=; see docs/events.md)"},
    {OPT_TRACE, "trace", 0, "FILE", CMD_ALL,
     "write every body's state at step 0 and after every\n"
     "step: step,t,body,x,y,angle,vx,vy,omega"},
    {OPT_EVENTS, "events", 0, "FILE", CMD_ALL,
     "write every impact, in time order:\n"
     "t,body_a,body_b,nx,ny,impulse,approach_speed"},
    {OPT_MAX_OUTPUT, "max-output", 0, "MB", CMD_ALL,
     "refuse a --trace or an SVG estimated larger than MB\n"
     "megabytes (default 300) unless --force"},
    {OPT_FORCE, "force", 0, NULL, CMD_ALL,
     "write outputs larger than --max-output (with a warning)"},
    {OPT_PROGRESS, "progress", 0, NULL, CMD_ALL,
     "show progress on stderr even when it is not a terminal\n"
     "(by default: only when stderr is a terminal)"},
    {OPT_NO_PROGRESS, "no-progress", 0, NULL, CMD_ALL, "never show progress"},
    {OPT_WEIGHTS, "weights", 0, "NAME|FILE", CMD_PROFILE,
     "operation costs: a preset (seed, the default;\n"
     "cortex-m4f; cortex-m0) or a file of 'KIND WEIGHT'\n"
     "lines naming all six kinds ('#' comments)"},
    {OPT_JSON, "json", 0, NULL, CMD_PROFILE, "print one JSON object instead of the table"},
    {OPT_OUTPUT, "output", 'o', "FILE", CMD_RENDER,
     "the animated SVG to write ('-': stdout)"},
    {OPT_PNG, "png", 0, "DIR", CMD_RENDER,
     "write the frames as DIR/frame-00000.png ... with gnuplot"},
    {OPT_FPS, "fps", 0, "N", CMD_RENDER,
     "frames per second of simulated time, at most 60\n"
     "(default 30; frames are taken every round(1 / (N dt))\n"
     "steps, plus the last step)"},
    {OPT_EVERY, "every", 0, "N", CMD_RENDER, "a frame every N steps (instead of --fps)"},
    {OPT_IMPACTS, "impacts", 0, NULL, CMD_RENDER,
     "mark each impact where it happens (for 0.25 s)"},
    {OPT_SIZE, "size", 0, "PX", CMD_RENDER,
     "pixels of the view's longer side (default 640)"},
    {OPT_VIEW, "view", 0, "X0,Y0,X1,Y1", CMD_RENDER,
     "show this rectangle of the world (m) instead of\n"
     "fitting every body over the whole run"},
    {OPT_HELP, "help", 'h', NULL, CMD_ALL, "show this help"},
};
#define OPTION_COUNT ((int)(sizeof options / sizeof options[0]))

typedef struct sim_opts {
    unsigned cmd;
    const char *scene_path, *trace_path, *events_path, *output_path, *png_dir;
    const char *method, *weights_arg;
    long steps;         /* -1: the scene's */
    double dt;          /* <= 0: the scene's */
    double max_output_mb;
    int force, progress; /* progress: -1 auto, 0 off, 1 on */
    int json, impacts;
    double fps;         /* <= 0: not given */
    long every;         /* 0: not given */
    long size;
    int fixed_view;
    double view[4];     /* xmin, ymin, xmax, ymax */
} sim_opts;

static const char *cmd_name(unsigned cmd)
{
    return cmd == CMD_RUN ? "run" : cmd == CMD_PROFILE ? "profile" : "render";
}

static void print_option_help(FILE *f, unsigned cmds)
{
    int i;
    for (i = 0; i < OPTION_COUNT; ++i) {
        const cli_option *o = &options[i];
        char head[64];
        const char *h = o->help;
        if (o->cmds != cmds)
            continue;
        if (o->short_name)
            snprintf(head, sizeof head, "-%c, --%s%s%s", o->short_name, o->name,
                     o->arg ? " " : "", o->arg ? o->arg : "");
        else
            snprintf(head, sizeof head, "--%s%s%s", o->name, o->arg ? " " : "",
                     o->arg ? o->arg : "");
        fprintf(f, "  %-19s", head);
        if (strlen(head) > 18)
            fprintf(f, "\n  %-19s", "");
        for (; *h; ++h) {
            fputc(*h, f);
            if (*h == '\n')
                fprintf(f, "  %-19s", "");
        }
        fputc('\n', f);
    }
}

static void print_usage(FILE *f)
{
    fputs("usage: carom run SCENE [options]\n"
          "       carom profile SCENE [--weights NAME|FILE] [--json] [options]\n"
          "       carom render SCENE -o FILE.svg [--png DIR] [options]\n"
          "       carom --help | --version\n"
          "\n"
          "run: step a scene file (docs/scene-format.md; '-' reads stdin) and\n"
          "write the final state of every body to stdout as CSV:\n"
          "body,x,y,angle,vx,vy,omega (x, y: body origin; angle in radians in\n"
          "(-pi, pi]; vx, vy: velocity of the centre of mass; omega: angular\n"
          "velocity). If the simulation stops with an error (exit 1), the state\n"
          "reached is still written, after a first line\n"
          "'# partial: stopped at step N of M: STATUS ...'.\n"
          "\n"
          "profile: run the scene counting every floating-point operation by kind\n"
          "(add sub mul div cmp sqrt) and pipeline phase, and print the counts and\n"
          "their weighted cost (docs/cost-model.md).\n"
          "\n"
          "render: run the scene and draw it as a self-contained animated SVG\n"
          "(looping; y up; the view fits every body over the whole run unless\n"
          "--view is given; the time is shown above it), and/or as PNG frames\n"
          "through gnuplot.\n"
          "\n"
          "Scene files may end lines with LF, CR LF or CR, and may start with a\n"
          "UTF-8 byte-order mark.\n"
          "\n"
          "Options are written --opt VALUE or --opt=VALUE.\n"
          "\n"
          "options of run, profile and render:\n", f);
    print_option_help(f, CMD_ALL);
    fputs("options of profile:\n", f);
    print_option_help(f, CMD_PROFILE);
    fputs("options of render (at least one of -o and --png):\n", f);
    print_option_help(f, CMD_RENDER);
    fputs("\n"
          "Progress (step, share done, simulated time) goes to stderr when it is\n"
          "a terminal, on one line that is erased when the run ends.\n"
          "\n"
          "exit status: 0 ok, 1 simulation error (or an output not written\n"
          "completely), 2 bad usage or bad scene\n", f);
}

static int usage_error(const char *fmt, ...)
{
    va_list ap;
    fputs("carom: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputs("\n(try 'carom --help')\n", stderr);
    return EXIT_USAGE;
}

static int parse_long_in(const char *opt, const char *v, long lo, long hi, long *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || errno || x < lo || x > hi)
        return usage_error("--%s: want an integer in [%ld, %ld], got '%s'", opt,
                           lo, hi, v);
    *out = x;
    return 0;
}

/* A finite number in (lo, hi] (lo_open) or [lo, hi]. */
static int parse_double_in(const char *opt, const char *v, double lo, int lo_open,
                           double hi, const char *want, double *out)
{
    char *end;
    double x;
    errno = 0;
    x = strtod(v, &end);
    if (*v == '\0' || *end != '\0' || errno || !isfinite(x) ||
        (lo_open ? !(x > lo) : !(x >= lo)) || x > hi)
        return usage_error("--%s: want %s, got '%s'", opt, want, v);
    *out = x;
    return 0;
}

static int apply_option(sim_opts *o, const cli_option *opt, const char *v)
{
    switch (opt->id) {
    case OPT_STEPS:
        return parse_long_in("steps", v, 0, 1000000000L, &o->steps);
    case OPT_DT:
        return parse_double_in("dt", v, 0.0, 1, 1.0e30, "a finite number > 0", &o->dt);
    case OPT_METHOD: {
        carom_method m;
        if (carom_method_from_name(v, &m) != CAROM_OK)
            return usage_error("--method: unknown method '%s' (events, discrete, "
                               "first-impact)", v);
        o->method = v;
        return 0;
    }
    case OPT_TRACE: o->trace_path = v; return 0;
    case OPT_EVENTS: o->events_path = v; return 0;
    case OPT_MAX_OUTPUT:
        return parse_double_in("max-output", v, 0.0, 0, 1.0e12,
                               "a number of megabytes >= 0", &o->max_output_mb);
    case OPT_FORCE: o->force = 1; return 0;
    case OPT_PROGRESS: o->progress = 1; return 0;
    case OPT_NO_PROGRESS: o->progress = 0; return 0;
    case OPT_WEIGHTS: o->weights_arg = v; return 0;
    case OPT_JSON: o->json = 1; return 0;
    case OPT_OUTPUT: o->output_path = v; return 0;
    case OPT_PNG: o->png_dir = v; return 0;
    case OPT_FPS:
        return parse_double_in("fps", v, 0.0, 1, MAX_FPS, "a number in (0, 60]", &o->fps);
    case OPT_EVERY:
        return parse_long_in("every", v, 1, 1000000000L, &o->every);
    case OPT_IMPACTS: o->impacts = 1; return 0;
    case OPT_SIZE:
        return parse_long_in("size", v, 16, 16384, &o->size);
    case OPT_VIEW: {
        char extra;
        if (sscanf(v, "%lf,%lf,%lf,%lf%c", &o->view[0], &o->view[1], &o->view[2],
                   &o->view[3], &extra) != 4 || !isfinite(o->view[0]) ||
            !isfinite(o->view[1]) || !isfinite(o->view[2]) ||
            !isfinite(o->view[3]) || !(o->view[2] > o->view[0]) ||
            !(o->view[3] > o->view[1]))
            return usage_error("--view: want X0,Y0,X1,Y1 with X0 < X1 and Y0 < Y1 "
                               "(metres), got '%s'", v);
        o->fixed_view = 1;
        return 0;
    }
    case OPT_HELP:
        break;
    }
    return 0;
}

static const char *cmds_list(unsigned cmds)
{
    switch (cmds) {
    case CMD_RUN: return "run";
    case CMD_PROFILE: return "profile";
    case CMD_RENDER: return "render";
    default: return "run, profile and render";
    }
}

/* Returns -1 to go on, or an exit status (0 after --help). */
static int parse_options(unsigned cmd, int argc, char **argv, sim_opts *o)
{
    int i, only_operands = 0;
    memset(o, 0, sizeof *o);
    o->cmd = cmd;
    o->steps = -1;
    o->dt = -1.0;
    o->max_output_mb = DEFAULT_MAX_OUTPUT_MB;
    o->progress = -1;
    o->weights_arg = "seed";
    o->size = DEFAULT_SIZE;
    for (i = 0; i < argc; ++i) {
        const char *a = argv[i], *value = NULL;
        const cli_option *opt = NULL;
        char shown[64];
        int k, rc;
        if (only_operands || a[0] != '-' || a[1] == '\0') {
            if (o->scene_path)
                return usage_error("more than one scene given ('%s')", a);
            o->scene_path = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            only_operands = 1;
            continue;
        }
        if (a[1] == '-') {
            const char *eq = strchr(a + 2, '=');
            size_t n = eq ? (size_t)(eq - (a + 2)) : strlen(a + 2);
            for (k = 0; k < OPTION_COUNT; ++k)
                if (strlen(options[k].name) == n && strncmp(options[k].name, a + 2, n) == 0)
                    opt = &options[k];
            if (!opt)
                return usage_error("unknown option '%.*s'", (int)(n + 2), a);
            if (eq)
                value = eq + 1;
            snprintf(shown, sizeof shown, "--%s", opt->name);
        } else {
            for (k = 0; k < OPTION_COUNT; ++k)
                if (options[k].short_name == a[1])
                    opt = &options[k];
            if (!opt)
                return usage_error("unknown option '%s'", a);
            if (a[2] != '\0') {
                if (!opt->arg)
                    return usage_error("unknown option '%s'", a);
                value = a[2] == '=' ? a + 3 : a + 2; /* -oFILE, -o=FILE */
            }
            snprintf(shown, sizeof shown, "-%c", opt->short_name);
        }
        if (!(opt->cmds & cmd))
            return usage_error("%s is an option of %s, not of %s", shown,
                               cmds_list(opt->cmds), cmd_name(cmd));
        if (opt->id == OPT_HELP) {
            if (value)
                return usage_error("%s takes no value", shown);
            print_usage(stdout);
            return 0;
        }
        if (!opt->arg && value)
            return usage_error("%s takes no value (got '%s')", shown, a);
        if (opt->arg && !value) {
            if (i + 1 >= argc)
                return usage_error("%s needs a value (%s)", shown, opt->arg);
            value = argv[++i];
        }
        rc = apply_option(o, opt, value);
        if (rc)
            return rc;
    }
    if (!o->scene_path)
        return usage_error("%s: missing SCENE", cmd_name(cmd));
    if (cmd == CMD_RENDER) {
        if (!o->output_path && !o->png_dir)
            return usage_error("render: say where to draw: -o FILE.svg and/or --png DIR");
        if (o->fps > 0.0 && o->every > 0)
            return usage_error("render: give --fps or --every, not both");
    }
    return -1;
}

/* ---- reading the scene ---------------------------------------------------- */

/* Read the scene file ourselves (rather than scene_load) so that a
 * directory, a UTF-16 file, a UTF-8 byte-order mark and CR line endings
 * are named or accepted: the text is normalised (BOM dropped; CR LF and
 * lone CR become LF, so line numbers are unchanged) and parsed with
 * scene_parse(). '-' reads stdin. */
static int read_scene(const char *path, scene *s, char *err, size_t errlen)
{
    int from_stdin = strcmp(path, "-") == 0;
    const char *name = from_stdin ? "<stdin>" : path;
    struct stat sb;
    FILE *f;
    char *text, *r, *w;
    size_t len = 0, cap = 65536;
    int rc;

    memset(s, 0, sizeof *s);
    if (!from_stdin) {
        if (stat(path, &sb) != 0) {
            snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
            return -1;
        }
        if (S_ISDIR(sb.st_mode)) {
            snprintf(err, errlen, "%s: is a directory, not a scene file", path);
            return -1;
        }
    }
    f = from_stdin ? stdin : fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    text = (char *)malloc(cap + 1);
    while (text) {
        size_t got = fread(text + len, 1, cap - len, f);
        len += got;
        if (got == 0 || len > (size_t)SCENE_MAX_BYTES)
            break;
        if (len == cap) {
            char *bigger = (char *)realloc(text, 2 * cap + 1);
            if (!bigger) {
                free(text);
                text = NULL;
                break;
            }
            text = bigger;
            cap *= 2;
        }
    }
    if (!text) {
        snprintf(err, errlen, "%s: out of memory", name);
        if (!from_stdin)
            fclose(f);
        return -1;
    }
    if (ferror(f)) {
        snprintf(err, errlen, "%s: read error: %s", name, strerror(errno));
        rc = -1;
    } else if (len > (size_t)SCENE_MAX_BYTES) {
        snprintf(err, errlen, "%s: larger than %ld bytes", name, SCENE_MAX_BYTES);
        rc = -1;
    } else if (len >= 2 && (((unsigned char)text[0] == 0xFF && (unsigned char)text[1] == 0xFE) ||
                            ((unsigned char)text[0] == 0xFE && (unsigned char)text[1] == 0xFF))) {
        snprintf(err, errlen, "%s: UTF-16 text; save the scene as UTF-8 or ASCII", name);
        rc = -1;
    } else if (memchr(text, '\0', len)) {
        snprintf(err, errlen, "%s: contains a NUL byte (not a text file?)", name);
        rc = -1;
    } else {
        rc = 0;
    }
    if (!from_stdin)
        fclose(f);
    if (rc) {
        free(text);
        return -1;
    }
    text[len] = '\0';
    r = text;
    if (len >= 3 && (unsigned char)r[0] == 0xEF && (unsigned char)r[1] == 0xBB &&
        (unsigned char)r[2] == 0xBF)
        r += 3; /* UTF-8 byte-order mark */
    for (w = text; *r; ++r) {
        if (*r == '\r') {
            *w++ = '\n';
            if (r[1] == '\n')
                ++r;
        } else {
            *w++ = *r;
        }
    }
    *w = '\0';
    rc = scene_parse(name, text, s, err, errlen);
    free(text);
    return rc;
}

/* ---- output -------------------------------------------------------------- */

static void write_state(FILE *f, const carom_world *w, int i, const char *prefix)
{
    carom_body_state st;
    carom_body_get_state(w, i, &st);
    fprintf(f, "%s%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", prefix, i,
            (double)st.position.x, (double)st.position.y,
            (double)carom_rot_angle(st.rotation), (double)st.velocity.x,
            (double)st.velocity.y, (double)st.angular_velocity);
}

static void write_trace(FILE *f, const carom_world *w)
{
    char prefix[64];
    int i;
    snprintf(prefix, sizeof prefix, "%ld,%.9g,", carom_world_step_count(w),
             (double)carom_world_time(w));
    for (i = 0; i < carom_world_body_count(w); ++i)
        write_state(f, w, i, prefix);
}

/* A weight preset name, or a file of "KIND WEIGHT" lines (all six kinds,
 * each once, weights finite and >= 0). */
static int load_weights(const char *arg, carom_op_weights *out)
{
    FILE *f;
    char line[256];
    int lineno = 0, seen[CAROM_OP_COUNT] = {0}, k;
    if (carom_op_weights_preset(arg, out) == CAROM_OK)
        return 0;
    f = fopen(arg, "r");
    if (!f) {
        fprintf(stderr, "carom: --weights: '%s' is neither a preset (seed, "
                        "cortex-m4f, cortex-m0) nor a readable file: %s\n",
                arg, strerror(errno));
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        char kind[32], extra[2];
        double v;
        char *hash = strchr(line, '#');
        int n;
        ++lineno;
        if (hash)
            *hash = '\0';
        n = sscanf(line, "%31s %lf %1s", kind, &v, extra);
        if (n <= 0)
            continue;
        if (n != 2) {
            fprintf(stderr, "carom: %s:%d: want 'KIND WEIGHT'\n", arg, lineno);
            fclose(f);
            return -1;
        }
        for (k = 0; k < CAROM_OP_COUNT; ++k)
            if (strcmp(kind, carom_op_name((carom_op)k)) == 0)
                break;
        if (k == CAROM_OP_COUNT) {
            fprintf(stderr, "carom: %s:%d: unknown kind '%s' (add sub mul div "
                            "cmp sqrt)\n", arg, lineno, kind);
            fclose(f);
            return -1;
        }
        if (seen[k]++) {
            fprintf(stderr, "carom: %s:%d: '%s' given twice\n", arg, lineno, kind);
            fclose(f);
            return -1;
        }
        if (!isfinite(v) || v < 0.0 || v > 1e30) {
            fprintf(stderr, "carom: %s:%d: weight must be finite and >= 0\n",
                    arg, lineno);
            fclose(f);
            return -1;
        }
        out->w[k] = (float)v;
    }
    fclose(f);
    for (k = 0; k < CAROM_OP_COUNT; ++k) {
        if (!seen[k]) {
            fprintf(stderr, "carom: %s: no weight for '%s'\n", arg,
                    carom_op_name((carom_op)k));
            return -1;
        }
    }
    return 0;
}

/* Costs are summed in double here: counts reach billions. */
static double phase_cost(const carom_profile *p, const carom_op_weights *wt, int ph)
{
    double c = 0.0;
    int k;
    for (k = 0; k < CAROM_OP_COUNT; ++k)
        c += (double)p->ops[ph][k] * (double)wt->w[k];
    return c;
}

static void print_profile_table(const carom_profile *p, const carom_op_weights *wt,
                                const char *wname, const char *path,
                                carom_method method, int bodies)
{
    int ph, k;
    double total = 0.0, impulse;
    uint64_t kinds[CAROM_OP_COUNT] = {0};
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
        total += phase_cost(p, wt, ph);
    printf("scene %s: method %s, %lu steps, %d bodies, %lu body-steps, %lu impacts\n",
           path, carom_method_name(method), (unsigned long)p->steps, bodies,
           (unsigned long)p->body_steps, (unsigned long)p->impacts);
    printf("weights %s:", wname);
    for (k = 0; k < CAROM_OP_COUNT; ++k)
        printf(" %s %g", carom_op_name((carom_op)k), (double)wt->w[k]);
    printf("\n\n%-19s", "phase");
    for (k = 0; k < CAROM_OP_COUNT; ++k)
        printf(" %12s", carom_op_name((carom_op)k));
    printf(" %14s %6s\n", "cost", "share");
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph) {
        double c = phase_cost(p, wt, ph);
        printf("%-19s", carom_phase_name((carom_phase)ph));
        for (k = 0; k < CAROM_OP_COUNT; ++k) {
            printf(" %12lu", (unsigned long)p->ops[ph][k]);
            kinds[k] += p->ops[ph][k];
        }
        printf(" %14.1f %5.1f%%\n", c, total > 0 ? 100.0 * c / total : 0.0);
    }
    printf("%-19s", "total");
    for (k = 0; k < CAROM_OP_COUNT; ++k)
        printf(" %12lu", (unsigned long)kinds[k]);
    printf(" %14.1f %5.1f%%\n\n", total, 100.0);
    impulse = phase_cost(p, wt, CAROM_PHASE_IMPULSES);
    printf("cost per step      %14.1f\n", p->steps ? total / (double)p->steps : 0.0);
    printf("cost per body-step %14.1f\n",
           p->body_steps ? total / (double)p->body_steps : 0.0);
    if (p->impacts)
        printf("cost per impact    %14.1f  (of which impulse resolution %.1f)\n",
               total / (double)p->impacts, impulse / (double)p->impacts);
    else
        printf("cost per impact    %14s\n", "(no impacts)");
}

static void put_json_string(const char *s)
{
    putchar('"');
    for (; *s; ++s) /* a file path may hold any character */
        if (*s == '"' || *s == '\\')
            printf("\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            printf("\\u%04x", (unsigned)(unsigned char)*s);
        else
            putchar(*s);
    putchar('"');
}

static void print_profile_json(const carom_profile *p, const carom_op_weights *wt,
                               const char *wname, int bodies, const char *partial)
{
    int ph, k;
    double total = 0.0;
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
        total += phase_cost(p, wt, ph);
    printf("{");
    if (partial) {
        printf("\"partial\": ");
        put_json_string(partial);
        printf(", ");
    }
    printf("\"steps\": %lu, \"bodies\": %d, \"impacts\": %lu, \"body_steps\": %lu, ",
           (unsigned long)p->steps, bodies, (unsigned long)p->impacts,
           (unsigned long)p->body_steps);
    printf("\"weights_name\": ");
    put_json_string(wname);
    printf(", \"weights\": {");
    for (k = 0; k < CAROM_OP_COUNT; ++k)
        printf("%s\"%s\": %.9g", k ? ", " : "", carom_op_name((carom_op)k),
               (double)wt->w[k]);
    printf("}, \"phases\": {");
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph) {
        printf("%s\"%s\": {", ph ? ", " : "", carom_phase_name((carom_phase)ph));
        for (k = 0; k < CAROM_OP_COUNT; ++k)
            printf("%s\"%s\": %lu", k ? ", " : "", carom_op_name((carom_op)k),
                   (unsigned long)p->ops[ph][k]);
        printf("}");
    }
    printf("}, \"total_cost\": %.17g}\n", total);
}

/* '-' is stdout only where allowed (render -o); elsewhere a file named -. */
static FILE *open_out(const char *path, int dash_is_stdout)
{
    FILE *f = dash_is_stdout && strcmp(path, "-") == 0 ? stdout : fopen(path, "w");
    if (!f)
        fprintf(stderr, "carom: cannot write '%s': %s\n", path, strerror(errno));
    return f;
}

/* 0 if closed (or, for stdout, flushed) fine; -1 on a write error. */
static int close_out(FILE *f)
{
    if (!f)
        return 0;
    if (f == stdout)
        return fflush(f) == 0 ? 0 : -1;
    return fclose(f) == 0 ? 0 : -1;
}

/* Refuse (exit 2) an output estimated above --max-output, unless --force;
 * with --force, warn. Returns 0 to go on. */
static int check_output_size(const sim_opts *o, const char *what, const char *path,
                             double bytes, const char *how, const char *fewer)
{
    double mb = bytes / 1e6;
    if (mb <= o->max_output_mb)
        return 0;
    if (o->force) {
        fprintf(stderr, "carom: warning: %s '%s' will be about %.3g MB (%s)\n",
                what, path, mb, how);
        return 0;
    }
    fprintf(stderr, "carom: %s '%s' would be about %.3g MB (%s), more than "
                    "--max-output %g MB; add --force to write it anyway, or "
                    "%s\n", what, path, mb, how, o->max_output_mb, fewer);
    return EXIT_USAGE;
}

/* ---- progress on stderr ---------------------------------------------------- */

typedef struct progress {
    int on, tty, shown;
    double last;
    long total;
} progress;

static double now_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void progress_start(progress *p, int mode, long total)
{
    memset(p, 0, sizeof *p);
    p->tty = isatty(STDERR_FILENO);
    p->on = mode > 0 || (mode < 0 && p->tty);
    p->total = total;
    if (p->on)
        p->last = now_seconds();
}

static void progress_print(progress *p, long k, double t)
{
    fprintf(stderr, "%scarom: step %ld of %ld (%d%%), t = %.3f s%s",
            p->tty ? "\r" : "", k, p->total,
            p->total > 0 ? (int)(100.0 * (double)k / (double)p->total) : 100, t,
            p->tty ? "\033[K" : "\n");
    fflush(stderr);
    p->shown = 1;
}

static void progress_update(progress *p, long k, double t)
{
    double now;
    if (!p->on)
        return;
    now = now_seconds();
    if (p->shown && now - p->last < PROGRESS_PERIOD)
        return;
    p->last = now;
    progress_print(p, k, t);
}

/* On a terminal the line is erased; otherwise the last count is printed. */
static void progress_end(progress *p, long k, double t)
{
    if (!p->on)
        return;
    if (p->tty) {
        if (p->shown)
            fputs("\r\033[K", stderr);
    } else {
        progress_print(p, k, t);
    }
}

/* ---- render: what is recorded during the run ------------------------------ */

typedef struct recorder {
    long every;
    int bodies, frames, cap;
    render_shape *shapes;
    double *times;
    long *steps;
    render_pose *poses;
    render_impact *impacts;
    long impact_count, impact_cap, impacts_seen;
} recorder;

static void recorder_free(recorder *r)
{
    free(r->shapes);
    free(r->times);
    free(r->steps);
    free(r->poses);
    free(r->impacts);
    memset(r, 0, sizeof *r);
}

static int recorder_init(recorder *r, const scene *s, long every, long frames)
{
    int b;
    memset(r, 0, sizeof *r);
    r->every = every;
    r->bodies = s->body_count;
    r->cap = (int)frames;
    r->shapes = (render_shape *)calloc((size_t)(s->body_count ? s->body_count : 1),
                                       sizeof *r->shapes);
    r->times = (double *)malloc((size_t)frames * sizeof *r->times);
    r->steps = (long *)malloc((size_t)frames * sizeof *r->steps);
    r->poses = (render_pose *)malloc((size_t)frames * (size_t)(s->body_count ? s->body_count : 1) *
                                     sizeof *r->poses);
    if (!r->shapes || !r->times || !r->steps || !r->poses) {
        recorder_free(r);
        return -1;
    }
    for (b = 0; b < s->body_count; ++b) {
        const carom_body_def *d = &s->bodies[b].def;
        render_shape *sh = &r->shapes[b];
        sh->circle = d->shape == CAROM_SHAPE_CIRCLE;
        sh->fixed = d->type == CAROM_BODY_STATIC;
        sh->radius = d->radius;
        sh->vertex_count = d->vertex_count;
        memcpy(sh->vertices, d->vertices, sizeof sh->vertices);
    }
    return 0;
}

static void recorder_frame(recorder *r, const carom_world *w)
{
    int b;
    long step = carom_world_step_count(w);
    if (r->frames > 0 && r->steps[r->frames - 1] == step)
        return;
    if (r->frames >= r->cap)
        return; /* cannot happen: frames are counted in advance */
    r->times[r->frames] = (double)carom_world_time(w);
    r->steps[r->frames] = step;
    for (b = 0; b < r->bodies; ++b) {
        carom_body_state st;
        render_pose *p = &r->poses[(size_t)r->frames * (size_t)r->bodies + (size_t)b];
        carom_body_get_state(w, b, &st);
        p->x = st.position.x;
        p->y = st.position.y;
        p->angle = carom_rot_angle(st.rotation);
    }
    r->frames++;
}

/* A body's pose `back` seconds before its current state, moving as a
 * rigid body with its current velocities (the impact's instant inside the
 * step, after the impact). */
static render_pose pose_before(const carom_world *w, int id, double back)
{
    carom_body_state st;
    render_pose p;
    double da, c, s, ox, oy, cx, cy;
    carom_body_get_state(w, id, &st);
    da = (double)st.angular_velocity * back;
    c = cos(da);
    s = sin(da);
    ox = (double)st.position.x - (double)st.center.x;
    oy = (double)st.position.y - (double)st.center.y;
    cx = (double)st.center.x - (double)st.velocity.x * back;
    cy = (double)st.center.y - (double)st.velocity.y * back;
    p.x = (float)(cx + c * ox + s * oy); /* rotate the offset by -da */
    p.y = (float)(cy - s * ox + c * oy);
    p.angle = (float)((double)carom_rot_angle(st.rotation) - da);
    return p;
}

static void recorder_impacts(recorder *r, const carom_world *w)
{
    int n, e;
    const carom_event *ev = carom_world_events(w, &n);
    double t_end = (double)carom_world_time(w);
    for (e = 0; e < n; ++e) {
        int a = ev[e].body_a, b = ev[e].body_b;
        render_pose pa, pb;
        carom_vec2 at;
        r->impacts_seen++;
        if (r->impact_count >= MAX_MARKERS || a < 0 || b < 0 || a >= r->bodies ||
            b >= r->bodies)
            continue;
        if (r->impact_count == r->impact_cap) {
            long cap = r->impact_cap ? 2 * r->impact_cap : 256;
            render_impact *more = (render_impact *)realloc(r->impacts, (size_t)cap * sizeof *more);
            if (!more)
                continue;
            r->impacts = more;
            r->impact_cap = cap;
        }
        pa = pose_before(w, a, t_end - (double)ev[e].t);
        pb = pose_before(w, b, t_end - (double)ev[e].t);
        at = render_contact_point(&r->shapes[a], &pa, &r->shapes[b], &pb, ev[e].normal);
        r->impacts[r->impact_count].t = (double)ev[e].t;
        r->impacts[r->impact_count].x = at.x;
        r->impacts[r->impact_count].y = at.y;
        r->impact_count++;
    }
}

/* ---- the commands ---------------------------------------------------------- */

static int cmd_sim(unsigned cmd, int argc, char **argv)
{
    sim_opts o;
    long k, every = 1, frames = 0, dropped = 0;
    int i, rc;
    scene s;
    char err[512], partial[512], note[256];
    carom_world *w = NULL;
    void *mem = NULL;
    FILE *trace = NULL, *events = NULL, *svg = NULL;
    carom_op_weights weights;
    carom_profile prof;
    recorder rec;
    progress prog;
    carom_status st = CAROM_OK;
    int profile = cmd == CMD_PROFILE, render = cmd == CMD_RENDER;

    rc = parse_options(cmd, argc, argv, &o);
    if (rc >= 0)
        return rc;
    rc = 0;
    partial[0] = '\0';
    memset(&rec, 0, sizeof rec);
    if (profile && load_weights(o.weights_arg, &weights) != 0)
        return EXIT_USAGE;
    if (render && o.png_dir && !render_have_gnuplot()) {
        fprintf(stderr, "carom: --png needs gnuplot, which is not on PATH "
                        "(Debian: apt-get install gnuplot-nox); -o FILE.svg needs "
                        "nothing\n");
        return EXIT_USAGE;
    }
    if (read_scene(o.scene_path, &s, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s\n", err);
        return EXIT_USAGE;
    }
    if (o.steps >= 0)
        s.steps = o.steps;
    if (o.dt > 0.0)
        s.world.dt = (float)o.dt;
    if (o.method)
        carom_method_from_name(o.method, &s.world.method);
    if (scene_build_world(&s, &w, &mem, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s: %s\n", o.scene_path, err);
        scene_free(&s);
        return EXIT_USAGE;
    }

    /* sizes of what will be written, before anything is */
    if (o.trace_path) {
        char how[128];
        double rows = ((double)s.steps + 1.0) * (double)s.body_count;
        snprintf(how, sizeof how, "%.0f rows: (%ld steps + 1) x %d bodies", rows,
                 s.steps, s.body_count);
        if ((rc = check_output_size(&o, "--trace", o.trace_path,
                                    rows * TRACE_ROW_BYTES, how, "lower --steps")) != 0)
            goto done;
    }
    if (render) {
        double h = (double)s.world.dt;
        every = o.every > 0 ? o.every
                            : (long)floor(1.0 / ((o.fps > 0.0 ? o.fps : DEFAULT_FPS) * h) + 0.5);
        if (every < 1)
            every = 1;
        frames = s.steps / every + 1 + (s.steps % every != 0);
        if (o.output_path) {
            char how[128];
            snprintf(how, sizeof how, "%ld frames (one every %ld steps) x %d bodies",
                     frames, every, s.body_count);
            if ((rc = check_output_size(&o, "SVG", o.output_path,
                                        render_svg_estimate(frames, s.body_count, 0),
                                        how, "take fewer frames (--every, --fps) "
                                        "or lower --steps")) != 0)
                goto done;
        } else if (frames > 100000L && !o.force) {
            fprintf(stderr, "carom: --png would write %ld frames; add --force to "
                            "write them anyway, or raise --every\n", frames);
            rc = EXIT_USAGE;
            goto done;
        }
        if (recorder_init(&rec, &s, every, frames) != 0) {
            fprintf(stderr, "carom: out of memory for %ld frames\n", frames);
            rc = EXIT_USAGE;
            goto done;
        }
    }
    if (o.trace_path && !(trace = open_out(o.trace_path, 0))) {
        rc = EXIT_USAGE;
        goto done;
    }
    if (o.events_path && !(events = open_out(o.events_path, 0))) {
        rc = EXIT_USAGE;
        goto done;
    }
    if (o.output_path && !(svg = open_out(o.output_path, 1))) {
        rc = EXIT_USAGE;
        goto done;
    }
    if (trace) {
        fputs("step,t,body,x,y,angle,vx,vy,omega\n", trace);
        write_trace(trace, w);
    }
    if (events)
        fputs("t,body_a,body_b,nx,ny,impulse,approach_speed\n", events);
    if (profile) {
        carom_profile_reset(&prof);
        if (carom_world_set_profile(w, &prof) != CAROM_OK) {
            fprintf(stderr, "carom: this build has no profiler "
                            "(CAROM_ENABLE_PROFILE=0)\n");
            rc = EXIT_USAGE;
            goto done;
        }
    }
    if (render)
        recorder_frame(&rec, w);

    progress_start(&prog, o.progress, s.steps);
    for (k = 0; k < s.steps; ++k) {
        st = carom_world_step(w);
        if (st != CAROM_OK)
            break;
        dropped += carom_world_events_dropped(w);
        if (events) {
            int n, e;
            const carom_event *ev = carom_world_events(w, &n);
            for (e = 0; e < n; ++e)
                fprintf(events, "%.9g,%d,%d,%.9g,%.9g,%.9g,%.9g\n",
                        (double)ev[e].t, ev[e].body_a, ev[e].body_b,
                        (double)ev[e].normal.x, (double)ev[e].normal.y,
                        (double)ev[e].impulse, (double)ev[e].approach_speed);
        }
        if (trace)
            write_trace(trace, w);
        if (render) {
            if (o.impacts)
                recorder_impacts(&rec, w);
            if ((k + 1) % every == 0)
                recorder_frame(&rec, w);
        }
        progress_update(&prog, k + 1, (double)carom_world_time(w));
    }
    progress_end(&prog, carom_world_step_count(w), (double)carom_world_time(w));
    if (render)
        recorder_frame(&rec, w); /* the last step reached */

    if (st != CAROM_OK) {
        int eb = carom_world_error_body(w);
        char body[32] = "";
        fprintf(stderr, "carom: %s: step %ld (t = %.9g s): %s\n", o.scene_path,
                k + 1, (double)carom_world_time(w), carom_status_string(st));
        if (st == CAROM_ERR_PAIR_CAPACITY)
            fprintf(stderr, "carom: raise the world's max-pairs= (now %d)\n",
                    s.world.max_pairs);
        else if (st == CAROM_ERR_CONTACT_CAPACITY)
            fprintf(stderr, "carom: raise the world's max-contacts= (now %d)\n",
                    s.world.max_contacts);
        else if (eb >= 0)
            fprintf(stderr, "carom: body %d\n", eb);
        if (eb >= 0)
            snprintf(body, sizeof body, " (body %d)", eb);
        snprintf(partial, sizeof partial,
                 "stopped at step %ld of %ld: %s%s; the state after step %ld, "
                 "t = %.9g s", k + 1, s.steps, carom_status_string(st), body,
                 carom_world_step_count(w), (double)carom_world_time(w));
        snprintf(note, sizeof note, "partial: step %ld of %ld failed: %s%s",
                 k + 1, s.steps, carom_status_string(st), body);
        rc = EXIT_SIM;
    }
    if (dropped > 0 && (events || (render && o.impacts)))
        fprintf(stderr, "carom: warning: %ld impacts were not recorded (more "
                        "than max-events= in a step)\n", dropped);

    if (profile) {
        if (o.json) {
            print_profile_json(&prof, &weights, o.weights_arg,
                               carom_world_body_count(w), partial[0] ? partial : NULL);
        } else {
            if (partial[0])
                printf("# partial: %s\n", partial);
            print_profile_table(&prof, &weights, o.weights_arg, o.scene_path,
                                s.world.method, carom_world_body_count(w));
        }
    } else if (render) {
        render_movie m;
        render_options ro;
        char generator[64];
        snprintf(generator, sizeof generator, "carom %s", carom_version());
        m.title = o.scene_path;
        m.generator = generator;
        m.body_count = rec.bodies;
        m.shapes = rec.shapes;
        m.frame_count = rec.frames;
        m.times = rec.times;
        m.steps = rec.steps;
        m.poses = rec.poses;
        m.impact_count = (int)rec.impact_count;
        m.impacts = rec.impacts;
        m.note = partial[0] ? note : NULL;
        ro.size = (int)o.size;
        ro.impacts = o.impacts;
        ro.fixed_view = o.fixed_view;
        memcpy(ro.view, o.view, sizeof ro.view);
        if (o.impacts && rec.impacts_seen > rec.impact_count)
            fprintf(stderr, "carom: render: marking the first %ld of %ld impacts\n",
                    rec.impact_count, rec.impacts_seen);
        if (svg && render_svg(svg, &m, &ro) != 0) {
            fprintf(stderr, "carom: error writing '%s'\n", o.output_path);
            rc = EXIT_SIM;
        }
        if (o.png_dir && render_png(o.png_dir, &m, &ro, err, sizeof err) != 0) {
            fprintf(stderr, "carom: %s\n", err);
            rc = EXIT_SIM;
        }
    } else {
        if (partial[0])
            printf("# partial: %s\n", partial);
        puts("body,x,y,angle,vx,vy,omega");
        for (i = 0; i < carom_world_body_count(w); ++i)
            write_state(stdout, w, i, "");
    }
done:
    if (close_out(trace) != 0 && rc == 0) {
        fprintf(stderr, "carom: error writing '%s'\n", o.trace_path);
        rc = EXIT_SIM;
    }
    if (close_out(events) != 0 && rc == 0) {
        fprintf(stderr, "carom: error writing '%s'\n", o.events_path);
        rc = EXIT_SIM;
    }
    if (close_out(svg) != 0 && rc == 0) {
        fprintf(stderr, "carom: error writing '%s'\n", o.output_path);
        rc = EXIT_SIM;
    }
    recorder_free(&rec);
    free(mem);
    scene_free(&s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_usage(stderr);
        return EXIT_USAGE;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "help") == 0) {
        print_usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "version") == 0) {
        printf("carom %s\n", carom_version());
        return 0;
    }
    if (strcmp(argv[1], "run") == 0)
        return cmd_sim(CMD_RUN, argc - 2, argv + 2);
    if (strcmp(argv[1], "profile") == 0)
        return cmd_sim(CMD_PROFILE, argc - 2, argv + 2);
    if (strcmp(argv[1], "render") == 0)
        return cmd_sim(CMD_RENDER, argc - 2, argv + 2);
    return usage_error("unknown command '%s' (run, profile, render)", argv[1]);
}
