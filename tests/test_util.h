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
