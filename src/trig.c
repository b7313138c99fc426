/*
 * trig.c -- carom's own rotation trigonometry, from + - * / and sqrt only.
 *
 * libm's sinf/cosf/atan2f differ between C libraries and CPUs; these do
 * not: with IEEE single precision, round-to-nearest and no contraction,
 * every platform computes the same bits.
 */
#include "internal.h"

/* pi/2 split in two floats (Cody-Waite): HI holds the leading 24 bits, LO
 * the rest, so x - k*HI is exact for moderate k. */
#define CR_PIO2_HI 1.57079637050628662109375f
#define CR_PIO2_LO (-4.37113900018624283e-8f)
#define CR_TWO_OVER_PI 0.636619772367581343f
#define CR_PI 3.14159265358979323846f
#define CR_PIO4 0.785398163397448309616f

/* Beyond this the quadrant count no longer fits comfortably and the float
 * angle has no fractional bits left anyway. */
#define CR_TRIG_MAX_ARG 1.0e7f

carom_rot carom_rot_from_angle(float angle)
{
    float k, r, r2, s, c, tmp;
    long quadrant;

    if (!cr_finite(angle) || cr_gt(cr_abs(angle), CR_TRIG_MAX_ARG))
        return cr_rot_identity();
    /* nearest multiple of pi/2 */
    k = cr_mul(angle, CR_TWO_OVER_PI);
    quadrant = (long)(cr_ge(k, 0.0f) ? cr_add(k, 0.5f) : cr_sub(k, 0.5f));
    k = (float)quadrant;
    r = cr_sub(cr_sub(angle, cr_mul(k, CR_PIO2_HI)), cr_mul(k, CR_PIO2_LO));

    /* |r| <= pi/4: Taylor series in Horner form; the first omitted terms
     * are below 2e-9, under half an ulp of the results. */
    r2 = cr_mul(r, r);
    s = cr_mul(r2, 1.0f / 362880.0f);
    s = cr_mul(r2, cr_add(-1.0f / 5040.0f, s));
    s = cr_mul(r2, cr_add(1.0f / 120.0f, s));
    s = cr_mul(r2, cr_add(-1.0f / 6.0f, s));
    s = cr_add(r, cr_mul(r, s));
    c = cr_mul(r2, -1.0f / 3628800.0f);
    c = cr_mul(r2, cr_add(1.0f / 40320.0f, c));
    c = cr_mul(r2, cr_add(-1.0f / 720.0f, c));
    c = cr_mul(r2, cr_add(1.0f / 24.0f, c));
    c = cr_mul(r2, cr_add(-0.5f, c));
    c = cr_add(1.0f, c);

    switch ((int)(quadrant & 3)) {
    case 1: tmp = c; c = cr_neg(s); s = tmp; break;
    case 2: c = cr_neg(c); s = cr_neg(s); break;
    case 3: tmp = c; c = s; s = cr_neg(tmp); break;
    default: break;
    }
    return cr_rot_normalize(cr_r(c, s));
}

/* atan(t) for 0 <= t <= 1: two half-angle reductions bring t below
 * tan(pi/16) ~ 0.2, where six terms of the series are exact to float. */
static float cr_atan_unit(float t)
{
    int i;
    float t2, sum;
    for (i = 0; i < 2; ++i)
        t = cr_div(t, cr_add(1.0f, cr_sqrt(cr_add(1.0f, cr_mul(t, t)))));
    t2 = cr_mul(t, t);
    sum = cr_mul(t2, -1.0f / 11.0f);
    sum = cr_mul(t2, cr_add(1.0f / 9.0f, sum));
    sum = cr_mul(t2, cr_add(-1.0f / 7.0f, sum));
    sum = cr_mul(t2, cr_add(1.0f / 5.0f, sum));
    sum = cr_mul(t2, cr_add(-1.0f / 3.0f, sum));
    sum = cr_add(t, cr_mul(t, sum));
    return cr_mul(4.0f, sum);
}

float carom_rot_angle(carom_rot r)
{
    float ax = cr_abs(r.c), ay = cr_abs(r.s), a;
    if (cr_eq(ax, 0.0f) && cr_eq(ay, 0.0f))
        return 0.0f;
    if (cr_le(ay, ax))
        a = cr_atan_unit(cr_div(ay, ax));
    else
        a = cr_sub(cr_mul(2.0f, CR_PIO4), cr_atan_unit(cr_div(ax, ay)));
    if (cr_lt(r.c, 0.0f))
        a = cr_sub(CR_PI, a);
    if (cr_lt(r.s, 0.0f))
        a = cr_neg(a);
    return a;
}
