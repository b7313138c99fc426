/*
 * test_trig.c -- the library's own rotation trigonometry against libm's
 * double-precision sin, cos and atan2.
 */
#include "test_util.h"

#define PI 3.14159265358979323846

START_TEST(test_rot_from_angle_matches_sin_cos_to_float_precision)
{
    int i;
    for (i = -2000; i <= 2000; ++i) {
        float a = (float)i * 0.00731f;
        carom_rot r = carom_rot_from_angle(a);
        ck_assert_msg(fabs(r.c - cos((double)a)) < 2.5e-7, "cos(%g): %.9g", (double)a, (double)r.c);
        ck_assert_msg(fabs(r.s - sin((double)a)) < 2.5e-7, "sin(%g): %.9g", (double)a, (double)r.s);
    }
}
END_TEST

START_TEST(test_rot_from_angle_is_unit_length)
{
    int i;
    for (i = 0; i < 1000; ++i) {
        float a = -500.0f + (float)i * 1.013f;
        carom_rot r = carom_rot_from_angle(a);
        double len = sqrt((double)r.c * r.c + (double)r.s * r.s);
        ck_assert_msg(fabs(len - 1.0) < 2.5e-7, "|rot(%g)| = %.9g", (double)a, len);
    }
}
END_TEST

START_TEST(test_rot_angle_inverts_rot_from_angle_in_minus_pi_to_pi)
{
    int i;
    for (i = -3000; i <= 3000; ++i) {
        float a = (float)i * 0.001f;
        float b = carom_rot_angle(carom_rot_from_angle(a));
        ck_assert_msg(fabs((double)b - (double)a) < 1e-6, "angle(rot(%g)) = %.9g", (double)a, (double)b);
    }
}
END_TEST

START_TEST(test_rot_angle_matches_atan2_in_every_quadrant)
{
    int i;
    for (i = 0; i < 720; ++i) {
        double t = (i + 0.5) * PI / 360.0 - PI;
        carom_rot r;
        r.c = (float)cos(t);
        r.s = (float)sin(t);
        ck_assert_msg(fabs((double)carom_rot_angle(r) - atan2(r.s, r.c)) < 5e-7,
                      "angle at %g", t);
    }
}
END_TEST

START_TEST(test_rot_angle_on_the_axes_is_exact_multiple_of_half_pi)
{
    carom_rot r;
    r.c = 1.0f; r.s = 0.0f;
    ck_assert(carom_rot_angle(r) == 0.0f);
    r.c = 0.0f; r.s = 1.0f;
    ck_assert_close(carom_rot_angle(r), PI / 2.0, 1e-7);
    r.c = -1.0f; r.s = 0.0f;
    ck_assert_close(carom_rot_angle(r), PI, 1e-7);
    r.c = 0.0f; r.s = -1.0f;
    ck_assert_close(carom_rot_angle(r), -PI / 2.0, 1e-7);
}
END_TEST

START_TEST(test_rot_from_non_finite_angle_is_identity)
{
    carom_rot r = carom_rot_from_angle(NAN);
    ck_assert(r.c == 1.0f && r.s == 0.0f);
    r = carom_rot_from_angle(INFINITY);
    ck_assert(r.c == 1.0f && r.s == 0.0f);
}
END_TEST

Suite *suite_trig(void)
{
    Suite *s = suite_create("trig");
    TCase *tc = tcase_create("rotation");
    tcase_add_test(tc, test_rot_from_angle_matches_sin_cos_to_float_precision);
    tcase_add_test(tc, test_rot_from_angle_is_unit_length);
    tcase_add_test(tc, test_rot_angle_inverts_rot_from_angle_in_minus_pi_to_pi);
    tcase_add_test(tc, test_rot_angle_matches_atan2_in_every_quadrant);
    tcase_add_test(tc, test_rot_angle_on_the_axes_is_exact_multiple_of_half_pi);
    tcase_add_test(tc, test_rot_from_non_finite_angle_is_identity);
    suite_add_tcase(s, tc);
    return s;
}
