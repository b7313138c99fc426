/*
 * test_broadphase.c -- sort and sweep finds exactly the pairs that the
 * all-pairs bounding-box test finds, in (a, b) order.
 */
#include "test_util.h"

#include "internal.h"

static unsigned lcg(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float uniform(unsigned *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)(lcg(s) & 0xffff) / 65535.0f;
}

START_TEST(test_sort_and_sweep_equals_all_pairs)
{
    carom_world_def wd = carom_default_world_def();
    tw t;
    unsigned seed = 12345u;
    int i, a, b, k = 0, expected = 0, n = 300;
    wd.max_bodies = n;
    wd.max_pairs = 20000;
    t = tw_make(&wd);
    for (i = 0; i < n; ++i) {
        carom_body_def bd = carom_default_body_def();
        if (i % 3 == 0) {
            carom_body_def_set_box(&bd, uniform(&seed, 0.1f, 1.0f), uniform(&seed, 0.1f, 1.0f));
            bd.rotation = carom_rot_from_angle(uniform(&seed, -3.0f, 3.0f));
        } else {
            bd.radius = uniform(&seed, 0.05f, 0.8f);
        }
        if (i % 17 == 0)
            bd.type = CAROM_BODY_STATIC;
        bd.position.x = uniform(&seed, -10.0f, 10.0f);
        bd.position.y = uniform(&seed, -10.0f, 10.0f);
        tw_add(&t, &bd);
    }
    cr_broadphase(t.w, 0.01f);
    ck_assert_int_eq(t.w->pairs_dropped, 0);
    for (a = 0; a < n; ++a) {
        for (b = a + 1; b < n; ++b) {
            cr_proxy pa, pb;
            int overlap;
            cr_body_bounds(&t.w->bodies[a], 0.01f, &pa);
            cr_body_bounds(&t.w->bodies[b], 0.01f, &pb);
            overlap = pa.lo_x <= pb.hi_x && pb.lo_x <= pa.hi_x &&
                      pa.lo_y <= pb.hi_y && pb.lo_y <= pa.hi_y &&
                      !(t.w->bodies[a].type == CAROM_BODY_STATIC &&
                        t.w->bodies[b].type == CAROM_BODY_STATIC);
            if (!overlap)
                continue;
            ++expected;
            ck_assert_msg(k < t.w->pair_count, "missing pair (%d, %d)", a, b);
            ck_assert_msg(t.w->pairs[k].a == a && t.w->pairs[k].b == b,
                          "pair %d is (%d, %d), expected (%d, %d)", k,
                          t.w->pairs[k].a, t.w->pairs[k].b, a, b);
            ++k;
        }
    }
    ck_assert_int_eq(t.w->pair_count, expected);
    ck_assert_int_gt(expected, 50); /* the scene really has overlaps */
    tw_free(&t);
}
END_TEST

START_TEST(test_pair_capacity_overflow_is_counted_not_written)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    int i;
    wd.max_bodies = 4;
    wd.max_pairs = 2;
    t = tw_make(&wd);
    for (i = 0; i < 4; ++i) {
        bd.position.x = 0.1f * (float)i; /* all overlap: 6 pairs */
        tw_add(&t, &bd);
    }
    ck_assert_int_eq(cr_broadphase(t.w, 0.0f), 6);
    ck_assert_int_eq(t.w->pair_count, 2);
    ck_assert_int_eq(t.w->pairs_dropped, 4);
    tw_free(&t);
}
END_TEST

Suite *suite_broadphase(void)
{
    Suite *s = suite_create("broadphase");
    TCase *tc = tcase_create("sweep");
    tcase_add_test(tc, test_sort_and_sweep_equals_all_pairs);
    tcase_add_test(tc, test_pair_capacity_overflow_is_counted_not_written);
    suite_add_tcase(s, tc);
    return s;
}
