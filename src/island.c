/*
 * island.c -- islands of touching bodies, and sleep.
 *
 * A dynamic body is still while its fastest point, |v| + |w| extent, stays
 * under the sleep speed (CAROM_SLEEP_SPEED_PER_LENGTH x length unit), or
 * while its mean speed over a window does (cr_slow_on_average); its still
 * time counts up, and resets when it moves. At the end of a step the
 * bodies linked by touching contacts or by meeting boxes form islands
 * (union-find over the step's contacts and pairs; static bodies do not
 * link islands); an island whose every body has been still, and held by
 * a contact that pushes on it, for the world's sleep_time falls asleep: its
 * bodies stop, leave the step's work entirely (no box, no contact, no
 * drift), and remember their island. A sleeping island wakes as a whole
 * when a moving body reaches one of its bodies, or when the program pushes
 * one (carom_body_set_force and the other setters). A settled pile then
 * costs almost nothing.
 */
#include "island.h"

void cr_island_awake_list(carom_world *w)
{
    /* (locals: a store into awake[] could otherwise be one into *w) */
    const cr_body *bodies = w->bodies;
    int *awake = w->awake, i, n = 0, slots = w->slot_count;
    for (i = 0; i < slots; ++i) {
        const cr_body *b = &bodies[i];
        if ((b->flags & (CR_BODY_ALIVE | CR_BODY_AWAKE)) == (CR_BODY_ALIVE | CR_BODY_AWAKE) &&
            b->type != CAROM_BODY_STATIC)
            awake[n++] = i;
    }
    w->awake_count = n;
}

/* A new window of body `slot`'s mean speed, from where it is now. */
static void cr_window_restart(carom_world *w, int slot)
{
    cr_body_info *in = &w->info[slot];
    in->sleep_x = w->bodies[slot].x;
    in->sleep_q = w->bodies[slot].q;
    in->sleep_window = 0.0f;
    in->sleep_travel = 0.0f;
    in->sleep_away = 0.0f;
}

void cr_island_wake(carom_world *w, int slot)
{
    int island = w->bodies[slot].sleep_island, j;
    cr_body *b = &w->bodies[slot];
    b->still_time = 0.0f;
    cr_window_restart(w, slot);
    if (b->flags & CR_BODY_AWAKE)
        return;
    b->flags |= CR_BODY_AWAKE;
    w->bodies[slot].sleep_island = -1;
    if (island < 0)
        return;
    for (j = 0; j < w->slot_count; ++j) {
        cr_body *o = &w->bodies[j];
        if ((o->flags & CR_BODY_ALIVE) && !(o->flags & CR_BODY_AWAKE) &&
            w->bodies[j].sleep_island == island) {
            o->flags |= CR_BODY_AWAKE;
            o->still_time = 0.0f;
            cr_window_restart(w, j);
            w->bodies[j].sleep_island = -1;
        }
    }
}

static int cr_asleep(const cr_body *b)
{
    return b->type == CAROM_BODY_DYNAMIC && !(b->flags & CR_BODY_AWAKE);
}

/* Able to move into a sleeping body this step. */
static int cr_awake_mover(const cr_body *b)
{
    return cr_body_moves(b);
}

/*
 * A sleeping body paired with an awake one (their boxes over the step
 * overlap) wakes with its island: the two may touch this step, and a
 * sleeping body takes no part in the solve (it would be pushed without
 * moving, or move while asleep). Even an awake body that is itself still
 * wakes it: the two are one island now, which sleeps again when all of it
 * is still.
 */
int cr_island_wake_touched(carom_world *w)
{
    int i, woke = 0;
#if !CAROM_ENABLE_SLEEP
    (void)i;
    (void)w;
    return 0; /* nothing sleeps */
#endif
    for (i = 0; i < w->pair_count; ++i) {
        const cr_pair *p = &w->pairs[i];
        const cr_body *A = &w->bodies[p->a], *B = &w->bodies[p->b];
        if (cr_asleep(A) && cr_awake_mover(B)) {
            cr_island_wake(w, p->a);
            woke = 1;
        } else if (cr_asleep(B) && cr_awake_mover(A)) {
            cr_island_wake(w, p->b);
            woke = 1;
        }
    }
    return woke;
}

#if CAROM_ENABLE_SLEEP
static int cr_find(int *parent, int i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}


/* One island of the islands of a and b (the lower root). */
static void cr_union(int *parent, int a, int b)
{
    int ra = cr_find(parent, a), rb = cr_find(parent, b);
    if (ra != rb)
        parent[ra < rb ? rb : ra] = ra < rb ? ra : rb;
}

/*
 * Is body id slow on average: still within sleep_speed x window of where
 * its window started, a whole window (CAROM_SLEEP_WINDOW sleep times)
 * ago or more? Its fastest point's travel is bounded by the move of its
 * centre plus the chord its rotation sweeps at the extent. A body that
 * goes further starts a new window where it is. A box resting tilted on a
 * circle that rolls on the floor rocks with the circle at 0.1 m/s for
 * ever (no slip, so no contact dissipates it: a pile of 2000 bodies never
 * slept, nor in Box2D v3); its mean speed over a window is nil.
 */
static int cr_slow_on_average(carom_world *w, int id, float dt)
{
    const cr_body *b = &w->bodies[id];
    cr_body_info *in = &w->info[id];
    float window = cr_mul(CAROM_SLEEP_WINDOW, w->def.sleep_time);
    cr_v2 dq = cr_v(cr_sub(b->q.c, in->sleep_q.c), cr_sub(b->q.s, in->sleep_q.s));
    float travel = cr_add(cr_vlen(cr_vsub(b->x, in->sleep_x)),
                          cr_mul(in->shape.extent, cr_vlen(dq)));
    if (cr_gt(travel, cr_mul(w->scale.sleep_speed, window))) {
        cr_window_restart(w, id);
        return 0;
    }
    /* A body rocking about a place comes back towards where its window
     * started; one sliding or tipping away goes further every step. One
     * that has gone further in every step for half a window is moving
     * off, however slowly on average: a box released on an incline 0.1
     * degree steeper than its friction angle slides off at 0.02 m/s^2,
     * 0.16 m in its first 4 s, within the window's bound (0.32 m), and
     * slept sliding at 0.087 m/s. Such a body is still only if it is
     * slow now (the caller's speed test). */
    if (cr_gt(travel, in->sleep_travel))
        in->sleep_away = cr_add(in->sleep_away, dt);
    else
        in->sleep_away = 0.0f;
    in->sleep_travel = travel;
    in->sleep_window = cr_add(in->sleep_window, dt);
    return !cr_lt(in->sleep_window, window) &&
           cr_lt(in->sleep_away, cr_mul(0.5f, window));
}
#endif

void cr_island_sleep(carom_world *w, float dt)
{
#if CAROM_ENABLE_SLEEP
    int *parent = w->regrown;   /* scratch at the end of the step */
    int *can_sleep = w->pair_head;
    float g = cr_vlen(w->def.gravity), speedup;
    int i;
    if (!w->def.enable_sleep)
        return;
    /* how much faster a slow body may get and still be still: a fraction
     * of the sleep speed, and under gravity at most a fraction of what
     * gravity gives in the sleep time (big bodies tip slowly for their
     * size: the top of a tower of 4 m boxes 0.5 % past its edge gains
     * about 5 mm/s in its first 0.5 s, a fifth of a tenth of their sleep
     * speed) */
    speedup = cr_mul(CAROM_SLEEP_SPEEDUP, w->scale.sleep_speed);
    if (cr_gt(g, 0.0f))
        speedup = cr_min(speedup, cr_mul(CAROM_SLEEP_SPEEDUP_PER_G,
                                         cr_mul(g, w->def.sleep_time)));
    /* A body is at rest only while something holds it: a touching
     * contact that pushed on it this step. A body coasting slowly through
     * empty space is not at rest however slow, nor when it comes within
     * reach of a wall or another body, nor in the step it strikes one (a
     * ball drifting at 3 cm/s in zero gravity slept 1.5 mm short of the
     * wall it was about to bounce off, and a slow ball that struck a wall
     * slept against it) */
    for (i = 0; i < w->awake_count; ++i)
        can_sleep[w->awake[i]] = 0;
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        int k, pushed = 0;
        if (!(c->flags & CR_CONTACT_TOUCHING))
            continue;
        for (k = 0; k < c->count; ++k)
            if (cr_gt(c->pts[k].max_pn, 0.0f))
                pushed = 1;
        if (!pushed)
            continue;
        if (w->bodies[c->a].type == CAROM_BODY_DYNAMIC)
            can_sleep[c->a] = 1;
        if (w->bodies[c->b].type == CAROM_BODY_DYNAMIC)
            can_sleep[c->b] = 1;
    }
    for (i = 0; i < w->awake_count; ++i) {
        int id = w->awake[i];
        cr_body *b = &w->bodies[id];
        cr_body_info *in = &w->info[id];
        float speed = cr_add(cr_vlen(b->v), cr_mul(cr_abs(b->w), in->shape.extent));
        parent[id] = id;
        if (b->type != CAROM_BODY_DYNAMIC) {
            b->still_time = 0.0f;
            continue;
        }
        /* (a body not moving at all is at rest held or not: sleeping
         * changes nothing of it, and a rack of touching balls in zero
         * gravity sleeps until the break) */
        if ((!can_sleep[id] && !cr_eq(speed, 0.0f)) || (b->flags & CR_BODY_SHIFTED)) {
            b->still_time = 0.0f;
            cr_window_restart(w, id);
            continue;
        }
        if (cr_slow_on_average(w, id, dt)) {
            b->still_time = cr_add(b->still_time, dt);
            continue;
        }
        if (cr_gt(speed, w->scale.sleep_speed)) {
            b->still_time = 0.0f;
            continue;
        }
        /* slow, but starting to fall? A leaning tower released at rest
         * tips slower than the sleep speed for longer than the sleep
         * time, and slept standing (a 6-box tower of 2 m boxes whose top
         * five hung 5 % of a box past the edge). A body going faster
         * than ever since it became still, and faster than the slowest
         * it went by `speedup`, is speeding up: its still time starts
         * again. A body that rocks or jitters at a steady amplitude
         * makes no new top speed after its first swing, and stays
         * still */
        if (!cr_gt(b->still_time, 0.0f)) {
            in->still_speed = speed;
            in->still_max = speed;
        }
        if (cr_lt(speed, in->still_speed))
            in->still_speed = speed;
        if (!cr_lt(speed, in->still_max) &&
            cr_gt(speed, cr_add(in->still_speed, speedup))) {
            b->still_time = 0.0f;
            in->still_speed = speed;
            in->still_max = speed;
        } else {
            in->still_max = cr_max(in->still_max, speed);
            b->still_time = cr_add(b->still_time, dt);
        }
    }
    for (i = 0; i < w->contact_count; ++i) {
        const cr_contact *c = &w->contacts[i];
        const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        if (!(c->flags & CR_CONTACT_TOUCHING))
            continue;
        /* a body carried by a moving kinematic body never sleeps */
#if CAROM_ENABLE_KINEMATIC
        if (A->type == CAROM_BODY_KINEMATIC && cr_body_moves(A))
            w->bodies[c->b].still_time = 0.0f;
        if (B->type == CAROM_BODY_KINEMATIC && cr_body_moves(B))
            w->bodies[c->a].still_time = 0.0f;
#endif
        if (A->type != CAROM_BODY_DYNAMIC || B->type != CAROM_BODY_DYNAMIC)
            continue;
        cr_union(parent, c->a, c->b);
    }
    /* bodies whose boxes meet (a candidate pair) sleep together too, as
     * the wake above wakes them together: two still islands whose boxes
     * met without touching woke each other in turn, each wake starting
     * the woken island's still time again, and never slept (the events
     * method's falling pile of 2000 bodies) */
    for (i = 0; i < w->pair_count; ++i) {
        const cr_pair *p = &w->pairs[i];
        const cr_body *A = &w->bodies[p->a], *B = &w->bodies[p->b];
        if (A->type == CAROM_BODY_DYNAMIC && B->type == CAROM_BODY_DYNAMIC &&
            !((A->flags | B->flags) & CR_BODY_SENSOR) && (A->flags & B->flags & CR_BODY_AWAKE))
            cr_union(parent, p->a, p->b);
    }
    /* still (and held) for sleep_time, and for at least this step
     * (sleep_time 0: an island sleeps after its first still step, never
     * while moving) */
    for (i = 0; i < w->awake_count; ++i)
        can_sleep[w->awake[i]] = 1;
    for (i = 0; i < w->awake_count; ++i) {
        int id = w->awake[i];
        const cr_body *b = &w->bodies[id];
        if (b->type != CAROM_BODY_DYNAMIC || cr_lt(b->still_time, w->def.sleep_time) ||
            !cr_gt(b->still_time, 0.0f))
            can_sleep[cr_find(parent, id)] = 0;
    }
    for (i = 0; i < w->awake_count; ++i) {
        int id = w->awake[i], root;
        cr_body *b = &w->bodies[id];
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        root = cr_find(parent, id);
        if (!can_sleep[root])
            continue;
        b->flags &= (unsigned short)~CR_BODY_AWAKE;
        b->v = cr_v(0.0f, 0.0f);
        b->w = 0.0f;
#if CAROM_ENABLE_COMPENSATED
        b->vc = cr_v(0.0f, 0.0f);
        b->wc = 0.0f;
#endif
        w->bodies[id].sleep_island = root;
    }
#else
    (void)w;
    (void)dt;
#endif
}
