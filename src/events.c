/*
 * events.c -- the events methods: every impact at its instant, in time
 * order.
 *
 * Within each contact substep (solver.c) the bodies move along drifts: a
 * body in resting contact from its start velocity to its solved velocity,
 * a free body along its Verlet parabola. This module is that motion: it
 * keeps, for every candidate pair that the contact solver does not take
 * (pairs apart, or approaching faster than the rest speed), the instant of
 * its next impact (toi.c), in a binary heap; it takes the earliest impact,
 * moves only the bodies involved to that instant, solves it, and searches
 * again only the pairs of those bodies. Bodies without impacts are never
 * touched: they follow their drifts exactly. The cost of an impact is the
 * number of pairs of its bodies, not the number of pairs in the world.
 *
 * Simultaneous impacts. Impacts at the same instant (within
 * CAROM_SIMULTANEOUS_TIME_TOL of the step) are solved together, with the
 * resting contacts that link their bodies (a ball striking a stack meets
 * the whole stack, through the contacts, up to
 * CAROM_IMPACT_ISLAND_MAX_BODIES bodies): one small problem
 *     vn+ >= target, impulse >= 0, one of them tight, at every contact,
 * target = e vn- (Newton) where the approach vn- exceeds the rest speed and
 * 0 elsewhere, with Coulomb friction, iterated to convergence. The result
 * does not depend on the order of the bodies (to rounding), so a
 * mirror-symmetric scene stays symmetric; impacts that are not simultaneous
 * (Newton's cradle with gaps, the pi billiard) are taken one by one.
 *
 * After an impact the bodies keep touching where they touch: for the rest
 * of the substep their drifts are corrected so that no touching contact of
 * the island closes in (an inelastic landing stays on the floor however
 * long the step), and the contact joins the solver at the next substep.
 *
 * Budget: after max_impacts impacts in a step the rest of the step's
 * contacts are solved together by the contact solver, with restitution at
 * the end of the step, as in the discrete method (counted in
 * carom_stats.budget_steps). Momentum is conserved either way.
 */
#include "events.h"

#include "narrowphase.h"
#include "solver.h"
#include "toi.h"

#if CAROM_ENABLE_EVENTS

/* Convergence of a simultaneous impact solve: a sweep changes no point's
 * velocity by more than CR_ISLAND_TOL of the fastest approach of the
 * island, or CR_ISLAND_REST_TOL of its rest speed (below which speeds are
 * resting contact anyway): float rounding in zero gravity, a small
 * fraction of what any contact resolves under gravity. */
#define CR_ISLAND_TOL 1.0e-6f
#define CR_ISLAND_REST_TOL 1.0e-5f

/* Sweeps that keep an island's touching contacts from closing in for the
 * rest of the substep (cr_hold_contacts). */
#define CR_HOLD_SWEEPS 8
/* Earlier holds an island's hold tells apart (cr_hold_keep). */
#define CR_HOLD_KEPT_GROUPS 16
/* Sweeps of the solve after each ring of rows joins a growing island
 * (cr_island_grow): it only has to show which contacts the new rows push;
 * the island is solved to convergence once, when it stops growing. A
 * full solve per ring made an impact into a deep pile cost one converged
 * solve per ring of bodies (1.7x the time of a 10^4-body pile). */
#define CR_GROW_SWEEPS 16
/* An island solve still moving after this many sweeps (and every 16
 * more) tries the exact solve of its acting rows (cr_rows_direct); a
 * pivot below this fraction of the largest diagonal entry means
 * redundant rows, left to the sweeps. Rounding leaves a redundant
 * system pivots of a few float epsilons (1.2e-7) of the diagonal; a
 * chain of rows through bodies of mass ratio R leaves about 1 / R, which
 * the sweeps hardly move (a box 1000 times heavier landing on a light
 * box on the floor: each sweep took 1/1000 of the heavy box's momentum,
 * 128 sweeps left it 95 % of its speed, and it sank through the light
 * box at 1e-3, the old bound). Chains up to about R = 1e5 are solved;
 * past that (R = 1e6) elimination in float is too coarse, the instant is
 * unsettled, and its contacts stay the solver's (CR_CONTACT_UNSETTLED). */
#define CR_DIRECT_AFTER 8
#define CR_DIRECT_MIN_PIVOT 1.0e-6f
/* pairs taken again at the instant they were taken at, before the rest
 * of that instant is the solver's (cr_events_advance): piles of 500 take
 * a pair again up to between 8 and 32 times at one instant (8 changed
 * their runs; 32 changes none of the scene library's) */
#define CR_INSTANT_REHITS 32
/* ... and one with an impulse larger than this many times the momentum
 * its rows' bodies could need, the sum of m (|v| before the instant + the
 * largest velocity an unknown lacks): a squeeze with no bounded answer (a body caught
 * between kinematic blades closing on it), whose nearly singular system
 * sent a 0.1 g body off at 10^10 m/s */
#define CR_DIRECT_MAX_GAIN 10.0f
/* A solve that has stalled stops: after at least CR_STALL_MIN sweeps and
 * twice as many sweeps as it has rows (an impulse crosses a chain of rows,
 * a Newton's cradle, one row per sweep, and the change stays level while
 * it does), a change that has not halved over the last CR_STALL_SPAN
 * sweeps is a slowly converging frictional island in a pile (its change
 * falls about 0.6x per doubling of the sweeps), and what is left of it is
 * the contact solver's, as it is for every contact in the discrete
 * method. Measured on a falling pile of 10^4 bodies, a quarter of the
 * converged solves ran into the CAROM_IMPACT_ISLAND_ITERATIONS cap and
 * took more than half of all the sweeps of the events method. */
#define CR_STALL_MIN 32
#define CR_STALL_SPAN 16

/* An impact instant may leave its island with at most this fraction more
 * kinetic energy than before it (rounding); past it the energy limit
 * (cr_limit_impact_energy) acts. */
#define CR_IMPACT_ENERGY_TOL 1.0e-4f

/* Smallest det(K) / (k11 k22) for which a 2-point row is solved as a block
 * (1 - cos^2 of the angle between the two points' impulse rows). */
#define CR_BLOCK_MIN_DET 1.0e-3f

#endif


void cr_pairs_link(carom_world *w)
{
    /* (locals: the int stores could otherwise be into *w) */
    int *head = w->pair_head, i, slots = w->slot_count;
    cr_pair *pairs = w->pairs;
    for (i = 0; i < slots; ++i)
        head[i] = -1;
    for (i = w->pair_count - 1; i >= 0; --i) {
        cr_pair *p = &pairs[i];
        p->next_a = head[p->a];
        head[p->a] = i;
        p->next_b = head[p->b];
        head[p->b] = i;
    }
}

void cr_drifts_begin(carom_world *w)
{
    /* (locals: the stores into the drifts could otherwise be into *w) */
    cr_drift *drift = w->drift;
    const cr_body *bodies = w->bodies;
    int i, slots = w->slot_count;
    for (i = 0; i < slots; ++i) {
        cr_drift *d = &drift[i];
        const cr_body *b = &bodies[i];
        d->t = 0.0f;
        if (b->type == CAROM_BODY_DYNAMIC && (b->flags & CR_BODY_AWAKE)) {
            d->a = b->a;
            d->alpha = b->alpha;
        } else {
            d->a = cr_v(0.0f, 0.0f);
            d->alpha = 0.0f;
        }
        ++d->version;
    }
}

void cr_sync_all(carom_world *w, float t)
{
    cr_body *bodies = w->bodies;
    cr_drift *drift = w->drift;
    const int *awake = w->awake;
    int i, n = w->awake_count;
    for (i = 0; i < n; ++i) {
        int id = awake[i];
        cr_sync(&bodies[id], &drift[id], t);
    }
}

#if CAROM_ENABLE_EVENTS

static int cr_moving(const cr_body *b)
{
    return b->type != CAROM_BODY_STATIC && (b->flags & CR_BODY_AWAKE);
}

static cr_mover cr_mover_of(const carom_world *w, int i)
{
    cr_mover m;
    m.s = &w->info[i].shape;
    m.b = &w->bodies[i];
    m.d = &w->drift[i];
    return m;
}

/* ---- the heap of impact times ---------------------------------------------- */

static int cr_entry_less(const cr_heap_entry *x, const cr_heap_entry *y)
{
    /* earliest first; at equal times the lower pair, so the order never
     * depends on how the heap was filled */
    return cr_lt(x->t, y->t) || (cr_eq(x->t, y->t) && x->pair < y->pair);
}

static void cr_heap_sift_down(carom_world *w, int i)
{
    cr_heap_entry *h = w->heap;
    int n = w->heap_count;
    for (;;) {
        int l = 2 * i + 1, r = l + 1, m = i;
        cr_heap_entry t;
        if (l < n && cr_entry_less(&h[l], &h[m]))
            m = l;
        if (r < n && cr_entry_less(&h[r], &h[m]))
            m = r;
        if (m == i)
            return;
        t = h[i];
        h[i] = h[m];
        h[m] = t;
        i = m;
    }
}

static void cr_heap_sift_up(carom_world *w, int i)
{
    cr_heap_entry *h = w->heap;
    while (i > 0) {
        int parent = (i - 1) / 2;
        cr_heap_entry t;
        if (!cr_entry_less(&h[i], &h[parent]))
            return;
        t = h[i];
        h[i] = h[parent];
        h[parent] = t;
        i = parent;
    }
}

static void cr_heap_pop(carom_world *w)
{
    w->heap[0] = w->heap[--w->heap_count];
    cr_heap_sift_down(w, 0);
}

/* Rebuild from the pairs' current times (drops every stale entry). */
static void cr_heap_rebuild(carom_world *w)
{
    int i;
    w->heap_count = 0;
    for (i = 0; i < w->pair_count; ++i) {
        const cr_pair *p = &w->pairs[i];
        if (!cr_le(p->toi, w->def.dt))
            continue;
        w->heap[w->heap_count].t = p->toi;
        w->heap[w->heap_count].pair = i;
        w->heap[w->heap_count].stamp = p->stamp;
        ++w->heap_count;
    }
    for (i = w->heap_count / 2 - 1; i >= 0; --i)
        cr_heap_sift_down(w, i);
}

static void cr_heap_push(carom_world *w, int pair)
{
    const cr_pair *p = &w->pairs[pair];
    if (w->heap_count >= w->heap_cap) {
        cr_heap_rebuild(w); /* holds at most one entry per pair */
        return;
    }
    w->heap[w->heap_count].t = p->toi;
    w->heap[w->heap_count].pair = pair;
    w->heap[w->heap_count].stamp = p->stamp;
    cr_heap_sift_up(w, w->heap_count++);
}

/* ---- searching a pair ------------------------------------------------------- */

static int cr_solved_contact(const carom_world *w, const cr_pair *p)
{
    return p->contact >= 0 && (w->contacts[p->contact].flags & CR_CONTACT_SOLVE);
}

/* The approach speed above which the pair is an impact. */
static float cr_impact_speed(const carom_world *w, int a, int b, float scale)
{
    return cr_add(cr_rest_speed(w, a, b), cr_mul(CR_IMPACT_REL_TOL, scale));
}

/* A polygon of the pair turning so fast that its extent sweeps more
 * than CR_PIVOT_REACH slops before the step ends: touching (and not
 * approaching), the pair is on a pivot, searched past for the next part
 * of it to come down (the far corner of a box spun by a corner's impact,
 * or tipping onto its face), not a contact for the solver, which sees
 * only the points it was made with. Not a resting contact (those stay
 * the solver's), and not in the first-impact method, which searches a
 * pair once a step. */
#define CR_PIVOT_REACH 2.0f
/* Searches past pivots a step may make, per body of the world; past them
 * a pivot is the solver's, as before. A light body squeezed between heavy
 * ones (masses 1e5 apart), left unsupported on its pivots, struck them
 * again and again at one instant, to the impact budget (16,384): 22
 * times the impacts and up to 24 times the time of a 12-body scene. A
 * smaller budget bounds that better but lets more fast bodies out: of
 * the 103 scenes of a random sweep where some build failed, 16 a body
 * let 15 out, 64 let 10, 256 let 6, none let 4 (the old code 39). */
#define CR_PIVOT_SEARCHES_PER_BODY 256

static int cr_turns_over(const carom_world *w, int i, float t)
{
    const cr_body *b = &w->bodies[i];
    return !CR_BODY_IS_CIRCLE(b) && cr_moving(b) &&
           cr_gt(cr_mul(cr_mul(cr_abs(b->w), w->info[i].shape.extent), cr_sub(w->def.dt, t)),
                 cr_mul(CR_PIVOT_REACH, w->scale.slop));
}

static int cr_pivots(const carom_world *w, const cr_pair *p, float t)
{
    if (w->method == CAROM_METHOD_FIRST_IMPACT ||
        w->pivot_searches >= CR_PIVOT_SEARCHES_PER_BODY * w->body_count ||
        (p->contact >= 0 && (w->contacts[p->contact].flags & CR_CONTACT_RESTING)))
        return 0;
    return cr_turns_over(w, p->a, t) || cr_turns_over(w, p->b, t);
}

/* Next impact of pair k from local time t0: into p->toi and the heap. */
static void cr_pair_search(carom_world *w, int k, float t0)
{
    cr_pair *p = &w->pairs[k];
    cr_mover A, B;
    float dt = w->def.dt, slop = w->scale.slop;
    float tol = cr_mul(CAROM_TOI_TOLERANCE, slop), toi, sep, scale, approach;
    int slow = 0, found;
    cr_v2 xa, xb;
    cr_rot qa, qb;

    ++p->stamp;
    p->toi = CR_NEVER;
    p->met &= (unsigned char)~CR_PAIR_RESUME;
    p->va = w->drift[p->a].version;
    p->vb = w->drift[p->b].version;
    p->solved = cr_solved_contact(w, p);
    if (p->solved ||
        (!cr_moving(&w->bodies[p->a]) && !cr_moving(&w->bodies[p->b])) ||
        ((w->bodies[p->a].flags | w->bodies[p->b].flags) & CR_BODY_SENSOR))
        return;
    A = cr_mover_of(w, p->a);
    B = cr_mover_of(w, p->b);
    ++w->stats.toi_queries;
    if (cr_cannot_meet(&A, &B, t0, dt, slop)) {
        ++w->stats.toi_early_outs;
        return;
    }
    cr_pose_at(A.b, A.d, t0, &xa, &qa);
    cr_pose_at(B.b, B.d, t0, &xb, &qb);
    if (A.b->type == CAROM_BODY_STATIC) {
        xa = A.b->x;
        qa = A.b->q;
    }
    if (B.b->type == CAROM_BODY_STATIC) {
        xb = B.b->x;
        qb = B.b->q;
    }
    sep = cr_separation(A.s, xa, qa, B.s, xb, qb);
    if (cr_le(sep, tol)) {
        /* touching now: an impact at once if approaching fast; a search
         * on if parting or on a pivot; otherwise a contact for the
         * solver */
        float recede, t1;
        int pivot = 0;
        approach = cr_approach_speed(&A, &B, t0, slop, &scale, &recede);
        if (cr_gt(approach, cr_impact_speed(w, p->a, p->b, scale))) {
            p->toi = t0;
        } else if ((pivot = cr_pivots(w, p, t0)) != 0 ||
                   cr_gt(recede, cr_impact_speed(w, p->a, p->b, scale))) {
            /* every touching point leaves fast (a body rebounding off a
             * corner): the pair is parting, no contact. Where they have
             * left, another part of it may still come down within the
             * step (the far corner of a box landing nearly flat): that is
             * an impact of its own, at its instant (or, arriving slowly,
             * a contact for the solver). A pair on a pivot (a polygon
             * turning on the corner a plastic impact left touching) is
             * searched past it from now, leaving or not: its next corner
             * may come down within the step, which the solver would not
             * see, and before a slowly leaving pivot has left */
            if (pivot) {
                ++w->pivot_searches;
                found = cr_time_of_impact_pivot(&A, &B, t0, dt, tol, slop, &toi);
            } else {
                t1 = cr_add(t0, cr_div(cr_mul(2.0f, slop), recede));
                found = cr_lt(t1, dt) ? cr_time_of_impact(&A, &B, t1, dt, tol, &toi) : 0;
            }
            if (found) {
                if (found == CR_TOI_RESUME) {
                    p->toi = toi;
                    p->met |= CR_PAIR_RESUME;
                } else if (cr_gt(cr_approach_speed(&A, &B, toi, slop, &scale, 0),
                                 cr_impact_speed(w, p->a, p->b, scale))) {
                    p->toi = toi;
                } else {
                    p->met |= CR_PAIR_MET;
                    slow = 1;
                }
            }
        } else {
            p->met |= CR_PAIR_MET;
            slow = 1;
        }
    } else if ((found = cr_time_of_impact(&A, &B, t0, dt, tol, &toi)) == CR_TOI_RESUME) {
        /* still apart where the search stopped: take it up from there
         * (cr_impact_instant finds it apart and searches on) */
        p->toi = toi;
        p->met |= CR_PAIR_RESUME;
    } else if (found) {
        /* arriving slower than the rest speed is coming to rest, not an
         * impact: the contact solver takes it */
        approach = cr_approach_speed(&A, &B, toi, slop, &scale, 0);
        if (cr_gt(approach, cr_impact_speed(w, p->a, p->b, scale)))
            p->toi = toi;
        else {
            p->met |= CR_PAIR_MET;
            slow = 1;
        }
    }
    if (cr_le(p->toi, dt)) {
        cr_heap_push(w, k);
    } else if (p->contact >= 0 && slow) {
        /* a contact the solver left to the impacts that is no impact
         * after all (it touches or arrives slowly): the solver's again, so
         * nothing is left unsolved. A pair that does not meet before the
         * step ends is left alone: a speculative row would stop it at the
         * step's end and lose its bounce (the next step's search finds
         * the impact at its instant) */
        cr_contact *c = &w->contacts[p->contact];
        if (cr_gt(t0, 0.0f)) {
            /* made at the step start, before the bodies changed course:
             * its normal and points again, as they are now */
            if (cr_moving(A.b))
                cr_sync(&w->bodies[p->a], &w->drift[p->a], t0);
            if (cr_moving(B.b))
                cr_sync(&w->bodies[p->b], &w->drift[p->b], t0);
            cr_contact_remake(w, c);
        }
        c->flags |= CR_CONTACT_SOLVE;
        cr_solver_activate(w, p->a);
        cr_solver_activate(w, p->b);
        w->reorder = 1;
        p->solved = 1;
    }
}

void cr_events_begin(carom_world *w)
{
    int k;
    w->instant_t = CR_NEVER;
    w->instant_stamp = 0;
    w->instant_unsettled = 0;
    w->instant_rehits = 0;
    w->heap_count = 0;
    w->regrown_count = 0;
    w->resumed_searches = 0;
    /* (a bound per step: kept over steps, it ran out in the world's
     * lifetime, and a failed step used up what the retry then lacked) */
    w->pivot_searches = 0;
    for (k = 0; k < w->pair_count; ++k)
        cr_pair_search(w, k, 0.0f);
}

/* Must pair p be searched again: a body's drift changed, or its contact
 * changed hands between the solver and the impacts. The first-impact
 * method (the design note's) finds each pair's first impact once and
 * ignores later changes of course; but a pair the solver stops taking is
 * searched, once, or nothing would stop it. */
static int cr_stale(const carom_world *w, const cr_pair *p)
{
    if (w->method == CAROM_METHOD_FIRST_IMPACT)
        return !(p->met & CR_PAIR_HIT) && p->solved != cr_solved_contact(w, p);
    return p->va != w->drift[p->a].version || p->vb != w->drift[p->b].version ||
           p->solved != cr_solved_contact(w, p);
}

void cr_events_refresh(carom_world *w, float t)
{
    int k;
    for (k = 0; k < w->pair_count; ++k)
        if (cr_stale(w, &w->pairs[k]))
            cr_pair_search(w, k, t);
}

/* ---- growing a body's box after an impact ----------------------------------- */

typedef struct cr_regrow_ctx {
    carom_world *w;
    int body;
    float t;
    carom_status st;
} cr_regrow_ctx;

static int cr_regrow_visit(void *ctx, int other)
{
    cr_regrow_ctx *c = (cr_regrow_ctx *)ctx;
    carom_world *w = c->w;
    int a = c->body < other ? c->body : other;
    int b = c->body < other ? other : c->body;
    cr_pair *p;
    if (other == c->body || cr_has_pair(w, a, b) || !cr_may_collide(w, a, b))
        return 1;
    /* A sleeping body is not simulated this step: an impulse now would
     * leave it asleep and moving. The next step's pairs wake its island
     * and its contacts settle what this step's motion overlapped. */
    if (w->bodies[other].type == CAROM_BODY_DYNAMIC && !(w->bodies[other].flags & CR_BODY_AWAKE))
        return 1;
    if (w->pair_count >= w->def.max_pairs) {
        c->st = CAROM_ERR_PAIR_CAPACITY;
        return 0;
    }
    p = &w->pairs[w->pair_count];
    cr_pair_init(p, a, b);
    p->next_a = w->pair_head[a];
    w->pair_head[a] = w->pair_count;
    p->next_b = w->pair_head[b];
    w->pair_head[b] = w->pair_count;
    cr_pair_search(w, w->pair_count++, c->t);
    return 1;
}

/* An impulse can send a body out of the box it was expected to sweep (a
 * light ball struck by a heavy one): grow the box, and add the pairs the
 * larger box makes, so no impact is missed for want of a candidate pair.
 * The body's drift after the impact holds until t_end, the substep's end
 * (cr_release_active puts every body of an impact island, all of them
 * active, back on its free motion there). */
static carom_status cr_regrow(carom_world *w, int i, float t, float t_end)
{
    cr_mover m = cr_mover_of(w, i);
    cr_box now, *box = &w->boxes[i];
    cr_regrow_ctx ctx;
    int j;
    cr_swept_box_until(&m, t, t_end, w->def.dt, w->scale.spec, &now);
    if (cr_le(box->lo_x, now.lo_x) && cr_ge(box->hi_x, now.hi_x) &&
        cr_le(box->lo_y, now.lo_y) && cr_ge(box->hi_y, now.hi_y))
        return CAROM_OK;
#if CAROM_ENABLE_QUERIES || CAROM_ENABLE_SENSORS
    w->bodies[i].flags |= CR_BODY_REGROWN;
#endif
    box->lo_x = cr_min(box->lo_x, now.lo_x);
    box->lo_y = cr_min(box->lo_y, now.lo_y);
    box->hi_x = cr_max(box->hi_x, now.hi_x);
    box->hi_y = cr_max(box->hi_y, now.hi_y);
    ctx.w = w;
    ctx.body = i;
    ctx.t = t;
    ctx.st = CAROM_OK;
    cr_broadphase_query(&w->bp, w->boxes, box, cr_regrow_visit, &ctx);
    /* bodies that grew earlier may reach beyond their grid cells */
    for (j = 0; j < w->regrown_count && ctx.st == CAROM_OK; ++j)
        if (cr_boxes_overlap(box, &w->boxes[w->regrown[j]]))
            cr_regrow_visit(&ctx, w->regrown[j]);
    for (j = 0; j < w->regrown_count; ++j)
        if (w->regrown[j] == i)
            break;
    if (j == w->regrown_count && w->regrown_count < w->def.max_bodies)
        w->regrown[w->regrown_count++] = i;
    return ctx.st;
}

/* ---- simultaneous impacts --------------------------------------------------- */

static float cr_lever_n(const carom_world *w, int body, cr_v2 r, cr_v2 n)
{
    return CR_BODY_IS_CIRCLE(&w->bodies[body]) ? 0.0f : cr_vcross(r, n);
}

/* Impulse P along dir at lever arms la, lb: -P on A, +P on B. */
CR_INLINE void cr_bodies_apply(cr_body *A, cr_body *B, cr_v2 dir, float la, float lb,
                               float P)
{
    cr_v2 I = cr_vscale(P, dir);
    A->v = cr_vmadd(A->v, cr_neg(A->inv_m), I);
    B->v = cr_vmadd(B->v, B->inv_m, I);
#if CAROM_ENABLE_ROTATION
    A->w = cr_sub(A->w, cr_mul(A->inv_I, cr_mul(la, P)));
    B->w = cr_add(B->w, cr_mul(B->inv_I, cr_mul(lb, P)));
#else
    (void)la;
    (void)lb;
#endif
}

/* Relative velocity along dir of the points at ra (on A) and rb (on B). */
CR_INLINE float cr_bodies_vn(const cr_body *A, const cr_body *B, cr_v2 ra, cr_v2 rb,
                             cr_v2 dir)
{
    return cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, rb),
                           cr_point_velocity(A->v, A->w, ra)),
                   dir);
}

#if CAROM_IMPACT_DIRECT_MAX > 0 /* (the exact island solve's) */
static void cr_row_apply(carom_world *w, const cr_impact_row *r, cr_v2 dir, float la,
                         float lb, float P)
{
    cr_bodies_apply(&w->bodies[r->a], &w->bodies[r->b], dir, la, lb, P);
}
#endif

/* One sweep over a row: friction, then the normal impulses (a 2-point row
 * as a block when well conditioned). Returns the largest velocity change
 * it made at one of its points (impulse change over effective mass). */
static float cr_row_sweep(carom_world *w, cr_impact_row *r)
{
    cr_body *A = &w->bodies[r->a], *B = &w->bodies[r->b];
    float change = 0.0f;
    int k;
#if CAROM_ENABLE_FRICTION
    cr_v2 t = cr_vright(r->n);
    if (CR_TWO_POINTS && cr_gt(r->friction, 0.0f) && r->count == 2) {
        /* one row for both points (same line of action), as the contact
         * solver does: no favoured point */
        cr_v2 ra = cr_vscale(0.5f, cr_vadd(r->ra[0], r->ra[1]));
        cr_v2 rb = cr_vscale(0.5f, cr_vadd(r->rb[0], r->rb[1]));
        float vt = cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, rb),
                                   cr_point_velocity(A->v, A->w, ra)),
                           t);
        float pn = cr_add(r->pn[0], r->pn[1]);
        float limit = cr_mul(r->friction, pn);
        float old = cr_add(r->pt[0], r->pt[1]);
        float mass_t = cr_mul(0.5f, cr_add(r->mass_t[0], r->mass_t[1]));
        float pt = cr_clamp(cr_sub(old, cr_mul(mass_t, vt)), cr_neg(limit), limit);
        float d = cr_sub(pt, old);
        cr_bodies_apply(A, B, t, cr_vcross(ra, t), cr_vcross(rb, t), d);
        r->pt[0] = cr_mul(cr_gt(pn, 0.0f) ? cr_div(r->pn[0], pn) : 0.5f, pt);
        r->pt[1] = cr_sub(pt, r->pt[0]);
        change = cr_max(change, cr_div(cr_abs(d), mass_t));
    } else if (cr_gt(r->friction, 0.0f))
        for (k = 0; k < r->count; ++k) {
            float vt = cr_bodies_vn(A, B, r->ra[k], r->rb[k], t);
            float limit = cr_mul(r->friction, r->pn[k]);
            float pt = cr_clamp(cr_sub(r->pt[k], cr_mul(r->mass_t[k], vt)),
                                cr_neg(limit), limit);
            float d = cr_sub(pt, r->pt[k]);
            r->pt[k] = pt;
            cr_bodies_apply(A, B, t, cr_vcross(r->ra[k], t), cr_vcross(r->rb[k], t), d);
            change = cr_max(change, cr_div(cr_abs(d), r->mass_t[k]));
        }
#endif
#if CR_TWO_POINTS
    if (CR_TWO_POINTS && r->block) {
        float a1 = r->pn[0], a2 = r->pn[1], x1, x2;
        float b1 = cr_sub(cr_sub(cr_bodies_vn(A, B, r->ra[0], r->rb[0], r->n), r->target[0]),
                          cr_add(cr_mul(r->k11, a1), cr_mul(r->k12, a2)));
        float b2 = cr_sub(cr_sub(cr_bodies_vn(A, B, r->ra[1], r->rb[1], r->n), r->target[1]),
                          cr_add(cr_mul(r->k12, a1), cr_mul(r->k22, a2)));
        if (cr_lcp2(r->k11, r->k12, r->k22, b1, b2, &x1, &x2)) {
            float d1 = cr_sub(x1, a1), d2 = cr_sub(x2, a2);
            r->pn[0] = x1;
            r->pn[1] = x2;
            cr_bodies_apply(A, B, r->n, r->la[0], r->lb[0], d1);
            cr_bodies_apply(A, B, r->n, r->la[1], r->lb[1], d2);
            return cr_max(change, cr_max(cr_mul(cr_abs(d1), r->k11),
                                         cr_mul(cr_abs(d2), r->k22)));
        }
    }
#endif
    for (k = 0; k < r->count; ++k) {
        float vn = cr_bodies_vn(A, B, r->ra[k], r->rb[k], r->n);
        float pn = cr_max(cr_sub(r->pn[k], cr_mul(r->mass_n[k], cr_sub(vn, r->target[k]))),
                          0.0f);
        float d = cr_sub(pn, r->pn[k]);
        r->pn[k] = pn;
        cr_bodies_apply(A, B, r->n, r->la[k], r->lb[k], d);
        change = cr_max(change, cr_div(cr_abs(d), r->mass_n[k]));
    }
    return change;
}

/*
 * The exact solve of a small island. Projected Gauss-Seidel converges
 * slowly where rows are strongly coupled through rotation (a box landing
 * on a short column: each friction row turns the boxes, which moves the
 * normal rows of the next box), a few per cent per sweep. Its iterate
 * shows which rows act (normal impulse positive, friction below its
 * limit); with those rows as equalities the island is a linear system,
 * K x = b, small enough to eliminate directly. Its solution is taken if
 * it is feasible (no pulling normal, no friction past its cone), and the
 * sweeps go on from there: they confirm it, or they correct a wrong
 * guess of the active rows. It is tried only when the sweeps are slow,
 * and only for islands of at most CAROM_IMPACT_DIRECT_MAX unknowns.
 */
#if CAROM_IMPACT_DIRECT_MAX > 0
static void cr_unknown_dir(const cr_impact_row *r, int kind, cr_v2 *d,
                           float *la, float *lb)
{
    if (kind < 2 || !CAROM_ENABLE_FRICTION) { /* (friction unknowns: kinds 2 to 4) */
        *d = r->n;
        *la = r->la[kind];
        *lb = r->lb[kind];
    } else {
        cr_v2 t = cr_vright(r->n), ra, rb;
        if (CR_TWO_POINTS && kind == 2) {
            ra = cr_vscale(0.5f, cr_vadd(r->ra[0], r->ra[1]));
            rb = cr_vscale(0.5f, cr_vadd(r->rb[0], r->rb[1]));
        } else {
            ra = r->ra[kind - 3];
            rb = r->rb[kind - 3];
        }
        *d = t;
        *la = cr_vcross(ra, t);
        *lb = cr_vcross(rb, t);
    }
}

/* The velocity change along unknown u per unit impulse of unknown v,
 * through the bodies they share (body a of a row takes -P, body b +P). */
static float cr_coupling(const carom_world *w, const cr_impact_row *ru,
                         cr_v2 du, float lau, float lbu,
                         const cr_impact_row *rv, cr_v2 dv, float lav,
                         float lbv)
{
    float k = 0.0f, dot = cr_vdot(du, dv);
    int bu[2], bv[2], i, j;
    float lu[2], lv[2];
    bu[0] = ru->a; bu[1] = ru->b; lu[0] = lau; lu[1] = lbu;
    bv[0] = rv->a; bv[1] = rv->b; lv[0] = lav; lv[1] = lbv;
    for (i = 0; i < 2; ++i)
        for (j = 0; j < 2; ++j) {
            const cr_body *c = &w->bodies[bu[i]];
            float term;
            if (bu[i] != bv[j] || c->type != CAROM_BODY_DYNAMIC)
                continue;
            term = cr_mul(c->inv_m, dot);
#if CAROM_ENABLE_ROTATION
            term = cr_add(term, cr_mul(c->inv_I, cr_mul(lu[i], lv[j])));
#else
            (void)lu;
            (void)lv;
#endif
            k = i == j ? cr_add(k, term) : cr_sub(k, term); /* signs -1, +1 */
        }
    return k;
}

/* Velocity along unknown u now. */
static float cr_unknown_vel(const carom_world *w, const cr_impact_row *r,
                            cr_v2 d, float la, float lb)
{
    const cr_body *A = &w->bodies[r->a], *B = &w->bodies[r->b];
    cr_v2 dv = cr_vsub(B->v, A->v);
    float v = cr_vdot(dv, d);
#if CAROM_ENABLE_ROTATION
    v = cr_add(v, cr_sub(cr_mul(B->w, lb), cr_mul(A->w, la)));
#else
    (void)la;
    (void)lb;
#endif
    return v;
}

/* Returns 1 if the island was set to the exact solution of its active
 * rows. */
static int cr_rows_direct(carom_world *w, cr_impact_row *rows, int n)
{
    const int M = w->direct_cap;
    float *x = w->direct_x;
    int *u = w->direct_u;
    int m = 0, i, j, c;
    float lack = 0.0f, mass = 0.0f, momentum = 0.0f;
#define K(i, j) w->direct_k[(i) * M + (j)]
#define U_ROW(i) (u[i] >> 3)
#define U_KIND(i) (u[i] & 7)
    for (i = 0; i < n; ++i) {
        const cr_impact_row *r = &rows[i];
        int k;
        for (k = 0; k < r->count; ++k)
            if (cr_gt(r->pn[k], 0.0f)) {
                if (m == M)
                    return 0;
                u[m++] = i * 8 + k;
            }
#if CAROM_ENABLE_FRICTION
        if (cr_gt(r->friction, 0.0f)) {
            if (CR_TWO_POINTS && r->count == 2) {
                float limit = cr_mul(r->friction, cr_add(r->pn[0], r->pn[1]));
                if (cr_lt(cr_abs(cr_add(r->pt[0], r->pt[1])), limit)) {
                    if (m == M)
                        return 0;
                    u[m++] = i * 8 + 2;
                }
            } else {
                for (k = 0; k < r->count; ++k)
                    if (cr_lt(cr_abs(r->pt[k]), cr_mul(r->friction, r->pn[k]))) {
                        if (m == M)
                            return 0;
                        u[m++] = i * 8 + 3 + k;
                    }
            }
        }
#endif
    }
    if (m < 2)
        return 0;
    if (m > w->stats.max_direct_used)
        w->stats.max_direct_used = m;
    /* K and the right-hand side: the velocity each unknown still lacks */
    for (i = 0; i < m; ++i) {
        const cr_impact_row *ri = &rows[U_ROW(i)];
        cr_v2 di;
        float lai, lbi, target;
        cr_unknown_dir(ri, U_KIND(i), &di, &lai, &lbi);
        target = U_KIND(i) < 2 ? ri->target[U_KIND(i)] : 0.0f;
        x[i] = cr_sub(target, cr_unknown_vel(w, ri, di, lai, lbi));
        for (j = 0; j <= i; ++j) {
            const cr_impact_row *rj = &rows[U_ROW(j)];
            cr_v2 dj;
            float laj, lbj;
            cr_unknown_dir(rj, U_KIND(j), &dj, &laj, &lbj);
            K(i, j) = K(j, i) = cr_coupling(w, ri, di, lai, lbi, rj, dj, laj, lbj);
        }
        lack = cr_max(lack, cr_abs(x[i]));
        for (j = 0; j < 2; ++j) {
            int id = j == 0 ? ri->a : ri->b;
            const cr_body *b = &w->bodies[id];
            if (b->type == CAROM_BODY_DYNAMIC) {
                mass = cr_add(mass, w->info[id].m);
                /* (its velocity before the instant: the bound stays put
                 * while the sweeps and solves of the instant go on) */
                const cr_v2 v0 = w->drift[id].v_pre;
                momentum = cr_add(momentum, cr_mul(w->info[id].m,
                                                   cr_add(cr_abs(v0.x), cr_abs(v0.y))));
            }
        }
    }
    momentum = cr_mul(CR_DIRECT_MAX_GAIN, cr_add(momentum, cr_mul(mass, lack)));
    /* Gaussian elimination with partial pivoting; a (nearly) singular
     * system (redundant rows) is left to the sweeps */
    for (c = 0; c < m; ++c) {
        int p = c;
        float big = cr_abs(K(c, c)), scale = cr_abs(K(c, c));
        for (i = c + 1; i < m; ++i) {
            if (cr_gt(cr_abs(K(i, c)), big)) {
                big = cr_abs(K(i, c));
                p = i;
            }
        }
        for (i = 0; i < m; ++i)
            scale = cr_max(scale, cr_abs(K(i, i)));
        if (!cr_gt(big, cr_mul(CR_DIRECT_MIN_PIVOT, scale)))
            return 0;
        if (p != c) {
            for (j = 0; j < m; ++j) {
                float tmp = K(c, j);
                K(c, j) = K(p, j);
                K(p, j) = tmp;
            }
            {
                float tmp = x[c];
                x[c] = x[p];
                x[p] = tmp;
            }
        }
        for (i = c + 1; i < m; ++i) {
            float f = cr_div(K(i, c), K(c, c));
            for (j = c + 1; j < m; ++j)
                K(i, j) = cr_sub(K(i, j), cr_mul(f, K(c, j)));
            x[i] = cr_sub(x[i], cr_mul(f, x[c]));
        }
    }
    for (i = m - 1; i >= 0; --i) {
        float s = x[i];
        for (j = i + 1; j < m; ++j)
            s = cr_sub(s, cr_mul(K(i, j), x[j]));
        x[i] = cr_div(s, K(i, i));
    }
    /* bounded? */
    for (i = 0; i < m; ++i)
        if (!cr_le(cr_abs(x[i]), momentum))
            return 0;
    /* feasible? normal impulses stay pushing, friction within its cone */
    for (i = 0; i < m; ++i) {
        const cr_impact_row *r = &rows[U_ROW(i)];
        if (U_KIND(i) < 2) {
            if (cr_lt(cr_add(r->pn[U_KIND(i)], x[i]), 0.0f))
                return 0;
        }
    }
#if CAROM_ENABLE_FRICTION /* (friction unknowns exist only with it) */
    for (i = 0; i < m; ++i) {
        const cr_impact_row *r = &rows[U_ROW(i)];
        float pn0 = r->pn[0], pn1 = CR_TWO_POINTS && r->count == 2 ? r->pn[CR_MANIFOLD_POINTS - 1] : 0.0f, pt;
        if (U_KIND(i) < 2)
            continue;
        for (j = 0; j < m; ++j) {
            if (U_ROW(j) != U_ROW(i) || U_KIND(j) >= 2)
                continue;
            if (U_KIND(j) == 0)
                pn0 = cr_add(pn0, x[j]);
            else
                pn1 = cr_add(pn1, x[j]);
        }
        if (CR_TWO_POINTS && U_KIND(i) == 2)
            pt = cr_add(cr_add(r->pt[0], r->pt[CR_MANIFOLD_POINTS - 1]), x[i]);
        else
            pt = cr_add(r->pt[U_KIND(i) - 3], x[i]);
        if (cr_gt(cr_abs(pt), cr_mul(r->friction, U_KIND(i) == 2 ? cr_add(pn0, pn1) : pn0)))
            return 0;
    }
#endif
    /* apply it */
    for (i = 0; i < m; ++i) {
        cr_impact_row *r = &rows[U_ROW(i)];
        cr_v2 d;
        float la, lb;
        cr_unknown_dir(r, U_KIND(i), &d, &la, &lb);
        cr_row_apply(w, r, d, la, lb, x[i]);
        if (U_KIND(i) < 2)
            r->pn[U_KIND(i)] = cr_add(r->pn[U_KIND(i)], x[i]);
#if CAROM_ENABLE_FRICTION
        else if (U_KIND(i) >= 3)
            r->pt[U_KIND(i) - 3] = cr_add(r->pt[U_KIND(i) - 3], x[i]);
#endif
    }
    for (i = 0; CR_TWO_POINTS && CAROM_ENABLE_FRICTION && i < m; ++i) {
        cr_impact_row *r = &rows[U_ROW(i)];
        if (U_KIND(i) == 2) {
            float pt = cr_add(cr_add(r->pt[0], r->pt[1]), x[i]);
            float pn = cr_add(r->pn[0], r->pn[1]);
            r->pt[0] = cr_mul(cr_gt(pn, 0.0f) ? cr_div(r->pn[0], pn) : 0.5f, pt);
            r->pt[1] = cr_sub(pt, r->pt[0]);
        }
    }
#undef K
#undef U_ROW
#undef U_KIND
    return 1;
}
#endif

/* Sweeps over rows[0..n) until the impulses settle; returns 0 if they did
 * not (the sweeps stalled or ran out). */
static int cr_rows_solve(carom_world *w, cr_impact_row *rows, int n, int max_sweeps)
{
    int it, i, k;
    float tol = 0.0f, last = 0.0f;
    for (i = 0; i < n; ++i) {
        const cr_impact_row *r = &rows[i];
        tol = cr_max(tol, cr_max(cr_mul(CR_ISLAND_TOL, r->approach),
                                 cr_mul(CR_ISLAND_REST_TOL, cr_rest_speed(w, r->a, r->b))));
        for (k = 0; k < r->count; ++k)
            tol = cr_max(tol, cr_mul(CR_ISLAND_TOL, cr_abs(r->target[k])));
    }
    for (it = 0; it < max_sweeps; ++it) {
        float change = 0.0f;
        for (i = 0; i < n; ++i)
            change = cr_max(change, cr_row_sweep(w, &rows[i]));
        if (!cr_gt(change, tol))
            return 1;
        if ((it + 1) % CR_STALL_SPAN == 0) {
            if (it + 1 >= CR_STALL_MIN && it + 1 >= 2 * n &&
                cr_gt(change, cr_mul(0.5f, last)))
                return 0;
            last = change;
        }
        /* a single frictionless point is exact after one sweep */
        if (n == 1 && rows[0].count == 1 && !cr_gt(rows[0].friction, 0.0f))
            return 1;
#if CAROM_IMPACT_DIRECT_MAX > 0
        /* slow: solve the rows that act exactly; the sweeps that follow
         * confirm it (or correct the guess) */
        if ((it & 15) == CR_DIRECT_AFTER - 1 && it + 1 < max_sweeps)
            (void)cr_rows_direct(w, rows, n);
#endif
    }
    return 0;
}

/* A body's velocity before the impulses of the current instant: recorded
 * when it joined the island; static and kinematic bodies never change. */
static void cr_pre_velocity(const carom_world *w, int i, cr_v2 *v, float *om)
{
    if (w->mark[i] == w->mark_stamp && w->bodies[i].type == CAROM_BODY_DYNAMIC) {
        *v = w->drift[i].v_pre;
        *om = w->drift[i].w_pre;
    } else {
        *v = w->bodies[i].v;
        *om = w->bodies[i].w;
    }
}

/* Remember the velocity of body i before this instant's impulses. */
static void cr_note_pre(carom_world *w, int i)
{
    w->drift[i].v_pre = w->bodies[i].v;
    w->drift[i].w_pre = w->bodies[i].w;
}

/* Row for pair k at the bodies' current poses (synchronised), 0 if the
 * pair does not touch. The Newton target of each point is e times its
 * approach before this instant's impulses (a body pushed by another row of
 * the same solve is not approaching on its own). */
static int cr_row_make(carom_world *w, int k, cr_impact_row *r)
{
    const cr_pair *p = &w->pairs[k];
    const cr_body *A = &w->bodies[p->a], *B = &w->bodies[p->b];
    const cr_body_info *ia = &w->info[p->a], *ib = &w->info[p->b];
    float scale, threshold, wa, wb, gap = cr_mul(CAROM_TOI_TOLERANCE, w->scale.slop);
    cr_manifold m;
#if CAROM_ENABLE_FRICTION
    cr_v2 t;
#endif
    cr_v2 va, vb;
    int j;
    /* touching within the slop: the simultaneous rows */
    if (!cr_collide(&ia->shape, A->x, A->q, &ib->shape, B->x, B->q, w->scale.slop,
                    w->scale.face_tol, w->scale.corner, &m) ||
        cr_ghost(w, p->a, p->b, &m))
        return 0;
    r->a = p->a;
    r->b = p->b;
    r->pair = k;
    r->n = m.n;
    r->count = m.count;
    r->restitution = cr_max(ia->restitution, ib->restitution);
#if CAROM_ENABLE_FRICTION
    r->friction = cr_sqrt(cr_mul(ia->friction, ib->friction));
    t = cr_vright(m.n);
#else
    r->friction = 0.0f;
#endif
    r->approach = 0.0f;
    scale = cr_add(cr_add(cr_vlen(A->v), cr_vlen(B->v)),
                   cr_add(cr_mul(cr_abs(A->w), ia->shape.extent),
                          cr_mul(cr_abs(B->w), ib->shape.extent)));
    cr_pre_velocity(w, p->a, &va, &wa);
    cr_pre_velocity(w, p->b, &vb, &wb);
    for (j = 0; j < m.count; ++j) {
        r->ra[j] = cr_vsub(m.pts[j].p, A->x);
        r->rb[j] = cr_vsub(m.pts[j].p, B->x);
        r->mass_n[j] = cr_effective_mass(A, B, cr_lever_n(w, p->a, r->ra[j], m.n),
                                         cr_lever_n(w, p->b, r->rb[j], m.n));
#if CAROM_ENABLE_FRICTION /* (only friction reads it) */
        r->mass_t[j] = cr_effective_mass(A, B, cr_vcross(r->ra[j], t),
                                         cr_vcross(r->rb[j], t));
#else
        r->mass_t[j] = 0.0f;
#endif
        r->pn[j] = 0.0f;
        r->pt[j] = 0.0f;
        /* the approach before the instant, for now */
        r->target[j] = cr_neg(cr_vdot(cr_vsub(cr_point_velocity(vb, wb, r->rb[j]),
                                              cr_point_velocity(va, wa, r->ra[j])),
                                      m.n));
        r->approach = cr_max(r->approach, r->target[j]);
    }
    for (j = 0; j < m.count; ++j) {
        r->la[j] = cr_lever_n(w, p->a, r->ra[j], m.n);
        r->lb[j] = cr_lever_n(w, p->b, r->rb[j], m.n);
    }
    r->block = 0;
    if (CR_TWO_POINTS && m.count == 2) {
        float lin = cr_add(A->inv_m, B->inv_m), det;
        r->k11 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r->la[0], r->la[0])),
                                    cr_mul(B->inv_I, cr_mul(r->lb[0], r->lb[0]))));
        r->k22 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r->la[1], r->la[1])),
                                    cr_mul(B->inv_I, cr_mul(r->lb[1], r->lb[1]))));
        r->k12 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(r->la[0], r->la[1])),
                                    cr_mul(B->inv_I, cr_mul(r->lb[0], r->lb[1]))));
        det = cr_sub(cr_mul(r->k11, r->k22), cr_mul(r->k12, r->k12));
        r->block = cr_gt(det, cr_mul(CR_BLOCK_MIN_DET, cr_mul(r->k11, r->k22)));
    }
    threshold = cr_impact_speed(w, p->a, p->b, scale);
    r->impact = cr_gt(r->approach, threshold);
    /* past the impact budget an impact is plastic (e = 0): a squeezed
     * chain then ends, and no energy is made (simultaneous Newton targets
     * would make it; Poisson's expansion after the fact is stale).
     * A touching point that is not an impact holds (target 0) unless it
     * was opening: then it may close in as fast as it was opening. Held
     * at 0, its impulse P did work P vn- / 2 > 0 (a ball leaving a
     * neighbour it had just bounced off, struck by a third ball, pushed
     * the neighbour away too); now its work is P (vn+ + vn-) / 2 = 0, and
     * the closing point is an impact of its own an instant later. */
    for (j = 0; j < m.count; ++j) {
        float before = r->target[j];
        int rebound = r->impact && !w->budget_hit && cr_gt(r->restitution, 0.0f);
        r->target[j] = r->impact && !w->budget_hit
                           ? cr_mul(r->restitution, cr_max(0.0f, r->target[j]))
                           : cr_min(0.0f, r->target[j]);
        /* a point closing on a gap (farther than the search calls
         * touching) too slowly to close it within the step is no part of
         * this instant: it may close in as fast as that gap allows, as
         * the solver's speculative rows let it (a rebound keeps its
         * target: the points of an elastic instant within the slop
         * bounce together; an opening point may close as fast as it
         * opened, as above). Held at once, the far corner of a box
         * pivoting slowly on the other (dt 1e-6 s, a gap of 0.17 mm) was
         * stopped at every impact of the near one, and the box stayed
         * tilted on one corner, its turn frozen. */
        if (!rebound && cr_gt(before, 0.0f) && cr_gt(m.pts[j].sep, gap) &&
            cr_lt(cr_mul(before, w->def.dt), m.pts[j].sep))
            r->target[j] = cr_sub(r->target[j], cr_div(m.pts[j].sep, w->def.dt));
    }
    return 1;
}

/* Row slots 0 .. n-1 of w->rows are written: the most an instant wrote is
 * what `carom lean` sizes CAROM_IMPACT_ROWS_MAX to. */
/* Is there room for n rows in a simultaneous solve? Asked before each
 * look at a contact that could join it, and counted whatever the answer:
 * stats.max_rows_used is the room a solve needed to look at everything
 * it would with any more, so a build whose CAROM_IMPACT_ROWS_MAX is that
 * (`carom lean`) takes the same path to the last bit. (Counting only the
 * rows that joined undercounted: with room for one row, a kinematic
 * platform's neighbour was not brought to the instant, and a rotation
 * came out one ulp off.) */
static int cr_room_for_rows(carom_world *w, int n)
{
    if (n > w->stats.max_rows_used)
        w->stats.max_rows_used = n;
    return n <= w->row_cap;
}

static int cr_island_add_body(carom_world *w, int i, int *n)
{
    if (!cr_moving(&w->bodies[i]) || w->mark[i] == w->mark_stamp)
        return 1;
    if (*n >= w->island_cap)
        return 0;
    w->mark[i] = w->mark_stamp;
    w->island[(*n)++] = i;
    return 1;
}

static void cr_record(carom_world *w, const cr_impact_row *r, float t)
{
    float impulse = 0.0f;
    int k;
    for (k = 0; k < r->count; ++k)
        impulse = cr_add(impulse, r->pn[k]);
    if (cr_gt(impulse, 0.0f))
        cr_record_impact(w, r->a, r->b, t, r->n, impulse, r->approach);
}

/*
 * A hold spreads its impulses over the rest of the substep, and a later
 * hold of a body drops what of them is still to come (it predicts from
 * the solver's drift, cr_hold_contacts). Dropped for some bodies of an
 * earlier hold and kept by the others, they change the momentum: three
 * circles and a box pressed together, in zero gravity, lost 1.6e-4 of it
 * in a step where a second instant took three of the four bodies of the
 * first instant's hold. So the bodies of this island whose earlier hold
 * (their group: the mark stamp of the hold that pushed them) is not all
 * here keep what is left of it, and are held from their drift as it is:
 * a group is kept when one of its bodies here touches, through a pair, a
 * body of the group outside the island, or a body that keeps. A body
 * that keeps, keeps to the substep's end (its old group's bodies may be
 * anywhere). (Joining the rest of the group to the hold instead, with
 * its rows, is as exact, but searches all of their pairs again: 12 %
 * more operations on a falling pile of 10^4 bodies, against 2 %.)
 */
static void cr_hold_keep(carom_world *w, int nb)
{
    /* the groups to keep (past CR_HOLD_KEPT_GROUPS of them, every held
     * body of the island keeps: never wrong, only less exact in energy) */
    int kept[CR_HOLD_KEPT_GROUPS], nk = 0, i, j, all = 0;
    for (i = 0; i < nb && !all; ++i) {
        int body = w->island[i], k, partial = 0;
        const cr_solver_body *sb = &w->sbody[body];
        int group;
        if (!sb->held || sb->u.hold_group == 0)
            continue;
        group = sb->u.hold_group;
        partial = sb->keep;
        for (k = w->pair_head[body]; k >= 0 && !partial;) {
            const cr_pair *p = &w->pairs[k];
            int other = p->a == body ? p->b : p->a;
            const cr_solver_body *so = &w->sbody[other];
            partial = so->held && (so->keep || (w->mark[other] != w->mark_stamp &&
                                                 so->u.hold_group == group));
            k = p->a == body ? p->next_a : p->next_b;
        }
        if (partial) {
            for (j = 0; j < nk && kept[j] != group; ++j)
                ;
            if (j == nk) {
                if (nk == CR_HOLD_KEPT_GROUPS)
                    all = 1;
                else
                    kept[nk++] = group;
            }
        }
    }
    for (i = 0; i < nb; ++i) {
        cr_solver_body *sb = &w->sbody[w->island[i]];
        if (!sb->held || sb->u.hold_group == 0)
            continue;
        if (all)
            sb->keep = 1;
        else
            for (j = 0; j < nk; ++j)
                if (kept[j] == sb->u.hold_group)
                    sb->keep = 1;
    }
}

/*
 * For the rest of the substep, keep the island's touching contacts from
 * closing in: predict each body's velocity at t_end on its drift, remove
 * the approach of every touching row (inelastically), and make the drift
 * reach the corrected velocity instead.
 */
static void cr_hold_contacts(carom_world *w, int nb, int nr, float t, float t_end)
{
    float h = cr_sub(t_end, t), inv_h;
    int i, k;
    if (!cr_gt(h, 0.0f))
        return;
    inv_h = cr_div(1.0f, h);
    for (i = 0; i < nb; ++i) {
        int id = w->island[i];
        cr_body *b = &w->bodies[id];
        cr_solver_body *sb = &w->sbody[id];
        w->island_v[i] = b->v;
        w->island_w[i] = b->w;
        /* predicted on the drift the solver gave it, not on an earlier
         * hold of this substep: that hold answered the velocities before
         * this instant's impulses, and kept on top of a bounce it would
         * add the bounce again (energy made: two holds in one substep sent
         * an elastic pair apart at twice its approach); unless the body
         * keeps the earlier hold (cr_hold_keep) */
        if (!sb->held) {
            sb->held = 1;
            sb->a_held = w->drift[id].a;
            sb->alpha_held = w->drift[id].alpha;
        }
        if (sb->keep) {
            b->v = cr_vmadd(b->v, h, w->drift[id].a);
            b->w = cr_add(b->w, cr_mul(h, w->drift[id].alpha));
        } else {
            b->v = cr_vmadd(b->v, h, sb->a_held);
            b->w = cr_add(b->w, cr_mul(h, sb->alpha_held));
        }
    }
    /* held at 0, as the solve held it, but a row that was opening before
     * the instant may close as fast as it opened (cr_row_make): held at
     * 0, the floor's instant under a ball B had just struck, within the
     * slop of B, stopped the ball coming back up into B for the rest of
     * the substep, inelastically (0.25 % of the energy; an elastic gas
     * lost 0.7 % in 10^5 steps, a drop at a time) */
    for (i = 0; i < nr; ++i)
        for (k = 0; k < w->rows[i].count; ++k) {
            w->rows[i].target[k] = cr_min(0.0f, w->rows[i].target[k]);
            w->rows[i].pn[k] = 0.0f;
            w->rows[i].pt[k] = 0.0f;
        }
    /* a few sweeps: what is left is the contact solver's, whose relax
     * sweeps follow this move */
    (void)cr_rows_solve(w, w->rows, nr, CR_HOLD_SWEEPS);
    /* Whose drift now carries this hold's impulses: the bodies of its
     * rows that took one. They are the solver's for the rest of the
     * substep, so that their hold ends with it (cr_release_active): kept
     * past it, a hold's impulses went on as a force on the body alone for
     * the rest of the step (0.2 % of a zero-gravity cluster's momentum in a
     * step). Their group is for cr_hold_keep; the other bodies' earlier
     * holds are dropped, unless they keep them. */
    for (i = 0; i < nb; ++i)
        if (!w->sbody[w->island[i]].keep)
            w->sbody[w->island[i]].u.hold_group = 0;
    for (i = 0; i < nr; ++i) {
        const cr_impact_row *r = &w->rows[i];
        int pushed = 0, j;
        for (k = 0; k < r->count; ++k)
            pushed |= cr_gt(r->pn[k], 0.0f) || !cr_eq(r->pt[k], 0.0f);
        for (j = 0; j < 2 && pushed; ++j) {
            int id = j == 0 ? r->a : r->b;
            if (w->mark[id] == w->mark_stamp && w->bodies[id].type == CAROM_BODY_DYNAMIC) {
                w->sbody[id].u.hold_group = w->mark_stamp;
                cr_solver_activate(w, id);
            }
        }
    }
    for (i = 0; i < nb; ++i) {
        int id = w->island[i];
        cr_body *b = &w->bodies[id];
        cr_drift *d = &w->drift[id];
        if (b->type == CAROM_BODY_DYNAMIC) {
            d->a = cr_vscale(inv_h, cr_vsub(b->v, w->island_v[i]));
            d->alpha = cr_mul(inv_h, cr_sub(b->w, w->island_w[i]));
        }
        b->v = w->island_v[i];
        b->w = w->island_w[i];
    }
}

/*
 * The island grows as far as the impulse reaches: a resting contact of an
 * island body that the solve has set approaching faster than the rest speed
 * (a struck box pushed into the one below it) joins, with its other body,
 * and the island is solved again, until nothing more is reached (or the
 * island is full). A ball striking a stack meets the whole column down to
 * the floor; a body landing on a pile meets only what it pushes.
 */
static int cr_island_grow(carom_world *w, int *nb, int nr, float t)
{
    int grown = 1, converged = 1, i, k; /* the caller solved the seeds */
    for (;;) {
        if (!grown) {
            /* nothing joined after a rough solve: solve to convergence,
             * then look once more (a converged solve can push a contact
             * the rough one did not) */
            if (converged)
                break;
            w->rows_settled = cr_rows_solve(w, w->rows, nr, CAROM_IMPACT_ISLAND_ITERATIONS);
            converged = 1;
        }
        grown = 0;
        for (i = 0; i < *nb; ++i) {
            int body = w->island[i];
            k = w->pair_head[body];
            while (k >= 0) {
                cr_pair *p = &w->pairs[k];
                int other = p->a == body ? p->b : p->a;
                int next = p->a == body ? p->next_a : p->next_b;
                if (p->mark != w->mark_stamp && p->contact >= 0 &&
                    (w->contacts[p->contact].flags & CR_CONTACT_SOLVE) &&
                    (w->contacts[p->contact].flags & CR_CONTACT_TOUCHING) &&
                    cr_room_for_rows(w, nr + 1)) {
                    const cr_contact *c = &w->contacts[p->contact];
                    int in = w->mark[other] == w->mark_stamp;
                    if (!in && cr_moving(&w->bodies[other])) {
                        cr_sync(&w->bodies[other], &w->drift[other], t);
                        cr_note_pre(w, other);
                    }
                    if (cr_gt(cr_contact_approach(w, c), cr_rest_speed(w, c->a, c->b)) &&
                        (in || cr_island_add_body(w, other, nb))) {
                        p->mark = w->mark_stamp;
                        if (cr_row_make(w, k, &w->rows[nr])) {
                            ++nr;
                            grown = 1;
                        }
                    }
                }
                k = next;
            }
        }
        if (grown) {
            /* rows joined: a rough solve is enough to show which of their
             * neighbours they push; the converged solve comes last */
            (void)cr_rows_solve(w, w->rows, nr, CR_GROW_SWEEPS);
            converged = 0;
        }
    }
    return nr;
}

/*
 * No impact makes energy. Newton's law (vn+ = -e vn-) with Coulomb
 * friction can: where the normal impulse's torque turns a point's sliding
 * around (a box spinning into a wall), sticking needs friction along the
 * sliding the point had, which does positive work; an elastic spinning box
 * left a static wall with up to 1.56 times its kinetic energy, and a light
 * box squeezed between a wall and a ball, struck again and again at one
 * instant, gained that much per strike until its speed passed 1e17 m/s.
 * The plastic answer cannot: with every target min(0, target) each
 * impulse P meets vn+ = target <= 0 where it pushes and friction opposes
 * the sliding it leaves, so the energy change P.(u- + u+) / 2 =
 * P.u+ - P.K.P / 2 <= 0. So when the instant's island (no kinematic body
 * in it: that may do work) ends with more kinetic energy than it had
 * before it, it is solved again plastic from the same velocities, and
 * the bodies take v0 + s (v1 - v0) between the plastic (v0) and the first
 * (v1) answer, with the largest s in [0, 1] whose energy (a quadratic in
 * s) is not above the energy before; every point between the two answers
 * leaves every contact at least as fast as the plastic answer does (not
 * approaching). The rows' impulses are mixed alike.
 */
static void cr_limit_impact_energy(carom_world *w, int nb, int nr)
{
    float before = 0.0f, after = 0.0f, e0 = 0.0f, lin = 0.0f, quad = 0.0f, room, s = 0.0f;
    int i, k;
    for (i = 0; i < nb; ++i) {
        int id = w->island[i];
        const cr_body *b = &w->bodies[id];
        if (b->type != CAROM_BODY_DYNAMIC)
            return;
        before = cr_add(before, cr_kinetic(&w->info[id], w->drift[id].v_pre, w->drift[id].w_pre));
        after = cr_add(after, cr_kinetic(&w->info[id], b->v, b->w));
    }
    if (!cr_gt(after, cr_mul(before, cr_add(1.0f, CR_IMPACT_ENERGY_TOL))))
        return;
    for (i = 0; i < nb; ++i) {
        int id = w->island[i];
        cr_body *b = &w->bodies[id];
        w->island_v[i] = b->v;
        w->island_w[i] = b->w;
        b->v = w->drift[id].v_pre;
        b->w = w->drift[id].w_pre;
    }
    for (i = 0; i < nr; ++i) {
        cr_impact_row *r = &w->rows[i];
        r->impulse_full = 0.0f;
        for (k = 0; k < r->count; ++k) {
            r->impulse_full = cr_add(r->impulse_full, r->pn[k]);
            r->pn[k] = 0.0f;
            r->pt[k] = 0.0f;
            r->target[k] = cr_min(0.0f, r->target[k]);
        }
    }
    if (!cr_rows_solve(w, w->rows, nr, CAROM_IMPACT_ISLAND_ITERATIONS))
        w->rows_settled = 0;
    /* E(s) = e0 + lin s + quad s^2 along v0 + s (v1 - v0) */
    for (i = 0; i < nb; ++i) {
        int id = w->island[i];
        const cr_body *b = &w->bodies[id];
        cr_v2 dv = cr_vsub(w->island_v[i], b->v);
        float dw = cr_sub(w->island_w[i], b->w);
        e0 = cr_add(e0, cr_kinetic(&w->info[id], b->v, b->w));
#if CAROM_ENABLE_ROTATION
        lin = cr_add(lin, cr_add(cr_mul(w->info[id].m, cr_vdot(b->v, dv)),
                                 cr_mul(w->info[id].I, cr_mul(b->w, dw))));
#else
        lin = cr_add(lin, cr_mul(w->info[id].m, cr_vdot(b->v, dv)));
#endif
        quad = cr_add(quad, cr_kinetic(&w->info[id], dv, dw));
    }
    room = cr_max(cr_sub(before, e0), 0.0f);
    if (cr_gt(quad, 0.0f))
        s = cr_energy_share(lin, quad, room);
    for (i = 0; i < nb; ++i) {
        cr_body *b = &w->bodies[w->island[i]];
        b->v = cr_vmadd(b->v, s, cr_vsub(w->island_v[i], b->v));
#if CAROM_ENABLE_ROTATION
        b->w = cr_add(b->w, cr_mul(s, cr_sub(w->island_w[i], b->w)));
#endif
    }
    /* each row's total impulse (what its event records): mixed alike */
    for (i = 0; i < nr; ++i) {
        cr_impact_row *r = &w->rows[i];
        float rest = cr_sub(1.0f, s);
        for (k = 0; k < r->count; ++k)
            r->pn[k] = cr_mul(rest, r->pn[k]);
        r->pn[0] = cr_add(r->pn[0], cr_mul(s, r->impulse_full));
    }
}

/* Contact of pair k at local time t to the solver, its normal and points
 * as they are now (a pair without one gets it made); -2: no contact
 * capacity left. */
static int cr_pair_to_solver(carom_world *w, int k, float t)
{
    cr_pair *p = &w->pairs[k];
    int c, had = p->contact >= 0;
    if (cr_moving(&w->bodies[p->a]))
        cr_sync(&w->bodies[p->a], &w->drift[p->a], t);
    if (cr_moving(&w->bodies[p->b]))
        cr_sync(&w->bodies[p->b], &w->drift[p->b], t);
    c = cr_contact_add(w, k);
    if (c < 0)
        return c;
    if (had && cr_gt(t, 0.0f))
        cr_contact_remake(w, &w->contacts[c]);
    p->toi = CR_NEVER;
    p->solved = 1;
    w->contacts[c].flags |= CR_CONTACT_SOLVE | CR_CONTACT_UNSETTLED;
    cr_solver_activate(w, p->a);
    cr_solver_activate(w, p->b);
    w->reorder = 1;
    return c;
}

/* Fastest approach at row r's points now (0 if every point parts). */
static float cr_row_approach(const carom_world *w, const cr_impact_row *r)
{
    const cr_body *A = &w->bodies[r->a], *B = &w->bodies[r->b];
    float fastest = 0.0f;
    int k;
    for (k = 0; k < r->count; ++k) {
        cr_v2 dv = cr_vsub(cr_point_velocity(B->v, B->w, r->rb[k]),
                           cr_point_velocity(A->v, A->w, r->ra[k]));
        fastest = cr_max(fastest, cr_neg(cr_vdot(dv, r->n)));
    }
    return fastest;
}

/*
 * A pair that was a row of an instant at time t and is due again at the
 * same t, after an instant at t whose solve did not settle (its sweeps
 * stalled or ran out): that solve left it approaching. Such an island
 * (a 48 kg box wedged into a corner by a 300 kg ball that a 4.6e6 kg
 * ball drives on, friction, no gravity) was solved again and again at
 * that one instant, each solve taking a little more of the heavy ball's
 * momentum, to the impact budget in every step: 98000 impacts in 100
 * steps; a 20-body random scene took minutes. Its contact goes to the
 * contact solver instead, which works on it over the substeps (with
 * restitution at the step's end), as in the discrete method. After
 * settled solves a pair can be due again at once for a reason (a
 * neighbour's instant at the same t pushed one of its bodies back into
 * it, as in a dense elastic gas): that stays an impact of its own. (Mark
 * stamps only grow within a step, but wrap: a stamp above the current
 * one is from before a wrap.)
 */
static int cr_again_at_once(const carom_world *w, const cr_pair *p, float t)
{
    return w->instant_unsettled && cr_eq(t, w->instant_t) && p->mark >= w->instant_stamp &&
           p->mark <= w->mark_stamp;
}

/* The impacts at local time t: pair `seed`, and every other pair due at
 * the same instant. */
static carom_status cr_impact_instant(carom_world *w, int seed, float t,
                                      float t_end)
{
    float eps = cr_mul(CAROM_SIMULTANEOUS_TIME_TOL, w->def.dt);
    int nb = 0, nr = 0, i, k, any = 0, seeds = 0;
    carom_status st = CAROM_OK;

    if (++w->mark_stamp == 0)
        ++w->mark_stamp;
    if (!cr_eq(t, w->instant_t)) {
        w->instant_t = t;
        w->instant_stamp = w->mark_stamp;
        w->instant_unsettled = 0;
        w->instant_rehits = 0;
    }
    /* seeds: this pair and every pair due within eps */
    w->pairs[seed].mark = w->mark_stamp;
    cr_island_add_body(w, w->pairs[seed].a, &nb);
    cr_island_add_body(w, w->pairs[seed].b, &nb);
    w->rows[0].pair = seed;
    seeds = 1;
    while (w->heap_count > 0 && cr_le(w->heap[0].t, cr_add(t, eps))) {
        cr_heap_entry e = w->heap[0];
        cr_pair *p = &w->pairs[e.pair];
        cr_heap_pop(w);
        if (e.stamp != p->stamp || p->mark == w->mark_stamp)
            continue;
        if (!cr_room_for_rows(w, seeds + 1) || !cr_island_add_body(w, p->a, &nb) ||
            !cr_island_add_body(w, p->b, &nb)) {
            /* no room: leave it for right after this instant */
            p->toi = t;
            cr_heap_push(w, e.pair);
            break;
        }
        p->mark = w->mark_stamp;
        w->rows[seeds++].pair = e.pair;
    }
    (void)cr_room_for_rows(w, seeds);
    /* everyone to the instant, then the rows */
    for (i = 0; i < nb; ++i) {
        cr_sync(&w->bodies[w->island[i]], &w->drift[w->island[i]], t);
        cr_note_pre(w, w->island[i]);
    }
    for (i = 0; i < seeds; ++i) {
        int k_pair = w->rows[i].pair;
        cr_pair *p = &w->pairs[k_pair];
        if (cr_row_make(w, k_pair, &w->rows[nr])) {
            ++nr;
            p->toi = CR_NEVER;
        } else if ((p->met & CR_PAIR_RESUME) && w->resumed_searches < w->def.max_impacts) {
            /* apart at the instant where a conservative advancement ran
             * out of iterations (a corner of a fast-turning polygon
             * sweeping past a face): search on from here, or the pair
             * would pass through for the rest of the step (at most
             * max_impacts such searches a step) */
            ++w->resumed_searches;
            cr_pair_search(w, k_pair, t);
        } else {
            p->toi = CR_NEVER;
        }
    }
    CR_PHASE(w, CAROM_PHASE_IMPULSES);
    w->rows_settled = cr_rows_solve(w, w->rows, nr, CAROM_IMPACT_ISLAND_ITERATIONS);
    nr = cr_island_grow(w, &nb, nr, t);
    cr_limit_impact_energy(w, nb, nr);
    if (!w->rows_settled)
        w->instant_unsettled = 1;
    for (i = 0; i < nr; ++i) {
        const cr_impact_row *r = &w->rows[i];
        const cr_pair *p = &w->pairs[r->pair];
        /* a contact the impact leaves touching is the solver's again, for
         * this substep's relax and position correction too (unless it is
         * on a pivot: its pair search below decides) */
        if (p->contact >= 0 &&
            (w->contacts[p->contact].flags & CR_CONTACT_TOUCHING) &&
            !cr_gt(cr_contact_approach(w, &w->contacts[p->contact]),
                   cr_rest_speed(w, r->a, r->b)) &&
            !cr_pivots(w, p, t)) {
            /* its normal and points as they are now, not at the step
             * start: a stale normal would take energy out of a pair that
             * separates along the true one */
            if (r->impact && !(w->contacts[p->contact].flags & CR_CONTACT_SOLVE))
                cr_contact_remake(w, &w->contacts[p->contact]);
            w->contacts[p->contact].flags |= CR_CONTACT_SOLVE;
            cr_solver_activate(w, r->a);
            cr_solver_activate(w, r->b);
            w->reorder = 1;
            /* both rest now: what lands on them inelastically later in
             * the step is the solver's (cr_onto_rest in solver.c) */
            if (w->bodies[r->a].type == CAROM_BODY_DYNAMIC)
                w->bodies[r->a].flags |= CR_BODY_RESTS;
            if (w->bodies[r->b].type == CAROM_BODY_DYNAMIC)
                w->bodies[r->b].flags |= CR_BODY_RESTS;
        }
        /* first-impact: a pair the solve left approaching (an unsettled
         * solve) is not searched again this step, so only the solver can
         * stop it */
        if (w->method == CAROM_METHOD_FIRST_IMPACT && !w->rows_settled &&
            cr_gt(cr_row_approach(w, r), cr_rest_speed(w, r->a, r->b)) &&
            !cr_solved_contact(w, p) && cr_pair_to_solver(w, r->pair, t) == -2)
            st = CAROM_ERR_CONTACT_CAPACITY;
        if (!r->impact)
            continue;
        for (k = 0; k < r->count; ++k)
            any |= cr_gt(r->pn[k], 0.0f);
        cr_record(w, r, t);
        w->pairs[r->pair].met |= CR_PAIR_MET | CR_PAIR_HIT;
    }
    ++w->stats.impact_solves;
    CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    if (!any) {
        /* nothing changed course: the seeds were not impacts after all;
         * their contacts are the solver's (a pair on a pivot is searched
         * on past it instead, a bounded number of times a step) */
        for (i = 0; i < seeds && i < nr; ++i) {
            const cr_pair *p = &w->pairs[w->rows[i].pair];
            if (cr_pivots(w, p, t) && w->resumed_searches < w->def.max_impacts) {
                ++w->resumed_searches;
                cr_pair_search(w, w->rows[i].pair, t);
            } else if (p->contact >= 0) {
                w->contacts[p->contact].flags |= CR_CONTACT_SOLVE;
                cr_solver_activate(w, p->a);
                cr_solver_activate(w, p->b);
                w->reorder = 1;
            }
        }
        return st;
    }
    cr_hold_keep(w, nb);
    cr_hold_contacts(w, nb, nr, t, t_end);
    /* the island's dynamic bodies changed course: search their pairs
     * again. A kinematic body keeps its course and the box of its whole
     * step: its other pairs stay as they were found (searching them all
     * again after each of its impacts made a 300-body tumbler's rotor,
     * paired with every body, cost 24 impact searches per impact). */
    for (i = 0; i < nb; ++i)
        if (w->bodies[w->island[i]].type == CAROM_BODY_DYNAMIC)
            ++w->drift[w->island[i]].version;
    for (i = 0; i < nb && st == CAROM_OK; ++i) {
        if (w->bodies[w->island[i]].type != CAROM_BODY_DYNAMIC)
            continue;
        CR_PHASE(w, CAROM_PHASE_BROADPHASE);
        st = cr_regrow(w, w->island[i], t, t_end);
        CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    }
    for (i = 0; i < nb; ++i) {
        int body = w->island[i];
        if (w->bodies[body].type != CAROM_BODY_DYNAMIC)
            continue;
        k = w->pair_head[body];
        while (k >= 0) {
            cr_pair *p = &w->pairs[k];
            int next = p->a == body ? p->next_a : p->next_b;
            /* a resting contact the impact sent one body into is an impact
             * now, for this loop, not the solver; but not after an
             * unsettled solve: then the solver keeps what the solve left
             * (the first-impact method would not search it again, and
             * the events method would take it again at the same instant) */
            if (p->contact >= 0 && w->rows_settled) {
                cr_contact *c = &w->contacts[p->contact];
                if ((c->flags & CR_CONTACT_SOLVE) &&
                    cr_gt(cr_contact_approach(w, c), cr_rest_speed(w, c->a, c->b)))
                    c->flags &= ~CR_CONTACT_SOLVE;
            }
            if (w->method == CAROM_METHOD_FIRST_IMPACT)
                p->solved = cr_solved_contact(w, p); /* found once: no search */
            else if (cr_stale(w, p))
                cr_pair_search(w, k, t);
            k = next;
        }
    }
    return st;
}

/* The solver takes what the event loop leaves past its last resort: the
 * contact of every pair still due this substep. */
static carom_status cr_hand_over(carom_world *w, float t_end)
{
    while (w->heap_count > 0 && !cr_gt(w->heap[0].t, t_end)) {
        cr_heap_entry e = w->heap[0];
        cr_pair *p = &w->pairs[e.pair];
        int c;
        cr_heap_pop(w);
        if (e.stamp != p->stamp)
            continue;
        cr_sync(&w->bodies[p->a], &w->drift[p->a], e.t);
        cr_sync(&w->bodies[p->b], &w->drift[p->b], e.t);
        c = cr_contact_add(w, e.pair);
        if (c == -2)
            return CAROM_ERR_CONTACT_CAPACITY;
        if (c < 0)
            continue;
        w->contacts[c].flags |= CR_CONTACT_SOLVE;
        cr_solver_activate(w, p->a);
        cr_solver_activate(w, p->b);
        w->reorder = 1;
    }
    return CAROM_OK;
}

/*
 * The impacts of the substep up to t_end, in time order. After max_impacts
 * in the step (a ball squeezed between a closing slab and a wall would
 * meet infinitely many) the rest of the substep's impacts are plastic at
 * their instants (nothing is passed through, no chain goes on for ever,
 * momentum is kept and energy is only lost), and the next substeps are
 * solved like the discrete method's, restitution included. After as many
 * plastic instants again the solver takes what is left.
 */
carom_status cr_events_advance(carom_world *w, float t_end)
{
    carom_status st = CAROM_OK;
    int budget = w->def.max_impacts, plastic = 0;
    CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    while (st == CAROM_OK && w->heap_count > 0) {
        cr_heap_entry e = w->heap[0];
        cr_pair *p = &w->pairs[e.pair];
        if (cr_gt(e.t, t_end))
            break;
        if (w->impacts_this_step >= budget)
            w->budget_hit = 1;
        if (w->budget_hit && plastic++ >= budget) {
            st = cr_hand_over(w, t_end);
            break;
        }
        cr_heap_pop(w);
        if (e.stamp != p->stamp)
            continue;
        /* a pair taken again at the instant it was taken at: a body
         * caught between two others that send it back at once (a 0.8 mm
         * box between two kinematic rotors crossing each other, each hit
         * 6 % faster than the last, reached 10^17 m/s). Past a few such,
         * the instant is the solver's, as an unsettled one is */
        if (cr_eq(e.t, w->instant_t) && p->mark >= w->instant_stamp &&
            p->mark <= w->mark_stamp && ++w->instant_rehits > CR_INSTANT_REHITS)
            w->instant_unsettled = 1;
        if (cr_again_at_once(w, p, e.t)) {
            if (cr_pair_to_solver(w, e.pair, e.t) == -2)
                st = CAROM_ERR_CONTACT_CAPACITY;
            continue;
        }
        st = cr_impact_instant(w, e.pair, e.t, t_end);
    }
    /* the contacts handed to the solver here and by the searches of
     * cr_events_refresh join this substep's sweeps: the position sweep,
     * the relax sweeps and shock propagation, which reads the
     * separations the relax sweeps cache (a box whose corner landed at
     * dt 1e-6 s had its contact handed over by the refresh, left out of
     * the order: shock propagation read its far corner, 1.1 mm up, as
     * touching, and stopped the box level on one corner, its turn
     * frozen) */
    if (w->reorder)
        cr_solver_order(w);
    return st;
}

carom_status cr_events_add_contacts(carom_world *w, float t)
{
    int k;
    for (k = 0; k < w->pair_count; ++k) {
        cr_pair *p = &w->pairs[k];
        if (!(p->met & CR_PAIR_MET))
            continue;
        p->met &= ~CR_PAIR_MET;
        if (p->contact >= 0)
            continue;
        /* both bodies at this instant, displacements up to date */
        cr_sync(&w->bodies[p->a], &w->drift[p->a], t);
        cr_sync(&w->bodies[p->b], &w->drift[p->b], t);
        if (cr_contact_add(w, k) == -2)
            return CAROM_ERR_CONTACT_CAPACITY;
    }
    return CAROM_OK;
}

#else /* !CAROM_ENABLE_EVENTS */

void cr_events_begin(carom_world *w) { (void)w; }
void cr_events_refresh(carom_world *w, float t) { (void)w; (void)t; }
carom_status cr_events_advance(carom_world *w, float t_end)
{
    (void)w;
    (void)t_end;
    return CAROM_OK;
}
carom_status cr_events_add_contacts(carom_world *w, float t)
{
    (void)w;
    (void)t;
    return CAROM_OK;
}

#endif /* CAROM_ENABLE_EVENTS */
