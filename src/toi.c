/*
 * toi.c -- time of impact of a body pair under the step's drift.
 *
 * Within a step every body follows the drift of velocity Verlet from its
 * last synchronisation time ts (the step start, or its last impact):
 *
 *     x(t) = x + v (t - ts) + a (t - ts)^2 / 2,   a = a0 + a_c (constant)
 *     angle(t) = w (t - ts) + alpha (t - ts)^2 / 2
 *
 * With d(s) = p + u s + q s^2 the relative motion of the centres from the
 * search start (s = t - t_from), the first impact is the first root of the
 * gap at which the gap is decreasing:
 *
 *   circle - circle     |d(s)| = R: quadratic in s when q = 0 (uniform
 *                       gravity: the common case), else a quartic.
 *   circle - polygon    not rotating: per edge the gap n.d(s) - c is a
 *                       quadratic (linear when n.q = 0); per vertex it is
 *                       circle - point. Rotating: conservative advancement.
 *   polygon - polygon   neither rotating: the first contact is a vertex of
 *                       one meeting an edge of the other, a quadratic per
 *                       vertex-edge couple. Else conservative advancement.
 *
 * Quadratics use the cancellation-free form of the roots, q = -(b + sgn(b)
 * sqrt(disc)) / 2, roots q / c2 and c0 / q, so neither a small leading
 * coefficient nor a small discriminant loses digits, and the constant term
 * (the gap, or |p|^2 - R^2 = gap (2R + gap)) is computed without
 * subtracting nearly equal numbers. The quartic is isolated by subdivision
 * with a Lipschitz bound, then bisected. Conservative advancement moves by
 * separation / (bound on the closing speed), which never passes the
 * impact, until the separation is below a tolerance.
 */
#include "internal.h"

#if CAROM_ENABLE_EVENTS

/* Approach below this fraction of the bodies' speeds is rounding, not an
 * impact (cr_impact_threshold). */
#define CR_APPROACH_REL_TOL 1.0e-5f

/* Subdivision of the quartic: at most this many interval tests. */
#define CR_QUARTIC_MAX_EVALS 256
#define CR_QUARTIC_STACK 48
/* Bisect once a bracketing interval is this fraction of the search span. */
#define CR_QUARTIC_BRACKET 0.015625f
#define CR_BISECTIONS 40

/* ---- body motion inside a step -------------------------------------------- */

static int cr_rotates(const cr_body *b)
{
#if CAROM_ENABLE_ROTATION
    return b->shape == CAROM_SHAPE_POLYGON &&
           (!cr_eq(b->w, 0.0f) || !cr_eq(b->alpha_d, 0.0f));
#else
    (void)b;
    return 0;
#endif
}

static int cr_spins(const cr_body *b)
{
#if CAROM_ENABLE_ROTATION
    return !cr_eq(b->w, 0.0f) || !cr_eq(b->alpha_d, 0.0f);
#else
    (void)b;
    return 0;
#endif
}

static cr_v2 cr_body_position_at(const cr_body *b, float t)
{
    float h = cr_sub(t, b->t_sync);
    return cr_vadd(cr_vadd(b->x, cr_vscale(h, b->vel)),
                   cr_vscale(cr_mul(0.5f, cr_mul(h, h)), b->acc_d));
}

void cr_body_pose(const cr_body *b, float t, cr_v2 *x, cr_rot *q)
{
    float h = cr_sub(t, b->t_sync);
    *x = cr_vadd(cr_vadd(b->x, cr_vscale(h, b->vel)),
                 cr_vscale(cr_mul(0.5f, cr_mul(h, h)), b->acc_d));
    if (cr_spins(b))
        *q = cr_rot_advance(b->q, cr_add(cr_mul(b->w, h),
                                         cr_mul(cr_mul(0.5f, cr_mul(h, h)),
                                                b->alpha_d)));
    else
        *q = b->q;
}

void cr_body_sync(cr_body *b, float t)
{
    float h = cr_sub(t, b->t_sync);
    if (b->type != CAROM_BODY_DYNAMIC || cr_eq(h, 0.0f)) {
        b->t_sync = t;
        return;
    }
    cr_body_pose(b, t, &b->x, &b->q);
    b->vel = cr_vmadd(b->vel, h, b->acc_d);
#if CAROM_ENABLE_ROTATION
    b->w = cr_add(b->w, cr_mul(h, b->alpha_d));
#endif
    b->t_sync = t;
}

/* Axis-aligned box swept by the body over [t0, t1], grown by margin: the
 * exact range of the centre's parabola on each axis, plus the shape. */
void cr_body_swept_bounds(const cr_body *b, float t0, float t1, float margin,
                          cr_proxy *out)
{
    cr_v2 x0, x1, u;
    float s1 = cr_sub(t1, t0), lo[2], hi[2], half[4];
    int k;
    /* positions only: the shape's box or extent covers the rotation */
    x0 = cr_body_position_at(b, t0);
    x1 = cr_body_position_at(b, t1);
    u = cr_vmadd(b->vel, cr_sub(t0, b->t_sync), b->acc_d); /* velocity at t0 */
    lo[0] = cr_min(x0.x, x1.x); hi[0] = cr_max(x0.x, x1.x);
    lo[1] = cr_min(x0.y, x1.y); hi[1] = cr_max(x0.y, x1.y);
    for (k = 0; k < 2; ++k) {
        float uk = k ? u.y : u.x, ak = k ? b->acc_d.y : b->acc_d.x;
        float xk = k ? x0.y : x0.x;
        /* turning point of the parabola inside the interval */
        if (!cr_eq(ak, 0.0f)) {
            float s = cr_neg(cr_div(uk, ak));
            if (cr_gt(s, 0.0f) && cr_lt(s, s1)) {
                float e = cr_add(xk, cr_mul(cr_mul(0.5f, s), uk));
                lo[k] = cr_min(lo[k], e);
                hi[k] = cr_max(hi[k], e);
            }
        }
    }
    if (b->shape == CAROM_SHAPE_CIRCLE || cr_rotates(b)) {
        half[0] = half[1] = half[2] = half[3] = b->extent;
    } else {
        /* fixed orientation: the shape's own box about its centre */
        cr_proxy local;
        cr_body tmp = *b;
        tmp.x = cr_v(0.0f, 0.0f);
        cr_body_bounds(&tmp, 0.0f, &local);
        half[0] = cr_neg(local.lo_x);
        half[1] = local.hi_x;
        half[2] = cr_neg(local.lo_y);
        half[3] = local.hi_y;
    }
    out->lo_x = cr_sub(lo[0], cr_add(half[0], margin));
    out->hi_x = cr_add(hi[0], cr_add(half[1], margin));
    out->lo_y = cr_sub(lo[1], cr_add(half[2], margin));
    out->hi_y = cr_add(hi[1], cr_add(half[3], margin));
}

/* ---- roots ------------------------------------------------------------------------ */

/*
 * Earliest s in [0, hi] with c0 + c1 s + c2 s^2 = 0 where the function is
 * decreasing (an approach, not a graze or a separation). c0 > 0.
 */
int cr_first_down_root2(float c0, float c1, float c2, float hi, float *out)
{
    float disc, sq, q, r1, r2, lo_r, hi_r;
    if (!cr_gt(c0, 0.0f))
        return 0;
    if (cr_eq(c2, 0.0f)) {
        float s;
        if (!cr_lt(c1, 0.0f))
            return 0;
        s = cr_div(c0, cr_neg(c1));
        if (cr_gt(s, hi))
            return 0;
        *out = s;
        return 1;
    }
    disc = cr_sub(cr_mul(c1, c1), cr_mul(cr_mul(4.0f, c2), c0));
    if (cr_lt(disc, 0.0f))
        return 0;
    sq = cr_sqrt(disc);
    q = cr_mul(-0.5f, cr_add(c1, cr_ge(c1, 0.0f) ? sq : cr_neg(sq)));
    if (cr_eq(q, 0.0f))
        return 0;
    r1 = cr_div(q, c2);
    r2 = cr_div(c0, q);
    lo_r = cr_min(r1, r2);
    hi_r = cr_max(r1, r2);
    if (cr_ge(lo_r, 0.0f) && cr_le(lo_r, hi) &&
        cr_lt(cr_add(c1, cr_mul(cr_mul(2.0f, c2), lo_r)), 0.0f)) {
        *out = lo_r;
        return 1;
    }
    if (cr_ge(hi_r, 0.0f) && cr_le(hi_r, hi) &&
        cr_lt(cr_add(c1, cr_mul(cr_mul(2.0f, c2), hi_r)), 0.0f)) {
        *out = hi_r;
        return 1;
    }
    return 0;
}

static float cr_poly4(const float c[5], float s)
{
    return cr_add(c[0], cr_mul(s, cr_add(c[1], cr_mul(s, cr_add(c[2],
               cr_mul(s, cr_add(c[3], cr_mul(s, c[4]))))))));
}

/*
 * Earliest root of the quartic c0 + c1 s + ... + c4 s^4 in [0, hi], c0 > 0.
 * Intervals [a, b] are discarded when f(a) - L (b - a) > 0, where L bounds
 * |f'| on [a, b]: |f'(m)| at the midpoint plus (b - a) / 2 times a bound of
 * |f''| there, which is tight near a simple root, so the search homes in
 * on it in a few dozen tests. The leftmost small interval with f(b) <= 0
 * is bisected. After CR_QUARTIC_MAX_EVALS tests it stops and reports the
 * last instant known to be before any root (conservative, like
 * advancement): the event loop then finds the bodies apart and searches on.
 */
int cr_first_root4(const float c[5], float hi, float *out)
{
    float stack[CR_QUARTIC_STACK];
    int top = 0, it, k;
    float a = 0.0f, b = hi, fa = c[0];
    float small = cr_mul(CR_QUARTIC_BRACKET, hi);
    float d2 = cr_mul(2.0f, cr_abs(c[2])), d3 = cr_mul(6.0f, cr_abs(c[3]));
    float d4 = cr_mul(12.0f, cr_abs(c[4]));
    if (!cr_gt(c[0], 0.0f))
        return 0;
    for (it = 0; it < CR_QUARTIC_MAX_EVALS; ++it) {
        float fb = cr_poly4(c, b);
        float m = cr_mul(0.5f, cr_add(a, b)), half = cr_mul(0.5f, cr_sub(b, a));
        /* f'(m) = c1 + 2 c2 m + 3 c3 m^2 + 4 c4 m^3 */
        float dm = cr_add(c[1], cr_mul(m, cr_add(cr_mul(2.0f, c[2]),
                       cr_mul(m, cr_add(cr_mul(3.0f, c[3]), cr_mul(m, cr_mul(4.0f, c[4])))))));
        float f2 = cr_add(d2, cr_mul(b, cr_add(d3, cr_mul(b, d4))));
        float lip = cr_add(cr_abs(dm), cr_mul(half, f2));
        if (cr_le(fb, 0.0f) && (cr_le(cr_sub(b, a), small) ||
                                top == CR_QUARTIC_STACK)) {
            for (k = 0; k < CR_BISECTIONS; ++k) {
                float mid = cr_mul(0.5f, cr_add(a, b));
                if (cr_le(mid, a) || cr_ge(mid, b))
                    break;
                if (cr_gt(cr_poly4(c, mid), 0.0f))
                    a = mid;
                else
                    b = mid;
            }
            *out = a; /* last time known not to touch */
            return 1;
        }
        if (cr_gt(fb, 0.0f) &&
            (cr_gt(cr_sub(fa, cr_mul(lip, cr_sub(b, a))), 0.0f) ||
             top == CR_QUARTIC_STACK)) {
            if (top == 0)
                return 0;
            a = b;
            fa = fb;
            b = stack[--top];
            continue;
        }
        stack[top++] = b;
        b = m;
    }
    *out = a; /* out of budget: nothing before a, maybe something after */
    return 1;
}

/* ---- shape pairs ------------------------------------------------------------------ */

/* First s in [0, hi] with |p + u s + q s^2| = R, approaching; |p| > R. */
static int cr_toi_point(cr_v2 p, cr_v2 u, cr_v2 q, float R, float hi, float *s)
{
    float len = cr_vlen(p);
    float gap = cr_sub(len, R);
    float c0 = cr_mul(gap, cr_add(len, R)); /* |p|^2 - R^2 without cancelling */
    if (!cr_gt(gap, 0.0f))
        return 0;
    if (cr_eq(q.x, 0.0f) && cr_eq(q.y, 0.0f))
        return cr_first_down_root2(c0, cr_mul(2.0f, cr_vdot(p, u)),
                                   cr_vdot(u, u), hi, s);
    {
        float c[5];
        c[0] = c0;
        c[1] = cr_mul(2.0f, cr_vdot(p, u));
        c[2] = cr_add(cr_vdot(u, u), cr_mul(2.0f, cr_vdot(p, q)));
        c[3] = cr_mul(2.0f, cr_vdot(u, q));
        c[4] = cr_vdot(q, q);
        return cr_first_root4(c, hi, s);
    }
}

/* Relative motion of B w.r.t. A from time t: d(s) = p + u s + q s^2. */
static void cr_relative_motion(const cr_body *A, const cr_body *B, float t,
                               cr_v2 *p, cr_v2 *u, cr_v2 *q)
{
    cr_v2 xa, xb;
    cr_rot qa, qb;
    cr_body_pose(A, t, &xa, &qa);
    cr_body_pose(B, t, &xb, &qb);
    *p = cr_vsub(xb, xa);
    *u = cr_vsub(cr_vmadd(B->vel, cr_sub(t, B->t_sync), B->acc_d),
                 cr_vmadd(A->vel, cr_sub(t, A->t_sync), A->acc_d));
    *q = cr_vscale(0.5f, cr_vsub(B->acc_d, A->acc_d));
}

#if CAROM_ENABLE_POLYGONS
/* Gap of a point d(s) + off against edge i of polygon P (world frame,
 * P's orientation qp fixed): first approach within the edge's span. */
static int cr_toi_point_edge(const cr_body *P, cr_rot qp, int i, cr_v2 p,
                             cr_v2 u, cr_v2 q, float radius, float hi, float *s)
{
    cr_v2 n = cr_rotate(qp, P->norms[i]);
    cr_v2 v1 = cr_rotate(qp, P->verts[i]);
    cr_v2 v2 = cr_rotate(qp, P->verts[(i + 1) % P->count]);
    cr_v2 e = cr_vsub(v2, v1), at;
    float c0 = cr_sub(cr_vdot(n, cr_vsub(p, v1)), radius), t, len2;
    if (!cr_first_down_root2(c0, cr_vdot(n, u), cr_vdot(n, q), hi, &t))
        return 0;
    /* where along the edge the point arrives: inside [v1, v2]? */
    at = cr_vsub(cr_vadd(p, cr_vadd(cr_vscale(t, u), cr_vscale(cr_mul(t, t), q))), v1);
    len2 = cr_vdot(e, e);
    if (cr_lt(cr_vdot(at, e), 0.0f) || cr_gt(cr_vdot(at, e), len2))
        return 0;
    *s = t;
    return 1;
}

/* Circle C against polygon P, P not rotating in the step. */
static int cr_toi_circle_polygon(const cr_body *P, const cr_body *C, float t0,
                                 float hi, float *best)
{
    cr_v2 p, u, q, xp;
    cr_rot qp;
    int i, found = 0;
    float s;
    cr_relative_motion(P, C, t0, &p, &u, &q);
    cr_body_pose(P, t0, &xp, &qp);
    for (i = 0; i < P->count; ++i) {
        if (cr_toi_point_edge(P, qp, i, p, u, q, C->radius, hi, &s) &&
            (!found || cr_lt(s, *best))) {
            *best = s;
            found = 1;
        }
        if (cr_toi_point(cr_vsub(p, cr_rotate(qp, P->verts[i])), u, q,
                         C->radius, hi, &s) &&
            (!found || cr_lt(s, *best))) {
            *best = s;
            found = 1;
        }
    }
    return found;
}

/* Vertices of B against edges of A, neither rotating. */
static int cr_toi_vertices_edges(const cr_body *A, const cr_body *B, float t0,
                                 float hi, float *best, int found)
{
    cr_v2 p, u, q, xa, xb;
    cr_rot qa, qb;
    int i, j;
    float s;
    cr_relative_motion(A, B, t0, &p, &u, &q);
    cr_body_pose(A, t0, &xa, &qa);
    cr_body_pose(B, t0, &xb, &qb);
    for (j = 0; j < B->count; ++j) {
        cr_v2 pj = cr_vadd(p, cr_rotate(qb, B->verts[j]));
        for (i = 0; i < A->count; ++i)
            if (cr_toi_point_edge(A, qa, i, pj, u, q, 0.0f, hi, &s) &&
                (!found || cr_lt(s, *best))) {
                *best = s;
                found = 1;
            }
    }
    return found;
}
#endif

/*
 * The approach speed above which a contact of A and B is an impact:
 * rest_speed, plus CR_APPROACH_REL_TOL of the speeds the bodies' points can
 * have. Without the second term, with rest_speed 0, an approach at the
 * rounding level of fast bodies (1e-7 m/s at 16 m/s) would be an impact,
 * and its impulse would leave another: an endless loop at one instant.
 */
float cr_impact_threshold(const cr_body *A, const cr_body *B, float rest_speed)
{
    float scale = cr_add(cr_add(cr_vlen(A->vel), cr_vlen(B->vel)),
                         cr_add(cr_mul(cr_abs(A->w), A->extent),
                                cr_mul(cr_abs(B->w), B->extent)));
    return cr_add(rest_speed, cr_mul(CR_APPROACH_REL_TOL, scale));
}

/* Fastest normal approach of A and B over the points of their manifold at
 * local time t inside the step (0 if not within margin of each other). The
 * velocities on the drift already include the resting forces. */
float cr_approach_speed_at(const cr_body *A0, const cr_body *B0, float t,
                           float margin, float dt)
{
    cr_body A = *A0, B = *B0;
    cr_manifold m;
    float fastest = 0.0f;
    int k;
    cr_body_sync(&A, t);
    cr_body_sync(&B, t);
    if (!cr_collide(&A, &B, margin, &m))
        return 0.0f;
    (void)dt;
    for (k = 0; k < m.count; ++k) {
        cr_v2 ra = cr_vsub(m.pts[k].p, A.x), rb = cr_vsub(m.pts[k].p, B.x);
        cr_v2 vb = cr_vadd(B.vel, cr_vcross_sv(B.w, rb));
        cr_v2 va = cr_vadd(A.vel, cr_vcross_sv(A.w, ra));
        fastest = cr_max(fastest, cr_neg(cr_vdot(cr_vsub(vb, va), m.n)));
    }
    return fastest;
}

/* ---- conservative advancement -------------------------------------------------- */

#if CAROM_ENABLE_POLYGONS
/* A lower bound of the distance between A and B posed at time t. */
static float cr_separation_at(const cr_body *A, const cr_body *B, float t)
{
    cr_body a = *A, b = *B;
    cr_body_pose(A, t, &a.x, &a.q);
    cr_body_pose(B, t, &b.x, &b.q);
    return cr_separation(&a, &b);
}

static int cr_toi_advance(const cr_body *A, const cr_body *B, float t0,
                          float t1, float tol, float dt, float *out)
{
    int it;
    float t = t0;
    float span = cr_sub(t1, t0);
    /* closing speed bound over the interval: relative linear speed, plus
     * each body's spin times its reach */
    cr_v2 p, u, q;
    float vrel, wa, wb, vmax;
    cr_relative_motion(A, B, t0, &p, &u, &q);
    vrel = cr_add(cr_vlen(u), cr_mul(cr_mul(2.0f, cr_vlen(q)), span));
    wa = cr_add(cr_abs(cr_add(A->w, cr_mul(cr_sub(t0, A->t_sync), A->alpha_d))),
                cr_mul(cr_abs(A->alpha_d), span));
    wb = cr_add(cr_abs(cr_add(B->w, cr_mul(cr_sub(t0, B->t_sync), B->alpha_d))),
                cr_mul(cr_abs(B->alpha_d), span));
    vmax = cr_add(vrel, cr_add(cr_mul(wa, A->extent), cr_mul(wb, B->extent)));
    if (!cr_gt(vmax, 0.0f))
        return 0;
    for (it = 0; it < CAROM_TOI_MAX_ITERATIONS; ++it) {
        float sep = cr_separation_at(A, B, t);
        if (cr_le(sep, tol)) {
            /* within tolerance: an impact only if they are closing in;
             * otherwise a graze or a resting contact */
            if (!cr_gt(cr_approach_speed_at(A, B, t, cr_mul(2.0f, tol), dt),
                       cr_impact_threshold(A, B, 0.0f)))
                return 0;
            *out = cr_sub(t, t0);
            return 1;
        }
        t = cr_add(t, cr_div(sep, vmax));
        if (cr_gt(t, t1))
            return 0;
    }
    /* not converged: report the conservative time reached so far; the
     * event loop finds the bodies apart there and searches again */
    *out = cr_sub(t, t0);
    return 1;
}

#endif /* CAROM_ENABLE_POLYGONS */

/* ---- entry point -------------------------------------------------------------------- */

/*
 * First impact of A and B in [t0, t1] (local step time), for bodies that
 * are apart at t0 (separation > tol); dt is the step (for the resting
 * forces' share of an approach). Returns 1 and the time in *toi.
 */
int cr_time_of_impact(const cr_body *A, const cr_body *B, float t0, float t1,
                      float tol, float dt, float *toi)
{
    float s = 0.0f, hi = cr_sub(t1, t0);
    int hit = 0;
    (void)tol;
    (void)dt;
    if (!cr_gt(hi, 0.0f))
        return 0;
    if (A->shape == CAROM_SHAPE_CIRCLE && B->shape == CAROM_SHAPE_CIRCLE) {
        cr_v2 p, u, q;
        cr_relative_motion(A, B, t0, &p, &u, &q);
        hit = cr_toi_point(p, u, q, cr_add(A->radius, B->radius), hi, &s);
    }
#if CAROM_ENABLE_POLYGONS
    else if (cr_rotates(A) || cr_rotates(B)) {
        hit = cr_toi_advance(A, B, t0, t1, tol, dt, &s);
    } else if (A->shape == CAROM_SHAPE_POLYGON && B->shape == CAROM_SHAPE_CIRCLE) {
        hit = cr_toi_circle_polygon(A, B, t0, hi, &s);
    } else if (A->shape == CAROM_SHAPE_CIRCLE) {
        hit = cr_toi_circle_polygon(B, A, t0, hi, &s);
    } else {
        hit = cr_toi_vertices_edges(A, B, t0, hi, &s, 0);
        hit = cr_toi_vertices_edges(B, A, t0, hi, &s, hit);
    }
#endif
    if (hit)
        *toi = cr_add(t0, s);
    return hit;
}

#else
/* ISO C forbids an empty translation unit */
typedef int cr_toi_disabled;
#endif /* CAROM_ENABLE_EVENTS */
