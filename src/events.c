/*
 * events.c -- the events method: every impact at its instant, in time order.
 *
 * One step:
 *   1. Every dynamic body gets its drift for the step: the Verlet parabola
 *      with acceleration a0 + a_c (forces and last step's resting contact
 *      forces, integrate.c), from local time 0.
 *   2. Broadphase over the boxes each body sweeps in the step.
 *   3. For every candidate pair, its first impact in [0, dt] (toi.c),
 *      unless the early-out rules it out: the distance of the centres at
 *      their time of closest approach (the note's question) exceeds the sum
 *      of the bodies' reaches.
 *   4. Repeatedly take the earliest impact (ties: lowest body pair), move
 *      only its two bodies to that instant, apply the impulse, and recompute
 *      the impacts of every pair involving either body from that instant.
 *      Bodies without impacts are never touched: they follow their drift.
 *   5. At dt every body is advanced to the end of the step and its velocity
 *      finished the Verlet way, v1 = v(dt) - a_c dt + (a1 - a0) dt / 2, with
 *      a1 the forces at the new positions.
 *   6. Resting contacts are not impacts: pairs touching, or arriving,
 *      with an approach slower than rest_speed. The solver handles them at
 *      the end of the step exactly as in the discrete method, and would
 *      also catch an impact the loop missed (recorded at the step's end).
 *
 * Ordering: impacts at equal times are taken in (body_a, body_b) order, one
 * pair at a time, so a row of touching balls hit at one end passes the
 * impulse along pair by pair (Newton's cradle), deterministically.
 *
 * Bounds: the loop processes at most max_events impacts per step. At the
 * cap, motion stops at the instant of the first impact not taken: every
 * body is advanced to that instant only (the rest of the step's motion is
 * dropped, so nothing passes through an impact it was not given), the
 * pending impacts are taken at the start of the next step, and the step
 * returns CAROM_ERR_EVENT_CAPACITY.
 */
#include "internal.h"

#if CAROM_ENABLE_EVENTS

#define CR_NO_IMPACT 3.0e38f

/* Contact closer than this fraction of linear_slop counts as touching. */
#define CR_TOUCH_FRACTION 0.01f

/*
 * The note's early-out: over [t0, t1], can the two bodies' bounding circles
 * meet at all? With d(s) = p + u s + q s^2, |d(s)| >= |p + u s| - |q| h^2;
 * the first term is smallest at the time of closest approach
 * s_c = -p.u / |u|^2, clamped to [0, h].
 */
static int cr_cannot_meet(const cr_body *A, const cr_body *B, float t0,
                          float t1)
{
    cr_v2 xa, xb, p, u, q;
    cr_rot ra, rb;
    float h = cr_sub(t1, t0), uu, sc, dist, reach;
    cr_body_pose(A, t0, &xa, &ra);
    cr_body_pose(B, t0, &xb, &rb);
    p = cr_vsub(xb, xa);
    u = cr_vsub(cr_vmadd(B->vel, cr_sub(t0, B->t_sync), B->acc_d),
                cr_vmadd(A->vel, cr_sub(t0, A->t_sync), A->acc_d));
    q = cr_vscale(0.5f, cr_vsub(B->acc_d, A->acc_d));
    uu = cr_vdot(u, u);
    sc = cr_gt(uu, 0.0f) ? cr_clamp(cr_neg(cr_div(cr_vdot(p, u), uu)), 0.0f, h)
                         : 0.0f;
    dist = cr_sub(cr_vlen(cr_vmadd(p, sc, u)), cr_mul(cr_vlen(q), cr_mul(h, h)));
    reach = cr_add(A->extent, B->extent);
    return cr_gt(dist, reach);
}

/* Next impact of pair k at or after t0 (local time), or CR_NO_IMPACT. */
static float cr_pair_next_impact(carom_world *w, int k, float t0)
{
    const cr_body *A = &w->bodies[w->pairs[k].a];
    const cr_body *B = &w->bodies[w->pairs[k].b];
    float dt = w->def.dt, slop = w->def.linear_slop, toi, sep;
    cr_body a = *A, b = *B;

    ++w->toi_queries;
    if (cr_cannot_meet(A, B, t0, dt)) {
        ++w->toi_early_outs;
        return CR_NO_IMPACT;
    }
    cr_body_pose(A, t0, &a.x, &a.q);
    cr_body_pose(B, t0, &b.x, &b.q);
    sep = cr_separation(&a, &b);
    if (cr_le(sep, cr_mul(CR_TOUCH_FRACTION, slop))) {
        /* touching now: an impact at once if approaching fast, otherwise a
         * resting contact, left to the solver at the end of the step */
        return cr_gt(cr_approach_speed_at(A, B, t0, slop, dt),
                     cr_impact_threshold(A, B, w->def.rest_speed))
                   ? t0
                   : CR_NO_IMPACT;
    }
    if (!cr_time_of_impact(A, B, t0, dt, cr_mul(CAROM_TOI_TOLERANCE, slop), dt, &toi))
        return CR_NO_IMPACT;
    /* arriving slower than rest_speed is coming to rest, not an impact:
     * the solver takes it at the end of the step. (Taking such arrivals as
     * impacts would never end where bodies press on each other: each
     * inelastic impulse starts the next approach, an inelastic collapse.) */
    if (!cr_gt(cr_approach_speed_at(A, B, toi, slop, dt),
               cr_impact_threshold(A, B, w->def.rest_speed)))
        return CR_NO_IMPACT;
    return toi;
}

/* Apply the impact of pair k at local time t; 1 if there was one. */
static int cr_impact(carom_world *w, int k, float t, float t_start)
{
    int a = w->pairs[k].a, b = w->pairs[k].b;
    cr_body *A = &w->bodies[a], *B = &w->bodies[b];
    cr_manifold m;
    float impulse, approach;
    carom_event *e;

    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    cr_body_sync(A, t);
    cr_body_sync(B, t);
    CR_PHASE(w, CAROM_PHASE_NARROWPHASE);
    if (!cr_collide(A, B, w->def.linear_slop, &m))
        return 0;
    m.a = a;
    m.b = b;
    CR_PHASE(w, CAROM_PHASE_IMPULSES);
    impulse = cr_solver_impact(w, &m, &approach);
    if (!cr_gt(impulse, 0.0f))
        return 0;
    /* the resting share of later contacts is judged from here on */
    A->vel_saved = cr_vmadd(A->vel, cr_neg(t), A->acc_c);
    A->w_saved = cr_sub(A->w, cr_mul(t, A->alpha_c));
    B->vel_saved = cr_vmadd(B->vel, cr_neg(t), B->acc_c);
    B->w_saved = cr_sub(B->w, cr_mul(t, B->alpha_c));
    if (w->event_count >= w->def.max_events) {
        ++w->events_dropped;
        return 1;
    }
    e = &w->events[w->event_count++];
    e->t = cr_add(t_start, t);
    e->body_a = a;
    e->body_b = b;
    e->normal = m.n;
    e->impulse = impulse;
    e->approach_speed = approach;
    return 1;
}

static int cr_box_contains(const cr_proxy_box *outer, const cr_proxy *inner)
{
    return cr_le(outer->lo_x, inner->lo_x) && cr_ge(outer->hi_x, inner->hi_x) &&
           cr_le(outer->lo_y, inner->lo_y) && cr_ge(outer->hi_y, inner->hi_y);
}

static int cr_boxes_overlap(const cr_proxy_box *p, const cr_proxy_box *q)
{
    return !(cr_lt(q->hi_x, p->lo_x) || cr_lt(p->hi_x, q->lo_x) ||
             cr_lt(q->hi_y, p->lo_y) || cr_lt(p->hi_y, q->lo_y));
}

static void cr_set_box(cr_proxy_box *box, const cr_proxy *p)
{
    box->lo_x = p->lo_x;
    box->hi_x = p->hi_x;
    box->lo_y = p->lo_y;
    box->hi_y = p->hi_y;
}

/*
 * An impulse can send a body out of the box it was expected to sweep (a
 * light ball struck by a heavy one). Grow its box, and add the pairs the
 * larger box creates, so no impact is missed for want of a candidate pair.
 */
static void cr_regrow(carom_world *w, int i, float t)
{
    cr_body *b = &w->bodies[i];
    cr_proxy now;
    int j, k;
    if (b->type != CAROM_BODY_DYNAMIC)
        return;
    cr_body_swept_bounds(b, t, w->def.dt, w->def.linear_slop, &now);
    if (cr_box_contains(&b->sweep, &now))
        return;
    b->sweep.lo_x = cr_min(b->sweep.lo_x, now.lo_x);
    b->sweep.hi_x = cr_max(b->sweep.hi_x, now.hi_x);
    b->sweep.lo_y = cr_min(b->sweep.lo_y, now.lo_y);
    b->sweep.hi_y = cr_max(b->sweep.hi_y, now.hi_y);
    for (j = 0; j < w->body_count; ++j) {
        int lo = i < j ? i : j, hi = i < j ? j : i, known = 0;
        if (j == i || !cr_boxes_overlap(&b->sweep, &w->bodies[j].sweep))
            continue;
        for (k = 0; k < w->pair_count && !known; ++k)
            known = w->pairs[k].a == lo && w->pairs[k].b == hi;
        if (known)
            continue;
        if (w->pair_count >= w->def.max_pairs) {
            ++w->pairs_dropped;
            continue;
        }
        w->pairs[w->pair_count].a = lo;
        w->pairs[w->pair_count].b = hi;
        w->pair_toi[w->pair_count] = cr_pair_next_impact(w, w->pair_count, t);
        ++w->pair_count;
    }
}

/* Earliest pending impact (ties: lowest pair); -1 if none in the step. */
static int cr_next(const carom_world *w)
{
    int k, best = -1;
    for (k = 0; k < w->pair_count; ++k) {
        float t = w->pair_toi[k];
        if (!cr_le(t, w->def.dt))
            continue;
        if (best < 0 || cr_lt(t, w->pair_toi[best]) ||
            (cr_eq(t, w->pair_toi[best]) &&
             (w->pairs[k].a < w->pairs[best].a ||
              (w->pairs[k].a == w->pairs[best].a &&
               w->pairs[k].b < w->pairs[best].b))))
            best = k;
    }
    return best;
}

carom_status cr_step_events(carom_world *w)
{
    carom_status st = CAROM_OK;
    float dt = w->def.dt;
    float t_start;
    int i, k, impacts = 0, loops = 0;
    int max_loops = 4 * w->def.max_events + 64;
    int recompute_all = w->method == CAROM_METHOD_EVENTS;
    float t_stop = dt;

    /* 1. drifts */
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    t_start = cr_mul((float)w->steps, dt);
    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        b->t_sync = 0.0f;
        b->vel_saved = b->vel;
        b->w_saved = b->w;
        if (b->type == CAROM_BODY_DYNAMIC) {
            b->acc_d = cr_vadd(b->acc, b->acc_c);
            b->alpha_d = cr_add(b->alpha, b->alpha_c);
        } else {
            b->acc_d = cr_v(0.0f, 0.0f);
            b->alpha_d = 0.0f;
        }
    }
    /* 2. candidate pairs from the swept boxes */
    CR_PHASE(w, CAROM_PHASE_BROADPHASE);
    for (i = 0; i < w->body_count; ++i) {
        cr_body_swept_bounds(&w->bodies[i], 0.0f, dt, w->def.linear_slop,
                             &w->proxies[i]);
        w->proxies[i].body = i;
        cr_set_box(&w->bodies[i].sweep, &w->proxies[i]);
    }
    cr_broadphase_pairs(w);
    /* 3. first impacts */
    CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    for (k = 0; k < w->pair_count; ++k)
        w->pair_toi[k] = cr_pair_next_impact(w, k, 0.0f);

    /* 4. impacts in time order */
    while ((k = cr_next(w)) >= 0) {
        float t = w->pair_toi[k];
        int a = w->pairs[k].a, b = w->pairs[k].b, j, hit;
        if (impacts >= w->def.max_events || ++loops > max_loops) {
            /* cap: motion stops at this instant for the rest of the step,
             * so no body moves past an impact it was not given; the
             * pending impacts are taken at the start of the next step */
            st = CAROM_ERR_EVENT_CAPACITY;
            ++w->events_dropped;
            t_stop = t;
            break;
        }
        hit = cr_impact(w, k, t, t_start);
        impacts += hit;
        CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
        if (!recompute_all) {
            /* first-impact: each pair's first impact only, found once */
            w->pair_toi[k] = CR_NO_IMPACT;
            continue;
        }
        if (!hit) {
            /* nothing changed but this pair's search start; no progress
             * means no impact: leave the pair to the end-of-step solver */
            float next = cr_pair_next_impact(w, k, t);
            w->pair_toi[k] = cr_gt(next, t) ? next : CR_NO_IMPACT;
            continue;
        }
        /* the impulse changed the paths of a and b (a static body's never
         * changes): their pairs' impacts are found again from t */
        for (j = 0; j < w->pair_count; ++j) {
            int pa = w->pairs[j].a, pb = w->pairs[j].b;
            int moved = (pa == a || pb == a) && w->bodies[a].type == CAROM_BODY_DYNAMIC;
            moved |= (pa == b || pb == b) && w->bodies[b].type == CAROM_BODY_DYNAMIC;
            if (moved)
                w->pair_toi[j] = cr_pair_next_impact(w, j, t);
        }
        CR_PHASE(w, CAROM_PHASE_BROADPHASE);
        cr_regrow(w, a, t);
        cr_regrow(w, b, t);
        CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    }

    /* 5. finish the drift and the Verlet velocity update */
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        cr_v2 acc1;
        float alpha1;
        cr_body_sync(b, t_stop);
        b->t_sync = 0.0f;
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        if (!cr_body_forces(w, i, b, &acc1, &alpha1) && st == CAROM_OK)
            st = CAROM_ERR_NOT_FINITE;
        b->vel = cr_vadd(cr_vmadd(b->vel, cr_neg(t_stop), b->acc_c),
                         cr_vscale(cr_mul(0.5f, t_stop), cr_vsub(acc1, b->acc)));
        b->acc = acc1;
#if CAROM_ENABLE_ROTATION
        b->w = cr_add(cr_sub(b->w, cr_mul(t_stop, b->alpha_c)),
                      cr_mul(cr_mul(0.5f, t_stop), cr_sub(alpha1, b->alpha)));
        b->alpha = alpha1;
#endif
    }
    return st;
}

#else
/* ISO C forbids an empty translation unit */
typedef int cr_events_disabled;
#endif /* CAROM_ENABLE_EVENTS */
