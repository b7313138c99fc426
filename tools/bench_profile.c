/*
 * bench_profile.c -- time one scene's steps with whichever carom library
 * this is linked against (tools/bench.sh builds it four times: default,
 * bare operators, profiling compiled in but detached, profiling counting).
 *
 * usage: bench_profile SCENE STEPS REPS [count]
 * prints the median over REPS of the time per step, in ns.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "carom.h"
#include "scene.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    scene s;
    char err[512];
    long steps, k;
    int reps, r, count;
    double *ns;
    if (argc < 4) {
        fprintf(stderr, "usage: bench_profile SCENE STEPS REPS [count]\n");
        return 2;
    }
    steps = atol(argv[2]);
    reps = atoi(argv[3]);
    count = argc > 4 && strcmp(argv[4], "count") == 0;
    if (steps <= 0 || reps <= 0) {
        fprintf(stderr, "bench_profile: STEPS and REPS must be > 0\n");
        return 2;
    }
    if (scene_load(argv[1], &s, err, sizeof err) != 0) {
        fprintf(stderr, "bench_profile: %s\n", err);
        return 2;
    }
    ns = (double *)malloc((size_t)reps * sizeof *ns);
    for (r = 0; r < reps; ++r) {
        carom_world *w;
        void *mem;
        carom_profile prof;
        double t0;
        if (scene_build_world(&s, &w, &mem, err, sizeof err) != 0) {
            fprintf(stderr, "bench_profile: %s\n", err);
            return 2;
        }
        if (count && carom_world_set_profile(w, &prof) != CAROM_OK) {
            fprintf(stderr, "bench_profile: library built without profiling\n");
            return 2;
        }
        carom_profile_reset(&prof);
        t0 = now();
        for (k = 0; k < steps; ++k) {
            carom_status st = carom_world_step(w);
            if (st != CAROM_OK) {
                fprintf(stderr, "bench_profile: step %ld: %s\n", k, carom_status_string(st));
                return 1;
            }
        }
        ns[r] = (now() - t0) * 1e9 / (double)steps;
        free(mem);
    }
    qsort(ns, (size_t)reps, sizeof *ns, cmp_double);
    printf("%.1f\n", ns[reps / 2]);
    free(ns);
    scene_free(&s);
    return 0;
}
