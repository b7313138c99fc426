/*
 * solver.c -- the contact solver: substeps of sequential impulses, with
 * overlap removed on positions only, on velocity Verlet.
 *
 * A step is cut into substeps of length h. In each, for the contacts the
 * solver takes:
 *   1. kick: v += a h (the forces), then re-apply the impulses accumulated
 *      so far (warm start: at rest they are exactly the weight);
 *   2. velocity sweeps: sequential impulses on accumulated impulses clamped
 *      to >= 0, with Coulomb friction (|pt| <= mu pn per point). The
 *      target is vn >= 0 at a touching point; a point still apart may close
 *      exactly its gap in the substep (speculative), which is what stops a
 *      thin rod's far end on a thin floor, however fast it sweeps;
 *   3. move: every body drifts over the substep, from its start velocity to
 *      the solved one at constant acceleration (events.c takes the impacts
 *      at their instants inside this motion);
 *   4. position sweep: what overlap is left is removed, a fraction
 *      CAROM_POSITION_CORRECTION per substep, by moving positions along
 *      pseudo-velocities that are then dropped: no momentum is added, so
 *      overlap recovery never turns into bounce;
 *   5. relax sweeps: velocity sweeps again, after the move.
 * After the last substep a restitution pass (Box2D v3's, iterated to
 * convergence here) bounces the points the solver stopped that were hit
 * faster than the rest speed: every impact of the discrete method; in the
 * events methods, which take their impacts at their instants, only what the
 * solver stopped (a toppling rod's far end, the substeps past the impact
 * budget).
 *
 * This is Box2D v3's "soft step" with its push-out replaced by Box2D 2.4's
 * split position correction. The soft constraint of v3 is a stiff spring:
 * under a load W it settles W / (m w^2) deep, so a stack sinks by that much
 * per box of load above each contact (11 cm for 40 boxes at 30 Hz); and a
 * rigid push-out through the velocities, undamped, rings in tall stacks
 * because one sweep cannot take the push-out velocity back out of them.
 * The split correction has neither fault: at rest the warm-started
 * impulses are exact and the overlap goes to zero.
 *
 * The drift of step 3 is the trapezoid x += h (v0 + v1) / 2: for free
 * flight it is velocity Verlet exactly, and for a resting body (v0 = v1 = 0)
 * it moves nothing, so a stack at rest reports zero velocity and stays put.
 * So the speculative target closes the gap with the substep's mean
 * velocity: s + h (vn0 + vn) / 2 = 0, i.e. vn = -(2 s / h + vn0), never a
 * bounce.
 *
 * Anchors, normals and effective masses are those of the step start; the
 * separation is updated from the bodies' displacements dp and rotations
 * dq since then: s = base_sep + n . (dp_b + dq_b rb - dp_a - dq_a ra),
 * where a circle's dq is the identity (cr_anchor_turn: its contact point
 * is where its surface faces the other body, not a material point). The
 * two points of a face contact are coupled through rotation, so their
 * normal impulses are solved together, as the 2x2 complementarity problem
 * (Box2D 2.4's block solver): a box rests and rises level. Contacts with a
 * static or kinematic body are swept last, so their solve has the last
 * word: a light box under a heavy one is not pushed into the floor.
 */
#include "solver.h"

void cr_substep_init(cr_substep *s, const carom_world *w, float h)
{
    s->h = h;
    s->inv_h = cr_div(1.0f, h);
    s->push = w->scale.push;
    s->t = 0.0f;
}

#if CAROM_SOFT_DEEP_CONTACTS
static void cr_mark_mixed(carom_world *w);
#endif

void cr_solver_begin(carom_world *w)
{
    int i;
    for (i = 0; i < w->slot_count; ++i) {
        cr_solver_body *sb = &w->sbody[i];
        sb->dp = cr_v(0.0f, 0.0f);
        sb->dq = cr_rot_identity();
        sb->v0 = w->bodies[i].v;
        sb->w0 = w->bodies[i].w;
        sb->vp = cr_v(0.0f, 0.0f);
        sb->wp = 0.0f;
        sb->active = 0;
        sb->held = 0;
        sb->keep = 0;
#if CAROM_SOFT_DEEP_CONTACTS
        sb->mixed = 0;
#endif
    }
    w->active_count = 0;
#if CAROM_SOFT_DEEP_CONTACTS
    cr_mark_mixed(w);
#endif
}

void cr_solver_activate(carom_world *w, int i)
{
    /* static and sleeping bodies never move */
    if (w->bodies[i].type == CAROM_BODY_STATIC || !(w->bodies[i].flags & CR_BODY_AWAKE) ||
        w->sbody[i].active)
        return;
    w->sbody[i].active = 1;
    w->active[w->active_count++] = i;
}

float cr_rest_speed(const carom_world *w, int a, int b)
{
    const cr_body *A = &w->bodies[a], *B = &w->bodies[b];
    float acc;
    if (!cr_lt(w->def.rest_speed, 0.0f))
        return w->def.rest_speed;
    acc = cr_max(cr_vlen(A->a), cr_vlen(B->a));
    return cr_mul(cr_mul(CAROM_REST_SPEED_PER_ACCEL_DT, acc), w->def.dt);
}

static int cr_moves(const cr_body *b)
{
    return b->type != CAROM_BODY_STATIC;
}

/* The sweeps' pass of contact c: 0 between dynamic bodies, 1 with a
 * kinematic body, 2 with a static one. Static contacts come last, so
 * they have the last word: a body a kinematic piston crushes against a
 * static wall stays at the wall's face, where the piston, solved last,
 * pushed it into the wall at its own speed until the far face pushed it
 * out (walls thicker than the body's step). */
static int cr_grounded(const carom_world *w, const cr_contact *c)
{
    int ta = w->bodies[c->a].type, tb = w->bodies[c->b].type;
    if (ta == CAROM_BODY_STATIC || tb == CAROM_BODY_STATIC)
        return 2;
    return ta != CAROM_BODY_DYNAMIC || tb != CAROM_BODY_DYNAMIC;
}

/* Separation of point p now, from the bodies' motion since the step start. */
CR_INLINE float cr_current_sep(const cr_contact *c, const cr_contact_point *p,
                            const cr_solver_body *sa, const cr_solver_body *sb)
{
    cr_v2 d = cr_vadd(cr_vsub(sb->dp, sa->dp),
                      cr_vsub(cr_rotate(sb->dq, p->rb), cr_rotate(sa->dq, p->ra)));
    return cr_add(p->base_sep, cr_vdot(c->n, d));
}

float cr_contact_approach(const carom_world *w, const cr_contact *c)
{
    const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    float fastest = 0.0f, sep[CR_MANIFOLD_POINTS];
    int k, touching = 0;
    /* if some point touches, only the touching points count: the far end
     * of a rod toppling about its other end is a speculative point, which
     * the solver stops where it meets, not an impact of the pair */
    for (k = 0; k < c->count; ++k) {
        sep[k] = cr_current_sep(c, &c->pts[k], sa, sb);
        touching |= cr_le(sep[k], w->scale.spec);
    }
    for (k = 0; k < c->count; ++k) {
        const cr_contact_point *p = &c->pts[k];
        cr_v2 dv;
        if (touching && cr_gt(sep[k], w->scale.spec))
            continue;
        dv = cr_vsub(cr_point_velocity(B->v, B->w, p->rb),
                     cr_point_velocity(A->v, A->w, p->ra));
        fastest = cr_max(fastest, cr_neg(cr_vdot(dv, c->n)));
    }
    return fastest;
}

float cr_contact_recede(const carom_world *w, const cr_contact *c)
{
    const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    float slowest = 0.0f;
    int k, touching = 0;
    for (k = 0; k < c->count; ++k) {
        const cr_contact_point *p = &c->pts[k];
        float vn;
        if (cr_gt(cr_current_sep(c, p, sa, sb), w->scale.spec))
            continue;
        vn = cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, p->rb),
                             cr_point_velocity(A->v, A->w, p->ra)),
                     c->n);
        slowest = touching ? cr_min(slowest, vn) : vn;
        touching = 1;
    }
    return slowest;
}

/* Largest turn of a polygon in a step (rad) for which the contact solver
 * takes its new contacts in the events methods. The solver follows the
 * anchor points of the step's start, turned with the body: a polygon that
 * turns further than about half the angle between its corners brings
 * another corner forward, which the solver does not see (a 5 cm octagon
 * at 11312 rad/s, 7.5 turns a step, went through a 2 m wall). Such a
 * contact is left to the impact search, whose conservative advancement
 * follows the turn. */
#define CR_SOLVER_MAX_TURN 0.25f

static int cr_turns_fast(const carom_world *w, const cr_body *b)
{
    return !CR_BODY_IS_CIRCLE(b) &&
           cr_gt(cr_mul(cr_abs(b->w), w->def.dt), CR_SOLVER_MAX_TURN);
}

/*
 * Events methods: an inelastic meeting on a resting body is the solver's,
 * as in the discrete method, not an impact taken at its instant (unless
 * built with CAROM_EXACT_PILE_IMPACTS). Contact c joins two dynamic bodies
 * of like masses (within CR_ONTO_REST_MASS_RATIO), its restitution is 0,
 * one of its bodies rests on another (CR_BODY_RESTS: a body landing on a
 * pile, a pile body pushed into its neighbour), neither turns fast, and
 * it closes at most CR_ONTO_REST_REACH of the smaller body's half width in
 * a step (the manifold of the step's start still holds at the meeting).
 * There the instant changes little an impact would keep: no bounce to
 * time, and what the body pushes spreads through resting contacts, which
 * are the solver's anyway; at the end of the substep the speculative
 * contact leaves the bodies touching and closing no more, as the impact
 * would, though friction and turn during the landing substep are the
 * solver's (a box dropped 0.5 m onto a resting box, 10 cm off its centre:
 * 2 mm further along, docs/events.md). Taken at their instants, such
 * meetings cost a falling pile of 1000 bodies an island solve each, its
 * rows grown through the pile: 2.44 times the discrete method's time, now
 * 1.46 (docs/benchmarks.md). Unlike masses keep their impacts (the
 * island's exact solve stops a heavy body on a light one at once, where
 * the sweeps take about m_heavy / m_light sweeps to), and so do meetings
 * with static and kinematic bodies and free bodies meeting in flight
 * (validated to their instants).
 */
#define CR_ONTO_REST_MASS_RATIO 2.0f
#define CR_ONTO_REST_REACH 1.0f

static int cr_onto_rest(const carom_world *w, const cr_contact *c)
{
    const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    float ha, hb;
    if (CAROM_EXACT_PILE_IMPACTS || !cr_eq(c->restitution, 0.0f) ||
        A->type != CAROM_BODY_DYNAMIC || B->type != CAROM_BODY_DYNAMIC ||
        !((A->flags | B->flags) & CR_BODY_RESTS) ||
        cr_gt(A->inv_m, cr_mul(CR_ONTO_REST_MASS_RATIO, B->inv_m)) ||
        cr_gt(B->inv_m, cr_mul(CR_ONTO_REST_MASS_RATIO, A->inv_m)) || cr_turns_fast(w, A) ||
        cr_turns_fast(w, B))
        return 0;
    ha = w->info[c->a].shape.half_width;
    hb = w->info[c->b].shape.half_width;
    return !cr_gt(cr_mul(cr_contact_approach(w, c), w->def.dt),
                  cr_mul(CR_ONTO_REST_REACH, cr_min(ha, hb)));
}

/* The approach above which contact c is an impact, not the solver's: the
 * event search's bound (cr_impact_speed in events.c), the rest speed and
 * the pair's speed times CR_IMPACT_REL_TOL, which it calls rounding. */
static float cr_solver_bound(const carom_world *w, const cr_contact *c)
{
    return cr_add(cr_rest_speed(w, c->a, c->b),
                  cr_mul(CR_IMPACT_REL_TOL, cr_pair_speed(w, c->a, c->b)));
}

/*
 * After the impacts of a substep (events methods): a contact the solver
 * took at the substep's start, not closing then, whose body an impact
 * has since sent towards the other faster than the impact bound, with no
 * point in overlap, is an impact to come, the search's at the next
 * substep, not a contact for this substep's relax sweeps: their
 * speculative limit (close no more than the gap in a substep) would stop
 * it inelastically. Touching contacts of the impact's island are held
 * already (events.c), and resting ones stay the solver's. (Three elastic
 * polygons in zero gravity: a pair that had bounced apart was struck back
 * towards itself by the third body, 2.9 mm apart at 0.74 m/s, and the
 * relax took 0.18 % of the energy.)
 */
void cr_solver_release_struck(carom_world *w)
{
    int i, k;
    for (i = 0; i < w->solve_count; ++i) {
        cr_contact *c = &w->contacts[w->solve_order[i]];
        const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
        int apart = 1;
        if (!(c->flags & CR_CONTACT_SOLVE) ||
            (c->flags & (CR_CONTACT_RESTING | CR_CONTACT_UNSETTLED)) || (!sa->held && !sb->held) ||
            cr_onto_rest(w, c))
            continue;
        for (k = 0; k < c->count && apart; ++k)
            apart = cr_gt(cr_current_sep(c, &c->pts[k], sa, sb), 0.0f);
        if (apart && cr_gt(cr_contact_approach(w, c), cr_solver_bound(w, c)))
            c->flags &= ~CR_CONTACT_SOLVE;
    }
}

int cr_solver_classify(carom_world *w, int events)
{
    int i, solved = 0;
    for (i = 0; i < w->active_count; ++i)
        w->sbody[w->active[i]].active = 0;
    w->active_count = 0;
    for (i = 0; i < w->contact_count; ++i) {
        cr_contact *c = &w->contacts[i];
        const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        int take = 1;
        /* an approach faster than the rest speed is an impact: the event
         * loop takes it at its instant; but a resting contact (touching
         * and pushing since the last step) stays the solver's, or a
         * settling pile would turn into a storm of micro-collisions */
        if (events && !(c->flags & (CR_CONTACT_RESTING | CR_CONTACT_UNSETTLED))) {
            /* the event search's bound (cr_impact_speed in events.c):
             * an approach it calls rounding is the solver's. Two bodies
             * overlapping by 9 mm, closing at 4e-5 m/s while both moved
             * at 10 m/s, were left here to the impacts and there to the
             * solver, after this step's solve: neither, for ever, and
             * they sank into each other */
            float bound = cr_solver_bound(w, c);
            /* and a pair whose touching points all leave faster is
             * parting, not resting: the search follows it past the
             * touch to its next impact (two boxes that bounced apart at
             * half their approach in zero gravity, whose turn brought
             * another corner onto the other's face 4 ms into the next
             * step: the solver's, that impact was taken at the step's
             * end, 14 ms late) */
            take = (!cr_gt(cr_contact_approach(w, c), bound) &&
                    !cr_gt(cr_contact_recede(w, c), bound) && !cr_turns_fast(w, A) &&
                    !cr_turns_fast(w, B)) ||
                   cr_onto_rest(w, c);
        }
        if (take) {
            c->flags |= CR_CONTACT_SOLVE;
            if (cr_moves(A))
                cr_solver_activate(w, c->a);
            if (cr_moves(B))
                cr_solver_activate(w, c->b);
            ++solved;
        } else {
            c->flags &= ~CR_CONTACT_SOLVE;
        }
    }
    cr_solver_order(w);
    return solved;
}

void cr_solver_order(carom_world *w)
{
    int i, pass;
    /* the order of the sweeps: moving pairs, then those with a kinematic
     * body, then those with a static one (cr_grounded) */
    w->solve_count = 0;
    w->reorder = 0;
    for (pass = 0; pass < 3; ++pass)
        for (i = 0; i < w->contact_count; ++i) {
            const cr_contact *c = &w->contacts[i];
            if ((c->flags & CR_CONTACT_SOLVE) && cr_grounded(w, c) == pass)
                w->solve_order[w->solve_count++] = i;
        }
}

/* Impulse P along dir at lever arms la, lb: -P on A, +P on B. */
/* The same on the velocities (va, wa), (vb, wb) of bodies with inverse
 * masses ima, imb and inverse inertias iia, iib: their velocities or,
 * in the position sweep, their pseudo-velocities. */
CR_INLINE void cr_apply_to(cr_v2 *va, float *wa, float ima, float iia, cr_v2 *vb, float *wb,
                           float imb, float iib, float la, float lb, cr_v2 dir, float P)
{
    cr_v2 I = cr_vscale(P, dir);
    *va = cr_vmadd(*va, cr_neg(ima), I);
    *vb = cr_vmadd(*vb, imb, I);
#if CAROM_ENABLE_ROTATION
    *wa = cr_sub(*wa, cr_mul(iia, cr_mul(la, P)));
    *wb = cr_add(*wb, cr_mul(iib, cr_mul(lb, P)));
#else
    (void)wa;
    (void)wb;
    (void)iia;
    (void)iib;
    (void)la;
    (void)lb;
#endif
}

CR_INLINE void cr_apply(cr_body *A, cr_body *B, float la, float lb, cr_v2 dir,
                     float P)
{
    cr_apply_to(&A->v, &A->w, A->inv_m, A->inv_I, &B->v, &B->w, B->inv_m, B->inv_I, la, lb,
                dir, P);
}

static float cr_normal_lever(const carom_world *w, int body, cr_v2 r, cr_v2 n)
{
    return CR_BODY_IS_CIRCLE(&w->bodies[body]) ? 0.0f : cr_vcross(r, n);
}

#if CAROM_ENABLE_FRICTION
/*
 * Apply tangent impulse P of point k of contact c. A 2-point manifold's
 * friction is one row at the mean lever arm (cr_solve_friction_pair), so
 * its points' tangent impulses act there too: warm-started at each point's
 * own arm and taken back by the row at the mean one, the difference was a
 * torque from nothing on a face whose points do not lie along the tangent
 * (an octagon rolling off a slope, friction 2: -7.2747 -> -7.2957 rad/s
 * in a step whose velocity change was gravity alone, +0.012 J).
 */
static void cr_apply_tangent(cr_body *A, cr_body *B, const cr_contact *c, int k, float P)
{
    cr_v2 t = cr_vright(c->n), ra = c->pts[k].ra, rb = c->pts[k].rb;
    if (CR_TWO_POINTS && c->count == 2) {
        ra = cr_vscale(0.5f, cr_vadd(c->pts[0].ra, c->pts[1].ra));
        rb = cr_vscale(0.5f, cr_vadd(c->pts[0].rb, c->pts[1].rb));
    }
    cr_apply(A, B, cr_vcross(ra, t), cr_vcross(rb, t), t, P);
}
#endif

void cr_solver_kick_and_warm(carom_world *w, const cr_substep *s)
{
    int i, k;
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        cr_body *b = &w->bodies[id];
        cr_solver_body *sb = &w->sbody[id];
        sb->v0 = b->v;
        sb->w0 = b->w;
        if (b->type == CAROM_BODY_DYNAMIC) {
            b->v = cr_vmadd(b->v, s->h, b->a);
#if CAROM_ENABLE_ROTATION
            b->w = cr_add(b->w, cr_mul(s->h, b->alpha));
#endif
        }
    }
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        if (!(c->flags & CR_CONTACT_SOLVE))
            continue;
        for (k = 0; k < c->count; ++k) {
            const cr_contact_point *p = &c->pts[k];
            if (!cr_eq(p->pn, 0.0f))
                cr_apply(A, B, cr_contact_lever_a(c, p->ra), cr_contact_lever_b(c, p->rb),
                         c->n, p->pn);
#if CAROM_ENABLE_FRICTION /* (without it every tangent impulse is 0) */
            if (!cr_eq(p->pt, 0.0f))
                cr_apply_tangent(A, B, c, k, p->pt);
#endif
        }
    }
}

CR_INLINE float cr_point_vn(cr_v2 va, float wa, cr_v2 vb, float wb, const cr_contact *c,
                         const cr_contact_point *p)
{
    return cr_vdot(cr_vsub(cr_point_velocity(vb, wb, p->rb),
                           cr_point_velocity(va, wa, p->ra)),
                   c->n);
}

/*
 * The normal rows of one contact, on one kind of velocity: the bodies'
 * velocities (the velocity sweeps) or their pseudo-velocities (the
 * position sweep). Pointers to the two bodies' (v, w) being solved, their
 * inverse masses, and the normal lever arms of each point, taken once per
 * contact (an impulse's lever is the same for every row of a sweep).
 */
typedef struct cr_rows_ctx {
    cr_v2 *va, *vb;
    float *wa, *wb;
    float ima, imb, iia, iib;
    float la[CR_MANIFOLD_POINTS], lb[CR_MANIFOLD_POINTS];
} cr_rows_ctx;

CR_INLINE void cr_rows_levers(const carom_world *w, const cr_contact *c, cr_rows_ctx *x)
{
    int k;
    (void)w;
    for (k = 0; k < c->count; ++k) {
        x->la[k] = cr_contact_lever_a(c, c->pts[k].ra);
        x->lb[k] = cr_contact_lever_b(c, c->pts[k].rb);
    }
}

/* Normal impulse d at point k: -d n on A, +d n on B. */
CR_INLINE void cr_rows_apply(cr_rows_ctx *x, cr_v2 n, int k, float d)
{
    cr_apply_to(x->va, x->wa, x->ima, x->iia, x->vb, x->wb, x->imb, x->iib, x->la[k],
                x->lb[k], n, d);
}

CR_INLINE float cr_rows_vn(const cr_rows_ctx *x, const cr_contact *c, int k)
{
    return cr_point_vn(*x->va, *x->wa, *x->vb, *x->wb, c, &c->pts[k]);
}

/*
 * Solve the normal rows of contact c for the velocities of x, accumulated
 * impulses acc[] (>= 0) and targets vn + bias[] >= 0: both points as one
 * 2x2 problem when the manifold allows, else one after the other.
 */
#if CR_TWO_POINTS
#define CR_ROWS_INLINE CR_INLINE
#else
/* (one-point builds: inlined into the sweeps' loops over one-element
 * arrays, gcc cannot see that count <= 1 and warns of accesses past them) */
#define CR_ROWS_INLINE static
#endif
CR_ROWS_INLINE void cr_normal_rows(cr_rows_ctx *x, const cr_contact *c, float *acc,
                           const float *bias, const float *vn)
{
    int k;
#if CR_TWO_POINTS
    if (CR_TWO_POINTS && c->count == 2 && c->block) {
        float a1 = acc[0], a2 = acc[1], x1, x2;
        float b1 = cr_sub(cr_add(vn[0], bias[0]),
                          cr_add(cr_mul(c->k11, a1), cr_mul(c->k12, a2)));
        float b2 = cr_sub(cr_add(vn[1], bias[1]),
                          cr_add(cr_mul(c->k12, a1), cr_mul(c->k22, a2)));
        if (cr_lcp2(c->k11, c->k12, c->k22, b1, b2, &x1, &x2)) {
            acc[0] = x1;
            acc[1] = x2;
            cr_rows_apply(x, c->n, 0, cr_sub(x1, a1));
            cr_rows_apply(x, c->n, 1, cr_sub(x2, a2));
            return;
        }
    }
#endif
    for (k = 0; k < c->count; ++k) {
        /* the first point's impulse changed the second's velocity */
        float v = k == 0 ? vn[0] : cr_rows_vn(x, c, k);
        float p = cr_max(cr_sub(acc[k], cr_mul(c->pts[k].mass_n, cr_add(v, bias[k]))),
                         0.0f);
        float d = cr_sub(p, acc[k]);
        acc[k] = p;
        cr_rows_apply(x, c->n, k, d);
    }
}

/* ---- velocities ------------------------------------------------------------ */

CR_INLINE void cr_rows_of_velocity(carom_world *w, const cr_contact *c, cr_rows_ctx *x)
{
    cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    x->va = &A->v;
    x->vb = &B->v;
    x->wa = &A->w;
    x->wb = &B->w;
    x->ima = A->inv_m;
    x->imb = B->inv_m;
    x->iia = A->inv_I;
    x->iib = B->inv_I;
    cr_rows_levers(w, c, x);
}

#if CAROM_ENABLE_FRICTION
/*
 * Friction of a 2-point manifold as one row. Both points lie on the
 * reference face, along the tangent, so their tangent rows are the same
 * constraint (the same line of action): solving them one after the other
 * would favour the first point and turn a symmetric landing into a
 * lopsided one. One row at the mean lever arm, limited by mu times the
 * total normal impulse, shared between the points in proportion to their
 * normal impulses (for the warm start).
 */
static void cr_solve_friction_pair(carom_world *w, cr_contact *c)
{
    cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    cr_contact_point *p0 = &c->pts[0], *p1 = &c->pts[1];
    cr_v2 t = cr_vright(c->n);
    cr_v2 ra = cr_vscale(0.5f, cr_vadd(p0->ra, p1->ra));
    cr_v2 rb = cr_vscale(0.5f, cr_vadd(p0->rb, p1->rb));
    float mass_t = cr_mul(0.5f, cr_add(p0->mass_t, p1->mass_t));
    float vt = cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, rb),
                               cr_point_velocity(A->v, A->w, ra)),
                       t);
    float pn = cr_add(p0->pn, p1->pn);
    float limit = cr_mul(c->friction, pn);
    float old = cr_add(p0->pt, p1->pt);
    float pt = cr_clamp(cr_sub(old, cr_mul(mass_t, vt)), cr_neg(limit), limit);
    float share = cr_gt(pn, 0.0f) ? cr_div(p0->pn, pn) : 0.5f;
    cr_apply(A, B, cr_vcross(ra, t), cr_vcross(rb, t), t, cr_sub(pt, old));
    p0->pt = cr_mul(share, pt);
    p1->pt = cr_sub(pt, p0->pt);
}
#endif

/* The velocity body `id` would have at time t of the step had no contact
 * acted on it since the step's start: its start velocity plus what its
 * acceleration gives it (static and kinematic bodies: none). */
CR_INLINE void cr_free_velocity(const carom_world *w, int id, float t, cr_v2 *v, float *om)
{
    const cr_body *b = &w->bodies[id], *b0 = &w->backup[id];
    *v = b0->v;
    *om = b0->w;
    if (b->type != CAROM_BODY_DYNAMIC)
        return;
    *v = cr_vmadd(b0->v, t, b->a);
#if CAROM_ENABLE_ROTATION
    *om = cr_add(b0->w, cr_mul(t, b->alpha));
#endif
}

/*
 * The approach that Newton's law answers at point p of contact c, taken
 * when the point first pushes, in the substep s. Taken before the warm
 * start, whose impulse is last step's support, not this approach.
 *
 * Events methods: the velocities at the substep's start. Their impacts
 * were taken at their instants, so these are the velocities just before
 * this one.
 *
 * Discrete method: the velocities the bodies would have at the substep's
 * start had no contact acted on them in this step (cr_free_velocity). The
 * restitution pass answers every bounce of the step at once, so every
 * approach must belong to one state. Taken from the velocities at the
 * substep's start instead, a ball that a wall had already stopped in an
 * earlier substep met a second ball with the approach of a stopped ball,
 * while the wall still asked for the first ball's rebound: the targets
 * added energy (1D: a ball at -1 m/s against a wall, struck by one at -3
 * in the same step, left at +1 and up to +4 instead of +3: kinetic energy
 * 5 -> 8.5; +3.6 in test_discrete_wall_and_two_balls_in_one_step_keep_
 * the_energy), and an elastic gas of 100 balls
 * heated up 2.6x in 6000 steps (docs/physics.md). For a lone contact the
 * two are the same approach, within rounding.
 */
static float cr_approach_before(const carom_world *w, const cr_contact *c,
                                const cr_contact_point *p, const cr_substep *s)
{
    const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    cr_v2 va, vb;
    float wa, wb;
    if (!CAROM_ENABLE_DISCRETE || w->method != CAROM_METHOD_DISCRETE)
        return cr_point_vn(sa->v0, sa->w0, sb->v0, sb->w0, c, p);
    cr_free_velocity(w, c->a, s->t, &va, &wa);
    cr_free_velocity(w, c->b, s->t, &vb, &wb);
    return cr_point_vn(va, wa, vb, wb, c, p);
}

/*
 * Deep resting overlaps of unlike bodies (CAROM_SOFT_DEEP_CONTACTS, off by
 * default): a soft push in the velocity sweeps instead of the position
 * sweep (Box2D v3's soft contact, for that part of the overlap only).
 *
 * A light box jammed deep between heavy ones (a pour of mixed densities)
 * is the position sweep's weak case: its rigid pseudo-velocities, one
 * sweep from zero in each substep, swing the light box back and forth and
 * the pile never settles. Where a resting contact joins two dynamic
 * bodies of masses more than CR_SOFT_MASS_RATIO apart, one of them in a
 * jam of unlike densities (cr_mark_mixed), what lies deeper than
 * CR_SOFT_DEEP_SLOPS slops is left to the sweeps before the move: a
 * damped spring (b2MakeSoft) of h w = CR_SOFT_H_OMEGA, damping ratio
 * CR_SOFT_DAMPING, pushing at most at the push speed, solved with
 * friction; the relax sweeps take its push back out of the velocities. Its
 * impulse scale lets the accumulated impulse go, so a jam settles with its
 * overlap (a loaded point sinks about W h^2 / (m (h w)^2) past the depth).
 * h w = pi / 2 is v3's stiffest contact (a quarter of the substep rate).
 * That sink is why the push is kept to jams of unlike densities: gated on
 * the masses alone, it took every pile of boxes of unequal sizes, whose
 * small bottom boxes carry 200 times their weight, and left 30 to 43
 * pairs 1 cm deep in a pile of one density that the rigid correction
 * leaves within 6 mm; gated on the pair's densities, the mixed pile
 * churned on through its pairs of like density (docs/physics.md).
 */
#define CR_SOFT_MASS_RATIO 2.0f
#define CR_SOFT_DENSITY_RATIO 2.0f
#define CR_SOFT_DEEP_SLOPS 10.0f
#define CR_SOFT_H_OMEGA 1.5707963f
#define CR_SOFT_DAMPING 30.0f
#define CR_SOFT_A1 (2.0f * CR_SOFT_DAMPING + CR_SOFT_H_OMEGA)
#define CR_SOFT_A2 (CR_SOFT_H_OMEGA * CR_SOFT_A1)
/* bias per unit overlap, times 1/h; mass and impulse scales */
#define CR_SOFT_RATE (CR_SOFT_H_OMEGA / CR_SOFT_A1)
#define CR_SOFT_MASS_SCALE (CR_SOFT_A2 / (1.0f + CR_SOFT_A2))
#define CR_SOFT_IMPULSE_SCALE (1.0f / (1.0f + CR_SOFT_A2))

/* Does contact c take the soft push for its deep points? Marked at the
 * step's start (cr_mark_mixed), while it rests (a contact the events
 * method remakes after an impact rests no more). */
static int cr_soft_pair(const cr_contact *c)
{
    const unsigned both = CR_CONTACT_SOFT | CR_CONTACT_RESTING;
    return CAROM_SOFT_DEEP_CONTACTS && (c->flags & both) == both;
}

/* The overlap past which a soft pair's point is pushed softly. */
static float cr_soft_depth(const carom_world *w)
{
    return cr_mul(CR_SOFT_DEEP_SLOPS, w->scale.slop);
}

#if CAROM_SOFT_DEEP_CONTACTS
/* Mark the bodies of the deep resting overlaps (deeper than
 * CR_SOFT_DEEP_SLOPS slops at the step's start) between two dynamic
 * bodies of densities more than CR_SOFT_DENSITY_RATIO apart: the jams of
 * a mixed pile, and their resting contacts with bodies of unlike mass,
 * which take the soft push (cr_soft_pair); a pile of one density marks
 * none. */
static void cr_mark_mixed(carom_world *w)
{
    float deep = cr_neg(cr_soft_depth(w));
    int i, k;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        float a = w->bodies[c->a].inv_m, b = w->bodies[c->b].inv_m;
        float sa = w->info[c->a].shape.size, sb = w->info[c->b].shape.size;
        int hit = 0;
        if (!(c->flags & CR_CONTACT_RESTING) || cr_eq(a, 0.0f) || cr_eq(b, 0.0f))
            continue;
        /* 1 / density, up to pi: the inverse mass times the area */
        a = cr_mul(a, cr_mul(sa, sa));
        b = cr_mul(b, cr_mul(sb, sb));
        if (!cr_gt(a, cr_mul(CR_SOFT_DENSITY_RATIO, b)) &&
            !cr_gt(b, cr_mul(CR_SOFT_DENSITY_RATIO, a)))
            continue;
        for (k = 0; k < c->count; ++k)
            hit |= cr_lt(cr_current_sep(c, &c->pts[k], &w->sbody[c->a], &w->sbody[c->b]), deep);
        if (hit) {
            w->sbody[c->a].mixed = 1;
            w->sbody[c->b].mixed = 1;
        }
    }
    /* their resting contacts with bodies of unlike mass */
    for (i = 0; i < w->contact_count; ++i) {
        cr_contact *c = &w->contacts[i];
        float a, b;
        if (!(c->flags & CR_CONTACT_RESTING) || (!w->sbody[c->a].mixed && !w->sbody[c->b].mixed))
            continue;
        a = w->bodies[c->a].inv_m;
        b = w->bodies[c->b].inv_m;
        if (!cr_eq(a, 0.0f) && !cr_eq(b, 0.0f) &&
            (cr_gt(a, cr_mul(CR_SOFT_MASS_RATIO, b)) || cr_gt(b, cr_mul(CR_SOFT_MASS_RATIO, a))))
            c->flags |= CR_CONTACT_SOFT;
    }
}
#endif

/* The normal rows of a contact with soft points, one after the other. */
static void cr_soft_rows(cr_rows_ctx *x, const cr_contact *c, float *acc, const float *bias,
                         const float *vn, const int *soft)
{
    int k;
    for (k = 0; k < c->count; ++k) {
        float v = k == 0 ? vn[0] : cr_rows_vn(x, c, k);
        float m = c->pts[k].mass_n, p;
        if (soft[k])
            p = cr_sub(cr_sub(acc[k], cr_mul(cr_mul(CR_SOFT_MASS_SCALE, m), cr_add(v, bias[k]))),
                       cr_mul(CR_SOFT_IMPULSE_SCALE, acc[k]));
        else
            p = cr_sub(acc[k], cr_mul(m, cr_add(v, bias[k])));
        p = cr_max(p, 0.0f);
        cr_rows_apply(x, c->n, k, cr_sub(p, acc[k]));
        acc[k] = p;
    }
}

/* One sweep's rows of contact c; `biased`: a sweep before the move, where
 * deep points of soft pairs are pushed out softly. */
static void cr_solve_velocity(carom_world *w, cr_contact *c, const cr_substep *s,
                              int first, int cached, int biased)
{
    const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    float bias[CR_MANIFOLD_POINTS], vn[CR_MANIFOLD_POINTS];
    float acc[CR_MANIFOLD_POINTS];
    int soft[CR_MANIFOLD_POINTS], any_soft = 0;
    int soft_pair = biased && cr_soft_pair(c);
    float deep = soft_pair ? cr_soft_depth(w) : 0.0f;
    cr_rows_ctx x;
    int k;
    cr_rows_of_velocity(w, c, &x);
    for (k = 0; k < c->count; ++k) {
        cr_contact_point *p = &c->pts[k];
        /* the separation of the poses: the same in every sweep of a
         * solve (velocities change, positions do not), so the first
         * sweep keeps it in pp, the position sweep's scratch, free
         * until that sweep starts again from zero */
        float sep = cached ? p->pp : cr_current_sep(c, p, sa, sb);
        p->pp = sep;
        bias[k] = 0.0f;
        soft[k] = 0;
        if (soft_pair && cr_lt(sep, cr_neg(deep))) {
            soft[k] = 1;
            any_soft = 1;
            bias[k] = cr_max(cr_mul(cr_mul(CR_SOFT_RATE, s->inv_h), cr_add(sep, deep)),
                             cr_neg(s->push));
        } else if (cr_gt(sep, 0.0f)) {
            if (first) {
                /* close the gap with the substep's mean velocity */
                float vn0 = cr_point_vn(sa->v0, sa->w0, sb->v0, sb->w0, c, p);
                bias[k] = cr_max(0.0f, cr_add(cr_mul(2.0f, cr_mul(sep, s->inv_h)), vn0));
            } else {
                bias[k] = cr_mul(sep, s->inv_h);
            }
        }
        vn[k] = cr_rows_vn(&x, c, k);
        acc[k] = p->pn;
        /* restitution answers the approach of the substep in which the
         * point first pushes: nearer the instant of impact than the start
         * of the step (cr_approach_before) */
        if (first && cr_eq(p->max_pn, 0.0f))
            c->pts[k].rel_vn = cr_approach_before(w, c, p, s);
    }
    if (any_soft)
        cr_soft_rows(&x, c, acc, bias, vn, soft);
    else
        cr_normal_rows(&x, c, acc, bias, vn);
    for (k = 0; k < c->count; ++k) {
        c->pts[k].pn = acc[k];
        c->pts[k].max_pn = cr_max(c->pts[k].max_pn, acc[k]);
    }
#if CAROM_ENABLE_FRICTION
    if (CR_TWO_POINTS && cr_gt(c->friction, 0.0f) && c->count == 2) {
        cr_solve_friction_pair(w, c);
    } else if (cr_gt(c->friction, 0.0f)) {
        cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        cr_v2 t = cr_vright(c->n);
        for (k = 0; k < c->count; ++k) {
            cr_contact_point *p = &c->pts[k];
            float vt = cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, p->rb),
                                       cr_point_velocity(A->v, A->w, p->ra)),
                               t);
            float limit = cr_mul(c->friction, p->pn);
            float pt = cr_clamp(cr_sub(p->pt, cr_mul(p->mass_t, vt)),
                                cr_neg(limit), limit);
            float d = cr_sub(pt, p->pt);
            p->pt = pt;
            cr_apply(A, B, cr_vcross(p->ra, t), cr_vcross(p->rb, t), t, d);
        }
    }
#endif
}

void cr_solver_solve(carom_world *w, const cr_substep *s, int first,
                     int iterations)
{
    int it, j;
    for (it = 0; it < iterations; ++it)
        for (j = 0; j < w->solve_count; ++j) {
            /* extra sweeps (priming) alternate direction: symmetric
             * Gauss-Seidel carries a load down a stack and the support up
             * it equally fast */
            int i = (it & 1) ? w->solve_count - 1 - j : j;
            cr_contact *c = &w->contacts[w->solve_order[i]];
            /* an impact inside the substep may have made it one */
            if (c->flags & CR_CONTACT_SOLVE)
                cr_solve_velocity(w, c, s, first && it == 0, it > 0, first);
        }
    w->sep_cached = iterations > 0;
}

/* ---- positions ---------------------------------------------------------------- */

CR_INLINE void cr_rows_of_pseudo(carom_world *w, const cr_contact *c, cr_rows_ctx *x)
{
    cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    x->va = &sa->vp;
    x->vb = &sb->vp;
    x->wa = &sa->wp;
    x->wb = &sb->wp;
    x->ima = w->bodies[c->a].inv_m;
    x->imb = w->bodies[c->b].inv_m;
    x->iia = w->bodies[c->a].inv_I;
    x->iib = w->bodies[c->b].inv_I;
    cr_rows_levers(w, c, x);
}

CR_INLINE float cr_pseudo_vn(carom_world *w, const cr_contact *c, int k)
{
    const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
    return cr_point_vn(sa->vp, sa->wp, sb->vp, sb->wp, c, &c->pts[k]);
}

static void cr_correct_shock(carom_world *w, const cr_substep *s, float cap);

/*
 * The overlap the position correction works on. At a resting contact
 * (touching and pushing since the last step) only what lies deeper than
 * one linear slop (Box2D 2.4's allowed penetration); other contacts
 * (impacts, a gas of elastic balls) are corrected to zero overlap.
 * Removing every last bit of a resting overlap moves positions in every
 * substep, and in a deep pile each such move turns the contacts a little,
 * so last step's impulses no longer balance the weights: the bodies sink,
 * the correction pushes them apart along slanted normals, and the pile
 * creeps without end and never sleeps (docs/physics.md). A deep point of
 * a soft pair is left to the soft push of the velocity sweeps
 * (cr_soft_pair): none.
 */
static float cr_excess_overlap(const carom_world *w, const cr_contact *c, float sep)
{
    if (c->flags & CR_CONTACT_RESTING) {
        if (cr_soft_pair(c) && cr_lt(sep, cr_neg(cr_soft_depth(w))))
            return 0.0f;
        return cr_neg(cr_add(sep, w->scale.slop));
    }
    return cr_neg(sep);
}

/*
 * Position sweeps of a substep in which some point's correction is capped
 * (more overlap than one substep's push-out): 4, but only over the rows
 * of the bodies such a point holds and of those the extra sweeps push
 * (marked by cr_solver_body's flag `walk`, cleared after). One sweep
 * cannot free a body jammed deep among others: the support lift
 * (cr_correct_shock) and the rows around it take back what it pushes
 * out. The stress pours need them: without them, the pour of 500 bodies
 * at dt 1/30 ends with 10.1 mm of overlap (events; the bound is 1 cm) and
 * the one of 6 cm bodies under 10 m/s^2 with 8.9 and 9.3 mm (bound 3 mm);
 * with them 2.2 and 4.1 mm, 0.3 and 0.4 mm. Substeps without a deep point
 * keep one sweep, and a deep point far away changes nothing here.
 */
#define CR_CORRECT_DEEP_SWEEPS 4

/* Mark body i (dynamic) for the deep sweeps. */
static void cr_mark_deep(carom_world *w, int i)
{
    if (w->bodies[i].type == CAROM_BODY_DYNAMIC)
        w->sbody[i].walk = 1;
}

static int cr_deep_marked(const carom_world *w, int i)
{
    return w->bodies[i].type == CAROM_BODY_DYNAMIC && w->sbody[i].walk;
}

/*
 * The position sweep takes the rows between two dynamic bodies as Box2D
 * 2.4's position solver does (nonlinear Gauss-Seidel): each pushes its
 * pair apart by a fraction of the overlap the pair will have once the
 * pseudo-velocities found so far in the sweep have moved it, and holds
 * nothing else. Taken as velocity rows instead (reach the target
 * separating speed, whatever the rows before did), each row undid all of
 * the compression the rows before it had pushed into its pair, and then
 * only a fraction of its own overlap, so in a squeeze (more bodies than
 * room) the overlap drifted to the pairs solved first and grew without
 * bound: eight unit circles between walls 0.7 m too close ended with one
 * pair 0.52 m deep and the others 0.03 m; a 32 x 32 grid of them with
 * circles coincident at a corner; a circle in a pour at dt 1/30 stayed
 * wedged 17 mm into a box beside a wall for 7 s. Now every pair of the
 * squeeze keeps 0.1 m, as in Box2D 2.4.1 and v3, and the pour's circle is
 * out within 2 s. A row with a static or kinematic body stays a velocity
 * row: it has the last word (cr_grounded), so a piston or an elevator
 * cannot push a body into a wall or a ceiling.
 */
void cr_solver_correct(carom_world *w, const cr_substep *s, int iterations)
{
    int it, i, k, deep = 0;
    float cap = cr_mul(s->push, s->h);
    w->sep_cached = 0; /* pp is this sweep's again */
    for (i = 0; i < w->active_count; ++i) {
        cr_solver_body *sb = &w->sbody[w->active[i]];
        sb->vp = cr_v(0.0f, 0.0f);
        sb->wp = 0.0f;
        sb->walk = 0;
    }
    for (it = 0; it < iterations || (deep && it < CR_CORRECT_DEEP_SWEEPS); ++it)
        for (i = 0; i < w->solve_count; ++i) {
            cr_contact *c = &w->contacts[w->solve_order[i]];
            const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
            float bias[CR_MANIFOLD_POINTS], vn[CR_MANIFOLD_POINTS];
            int any = 0, free_pair, capped = 0;
            if (!(c->flags & CR_CONTACT_SOLVE))
                continue;
            /* the deep sweeps: only where the deep rows push (the marks
             * of dynamic bodies: static and kinematic ones keep theirs
             * from other passes, or none) */
            if (it >= iterations && !cr_deep_marked(w, c->a) && !cr_deep_marked(w, c->b))
                continue;
            free_pair = cr_grounded(w, c) == 0;
            for (k = 0; k < c->count; ++k) {
                float sep = cr_current_sep(c, &c->pts[k], sa, sb), want, fix;
                vn[k] = cr_pseudo_vn(w, c, k);
                /* between dynamic bodies: the separation the sweep so far
                 * leads to */
                if (free_pair)
                    sep = cr_add(sep, cr_mul(s->h, vn[k]));
                /* the part of the overlap to remove in this substep, as a
                 * separating pseudo-velocity over h: added to the one the
                 * pair has (dynamic bodies), or the one it must reach */
                want = cr_mul(CAROM_POSITION_CORRECTION, cr_excess_overlap(w, c, sep));
                capped |= cr_gt(want, cap);
                fix = cr_max(cr_min(want, cap), 0.0f);
                bias[k] = cr_neg(cr_mul(fix, s->inv_h));
                if (free_pair)
                    bias[k] = cr_sub(bias[k], vn[k]);
                any |= cr_gt(fix, 0.0f);
                c->pts[k].pp = it == 0 ? 0.0f : c->pts[k].pp;
            }
            if (!any && (free_pair || it == 0))
                continue;
            if (capped && it == 0)
                deep = 1;
            if ((capped && it == 0) || it >= iterations) {
                cr_mark_deep(w, c->a);
                cr_mark_deep(w, c->b);
            }
            {
                float acc[CR_MANIFOLD_POINTS];
                cr_rows_ctx x;
                cr_rows_of_pseudo(w, c, &x);
                for (k = 0; k < c->count; ++k)
                    acc[k] = c->pts[k].pp;
                cr_normal_rows(&x, c, acc, bias, vn);
                for (k = 0; k < c->count; ++k)
                    c->pts[k].pp = acc[k];
            }
        }
    if (deep)
        for (i = 0; i < w->active_count; ++i)
            w->sbody[w->active[i]].walk = 0;
    cr_correct_shock(w, s, cap);
    /* move along the pseudo-velocities, then forget them */
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        cr_solver_body *sb = &w->sbody[id];
        cr_body *b = &w->bodies[id];
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        /* pushed out of an overlap by more than a slop (along an axis):
         * not at rest, whatever its velocity (circles spawned coincident
         * in zero gravity, velocities 0, slept 0.18 m deep in each other) */
        if (!(b->flags & CR_BODY_SHIFTED) &&
            cr_gt(cr_mul(s->h, cr_add(cr_max(cr_abs(sb->vp.x), cr_abs(sb->vp.y)),
                                      cr_mul(cr_abs(sb->wp), w->info[id].shape.extent))),
                  w->scale.slop))
            b->flags |= CR_BODY_SHIFTED;
        if (!cr_eq(sb->vp.x, 0.0f) || !cr_eq(sb->vp.y, 0.0f))
            cr_add_position(b, cr_vscale(s->h, sb->vp));
#if CAROM_ENABLE_ROTATION
        if (!cr_eq(sb->wp, 0.0f))
            b->q = cr_rot_advance(b->q, cr_mul(s->h, sb->wp));
#endif
    }
}

void cr_solver_set_drifts(carom_world *w, const cr_substep *s)
{
    int i;
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        cr_body *b = &w->bodies[id];
        cr_solver_body *sb = &w->sbody[id];
        cr_drift *d = &w->drift[id];
        d->a = cr_vscale(s->inv_h, cr_vsub(b->v, sb->v0));
        d->alpha = cr_mul(s->inv_h, cr_sub(b->w, sb->w0));
        sb->held = 0;
        sb->keep = 0;
        ++d->version;
        b->v = sb->v0;
        b->w = sb->w0;
    }
}

void cr_solver_update_deltas(carom_world *w)
{
    int i;
    w->sep_cached = 0; /* the poses moved */
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        cr_solver_body *sb = &w->sbody[id];
        const cr_body *b = &w->bodies[id], *b0 = &w->backup[id];
        sb->dp = cr_vsub(b->x, b0->x);
        sb->dq = cr_anchor_turn(b, b0);
    }
}

/* Is point p of contact c an impact for the restitution pass: met faster
 * than the rest speed, and pushed? */
static int cr_bounces(const carom_world *w, const cr_contact *c,
                      const cr_contact_point *p)
{
    return cr_lt(p->rel_vn, cr_neg(cr_rest_speed(w, c->a, c->b))) &&
           !cr_eq(p->max_pn, 0.0f);
}

/* Sweeps of the restitution pass before it gives up converging (a row of
 * touching balls struck at one end needs about one per ball). */
#define CR_RESTITUTION_SWEEPS 64

/* Relative change of the bounce impulses below which the pass stops. */
#define CR_RESTITUTION_TOL 1e-6f

/* Relative kinetic energy gain an island of bounces may show before the
 * limit acts (rounding of the Newton targets stays far below it). */
#define CR_BOUNCE_ENERGY_TOL 1e-4f

static int cr_root(int *parent, int i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

float cr_kinetic(const cr_body_info *in, cr_v2 v, float om)
{
#if CAROM_ENABLE_ROTATION
    return cr_mul(0.5f, cr_add(cr_mul(in->m, cr_vdot(v, v)), cr_mul(in->I, cr_mul(om, om))));
#else
    (void)om; /* no body turns */
    return cr_mul(0.5f, cr_mul(in->m, cr_vdot(v, v)));
#endif
}

float cr_energy_share(float lin, float quad, float room)
{
    float disc = cr_add(cr_mul(lin, lin), cr_mul(cr_mul(4.0f, quad), room));
    return cr_clamp(cr_div(cr_add(cr_neg(lin), cr_sqrt(disc)), cr_mul(2.0f, quad)), 0.0f, 1.0f);
}

/*
 * Discrete method: the restitution pass answers the Newton targets of all
 * of a step's bounces at once, from the approaches before the step. For a
 * turning polygon that meets two bodies in one step (a spinning box in a
 * corner, boxes of an elastic gas) the targets are not those of the
 * impacts taken in turn, and can add energy (x 1.085 in one step in
 * tools/scenes/limits/spinning-box-two-walls.scene; an elastic box gas
 * heated up 25 % in 3600 steps). Per island of bodies joined by bounces,
 * the kinetic energy after the pass may not pass what the bodies would
 * have had with no contact at all (their free velocities at the step's
 * end), nor what they had before the pass, plus the work a moving
 * kinematic body they bounce off may do (cr_kinematic_work): if it does,
 * the pass's velocity changes are scaled back by the largest factor in
 * [0, 1] that keeps it there (the energy is a quadratic in the factor).
 * The velocities before the pass are in vp, wp (the position correction's
 * scratch, done); the sums go in the island root's v0, w0, dp, dq (free
 * at the step's end: cr_solver_begin sets them again). Returns 1 if some
 * island was scaled.
 */
#if CAROM_ENABLE_KINEMATIC
/* The most work moving kinematic body k may do on dynamic body d in the
 * restitution pass: an impulse P from a surface moving at u changes the
 * energy by P.u at most (in the surface's frame no bounce with e <= 1
 * adds energy), and P is at most 2 m (s + u), s the fastest point of d
 * before the pass and u of k near d. (Left unlimited, a thin box spinning
 * at thousands of rad/s in a pile a fast rotor stirred took 70,000 rad/s
 * from one pass, and the pile's speeds grew without end.) */
static float cr_kinematic_work(const carom_world *w, int k, int d)
{
    const cr_body *K = &w->bodies[k], *D = &w->bodies[d];
    const cr_solver_body *sd = &w->sbody[d];
    float ext = w->info[d].shape.extent;
    float u = cr_add(cr_vlen(K->v),
                     cr_mul(cr_abs(K->w), cr_add(cr_vlen(cr_vsub(D->x, K->x)), ext)));
    float sp = cr_add(cr_vlen(sd->vp), cr_mul(cr_abs(sd->wp), ext));
    return cr_mul(cr_mul(2.0f, w->info[d].m), cr_mul(u, cr_add(sp, u)));
}
#endif

#define CR_E_PRE(sb) ((sb)->v0.x)
#define CR_E_LIN(sb) ((sb)->v0.y)
#define CR_E_QUAD(sb) ((sb)->w0)
#define CR_E_REF(sb) ((sb)->dp.x)
#define CR_E_WORK(sb) ((sb)->dp.y)
#define CR_E_SCALE(sb) ((sb)->dq.c)
static int cr_limit_bounce_energy(carom_world *w)
{
    int *parent = w->regrown; /* scratch at the end of the step */
    int i, k, limited = 0;
    for (i = 0; i < w->slot_count; ++i)
        parent[i] = -1;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        int bounced = 0, ra, rb;
        for (k = 0; k < c->count; ++k)
            bounced |= !cr_eq(c->pts[k].pp, 0.0f);
        if (!bounced)
            continue;
        if (A->type == CAROM_BODY_DYNAMIC && parent[c->a] < 0) {
            parent[c->a] = c->a;
            CR_E_WORK(&w->sbody[c->a]) = 0.0f;
        }
        if (B->type == CAROM_BODY_DYNAMIC && parent[c->b] < 0) {
            parent[c->b] = c->b;
            CR_E_WORK(&w->sbody[c->b]) = 0.0f;
        }
        if (A->type == CAROM_BODY_DYNAMIC && B->type == CAROM_BODY_DYNAMIC) {
            ra = cr_root(parent, c->a);
            rb = cr_root(parent, c->b);
            if (ra != rb) {
                float f = cr_add(CR_E_WORK(&w->sbody[ra]),
                                 CR_E_WORK(&w->sbody[rb]));
                parent[ra < rb ? rb : ra] = ra < rb ? ra : rb;
                CR_E_WORK(&w->sbody[ra < rb ? ra : rb]) = f;
            }
        }
#if CAROM_ENABLE_KINEMATIC
        else if (A->type == CAROM_BODY_KINEMATIC && cr_body_moves(A)) {
            cr_solver_body *r = &w->sbody[cr_root(parent, c->b)];
            CR_E_WORK(r) = cr_add(CR_E_WORK(r), cr_kinematic_work(w, c->a, c->b));
        } else if (B->type == CAROM_BODY_KINEMATIC && cr_body_moves(B)) {
            cr_solver_body *r = &w->sbody[cr_root(parent, c->a)];
            CR_E_WORK(r) = cr_add(CR_E_WORK(r), cr_kinematic_work(w, c->b, c->a));
        }
#endif
    }
    for (i = 0; i < w->slot_count; ++i)
        if (parent[i] == i) {
            cr_solver_body *sr = &w->sbody[i];
            CR_E_PRE(sr) = CR_E_LIN(sr) = CR_E_QUAD(sr) = CR_E_REF(sr) = 0.0f;
        }
    for (i = 0; i < w->slot_count; ++i) {
        const cr_body *b = &w->bodies[i];
        const cr_body_info *in = &w->info[i];
        const cr_solver_body *sb = &w->sbody[i];
        cr_solver_body *sr;
        cr_v2 dv, vf;
        float dw, wf;
        if (parent[i] < 0)
            continue;
        sr = &w->sbody[cr_root(parent, i)];
        dv = cr_vsub(b->v, sb->vp);
        dw = cr_sub(b->w, sb->wp);
        cr_free_velocity(w, i, w->def.dt, &vf, &wf);
        CR_E_PRE(sr) = cr_add(CR_E_PRE(sr), cr_kinetic(in, sb->vp, sb->wp));
#if CAROM_ENABLE_ROTATION
        CR_E_LIN(sr) = cr_add(CR_E_LIN(sr), cr_add(cr_mul(in->m, cr_vdot(sb->vp, dv)),
                                                    cr_mul(in->I, cr_mul(sb->wp, dw))));
#else
        CR_E_LIN(sr) = cr_add(CR_E_LIN(sr), cr_mul(in->m, cr_vdot(sb->vp, dv)));
#endif
        CR_E_QUAD(sr) = cr_add(CR_E_QUAD(sr), cr_kinetic(in, dv, dw));
        CR_E_REF(sr) = cr_add(CR_E_REF(sr), cr_kinetic(in, vf, wf));
    }
    /* E(s) = E_pre + lin s + quad s^2: the largest s in [0, 1] with
     * E(s) <= max(E_ref, E_pre) */
    for (i = 0; i < w->slot_count; ++i) {
        cr_solver_body *sr = &w->sbody[i];
        float cap, after, room;
        if (parent[i] != i)
            continue;
        CR_E_SCALE(sr) = 1.0f;
        cap = cr_add(cr_max(CR_E_REF(sr), CR_E_PRE(sr)), CR_E_WORK(sr));
        after = cr_add(CR_E_PRE(sr), cr_add(CR_E_LIN(sr), CR_E_QUAD(sr)));
        if (!cr_gt(after, cr_mul(cap, cr_add(1.0f, CR_BOUNCE_ENERGY_TOL))) ||
            !cr_gt(CR_E_QUAD(sr), 0.0f))
            continue;
        room = cr_max(cr_sub(cap, CR_E_PRE(sr)), 0.0f);
        CR_E_SCALE(sr) = cr_energy_share(CR_E_LIN(sr), CR_E_QUAD(sr), room);
        limited = 1;
    }
    if (!limited)
        return 0;
    for (i = 0; i < w->slot_count; ++i) {
        cr_body *b = &w->bodies[i];
        const cr_solver_body *sb = &w->sbody[i];
        float f;
        if (parent[i] < 0)
            continue;
        f = CR_E_SCALE(&w->sbody[cr_root(parent, i)]);
        if (cr_lt(f, 1.0f)) {
            b->v = cr_vmadd(sb->vp, f, cr_vsub(b->v, sb->vp));
#if CAROM_ENABLE_ROTATION
            b->w = cr_add(sb->wp, cr_mul(f, cr_sub(b->w, sb->wp)));
#endif
        }
    }
    /* the bounce impulses recorded: as scaled */
    for (i = 0; i < w->contact_count; ++i) {
        cr_contact *c = &w->contacts[i];
        int d = w->bodies[c->a].type == CAROM_BODY_DYNAMIC ? c->a : c->b;
        float f;
        if (parent[d] < 0)
            continue;
        f = CR_E_SCALE(&w->sbody[cr_root(parent, d)]);
        for (k = 0; k < c->count; ++k)
            c->pts[k].pp = cr_mul(f, c->pts[k].pp);
    }
    return 1;
}
#undef CR_E_PRE
#undef CR_E_LIN
#undef CR_E_QUAD
#undef CR_E_REF
#undef CR_E_WORK
#undef CR_E_SCALE

/* The bounce's friction at point p: within mu of the bounce's impulse,
 * the solver's friction having been bounded by the impulse that stopped
 * the approach alone (a disc spinning at 10 rad/s bouncing elastically
 * off a floor at 3 m/s with mu 0.3 slid on at +0.1 m/s instead of -0.8;
 * Coulomb's law over the whole impulse, (1 + e) m v). */
static void cr_bounce_friction(const cr_contact *c, cr_body *A, cr_body *B, cr_contact_point *p,
                               float *change)
{
#if CAROM_ENABLE_FRICTION
    if (cr_gt(c->friction, 0.0f)) {
        cr_v2 t = cr_vright(c->n);
        float vt = cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, p->rb),
                                   cr_point_velocity(A->v, A->w, p->ra)),
                           t);
        float limit = cr_mul(c->friction, cr_max(p->pp, 0.0f));
        float pt = cr_clamp(cr_sub(p->pt_bounce, cr_mul(p->mass_t, vt)), cr_neg(limit), limit);
        float d = cr_sub(pt, p->pt_bounce);
        p->pt_bounce = pt;
        cr_apply(A, B, cr_vcross(p->ra, t), cr_vcross(p->rb, t), t, d);
        *change = cr_max(*change, cr_abs(d));
    }
#else
    (void)c;
    (void)A;
    (void)B;
    (void)p;
    (void)change;
#endif
}

/*
 * The Newton targets of both points of a 2-point contact as one 2x2
 * problem, where K allows (c->block) and both points bounce: the total
 * impulses z = pn + pp >= 0 with vn + e v_before >= 0, complementary.
 * One after the other, the points of a nearly singular K (a rod 4 mm
 * thick striking a wall end-on, its points 4 mm apart: K's two rows
 * differ by 0.1 %) converge at 0.5 % a sweep: the sweeps stopped on a
 * lopsided answer and the rod, struck symmetrically at 100 m/s, left
 * spinning at 44 rad/s (1000 m/s: 441 rad/s). Returns 0 where it does
 * not apply (the points then go one after the other).
 */
static int cr_bounce_block(const carom_world *w, cr_contact *c, cr_body *A, cr_body *B,
                           float *change, float *biggest)
{
#if CR_TWO_POINTS
    cr_contact_point *p0 = &c->pts[0], *p1 = &c->pts[1];
    float z0, z1, b1, b2, x1, x2, d0, d1;
    if (c->count != 2 || !c->block || !cr_bounces(w, c, p0) || !cr_bounces(w, c, p1))
        return 0;
    z0 = cr_add(p0->pn, p0->pp);
    z1 = cr_add(p1->pn, p1->pp);
    b1 = cr_sub(cr_add(cr_point_vn(A->v, A->w, B->v, B->w, c, p0),
                       cr_mul(c->restitution, p0->rel_vn)),
                cr_add(cr_mul(c->k11, z0), cr_mul(c->k12, z1)));
    b2 = cr_sub(cr_add(cr_point_vn(A->v, A->w, B->v, B->w, c, p1),
                       cr_mul(c->restitution, p1->rel_vn)),
                cr_add(cr_mul(c->k12, z0), cr_mul(c->k22, z1)));
    if (!cr_lcp2(c->k11, c->k12, c->k22, b1, b2, &x1, &x2))
        return 0;
    d0 = cr_sub(x1, z0);
    d1 = cr_sub(x2, z1);
    p0->pp = cr_sub(x1, p0->pn);
    p1->pp = cr_sub(x2, p1->pn);
    cr_apply(A, B, cr_contact_lever_a(c, p0->ra), cr_contact_lever_b(c, p0->rb), c->n, d0);
    cr_apply(A, B, cr_contact_lever_a(c, p1->ra), cr_contact_lever_b(c, p1->rb), c->n, d1);
    *change = cr_max(*change, cr_max(cr_abs(d0), cr_abs(d1)));
    *biggest = cr_max(*biggest, cr_max(cr_abs(p0->pp), cr_abs(p1->pp)));
    return 1;
#else
    (void)w;
    (void)c;
    (void)A;
    (void)B;
    (void)change;
    (void)biggest;
    return 0;
#endif
}

int cr_solver_restitution(carom_world *w)
{
    int i, k, it, bounced = 0, bounced_any = 0;
    const int discrete = CAROM_ENABLE_DISCRETE && w->method == CAROM_METHOD_DISCRETE;
    w->sep_cached = 0;
    /* the bounce impulse of each point, in the position correction's
     * scratch (pp, done by now); it is not kept for the warm start, which
     * is last step's support of a resting contact, not its bounce */
    for (i = 0; i < w->contact_count; ++i)
        for (k = 0; k < w->contacts[i].count; ++k) {
            w->contacts[i].pts[k].pp = 0.0f;
#if CAROM_ENABLE_FRICTION
            w->contacts[i].pts[k].pt_bounce = 0.0f;
#endif
        }
    if (discrete) /* the velocities before the pass, for the energy limit */
        for (i = 0; i < w->contact_count; ++i) {
            const cr_contact *c = &w->contacts[i];
            w->sbody[c->a].vp = w->bodies[c->a].v;
            w->sbody[c->a].wp = w->bodies[c->a].w;
            w->sbody[c->b].vp = w->bodies[c->b].v;
            w->sbody[c->b].wp = w->bodies[c->b].w;
        }
    /* Newton targets, iterated to convergence: simultaneous bounces come
     * out of the same answer whatever the order of the contacts (a cue
     * ball striking two touching balls symmetrically) */
    for (it = 0; it < CR_RESTITUTION_SWEEPS; ++it) {
        float change = 0.0f, biggest = 0.0f;
        for (i = 0; i < w->contact_count; ++i) {
            cr_contact *c = &w->contacts[i];
            cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
            if (!cr_gt(c->restitution, 0.0f))
                continue;
            if (cr_bounce_block(w, c, A, B, &change, &biggest)) {
                for (k = 0; k < c->count; ++k)
                    cr_bounce_friction(c, A, B, &c->pts[k], &change);
                continue;
            }
            for (k = 0; k < c->count; ++k) {
                cr_contact_point *p = &c->pts[k];
                float vn, d, pb;
                if (!cr_bounces(w, c, p))
                    continue;
                vn = cr_point_vn(A->v, A->w, B->v, B->w, c, p);
                d = cr_neg(cr_mul(p->mass_n, cr_add(vn, cr_mul(c->restitution, p->rel_vn))));
                /* the total normal impulse stays >= 0 */
                pb = cr_max(cr_add(p->pp, d), cr_neg(p->pn));
                d = cr_sub(pb, p->pp);
                p->pp = pb;
                cr_apply(A, B, cr_contact_lever_a(c, p->ra), cr_contact_lever_b(c, p->rb),
                         c->n, d);
                change = cr_max(change, cr_abs(d));
                biggest = cr_max(biggest, cr_abs(pb));
                cr_bounce_friction(c, A, B, p, &change);
            }
        }
        bounced_any |= cr_gt(biggest, 0.0f);
        if (!cr_gt(change, cr_mul(CR_RESTITUTION_TOL, biggest)))
            break;
    }
    if (discrete && bounced_any)
        w->stats.bounce_limits += cr_limit_bounce_energy(w);
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        float approach = 0.0f, impulse = 0.0f;
        int hit = 0;
        for (k = 0; k < c->count; ++k) {
            const cr_contact_point *p = &c->pts[k];
            if (!cr_bounces(w, c, p))
                continue;
            hit = 1;
            bounced += cr_gt(c->restitution, 0.0f);
            approach = cr_max(approach, cr_neg(p->rel_vn));
            impulse = cr_add(impulse, cr_add(p->max_pn, p->pp));
        }
        if (hit)
            cr_record_impact(w, c->a, c->b, w->def.dt, c->n, impulse, approach);
    }
    return bounced;
}

/* ---- cold start -------------------------------------------------------------- */

/* Up-component of contact c's normal seen from body `lower` to the other. */
static float cr_lift(const cr_contact *c, int lower, cr_v2 up)
{
    float u = cr_vdot(c->n, up);
    return c->a == lower ? u : cr_neg(u);
}

/* A contact supports its upper body when its normal is within 60 degrees
 * of the vertical. */
#define CR_SUPPORT_COS 0.5f

/* Both sweeps of shock propagation take a point support only within 8
 * degrees of the vertical: along a slanted point (a circle on a circle, a
 * corner on a face), an impulse or a lift with no reaction pushes sideways
 * too, and a pile of circles never settles (with the position sweep on
 * every support within 60 degrees, a pile of 3000 circles and boxes kept
 * sinking, 6 cm in 20 s, with a thousand bodies or more moving:
 * docs/physics.md). A face resting on a face (a two-point contact) is
 * taken at any support angle, on a body that holds it (cr_solver_shock):
 * it is what holds a heavy box on a light one on a slope, where the sweeps
 * alone let a 1000 kg box sink 0.44 m into the 1 kg box under it in 10 s
 * (10 degrees, friction 0.5; 20 degrees: 0.37 m, and 0.45 m down the
 * slope). */
#define CR_SHOCK_COS 0.99f

/* Is contact c a support of body `upper` by the other body `lower`
 * (static, kinematic, or lower in the support order)? Touching or not yet
 * (speculative points, apart): a body about to land is held by what it
 * lands on. With touching supports only, a box landing on a lighter one
 * was left to the sweeps in its landing step (dropped 3 m onto 1 kg, 10
 * kg sank 3.6 cm into it, 100 kg or more 6.8 cm); shock propagation's
 * bias lets a point apart close its gap, and stops it there. */
static int cr_supports(const cr_contact *c, int lower, cr_v2 up)
{
    return c->count > 0 && cr_gt(cr_lift(c, lower, up), CR_SUPPORT_COS);
}

static int cr_up(const carom_world *w, cr_v2 *up)
{
#if !CAROM_ENABLE_STACKING
    /* no support order, priming or shock propagation (what they do for
     * stacks under gravity is compiled out; without gravity they do
     * nothing anyway) */
    (void)w;
    (void)up;
    return 0;
#else
    float g = cr_vlen(w->def.gravity);
    if (!cr_gt(g, 0.0f))
        return 0;
    *up = cr_vscale(cr_div(-1.0f, g), w->def.gravity);
    return 1;
#endif
}

/*
 * Support order: the bodies resting on static (or kinematic) bodies are
 * level 0, those resting on them level 1, and so on (breadth first over
 * touching contacts whose normal is within 60 degrees of the vertical). No
 * gravity, no order.
 */
void cr_solver_levels(carom_world *w)
{
    int *queue = w->support, n = 0, head, i, k;
    cr_v2 up;
    for (i = 0; i < w->slot_count; ++i) {
        w->sbody[i].level = -1;
        w->bodies[i].flags = (unsigned short)(w->bodies[i].flags &
                                              ~(CR_BODY_CAPPED | CR_BODY_SHIFTED | CR_BODY_RESTS));
    }
    /* the bodies an inelastic meeting may land on (cr_onto_rest) */
    for (i = 0; CAROM_ENABLE_EVENTS && !CAROM_EXACT_PILE_IMPACTS &&
                w->method != CAROM_METHOD_DISCRETE && i < w->contact_count;
         ++i) {
        const cr_contact *c = &w->contacts[i];
        if (!(c->flags & CR_CONTACT_TOUCHING) ||
            (!(c->flags & CR_CONTACT_RESTING) &&
             cr_gt(cr_contact_approach(w, c), cr_solver_bound(w, c))))
            continue;
        if (w->bodies[c->a].type == CAROM_BODY_DYNAMIC)
            w->bodies[c->a].flags |= CR_BODY_RESTS;
        if (w->bodies[c->b].type == CAROM_BODY_DYNAMIC)
            w->bodies[c->b].flags |= CR_BODY_RESTS;
    }
    w->support_count = 0;
    if (!cr_up(w, &up))
        return;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        int a = c->a, b = c->b;
        /* a static body resting on a dynamic one is its ceiling */
        if (w->bodies[a].type == CAROM_BODY_STATIC && w->bodies[b].type == CAROM_BODY_DYNAMIC &&
            cr_supports(c, b, up))
            w->bodies[b].flags |= CR_BODY_CAPPED;
        else if (w->bodies[b].type == CAROM_BODY_STATIC &&
                 w->bodies[a].type == CAROM_BODY_DYNAMIC && cr_supports(c, a, up))
            w->bodies[a].flags |= CR_BODY_CAPPED;
        if (w->bodies[a].type != CAROM_BODY_DYNAMIC && w->bodies[b].type == CAROM_BODY_DYNAMIC &&
            w->sbody[b].level < 0 && cr_supports(c, a, up)) {
            w->sbody[b].level = 0;
            queue[n++] = b;
        } else if (w->bodies[b].type != CAROM_BODY_DYNAMIC &&
                   w->bodies[a].type == CAROM_BODY_DYNAMIC && w->sbody[a].level < 0 &&
                   cr_supports(c, b, up)) {
            w->sbody[a].level = 0;
            queue[n++] = a;
        }
    }
    for (head = 0; head < n; ++head) {
        int u = queue[head];
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int v = p->a == u ? p->b : p->a, next = p->a == u ? p->next_a : p->next_b;
            if (p->contact >= 0 && w->sbody[v].level < 0 &&
                w->bodies[v].type == CAROM_BODY_DYNAMIC &&
                cr_supports(&w->contacts[p->contact], u, up)) {
                w->sbody[v].level = w->sbody[u].level + 1;
                queue[n++] = v;
            }
            k = next;
        }
    }
    w->support_count = n;
    cr_solver_mark_shocks(w);
}

/* Does the contact through pair p support body u (from a body below)? */
static int cr_support_of(const carom_world *w, const cr_pair *p, int u, cr_v2 up)
{
    int v = p->a == u ? p->b : p->a;
    if (p->contact < 0)
        return 0;
    if (w->bodies[v].type == CAROM_BODY_DYNAMIC &&
        (w->sbody[v].level < 0 || w->sbody[v].level >= w->sbody[u].level))
        return 0;
    return cr_supports(&w->contacts[p->contact], v, up);
}

/* The flag that marks the contact through pair p a shock support of u. */
static unsigned cr_shock_flag(const cr_pair *p, int u)
{
    return p->a == u ? CR_CONTACT_SHOCK_A : CR_CONTACT_SHOCK_B;
}

/* The unloading acts under a body at least this many times heavier than
 * the one below it (and then down the column it pushes): where the sweeps
 * are slow to take an excess back. Between bodies of like mass they take
 * it back within the substep, and the turning the warm start gives a box
 * whose two points' impulses no longer balance (as much as 5 rad/s in a
 * settled pile of 10^4 bodies, gone after the first sweep) read as a rise
 * kept a deep pile from ever sleeping when every support was unloaded. */
#define CR_UNLOAD_MASS_RATIO 2.0f

/* Is u at least CR_UNLOAD_MASS_RATIO times heavier than the dynamic body
 * `lower` it rests on? */
static int cr_heavy_on(const cr_body *U, const cr_body *lower)
{
    return lower->type == CAROM_BODY_DYNAMIC &&
           cr_le(cr_mul(CR_UNLOAD_MASS_RATIO, U->inv_m), lower->inv_m);
}

/*
 * The shock supports, up the support order. A support is taken only from
 * a body that cannot turn under what it carries (braced): static or
 * kinematic, or resting on a braced body and held by its contacts with
 * everything but what rests on it at two points at least (a face, two
 * bodies, a neighbour), or at one for a circle (its support passes
 * through its centre). A polygon held at one point is a lever: a plank
 * balanced on a single point, held fixed under the loads it carries, had
 * the heavier load's sinking stopped with no reaction on the plank, and
 * the seesaw's angular momentum about its pivot was taken away in every
 * substep (1 kg and 2 kg boxes at either end of a 40 g plank: it turned
 * 23 % short of the lever law at dt 1/60, 69 % short at dt 1e-5 s;
 * test_seesaw_turns_by_the_lever_law_at_any_step).
 */
static int cr_braced(const carom_world *w, int i)
{
    return w->bodies[i].type != CAROM_BODY_DYNAMIC || w->sbody[i].braced;
}

/* Point k of contact c from body u's centre of mass (u is a or b). */
CR_INLINE cr_v2 cr_arm_of(const cr_contact *c, int k, int u)
{
    return c->a == u ? c->pts[k].ra : c->pts[k].rb;
}

/* Where contact c meets body u, across `up` (h), from u's centre of mass:
 * the mean of its points weighted by their normal impulses (the line of
 * action of the load it carries), or their plain mean before any. */
static float cr_load_line(const cr_contact *c, int u, cr_v2 h)
{
    float at = 0.0f, mean = 0.0f, pn = 0.0f;
    int k;
    for (k = 0; k < c->count; ++k) {
        float x = cr_vdot(cr_arm_of(c, k, u), h);
        at = cr_add(at, cr_mul(c->pts[k].pn, x));
        mean = cr_add(mean, x);
        pn = cr_add(pn, c->pts[k].pn);
    }
    return cr_gt(pn, 0.0f) ? cr_div(at, pn) : cr_div(mean, (float)c->count);
}

/*
 * Can body `lower` hold the load of contact c without turning? Static and
 * kinematic bodies and circles (their supports pass through the centre)
 * always; a braced polygon when the load's line of action (cr_load_line)
 * falls within the span, across the vertical, of the points that hold it
 * (marked CR_CONTACT_SPANNED by cr_solver_mark_shocks, within a slop). A
 * plank on a pivot with one end on the floor is braced by the two, but a
 * load on its free end beyond the pivot turns it, lifting the end off the
 * floor: held fixed under that load, the plank took a heavy ball's
 * landing with no reaction, and the ball's angular momentum about the
 * pivot was lost (a 1 kg plank struck at 5 m/s by 100 kg: 3.8 % short
 * after two steps at dt 1/60; 1000 kg: 10 %; the events method's impact
 * solve was right: test_catapult_keeps_the_angular_momentum).
 */
static int cr_holds(const carom_world *w, const cr_contact *c, int lower)
{
    return w->bodies[lower].type != CAROM_BODY_DYNAMIC ||
           CR_BODY_IS_CIRCLE(&w->bodies[lower]) || (c->flags & CR_CONTACT_SPANNED);
}

void cr_solver_mark_shocks(carom_world *w)
{
    int i, k;
    cr_v2 up, h;
    w->shock_marked = w->contact_edits;
    w->heavy_supports = 0;
    for (i = 0; i < w->contact_count; ++i)
        w->contacts[i].flags &= (unsigned short)~(CR_CONTACT_SHOCK_A | CR_CONTACT_SHOCK_B |
                                                  CR_CONTACT_SPANNED);
    if (w->support_count == 0 || !cr_up(w, &up))
        return;
    h = cr_vright(up);
    /* (a supporting body is earlier in the order: level below) */
    for (i = 0; i < w->support_count; ++i)
        w->sbody[w->support[i]].braced = 0;
    for (i = 0; i < w->support_count; ++i) {
        int u = w->support[i], held = 0, on_braced = 0;
        float lo = 0.0f, hi = 0.0f, slop = w->scale.slop;
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int other = p->a == u ? p->b : p->a, j;
            const cr_contact *c = p->contact >= 0 ? &w->contacts[p->contact] : 0;
            k = p->a == u ? p->next_a : p->next_b;
            if (!c)
                continue;
            /* what rests on u is its load, not what holds it */
            if (w->bodies[other].type != CAROM_BODY_DYNAMIC || !cr_supports(c, u, up)) {
                for (j = 0; j < c->count; ++j) {
                    float x = cr_vdot(cr_arm_of(c, j, u), h);
                    lo = held + j == 0 ? x : cr_min(lo, x);
                    hi = held + j == 0 ? x : cr_max(hi, x);
                }
                held += c->count;
            }
            if (cr_support_of(w, p, u, up) && cr_braced(w, other) && cr_holds(w, c, other)) {
                on_braced = 1;
                if (cr_gt(cr_lift(c, other, up),
                          c->count == 2 ? CR_SUPPORT_COS : CR_SHOCK_COS)) {
                    w->contacts[p->contact].flags |= (unsigned short)cr_shock_flag(p, u);
                    w->heavy_supports += cr_heavy_on(&w->bodies[u], &w->bodies[other]);
                }
            }
        }
        w->sbody[u].braced =
            (unsigned char)(on_braced && held >= (CR_BODY_IS_CIRCLE(&w->bodies[u]) ? 1 : 2));
        if (!w->sbody[u].braced || CR_BODY_IS_CIRCLE(&w->bodies[u]))
            continue;
        /* the loads it holds without turning */
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            cr_contact *c = p->contact >= 0 ? &w->contacts[p->contact] : 0;
            int other = p->a == u ? p->b : p->a;
            float x;
            k = p->a == u ? p->next_a : p->next_b;
            if (!c || w->bodies[other].type != CAROM_BODY_DYNAMIC || !cr_supports(c, u, up))
                continue;
            x = cr_load_line(c, u, h);
            if (!cr_lt(x, cr_sub(lo, slop)) && !cr_gt(x, cr_add(hi, slop)))
                c->flags |= CR_CONTACT_SPANNED;
        }
    }
}

/* Does shock propagation take the contact through pair p, with u above? */
static int cr_shock_of(const carom_world *w, const cr_pair *p, int u)
{
    return p->contact >= 0 &&
           (w->contacts[p->contact].flags & cr_shock_flag(p, u)) &&
           (w->contacts[p->contact].flags & CR_CONTACT_SOLVE);
}

/*
 * Support impulses from the weights (Guendelman et al.'s shock propagation,
 * used only to start the solver): walk the support order down: each body
 * hands its weight, plus what it carries, to the contacts beneath it,
 * shared equally among them and between the two points of a face by the
 * lever rule. Exact for a column, close for a pyramid or a pile; the
 * velocity sweeps correct the rest. Contacts that already have an impulse
 * from the last step keep it.
 */
void cr_solver_prime(carom_world *w, const cr_substep *s)
{
    float g = cr_vlen(w->def.gravity);
    int i, k;
    cr_v2 up;
#ifdef CR_DEBUG_NO_PRIME
    return;
#endif
    if (!cr_up(w, &up))
        return;
    for (i = 0; i < w->support_count; ++i) {
        int u = w->support[i];
        w->sbody[u].u.load = cr_mul(cr_mul(w->info[u].m, g), s->h);
    }
    for (i = w->support_count - 1; i >= 0; --i) {
        int u = w->support[i], supports = 0;
        float share;
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            supports += cr_support_of(w, p, u, up);
            k = p->a == u ? p->next_a : p->next_b;
        }
        if (supports == 0)
            continue;
        share = cr_div(w->sbody[u].u.load, (float)supports);
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int v = p->a == u ? p->b : p->a, next = p->a == u ? p->next_a : p->next_b;
            if (cr_support_of(w, p, u, up)) {
                cr_contact *c = &w->contacts[p->contact];
                float total = cr_div(share, cr_lift(c, v, up));
                int warm = 0, j;
                for (j = 0; j < c->count; ++j)
                    warm |= !cr_eq(c->pts[j].pn, 0.0f);
                if (CR_TWO_POINTS && !warm && c->count == 2) {
                    /* lever rule about u's centre along the face */
                    cr_v2 t = cr_vright(c->n);
                    float d1 = cr_vdot(u == c->a ? c->pts[0].ra : c->pts[0].rb, t);
                    float d2 = cr_vdot(u == c->a ? c->pts[1].ra : c->pts[1].rb, t);
                    float span = cr_sub(d2, d1);
                    float f1 = cr_gt(cr_abs(span), 0.0f)
                                   ? cr_clamp(cr_div(d2, span), 0.0f, 1.0f) : 0.5f;
                    c->pts[0].pn = cr_mul(total, f1);
                    c->pts[1].pn = cr_mul(total, cr_sub(1.0f, f1));
                } else if (!warm) {
                    c->pts[0].pn = total;
                }
                if (w->bodies[v].type == CAROM_BODY_DYNAMIC)
                    w->sbody[v].u.load = cr_add(w->sbody[v].u.load, share);
            }
            k = next;
        }
    }
}

/*
 * Shock propagation (Guendelman, Bridson, Fedkiw 2003): one more velocity
 * sweep, up the support order, in which every supporting contact is solved
 * as if the body below could not move. A support then always has the last
 * word on what rests on it, whatever the mass ratio: Gauss-Seidel alone
 * needs about m_heavy / m_light sweeps to stop a heavy box on a light one.
 * Only supports between supported bodies take part (a point within 8
 * degrees of the vertical, a face within 60: CR_SHOCK_COS), and only to
 * stop an approach; the body below is not pushed back (its own support,
 * solved before, has stopped it: the floor takes the reaction), and the
 * impulse is not kept for the warm start, which stays the load the sweeps
 * found.
 *
 * A slanted face is taken only on a body held where it is (anchored):
 * static or kinematic, level on an anchored body, or stuck by friction to
 * an anchored body on a slanted face of its own; there the pass also
 * stops the slip along the face, within the friction cone
 * (cr_shock_friction). On a body that slides, the push would hold up what
 * rests on it with no reaction on the body under it, whose friction with
 * the slope then lacks the load: 1 kg under 100 kg, sliding down a 25
 * degree slope (friction 0.3 on the slope, 0.8 between them), went 20 %
 * too far in 2 s; left to the sweeps there, it goes as far as it should.
 */
/* Impulses x >= 0 on body u alone (the body below held fixed) at the
 * points of contact c, removing the velocity errors err[] (> 0 where the
 * point still sinks): a 2-point face as one 2x2 problem, so the body is
 * stopped level, without spin. Returns the count of points (0: nothing). */
static int cr_one_sided(const carom_world *w, const cr_contact *c, int u,
                        const float *err, float *x)
{
    const cr_body *U = &w->bodies[u];
    float l[CR_MANIFOLD_POINTS], kk[CR_MANIFOLD_POINTS];
    int j, any = 0;
    for (j = 0; j < c->count; ++j) {
        cr_v2 r = u == c->b ? c->pts[j].rb : c->pts[j].ra;
        l[j] = cr_normal_lever(w, u, r, c->n);
        kk[j] = cr_add(U->inv_m, cr_mul(U->inv_I, cr_mul(l[j], l[j])));
        x[j] = 0.0f;
        any |= cr_gt(err[j], 0.0f) && cr_gt(kk[j], 0.0f);
    }
    if (!any)
        return 0;
#if CR_TWO_POINTS
    if (CR_TWO_POINTS && c->count == 2) {
        float k12 = cr_add(U->inv_m, cr_mul(U->inv_I, cr_mul(l[0], l[1])));
        float det = cr_sub(cr_mul(kk[0], kk[1]), cr_mul(k12, k12));
        if (cr_gt(det, cr_mul(1.0e-3f, cr_mul(kk[0], kk[1]))) &&
            cr_lcp2(kk[0], k12, kk[1], cr_neg(err[0]), cr_neg(err[1]), &x[0], &x[1]))
            return 2;
    }
#endif
    for (j = 0; j < c->count; ++j)
        x[j] = cr_gt(kk[j], 0.0f) ? cr_max(0.0f, cr_div(err[j], kk[j])) : 0.0f;
    return c->count == 2 ? 1 : c->count; /* sequential fallback: approximate */
}

/* Apply impulse x along the normal, upwards, at point j to body u alone:
 * to its velocity (pseudo = 0) or its pseudo-velocity. */
static void cr_push_up(carom_world *w, const cr_contact *c, int u, int j, float x,
                       int pseudo)
{
    cr_body *U = &w->bodies[u];
    cr_solver_body *su = &w->sbody[u];
    float sign = u == c->b ? 1.0f : -1.0f;
    cr_v2 r = u == c->b ? c->pts[j].rb : c->pts[j].ra;
    float lever = cr_normal_lever(w, u, r, c->n);
    cr_v2 dv = cr_vscale(cr_mul(cr_mul(sign, x), U->inv_m), c->n);
    float dw = cr_mul(cr_mul(sign, U->inv_I), cr_mul(lever, x));
    if (pseudo) {
        su->vp = cr_vadd(su->vp, dv);
        su->wp = cr_add(su->wp, dw);
    } else {
        U->v = cr_vadd(U->v, dv);
#if CAROM_ENABLE_ROTATION
        U->w = cr_add(U->w, dw);
#endif
    }
#if !CAROM_ENABLE_ROTATION
    (void)dw;
#endif
}

/* The normal velocities, seen from below up, of body u's point j of its
 * supporting contact c (*vu) and of the supporting body's (*vl). */
/* The normal velocity, seen from below up (upper_b: the upper body is
 * contact c's b), of the point at arm r of a body moving at (v, om). */
CR_INLINE float cr_vn_up(const cr_contact *c, int upper_b, cr_v2 r, cr_v2 v, float om)
{
    return cr_mul(upper_b ? 1.0f : -1.0f, cr_vdot(cr_point_velocity(v, om, r), c->n));
}

CR_INLINE void cr_support_vn(const carom_world *w, const cr_contact *c, int u, int j,
                             float *vu, float *vl)
{
    const cr_contact_point *cp = &c->pts[j];
    const int upper_b = u == c->b;
    const cr_body *U = &w->bodies[u], *L = &w->bodies[upper_b ? c->a : c->b];
    *vu = cr_vn_up(c, upper_b, upper_b ? cp->rb : cp->ra, U->v, U->w);
    *vl = cr_vn_up(c, upper_b, upper_b ? cp->ra : cp->rb, L->v, L->w);
}

/* Is the shock support p of body u by `lower` slanted (beyond
 * CR_SHOCK_COS: a face on a face, as only those are taken there)? */
static int cr_slanted(const carom_world *w, const cr_pair *p, int lower, cr_v2 up)
{
    return !cr_gt(cr_lift(&w->contacts[p->contact], lower, up), CR_SHOCK_COS);
}

#if CAROM_ENABLE_FRICTION
/* Shock propagation's friction, on a slanted support (beyond CR_SHOCK_COS)
 * after its normal impulses x[0..n-1]: the slip of body u along contact c
 * against the body below (at the mean of its points) is stopped by u
 * alone, within the Coulomb cone of the contact's normal impulse,
 * accumulated and added. Returns 1 if the slip was stopped within the
 * cone (u sticks). `keep`: the body below is static or kinematic, and the
 * impulse is added to the contact's friction, as its normal ones are
 * (cr_solver_shock).
 *
 * On a slope the friction carries the weight's share along the face, and
 * the sweeps alone hold a heavy box on a light one about m_light / m_heavy
 * as well as it needs: 1000 kg on 1 kg on a 20 degree slope (friction
 * 0.5), held up by the normal push alone, slid off it in 10 s; with this,
 * 5 cm. On a level support nothing loads the friction, and the pass is
 * left out: there it only turned rounding into sway (a 25-box column of
 * slender boxes, each stopped against the one below through its own
 * rotation, was 2 cm off after 10 s, where without it it stays exact). */
static int cr_shock_friction(carom_world *w, cr_contact *c, int u, const float *x, int n,
                             int keep)
{
    cr_body *U = &w->bodies[u];
    const int upper_b = u == c->b;
    const cr_body *L = &w->bodies[upper_b ? c->a : c->b];
    cr_v2 t = cr_vright(c->n), ru = cr_v(0.0f, 0.0f), rl = cr_v(0.0f, 0.0f);
    float pn = 0.0f, pt = 0.0f, vt, lever, k, f, limit, d;
    int j;
    for (j = 0; j < c->count; ++j) {
        const cr_contact_point *cp = &c->pts[j];
        ru = cr_vadd(ru, upper_b ? cp->rb : cp->ra);
        rl = cr_vadd(rl, upper_b ? cp->ra : cp->rb);
        pn = cr_add(pn, j < n ? cr_add(cp->pn, x[j]) : cp->pn);
        pt = cr_add(pt, cp->pt);
    }
    if (!cr_gt(pn, 0.0f))
        return 0;
    if (c->count == 2) {
        ru = cr_vscale(0.5f, ru);
        rl = cr_vscale(0.5f, rl);
    }
    vt = cr_vdot(cr_vsub(cr_point_velocity(U->v, U->w, ru), cr_point_velocity(L->v, L->w, rl)),
                 t);
    lever = cr_vcross(ru, t);
    k = cr_add(U->inv_m, cr_mul(U->inv_I, cr_mul(lever, lever)));
    if (!cr_gt(k, 0.0f))
        return 0;
    /* the friction on u so far (pt acts on body b, its opposite on a) */
    f = upper_b ? pt : cr_neg(pt);
    limit = cr_mul(c->friction, pn);
    {
        float want = cr_sub(f, cr_div(vt, k)), got = cr_clamp(want, cr_neg(limit), limit);
        d = cr_sub(got, f);
        if (keep) {
            /* shared between the points as their normal impulses */
            float dp = upper_b ? d : cr_neg(d);
            if (c->count == 2) {
                float both = cr_add(c->pts[0].pn, c->pts[1].pn);
                float share = cr_gt(both, 0.0f) ? cr_div(c->pts[0].pn, both) : 0.5f;
                c->pts[0].pt = cr_add(c->pts[0].pt, cr_mul(share, dp));
                c->pts[1].pt = cr_add(c->pts[1].pt, cr_mul(cr_sub(1.0f, share), dp));
            } else {
                c->pts[0].pt = cr_add(c->pts[0].pt, dp);
            }
        }
        U->v = cr_vadd(U->v, cr_vscale(cr_mul(d, U->inv_m), t));
#if CAROM_ENABLE_ROTATION
        U->w = cr_add(U->w, cr_mul(cr_mul(d, U->inv_I), lever));
#endif
        return cr_eq(want, got);
    }
}
#endif

void cr_solver_shock(carom_world *w, const cr_substep *s)
{
    int i, k, j;
    cr_v2 up;
#if defined(CR_DEBUG_NO_SHOCK) || defined(CR_DEBUG_NO_VSHOCK)
    return;
#endif
    if (!cr_up(w, &up))
        return;
    for (i = 0; i < w->support_count; ++i)
        w->sbody[w->support[i]].walk = 0; /* anchored */
    for (i = 0; i < w->support_count; ++i) {
        int u = w->support[i];
        if (w->bodies[u].flags & CR_BODY_CAPPED)
            continue; /* a static body above has the last word */
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int next = p->a == u ? p->next_a : p->next_b;
            int lower = p->a == u ? p->b : p->a;
            int fixed = w->bodies[lower].type != CAROM_BODY_DYNAMIC; /* static, kinematic */
            int anchored = fixed || w->sbody[lower].walk;
            int shock = cr_shock_of(w, p, u), slanted = shock && cr_slanted(w, p, lower, up);
            if (shock && (anchored || !slanted)) {
                cr_contact *c = &w->contacts[p->contact];
                const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
                float err[CR_MANIFOLD_POINTS], x[CR_MANIFOLD_POINTS];
                int n;
                for (j = 0; j < c->count; ++j) {
                    const cr_contact_point *cp = &c->pts[j];
                    float sep = w->sep_cached ? cp->pp : cr_current_sep(c, cp, sa, sb);
                    float bias = cr_gt(sep, 0.0f) ? cr_mul(sep, s->inv_h) : 0.0f;
                    float vu, vl;
                    cr_support_vn(w, c, u, j, &vu, &vl);
                    /* stop a sinking body, never lift one: a support moving
                     * up is no reason to push what rests on it (that would
                     * be momentum from nowhere) */
                    err[j] = cr_neg(cr_add(cr_sub(vu, cr_min(vl, 0.0f)), bias));
                }
                n = cr_one_sided(w, c, u, err, x);
                for (j = 0; j < n; ++j)
                    cr_push_up(w, c, u, j, x[j], 0);
                if (CR_TWO_POINTS && n == 1 && c->count == 2) {
                    /* sequential: the second point after the first */
                    float vu, vl, e2, e[2], y[2];
                    cr_support_vn(w, c, u, 1, &vu, &vl);
                    e2 = cr_neg(cr_sub(vu, cr_min(vl, 0.0f)));
                    e[0] = 0.0f;
                    e[1] = e2;
                    if (cr_one_sided(w, c, u, e, y))
                        cr_push_up(w, c, u, 1, y[1], 0);
                }
                /* on a static or kinematic body a one-sided impulse is
                 * the contact's own (what it pushes against cannot move):
                 * kept, so that the sweeps' friction of the next substep
                 * has the load (a light box under a heavy one sliding down
                 * a slope: 1000:1 went 45 % too far, now 7 to 11 %) */
                if (slanted && fixed)
                    for (j = 0; j < n; ++j)
                        c->pts[j].pn = cr_add(c->pts[j].pn, x[j]);
                /* held where it is by what is under it: level, on an
                 * anchored body with friction (a wedge on a frictionless
                 * floor slides away under a block on its slope: held, the
                 * block's push along the slope's normal had no reaction,
                 * and a 100 kg block gave the system 1 kg m/s of
                 * sideways momentum in 0.3 s); slanted, by friction
                 * within its cone */
#if CAROM_ENABLE_FRICTION
                if (slanted ? cr_shock_friction(w, c, u, x, n, fixed)
                            : anchored && cr_gt(c->friction, 0.0f))
                    w->sbody[u].walk = 1;
#endif
                /* (without friction nothing holds a body sideways: none
                 * is anchored but static and kinematic ones) */
            }
            k = next;
        }
    }
}

/*
 * Unloading the warm start. The impulses a substep carries into the next
 * are its load, except where it stopped an impact: a heavy box landing on
 * a light one leaves both contacts of the column holding the heavy box's
 * momentum, and carried into the next substep those impulses throw both
 * boxes up (Gauss-Seidel needs about m_heavy / m_light sweeps to take
 * them back: a box ten times heavier, falling at 2.6 m/s onto a light box
 * with restitution 0, left the step with the light box rising at 4.7 m/s).
 * So after the warm start, down the support order (top first), where a
 * body at least CR_UNLOAD_MASS_RATIO times heavier than its support rises
 * off it faster than the rest speed, the support's impulse is reduced
 * (never below zero) until it no longer does, reckoned with the body
 * alone (the one below held fixed, as shock propagation does), and
 * applied to both bodies: the body below, now rising in its turn, has its
 * own supports reduced next, whatever their masses. A column is unloaded
 * in one pass, down to the static body that takes the rest; resting
 * contacts, which the warm start leaves at rest, are untouched.
 *
 * The heavy body's rise counts against its support, or against its own
 * motion before the warm start, whichever is larger: a column that the
 * warm start throws up together rises off nothing but the floor. A 10 kg
 * box on a 1 kg box, both landing on the floor at 5 m/s in contact, was
 * thrown up at 5 m/s in the second substep and left the step rising at
 * 5.8 m/s (restitution 0, discrete method); a kinematic elevator starting
 * at 1 m/s under them threw them up at 2 to 3 m/s.
 */
/* The normal velocity, seen from below up, that body u's point j of its
 * support c had before the warm start (the substep's start velocity and
 * the kick of its forces). */
static float cr_prewarm_vn(const carom_world *w, const cr_contact *c, int u, int j,
                           const cr_substep *s)
{
    const cr_body *U = &w->bodies[u];
    const cr_solver_body *su = &w->sbody[u];
    const int upper_b = u == c->b;
    cr_v2 v = cr_vmadd(su->v0, s->h, U->a);
    float om = su->w0;
#if CAROM_ENABLE_ROTATION
    om = cr_add(om, cr_mul(s->h, U->alpha));
#endif
    return cr_vn_up(c, upper_b, upper_b ? c->pts[j].rb : c->pts[j].ra, v, om);
}

void cr_solver_unload(carom_world *w, const cr_substep *s)
{
    int i, k, j;
    /* (no support order without gravity: nothing to walk; nothing to
     * unload without a heavy body on a light one) */
    if (!CAROM_ENABLE_STACKING || w->heavy_supports == 0)
        return;
    for (i = 0; i < w->support_count; ++i)
        w->sbody[w->support[i]].walk = 0;
    for (i = w->support_count - 1; i >= 0; --i) {
        int u = w->support[i];
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int next = p->a == u ? p->next_a : p->next_b;
            if (cr_shock_of(w, p, u)) {
                cr_contact *c = &w->contacts[p->contact];
                cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
                const cr_body *U = u == c->b ? B : A, *L = u == c->b ? A : B;
                float rest;
                float err[CR_MANIFOLD_POINTS], x[CR_MANIFOLD_POINTS];
                int n, any = 0;
                /* only under a body CR_UNLOAD_MASS_RATIO times heavier, or
                 * under one an unloading above has pushed up */
                if (!w->sbody[u].walk && !cr_heavy_on(U, L)) {
                    k = next;
                    continue;
                }
                rest = cr_rest_speed(w, c->a, c->b);
                for (j = 0; j < c->count; ++j) {
                    float vu, vl, rise;
                    cr_support_vn(w, c, u, j, &vu, &vl);
                    rise = cr_sub(vu, vl);
                    if (w->sbody[u].active)
                        rise = cr_max(rise, cr_sub(vu, cr_prewarm_vn(w, c, u, j, s)));
                    err[j] = cr_gt(rise, rest) && cr_gt(c->pts[j].pn, 0.0f) ? rise : 0.0f;
                    any |= cr_gt(err[j], 0.0f);
                }
                if (any) {
                    n = cr_one_sided(w, c, u, err, x);
                    for (j = 0; j < n; ++j) {
                        cr_contact_point *cp = &c->pts[j];
                        float d = cr_min(x[j], cp->pn);
                        cr_apply(A, B, cr_contact_lever_a(c, cp->ra), cr_contact_lever_b(c, cp->rb),
                                 c->n, cr_neg(d));
                        cp->pn = cr_sub(cp->pn, d);
                        if (cr_gt(d, 0.0f))
                            w->sbody[u == c->b ? c->a : c->b].walk = 1;
#if CAROM_ENABLE_FRICTION
                        {
                            /* friction within the cone of what is left */
                            float limit = cr_mul(c->friction, cp->pn);
                            float pt = cr_clamp(cp->pt, cr_neg(limit), limit);
                            if (!cr_eq(pt, cp->pt)) {
                                cr_apply_tangent(A, B, c, j, cr_sub(pt, cp->pt));
                                cp->pt = pt;
                            }
                        }
#endif
                    }
                }
            }
            k = next;
        }
    }
}

/* The position sweep's shock propagation: up the support order, what
 * overlap a supported body still has with what is below it is removed by
 * moving it alone (a heavy box is lifted out of a light one instead of
 * pressing the light one into the floor). */
static void cr_correct_shock(carom_world *w, const cr_substep *s, float cap)
{
    int i, k, j;
    cr_v2 up;
#ifdef CR_DEBUG_NO_SHOCK
    return;
#endif
    if (!cr_up(w, &up))
        return;
    for (i = 0; i < w->support_count; ++i) {
        int u = w->support[i];
        if (w->bodies[u].flags & CR_BODY_CAPPED)
            continue; /* a static body above has the last word */
        for (k = w->pair_head[u]; k >= 0;) {
            const cr_pair *p = &w->pairs[k];
            int next = p->a == u ? p->next_a : p->next_b;
            int lower = p->a == u ? p->b : p->a;
            /* a slanted face only on a static or kinematic body */
            if (cr_shock_of(w, p, u) && (w->bodies[lower].type != CAROM_BODY_DYNAMIC ||
                                         !cr_slanted(w, p, lower, up))) {
                const cr_contact *c = &w->contacts[p->contact];
                const cr_solver_body *sa = &w->sbody[c->a], *sb = &w->sbody[c->b];
                float sign = u == c->b ? 1.0f : -1.0f;
                float err[CR_MANIFOLD_POINTS], x[CR_MANIFOLD_POINTS];
                int n;
                for (j = 0; j < c->count; ++j) {
                    float sep = cr_current_sep(c, &c->pts[j], sa, sb);
                    float fix = cr_min(cr_mul(CAROM_POSITION_CORRECTION, cr_excess_overlap(w, c, sep)), cap);
                    float target = cr_mul(cr_max(fix, 0.0f), s->inv_h);
                    /* what the pseudo-velocities already lift, seen from u */
                    float vn = cr_mul(sign, cr_pseudo_vn(w, c, j));
                    err[j] = cr_gt(fix, 0.0f) ? cr_sub(target, cr_mul(sign, vn)) : 0.0f;
                }
                n = cr_one_sided(w, c, u, err, x);
                for (j = 0; j < n; ++j)
                    cr_push_up(w, c, u, j, x[j], 1);
            }
            k = next;
        }
    }
}
