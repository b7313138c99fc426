/*
 * test_contact.c -- contacts (src/contact.c): the 2x2 complementarity
 * problem of a two-point manifold against an independent double-precision
 * solution, and the contact capacity as a clean failure of the step.
 */
#include <string.h>

#include "test_util.h"

#include "contact.h"

Suite *suite_contact(void);

/* ---- cr_lcp2 ---------------------------------------------------------------- */

/* The LCP x >= 0, y = K x + b >= 0, x_i y_i = 0 for symmetric positive
 * definite K has exactly one solution; found here by testing the four
 * supports in double precision (Cramer's rule for both pushing). */
static void lcp2_d(double k11, double k12, double k22, double b1, double b2,
                   double *x1, double *x2)
{
    double det = k11 * k22 - k12 * k12;
    double y1 = (k12 * b2 - k22 * b1) / det, y2 = (k12 * b1 - k11 * b2) / det;
    if (y1 >= 0.0 && y2 >= 0.0) {
        *x1 = y1;
        *x2 = y2;
    } else if (-b1 / k11 >= 0.0 && k12 * (-b1 / k11) + b2 >= 0.0) {
        *x1 = -b1 / k11;
        *x2 = 0.0;
    } else if (-b2 / k22 >= 0.0 && k12 * (-b2 / k22) + b1 >= 0.0) {
        *x1 = 0.0;
        *x2 = -b2 / k22;
    } else {
        *x1 = 0.0;
        *x2 = 0.0;
    }
}

/* The conditions themselves, to the rounding of float inputs of size s. */
static void assert_complementary(double k11, double k12, double k22, double b1,
                                 double b2, float x1, float x2, double s,
                                 const char *what)
{
    double y1 = k11 * x1 + k12 * x2 + b1, y2 = k12 * x1 + k22 * x2 + b2;
    double tol = 1e-5 * s;
    ck_assert_msg(x1 >= 0.0f && x2 >= 0.0f, "%s: x = (%g, %g)", what, (double)x1, (double)x2);
    ck_assert_msg(y1 >= -tol && y2 >= -tol, "%s: y = (%g, %g)", what, y1, y2);
    ck_assert_msg(fabs(x1 * y1) <= tol * (1.0 + x1) && fabs(x2 * y2) <= tol * (1.0 + x2),
                  "%s: x.y = (%g, %g)", what, x1 * y1, x2 * y2);
}

/* One of each support: both points push, only the first, only the second,
 * neither (both separating). */
START_TEST(test_lcp2_each_support_against_the_closed_form)
{
    static const float cases[][5] = {
        {2.0f, 0.5f, 1.0f, -1.0f, -1.0f},  /* both: x = -K^-1 b = (2/7, 6/7) */
        {2.0f, 0.5f, 1.0f, -1.0f, 2.0f},   /* first only: x1 = 1/2, y2 = 9/4 */
        {2.0f, 0.5f, 1.0f, 3.0f, -1.0f},   /* second only: x2 = 1, y1 = 7/2 */
        {2.0f, 0.5f, 1.0f, 0.5f, 0.25f},   /* neither */
        {1.0f, -0.9f, 1.0f, -1.0f, 0.5f},  /* negative coupling: both push */
    };
    static const double expected[][2] = {
        {2.0 / 7.0, 6.0 / 7.0}, {0.5, 0.0}, {0.0, 1.0}, {0.0, 0.0}, {0.55 / 0.19, 0.4 / 0.19},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const float *c = cases[i];
        float x1 = -1.0f, x2 = -1.0f;
        double e1, e2;
        lcp2_d(c[0], c[1], c[2], c[3], c[4], &e1, &e2);
        /* the inputs are floats (-0.9f is not -0.9): agree to their rounding */
        ck_assert_close(e1, expected[i][0], 1e-6);
        ck_assert_close(e2, expected[i][1], 1e-6);
        ck_assert_msg(cr_lcp2(c[0], c[1], c[2], c[3], c[4], &x1, &x2) == 1, "case %d", (int)i);
        ck_assert_close(x1, e1, 1e-6);
        ck_assert_close(x2, e2, 1e-6);
        assert_complementary(c[0], c[1], c[2], c[3], c[4], x1, x2, 4.0, "case");
    }
}
END_TEST

/* Random well-conditioned rows (det K / (k11 k22) >= 1e-3, as the solver
 * asks before solving a block): always solved, and the solution is the
 * unique one. */
START_TEST(test_lcp2_well_conditioned_rows_are_always_solved)
{
    unsigned long st = 99;
    int i;
    for (i = 0; i < 20000; ++i) {
        float k11, k22, k12, b1, b2, x1, x2;
        double e1, e2, rho;
        st = (st * 1103515245ul + 12345ul) & 0x7fffffffu;
        k11 = (float)(0.01 + 100.0 * (double)st / 2147483648.0);
        st = (st * 1103515245ul + 12345ul) & 0x7fffffffu;
        k22 = (float)(0.01 + 100.0 * (double)st / 2147483648.0);
        st = (st * 1103515245ul + 12345ul) & 0x7fffffffu;
        rho = -0.9995 + 1.999 * (double)st / 2147483648.0;
        k12 = (float)(rho * sqrt((double)k11 * k22));
        st = (st * 1103515245ul + 12345ul) & 0x7fffffffu;
        b1 = (float)(-10.0 + 20.0 * (double)st / 2147483648.0);
        st = (st * 1103515245ul + 12345ul) & 0x7fffffffu;
        b2 = (float)(-10.0 + 20.0 * (double)st / 2147483648.0);
        if (((double)k11 * k22 - (double)k12 * k12) < 1e-3 * (double)k11 * k22)
            continue;
        ck_assert_msg(cr_lcp2(k11, k12, k22, b1, b2, &x1, &x2) == 1,
                      "K = [%g %g; %g %g], b = (%g, %g): no solution", (double)k11,
                      (double)k12, (double)k12, (double)k22, (double)b1, (double)b2);
        lcp2_d(k11, k12, k22, b1, b2, &e1, &e2);
        /* the conditioning bounds the error: |dx| <= |K^-1| |db| */
        ck_assert_msg(fabs(x1 - e1) <= 2e-3 * (1.0 + fabs(e1)) &&
                          fabs(x2 - e2) <= 2e-3 * (1.0 + fabs(e2)),
                      "K = [%g %g; %g %g], b = (%g, %g): x = (%g, %g), expected (%g, %g)",
                      (double)k11, (double)k12, (double)k12, (double)k22, (double)b1,
                      (double)b2, (double)x1, (double)x2, e1, e2);
    }
}
END_TEST

/* K singular to float's rounding (det K ~ 1e-6 of k11 k22): no support
 * may fit any more; the result is then "none" (0) or a finite,
 * non-negative impulse, never a NaN. */
START_TEST(test_lcp2_nearly_singular_row_gives_none_or_a_finite_impulse)
{
    float x1 = -1.0f, x2 = -1.0f;
    double det = 3.5999999 * 7.38999987 - 5.15790653 * 5.15790653;
    ck_assert(fabs(det) < 1e-5 * 3.6 * 7.39);
    if (cr_lcp2(3.5999999f, -5.15790653f, 7.38999987f, -6.38000011f, -8.10000038f, &x1, &x2)) {
        ck_assert(x1 >= 0.0f && x2 >= 0.0f);
        ck_assert(x1 - x1 == 0.0f && x2 - x2 == 0.0f);
    }
}
END_TEST

/* ---- contact capacity ------------------------------------------------------- */

/* One contact fits: a ball resting on the floor has it; a second ball then
 * lands during a step and needs another. That step fails with
 * CAROM_ERR_CONTACT_CAPACITY and is not taken: every body, the time and
 * the step count are as before it. The same with each method. */
START_TEST(test_contact_capacity_fails_the_step_cleanly)
{
    int method;
    for (method = 0; method < CAROM_METHOD_COUNT; ++method) {
        carom_world_def wd = carom_default_world_def();
        carom_body_def bd = carom_default_body_def();
        carom_body_state before[3], after[3];
        carom_status st = CAROM_OK;
        float t0;
        long n0;
        int id[3], k, steps = 0;
        tw t;
        wd.method = (carom_method)method;
        wd.max_bodies = 3;
        wd.max_contacts = 1;
        t = tw_make(&wd);
        carom_body_def_set_box(&bd, 5.0f, 0.5f);
        bd.type = CAROM_BODY_STATIC;
        bd.position.y = -0.5f;
        id[0] = tw_add(&t, &bd);
        bd = carom_default_body_def();
        bd.position.x = -2.0f;
        bd.position.y = 0.5f; /* resting on the floor */
        id[1] = tw_add(&t, &bd);
        bd.position.x = 2.0f;
        bd.position.y = 1.5f; /* lands after about 0.45 s */
        id[2] = tw_add(&t, &bd);
        while (st == CAROM_OK && steps < 120) {
            for (k = 0; k < 3; ++k)
                before[k] = tw_state(&t, id[k]);
            t0 = carom_world_time(t.w);
            n0 = carom_world_step_count(t.w);
            st = carom_world_step(t.w);
            ++steps;
        }
        ck_assert_msg(st == CAROM_ERR_CONTACT_CAPACITY, "%s: %s after %d steps",
                      carom_method_name((carom_method)method), carom_status_string(st), steps);
        ck_assert_msg(steps > 1, "%s: the resting ball alone must fit",
                      carom_method_name((carom_method)method));
        for (k = 0; k < 3; ++k) {
            after[k] = tw_state(&t, id[k]);
            ck_assert_msg(memcmp(&before[k], &after[k], sizeof before[k]) == 0,
                          "%s: body %d changed by the failed step",
                          carom_method_name((carom_method)method), k);
        }
        ck_assert(carom_world_time(t.w) == t0);
        ck_assert_int_eq(carom_world_step_count(t.w), n0);
        tw_free(&t);
    }
}
END_TEST


/* ---- warm starts -------------------------------------------------------------- */

/* Two boxes stacked until they sleep, `idle` steps more (nothing awake),
 * then the top one pushed: its state after 30 steps. */
static carom_body_state stack_after_idle_steps(int idle)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def g = carom_default_body_def(), bd = carom_default_body_def();
    carom_body_state st;
    int top = -1, k;
    tw t;
    wd.max_bodies = 3;
    t = tw_make(&wd);
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 5.0f, 0.5f);
    g.position.y = -0.5f;
    tw_add(&t, &g);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    for (k = 0; k < 2; ++k) {
        bd.position.y = 0.5f + (float)k;
        top = tw_add(&t, &bd);
    }
    for (k = 0; k < 600 && carom_body_is_awake(t.w, top); ++k)
        tw_steps(&t, 1);
    ck_assert(!carom_body_is_awake(t.w, top));
    tw_steps(&t, idle);
    ck_assert_int_eq(carom_body_set_velocity(t.w, top, (carom_vec2){0.5f, 0.0f}), CAROM_OK);
    tw_steps(&t, 30);
    st = tw_state(&t, top);
    tw_free(&t);
    return st;
}

/* A step in which nothing is awake changes nothing, so neither does the
 * number of such steps (found by the API fuzzer: such a step handed the
 * warm starts of two steps before, or never written ones, to the next). */
START_TEST(test_steps_with_nothing_awake_leave_no_trace)
{
    carom_body_state a = stack_after_idle_steps(1), b = stack_after_idle_steps(2);
    carom_body_state c = stack_after_idle_steps(0);
    ck_assert(memcmp(&a, &b, sizeof a) == 0);
    ck_assert(memcmp(&a, &c, sizeof a) == 0);
}
END_TEST

/*
 * A pair's reach covers what a body dropped onto a supported one closes
 * in a step: 1 mm boxes under 9.81 m/s^2 at dt = 1/60, the top one
 * released 0.2 mm above one resting on the floor. In the step it falls
 * g dt^2 / 2 = 1.4 mm, and the relative acceleration the reach took
 * (both bodies under gravity: 0) hid it: the discrete and first-impact
 * methods left the two boxes coincident after one step. Every method
 * must land it on the lower box: centres at 0.5 and 1.5 mm, to 1 % of
 * a box.
 */
START_TEST(test_box_dropped_onto_a_resting_box_is_caught)
{
    int m;
    for (m = 0; m < CAROM_METHOD_COUNT; ++m) {
        carom_world_def wd = carom_default_world_def();
        carom_body_def bd = carom_default_body_def();
        tw t;
        int low, top, k;
        wd.method = (carom_method)m;
        wd.max_bodies = 3;
        wd.gravity.y = -9.81f;
        wd.enable_sleep = 0;
        t = tw_make(&wd);
        bd.type = CAROM_BODY_STATIC;
        carom_body_def_set_box(&bd, 0.01f, 0.0005f);
        bd.position.y = -0.0005f;
        tw_add(&t, &bd);
        bd.type = CAROM_BODY_DYNAMIC;
        carom_body_def_set_box(&bd, 0.0005f, 0.0005f);
        bd.position.y = 0.0005f;
        low = tw_add(&t, &bd);
        bd.position.y = 0.0017f;
        top = tw_add(&t, &bd);
        for (k = 0; k < 60; ++k) {
            tw_steps(&t, 1);
            ck_assert_msg(tw_state(&t, top).position.y - tw_state(&t, low).position.y > 0.00099f,
                          "%s: step %d: the boxes' centres are %g mm apart (1 mm: touching)",
                          carom_method_name((carom_method)m), k + 1,
                          1000.0 * (tw_state(&t, top).position.y - tw_state(&t, low).position.y));
        }
        ck_assert_close(tw_state(&t, low).position.y, 0.0005, 1e-5);
        ck_assert_close(tw_state(&t, top).position.y, 0.0015, 1e-5);
        tw_free(&t);
    }
}
END_TEST

/* ---- contact points -------------------------------------------------------- */

/*
 * A disc (radius 0.5, I = m r^2 / 2) strikes the floor from a gap, no
 * gravity, e and mu given: Newton's normal impulse Jn = (1 + e) m |vy| and
 * a tangential one that stops the slip of its lowest point, vx + w r, if
 * mu Jn allows: Jt = m slip / 3, so vx' = vx - slip / 3 and w' = w -
 * 2 slip / (3 r). (a) vx 2, no spin, vy -5, e 0.5, mu 0.3, 5 cm gap:
 * Jt = 2/3 m < mu Jn = 2.25 m, so it sticks: vx' = 4/3, w' = -8/3. (b)
 * Rolling already (vx 4, w -8), vy -5, e 0.9, mu 0.3, 8 cm gap: no slip,
 * no friction: vx and w unchanged. The discrete method took a circle's
 * contact point midway across the gap, its friction lever R + gap / 2:
 * (a) left at 1.376 m/s and -2.621 rad/s still slipping, (b) at 4.096 and
 * -7.585 (found by a review). A circle's arm is its surface point now.
 */
START_TEST(test_disc_bounce_from_a_gap_takes_friction_at_its_surface)
{
    static const float gap[2] = {0.05f, 0.08f}, vx[2] = {2.0f, 4.0f}, w0[2] = {0.0f, -8.0f},
                       e[2] = {0.5f, 0.9f};
    int m, k;
    for (m = 0; m < CAROM_METHOD_COUNT; ++m)
        for (k = 0; k < 2; ++k) {
            carom_world_def wd = carom_default_world_def();
            carom_body_def bd = carom_default_body_def();
            double slip = (double)vx[k] + 0.5 * (double)w0[k];
            carom_body_state d;
            tw t;
            int disc;
            wd.method = (carom_method)m;
            wd.gravity.y = 0.0f;
            wd.max_bodies = 2;
            t = tw_make(&wd);
            bd.type = CAROM_BODY_STATIC;
            ck_assert_int_eq(carom_body_def_set_box(&bd, 500.0f, 0.5f), CAROM_OK);
            bd.position.y = -0.5f;
            bd.restitution = e[k];
            bd.friction = 0.3f;
            tw_add(&t, &bd);
            bd = carom_default_body_def();
            bd.radius = 0.5f;
            bd.position.y = 0.5f + gap[k];
            bd.velocity.x = vx[k];
            bd.velocity.y = -5.0f;
            bd.angular_velocity = w0[k];
            bd.restitution = e[k];
            bd.friction = 0.3f;
            disc = tw_add(&t, &bd);
            tw_steps(&t, 30);
            d = tw_state(&t, disc);
            ck_assert_msg(fabs(d.velocity.x - ((double)vx[k] - slip / 3.0)) < 1e-4 &&
                              fabs(d.angular_velocity - ((double)w0[k] - 2.0 * slip / 1.5)) < 1e-4 &&
                              fabs(d.velocity.y - 5.0 * (double)e[k]) < 1e-4,
                          "%s, case %d: v = (%g, %g), w = %g; want (%g, %g), %g",
                          carom_method_name((carom_method)m), k, (double)d.velocity.x,
                          (double)d.velocity.y, (double)d.angular_velocity,
                          (double)vx[k] - slip / 3.0, 5.0 * (double)e[k],
                          (double)w0[k] - 2.0 * slip / 1.5);
            tw_free(&t);
        }
}
END_TEST

Suite *suite_contact(void)
{
    Suite *s = suite_create("contact");
    TCase *tc = tcase_create("lcp2");
    TCase *tk = tcase_create("capacity");
    tcase_add_test(tc, test_lcp2_each_support_against_the_closed_form);
    tcase_add_test(tc, test_lcp2_well_conditioned_rows_are_always_solved);
    tcase_add_test(tc, test_lcp2_nearly_singular_row_gives_none_or_a_finite_impulse);
    tcase_add_test(tk, test_contact_capacity_fails_the_step_cleanly);
    tcase_add_test(tk, test_steps_with_nothing_awake_leave_no_trace);
    tcase_add_test(tk, test_box_dropped_onto_a_resting_box_is_caught);
    tcase_add_test(tk, test_disc_bounce_from_a_gap_takes_friction_at_its_surface);
    suite_add_tcase(s, tc);
    suite_add_tcase(s, tk);
    return s;
}
