/*
 * sizes.c -- what a world costs in memory, from carom_world_buffer_size():
 * the fixed part, the bytes each unit of every capacity adds, and worlds
 * at default capacities. Run on the build host (suite_host --sizes) and on
 * a Cortex-M0 (the m0-sizes firmware): pointers and alignment differ.
 *
 * Prints lines "size KEY VALUE" (docs/embedded.md is made from them).
 */
#include "suite.h"

static void out_line(const char *key, long v)
{
    char buf[96], tmp[24];
    int n = 0, i = 0;
    unsigned long u = v < 0 ? 0ul - (unsigned long)v : (unsigned long)v;
    const char *k = "size ";
    while (*k)
        buf[n++] = *k++;
    for (k = key; *k && n < 70; ++k)
        buf[n++] = *k;
    buf[n++] = ' ';
    if (v < 0)
        buf[n++] = '-';
    do {
        tmp[i++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u);
    while (i > 0)
        buf[n++] = tmp[--i];
    buf[n++] = '\n';
    buf[n] = '\0';
    platform_out(buf);
}

/* A world of `bodies` bodies and the given capacities (0: the default). */
static long bytes(int bodies, int pairs, int contacts, int events, int impacts)
{
    carom_world_def d = carom_default_world_def();
    d.max_bodies = bodies;
    d.max_pairs = pairs;
    d.max_contacts = contacts;
    d.max_events = events;
    d.max_impacts = impacts;
    return (long)carom_world_buffer_size(&d);
}

int sizes_run(void)
{
    static const int examples[] = {6, 16, 256, 4096};
    unsigned i;
    out_line("pointer_bits", (long)(8u * sizeof(void *)));
    out_line("world_1_body_all_capacities_1", bytes(1, 1, 1, 1, 1));
    /* per unit: the difference of two large worlds, over the units */
    out_line("per_body_below_256", (bytes(200, 1, 1, 1, 1) - bytes(100, 1, 1, 1, 1)) / 100);
    out_line("per_body_above_256", (bytes(2000, 1, 1, 1, 1) - bytes(1000, 1, 1, 1, 1)) / 1000);
    out_line("per_pair", (bytes(16, 2000, 1, 1, 1) - bytes(16, 1000, 1, 1, 1)) / 1000);
    out_line("per_contact", (bytes(16, 1, 2000, 1, 1) - bytes(16, 1, 1000, 1, 1)) / 1000);
    out_line("per_event", (bytes(16, 1, 1, 2000, 1) - bytes(16, 1, 1, 1000, 1)) / 1000);
    out_line("per_impact", (bytes(16, 1, 1, 1, 2000) - bytes(16, 1, 1, 1, 1000)) / 1000);
    for (i = 0; i < sizeof examples / sizeof examples[0]; ++i) {
        char key[48] = "default_world_";
        int n = 14, b = examples[i], d = 1, j;
        while (d * 10 <= b)
            d *= 10;
        for (; d > 0; d /= 10)
            key[n++] = (char)('0' + (b / d) % 10);
        for (j = 0; "_bodies"[j]; ++j)
            key[n++] = "_bodies"[j];
        key[n] = '\0';
        out_line(key, bytes(b, 0, 0, 0, 0));
    }
    return 0;
}
