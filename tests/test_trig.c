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

/* From 6000 to 1e5 rad the quadrants come off with pi/2 in four floats:
 * every float angle there gives sin and cos to float precision (3e-7)
 * against the double ones of the same float angle. (They were taken off
 * in whole turns, 2 pi a float: 7.6e-4 off at 1e4 rad and 6.6e-3 at 1e5;
 * found by a review, the header promised accuracy to about 1e5.) */
START_TEST(test_rot_from_angle_to_1e5_matches_sin_cos_to_float_precision)
{
    double worst = 0.0;
    int i;
    for (i = 0; i <= 20000; ++i) {
        /* 6000 to 1e5, spread over every exponent, both signs */
        float a = (float)(6000.0 * pow(1e5 / 6000.0, i / 20000.0)) * (i % 2 ? -1.0f : 1.0f);
        carom_rot r = carom_rot_from_angle(a);
        double ec = fabs(r.c - cos((double)a)), es = fabs(r.s - sin((double)a));
        worst = ec > worst ? ec : worst;
        worst = es > worst ? es : worst;
    }
    ck_assert_msg(worst < 3e-7, "worst error %g", worst);
}
END_TEST

/* Beyond 1e5 rad whole turns are taken off first: a - q 2pi, with 2pi a
 * float (1.75e-7 too large) and the product rounded (half an ulp of |a|);
 * the difference is exact. The rotation is that of the reduced angle. */
START_TEST(test_rot_from_large_angle_matches_sin_cos_within_its_rounding)
{
    static const float angles[] = {6000.5f, 12345.678f, -23456.5f, 1.0e5f, -3.0e5f};
    /* from 2^24 turns on the count itself rounds: only |q| = 1 is left */
    static const float huge[] = {9.87654e6f, -1.0e8f, 9.9e8f};
    size_t i;
    for (i = 0; i < sizeof huge / sizeof huge[0]; ++i) {
        carom_rot r = carom_rot_from_angle(huge[i]);
        ck_assert_msg(fabs(sqrt((double)r.c * r.c + (double)r.s * r.s) - 1.0) < 2.5e-7,
                      "|rot(%g)| is not 1", (double)huge[i]);
    }
    for (i = 0; i < sizeof angles / sizeof angles[0]; ++i) {
        float a = angles[i];
        carom_rot r = carom_rot_from_angle(a);
        /* the bound: the turn count times the float error of 2 pi (1.75e-7),
         * the rounding of that product and of the difference (2 ulp of |a|) */
        double turns = fabs((double)a) / (2.0 * PI);
        double tol = turns * 1.75e-7 + 2.0 * fabs((double)a) * ldexp(1.0, -24) + 5e-7;
        ck_assert_msg(fabs(r.c - cos((double)a)) <= tol, "cos(%g): %.9g, expected %.9g (tol %.3g)",
                      (double)a, (double)r.c, cos((double)a), tol);
        ck_assert_msg(fabs(r.s - sin((double)a)) <= tol, "sin(%g): %.9g, expected %.9g (tol %.3g)",
                      (double)a, (double)r.s, sin((double)a), tol);
        ck_assert_msg(fabs(sqrt((double)r.c * r.c + (double)r.s * r.s) - 1.0) < 2.5e-7,
                      "|rot(%g)| is not 1", (double)a);
    }
}
END_TEST

/* Above 1e9 rad a float angle is a multiple of 64 rad: its fractional turn
 * is noise, and the rotation is the identity (documented in trig.c). */
START_TEST(test_rot_from_angle_beyond_1e9_is_identity)
{
    carom_rot r = carom_rot_from_angle(2.0e9f);
    ck_assert(r.c == 1.0f && r.s == 0.0f);
    r = carom_rot_from_angle(-3.0e30f);
    ck_assert(r.c == 1.0f && r.s == 0.0f);
    r = carom_rot_from_angle(-INFINITY);
    ck_assert(r.c == 1.0f && r.s == 0.0f);
}
END_TEST

/* The zero "rotation" (not a unit vector) has no angle; 0 is returned. */
START_TEST(test_rot_angle_of_the_zero_vector_is_zero)
{
    carom_rot r;
    r.c = 0.0f;
    r.s = 0.0f;
    ck_assert(carom_rot_angle(r) == 0.0f);
    r.c = -0.0f;
    r.s = -0.0f;
    ck_assert(carom_rot_angle(r) == 0.0f);
}
END_TEST

/* The angle does not depend on the length of (c, s): atan2 is scale-free. */
START_TEST(test_rot_angle_ignores_the_length_of_the_vector)
{
    int i;
    for (i = 0; i < 16; ++i) {
        double t = -PI + (i + 0.5) * PI / 8.0;
        double k = i % 2 ? 1e-3 : 250.0;
        carom_rot r;
        r.c = (float)(k * cos(t));
        r.s = (float)(k * sin(t));
        ck_assert_msg(fabs((double)carom_rot_angle(r) - atan2(r.s, r.c)) < 5e-7,
                      "angle of %g (%g, %g)", t, (double)r.c, (double)r.s);
    }
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
    tcase_add_test(tc, test_rot_from_angle_to_1e5_matches_sin_cos_to_float_precision);
    tcase_add_test(tc, test_rot_from_large_angle_matches_sin_cos_within_its_rounding);
    tcase_add_test(tc, test_rot_from_angle_beyond_1e9_is_identity);
    tcase_add_test(tc, test_rot_angle_of_the_zero_vector_is_zero);
    tcase_add_test(tc, test_rot_angle_ignores_the_length_of_the_vector);
    suite_add_tcase(s, tc);
    return s;
}
