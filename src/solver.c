/*
 * solver.c -- contact impulses.
 *
 * Velocities: sequential impulses (projected Gauss-Seidel) on every contact
 * point, with accumulated impulses clamped to >= 0 (normal) and to the
 * Coulomb cone |pt| <= mu pn (friction). Each point aims for the Newton
 * restitution law
 *
 *     vn+ = -e vn-      if the approach speed -vn- exceeds rest_speed,
 *     vn+ >= 0          otherwise (resting contact),
 *
 * where vn- is the relative normal velocity before the solve. For a single
 * head-on contact one sweep gives exactly the 1D formula of the design
 * note, corrected as in ERRATA.md 1-2:
 *     P = (1 + e) (-vn-) / (1/m_a + 1/m_b + angular terms).
 * Impulses are warm-started from the last step's when the same features
 * touch, so a resting stack starts each step from its converged forces and
 * does not jitter.
 *
 * The two points of a face contact are coupled through rotation: pushing
 * one end of a box changes the velocity at the other end. Solving them one
 * after the other converges slowly (a box rocks on its support). So the
 * normal impulses of a 2-point manifold are solved together, exactly, as
 * the 2x2 linear complementarity problem
 *     x >= 0,  K x + b >= 0,  x_i (K x + b)_i = 0,
 * by trying its four cases (both points pushing, only one, none).
 *
 * Positions: the drift of a step moves a resting body into its support by
 * |g| dt^2 / 2; a projection (nonlinear Gauss-Seidel on the linearised
 * separations) removes a fraction CAROM_POSITION_BETA of each remaining
 * overlap per sweep, without touching velocities, so no energy is added.
 *
 * Mixing: e = max(e_a, e_b) and mu = sqrt(mu_a mu_b), as Box2D does, so the
 * two engines can be compared on identical scenes.
 */
#include "internal.h"

/* Smallest det(K) / (k11 k22) for which a 2-point manifold is solved as a
 * block (1 - cos^2 of the angle between the two points' impulse rows). */
#define CR_BLOCK_MIN_DET 1.0e-3f

/* Approach speed at the start of a step, as a fraction of rest_speed, below
 * which a contact counts as having been at rest (solver residue). */
#define CR_REST_TOL_FRACTION 0.01f

/* Gauss-Seidel visits of a single impact (events method): the normal part
 * is exact after one, friction and the normal/tangent coupling converge in
 * a few. */
#define CR_IMPACT_ITERATIONS 4

static cr_v2 cr_tangent(cr_v2 n) { return cr_v(n.y, cr_neg(n.x)); }

/* 1 / (1/m_a + 1/m_b + ra_x^2 / I_a + rb_x^2 / I_b) for lever arms
 * ra_x = ra x dir, rb_x = rb x dir. */
static float cr_effective_mass(const cr_body *A, const cr_body *B, float rla,
                               float rlb)
{
    float k = cr_add(cr_add(A->inv_m, B->inv_m),
                     cr_add(cr_mul(A->inv_I, cr_mul(rla, rla)),
                            cr_mul(B->inv_I, cr_mul(rlb, rlb))));
    return cr_gt(k, 0.0f) ? cr_div(1.0f, k) : 0.0f;
}

/* Lever arm of an impulse along dir at r from the centre of b: r x dir,
 * except for the normal of a circle, where it is 0 by geometry (rounding
 * would otherwise spin every circle a little at every impact). */
static float cr_lever(const cr_body *b, cr_v2 r, cr_v2 dir, int normal)
{
    if (normal && b->shape == CAROM_SHAPE_CIRCLE)
        return 0.0f;
    return cr_vcross(r, dir);
}

/* Relative velocity of B's material point at rb w.r.t. A's at ra. */
static cr_v2 cr_relative_velocity(const cr_body *A, const cr_body *B,
                                  cr_v2 ra, cr_v2 rb)
{
    cr_v2 vb = cr_vadd(B->vel, cr_vcross_sv(B->w, rb));
    cr_v2 va = cr_vadd(A->vel, cr_vcross_sv(A->w, ra));
    return cr_vsub(vb, va);
}

/* Impulse d along dir at a point with lever arms rla, rlb: -d on A, +d on B. */
static void cr_apply(cr_body *A, cr_body *B, float rla, float rlb, cr_v2 dir,
                     float d)
{
    cr_v2 P = cr_vscale(d, dir);
    A->vel = cr_vmadd(A->vel, cr_neg(A->inv_m), P);
    B->vel = cr_vmadd(B->vel, B->inv_m, P);
#if CAROM_ENABLE_ROTATION
    A->w = cr_sub(A->w, cr_mul(A->inv_I, cr_mul(rla, d)));
    B->w = cr_add(B->w, cr_mul(B->inv_I, cr_mul(rlb, d)));
#else
    (void)rla;
    (void)rlb;
#endif
}

/*
 * Which share of a non-bouncing point's impulse is a resting force, to be
 * carried into the next drift (cr_solver_store)? The approach speed the
 * solver cancels has two sources: motion the bodies already had at the
 * start of the step (an impact: the impulse stops it once), and the kick
 * the step's own forces gave them (a force: it acts again next step). With
 * approach = -vn0 after the kick and before = the approach at the start of
 * the step, the share is 1 - before / approach. A body at rest in a stack
 * has before ~ 0 (solver residue below CR_REST_TOL_FRACTION of rest_speed
 * counts as 0) and share 1; a ball landing softly at 0.4 m/s under gravity
 * has share |g| dt / 0.4, so the force it keeps is its weight, not more.
 */
static float cr_resting_fraction(const cr_body *A, const cr_body *B,
                                 const cr_point *p, cr_v2 n, float rest_speed)
{
    cr_v2 vb = cr_vadd(B->vel_saved, cr_vcross_sv(B->w_saved, p->rb));
    cr_v2 va = cr_vadd(A->vel_saved, cr_vcross_sv(A->w_saved, p->ra));
    float before = cr_neg(cr_vdot(cr_vsub(vb, va), n));
    float approach = cr_neg(p->vn0);
    if (cr_le(before, cr_mul(CR_REST_TOL_FRACTION, rest_speed)) ||
        cr_le(approach, 0.0f))
        return 1.0f;
    return cr_max(0.0f, cr_sub(1.0f, cr_div(before, approach)));
}

/*
 * Approach speed along n at ra, rb at the END of a step, with last step's
 * resting contact forces applied to the velocities as they were to the
 * positions (the drift).
 * The velocities the solver sees leave those forces out, because the solver
 * applies them itself as impulses; but the approach they cancel is not
 * motion: a box resting on the ground "approaches" it at |g| dt at the end
 * of every step, which is no impact however large dt is. A body that was
 * not resting (no force) keeps its whole approach.
 */
static float cr_held(const cr_body *A, const cr_body *B, cr_v2 ra, cr_v2 rb,
                     cr_v2 n, float dt)
{
    cr_v2 ab = cr_vadd(B->acc_c, cr_vcross_sv(B->alpha_c, rb));
    cr_v2 aa = cr_vadd(A->acc_c, cr_vcross_sv(A->alpha_c, ra));
    return cr_mul(cr_vdot(cr_vsub(ab, aa), n), dt);
}

float cr_effective_approach(const cr_body *A, const cr_body *B, cr_v2 ra,
                            cr_v2 rb, cr_v2 n, float dt)
{
    return cr_sub(cr_neg(cr_vdot(cr_relative_velocity(A, B, ra, rb), n)),
                  cr_held(A, B, ra, rb, n, dt));
}

/*
 * Approach speed at the instant of contact. The overlap-based step finds
 * an impact only after the bodies have moved a depth d = -sep past it,
 * still accelerating towards each other at a_close, so the speed at the
 * end of the step is too high: v^2 = v_c^2 + 2 a_close d. Bouncing with
 * e v instead of e v_c, and then being projected out of the overlap, would
 * pump energy in (a ball with e = 0.8 hops forever at ~0.5 m/s). With v_c
 * the kinetic energy after the bounce is exactly (e v_c)^2 m / 2.
 */
static float cr_contact_speed(const cr_body *A, const cr_body *B,
                              const cr_point *p, cr_v2 n, float dt,
                              int step_end)
{
    /* at the end of a step the velocities leave last step's resting forces
     * out (the solver re-applies them); inside it, at an impact, a body's
     * velocity on its drift already includes them */
    float v = step_end ? cr_sub(cr_neg(p->vn0), cr_held(A, B, p->ra, p->rb, n, dt))
                       : cr_neg(p->vn0);
    float depth = cr_neg(p->sep), a_close, v2;
    cr_v2 ab, aa;
    if (!cr_gt(v, 0.0f))
        return 0.0f;
    if (!cr_gt(depth, 0.0f))
        return v;
    ab = cr_vadd(B->acc, cr_vcross_sv(B->alpha, p->rb));
    aa = cr_vadd(A->acc, cr_vcross_sv(A->alpha, p->ra));
    a_close = cr_max(0.0f, cr_neg(cr_vdot(cr_vsub(ab, aa), n)));
    v2 = cr_sub(cr_mul(v, v), cr_mul(cr_mul(2.0f, a_close), depth));
    return cr_gt(v2, 0.0f) ? cr_sqrt(v2) : 0.0f;
}

/* Copy last step's accumulated impulses onto points with the same ids.
 * Both manifold arrays are sorted by (a, b), so one merge walk suffices. */
static void cr_match_previous(carom_world *w)
{
    int i, j = 0;
    for (i = 0; i < w->manifold_count; ++i) {
        cr_manifold *m = &w->manifolds[i];
        int k, l;
        while (j < w->prev_manifold_count &&
               (w->prev_manifolds[j].a < m->a ||
                (w->prev_manifolds[j].a == m->a &&
                 w->prev_manifolds[j].b < m->b)))
            ++j;
        if (j >= w->prev_manifold_count || w->prev_manifolds[j].a != m->a ||
            w->prev_manifolds[j].b != m->b)
            continue;
        for (k = 0; k < m->count; ++k)
            for (l = 0; l < w->prev_manifolds[j].count; ++l)
                if (w->prev_manifolds[j].pts[l].id == m->pts[k].id) {
                    m->pts[k].pn = w->prev_manifolds[j].pts[l].pn;
                    m->pts[k].pt = w->prev_manifolds[j].pts[l].pt;
                }
    }
}

/* resting_only: every point aims for vn >= 0 (no restitution); used to
 * find the resting contact forces of a state (world.c, priming). */
/* Mixing, anchors, effective masses, pre-solve velocities and targets of
 * one manifold. */
static void cr_prepare_manifold(carom_world *w, cr_manifold *m,
                                int resting_only, int step_end)
{
    int k;
    float rest = w->def.rest_speed;
    cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
    cr_v2 t = cr_tangent(m->n);
    m->restitution = cr_max(A->restitution, B->restitution);
#if CAROM_ENABLE_FRICTION
    m->friction = cr_sqrt(cr_mul(A->friction, B->friction));
#else
    m->friction = 0.0f;
#endif
    for (k = 0; k < m->count; ++k) {
        cr_point *p = &m->pts[k];
        p->ra = cr_vsub(p->p, A->x);
        p->rb = cr_vsub(p->p, B->x);
        p->rna = cr_lever(A, p->ra, m->n, 1);
        p->rnb = cr_lever(B, p->rb, m->n, 1);
        p->rta = cr_lever(A, p->ra, t, 0);
        p->rtb = cr_lever(B, p->rb, t, 0);
        p->mass_n = cr_effective_mass(A, B, p->rna, p->rnb);
        p->mass_t = cr_effective_mass(A, B, p->rta, p->rtb);
        p->vn0 = cr_vdot(cr_relative_velocity(A, B, p->ra, p->rb), m->n);
        p->approach = cr_contact_speed(A, B, p, m->n, w->def.dt, step_end);
        p->target = !resting_only && cr_gt(p->approach, rest)
                        ? cr_mul(m->restitution, p->approach)
                        : 0.0f;
        p->rest_frac = cr_gt(p->target, 0.0f)
                           ? 0.0f
                           : cr_resting_fraction(A, B, p, m->n, rest);
    }
    m->block = 0;
    if (m->count == 2) {
        float r1a = m->pts[0].rna, r1b = m->pts[0].rnb;
        float r2a = m->pts[1].rna, r2b = m->pts[1].rnb;
        float lin = cr_add(A->inv_m, B->inv_m);
        float det;
        m->k11 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r1a, r1a)),
                                    cr_mul(B->inv_I, cr_mul(r1b, r1b))));
        m->k22 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r2a, r2a)),
                                    cr_mul(B->inv_I, cr_mul(r2b, r2b))));
        m->k12 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r1a, r2a)),
                                    cr_mul(B->inv_I, cr_mul(r1b, r2b))));
        /* points too close together make K near singular: then solve
         * them one after the other */
        det = cr_sub(cr_mul(m->k11, m->k22), cr_mul(m->k12, m->k12));
        m->block = cr_gt(det, cr_mul(CR_BLOCK_MIN_DET, cr_mul(m->k11, m->k22)));
    }
}

static void cr_warm_start(carom_world *w, const cr_manifold *m)
{
    int k;
    cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
    cr_v2 t = cr_tangent(m->n);
    for (k = 0; k < m->count; ++k) {
        const cr_point *p = &m->pts[k];
        if (!cr_eq(p->pn, 0.0f))
            cr_apply(A, B, p->rna, p->rnb, m->n, p->pn);
        if (!cr_eq(p->pt, 0.0f))
            cr_apply(A, B, p->rta, p->rtb, t, p->pt);
    }
}

void cr_solver_prepare(carom_world *w, int resting_only)
{
    int i, k;
    for (i = 0; i < w->manifold_count; ++i) {
        cr_manifold *m = &w->manifolds[i];
        for (k = 0; k < m->count; ++k) {
            m->pts[k].pn = 0.0f;
            m->pts[k].pt = 0.0f;
        }
    }
    cr_match_previous(w);
    for (i = 0; i < w->manifold_count; ++i)
        cr_prepare_manifold(w, &w->manifolds[i], resting_only, 1);
    /* warm start only now: every vn0 above is a pre-solve velocity */
    for (i = 0; i < w->manifold_count; ++i)
        cr_warm_start(w, &w->manifolds[i]);
}

/*
 * The 2x2 linear complementarity problem of a 2-point manifold:
 *     find x >= 0 with r = K x + b >= 0 and x_i r_i = 0,
 * K = [k11 k12; k12 k22] symmetric positive definite. Tries the four cases
 * in turn (both points active, only the first, only the second, none).
 * Returns 0 if none fits, which only rounding at a degenerate K can cause.
 */
static int cr_lcp2(const cr_manifold *m, float b1, float b2, float *x1,
                   float *x2)
{
    float det = cr_sub(cr_mul(m->k11, m->k22), cr_mul(m->k12, m->k12));
    float y1 = cr_div(cr_sub(cr_mul(m->k12, b2), cr_mul(m->k22, b1)), det);
    float y2 = cr_div(cr_sub(cr_mul(m->k12, b1), cr_mul(m->k11, b2)), det);
    if (cr_ge(y1, 0.0f) && cr_ge(y2, 0.0f)) {
        *x1 = y1;
        *x2 = y2;
        return 1;
    }
    y1 = cr_div(cr_neg(b1), m->k11);
    if (cr_ge(y1, 0.0f) && cr_ge(cr_add(cr_mul(m->k12, y1), b2), 0.0f)) {
        *x1 = y1;
        *x2 = 0.0f;
        return 1;
    }
    y2 = cr_div(cr_neg(b2), m->k22);
    if (cr_ge(y2, 0.0f) && cr_ge(cr_add(cr_mul(m->k12, y2), b1), 0.0f)) {
        *x1 = 0.0f;
        *x2 = y2;
        return 1;
    }
    if (cr_ge(b1, 0.0f) && cr_ge(b2, 0.0f)) {
        *x1 = 0.0f;
        *x2 = 0.0f;
        return 1;
    }
    return 0;
}

/* Normal impulses of a 2-point manifold, solved together. With accumulated
 * impulses a and new ones x, the velocity residual is K x + b with
 * b = vn - target - K a. Returns 0 to ask for the one-at-a-time fallback. */
static int cr_block_normal(cr_manifold *m, cr_body *A, cr_body *B)
{
    cr_point *p1 = &m->pts[0], *p2 = &m->pts[1];
    float a1 = p1->pn, a2 = p2->pn, x1, x2, b1, b2;
    float vn1 = cr_vdot(cr_relative_velocity(A, B, p1->ra, p1->rb), m->n);
    float vn2 = cr_vdot(cr_relative_velocity(A, B, p2->ra, p2->rb), m->n);
    b1 = cr_sub(cr_sub(vn1, p1->target),
                cr_add(cr_mul(m->k11, a1), cr_mul(m->k12, a2)));
    b2 = cr_sub(cr_sub(vn2, p2->target),
                cr_add(cr_mul(m->k12, a1), cr_mul(m->k22, a2)));
    if (!cr_lcp2(m, b1, b2, &x1, &x2))
        return 0;
    p1->pn = x1;
    p2->pn = x2;
    cr_apply(A, B, p1->rna, p1->rnb, m->n, cr_sub(x1, a1));
    cr_apply(A, B, p2->rna, p2->rnb, m->n, cr_sub(x2, a2));
    return 1;
}

/* One Gauss-Seidel visit of a manifold: friction, then normal impulses. */
static void cr_solve_manifold(carom_world *w, cr_manifold *m)
{
    int k;
    cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
#if CAROM_ENABLE_FRICTION
    if (cr_gt(m->friction, 0.0f)) {
        cr_v2 t = cr_tangent(m->n);
        for (k = 0; k < m->count; ++k) {
            cr_point *p = &m->pts[k];
            float vt = cr_vdot(cr_relative_velocity(A, B, p->ra, p->rb), t);
            float limit = cr_mul(m->friction, p->pn);
            float pt = cr_clamp(cr_sub(p->pt, cr_mul(p->mass_t, vt)),
                                cr_neg(limit), limit);
            float d = cr_sub(pt, p->pt);
            p->pt = pt;
            cr_apply(A, B, p->rta, p->rtb, t, d);
        }
    }
#endif
    if (m->block && cr_block_normal(m, A, B))
        return;
    for (k = 0; k < m->count; ++k) {
        cr_point *p = &m->pts[k];
        float vn = cr_vdot(cr_relative_velocity(A, B, p->ra, p->rb), m->n);
        float pn = cr_max(cr_sub(p->pn, cr_mul(p->mass_n, cr_sub(vn, p->target))),
                          0.0f);
        float d = cr_sub(pn, p->pn);
        p->pn = pn;
        cr_apply(A, B, p->rna, p->rnb, m->n, d);
    }
}

void cr_solver_velocities(carom_world *w, int iterations)
{
    int it, j;
    for (it = 0; it < iterations; ++it) {
        for (j = 0; j < w->manifold_count; ++j) {
            /* symmetric Gauss-Seidel: odd sweeps run backwards, so a push
             * travels up a stack as fast as down it */
            int i = (it & 1) ? w->manifold_count - 1 - j : j;
            cr_solve_manifold(w, &w->manifolds[i]);
        }
    }
}

/*
 * One impact of the events method: the manifold of a pair at the instant
 * its surfaces meet, solved alone from zero impulses (the block solve makes
 * a 2-point impact exact in one visit; further visits settle friction).
 * Returns the total normal impulse; *approach gets the approach speed.
 */
float cr_solver_impact(carom_world *w, cr_manifold *m, float *approach)
{
    int it, k, iterations;
    float total = 0.0f, fastest = 0.0f;
    for (k = 0; k < m->count; ++k) {
        m->pts[k].pn = 0.0f;
        m->pts[k].pt = 0.0f;
    }
    cr_prepare_manifold(w, m, 0, 0);
    /* without friction the first visit is already exact */
    iterations = cr_gt(m->friction, 0.0f) ? CR_IMPACT_ITERATIONS : 1;
    for (it = 0; it < iterations; ++it)
        cr_solve_manifold(w, m);
    for (k = 0; k < m->count; ++k) {
        total = cr_add(total, m->pts[k].pn);
        fastest = cr_max(fastest, m->pts[k].approach);
    }
    *approach = fastest;
    return total;
}

/* Separation of point p now, from its separation at detection and the
 * projection moves of both bodies so far (linearised in the rotation). */
static float cr_current_sep(const cr_manifold *m, const cr_point *p,
                            const cr_body *A, const cr_body *B)
{
    cr_v2 db = cr_vadd(B->dx, cr_vcross_sv(B->dtheta, p->rb));
    cr_v2 da = cr_vadd(A->dx, cr_vcross_sv(A->dtheta, p->ra));
    return cr_add(p->sep, cr_vdot(m->n, cr_vsub(db, da)));
}

static void cr_move(cr_body *A, cr_body *B, const cr_point *p, cr_v2 n,
                    float d)
{
    cr_v2 P = cr_vscale(d, n);
    A->dx = cr_vmadd(A->dx, cr_neg(A->inv_m), P);
    B->dx = cr_vmadd(B->dx, B->inv_m, P);
#if CAROM_ENABLE_ROTATION
    A->dtheta = cr_sub(A->dtheta, cr_mul(A->inv_I, cr_mul(p->rna, d)));
    B->dtheta = cr_add(B->dtheta, cr_mul(B->inv_I, cr_mul(p->rnb, d)));
#else
    (void)p;
#endif
}

/* The correction a point asks for: a fraction beta of its overlap, capped;
 * zero when separated. */
static float cr_correction(float sep)
{
    if (!cr_lt(sep, 0.0f))
        return 0.0f;
    return cr_max(cr_mul(CAROM_POSITION_BETA, sep),
                  cr_neg(CAROM_MAX_LINEAR_CORRECTION));
}

void cr_solver_positions(carom_world *w)
{
    int it, i, j, k;

    for (i = 0; i < w->body_count; ++i) {
        w->bodies[i].dx = cr_v(0.0f, 0.0f);
        w->bodies[i].dtheta = 0.0f;
    }
    for (it = 0; it < w->def.position_iterations; ++it) {
        for (j = 0; j < w->manifold_count; ++j) {
            int i = (it & 1) ? w->manifold_count - 1 - j : j;
            cr_manifold *m = &w->manifolds[i];
            cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
            if (m->block) {
                /* both points at once, so a symmetric overlap is removed
                 * without tilting the body */
                float c1 = cr_correction(cr_current_sep(m, &m->pts[0], A, B));
                float c2 = cr_correction(cr_current_sep(m, &m->pts[1], A, B));
                float x1, x2;
                if (cr_eq(c1, 0.0f) && cr_eq(c2, 0.0f))
                    continue;
                if (cr_lcp2(m, c1, c2, &x1, &x2)) {
                    cr_move(A, B, &m->pts[0], m->n, x1);
                    cr_move(A, B, &m->pts[1], m->n, x2);
                    continue;
                }
            }
            for (k = 0; k < m->count; ++k) {
                cr_point *p = &m->pts[k];
                float c = cr_correction(cr_current_sep(m, p, A, B));
                if (cr_eq(c, 0.0f))
                    continue;
                cr_move(A, B, p, m->n, cr_neg(cr_mul(p->mass_n, c)));
            }
        }
    }
    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        b->x = cr_vadd(b->x, b->dx);
        b->q = cr_rot_advance(b->q, b->dtheta);
    }
}

/*
 * Keep this step's manifolds (and impulses) for warm starting the next, and
 * turn the resting share of each point's impulse (cr_resting_fraction) into
 * the constant contact accelerations the next drift uses: a resting
 * contact's impulse over a step is its force times dt.
 */
void cr_solver_store(carom_world *w)
{
    int i, k;
    float inv_dt = cr_div(1.0f, w->def.dt);
    for (i = 0; i < w->body_count; ++i) {
        w->bodies[i].acc_c = cr_v(0.0f, 0.0f);
        w->bodies[i].alpha_c = 0.0f;
    }
    for (i = 0; i < w->manifold_count; ++i) {
        cr_manifold *m = &w->manifolds[i];
        cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
        cr_v2 t = cr_tangent(m->n);
        for (k = 0; k < m->count; ++k) {
            cr_point *p = &m->pts[k];
            cr_v2 F;
            float scale, fn, ft;
            if (cr_eq(p->rest_frac, 0.0f))
                continue; /* an impact, not a resting force */
            scale = cr_mul(inv_dt, p->rest_frac);
            fn = cr_mul(scale, p->pn);
            ft = cr_mul(scale, p->pt);
            F = cr_vadd(cr_vscale(fn, m->n), cr_vscale(ft, t));
            A->acc_c = cr_vmadd(A->acc_c, cr_neg(A->inv_m), F);
            B->acc_c = cr_vmadd(B->acc_c, B->inv_m, F);
#if CAROM_ENABLE_ROTATION
            /* torque: the lever arms times the force components */
            A->alpha_c = cr_sub(A->alpha_c, cr_mul(A->inv_I, cr_add(cr_mul(p->rna, fn),
                                                                    cr_mul(p->rta, ft))));
            B->alpha_c = cr_add(B->alpha_c, cr_mul(B->inv_I, cr_add(cr_mul(p->rnb, fn),
                                                                    cr_mul(p->rtb, ft))));
#endif
        }
    }

    {
    cr_manifold *t = w->prev_manifolds;
    w->prev_manifolds = w->manifolds;
    w->prev_manifold_count = w->manifold_count;
    w->manifolds = t;
    w->manifold_count = 0;
    }
}
