/*
 * test_shape.c -- mass properties against closed forms, and validation of
 * body definitions (every bad-input class returns its status).
 */
#include "test_util.h"

#define PI 3.14159265358979323846

static tw world0(void)
{
    carom_world_def wd = carom_default_world_def();
    wd.max_bodies = 8;
    wd.gravity.y = 0.0f;
    return tw_make(&wd);
}

START_TEST(test_circle_mass_is_density_pi_r2_and_inertia_m_r2_over_2)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    float m, I;
    int id;
    bd.radius = 0.5f;
    bd.density = 2.0f;
    id = tw_add(&t, &bd);
    carom_body_get_mass(t.w, id, &m, &I);
    ck_assert_close(m, 2.0 * PI * 0.25, 1e-6);
    ck_assert_close(I, 2.0 * PI * 0.25 * 0.25 / 2.0, 1e-6);
    tw_free(&t);
}
END_TEST

START_TEST(test_box_mass_and_inertia_m_w2_plus_h2_over_12)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    float m, I;
    int id;
    carom_body_def_set_box(&bd, 1.0f, 0.5f); /* 2 x 1 */
    bd.density = 3.0f;
    id = tw_add(&t, &bd);
    carom_body_get_mass(t.w, id, &m, &I);
    ck_assert_close(m, 6.0, 1e-6);
    ck_assert_close(I, 6.0 * (4.0 + 1.0) / 12.0, 1e-6);
    tw_free(&t);
}
END_TEST

START_TEST(test_right_triangle_inertia_about_centroid_m_a2_plus_b2_over_18)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    float m, I;
    int id;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 3;
    bd.vertices[0].x = 0; bd.vertices[0].y = 0;
    bd.vertices[1].x = 3; bd.vertices[1].y = 0;
    bd.vertices[2].x = 0; bd.vertices[2].y = 3;
    id = tw_add(&t, &bd);
    carom_body_get_mass(t.w, id, &m, &I);
    ck_assert_close(m, 4.5, 1e-6);
    ck_assert_close(I, 4.5 * (9.0 + 9.0) / 18.0, 1e-6);
    s = tw_state(&t, id);
    ck_assert_close(s.center.x, 1.0, 1e-6); /* centroid of the legs' triangle */
    ck_assert_close(s.center.y, 1.0, 1e-6);
    ck_assert_close(s.position.x, 0.0, 1e-6); /* origin stays where it was put */
    ck_assert_close(s.position.y, 0.0, 1e-6);
    tw_free(&t);
}
END_TEST

START_TEST(test_mass_overrides_density_and_scales_inertia)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    float m, I;
    int id;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 3;
    bd.vertices[0].x = 0; bd.vertices[0].y = 0;
    bd.vertices[1].x = 3; bd.vertices[1].y = 0;
    bd.vertices[2].x = 0; bd.vertices[2].y = 3;
    bd.mass = 2.0f;
    id = tw_add(&t, &bd);
    carom_body_get_mass(t.w, id, &m, &I);
    ck_assert_close(m, 2.0, 1e-6);
    ck_assert_close(I, 2.0 * 18.0 / 18.0, 1e-6);
    tw_free(&t);
}
END_TEST

START_TEST(test_rotated_polygon_reports_origin_and_centroid)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    carom_body_state s;
    int id;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 3;
    bd.vertices[0].x = -1; bd.vertices[0].y = 0;
    bd.vertices[1].x = 1; bd.vertices[1].y = 0;
    bd.vertices[2].x = 0; bd.vertices[2].y = 1;
    bd.position.x = 0; bd.position.y = 3;
    bd.rotation = carom_rot_from_angle(0.3f);
    id = tw_add(&t, &bd);
    s = tw_state(&t, id);
    ck_assert_close(s.position.x, 0.0, 1e-6);
    ck_assert_close(s.position.y, 3.0, 1e-6);
    /* centroid (0, 1/3) in the body frame, rotated by 0.3 rad */
    ck_assert_close(s.center.x, -sin(0.3) / 3.0, 1e-6);
    ck_assert_close(s.center.y, 3.0 + cos(0.3) / 3.0, 1e-6);
    tw_free(&t);
}
END_TEST

START_TEST(test_clockwise_polygon_is_reversed_not_rejected)
{
    carom_body_def bd = carom_default_body_def();
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 4;
    bd.vertices[0].x = -1; bd.vertices[0].y = -1;
    bd.vertices[1].x = -1; bd.vertices[1].y = 1;
    bd.vertices[2].x = 1; bd.vertices[2].y = 1;
    bd.vertices[3].x = 1; bd.vertices[3].y = -1;
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_OK);
}
END_TEST

static carom_status poly_status(const float *xy, int n)
{
    carom_body_def bd = carom_default_body_def();
    int i;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = n;
    for (i = 0; i < n && i < CAROM_MAX_POLYGON_VERTICES; ++i) {
        bd.vertices[i].x = xy[2 * i];
        bd.vertices[i].y = xy[2 * i + 1];
    }
    return carom_body_def_validate(&bd);
}

START_TEST(test_bad_polygons_get_their_status)
{
    static const float two[] = {0, 0, 1, 0};
    static const float nine[] = {0, 0, 1, 0, 2, 1, 2, 2, 1, 3, 0, 3, -1, 2, -1, 1, -0.5f, 0.2f};
    static const float collinear[] = {0, 0, 1, 0, 2, 0};
    static const float repeated[] = {0, 0, 1, 0, 1, 0, 0, 1};
    static const float bowtie[] = {0, 0, 1, 1, 1, 0, 0, 1};
    static const float arrow[] = {0, 0, 2, 0, 1, 0.5f, 2, 2, 0, 2};
    static const float star[] = {0, 1, 0.588f, -0.809f, -0.951f, 0.309f, 0.951f, 0.309f, -0.588f, -0.809f};
    static const float flat[] = {0, 0, 1, 0, 2, 1e-6f, 0, 1};
    static const float nan_v[] = {0, 0, 1, 0, NAN, 1};
    ck_assert_int_eq(poly_status(two, 2), CAROM_ERR_TOO_FEW_VERTICES);
    ck_assert_int_eq(poly_status(nine, 9), CAROM_ERR_TOO_MANY_VERTICES);
    ck_assert_int_eq(poly_status(collinear, 3), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(poly_status(repeated, 4), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(poly_status(bowtie, 4), CAROM_ERR_SELF_INTERSECTING);
    ck_assert_int_eq(poly_status(arrow, 5), CAROM_ERR_NOT_CONVEX);
    ck_assert_int_eq(poly_status(star, 5), CAROM_ERR_SELF_INTERSECTING);
    ck_assert_int_eq(poly_status(flat, 4), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(poly_status(nan_v, 3), CAROM_ERR_NOT_FINITE);
}
END_TEST

START_TEST(test_bad_body_fields_get_their_status)
{
    carom_body_def bd;
#define EXPECT(field_stmt, status)                                             \
    bd = carom_default_body_def();                                             \
    field_stmt;                                                                \
    ck_assert_int_eq(carom_body_def_validate(&bd), status)
    EXPECT(bd.radius = 0.0f, CAROM_ERR_BAD_RADIUS);
    EXPECT(bd.radius = -1.0f, CAROM_ERR_BAD_RADIUS);
    EXPECT(bd.density = 0.0f, CAROM_ERR_BAD_DENSITY);
    EXPECT(bd.density = -2.0f, CAROM_ERR_BAD_DENSITY);
    EXPECT(bd.mass = -1.0f, CAROM_ERR_BAD_MASS);
    EXPECT(bd.restitution = 1.5f, CAROM_ERR_BAD_RESTITUTION);
    EXPECT(bd.restitution = -0.1f, CAROM_ERR_BAD_RESTITUTION);
    EXPECT(bd.friction = -1.0f, CAROM_ERR_BAD_FRICTION);
    EXPECT(bd.position.x = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.velocity.y = INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.radius = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.mass = -INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.angular_velocity = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT((bd.rotation.c = 0.0f, bd.rotation.s = 0.0f), CAROM_ERR_BAD_ROTATION);
    EXPECT(bd.type = (carom_body_type)7, CAROM_ERR_BAD_BODY_TYPE);
    EXPECT(bd.shape = (carom_shape_type)9, CAROM_ERR_BAD_SHAPE);
    EXPECT((void)0, CAROM_OK);
#undef EXPECT
    ck_assert_int_eq(carom_body_def_validate(NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 0.0f, 1.0f), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(carom_body_def_set_box(&bd, NAN, 1.0f), CAROM_ERR_NOT_FINITE);
}
END_TEST

START_TEST(test_failed_add_leaves_world_unchanged)
{
    tw t = world0();
    carom_body_def bd = carom_default_body_def();
    int id = 42;
    tw_add(&t, &bd);
    bd.radius = -1.0f;
    ck_assert_int_eq(carom_world_add_body(t.w, &bd, &id), CAROM_ERR_BAD_RADIUS);
    ck_assert_int_eq(id, 42);
    ck_assert_int_eq(carom_world_body_count(t.w), 1);
    tw_free(&t);
}
END_TEST

Suite *suite_shape(void)
{
    Suite *s = suite_create("shape");
    TCase *tc = tcase_create("mass");
    TCase *tv = tcase_create("validation");
    tcase_add_test(tc, test_circle_mass_is_density_pi_r2_and_inertia_m_r2_over_2);
    tcase_add_test(tc, test_box_mass_and_inertia_m_w2_plus_h2_over_12);
    tcase_add_test(tc, test_right_triangle_inertia_about_centroid_m_a2_plus_b2_over_18);
    tcase_add_test(tc, test_mass_overrides_density_and_scales_inertia);
    tcase_add_test(tc, test_rotated_polygon_reports_origin_and_centroid);
    tcase_add_test(tv, test_clockwise_polygon_is_reversed_not_rejected);
    tcase_add_test(tv, test_bad_polygons_get_their_status);
    tcase_add_test(tv, test_bad_body_fields_get_their_status);
    tcase_add_test(tv, test_failed_add_leaves_world_unchanged);
    suite_add_tcase(s, tc);
    suite_add_tcase(s, tv);
    return s;
}
