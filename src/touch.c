/*
 * touch.c -- contact reporting: which pairs touch after each step, and the
 * begin-touch / end-touch events a program reads with
 * carom_world_touch_events().
 *
 * The list of touching pairs persists from step to step, sorted by slot
 * pair. At the end of a successful step the pairs touching now are
 * collected (unsorted: the events methods add pairs during the step),
 * together with the old touches of bodies that could not move this step
 * (asleep, static, or kinematic at rest: nothing looked at them, nothing
 * changed); sorted,
 * and merged against the old list: a pair only in the new list began
 * touching, one only in the old list ended. A sensor's touches are its
 * overlaps at the end of the step; a body that crossed it within the
 * step (its way there straight, found by the time-of-impact search) gets
 * a begin and an end in that step.
 */
#include "touch.h"

#include <stdint.h>
#include <string.h>

#include "integrate.h"
#include "narrowphase.h"
#include "toi.h"

#if CAROM_ENABLE_TOUCH_EVENTS || CAROM_ENABLE_SENSORS

static int cr_touch_less(const cr_touch *x, const cr_touch *y)
{
    int xb = x->b & ~CR_TOUCH_SENSOR, yb = y->b & ~CR_TOUCH_SENSOR;
    return x->a < y->a || (x->a == y->a && xb < yb);
}

/* Is touch t among the n sorted touches of list? */
static int cr_touch_in(const cr_touch *list, int n, const cr_touch *t)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (cr_touch_less(&list[mid], t))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && !cr_touch_less(t, &list[lo]);
}

/* Sort by (a, b) in linear time: two counting passes over body slots (by
 * b, then stably by a), through the pair sort's scratch, free at the end
 * of the step (it holds max_pairs pairs, far more than as many touches). */
static void cr_touch_sort(carom_world *w, cr_touch *t, int n)
{
    cr_touch *tmp = (cr_touch *)(void *)w->pair_tmp;
    int *count = w->bp.count, slots = w->slot_count, i;
    if ((long)n * n <= 2L * slots) {
        /* few touches for the slots: an insertion sort (stable, so the
         * same order) without the four passes over every slot */
        for (i = 1; i < n; ++i) {
            cr_touch x = t[i];
            int j = i;
            while (j > 0 && cr_touch_less(&x, &t[j - 1])) {
                t[j] = t[j - 1];
                --j;
            }
            t[j] = x;
        }
        return;
    }
    for (i = 0; i <= slots; ++i)
        count[i] = 0;
    for (i = 0; i < n; ++i)
        ++count[(t[i].b & ~CR_TOUCH_SENSOR) + 1];
    for (i = 0; i < slots; ++i)
        count[i + 1] += count[i];
    for (i = 0; i < n; ++i)
        tmp[count[t[i].b & ~CR_TOUCH_SENSOR]++] = t[i];
    for (i = 0; i <= slots; ++i)
        count[i] = 0;
    for (i = 0; i < n; ++i)
        ++count[tmp[i].a + 1];
    for (i = 0; i < slots; ++i)
        count[i + 1] += count[i];
    for (i = 0; i < n; ++i)
        t[count[tmp[i].a]++] = tmp[i];
}

static void cr_touch_event(carom_world *w, const cr_touch *t, int begin)
{
    carom_touch_event *e;
    if (w->touch_event_count >= w->max_touch_events) {
        ++w->touch_events_dropped;
        return;
    }
    e = &w->touch_events[w->touch_event_count++];
    e->body_a = cr_body_id(w, t->a);
    e->body_b = cr_body_id(w, t->b & ~CR_TOUCH_SENSOR);
    e->begin = begin;
    e->sensor = (t->b & CR_TOUCH_SENSOR) ? 1 : 0;
}

static int cr_still(const cr_body *b)
{
    return (b->flags & CR_BODY_ALIVE) && !cr_body_moves(b);
}

/* Did body s change its pose in the step just taken (against the copy
 * of its state at the step's start)? Compared as bits: no arithmetic. */
static int cr_same_bits(float a, float b)
{
    uint32_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

static int cr_moved_in_step(const carom_world *w, int s)
{
    const cr_body *b = &w->bodies[s], *b0 = &w->backup[s];
    return !cr_same_bits(b->x.x, b0->x.x) || !cr_same_bits(b->x.y, b0->x.y) ||
           !cr_same_bits(b->q.c, b0->q.c) || !cr_same_bits(b->q.s, b0->q.s);
}

/* Does pair k touch at the end of this step? */
static int cr_pair_touches(const carom_world *w, const cr_pair *p, int *sensor)
{
    const cr_body *A = &w->bodies[p->a], *B = &w->bodies[p->b];
    *sensor = ((A->flags | B->flags) & CR_BODY_SENSOR) ? 1 : 0;
#if CAROM_ENABLE_SENSORS
    if (*sensor)
        return cr_lt(cr_separation(&w->info[p->a].shape, A->x, A->q, &w->info[p->b].shape,
                                   B->x, B->q),
                     0.0f);
#endif
#if CAROM_ENABLE_TOUCH_EVENTS
    if (p->met & CR_PAIR_HIT)
        return 1;
    return p->contact >= 0 && (w->contacts[p->contact].flags & CR_CONTACT_TOUCHING);
#else
    return 0; /* (only sensors' touches are kept) */
#endif
}

#if CAROM_ENABLE_SENSORS
/* Body i's way through the step just taken, for the sensor search below:
 * from its pose at the step's start, straight to its end pose, turning
 * at its mean spin. */
static void cr_sensor_way(const carom_world *w, int i, float inv_dt, cr_body *way)
{
    const cr_body *b = &w->bodies[i];
    *way = w->backup[i];
    way->v = cr_vscale(inv_dt, cr_vsub(b->x, way->x));
    way->w = cr_mul(0.5f, cr_add(way->w, b->w));
}

/*
 * Did pair p, a sensor and a body apart at the step's end and not
 * touching at its start, overlap during the step? A body crossing a
 * sensor within one step (a ball at 60 m/s through a sensor 0.2 m wide
 * at dt 1/60) was never reported: touches were only the overlaps at the
 * step's ends. It is now reported as a begin and an end in that step.
 */
static int cr_sensor_crossed(const carom_world *w, const cr_pair *p)
{
    const float dt = w->def.dt;
    cr_body wa, wb;
    cr_drift still;
    cr_mover A, B;
    float toi;
    if (!cr_moved_in_step(w, p->a) && !cr_moved_in_step(w, p->b))
        return 0;
    cr_sensor_way(w, p->a, cr_div(1.0f, dt), &wa);
    cr_sensor_way(w, p->b, cr_div(1.0f, dt), &wb);
    cr_drift_still(&still);
    A.s = &w->info[p->a].shape;
    A.b = &wa;
    A.d = &still;
    B.s = &w->info[p->b].shape;
    B.b = &wb;
    B.d = &still;
    return cr_time_of_impact(&A, &B, 0.0f, dt, 0.0f, &toi) == 1;
}
#endif

#if CAROM_ENABLE_SENSORS
typedef struct cr_escape_ctx {
    carom_world *w;
    int body, n;
} cr_escape_ctx;

/* A sensor overlap of an escaped body (touch list, deduplicated later). */
static int cr_escape_visit(void *ctx, int other)
{
    cr_escape_ctx *c = (cr_escape_ctx *)ctx;
    carom_world *w = c->w;
    const cr_body *A = &w->bodies[c->body], *B = &w->bodies[other];
    int a = c->body < other ? c->body : other;
    /* (the escaped body moved this step, even if it fell asleep at its
     * end: not cr_may_collide, which would drop it then) */
    if (other == c->body || c->n >= w->touch_cap ||
        !((A->flags | B->flags) & CR_BODY_SENSOR) || !cr_may_touch(w, c->body, other))
        return 1;
    if (!cr_lt(cr_separation(&w->info[c->body].shape, A->x, A->q, &w->info[other].shape,
                             B->x, B->q),
               0.0f))
        return 1;
    w->touch_next[c->n].a = a;
    w->touch_next[c->n].b = (a == c->body ? other : c->body) | CR_TOUCH_SENSOR;
    ++c->n;
    return 1;
}

static int cr_escape_grid_visit(void *ctx, int other)
{
    const cr_escape_ctx *c = (const cr_escape_ctx *)ctx;
    return (c->w->bodies[other].flags & CR_BODY_ESCAPED) ? 1 : cr_escape_visit(ctx, other);
}

/* The pairs hold the sensor overlaps of the boxes the step swept; a body
 * pushed out of its box (cr_note_escapes) is tested where it ended. */
static int cr_escaped_overlaps(carom_world *w, int n)
{
    cr_escape_ctx c;
    int i, j;
    c.w = w;
    c.n = n;
    for (i = 0; i < w->escaped_count; ++i) {
        int s = w->regrown[i];
        cr_box b;
        c.body = s;
        cr_shape_box(&w->info[s].shape, w->bodies[s].x, w->bodies[s].q, &b);
        cr_broadphase_query(&w->bp, w->boxes, &b, cr_escape_grid_visit, &c);
        for (j = i + 1; j < w->escaped_count; ++j) {
            int o = w->regrown[j];
            cr_box ob;
            cr_shape_box(&w->info[o].shape, w->bodies[o].x, w->bodies[o].q, &ob);
            if (cr_boxes_overlap(&b, &ob))
                cr_escape_visit(&c, o);
        }
    }
    return c.n;
}
#endif

int cr_touch_fits(const carom_world *w)
{
    int need = w->pair_count, i;
    if (need + w->touch_count <= w->touch_cap)
        return 1;
    /* a touch with a body that moved is a candidate pair of the step
     * (counted already); only those of two bodies that did not are
     * carried over besides */
    for (i = 0; i < w->touch_count && need <= w->touch_cap; ++i) {
        const cr_touch *t = &w->touch[i];
        if (!cr_body_moves(&w->bodies[t->a]) &&
            !cr_body_moves(&w->bodies[t->b & ~CR_TOUCH_SENSOR]))
            ++need;
    }
    return need <= w->touch_cap;
}

void cr_touch_update(carom_world *w)
{
    int n = 0, i, j, k, found;
    w->touch_event_count = 0;
    w->touch_events_dropped = 0;
    for (k = 0; k < w->pair_count && n < w->touch_cap; ++k) {
        const cr_pair *p = &w->pairs[k];
        int sensor;
        if (!cr_pair_touches(w, p, &sensor))
            continue;
#if !CAROM_ENABLE_TOUCH_EVENTS
        if (!sensor)
            continue;
#endif
        w->touch_next[n].a = p->a;
        w->touch_next[n].b = p->b | (sensor ? CR_TOUCH_SENSOR : 0);
        ++n;
    }
#if CAROM_ENABLE_SENSORS
    if (w->escaped_count > 0 && w->sensor_count > 0 && w->grid_valid)
        n = cr_escaped_overlaps(w, n);
#endif
    /* what nothing could change keeps touching: two bodies that do not
     * move and did not move in this step (a body that fell asleep at its
     * end was simulated, and its pairs say whether it still touches: the
     * continuous guard can have put it back off a sensor it had entered).
     * A touch the pairs found already is not taken twice: with the
     * copies, a world of two 4-box stacks, one asleep, filled a list of 8
     * (max_pairs) and lost a touch of the sleeping stack, which ended and
     * began again though nothing moved */
    found = n;
    cr_touch_sort(w, w->touch_next, found);
    for (i = 0; i < w->touch_count && n < w->touch_cap; ++i) {
        const cr_touch *t = &w->touch[i];
        int b = t->b & ~CR_TOUCH_SENSOR;
        if (cr_still(&w->bodies[t->a]) && cr_still(&w->bodies[b]) &&
            !cr_moved_in_step(w, t->a) && !cr_moved_in_step(w, b) &&
            !((w->bodies[t->a].flags | w->bodies[b].flags) & CR_BODY_TELEPORTED) &&
            !cr_touch_in(w->touch_next, found, t))
            w->touch_next[n++] = *t;
    }
    /* (a body teleported before the step moved where the step's copy
     * cannot see: a static sensor moved off a ball that then fell asleep
     * in the step kept touching it, 1.7 m away) */
    if (w->teleported) {
        for (i = 0; i < w->slot_count; ++i)
            w->bodies[i].flags = (unsigned short)(w->bodies[i].flags & ~CR_BODY_TELEPORTED);
        w->teleported = 0;
    }
    cr_touch_sort(w, w->touch_next, n);
    /* a sensor overlap of an escaped body found both in the pairs and
     * by its query is there twice (carried touches are not: above) */
    for (i = 1, j = 1; i < n; ++i)
        if (cr_touch_less(&w->touch_next[j - 1], &w->touch_next[i]))
            w->touch_next[j++] = w->touch_next[i];
    n = n > 0 ? j : 0;
    /* merge: begins and ends */
    for (i = 0, j = 0; i < w->touch_count || j < n;) {
        if (j >= n || (i < w->touch_count && cr_touch_less(&w->touch[i], &w->touch_next[j]))) {
            cr_touch_event(w, &w->touch[i++], 0);
        } else if (i >= w->touch_count || cr_touch_less(&w->touch_next[j], &w->touch[i])) {
            cr_touch_event(w, &w->touch_next[j++], 1);
        } else {
            /* in both (the same pair) */
            ++i;
            ++j;
        }
    }
#if CAROM_ENABLE_SENSORS
    /* bodies that crossed a sensor within the step: a begin and an end */
    for (k = 0; k < w->pair_count && w->sensor_count > 0; ++k) {
        const cr_pair *p = &w->pairs[k];
        cr_touch t;
        int sensor;
        if (cr_pair_touches(w, p, &sensor) || !sensor)
            continue;
        t.a = p->a;
        t.b = p->b | CR_TOUCH_SENSOR;
        if (cr_touch_in(w->touch, w->touch_count, &t) || !cr_sensor_crossed(w, p))
            continue;
        cr_touch_event(w, &t, 1);
        cr_touch_event(w, &t, 0);
    }
#endif
    /* (touch_next is the impact heap's memory, the next step's: the
     * list is kept in touch) */
    for (i = 0; i < n; ++i)
        w->touch[i] = w->touch_next[i];
    w->touch_count = n;
}

void cr_touch_forget(carom_world *w, int s)
{
    int i, n = 0;
    for (i = 0; i < w->touch_count; ++i)
        if (w->touch[i].a != s && (w->touch[i].b & ~CR_TOUCH_SENSOR) != s)
            w->touch[n++] = w->touch[i];
    w->touch_count = n;
}

#else

int cr_touch_fits(const carom_world *w)
{
    (void)w;
    return 1;
}

void cr_touch_update(carom_world *w)
{
    (void)w;
}

void cr_touch_forget(carom_world *w, int s)
{
    (void)w;
    (void)s;
}

#endif

const carom_touch_event *carom_world_touch_events(const carom_world *w, int *count)
{
    if (count)
        *count = w ? w->touch_event_count : 0;
    return w ? w->touch_events : 0;
}

int carom_world_touch_events_dropped(const carom_world *w)
{
    return w ? w->touch_events_dropped : 0;
}
