/*
 * test_profile.c -- the op-count profiler. In the profiling build: exact
 * operation counts, each derived operation by operation from the code in
 * docs/cost-model.md (the expected numbers below are those derivations, not
 * measurements). In the default build: the profiler is absent and says so.
 */
#include <string.h>

#include "test_util.h"

#include "internal.h"

#if CAROM_ENABLE_PROFILE
typedef struct counts {
    unsigned long add, sub, mul, div, cmp, sqrt_;
} counts;

static void expect_row(const uint64_t *row, counts c, const char *what)
{
    ck_assert_msg(row[CAROM_OP_ADD] == c.add && row[CAROM_OP_SUB] == c.sub &&
                      row[CAROM_OP_MUL] == c.mul && row[CAROM_OP_DIV] == c.div &&
                      row[CAROM_OP_CMP] == c.cmp && row[CAROM_OP_SQRT] == c.sqrt_,
                  "%s: add %lu sub %lu mul %lu div %lu cmp %lu sqrt %lu, derived "
                  "add %lu sub %lu mul %lu div %lu cmp %lu sqrt %lu",
                  what, (unsigned long)row[0], (unsigned long)row[1],
                  (unsigned long)row[2], (unsigned long)row[3], (unsigned long)row[4],
                  (unsigned long)row[5], c.add, c.sub, c.mul, c.div, c.cmp, c.sqrt_);
}

#endif

START_TEST(test_seed_preset_is_the_design_notes_table)
{
    carom_op_weights w;
    ck_assert_int_eq(carom_op_weights_preset("seed", &w), CAROM_OK);
    ck_assert(w.w[CAROM_OP_ADD] == 1.0f && w.w[CAROM_OP_SUB] == 1.0f &&
              w.w[CAROM_OP_MUL] == 1.5f && w.w[CAROM_OP_DIV] == 4.0f &&
              w.w[CAROM_OP_CMP] == 1.0f && w.w[CAROM_OP_SQRT] == 6.0f);
    ck_assert_int_eq(carom_op_weights_preset("cortex-m4f", &w), CAROM_OK);
    ck_assert(w.w[CAROM_OP_DIV] == 14.0f && w.w[CAROM_OP_MUL] == 1.0f);
    ck_assert_int_eq(carom_op_weights_preset("cortex-m0", &w), CAROM_OK);
    ck_assert_int_eq(carom_op_weights_preset("pentium", &w), CAROM_ERR_BAD_PARAMETER);
    ck_assert_int_eq(carom_op_weights_preset(NULL, &w), CAROM_ERR_NULL);
}
END_TEST

START_TEST(test_cost_is_the_weighted_sum_of_counts)
{
    carom_profile p;
    carom_op_weights w;
    carom_profile_reset(&p);
    carom_op_weights_preset("seed", &w);
    p.ops[CAROM_PHASE_INTEGRATION][CAROM_OP_MUL] = 10;  /* 15 */
    p.ops[CAROM_PHASE_INTEGRATION][CAROM_OP_SQRT] = 2;  /* 12 */
    p.ops[CAROM_PHASE_RESTING][CAROM_OP_DIV] = 3;       /* 12 */
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_INTEGRATION) == 27.0f);
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_RESTING) == 12.0f);
    ck_assert(carom_profile_cost(&p, &w, -1) == 39.0f);
    ck_assert_str_eq(carom_phase_name(CAROM_PHASE_INTEGRATION), "integration");
    ck_assert_str_eq(carom_op_name(CAROM_OP_SQRT), "sqrt");
}
END_TEST

#if CAROM_ENABLE_PROFILE

/* One discrete step of one circle under gravity, nothing to collide with;
 * returns the integration row. */
static void one_verlet_step(float w0, uint64_t out[CAROM_OP_COUNT])
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_profile p;
    tw t;
    wd.method = CAROM_METHOD_DISCRETE;
    wd.max_bodies = 1;
    t = tw_make(&wd);
    bd.velocity.x = 1.0f;
    bd.angular_velocity = w0;
    tw_add(&t, &bd);
    carom_profile_reset(&p);
    ck_assert_int_eq(carom_world_set_profile(t.w, &p), CAROM_OK);
    tw_steps(&t, 1);
    memcpy(out, p.ops[CAROM_PHASE_INTEGRATION], sizeof p.ops[0]);
    ck_assert(p.steps == 1 && p.body_steps == 1 && p.impacts == 0);
    tw_free(&t);
}

/* docs/cost-model.md, "Velocity Verlet": 3 mul per step (t1, dt/2,
 * dt^2/2) and per body: drift 4 mul 6 add, angle increment 2 mul 2 add and
 * its zero test 1 cmp, forces 3 mul 2 add, velocity 2 mul 4 add, angular
 * velocity 1 mul 2 add. */
START_TEST(test_verlet_step_of_one_body_without_rotation_counts)
{
    uint64_t row[CAROM_OP_COUNT];
    counts c = {16, 0, 15, 0, 1, 0};
    one_verlet_step(0.0f, row);
    expect_row(row, c, "Verlet step, not rotating");
}
END_TEST

/* ... plus, for a spinning body, the rotation by the angle increment:
 * carom_rot_from_angle (add 11, sub 3, mul 19, div 1, cmp 5, sqrt 1), the
 * product of two rotations (add 1, sub 1, mul 4) and renormalisation (add
 * 1, mul 4, div 1, sqrt 1). */
START_TEST(test_verlet_step_of_one_body_with_rotation_counts)
{
    uint64_t row[CAROM_OP_COUNT];
    counts c = {16 + 13, 4, 15 + 27, 2, 1 + 5, 2};
    one_verlet_step(2.0f, row);
    expect_row(row, c, "Verlet step, rotating");
}
END_TEST

/* The stable root of a gap c0 + c1 s (+ c2 s^2): the note's 1D impact time.
 * Linear: 4 cmp, 1 sub (negation), 1 div. Quadratic: 10 cmp, 6 mul, 2 sub,
 * 2 add, 2 div, 1 sqrt. */
START_TEST(test_root_of_linear_and_quadratic_gap_counts)
{
    uint64_t row[CAROM_OP_COUNT] = {0};
    counts lin = {0, 1, 0, 1, 4, 0}, quad = {2, 2, 6, 2, 10, 1};
    float s;
    carom__op_row = row;
    ck_assert(cr_first_down_root2(2.0f, -3.0f, 0.0f, 1.0f, &s));
    carom__op_row = 0;
    ck_assert_close(s, 2.0 / 3.0, 1e-7);
    expect_row(row, lin, "linear root");
    memset(row, 0, sizeof row);
    carom__op_row = row;
    /* 2 - 3 s + 0.5 s^2 = 0: s = 3 - sqrt(5) */
    ck_assert(cr_first_down_root2(2.0f, -3.0f, 0.5f, 1.0f, &s));
    carom__op_row = 0;
    ck_assert_close(s, 3.0 - sqrt(5.0), 1e-6);
    expect_row(row, quad, "quadratic root");
}
END_TEST

/* The whole circle-circle impact time for uniform acceleration (relative
 * motion linear in time, |p + u s| = R): the search span and its test (1
 * sub, 1 cmp); two poses (2 sub, 12 mul, 8 add, 4 cmp); p, u and q (8 sub,
 * 6 mul, 4 add); R, |p|, the gap, the stable constant term and the
 * coefficients (5 add, 1 sub, 8 mul, 3 cmp, 1 sqrt); the quadratic root
 * (as above); t0 + s (1 add). */
START_TEST(test_circle_circle_impact_time_counts)
{
    uint64_t row[CAROM_OP_COUNT] = {0};
    counts c = {20, 14, 32, 2, 18, 2};
    carom_body_def bd = carom_default_body_def();
    cr_body a, b;
    float toi;
    bd.position.x = -2.0f;
    ck_assert_int_eq(cr_body_build(&bd, &a), CAROM_OK);
    bd.position.x = 2.0f;
    ck_assert_int_eq(cr_body_build(&bd, &b), CAROM_OK);
    a.vel = cr_v(3.0f, 0.0f);
    b.vel = cr_v(-1.0f, 0.0f);
    a.t_sync = b.t_sync = 0.0f;
    a.acc_d = b.acc_d = cr_v(0.0f, -10.0f); /* same: q = 0 */
    a.alpha_d = b.alpha_d = 0.0f;
    carom__op_row = row;
    ck_assert(cr_time_of_impact(&a, &b, 0.0f, 1.0f, 1e-5f, 1.0f /* dt */, &toi));
    carom__op_row = 0;
    ck_assert_close(toi, 3.0 / 4.0, 1e-6); /* gap 3 closed at 4 m/s */
    expect_row(row, c, "circle-circle impact time");
}
END_TEST

/* One head-on frictionless impact of two circles touching at the origin:
 * the 1D restitution impulse as the engine computes it (2D, with the
 * angular terms; a circle's normal lever arm is 0 without arithmetic).
 * Preparation: add 11, sub 13, mul 20, div 2, cmp 7, sqrt 1; the test for
 * friction's extra visits: cmp 1; one visit: add 10, sub 9, mul 17, cmp 2;
 * the sums: add 1, cmp 1. (Inside a step, the resting forces' share of the
 * approach is not taken off: the drift's velocities include them.) */
START_TEST(test_restitution_impulse_counts)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    uint64_t row[CAROM_OP_COUNT] = {0};
    counts c = {22, 22, 37, 2, 11, 1};
    cr_manifold m;
    float approach, impulse;
    tw t;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    bd.friction = 0.0f;
    bd.restitution = 0.5f;
    bd.position.x = -0.5f;
    bd.velocity.x = 2.0f;
    tw_add(&t, &bd);
    bd.position.x = 0.5f;
    bd.velocity.x = -1.0f;
    tw_add(&t, &bd);
    ck_assert(cr_collide(&t.w->bodies[0], &t.w->bodies[1], 0.0f, &m));
    m.a = 0;
    m.b = 1;
    carom__op_row = row;
    impulse = cr_solver_impact(t.w, &m, &approach);
    carom__op_row = 0;
    /* P = (1 + e) v m / 2 for equal masses m = pi / 4 */
    ck_assert_close(impulse, 1.5 * 3.0 * (3.14159265 / 4.0) / 2.0, 1e-6);
    expect_row(row, c, "restitution impulse");
    tw_free(&t);
}
END_TEST

#else /* !CAROM_ENABLE_PROFILE */

START_TEST(test_default_build_has_no_profiler)
{
    carom_world_def wd = carom_default_world_def();
    carom_profile p;
    tw t;
    wd.max_bodies = 1;
    t = tw_make(&wd);
    ck_assert_int_eq(carom_world_set_profile(t.w, &p), CAROM_ERR_DISABLED);
    tw_free(&t);
}
END_TEST

#endif

Suite *suite_profile(void)
{
    Suite *s = suite_create("profile");
    TCase *tc = tcase_create("counts");
    tcase_add_test(tc, test_seed_preset_is_the_design_notes_table);
    tcase_add_test(tc, test_cost_is_the_weighted_sum_of_counts);
#if CAROM_ENABLE_PROFILE
    tcase_add_test(tc, test_verlet_step_of_one_body_without_rotation_counts);
    tcase_add_test(tc, test_verlet_step_of_one_body_with_rotation_counts);
    tcase_add_test(tc, test_root_of_linear_and_quadratic_gap_counts);
    tcase_add_test(tc, test_circle_circle_impact_time_counts);
    tcase_add_test(tc, test_restitution_impulse_counts);
#else
    tcase_add_test(tc, test_default_build_has_no_profiler);
#endif
    suite_add_tcase(s, tc);
    return s;
}
