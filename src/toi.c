/*
 * toi.c -- time of impact of a body pair on their drifts.
 *
 * Within a step every body follows a drift (integrate.h) from the instant
 * t_d of its last change:
 *
 *     x(t) = x + v (t - t_d) + a (t - t_d)^2 / 2
 *     angle(t) = w (t - t_d) + alpha (t - t_d)^2 / 2
 *
 * With d(s) = p + u s + q s^2 the relative motion of the centres from the
 * search start (s = t - t0), the first impact is the first root of the gap
 * at which the gap is decreasing:
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
 * separation / (bound on the closing speed: relative speed plus spin times
 * extent), which never passes the impact, until the separation is below a
 * tolerance: a thin rod toppling onto a thin floor is caught however fast
 * its far end sweeps.
 *
 * Every search is bounded whatever its input: coefficients that are not
 * finite mean "no root", the subdivision stack never grows past its size,
 * and every loop has a fixed budget.
 */
#include "toi.h"

#include "narrowphase.h"

/* Subdivision of the quartic: at most this many interval tests. */
#define CR_QUARTIC_MAX_EVALS 256
#define CR_QUARTIC_STACK 48
/* Bisect once a bracketing interval is this fraction of the search span. */
#define CR_QUARTIC_BRACKET 0.015625f
#define CR_BISECTIONS 40

/* Approach below this fraction of the bodies' speeds is rounding, not an
 * approach (a graze during conservative advancement). */
#define CR_APPROACH_REL_TOL 1.0e-5f

/* ---- motion ------------------------------------------------------------------ */

static int cr_spins(const cr_mover *m)
{
#if CAROM_ENABLE_ROTATION
    return !cr_eq(m->b->w, 0.0f) || !cr_eq(m->d->alpha, 0.0f);
#else
    (void)m;
    return 0;
#endif
}

static int cr_rotates(const cr_mover *m)
{
    return !CR_KIND_CIRCLE(m->s->kind) && cr_spins(m);
}

static cr_v2 cr_position_at(const cr_mover *m, float t)
{
    float h = cr_sub(t, m->d->t);
    return cr_vadd(cr_vadd(m->b->x, cr_vscale(h, m->b->v)),
                   cr_vscale(cr_mul(0.5f, cr_mul(h, h)), m->d->a));
}

static cr_v2 cr_speed_at(const cr_mover *m, float t)
{
    return cr_vmadd(m->b->v, cr_sub(t, m->d->t), m->d->a);
}

/* Widen [lo, hi] to the turning point of x + u s + a s^2 / 2 (a != 0)
 * if it lies within s in (0, s1). */
CR_INLINE void cr_sweep_turn(float x, float u, float a, float s1, float *lo, float *hi)
{
    float s = cr_neg(cr_div(u, a));
    if (cr_gt(s, 0.0f) && cr_lt(s, s1)) {
        float e = cr_add(x, cr_mul(cr_mul(0.5f, s), u));
        *lo = cr_min(*lo, e);
        *hi = cr_max(*hi, e);
    }
}

/* One axis of a swept box from the drift's start: x + u s + a s^2 / 2
 * over s in [0, s1] (c = s1^2 / 2), as cr_position_at and cr_speed_at
 * give it with an acceleration (acc), without the terms that add zero
 * when there is none. */
CR_INLINE void cr_sweep_axis(float x, float u, float a, int acc, float s1, float c,
                             float *lo, float *hi)
{
    float x1 = cr_add(x, cr_mul(s1, u));
    if (acc)
        x1 = cr_add(x1, cr_mul(c, a));
    *lo = cr_min(x, x1);
    *hi = cr_max(x, x1);
    if (acc)
        cr_sweep_turn(x, u, a, s1, lo, hi);
}

void cr_swept_box(const cr_mover *m, float t0, float t1, float margin,
                  cr_box *out)
{
    cr_v2 x0, x1, u;
    float s1 = cr_sub(t1, t0), lo[2], hi[2];
    int k;
    if (m->b->type == CAROM_BODY_STATIC) {
        cr_shape_box(m->s, m->b->x, m->b->q, out);
        out->lo_x = cr_sub(out->lo_x, margin);
        out->lo_y = cr_sub(out->lo_y, margin);
        out->hi_x = cr_add(out->hi_x, margin);
        out->hi_y = cr_add(out->hi_y, margin);
        return;
    }
    if (cr_eq(t0, m->d->t)) {
        /* From the drift's start (the broadphase's boxes: every drift
         * starts the step at 0): the position and speed at t0 are the
         * body's own, and an axis without acceleration is a segment. The
         * same bits as the general case below: that adds only zeros to x
         * and v there (h = 0, or a = 0), which at most flips the sign of a
         * zero, and the margin (e > 0, or a polygon's nonzero box) then
         * adds the same nonzero to either. Measured on a 100-body elastic
         * gas: 89 -> 70 instructions a box (1.5 % of the step). */
        const cr_v2 x = m->b->x, v = m->b->v, a = m->d->a;
        int ax = !cr_eq(a.x, 0.0f), ay = !cr_eq(a.y, 0.0f);
        float c = ax || ay ? cr_mul(0.5f, cr_mul(s1, s1)) : 0.0f;
        cr_sweep_axis(x.x, v.x, a.x, ax, s1, c, &lo[0], &hi[0]);
        cr_sweep_axis(x.y, v.y, a.y, ay, s1, c, &lo[1], &hi[1]);
    } else {
        /* the exact range of the centre's parabola on each axis */
        x0 = cr_position_at(m, t0);
        x1 = cr_position_at(m, t1);
        u = cr_speed_at(m, t0);
        lo[0] = cr_min(x0.x, x1.x); hi[0] = cr_max(x0.x, x1.x);
        lo[1] = cr_min(x0.y, x1.y); hi[1] = cr_max(x0.y, x1.y);
        for (k = 0; k < 2; ++k) {
            float uk = k ? u.y : u.x, ak = k ? m->d->a.y : m->d->a.x;
            if (!cr_eq(ak, 0.0f))
                cr_sweep_turn(k ? x0.y : x0.x, uk, ak, s1, &lo[k], &hi[k]);
        }
    }
    if (CR_KIND_CIRCLE(m->s->kind) || cr_rotates(m)) {
        float e = cr_add(m->s->extent, margin);
        out->lo_x = cr_sub(lo[0], e);
        out->hi_x = cr_add(hi[0], e);
        out->lo_y = cr_sub(lo[1], e);
        out->hi_y = cr_add(hi[1], e);
    } else {
        /* fixed orientation: the shape's own box about its centre */
        cr_box local;
        cr_shape_box(m->s, cr_v(0.0f, 0.0f), m->b->q, &local);
        out->lo_x = cr_sub(cr_add(lo[0], local.lo_x), margin);
        out->hi_x = cr_add(cr_add(hi[0], local.hi_x), margin);
        out->lo_y = cr_sub(cr_add(lo[1], local.lo_y), margin);
        out->hi_y = cr_add(cr_add(hi[1], local.hi_y), margin);
    }
}

void cr_swept_box_until(const cr_mover *m, float t0, float t_mid, float t1,
                        float margin, cr_box *out)
{
    cr_body b;
    cr_drift d;
    cr_mover rest;
    cr_box later;
    if (m->b->type == CAROM_BODY_STATIC || !cr_lt(t_mid, t1)) {
        cr_swept_box(m, t0, t1, margin, out);
        return;
    }
    cr_swept_box(m, t0, t_mid, margin, out);
    b = *m->b;
    d = *m->d;
    cr_pose_at(m->b, m->d, t_mid, &b.x, &b.q);
    cr_velocity_at(m->b, m->d, t_mid, &b.v, &b.w);
    d.t = t_mid;
    if (b.type == CAROM_BODY_DYNAMIC) {
        d.a = b.a;
        d.alpha = b.alpha;
    } else {
        d.a = cr_v(0.0f, 0.0f);
        d.alpha = 0.0f;
    }
    rest.s = m->s;
    rest.b = &b;
    rest.d = &d;
    cr_swept_box(&rest, t_mid, t1, margin, &later);
    out->lo_x = cr_min(out->lo_x, later.lo_x);
    out->lo_y = cr_min(out->lo_y, later.lo_y);
    out->hi_x = cr_max(out->hi_x, later.hi_x);
    out->hi_y = cr_max(out->hi_y, later.hi_y);
}

/* The swept boxes above serve every method (the broadphase); what follows
 * times impacts, for the events methods and the step's continuous guard
 * (continuous.c). */
#if CAROM_ENABLE_EVENTS || CR_CONTINUOUS

static void cr_mover_pose(const cr_mover *m, float t, cr_v2 *x, cr_rot *q)
{
    if (m->b->type == CAROM_BODY_STATIC) {
        *x = m->b->x;
        *q = m->b->q;
        return;
    }
    cr_pose_at(m->b, m->d, t, x, q);
}

/* Relative motion of B w.r.t. A from time t: d(s) = p + u s + q s^2. */
static void cr_relative_motion(const cr_mover *A, const cr_mover *B, float t,
                               cr_v2 *p, cr_v2 *u, cr_v2 *q)
{
    *p = cr_vsub(cr_position_at(B, t), cr_position_at(A, t));
    *u = cr_vsub(cr_speed_at(B, t), cr_speed_at(A, t));
    *q = cr_vscale(0.5f, cr_vsub(B->d->a, A->d->a));
}

int cr_cannot_meet(const cr_mover *A, const cr_mover *B, float t0, float t1,
                   float margin)
{
    cr_v2 p, u, q;
    float h = cr_sub(t1, t0), uu, sc, dist, reach;
    cr_relative_motion(A, B, t0, &p, &u, &q);
    uu = cr_vdot(u, u);
    sc = cr_gt(uu, 0.0f) ? cr_clamp(cr_neg(cr_div(cr_vdot(p, u), uu)), 0.0f, h)
                         : 0.0f;
    dist = cr_sub(cr_vlen(cr_vmadd(p, sc, u)), cr_mul(cr_vlen(q), cr_mul(h, h)));
    reach = cr_add(cr_add(A->s->extent, B->s->extent), margin);
    return cr_gt(dist, reach);
}

/* ---- roots ------------------------------------------------------------------- */

int cr_first_down_root2(float c0, float c1, float c2, float hi, float *out)
{
    float disc, sq, q, r1, r2, lo_r, hi_r;
    if (!cr_finite(c0) || !cr_finite(c1) || !cr_finite(c2) || !cr_finite(hi))
        return 0;
    if (!cr_gt(c0, 0.0f))
        return 0;
    if (cr_eq(c2, 0.0f)) {
        float s;
        if (!cr_lt(c1, 0.0f))
            return 0;
        s = cr_div(c0, cr_neg(c1));
        if (!cr_le(s, hi))
            return 0;
        *out = s;
        return 1;
    }
    disc = cr_sub(cr_mul(c1, c1), cr_mul(cr_mul(4.0f, c2), c0));
    if (!cr_ge(disc, 0.0f))
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
    float a = 0.0f, b = hi, fa = c[0], small, d2, d3, d4;
    for (k = 0; k < 5; ++k)
        if (!cr_finite(c[k]))
            return 0;
    if (!cr_finite(hi) || !cr_gt(hi, 0.0f) || !cr_gt(c[0], 0.0f))
        return 0;
    small = cr_mul(CR_QUARTIC_BRACKET, hi);
    d2 = cr_mul(2.0f, cr_abs(c[2]));
    d3 = cr_mul(6.0f, cr_abs(c[3]));
    d4 = cr_mul(12.0f, cr_abs(c[4]));
    for (it = 0; it < CR_QUARTIC_MAX_EVALS; ++it) {
        float fb = cr_poly4(c, b);
        float m = cr_mul(0.5f, cr_add(a, b)), half = cr_mul(0.5f, cr_sub(b, a));
        /* f'(m) = c1 + 2 c2 m + 3 c3 m^2 + 4 c4 m^3 */
        float dm = cr_add(c[1], cr_mul(m, cr_add(cr_mul(2.0f, c[2]),
                       cr_mul(m, cr_add(cr_mul(3.0f, c[3]), cr_mul(m, cr_mul(4.0f, c[4])))))));
        float f2 = cr_add(d2, cr_mul(b, cr_add(d3, cr_mul(b, d4))));
        float lip = cr_add(cr_abs(dm), cr_mul(half, f2));
        int full = top >= CR_QUARTIC_STACK;
        if (!cr_finite(fb) || !cr_finite(lip))
            break; /* overflow inside the range: stop at what is known */
        if (cr_le(fb, 0.0f) && (cr_le(cr_sub(b, a), small) || full)) {
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
            (cr_gt(cr_sub(fa, cr_mul(lip, cr_sub(b, a))), 0.0f) || full)) {
            if (top == 0)
                return 0;
            a = b;
            fa = fb;
            b = stack[--top];
            continue;
        }
        if (full)
            break;
        stack[top++] = b;
        b = m;
    }
    *out = a; /* out of budget: nothing before a, maybe something after */
    return 1;
}

/* ---- shape pairs -------------------------------------------------------------- */

/* First s in [0, hi] with |p + u s + q s^2| = R, approaching; |p| > R. */
static int cr_toi_point(cr_v2 p, cr_v2 u, cr_v2 q, float R, float hi, float *s)
{
    float len = cr_vlen(p);
    float gap = cr_sub(len, R);
    float c0 = cr_mul(gap, cr_add(len, R)); /* |p|^2 - R^2 without cancelling */
    if (!cr_gt(gap, 0.0f))
        return 0;
    if (!cr_eq(q.x, 0.0f) || !cr_eq(q.y, 0.0f)) {
        float c[5];
        c[0] = c0;
        c[1] = cr_mul(2.0f, cr_vdot(p, u));
        c[2] = cr_add(cr_vdot(u, u), cr_mul(2.0f, cr_vdot(p, q)));
        c[3] = cr_mul(2.0f, cr_vdot(u, q));
        c[4] = cr_vdot(q, q);
        return cr_first_root4(c, hi, s);
    }
    return cr_first_down_root2(c0, cr_mul(2.0f, cr_vdot(p, u)), cr_vdot(u, u), hi, s);
}

/* Fastest normal approach of A and B at local time t over the points of
 * their manifold within `reach`, and the speed scale of the pair. */
float cr_approach_speed(const cr_mover *A, const cr_mover *B, float t,
                            float reach, float *scale, float *recede)
{
    cr_v2 xa, xb, va, vb;
    cr_rot qa, qb;
    float wa, wb, fastest = 0.0f;
    if (recede)
        *recede = 0.0f;
    cr_manifold m;
    int k;
    cr_mover_pose(A, t, &xa, &qa);
    cr_mover_pose(B, t, &xb, &qb);
    cr_velocity_at(A->b, A->d, t, &va, &wa);
    cr_velocity_at(B->b, B->d, t, &vb, &wb);
    if (A->b->type == CAROM_BODY_STATIC) {
        va = cr_v(0.0f, 0.0f);
        wa = 0.0f;
    }
    if (B->b->type == CAROM_BODY_STATIC) {
        vb = cr_v(0.0f, 0.0f);
        wb = 0.0f;
    }
    *scale = cr_add(cr_add(cr_vlen(va), cr_vlen(vb)),
                    cr_add(cr_mul(cr_abs(wa), A->s->extent),
                           cr_mul(cr_abs(wb), B->s->extent)));
    if (!cr_collide(A->s, xa, qa, B->s, xb, qb, reach, 0.0f, 0.0f, &m))
        return 0.0f;
    for (k = 0; k < m.count; ++k) {
        cr_v2 ra = cr_vsub(m.pts[k].p, xa), rb = cr_vsub(m.pts[k].p, xb);
        cr_v2 dv = cr_vsub(cr_vadd(vb, cr_vcross_sv(wb, rb)),
                           cr_vadd(va, cr_vcross_sv(wa, ra)));
        fastest = cr_max(fastest, cr_neg(cr_vdot(dv, m.n)));
        if (recede)
            *recede = k == 0 ? cr_vdot(dv, m.n) : cr_min(*recede, cr_vdot(dv, m.n));
    }
    return fastest;
}

#if CAROM_ENABLE_POLYGONS
/* Gap of a point d(s) against edge i of polygon P (world frame, P's
 * orientation qp fixed, P's centre at the origin of d): first approach
 * within the edge's span. */
static int cr_toi_point_edge(const cr_shape *P, cr_rot qp, int i, cr_v2 p,
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
static int cr_toi_circle_polygon(const cr_mover *P, const cr_mover *C, float t0,
                                 float hi, float *best)
{
    cr_v2 p, u, q, xp;
    cr_rot qp;
    int i, found = 0;
    float s;
    cr_relative_motion(P, C, t0, &p, &u, &q);
    cr_mover_pose(P, t0, &xp, &qp);
    for (i = 0; i < P->s->count; ++i) {
        if (cr_toi_point_edge(P->s, qp, i, p, u, q, C->s->radius, hi, &s) &&
            (!found || cr_lt(s, *best))) {
            *best = s;
            found = 1;
        }
        if (cr_toi_point(cr_vsub(p, cr_rotate(qp, P->s->verts[i])), u, q,
                         C->s->radius, hi, &s) &&
            (!found || cr_lt(s, *best))) {
            *best = s;
            found = 1;
        }
    }
    return found;
}

#if CAROM_ENABLE_POLYGON_POLYGON
/* Vertices of B against edges of A, neither rotating. */
static int cr_toi_vertices_edges(const cr_mover *A, const cr_mover *B, float t0,
                                 float hi, float *best, int found)
{
    cr_v2 p, u, q, xa, xb;
    cr_rot qa, qb;
    int i, j;
    float s;
    cr_relative_motion(A, B, t0, &p, &u, &q);
    cr_mover_pose(A, t0, &xa, &qa);
    cr_mover_pose(B, t0, &xb, &qb);
    for (j = 0; j < B->s->count; ++j) {
        cr_v2 pj = cr_vadd(p, cr_rotate(qb, B->s->verts[j]));
        for (i = 0; i < A->s->count; ++i)
            if (cr_toi_point_edge(A->s, qa, i, pj, u, q, 0.0f, hi, &s) &&
                (!found || cr_lt(s, *best))) {
                *best = s;
                found = 1;
            }
    }
    return found;
}
#endif

static float cr_separation_at(const cr_mover *A, const cr_mover *B, float t)
{
    cr_v2 xa, xb;
    cr_rot qa, qb;
    cr_mover_pose(A, t, &xa, &qa);
    cr_mover_pose(B, t, &xb, &qb);
    return cr_separation(A->s, xa, qa, B->s, xb, qb);
}

/* Conservative advancement: step by separation / closing-speed bound.
 * depth > 0: the pair starts touching on a pivot (a corner a fast-turning
 * polygon turns on), at a separation `base` (0, or below if it starts
 * inside, within an impact's tolerance); until the separation first
 * exceeds depth the search steps by (separation - base + depth) / bound
 * instead, so that no part of the pair passes base - depth unseen. A
 * separation at or below base - depth / 2 is the impact if the pair
 * approaches there (another part of it has come down while the pivot
 * still touched), and the new base if not. Past that, depth is 0. */
static int cr_toi_advance(const cr_mover *A, const cr_mover *B, float t0,
                          float t1, float tol, float depth, float *out)
{
    int it;
    float t = t0, span = cr_sub(t1, t0);
    cr_v2 p, u, q;
    float vrel, wa, wb, vmax, base = 0.0f;
    cr_relative_motion(A, B, t0, &p, &u, &q);
    vrel = cr_add(cr_vlen(u), cr_mul(cr_mul(2.0f, cr_vlen(q)), span));
    wa = cr_add(cr_abs(cr_add(A->b->w, cr_mul(cr_sub(t0, A->d->t), A->d->alpha))),
                cr_mul(cr_abs(A->d->alpha), span));
    wb = cr_add(cr_abs(cr_add(B->b->w, cr_mul(cr_sub(t0, B->d->t), B->d->alpha))),
                cr_mul(cr_abs(B->d->alpha), span));
    if (A->b->type == CAROM_BODY_STATIC)
        wa = 0.0f;
    if (B->b->type == CAROM_BODY_STATIC)
        wb = 0.0f;
    vmax = cr_add(vrel, cr_add(cr_mul(wa, A->s->extent), cr_mul(wb, B->s->extent)));
    if (!cr_gt(vmax, 0.0f) || !cr_finite(vmax))
        return 0;
    for (it = 0; it < CAROM_TOI_MAX_ITERATIONS; ++it) {
        float sep = cr_separation_at(A, B, t);
        if (!cr_finite(sep))
            return 0;
        if (cr_gt(depth, 0.0f) && cr_le(sep, depth)) {
            if (it == 0 && cr_lt(sep, 0.0f))
                base = sep; /* already that deep (an impact's tolerance) */
            if (cr_le(sep, cr_sub(base, cr_mul(0.5f, depth)))) {
                /* something came down while the pivot still touched: an
                 * impact if it approaches; if not, this is the depth to
                 * search past */
                float scale = 0.0f;
                if (cr_gt(cr_approach_speed(A, B, t, cr_mul(2.0f, tol), &scale, 0),
                          cr_mul(CR_APPROACH_REL_TOL, scale))) {
                    *out = cr_sub(t, t0);
                    return 1;
                }
                base = sep;
            }
            /* still on the pivot: step so that nothing can pass
             * base - depth (at least depth / 2 / vmax a step) */
            t = cr_add(t, cr_div(cr_add(cr_sub(sep, base), depth), vmax));
            if (cr_gt(t, t1))
                return 0;
            continue;
        }
        depth = 0.0f;
        if (cr_le(sep, tol)) {
            float scale;
            float approach = cr_approach_speed(A, B, t, cr_mul(2.0f, tol), &scale, 0);
            if (cr_gt(approach, cr_mul(CR_APPROACH_REL_TOL, scale))) {
                *out = cr_sub(t, t0);
                return 1;
            }
            return 0; /* a graze: the contact solver keeps them apart */
        }
        t = cr_add(t, cr_div(sep, vmax));
        if (cr_gt(t, t1))
            return 0;
    }
    /* not converged: the conservative time reached so far; the event loop
     * takes the pair up there, finds it apart and searches on */
    *out = cr_sub(t, t0);
    return CR_TOI_RESUME;
}
#endif /* CAROM_ENABLE_POLYGONS */

/* ---- entry point ----------------------------------------------------------------- */

int cr_time_of_impact(const cr_mover *A, const cr_mover *B, float t0, float t1,
                      float tol, float *toi)
{
    float s = 0.0f, hi = cr_sub(t1, t0);
    int hit = 0;
    if (!cr_gt(hi, 0.0f))
        return 0;
    if (CR_KIND_CIRCLE(A->s->kind) && CR_KIND_CIRCLE(B->s->kind)) {
        cr_v2 p, u, q;
        cr_relative_motion(A, B, t0, &p, &u, &q);
        hit = cr_toi_point(p, u, q, cr_add(A->s->radius, B->s->radius), hi, &s);
    }
#if CAROM_ENABLE_POLYGONS
    else if (cr_rotates(A) || cr_rotates(B)) {
        hit = cr_toi_advance(A, B, t0, t1, tol, 0.0f, &s);
    } else if (A->s->kind == CAROM_SHAPE_POLYGON && B->s->kind == CAROM_SHAPE_CIRCLE) {
        hit = cr_toi_circle_polygon(A, B, t0, hi, &s);
    } else if (A->s->kind == CAROM_SHAPE_CIRCLE) {
        hit = cr_toi_circle_polygon(B, A, t0, hi, &s);
    } else {
#if CAROM_ENABLE_POLYGON_POLYGON
        hit = cr_toi_vertices_edges(A, B, t0, hi, &s, 0);
        hit = cr_toi_vertices_edges(B, A, t0, hi, &s, hit);
#endif
    }
#else
    (void)tol;
#endif
    if (hit)
        *toi = cr_add(t0, s);
    return hit;
}

int cr_time_of_impact_pivot(const cr_mover *A, const cr_mover *B, float t0, float t1,
                            float tol, float depth, float *toi)
{
    float s = 0.0f;
    int hit = 0;
    if (!cr_gt(cr_sub(t1, t0), 0.0f))
        return 0;
#if CAROM_ENABLE_POLYGONS
    if (cr_rotates(A) || cr_rotates(B))
        hit = cr_toi_advance(A, B, t0, t1, tol, depth, &s);
#else
    (void)A;
    (void)B;
    (void)tol;
    (void)depth;
#endif
    if (hit)
        *toi = cr_add(t0, s);
    return hit;
}

#else
/* ISO C forbids an empty translation unit */
typedef int cr_toi_disabled;
#endif /* CAROM_ENABLE_EVENTS || CR_CONTINUOUS */
