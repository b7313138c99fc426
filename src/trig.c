/*
 * trig.c -- carom's own rotation trigonometry, from + - * / and sqrt only.
 *
 * libm's sinf/cosf/atan2f differ between C libraries and CPUs; these do
 * not: with IEEE single precision, round-to-nearest and no contraction,
 * every platform computes the same bits.
 */
#include "arith.h"

/* pi/2 split in three floats (Cody-Waite): P1 has 8 significant bits and
 * P2 12, so k * P1 and k * P2 are exact for the quadrant counts k < 2^12
 * that angles up to CR_TRIG_MAX_ARG give, and x - k pi/2 loses nothing. */
#define CR_PIO2_1 1.5703125f
#define CR_PIO2_2 4.837512969970703125e-4f
#define CR_PIO2_3 7.549790126404332e-8f
#define CR_TWO_OVER_PI 0.636619772367581343f
#define CR_PIO4 0.785398163397448309616f

/* Largest |angle| reduced exactly (quadrant count below 2^12). */
#define CR_TRIG_MAX_ARG 6.0e3f
/* Past CR_TRIG_MAX_ARG, up to CR_TRIG_FAR_ARG, pi/2 in four floats of 8,
 * 8, 7 and 24 significant bits: k * Q1..Q3 are exact for quadrant counts
 * k < 2^16 (below CR_TRIG_MAX_ARG the three-float split above gives the
 * bits it always gave). Larger angles are first brought into range by
 * whole turns, with the rounding error of that subtraction (their own
 * spacing is 0.008 rad and more there). */
#define CR_PIO2_Q1 1.5703125f
#define CR_PIO2_Q2 4.825592041015625e-4f
#define CR_PIO2_Q3 1.2665987014770508e-6f
#define CR_PIO2_Q4 9.92093629470503e-10f
#define CR_TRIG_FAR_ARG 1.0e5f
/* Beyond this a float angle has no fractional bits worth reducing. */
#define CR_TRIG_HUGE_ARG 1.0e9f

#if CAROM_ENABLE_ANGLES || CAROM_ENABLE_ROTATION
carom_rot cr_rot_from_angle(float angle)
{
    float k, r, r2, s, c, tmp;
    long quadrant;

    if (!cr_finite(angle) || cr_gt(cr_abs(angle), CR_TRIG_HUGE_ARG))
        return cr_rot_identity();
    if (cr_gt(cr_abs(angle), CR_TRIG_FAR_ARG)) {
        /* whole turns off: q = round(angle / 2 pi) */
        float turns = cr_mul(angle, 0.159154943091895336f);
        long q = (long)(cr_ge(turns, 0.0f) ? cr_add(turns, 0.5f) : cr_sub(turns, 0.5f));
        angle = cr_sub(angle, cr_mul((float)q, 6.28318530717958648f));
    }
    /* nearest multiple of pi/2 */
    k = cr_mul(angle, CR_TWO_OVER_PI);
    quadrant = (long)(cr_ge(k, 0.0f) ? cr_add(k, 0.5f) : cr_sub(k, 0.5f));
    k = (float)quadrant;
    if (cr_gt(cr_abs(angle), CR_TRIG_MAX_ARG))
        r = cr_sub(cr_sub(cr_sub(cr_sub(angle, cr_mul(k, CR_PIO2_Q1)), cr_mul(k, CR_PIO2_Q2)),
                          cr_mul(k, CR_PIO2_Q3)),
                   cr_mul(k, CR_PIO2_Q4));
    else
        r = cr_sub(cr_sub(cr_sub(angle, cr_mul(k, CR_PIO2_1)), cr_mul(k, CR_PIO2_2)),
                   cr_mul(k, CR_PIO2_3));

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
#endif

#if CAROM_ENABLE_ANGLES
carom_rot carom_rot_from_angle(float angle)
{
    return cr_rot_from_angle(angle);
}
#endif

#if CAROM_ENABLE_ANGLES || (CR_CONTINUOUS && CAROM_ENABLE_ROTATION)
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

float cr_rot_angle(carom_rot r)
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
#endif

#if CAROM_ENABLE_ANGLES
float carom_rot_angle(carom_rot r) { return cr_rot_angle(r); }
#endif /* CAROM_ENABLE_ANGLES */
