/*
 * fuzz_common.h -- invariants shared by the libFuzzer harnesses of carom
 * (tests/fuzz/fuzz_*.c). Header-only; every function is static.
 *
 * What is checked, and where the promise is written:
 *   - every call returns a named status (fz_check_status_named);
 *   - a call that returns an error leaves the world as it was: every
 *     body's state, awake flag, mass, validity, type, velocity and user
 *     data, the body count, time, step count, stats, method and
 *     tolerances, compared bit for bit (carom.h, "Status", and
 *     carom_world_step: only the event list may change); where a promise
 *     covers them, also the last step's error body, impact and touch
 *     events (fz_expect_same_results);
 *   - after a call that returns CAROM_OK every body state is finite, its
 *     centre and velocity are inside CAROM_LIMIT_MAX_LENGTH / _MAX_SPEED
 *     (the end-of-step check promises an error otherwise) and its rotation
 *     is a unit pair;
 *   - time is steps x dt (one float product) and stats.steps == steps;
 *   - events: at most max_events, ids of bodies, body_a < body_b in slot
 *     order, unit finite normal, impulse and approach speed >= 0, time
 *     inside the step;
 *   - across a step: static bodies never move, kinematic bodies keep
 *     their velocity and move by it, sleeping bodies stay put;
 *   - get_mass: 0 if not dynamic, else within the CAROM_LIMIT_*_MASS range;
 *   - two worlds built and driven the same way give the same bits.
 *
 * A violation prints "carom-fuzz: INVARIANT VIOLATED: <name>: <detail>"
 * with the operation being run (fz_where) and aborts, so libFuzzer saves
 * the input as a crash.
 */
#ifndef CAROM_FUZZ_COMMON_H
#define CAROM_FUZZ_COMMON_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "carom.h"

#define FZ_MAX_BODIES 64
/* The slot of an id (carom_config.h: the low CAROM_ID_INDEX_BITS bits). */
#define FZ_SLOT_MASK ((int)((1u << CAROM_ID_INDEX_BITS) - 1u))

/* What the harness is doing now: printed with every violation. */
static char fz_where[768];

/* CAROM_FUZZ_TRACE=1 in the environment prints every operation (to
 * diagnose a crasher: build/fuzz/fuzz_api FILE). */
static int fz_trace = -1;

static inline void fz_set_where(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(fz_where, sizeof fz_where, fmt, ap);
    va_end(ap);
    if (fz_trace < 0) {
        const char *e = getenv("CAROM_FUZZ_TRACE");
        fz_trace = e && *e && *e != '0';
    }
    if (fz_trace)
        fprintf(stderr, "carom-fuzz: %s\n", fz_where);
}

/* CAROM_FUZZ_IGNORE="name,name" (substrings of invariant names) lets a
 * fuzzing run go on past a known finding: the violation is not reported
 * and the harness carries on. Only for exploring; replays never set it. */
static inline int fz_ignored(const char *invariant)
{
    const char *e = getenv("CAROM_FUZZ_IGNORE"), *p;
    if (!e)
        return 0;
    for (p = e; *p;) {
        size_t n = strcspn(p, ",");
        if (n > 0) {
            const char *q;
            for (q = invariant; *q; ++q)
                if (strncmp(q, p, n) == 0)
                    return 1;
        }
        p += n;
        if (*p == ',')
            ++p;
    }
    return 0;
}

static inline void fz_fail(const char *invariant, const char *fmt, ...)
{
    va_list ap;
    if (fz_ignored(invariant))
        return;
    fprintf(stderr, "\ncarom-fuzz: INVARIANT VIOLATED: %s: ", invariant);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\ncarom-fuzz: while: %s\n", fz_where);
    fflush(stderr);
    abort();
}

static inline uint32_t fz_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static inline int fz_finite(float f)
{
    /* exponent not all ones; no libm, no reliance on -ffinite-math */
    return (fz_bits(f) & 0x7f800000u) != 0x7f800000u;
}

static inline float fz_abs(float f) { return f < 0.0f ? -f : f; }

/* ---- snapshots ------------------------------------------------------------ */

typedef struct fz_body_snap {
    int status;                /* of carom_body_get_state */
    carom_body_state st;
    int awake;
    int mass_status;
    float mass, inertia;
    int valid;                 /* carom_body_is_valid */
    int type_status, type;     /* carom_body_get_type */
    int vel_status;            /* carom_body_get_velocity */
    carom_vec2 vel;
    float angvel;
    uintptr_t user;            /* carom_body_get_user_data */
} fz_body_snap;

typedef struct fz_snap {
    int body_count;
    float time;
    long step_count;
    int stats_status;
    carom_stats stats;
    int method;
    int tol_status;
    carom_tolerances tol;
    int n;                     /* bodies snapshotted */
    fz_body_snap b[FZ_MAX_BODIES];
    /* the last step's results (compared only where a promise covers them:
     * fz_expect_same_results) */
    int error_body;
    int ev_count, ev_dropped, touch_count, touch_dropped;
    uint32_t ev_hash, touch_hash;
} fz_snap;

/* FNV-1a over bytes (the event lists are arrays of 4-byte fields). */
static inline uint32_t fz_hash(const void *p, size_t n)
{
    const unsigned char *c = (const unsigned char *)p;
    uint32_t h = 2166136261u;
    size_t i;
    for (i = 0; i < n; ++i)
        h = (h ^ c[i]) * 16777619u;
    return h;
}

static inline void fz_snap_take(const carom_world *w, const int *ids, int n,
                         fz_snap *s)
{
    int i;
    memset(s, 0, sizeof *s);
    s->body_count = carom_world_body_count(w);
    s->time = carom_world_time(w);
    s->step_count = carom_world_step_count(w);
    s->stats_status = (int)carom_world_get_stats(w, &s->stats);
    s->method = (int)carom_world_get_method(w);
    s->tol_status = (int)carom_world_get_tolerances(w, &s->tol);
    s->n = n > FZ_MAX_BODIES ? FZ_MAX_BODIES : n;
    for (i = 0; i < s->n; ++i) {
        fz_body_snap *b = &s->b[i];
        b->status = (int)carom_body_get_state(w, ids[i], &b->st);
        b->awake = carom_body_is_awake(w, ids[i]);
        b->mass_status = (int)carom_body_get_mass(w, ids[i], &b->mass,
                                                  &b->inertia);
        b->valid = carom_body_is_valid(w, ids[i]);
        {
            carom_body_type t = CAROM_BODY_DYNAMIC;
            b->type_status = (int)carom_body_get_type(w, ids[i], &t);
            b->type = (int)t;
        }
        b->vel_status = (int)carom_body_get_velocity(w, ids[i], &b->vel,
                                                     &b->angvel);
        b->user = (uintptr_t)carom_body_get_user_data(w, ids[i]);
    }
    s->error_body = carom_world_error_body(w);
    {
        const carom_event *ev = carom_world_events(w, &s->ev_count);
        const carom_touch_event *te = carom_world_touch_events(w,
                                                               &s->touch_count);
        s->ev_dropped = carom_world_events_dropped(w);
        s->touch_dropped = carom_world_touch_events_dropped(w);
        s->ev_hash = s->ev_count > 0 && ev
                         ? fz_hash(ev, (size_t)s->ev_count * sizeof *ev)
                         : 0u;
        s->touch_hash = s->touch_count > 0 && te
                            ? fz_hash(te, (size_t)s->touch_count * sizeof *te)
                            : 0u;
    }
}

/* Compare two snapshots field by field, bit for bit. Returns 0 when equal,
 * else writes the first difference into msg. */
#define FZ_CMP_INT(field, name)                                                \
    do {                                                                       \
        if ((long)(a->field) != (long)(b->field)) {                            \
            snprintf(msg, len, "%s: %ld vs %ld", name, (long)(a->field),       \
                     (long)(b->field));                                        \
            return 1;                                                          \
        }                                                                      \
    } while (0)
#define FZ_CMP_FLOAT(field, name)                                              \
    do {                                                                       \
        if (fz_bits(a->field) != fz_bits(b->field)) {                          \
            snprintf(msg, len, "%s: %.9g (0x%08lx) vs %.9g (0x%08lx)", name,   \
                     (double)(a->field), (unsigned long)fz_bits(a->field),     \
                     (double)(b->field), (unsigned long)fz_bits(b->field));    \
            return 1;                                                          \
        }                                                                      \
    } while (0)

static inline int fz_snap_diff_body(const fz_body_snap *a, const fz_body_snap *b,
                             int i, char *msg, size_t len)
{
    char name[96];
#define FZ_B_INT(f)                                                            \
    do {                                                                       \
        snprintf(name, sizeof name, "body #%d " #f, i);                       \
        FZ_CMP_INT(f, name);                                                   \
    } while (0)
#define FZ_B_FLOAT(f)                                                          \
    do {                                                                       \
        snprintf(name, sizeof name, "body #%d " #f, i);                       \
        FZ_CMP_FLOAT(f, name);                                                 \
    } while (0)
    FZ_B_INT(status);
    FZ_B_FLOAT(st.position.x);
    FZ_B_FLOAT(st.position.y);
    FZ_B_FLOAT(st.rotation.c);
    FZ_B_FLOAT(st.rotation.s);
    FZ_B_FLOAT(st.velocity.x);
    FZ_B_FLOAT(st.velocity.y);
    FZ_B_FLOAT(st.angular_velocity);
    FZ_B_FLOAT(st.center.x);
    FZ_B_FLOAT(st.center.y);
    FZ_B_INT(awake);
    FZ_B_INT(mass_status);
    FZ_B_FLOAT(mass);
    FZ_B_FLOAT(inertia);
    FZ_B_INT(valid);
    FZ_B_INT(type_status);
    FZ_B_INT(type);
    FZ_B_INT(vel_status);
    FZ_B_FLOAT(vel.x);
    FZ_B_FLOAT(vel.y);
    FZ_B_FLOAT(angvel);
    FZ_B_INT(user);
#undef FZ_B_INT
#undef FZ_B_FLOAT
    return 0;
}

static inline int fz_snap_diff(const fz_snap *a, const fz_snap *b, char *msg,
                        size_t len)
{
    int i;
    FZ_CMP_INT(body_count, "carom_world_body_count");
    FZ_CMP_FLOAT(time, "carom_world_time");
    FZ_CMP_INT(step_count, "carom_world_step_count");
    FZ_CMP_INT(stats_status, "carom_world_get_stats status");
    FZ_CMP_INT(stats.steps, "stats.steps");
    FZ_CMP_INT(stats.impacts, "stats.impacts");
    FZ_CMP_INT(stats.impact_solves, "stats.impact_solves");
    FZ_CMP_INT(stats.toi_queries, "stats.toi_queries");
    FZ_CMP_INT(stats.toi_early_outs, "stats.toi_early_outs");
    FZ_CMP_INT(stats.budget_steps, "stats.budget_steps");
    FZ_CMP_INT(stats.max_pairs_used, "stats.max_pairs_used");
    FZ_CMP_INT(stats.max_contacts_used, "stats.max_contacts_used");
    FZ_CMP_INT(stats.max_impacts_used, "stats.max_impacts_used");
    FZ_CMP_INT(stats.awake_bodies, "stats.awake_bodies");
    FZ_CMP_INT(stats.contacts, "stats.contacts");
    FZ_CMP_INT(method, "carom_world_get_method");
    FZ_CMP_INT(tol_status, "carom_world_get_tolerances status");
    FZ_CMP_FLOAT(tol.length_unit, "tolerances.length_unit");
    FZ_CMP_FLOAT(tol.linear_slop, "tolerances.linear_slop");
    FZ_CMP_FLOAT(tol.rest_speed, "tolerances.rest_speed");
    FZ_CMP_FLOAT(tol.sleep_speed, "tolerances.sleep_speed");
    FZ_CMP_INT(n, "bodies snapshotted");
    for (i = 0; i < a->n; ++i)
        if (fz_snap_diff_body(&a->b[i], &b->b[i], i, msg, len))
            return 1;
    return 0;
}

/* The last step's results: error body, impact and touch event lists. */
static inline int fz_snap_diff_results(const fz_snap *a, const fz_snap *b,
                                       char *msg, size_t len)
{
    FZ_CMP_INT(error_body, "carom_world_error_body");
    FZ_CMP_INT(ev_count, "impact event count");
    FZ_CMP_INT(ev_dropped, "carom_world_events_dropped");
    FZ_CMP_INT(ev_hash, "impact events (hash)");
    FZ_CMP_INT(touch_count, "touch event count");
    FZ_CMP_INT(touch_dropped, "carom_world_touch_events_dropped");
    FZ_CMP_INT(touch_hash, "touch events (hash)");
    return 0;
}

/* ---- checks after a call ------------------------------------------------- */

/* Every call returns a named status (carom.h, "Status"): one of the enum's
 * values, which carom_status_string names. */
static inline void fz_check_status_named(carom_status st, const char *what)
{
    const char *name;
    if ((unsigned)st >= (unsigned)CAROM_STATUS_COUNT)
        fz_fail("named status", "%s returned %d, not a carom_status", what,
                (int)st);
    name = carom_status_string(st);
    if (!name || !*name)
        fz_fail("named status", "%s returned %d, which carom_status_string "
                "does not name", what, (int)st);
}

/* Body i of two snapshots is the same but for its awake flag (a call that
 * wakes bodies changed nothing else of them). Returns 0 when equal. */
static inline int fz_snap_diff_body_but_awake(const fz_body_snap *a,
                                              const fz_body_snap *b, int i,
                                              char *msg, size_t len)
{
    fz_body_snap c = *b;
    c.awake = a->awake;
    return fz_snap_diff_body(a, &c, i, msg, len);
}

static inline void fz_check_body_state(const char *what, int i,
                                const carom_body_state *s)
{
    const float v[9] = {s->position.x, s->position.y, s->rotation.c,
                        s->rotation.s, s->velocity.x, s->velocity.y,
                        s->angular_velocity, s->center.x, s->center.y};
    static const char *const names[9] = {"position.x", "position.y",
                                         "rotation.c", "rotation.s",
                                         "velocity.x", "velocity.y",
                                         "angular_velocity", "center.x",
                                         "center.y"};
    float q;
    int k;
    for (k = 0; k < 9; ++k)
        if (!fz_finite(v[k]))
            fz_fail("finite state after CAROM_OK",
                    "%s returned CAROM_OK but body #%d has %s = %g "
                    "(pos %g %g, rot %g %g, vel %g %g, w %g, centre %g %g)",
                    what, i, names[k], (double)v[k], (double)v[0],
                    (double)v[1], (double)v[2], (double)v[3], (double)v[4],
                    (double)v[5], (double)v[6], (double)v[7], (double)v[8]);
    if (!(fz_abs(s->center.x) <= CAROM_LIMIT_MAX_LENGTH &&
          fz_abs(s->center.y) <= CAROM_LIMIT_MAX_LENGTH))
        fz_fail("state in documented range after CAROM_OK",
                "%s returned CAROM_OK but body #%d's centre (%g, %g) is "
                "beyond CAROM_LIMIT_MAX_LENGTH",
                what, i, (double)s->center.x, (double)s->center.y);
    if (!(fz_abs(s->velocity.x) <= CAROM_LIMIT_MAX_SPEED &&
          fz_abs(s->velocity.y) <= CAROM_LIMIT_MAX_SPEED))
        fz_fail("state in documented range after CAROM_OK",
                "%s returned CAROM_OK but body #%d's velocity (%g, %g) is "
                "beyond CAROM_LIMIT_MAX_SPEED",
                what, i, (double)s->velocity.x, (double)s->velocity.y);
    q = s->rotation.c * s->rotation.c + s->rotation.s * s->rotation.s;
    if (!(fz_abs(q - 1.0f) <= 1.0e-3f))
        fz_fail("unit rotation", "%s returned CAROM_OK but body #%d's "
                "rotation (%.9g, %.9g) has c^2 + s^2 = %.9g",
                what, i, (double)s->rotation.c, (double)s->rotation.s,
                (double)q);
}

/* After a call that returned CAROM_OK: every body readable and sane, the
 * counters consistent. `dt` is the world's dt. */
static inline void fz_check_world_ok(const carom_world *w, const int *ids, int n,
                              float dt, const char *what)
{
    carom_stats st;
    long steps = carom_world_step_count(w);
    float t = carom_world_time(w), want = (float)steps * dt;
    int i;
    if (carom_world_body_count(w) != n)
        fz_fail("body count", "%s: carom_world_body_count %d, bodies added %d",
                what, carom_world_body_count(w), n);
    for (i = 0; i < n && i < FZ_MAX_BODIES; ++i) {
        carom_body_state s;
        carom_status rc = carom_body_get_state(w, ids[i], &s);
        if (rc != CAROM_OK)
            fz_fail("body readable", "%s: carom_body_get_state(id %d) of an "
                    "added body returned %s", what, ids[i],
                    carom_status_string(rc));
        fz_check_body_state(what, i, &s);
    }
    if (fz_bits(t) != fz_bits(want))
        fz_fail("time is steps x dt", "%s: carom_world_time %.9g, steps %ld "
                "x dt %.9g = %.9g", what, (double)t, steps, (double)dt,
                (double)want);
    if (carom_world_get_stats(w, &st) != CAROM_OK || st.steps != steps)
        fz_fail("stats.steps", "%s: stats.steps %ld, step count %ld", what,
                st.steps, steps);
}

/* After a step that returned CAROM_OK: the events of that step.
 * t0 is the world time before the step, t1 after it. */
static inline void fz_check_events(const carom_world *w, const int *ids, int n,
                            int max_events, float t0, float t1)
{
    int count = -1, i, k;
    const carom_event *ev = carom_world_events(w, &count);
    float slack = (fz_abs(t1) + fz_abs(t1 - t0)) * 1.0e-5f + 1.0e-30f;
    if (count < 0 || (count > 0 && !ev) ||
        (max_events > 0 && count > max_events))
        fz_fail("event list", "%d events (max_events %d)", count,
                max_events);
    for (k = 0; k < count; ++k) {
        const carom_event *e = &ev[k];
        int ia = -1, ib = -1;
        float nn;
        for (i = 0; i < n; ++i) {
            if (ids[i] == e->body_a)
                ia = i;
            if (ids[i] == e->body_b)
                ib = i;
        }
        if (ia < 0 || ib < 0 ||
            !((e->body_a & FZ_SLOT_MASK) < (e->body_b & FZ_SLOT_MASK)))
            fz_fail("event body ids", "event %d: body_a %d, body_b %d "
                    "(not two bodies of the world with body_a's slot first)",
                    k, e->body_a, e->body_b);
        if (!fz_finite(e->t) || !fz_finite(e->normal.x) ||
            !fz_finite(e->normal.y) || !fz_finite(e->impulse) ||
            !fz_finite(e->approach_speed))
            fz_fail("finite event", "event %d: t %g normal %g %g impulse %g "
                    "approach %g", k, (double)e->t, (double)e->normal.x,
                    (double)e->normal.y, (double)e->impulse,
                    (double)e->approach_speed);
        nn = e->normal.x * e->normal.x + e->normal.y * e->normal.y;
        if (!(fz_abs(nn - 1.0f) <= 1.0e-3f))
            fz_fail("unit event normal", "event %d: normal (%g, %g)", k,
                    (double)e->normal.x, (double)e->normal.y);
        if (!(e->impulse >= 0.0f) || !(e->approach_speed >= 0.0f))
            fz_fail("event impulse/approach >= 0",
                    "event %d: impulse %g approach %g", k,
                    (double)e->impulse, (double)e->approach_speed);
        if (!(e->t >= t0 - slack && e->t <= t1 + slack))
            fz_fail("event inside its step", "event %d at t %.9g, step "
                    "[%.9g, %.9g]", k, (double)e->t, (double)t0, (double)t1);
        if (k > 0 && !(e->t >= ev[k - 1].t))
            fz_fail("events in time order", "event %d at %.9g after event "
                    "%d at %.9g", k, (double)e->t, k - 1,
                    (double)ev[k - 1].t);
    }
}

/* Two worlds driven the same way: the same event lists, bit for bit. */
static inline void fz_check_same_events(const carom_world *a, const carom_world *b,
                                 const char *invariant)
{
    int na = -1, nb = -1, k;
    const carom_event *ea = carom_world_events(a, &na);
    const carom_event *eb = carom_world_events(b, &nb);
    if (na != nb ||
        carom_world_events_dropped(a) != carom_world_events_dropped(b))
        fz_fail(invariant, "event counts %d vs %d (dropped %d vs %d)", na,
                nb, carom_world_events_dropped(a),
                carom_world_events_dropped(b));
    for (k = 0; k < na; ++k) {
        const carom_event *x = &ea[k], *y = &eb[k];
        if (fz_bits(x->t) != fz_bits(y->t) || x->body_a != y->body_a ||
            x->body_b != y->body_b ||
            fz_bits(x->normal.x) != fz_bits(y->normal.x) ||
            fz_bits(x->normal.y) != fz_bits(y->normal.y) ||
            fz_bits(x->impulse) != fz_bits(y->impulse) ||
            fz_bits(x->approach_speed) != fz_bits(y->approach_speed))
            fz_fail(invariant, "event %d differs: t %.9g/%.9g bodies %d-%d/"
                    "%d-%d impulse %.9g/%.9g", k, (double)x->t, (double)y->t,
                    x->body_a, x->body_b, y->body_a, y->body_b,
                    (double)x->impulse, (double)y->impulse);
    }
}

/* Across one step that returned CAROM_OK (carom.h, carom_body_type and
 * carom_body_is_awake; src/island.c: a sleeping island's bodies stop): a
 * static body never moves; a kinematic body keeps the velocity the program
 * set and moves by it; a dynamic body reported asleep has zero velocity;
 * a body asleep before and after the step was not simulated, unless
 * sleep_time <= dt (then a body woken in the step may sleep again at its
 * end). types[i] is body i's carom_body_type. */
static inline void fz_check_motion(const fz_snap *before, const fz_snap *after,
                                   const int *types, float dt,
                                   float sleep_time)
{
    int i;
    for (i = 0; i < before->n && i < after->n; ++i) {
        const carom_body_state *x = &before->b[i].st, *y = &after->b[i].st;
        int same = fz_bits(x->position.x) == fz_bits(y->position.x) &&
                   fz_bits(x->position.y) == fz_bits(y->position.y) &&
                   fz_bits(x->rotation.c) == fz_bits(y->rotation.c) &&
                   fz_bits(x->rotation.s) == fz_bits(y->rotation.s) &&
                   fz_bits(x->center.x) == fz_bits(y->center.x) &&
                   fz_bits(x->center.y) == fz_bits(y->center.y);
        /* by value: a velocity of -0 may come back as +0 */
        int same_v = x->velocity.x == y->velocity.x &&
                     x->velocity.y == y->velocity.y &&
                     x->angular_velocity == y->angular_velocity;
        if (before->b[i].status != CAROM_OK || after->b[i].status != CAROM_OK)
            continue;
        if (types[i] == CAROM_BODY_STATIC && !(same && same_v))
            fz_fail("static bodies never move", "body #%d: centre (%.9g, "
                    "%.9g) -> (%.9g, %.9g), velocity (%g, %g) -> (%g, %g), "
                    "w %g -> %g", i, (double)x->center.x,
                    (double)x->center.y, (double)y->center.x,
                    (double)y->center.y, (double)x->velocity.x,
                    (double)x->velocity.y, (double)y->velocity.x,
                    (double)y->velocity.y, (double)x->angular_velocity,
                    (double)y->angular_velocity);
        if (types[i] == CAROM_BODY_KINEMATIC) {
            float ex = x->center.x + x->velocity.x * dt;
            float ey = x->center.y + x->velocity.y * dt;
            float tol = 1.0e-4f * (fz_abs(ex) + fz_abs(ey) +
                                   fz_abs(x->velocity.x * dt) +
                                   fz_abs(x->velocity.y * dt)) + 1.0e-30f;
            if (!same_v)
                fz_fail("kinematic bodies keep their velocity", "body #%d: "
                        "velocity (%.9g, %.9g) w %.9g -> (%.9g, %.9g) w "
                        "%.9g", i, (double)x->velocity.x,
                        (double)x->velocity.y, (double)x->angular_velocity,
                        (double)y->velocity.x, (double)y->velocity.y,
                        (double)y->angular_velocity);
            if (!(fz_abs(y->center.x - ex) <= tol &&
                  fz_abs(y->center.y - ey) <= tol))
                fz_fail("kinematic bodies move by their velocity", "body "
                        "#%d: centre (%.9g, %.9g) + v dt = (%.9g, %.9g), "
                        "but the step left it at (%.9g, %.9g) (awake %d -> "
                        "%d)", i, (double)x->center.x, (double)x->center.y,
                        (double)ex, (double)ey, (double)y->center.x,
                        (double)y->center.y, before->b[i].awake,
                        after->b[i].awake);
        }
        if (types[i] == CAROM_BODY_DYNAMIC && !after->b[i].awake &&
            !(y->velocity.x == 0.0f && y->velocity.y == 0.0f &&
              y->angular_velocity == 0.0f))
            fz_fail("a sleeping body is at rest", "body #%d is asleep after "
                    "the step with velocity (%.9g, %.9g) w %.9g (awake before "
                    "the step: %d, velocity (%.9g, %.9g) w %.9g)", i,
                    (double)y->velocity.x, (double)y->velocity.y,
                    (double)y->angular_velocity, before->b[i].awake,
                    (double)x->velocity.x, (double)x->velocity.y,
                    (double)x->angular_velocity);
        /* to sleep after this step with sleep_time > dt it was still
         * (fastest point under the sleep speed) at the end of the last */
        if (types[i] == CAROM_BODY_DYNAMIC && before->b[i].awake &&
            !after->b[i].awake && sleep_time > dt &&
            !(fz_abs(x->velocity.x) + fz_abs(x->velocity.y) <=
              1.5f * before->tol.sleep_speed))
            fz_fail("only still bodies fall asleep", "body #%d fell asleep "
                    "although its velocity before the step was (%.9g, %.9g)"
                    ", sleep speed %.9g", i, (double)x->velocity.x,
                    (double)x->velocity.y, (double)before->tol.sleep_speed);
        if (!before->b[i].awake && !after->b[i].awake && !(same && same_v) &&
            sleep_time > dt)
            fz_fail("a sleeping body is not simulated", "body #%d asleep "
                    "before and after the step changed: centre (%.9g, %.9g)"
                    " -> (%.9g, %.9g), rotation (%.9g, %.9g) -> (%.9g, %.9g)"
                    ", velocity (%.9g, %.9g) -> (%.9g, %.9g), w %.9g -> "
                    "%.9g", i, (double)x->center.x, (double)x->center.y,
                    (double)y->center.x, (double)y->center.y,
                    (double)x->rotation.c, (double)x->rotation.s,
                    (double)y->rotation.c, (double)y->rotation.s,
                    (double)x->velocity.x, (double)x->velocity.y,
                    (double)y->velocity.x, (double)y->velocity.y,
                    (double)x->angular_velocity, (double)y->angular_velocity);
    }
}

/* After an add that returned CAROM_OK: carom_body_get_mass is 0 for a
 * body that is not dynamic, else within [CAROM_LIMIT_MIN_MASS,
 * CAROM_LIMIT_MAX_MASS]. */
static inline void fz_check_mass(const carom_world *w, int id, int type)
{
    float m = -1.0f, I = -1.0f;
    carom_status st = carom_body_get_mass(w, id, &m, &I);
    int ok;
    if (type == CAROM_BODY_DYNAMIC)
        ok = m >= CAROM_LIMIT_MIN_MASS && m <= CAROM_LIMIT_MAX_MASS &&
             I >= CAROM_LIMIT_MIN_MASS && I <= CAROM_LIMIT_MAX_MASS;
    else
        ok = fz_bits(m) == 0u && fz_bits(I) == 0u;
    if (st != CAROM_OK || !ok)
        fz_fail("body mass", "id %d type %d: get_mass %s, mass %g inertia %g",
                id, type, carom_status_string(st), (double)m, (double)I);
}

/* Two snapshots that must be equal; `invariant` names the promise. */
static inline void fz_expect_same(const fz_snap *a, const fz_snap *b,
                           const char *invariant, const char *detail)
{
    char msg[256];
    if (fz_snap_diff(a, b, msg, sizeof msg))
        fz_fail(invariant, "%s: %s", detail, msg);
}

/* The same, for the last step's results (fz_snap_diff_results). */
static inline void fz_expect_same_results(const fz_snap *a, const fz_snap *b,
                                          const char *invariant,
                                          const char *detail)
{
    char msg[256];
    if (fz_snap_diff_results(a, b, msg, sizeof msg))
        fz_fail(invariant, "%s: %s", detail, msg);
}

#endif /* CAROM_FUZZ_COMMON_H */
