/*
 * test_toi.c -- time of impact (src/toi.c): the quadratic and quartic root
 * finders, and the first impact of body pairs under the step's drift.
 *
 * Expected times are worked out independently in double precision: closed
 * forms (the cancellation-free quadratic formula, kinematics), or a dense
 * scan of the double-precision function followed by bisection.
 */
#include <string.h>

#include "test_util.h"

#include "narrowphase.h"
#include "toi.h"

Suite *suite_toi(void);

/* ---- helpers ------------------------------------------------------------- */

/* A body as the time of impact sees it: its hot state, its shape and its
 * drift (synchronised at 0). */
typedef struct tb {
    cr_body b;
    cr_body_info info;
    cr_drift d;
} tb;

static cr_mover mover(const tb *t)
{
    cr_mover m;
    m.s = &t->info.shape;
    m.b = &t->b;
    m.d = &t->d;
    return m;
}

static int toi_of(const tb *a, const tb *b, float t0, float t1, float tol, float *out)
{
    cr_mover ma = mover(a), mb = mover(b);
    return cr_time_of_impact(&ma, &mb, t0, t1, tol, out);
}

static void set_motion(tb *t, double vx, double vy, double w, double ax,
                       double ay)
{
    t->d.t = 0.0f;
    t->b.v.x = (float)vx;
    t->b.v.y = (float)vy;
    t->b.w = (float)w;
    t->d.a.x = (float)ax;
    t->d.a.y = (float)ay;
    t->d.alpha = 0.0f;
    t->d.version = 0;
}

static tb make_circle(double x, double y, double r, int type)
{
    carom_body_def bd = carom_default_body_def();
    tb t;
    bd.type = (carom_body_type)type;
    bd.radius = (float)r;
    bd.position.x = (float)x;
    bd.position.y = (float)y;
    ck_assert_int_eq(cr_body_build(&bd, &t.b, &t.info), CAROM_OK);
    set_motion(&t, 0, 0, 0, 0, 0);
    return t;
}

static tb make_box(double x, double y, double hx, double hy,
                   double angle, int type)
{
    carom_body_def bd = carom_default_body_def();
    tb t;
    bd.type = (carom_body_type)type;
    carom_body_def_set_box(&bd, (float)hx, (float)hy);
    bd.position.x = (float)x;
    bd.position.y = (float)y;
    bd.rotation = carom_rot_from_angle((float)angle);
    ck_assert_int_eq(cr_body_build(&bd, &t.b, &t.info), CAROM_OK);
    set_motion(&t, 0, 0, 0, 0, 0);
    return t;
}

/* Earliest root of c0 + c1 s + c2 s^2 where it decreases, in double, by
 * the textbook formula for an upward parabola or a line. -1 if none. */
static double down_root2_d(double c0, double c1, double c2, double hi)
{
    double disc, sq, r;
    if (c2 == 0.0) {
        r = c1 < 0.0 ? -c0 / c1 : -1.0;
    } else {
        disc = c1 * c1 - 4.0 * c2 * c0;
        if (disc < 0.0)
            return -1.0;
        sq = sqrt(disc);
        /* the root with derivative c1 + 2 c2 s = -sgn(c2) sq < 0 */
        r = c2 > 0.0 ? 2.0 * c0 / (-c1 + sq) : (-c1 - sq) / (2.0 * c2);
        if (c2 > 0.0 && r < 0.0)
            return -1.0;
    }
    return r >= 0.0 && r <= hi ? r : -1.0;
}

static double poly4_d(const float c[5], double s)
{
    return (double)c[0] +
           s * ((double)c[1] +
                s * ((double)c[2] + s * ((double)c[3] + s * (double)c[4])));
}

/* First root of the quartic (float coefficients, evaluated in double) in
 * [0, hi]: dense scan, then bisection. -1 if the scan finds none. */
static double first_root4_scan(const float c[5], double hi)
{
    const int n = 200000;
    double prev = 0.0;
    int i, k;
    for (i = 1; i <= n; ++i) {
        double s = hi * (double)i / (double)n;
        if (poly4_d(c, s) <= 0.0) {
            double a = prev, b = s;
            for (k = 0; k < 200; ++k) {
                double m = 0.5 * (a + b);
                if (poly4_d(c, m) > 0.0)
                    a = m;
                else
                    b = m;
            }
            return a;
        }
        prev = s;
    }
    return -1.0;
}

/* Quartic |p + u s + q s^2|^2 - R^2, coefficients in double then rounded. */
static void circle_quartic(double px, double py, double ux, double uy,
                           double qx, double qy, double R, float c[5])
{
    c[0] = (float)(px * px + py * py - R * R);
    c[1] = (float)(2.0 * (px * ux + py * uy));
    c[2] = (float)(ux * ux + uy * uy + 2.0 * (px * qx + py * qy));
    c[3] = (float)(2.0 * (ux * qx + uy * qy));
    c[4] = (float)(qx * qx + qy * qy);
}

/* The drift of a body, in double: centre at time t (synchronised at 0). */
static void centre_d(const tb *t_, double t, double *x, double *y)
{
    const cr_body *b = &t_->b;
    *x = (double)b->x.x + (double)b->v.x * t + 0.5 * (double)t_->d.a.x * t * t;
    *y = (double)b->x.y + (double)b->v.y * t + 0.5 * (double)t_->d.a.y * t * t;
}

static double circles_gap_d(const tb *a, const tb *b, double t)
{
    double ax, ay, bx, by;
    centre_d(a, t, &ax, &ay);
    centre_d(b, t, &bx, &by);
    return hypot(bx - ax, by - ay) -
           ((double)a->info.shape.radius + (double)b->info.shape.radius);
}

/* World vertices of a polygon at time t in double, turning at constant w. */
static void polygon_d(const tb *t_, double t, double vx[], double vy[])
{
    const cr_body *b = &t_->b;
    double cx, cy, ang = atan2((double)b->q.s, (double)b->q.c) + (double)b->w * t;
    double co = cos(ang), si = sin(ang);
    int i;
    centre_d(t_, t, &cx, &cy);
    for (i = 0; i < t_->info.shape.count; ++i) {
        double lx = t_->info.shape.verts[i].x, ly = t_->info.shape.verts[i].y;
        vx[i] = cx + co * lx - si * ly;
        vy[i] = cy + si * lx + co * ly;
    }
}

/* Largest separation along an edge normal of P of the vertices of Q. */
static double sat_one_d(int np, const double px[], const double py[], int nq,
                        const double qx[], const double qy[])
{
    double best = -1e300;
    int i, j;
    for (i = 0; i < np; ++i) {
        int k = (i + 1) % np;
        double ex = px[k] - px[i], ey = py[k] - py[i], len = hypot(ex, ey);
        double nx = ey / len, ny = -ex / len, lo = 1e300; /* ccw: outward */
        for (j = 0; j < nq; ++j) {
            double d = nx * (qx[j] - px[i]) + ny * (qy[j] - py[i]);
            lo = d < lo ? d : lo;
        }
        best = lo > best ? lo : best;
    }
    return best;
}

/* Separating-axis separation of two polygons at time t (> 0: apart). */
static double polygons_sat_d(const tb *a, const tb *b, double t)
{
    double ax[CAROM_MAX_POLYGON_VERTICES], ay[CAROM_MAX_POLYGON_VERTICES];
    double bx[CAROM_MAX_POLYGON_VERTICES], by[CAROM_MAX_POLYGON_VERTICES];
    double s1, s2;
    polygon_d(a, t, ax, ay);
    polygon_d(b, t, bx, by);
    s1 = sat_one_d(a->info.shape.count, ax, ay, b->info.shape.count, bx, by);
    s2 = sat_one_d(b->info.shape.count, bx, by, a->info.shape.count, ax, ay);
    return s1 > s2 ? s1 : s2;
}

/* cr_separation of the two bodies posed at time t on their drifts. */
static float separation_at(const tb *a, const tb *b, float t)
{
    cr_v2 xa, xb;
    cr_rot qa, qb;
    cr_pose_at(&a->b, &a->d, t, &xa, &qa);
    cr_pose_at(&b->b, &b->d, t, &xb, &qb);
    return cr_separation(&a->info.shape, xa, qa, &b->info.shape, xb, qb);
}

/* Deterministic pseudo-random numbers in [lo, hi). */
static double lcg(unsigned long *state, double lo, double hi)
{
    *state = (*state * 1103515245ul + 12345ul) & 0x7fffffffu;
    return lo + (hi - lo) * ((double)*state / 2147483648.0);
}

/* ---- cr_first_down_root2 ------------------------------------------------------ */

START_TEST(test_root2_linear_gap_closes_at_c0_over_minus_c1)
{
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(2.0f, -4.0f, 0.0f, 1.0f, &s), 1);
    ck_assert_close(s, 0.5, 1e-7);
    ck_assert_int_eq(cr_first_down_root2(0.3f, -0.7f, 0.0f, 1.0f, &s), 1);
    ck_assert_close(s, (double)0.3f / (double)0.7f, 1e-6);
    /* the end of the range is included */
    ck_assert_int_eq(cr_first_down_root2(2.0f, -4.0f, 0.0f, 0.5f, &s), 1);
    ck_assert_close(s, 0.5, 1e-7);
}
END_TEST

START_TEST(test_root2_linear_opening_or_still_gap_has_no_root)
{
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(1.0f, 2.0f, 0.0f, 10.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, 0.0f, 0.0f, 10.0f, &s), 0);
    /* closing, but not within the range */
    ck_assert_int_eq(cr_first_down_root2(2.0f, -4.0f, 0.0f, 0.4f, &s), 0);
}
END_TEST

START_TEST(test_root2_quadratic_reports_the_earlier_root)
{
    /* 2 (s - 0.25)(s - 0.75): down at 0.25, up at 0.75 */
    float s = -1.0f;
    double e = down_root2_d(0.375, -2.0, 2.0, 1.0);
    ck_assert_close(e, 0.25, 1e-12);
    ck_assert_int_eq(cr_first_down_root2(0.375f, -2.0f, 2.0f, 1.0f, &s), 1);
    ck_assert_close(s, e, 1e-6);
    /* a generic one: gap 0.6 closing at 1.9, accelerating at 2 x 1.3 */
    e = down_root2_d((double)0.6f, (double)-1.9f, (double)1.3f, 1.0);
    ck_assert(e > 0.0);
    ck_assert_int_eq(cr_first_down_root2(0.6f, -1.9f, 1.3f, 1.0f, &s), 1);
    ck_assert_close(s, e, 1e-6);
}
END_TEST

START_TEST(test_root2_tiny_leading_coefficient_keeps_the_root_near_one)
{
    /* 1 - s + 1e-12 s^2: roots ~1 and ~1e12; the naive formula
     * (-c1 - sqrt(disc)) / (2 c2) loses the small one to cancellation */
    float s = -1.0f;
    double c2 = (double)1e-12f;
    double e = 2.0 / (1.0 + sqrt(1.0 - 4.0 * c2)); /* stable form */
    ck_assert_int_eq(cr_first_down_root2(1.0f, -1.0f, 1e-12f, 10.0f, &s), 1);
    ck_assert_msg(fabs((double)s - e) <= 1e-6 * e, "s = %.9g, expected %.12g",
                  (double)s, e);
}
END_TEST

START_TEST(test_root2_tiny_discriminant_gives_the_earlier_of_two_close_roots)
{
    /* (s - 0.5)^2 - 2^-26: roots 0.5 -+ 2^-13, every coefficient and the
     * discriminant 2^-24 exact in float */
    float s = -1.0f;
    double d = ldexp(1.0, -26);
    double e = 0.5 - sqrt(d);
    ck_assert_int_eq(cr_first_down_root2((float)(0.25 - d), -1.0f, 1.0f, 1.0f, &s), 1);
    ck_assert_msg(fabs((double)s - e) <= 1e-6 * e, "s = %.9g, expected %.12g",
                  (double)s, e);
    ck_assert(s < 0.5f);
    /* the same, scaled: 1024 ((s - 0.5)^2 - 2^-26), still exact; the
     * discriminant 2^-4 is 2^-24 of c1^2 */
    ck_assert_int_eq(cr_first_down_root2((float)(1024.0 * (0.25 - d)), -1024.0f,
                                         1024.0f, 1.0f, &s), 1);
    ck_assert_msg(fabs((double)s - e) <= 1e-6 * e, "scaled: s = %.9g, expected %.12g",
                  (double)s, e);
}
END_TEST

START_TEST(test_root2_double_root_is_a_graze_not_an_impact)
{
    /* (s - 0.5)^2: touches at 0.5 without decreasing through zero */
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(0.25f, -1.0f, 1.0f, 1.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(2.5f, -10.0f, 10.0f, 1.0f, &s), 0);
    /* closest approach still apart: no real root */
    ck_assert_int_eq(cr_first_down_root2(0.2501f, -1.0f, 1.0f, 1.0f, &s), 0);
}
END_TEST

START_TEST(test_root2_separating_motion_has_no_root)
{
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(1.0f, 0.5f, 0.0f, 100.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, 0.5f, 2.0f, 100.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(0.001f, 3.0f, 0.0f, 100.0f, &s), 0);
}
END_TEST

START_TEST(test_root2_returning_body_skips_the_up_crossing)
{
    /* gap 0.001 + 3 s - 5 s^2: opening first, then falling back through
     * zero; the up-crossing root (negative) must not be reported */
    float s = -1.0f;
    double c0 = (double)0.001f;
    double e = down_root2_d(c0, 3.0, -5.0, 10.0);
    ck_assert_close(e, (3.0 + sqrt(9.0 + 20.0 * c0)) / 10.0, 1e-12);
    ck_assert(e > 0.6);
    ck_assert_int_eq(cr_first_down_root2(0.001f, 3.0f, -5.0f, 10.0f, &s), 1);
    ck_assert_msg(fabs((double)s - e) <= 1e-6 * e, "s = %.9g, expected %.12g",
                  (double)s, e);
    /* and none before it falls back */
    ck_assert_int_eq(cr_first_down_root2(0.001f, 3.0f, -5.0f, 0.6f, &s), 0);
}
END_TEST

START_TEST(test_root2_root_beyond_hi_is_none)
{
    /* 1 - s + 0.1 s^2: down root (1 - sqrt(0.6)) / 0.2 ~ 1.127 */
    float s = -1.0f;
    double c2 = (double)0.1f;
    double e = down_root2_d(1.0, -1.0, c2, 10.0);
    ck_assert_close(e, (1.0 - sqrt(1.0 - 4.0 * c2)) / (2.0 * c2), 1e-12);
    ck_assert_int_eq(cr_first_down_root2(1.0f, -1.0f, 0.1f, 1.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, -1.0f, 0.1f, 2.0f, &s), 1);
    ck_assert_close(s, e, 1e-6);
}
END_TEST

START_TEST(test_root2_negative_roots_are_never_reported)
{
    /* (s + 1)(s + 0.5): decreasing through zero at s = -1, in the past */
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(0.5f, 1.5f, 1.0f, 10.0f, &s), 0);
    /* 2 + s - s^2 = -(s + 1)(s - 2): roots straddle 0, only 2 is reported */
    ck_assert_int_eq(cr_first_down_root2(2.0f, 1.0f, -1.0f, 10.0f, &s), 1);
    ck_assert_close(s, 2.0, 1e-6);
}
END_TEST

START_TEST(test_root2_requires_a_positive_gap)
{
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(0.0f, -1.0f, 0.0f, 10.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(-1.0f, -1.0f, 1.0f, 10.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(-0.0f, -1.0f, -1.0f, 10.0f, &s), 0);
}
END_TEST

START_TEST(test_root2_non_finite_input_has_no_root)
{
    float s = -1.0f;
    ck_assert_int_eq(cr_first_down_root2(NAN, -1.0f, 0.0f, 1.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, -INFINITY, 0.0f, 1.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, -1.0f, NAN, 1.0f, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(1.0f, -4.0f, 1.0f, INFINITY, &s), 0);
    ck_assert_int_eq(cr_first_down_root2(INFINITY, -1.0f, 0.0f, 1.0f, &s), 0);
    ck_assert(s == -1.0f);
}
END_TEST

/* 1e-20 - 1e-30 s^2: the root is at sqrt(1e10) = 1e5, far beyond the
 * range; c2 c0 is below float's range, the discriminant rounds to 0. */
START_TEST(test_root2_underflowing_discriminant_far_root_is_none)
{
    float s = -1.0f;
    ck_assert(down_root2_d(1e-20, 0.0, -1e-30, 10.0) < 0.0);
    ck_assert_int_eq(cr_first_down_root2(1e-20f, 0.0f, -1e-30f, 10.0f, &s), 0);
    /* the same shape in range: 1 - s^2 meets 0 at 1, decreasing */
    ck_assert_int_eq(cr_first_down_root2(1.0f, 0.0f, -1.0f, 10.0f, &s), 1);
    ck_assert_close(s, 1.0, 1e-7);
}
END_TEST

/* ---- cr_first_root4 ------------------------------------------------------------- */

/* Common check: found, no later than the true root, and within rel. */
static void assert_root4(const float c[5], float hi, double rel)
{
    float s = -1.0f;
    double e = first_root4_scan(c, hi);
    ck_assert_msg(e >= 0.0, "the scan finds no root");
    ck_assert_msg(cr_first_root4(c, hi, &s) == 1,
                  "no root reported; expected %.9g (c = %g %g %g %g %g, hi %g)",
                  e, (double)c[0], (double)c[1], (double)c[2], (double)c[3],
                  (double)c[4], (double)hi);
    ck_assert_msg(fabs((double)s - e) <= rel * (e > 1.0 ? e : 1.0),
                  "s = %.9g, expected %.9g", (double)s, e);
    /* the last time known before contact: not after the root */
    ck_assert_msg((double)s <= e + 1e-6 * e, "s = %.9g after the root %.9g",
                  (double)s, e);
}

START_TEST(test_root4_circles_with_different_accelerations_first_contact)
{
    /* d(s) = (3, 0.5) + (-4, 0.25) s + (0.5, -1) s^2, R = 1: every
     * coefficient is exact in float */
    float c[5];
    circle_quartic(3, 0.5, -4, 0.25, 0.5, -1, 1, c);
    ck_assert_close(c[0], 8.25, 0);
    ck_assert_close(c[4], 1.25, 0);
    assert_root4(c, 1.0f, 1e-5);
}
END_TEST

START_TEST(test_root4_two_roots_in_range_returns_the_first)
{
    /* (s - 0.3)(s - 0.7)(s - 1.2)(s - 1.6) */
    double r[4] = {0.3, 0.7, 1.2, 1.6};
    double e2 = r[0] * r[1] + r[0] * r[2] + r[0] * r[3] + r[1] * r[2] +
                r[1] * r[3] + r[2] * r[3];
    double e3 = r[0] * r[1] * r[2] + r[0] * r[1] * r[3] + r[0] * r[2] * r[3] +
                r[1] * r[2] * r[3];
    float c[5];
    c[0] = (float)(r[0] * r[1] * r[2] * r[3]);
    c[1] = (float)(-e3);
    c[2] = (float)e2;
    c[3] = (float)(-(r[0] + r[1] + r[2] + r[3]));
    c[4] = 1.0f;
    ck_assert_close(first_root4_scan(c, 2.0), 0.3, 1e-5);
    assert_root4(c, 2.0f, 1e-5);
    /* a circle passing right through the other: enters, then leaves */
    circle_quartic(3, 0, -4, 0, 0.5, 0.25, 1, c);
    assert_root4(c, 2.0f, 1e-5);
}
END_TEST

START_TEST(test_root4_grazing_near_miss_has_no_root)
{
    /* the centre passes at height 1.001 over a circle of radius 1:
     * |d|^2 - 1 >= 0.002001 all along */
    float c[5], s = -1.0f;
    circle_quartic(3, 1.001, -4, 0, 0.5, 0, 1, c);
    ck_assert(first_root4_scan(c, 2.0) < 0.0);
    ck_assert_int_eq(cr_first_root4(c, 2.0f, &s), 0);
}
END_TEST

START_TEST(test_root4_brief_dip_between_close_roots_is_found)
{
    /* ((s - 0.4)^2 - 1e-6)(1 + s^2): below zero only on 0.4 -+ 0.001 */
    double m = 0.4, w2 = 1e-6, a0 = m * m - w2;
    float c[5];
    c[0] = (float)a0;
    c[1] = (float)(-2.0 * m);
    c[2] = (float)(1.0 + a0);
    c[3] = (float)(-2.0 * m);
    c[4] = 1.0f;
    ck_assert_close(first_root4_scan(c, 1.0), 0.399, 1e-5);
    assert_root4(c, 1.0f, 1e-5);
}
END_TEST

START_TEST(test_root4_sign_change_over_the_range_is_a_root)
{
    /* f(s) = 8 - 18 s + 25 s^2 - 32 s^3 + 16 s^4, f(0) = 8, f(1) = -1:
     * a root in (0, 1) by continuity. It is |d|^2 - 1 for d(s) =
     * (-3 + 3 s, 4 s - 4 s^2), a ball thrown at another one under gravity */
    float c[5] = {8.0f, -18.0f, 25.0f, -32.0f, 16.0f};
    float d[5];
    circle_quartic(-3, 0, 3, 4, 0, -4, 1, d);
    ck_assert(memcmp(c, d, sizeof c) == 0);
    ck_assert(poly4_d(c, 1.0) < 0.0);
    assert_root4(c, 1.0f, 1e-5);
}
END_TEST

START_TEST(test_root4_requires_a_positive_constant_term)
{
    float c[5] = {0.0f, -1.0f, 0.0f, 0.0f, 1.0f}, s = -1.0f;
    ck_assert_int_eq(cr_first_root4(c, 1.0f, &s), 0);
    c[0] = -0.5f;
    ck_assert_int_eq(cr_first_root4(c, 1.0f, &s), 0);
}
END_TEST

START_TEST(test_root4_always_terminates_inside_the_range_before_the_root)
{
    /* many circle pairs: whatever is reported lies in [0, hi] and not after
     * the first root of the scan */
    unsigned long st = 2024;
    int i, reported = 0;
    for (i = 0; i < 300; ++i) {
        double px = lcg(&st, -4, 4), py = lcg(&st, -4, 4);
        double ux = lcg(&st, -6, 6), uy = lcg(&st, -6, 6);
        double qx = lcg(&st, -8, 8), qy = lcg(&st, -8, 8);
        double R = lcg(&st, 0.2, 1.5), hi = lcg(&st, 0.01, 2.0);
        float c[5], s = -1.0f;
        if (px * px + py * py <= 1.01 * R * R)
            continue;
        circle_quartic(px, py, ux, uy, qx, qy, R, c);
        if (!(c[0] > 0.0f))
            continue;
        if (cr_first_root4(c, (float)hi, &s)) {
            double e = first_root4_scan(c, (float)hi);
            ++reported;
            ck_assert_msg(s >= 0.0f && s <= (float)hi, "case %d: s = %g outside [0, %g]",
                          i, (double)s, hi);
            ck_assert_msg(e >= 0.0, "case %d: s = %g reported, the scan finds no root",
                          i, (double)s);
            ck_assert_msg((double)s <= e + 1e-6 * (e > 1.0 ? e : 1.0),
                          "case %d: s = %.9g after the root %.9g", i, (double)s, e);
        }
    }
    ck_assert_int_gt(reported, 10);
}
END_TEST

START_TEST(test_root4_non_finite_input_or_empty_range_has_no_root)
{
    float c[5] = {1.0f, -4.0f, 1.0f, 0.0f, 0.0f}, s = -1.0f;
    int k;
    ck_assert(first_root4_scan(c, 1.0) > 0.0);
    for (k = 0; k < 5; ++k) {
        float keep = c[k];
        c[k] = k % 2 ? INFINITY : NAN;
        ck_assert_msg(cr_first_root4(c, 1.0f, &s) == 0, "c[%d] not finite", k);
        c[k] = keep;
    }
    ck_assert_int_eq(cr_first_root4(c, NAN, &s), 0);
    ck_assert_int_eq(cr_first_root4(c, 0.0f, &s), 0);
    ck_assert_int_eq(cr_first_root4(c, -1.0f, &s), 0);
    ck_assert(s == -1.0f);
    ck_assert_int_eq(cr_first_root4(c, 1.0f, &s), 1);
}
END_TEST

/* 1 + 1e30 s^4 overflows float before the end of the range: the search
 * stops at an instant known to be before any root (there is none: the
 * polynomial is positive), inside [0, hi]. */
START_TEST(test_root4_overflow_inside_the_range_stops_before_any_root)
{
    float c[5] = {1.0f, 0.0f, 0.0f, 0.0f, 1e30f}, s = -1.0f;
    ck_assert(poly4_d(c, 1000.0) > 3.4e38);
    if (cr_first_root4(c, 1000.0f, &s)) {
        ck_assert(s >= 0.0f && s <= 1000.0f);
        ck_assert(poly4_d(c, s) > 0.0);
    }
    /* 1 - 4 s + 1e-3 s^4 meets 0 near 0.25 and overflows from s ~ 2e10:
     * over [0, 1e12] the answer may be early, never after the root */
    c[0] = 1.0f;
    c[1] = -4.0f;
    c[4] = 1e-3f;
    ck_assert(poly4_d(c, 1e12) > 3.4e38);
    s = -1.0f;
    ck_assert_int_eq(cr_first_root4(c, 1e12f, &s), 1);
    ck_assert(s >= 0.0f && (double)s <= first_root4_scan(c, 1.0));
    /* and over a range without overflow it is the root */
    assert_root4(c, 1.0f, 1e-5);
    /* f stays finite at the end of [0, 0.5] but its slope bound 12 c4 b^2
     * does not: stop before any root (f > 0 throughout) */
    c[0] = 1.0f;
    c[1] = 0.0f;
    c[4] = 3.0e38f;
    s = -1.0f;
    if (cr_first_root4(c, 0.5f, &s))
        ck_assert(s >= 0.0f && s <= 0.5f);
}
END_TEST

/* (s - 0.5)^2 (1 + s^2) touches zero at 0.5 without crossing it: a graze.
 * The search either finds nothing or stops before 0.5, within its budget
 * of tests and its fixed stack, however close to the touch it goes. */
START_TEST(test_root4_touching_double_root_stops_before_it_within_budget)
{
    /* (s^2 - s + 0.25)(1 + s^2) = 0.25 - s + 1.25 s^2 - s^3 + s^4 */
    float c[5] = {0.25f, -1.0f, 1.25f, -1.0f, 1.0f}, s = -1.0f;
    double x;
    for (x = 0.0; x <= 1.0; x += 1.0 / 1024.0)
        ck_assert(poly4_d(c, x) >= 0.0);
    if (cr_first_root4(c, 1.0f, &s))
        ck_assert_msg(s >= 0.0f && s <= 0.5f, "s = %.9g", (double)s);
    /* a whole family of grazes at different instants and heights */
    for (x = 0.05; x < 1.0; x += 0.05) {
        double e2 = x * x;
        float g[5];
        g[0] = (float)e2;
        g[1] = (float)(-2.0 * x);
        g[2] = (float)(1.0 + e2);
        g[3] = (float)(-2.0 * x);
        g[4] = 1.0f;
        s = -1.0f;
        if (cr_first_root4(g, 1.0f, &s))
            ck_assert_msg(s >= 0.0f && (double)s <= x + 1e-6, "graze at %g: s = %.9g", x, (double)s);
    }
}
END_TEST

/* A falling leading term: 1 - s^4 meets 0 at s = 1. */
START_TEST(test_root4_negative_leading_coefficient_meets_zero_at_one)
{
    float c[5] = {1.0f, 0.0f, 0.0f, 0.0f, -1.0f};
    ck_assert_close(first_root4_scan(c, 2.0), 1.0, 1e-9);
    assert_root4(c, 2.0f, 1e-6);
}
END_TEST

/* A root a billionth of the range from 0: the bisection's 40 halvings of
 * the first bracket (hi / 64) end within 2^-46 hi of it, never after. */
START_TEST(test_root4_root_near_zero_is_bisected_to_the_full_depth)
{
    float c[5] = {1e-9f, -1.0f, 0.0f, 0.0f, 1.0f}, s = -1.0f;
    double e = first_root4_scan(c, 1.0);
    ck_assert_close(e, (double)1e-9f, 1e-15);
    ck_assert_int_eq(cr_first_root4(c, 1.0f, &s), 1);
    ck_assert_msg((double)s <= e && e - (double)s <= ldexp(1.0, -46),
                  "s = %.12g, root %.12g", (double)s, e);
}
END_TEST

/* Two grazes close together, (s - 0.335)^2 (s - 0.386)^2 scaled by 0.158,
 * keep the search busy until its budget of 256 tests runs out; a graze at
 * 1e-15 from the start, (s - 1e-15)^2 with c0 = 1e-30, takes it 48
 * halvings deep, the size of its stack. Either way it stops, inside the
 * range, at an instant before the first root the double-precision scan
 * sees (for the second there is none: its dip, 4e-39 deep, is below float
 * resolution). */
START_TEST(test_root4_long_searches_stop_within_budget_and_stack)
{
    static const float cases[][5] = {
        {0.00265011191f, -0.0295527149f, 0.123377755f, -0.228541598f, 0.158489317f},
        {1e-30f, -2e-15f, 1.0f, 0.0f, 0.0f},
        {1e-36f, -2e-18f, 1.0f, 0.0f, 0.0f},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        float s = -1.0f;
        double e = first_root4_scan(cases[i], 1.0);
        if (!cr_first_root4(cases[i], 1.0f, &s))
            continue;
        ck_assert_msg(s >= 0.0f && s <= 1.0f, "case %d: s = %g", (int)i, (double)s);
        if (e >= 0.0)
            ck_assert_msg((double)s <= e + 1e-7, "case %d: s = %.9g after the root %.9g",
                          (int)i, (double)s, e);
    }
}
END_TEST

/* ---- cr_time_of_impact -------------------------------------------------------- */

START_TEST(test_toi_circles_head_on_gap_over_closing_speed)
{
    /* gap 3 - 0.5 - 0.25 = 2.25, closing at 2 + 1 = 3 */
    tb a = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    tb b = make_circle(3, 0, 0.25, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    set_motion(&a, 2, 0, 0, 0, 0);
    set_motion(&b, -1, 0, 0, 0, 0);
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, 2.25 / 3.0, 1e-6);
    ck_assert_int_eq(toi_of(&b, &a, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, 2.25 / 3.0, 1e-6);
    /* not within [0, 0.7] */
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 0.7f, 1e-4f, &toi), 0);
}
END_TEST

START_TEST(test_toi_is_a_step_time_when_searching_from_a_later_t0)
{
    /* same head-on pair, searched from t0 = 0.25: still 0.75, not 0.5 */
    tb a = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    tb b = make_circle(3, 0, 0.25, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    set_motion(&a, 2, 0, 0, 0, 0);
    set_motion(&b, -1, 0, 0, 0, 0);
    ck_assert_int_eq(toi_of(&a, &b, 0.25f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, 0.75, 1e-6);
    /* an empty search interval finds nothing */
    ck_assert_int_eq(toi_of(&a, &b, 1.0f, 1.0f, 1e-4f, &toi), 0);
}
END_TEST

START_TEST(test_toi_falling_circle_meets_box_top_face)
{
    /* top face at y = 0.5; centre at 2, r = 0.25, falling at 1 under g = 10:
     * 1.25 = t + 5 t^2 */
    tb box = make_box(0, 0, 2, 0.5, 0, CAROM_BODY_STATIC);
    tb ball = make_circle(0.3, 2, 0.25, CAROM_BODY_DYNAMIC);
    double h = 2.0 - 0.5 - 0.25, e = (-1.0 + sqrt(1.0 + 20.0 * h)) / 10.0;
    float toi = -1.0f;
    set_motion(&ball, 0, -1, 0, 0, -10);
    ck_assert_int_eq(toi_of(&box, &ball, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
    ck_assert_int_eq(toi_of(&ball, &box, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
}
END_TEST

START_TEST(test_toi_circle_meets_box_corner_at_radius_distance)
{
    /* centre (3, 1.8) moving at (-2, -0.5), r = 0.5, corner (1, 1):
     * |(2 - 2t, 0.8 - 0.5t)| = 0.5, i.e. 4.25 t^2 - 8.8 t + 4.39 = 0. It
     * passes the top face's line (t = 0.6, x = 1.8) and the right face's
     * (t = 0.75, y = 1.425) beyond the ends of those edges. */
    tb box = make_box(0, 0, 1, 1, 0, CAROM_BODY_STATIC);
    tb ball = make_circle(3, 1.8, 0.5, CAROM_BODY_DYNAMIC);
    double A = 4.25, B = -8.8, C = 4.39;
    double e = 2.0 * C / (-B + sqrt(B * B - 4.0 * A * C));
    double cx = 3.0 - 2.0 * e, cy = 1.8 - 0.5 * e;
    float toi = -1.0f;
    ck_assert(cx > 1.0 && cy > 1.0); /* vertex region */
    ck_assert_close(hypot(cx - 1.0, cy - 1.0), 0.5, 1e-12);
    set_motion(&ball, -2, -0.5, 0, 0, 0);
    ck_assert_int_eq(toi_of(&box, &ball, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-5);
    ck_assert_int_eq(toi_of(&ball, &box, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-5);
}
END_TEST

START_TEST(test_toi_falling_box_meets_box_face_with_a_vertex)
{
    /* bottom at 2 - 0.5 = 1.5 over a top face at 0.5: 1 = t + 5 t^2 */
    tb ground = make_box(0, 0, 2, 0.5, 0, CAROM_BODY_STATIC);
    tb top = make_box(0.3, 2, 0.5, 0.5, 0, CAROM_BODY_DYNAMIC);
    double e = (-1.0 + sqrt(21.0)) / 10.0;
    float toi = -1.0f;
    set_motion(&top, 0, -1, 0, 0, -10);
    ck_assert_int_eq(toi_of(&ground, &top, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
    ck_assert_int_eq(toi_of(&top, &ground, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
}
END_TEST

START_TEST(test_toi_circles_with_different_accelerations_match_scan)
{
    /* relative acceleration (0, -2): the quartic case */
    tb a = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    tb b = make_circle(3, 0.5, 0.5, CAROM_BODY_DYNAMIC);
    double e = -1.0, lo, hi;
    const int n = 200000;
    int i, k;
    float toi = -1.0f;
    set_motion(&a, 1, 0, 0, 0, -10);
    set_motion(&b, -2, 0.3, 0, 0, -12);
    for (i = 1; i <= n && e < 0.0; ++i)
        if (circles_gap_d(&a, &b, (double)i / n) <= 0.0) {
            lo = (double)(i - 1) / n;
            hi = (double)i / n;
            for (k = 0; k < 100; ++k) {
                double m = 0.5 * (lo + hi);
                if (circles_gap_d(&a, &b, m) > 0.0)
                    lo = m;
                else
                    hi = m;
            }
            e = lo;
        }
    ck_assert_msg(e > 0.0, "the scan finds no contact");
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-5);
    ck_assert_msg(toi <= e + 1e-6, "toi %.9g after the contact %.9g", (double)toi, e);
    ck_assert_int_eq(toi_of(&b, &a, 0.0f, 1.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-5);
}
END_TEST

START_TEST(test_toi_projectile_onto_static_circle_is_not_missed)
{
    /* ball thrown from (-3, 0) at (3, 4) under g = 8 lands on the centre of
     * a static ball at the origin at t = 1: d = (-3 + 3t, 4t - 4t^2) */
    tb peg = make_circle(0, 0, 0.5, CAROM_BODY_STATIC);
    tb ball = make_circle(-3, 0, 0.5, CAROM_BODY_DYNAMIC);
    double e = -1.0, lo, hi;
    const int n = 200000;
    int i, k;
    float toi = -1.0f;
    set_motion(&ball, 3, 4, 0, 0, -8);
    ck_assert(circles_gap_d(&peg, &ball, 1.0) < -0.9);
    for (i = 1; i <= n && e < 0.0; ++i)
        if (circles_gap_d(&peg, &ball, (double)i / n) <= 0.0) {
            lo = (double)(i - 1) / n;
            hi = (double)i / n;
            for (k = 0; k < 100; ++k) {
                double m = 0.5 * (lo + hi);
                if (circles_gap_d(&peg, &ball, m) > 0.0)
                    lo = m;
                else
                    hi = m;
            }
            e = lo;
        }
    ck_assert_msg(e > 0.0, "the scan finds no contact");
    ck_assert_msg(toi_of(&peg, &ball, 0.0f, 1.0f, 1e-4f, &toi) == 1,
                  "impact at %.9g missed", e);
    ck_assert_close(toi, e, 1e-5);
}
END_TEST

START_TEST(test_toi_rotating_box_stops_within_tolerance_before_contact)
{
    /* box spinning at 3 rad/s sliding at 2 towards a static box:
     * conservative advancement */
    tb ground = make_box(0, 0, 1, 0.5, 0, CAROM_BODY_STATIC);
    tb spin = make_box(3, 0.2, 0.5, 0.5, 0.3, CAROM_BODY_DYNAMIC);
    const float tol = 1e-3f;
    const int n = 100000;
    double e = -1.0, lo, hi;
    int i, k;
    float toi = -1.0f, sep;
    set_motion(&spin, -2, 0, 3, 0, 0);
    for (i = 1; i <= n && e < 0.0; ++i)
        if (polygons_sat_d(&ground, &spin, (double)i / n) <= 0.0) {
            lo = (double)(i - 1) / n;
            hi = (double)i / n;
            for (k = 0; k < 100; ++k) {
                double m = 0.5 * (lo + hi);
                if (polygons_sat_d(&ground, &spin, m) > 0.0)
                    lo = m;
                else
                    hi = m;
            }
            e = lo;
        }
    ck_assert_msg(e > 0.0, "the scan finds no contact");
    ck_assert_int_eq(toi_of(&ground, &spin, 0.0f, 1.0f, tol, &toi), 1);
    ck_assert_msg(toi >= 0.0f && (double)toi <= e + 1e-6,
                  "toi %.9g not in [0, contact %.9g]", (double)toi, e);
    sep = separation_at(&ground, &spin, toi);
    ck_assert_msg(sep >= 0.0f && sep <= tol + 1e-5f,
                  "separation %.9g at toi %.9g, tolerance %g", (double)sep,
                  (double)toi, (double)tol);
    /* the other order */
    ck_assert_int_eq(toi_of(&spin, &ground, 0.0f, 1.0f, tol, &toi), 1);
    sep = separation_at(&spin, &ground, toi);
    ck_assert_msg(sep >= 0.0f && sep <= tol + 1e-5f && (double)toi <= e + 1e-6,
                  "reversed: separation %.9g at toi %.9g", (double)sep, (double)toi);
}
END_TEST

START_TEST(test_toi_passing_bodies_miss)
{
    tb a = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    tb b = make_circle(3, 2, 0.5, CAROM_BODY_DYNAMIC);
    tb box = make_box(0, 0, 1, 1, 0, CAROM_BODY_STATIC);
    tb spin = make_box(3, 3, 0.5, 0.5, 0, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    /* passes 2 above, closest distance 2 > 1 */
    set_motion(&b, -4, 0, 0, 0, 0);
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 2.0f, 1e-4f, &toi), 0);
    /* over the box's top (1) with 0.5 to spare: centre at 2, r = 0.5 */
    ck_assert_int_eq(toi_of(&box, &b, 0.0f, 2.0f, 1e-4f, &toi), 0);
    /* the same, accelerating differently (the quartic): 0.25 to spare */
    set_motion(&b, -4, 0.25, 0, 0, -0.5);
    ck_assert(circles_gap_d(&a, &b, 0.5) > 0.5);
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 2.0f, 1e-4f, &toi), 0);
    /* a spinning box moving away */
    set_motion(&spin, 1, 1, 4, 0, 0);
    ck_assert_int_eq(toi_of(&box, &spin, 0.0f, 2.0f, 1e-4f, &toi), 0);
}
END_TEST

/* Circles already touching at the start of the search are the contact
 * solver's: no impact time. */
START_TEST(test_toi_circles_already_touching_have_no_impact)
{
    tb a = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    tb b = make_circle(0.9, 0, 0.5, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    set_motion(&b, -1, 0, 0, 0, 0);
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 1.0f, 1e-4f, &toi), 0);
    set_motion(&b, -1, 0, 0, 0, -3); /* the quartic path */
    set_motion(&a, 0, 0, 0, 0, 2);
    ck_assert_int_eq(toi_of(&a, &b, 0.0f, 1.0f, 1e-4f, &toi), 0);
}
END_TEST

/* A ball falling at x = -0.9 over a box of half-width 1 passes within its
 * radius of the corner (-1, 1) after hitting the top face: the face comes
 * first, at 1.25 = 2 - t - 5 t^2 ... from y = 2 at speed 1, g = 10. */
START_TEST(test_toi_ball_near_a_corner_meets_the_face_before_the_corner)
{
    tb box = make_box(0, 0, 1, 1, 0, CAROM_BODY_STATIC);
    tb ball = make_circle(-0.9, 2.5, 0.25, CAROM_BODY_DYNAMIC);
    double h = 2.5 - 1.0 - 0.25, e = (-1.0 + sqrt(1.0 + 20.0 * h)) / 10.0;
    float toi = -1.0f;
    set_motion(&ball, 0, -1, 0, 0, -10);
    ck_assert_int_eq(toi_of(&box, &ball, 0.0f, 2.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
    ck_assert_int_eq(toi_of(&ball, &box, 0.0f, 2.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-6);
    /* at x = 1.1 (past the right face, within r of the corner (1, 1)) the
     * corner is met first: |(0.1, y - 1)| = 0.25 */
    ball = make_circle(1.1, 2.5, 0.25, CAROM_BODY_DYNAMIC);
    set_motion(&ball, 0, -1, 0, 0, -10);
    h = 2.5 - 1.0 - sqrt(0.25 * 0.25 - 0.1 * 0.1);
    e = (-1.0 + sqrt(1.0 + 20.0 * h)) / 10.0;
    ck_assert_int_eq(toi_of(&box, &ball, 0.0f, 2.0f, 1e-4f, &toi), 1);
    ck_assert_close(toi, e, 1e-5);
}
END_TEST

/* A box tilted by 0.3 rad (not turning) falls at a constant 2 m/s onto a
 * static floor: its lowest corner, hy cos + hx sin below the centre,
 * arrives first; its other corners later. */
START_TEST(test_toi_tilted_box_lands_on_its_lowest_corner)
{
    const double hx = 0.6, hy = 0.4, cy = 3.0;
    int k;
    for (k = -1; k <= 1; k += 2) { /* tilted either way: another corner is lowest */
        double a = 0.3 * k;
        tb floor_ = make_box(0, 0, 5, 0.5, 0, CAROM_BODY_STATIC);
        tb box = make_box(0.2, cy, hx, hy, a, CAROM_BODY_DYNAMIC);
        double low = cy - (hy * cos(a) + hx * sin(fabs(a)));
        double e = (low - 0.5) / 2.0;
        float toi = -1.0f;
        set_motion(&box, 0, -2, 0, 0, 0);
        ck_assert_int_eq(toi_of(&floor_, &box, 0.0f, 2.0f, 1e-4f, &toi), 1);
        ck_assert_close(toi, e, 1e-6);
        ck_assert_int_eq(toi_of(&box, &floor_, 0.0f, 2.0f, 1e-4f, &toi), 1);
        ck_assert_close(toi, e, 1e-6);
    }
}
END_TEST

/* A diamond (a square on its corner) spinning just above a floor: its
 * lowest corner moves sideways, then rises, so it never strikes the floor
 * although it starts within the tolerance of it: a graze, no impact. */
START_TEST(test_toi_spinning_diamond_grazing_a_floor_has_no_impact)
{
    const float tol = 1e-3f;
    const double h = 0.5, d = h * sqrt(2.0);
    tb floor_ = make_box(0, 0, 5, 0.5, 0, CAROM_BODY_STATIC);
    tb diamond = make_box(0, 0.5 + d + 0.5 * tol, h, h, 0.78539816339744831, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    int i;
    set_motion(&diamond, 0, 0, 2, 0, 0);
    /* lowest point over the next 0.5 s (turning by up to 1 rad): never
     * below its start */
    for (i = 0; i <= 100; ++i) {
        double t = 0.5 * i / 100.0, ang = 0.78539816339744831 + 2.0 * t, lowest = 1e9;
        int k;
        for (k = 0; k < 4; ++k) {
            double vx = (k == 0 || k == 3) ? -h : h, vy = k < 2 ? -h : h;
            double y = (double)diamond.b.x.y + sin(ang) * vx + cos(ang) * vy;
            lowest = y < lowest ? y : lowest;
        }
        ck_assert(lowest >= 0.5 + 0.5 * tol - 1e-6);
    }
    ck_assert_int_eq(toi_of(&floor_, &diamond, 0.0f, 0.5f, tol, &toi), 0);
    ck_assert_int_eq(toi_of(&diamond, &floor_, 0.0f, 0.5f, tol, &toi), 0);
}
END_TEST

/* Conservative advancement refuses what it cannot bound: a spin whose
 * speed bound overflows float, a spin too slow to move at all (the bodies
 * at rest apart never meet), and bodies too far apart for a finite
 * separation. None of these loops or reports an impact. */
START_TEST(test_toi_advancement_without_a_finite_bound_reports_nothing)
{
    tb floor_ = make_box(0, 0, 5, 0.5, 0, CAROM_BODY_STATIC);
    tb spin = make_box(0, 2, 1, 1, 0.2, CAROM_BODY_DYNAMIC);
    tb still = make_box(0, 2, 0.25, 0.25, 0.2, CAROM_BODY_DYNAMIC);
    float toi = -1.0f;
    set_motion(&spin, 0, -1, 3.0e38, 0, 0);
    ck_assert_int_eq(toi_of(&floor_, &spin, 0.0f, 1.0f, 1e-4f, &toi), 0);
    /* 1.4e-45 rad/s times its extent 0.35 m rounds to 0 m/s */
    set_motion(&still, 0, 0, 1.4e-45, 0, 0);
    ck_assert(still.b.w > 0.0f);
    ck_assert_int_eq(toi_of(&floor_, &still, 0.0f, 1.0f, 1e-4f, &toi), 0);
    /* 3e38 m apart on each side: the offset between them is not finite */
    set_motion(&spin, 0, 0, 1, 0, 0);
    spin.b.x.x = 3.0e38f;
    floor_.b.x.x = -3.0e38f;
    ck_assert_int_eq(toi_of(&floor_, &spin, 0.0f, 1.0f, 1e-4f, &toi), 0);
    ck_assert(toi == -1.0f);
}
END_TEST

/* A hold drift lasts to its substep's end; the box after it follows the
 * free motion. An impact a microsecond before the end of a substep set a
 * drift of 10^6 m/s^2 (a 1 m/s change over 1 us): swept to the end of the
 * step it spanned 139 m, and the box of one body in a pile of 10^4
 * covered the pile (22,000 extra candidate pairs). */
START_TEST(test_swept_box_until_follows_the_free_motion_after_the_hold)
{
    tb t = make_circle(0, 0, 0.5, CAROM_BODY_DYNAMIC);
    cr_mover m;
    cr_box box, whole;
    const double t_mid = 1e-6, t1 = 1.0 / 60.0, margin = 0.01;
    /* hold: 1e6 m/s^2 along x until t_mid; then gravity only */
    double x_mid = 0.5 * 1e6 * t_mid * t_mid, v_mid = 1e6 * t_mid;
    double x_end = x_mid + v_mid * (t1 - t_mid);
    double y_end = -0.5 * 10.0 * (t1 - t_mid) * (t1 - t_mid);
    set_motion(&t, 0, 0, 0, 1e6, 0);
    t.b.a = cr_v(0.0f, -10.0f);
    m = mover(&t);
    cr_swept_box_until(&m, 0.0f, (float)t_mid, (float)t1, (float)margin, &box);
    ck_assert_double_eq_tol(box.lo_x, -0.5 - margin, 1e-6);
    ck_assert_double_eq_tol(box.hi_x, 0.5 + margin + x_end, 1e-5);
    ck_assert_double_eq_tol(box.lo_y, -0.5 - margin + y_end, 1e-5);
    ck_assert_double_eq_tol(box.hi_y, 0.5 + margin, 1e-6);
    /* the whole sweep on the hold's drift: the runaway box */
    cr_swept_box(&m, 0.0f, (float)t1, (float)margin, &whole);
    ck_assert(whole.hi_x > 100.0f);
    /* a drift that holds to the end is swept as before */
    cr_swept_box_until(&m, 0.0f, (float)t1, (float)t1, (float)margin, &box);
    ck_assert(box.lo_x == whole.lo_x && box.hi_x == whole.hi_x &&
              box.lo_y == whole.lo_y && box.hi_y == whole.hi_y);
}
END_TEST

Suite *suite_toi(void)
{
    Suite *s = suite_create("toi");
    TCase *r2 = tcase_create("root2");
    TCase *r4 = tcase_create("root4");
    TCase *tc = tcase_create("time_of_impact");
    tcase_add_test(r2, test_root2_linear_gap_closes_at_c0_over_minus_c1);
    tcase_add_test(r2, test_root2_linear_opening_or_still_gap_has_no_root);
    tcase_add_test(r2, test_root2_quadratic_reports_the_earlier_root);
    tcase_add_test(r2, test_root2_tiny_leading_coefficient_keeps_the_root_near_one);
    tcase_add_test(r2, test_root2_tiny_discriminant_gives_the_earlier_of_two_close_roots);
    tcase_add_test(r2, test_root2_double_root_is_a_graze_not_an_impact);
    tcase_add_test(r2, test_root2_separating_motion_has_no_root);
    tcase_add_test(r2, test_root2_returning_body_skips_the_up_crossing);
    tcase_add_test(r2, test_root2_root_beyond_hi_is_none);
    tcase_add_test(r2, test_root2_negative_roots_are_never_reported);
    tcase_add_test(r2, test_root2_requires_a_positive_gap);
    tcase_add_test(r2, test_root2_non_finite_input_has_no_root);
    tcase_add_test(r2, test_root2_underflowing_discriminant_far_root_is_none);
    suite_add_tcase(s, r2);
    tcase_add_test(r4, test_root4_circles_with_different_accelerations_first_contact);
    tcase_add_test(r4, test_root4_two_roots_in_range_returns_the_first);
    tcase_add_test(r4, test_root4_grazing_near_miss_has_no_root);
    tcase_add_test(r4, test_root4_brief_dip_between_close_roots_is_found);
    tcase_add_test(r4, test_root4_sign_change_over_the_range_is_a_root);
    tcase_add_test(r4, test_root4_requires_a_positive_constant_term);
    tcase_add_test(r4, test_root4_always_terminates_inside_the_range_before_the_root);
    tcase_add_test(r4, test_root4_non_finite_input_or_empty_range_has_no_root);
    tcase_add_test(r4, test_root4_overflow_inside_the_range_stops_before_any_root);
    tcase_add_test(r4, test_root4_touching_double_root_stops_before_it_within_budget);
    tcase_add_test(r4, test_root4_negative_leading_coefficient_meets_zero_at_one);
    tcase_add_test(r4, test_root4_root_near_zero_is_bisected_to_the_full_depth);
    tcase_add_test(r4, test_root4_long_searches_stop_within_budget_and_stack);
    suite_add_tcase(s, r4);
    tcase_add_test(tc, test_toi_circles_head_on_gap_over_closing_speed);
    tcase_add_test(tc, test_toi_is_a_step_time_when_searching_from_a_later_t0);
    tcase_add_test(tc, test_toi_falling_circle_meets_box_top_face);
    tcase_add_test(tc, test_toi_circle_meets_box_corner_at_radius_distance);
    tcase_add_test(tc, test_toi_falling_box_meets_box_face_with_a_vertex);
    tcase_add_test(tc, test_toi_circles_with_different_accelerations_match_scan);
    tcase_add_test(tc, test_toi_projectile_onto_static_circle_is_not_missed);
    tcase_add_test(tc, test_toi_rotating_box_stops_within_tolerance_before_contact);
    tcase_add_test(tc, test_toi_passing_bodies_miss);
    tcase_add_test(tc, test_toi_circles_already_touching_have_no_impact);
    tcase_add_test(tc, test_toi_ball_near_a_corner_meets_the_face_before_the_corner);
    tcase_add_test(tc, test_toi_tilted_box_lands_on_its_lowest_corner);
    tcase_add_test(tc, test_toi_spinning_diamond_grazing_a_floor_has_no_impact);
    tcase_add_test(tc, test_toi_advancement_without_a_finite_bound_reports_nothing);
    tcase_add_test(tc, test_swept_box_until_follows_the_free_motion_after_the_hold);
    suite_add_tcase(s, tc);
    return s;
}
