/*
 * test_api.c -- the calls a program makes between steps: body control,
 * kinematic bodies, removal with stable ids, collision filtering, sensors,
 * touch events and queries. Expected values are closed-form (impulse over
 * mass, free fall, ray-circle intersections) or properties (a stale id is
 * refused, a filtered pair never meets).
 */
#include <string.h>

#include "test_util.h"

static carom_world_def zero_g(int n)
{
    carom_world_def wd = carom_default_world_def();
    wd.gravity.y = 0.0f;
    wd.max_bodies = n;
    wd.rest_speed = 0.0f;
    return wd;
}

static int add_ball(tw *t, float r, float x, float y, float vx, float vy)
{
    carom_body_def bd = carom_default_body_def();
    bd.radius = r;
    bd.position.x = x;
    bd.position.y = y;
    bd.velocity.x = vx;
    bd.velocity.y = vy;
    bd.friction = 0.0f;
    bd.restitution = 1.0f;
    return tw_add(t, &bd);
}

static int add_ground(tw *t)
{
    carom_body_def g = carom_default_body_def();
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 10.0f, 0.5f);
    g.position.y = -0.5f;
    return tw_add(t, &g);
}

/* ---- body control --------------------------------------------------------- */

START_TEST(test_velocity_setters_and_getters)
{
    carom_world_def wd = zero_g(3);
    tw t = tw_make(&wd);
    int b = add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f), g;
    carom_vec2 v = {3.0f, -4.0f}, got;
    float om;
    carom_body_def sd = carom_default_body_def();
    sd.type = CAROM_BODY_STATIC;
    sd.position.x = 5.0f;
    g = tw_add(&t, &sd);
    ck_assert_int_eq(carom_body_set_velocity(t.w, b, v), CAROM_OK);
    ck_assert_int_eq(carom_body_set_angular_velocity(t.w, b, 2.5f), CAROM_OK);
    ck_assert_int_eq(carom_body_get_velocity(t.w, b, &got, &om), CAROM_OK);
    ck_assert(got.x == 3.0f && got.y == -4.0f && om == 2.5f);
    ck_assert_int_eq(carom_body_get_velocity(t.w, b, NULL, NULL), CAROM_OK);
    /* one step of free flight: x = v dt exactly in zero gravity */
    tw_steps(&t, 1);
    ck_assert_close(tw_state(&t, b).position.x, 3.0 / 60.0, 1e-6);
    /* refused: static bodies, NaN, out of range */
    ck_assert_int_eq(carom_body_set_velocity(t.w, g, v), CAROM_ERR_BAD_BODY_TYPE);
    v.x = NAN;
    ck_assert_int_eq(carom_body_set_velocity(t.w, b, v), CAROM_ERR_NOT_FINITE);
    v.x = 2.0f * CAROM_LIMIT_MAX_SPEED;
    ck_assert_int_eq(carom_body_set_velocity(t.w, b, v), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_set_angular_velocity(t.w, b, INFINITY), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_get_velocity(t.w, b, &got, NULL), CAROM_OK);
    ck_assert(got.x == 3.0f); /* unchanged by the refused calls */
    tw_free(&t);
}
END_TEST

/* An impulse J at a point r from the centre: dv = J / m, dw = (r x J) / I. */
START_TEST(test_impulse_at_a_point_changes_velocity_exactly)
{
    carom_world_def wd = zero_g(2);
    tw t = tw_make(&wd);
    carom_body_def bd = carom_default_body_def();
    carom_vec2 J = {0.0f, 2.0f}, p = {0.5f, 0.0f}, v;
    float m, I, om;
    int b;
    carom_body_def_set_box(&bd, 0.5f, 0.25f);
    b = tw_add(&t, &bd);
    carom_body_get_mass(t.w, b, &m, &I);
    ck_assert_int_eq(carom_body_apply_impulse(t.w, b, J, p), CAROM_OK);
    carom_body_get_velocity(t.w, b, &v, &om);
    ck_assert_close(v.y, 2.0 / m, 1e-6);
    ck_assert_close(om, 0.5 * 2.0 / I, 1e-6);
    ck_assert_int_eq(carom_body_apply_angular_impulse(t.w, b, -1.0f), CAROM_OK);
    carom_body_get_velocity(t.w, b, &v, &om);
    ck_assert_close(om, (1.0 - 1.0) / I, 1e-6);
    J.x = NAN;
    ck_assert_int_eq(carom_body_apply_impulse(t.w, b, J, p), CAROM_ERR_NOT_FINITE);
    tw_free(&t);
}
END_TEST

/* A force for one step only, in zero gravity: after that step v = F dt / m
 * and x = F dt^2 / (2 m); afterwards the body coasts. */
START_TEST(test_one_step_force_and_torque)
{
    carom_world_def wd = zero_g(1);
    tw t = tw_make(&wd);
    carom_body_def bd = carom_default_body_def();
    const double dt = 1.0 / 60.0;
    carom_vec2 F = {6.0f, 0.0f}, at;
    carom_body_state s;
    float m, I;
    int b;
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    b = tw_add(&t, &bd);
    carom_body_get_mass(t.w, b, &m, &I);
    at = tw_state(&t, b).center;
    ck_assert_int_eq(carom_body_apply_force(t.w, b, F, at), CAROM_OK);
    ck_assert_int_eq(carom_body_apply_force(t.w, b, F, at), CAROM_OK); /* adds up */
    ck_assert_int_eq(carom_body_apply_torque(t.w, b, 3.0f), CAROM_OK);
    tw_steps(&t, 1);
    s = tw_state(&t, b);
    ck_assert_close(s.velocity.x, 12.0 * dt / m, 1e-5);
    ck_assert_close(s.position.x, 12.0 * dt * dt / (2.0 * m), 1e-5);
    ck_assert_close(s.angular_velocity, 3.0 * dt / I, 1e-5);
    tw_steps(&t, 3);
    s = tw_state(&t, b);
    ck_assert_close(s.velocity.x, 12.0 * dt / m, 1e-5);
    ck_assert_close(s.angular_velocity, 3.0 * dt / I, 1e-5);
    ck_assert_int_eq(carom_body_apply_torque(t.w, b, NAN), CAROM_ERR_NOT_FINITE);
    tw_free(&t);
}
END_TEST

/* Teleporting a box resting on the ground up into the air: its contact is
 * forgotten, it falls freely from there (y = y0 - g t^2 / 2 at the step
 * ends, Verlet being exact under constant gravity). */
START_TEST(test_set_transform_teleports_and_forgets_contacts)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_vec2 up = {1.0f, 5.0f};
    carom_body_state s;
    tw t;
    int b, k;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.y = 0.5f;
    b = tw_add(&t, &bd);
    tw_steps(&t, 30);
    ck_assert_int_eq(carom_body_set_transform(t.w, b, up, carom_rot_from_angle(0.5f)),
                     CAROM_OK);
    s = tw_state(&t, b);
    ck_assert(s.position.x == 1.0f && s.position.y == 5.0f);
    ck_assert_close(carom_rot_angle(s.rotation), 0.5, 1e-6);
    for (k = 1; k <= 20; ++k) {
        double tt = k / 60.0;
        tw_steps(&t, 1);
        s = tw_state(&t, b);
        ck_assert_close(s.position.y, 5.0 - 5.0 * tt * tt, 1e-5);
    }
    ck_assert_int_eq(carom_body_set_transform(t.w, b, up, (carom_rot){0.0f, 0.0f}),
                     CAROM_ERR_BAD_ROTATION);
    up.y = NAN;
    ck_assert_int_eq(carom_body_set_transform(t.w, b, up, carom_rot_from_angle(0.0f)),
                     CAROM_ERR_NOT_FINITE);
    tw_free(&t);
}
END_TEST

START_TEST(test_material_and_user_data_setters)
{
    carom_world_def wd = carom_default_world_def();
    tw t;
    int ground, b, k, x = 42;
    float top = -1.0f;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    ground = add_ground(&t);
    b = add_ball(&t, 0.25f, 0.0f, 2.25f, 0.0f, 0.0f);
    ck_assert_int_eq(carom_body_set_restitution(t.w, b, 0.5f), CAROM_OK);
    ck_assert_int_eq(carom_body_set_restitution(t.w, ground, 0.5f), CAROM_OK);
    ck_assert_int_eq(carom_body_set_restitution(t.w, b, 1.5f), CAROM_ERR_BAD_RESTITUTION);
    ck_assert_int_eq(carom_body_set_friction(t.w, b, -1.0f), CAROM_ERR_BAD_FRICTION);
    ck_assert_int_eq(carom_body_set_friction(t.w, b, 1.0e20f), CAROM_ERR_BAD_FRICTION);
    ck_assert_int_eq(carom_body_set_friction(t.w, b, 0.2f), CAROM_OK);
    /* dropped 2 m with e = 0.5: it rebounds to 2 e^2 = 0.5 m */
    for (k = 0; k < 100; ++k) {
        carom_body_state s;
        tw_steps(&t, 1);
        s = tw_state(&t, b);
        if (k > 45 && s.position.y - 0.25f > top)
            top = s.position.y - 0.25f;
    }
    ck_assert_close(top, 0.5, 0.02);
    ck_assert_ptr_null(carom_body_get_user_data(t.w, b));
    ck_assert_int_eq(carom_body_set_user_data(t.w, b, &x), CAROM_OK);
    ck_assert_ptr_eq(carom_body_get_user_data(t.w, b), &x);
    ck_assert_ptr_null(carom_body_get_user_data(t.w, 999));
    tw_free(&t);
}
END_TEST

/* ---- kinematic bodies ----------------------------------------------------- */

/* A kinematic paddle moving at u strikes a resting ball (e = 1): the impact
 * is at gap / u exactly, the ball leaves at 2u, the paddle keeps u. */
START_TEST(test_kinematic_paddle_pushes_and_is_not_pushed)
{
    carom_world_def wd = zero_g(2);
    carom_body_def pd = carom_default_body_def();
    const carom_event *ev = NULL;
    carom_vec2 v;
    tw t;
    int p, b, n = 0, k;
    wd.method = CAROM_METHOD_EVENTS;
    t = tw_make(&wd);
    pd.type = CAROM_BODY_KINEMATIC;
    carom_body_def_set_box(&pd, 0.25f, 1.0f);
    pd.restitution = 1.0f;
    pd.friction = 0.0f;
    p = tw_add(&t, &pd);
    ck_assert_int_eq(carom_body_set_velocity(t.w, p, (carom_vec2){2.0f, 0.0f}), CAROM_OK);
    b = add_ball(&t, 0.5f, 1.75f, 0.0f, 0.0f, 0.0f); /* gap 1 m */
    for (k = 0; k < 60 && n == 0; ++k) {
        tw_steps(&t, 1);
        ev = carom_world_events(t.w, &n);
    }
    ck_assert_int_eq(n, 1);
    ck_assert_close(ev[0].t, 0.5, 1e-6);
    carom_body_get_velocity(t.w, b, &v, NULL);
    ck_assert_close(v.x, 4.0, 1e-5);
    carom_body_get_velocity(t.w, p, &v, NULL);
    ck_assert(v.x == 2.0f && v.y == 0.0f);
    tw_free(&t);
}
END_TEST

/* A kinematic platform carries a box up against gravity (friction holds it
 * on the platform while both rise). */
START_TEST(test_kinematic_platform_lifts_a_box)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def pd = carom_default_body_def(), bd = carom_default_body_def();
    carom_body_state s;
    tw t;
    int p, b;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    pd.type = CAROM_BODY_KINEMATIC;
    carom_body_def_set_box(&pd, 2.0f, 0.25f);
    pd.velocity.y = 1.0f;
    p = tw_add(&t, &pd);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.y = 0.75f;
    b = tw_add(&t, &bd);
    tw_steps(&t, 120);
    s = tw_state(&t, b);
    /* the platform is at y = 2 after 2 s; the box rests on it */
    ck_assert_close(tw_state(&t, p).position.y, 2.0, 1e-5);
    ck_assert_close(s.position.y, 2.75, 0.02);
    ck_assert_close(s.velocity.y, 1.0, 0.05);
    tw_free(&t);
}
END_TEST

/* ---- removal ------------------------------------------------------------------ */

START_TEST(test_removal_frees_the_slot_and_refuses_stale_ids)
{
    carom_world_def wd = zero_g(2);
    tw t = tw_make(&wd);
    carom_body_state s;
    carom_vec2 v = {1.0f, 0.0f};
    int a = add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f);
    int b = add_ball(&t, 0.5f, 3.0f, 0.0f, 0.0f, 0.0f), c;
    ck_assert_int_eq(carom_world_remove_body(t.w, a), CAROM_OK);
    ck_assert_int_eq(carom_world_body_count(t.w), 1);
    ck_assert(!carom_body_is_valid(t.w, a));
    ck_assert(carom_body_is_valid(t.w, b));
    /* every call refuses the stale id */
    ck_assert_int_eq(carom_body_get_state(t.w, a, &s), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_set_velocity(t.w, a, v), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_apply_impulse(t.w, a, v, v), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_world_remove_body(t.w, a), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_set_force(t.w, a, v, 0.0f), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_world_remove_body(t.w, 12345), CAROM_ERR_BAD_BODY_ID);
    /* the slot is reused, with a new id */
    c = add_ball(&t, 0.5f, -3.0f, 0.0f, 0.0f, 0.0f);
    ck_assert_int_ne(c, a);
    ck_assert_int_eq(c & ((1 << CAROM_ID_INDEX_BITS) - 1), a & ((1 << CAROM_ID_INDEX_BITS) - 1));
    ck_assert_int_eq(carom_body_get_state(t.w, a, &s), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_get_state(t.w, c, &s), CAROM_OK);
    ck_assert(s.position.x == -3.0f);
    ck_assert_int_eq(carom_world_body_count(t.w), 2);
    tw_steps(&t, 5);
    tw_free(&t);
}
END_TEST

/* A slot reused 2^(31 - CAROM_ID_INDEX_BITS) times wraps its generation
 * back to 0 (documented): its removed body's id is still stale, never
 * "no such body", at every count, the wrap included. */
START_TEST(test_stale_id_stays_stale_when_the_generation_wraps)
{
    carom_world_def wd = zero_g(2);
    tw t = tw_make(&wd);
    const int wrap = 1 << (31 - CAROM_ID_INDEX_BITS);
    int k, id = add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f), first = id;
    (void)add_ball(&t, 0.5f, 3.0f, 0.0f, 0.0f, 0.0f);
    for (k = 1; k <= wrap + 1; ++k) {
        ck_assert_int_eq(carom_world_remove_body(t.w, id), CAROM_OK);
        ck_assert_msg(carom_world_remove_body(t.w, id) == CAROM_ERR_STALE_ID,
                      "removal %d: %s", k, carom_status_string(carom_world_remove_body(t.w, id)));
        id = add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f);
        /* the id comes back only when the generation has wrapped */
        ck_assert_int_eq(id == first, k == wrap);
    }
    tw_free(&t);
}
END_TEST

/* Removing the ground under a settled (sleeping) stack: the stack wakes and
 * falls freely, and no warm start of the ground's contacts reaches the
 * body that takes its slot. */
START_TEST(test_removing_a_support_wakes_and_drops_what_it_held)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int ground, boxes[3], i, k, other;
    wd.max_bodies = 5;
    t = tw_make(&wd);
    ground = add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    for (i = 0; i < 3; ++i) {
        bd.position.y = 0.5f + (float)i;
        boxes[i] = tw_add(&t, &bd);
    }
    tw_steps(&t, 120);
    ck_assert(!carom_body_is_awake(t.w, boxes[2])); /* asleep */
    ck_assert_int_eq(carom_world_remove_body(t.w, ground), CAROM_OK);
    ck_assert(carom_body_is_awake(t.w, boxes[0]) && carom_body_is_awake(t.w, boxes[2]));
    /* a new static body in the ground's slot, far away */
    bd = carom_default_body_def();
    bd.type = CAROM_BODY_STATIC;
    bd.position.x = 100.0f;
    other = tw_add(&t, &bd);
    (void)other;
    for (k = 1; k <= 30; ++k) {
        double tt = k / 60.0;
        tw_steps(&t, 1);
        for (i = 0; i < 3; ++i)
            ck_assert_close(tw_state(&t, boxes[i]).position.y, 0.5 + i - 5.0 * tt * tt, 2e-3);
    }
    tw_free(&t);
}
END_TEST

/* Removal in mid-impact: a ball about to strike another is removed; the
 * other never moves and every step succeeds. */
START_TEST(test_removal_mid_simulation_leaves_nothing_dangling)
{
    carom_world_def wd = zero_g(3);
    tw t = tw_make(&wd);
    int a = add_ball(&t, 0.5f, 0.0f, 0.0f, 10.0f, 0.0f);
    int b = add_ball(&t, 0.5f, 1.2f, 0.0f, 0.0f, 0.0f);
    tw_steps(&t, 1);
    ck_assert_int_eq(carom_world_remove_body(t.w, a), CAROM_OK);
    tw_steps(&t, 30);
    ck_assert(tw_state(&t, b).velocity.x == 0.0f);
    tw_free(&t);
}
END_TEST

/* ---- filtering ---------------------------------------------------------------- */

/* Two balls on a collision course: they bounce unless the filter says no. */
static int balls_meet(uint32_t cat_a, uint32_t mask_a, int group_a, uint32_t cat_b,
                      uint32_t mask_b, int group_b)
{
    carom_world_def wd = zero_g(2);
    carom_body_def bd = carom_default_body_def();
    tw t = tw_make(&wd);
    int met;
    bd.restitution = 1.0f;
    bd.friction = 0.0f;
    bd.position.x = -2.0f;
    bd.velocity.x = 2.0f;
    bd.category_bits = cat_a;
    bd.mask_bits = mask_a;
    bd.group_index = group_a;
    tw_add(&t, &bd);
    bd.position.x = 2.0f;
    bd.velocity.x = -2.0f;
    bd.category_bits = cat_b;
    bd.mask_bits = mask_b;
    bd.group_index = group_b;
    tw_add(&t, &bd);
    tw_steps(&t, 120);
    met = tw_state(&t, 0).velocity.x < 0.0f;
    if (!met)
        ck_assert(tw_state(&t, 0).position.x > 2.0f); /* passed through */
    tw_free(&t);
    return met;
}

START_TEST(test_collision_filter_bits_and_groups)
{
    ck_assert(balls_meet(1u, 0xffffffffu, 0, 1u, 0xffffffffu, 0));
    ck_assert(!balls_meet(1u, 0xfffffffdu, 0, 2u, 0xffffffffu, 0)); /* a ignores 2 */
    ck_assert(!balls_meet(1u, 0xffffffffu, 0, 2u, 0xfffffffeu, 0)); /* b ignores 1 */
    ck_assert(balls_meet(1u, 2u, 0, 2u, 1u, 0));
    ck_assert(!balls_meet(1u, 0xffffffffu, -3, 1u, 0xffffffffu, -3)); /* same negative */
    ck_assert(balls_meet(1u, 0u, 4, 1u, 0u, 4));                     /* same positive */
    ck_assert(!balls_meet(1u, 0u, 4, 1u, 0u, 5));                    /* groups differ */
}
END_TEST

START_TEST(test_filter_set_after_creation)
{
    carom_world_def wd = zero_g(2);
    tw t = tw_make(&wd);
    int a = add_ball(&t, 0.5f, -2.0f, 0.0f, 2.0f, 0.0f);
    add_ball(&t, 0.5f, 2.0f, 0.0f, -2.0f, 0.0f);
    ck_assert_int_eq(carom_body_set_filter(t.w, a, 1u, 0u, 0), CAROM_OK);
    tw_steps(&t, 120);
    ck_assert(tw_state(&t, a).position.x > 2.0f);
    tw_free(&t);
}
END_TEST

/* ---- sensors and touch events ----------------------------------------------------- */

/* A ball falls through a static sensor box: no impulse (free fall exactly),
 * one begin event when it first overlaps, one end event after it leaves. */
START_TEST(test_sensor_reports_overlap_without_impulse)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def sd = carom_default_body_def();
    tw t;
    int sensor, ball, k, begins = 0, ends = 0, begin_step = -1, end_step = -1;
    wd.max_bodies = 2;
    wd.enable_sleep = 0;
    t = tw_make(&wd);
    sd.type = CAROM_BODY_STATIC;
    sd.is_sensor = 1;
    carom_body_def_set_box(&sd, 2.0f, 0.5f);
    sensor = tw_add(&t, &sd);
    ball = add_ball(&t, 0.25f, 0.0f, 2.1f, 0.0f, 0.0f);
    for (k = 1; k <= 90; ++k) {
        int n, i;
        const carom_touch_event *e;
        double tt = k / 60.0;
        tw_steps(&t, 1);
        ck_assert_close(tw_state(&t, ball).position.y, 2.1 - 5.0 * tt * tt, 1e-5);
        e = carom_world_touch_events(t.w, &n);
        for (i = 0; i < n; ++i) {
            ck_assert_int_eq(e[i].sensor, 1);
            ck_assert_int_eq(e[i].body_a, sensor);
            ck_assert_int_eq(e[i].body_b, ball);
            if (e[i].begin) {
                ++begins;
                begin_step = k;
            } else {
                ++ends;
                end_step = k;
            }
        }
    }
    ck_assert_int_eq(begins, 1);
    ck_assert_int_eq(ends, 1);
    /* overlapping from the first step end with y - 0.25 < 0.5, i.e.
     * 5 t^2 > 1.35, until y + 0.25 < -0.5, i.e. 5 t^2 > 2.85 */
    ck_assert_int_eq(begin_step, (int)floor(60.0 * sqrt(1.35 / 5.0)) + 1);
    ck_assert_int_eq(end_step, (int)floor(60.0 * sqrt(2.85 / 5.0)) + 1);
    tw_free(&t);
}
END_TEST

/*
 * A ball (r 0.1 m) at 60 to 300 m/s through a static sensor 0.2 m wide,
 * zero gravity, dt 1/60, from ten starting offsets: at 60 m/s it moves
 * 1 m a step, and is apart from the sensor at most step ends. Every
 * crossing is one begin and one end, in the step of the crossing, both
 * methods; a ball passing beside the sensor (0.05 m clear) none. Touches
 * were the overlaps at step ends alone, and 4 to 10 of 10 crossings went
 * unreported.
 */
START_TEST(test_a_fast_body_crossing_a_sensor_is_reported)
{
    static const float speeds[] = {60.0f, 100.0f, 300.0f};
    static const carom_method methods[] = {CAROM_METHOD_EVENTS, CAROM_METHOD_DISCRETE};
    int m, v, o, k, beside;
    for (m = 0; m < 2; ++m)
        for (v = 0; v < 3; ++v)
            for (o = 0; o < 10; ++o)
                for (beside = 0; beside < 2; ++beside) {
                    carom_world_def wd = carom_default_world_def();
                    carom_body_def sd = carom_default_body_def();
                    int begins = 0, ends = 0;
                    tw t;
                    wd.gravity.y = 0.0f;
                    wd.method = methods[m];
                    wd.max_bodies = 2;
                    wd.enable_sleep = 0;
                    t = tw_make(&wd);
                    sd.type = CAROM_BODY_STATIC;
                    sd.is_sensor = 1;
                    carom_body_def_set_box(&sd, 0.1f, 0.5f);
                    (void)tw_add(&t, &sd);
                    (void)add_ball(&t, 0.1f, -5.0f - 0.1f * (float)o,
                                   beside ? 0.65f : 0.0f, speeds[v], 0.0f);
                    for (k = 0; k < 20; ++k) {
                        int n, i, b = 0, e = 0;
                        const carom_touch_event *ev;
                        tw_steps(&t, 1);
                        ev = carom_world_touch_events(t.w, &n);
                        for (i = 0; i < n; ++i) {
                            ck_assert_int_eq(ev[i].sensor, 1);
                            b += ev[i].begin;
                            e += !ev[i].begin;
                        }
                        begins += b;
                        ends += e;
                    }
                    ck_assert_msg(begins == !beside && ends == !beside,
                                  "%s, %g m/s, offset %d%s: %d begins, %d ends",
                                  carom_method_name(methods[m]), (double)speeds[v], o,
                                  beside ? ", beside" : "", begins, ends);
                    tw_free(&t);
                }
}
END_TEST

/*
 * Touches of sleeping bodies are kept, without events, while they hold.
 * Stack A of 4 boxes falls asleep; stack B of 4 is added far away and
 * falls asleep too; A is woken and sleeps again. Every box touches its
 * neighbours throughout, so after the first begins of each stack no touch
 * event may come at all. With max_pairs 8 (the 8 touches exactly), the
 * touches found in a step's pairs and the same touches carried over for
 * bodies that fell asleep filled the list twice over: a touch of the
 * sleeping stack was lost, ended and began again.
 */
START_TEST(test_touches_of_sleeping_stacks_hold_without_events)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int k, s, begins = 0, ends = 0;
    wd.max_bodies = 16;
    wd.max_pairs = 8;
    wd.max_contacts = 8;
    t = tw_make(&wd);
    bd.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&bd, 30.0f, 0.5f);
    bd.position.y = -0.5f;
    tw_add(&t, &bd);
    for (s = 0; s < 2; ++s) {
        bd = carom_default_body_def();
        carom_body_def_set_box(&bd, 0.5f, 0.5f);
        bd.position.x = s == 0 ? -10.0f : 10.0f;
        for (k = 0; k < 4; ++k) {
            bd.position.y = 0.5f + (float)k;
            tw_add(&t, &bd);
        }
        for (k = 0; k < 600 && carom_body_is_awake(t.w, 1 + 4 * s + 3); ++k) {
            int n, i;
            const carom_touch_event *e;
            tw_steps(&t, 1);
            e = carom_world_touch_events(t.w, &n);
            for (i = 0; i < n; ++i) {
                begins += e[i].begin;
                ends += !e[i].begin;
            }
        }
        ck_assert_msg(!carom_body_is_awake(t.w, 1 + 4 * s), "stack %d awake", s);
    }
    ck_assert_int_eq(begins, 8);
    {
        carom_vec2 zero = {0.0f, 0.0f};
        carom_body_state top = tw_state(&t, 4);
        ck_assert_int_eq(carom_body_apply_impulse(t.w, 4, zero, top.center), CAROM_OK);
    }
    for (k = 0; k < 600; ++k) {
        int n, i;
        const carom_touch_event *e;
        tw_steps(&t, 1);
        e = carom_world_touch_events(t.w, &n);
        for (i = 0; i < n; ++i) {
            begins += e[i].begin;
            ends += !e[i].begin;
        }
    }
    ck_assert_int_eq(begins, 8);
    ck_assert_int_eq(ends, 0);
    tw_free(&t);
}
END_TEST

/* The touch list holds max_pairs touches: the step's candidate pairs and
 * the touches of sleeping bodies, which are not candidate pairs. Three
 * stacks of 4 boxes under max_pairs 10: with two asleep (8 touches), the
 * third's 4 pairs make 12 touches. The step that would lose 2 of them
 * fails with CAROM_ERR_PAIR_CAPACITY and is undone; a world that may grow
 * takes a larger pool and steps on: 12 begins, no end. */
static void *touch_grow_alloc(void *user, size_t bytes)
{
    ++*(int *)user;
    return malloc(bytes);
}

static void touch_grow_release(void *user, void *block)
{
    (void)user;
    free(block);
}

static void three_stacks(int grow)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int k, s, grows = 0, begins = 0, ends = 0, failed = 0;
    wd.max_bodies = 16;
    wd.max_pairs = 10;
    wd.max_contacts = 10;
    if (grow) {
        wd.grow.alloc = touch_grow_alloc;
        wd.grow.release = touch_grow_release;
        wd.grow.user = &grows;
    }
    t = tw_make(&wd);
    bd.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&bd, 30.0f, 0.5f);
    bd.position.y = -0.5f;
    tw_add(&t, &bd);
    for (s = 0; s < 3 && !failed; ++s) {
        bd = carom_default_body_def();
        carom_body_def_set_box(&bd, 0.5f, 0.5f);
        bd.position.x = 10.0f * (float)(s - 1);
        for (k = 0; k < 4; ++k) {
            bd.position.y = 0.5f + (float)k;
            tw_add(&t, &bd);
        }
        for (k = 0; k < 600 && carom_body_is_awake(t.w, 1 + 4 * s + 3); ++k) {
            int n, i;
            const carom_touch_event *e;
            carom_stats before, after;
            carom_body_state b0 = tw_state(&t, 1 + 4 * s), b1;
            carom_status st;
            carom_world_get_stats(t.w, &before);
            st = carom_world_step(t.w);
            if (st != CAROM_OK) {
                /* refused and undone */
                ck_assert_int_eq(grow, 0);
                ck_assert_int_eq(s, 2);
                ck_assert_int_eq(st, CAROM_ERR_PAIR_CAPACITY);
                carom_world_get_stats(t.w, &after);
                ck_assert_int_eq(after.steps, before.steps);
                b1 = tw_state(&t, 1 + 4 * s);
                ck_assert(b1.center.y == b0.center.y && b1.velocity.y == b0.velocity.y);
                failed = 1;
                break;
            }
            e = carom_world_touch_events(t.w, &n);
            for (i = 0; i < n; ++i) {
                begins += e[i].begin;
                ends += !e[i].begin;
            }
        }
        if (!failed)
            ck_assert_msg(!carom_body_is_awake(t.w, 1 + 4 * s), "stack %d awake", s);
    }
    if (grow) {
        ck_assert_int_eq(begins, 12);
        ck_assert_int_gt(grows, 0);
    } else {
        ck_assert_int_eq(failed, 1);
        ck_assert_int_eq(begins, 8);
    }
    ck_assert_int_eq(ends, 0);
    (void)carom_world_release(t.w);
    tw_free(&t);
}

START_TEST(test_a_touch_list_too_small_fails_the_step_or_grows)
{
    three_stacks(0);
    three_stacks(1);
}
END_TEST

/* A box dropped on the ground: one begin-touch when it lands, none while it
 * rests (or sleeps), one end-touch when it is thrown up. The buffer holds
 * max_touch_events; the rest are counted as dropped. */
START_TEST(test_touch_events_begin_end_and_full_buffer)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int g, b, c, k, n, begins = 0, ends = 0;
    const carom_touch_event *e;
    wd.max_bodies = 3;
    wd.max_touch_events = 1;
    t = tw_make(&wd);
    g = add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.x = -2.0f;
    bd.position.y = 1.0f;
    b = tw_add(&t, &bd);
    bd.position.x = 2.0f;
    c = tw_add(&t, &bd);
    for (k = 0; k < 200; ++k) {
        tw_steps(&t, 1);
        e = carom_world_touch_events(t.w, &n);
        ck_assert_int_le(n, 1);
        if (n == 1) {
            ck_assert_int_eq(e[0].begin, 1);
            ck_assert_int_eq(e[0].body_a, g);
            ++begins;
            /* both land in the same step: one kept, one dropped */
            ck_assert_int_eq(carom_world_touch_events_dropped(t.w), 1);
        }
    }
    ck_assert_int_eq(begins, 1);
    ck_assert_int_eq(carom_body_set_velocity(t.w, b, (carom_vec2){0.0f, 5.0f}), CAROM_OK);
    for (k = 0; k < 10; ++k) {
        tw_steps(&t, 1);
        e = carom_world_touch_events(t.w, &n);
        if (n == 1 && !e[0].begin) {
            ck_assert_int_eq(e[0].body_b, b);
            ++ends;
        }
    }
    ck_assert_int_eq(ends, 1);
    (void)c;
    tw_free(&t);
}
END_TEST


/* A teleport or a new filter that leaves a touching pair touching begins
 * no second touch; a filter that ends the pair ends the touch (found by
 * the API fuzzer: both calls dropped the touch, which then began again). */
START_TEST(test_teleport_and_filter_keep_a_touch_that_holds)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state st;
    tw t;
    int g, b, k, n, begins = 0, ends = 0;
    const carom_touch_event *e;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    g = add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.y = 0.5f;
    b = tw_add(&t, &bd);
    for (k = 0; k < 4; ++k) {
        tw_steps(&t, 1);
        e = carom_world_touch_events(t.w, &n);
        begins += n;
    }
    ck_assert_int_eq(begins, 1);
    ck_assert_int_eq(carom_body_get_state(t.w, b, &st), CAROM_OK);
    for (k = 0; k < 3; ++k) {
        /* k 0: teleport in place; 1: the same filter again; 2: a 1 cm shift */
        if (k == 0)
            ck_assert_int_eq(carom_body_set_transform(t.w, b, st.position, st.rotation), CAROM_OK);
        else if (k == 1)
            ck_assert_int_eq(carom_body_set_filter(t.w, b, 1u, 0xffffffffu, 0), CAROM_OK);
        else
            ck_assert_int_eq(carom_body_set_transform(t.w, b,
                                                      (carom_vec2){st.position.x + 0.01f,
                                                                   st.position.y},
                                                      st.rotation),
                             CAROM_OK);
        tw_steps(&t, 1);
        e = carom_world_touch_events(t.w, &n);
        ck_assert_int_eq(n, 0);
    }
    /* a filter that no longer meets the ground: one end event */
    ck_assert_int_eq(carom_body_set_filter(t.w, b, 2u, 0xfffffffeu, 0), CAROM_OK);
    tw_steps(&t, 1);
    e = carom_world_touch_events(t.w, &n);
    ck_assert_int_eq(n, 1);
    ck_assert(e[0].begin == 0 && e[0].body_a == g && e[0].body_b == b);
    ++ends;
    ck_assert_int_eq(ends, 1);
    tw_free(&t);
}
END_TEST

/* ---- queries -------------------------------------------------------------------- */

typedef struct found_set {
    int ids[16];
    int n;
} found_set;

static int collect(void *ctx, int body)
{
    found_set *f = (found_set *)ctx;
    if (f->n < 16)
        f->ids[f->n++] = body;
    return 1;
}

static int has(const found_set *f, int id)
{
    int i;
    for (i = 0; i < f->n; ++i)
        if (f->ids[i] == id)
            return 1;
    return 0;
}

/* A circle, a rotated box and a triangle; the same answers before the
 * first step (every body scanned) and after it (through the grid). */
START_TEST(test_box_and_point_queries_are_exact)
{
    carom_world_def wd = zero_g(3);
    carom_body_def bd = carom_default_body_def();
    tw t = tw_make(&wd);
    int circle, box, tri, pass;
    circle = add_ball(&t, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    carom_body_def_set_box(&bd, 1.0f, 1.0f);
    bd.position.x = 5.0f;
    bd.rotation = carom_rot_from_angle(0.78539816f); /* a diamond */
    box = tw_add(&t, &bd);
    bd = carom_default_body_def();
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 3;
    bd.vertices[0] = (carom_vec2){0.0f, 0.0f};
    bd.vertices[1] = (carom_vec2){2.0f, 0.0f};
    bd.vertices[2] = (carom_vec2){0.0f, 2.0f};
    bd.position.x = 10.0f;
    tri = tw_add(&t, &bd);
    for (pass = 0; pass < 2; ++pass) {
        found_set f;
        /* the box [0.8, 1]^2 is inside the circle's bounding box but
         * outside the circle (its nearest corner is at 0.8 sqrt 2 > 1) */
        f.n = 0;
        carom_world_query_box(t.w, (carom_vec2){0.8f, 0.8f}, (carom_vec2){1.0f, 1.0f}, collect, &f);
        ck_assert_int_eq(f.n, 0);
        f.n = 0;
        carom_world_query_box(t.w, (carom_vec2){0.6f, 0.6f}, (carom_vec2){1.0f, 1.0f}, collect, &f);
        ck_assert(f.n == 1 && has(&f, circle));
        /* near the diamond's corner region, outside its edges */
        f.n = 0;
        carom_world_query_box(t.w, (carom_vec2){5.8f, 0.8f}, (carom_vec2){6.2f, 1.2f}, collect, &f);
        ck_assert_int_eq(f.n, 0);
        f.n = 0;
        carom_world_query_box(t.w, (carom_vec2){5.5f, 0.5f}, (carom_vec2){6.2f, 1.2f}, collect, &f);
        ck_assert(f.n == 1 && has(&f, box));
        /* across everything */
        f.n = 0;
        carom_world_query_box(t.w, (carom_vec2){-2.0f, -0.1f}, (carom_vec2){11.0f, 0.1f}, collect, &f);
        ck_assert(f.n == 3 && has(&f, circle) && has(&f, box) && has(&f, tri));
        /* points: inside the triangle, beyond its hypotenuse */
        f.n = 0;
        carom_world_query_point(t.w, (carom_vec2){10.9f, 0.9f}, collect, &f);
        ck_assert(f.n == 1 && has(&f, tri));
        f.n = 0;
        carom_world_query_point(t.w, (carom_vec2){11.1f, 1.0f}, collect, &f);
        ck_assert_int_eq(f.n, 0);
        f.n = 0;
        carom_world_query_point(t.w, (carom_vec2){0.7f, 0.7f}, collect, &f);
        ck_assert(f.n == 1 && has(&f, circle));
        tw_steps(&t, 1);
    }
    ck_assert_int_eq(carom_world_query_point(t.w, (carom_vec2){NAN, 0.0f}, collect, NULL),
                     CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_world_query_point(t.w, (carom_vec2){0.0f, 0.0f}, NULL, NULL),
                     CAROM_ERR_NULL);
    tw_free(&t);
}
END_TEST

/* Rays: the hit point, normal and fraction against a circle (closed form)
 * and a box face; all hits in order; a ray from inside a shape does not
 * hit it. */
START_TEST(test_raycasts_are_exact_and_ordered)
{
    carom_world_def wd = zero_g(3);
    carom_body_def bd = carom_default_body_def();
    tw t = tw_make(&wd);
    carom_ray_hit h, all[2];
    int found, n, circle, box;
    circle = add_ball(&t, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    carom_body_def_set_box(&bd, 0.5f, 2.0f);
    bd.position.x = 5.0f;
    box = tw_add(&t, &bd);
    add_ball(&t, 0.5f, 9.0f, 0.0f, 0.0f, 0.0f);
    /* from (-5, 0.5) along +x: enters the circle at x = -sqrt(1 - 0.25) */
    ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){-5.0f, 0.5f}, (carom_vec2){15.0f, 0.5f},
                                         &h, &found),
                     CAROM_OK);
    ck_assert_int_eq(found, 1);
    ck_assert_int_eq(h.body, circle);
    ck_assert_close(h.point.x, -sqrt(0.75), 1e-6);
    ck_assert_close(h.point.y, 0.5, 1e-6);
    ck_assert_close(h.normal.x, -sqrt(0.75), 1e-6);
    ck_assert_close(h.normal.y, 0.5, 1e-6);
    ck_assert_close(h.fraction, (5.0 - sqrt(0.75)) / 20.0, 1e-6);
    /* above the circle: the box's left face at x = 4.5 */
    carom_world_raycast(t.w, (carom_vec2){-5.0f, 1.5f}, (carom_vec2){15.0f, 1.5f}, &h, &found);
    ck_assert(found == 1 && h.body == box);
    ck_assert_close(h.point.x, 4.5, 1e-6);
    ck_assert_close(h.normal.x, -1.0, 1e-6);
    ck_assert_close(h.fraction, 9.5 / 20.0, 1e-6);
    /* every hit, nearest first, two stored of three */
    ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){-5.0f, 0.0f},
                                             (carom_vec2){15.0f, 0.0f}, all, 2, &n),
                     CAROM_OK);
    ck_assert_int_eq(n, 3);
    ck_assert(all[0].body == circle && all[1].body == box);
    ck_assert_close(all[0].fraction, 4.0 / 20.0, 1e-6);
    ck_assert_close(all[1].fraction, 9.5 / 20.0, 1e-6);
    /* from inside the circle: the box is the first hit */
    carom_world_raycast(t.w, (carom_vec2){0.0f, 0.0f}, (carom_vec2){15.0f, 0.0f}, &h, &found);
    ck_assert(found == 1 && h.body == box);
    /* nothing there */
    carom_world_raycast(t.w, (carom_vec2){-5.0f, 5.0f}, (carom_vec2){15.0f, 5.0f}, &h, &found);
    ck_assert_int_eq(found, 0);
    ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){0, 0}, (carom_vec2){1, 0}, all, -1, &n),
                     CAROM_ERR_BAD_CAPACITY);
    ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){0, 0}, (carom_vec2){INFINITY, 0}, &h, &found),
                     CAROM_ERR_NOT_FINITE);
    tw_free(&t);
}
END_TEST


static int stop_at_second(void *ctx, int body)
{
    int *calls = (int *)ctx;
    (void)body;
    return ++*calls < 2;
}

/*
 * Five circles of r = 0.5 at x = 8, 6, 4, 2, 0 (added far to near, so
 * bodies are met out of ray order) and a unit box at x = 12, a sixth
 * circle at x = 16 removed: before the first step (every slot scanned,
 * the removed one skipped) and after it (the grid). A query stops at the
 * callback's 0; rays report every hit nearest first whatever order they
 * are met in, and miss what they should: a zero-length ray, a segment
 * that ends short or points away, a line that passes a circle, rays past
 * a box's corner or over it, a ray from inside.
 */
START_TEST(test_queries_stop_and_rays_miss_where_they_should)
{
    carom_world_def wd = zero_g(7);
    carom_body_def bd = carom_default_body_def();
    tw t = tw_make(&wd);
    carom_ray_hit h, all[3];
    int i, pass, found, n, calls, gone;
    for (i = 4; i >= 0; --i)
        add_ball(&t, 0.5f, 2.0f * (float)i, 0.0f, 0.0f, 0.0f);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.x = 12.0f;
    tw_add(&t, &bd);
    gone = add_ball(&t, 0.5f, 16.0f, 0.0f, 0.0f, 0.0f);
    ck_assert_int_eq(carom_world_remove_body(t.w, gone), CAROM_OK);
    for (pass = 0; pass < 2; ++pass) {
        calls = 0;
        ck_assert_int_eq(carom_world_query_box(t.w, (carom_vec2){-1.0f, -1.0f},
                                               (carom_vec2){20.0f, 1.0f}, stop_at_second, &calls),
                         CAROM_OK);
        ck_assert_int_eq(calls, 2);
        ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){-5.0f, 0.0f},
                                                 (carom_vec2){20.0f, 0.0f}, all, 3, &n),
                         CAROM_OK);
        ck_assert_int_eq(n, 6);
        for (i = 0; i < 3; ++i) {
            ck_assert_int_eq(all[i].body, 4 - i); /* the circle at x = 2 i */
            ck_assert_close(all[i].fraction, (4.5 + 2.0 * i) / 25.0, 1e-6);
        }
        ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){-5.0f, 0.0f},
                                                 (carom_vec2){20.0f, 0.0f}, NULL, 0, &n),
                         CAROM_OK);
        ck_assert_int_eq(n, 6);
        {
            /* each within the bounding box of the circle at 0, or of the
             * box, so that the shape itself is tested */
            static const float rays[9][4] = {
                {0.45f, 0.45f, 0.45f, 0.45f}, /* no length, outside the circle */
                {-2.0f, -2.0f, -0.45f, -0.45f}, /* ends short of the circle */
                {-0.45f, 0.45f, -0.6f, 0.6f}, /* points away from it */
                {0.3f, 0.6f, 0.6f, 0.3f},     /* its line passes the circle at
                                                 0.9 / sqrt 2 > r */
                {-5.0f, 0.7f, 20.0f, 0.7f},   /* above everything */
                {11.0f, 0.2f, 12.0f, 1.2f},   /* past the box's corner */
                {12.0f, 0.0f, 12.2f, 0.0f},   /* from inside the box */
                {0.1f, 0.0f, 1.4f, 0.0f},     /* from inside a circle */
                {11.0f, 0.5f, 13.0f, 0.7f},   /* over the box, rising */
            };
            for (i = 0; i < 9; ++i) {
                ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){rays[i][0], rays[i][1]},
                                                     (carom_vec2){rays[i][2], rays[i][3]}, &h,
                                                     &found),
                                 CAROM_OK);
                ck_assert_msg(found == 0, "ray %d hit body %d", i, h.body);
            }
        }
        tw_steps(&t, 1);
    }
    ck_assert_int_eq(carom_world_query_box(NULL, (carom_vec2){0, 0}, (carom_vec2){1, 1},
                                           stop_at_second, &calls),
                     CAROM_ERR_NULL);
    ck_assert_int_eq(carom_world_query_box(t.w, (carom_vec2){0, 0}, (carom_vec2){1, 1}, NULL, NULL),
                     CAROM_ERR_NULL);
    ck_assert_int_eq(carom_world_query_box(t.w, (carom_vec2){NAN, 0}, (carom_vec2){1, 1},
                                           stop_at_second, &calls),
                     CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_world_raycast(NULL, (carom_vec2){0, 0}, (carom_vec2){1, 0}, &h, &found),
                     CAROM_ERR_NULL);
    ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){0, 0}, (carom_vec2){1, 0}, NULL, &found),
                     CAROM_ERR_NULL);
    ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){0, 0}, (carom_vec2){1, 0}, NULL, 2, &n),
                     CAROM_ERR_NULL);
    ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){0, 0}, (carom_vec2){1, 0}, all, 3, NULL),
                     CAROM_ERR_NULL);
    tw_free(&t);
}
END_TEST

/* A ray a thousand times longer than the circle it hits: the hit from the
 * closest approach, without the cancellation of b^2 - a c (found by the
 * API fuzzer: |normal| was 1.017 for a 1 km ray and a 0.5 m circle). The
 * reference is the same intersection in double precision. */
START_TEST(test_long_ray_hits_a_circle_exactly)
{
    carom_world_def wd = zero_g(1);
    tw t = tw_make(&wd);
    carom_ray_hit h;
    carom_vec2 p0 = {-1000.0f, -299.75f}, p1 = {1000.0f, 300.5f};
    double dx = (double)p1.x - p0.x, dy = (double)p1.y - p0.y;
    double a = dx * dx + dy * dy, fd = p0.x * dx + p0.y * dy;
    double c = (double)p0.x * p0.x + (double)p0.y * p0.y - 0.25;
    double tt = (-fd - sqrt(fd * fd - a * c)) / a;
    double hx = p0.x + tt * dx, hy = p0.y + tt * dy;
    int found;
    add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f);
    ck_assert_int_eq(carom_world_raycast(t.w, p0, p1, &h, &found), CAROM_OK);
    ck_assert_int_eq(found, 1);
    ck_assert_close(h.fraction, tt, 1e-6);
    ck_assert_close(h.normal.x * h.normal.x + h.normal.y * h.normal.y, 1.0, 1e-6);
    /* float endpoints of 1e3 m carry 6e-5 m: the direction to 3e-4 */
    ck_assert_close(h.normal.x, hx / 0.5, 3e-4);
    ck_assert_close(h.normal.y, hy / 0.5, 3e-4);
    tw_free(&t);
}
END_TEST

/* A ray shorter than sqrt(FLT_MIN) (|d|^2 subnormal) has no direction that
 * d / |d| gives to unit length: it counts as no ray, even from a point on
 * a circle's surface; a ray of 1e-6 m from there hits at once, with the
 * outward normal. */
START_TEST(test_ray_too_short_for_a_direction_finds_nothing)
{
    carom_world_def wd = zero_g(1);
    tw t = tw_make(&wd);
    carom_ray_hit h;
    carom_vec2 p0 = {0.0f, 0.0f}, tiny = {1e-20f, 0.0f}, short_ = {1e-6f, 0.0f};
    int found = 1;
    add_ball(&t, 0.5f, 0.5f, 0.0f, 0.0f, 0.0f); /* surface through p0 */
    ck_assert_int_eq(carom_world_raycast(t.w, p0, tiny, &h, &found), CAROM_OK);
    ck_assert_int_eq(found, 0);
    ck_assert_int_eq(carom_world_raycast(t.w, p0, short_, &h, &found), CAROM_OK);
    ck_assert_int_eq(found, 1);
    ck_assert_close(h.fraction, 0.0, 1e-6);
    ck_assert_close(h.normal.x, -1.0, 1e-6);
    ck_assert_close(h.normal.y, 0.0, 1e-6);
    tw_free(&t);
}
END_TEST

/* A ray's ends lie within CAROM_LIMIT_MAX_LENGTH, like every position
 * (found by the API fuzzer: a 1e19 m ray hit with a NaN fraction). */
START_TEST(test_ray_beyond_the_length_limit_is_refused)
{
    carom_world_def wd = zero_g(1);
    tw t = tw_make(&wd);
    carom_ray_hit h;
    int found = -1, n = -1;
    add_ball(&t, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f);
    ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){-1.0e19f, 0.0f},
                                         (carom_vec2){1.0e19f, 0.0f}, &h, &found),
                     CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_world_raycast_all(t.w, (carom_vec2){0.0f, -2.0f * CAROM_LIMIT_MAX_LENGTH},
                                             (carom_vec2){0.0f, 2.0f}, &h, 1, &n),
                     CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_world_raycast(t.w, (carom_vec2){-CAROM_LIMIT_MAX_LENGTH, 0.0f},
                                         (carom_vec2){CAROM_LIMIT_MAX_LENGTH, 0.0f}, &h, &found),
                     CAROM_OK);
    ck_assert_int_eq(found, 1);
    ck_assert_close(h.point.x, -0.5, 1e-6 * CAROM_LIMIT_MAX_LENGTH);
    ck_assert_close(h.normal.x, -1.0, 1e-6);
    tw_free(&t);
}
END_TEST

/* A ball overlapping a heavy triangle is pushed out in the first step
 * far beyond the box its own motion swept: queries and a sensor still see
 * it where it ended (found by the API fuzzer). Expected: the ball's centre
 * is inside it; it overlaps the sensor circle exactly when the centres are
 * closer than the sum of radii. */
START_TEST(test_queries_and_sensors_see_a_body_pushed_out_of_its_box)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def sd = carom_default_body_def(), td = carom_default_body_def();
    carom_vec2 tri[3] = {{87.758255f, 47.9425545f}, {-85.3986053f, 52.0295982f},
                         {-2.35964704f, -99.9721603f}};
    carom_body_state bs;
    tw t;
    int sensor, ball, k;
    wd.max_bodies = 3;
    wd.substeps = 4;
    wd.iterations = 1;
    wd.relax_iterations = 2;
    t = tw_make(&wd);
    sd.type = CAROM_BODY_STATIC;
    sd.is_sensor = 1;
    sd.radius = 1.0f;
    sd.position.x = 0.5f;
    sensor = tw_add(&t, &sd);
    td.shape = CAROM_SHAPE_POLYGON;
    td.vertex_count = 3;
    memcpy(td.vertices, tri, sizeof tri);
    td.position.x = -5.0f;
    td.position.y = 1.0f;
    tw_add(&t, &td);
    ball = add_ball(&t, 0.5f, -3.0f, 1.0f, 0.0f, 0.0f);
    for (k = 0; k < 3; ++k) {
        found_set f;
        int n, i, touching = 0, overlap;
        const carom_touch_event *e;
        double dx, dy;
        static int was_touching = 0;
        tw_steps(&t, 1);
        bs = tw_state(&t, ball);
        f.n = 0;
        ck_assert_int_eq(carom_world_query_point(t.w, bs.position, collect, &f), CAROM_OK);
        ck_assert(has(&f, ball));
        f.n = 0;
        ck_assert_int_eq(carom_world_query_box(t.w, (carom_vec2){bs.position.x - 0.1f, bs.position.y - 0.1f},
                                               (carom_vec2){bs.position.x + 0.1f, bs.position.y + 0.1f},
                                               collect, &f),
                         CAROM_OK);
        ck_assert(has(&f, ball));
        e = carom_world_touch_events(t.w, &n);
        touching = was_touching;
        for (i = 0; i < n; ++i)
            if (e[i].sensor && e[i].body_a == sensor && e[i].body_b == ball)
                touching = e[i].begin;
        dx = bs.position.x - 0.5;
        dy = bs.position.y;
        overlap = dx * dx + dy * dy < 1.5 * 1.5;
        ck_assert_int_eq(touching, overlap);
        was_touching = touching;
    }
    tw_free(&t);
}
END_TEST

/* NULL worlds and bad ids through every new call. */
START_TEST(test_new_calls_refuse_null_and_bad_ids)
{
    carom_world_def wd = zero_g(1);
    tw t = tw_make(&wd);
    carom_vec2 z = {0.0f, 0.0f};
    carom_body_type ty;
    int bad = 77;
    ck_assert_int_eq(carom_world_remove_body(NULL, 0), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_velocity(NULL, 0, z), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_transform(NULL, 0, z, carom_rot_from_angle(0)), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_type(t.w, 0, NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_type(t.w, bad, &ty), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_velocity(t.w, bad, z), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_angular_velocity(t.w, bad, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_apply_force(t.w, bad, z, z), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_apply_torque(t.w, bad, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_apply_angular_impulse(t.w, bad, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_restitution(t.w, bad, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_friction(t.w, bad, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_user_data(t.w, bad, NULL), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_set_filter(t.w, bad, 1u, 1u, 0), CAROM_ERR_BAD_BODY_ID);
    ck_assert(!carom_body_is_valid(NULL, 0));
    ck_assert_ptr_null(carom_world_touch_events(NULL, NULL));
    ck_assert_int_eq(carom_world_touch_events_dropped(NULL), 0);
    tw_free(&t);
}
END_TEST

/* Everything a world's bodies hold that the program can read: state bits,
 * mass, awake flag, user data. */
static int same_bodies(const carom_world *a, const carom_world *b)
{
    int i, n = carom_world_body_count(a);
    if (n != carom_world_body_count(b))
        return 0;
    for (i = 0; i < n; ++i) {
        carom_body_state sa, sb;
        float ma, mb, ia, ib;
        ck_assert_int_eq(carom_body_get_state(a, i, &sa), CAROM_OK);
        ck_assert_int_eq(carom_body_get_state(b, i, &sb), CAROM_OK);
        ck_assert_int_eq(carom_body_get_mass(a, i, &ma, &ia), CAROM_OK);
        ck_assert_int_eq(carom_body_get_mass(b, i, &mb, &ib), CAROM_OK);
        if (memcmp(&sa, &sb, sizeof sa) != 0 || ma != mb || ia != ib ||
            carom_body_is_awake(a, i) != carom_body_is_awake(b, i) ||
            carom_body_get_user_data(a, i) != carom_body_get_user_data(b, i))
            return 0;
    }
    return 1;
}

/* A box resting on the ground, a kinematic ball gliding past, a dynamic
 * ball in flight: bodies 0 ground, 1 box, 2 kinematic, 3 ball. */
static tw refusal_scene(void)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    wd.max_bodies = 4;
    t = tw_make(&wd);
    add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.y = 0.5f;
    tw_add(&t, &bd);
    bd = carom_default_body_def();
    bd.type = CAROM_BODY_KINEMATIC;
    bd.position.x = -5.0f;
    bd.position.y = 3.0f;
    bd.velocity.x = 1.0f;
    bd.angular_velocity = 0.5f;
    tw_add(&t, &bd);
    add_ball(&t, 0.25f, 3.0f, 4.0f, -1.0f, 2.0f);
    tw_steps(&t, 10);
    return t;
}

/*
 * Every body call given a bad argument returns its named status and
 * changes nothing: the world that took a hundred refused calls steps on
 * bit for bit like its twin that took none (bad input never leaves a
 * silently wrong state).
 */
START_TEST(test_refused_calls_change_nothing)
{
    tw t = refusal_scene(), twin = refusal_scene();
    carom_world *w = t.w;
    const float nan = (float)NAN, inf = (float)INFINITY, huge = 1.0e30f;
    const carom_vec2 z = {0.0f, 0.0f}, vnan = {nan, 0.0f}, vinf = {0.0f, inf};
    const carom_vec2 vhuge = {huge, 0.0f}, vmax = {3.0e38f, 3.0e38f};
    const carom_rot r0 = carom_rot_from_angle(0.0f), rnan = {nan, 0.0f};
    const int ground = 0, box = 1, kin = 2, ball = 3, bad = 77, stale = 1 << 20;
    carom_body_type ty;
    carom_body_state st;
    carom_vec2 v;
    float f;
    int i;

    /* no world */
    ck_assert_int_eq(carom_body_set_velocity(NULL, box, z), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_angular_velocity(NULL, box, 0.0f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_transform(NULL, box, z, r0), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_apply_impulse(NULL, box, z, z), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_apply_angular_impulse(NULL, box, 0.0f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_apply_force(NULL, box, z, z), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_apply_torque(NULL, box, 0.0f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_force(NULL, box, z, 0.0f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_restitution(NULL, box, 0.5f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_friction(NULL, box, 0.5f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_user_data(NULL, box, &t), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_set_filter(NULL, box, 1u, 1u, 0), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_type(NULL, box, &ty), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_velocity(NULL, box, &v, &f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_state(NULL, box, &st), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_get_mass(NULL, box, &f, &f), CAROM_ERR_NULL);
    /* a slot past max_bodies; slot 0 under a generation it never had */
    ck_assert_int_eq(carom_body_get_mass(w, bad, &f, &f), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_get_velocity(w, bad, &v, &f), CAROM_ERR_BAD_BODY_ID);
    ck_assert_int_eq(carom_body_get_mass(w, stale, &f, &f), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_set_velocity(w, stale, z), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_apply_impulse(w, stale, z, z), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_set_force(w, stale, z, 0.0f), CAROM_ERR_STALE_ID);
    ck_assert_ptr_null(carom_body_get_user_data(NULL, box));
    ck_assert(!carom_body_is_awake(NULL, box));

    /* a static body cannot be moved or pushed; a kinematic body cannot be
     * pushed (it moves only as the program sets it) */
    ck_assert_int_eq(carom_body_set_velocity(w, ground, z), CAROM_ERR_BAD_BODY_TYPE);
    ck_assert_int_eq(carom_body_set_angular_velocity(w, ground, 1.0f), CAROM_ERR_BAD_BODY_TYPE);
    for (i = 0; i < 2; ++i) {
        int id = i == 0 ? ground : kin;
        ck_assert_int_eq(carom_body_apply_impulse(w, id, z, z), CAROM_ERR_BAD_BODY_TYPE);
        ck_assert_int_eq(carom_body_apply_angular_impulse(w, id, 1.0f), CAROM_ERR_BAD_BODY_TYPE);
        ck_assert_int_eq(carom_body_apply_force(w, id, z, z), CAROM_ERR_BAD_BODY_TYPE);
        ck_assert_int_eq(carom_body_apply_torque(w, id, 1.0f), CAROM_ERR_BAD_BODY_TYPE);
        /* nor given a constant force (it was accepted, 1e30 N included) */
        ck_assert_int_eq(carom_body_set_force(w, id, vhuge, 0.0f), CAROM_ERR_BAD_BODY_TYPE);
        ck_assert_int_eq(carom_body_set_force(w, id, z, 0.0f), CAROM_ERR_BAD_BODY_TYPE);
    }

    /* NaN and infinity, in every argument that is a number */
    ck_assert_int_eq(carom_body_set_velocity(w, box, vnan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_velocity(w, kin, vinf), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_angular_velocity(w, box, nan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_transform(w, box, vnan, r0), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_transform(w, box, z, rnan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_impulse(w, ball, vnan, z), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_impulse(w, ball, z, vinf), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_angular_impulse(w, ball, inf), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_force(w, ball, vinf, z), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_force(w, ball, z, vnan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_apply_torque(w, ball, nan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_force(w, ball, vnan, 0.0f), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_force(w, ball, z, inf), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_restitution(w, ball, nan), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_set_friction(w, ball, nan), CAROM_ERR_NOT_FINITE);
    /* an impulse whose velocity change overflows float */
    ck_assert_int_eq(carom_body_apply_impulse(w, ball, vmax, z), CAROM_ERR_NOT_FINITE);

    /* finite, but past the limits of carom_config.h or of the physics */
    ck_assert_int_eq(carom_body_set_velocity(w, box, vhuge), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_set_angular_velocity(w, box, huge), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_set_transform(w, box, vhuge, r0), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_apply_impulse(w, ball, vhuge, z), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_apply_angular_impulse(w, ball, huge), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_apply_force(w, ball, vhuge, tw_state(&t, ball).center),
                     CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_apply_torque(w, ball, huge), CAROM_ERR_OUT_OF_RANGE);
    /* a point beyond the world, even on the force's line through the
     * centre (no torque: it was accepted by apply_force) */
    {
        carom_vec2 c = tw_state(&t, ball).center, far = c, up = {0.0f, 1.0f};
        far.y = huge;
        ck_assert_int_eq(carom_body_apply_force(w, ball, up, far), CAROM_ERR_OUT_OF_RANGE);
        ck_assert_int_eq(carom_body_apply_impulse(w, ball, up, far), CAROM_ERR_OUT_OF_RANGE);
    }
    ck_assert_int_eq(carom_body_set_force(w, ball, vhuge, 0.0f), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_set_force(w, ball, z, huge), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_set_restitution(w, ball, 1.5f), CAROM_ERR_BAD_RESTITUTION);
    ck_assert_int_eq(carom_body_set_restitution(w, ball, -0.1f), CAROM_ERR_BAD_RESTITUTION);
    ck_assert_int_eq(carom_body_set_friction(w, ball, -1.0f), CAROM_ERR_BAD_FRICTION);

    /* nothing changed: the same bodies now and after a second of motion */
    ck_assert(same_bodies(t.w, twin.w));
    tw_steps(&t, 60);
    tw_steps(&twin, 60);
    ck_assert(same_bodies(t.w, twin.w));
    tw_free(&t);
    tw_free(&twin);
}
END_TEST

/* Removing a sleeping body wakes what slept with it: the upper box of a
 * sleeping stack of two, its support removed, falls freely from rest
 * (y = y0 - g t^2 / 2). Removing a sensor ends its overlaps without an
 * event about the removed body, and the other body is not disturbed. */
START_TEST(test_removing_a_sleeping_body_or_a_sensor)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int boxes[2], sensor, i, k, n;
    wd.max_bodies = 4;
    t = tw_make(&wd);
    add_ground(&t);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    for (i = 0; i < 2; ++i) {
        bd.position.y = 0.5f + (float)i;
        boxes[i] = tw_add(&t, &bd);
    }
    bd = carom_default_body_def();
    bd.type = CAROM_BODY_STATIC;
    bd.is_sensor = 1;
    carom_body_def_set_box(&bd, 1.0f, 1.0f);
    bd.position.y = 1.0f;
    sensor = tw_add(&t, &bd);
    tw_steps(&t, 120);
    ck_assert(!carom_body_is_awake(t.w, boxes[0]) && !carom_body_is_awake(t.w, boxes[1]));
    ck_assert_int_eq(carom_world_remove_body(t.w, boxes[0]), CAROM_OK);
    ck_assert(carom_body_is_awake(t.w, boxes[1]));
    ck_assert_int_eq(carom_world_remove_body(t.w, sensor), CAROM_OK);
    ck_assert(!carom_body_is_valid(t.w, sensor));
    for (k = 1; k <= 15; ++k) {
        const carom_touch_event *e;
        double tt = k / 60.0;
        tw_steps(&t, 1);
        /* from y = 1.5 to the ground top (y = 0.5 at the centre) takes
         * sqrt(2 / 10) = 0.447 s: 15 steps are 0.25 s, all in flight */
        ck_assert_close(tw_state(&t, boxes[1]).position.y, 1.5 - 5.0 * tt * tt, 2e-3);
        e = carom_world_touch_events(t.w, &n);
        for (i = 0; i < n; ++i)
            ck_assert(e[i].body_a != sensor && e[i].body_b != sensor);
    }
    tw_free(&t);
}
END_TEST

/* Removing the body in the last slot in use, then adding one: the new body
 * takes the slot with a new generation, and the old id stays stale (found
 * by the API fuzzer: the freed end slot restarted its generation). */
START_TEST(test_id_of_the_last_slot_stays_stale_after_reuse)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state st;
    int a = -1, b = -1;
    tw t;
    wd.max_bodies = 4;
    t = tw_make(&wd);
    ck_assert_int_eq(carom_world_add_body(t.w, &bd, &a), CAROM_OK);
    ck_assert_int_eq(carom_world_remove_body(t.w, a), CAROM_OK);
    ck_assert_int_eq(carom_body_get_state(t.w, a, &st), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_get_state(t.w, 3, &st), CAROM_ERR_BAD_BODY_ID);
    bd.position.y = 7.0f;
    ck_assert_int_eq(carom_world_add_body(t.w, &bd, &b), CAROM_OK);
    ck_assert_int_ne(a, b);
    ck_assert_int_eq(carom_body_get_state(t.w, a, &st), CAROM_ERR_STALE_ID);
    ck_assert_int_eq(carom_body_get_state(t.w, b, &st), CAROM_OK);
    ck_assert_close(st.position.y, 7.0, 1e-7);
    tw_free(&t);
}
END_TEST

/* A rotation pair is normalized when its squared length is a normal
 * float, and refused otherwise (found by the API fuzzer: a pair of length
 * 1e-22 came back with c^2 + s^2 = 1.06). */
START_TEST(test_rotation_pairs_too_short_to_normalize_are_refused)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state st;
    carom_vec2 p = {0.0f, 0.0f};
    carom_rot tiny, small;
    int id = -1;
    tw t;
    wd.max_bodies = 2;
    t = tw_make(&wd);
    tiny.c = 7.28888e-37f;
    tiny.s = 1.09136e-22f;
    small.c = 3.0e-19f; /* c^2 + s^2 = 2.5e-37, a normal float */
    small.s = 4.0e-19f;
    bd.rotation = tiny;
    ck_assert_int_eq(carom_world_add_body(t.w, &bd, &id), CAROM_ERR_BAD_ROTATION);
    bd.rotation = small;
    ck_assert_int_eq(carom_world_add_body(t.w, &bd, &id), CAROM_OK);
    ck_assert_int_eq(carom_body_get_state(t.w, id, &st), CAROM_OK);
    ck_assert_close(st.rotation.c, 0.6, 1e-6);
    ck_assert_close(st.rotation.s, 0.8, 1e-6);
    ck_assert_int_eq(carom_body_set_transform(t.w, id, p, tiny), CAROM_ERR_BAD_ROTATION);
    tw_free(&t);
}
END_TEST

Suite *suite_api(void)
{
    Suite *s = suite_create("api");
    TCase *tb = tcase_create("body control");
    TCase *tk = tcase_create("kinematic");
    TCase *tr = tcase_create("removal");
    TCase *tf = tcase_create("filtering");
    TCase *te = tcase_create("touch");
    TCase *tq = tcase_create("queries");
    tcase_add_test(tb, test_velocity_setters_and_getters);
    tcase_add_test(tb, test_impulse_at_a_point_changes_velocity_exactly);
    tcase_add_test(tb, test_one_step_force_and_torque);
    tcase_add_test(tb, test_set_transform_teleports_and_forgets_contacts);
    tcase_add_test(tb, test_material_and_user_data_setters);
    tcase_add_test(tb, test_new_calls_refuse_null_and_bad_ids);
    tcase_add_test(tb, test_refused_calls_change_nothing);
    tcase_add_test(tk, test_kinematic_paddle_pushes_and_is_not_pushed);
    tcase_add_test(tk, test_kinematic_platform_lifts_a_box);
    tcase_add_test(tr, test_rotation_pairs_too_short_to_normalize_are_refused);
    tcase_add_test(tr, test_id_of_the_last_slot_stays_stale_after_reuse);
    tcase_add_test(tr, test_removal_frees_the_slot_and_refuses_stale_ids);
    tcase_add_test(tr, test_stale_id_stays_stale_when_the_generation_wraps);
    tcase_add_test(tr, test_removing_a_support_wakes_and_drops_what_it_held);
    tcase_add_test(tr, test_removal_mid_simulation_leaves_nothing_dangling);
    tcase_add_test(tr, test_removing_a_sleeping_body_or_a_sensor);
    tcase_add_test(tf, test_collision_filter_bits_and_groups);
    tcase_add_test(tf, test_filter_set_after_creation);
    tcase_add_test(te, test_sensor_reports_overlap_without_impulse);
    tcase_add_test(te, test_a_fast_body_crossing_a_sensor_is_reported);
    tcase_add_test(te, test_touch_events_begin_end_and_full_buffer);
    tcase_add_test(te, test_touches_of_sleeping_stacks_hold_without_events);
    tcase_add_test(te, test_a_touch_list_too_small_fails_the_step_or_grows);
    tcase_add_test(te, test_teleport_and_filter_keep_a_touch_that_holds);
    tcase_add_test(tq, test_box_and_point_queries_are_exact);
    tcase_add_test(tq, test_raycasts_are_exact_and_ordered);
    tcase_add_test(tq, test_queries_stop_and_rays_miss_where_they_should);
    tcase_add_test(tq, test_long_ray_hits_a_circle_exactly);
    tcase_add_test(tq, test_ray_beyond_the_length_limit_is_refused);
    tcase_add_test(tq, test_ray_too_short_for_a_direction_finds_nothing);
    tcase_add_test(tq, test_queries_and_sensors_see_a_body_pushed_out_of_its_box);
    suite_add_tcase(s, tb);
    suite_add_tcase(s, tk);
    suite_add_tcase(s, tr);
    suite_add_tcase(s, tf);
    suite_add_tcase(s, te);
    suite_add_tcase(s, tq);
    return s;
}
