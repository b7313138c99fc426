/*
 * test_narrowphase.c -- manifolds of each shape pair against geometry
 * worked out by hand: normal (from body a to body b), separation, points.
 */
#include "test_util.h"

#include "internal.h"

static cr_body make_circle(float x, float y, float r)
{
    carom_body_def bd = carom_default_body_def();
    cr_body b;
    bd.radius = r;
    bd.position.x = x;
    bd.position.y = y;
    ck_assert_int_eq(cr_body_build(&bd, &b), CAROM_OK);
    return b;
}

static cr_body make_box(float x, float y, float hx, float hy, float angle)
{
    carom_body_def bd = carom_default_body_def();
    cr_body b;
    carom_body_def_set_box(&bd, hx, hy);
    bd.position.x = x;
    bd.position.y = y;
    bd.rotation = carom_rot_from_angle(angle);
    ck_assert_int_eq(cr_body_build(&bd, &b), CAROM_OK);
    return b;
}

START_TEST(test_circle_circle_overlap_normal_and_midpoint)
{
    cr_body a = make_circle(0, 0, 1), b = make_circle(3, 4, 4.5f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&a, &b, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 1);
    ck_assert_close(m.n.x, 0.6, 1e-6);
    ck_assert_close(m.n.y, 0.8, 1e-6);
    ck_assert_close(m.pts[0].sep, 5.0 - 5.5, 1e-6);
    /* surfaces at 1 * n and (5 - 4.5) * n: midpoint at 0.75 n */
    ck_assert_close(m.pts[0].p.x, 0.75 * 0.6, 1e-6);
    ck_assert_close(m.pts[0].p.y, 0.75 * 0.8, 1e-6);
}
END_TEST

START_TEST(test_circle_circle_apart_beyond_margin_is_no_contact)
{
    cr_body a = make_circle(0, 0, 1), b = make_circle(2.1f, 0, 1);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&a, &b, 0.05f, &m), 0);
    ck_assert_int_eq(cr_collide(&a, &b, 0.2f, &m), 1);
    ck_assert_close(m.pts[0].sep, 0.1, 1e-6);
}
END_TEST

START_TEST(test_box_circle_face_region)
{
    cr_body box = make_box(0, 0, 1, 1, 0), c = make_circle(0.3f, 1.4f, 0.5f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 0.0, 1e-6);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.1, 1e-6);
    ck_assert_close(m.pts[0].p.x, 0.3, 1e-6);
    ck_assert_close(m.pts[0].p.y, 0.95, 1e-6);
}
END_TEST

START_TEST(test_box_circle_vertex_region)
{
    /* corner (1, 1); centre at (1.3, 1.4): distance 0.5 along (0.6, 0.8) */
    cr_body box = make_box(0, 0, 1, 1, 0), c = make_circle(1.3f, 1.4f, 0.45f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&box, &c, 0.0f, &m), 0); /* gap 0.05 */
    c = make_circle(1.3f, 1.4f, 0.55f);
    ck_assert_int_eq(cr_collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 0.6, 1e-6);
    ck_assert_close(m.n.y, 0.8, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.05, 1e-6);
}
END_TEST

START_TEST(test_circle_box_order_reverses_the_normal)
{
    cr_body box = make_box(0, 0, 1, 1, 0), c = make_circle(0.3f, 1.4f, 0.5f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&c, &box, 0.0f, &m), 1);
    ck_assert_close(m.n.y, -1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.1, 1e-6);
}
END_TEST

START_TEST(test_circle_centre_inside_box_pushes_out_of_nearest_face)
{
    cr_body box = make_box(0, 0, 2, 1, 0), c = make_circle(1.8f, 0.1f, 0.1f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.2 - 0.1, 1e-6);
}
END_TEST

START_TEST(test_box_on_box_gives_two_points_on_the_face)
{
    cr_body ground = make_box(0, 0, 2, 0.5f, 0), top = make_box(0.3f, 0.9f, 0.5f, 0.5f, 0);
    cr_manifold m;
    int i;
    ck_assert_int_eq(cr_collide(&ground, &top, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 2);
    ck_assert_close(m.n.x, 0.0, 1e-6);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    for (i = 0; i < 2; ++i) {
        ck_assert_close(m.pts[i].sep, -0.1, 1e-6);
        ck_assert_close(m.pts[i].p.y, 0.45, 1e-6);
        ck_assert_close(fabs(m.pts[i].p.x - 0.3), 0.5, 1e-6);
    }
    ck_assert_uint_ne(m.pts[0].id, m.pts[1].id);
}
END_TEST

START_TEST(test_tilted_box_corner_gives_one_point)
{
    /* square of half side 0.5 at 45 deg: corner 0.7071 below its centre */
    cr_body ground = make_box(0, 0, 2, 0.5f, 0);
    cr_body top = make_box(0, 0.5f + 0.70710678f - 0.02f, 0.5f, 0.5f, 0.78539816f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&ground, &top, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 1);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.02, 1e-5);
    ck_assert_close(m.pts[0].p.x, 0.0, 1e-5);
}
END_TEST

START_TEST(test_separated_polygons_are_no_contact)
{
    cr_body a = make_box(0, 0, 1, 1, 0), b = make_box(2.5f, 0, 1, 1, 0.3f);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&a, &b, 0.0f, &m), 0);
}
END_TEST

START_TEST(test_box_box_side_by_side_normal_points_from_a_to_b)
{
    cr_body a = make_box(0, 0, 1, 1, 0), b = make_box(1.95f, 0.2f, 1, 1, 0);
    cr_manifold m;
    ck_assert_int_eq(cr_collide(&a, &b, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 1.0, 1e-6);
    ck_assert_int_eq(m.count, 2);
    ck_assert_close(m.pts[0].sep, -0.05, 1e-5);
    ck_assert_int_eq(cr_collide(&b, &a, 0.0f, &m), 1);
    ck_assert_close(m.n.x, -1.0, 1e-6);
}
END_TEST

Suite *suite_narrowphase(void)
{
    Suite *s = suite_create("narrowphase");
    TCase *tc = tcase_create("manifolds");
    tcase_add_test(tc, test_circle_circle_overlap_normal_and_midpoint);
    tcase_add_test(tc, test_circle_circle_apart_beyond_margin_is_no_contact);
    tcase_add_test(tc, test_box_circle_face_region);
    tcase_add_test(tc, test_box_circle_vertex_region);
    tcase_add_test(tc, test_circle_box_order_reverses_the_normal);
    tcase_add_test(tc, test_circle_centre_inside_box_pushes_out_of_nearest_face);
    tcase_add_test(tc, test_box_on_box_gives_two_points_on_the_face);
    tcase_add_test(tc, test_tilted_box_corner_gives_one_point);
    tcase_add_test(tc, test_separated_polygons_are_no_contact);
    tcase_add_test(tc, test_box_box_side_by_side_normal_points_from_a_to_b);
    suite_add_tcase(s, tc);
    return s;
}
