/*
 * world.c -- the world's life in caller memory, its bodies, and the step.
 *
 * Memory: one caller buffer holds the world header and every array, each
 * aligned to CR_ALIGN; carom_world_buffer_size() and carom_world_init() use
 * the same layout function, so they cannot disagree.
 */
#include "world.h"

#include "events.h"
#include "island.h"
#include "solver.h"
#include "toi.h"
#include "continuous.h"
#include "touch.h"

#define CR_ALIGN 16u
#define CR_MAX_BODIES (1 << CAROM_ID_INDEX_BITS)
#define CR_INDEX_MASK ((unsigned)CR_MAX_BODIES - 1u)
/* Pairs, contacts and events: at most this many (fits every index). */
#define CR_MAX_CAPACITY (1 << 26)
#define CR_MAX_SUBSTEPS 64
#define CR_MAX_ITERATIONS 64
/* Heap slack over the pair capacity (a pair has at most one live entry). */
#define CR_HEAP_SLACK 64
/* Velocity sweeps of the first substep after bodies were added: nothing
 * to warm-start from, so the support of a stack must be found from zero
 * (a 40-box column needs a few hundred sweeps; they run once). Only when
 * a contact holds one of the new bodies (one dropped into a running pile
 * from above is primed by nothing: a step of the awake pile of 10^3 that
 * primed it took 4.4 times a plain step), and at most
 * CR_PRIME_BUDGET contact sweeps in all (1000 coincident circles, half a
 * million contacts: 256 sweeps took 5 s; they now take 2). */
#define CR_PRIME_ITERATIONS 256
#define CR_PRIME_BUDGET (1L << 20)
#ifndef CR_CORRECT_SWEEPS
#define CR_CORRECT_SWEEPS 1
#endif
/* Contact rows per body of a simultaneous impact solve. */
#define CR_ROWS_PER_ISLAND_BODY 4

#if CAROM_IMPACT_ROWS_MAX < 1
#error "CAROM_IMPACT_ROWS_MAX must be at least 1 (an impact instant holds its first pair's row)"
#endif

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
    d.max_contacts = 0;
    d.max_events = 0;
    d.max_impacts = 0;
    d.length_unit = CAROM_AUTO;
    d.rest_speed = CAROM_AUTO;
    d.linear_slop = CAROM_AUTO;
    d.substeps = CAROM_DEFAULT_SUBSTEPS;
    d.max_substeps = 0;
    d.iterations = CAROM_DEFAULT_ITERATIONS;
    d.relax_iterations = CAROM_DEFAULT_RELAX_ITERATIONS;
    d.enable_sleep = 1;
    d.sleep_time = CAROM_DEFAULT_SLEEP_TIME;
    d.force_fn = 0;
    d.force_user = 0;
    d.max_touch_events = 0;
    d.grow.alloc = 0;
    d.grow.release = 0;
    d.grow.user = 0;
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
#if !CAROM_ENABLE_DISCRETE
    if (m == CAROM_METHOD_DISCRETE)
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
        !cr_finite(d->linear_slop) || !cr_finite(d->length_unit) ||
        !cr_finite(d->sleep_time))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_ge(d->dt, CAROM_LIMIT_MIN_DT) || !cr_le(d->dt, CAROM_LIMIT_MAX_DT))
        return CAROM_ERR_BAD_DT;
    if (!cr_v2_within(d->gravity, CAROM_LIMIT_MAX_ACCEL))
        return CAROM_ERR_OUT_OF_RANGE;
    if (d->max_bodies <= 0 || d->max_bodies > CR_MAX_BODIES ||
        d->max_pairs < 0 || d->max_pairs > CR_MAX_CAPACITY ||
        d->max_contacts < 0 || d->max_contacts > CR_MAX_CAPACITY ||
        d->max_events < 0 || d->max_events > CR_MAX_CAPACITY ||
        d->max_impacts < 0 || d->max_touch_events < 0 ||
        d->max_touch_events > CR_MAX_CAPACITY)
        return CAROM_ERR_BAD_CAPACITY;
    if (d->substeps < 1 || d->substeps > CR_MAX_SUBSTEPS || d->max_substeps < 0 ||
        d->max_substeps > CR_MAX_SUBSTEPS || d->iterations < 1 ||
        d->iterations > CR_MAX_ITERATIONS || d->relax_iterations < 0 ||
        d->relax_iterations > CR_MAX_ITERATIONS || cr_lt(d->sleep_time, 0.0f))
        return CAROM_ERR_BAD_PARAMETER;
    /* lengths and speeds: CAROM_AUTO or within the limits; another
     * negative value is a mistake (a sign error), not a wish for auto */
    if ((cr_lt(d->length_unit, 0.0f) && !cr_eq(d->length_unit, CAROM_AUTO)) ||
        (cr_lt(d->linear_slop, 0.0f) && !cr_eq(d->linear_slop, CAROM_AUTO)) ||
        (cr_lt(d->rest_speed, 0.0f) && !cr_eq(d->rest_speed, CAROM_AUTO)))
        return CAROM_ERR_OUT_OF_RANGE;
    if (cr_gt(d->length_unit, CAROM_LIMIT_MAX_LENGTH) ||
        cr_gt(d->linear_slop, CAROM_LIMIT_MAX_LENGTH) ||
        cr_gt(d->rest_speed, CAROM_LIMIT_MAX_SPEED) ||
        (cr_ge(d->length_unit, 0.0f) && cr_lt(d->length_unit, CAROM_LIMIT_MIN_SIZE)))
        return CAROM_ERR_OUT_OF_RANGE;
#if !CAROM_ENABLE_FORCES
    if (d->force_fn)
        return CAROM_ERR_DISABLED;
#endif
    if (!d->grow.alloc != !d->grow.release)
        return CAROM_ERR_BAD_PARAMETER; /* both or neither */
#if !CAROM_ENABLE_GROW
    if (d->grow.alloc)
        return CAROM_ERR_DISABLED;
#endif
    return cr_method_available(d->method);
}

/* ---- memory layout ------------------------------------------------------------ */

typedef struct cr_caps {
    int bodies, pairs, contacts, events, impacts, heap, island, rows, buckets;
    int touches, touch_events, direct;
} cr_caps;

static void cr_caps_of(const carom_world_def *d, cr_caps *c)
{
    int b = d->max_bodies;
    c->bodies = b;
    c->pairs = d->max_pairs > 0 ? d->max_pairs : CAROM_DEFAULT_PAIRS_PER_BODY * b;
    c->contacts = d->max_contacts > 0 ? d->max_contacts
                                      : CAROM_DEFAULT_CONTACTS_PER_BODY * b;
    c->events = d->max_events > 0 ? d->max_events
                                  : (CAROM_DEFAULT_EVENTS_PER_BODY * b > CAROM_MIN_EVENTS
                                         ? CAROM_DEFAULT_EVENTS_PER_BODY * b
                                         : CAROM_MIN_EVENTS);
    c->impacts = d->max_impacts > 0
                     ? d->max_impacts
                     : ((long)CAROM_DEFAULT_IMPACTS_PER_BODY * b > CAROM_MIN_IMPACTS
                            ? CAROM_DEFAULT_IMPACTS_PER_BODY * b
                            : CAROM_MIN_IMPACTS);
    c->heap = c->pairs + (c->pairs < CR_HEAP_SLACK ? c->pairs : CR_HEAP_SLACK);
    c->island = b < CAROM_IMPACT_ISLAND_MAX_BODIES ? b : CAROM_IMPACT_ISLAND_MAX_BODIES;
    /* a row is a pair: never more rows than pairs */
    c->rows = CR_ROWS_PER_ISLAND_BODY * c->island < c->pairs
                  ? CR_ROWS_PER_ISLAND_BODY * c->island
                  : c->pairs;
    if (c->rows > CAROM_IMPACT_ROWS_MAX)
        c->rows = CAROM_IMPACT_ROWS_MAX;
    /* an impact row has at most three unknowns (two normals, friction) */
    c->direct = 3 * c->rows < CAROM_IMPACT_DIRECT_MAX ? 3 * c->rows : CAROM_IMPACT_DIRECT_MAX;
#if !CAROM_ENABLE_EVENTS
    c->direct = 0;
#endif
    c->buckets = cr_broadphase_bucket_cap(b);
#if CAROM_ENABLE_TOUCH_EVENTS || CAROM_ENABLE_SENSORS
    /* a touching pair is a candidate pair */
    c->touches = c->pairs;
    c->touch_events = d->max_touch_events > 0
                          ? d->max_touch_events
                          : (CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY * b > CAROM_MIN_EVENTS
                                 ? CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY * b
                                 : CAROM_MIN_EVENTS);
#else
    c->touches = 0;
    c->touch_events = 0;
#endif
}

/* The world in its buffer: the header and the per-body arrays, then the
 * pool of the arrays that follow the pair, contact and event capacities
 * (l->pool on, l->total - CR_ALIGN - l->pool bytes long). A world that
 * grows (carom_world_def.grow) moves only the pool, to a block of its own. */
typedef struct cr_layout {
    size_t world, bodies, backup, info, boxes, awake, sbody, drift, mark, island,
        island_v, island_w, regrown, pair_head, proxies, ptmp, start, count,
        support, active, pool, pairs, pair_tmp, contacts, solve_order, warm, heap,
        rows, direct_k, direct_x, direct_u, events, touch, touch_next, touch_events,
        total;
} cr_layout;

static size_t cr_round_up(size_t n) { return (n + CR_ALIGN - 1u) & ~(size_t)(CR_ALIGN - 1u); }

/* Offsets of every array; every count is below 2^27 and every element
 * below 2^10 bytes, so on a 64-bit size_t nothing overflows; on 32-bit
 * targets the running total is checked. */
static int cr_layout_of(const cr_caps *c, cr_layout *l)
{
    size_t at = 0;
    const size_t limit = (size_t)-1 / 4u;
#define CR_PLACE(field, count, type)                                           \
    do {                                                                       \
        size_t n_ = (size_t)(count);                                           \
        /* at <= limit and n_ * size <= limit: the sum cannot wrap */          \
        if (at > limit || n_ > limit / sizeof(type))                           \
            return 0;                                                          \
        l->field = at;                                                         \
        at += cr_round_up(n_ * sizeof(type));                                  \
    } while (0)
    CR_PLACE(world, 1, carom_world);
    CR_PLACE(bodies, c->bodies, cr_body);
    CR_PLACE(backup, c->bodies, cr_body);
    CR_PLACE(info, c->bodies, cr_body_info);
    CR_PLACE(boxes, c->bodies, cr_box);
    CR_PLACE(awake, c->bodies, int);
    CR_PLACE(sbody, c->bodies, cr_solver_body);
    CR_PLACE(drift, c->bodies, cr_drift);
    CR_PLACE(mark, c->bodies, int);
    CR_PLACE(island, c->island, int);
    CR_PLACE(island_v, c->island, cr_v2);
    CR_PLACE(island_w, c->island, float);
    CR_PLACE(regrown, c->bodies, int);
    CR_PLACE(pair_head, c->bodies, int);
    CR_PLACE(proxies, c->bodies, cr_proxy);
    CR_PLACE(start, c->buckets + 1, int);
    CR_PLACE(count, c->bodies + 1, int);
    CR_PLACE(support, c->bodies, int);
    CR_PLACE(active, c->bodies, int);
    l->pool = at;
    CR_PLACE(pairs, c->pairs, cr_pair);
    CR_PLACE(contacts, c->contacts, cr_contact);
    /* the pair sort's scratch (and the touch sort's, at the step's end) is
     * the contact array, free while pairs are found: no memory of its own
     * unless the contacts are too few to hold the pairs */
    if ((size_t)c->contacts * sizeof(cr_contact) >= (size_t)c->pairs * sizeof(cr_pair) &&
        (size_t)c->contacts * sizeof(cr_contact) >= (size_t)c->touches * sizeof(cr_touch))
        l->pair_tmp = l->contacts;
    else
        CR_PLACE(pair_tmp, c->pairs > c->touches ? c->pairs : c->touches, cr_pair);
    /* so is the grid's sort scratch, used before the pairs are found */
    if (!CAROM_ENABLE_GRID ||
        (size_t)c->contacts * sizeof(cr_contact) >= (size_t)c->bodies * sizeof(cr_proxy))
        l->ptmp = l->contacts;
    else
        CR_PLACE(ptmp, c->bodies, cr_proxy);
    CR_PLACE(solve_order, c->contacts, int);
    CR_PLACE(warm, c->contacts, cr_warm);
    CR_PLACE(heap, c->heap, cr_heap_entry);
    CR_PLACE(rows, c->rows, cr_impact_row);
    CR_PLACE(direct_k, (long)c->direct * c->direct, float);
    CR_PLACE(direct_x, c->direct, float);
    CR_PLACE(direct_u, c->direct, int);
    CR_PLACE(events, c->events, carom_event);
    CR_PLACE(touch, c->touches, cr_touch);
    /* the new touch list is built at the step's end, when the impact
     * heap is free: it is the heap (12 bytes a slot, at least one slot a
     * pair, against 8 bytes a touching pair) */
    l->touch_next = l->heap;
    CR_PLACE(touch_events, c->touch_events, carom_touch_event);
#undef CR_PLACE
    if (at > limit)
        return 0;
    l->total = at + CR_ALIGN; /* slack to align any caller buffer */
    return 1;
}

/* Point the world's pool arrays into `pool` (laid out as l's pool) and
 * take c's capacities. */
static void cr_pool_assign(carom_world *w, unsigned char *pool, const cr_caps *c,
                           const cr_layout *l)
{
#define CR_PAT(field, type) ((type *)(void *)(pool + (l->field - l->pool)))
    w->pairs = CR_PAT(pairs, cr_pair);
    w->pair_tmp = CR_PAT(pair_tmp, cr_pair);
    w->bp.tmp = CR_PAT(ptmp, cr_proxy);
    w->contacts = CR_PAT(contacts, cr_contact);
    w->solve_order = CR_PAT(solve_order, int);
    w->warm = CR_PAT(warm, cr_warm);
    w->heap = CR_PAT(heap, cr_heap_entry);
    w->rows = CR_PAT(rows, cr_impact_row);
    w->direct_k = CR_PAT(direct_k, float);
    w->direct_x = CR_PAT(direct_x, float);
    w->direct_u = CR_PAT(direct_u, int);
    w->events = CR_PAT(events, carom_event);
    w->touch = CR_PAT(touch, cr_touch);
    w->touch_next = CR_PAT(touch_next, cr_touch);
    w->touch_events = CR_PAT(touch_events, carom_touch_event);
#undef CR_PAT
    w->def.max_pairs = c->pairs;
    w->def.max_contacts = c->contacts;
    w->def.max_events = c->events;
    w->heap_cap = c->heap;
    w->row_cap = c->rows;
    w->direct_cap = c->direct;
    w->touch_cap = c->touches;
    w->max_touch_events = c->touch_events;
    w->def.max_touch_events = c->touch_events;
}

size_t carom_world_buffer_size(const carom_world_def *def)
{
    cr_caps c;
    cr_layout l;
    if (carom_world_def_validate(def) != CAROM_OK)
        return 0;
    cr_caps_of(def, &c);
    if (!cr_layout_of(&c, &l))
        return 0;
    return l.total;
}

carom_status carom_world_init(carom_world **out, const carom_world_def *def,
                              void *buffer, size_t bytes)
{
    cr_caps c;
    cr_layout l;
    unsigned char *base;
    carom_world *w;
    carom_status st;
    size_t pad;
    int i;

    if (!out || !def || !buffer)
        return CAROM_ERR_NULL;
    st = carom_world_def_validate(def);
    if (st != CAROM_OK)
        return st;
    cr_caps_of(def, &c);
    if (!cr_layout_of(&c, &l))
        return CAROM_ERR_BAD_CAPACITY;
    if (bytes < l.total)
        return CAROM_ERR_BUFFER_TOO_SMALL;

    pad = (CR_ALIGN - ((size_t)buffer & (CR_ALIGN - 1u))) & (CR_ALIGN - 1u);
    base = (unsigned char *)buffer + pad;
    w = (carom_world *)(void *)(base + l.world);
#define CR_AT(field, type) ((type *)(void *)(base + l.field))
    w->def = *def;
    w->pool_mem = 0;
    w->buf_pool = base + l.pool;
    w->buf_pairs = c.pairs;
    w->buf_contacts = c.contacts;
    cr_pool_assign(w, w->buf_pool, &c, &l);
    w->def.max_impacts = c.impacts;
    w->method = def->method;
    w->steps = 0;
    w->bodies = CR_AT(bodies, cr_body);
    w->backup = CR_AT(backup, cr_body);
    w->info = CR_AT(info, cr_body_info);
    w->slot_count = 0;
    w->body_count = 0;
    w->prime = 0;
    w->awake = CR_AT(awake, int);
    w->awake_count = 0;
    w->boxes = CR_AT(boxes, cr_box);
    w->bp.proxies = CR_AT(proxies, cr_proxy);
    w->bp.start = CR_AT(start, int);
    w->bp.count = CR_AT(count, int);
    w->bp.capacity = c.bodies;
    w->bp.bucket_cap = c.buckets;
    w->bp.grid_count = w->bp.big_count = 0;
    w->scale_valid = 0;
    w->bp.buckets = 1;
    w->bp.xbits = 0;
    w->bp.xmask = w->bp.ymask = 0u;
    w->bp.cell = w->bp.inv_cell = 1.0f;
    w->bp.sweep_max = CR_SWEEP_MAX;
    w->bp.sweep = 0;
    w->bp.sweep_axis = 0;
    w->bp.order_n = 0;
    w->pair_count = 0;
    w->pair_head = CR_AT(pair_head, int);
    w->contact_count = 0;
    w->turning_contacts = 0;
    w->warm_count = 0;
    w->warm_h = 0.0f;
    w->sbody = CR_AT(sbody, cr_solver_body);
    w->solve_count = 0;
    w->support = CR_AT(support, int);
    w->support_count = 0;
    w->sep_cached = 0;
    w->contact_edits = w->shock_marked = 0u;
    w->heavy_supports = 0;
    w->drift = CR_AT(drift, cr_drift);
    w->heap_count = 0;
    w->mark = CR_AT(mark, int);
    w->mark_stamp = 0;
    w->island = CR_AT(island, int);
    w->island_v = CR_AT(island_v, cr_v2);
    w->island_w = CR_AT(island_w, float);
    w->island_cap = c.island;
    w->regrown = CR_AT(regrown, int);
    w->regrown_count = 0;
    w->impacts_this_step = 0;
    w->budget_hit = 0;
    w->resumed_searches = 0;
    w->pivot_searches = 0;
    w->event_count = 0;
    w->events_dropped = 0;
    w->error_body = -1;
    w->profile = 0;
    w->touch_count = 0;
    w->touch_event_count = 0;
    w->touch_events_dropped = 0;
    w->grid_valid = 0;
    w->carried_count = 0;
    w->escaped_count = 0;
    w->teleported = 0;
    w->sensor_count = 0;
    w->active = CR_AT(active, int);
    w->active_count = 0;
#undef CR_AT
    for (i = 0; i < c.bodies; ++i) {
        w->mark[i] = 0;
        w->drift[i].version = 0;
        w->drift[i].t = 0.0f;
        w->drift[i].a = cr_v(0.0f, 0.0f);
        w->drift[i].alpha = 0.0f;
        /* every slot counts its generation from 0, whether or not it is
         * in use: an id removed from the last slot stays stale when the
         * slot is taken again */
        w->info[i].generation = 0u;
        w->bodies[i].flags = 0u;
    }
    {
        static const carom_stats z = {0};
        w->stats = z;
    }
    *out = w;
    return CAROM_OK;
}

/* ---- ids ---------------------------------------------------------------------- */

int cr_body_id(const carom_world *w, int slot)
{
    unsigned gen = w->info[slot].generation;
    return (int)(((gen & ((1u << (31 - CAROM_ID_INDEX_BITS)) - 1u)) << CAROM_ID_INDEX_BITS) |
                 (unsigned)slot);
}

carom_status cr_slot_of(const carom_world *w, int id, int *slot)
{
    unsigned u = (unsigned)id, s = u & CR_INDEX_MASK;
    /* slots past slot_count were never used, or were freed from the end
     * (their generation says which) */
    if (id < 0 || (int)s >= w->def.max_bodies)
        return CAROM_ERR_BAD_BODY_ID;
    if (!(w->bodies[s].flags & CR_BODY_ALIVE) || cr_body_id(w, (int)s) != id)
        return (w->bodies[s].flags & CR_BODY_ALIVE) || w->info[s].generation != 0u
                   ? CAROM_ERR_STALE_ID
                   : CAROM_ERR_BAD_BODY_ID;
    *slot = (int)s;
    return CAROM_OK;
}

void cr_record_impact(carom_world *w, int a, int b, float t, cr_v2 n,
                      float impulse, float approach)
{
    carom_event *e;
    ++w->stats.impacts;
    ++w->impacts_this_step;
    if (w->event_count >= w->def.max_events) {
        ++w->events_dropped;
        return;
    }
    e = &w->events[w->event_count++];
    e->t = cr_add(cr_mul((float)w->steps, w->def.dt), t);
    e->body_a = cr_body_id(w, a);
    e->body_b = cr_body_id(w, b);
    e->normal = n;
    e->impulse = impulse;
    e->approach_speed = approach;
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

/* The substeps for q = dt sqrt(|g| / fall) (the fall allowed per
 * substep): at least def.substeps, at most the cap. */
static int cr_substeps_of_q(const carom_world *w, float q)
{
    int n = w->def.substeps;
    int cap = w->def.max_substeps > 0 ? w->def.max_substeps : CAROM_DEFAULT_MAX_SUBSTEPS;
    if (cap <= n)
        return n;
    if (!cr_lt(q, (float)cap))
        return cap; /* (and a q that is not finite) */
    if (cr_gt(q, (float)n)) {
        int m = (int)q;
        n = cr_lt((float)m, q) ? m + 1 : m;
    }
    return n;
}

/* How far a body may fall from rest in a substep: 2 f s of the length. */
static float cr_substep_fall(float length)
{
    return cr_mul(cr_mul(2.0f, CAROM_SUBSTEP_FALL_SLOPS), cr_mul(CAROM_SLOP_PER_LENGTH, length));
}

/*
 * Substeps of a step. The contact solver takes a body's weight off it once
 * a substep; in between, gravity moves it g h^2 / 2 from rest, and in a
 * deep pile the sweeps do not take all of it back before the next substep
 * adds more. While that fall stays within a slop of the length unit the
 * default 4 substeps hold a 500-body pour to 2 mm (dt 1/60, bodies 0.2 m
 * across: 0.8 slop); twice as far per substep (dt 1/40) it ended 17 mm
 * deep, at dt 1/30 130 mm, and bodies 6 cm across under the same gravity
 * sank 44 mm into each other at dt 1/60 (docs/physics.md, "Small bodies
 * and long steps"). So a step takes
 * n = ceil(dt sqrt(|g| / (2 f s))) substeps, s the slop of the length
 * unit and f CAROM_SUBSTEP_FALL_SLOPS, at least def.substeps and at most
 * def.max_substeps. A dimensionless rule (g h^2 / L): a scene scaled
 * with its gravity keeps its count.
 */
static int cr_substeps_for(const carom_world *w, float length)
{
    int cap = w->def.max_substeps > 0 ? w->def.max_substeps : CAROM_DEFAULT_MAX_SUBSTEPS;
    if (cap <= w->def.substeps)
        return w->def.substeps;
    return cr_substeps_of_q(
        w, cr_mul(w->def.dt, cr_sqrt(cr_div(cr_vlen(w->def.gravity), cr_substep_fall(length)))));
}

/*
 * Substeps for unlike masses. Where a heavy body rests on a light one, the
 * sweeps carry its weight through the light body only slowly: Gauss-Seidel
 * takes about m_heavy / m_light sweeps to do it, and the warm start
 * carries what is left over from substep to substep, so an error of the
 * light body's (its fall under the load, its tilt, its slip) grows with
 * g h^2 m_heavy / m_light. Shock propagation (solver.c) holds a column
 * up, but not a heavy ball in the notch between light ones, nor the light
 * box's rocking and slipping between heavy ones in a stack of mixed
 * densities. So a step whose touching contacts join two dynamic bodies of
 * masses R > CAROM_SUBSTEP_MASS_RATIO apart lets a body fall only 1 / R
 * of the usual slop per substep: n = ceil(dt sqrt(|g| R / (2 f s))), at
 * most the cap (docs/physics.md, "Unlike masses leaning on each other":
 * ball pits of densities 0.1 to 10 and stacks of mixed densities).
 * |g| is the larger acceleration of the pair's two bodies (gravity and
 * their forces). Returns 0 where nothing asks for more (no load, no such
 * contact).
 */
static int cr_substeps_mixed(const carom_world *w)
{
    float need = 0.0f; /* the largest acceleration times mass ratio */
    int i, cap = w->def.max_substeps > 0 ? w->def.max_substeps : CAROM_DEFAULT_MAX_SUBSTEPS;
    if (cap <= w->scale.substeps)
        return 0;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        float a = A->inv_m, b = B->inv_m, ratio;
        if (!(c->flags & CR_CONTACT_TOUCHING))
            continue;
        if (cr_eq(a, 0.0f) || cr_eq(b, 0.0f))
            continue; /* static, kinematic */
        if (cr_gt(a, cr_mul(CAROM_SUBSTEP_MASS_RATIO, b)))
            ratio = cr_div(a, b);
        else if (cr_gt(b, cr_mul(CAROM_SUBSTEP_MASS_RATIO, a)))
            ratio = cr_div(b, a);
        else
            continue;
        /* what loads the pair: gravity, or the bodies' own forces (a
         * 1000 kg box pressed by a force of 10 m/s^2 times its mass onto
         * a 1 kg box, in zero gravity, sank 39 cm into it at 4 substeps) */
        need = cr_max(need, cr_mul(cr_max(cr_vlen(A->a), cr_vlen(B->a)), ratio));
    }
    if (!cr_gt(need, 0.0f))
        return 0;
    return cr_substeps_of_q(w, cr_mul(w->def.dt, cr_sqrt(cr_div(need, cr_substep_fall(w->scale.length)))));
}

/* The tolerances of this step (carom_config.h: scale). */
void cr_scale_compute(const carom_world *w, cr_scale *s)
{
    float sum = 0.0f, all = 0.0f, far = 0.0f;
    int i, n = 0, m = 0;
    for (i = 0; i < w->slot_count; ++i) {
        const cr_body *b = &w->bodies[i];
        if (!(b->flags & CR_BODY_ALIVE))
            continue;
        all = cr_add(all, w->info[i].shape.size);
        far = cr_max(far, cr_max(cr_abs(b->x.x), cr_abs(b->x.y)));
        ++m;
        if (b->type == CAROM_BODY_DYNAMIC) {
            sum = cr_add(sum, w->info[i].shape.size);
            ++n;
        }
    }
    if (cr_gt(w->def.length_unit, 0.0f))
        s->length = w->def.length_unit;
    else if (n > 0)
        s->length = cr_div(sum, (float)n);
    else if (m > 0)
        s->length = cr_div(all, (float)m);
    else
        s->length = 1.0f;
    /* automatic: at least CAROM_SLOP_SPACINGS float spacings of the
     * farthest centre from the origin: a slop the positions cannot
     * resolve lets a resting pile creep on their rounding (a pyramid of
     * 1 m boxes at y = 1e4, where floats are 1 mm apart, spread 0.5 m in
     * a minute with its slop of 0.56 mm) */
    s->slop = cr_ge(w->def.linear_slop, 0.0f)
                  ? w->def.linear_slop
                  : cr_max(cr_mul(CAROM_SLOP_PER_LENGTH, s->length),
                           cr_mul(cr_mul(CAROM_SLOP_SPACINGS, FLT_EPSILON), far));
    s->spec = cr_mul(CAROM_SPECULATIVE_SLOPS, s->slop);
    s->push = cr_mul(CAROM_PUSH_SPEED_PER_LENGTH, s->length);
    s->face_tol = cr_mul(CAROM_FACE_TOL_PER_SLOP, s->slop);
    s->corner = cr_mul(CAROM_CORNER_SLOPS, s->slop);
    s->sleep_speed = cr_mul(CAROM_SLEEP_SPEED_PER_LENGTH, s->length);
    s->substeps = cr_substeps_for(w, s->length);
}

int cr_may_collide(const carom_world *w, int a, int b)
{
    if (!cr_body_moves(&w->bodies[a]) && !cr_body_moves(&w->bodies[b]))
        return 0;
    return cr_may_touch(w, a, b);
}

int cr_may_touch(const carom_world *w, int a, int b)
{
    const cr_body *A = &w->bodies[a], *B = &w->bodies[b];
#if CAROM_ENABLE_SENSORS
    /* two sensors never report each other; a sensor sees any body */
    if ((A->flags & B->flags) & CR_BODY_SENSOR)
        return 0;
    if (!((A->flags | B->flags) & CR_BODY_SENSOR) && A->type != CAROM_BODY_DYNAMIC &&
        B->type != CAROM_BODY_DYNAMIC)
        return 0; /* kinematic against kinematic or static: no contact */
#else
    if (A->type != CAROM_BODY_DYNAMIC && B->type != CAROM_BODY_DYNAMIC)
        return 0;
#endif
#if CAROM_ENABLE_FILTERING
    if (((A->flags | B->flags) & CR_BODY_FILTERED) &&
        !cr_filter_pass(&w->info[a], &w->info[b]))
        return 0;
#endif
    return 1;
}

/* Bodies pair unless neither can move (static, asleep, or kinematic at
 * rest), or their filter says no. */
static int cr_accept_pair(void *ctx, int a, int b)
{
    const carom_world *w = (const carom_world *)ctx;
    const cr_body *A = &w->bodies[a], *B = &w->bodies[b];
    const unsigned awake = CR_BODY_ALIVE | CR_BODY_AWAKE;
    /* the usual pair first, without cr_may_collide's calls: an awake
     * dynamic body (it moves, and may touch any body) with a body,
     * neither a sensor nor filtered */
    if (!((A->flags | B->flags) & (CR_BODY_SENSOR | CR_BODY_FILTERED)) &&
        (((A->flags & awake) == awake && A->type == CAROM_BODY_DYNAMIC) ||
         ((B->flags & awake) == awake && B->type == CAROM_BODY_DYNAMIC)))
        return 1;
    if (A->type == CAROM_BODY_STATIC && B->type == CAROM_BODY_STATIC)
        return 0; /* (walls that meet at a corner) */
    return cr_may_collide(w, a, b);
}

/* Has body a a pair with body b (the linked lists of the pairs)? */
int cr_has_pair(const carom_world *w, int a, int b)
{
    int k = w->pair_head[a];
    while (k >= 0) {
        const cr_pair *p = &w->pairs[k];
        if ((p->a == a && p->b == b) || (p->a == b && p->b == a))
            return 1;
        k = p->a == a ? p->next_a : p->next_b;
    }
    return 0;
}

#if CR_CONTINUOUS
/*
 * Pushed reach (with the continuous guard, CAROM_ENABLE_CONTINUOUS). A
 * body's box covers its own motion over the step, but a
 * body that another drives into it may move further: a ball under a
 * large force, or one struck at 50 m/s, pushing a box that rests 1 cm
 * from a wall drove the box 6 cm into the wall in one step (both
 * methods; 23 cm at 50 m/s with the discrete method), and past it under
 * 10^4 N: the box-wall pair was never a candidate, so no contact and no
 * search held it. So a dynamic body i near a static or kinematic body
 * takes a push bound P_i: over its pairs with a moving body j, what j's
 * motion over the step M_j (|v| dt + |a| dt^2 / 2, and |w| dt times a
 * polygon's extent; lengths as |x| + |y|, a bound of them) could carry it,
 * (1 + e) m_j / (m_i + m_j) times M_j (what a head-on impact of
 * restitution e gives a body at rest; 1 + e times for a kinematic j),
 * with j itself carried by its own pairs the same way (two links: a ball,
 * two boxes, a wall). Where P_i exceeds i's own motion by a speculative
 * distance, its box grown by P_i is searched for static and kinematic
 * bodies it has no pair with, and its contacts with them reach P_i
 * further (cr_pair_reach): the solver stops the pushed body at the wall.
 * "Near" is within four times the largest motion of the step of a static
 * or kinematic body's box (two links of at most twice each), so a pile
 * looks at its bodies along the walls, a gas at those about to meet one.
 * Pairs between dynamic bodies are left as they were: the solver pushes
 * overlaps between them apart. At the pair capacity the search stops (the
 * pairs of before). Only inelastic pairs (restitution 0, the default)
 * take the reach: a speculative contact made early stops an elastic body
 * with the approach of the substep it started in, and the discrete
 * method's restitution pass then bounced boxes of an elastic gas off the
 * walls with up to 0.3 % more energy than they had
 * (test_discrete_elastic_box_gas_gains_no_energy); an elastic body
 * pushed into a wall is pushed out by the next step's contact, as before.
 */
/* Static and kinematic bodies a pushed body's box is tested against one
 * by one (more: through the broadphase's query, which in a world swept
 * along one axis visits every body). */
#define CR_PUSH_FEW_FIXED 32

static float cr_motion_bound(const carom_world *w, int i)
{
    const cr_body *b = &w->bodies[i];
    float dt = w->def.dt;
    float m = cr_add(cr_mul(cr_add(cr_abs(b->v.x), cr_abs(b->v.y)), dt),
                     cr_mul(cr_mul(0.5f, cr_add(cr_abs(b->a.x), cr_abs(b->a.y))), cr_mul(dt, dt)));
    if (!CR_BODY_IS_CIRCLE(b))
        m = cr_add(m, cr_mul(cr_mul(cr_abs(b->w), dt), w->info[i].shape.extent));
    return m;
}

/* What body j's motion could carry dynamic body i through their pair. */
static float cr_push_by(const carom_world *w, int i, int j, float mj)
{
    const cr_body *I = &w->bodies[i], *J = &w->bodies[j];
    float e = cr_add(1.0f, cr_max(w->info[i].restitution, w->info[j].restitution));
    if (J->type != CAROM_BODY_DYNAMIC)
        return cr_mul(e, mj);
    /* m_j / (m_i + m_j), with inverse masses */
    return cr_div(cr_mul(cr_mul(e, I->inv_m), mj), cr_add(I->inv_m, J->inv_m));
}

static int cr_moving_other(const carom_world *w, int j)
{
    const cr_body *J = &w->bodies[j];
    return J->type != CAROM_BODY_STATIC && (J->flags & CR_BODY_AWAKE);
}

/* P_i of dynamic body i (above): two links of its pairs. */
static float cr_push_of(const carom_world *w, int i)
{
    float best = 0.0f;
    int k = w->pair_head[i];
    while (k >= 0) {
        const cr_pair *p = &w->pairs[k];
        int j = p->a == i ? p->b : p->a, k2;
        float mj;
        k = p->a == i ? p->next_a : p->next_b;
        if (!cr_moving_other(w, j))
            continue;
        mj = cr_motion_bound(w, j);
        if (w->bodies[j].type == CAROM_BODY_DYNAMIC)
            for (k2 = w->pair_head[j]; k2 >= 0;) {
                const cr_pair *q = &w->pairs[k2];
                int l = q->a == j ? q->b : q->a;
                k2 = q->a == j ? q->next_a : q->next_b;
                if (l != i && cr_moving_other(w, l))
                    mj = cr_max(mj, cr_push_by(w, j, l, cr_motion_bound(w, l)));
            }
        best = cr_max(best, cr_push_by(w, i, j, mj));
    }
    return best;
}

typedef struct cr_push_ctx {
    carom_world *w;
    int body, full;
    const int *fixed;
    int nfixed;
    float reach;
} cr_push_ctx;

/* A static or kinematic body `other` overlapping a pushed body's box:
 * their pair, if it has none. */
static int cr_push_pair(void *ctx, int other)
{
    cr_push_ctx *c = (cr_push_ctx *)ctx;
    carom_world *w = c->w;
    int a = c->body < other ? c->body : other, b = c->body < other ? other : c->body;
    if (other == c->body || w->bodies[other].type == CAROM_BODY_DYNAMIC ||
        cr_gt(w->info[other].restitution, 0.0f) || cr_has_pair(w, a, b) ||
        !cr_may_collide(w, a, b))
        return 1;
    if (w->pair_count >= w->def.max_pairs) {
        c->full = 1;
        return 0;
    }
    cr_pair_init(&w->pairs[w->pair_count++], a, b);
    return 1;
}

static void cr_box_grow(cr_box *b, float d)
{
    b->lo_x = cr_sub(b->lo_x, d);
    b->lo_y = cr_sub(b->lo_y, d);
    b->hi_x = cr_add(b->hi_x, d);
    b->hi_y = cr_add(b->hi_y, d);
}

/* A dynamic body near a static or kinematic one: its push, and if that
 * reaches past its own motion, the pairs of its grown box (pushes of
 * bodies looked at are marked -1 until the end). */
static int cr_push_candidate(void *ctx, int i)
{
    cr_push_ctx *c = (cr_push_ctx *)ctx;
    carom_world *w = c->w;
    const cr_body *b = &w->bodies[i];
    float push;
    cr_box box;
    int f;
    if (b->type != CAROM_BODY_DYNAMIC || !(b->flags & CR_BODY_AWAKE) ||
        !cr_eq(w->sbody[i].push, 0.0f) || cr_gt(w->info[i].restitution, 0.0f))
        return !c->full;
    push = cr_push_of(w, i);
    if (!cr_gt(push, cr_add(cr_motion_bound(w, i), w->scale.spec))) {
        w->sbody[i].push = -1.0f;
        return 1;
    }
    w->sbody[i].push = push;
    box = w->boxes[i];
    cr_box_grow(&box, push);
    c->body = i;
    if (c->nfixed <= CR_PUSH_FEW_FIXED) {
        for (f = 0; f < c->nfixed && !c->full; ++f)
            if (cr_boxes_overlap(&box, &w->boxes[c->fixed[f]]))
                (void)cr_push_pair(c, c->fixed[f]);
    } else {
        cr_broadphase_query(&w->bp, w->boxes, &box, cr_push_pair, c);
    }
    return !c->full;
}

static int cr_pair_before(const cr_pair *p, const cr_pair *q)
{
    return p->a < q->a || (p->a == q->a && p->b < q->b);
}

/* Pairs [0, n0) sorted by (a, b), and [n0, n) appended: all sorted, the
 * same order in every build (the few appended by insertion, then one
 * merge through tmp, which holds n). */
static void cr_pairs_merge_tail(cr_pair *pairs, cr_pair *tmp, int n0, int n)
{
    int i, j, k;
    for (i = n0 + 1; i < n; ++i) {
        cr_pair p = pairs[i];
        for (j = i; j > n0 && cr_pair_before(&p, &pairs[j - 1]); --j)
            pairs[j] = pairs[j - 1];
        pairs[j] = p;
    }
    for (i = 0, j = n0, k = 0; k < n; ++k)
        tmp[k] = (j >= n || (i < n0 && cr_pair_before(&pairs[i], &pairs[j]))) ? pairs[i++]
                                                                             : pairs[j++];
    for (k = 0; k < n; ++k)
        pairs[k] = tmp[k];
}

static void cr_push_reach(carom_world *w)
{
    int i, k, n0 = w->pair_count, moved = 0, nfixed = 0;
    int fixed[CR_PUSH_FEW_FIXED];
    float most = 0.0f;
    cr_push_ctx ctx;
    for (i = 0; i < w->slot_count; ++i)
        w->sbody[i].push = 0.0f;
    for (k = 0; k < n0 && !moved; ++k) {
        const cr_pair *p = &w->pairs[k];
        moved = w->bodies[p->a].type != CAROM_BODY_STATIC &&
                w->bodies[p->b].type != CAROM_BODY_STATIC;
    }
    if (!moved)
        return; /* no pair of two moving bodies: nothing pushes */
    /* only inelastic bodies take a push (below) */
    for (k = 0; k < w->awake_count; ++k)
        if (w->bodies[w->awake[k]].type == CAROM_BODY_DYNAMIC &&
            !cr_gt(w->info[w->awake[k]].restitution, 0.0f))
            break;
    if (k == w->awake_count)
        return;
    {
        /* the largest motion of the step, bounded by the largest of each
         * of its terms (cr_motion_bound) */
        float v = 0.0f, a = 0.0f, turn = 0.0f, dt = w->def.dt;
        for (k = 0; k < w->awake_count; ++k) {
            const cr_body *b = &w->bodies[w->awake[k]];
            v = cr_max(v, cr_add(cr_abs(b->v.x), cr_abs(b->v.y)));
            a = cr_max(a, cr_add(cr_abs(b->a.x), cr_abs(b->a.y)));
            if (!CR_BODY_IS_CIRCLE(b))
                turn = cr_max(turn, cr_mul(cr_abs(b->w), w->info[w->awake[k]].shape.extent));
        }
        most = cr_add(cr_mul(cr_add(v, turn), dt), cr_mul(cr_mul(0.5f, a), cr_mul(dt, dt)));
    }
    /* two links, each at most (1 + e) <= 2 times what drives it */
    most = cr_mul(4.0f, most);
    if (!cr_gt(most, w->scale.spec))
        return;
    for (i = 0; i < w->slot_count && nfixed <= CR_PUSH_FEW_FIXED; ++i)
        if ((w->bodies[i].flags & CR_BODY_ALIVE) && w->bodies[i].type != CAROM_BODY_DYNAMIC) {
            if (nfixed < CR_PUSH_FEW_FIXED)
                fixed[nfixed] = i;
            ++nfixed;
        }
    ctx.w = w;
    ctx.full = 0;
    ctx.fixed = fixed;
    ctx.nfixed = nfixed;
    /* the dynamic bodies within `most` of a static or kinematic body: a
     * few of those, each against every awake body; more, through the
     * broadphase */
    if (nfixed <= CR_PUSH_FEW_FIXED) {
        cr_box near[CR_PUSH_FEW_FIXED];
        int f;
        for (f = 0; f < nfixed; ++f) {
            near[f] = w->boxes[fixed[f]];
            cr_box_grow(&near[f], most);
        }
        for (k = 0; k < w->awake_count && !ctx.full; ++k) {
            i = w->awake[k];
            for (f = 0; f < nfixed; ++f)
                if (cr_boxes_overlap(&near[f], &w->boxes[i])) {
                    (void)cr_push_candidate(&ctx, i);
                    break;
                }
        }
    } else {
        for (i = 0; i < w->slot_count && !ctx.full; ++i) {
            cr_box box;
            if (!(w->bodies[i].flags & CR_BODY_ALIVE) || w->bodies[i].type == CAROM_BODY_DYNAMIC)
                continue;
            box = w->boxes[i];
            cr_box_grow(&box, most);
            cr_broadphase_query(&w->bp, w->boxes, &box, cr_push_candidate, &ctx);
        }
    }
    for (k = 0; k < w->awake_count; ++k)
        if (cr_lt(w->sbody[w->awake[k]].push, 0.0f))
            w->sbody[w->awake[k]].push = 0.0f;
    if (w->pair_count > n0) {
        cr_pairs_merge_tail(w->pairs, w->pair_tmp, n0, w->pair_count);
        cr_pairs_link(w);
    }
}

#endif /* CR_CONTINUOUS */

/* Candidate pairs from every body's box over the step. */
static carom_status cr_find_pairs(carom_world *w)
{
    int i, n = 0;
    long found;
    CR_PHASE(w, CAROM_PHASE_BROADPHASE);
    /* the last grid's escapes are gone with it */
    for (i = 0; i < w->escaped_count; ++i)
        w->bodies[w->regrown[i]].flags &= (unsigned short)~CR_BODY_ESCAPED;
    w->escaped_count = 0;
    {
        /* (locals: the box stores could otherwise be into *w) */
        const cr_body *bodies = w->bodies;
        cr_box *boxes = w->boxes;
        int *list = w->regrown, slots = w->slot_count;
        float dt = w->def.dt, spec = w->scale.spec;
        for (i = 0; i < slots; ++i) {
            cr_mover m;
            if (!(bodies[i].flags & CR_BODY_ALIVE))
                continue;
            m.s = &w->info[i].shape;
            m.b = &bodies[i];
            m.d = &w->drift[i];
            if (bodies[i].flags & CR_BODY_AWAKE)
                cr_swept_box(&m, 0.0f, dt, spec, &boxes[i]);
            else {
                cr_box *b = &boxes[i];
                cr_shape_box(m.s, m.b->x, m.b->q, b);
                b->lo_x = cr_sub(b->lo_x, spec);
                b->lo_y = cr_sub(b->lo_y, spec);
                b->hi_x = cr_add(b->hi_x, spec);
                b->hi_y = cr_add(b->hi_y, spec);
            }
            list[n++] = i; /* scratch: the list of bodies in the grid */
        }
    }
    cr_broadphase_build(&w->bp, w->boxes, w->regrown, n);
    found = cr_broadphase_pairs(&w->bp, w->boxes, cr_accept_pair, w, w->pairs,
                                w->def.max_pairs);
    if (found > (long)w->def.max_pairs) {
        w->pair_count = 0;
        return CAROM_ERR_PAIR_CAPACITY;
    }
    w->pair_count = (int)found;
    w->grid_valid = 1;
#if CAROM_ENABLE_GRID
    cr_pairs_sort(w->pairs, w->pair_tmp, w->pair_count, w->bp.count, w->slot_count);
#endif /* without the grid the pairs come sorted */
    cr_pairs_link(w);
#if CR_CONTINUOUS
    cr_push_reach(w);
#endif
    return CAROM_OK;
}

#if CAROM_ENABLE_QUERIES || CAROM_ENABLE_SENSORS
/* Did the step leave body slot s outside its grid box? An impulse can
 * push a body past the box of its predicted motion (the solver's
 * push-out; an impact beyond a regrown box). The circle of the shape's
 * extent about the centre answers most bodies at once. */
static int cr_escaped(const carom_world *w, int s)
{
    const cr_body *b = &w->bodies[s];
    const cr_shape *sh = &w->info[s].shape;
    const cr_box *g = &w->boxes[s];
    cr_box e;
    if (cr_ge(cr_sub(b->x.x, sh->extent), g->lo_x) && cr_le(cr_add(b->x.x, sh->extent), g->hi_x) &&
        cr_ge(cr_sub(b->x.y, sh->extent), g->lo_y) && cr_le(cr_add(b->x.y, sh->extent), g->hi_y))
        return 0;
    if (CR_KIND_CIRCLE(sh->kind))
        return 1;
    cr_shape_box(sh, b->x, b->q, &e);
    return cr_lt(e.lo_x, g->lo_x) || cr_gt(e.hi_x, g->hi_x) || cr_lt(e.lo_y, g->lo_y) ||
           cr_gt(e.hi_y, g->hi_y);
}

/* Body slot s, in a pair that touched or met this step: list it if the
 * step left it outside its grid box. */
static void cr_note_escape(carom_world *w, int s)
{
    cr_body *b = &w->bodies[s];
    if ((b->flags & CR_BODY_ESCAPED) || b->type == CAROM_BODY_STATIC)
        return;
    if ((b->flags & CR_BODY_REGROWN) || cr_escaped(w, s)) {
        b->flags = (unsigned short)((b->flags | CR_BODY_ESCAPED) & ~CR_BODY_REGROWN);
        w->regrown[w->escaped_count++] = s;
    }
}

/* Only an impulse moves a body off the path its grid box was swept
 * along (forces are constant over the step, a kinematic body keeps its
 * velocity), and impulses act through the pairs that touched or met:
 * their bodies are the only ones to check. */
void cr_note_escapes(carom_world *w)
{
    int k;
    /* nothing moved (then the grid is older, its escapes still listed), or
     * the program moved bodies since the grid was built */
    if (w->awake_count == 0 || !w->grid_valid)
        return;
    for (k = 0; k < w->pair_count; ++k) {
        const cr_pair *p = &w->pairs[k];
        if (p->contact < 0 && !p->met)
            continue;
        cr_note_escape(w, p->a);
        cr_note_escape(w, p->b);
    }
}
#else
void cr_note_escapes(carom_world *w)
{
    (void)w; /* only queries and sensors look at escapes */
}
#endif

/* Sync the bodies the solver takes this substep to its start. */
static void cr_sync_active(carom_world *w, float t)
{
    int i;
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        cr_sync(&w->bodies[id], &w->drift[id], t);
    }
}

/* After the relax at the end of a substep: bodies the solver moved leave
 * it at t with their relaxed velocity and their forces' drift, and any
 * impact's hold of them (events.c) is over: a later hold reads its drift
 * afresh. (Kept, a hold in a later substep in which the body was not the
 * solver's predicted from this substep's drift: 0.6 N s of momentum made
 * in one step of a zero-gravity cluster.) */
static void cr_release_active(carom_world *w, float t)
{
    int i;
    for (i = 0; i < w->active_count; ++i) {
        int id = w->active[i];
        const cr_body *b = &w->bodies[id];
        cr_drift *d = &w->drift[id];
        w->sbody[id].held = 0;
        w->sbody[id].keep = 0;
        d->t = t;
        d->a = b->type == CAROM_BODY_DYNAMIC ? b->a : cr_v(0.0f, 0.0f);
        d->alpha = b->type == CAROM_BODY_DYNAMIC ? b->alpha : 0.0f;
        ++d->version;
    }
}

/* Velocity Verlet's finish: forces at the new positions, v1 = v(dt) +
 * (a1 - a0) dt / 2 (v(dt) already holds a0 dt). */
static carom_status cr_finish_velocities(carom_world *w)
{
    float half = cr_mul(0.5f, w->def.dt);
    int i;
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    for (i = 0; i < w->awake_count; ++i) {
        int id = w->awake[i];
        cr_body *b = &w->bodies[id];
        cr_v2 a1;
        float alpha1;
        carom_status st;
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        st = cr_body_accel(&w->def, cr_body_id(w, id), b, &w->info[id], &a1, &alpha1);
        if (st != CAROM_OK) {
            w->error_body = cr_body_id(w, id);
            return st;
        }
        if (!cr_eq(a1.x, b->a.x) || !cr_eq(a1.y, b->a.y))
            cr_add_velocity(b, cr_vscale(half, cr_vsub(a1, b->a)));
        b->a = a1;
#if CAROM_ENABLE_ROTATION
        cr_add_angular(b, cr_mul(half, cr_sub(alpha1, b->alpha)));
        b->alpha = alpha1;
#endif
        if (b->flags & CR_BODY_ONCE) {
            /* the one-step force acted over this whole step (in a0 and
             * a1); the next step starts without it */
            b->flags &= (unsigned short)~CR_BODY_ONCE;
            st = cr_body_accel(&w->def, cr_body_id(w, id), b, &w->info[id], &b->a,
                               &b->alpha);
            if (st != CAROM_OK) {
                w->error_body = cr_body_id(w, id);
                return st;
            }
        }
    }
    return CAROM_OK;
}

/* Every awake body's state finite and within the documented range. */
static carom_status cr_check_state(carom_world *w)
{
    int i;
    for (i = 0; i < w->awake_count; ++i) {
        int id = w->awake[i];
        const cr_body *b = &w->bodies[id];
        /* the usual case first: within range implies finite for x and v,
         * and these are the operations the checks below make when all
         * pass; a body that fails any is checked again in full, so the
         * error reported is the same */
        if (cr_v2_within(b->x, CAROM_LIMIT_MAX_LENGTH) &&
            cr_v2_within(b->v, CAROM_LIMIT_MAX_SPEED) && cr_finite(b->w) &&
            cr_finite(b->q.c) && cr_finite(b->q.s) &&
            (cr_eq(b->w, 0.0f) ||
             !cr_gt(cr_mul(cr_abs(b->w), w->info[id].shape.extent), CAROM_LIMIT_MAX_SPEED)))
            continue;
        if (!cr_finite(b->x.x) || !cr_finite(b->x.y) || !cr_finite(b->v.x) ||
            !cr_finite(b->v.y) || !cr_finite(b->w) || !cr_finite(b->q.c) ||
            !cr_finite(b->q.s)) {
            w->error_body = cr_body_id(w, id);
            return CAROM_ERR_NOT_FINITE;
        }
        if (!cr_v2_within(b->x, CAROM_LIMIT_MAX_LENGTH) ||
            !cr_v2_within(b->v, CAROM_LIMIT_MAX_SPEED) ||
            /* (the extent is in the cold record: read only if it turns) */
            (!cr_eq(b->w, 0.0f) &&
             cr_gt(cr_mul(cr_abs(b->w), w->info[id].shape.extent), CAROM_LIMIT_MAX_SPEED))) {
            w->error_body = cr_body_id(w, id);
            return CAROM_ERR_OUT_OF_RANGE;
        }
    }
    return CAROM_OK;
}

/*
 * One step, all methods:
 *   pairs -> contacts -> drifts -> for each substep:
 *       classify -> kick + warm start -> solve (push-out) ->
 *       move (drifts; events: impacts in time order) -> relax
 *   -> restitution (discrete) -> finish velocities (Verlet) -> check ->
 *   sleep -> keep impulses.
 */
/* The sweeps that prime this step's first substep (0: none): bodies were
 * added since the last step and a contact holds one of them. */
static int cr_prime_sweeps(const carom_world *w)
{
    int i;
    if (!w->prime || w->contact_count == 0)
        return 0;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        if ((w->bodies[c->a].flags | w->bodies[c->b].flags) & CR_BODY_NEW) {
            long most = CR_PRIME_BUDGET / w->contact_count;
            return most < CR_PRIME_ITERATIONS
                       ? (most > w->def.iterations ? (int)most : w->def.iterations)
                       : CR_PRIME_ITERATIONS;
        }
    }
    return 0;
}

/* The warm start's impulses are per substep (at rest, the weight times
 * h): a step of another substep length than the one that stored them
 * takes them scaled by h / h_then, as Jolt scales its warm start by the
 * ratio of the steps. Without it a step with 5 substeps after one of 14
 * would start every resting contact at 5/14 of its load. The sweeps take
 * that back within the step where the masses are alike
 * (test_stack_holds_when_the_substep_count_changes passes either way);
 * between unlike masses they take it back slowly. */
static void cr_warm_rescale(carom_world *w, float h)
{
    float f;
    int i, k;
    if (!cr_gt(w->warm_h, 0.0f) || cr_eq(w->warm_h, h))
        return;
    f = cr_div(h, w->warm_h);
    for (i = 0; i < w->contact_count; ++i) {
        cr_contact *c = &w->contacts[i];
        for (k = 0; k < c->count; ++k) {
            c->pts[k].pn = cr_mul(f, c->pts[k].pn);
            c->pts[k].pt = cr_mul(f, c->pts[k].pt);
        }
    }
}

static carom_status cr_step(carom_world *w)
{
    int n, k, prime, mixed;
    float dt = w->def.dt, h;
    int events = CAROM_ENABLE_EVENTS &&
                 (!CAROM_ENABLE_DISCRETE || w->method != CAROM_METHOD_DISCRETE);
    carom_status st;
    cr_substep sub;

    /* the scale follows the bodies' shapes and types: it changes only
     * when a body is added or removed */
    if (!w->scale_valid) {
        cr_scale_compute(w, &w->scale);
        w->scale_valid = 1;
    }
    n = w->scale.substeps;
    h = cr_div(dt, (float)n);
    w->stats.substeps = 0;
    cr_island_awake_list(w);
    if (w->awake_count == 0)
        return CAROM_OK; /* everything sleeps or stands still */
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    cr_drifts_begin(w);

    st = cr_find_pairs(w);
    /* a moving body reaching a sleeping island wakes it: then the pairs
     * of the woken bodies are wanted too */
    while (st == CAROM_OK && cr_island_wake_touched(w)) {
        cr_island_awake_list(w);
        cr_drifts_begin(w);
        st = cr_find_pairs(w);
    }
    if (st != CAROM_OK)
        return st;
    CR_PHASE(w, CAROM_PHASE_NARROWPHASE);
    st = cr_contacts_build(w, dt);
    if (st != CAROM_OK)
        return st;

    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    cr_solver_begin(w);
    cr_solver_levels(w);
    mixed = cr_substeps_mixed(w);
    if (mixed > n) {
        n = mixed;
        h = cr_div(dt, (float)n);
    }
    w->stats.substeps = n;
    cr_warm_rescale(w, h);
    cr_substep_init(&sub, w, h);
    prime = cr_prime_sweeps(w);
    if (prime > 0)
        cr_solver_prime(w, &sub);
    if (events) {
        CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
        cr_solver_classify(w, 1);
        cr_events_begin(w);
    }

    for (k = 0; k < n; ++k) {
        float t0 = cr_mul((float)k, h);
        float t1 = k + 1 == n ? dt : cr_mul((float)(k + 1), h);
        int events_now = events && !w->budget_hit, impacts_before;
        sub.t = t0;
        if (k > 0 && events_now) {
            CR_PHASE(w, CAROM_PHASE_NARROWPHASE);
            st = cr_events_add_contacts(w, t0);
            if (st != CAROM_OK)
                return st;
        }
        CR_PHASE(w, CAROM_PHASE_RESTING);
        /* the discrete method's contacts are all the solver's, and none
         * is added during the step: the first substep's list holds */
        if (k == 0 || events)
            cr_solver_classify(w, events_now);
        cr_sync_active(w, t0);
        cr_solver_update_deltas(w);
        cr_solver_kick_and_warm(w, &sub);
        cr_solver_unload(w, &sub);
        cr_solver_solve(w, &sub, 1,
                        k == 0 && prime > 0 ? prime : w->def.iterations);
        cr_solver_set_drifts(w, &sub);
        impacts_before = w->impacts_this_step;
        if (events_now) {
            CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
            cr_events_refresh(w, t0);
            st = cr_events_advance(w, t1);
            if (st != CAROM_OK)
                return st;
            /* contacts made or remade since the marks (impacts) */
            if (w->contact_edits != w->shock_marked)
                cr_solver_mark_shocks(w);
        }
        CR_PHASE(w, CAROM_PHASE_INTEGRATION);
        cr_sync_active(w, t1);
        CR_PHASE(w, CAROM_PHASE_RESTING);
        cr_solver_update_deltas(w);
        if (events_now && w->impacts_this_step > impacts_before) {
            CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
            cr_solver_release_struck(w);
            CR_PHASE(w, CAROM_PHASE_RESTING);
        }
#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
        /* contacts with a turning kinematic body, as the poses are now: for
         * the position sweep, and the next substep's velocity sweeps */
        if (w->turning_contacts > 0) {
            CR_PHASE(w, CAROM_PHASE_NARROWPHASE);
            cr_contacts_turn(w);
            CR_PHASE(w, CAROM_PHASE_RESTING);
        }
#endif
        cr_solver_correct(w, &sub, CR_CORRECT_SWEEPS);
        cr_solver_update_deltas(w);
        cr_solver_solve(w, &sub, 0, w->def.relax_iterations);
        cr_solver_shock(w, &sub);
        cr_release_active(w, t1);
    }
    /* restitution for the contacts the solver stopped faster than the rest
     * speed: all impacts in the discrete method; in the events methods the
     * speculative points of resting pairs (a toppling rod's far end) and,
     * past the impact budget, the rest of the step's impacts */
    CR_PHASE(w, CAROM_PHASE_IMPULSES);
    cr_solver_restitution(w);
    if (w->budget_hit)
        ++w->stats.budget_steps;

    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
    cr_sync_all(w, dt);
#if CR_CONTINUOUS
    CR_PHASE(w, CAROM_PHASE_IMPACT_TIMING);
    cr_continuous_statics(w, dt);
    CR_PHASE(w, CAROM_PHASE_INTEGRATION);
#endif
    st = cr_finish_velocities(w);
    if (st != CAROM_OK)
        return st;
    st = cr_check_state(w);
    if (st != CAROM_OK)
        return st;
    if (!cr_touch_fits(w))
        return CAROM_ERR_PAIR_CAPACITY;
    CR_PHASE(w, CAROM_PHASE_RESTING);
    cr_contacts_store(w);
    w->warm_h = h;
    cr_island_sleep(w, dt);
    if (w->prime) {
        int i;
        for (i = 0; i < w->slot_count; ++i)
            w->bodies[i].flags = (unsigned short)(w->bodies[i].flags & ~CR_BODY_NEW);
        w->prime = 0;
    }
    return CAROM_OK;
}

static carom_status cr_step_taken(carom_world *w)
{
    carom_status st;
    carom_stats saved;
    int i;
    for (i = 0; i < w->slot_count; ++i)
        w->backup[i] = w->bodies[i];
    saved = w->stats;
    w->event_count = 0;
    w->events_dropped = 0;
    w->impacts_this_step = 0;
    w->budget_hit = 0;
    w->error_body = -1;
    w->contact_count = 0;
    w->turning_contacts = 0;
    w->pair_count = 0;

    st = cr_step(w);
    CR_PHASE_OFF();

    if (st != CAROM_OK) {
        /* undo: the bodies as they were, the impulses and counters too */
        int err = w->error_body;
        for (i = 0; i < w->slot_count; ++i) {
            w->bodies[i] = w->backup[i];
            w->bodies[i].flags &= (unsigned short)~(CR_BODY_ESCAPED | CR_BODY_REGROWN);
        }
        if (w->escaped_count > 0) {
            w->escaped_count = 0; /* (the grid was not rebuilt) */
            w->grid_valid = 0;
        }
        w->stats = saved;
        w->event_count = 0;
        w->events_dropped = 0;
        w->touch_event_count = 0;
        w->touch_events_dropped = 0;
        w->error_body = err;
        return st;
    }
    cr_note_escapes(w);
    cr_touch_update(w);
    ++w->steps;
    ++w->stats.steps;
    if (w->pair_count > w->stats.max_pairs_used)
        w->stats.max_pairs_used = w->pair_count;
    if (w->contact_count > w->stats.max_contacts_used)
        w->stats.max_contacts_used = w->contact_count;
    if (w->impacts_this_step > w->stats.max_impacts_used)
        w->stats.max_impacts_used = w->impacts_this_step;
    w->stats.awake_bodies = w->awake_count;
    w->stats.contacts = w->contact_count;
#if CAROM_ENABLE_PROFILE
    if (w->profile) {
        w->profile->steps += 1u;
        w->profile->body_steps += (uint64_t)w->body_count;
        w->profile->impacts += (uint64_t)w->impacts_this_step;
    }
#endif
    return CAROM_OK;
}

#if CAROM_ENABLE_GROW
/* ---- growing ------------------------------------------------------------------ */

/* Move the pool to new capacities in `pool` (a block of l's pool size, or
 * the buffer's own pool): the last step's warm starts and touching pairs
 * go along if they fit; everything else in the pool is the next step's. */
static void cr_pool_move(carom_world *w, unsigned char *pool, const cr_caps *c,
                         const cr_layout *l)
{
    const cr_warm *warm = w->warm;
    const cr_touch *touch = w->touch;
    cr_warm *nw = (cr_warm *)(void *)(pool + (l->warm - l->pool));
    cr_touch *nt = (cr_touch *)(void *)(pool + (l->touch - l->pool));
    int i;
    if (w->warm_count > c->contacts)
        w->warm_count = 0;
    if (w->touch_count > c->touches)
        w->touch_count = 0;
    /* (the old and new pools never overlap: one of them is a block) */
    for (i = 0; i < w->warm_count; ++i)
        nw[i] = warm[i];
    for (i = 0; i < w->touch_count; ++i)
        nt[i] = touch[i];
    cr_pool_assign(w, pool, c, l);
    w->pair_count = 0;
    w->contact_count = 0;
    w->turning_contacts = 0;
    w->heap_count = 0;
    w->event_count = 0;
    w->touch_event_count = 0;
}

/* A step fell short of capacity `st`: take a pool with twice as much from
 * the program's allocator. 0 if there is none, it gives nothing, or the
 * capacity is at its limit. */
static int cr_grow(carom_world *w, carom_status st)
{
    carom_world_def nd = w->def;
    cr_caps c;
    cr_layout l;
    size_t bytes;
    void *block;
    unsigned char *pool;
    if (!w->def.grow.alloc)
        return 0;
    if (st == CAROM_ERR_PAIR_CAPACITY) {
        if (nd.max_pairs >= CR_MAX_CAPACITY)
            return 0;
        nd.max_pairs = nd.max_pairs > CR_MAX_CAPACITY / 2 ? CR_MAX_CAPACITY : 2 * nd.max_pairs;
    } else {
        if (nd.max_contacts >= CR_MAX_CAPACITY)
            return 0;
        nd.max_contacts = nd.max_contacts > CR_MAX_CAPACITY / 2 ? CR_MAX_CAPACITY
                                                               : 2 * nd.max_contacts;
    }
    cr_caps_of(&nd, &c);
    if (!cr_layout_of(&c, &l))
        return 0;
    bytes = l.total - l.pool; /* the pool, and CR_ALIGN of slack */
    block = w->def.grow.alloc(w->def.grow.user, bytes);
    if (!block)
        return 0;
    pool = (unsigned char *)block +
           ((CR_ALIGN - ((size_t)block & (CR_ALIGN - 1u))) & (CR_ALIGN - 1u));
    cr_pool_move(w, pool, &c, &l);
    if (w->pool_mem)
        w->def.grow.release(w->def.grow.user, w->pool_mem);
    w->pool_mem = block;
    ++w->stats.grows;
    return 1;
}

#else
static int cr_grow(carom_world *w, carom_status st)
{
    (void)w;
    (void)st;
    return 0; /* capacities are hard limits */
}
#endif

carom_status carom_world_step(carom_world *w)
{
    carom_status st;
    if (!w)
        return CAROM_ERR_NULL;
    for (;;) {
        st = cr_step_taken(w);
        if ((st != CAROM_ERR_PAIR_CAPACITY && st != CAROM_ERR_CONTACT_CAPACITY) ||
            !cr_grow(w, st))
            return st;
    }
}

#if CAROM_ENABLE_GROW
carom_status carom_world_release(carom_world *w)
{
    carom_world_def nd;
    cr_caps c;
    cr_layout l;
    int kept;
    if (!w)
        return CAROM_ERR_NULL;
    if (!w->pool_mem)
        return CAROM_OK;
    nd = w->def;
    nd.max_pairs = w->buf_pairs;
    nd.max_contacts = w->buf_contacts;
    cr_caps_of(&nd, &c);
    (void)cr_layout_of(&c, &l); /* (it fitted the buffer at init) */
    /* touching pairs that do not fit are dropped: the next step begins
     * them again, with no end between (a program counting its begin and
     * end events must know: the status says so) */
    kept = w->touch_count <= c.touches;
    cr_pool_move(w, w->buf_pool, &c, &l);
    w->def.grow.release(w->def.grow.user, w->pool_mem);
    w->pool_mem = 0;
    return kept ? CAROM_OK : CAROM_ERR_PAIR_CAPACITY;
}
#else
carom_status carom_world_release(carom_world *w)
{
    return w ? CAROM_OK : CAROM_ERR_NULL; /* nothing was ever taken */
}
#endif

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

int carom_world_error_body(const carom_world *w)
{
    return w ? w->error_body : -1;
}

carom_status carom_world_get_tolerances(const carom_world *w,
                                        carom_tolerances *out)
{
    cr_scale s;
    float g;
    if (!w || !out)
        return CAROM_ERR_NULL;
    /* the scale follows the bodies: computed as the next step would */
    cr_scale_compute(w, &s);
    g = cr_vlen(w->def.gravity);
    out->length_unit = s.length;
    out->linear_slop = s.slop;
    out->rest_speed = cr_lt(w->def.rest_speed, 0.0f)
                          ? cr_mul(cr_mul(CAROM_REST_SPEED_PER_ACCEL_DT, g), w->def.dt)
                          : w->def.rest_speed;
    out->sleep_speed = s.sleep_speed;
    out->substeps = s.substeps;
    return CAROM_OK;
}

carom_status carom_world_get_stats(const carom_world *w, carom_stats *out)
{
    if (!w || !out)
        return CAROM_ERR_NULL;
    *out = w->stats;
    return CAROM_OK;
}

#define CR_STR(x) #x
#define CR_VERSION_STRING(a, b, c) CR_STR(a) "." CR_STR(b) "." CR_STR(c)

const char *carom_version(void)
{
    return CR_VERSION_STRING(CAROM_VERSION_MAJOR, CAROM_VERSION_MINOR,
                             CAROM_VERSION_PATCH);
}
