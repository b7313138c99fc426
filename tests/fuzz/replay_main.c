/*
 * replay_main.c -- run a harness's inputs without libFuzzer: link it with
 * one tests/fuzz/fuzz_*.c to replay crashers with any compiler, under
 * valgrind, or against the optimised library to time a slow input:
 *
 *   cc -std=c99 -O2 -ffp-contract=off -Iinclude -Itools \
 *      -D_POSIX_C_SOURCE=200809L tests/fuzz/replay_main.c \
 *      tests/fuzz/fuzz_api.c tools/scene.c build/libcarom.a -lm -o replay
 *   ./replay FILE...        (prints each file's time; a violation aborts)
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; ++i) {
        FILE *f = fopen(argv[i], "rb");
        unsigned char *buf;
        long n;
        struct timespec t0, t1;
        if (!f || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 ||
            fseek(f, 0, SEEK_SET) != 0) {
            fprintf(stderr, "replay: cannot read %s\n", argv[i]);
            return 2;
        }
        buf = (unsigned char *)malloc((size_t)n + 1);
        if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) {
            fprintf(stderr, "replay: cannot read %s\n", argv[i]);
            return 2;
        }
        fclose(f);
        clock_gettime(CLOCK_MONOTONIC, &t0);
        LLVMFuzzerTestOneInput(buf, (size_t)n);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        printf("%s: %ld bytes, %.3f s\n", argv[i], n,
               (double)(t1.tv_sec - t0.tv_sec) +
                   1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
        free(buf);
    }
    return 0;
}
