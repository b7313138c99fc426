/*
 * carom_cli.c -- build/carom: run scene files through the library.
 *
 * Exit status: 0 success, 1 the simulation reported an error (for example
 * event capacity), 2 bad usage or a bad scene.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "carom.h"
#include "scene.h"

#define EXIT_SIM 1
#define EXIT_USAGE 2

static const char usage[] =
    "usage: carom run SCENE [options]\n"
    "       carom --help\n"
    "\n"
    "Step a scene file (docs/scene-format.md) and write the final state of\n"
    "every body to stdout as CSV: body,x,y,angle,vx,vy,omega\n"
    "(x, y: body origin; angle in radians in (-pi, pi]; vx, vy: velocity of\n"
    "the centre of mass; omega: angular velocity).\n"
    "\n"
    "options:\n"
    "  --steps N        number of steps (overrides the scene's steps=)\n"
    "  --dt DT          time step in seconds (overrides dt=)\n"
    "  --method NAME    events (default), discrete or first-impact\n"
    "                   (overrides method=; see docs/events.md)\n"
    "  --trace FILE     write every body's state at step 0 and after every\n"
    "                   step: step,t,body,x,y,angle,vx,vy,omega\n"
    "  --events FILE    write every impact, in time order:\n"
    "                   t,body_a,body_b,nx,ny,impulse,approach_speed\n"
    "  -h, --help       show this help\n"
    "\n"
    "exit status: 0 ok, 1 simulation error, 2 bad usage or bad scene\n";

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "carom: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(try 'carom --help')\n");
    return EXIT_USAGE;
}

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

static FILE *open_out(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "carom: cannot write '%s': %s\n", path, strerror(errno));
    return f;
}

static int cmd_run(int argc, char **argv)
{
    const char *scene_path = NULL, *trace_path = NULL, *events_path = NULL;
    const char *method = NULL;
    long steps = -1, k;
    double dt = -1.0;
    int i, rc = 0;
    scene s;
    char err[512];
    carom_world *w = NULL;
    void *mem = NULL;
    FILE *trace = NULL, *events = NULL;

    for (i = 0; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--steps") == 0 || strcmp(a, "--dt") == 0 ||
                   strcmp(a, "--method") == 0 || strcmp(a, "--trace") == 0 ||
                   strcmp(a, "--events") == 0) {
            const char *v;
            char *end;
            if (i + 1 >= argc)
                return usage_error("%s needs a value", a);
            v = argv[++i];
            if (strcmp(a, "--steps") == 0) {
                errno = 0;
                steps = strtol(v, &end, 10);
                if (*v == '\0' || *end != '\0' || errno || steps < 0 || steps > 1000000000L)
                    return usage_error("--steps: want an integer in [0, 1e9], got '%s'", v);
            } else if (strcmp(a, "--dt") == 0) {
                errno = 0;
                dt = strtod(v, &end);
                if (*v == '\0' || *end != '\0' || errno || !isfinite(dt) || !(dt > 0.0) || dt > 1.0e30)
                    return usage_error("--dt: want a finite number > 0, got '%s'", v);
            } else if (strcmp(a, "--method") == 0) {
                carom_method m;
                if (carom_method_from_name(v, &m) != CAROM_OK)
                    return usage_error("--method: unknown method '%s' (events, discrete, first-impact)", v);
                method = v;
            } else if (strcmp(a, "--trace") == 0) {
                trace_path = v;
            } else {
                events_path = v;
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else if (!scene_path) {
            scene_path = a;
        } else {
            return usage_error("more than one scene given ('%s')", a);
        }
    }
    if (!scene_path)
        return usage_error("%s", "run: missing SCENE");

    if (scene_load(scene_path, &s, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s\n", err);
        return EXIT_USAGE;
    }
    if (steps >= 0)
        s.steps = steps;
    if (dt > 0.0)
        s.world.dt = (float)dt;
    if (method)
        carom_method_from_name(method, &s.world.method);
    if (scene_build_world(&s, &w, &mem, err, sizeof err) != 0) {
        fprintf(stderr, "carom: %s: %s\n", scene_path, err);
        scene_free(&s);
        return EXIT_USAGE;
    }
    if (trace_path && !(trace = open_out(trace_path))) {
        rc = EXIT_USAGE;
        goto done;
    }
    if (events_path && !(events = open_out(events_path))) {
        rc = EXIT_USAGE;
        goto done;
    }
    if (trace) {
        fputs("step,t,body,x,y,angle,vx,vy,omega\n", trace);
        write_trace(trace, w);
    }
    if (events)
        fputs("t,body_a,body_b,nx,ny,impulse,approach_speed\n", events);

    for (k = 0; k < s.steps; ++k) {
        carom_status st = carom_world_step(w);
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
        if (st != CAROM_OK) {
            fprintf(stderr, "carom: %s: step %ld (t = %.9g s): %s\n", scene_path,
                    k + 1, (double)carom_world_time(w), carom_status_string(st));
            if (st == CAROM_ERR_EVENT_CAPACITY)
                fprintf(stderr, "carom: raise the world's max-events= "
                                "(now %d) or use a smaller dt\n", s.world.max_events);
            if (st == CAROM_ERR_PAIR_CAPACITY)
                fprintf(stderr, "carom: raise the world's max-pairs=\n");
            rc = EXIT_SIM;
            break;
        }
    }
    if (rc == 0) {
        puts("body,x,y,angle,vx,vy,omega");
        for (i = 0; i < carom_world_body_count(w); ++i)
            write_state(stdout, w, i, "");
    }
done:
    if (trace && fclose(trace) != 0 && rc == 0) {
        fprintf(stderr, "carom: error writing '%s'\n", trace_path);
        rc = EXIT_SIM;
    }
    if (events && fclose(events) != 0 && rc == 0) {
        fprintf(stderr, "carom: error writing '%s'\n", events_path);
        rc = EXIT_SIM;
    }
    free(mem);
    scene_free(&s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage, stderr);
        return EXIT_USAGE;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "help") == 0) {
        fputs(usage, stdout);
        return 0;
    }
    if (strcmp(argv[1], "run") == 0)
        return cmd_run(argc - 2, argv + 2);
    return usage_error("unknown command '%s' (run)", argv[1]);
}
