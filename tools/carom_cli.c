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
    "       carom profile SCENE [--weights NAME|FILE] [--json] [options]\n"
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
    "profile: run the scene counting every floating-point operation by kind\n"
    "(add sub mul div cmp sqrt) and pipeline phase, and print the counts and\n"
    "their weighted cost (docs/cost-model.md). --weights takes a preset\n"
    "(seed: the design note's table, the default; cortex-m4f; cortex-m0) or a\n"
    "file of 'KIND WEIGHT' lines naming all six kinds ('#' comments).\n"
    "--json prints one JSON object instead of the table. --steps, --dt and\n"
    "--method apply as for run.\n"
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
                                const scene *s, int bodies)
{
    int ph, k;
    double total = 0.0, impulse;
    uint64_t kinds[CAROM_OP_COUNT] = {0};
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
        total += phase_cost(p, wt, ph);
    printf("scene %s: method %s, %lu steps, %d bodies, %lu body-steps, %lu impacts\n",
           path, carom_method_name(s->world.method), (unsigned long)p->steps, bodies,
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

static void print_profile_json(const carom_profile *p, const carom_op_weights *wt,
                               const char *wname, int bodies)
{
    int ph, k;
    double total = 0.0;
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
        total += phase_cost(p, wt, ph);
    printf("{\"steps\": %lu, \"bodies\": %d, \"impacts\": %lu, \"body_steps\": %lu, ",
           (unsigned long)p->steps, bodies, (unsigned long)p->impacts,
           (unsigned long)p->body_steps);
    printf("\"weights_name\": \"");
    for (; *wname; ++wname) /* a file path may hold any character */
        if (*wname == '"' || *wname == '\\')
            printf("\\%c", *wname);
        else if ((unsigned char)*wname < 0x20)
            printf("\\u%04x", (unsigned)(unsigned char)*wname);
        else
            putchar(*wname);
    printf("\", \"weights\": {");
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

static FILE *open_out(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "carom: cannot write '%s': %s\n", path, strerror(errno));
    return f;
}

static int cmd_sim(int argc, char **argv, int profile)
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
    const char *weights_arg = "seed";
    int json = 0;
    carom_op_weights weights;
    carom_profile prof;

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
        } else if (profile && strcmp(a, "--json") == 0) {
            json = 1;
        } else if (profile && strcmp(a, "--weights") == 0) {
            if (i + 1 >= argc)
                return usage_error("%s needs a value", a);
            weights_arg = argv[++i];
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else if (!scene_path) {
            scene_path = a;
        } else {
            return usage_error("more than one scene given ('%s')", a);
        }
    }
    if (!scene_path)
        return usage_error("%s", profile ? "profile: missing SCENE" : "run: missing SCENE");
    if (profile && load_weights(weights_arg, &weights) != 0)
        return EXIT_USAGE;

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
    if (profile) {
        carom_profile_reset(&prof);
        if (carom_world_set_profile(w, &prof) != CAROM_OK) {
            fprintf(stderr, "carom: this build has no profiler "
                            "(CAROM_ENABLE_PROFILE=0)\n");
            rc = EXIT_USAGE;
            goto done;
        }
    }

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
            if (st == CAROM_ERR_PAIR_CAPACITY)
                fprintf(stderr, "carom: raise the world's max-pairs= (now %d)\n",
                        s.world.max_pairs);
            else if (st == CAROM_ERR_CONTACT_CAPACITY)
                fprintf(stderr, "carom: raise the world's max-contacts= (now %d)\n",
                        s.world.max_contacts);
            else if (carom_world_error_body(w) >= 0)
                fprintf(stderr, "carom: body %d\n", carom_world_error_body(w));
            rc = EXIT_SIM;
            break;
        }
    }
    if (rc == 0 && profile) {
        if (json)
            print_profile_json(&prof, &weights, weights_arg, carom_world_body_count(w));
        else
            print_profile_table(&prof, &weights, weights_arg, scene_path, &s,
                                carom_world_body_count(w));
    } else if (rc == 0) {
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
        return cmd_sim(argc - 2, argv + 2, 0);
    if (strcmp(argv[1], "profile") == 0)
        return cmd_sim(argc - 2, argv + 2, 1);
    return usage_error("unknown command '%s' (run, profile)", argv[1]);
}
