/*
 * engine_carom.c -- carom as a benchmark engine (tools/bench/bench.h):
 * the scene through the public API only (include/carom.h), one engine per
 * method. Linked with build/libcarom.a for timing, or with the profiling
 * build (build/profile/libcarom.a) for operation counts.
 */
#include "bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "carom.h"

typedef struct carom_bench_world {
    carom_world *w;
    void *mem;
    size_t bytes;
    carom_status last;
    int cap_pairs, cap_contacts, cap_impacts, cap_events; /* resolved */
} carom_bench_world;

static carom_world_def world_def(const bench_scene *s, const bench_config *c, int method)
{
    carom_world_def d = carom_default_world_def();
    d.gravity.x = s->gx;
    d.gravity.y = s->gy;
    d.dt = s->dt;
    d.method = (carom_method)method;
    d.max_bodies = s->body_count;
    if (s->rest_speed >= 0.0f)
        d.rest_speed = s->rest_speed;
    if (c) {
        d.enable_sleep = c->sleep;
        d.max_pairs = c->max_pairs;
        d.max_contacts = c->max_contacts;
        d.max_impacts = c->max_impacts;
        d.max_events = c->max_events;
    }
    return d;
}

long bench_carom_buffer_size(const bench_scene *s, int max_pairs, int max_contacts,
                             int max_impacts, int max_events)
{
    bench_config c;
    carom_world_def d;
    memset(&c, 0, sizeof c);
    c.max_pairs = max_pairs;
    c.max_contacts = max_contacts;
    c.max_impacts = max_impacts;
    c.max_events = max_events;
    d = world_def(s, &c, CAROM_METHOD_EVENTS);
    return (long)carom_world_buffer_size(&d);
}

int bench_carom_is_capacity_error(int status)
{
    return status == CAROM_ERR_PAIR_CAPACITY || status == CAROM_ERR_CONTACT_CAPACITY;
}

static void *carom_make(const bench_scene *s, const bench_config *c, int method, char *err,
                        size_t errlen)
{
    carom_bench_world *cw = (carom_bench_world *)calloc(1, sizeof *cw);
    carom_world_def d = world_def(s, c, method);
    carom_status st;
    int i;
    if (!cw) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    cw->bytes = carom_world_buffer_size(&d);
    if (cw->bytes == 0) {
        snprintf(err, errlen, "carom_world_buffer_size: bad world definition (%s)",
                 carom_status_string(carom_world_def_validate(&d)));
        free(cw);
        return NULL;
    }
    cw->mem = malloc(cw->bytes);
    if (!cw->mem) {
        snprintf(err, errlen, "out of memory (%lu bytes)", (unsigned long)cw->bytes);
        free(cw);
        return NULL;
    }
    st = carom_world_init(&cw->w, &d, cw->mem, cw->bytes);
    for (i = 0; st == CAROM_OK && i < s->body_count; ++i) {
        const bench_body *b = &s->bodies[i];
        carom_body_def bd = carom_default_body_def();
        bd.type = b->is_static ? CAROM_BODY_STATIC : CAROM_BODY_DYNAMIC;
        if (b->is_box)
            st = carom_body_def_set_box(&bd, b->hx, b->hy);
        else
            bd.radius = b->radius;
        bd.position.x = b->x;
        bd.position.y = b->y;
        bd.velocity.x = b->vx;
        bd.velocity.y = b->vy;
        bd.density = b->density;
        bd.restitution = b->restitution;
        bd.friction = b->friction;
        if (st == CAROM_OK)
            st = carom_world_add_body(cw->w, &bd, NULL);
    }
    if (st != CAROM_OK) {
        snprintf(err, errlen, "building the world: %s", carom_status_string(st));
        free(cw->mem);
        free(cw);
        return NULL;
    }
    cw->last = CAROM_OK;
    /* the capacities as carom resolves 0 (carom_config.h) */
    cw->cap_pairs = d.max_pairs > 0 ? d.max_pairs : CAROM_DEFAULT_PAIRS_PER_BODY * d.max_bodies;
    cw->cap_contacts = d.max_contacts > 0 ? d.max_contacts
                                          : CAROM_DEFAULT_CONTACTS_PER_BODY * d.max_bodies;
    cw->cap_impacts = d.max_impacts > 0 ? d.max_impacts
                                        : CAROM_DEFAULT_IMPACTS_PER_BODY * d.max_bodies;
    if (cw->cap_impacts < CAROM_MIN_IMPACTS && d.max_impacts <= 0)
        cw->cap_impacts = CAROM_MIN_IMPACTS;
    cw->cap_events = d.max_events > 0 ? d.max_events
                                      : CAROM_DEFAULT_EVENTS_PER_BODY * d.max_bodies;
    if (cw->cap_events < CAROM_MIN_EVENTS && d.max_events <= 0)
        cw->cap_events = CAROM_MIN_EVENTS;
    return cw;
}

static int carom_step(void *world, char *err, size_t errlen)
{
    carom_bench_world *cw = (carom_bench_world *)world;
    carom_status st = carom_world_step(cw->w);
    cw->last = st;
    if (st != CAROM_OK) {
        carom_stats stats;
        carom_world_get_stats(cw->w, &stats);
        snprintf(err, errlen, "carom_world_step: %s (status %d) at step %ld; capacities "
                 "max_pairs %d, max_contacts %d; most used so far: pairs %d, contacts %d",
                 carom_status_string(st), (int)st, stats.steps + 1, cw->cap_pairs,
                 cw->cap_contacts,
                 stats.max_pairs_used, stats.max_contacts_used);
        return -1;
    }
    return 0;
}

int bench_carom_last_status(void *world)
{
    return (int)((carom_bench_world *)world)->last;
}

int bench_carom_attach_profile(void *world, void *profile)
{
    carom_bench_world *cw = (carom_bench_world *)world;
    return carom_world_set_profile(cw->w, (carom_profile *)profile) == CAROM_OK ? 0 : -1;
}

static void carom_info(void *world, bench_info *out)
{
    carom_bench_world *cw = (carom_bench_world *)world;
    carom_stats st;
    memset(out, 0, sizeof *out);
    out->heap_bytes = -1;
    carom_world_get_stats(cw->w, &st);
    out->impacts = st.impacts;
    out->awake = st.awake_bodies;
    out->contacts = st.contacts;
    out->buffer_bytes = (long)cw->bytes;
    out->max_pairs_used = st.max_pairs_used;
    out->max_contacts_used = st.max_contacts_used;
    out->max_impacts_used = st.max_impacts_used;
    out->budget_steps = st.budget_steps;
    out->cap_pairs = cw->cap_pairs;
    out->cap_contacts = cw->cap_contacts;
    out->cap_impacts = cw->cap_impacts;
    out->cap_events = cw->cap_events;
}

static void carom_destroy(void *world)
{
    carom_bench_world *cw = (carom_bench_world *)world;
    if (!cw)
        return;
    free(cw->mem);
    free(cw);
}

const bench_engine bench_carom_events = {
    "events", CAROM_METHOD_EVENTS, carom_make, carom_step, carom_info, carom_destroy
};
const bench_engine bench_carom_discrete = {
    "discrete", CAROM_METHOD_DISCRETE, carom_make, carom_step, carom_info, carom_destroy
};
const bench_engine bench_carom_first_impact = {
    "first-impact", CAROM_METHOD_FIRST_IMPACT, carom_make, carom_step, carom_info,
    carom_destroy
};
