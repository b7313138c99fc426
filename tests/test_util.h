/*
 * test_util.h -- helpers shared by the unit tests.
 *
 * Expected values in the tests are computed independently (the design
 * note's corrected formulas, analytic solutions, conservation laws), in
 * double precision, never copied from carom's own output.
 */
#ifndef CAROM_TEST_UTIL_H
#define CAROM_TEST_UTIL_H

#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "carom.h"

/* A world in malloc'd memory (the tests may allocate; the library not). */
typedef struct tw {
    carom_world *w;
    void *mem;
} tw;

static inline tw tw_make(const carom_world_def *def)
{
    tw t;
    size_t n = carom_world_buffer_size(def);
    ck_assert_msg(n > 0, "buffer size 0 for a valid def");
    t.mem = malloc(n);
    ck_assert_ptr_nonnull(t.mem);
    ck_assert_int_eq(carom_world_init(&t.w, def, t.mem, n), CAROM_OK);
    return t;
}

static inline void tw_free(tw *t)
{
    free(t->mem);
    t->mem = NULL;
    t->w = NULL;
}

static inline int tw_add(tw *t, const carom_body_def *bd)
{
    int id = -1;
    carom_status st = carom_world_add_body(t->w, bd, &id);
    ck_assert_msg(st == CAROM_OK, "add_body: %s", carom_status_string(st));
    return id;
}

static inline carom_body_state tw_state(const tw *t, int id)
{
    carom_body_state s;
    ck_assert_int_eq(carom_body_get_state(t->w, id, &s), CAROM_OK);
    return s;
}

static inline void tw_steps(tw *t, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        carom_status st = carom_world_step(t->w);
        ck_assert_msg(st == CAROM_OK, "step %d: %s", i, carom_status_string(st));
    }
}

/*
 * Two frictionless circles of radius r on the x axis, no gravity: A at xa
 * moving at va, B at xb moving at vb, restitution e, masses ma and mb (0:
 * from the default density). Bodies 0 and 1 of the returned world.
 */
static inline tw tw_pair(carom_method method, float dt, float rest_speed,
                         float r, float e, float ma, float xa, float va,
                         float mb, float xb, float vb)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    wd.method = method;
    wd.gravity.y = 0.0f;
    wd.dt = dt;
    wd.rest_speed = rest_speed;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    bd.radius = r;
    bd.friction = 0.0f;
    bd.restitution = e;
    bd.mass = ma;
    bd.position.x = xa;
    bd.velocity.x = va;
    tw_add(&t, &bd);
    bd.mass = mb;
    bd.position.x = xb;
    bd.velocity.x = vb;
    tw_add(&t, &bd);
    return t;
}

/*
 * An elastic gas: n frictionless balls (radius 0.1 m, e = 1) on a square
 * grid of 0.5 m pitch filling a closed box of static walls, no gravity,
 * rest speed 0, velocities drawn in [-1.5, 1.5]^2 m/s; `steps` steps of
 * `method`. Returns the largest and the final kinetic energy, each over
 * the starting one.
 */
static inline void tw_elastic_gas_seeded(carom_method method, int n, int steps,
                                         unsigned seed, double *worst, double *end);
static inline void tw_elastic_gas(carom_method method, int n, int steps,
                                  double *worst, double *end)
{
    tw_elastic_gas_seeded(method, n, steps, 12345u, worst, end);
}

/* The same gas, its velocities drawn from `seed`. */
static inline void tw_elastic_gas_seeded(carom_method method, int n, int steps,
                                         unsigned seed, double *worst, double *end)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_def g = carom_default_body_def();
    tw t;
    int i, k, side = 1;
    double e0 = 0.0, e = 0.0;
    float half, pitch;
    while (side * side < n)
        ++side;
    /* 0.25 m^2 per ball, at least */
    pitch = 0.5f;
    half = 0.5f * pitch * (float)side;
    wd.method = method;
    wd.gravity.y = 0.0f;
    wd.rest_speed = 0.0f;
    wd.max_bodies = n + 4;
    t = tw_make(&wd);
    g.type = CAROM_BODY_STATIC;
    g.friction = 0.0f;
    g.restitution = 1.0f;
    carom_body_def_set_box(&g, half + 1.0f, 0.5f);
    g.position.y = -half - 0.5f;
    tw_add(&t, &g);
    g.position.y = half + 0.5f;
    tw_add(&t, &g);
    carom_body_def_set_box(&g, 0.5f, half + 1.0f);
    g.position.y = 0.0f;
    g.position.x = -half - 0.5f;
    tw_add(&t, &g);
    g.position.x = half + 0.5f;
    tw_add(&t, &g);
    bd.radius = 0.1f;
    bd.friction = 0.0f;
    bd.restitution = 1.0f;
    for (i = 0; i < n; ++i) {
        float vx, vy;
        seed = seed * 1103515245u + 12345u;
        vx = (float)((seed >> 8) & 0xffff) / 65536.0f * 3.0f - 1.5f;
        seed = seed * 1103515245u + 12345u;
        vy = (float)((seed >> 8) & 0xffff) / 65536.0f * 3.0f - 1.5f;
        bd.position.x = -half + pitch * (0.5f + (float)(i % side));
        bd.position.y = -half + pitch * (0.5f + (float)(i / side));
        bd.velocity.x = vx;
        bd.velocity.y = vy;
        tw_add(&t, &bd);
        e0 += 0.5 * ((double)vx * vx + (double)vy * vy);
    }
    *worst = 0.0;
    for (k = 0; k < steps; ++k) {
        tw_steps(&t, 1);
        e = 0.0;
        for (i = 0; i < n; ++i) {
            carom_body_state s = tw_state(&t, 4 + i);
            e += 0.5 * ((double)s.velocity.x * s.velocity.x +
                        (double)s.velocity.y * s.velocity.y);
        }
        if (e / e0 > *worst)
            *worst = e / e0;
    }
    *end = e / e0;
    tw_free(&t);
}

/* |a - b| <= tol * max(1, |b|) */
#define ck_assert_close(a, b, tol)                                             \
    do {                                                                       \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);         \
        double s_ = fabs(b_) > 1.0 ? fabs(b_) : 1.0;                           \
        ck_assert_msg(fabs(a_ - b_) <= t_ * s_,                                \
                      "%s = %.9g, expected %.9g (tol %.3g)", #a, a_, b_, t_);  \
    } while (0)

/* suites, one per module (tests/test_MODULE.c) */
Suite *suite_trig(void);
Suite *suite_shape(void);
Suite *suite_integrate(void);
Suite *suite_broadphase(void);
Suite *suite_narrowphase(void);
Suite *suite_solver(void);
Suite *suite_world(void);
Suite *suite_island(void);
Suite *suite_continuous(void);
Suite *suite_scene(void);
Suite *suite_events(void);
Suite *suite_toi(void);
Suite *suite_profile(void);
Suite *suite_robust(void);
Suite *suite_api(void);
Suite *suite_contact(void);
Suite *suite_status(void);
Suite *suite_kinematic(void);
Suite *suite_world_def(void);

#endif
