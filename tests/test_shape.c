/*
 * test_shape.c -- mass properties against closed forms, and validation of
 * body definitions (every bad-input class returns its status).
 */
#include "test_util.h"

#include "body.h"

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
    /* a mass given overrides the density, which is not read then */
    EXPECT((bd.density = 0.0f, bd.mass = 2.0f), CAROM_OK);
    EXPECT(bd.mass = -1.0f, CAROM_ERR_BAD_MASS);
    EXPECT(bd.restitution = 1.5f, CAROM_ERR_BAD_RESTITUTION);
    EXPECT(bd.restitution = -0.1f, CAROM_ERR_BAD_RESTITUTION);
    EXPECT(bd.friction = -1.0f, CAROM_ERR_BAD_FRICTION);
    EXPECT(bd.friction = 2.0e6f, CAROM_ERR_BAD_FRICTION);
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
    /* thinner than a body may be: refused here, as carom_world_add_body would */
    ck_assert_int_eq(carom_body_def_set_box(&bd, 1.0f, 0.5f * CAROM_LIMIT_MIN_SIZE),
                     CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(carom_body_def_set_box(&bd, CAROM_LIMIT_MIN_SIZE, 1.0f), CAROM_OK);
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_OK);
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

/* A hexagon that turns left at every vertex but winds twice round its
 * centre, its edges meeting only where vertex (-2, -1) lies on the edge
 * from (-2, 1) to (-2, -2), so that no two edges cross strictly: a vertex
 * lies outside an edge, and the polygon is not convex. */
START_TEST(test_polygon_winding_twice_without_crossing_edges_is_not_convex)
{
    static const float twice[] = {-2, -2, 0, 0, -2, -1, -3, -3, 3, 2, -2, 1};
    double turning = 0.0;
    int i;
    /* its total turning is 4 pi (independently of carom) */
    for (i = 0; i < 6; ++i) {
        int j = (i + 1) % 6, k = (i + 2) % 6;
        double e1x = twice[2 * j] - twice[2 * i], e1y = twice[2 * j + 1] - twice[2 * i + 1];
        double e2x = twice[2 * k] - twice[2 * j], e2y = twice[2 * k + 1] - twice[2 * j + 1];
        turning += atan2(e1x * e2y - e1y * e2x, e1x * e2x + e1y * e2y);
    }
    ck_assert_close(turning, 4.0 * PI, 1e-12);
    ck_assert_int_eq(poly_status(twice, 6), CAROM_ERR_NOT_CONVEX);
}
END_TEST

START_TEST(test_polygons_beyond_the_length_limit_or_below_the_size_limit_are_refused)
{
    /* a vertex farther than CAROM_LIMIT_MAX_LENGTH from the body origin */
    const float far[] = {0, 0, 2.0f * CAROM_LIMIT_MAX_LENGTH, 0, 0, 1};
    /* a triangle 1e-20 m across: far thinner than CAROM_LIMIT_MIN_SIZE (its
     * area and second moment are below float's range) */
    static const float tiny[] = {0, 0, 1e-20f, 0, 0, 1e-20f};
    /* 1e-7 m across: representable, still thinner than the limit */
    static const float small[] = {0, 0, 1e-7f, 0, 0, 1e-7f};
    ck_assert_int_eq(poly_status(far, 3), CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(poly_status(tiny, 3), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(poly_status(small, 3), CAROM_ERR_DEGENERATE_POLYGON);
}
END_TEST

START_TEST(test_set_box_checks_its_half_extents_and_writes_four_corners)
{
    carom_body_def bd = carom_default_body_def();
    ck_assert_int_eq(carom_body_def_set_box(NULL, 1.0f, 1.0f), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 1.0f, INFINITY), CAROM_ERR_NOT_FINITE);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 1.0f, -2.0f), CAROM_ERR_DEGENERATE_POLYGON);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 2.0f * CAROM_LIMIT_MAX_LENGTH, 1.0f),
                     CAROM_ERR_OUT_OF_RANGE);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 1.0f, 2.0f * CAROM_LIMIT_MAX_LENGTH),
                     CAROM_ERR_OUT_OF_RANGE);
    /* a refused box leaves the definition a circle */
    ck_assert_int_eq(bd.shape, CAROM_SHAPE_CIRCLE);
    ck_assert_int_eq(carom_body_def_set_box(&bd, 1.5f, 0.25f), CAROM_OK);
    ck_assert_int_eq(bd.shape, CAROM_SHAPE_POLYGON);
    ck_assert_int_eq(bd.vertex_count, 4);
    ck_assert(bd.vertices[0].x == -1.5f && bd.vertices[0].y == -0.25f);
    ck_assert(bd.vertices[1].x == 1.5f && bd.vertices[1].y == -0.25f);
    ck_assert(bd.vertices[2].x == 1.5f && bd.vertices[2].y == 0.25f);
    ck_assert(bd.vertices[3].x == -1.5f && bd.vertices[3].y == 0.25f);
}
END_TEST

/* Every float field is checked for NaN and infinity, and values beyond the
 * documented limits (carom_config.h CAROM_LIMIT_*) are refused. */
START_TEST(test_every_field_out_of_its_range_gets_its_status)
{
    carom_body_def bd;
#define EXPECT(field_stmt, status)                                             \
    bd = carom_default_body_def();                                             \
    field_stmt;                                                                \
    ck_assert_msg(carom_body_def_validate(&bd) == (status), "%s: %s, expected %s", \
                  #field_stmt, carom_status_string(carom_body_def_validate(&bd)), \
                  carom_status_string(status))
    EXPECT(bd.rotation.s = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.rotation.c = -INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.density = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.restitution = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.friction = INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.force.x = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.force.y = -INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.torque = INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(bd.position.y = -INFINITY, CAROM_ERR_NOT_FINITE);
    /* |(c, s)|^2 overflows: no direction can be read from it */
    EXPECT((bd.rotation.c = 1e30f, bd.rotation.s = 1e30f), CAROM_ERR_BAD_ROTATION);
    EXPECT(bd.position.x = 2.0f * CAROM_LIMIT_MAX_LENGTH, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(bd.position.y = -2.0f * CAROM_LIMIT_MAX_LENGTH, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(bd.radius = 2.0f * CAROM_LIMIT_MAX_LENGTH, CAROM_ERR_BAD_RADIUS);
    EXPECT(bd.radius = 0.5f * CAROM_LIMIT_MIN_SIZE, CAROM_ERR_BAD_RADIUS);
    /* a = F / m beyond CAROM_LIMIT_MAX_ACCEL, on either axis (m = 1 kg) */
    EXPECT((bd.mass = 1.0f, bd.force.y = 2.0f * CAROM_LIMIT_MAX_ACCEL), CAROM_ERR_OUT_OF_RANGE);
    EXPECT((bd.mass = 1.0f, bd.force.x = -2.0f * CAROM_LIMIT_MAX_ACCEL), CAROM_ERR_OUT_OF_RANGE);
    /* the rim's acceleration alpha r = T r / I beyond the limit: for a disc
     * of radius 0.5 and mass 1, I = 1/8, so T r / I = 4 T */
    EXPECT((bd.mass = 1.0f, bd.torque = 0.5f * CAROM_LIMIT_MAX_ACCEL), CAROM_ERR_OUT_OF_RANGE);
    EXPECT((bd.mass = 1.0f, bd.torque = 0.2f * CAROM_LIMIT_MAX_ACCEL), CAROM_OK);
    EXPECT((bd.mass = 1.0f, bd.force.y = 0.5f * CAROM_LIMIT_MAX_ACCEL), CAROM_OK);
    /* a static body takes no force: nothing to check */
    EXPECT((bd.type = CAROM_BODY_STATIC, bd.force.y = 1e30f), CAROM_OK);
    /* a kinematic body: any velocity within the limit */
    EXPECT((bd.type = CAROM_BODY_KINEMATIC, bd.velocity.x = 3.0f, bd.angular_velocity = 1.0f),
           CAROM_OK);
    EXPECT((bd.type = CAROM_BODY_KINEMATIC, bd.velocity.x = 2.0f * CAROM_LIMIT_MAX_SPEED),
           CAROM_ERR_OUT_OF_RANGE);
#undef EXPECT
}
END_TEST

/* The origin may be in range while the centre of mass is not: a polygon
 * whose vertices sit 6e7 m from its origin, put at x = 9e7 m. */
START_TEST(test_centre_of_mass_beyond_the_length_limit_is_refused)
{
    carom_body_def bd = carom_default_body_def();
    double cx;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 3;
    bd.vertices[0].x = 5.0e7f; bd.vertices[0].y = 0.0f;
    bd.vertices[1].x = 7.0e7f; bd.vertices[1].y = 0.0f;
    bd.vertices[2].x = 6.0e7f; bd.vertices[2].y = 1.0e7f;
    bd.mass = 1.0f; /* keeps the inertia within CAROM_LIMIT_MAX_MASS */
    bd.position.x = 9.0e7f;
    cx = 9.0e7 + (5.0e7 + 7.0e7 + 6.0e7) / 3.0; /* the centroid of a triangle */
    ck_assert(cx > (double)CAROM_LIMIT_MAX_LENGTH);
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_ERR_OUT_OF_RANGE);
    bd.position.x = -9.0e7f; /* centre at -3e7 m: fine */
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_OK);
}
END_TEST

/* The internal builder refuses missing outputs as the API refuses a
 * missing definition. */
START_TEST(test_body_build_needs_every_pointer)
{
    carom_body_def bd = carom_default_body_def();
    cr_body hot;
    cr_body_info info;
    ck_assert_int_eq(cr_body_build(NULL, &hot, &info), CAROM_ERR_NULL);
    ck_assert_int_eq(cr_body_build(&bd, NULL, &info), CAROM_ERR_NULL);
    ck_assert_int_eq(cr_body_build(&bd, &hot, NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(cr_body_build(&bd, &hot, &info), CAROM_OK);
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
    tcase_add_test(tv, test_polygon_winding_twice_without_crossing_edges_is_not_convex);
    tcase_add_test(tv, test_polygons_beyond_the_length_limit_or_below_the_size_limit_are_refused);
    tcase_add_test(tv, test_set_box_checks_its_half_extents_and_writes_four_corners);
    tcase_add_test(tv, test_every_field_out_of_its_range_gets_its_status);
    tcase_add_test(tv, test_centre_of_mass_beyond_the_length_limit_is_refused);
    tcase_add_test(tv, test_body_build_needs_every_pointer);
    suite_add_tcase(s, tc);
    suite_add_tcase(s, tv);
    return s;
}
