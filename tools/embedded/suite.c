/*
 * suite.c -- run the embedded scene suite and print one line per run.
 *
 * Freestanding on purpose: no stdio, no printf (the firmware has neither
 * console nor room for them); numbers are formatted here.
 */
#include <string.h>

#include "suite.h"

#if defined(__arm__)
#define SUITE_READ_SP(sp) __asm__ volatile("mov %0, sp" : "=r"(sp))
#else
#define SUITE_READ_SP(sp) ((sp) = 0)
#endif

/* ---- definitions ---------------------------------------------------------- */

void suite_body_def(const suite_body *b, carom_body_def *d)
{
    int i;
    *d = carom_default_body_def();
    d->type = (carom_body_type)b->type;
    d->shape = (carom_shape_type)b->shape;
    d->radius = b->radius;
    d->vertex_count = b->vertex_count;
    for (i = 0; b->vertices && i < b->vertex_count &&
                i < CAROM_MAX_POLYGON_VERTICES; ++i) {
        d->vertices[i].x = b->vertices[2 * i];
        d->vertices[i].y = b->vertices[2 * i + 1];
    }
    d->position.x = b->px;
    d->position.y = b->py;
#if CAROM_ENABLE_ANGLES
    d->rotation = carom_rot_from_angle(b->angle);
#else
    if (b->angle != 0.0f) { /* refused: carom_body_def_validate says why */
        d->rotation.c = 0.0f;
        d->rotation.s = 0.0f;
    }
#endif
    d->velocity.x = b->vx;
    d->velocity.y = b->vy;
    d->angular_velocity = b->w;
    d->density = b->density;
    d->mass = b->mass;
    d->restitution = b->restitution;
    d->friction = b->friction;
    d->force.x = b->fx;
    d->force.y = b->fy;
    d->torque = b->torque;
}

void suite_world_def(const suite_scene *s, carom_method method,
                     carom_world_def *d)
{
    *d = carom_default_world_def();
    d->gravity.x = s->gx;
    d->gravity.y = s->gy;
    d->dt = s->dt;
    d->method = method;
    d->max_bodies = s->body_count > 0 ? s->body_count : 1;
    d->max_pairs = s->max_pairs;
    d->max_contacts = s->max_contacts;
    d->max_events = s->max_events;
    d->max_impacts = s->max_impacts;
    d->length_unit = s->length_unit;
    d->rest_speed = s->rest_speed;
    d->linear_slop = s->linear_slop;
    d->substeps = s->substeps;
    d->iterations = s->iterations;
    d->relax_iterations = s->relax_iterations;
    d->enable_sleep = s->enable_sleep;
    d->sleep_time = s->sleep_time;
#ifdef CAROM_LEAN_SET_CAPACITIES
    /* a lean firmware (embedded-lean8k): the capacities `carom lean` gave */
    CAROM_LEAN_SET_CAPACITIES(d);
#endif
}

/* ---- output ----------------------------------------------------------------- */

typedef struct line {
    char buf[160];
    size_t n;
} line;

static void put(line *l, const char *s)
{
    while (*s && l->n + 1 < sizeof l->buf)
        l->buf[l->n++] = *s++;
    l->buf[l->n] = '\0';
}

static void put_long(line *l, long v)
{
    char tmp[24];
    int i = 0;
    unsigned long u = v < 0 ? 0ul - (unsigned long)v : (unsigned long)v;
    if (v < 0)
        put(l, "-");
    do {
        tmp[i++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u);
    while (i > 0) {
        char c[2];
        c[0] = tmp[--i];
        c[1] = '\0';
        put(l, c);
    }
}

#if CAROM_ENABLE_PROFILE
static void put_u64(line *l, uint64_t v)
{
    char tmp[24];
    int i = 0;
    do {
        tmp[i++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    while (i > 0) {
        char c[2];
        c[0] = tmp[--i];
        c[1] = '\0';
        put(l, c);
    }
}
#endif

static void put_hex64(line *l, uint64_t v)
{
    static const char digits[] = "0123456789abcdef";
    char tmp[17];
    int i;
    for (i = 15; i >= 0; --i) {
        tmp[i] = digits[(unsigned)(v & 15u)];
        v >>= 4;
    }
    tmp[16] = '\0';
    put(l, tmp);
}

static void emit(line *l)
{
    put(l, "\n");
    platform_out(l->buf);
    l->n = 0;
    l->buf[0] = '\0';
}

/* ---- hashing ----------------------------------------------------------------- */

#define FNV_OFFSET 0xcbf29ce484222325ull
#define FNV_PRIME 0x100000001b3ull

/* FNV-1a 64 over the float's bits, least significant byte first (the
 * same bytes on any host, whatever its byte order). */
static uint64_t fnv_float(uint64_t h, float f)
{
    uint32_t bits;
    int i;
    memcpy(&bits, &f, sizeof bits);
    for (i = 0; i < 4; ++i) {
        h ^= (uint64_t)(bits & 0xffu);
        h *= FNV_PRIME;
        bits >>= 8;
    }
    return h;
}

/* ---- running ------------------------------------------------------------------- */

static int fail(const suite_scene *s, const char *method, const char *what,
                carom_status st)
{
    line l;
    l.n = 0;
    put(&l, "error ");
    put(&l, s->name);
    put(&l, " ");
    put(&l, method);
    put(&l, " ");
    put(&l, what);
    put(&l, ": ");
    put(&l, carom_status_string(st));
    emit(&l);
    return 1;
}

static int run_one(const suite_scene *s, carom_method method, void *mem,
                   size_t bytes)
{
    static int ids[SUITE_MAX_BODIES];
    const char *mname = carom_method_name(method);
    carom_world_def wd;
    carom_world *w;
    carom_body_def bd;
    carom_body_state st;
    carom_stats stats;
    carom_status status;
    size_t need;
    uint64_t h = FNV_OFFSET;
#if CAROM_ENABLE_PROFILE
    static carom_profile prof;
#endif
    uintptr_t sp;
    long i, peak;
    int b;
    line l;

    l.n = 0;
    if (s->body_count > SUITE_MAX_BODIES)
        return fail(s, mname, "too many bodies", CAROM_ERR_BAD_CAPACITY);
    suite_world_def(s, method, &wd);
    need = carom_world_buffer_size(&wd);
    if (method == CAROM_METHOD_EVENTS) {
        put(&l, "world ");
        put(&l, s->name);
        put(&l, " bytes=");
        put_long(&l, (long)need);
        put(&l, " bodies=");
        put_long(&l, s->body_count);
        put(&l, " pairs=");
        put_long(&l, wd.max_pairs);
        put(&l, " contacts=");
        put_long(&l, wd.max_contacts);
        put(&l, " events=");
        put_long(&l, wd.max_events);
        put(&l, " impacts=");
        put_long(&l, wd.max_impacts);
        put(&l, " buffer=");
        put_long(&l, (long)bytes);
        emit(&l);
    }
    if (need == 0)
        return fail(s, mname, "world definition", carom_world_def_validate(&wd));
    if (need > bytes)
        return fail(s, mname, "world buffer", CAROM_ERR_BUFFER_TOO_SMALL);
    status = carom_world_init(&w, &wd, mem, bytes);
    if (status != CAROM_OK)
        return fail(s, mname, "world init", status);
    for (b = 0; b < s->body_count; ++b) {
        suite_body_def(&s->bodies[b], &bd);
        status = carom_world_add_body(w, &bd, &ids[b]);
        if (status != CAROM_OK)
            return fail(s, mname, "add body", status);
    }

#if CAROM_ENABLE_PROFILE
    /* a profiling build (the phase firmware): count this run's operations */
    carom_profile_reset(&prof);
    carom_world_set_profile(w, &prof);
#endif
    platform_stack_paint();
    SUITE_READ_SP(sp);
    platform_mark(0);
    for (i = 0; i < s->steps; ++i) {
        status = carom_world_step(w);
        if (status != CAROM_OK)
            break;
    }
    platform_mark(1);
    peak = platform_stack_peak(sp);
    if (status != CAROM_OK)
        return fail(s, mname, "step", status);

    for (b = 0; b < s->body_count; ++b) {
        status = carom_body_get_state(w, ids[b], &st);
        if (status != CAROM_OK)
            return fail(s, mname, "body state", status);
        h = fnv_float(h, st.position.x);
        h = fnv_float(h, st.position.y);
        h = fnv_float(h, st.rotation.c);
        h = fnv_float(h, st.rotation.s);
        h = fnv_float(h, st.velocity.x);
        h = fnv_float(h, st.velocity.y);
        h = fnv_float(h, st.angular_velocity);
        h = fnv_float(h, st.center.x);
        h = fnv_float(h, st.center.y);
    }
    status = carom_world_get_stats(w, &stats);
    if (status != CAROM_OK)
        return fail(s, mname, "stats", status);
#if CAROM_ENABLE_PROFILE
    carom_world_set_profile(w, NULL);
    {
        int ph, k;
        for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph) {
            put(&l, "ops ");
            put(&l, s->name);
            put(&l, " ");
            put(&l, mname);
            put(&l, " ");
            put(&l, carom_phase_name((carom_phase)ph));
            for (k = 0; k < CAROM_OP_COUNT; ++k) {
                put(&l, " ");
                put_u64(&l, prof.ops[ph][k]);
            }
            emit(&l);
        }
        put(&l, "ops ");
        put(&l, s->name);
        put(&l, " ");
        put(&l, mname);
        put(&l, " body_steps ");
        put_u64(&l, prof.body_steps);
        put(&l, " impacts ");
        put_u64(&l, prof.impacts);
        emit(&l);
    }
#endif

    put(&l, "result ");
    put(&l, s->name);
    put(&l, " ");
    put(&l, mname);
    put(&l, " steps=");
    put_long(&l, s->steps);
    put(&l, " bodies=");
    put_long(&l, s->body_count);
    put(&l, " hash=");
    put_hex64(&l, h);
    put(&l, " impacts=");
    put_long(&l, stats.impacts);
    emit(&l);
    if (peak != -1) {
        put(&l, "stack ");
        put(&l, s->name);
        put(&l, " ");
        put(&l, mname);
        if (peak < 0) {
            put(&l, " overflow (the painted region was used up)");
            emit(&l);
            return 1;
        }
        put(&l, " step_peak=");
        put_long(&l, peak);
        emit(&l);
    }
    return 0;
}

int suite_run(void *world_mem, size_t world_bytes, int small_only)
{
    int i, failures = 0, runs = 0;
    line l;
    for (i = 0; i < suite_scene_count; ++i) {
        const suite_scene *s = &suite_scenes[i];
        if (small_only && !(s->flags & SUITE_SMALL))
            continue;
        failures += run_one(s, CAROM_METHOD_EVENTS, world_mem, world_bytes);
        runs += 1;
#ifndef SUITE_EVENTS_ONLY
        failures += run_one(s, CAROM_METHOD_DISCRETE, world_mem, world_bytes);
        runs += 1;
#endif
    }
    l.n = 0;
    put(&l, "done runs=");
    put_long(&l, runs);
    put(&l, " failures=");
    put_long(&l, failures);
    emit(&l);
    return failures;
}
