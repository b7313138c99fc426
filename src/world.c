/*
 * world.c -- world life cycle in caller memory, bodies, and the step.
 *
 * Memory: one caller buffer holds the world header and every array, each
 * aligned to CR_ALIGN; carom_world_buffer_size() and carom_world_init() use
 * the same layout function, so they cannot disagree.
 */
#include "internal.h"

#define CR_ALIGN 16u
#define CR_MAX_CAPACITY (1 << 24)
#define CR_MAX_ITERATIONS 1000
/* Sweeps of the priming solve: it runs cold (nothing to warm-start from)
 * and only when bodies were added, so it can afford to converge. */
#define CR_PRIME_ITERATIONS 100

/* ---- definitions ---------------------------------------------------------- */

carom_world_def carom_default_world_def(void)
{
    carom_world_def d;
    d.gravity = cr_v(0.0f, CAROM_DEFAULT_GRAVITY_Y);
    d.dt = CAROM_DEFAULT_DT;
#if CAROM_ENABLE_EVENTS
    d.method = CAROM_METHOD_EVENTS;
#else
    d.method = CAROM_METHOD_DISCRETE;
#endif
    d.max_bodies = CAROM_DEFAULT_MAX_BODIES;
    d.max_pairs = 0;
    d.max_events = 0; /* CAROM_DEFAULT_EVENTS_PER_BODY per body */
    d.rest_speed = CAROM_DEFAULT_REST_SPEED;
    d.linear_slop = CAROM_DEFAULT_LINEAR_SLOP;
    d.velocity_iterations = CAROM_DEFAULT_VELOCITY_ITERATIONS;
    d.position_iterations = CAROM_DEFAULT_POSITION_ITERATIONS;
    d.force_fn = 0;
    d.force_user = 0;
    return d;
}

static carom_status cr_method_available(carom_method m)
{
    if ((unsigned)m >= (unsigned)CAROM_METHOD_COUNT)
        return CAROM_ERR_BAD_METHOD;
#if !CAROM_ENABLE_EVENTS
    if (m != CAROM_METHOD_DISCRETE)
        return CAROM_ERR_DISABLED;
#endif
    return CAROM_OK;
}

carom_status carom_world_def_validate(const carom_world_def *d)
{
    if (!d)
        return CAROM_ERR_NULL;
    if (!cr_finite(d->gravity.x) || !cr_finite(d->gravity.y) ||
        !cr_finite(d->dt) || !cr_finite(d->rest_speed) ||
        !cr_finite(d->linear_slop))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_gt(d->dt, 0.0f))
        return CAROM_ERR_BAD_DT;
    if (d->max_bodies <= 0 || d->max_bodies > CR_MAX_CAPACITY ||
        d->max_pairs < 0 || d->max_pairs > CR_MAX_CAPACITY ||
        d->max_events < 0 || d->max_events > CR_MAX_CAPACITY)
        return CAROM_ERR_BAD_CAPACITY;
    if (cr_lt(d->rest_speed, 0.0f) || cr_lt(d->linear_slop, 0.0f) ||
        d->velocity_iterations < 0 || d->position_iterations < 0 ||
        d->velocity_iterations > CR_MAX_ITERATIONS ||
        d->position_iterations > CR_MAX_ITERATIONS)
        return CAROM_ERR_BAD_PARAMETER;
#if !CAROM_ENABLE_FORCES
    if (d->force_fn)
        return CAROM_ERR_DISABLED;
#endif
    return cr_method_available(d->method);
}

/* ---- memory layout ------------------------------------------------------------ */

typedef struct cr_layout {
    size_t world, bodies, proxies, proxy_tmp, pairs, pair_tmp, pair_toi, manifolds,
        prev_manifolds, events, total;
} cr_layout;

static size_t cr_round_up(size_t n) { return (n + CR_ALIGN - 1u) & ~(size_t)(CR_ALIGN - 1u); }

static int cr_event_capacity(const carom_world_def *d)
{
    int n = CAROM_DEFAULT_EVENTS_PER_BODY * d->max_bodies;
    if (d->max_events > 0)
        return d->max_events;
    return n > CAROM_MIN_EVENTS ? n : CAROM_MIN_EVENTS;
}

static int cr_pair_capacity(const carom_world_def *d)
{
    return d->max_pairs > 0 ? d->max_pairs
                            : CAROM_DEFAULT_PAIRS_PER_BODY * d->max_bodies;
}

/* Offsets of every array; capacities are <= 2^24 so nothing overflows a
 * 64-bit size_t, and on 32-bit targets the sizes are checked below. */
static int cr_layout_of(const carom_world_def *d, cr_layout *l)
{
    size_t nb = (size_t)d->max_bodies, np = (size_t)cr_pair_capacity(d);
    size_t ne = (size_t)cr_event_capacity(d), at = 0;
    const size_t limit = (size_t)-1 / 4u;
    if (np > limit / sizeof(cr_manifold) || nb > limit / sizeof(cr_body) ||
        ne > limit / sizeof(carom_event))
        return 0;
    l->world = at; at += cr_round_up(sizeof(carom_world));
    l->bodies = at; at += cr_round_up(nb * sizeof(cr_body));
    l->proxies = at; at += cr_round_up(nb * sizeof(cr_proxy));
    l->proxy_tmp = at; at += cr_round_up(nb * sizeof(cr_proxy));
    l->pairs = at; at += cr_round_up(np * sizeof(cr_pair));
    l->pair_tmp = at; at += cr_round_up(np * sizeof(cr_pair));
    l->pair_toi = at; at += cr_round_up(np * sizeof(float));
    l->manifolds = at; at += cr_round_up(np * sizeof(cr_manifold));
    l->prev_manifolds = at; at += cr_round_up(np * sizeof(cr_manifold));
    l->events = at; at += cr_round_up(ne * sizeof(carom_event));
    if (at > limit)
        return 0;
    l->total = at + CR_ALIGN; /* slack to align any caller buffer */
    return 1;
}

size_t carom_world_buffer_size(const carom_world_def *def)
{
    cr_layout l;
    carom_status st = carom_world_def_validate(def);
    if (st != CAROM_OK && st != CAROM_ERR_DISABLED)
        return 0;
    if (st == CAROM_ERR_DISABLED)
        return 0;
    if (!cr_layout_of(def, &l))
        return 0;
    return l.total;
}

carom_status carom_world_init(carom_world **out, const carom_world_def *def,
                              void *buffer, size_t bytes)
{
    cr_layout l;
    unsigned char *base;
    carom_world *w;
    carom_status st;
    size_t pad;

    if (!out || !def || !buffer)
        return CAROM_ERR_NULL;
    st = carom_world_def_validate(def);
    if (st != CAROM_OK)
        return st;
    if (!cr_layout_of(def, &l))
        return CAROM_ERR_BAD_CAPACITY;
    if (bytes < l.total)
        return CAROM_ERR_BUFFER_TOO_SMALL;

    pad = (CR_ALIGN - ((size_t)buffer & (CR_ALIGN - 1u))) & (CR_ALIGN - 1u);
    base = (unsigned char *)buffer + pad;
    w = (carom_world *)(void *)(base + l.world);
    w->def = *def;
    w->def.max_pairs = cr_pair_capacity(def);
    w->def.max_events = cr_event_capacity(def);
    w->method = def->method;
    w->steps = 0;
    w->bodies = (cr_body *)(void *)(base + l.bodies);
    w->body_count = 0;
    w->proxies = (cr_proxy *)(void *)(base + l.proxies);
    w->proxy_tmp = (cr_proxy *)(void *)(base + l.proxy_tmp);
    w->pairs = (cr_pair *)(void *)(base + l.pairs);
    w->pair_tmp = (cr_pair *)(void *)(base + l.pair_tmp);
    w->pair_toi = (float *)(void *)(base + l.pair_toi);
    w->pair_count = 0;
    w->pairs_dropped = 0;
    w->toi_queries = 0;
    w->toi_early_outs = 0;
    w->impacts_total = 0;
    w->manifolds = (cr_manifold *)(void *)(base + l.manifolds);
    w->prev_manifolds = (cr_manifold *)(void *)(base + l.prev_manifolds);
    w->manifold_count = 0;
    w->prev_manifold_count = 0;
    w->needs_prime = 1;
    w->profile = 0;
    w->events = (carom_event *)(void *)(base + l.events);
    w->event_count = 0;
    w->events_dropped = 0;
    *out = w;
    return CAROM_OK;
}

/* ---- bodies ------------------------------------------------------------------- */

carom_status carom_world_add_body(carom_world *w, const carom_body_def *def,
                                  int *id)
{
    cr_body b;
    carom_status st;
    if (!w || !def)
        return CAROM_ERR_NULL;
    st = cr_body_build(def, &b);
    if (st != CAROM_OK)
        return st;
    if (w->body_count >= w->def.max_bodies)
        return CAROM_ERR_WORLD_FULL;
    if (b.type == CAROM_BODY_DYNAMIC)
        cr_body_forces(w, w->body_count, &b, &b.acc, &b.alpha);
    w->bodies[w->body_count] = b;
    if (id)
        *id = w->body_count;
    ++w->body_count;
    w->needs_prime = 1;
    return CAROM_OK;
}

int carom_world_body_count(const carom_world *w)
{
    return w ? w->body_count : 0;
}

carom_status carom_body_get_state(const carom_world *w, int id,
                                  carom_body_state *out)
{
    const cr_body *b;
    if (!w || !out)
        return CAROM_ERR_NULL;
    if (id < 0 || id >= w->body_count)
        return CAROM_ERR_BAD_BODY_ID;
    b = &w->bodies[id];
    out->center = b->x;
    out->position = cr_body_origin(b);
    out->rotation = b->q;
    out->velocity = b->vel;
    out->angular_velocity = b->w;
    return CAROM_OK;
}

carom_status carom_body_get_mass(const carom_world *w, int id, float *mass,
                                 float *inertia)
{
    if (!w)
        return CAROM_ERR_NULL;
    if (id < 0 || id >= w->body_count)
        return CAROM_ERR_BAD_BODY_ID;
    if (mass)
        *mass = w->bodies[id].m;
    if (inertia)
        *inertia = w->bodies[id].I;
    return CAROM_OK;
}

carom_status carom_body_set_force(carom_world *w, int id, carom_vec2 force,
                                  float torque)
{
    cr_body *b;
    if (!w)
        return CAROM_ERR_NULL;
#if CAROM_ENABLE_FORCES
    if (id < 0 || id >= w->body_count)
        return CAROM_ERR_BAD_BODY_ID;
    if (!cr_finite(force.x) || !cr_finite(force.y) || !cr_finite(torque))
        return CAROM_ERR_NOT_FINITE;
    b = &w->bodies[id];
    b->force = force;
    b->torque = torque;
    /* a0 of the next step is the acceleration at the current state */
    if (b->type == CAROM_BODY_DYNAMIC)
        cr_body_forces(w, id, b, &b->acc, &b->alpha);
    return CAROM_OK;
#else
    (void)id;
    (void)force;
    (void)torque;
    (void)b;
    return CAROM_ERR_DISABLED;
#endif
}

/* ---- method ------------------------------------------------------------------ */

carom_status carom_world_set_method(carom_world *w, carom_method method)
{
    carom_status st;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_method_available(method);
    if (st == CAROM_OK)
        w->method = method;
    return st;
}

carom_method carom_world_get_method(const carom_world *w)
{
    return w ? w->method : CAROM_METHOD_DISCRETE;
}

/* ---- the step ------------------------------------------------------------------ */

/*
 * Events methods: a contact that was approaching faster than rest_speed
 * before this step's force kick and still is at its end is an impact (one
 * whose instant fell at the step boundary, or one the event cap left
 * over). A slow arrival (slower than rest_speed at contact, so not an
 * event) that the kick pushed past rest_speed by the end of the step is a
 * landing, for the solver. The end-of-step solver leaves
 * it alone; the next step's event loop finds the pair touching and
 * approaching and takes the impact at its start, in time order with the
 * others. The approach is judged with the resting forces applied
 * (cr_effective_approach): the |g| dt a resting body "approaches" its
 * support by at the end of a step is a resting force's to cancel, not an
 * impact to defer, however large dt is.
 */
static void cr_defer_impacts(carom_world *w)
{
    int i, k, kept = 0;
    for (i = 0; i < w->manifold_count; ++i) {
        cr_manifold *m = &w->manifolds[i];
        const cr_body *A = &w->bodies[m->a], *B = &w->bodies[m->b];
        int impact = 0;
        for (k = 0; k < m->count; ++k) {
            cr_v2 ra = cr_vsub(m->pts[k].p, A->x), rb = cr_vsub(m->pts[k].p, B->x);
            /* approach before this step's kick (start of step, or just
             * after the bodies' last impact) */
            cr_v2 vb = cr_vadd(B->vel_saved, cr_vcross_sv(B->w_saved, rb));
            cr_v2 va = cr_vadd(A->vel_saved, cr_vcross_sv(A->w_saved, ra));
            float before = cr_neg(cr_vdot(cr_vsub(vb, va), m->n));
            float threshold = cr_impact_threshold(A, B, w->def.rest_speed);
            impact |= cr_gt(before, threshold) &&
                      cr_gt(cr_effective_approach(A, B, ra, rb, m->n, w->def.dt),
                            threshold);
        }
        if (!impact)
            w->manifolds[kept++] = *m;
    }
    w->manifold_count = kept;
}

static void cr_find_contacts(carom_world *w)
{
    int i;
    w->manifold_count = 0;
    for (i = 0; i < w->pair_count; ++i) {
        cr_manifold *m = &w->manifolds[w->manifold_count];
        int a = w->pairs[i].a, b = w->pairs[i].b;
        if (cr_collide(&w->bodies[a], &w->bodies[b], w->def.linear_slop, m)) {
            m->a = a;
            m->b = b;
            ++w->manifold_count;
        }
    }
}

/* Record each manifold hit faster than rest_speed as an impact at time t. */
static void cr_record_impacts(carom_world *w, float t)
{
    int i, k;
    for (i = 0; i < w->manifold_count; ++i) {
        const cr_manifold *m = &w->manifolds[i];
        float approach = 0.0f, impulse = 0.0f;
        carom_event *e;
        for (k = 0; k < m->count; ++k) {
            approach = cr_max(approach, m->pts[k].approach);
            impulse = cr_add(impulse, m->pts[k].pn);
        }
        if (!cr_gt(approach, w->def.rest_speed))
            continue;
        if (w->event_count >= w->def.max_events) {
            ++w->events_dropped;
            continue;
        }
        e = &w->events[w->event_count++];
        e->t = t;
        e->body_a = m->a;
        e->body_b = m->b;
        e->normal = m->n;
        e->impulse = impulse;
        e->approach_speed = approach;
    }
}

/*
 * Priming: the forces of the contacts that already touch. The drift of a
 * step includes last step's resting contact forces (integrate.c); before
 * the first step there is no last step, so a stack placed at rest would
 * sink |g| dt^2 / 2 per contact in step 1. This solves, without moving
 * anything, the non-penetration impulses for the velocities a free step
 * would produce (v0 + a0 dt) and keeps them as if a step had found them.
 */
static void cr_prime(carom_world *w)
{
    int i;
    float dt = w->def.dt;
    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        b->vel_saved = b->vel;
        b->w_saved = b->w;
        if (b->type == CAROM_BODY_DYNAMIC) {
            b->vel = cr_vmadd(b->vel, dt, b->acc);
            b->w = cr_add(b->w, cr_mul(dt, b->alpha));
        }
    }
    cr_broadphase(w, w->def.linear_slop);
    cr_find_contacts(w);
    cr_solver_prepare(w, 1);
    cr_solver_velocities(w, CR_PRIME_ITERATIONS);
    cr_solver_store(w);
    for (i = 0; i < w->body_count; ++i) {
        w->bodies[i].vel = w->bodies[i].vel_saved;
        w->bodies[i].w = w->bodies[i].w_saved;
    }
    w->needs_prime = 0;
}

/*
 * Contacts where the bodies are now: find them, solve impulses (restitution
 * for impacts, resting forces otherwise), record impacts at time t, remove
 * overlap, keep the impulses for the next step. The whole collision work of
 * the discrete method; the resting-contact stage of the events methods.
 */
static carom_status cr_resolve_contacts(carom_world *w, float t,
                                        int defer_impacts)
{
    CR_PHASE(w, CAROM_PHASE_BROADPHASE);
    cr_broadphase(w, w->def.linear_slop);
    CR_PHASE(w, CAROM_PHASE_NARROWPHASE);
    cr_find_contacts(w);
    if (defer_impacts)
        cr_defer_impacts(w);
    /* with impacts deferred (events methods) what is left is resting */
    CR_PHASE(w, defer_impacts ? CAROM_PHASE_RESTING : CAROM_PHASE_IMPULSES);
    cr_solver_prepare(w, 0);
    cr_solver_velocities(w, w->def.velocity_iterations);
    cr_record_impacts(w, t);
    CR_PHASE(w, CAROM_PHASE_RESTING);
    cr_solver_positions(w);
    cr_solver_store(w);
    return w->pairs_dropped > 0 ? CAROM_ERR_PAIR_CAPACITY : CAROM_OK;
}

/*
 * One step of the discrete method:
 *   integrate -> broadphase -> narrowphase -> impulses -> projection.
 * Contacts are found where the bodies are at the end of the step, so an
 * impact inside the step is treated as if it happened at its end: the
 * time-step error of ERRATA.md 4 (see docs/physics.md).
 */
static carom_status cr_step_discrete(carom_world *w)
{
    carom_status st = CAROM_OK, st2;
    float t1;
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    t1 = cr_mul((float)(w->steps + 1), w->def.dt);
    if (!cr_integrate(w, w->def.dt))
        st = CAROM_ERR_NOT_FINITE;
    st2 = cr_resolve_contacts(w, t1, 0);
    return st != CAROM_OK ? st : st2;
}

#if CAROM_ENABLE_EVENTS
/* The events methods: impacts in time order inside the step (events.c),
 * then resting contacts as in the discrete method (impacts deferred). */
static carom_status cr_step_in_time_order(carom_world *w)
{
    carom_status st = cr_step_events(w);
    int dropped = w->pairs_dropped;
    float t1 = cr_mul((float)(w->steps + 1), w->def.dt);
    carom_status st2 = cr_resolve_contacts(w, t1, 1);
    if (st == CAROM_OK && dropped > 0)
        st = CAROM_ERR_PAIR_CAPACITY;
    return st != CAROM_OK ? st : st2;
}
#endif

carom_status carom_world_step(carom_world *w)
{
    carom_status st;
    if (!w)
        return CAROM_ERR_NULL;
    w->event_count = 0;
    w->events_dropped = 0;
    if (w->needs_prime) {
        CR_PHASE(w, CAROM_PHASE_RESTING); /* resting forces of the start */
        cr_prime(w);
    }
    switch (w->method) {
    case CAROM_METHOD_DISCRETE:
        st = cr_step_discrete(w);
        break;
#if CAROM_ENABLE_EVENTS
    case CAROM_METHOD_EVENTS:
    case CAROM_METHOD_FIRST_IMPACT:
        st = cr_step_in_time_order(w);
        break;
#endif
    default:
        return CAROM_ERR_BAD_METHOD;
    }
    CR_PHASE_OFF();
    ++w->steps;
    w->impacts_total += w->event_count;
#if CAROM_ENABLE_PROFILE
    if (w->profile) {
        w->profile->steps += 1u;
        w->profile->body_steps += (uint64_t)w->body_count;
        w->profile->impacts += (uint64_t)w->event_count;
    }
#endif
    if (st == CAROM_OK && w->events_dropped > 0)
        st = CAROM_ERR_EVENT_CAPACITY;
    return st;
}

/* ---- results --------------------------------------------------------------------- */

float carom_world_time(const carom_world *w)
{
    return w ? cr_mul((float)w->steps, w->def.dt) : 0.0f;
}

long carom_world_step_count(const carom_world *w)
{
    return w ? w->steps : 0;
}

const carom_event *carom_world_events(const carom_world *w, int *count)
{
    if (count)
        *count = w ? w->event_count : 0;
    return w ? w->events : 0;
}

int carom_world_events_dropped(const carom_world *w)
{
    return w ? w->events_dropped : 0;
}

carom_status carom_world_get_stats(const carom_world *w, carom_stats *out)
{
    if (!w || !out)
        return CAROM_ERR_NULL;
    out->steps = w->steps;
    out->impacts = w->impacts_total;
    out->toi_queries = w->toi_queries;
    out->toi_early_outs = w->toi_early_outs;
    return CAROM_OK;
}
