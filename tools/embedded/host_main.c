/*
 * host_main.c -- the embedded scene suite on the build host: the lines every
 * firmware must print (tools/embedded/check-embedded.sh compares them).
 *
 *   suite_host [--small]     --small: only the reduced suite
 *   suite_host --sizes       what a world costs in memory (sizes.c)
 */
#include <stdio.h>
#include <string.h>

#include "suite.h"

void platform_out(const char *s) { fputs(s, stdout); }
void platform_stack_paint(void) {}
long platform_stack_peak(uintptr_t sp) { (void)sp; return -1; }
void platform_mark(int what) { (void)what; }

static unsigned char world_mem[1 << 20];

int main(int argc, char **argv)
{
    int small = argc > 1 && strcmp(argv[1], "--small") == 0;
    if (argc == 2 && strcmp(argv[1], "--sizes") == 0)
        return sizes_run();
    if (argc > 2 || (argc == 2 && !small)) {
        fprintf(stderr, "usage: suite_host [--small | --sizes]\n");
        return 2;
    }
    return suite_run(world_mem, sizeof world_mem, small) == 0 ? 0 : 1;
}
