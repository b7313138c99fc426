/*
 * carom_cli.c -- build/carom: run scene files through the library.
 *
 *   carom run SCENE       final state as CSV (and --trace, --events)
 *   carom profile SCENE   operation counts and their weighted cost
 *   carom render SCENE    an animated SVG (and PNG frames with gnuplot)
 *   carom lean SCENE      a header of switches and capacities for the
 *                         smallest build that gives the scene's results
 *
 * The commands share one table of options (`options` below, read by
 * cli_options.c, the parser build/carom-box2d uses too); run, profile
 * and render share one simulation loop. Exit status: 0 success, 1 the
 * simulation reported an error (the state reached is still written,
 * marked partial), 2 bad usage or a bad scene.
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
#include "cli_options.h"
#include "render/render.h"
#include "scene.h"

#define EXIT_SIM 1
/* render --view: largest corner coordinate and smallest side, m */
#define VIEW_MAX (10.0 * (double)CAROM_LIMIT_MAX_LENGTH)
#define VIEW_MIN ((double)CAROM_LIMIT_MIN_SIZE)
#define EXIT_USAGE CLI_EXIT_USAGE

/* Scene files larger than this are refused (as tools/scene.c does). */
#define SCENE_MAX_BYTES (64L << 20)
/* Estimated bytes per --trace row ("step,t,body,x,y,angle,vx,vy,omega"
 * with %.9g numbers: 40 to 140, about 70 for moving bodies). */
#define TRACE_ROW_BYTES 72.0
/* Default of --max-output, MB (10^6 bytes). */
#define DEFAULT_MAX_OUTPUT_MB 300.0
/* render: default and largest --fps, default, least and largest --size,
 * most impact markers. MIN_SIZE is render.c's MIN_WIDTH_PX, the narrowest
 * picture it draws (room for the time label): a smaller --size could not
 * be the picture's longer side. */
#define DEFAULT_FPS 30.0
#define MAX_FPS 60.0
#define DEFAULT_SIZE 640L
#define MIN_SIZE 260L
#define MAX_SIZE 16384L
#define MAX_MARKERS 10000L
/* Progress is refreshed at most this often (seconds). */
#define PROGRESS_PERIOD 0.2
/* lean: default --margin (per cent) and --slack of the capacities. */
#define LEAN_DEFAULT_MARGIN 25L
#define LEAN_DEFAULT_SLACK 4L

/* ---- options: one table for run, profile and render ---------------------- */

/* Commands, as bits: an option lists the commands that accept it. CMD_SIM:
 * the three that step a scene and write what happened; CMD_ALL: every
 * command. */
enum {
    CMD_RUN = 1u, CMD_PROFILE = 2u, CMD_RENDER = 4u, CMD_LEAN = 8u,
    CMD_SIM = 7u, CMD_ALL = 15u
};

typedef enum opt_id {
    OPT_STEPS, OPT_DT, OPT_METHOD, OPT_TRACE, OPT_EVENTS, OPT_MAX_OUTPUT,
    OPT_FORCE, OPT_PROGRESS, OPT_NO_PROGRESS, OPT_WEIGHTS, OPT_JSON,
    OPT_OUTPUT, OPT_PNG, OPT_FPS, OPT_EVERY, OPT_IMPACTS, OPT_SIZE, OPT_VIEW,
    OPT_MARGIN, OPT_SLACK, OPT_CALIBRATION, OPT_HELP
} opt_id;

static const cli_option options[] = {
    {OPT_STEPS, "steps", 0, "N", CMD_ALL,
     "number of steps (overrides the scene's steps=)"},
    {OPT_DT, "dt", 0, "DT", CMD_ALL, "time step in seconds (overrides dt=)"},
    {OPT_METHOD, "method", 0, "NAME", CMD_ALL,
     "events (default), discrete or first-impact\n"
     "(overrides method=; see docs/events.md)"},
    {OPT_TRACE, "trace", 0, "FILE", CMD_SIM,
     "write every body's state at step 0 and after every\n"
     "step: step,t,body,x,y,angle,vx,vy,omega (a file:\n"
     "'-' is refused, standard output holds the result)"},
    {OPT_EVENTS, "events", 0, "FILE", CMD_SIM,
     "write every impact, in time order:\n"
     "t,body_a,body_b,nx,ny,impulse,approach_speed\n"
     "(a file, as for --trace)"},
    {OPT_MAX_OUTPUT, "max-output", 0, "MB", CMD_SIM,
     "refuse a --trace or an SVG estimated larger than MB\n"
     "megabytes (default 300) unless --force"},
    {OPT_FORCE, "force", 0, NULL, CMD_SIM,
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
    {OPT_CALIBRATION, "calibration", 0, "FILE", CMD_PROFILE,
     "also predict what the run executes on a target, from\n"
     "a calibration file (tools/embedded/cortex-m4f.cal:\n"
     "instructions on a Cortex-M4F, docs/embedded.md)"},
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
     "pixels of the view's longer side, 260 to 16384\n"
     "(default 640; the picture is at least 260 wide, for\n"
     "the time label)"},
    {OPT_VIEW, "view", 0, "X0,Y0,X1,Y1", CMD_RENDER,
     "show this rectangle of the world (m) instead of\n"
     "fitting every body over the whole run"},
    {OPT_MARGIN, "margin", 0, "PCT", CMD_LEAN,
     "capacities: the worst case met plus PCT per cent\n"
     "(default 25) plus --slack"},
    {OPT_SLACK, "slack", 0, "N", CMD_LEAN, "capacities: plus N more (default 4)"},
    {OPT_HELP, "help", 'h', NULL, CMD_ALL, "show this help"},
};
#define OPTION_COUNT ((int)(sizeof options / sizeof options[0]))

typedef struct sim_opts {
    unsigned cmd;
    const char *scene_path, *trace_path, *events_path, *output_path, *png_dir;
    const char *method, *weights_arg, *calibration_path;
    long steps;         /* -1: the scene's */
    double dt;          /* <= 0: the scene's */
    double max_output_mb;
    int force, progress; /* progress: -1 auto, 0 off, 1 on */
    int json, impacts;
    double fps;         /* <= 0: not given */
    long every;         /* 0: not given */
    long size;
    long margin, slack; /* lean: capacity = need + need * margin / 100 + slack */
    int fixed_view;
    double view[4];     /* xmin, ymin, xmax, ymax */
} sim_opts;

/* A set of commands as the messages name it. */
static const char *cmds_name(unsigned cmds)
{
    switch (cmds) {
    case CMD_RUN: return "run";
    case CMD_PROFILE: return "profile";
    case CMD_RENDER: return "render";
    case CMD_LEAN: return "lean";
    case CMD_SIM: return "run, profile and render";
    default: return "every command";
    }
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
          "       carom lean SCENE [--margin PCT] [--slack N] [options] > carom_lean.h\n"
          "       carom --help | --version\n"
          "\n"
          "run: step a scene file (docs/scene-format.md; '-' reads stdin) and\n"
          "write the final state of every body to stdout as CSV:\n"
          "body,x,y,angle,vx,vy,omega (x, y: body origin; angle in radians in\n"
          "[-pi, pi]; vx, vy: velocity of the centre of mass; omega: angular\n"
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
          "lean: run the scene once (twice if friction might act) and print a C\n"
          "header of #defines for the smallest build of carom that gives the same\n"
          "results on it: every capability switch of carom_config.h on or off,\n"
          "each with the reason, and the capacities of carom_world_def (bodies,\n"
          "pairs, contacts, impacts and events per step: the worst case met plus\n"
          "--margin and --slack) with the world buffer they need. Build the library\n"
          "and the program with it: cc -include carom_lean.h ... (make lean\n"
          "SCENE=FILE does it and checks the results are the same).\n"
          "\n"
          "Scene files may end lines with LF, CR LF or CR, and may start with a\n"
          "UTF-8 byte-order mark.\n"
          "\n"
          "Options are written --opt VALUE or --opt=VALUE, each at most once.\n"
          "\n"
          "options of every command:\n", f);
    print_option_help(f, CMD_ALL);
    fputs("options of run, profile and render:\n", f);
    print_option_help(f, CMD_SIM);
    fputs("options of profile:\n", f);
    print_option_help(f, CMD_PROFILE);
    fputs("options of render (at least one of -o and --png):\n", f);
    print_option_help(f, CMD_RENDER);
    fputs("options of lean:\n", f);
    print_option_help(f, CMD_LEAN);
    fputs("\n"
          "Progress (step, share done, simulated time) goes to stderr when it is\n"
          "a terminal, on one line that is erased when the run ends.\n"
          "\n"
          "exit status: 0 ok, 1 simulation error (or an output not written\n"
          "completely), 2 bad usage or bad scene\n", f);
}

static int apply_option(sim_opts *o, const cli_parser *p)
{
    const char *v = p->value;
    switch ((opt_id)p->opt->id) {
    case OPT_STEPS:
        return cli_long(p, 0, 1000000000L, NULL, &o->steps);
    case OPT_DT: {
        /* carom's range (CAROM_LIMIT_MIN_DT ... _MAX_DT) for the float the
         * world takes, checked here so that the message names the option,
         * not the scene */
        int rc = cli_double(p, 0.0, CLI_OPEN, 1.0e30, "a finite number > 0", &o->dt);
        if (rc == 0 && !((float)o->dt >= CAROM_LIMIT_MIN_DT && (float)o->dt <= CAROM_LIMIT_MAX_DT))
            return cli_usage_error("carom", "--dt: the time step must be in [%g, %g] s "
                                   "(CAROM_LIMIT_MIN_DT, _MAX_DT), got '%s'",
                                   (double)CAROM_LIMIT_MIN_DT, (double)CAROM_LIMIT_MAX_DT, v);
        return rc;
    }
    case OPT_METHOD: {
        carom_method m;
        if (carom_method_from_name(v, &m) != CAROM_OK)
            return cli_usage_error("carom", "--method: unknown method '%s' (events, "
                                   "discrete, first-impact)", v);
        o->method = v;
        return 0;
    }
    case OPT_TRACE:
    case OPT_EVENTS:
        /* '-' is not standard output here: that holds the final state, the
         * profile or render's -o -, and a CSV mixed into it is unreadable */
        if (strcmp(v, "-") == 0)
            return cli_usage_error("carom", "--%s: '-' (standard output) is not possible: "
                                   "standard output holds the command's result; give a "
                                   "file name (./- for a file named -)", p->opt->name);
        if (p->opt->id == OPT_TRACE)
            o->trace_path = v;
        else
            o->events_path = v;
        return 0;
    case OPT_MAX_OUTPUT:
        return cli_double(p, 0.0, CLI_CLOSED, 1.0e12, "a number of megabytes >= 0",
                          &o->max_output_mb);
    case OPT_FORCE: o->force = 1; return 0;
    case OPT_PROGRESS: o->progress = 1; return 0;
    case OPT_NO_PROGRESS: o->progress = 0; return 0;
    case OPT_WEIGHTS: o->weights_arg = v; return 0;
    case OPT_JSON: o->json = 1; return 0;
    case OPT_CALIBRATION: o->calibration_path = v; return 0;
    case OPT_OUTPUT: o->output_path = v; return 0;
    case OPT_PNG: o->png_dir = v; return 0;
    case OPT_FPS:
        return cli_double(p, 0.0, CLI_OPEN, MAX_FPS, "a number in (0, 60]", &o->fps);
    case OPT_EVERY:
        return cli_long(p, 1, 1000000000L, NULL, &o->every);
    case OPT_IMPACTS: o->impacts = 1; return 0;
    case OPT_SIZE: {
        char want[128];
        snprintf(want, sizeof want, "an integer in [%ld, %ld] (pixels; a picture is at "
                 "least %ld wide, for the time label)", MIN_SIZE, MAX_SIZE, MIN_SIZE);
        return cli_long(p, MIN_SIZE, MAX_SIZE, want, &o->size);
    }
    case OPT_MARGIN:
        return cli_long(p, 0, 1000, NULL, &o->margin);
    case OPT_SLACK:
        return cli_long(p, 0, 1000000, NULL, &o->slack);
    case OPT_VIEW: {
        char extra;
        if (sscanf(v, "%lf,%lf,%lf,%lf%c", &o->view[0], &o->view[1], &o->view[2],
                   &o->view[3], &extra) != 4 || !isfinite(o->view[0]) ||
            !isfinite(o->view[1]) || !isfinite(o->view[2]) ||
            !isfinite(o->view[3]) || !(o->view[2] > o->view[0]) ||
            !(o->view[3] > o->view[1]))
            return cli_usage_error("carom", "--view: want X0,Y0,X1,Y1 with X0 < X1 and "
                                   "Y0 < Y1 (metres), got '%s'", v);
        /* corners within ten times the longest coordinate a body may have,
         * sides no shorter than the smallest body (a narrower view has no
         * scale a picture can show: its pixels would be 1e300 per metre) */
        if (fabs(o->view[0]) > VIEW_MAX || fabs(o->view[1]) > VIEW_MAX ||
            fabs(o->view[2]) > VIEW_MAX || fabs(o->view[3]) > VIEW_MAX ||
            o->view[2] - o->view[0] < VIEW_MIN || o->view[3] - o->view[1] < VIEW_MIN)
            return cli_usage_error("carom", "--view: corners must be within %g m of the "
                                   "origin and each side at least %g m, got '%s'",
                                   VIEW_MAX, VIEW_MIN, v);
        o->fixed_view = 1;
        return 0;
    }
    case OPT_HELP:
        break;
    }
    return 0;
}

/* Returns -1 to go on, or an exit status (0 after --help). */
static int parse_options(unsigned cmd, int argc, char **argv, sim_opts *o)
{
    cli_parser p;
    cli_item item;
    int rc;
    memset(o, 0, sizeof *o);
    o->cmd = cmd;
    o->steps = -1;
    o->dt = -1.0;
    o->max_output_mb = DEFAULT_MAX_OUTPUT_MB;
    o->progress = -1;
    o->weights_arg = "seed";
    o->size = DEFAULT_SIZE;
    o->margin = LEAN_DEFAULT_MARGIN;
    o->slack = LEAN_DEFAULT_SLACK;
    cli_start(&p, "carom", options, OPTION_COUNT, cmd, argc, argv);
    p.cmds_name = cmds_name;
    while ((item = cli_next(&p)) != CLI_END) {
        if (item == CLI_ERROR)
            return EXIT_USAGE;
        if (item == CLI_OPERAND) {
            if (o->scene_path)
                return cli_usage_error("carom", "more than one scene given ('%s')", p.value);
            o->scene_path = p.value;
        } else if (p.opt->id == OPT_HELP) {
            print_usage(stdout);
            return 0;
        } else if ((rc = apply_option(o, &p)) != 0) {
            return rc;
        }
    }
    if (!o->scene_path)
        return cli_usage_error("carom", "%s: missing SCENE", cmds_name(cmd));
    if (cmd == CMD_RENDER) {
        if (!o->output_path && !o->png_dir)
            return cli_usage_error("carom", "render: say where to draw: -o FILE.svg and/or "
                                   "--png DIR");
        if (o->fps > 0.0 && o->every > 0)
            return cli_usage_error("carom", "render: give --fps or --every, not both");
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

/* A value for the CSV outputs, -0 written as 0: a normal (-1, -0) or a
 * velocity -0 is the library's sign of zero, not something to read. */
static double csv_num(float x)
{
    return x == 0.0f ? 0.0 : (double)x;
}

static void write_state(FILE *f, const carom_world *w, int i, const char *prefix)
{
    carom_body_state st;
    carom_body_get_state(w, i, &st);
    fprintf(f, "%s%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", prefix, i,
            csv_num(st.position.x), csv_num(st.position.y),
            csv_num(scene_rot_angle(st.rotation)), csv_num(st.velocity.x),
            csv_num(st.velocity.y), csv_num(st.angular_velocity));
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

/* A text input file for --weights or --calibration: NULL with errno
 * EISDIR for a directory (fopen opens one for reading, and every read
 * fails, which read as an empty file). */
static FILE *open_text(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        errno = EISDIR;
        return NULL;
    }
    return fopen(path, "r");
}

/* The next line of f into buf (1), 0 at the end; -1, with a message naming
 * file and line, for a line longer than buf holds (fgets would split it,
 * and its second part be read as the next line). */
static int next_line(FILE *f, char *buf, size_t n, const char *path, int lineno)
{
    size_t len;
    if (!fgets(buf, (int)n, f))
        return 0;
    len = strlen(buf);
    if (len + 1 == n && buf[len - 1] != '\n' && !feof(f)) {
        fprintf(stderr, "carom: %s:%d: line longer than %lu characters\n", path, lineno,
                (unsigned long)(n - 2));
        return -1;
    }
    return 1;
}

/* A weight preset name, or a file of "KIND WEIGHT" lines (all six kinds,
 * each once, weights finite and >= 0). */
static int load_weights(const char *arg, carom_op_weights *out)
{
    FILE *f;
    char line[256];
    int lineno = 0, seen[CAROM_OP_COUNT] = {0}, k, got;
    if (carom_op_weights_preset(arg, out) == CAROM_OK)
        return 0;
    f = open_text(arg);
    if (!f) {
        fprintf(stderr, "carom: --weights: '%s' is neither a preset (seed, "
                        "cortex-m4f, cortex-m0) nor a readable file: %s\n",
                arg, strerror(errno));
        return -1;
    }
    while ((got = next_line(f, line, sizeof line, arg, lineno + 1)) != 0) {
        char kind[32], extra[2];
        double v;
        char *hash = strchr(line, '#');
        int n;
        ++lineno;
        if (got < 0) {
            fclose(f);
            return -1;
        }
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

/* What `profile` adds up besides the op counts, from carom_world_get_stats
 * after every step: the work the op counts do not see scales with them. */
typedef struct run_sums {
    double awake_body_steps; /* bodies simulated, summed over the steps */
    double contact_steps;    /* contacts, summed over the steps */
} run_sums;

/* A calibration (--calibration FILE, written by make embedded-calibrate):
 * per phase, and for the step outside the phases ("step"), instructions =
 * per_op x the phase's operations (step: all of them) + per_step x steps +
 * per_body_step x body-steps + per_awake_body_step x awake body-steps +
 * per_contact_step x contact-steps; a phase that counted no operation adds
 * nothing. */
#define CAL_ROWS (CAROM_PHASE_COUNT + 1)
#define CAL_TERMS 5
typedef struct calibration {
    char name[64], unit[64];
    double c[CAL_ROWS][CAL_TERMS];
} calibration;

static const char *cal_row_name(int row)
{
    return row < CAROM_PHASE_COUNT ? carom_phase_name((carom_phase)row) : "step";
}

static int load_calibration(const char *path, calibration *cal)
{
    FILE *f = open_text(path);
    char line[512];
    int lineno = 0, seen[CAL_ROWS] = {0}, header = 0, row, got;
    if (!f) {
        fprintf(stderr, "carom: --calibration: cannot read '%s': %s\n", path, strerror(errno));
        return -1;
    }
    memset(cal, 0, sizeof *cal);
    strcpy(cal->name, "calibration");
    strcpy(cal->unit, "units");
    while ((got = next_line(f, line, sizeof line, path, lineno + 1)) != 0) {
        char word[64], rest[64], extra[2];
        double v[CAL_TERMS];
        char *hash = strchr(line, '#');
        int n;
        ++lineno;
        if (got < 0) {
            fclose(f);
            return -1;
        }
        if (hash)
            *hash = '\0';
        n = sscanf(line, "%63s", word);
        if (n <= 0)
            continue;
        if (!header) {
            if (strcmp(word, "carom-calibration") != 0 ||
                sscanf(line, "%*s %63s %1s", rest, extra) != 1 || strcmp(rest, "1") != 0) {
                fprintf(stderr, "carom: %s:%d: not a calibration file (want "
                                "'carom-calibration 1' first)\n", path, lineno);
                fclose(f);
                return -1;
            }
            header = 1;
            continue;
        }
        if (strcmp(word, "name") == 0 || strcmp(word, "unit") == 0) {
            if (sscanf(line, "%*s %63s %1s", rest, extra) != 1) {
                fprintf(stderr, "carom: %s:%d: want '%s WORD'\n", path, lineno, word);
                fclose(f);
                return -1;
            }
            strcpy(word[0] == 'n' ? cal->name : cal->unit, rest);
            continue;
        }
        for (row = 0; row < CAL_ROWS; ++row)
            if (strcmp(word, cal_row_name(row)) == 0)
                break;
        if (row == CAL_ROWS) {
            fprintf(stderr, "carom: %s:%d: unknown row '%s' (a phase, or step)\n", path,
                    lineno, word);
            fclose(f);
            return -1;
        }
        if (sscanf(line, "%*s %lf %lf %lf %lf %lf %1s", &v[0], &v[1], &v[2], &v[3], &v[4],
                   extra) != CAL_TERMS) {
            fprintf(stderr, "carom: %s:%d: want '%s' and %d numbers\n", path, lineno, word,
                    CAL_TERMS);
            fclose(f);
            return -1;
        }
        if (seen[row]++) {
            fprintf(stderr, "carom: %s:%d: '%s' given twice\n", path, lineno, word);
            fclose(f);
            return -1;
        }
        for (n = 0; n < CAL_TERMS; ++n) {
            if (!isfinite(v[n]) || v[n] < 0.0 || v[n] > 1e12) {
                fprintf(stderr, "carom: %s:%d: numbers must be finite and >= 0\n", path, lineno);
                fclose(f);
                return -1;
            }
            cal->c[row][n] = v[n];
        }
    }
    fclose(f);
    if (!header) {
        fprintf(stderr, "carom: %s: empty calibration file\n", path);
        return -1;
    }
    for (row = 0; row < CAL_ROWS; ++row) {
        if (!seen[row]) {
            fprintf(stderr, "carom: %s: no row for '%s'\n", path, cal_row_name(row));
            return -1;
        }
    }
    return 0;
}

/* The calibrated prediction of each row (CAL_ROWS of them); returns the
 * total. */
static double calibrated(const calibration *cal, const carom_profile *p,
                         const run_sums *sums, double out[CAL_ROWS])
{
    double total = 0.0, all_ops = 0.0;
    int row, k;
    for (row = 0; row < CAROM_PHASE_COUNT; ++row)
        for (k = 0; k < CAROM_OP_COUNT; ++k)
            all_ops += (double)p->ops[row][k];
    for (row = 0; row < CAL_ROWS; ++row) {
        double ops = 0.0, x;
        if (row < CAROM_PHASE_COUNT) {
            for (k = 0; k < CAROM_OP_COUNT; ++k)
                ops += (double)p->ops[row][k];
        } else {
            ops = all_ops;
        }
        x = row < CAROM_PHASE_COUNT && ops == 0.0
                ? 0.0
                : cal->c[row][0] * ops + cal->c[row][1] * (double)p->steps +
                      cal->c[row][2] * (double)p->body_steps +
                      cal->c[row][3] * sums->awake_body_steps +
                      cal->c[row][4] * sums->contact_steps;
        out[row] = x;
        total += x;
    }
    return total;
}

static void print_calibrated_table(const calibration *cal, const char *path,
                                   const carom_profile *p, const run_sums *sums)
{
    double rows[CAL_ROWS], total = calibrated(cal, p, sums, rows);
    int row;
    printf("\ncalibrated (%s, %s): predicted %s\n", cal->name, path, cal->unit);
    for (row = 0; row < CAL_ROWS; ++row)
        printf("%-19s %14.0f %5.1f%%\n",
               row < CAROM_PHASE_COUNT ? cal_row_name(row) : "step (no phase)", rows[row],
               total > 0.0 ? 100.0 * rows[row] / total : 0.0);
    printf("%-19s %14.0f %5.1f%%\n", "total", total, total > 0.0 ? 100.0 : 0.0);
    printf("%s per step %14.1f\n", cal->unit, p->steps ? total / (double)p->steps : 0.0);
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
                                carom_method method, int bodies, const run_sums *sums)
{
    int ph, k;
    double total = 0.0, impulse;
    uint64_t kinds[CAROM_OP_COUNT] = {0};
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
        total += phase_cost(p, wt, ph);
    printf("scene %s: method %s, %lu steps, %d bodies, %lu body-steps, %lu impacts\n",
           path, carom_method_name(method), (unsigned long)p->steps, bodies,
           (unsigned long)p->body_steps, (unsigned long)p->impacts);
    printf("awake body-steps %.0f, contact-steps %.0f\n", sums->awake_body_steps,
           sums->contact_steps);
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
    /* no work (no bodies, no steps): no shares, not 100 % of nothing */
    printf(" %14.1f %5.1f%%\n\n", total, total > 0 ? 100.0 : 0.0);
    impulse = phase_cost(p, wt, CAROM_PHASE_IMPULSES);
    /* a run whose first step failed took no step: its counts are the
     * failed step's work (executed, then rolled back), per nothing */
    if (p->steps)
        printf("cost per step      %14.1f\n", total / (double)p->steps);
    else
        printf("cost per step      %14s\n", "(no step taken)");
    if (p->body_steps)
        printf("cost per body-step %14.1f\n", total / (double)p->body_steps);
    else
        printf("cost per body-step %14s\n", "(no body-steps)");
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
                               const char *wname, int bodies, const char *partial,
                               const run_sums *sums, const calibration *cal)
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
    printf("\"awake_body_steps\": %.0f, \"contact_steps\": %.0f, ",
           sums->awake_body_steps, sums->contact_steps);
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
    printf("}, \"total_cost\": %.17g", total);
    if (cal) {
        double rows[CAL_ROWS], sum = calibrated(cal, p, sums, rows);
        printf(", \"calibrated\": {\"name\": ");
        put_json_string(cal->name);
        printf(", \"unit\": ");
        put_json_string(cal->unit);
        printf(", \"rows\": {");
        for (ph = 0; ph < CAL_ROWS; ++ph)
            printf("%s\"%s\": %.17g", ph ? ", " : "", cal_row_name(ph), rows[ph]);
        printf("}, \"total\": %.17g}", sum);
    }
    printf("}\n");
}

/* '-' is stdout only where allowed (render -o; --trace and --events refuse
 * it when the options are read). */
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
        p->angle = scene_rot_angle(st.rotation);
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
    p.angle = (float)((double)scene_rot_angle(st.rotation) - da);
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

#ifdef CAROM_LEAN_MAX_BODIES
/* A lean build (make lean, with the header of `carom lean`): worlds take the
 * header's capacities wherever the scene leaves them at their default and
 * has no more bodies than the header's, so its runs prove they suffice. */
static void apply_lean_capacities(scene *s)
{
    if (s->body_count > CAROM_LEAN_MAX_BODIES)
        return;
    if (s->world.max_pairs == 0)
        s->world.max_pairs = CAROM_LEAN_MAX_PAIRS;
    if (s->world.max_contacts == 0)
        s->world.max_contacts = CAROM_LEAN_MAX_CONTACTS;
    if (s->world.max_impacts == 0)
        s->world.max_impacts = CAROM_LEAN_MAX_IMPACTS;
    if (s->world.max_events == 0)
        s->world.max_events = CAROM_LEAN_MAX_EVENTS;
}
#endif

#ifdef CAROM_LEAN_STEPS
/* A lean build's switches decided from the motion hold for the run
 * `carom lean` measured: say so when this run goes beyond it. */
static void lean_warn_beyond(const scene *s)
{
    const char *m = carom_method_name(s->world.method);
    if (s->steps <= CAROM_LEAN_STEPS && s->world.dt == CAROM_LEAN_DT &&
        strcmp(m, CAROM_LEAN_METHOD) == 0)
        return;
    fprintf(stderr,
            "carom: warning: this lean build was measured on %s\n"
            "carom: (%ld steps of %.9g s, method %s); this run (%ld steps of %.9g s,\n"
            "carom: method %s) goes beyond it, where the switches decided from the\n"
            "carom: motion (polygon-polygon, rotation, friction, impact rows) may not\n"
            "carom: hold: run `carom lean` on this run\n",
            CAROM_LEAN_SCENE, (long)CAROM_LEAN_STEPS, (double)CAROM_LEAN_DT, CAROM_LEAN_METHOD,
            s->steps, (double)s->world.dt, m);
}
#endif

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
    run_sums sums = {0.0, 0.0};
    calibration cal;
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
    if (profile && o.calibration_path && load_calibration(o.calibration_path, &cal) != 0)
        return EXIT_USAGE;
    if (render && o.png_dir && !render_have_gnuplot()) {
        fprintf(stderr, "carom: --png needs gnuplot, which is not on PATH "
                        "(Debian: apt-get install gnuplot-nox); -o FILE.svg needs "
                        "nothing\n");
        return EXIT_USAGE;
    }
    /* an output that cannot be opened is a usage error, before any step */
    if (render && o.png_dir && render_png_dir(o.png_dir, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s\n", err);
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
#ifdef CAROM_LEAN_MAX_BODIES
    apply_lean_capacities(&s);
#endif
#ifdef CAROM_LEAN_STEPS
    lean_warn_beyond(&s);
#endif
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
        if (o.every > 0) {
            every = o.every;
        } else {
            /* steps per frame, at most one frame for the whole run (a tiny
             * --fps: the cast of a huge quotient to long is undefined) */
            double per = floor(1.0 / ((o.fps > 0.0 ? o.fps : DEFAULT_FPS) * h) + 0.5);
            every = !(per < (double)s.steps) ? (s.steps > 0 ? s.steps : 1) : (long)per;
        }
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
        if (profile) {
            carom_stats stats;
            carom_world_get_stats(w, &stats);
            sums.awake_body_steps += (double)stats.awake_bodies;
            sums.contact_steps += (double)stats.contacts;
        }
        if (events) {
            int n, e;
            const carom_event *ev = carom_world_events(w, &n);
            for (e = 0; e < n; ++e)
                fprintf(events, "%.9g,%d,%d,%.9g,%.9g,%.9g,%.9g\n",
                        csv_num(ev[e].t), ev[e].body_a, ev[e].body_b,
                        csv_num(ev[e].normal.x), csv_num(ev[e].normal.y),
                        csv_num(ev[e].impulse), csv_num(ev[e].approach_speed));
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
                               carom_world_body_count(w), partial[0] ? partial : NULL,
                               &sums, o.calibration_path ? &cal : NULL);
        } else {
            if (partial[0])
                printf("# partial: %s\n", partial);
            print_profile_table(&prof, &weights, o.weights_arg, o.scene_path,
                                s.world.method, carom_world_body_count(w), &sums);
            if (o.calibration_path)
                print_calibrated_table(&cal, o.calibration_path, &prof, &sums);
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
    /* the report and final state on standard output (a full disk, a
     * closed pipe's reader): lost output is a failure, as for files */
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == 0) {
        fprintf(stderr, "carom: error writing standard output\n");
        rc = EXIT_SIM;
    }
    recorder_free(&rec);
    scene_free_world(w, mem);
    scene_free(&s);
    return rc;
}

/* ---- lean: the smallest build that gives a scene's results ------------------ */

/* Shape pairs whose meeting `lean` records. */
enum { MEET_CC, MEET_CP, MEET_PP, MEET_KINDS };
static const char *const meet_names[MEET_KINDS] = {
    "circle-circle", "circle-polygon", "polygon-polygon"
};

/* What one run of the scene needed. Steps are counted from 1 (0: the
 * start); -1: never. */
typedef struct lean_need {
    long steps;
    int bodies, circles, polygons, dynamic_polygons, kinematic;
    int first_polygon, first_dynamic_polygon, first_kinematic;
    int max_vertices;        /* most vertices of a polygon (0: none) */
    int forced;              /* first body with a force or torque, or -1 */
    long spin_step;          /* first angular velocity or turn seen */
    int spin_body;
    long sleep_step;         /* first body asleep at a step's end */
    int sleep_body;
    int friction_pair;       /* two bodies that can touch (not both static)
                                both have friction > 0 */
    long friction_step;      /* first step whose state differs when every
                                friction is 0 (-1: none; not run if no
                                friction_pair) */
    long met_step[MEET_KINDS]; /* first step a pair of that kind came
                                  within reach */
    long lever_step;         /* first step a moving polygon came within
                                reach of another body */
    int lever_a, lever_b;
    int met_a[MEET_KINDS], met_b[MEET_KINDS];
    int events;              /* most impacts of a step: recorded + dropped */
    long dropped;            /* impacts not recorded, whole run */
    carom_stats stats;
    double slop;             /* linear slop at the start, m */
} lean_need;

/* A body's motion over one step, for the reach test. */
typedef struct lean_mover {
    double x0, y0, x1, y1; /* centre of mass at the step's start and end */
    double r;              /* bounding radius about the centre of mass */
    double reach;          /* how far it can stray from the segment */
    double lo_x, hi_x, lo_y, hi_y;
    int kind;              /* 0 circle, 1 polygon */
    int moving;            /* not static */
} lean_mover;

static const lean_mover *lean_sort_base;

static int lean_cmp_lo(const void *a, const void *b)
{
    double x = lean_sort_base[*(const int *)a].lo_x;
    double y = lean_sort_base[*(const int *)b].lo_x;
    return x < y ? -1 : x > y ? 1 : *(const int *)a - *(const int *)b;
}

static double clamp01(double t) { return t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t; }

/* Squared distance between segments p0-p1 and q0-q1 (closest points of
 * two segments, as in Ericson's Real-Time Collision Detection 5.1.9). */
static double seg_dist2(double p0x, double p0y, double p1x, double p1y,
                        double q0x, double q0y, double q1x, double q1y)
{
    double d1x = p1x - p0x, d1y = p1y - p0y, d2x = q1x - q0x, d2y = q1y - q0y;
    double rx = p0x - q0x, ry = p0y - q0y;
    double a = d1x * d1x + d1y * d1y, e = d2x * d2x + d2y * d2y;
    double f = d2x * rx + d2y * ry, s, t, dx, dy;
    if (a <= 1e-300 && e <= 1e-300) {
        s = t = 0.0;
    } else if (a <= 1e-300) {
        s = 0.0;
        t = clamp01(f / e);
    } else {
        double c = d1x * rx + d1y * ry;
        if (e <= 1e-300) {
            t = 0.0;
            s = clamp01(-c / a);
        } else {
            double b = d1x * d2x + d1y * d2y, den = a * e - b * b;
            s = den > 0.0 ? clamp01((b * f - c * e) / den) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = clamp01(-c / a);
            } else if (t > 1.0) {
                t = 1.0;
                s = clamp01((b - c) / a);
            }
        }
    }
    dx = p0x + d1x * s - (q0x + d2x * t);
    dy = p0y + d1y * s - (q0y + d2y * t);
    return dx * dx + dy * dy;
}

/* Bounding radius of body i about its centre of mass. */
static double lean_radius(const scene *s, int i, const carom_body_state *st)
{
    const carom_body_def *d = &s->bodies[i].def;
    double cx, cy, lx, ly, r = 0.0, c = (double)st->rotation.c,
           sn = (double)st->rotation.s;
    int k;
    if (d->shape == CAROM_SHAPE_CIRCLE)
        return (double)d->radius;
    /* the centre in the body frame: R^T (center - position) */
    cx = (double)st->center.x - (double)st->position.x;
    cy = (double)st->center.y - (double)st->position.y;
    lx = c * cx + sn * cy;
    ly = -sn * cx + c * cy;
    for (k = 0; k < d->vertex_count; ++k) {
        double dx = (double)d->vertices[k].x - lx, dy = (double)d->vertices[k].y - ly;
        double q = sqrt(dx * dx + dy * dy);
        if (q > r)
            r = q;
    }
    return r;
}

/* Mark the shape pairs that may have met during the step just taken:
 * bounding circles swept along their centres' paths, widened by each
 * body's speed times dt (a bounce inside the step), |g| dt^2 and ten
 * slops (the contact reach). Generous on purpose: a false "met" only
 * keeps code that was not needed. */
static void lean_reach(lean_need *n, lean_mover *m, int *order, int count, long step)
{
    int i, j;
    for (i = 0; i < count; ++i) {
        lean_mover *a = &m[i];
        double w = a->r * 1.05 + a->reach;
        a->lo_x = (a->x0 < a->x1 ? a->x0 : a->x1) - w;
        a->hi_x = (a->x0 > a->x1 ? a->x0 : a->x1) + w;
        a->lo_y = (a->y0 < a->y1 ? a->y0 : a->y1) - w;
        a->hi_y = (a->y0 > a->y1 ? a->y0 : a->y1) + w;
        order[i] = i;
    }
    lean_sort_base = m;
    qsort(order, (size_t)count, sizeof *order, lean_cmp_lo);
    for (i = 0; i < count; ++i) {
        const lean_mover *a = &m[order[i]];
        for (j = i + 1; j < count && m[order[j]].lo_x <= a->hi_x; ++j) {
            const lean_mover *b = &m[order[j]];
            double lim;
            int kind = a->kind + b->kind;
            int lever = (a->moving && a->kind) || (b->moving && b->kind);
            if ((!a->moving && !b->moving) ||
                (n->met_step[kind] >= 0 && (!lever || n->lever_step >= 0)) ||
                b->lo_y > a->hi_y || a->lo_y > b->hi_y)
                continue;
            lim = 1.05 * (a->r + b->r) + a->reach + b->reach;
            if (seg_dist2(a->x0, a->y0, a->x1, a->y1, b->x0, b->y0, b->x1, b->y1) <=
                lim * lim) {
                int lo = order[i] < order[j] ? order[i] : order[j];
                int hi = order[i] < order[j] ? order[j] : order[i];
                if (n->met_step[kind] < 0) {
                    n->met_step[kind] = step;
                    n->met_a[kind] = lo;
                    n->met_b[kind] = hi;
                }
                if (lever && n->lever_step < 0) {
                    n->lever_step = step;
                    n->lever_a = lo;
                    n->lever_b = hi;
                }
            }
        }
    }
}

/* Same bits (positions, rotations, velocities) in two worlds? */
static int lean_same_state(const carom_world *a, const carom_world *b, int bodies)
{
    int i;
    for (i = 0; i < bodies; ++i) {
        carom_body_state x, y;
        carom_body_get_state(a, i, &x);
        carom_body_get_state(b, i, &y);
        if (memcmp(&x, &y, sizeof x) != 0)
            return 0;
    }
    return 1;
}

/* Same impacts, to the bit, in the last step of two worlds? (Friction
 * unknowns change the rounding of a head-on impact's reported impulse
 * without changing any state: a scene of filtered balls whose impulse
 * came out 2.43225026 with friction and 2.4322505 without.) */
static int lean_same_events(const carom_world *a, const carom_world *b)
{
    int na = 0, nb = 0;
    const carom_event *ea = carom_world_events(a, &na), *eb = carom_world_events(b, &nb);
    return na == nb && carom_world_events_dropped(a) == carom_world_events_dropped(b) &&
           (na == 0 || memcmp(ea, eb, (size_t)na * sizeof *ea) == 0);
}

/* Run the scene and record what it needs. Returns 0, or an exit status
 * after a message. */
static int lean_measure(const char *path, scene *s, const sim_opts *o, lean_need *n)
{
    carom_world *w = NULL, *wf = NULL;
    void *mem = NULL, *memf = NULL;
    lean_mover *mv = NULL;
    int *order = NULL;
    char err[512];
    double g;
    long k;
    int i, rc = 0, nf_moving = 0, nf = 0;
    carom_status st = CAROM_OK;
    carom_tolerances tol;
    progress prog;

    memset(n, 0, sizeof *n);
    n->steps = s->steps;
    n->bodies = s->body_count;
    n->first_polygon = n->first_dynamic_polygon = n->first_kinematic = -1;
    n->forced = n->spin_body = n->sleep_body = -1;
    n->spin_step = n->sleep_step = n->friction_step = -1;
    for (i = 0; i < MEET_KINDS; ++i)
        n->met_step[i] = -1;
    n->lever_step = -1;
    for (i = 0; i < s->body_count; ++i) {
        const carom_body_def *d = &s->bodies[i].def;
        if (d->shape == CAROM_SHAPE_CIRCLE) {
            n->circles++;
        } else {
            if (n->polygons++ == 0)
                n->first_polygon = i;
            if (d->vertex_count > n->max_vertices)
                n->max_vertices = d->vertex_count;
            if (d->type != CAROM_BODY_STATIC && n->dynamic_polygons++ == 0)
                n->first_dynamic_polygon = i;
        }
        if (d->type == CAROM_BODY_KINEMATIC && n->kinematic++ == 0)
            n->first_kinematic = i;
        if (n->forced < 0 && (d->force.x != 0.0f || d->force.y != 0.0f || d->torque != 0.0f))
            n->forced = i;
        if (n->spin_step < 0 && (d->angular_velocity != 0.0f || d->torque != 0.0f)) {
            n->spin_step = 0;
            n->spin_body = i;
        }
        if (d->friction > 0.0f) {
            nf++;
            nf_moving += d->type != CAROM_BODY_STATIC;
        }
    }
    /* friction acts only between two bodies that both have some, one of
     * which can move (two static bodies never pair) */
    n->friction_pair = nf_moving >= 1 && nf >= 2;

    if (scene_build_world(s, &w, &mem, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s: %s\n", path, err);
        return EXIT_USAGE;
    }
    if (n->friction_pair) {
        scene f = *s;
        f.bodies = (scene_body *)malloc((size_t)(s->body_count ? s->body_count : 1) *
                                        sizeof *f.bodies);
        if (!f.bodies) {
            fprintf(stderr, "carom: out of memory\n");
            rc = EXIT_USAGE;
            goto done;
        }
        memcpy(f.bodies, s->bodies, (size_t)s->body_count * sizeof *f.bodies);
        for (i = 0; i < s->body_count; ++i)
            f.bodies[i].def.friction = 0.0f;
        i = scene_build_world(&f, &wf, &memf, err, sizeof err);
        free(f.bodies);
        if (i != 0) {
            fprintf(stderr, "carom: %s: %s\n", path, err);
            rc = EXIT_USAGE;
            goto done;
        }
    }
    mv = (lean_mover *)calloc((size_t)(s->body_count ? s->body_count : 1), sizeof *mv);
    order = (int *)calloc((size_t)(s->body_count ? s->body_count : 1), sizeof *order);
    if (!mv || !order) {
        fprintf(stderr, "carom: out of memory for %d bodies\n", s->body_count);
        rc = EXIT_USAGE;
        goto done;
    }
    carom_world_get_tolerances(w, &tol);
    n->slop = (double)tol.linear_slop;
    g = sqrt((double)s->world.gravity.x * (double)s->world.gravity.x +
             (double)s->world.gravity.y * (double)s->world.gravity.y);
    for (i = 0; i < s->body_count; ++i) {
        carom_body_state b;
        carom_body_get_state(w, i, &b);
        mv[i].x1 = (double)b.center.x;
        mv[i].y1 = (double)b.center.y;
        mv[i].r = lean_radius(s, i, &b);
        mv[i].kind = s->bodies[i].def.shape == CAROM_SHAPE_CIRCLE ? 0 : 1;
        mv[i].moving = s->bodies[i].def.type != CAROM_BODY_STATIC;
    }

    progress_start(&prog, o->progress, s->steps);
    for (k = 0; k < s->steps; ++k) {
        int count, dropped;
        double dt = (double)s->world.dt;
        for (i = 0; i < s->body_count; ++i) {
            carom_body_state b;
            carom_body_get_state(w, i, &b);
            mv[i].x0 = mv[i].x1;
            mv[i].y0 = mv[i].y1;
            mv[i].reach = sqrt((double)b.velocity.x * (double)b.velocity.x +
                               (double)b.velocity.y * (double)b.velocity.y) * dt;
        }
        st = carom_world_step(w);
        if (st != CAROM_OK)
            break;
        carom_world_events(w, &count);
        dropped = carom_world_events_dropped(w);
        n->dropped += dropped;
        if (count + dropped > n->events)
            n->events = count + dropped;
        for (i = 0; i < s->body_count; ++i) {
            carom_body_state b;
            double sp;
            carom_body_get_state(w, i, &b);
            if (n->spin_step < 0 && (b.angular_velocity != 0.0f ||
                                     b.rotation.c != s->bodies[i].def.rotation.c ||
                                     b.rotation.s != s->bodies[i].def.rotation.s)) {
                n->spin_step = k + 1;
                n->spin_body = i;
            }
            if (n->sleep_step < 0 && !carom_body_is_awake(w, i) &&
                s->bodies[i].def.type == CAROM_BODY_DYNAMIC) {
                n->sleep_step = k + 1;
                n->sleep_body = i;
            }
            mv[i].x1 = (double)b.center.x;
            mv[i].y1 = (double)b.center.y;
            sp = sqrt((double)b.velocity.x * (double)b.velocity.x +
                      (double)b.velocity.y * (double)b.velocity.y) * dt;
            if (sp > mv[i].reach)
                mv[i].reach = sp;
            mv[i].reach += g * dt * dt + 5.0 * n->slop;
            if (!mv[i].moving)
                mv[i].reach = 5.0 * n->slop;
        }
        if (n->met_step[MEET_CC] < 0 || n->met_step[MEET_CP] < 0 ||
            n->met_step[MEET_PP] < 0 || (n->lever_step < 0 && n->dynamic_polygons > 0))
            lean_reach(n, mv, order, s->body_count, k + 1);
        if (wf) {
            carom_status sf = carom_world_step(wf);
            if (sf != CAROM_OK || !lean_same_state(w, wf, s->body_count) ||
                !lean_same_events(w, wf)) {
                n->friction_step = k + 1;
                scene_free_world(wf, memf);
                memf = NULL;
                wf = NULL;
            }
        }
        progress_update(&prog, k + 1, (double)carom_world_time(w));
    }
    progress_end(&prog, carom_world_step_count(w), (double)carom_world_time(w));
    if (st != CAROM_OK) {
        fprintf(stderr, "carom: %s: step %ld (t = %.9g s): %s; lean measures a "
                        "scene that runs to its end\n", path, k + 1,
                (double)carom_world_time(w), carom_status_string(st));
        rc = EXIT_SIM;
        goto done;
    }
    carom_world_get_stats(w, &n->stats);
done:
    free(mv);
    free(order);
    scene_free_world(w, mem);
    scene_free_world(wf, memf);
    return rc;
}

/* need + need * margin / 100 (rounded up) + slack, at least 1 */
static long lean_cap(long need, const sim_opts *o)
{
    long c = need + (need * o->margin + 99) / 100 + o->slack;
    return c < 1 ? 1 : c > (1L << 26) ? (1L << 26) : c;
}

static void lean_switch(const char *name, int on, const char *why, ...)
{
    va_list ap;
    printf("#define CAROM_ENABLE_%s %d /* %s: ", name, on, on ? "on" : "off");
    va_start(ap, why);
    vprintf(why, ap);
    va_end(ap);
    printf(" */\n");
}

static void lean_body_ref(char *buf, size_t len, const scene *s, int i)
{
    snprintf(buf, len, "body %d (line %d)", i, s->bodies[i].line);
}

/* Up to this many bodies a lean build tests every pair of boxes instead of
 * keeping the broadphase grid (n^2 / 2 box tests: 2016 at 64 bodies). */
#define LEAN_GRID_MAX_BODIES 64

static int cmd_lean(int argc, char **argv)
{
    sim_opts o;
    scene s;
    lean_need n;
    char err[512], a[64], b[64];
    carom_world_def def;
    long pairs, contacts, impacts, events, default_impacts;
    size_t bytes, default_bytes;
    const char *p;
    int rc, polygons_on, dyn_on, pp_on, spin_on, friction_on, events_on, sleep_on;

    rc = parse_options(CMD_LEAN, argc, argv, &o);
    if (rc >= 0)
        return rc;
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
    if (s.body_count == 0) {
        fprintf(stderr, "carom: %s: no bodies: nothing to measure\n", o.scene_path);
        scene_free(&s);
        return EXIT_USAGE;
    }
    rc = lean_measure(o.scene_path, &s, &o, &n);
    if (rc != 0) {
        scene_free(&s);
        return rc;
    }

    /* capacities */
    def = s.world;
    def.max_bodies = s.body_count;
    default_bytes = carom_world_buffer_size(&def);
    default_impacts = s.world.max_impacts > 0
                          ? s.world.max_impacts
                          : ((long)CAROM_DEFAULT_IMPACTS_PER_BODY * s.body_count > CAROM_MIN_IMPACTS
                                 ? (long)CAROM_DEFAULT_IMPACTS_PER_BODY * s.body_count
                                 : CAROM_MIN_IMPACTS);
    pairs = lean_cap(n.stats.max_pairs_used, &o);
    contacts = lean_cap(n.stats.max_contacts_used, &o);
    /* past max_impacts the rest of a step's contacts are solved together:
     * a run that met the budget must keep it as it was */
    impacts = n.stats.budget_steps > 0 ? default_impacts
                                       : lean_cap(n.stats.max_impacts_used, &o);
    events = lean_cap(n.events, &o);
    def.max_pairs = (int)pairs;
    def.max_contacts = (int)contacts;
    def.max_impacts = (int)impacts;
    def.max_events = (int)events;
    bytes = carom_world_buffer_size(&def);

    polygons_on = n.polygons > 0;
    dyn_on = n.dynamic_polygons > 0;
    pp_on = n.met_step[MEET_PP] >= 0;
    spin_on = n.spin_step >= 0 || n.lever_step >= 0;
    friction_on = n.friction_step >= 0;
    events_on = s.world.method != CAROM_METHOD_DISCRETE;
    sleep_on = n.sleep_step >= 0;

    printf("/*\n * carom_lean.h -- the smallest build of carom %s that gives the same\n"
           " * results on ", carom_version());
    for (p = o.scene_path; *p; ++p)
        putchar(*p == '*' && p[1] == '/' ? '+' : (unsigned char)*p < 0x20 ? '?' : *p);
    printf("\n * (%d bodies, method %s, %ld steps of %.9g s). Written by `carom lean`,\n"
           " * which ran the scene to see what it uses.\n",
           s.body_count, carom_method_name(s.world.method), s.steps, (double)s.world.dt);
    printf(" *\n * Use the same header for the library and the program: compile both with\n"
           " * -include carom_lean.h (or include it before carom.h everywhere and\n"
           " * before compiling src/), and size the world from the capacities below:\n"
           " *\n"
           " *     carom_world_def wd = carom_default_world_def();\n"
           " *     static unsigned char mem[CAROM_LEAN_WORLD_BYTES];\n"
           " *     CAROM_LEAN_SET_CAPACITIES(&wd);\n"
           " *     carom_world_init(&w, &wd, mem, sizeof mem);\n"
           " *\n"
           " * A switch that is off makes the library refuse a call that needs what\n"
           " * it removed (CAROM_ERR_DISABLED: the other method, a setter, a body\n"
           " * type, a query). The switches and limits decided from the motion\n"
           " * (polygon-polygon, rotation, friction, continuous, stacking, sleep,\n"
           " * the impact rows and direct solve) hold for the run measured: these\n"
           " * steps, this dt, this method, these start states. Past it the library\n"
           " * simulates what the build has, without an error (polygons pass\n"
           " * through polygons, contacts are frictionless, bodies do not turn):\n"
           " * measure the longest run the program makes (carom lean --steps N).\n"
           " * The lean CLI warns when a run goes beyond the measured one.\n */\n");
    printf("#ifndef CAROM_LEAN_H\n#define CAROM_LEAN_H\n\n");
    printf("#define CAROM_LEAN_SCENE \"");
    for (p = o.scene_path; *p; ++p) {
        if (*p == '"' || *p == '\\')
            putchar('\\');
        if ((unsigned char)*p >= 0x20)
            putchar(*p);
    }
    printf("\"\n#define CAROM_LEAN_STEPS %ldL /* the run measured */\n"
           "#define CAROM_LEAN_DT %.9gf\n#define CAROM_LEAN_METHOD \"%s\"\n",
           s.steps, (double)s.world.dt, carom_method_name(s.world.method));
    printf("\n/* ---- capabilities (include/carom_config.h) ---- */\n\n");

    if (polygons_on) {
        lean_body_ref(a, sizeof a, &s, n.first_polygon);
        lean_switch("POLYGONS", 1, "%d polygon%s, the first is %s", n.polygons,
                    n.polygons == 1 ? "" : "s", a);
    } else {
        lean_switch("POLYGONS", 0, "every body is a circle");
    }
    if (dyn_on) {
        lean_body_ref(a, sizeof a, &s, n.first_dynamic_polygon);
        lean_switch("DYNAMIC_POLYGONS", 1, "%d moving polygon%s, the first is %s",
                    n.dynamic_polygons, n.dynamic_polygons == 1 ? "" : "s", a);
    } else if (polygons_on) {
        lean_switch("DYNAMIC_POLYGONS", 0, "every polygon is static");
    } else {
        lean_switch("DYNAMIC_POLYGONS", 0, "no polygons");
    }
    if (pp_on) {
        lean_body_ref(a, sizeof a, &s, n.met_a[MEET_PP]);
        lean_body_ref(b, sizeof b, &s, n.met_b[MEET_PP]);
        lean_switch("POLYGON_POLYGON", 1, "polygons %s and %s came within reach in step %ld",
                    a, b, n.met_step[MEET_PP]);
    } else if (dyn_on) {
        lean_switch("POLYGON_POLYGON", 0, "no two polygons ever came within reach");
    } else if (polygons_on) {
        lean_switch("POLYGON_POLYGON", 0, "only static polygons, and static bodies never collide");
    } else {
        lean_switch("POLYGON_POLYGON", 0, "no polygons");
    }
    if (!spin_on) {
        lean_switch("ROTATION", 0, "no body ever turned (angular velocity 0 after every step), "
                                   "and no moving polygon came within reach of another body");
    } else if (n.spin_step < 0) {
        lean_body_ref(a, sizeof a, &s, n.lever_a);
        lean_body_ref(b, sizeof b, &s, n.lever_b);
        lean_switch("ROTATION", 1, "nothing turned, but %s and %s came within reach in step "
                    "%ld: a polygon's contacts weigh its inertia even when it does not turn",
                    a, b, n.lever_step);
    } else {
        lean_body_ref(a, sizeof a, &s, n.spin_body);
        if (n.spin_step == 0)
            lean_switch("ROTATION", 1, "%s starts with an angular velocity or a torque", a);
        else
            lean_switch("ROTATION", 1, "%s turned in step %ld", a, n.spin_step);
    }
    if (friction_on)
        lean_switch("FRICTION", 1, "with every friction 0 the state or the impacts differ after step %ld",
                    n.friction_step);
    else if (n.friction_pair)
        lean_switch("FRICTION", 0, "a second run with every friction 0 gave the same bits "
                                   "after every step");
    else
        lean_switch("FRICTION", 0, "no two bodies that can touch both have friction > 0");
    if (n.forced >= 0) {
        lean_body_ref(a, sizeof a, &s, n.forced);
        lean_switch("FORCES", 1, "%s has a constant force or torque", a);
    } else {
        lean_switch("FORCES", 0, "no body has a force or torque: gravity only");
    }
    lean_switch("EVENTS", events_on, "the method is %s", carom_method_name(s.world.method));
#ifdef CAROM_ENABLE_DISCRETE
    if (events_on)
        lean_switch("DISCRETE", 0, "the method is %s; turn on if the program switches to the "
                                   "discrete method", carom_method_name(s.world.method));
    else
        lean_switch("DISCRETE", 1, "the method is discrete");
#endif
    if (sleep_on) {
        lean_body_ref(a, sizeof a, &s, n.sleep_body);
        lean_switch("SLEEP", 1, "%s fell asleep in step %ld", a, n.sleep_step);
    } else {
        lean_switch("SLEEP", 0, s.world.enable_sleep ? "no body ever fell asleep"
                                                     : "the scene has sleep=off");
    }
    if (n.kinematic > 0) {
        lean_body_ref(a, sizeof a, &s, n.first_kinematic);
        lean_switch("KINEMATIC", 1, "%d kinematic bod%s, the first is %s", n.kinematic,
                    n.kinematic == 1 ? "y" : "ies", a);
    } else {
        lean_switch("KINEMATIC", 0, "no kinematic body");
    }
    {
        int filtered = -1, sensor = -1, bi;
        for (bi = 0; bi < s.body_count; ++bi) {
            const carom_body_def *d = &s.bodies[bi].def;
            if (filtered < 0 && (d->category_bits != 1u || d->mask_bits != 0xffffffffu ||
                                 d->group_index != 0))
                filtered = bi;
            if (sensor < 0 && d->is_sensor)
                sensor = bi;
        }
        if (filtered >= 0) {
            lean_body_ref(a, sizeof a, &s, filtered);
            lean_switch("FILTERING", 1, "%s has a collision filter", a);
        } else {
            lean_switch("FILTERING", 0, "the scene sets no collision filter; turn on if the "
                                        "program does");
        }
        if (sensor >= 0) {
            lean_body_ref(a, sizeof a, &s, sensor);
            lean_switch("SENSORS", 1, "%s is a sensor", a);
        } else {
            lean_switch("SENSORS", 0, "the scene has no sensor bodies");
        }
    }
    if (s.world.gravity.x == 0.0f && s.world.gravity.y == 0.0f)
        lean_switch("STACKING", 0, "no gravity: the support order, priming and shock "
                                   "propagation do nothing");
    else
        lean_switch("STACKING", 1, "gravity (%g, %g): stacks need the support order and shock "
                                   "propagation", (double)s.world.gravity.x,
                    (double)s.world.gravity.y);
    if (n.stats.continuous_stops > 0)
        lean_switch("CONTINUOUS", 1, "a body went into or through a static or kinematic body and was put "
                                     "back where it met it, %ld time%s",
                    n.stats.continuous_stops, n.stats.continuous_stops == 1 ? "" : "s");
    else
        lean_switch("CONTINUOUS", 0, "no body went into or through a static or kinematic body: the guard "
                                     "never acted; turn on if bodies may spin faster than the "
                                     "contact solver follows, or be driven past their boxes");
    if (s.body_count <= LEAN_GRID_MAX_BODIES)
        lean_switch("GRID", 0, "%d bodies: testing every box against every other (%ld tests a "
                               "step) is small; the grid pays from about %d bodies",
                    s.body_count, (long)s.body_count * (s.body_count - 1) / 2,
                    LEAN_GRID_MAX_BODIES);
    else
        lean_switch("GRID", 1, "%d bodies: the grid finds pairs in time linear in the bodies",
                    s.body_count);
    lean_switch("STATUS_NAMES", 0, "status names are for messages; turn on if the program "
                                   "prints carom_status_string()");
    {
        int turned = -1, i;
        for (i = 0; i < s.body_count && turned < 0; ++i) {
            carom_rot q = s.bodies[i].def.rotation;
            if (q.c != 1.0f || q.s != 0.0f || signbit(q.s))
                turned = i;
        }
        if (spin_on)
            lean_switch("ANGLES", 1, "rotation is on (the library turns bodies with them)");
        else if (turned >= 0) {
            lean_body_ref(a, sizeof a, &s, turned);
            lean_switch("ANGLES", 1, "%s starts at an angle (the scene's angle= needs them)", a);
        } else
            lean_switch("ANGLES", 0, "every body starts at angle 0 and none turns; turn on if "
                                     "the program calls carom_rot_from_angle() or "
                                     "carom_rot_angle()");
    }
#ifdef CAROM_ENABLE_GROW
    lean_switch("GROW", 0, "the capacities below hold the scene; memory on demand needs an "
                           "allocator (turn on if the program gives one)");
#endif
#ifdef CAROM_ENABLE_QUERIES
    lean_switch("QUERIES", 0, "stepping makes no query; turn on if the program calls them");
#endif
#ifdef CAROM_ENABLE_BODY_EDITS
    lean_switch("BODY_EDITS", 0, "stepping changes no body from outside; turn on if the program "
                                 "sets velocities or transforms, applies impulses or forces, "
                                 "or removes bodies");
#endif
#ifdef CAROM_ENABLE_TOUCH_EVENTS
    lean_switch("TOUCH_EVENTS", 0, "stepping needs no touch reports; turn on if the program "
                                   "reads them");
#endif
    lean_switch("COMPENSATED", CAROM_ENABLE_COMPENSATED,
                "as this carom was built; it sets the rounding of every position and "
                "velocity sum, so changing it changes the results");
    /* limits: polygons' vertex arrays sized to the scene (4 at least:
     * carom_body_def_set_box writes four) */
    {
        int v = n.max_vertices > 4 ? n.max_vertices : 4;
        if (v < CAROM_MAX_POLYGON_VERTICES)
            printf("#define CAROM_MAX_POLYGON_VERTICES %d /* limit: the scene's polygons have at "
                   "most %d vertices (4 at least: boxes) */\n", v, n.max_vertices);
        else
            printf("#define CAROM_MAX_POLYGON_VERTICES %d /* limit: as this carom was built; "
                   "the scene's polygons have up to %d vertices */\n",
                   CAROM_MAX_POLYGON_VERTICES, n.max_vertices);
    }
    {
        int r = n.stats.max_rows_used > 1 ? n.stats.max_rows_used : 1;
        if (r < CAROM_IMPACT_ROWS_MAX)
            printf("#define CAROM_IMPACT_ROWS_MAX %d /* limit: a simultaneous impact solve "
                   "held at most %d contact rows%s */\n", r, n.stats.max_rows_used,
                   n.stats.max_rows_used > 0 ? "" : " (no impact: 1, the least)");
        else
            printf("#define CAROM_IMPACT_ROWS_MAX %d /* limit: as this carom was built; a "
                   "simultaneous impact solve held %d contact rows */\n",
                   CAROM_IMPACT_ROWS_MAX, n.stats.max_rows_used);
    }
#if CAROM_IMPACT_DIRECT_MAX > 0
    printf("#define CAROM_IMPACT_DIRECT_MAX %d /* limit: the exact solve of an impact island "
           "took at most %d impulses%s */\n", n.stats.max_direct_used, n.stats.max_direct_used,
           n.stats.max_direct_used > 0 ? "" : " (never tried: left out)");
#else
    printf("#define CAROM_IMPACT_DIRECT_MAX 0 /* limit: as this carom was built */\n");
#endif
    printf("#ifndef CAROM_ENABLE_PROFILE\n"
           "#define CAROM_ENABLE_PROFILE 0 /* off: counting operations is for "
           "measurement builds (make lean's CLI turns it on) */\n#endif\n");
    printf("\n/* Shape pairs that came within reach (bounding circles swept over "
           "each step):\n");
    for (rc = 0; rc < MEET_KINDS; ++rc) {
        if (n.met_step[rc] >= 0) {
            lean_body_ref(a, sizeof a, &s, n.met_a[rc]);
            lean_body_ref(b, sizeof b, &s, n.met_b[rc]);
            printf(" *   %-16s first in step %ld: %s and %s\n", meet_names[rc],
                   n.met_step[rc], a, b);
        } else {
            printf(" *   %-16s never\n", meet_names[rc]);
        }
    }
    printf(" */\n");

    printf("\n/* ---- capacities of carom_world_def: the most met in one step, plus "
           "%ld %% + %ld ---- */\n\n", o.margin, o.slack);
    printf("#define CAROM_LEAN_MAX_BODIES %d /* the scene's bodies */\n", s.body_count);
    printf("#define CAROM_LEAN_MAX_PAIRS %ld /* candidate pairs: at most %d */\n", pairs,
           n.stats.max_pairs_used);
    printf("#define CAROM_LEAN_MAX_CONTACTS %ld /* contacts: at most %d */\n", contacts,
           n.stats.max_contacts_used);
    if (n.stats.budget_steps > 0)
        printf("#define CAROM_LEAN_MAX_IMPACTS %ld /* as the scene ran it: %ld steps met "
               "more impacts than this, and a smaller budget would change them */\n",
               impacts, n.stats.budget_steps);
    else
        printf("#define CAROM_LEAN_MAX_IMPACTS %ld /* impacts taken one at a time: at "
               "most %d */\n", impacts, n.stats.max_impacts_used);
    printf("#define CAROM_LEAN_MAX_EVENTS %ld /* impacts recorded: at most %d%s */\n", events,
           n.events, n.dropped ? " (the default cap dropped some)" : "");
    printf("#define CAROM_LEAN_SET_CAPACITIES(def) \\\n"
           "    ((def)->max_bodies = CAROM_LEAN_MAX_BODIES, \\\n"
           "     (def)->max_pairs = CAROM_LEAN_MAX_PAIRS, \\\n"
           "     (def)->max_contacts = CAROM_LEAN_MAX_CONTACTS, \\\n"
           "     (def)->max_impacts = CAROM_LEAN_MAX_IMPACTS, \\\n"
           "     (def)->max_events = CAROM_LEAN_MAX_EVENTS)\n");
    printf("/* carom_world_buffer_size() of a world with these capacities, as measured\n"
           " * by the carom that wrote this header (%u-bit pointers, %d polygon\n"
           " * vertices): the lean build, and a 32-bit target, need no more; call\n"
           " * carom_world_buffer_size() there for the exact figure. At default\n"
           " * capacities the scene takes %lu bytes. */\n",
           (unsigned)(8u * sizeof(void *)), CAROM_MAX_POLYGON_VERTICES,
           (unsigned long)default_bytes);
    printf("#define CAROM_LEAN_WORLD_BYTES %lu\n", (unsigned long)bytes);
    printf("\n#endif /* CAROM_LEAN_H */\n");
    scene_free(&s);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "carom: lean: error writing the header\n");
        return EXIT_SIM;
    }
    return 0;
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
#ifdef CAROM_LEAN_SCENE
        printf("carom %s (lean build for %s)\n", carom_version(), CAROM_LEAN_SCENE);
#else
        printf("carom %s\n", carom_version());
#endif
        return 0;
    }
    if (strcmp(argv[1], "run") == 0)
        return cmd_sim(CMD_RUN, argc - 2, argv + 2);
    if (strcmp(argv[1], "profile") == 0)
        return cmd_sim(CMD_PROFILE, argc - 2, argv + 2);
    if (strcmp(argv[1], "render") == 0)
        return cmd_sim(CMD_RENDER, argc - 2, argv + 2);
    if (strcmp(argv[1], "lean") == 0)
        return cmd_lean(argc - 2, argv + 2);
    return cli_usage_error("carom", "unknown command '%s' (run, profile, render, lean)", argv[1]);
}
