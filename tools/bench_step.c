/*
 * bench_step.c -- build/bench_step: time carom_world_step on a scene file.
 *
 *   bench_step SCENE [--steps N] [--warmup N] [--method NAME]
 *
 * Loads the scene with the CLI's parser, builds the world, takes --warmup
 * untimed steps (default 0), then times --steps steps (default: the scene's
 * steps=) with CLOCK_MONOTONIC around carom_world_step only (no parsing, no
 * output). Prints one line to stdout:
 *
 *   steps=N bodies=B ns_per_step=X impacts=I
 *
 * (impacts: carom_world_get_stats, over the warm-up and the timed steps)
 *
 * Used by tools/bench-box2d.sh next to `carom-box2d run --time`.
 * Exit status: 0 ok, 1 the simulation reported an error, 2 bad usage/scene.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "carom.h"
#include "scene.h"

static const char usage[] =
    "usage: bench_step SCENE [--steps N] [--warmup N] [--method NAME]\n"
    "Times carom_world_step on SCENE; prints\n"
    "  steps=N bodies=B ns_per_step=X impacts=I\n"
    "exit status: 0 ok, 1 simulation error, 2 bad usage or bad scene\n";

static int bad(const char *what, const char *arg)
{
    fprintf(stderr, "bench_step: %s '%s'\n%s", what, arg, usage);
    return 2;
}

static int parse_steps(const char *v, long *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || errno || x < 0 || x > 1000000000L)
        return -1;
    *out = x;
    return 0;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    const char *path = NULL, *method = NULL;
    long steps = -1, warmup = 0, k;
    scene s;
    char err[512];
    carom_world *w;
    void *mem;
    carom_stats stats;
    double t0, spent;
    int i;

    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--steps") == 0 || strcmp(a, "--warmup") == 0 ||
                   strcmp(a, "--method") == 0) {
            if (i + 1 >= argc)
                return bad("missing value after", a);
            if (strcmp(a, "--method") == 0) {
                carom_method m;
                method = argv[++i];
                if (carom_method_from_name(method, &m) != CAROM_OK)
                    return bad("unknown method", method);
            } else if (parse_steps(argv[++i], a[2] == 's' ? &steps : &warmup) != 0) {
                return bad("want an integer in [0, 1e9], got", argv[i]);
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            return bad("unknown option", a);
        } else if (!path) {
            path = a;
        } else {
            return bad("more than one scene given:", a);
        }
    }
    if (!path) {
        fputs(usage, stderr);
        return 2;
    }
    if (scene_load(path, &s, err, sizeof err) != 0) {
        fprintf(stderr, "bench_step: %s\n", err);
        return 2;
    }
    if (steps >= 0)
        s.steps = steps;
    if (method)
        carom_method_from_name(method, &s.world.method);
    if (scene_build_world(&s, &w, &mem, err, sizeof err) != 0) {
        fprintf(stderr, "bench_step: %s: %s\n", path, err);
        scene_free(&s);
        return 2;
    }
    for (k = 0; k < warmup; ++k) {
        carom_status st = carom_world_step(w);
        if (st != CAROM_OK) {
            fprintf(stderr, "bench_step: %s: warm-up step %ld: %s\n", path, k + 1,
                    carom_status_string(st));
            free(mem);
            scene_free(&s);
            return 1;
        }
    }
    spent = 0.0;
    for (k = 0; k < s.steps; ++k) {
        carom_status st;
        t0 = now_ns();
        st = carom_world_step(w);
        spent += now_ns() - t0;
        if (st != CAROM_OK) {
            fprintf(stderr, "bench_step: %s: step %ld: %s\n", path, warmup + k + 1,
                    carom_status_string(st));
            free(mem);
            scene_free(&s);
            return 1;
        }
    }
    carom_world_get_stats(w, &stats);
    printf("steps=%ld bodies=%d ns_per_step=%.1f impacts=%ld\n", s.steps, s.body_count,
           s.steps > 0 ? spent / (double)s.steps : 0.0, stats.impacts);
    free(mem);
    scene_free(&s);
    return 0;
}
