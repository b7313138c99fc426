/*
 * engine_none.c -- stand-ins for the engines not compiled in: Box2D v3
 * when B2V3_DIR is not given (BENCH_NO_B2V3), Box2D 2.4.1 in the
 * operation-count build (BENCH_NO_BOX2D). They are never made: the driver
 * asks bench_box2d*_available() first.
 */
#include "bench.h"

#include <stdio.h>

static void *none_make(const bench_scene *s, const bench_config *c, int method, char *err,
                       size_t errlen)
{
    (void)s;
    (void)c;
    (void)method;
    snprintf(err, errlen, "engine not built");
    return NULL;
}

static int none_step(void *world, char *err, size_t errlen)
{
    (void)world;
    snprintf(err, errlen, "engine not built");
    return -1;
}

static void none_info(void *world, bench_info *out)
{
    (void)world;
    (void)out;
}

static void none_destroy(void *world)
{
    (void)world;
}

#ifdef BENCH_NO_B2V3
const bench_engine bench_box2d_v3 = { "box2d-v3", -1, none_make, none_step, none_info,
                                      none_destroy };
int bench_box2d_v3_available(void)
{
    return 0;
}
const char *bench_box2d_v3_version(void)
{
    return "not built";
}
#endif

#ifdef BENCH_NO_BOX2D
const bench_engine bench_box2d = { "box2d", -1, none_make, none_step, none_info,
                                   none_destroy };
int bench_box2d_available(void)
{
    return 0;
}
#endif
