/*
 * test_integrate.c -- velocity Verlet against analytic motion: exact for
 * constant acceleration (free fall, constant force, constant torque),
 * second-order and symplectic for a spring (force callback).
 */
#include <string.h>

#include "test_util.h"

static tw lone_world(float gy, float dt)
{
    carom_world_def wd = carom_default_world_def();
    wd.max_bodies = 4;
    wd.gravity.x = 0.0f;
    wd.gravity.y = gy;
    wd.dt = dt;
    return tw_make(&wd);
}

/* Verlet is exact for constant acceleration; what remains is float
 * rounding, about n ulp after n steps (120 * 6e-8 ~ 7e-6 relative). */
START_TEST(test_free_fall_follows_parabola_to_float_rounding)
{
    tw t = lone_world(-9.81f, 1.0f / 60.0f);
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    int id, n = 120;
    double time = n / 60.0;
    bd.position.x = 1.0f;
    bd.position.y = 100.0f;
    bd.velocity.x = 3.0f;
    bd.velocity.y = 7.0f;
    id = tw_add(&t, &bd);
    tw_steps(&t, n);
    s = tw_state(&t, id);
    ck_assert_close(s.position.x, 1.0 + 3.0 * time, 1e-5);
    ck_assert_close(s.position.y, 100.0 + 7.0 * time - 0.5 * 9.81 * time * time, 1e-5);
    ck_assert_close(s.velocity.x, 3.0, 1e-6);
    ck_assert_close(s.velocity.y, 7.0 - 9.81 * time, 1e-5);
    tw_free(&t);
}
END_TEST

START_TEST(test_constant_force_gives_x_equals_f_t2_over_2m)
{
    tw t = lone_world(0.0f, 0.01f);
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    int id;
    bd.mass = 4.0f;
    bd.force.x = 2.0f; /* a = 0.5 */
    id = tw_add(&t, &bd);
    tw_steps(&t, 200);
    s = tw_state(&t, id);
    ck_assert_close(s.position.x, 0.5 * 0.5 * 4.0, 1e-5);
    ck_assert_close(s.velocity.x, 0.5 * 2.0, 1e-5);
    tw_free(&t);
}
END_TEST

START_TEST(test_constant_torque_gives_angle_alpha_t2_over_2)
{
    tw t = lone_world(0.0f, 0.01f);
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    float m, I;
    int id;
    bd.radius = 1.0f;
    bd.torque = 0.3f;
    id = tw_add(&t, &bd);
    carom_body_get_mass(t.w, id, &m, &I);
    tw_steps(&t, 100); /* 1 s */
    s = tw_state(&t, id);
    ck_assert_close(carom_rot_angle(s.rotation), 0.5 * (0.3 / I), 1e-5);
    ck_assert_close(s.angular_velocity, 0.3 / I, 1e-5);
    tw_free(&t);
}
END_TEST

START_TEST(test_spin_without_torque_turns_at_constant_rate)
{
    tw t = lone_world(0.0f, 1.0f / 60.0f);
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    int id;
    carom_body_def_set_box(&bd, 1.0f, 0.25f);
    bd.angular_velocity = 2.0f;
    id = tw_add(&t, &bd);
    tw_steps(&t, 60);
    s = tw_state(&t, id);
    /* 60 steps of 2/60 rad: rounding of 60 rotation products only */
    ck_assert_close(s.rotation.c, cos(2.0), 2e-5);
    ck_assert_close(s.rotation.s, sin(2.0), 2e-5);
    ck_assert_close(s.angular_velocity, 2.0, 1e-7);
    tw_free(&t);
}
END_TEST

/* Spring to the origin: F = -k x. */
static void spring(void *user, int body, const carom_body_state *st,
                   carom_vec2 *f, float *torque)
{
    float k = *(const float *)user;
    (void)body;
    (void)torque;
    f->x = -k * st->center.x;
    f->y = -k * st->center.y;
}

START_TEST(test_force_callback_spring_has_second_order_phase_and_bounded_energy)
{
    float k = 1.0f;
    double dt = 0.01, omega = 1.0, emax = 0.0, period = 2.0 * 3.14159265358979;
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    tw t;
    int id, i, n;
    wd.gravity.y = 0.0f;
    wd.dt = (float)dt;
    wd.max_bodies = 2;
    wd.force_fn = spring;
    wd.force_user = &k;
    t = tw_make(&wd);
    bd.mass = 1.0f;
    bd.position.x = 1.0f;
    id = tw_add(&t, &bd);
    n = (int)(10.0 * period / dt + 0.5);
    for (i = 0; i < n; ++i) {
        double e;
        tw_steps(&t, 1);
        s = tw_state(&t, id);
        e = 0.5 * ((double)s.velocity.x * s.velocity.x) +
            0.5 * ((double)s.center.x * s.center.x);
        if (fabs(e - 0.5) > emax)
            emax = fabs(e - 0.5);
    }
    /* Verlet's shadow energy: |E - E0| <= (omega dt)^2 / 8 E0, no drift */
    ck_assert_msg(emax < 0.5 * (omega * dt) * (omega * dt) / 4.0 + 1e-5,
                  "energy error %g", emax);
    /* phase error after time T is about omega^3 dt^2 T / 24 */
    s = tw_state(&t, id);
    ck_assert_close(s.center.x, cos(n * dt), 1e-3);
    tw_free(&t);
}
END_TEST

/* A force callback whose result the program changes between steps. */
typedef struct push {
    float fx, fy, torque;
} push;

static void pushed(void *user, int body, const carom_body_state *st,
                   carom_vec2 *f, float *torque)
{
    const push *p = (const push *)user;
    (void)body;
    (void)st;
    f->x = p->fx;
    f->y = p->fy;
    *torque = p->torque;
}

/* Each bad result of the callback (a NaN or infinite component, or an
 * acceleration beyond CAROM_LIMIT_MAX_ACCEL: for a 1 kg disc of radius
 * 0.5, F > 1e12 N or T r / I = 4 T > 1e12) fails the step with its status,
 * names the body and leaves its state as it was; a good one then steps. */
START_TEST(test_bad_callback_results_fail_the_step_and_change_nothing)
{
    static const struct {
        float fx, fy, torque;
        carom_status st;
    } cases[] = {
        {0.0f, INFINITY, 0.0f, CAROM_ERR_NOT_FINITE},
        {0.0f, 0.0f, NAN, CAROM_ERR_NOT_FINITE},
        {NAN, 0.0f, 0.0f, CAROM_ERR_NOT_FINITE},
        {2.0e12f, 0.0f, 0.0f, CAROM_ERR_OUT_OF_RANGE},
        {0.0f, -2.0e12f, 0.0f, CAROM_ERR_OUT_OF_RANGE},
        {0.0f, 0.0f, 5.0e11f, CAROM_ERR_OUT_OF_RANGE},
    };
    push p = {0.0f, 0.0f, 0.0f};
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state before, after;
    size_t i;
    tw t;
    int id;
    wd.gravity.y = 0.0f;
    wd.max_bodies = 2;
    wd.force_fn = pushed;
    wd.force_user = &p;
    t = tw_make(&wd);
    bd.mass = 1.0f;
    bd.velocity.x = 1.0f;
    id = tw_add(&t, &bd);
    tw_steps(&t, 1);
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        carom_status st;
        before = tw_state(&t, id);
        p.fx = cases[i].fx;
        p.fy = cases[i].fy;
        p.torque = cases[i].torque;
        st = carom_world_step(t.w);
        ck_assert_msg(st == cases[i].st, "case %d: %s, expected %s", (int)i,
                      carom_status_string(st), carom_status_string(cases[i].st));
        ck_assert_int_eq(carom_world_error_body(t.w), id);
        after = tw_state(&t, id);
        ck_assert_msg(memcmp(&before, &after, sizeof before) == 0, "case %d moved the body", (int)i);
    }
    /* within range again: the step is taken, x advances by v dt */
    p.fx = p.fy = p.torque = 0.0f;
    before = tw_state(&t, id);
    tw_steps(&t, 1);
    after = tw_state(&t, id);
    ck_assert_close(after.center.x, before.center.x + 1.0 / 60.0, 1e-6);
    tw_free(&t);
}
END_TEST

Suite *suite_integrate(void)
{
    Suite *s = suite_create("integrate");
    TCase *tc = tcase_create("verlet");
    tcase_add_test(tc, test_free_fall_follows_parabola_to_float_rounding);
    tcase_add_test(tc, test_constant_force_gives_x_equals_f_t2_over_2m);
    tcase_add_test(tc, test_constant_torque_gives_angle_alpha_t2_over_2);
    tcase_add_test(tc, test_spin_without_torque_turns_at_constant_rate);
    tcase_add_test(tc, test_force_callback_spring_has_second_order_phase_and_bounded_energy);
    tcase_add_test(tc, test_bad_callback_results_fail_the_step_and_change_nothing);
    suite_add_tcase(s, tc);
    return s;
}
