/*
 * bodies.c -- the body calls of the public API: adding and removing bodies
 * (slots reused, ids with generations), reading their state, and the
 * program's controls between steps (velocities, teleport, impulses,
 * one-step forces, material, filter, user data). Every call validates its
 * arguments first and changes nothing on failure; calls that move a body
 * wake it, and what may rest on it.
 */
#include "world.h"

#include "island.h"
#include "touch.h"

static void cr_wake_neighbours(carom_world *w, int s);

carom_status carom_world_add_body(carom_world *w, const carom_body_def *def,
                                  int *id)
{
    cr_body b;
    cr_body_info info;
    carom_status st;
    int slot;
    if (!w || !def)
        return CAROM_ERR_NULL;
    st = cr_body_build(def, &b, &info);
    if (st != CAROM_OK)
        return st;
    /* the lowest free slot: a removed body's, else a new one */
    slot = w->slot_count;
    if (w->body_count < w->slot_count)
        for (slot = 0; slot < w->slot_count; ++slot)
            if (!(w->bodies[slot].flags & CR_BODY_ALIVE))
                break;
    if (slot >= w->def.max_bodies)
        return CAROM_ERR_WORLD_FULL;
    /* a reused slot keeps counting its generation */
    info.generation = w->info[slot].generation;
    {
        /* the force callback sees the id the body will have */
        unsigned saved = w->info[slot].generation;
        cr_body_info keep;
        int grow = slot == w->slot_count;
        if (!grow)
            keep = w->info[slot];
        w->info[slot].generation = info.generation;
        st = cr_body_accel(&w->def, cr_body_id(w, slot), &b, &info, &b.a, &b.alpha);
        if (!grow)
            w->info[slot] = keep;
        else
            w->info[slot].generation = saved;
        if (st != CAROM_OK)
            return st;
    }
    b.flags = (unsigned short)(b.flags | CR_BODY_NEW);
    w->bodies[slot] = b;
    w->info[slot] = info;
    w->drift[slot].version = 0;
    if (slot == w->slot_count)
        ++w->slot_count;
    ++w->body_count;
    if (b.flags & CR_BODY_SENSOR)
        ++w->sensor_count;
    w->prime = 1;
    w->grid_valid = 0;
    w->scale_valid = 0;
    /* a static or kinematic body, or a sensor, added over sleeping bodies
     * wakes them: nothing else would (a dynamic body wakes what it
     * touches through its pairs; before the first step nothing sleeps) */
    if (w->steps > 0 && (b.type != CAROM_BODY_DYNAMIC || (b.flags & CR_BODY_SENSOR)))
        cr_wake_neighbours(w, slot);
    if (id)
        *id = cr_body_id(w, slot);
    return CAROM_OK;
}

/* Wake every sleeping body whose shape comes within the speculative
 * distance of body slot s's (it may rest on s, which is about to go or
 * move). */
static void cr_wake_neighbours(carom_world *w, int s)
{
    cr_box me, other;
    cr_scale sc;
    float m;
    int i;
    cr_scale_compute(w, &sc);
    m = sc.spec;
    cr_shape_box(&w->info[s].shape, w->bodies[s].x, w->bodies[s].q, &me);
    me.lo_x = cr_sub(me.lo_x, m);
    me.lo_y = cr_sub(me.lo_y, m);
    me.hi_x = cr_add(me.hi_x, m);
    me.hi_y = cr_add(me.hi_y, m);
    for (i = 0; i < w->slot_count; ++i) {
        const cr_body *b = &w->bodies[i];
        if (i == s || !(b->flags & CR_BODY_ALIVE) || (b->flags & CR_BODY_AWAKE))
            continue;
        cr_shape_box(&w->info[i].shape, b->x, b->q, &other);
        if (cr_boxes_overlap(&me, &other))
            cr_island_wake(w, i);
    }
}

/* Forget the warm starts of body slot s: its contacts are found anew.
 * Its touches stay: the next step's merge ends those that no longer hold
 * (only a removal drops them silently), so a touch never begins twice. */
static void cr_forget_body(carom_world *w, int s)
{
    int i, n = 0;
    for (i = 0; i < w->warm_count; ++i)
        if (w->warm[i].a != s && w->warm[i].b != s)
            w->warm[n++] = w->warm[i];
    w->warm_count = n;
    w->grid_valid = 0;
}

carom_status carom_world_remove_body(carom_world *w, int id)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    /* what slept on it, or with it, falls */
    if (!(w->bodies[s].flags & CR_BODY_AWAKE))
        cr_island_wake(w, s);
    cr_wake_neighbours(w, s);
    cr_forget_body(w, s);
    cr_touch_forget(w, s);
    if (w->bodies[s].flags & CR_BODY_SENSOR)
        --w->sensor_count;
    w->bodies[s].flags = 0u;
    /* the next generation, and a mark above the id's bits that the slot
     * held a body: an id of it is stale, not unknown, even after the
     * generation wraps to 0 */
    w->info[s].generation = ((w->info[s].generation + 1u) &
                             ((1u << (31 - CAROM_ID_INDEX_BITS)) - 1u)) |
                            0x80000000u;
    w->bodies[s].sleep_island = -1;
    --w->body_count;
    w->scale_valid = 0;
    /* trailing free slots are no longer in use */
    while (w->slot_count > 0 && !(w->bodies[w->slot_count - 1].flags & CR_BODY_ALIVE))
        --w->slot_count;
    return CAROM_OK;
}

int carom_body_is_valid(const carom_world *w, int id)
{
    int s;
    return w && cr_slot_of(w, id, &s) == CAROM_OK;
}

carom_status carom_body_get_type(const carom_world *w, int id, carom_body_type *out)
{
    carom_status st;
    int s;
    if (!w || !out)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st == CAROM_OK)
        *out = (carom_body_type)w->bodies[s].type;
    return st;
}

carom_status carom_body_get_velocity(const carom_world *w, int id, carom_vec2 *velocity,
                                     float *angular)
{
    carom_status st;
    int s;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (velocity)
        *velocity = w->bodies[s].v;
    if (angular)
        *angular = w->bodies[s].w;
    return CAROM_OK;
}

/* The slot of a body the program may move (dynamic or kinematic). */
static carom_status cr_movable_slot(carom_world *w, int id, int *s)
{
    carom_status st;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, s);
    if (st != CAROM_OK)
        return st;
    return w->bodies[*s].type == CAROM_BODY_STATIC ? CAROM_ERR_BAD_BODY_TYPE : CAROM_OK;
}

carom_status carom_body_set_velocity(carom_world *w, int id, carom_vec2 velocity)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    st = cr_movable_slot(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (!cr_finite(velocity.x) || !cr_finite(velocity.y))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_v2_within(velocity, CAROM_LIMIT_MAX_SPEED))
        return CAROM_ERR_OUT_OF_RANGE;
    w->bodies[s].v = velocity;
#if CAROM_ENABLE_COMPENSATED
    w->bodies[s].vc = cr_v(0.0f, 0.0f);
#endif
    cr_island_wake(w, s);
    return CAROM_OK;
}

carom_status carom_body_set_angular_velocity(carom_world *w, int id, float angular)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    st = cr_movable_slot(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (!cr_finite(angular))
        return CAROM_ERR_NOT_FINITE;
#if !CAROM_ENABLE_ROTATION
    if (!cr_eq(angular, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
    if (cr_gt(cr_mul(cr_abs(angular), w->info[s].shape.extent), CAROM_LIMIT_MAX_SPEED))
        return CAROM_ERR_OUT_OF_RANGE;
    w->bodies[s].w = angular;
#if CAROM_ENABLE_COMPENSATED
    w->bodies[s].wc = 0.0f;
#endif
    cr_island_wake(w, s);
    return CAROM_OK;
}

carom_status carom_body_set_transform(carom_world *w, int id, carom_vec2 position,
                                      carom_rot rotation)
{
    carom_status st;
    cr_body *b;
    cr_rot q;
    cr_v2 x;
    float len;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (!cr_finite(position.x) || !cr_finite(position.y) || !cr_finite(rotation.c) ||
        !cr_finite(rotation.s))
        return CAROM_ERR_NOT_FINITE;
    len = cr_add(cr_mul(rotation.c, rotation.c), cr_mul(rotation.s, rotation.s));
    if (cr_lt(len, CR_ROT_MIN_LEN2) || !cr_finite(len))
        return CAROM_ERR_BAD_ROTATION;
    q = cr_rot_normalize(rotation);
#if !CAROM_ENABLE_ROTATION
    if (!cr_eq(q.s, w->bodies[s].q.s) || !cr_eq(q.c, w->bodies[s].q.c))
        return CAROM_ERR_DISABLED;
#endif
    x = cr_vadd(position, cr_rotate(q, w->info[s].shape.local_center));
    if (!cr_v2_within(position, CAROM_LIMIT_MAX_LENGTH) ||
        !cr_v2_within(x, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
    b = &w->bodies[s];
    {
        /* the force callback may read the position: a0 at the new pose
         * (first: a refused pose leaves the world as it was, asleep or
         * not) */
        cr_body moved = *b;
        cr_v2 a;
        float alpha;
        moved.x = x;
        moved.q = q;
        st = cr_body_accel(&w->def, id, &moved, &w->info[s], &a, &alpha);
        if (st != CAROM_OK)
            return st;
        moved.a = a;
        moved.alpha = alpha;
#if CAROM_ENABLE_COMPENSATED
        moved.xc = cr_v(0.0f, 0.0f);
#endif
        cr_wake_neighbours(w, s); /* what rested on it where it was */
        moved.flags = (unsigned short)(moved.flags | CR_BODY_TELEPORTED);
        w->teleported = 1;
        *b = moved;
    }
    cr_island_wake(w, s);
    cr_wake_neighbours(w, s); /* and what it now touches */
    cr_forget_body(w, s);
    return CAROM_OK;
}

carom_status carom_body_apply_impulse(carom_world *w, int id, carom_vec2 impulse,
                                      carom_vec2 point)
{
    carom_status st;
    cr_body *b;
    cr_v2 v;
    float om;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (!cr_finite(impulse.x) || !cr_finite(impulse.y) || !cr_finite(point.x) ||
        !cr_finite(point.y))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_v2_within(point, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
    b = &w->bodies[s];
    v = cr_vmadd(b->v, b->inv_m, impulse);
    om = b->w;
#if CAROM_ENABLE_ROTATION
    om = cr_add(om, cr_mul(b->inv_I, cr_vcross(cr_vsub(point, b->x), impulse)));
#endif
    if (!cr_finite(v.x) || !cr_finite(v.y) || !cr_finite(om))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_v2_within(v, CAROM_LIMIT_MAX_SPEED) ||
        cr_gt(cr_mul(cr_abs(om), w->info[s].shape.extent), CAROM_LIMIT_MAX_SPEED))
        return CAROM_ERR_OUT_OF_RANGE;
    b->v = v;
    b->w = om;
    cr_island_wake(w, s);
    return CAROM_OK;
}

carom_status carom_body_apply_angular_impulse(carom_world *w, int id, float impulse)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (!cr_finite(impulse))
        return CAROM_ERR_NOT_FINITE;
#if !CAROM_ENABLE_ROTATION
    return cr_eq(impulse, 0.0f) ? CAROM_OK : CAROM_ERR_DISABLED;
#else
    cr_body *b = &w->bodies[s];
    float om = cr_add(b->w, cr_mul(b->inv_I, impulse));
    if (!cr_finite(om))
        return CAROM_ERR_NOT_FINITE;
    if (cr_gt(cr_mul(cr_abs(om), w->info[s].shape.extent), CAROM_LIMIT_MAX_SPEED))
        return CAROM_ERR_OUT_OF_RANGE;
    b->w = om;
    cr_island_wake(w, s);
    return CAROM_OK;
#endif
}

/* Add a one-step force and torque to body slot s (dynamic). */
static carom_status cr_add_once(carom_world *w, int id, int s, cr_v2 f, float tq)
{
#if CAROM_ENABLE_FORCES
    cr_body *b = &w->bodies[s];
    cr_body_info *in = &w->info[s];
    cr_body moved = *b;
    cr_v2 fo = (b->flags & CR_BODY_ONCE) ? cr_vadd(in->force_once, f) : f;
    float to = (b->flags & CR_BODY_ONCE) ? cr_add(in->torque_once, tq) : tq;
    cr_v2 keep_f = in->force_once, a;
    float keep_t = in->torque_once, alpha;
    carom_status st;
    if (!cr_finite(fo.x) || !cr_finite(fo.y) || !cr_finite(to))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_accel_in_range(in, fo, to))
        return CAROM_ERR_OUT_OF_RANGE;
    in->force_once = fo;
    in->torque_once = to;
    moved.flags |= CR_BODY_ONCE;
    st = cr_body_accel(&w->def, id, &moved, in, &a, &alpha);
    if (st != CAROM_OK) {
        in->force_once = keep_f;
        in->torque_once = keep_t;
        return st;
    }
    moved.a = a;
    moved.alpha = alpha;
    *b = moved;
    cr_island_wake(w, s);
    return CAROM_OK;
#else
    (void)w;
    (void)id;
    (void)s;
    (void)f;
    (void)tq;
    return CAROM_ERR_DISABLED;
#endif
}

carom_status carom_body_apply_force(carom_world *w, int id, carom_vec2 force,
                                    carom_vec2 point)
{
    carom_status st;
    float tq = 0.0f;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (!cr_finite(force.x) || !cr_finite(force.y) || !cr_finite(point.x) ||
        !cr_finite(point.y))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_v2_within(point, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE; /* a point beyond the world */
#if CAROM_ENABLE_ROTATION
    tq = cr_vcross(cr_vsub(point, w->bodies[s].x), force);
#endif
    return cr_add_once(w, id, s, force, tq);
}

carom_status carom_body_apply_torque(carom_world *w, int id, float torque)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (!cr_finite(torque))
        return CAROM_ERR_NOT_FINITE;
#if !CAROM_ENABLE_ROTATION
    if (!cr_eq(torque, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
    return cr_add_once(w, id, s, cr_v(0.0f, 0.0f), torque);
}

carom_status carom_body_set_restitution(carom_world *w, int id, float e)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (!cr_finite(e))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_le(0.0f, e) || !cr_le(e, 1.0f))
        return CAROM_ERR_BAD_RESTITUTION;
    w->info[s].restitution = e;
    return CAROM_OK;
}

carom_status carom_body_set_friction(carom_world *w, int id, float mu)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (!cr_finite(mu))
        return CAROM_ERR_NOT_FINITE;
    if (cr_lt(mu, 0.0f) || cr_gt(mu, CAROM_LIMIT_MAX_FRICTION))
        return CAROM_ERR_BAD_FRICTION;
#if !CAROM_ENABLE_FRICTION
    if (cr_gt(mu, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
    w->info[s].friction = mu;
    cr_island_wake(w, s);
    /* a static or kinematic body has no island: what sleeps on it wakes
     * (a floor made slippery under a box asleep on a slope) */
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        cr_wake_neighbours(w, s);
    return CAROM_OK;
}

carom_status carom_body_set_user_data(carom_world *w, int id, void *data)
{
    carom_status st;
    int s;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st == CAROM_OK)
        w->info[s].user_data = data;
    return st;
}

void *carom_body_get_user_data(const carom_world *w, int id)
{
    int s;
    if (!w || cr_slot_of(w, id, &s) != CAROM_OK)
        return 0;
    return w->info[s].user_data;
}

carom_status carom_body_set_filter(carom_world *w, int id, uint32_t category, uint32_t mask,
                                   int group)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
#if !CAROM_ENABLE_FILTERING
    (void)category;
    (void)mask;
    (void)group;
    return CAROM_ERR_DISABLED;
#else
    w->info[s].category = category;
    w->info[s].mask = mask;
    w->info[s].group = group;
    if (category != 1u || mask != 0xffffffffu || group != 0)
        w->bodies[s].flags |= CR_BODY_FILTERED;
    else
        w->bodies[s].flags &= (unsigned short)~CR_BODY_FILTERED;
    cr_island_wake(w, s);
    cr_wake_neighbours(w, s); /* a pair it may no longer collide with */
    cr_forget_body(w, s);
    return CAROM_OK;
#endif
}

int carom_world_body_count(const carom_world *w)
{
    return w ? w->body_count : 0;
}

carom_status carom_body_get_state(const carom_world *w, int id,
                                  carom_body_state *out)
{
    const cr_body *b;
    carom_status st;
    int s;
    if (!w || !out)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    b = &w->bodies[s];
    out->center = b->x;
    out->position = cr_body_origin(b, &w->info[s]);
    out->rotation = b->q;
    out->velocity = b->v;
    out->angular_velocity = b->w;
    return CAROM_OK;
}

carom_status carom_body_get_mass(const carom_world *w, int id, float *mass,
                                 float *inertia)
{
    carom_status st;
    int s;
    if (!w)
        return CAROM_ERR_NULL;
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    if (mass)
        *mass = w->info[s].m;
    if (inertia)
        *inertia = w->info[s].I;
    return CAROM_OK;
}

carom_status carom_body_set_force(carom_world *w, int id, carom_vec2 force,
                                  float torque)
{
    carom_status st;
    int s;
    if (!CAROM_ENABLE_BODY_EDITS) /* compiled out: the rest is dead code */
        return w ? CAROM_ERR_DISABLED : CAROM_ERR_NULL;
    if (!w)
        return CAROM_ERR_NULL;
#if CAROM_ENABLE_FORCES
    st = cr_slot_of(w, id, &s);
    if (st != CAROM_OK)
        return st;
    /* forces move dynamic bodies only (as carom_body_apply_force; a review
     * found any force, 1e30 N included, accepted on a static body) */
    if (w->bodies[s].type != CAROM_BODY_DYNAMIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (!cr_finite(force.x) || !cr_finite(force.y) || !cr_finite(torque))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_accel_in_range(&w->info[s], force, torque))
        return CAROM_ERR_OUT_OF_RANGE;
    {
        cr_body_info saved = w->info[s];
        cr_body *b = &w->bodies[s];
        cr_v2 a;
        float alpha;
        w->info[s].force = force;
        w->info[s].torque = torque;
        /* a0 of the next step is the acceleration at the current state */
        st = cr_body_accel(&w->def, id, b, &w->info[s], &a, &alpha);
        if (st != CAROM_OK) {
            w->info[s] = saved;
            return st;
        }
        b->a = a;
        b->alpha = alpha;
        cr_island_wake(w, s);
    }
    return CAROM_OK;
#else
    (void)id;
    (void)force;
    (void)torque;
    (void)st;
    (void)s;
    return CAROM_ERR_DISABLED;
#endif
}

int carom_body_is_awake(const carom_world *w, int id)
{
    int s;
    if (!w || cr_slot_of(w, id, &s) != CAROM_OK)
        return 0;
    return (w->bodies[s].flags & CR_BODY_AWAKE) ? 1 : 0;
}

