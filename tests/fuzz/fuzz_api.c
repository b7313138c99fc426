/*
 * fuzz_api.c -- libFuzzer harness: the public API of carom driven by a
 * byte program (world definition, body additions, forces, a force
 * callback, method changes, steps, queries), every float of which may be
 * anything: NaN, infinities, denormals, huge, -0.
 *
 * THE INPUT (tests/fuzz/README.md has the same with examples)
 *
 *   byte 0        world flags; bit i set: the group is read from the input,
 *                 else carom_default_world_def()'s values (but max_bodies
 *                 16; max_impacts is at most 256, 0 included):
 *                   0 gravity (2 floats)        1 dt (float)
 *                   2 method (int)              3 capacities: max_bodies,
 *                   4 length_unit, rest_speed,    max_pairs, max_contacts,
 *                     linear_slop (floats)        max_events, max_impacts
 *                   5 substeps, iterations, relax_iterations,
 *                     enable_sleep (ints), sleep_time (float)
 *                   6 install the force callback
 *                   7 world B's buffer is misaligned by (next byte & 15)
 *   then operations until the input ends; op byte % 8:
 *     0, 1  add a body       2 set_force        3 set_method
 *     4, 5  1..8 steps       6 force callback parameters
 *     7     queries with an arbitrary id, and the rotation helpers
 *
 *   float: one byte b; b < 0x30: a table of edge values (0, -0, 1e-45,
 *          FLT_MIN, 1e-6, 1e8 and its neighbour, 1e12, 1e20, 1e38,
 *          FLT_MAX, inf, -inf, NaN, ...); b < 0xC0: (b - 0x78) / 8, a
 *          sensible value in [-9, 9); else the next 4 bytes, little-endian,
 *          are the float's bits.
 *   int:   one byte b; b < 0xF0: lo + b % (hi - lo + 1) for the field's
 *          usual range; else an edge value (0, -1, INT_MAX, INT_MIN, 2^20,
 *          2^26 + 1, 65, ...).
 *   Reading past the end gives zero bytes.
 *
 * THREE WORLDS are built from the definition and driven in lockstep:
 *   A   the world under test;
 *   B   the same calls, in another buffer (possibly misaligned): every
 *       status, state and event must be bit for bit those of A
 *       (determinism);
 *   C   the same calls except those that failed in A: since a failed call
 *       must leave the world as it was, C must stay bit for bit equal to A.
 *       A difference that appears later means a failed call changed state
 *       the snapshot cannot see (contacts, warm starts, sleep bookkeeping).
 * After a call that fails in A, A's snapshot (every body's state, awake
 * flag and mass; body count, time, step count, stats, method, tolerances)
 * must equal the one taken before the call. After a call that returns
 * CAROM_OK every body state must be finite, in range and with a unit
 * rotation. The force callback's outputs come from the input (so they
 * may be non-finite); it is a pure function of its parameters, the body
 * and the state, so the three worlds see the same forces.
 */
#include <limits.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"

#define FZ_MAX_OPS 96
#define FZ_MAX_TOTAL_STEPS 200
#define FZ_MAX_BUFFER ((size_t)32 << 20)
/* Impacts per input (all steps of world A): past it the input takes no
 * more steps. A world of a few bodies can spend the whole per-step impact
 * budget (at least CAROM_MIN_IMPACTS) in every step (tests/fuzz/README.md,
 * "slow inputs"); this keeps every input fast. */
#define FZ_MAX_TOTAL_IMPACTS 5000L
/* max_impacts of a world whose definition does not come from the input,
 * and the most an input may ask for (0, the library's default, and larger
 * values become this): a squeezed body can use the whole budget in every
 * step, and the default budget costs seconds per step. */
#define FZ_DEFAULT_MAX_IMPACTS 256
#define FZ_PI 3.14159265358979323846f

/* ---- reading the input ------------------------------------------------------ */

typedef struct fz_reader {
    const uint8_t *p;
    size_t n, i;
} fz_reader;

static int fz_more(const fz_reader *r) { return r->i < r->n; }

static unsigned fz_u8(fz_reader *r) { return r->i < r->n ? r->p[r->i++] : 0u; }

static unsigned fz_u16(fz_reader *r)
{
    unsigned lo = fz_u8(r);
    return lo | (fz_u8(r) << 8);
}

static uint32_t fz_u32(fz_reader *r)
{
    uint32_t v = 0;
    int k;
    for (k = 0; k < 4; ++k)
        v |= (uint32_t)fz_u8(r) << (8 * k);
    return v;
}

static float fz_from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Edge values: limits of carom_config.h and their neighbours, the
 * thresholds of float itself, and the values the issue found. */
static const uint32_t fz_edge_floats[0x30] = {
    0x00000000u, /* 0 */
    0x80000000u, /* -0 */
    0x3f800000u, /* 1 */
    0xbf800000u, /* -1 */
    0x3f000000u, /* 0.5 */
    0x41200000u, /* 10 */
    0xc1200000u, /* -10 */
    0x42c80000u, /* 100 */
    0x447a0000u, /* 1000 */
    0x461c4000u, /* 1e4 */
    0x49742400u, /* 1e6 */
    0x4cbebc20u, /* 1e8 (CAROM_LIMIT_MAX_LENGTH, _MAX_SPEED) */
    0x4cbebc21u, /* just above 1e8 */
    0xccbebc20u, /* -1e8 */
    0x4e6e6b28u, /* 1e9 */
    0x5368d4a5u, /* 1e12 (CAROM_LIMIT_MAX_ACCEL) */
    0x5368d4a6u, /* just above 1e12 */
    0x5d5e0b6bu, /* 1e18 */
    0x60ad78ecu, /* 1e20 (CAROM_LIMIT_MAX_MASS) */
    0x60ad78edu, /* just above 1e20 */
    0x6a4ee3b6u, /* 1e26 */
    0x7b2b8e4du, /* 1e36 */
    0x7e967699u, /* 1e38 */
    0x7f7fffffu, /* FLT_MAX */
    0xff7fffffu, /* -FLT_MAX */
    0x7f800000u, /* inf */
    0xff800000u, /* -inf */
    0x7fc00000u, /* NaN */
    0xffc00001u, /* -NaN with payload */
    0x00000001u, /* 1e-45, smallest denormal */
    0x80000001u, /* -1e-45 */
    0x000003e8u, /* 1.4e-42 (denormal) */
    0x006ce3eeu, /* 1e-38 (denormal) */
    0x00800000u, /* FLT_MIN */
    0x1e3ce508u, /* 1e-20 (CAROM_LIMIT_MIN_MASS) */
    0x1e3ce507u, /* just below 1e-20 */
    0x2edbe6ffu, /* 1e-10 */
    0x33d6bf95u, /* 1e-7 (CAROM_LIMIT_MIN_DT) */
    0x33d6bf94u, /* just below 1e-7 */
    0x358637bdu, /* 1e-6 (CAROM_LIMIT_MIN_SIZE) */
    0x358637bcu, /* just below 1e-6 */
    0x3c888889u, /* 1/60 */
    0x40490fdbu, /* pi */
    0x4f000000u, /* 2147483648 (2^31) */
    0x47c35000u, /* 1e5 (carom_rot_from_angle's accurate range) */
    0x41200001u, /* just above 10 (CAROM_LIMIT_MAX_DT) */
    0xbf000000u, /* -0.5 */
    0x3dcccccdu, /* 0.1 */
};

static float fz_float(fz_reader *r)
{
    unsigned b = fz_u8(r);
    if (b < 0x30u)
        return fz_from_bits(fz_edge_floats[b]);
    if (b < 0xC0u)
        return (float)((int)b - 0x78) / 8.0f;
    return fz_from_bits(fz_u32(r));
}

static const int fz_edge_ints[16] = {
    0, -1, 1, INT_MAX, INT_MIN, 1 << 20, (1 << 20) + 1, 1 << 26,
    (1 << 26) + 1, 64, 65, 2, 3, 1000000, -1000, 1 << 30};

static int fz_int(fz_reader *r, int lo, int hi)
{
    unsigned b = fz_u8(r);
    if (b < 0xF0u)
        return lo + (int)(b % (unsigned)(hi - lo + 1));
    return fz_edge_ints[b - 0xF0u];
}

/* ---- the force callback ----------------------------------------------------- */

typedef struct fz_cb_params {
    int mode;  /* 0 none, 1 constant, 2 spring, 3 below a height */
    float p[6];
} fz_cb_params;

typedef struct fz_cb_user {
    const fz_cb_params *params;
    int limit; /* highest slot the callback may be called for */
    const char *world;
} fz_cb_user;

static void fz_force(void *user, int body, const carom_body_state *state,
                     carom_vec2 *force, float *torque)
{
    const fz_cb_user *u = (const fz_cb_user *)user;
    const float *p = u->params->p;
    if (!state || !force || !torque)
        fz_fail("force callback arguments", "world %s: NULL state, force or "
                "torque", u->world);
    if (body < 0 || body > u->limit)
        fz_fail("force callback arguments", "world %s: body %d, but only "
                "slots 0..%d exist", u->world, body, u->limit);
    if (fz_bits(force->x) != 0u || fz_bits(force->y) != 0u ||
        fz_bits(*torque) != 0u)
        fz_fail("force callback arguments", "world %s: force (%g, %g) and "
                "torque %g do not start at zero", u->world,
                (double)force->x, (double)force->y, (double)*torque);
    switch (u->params->mode) {
    case 1: /* constant, by parity of the body */
        force->x = p[(body & 1) * 3 + 0];
        force->y = p[(body & 1) * 3 + 1];
        *torque = p[(body & 1) * 3 + 2];
        break;
    case 2: /* spring to (p3, p4) of stiffness p0, damping p1 */
        force->x = -p[0] * (state->center.x - p[3]) - p[1] * state->velocity.x;
        force->y = -p[0] * (state->center.y - p[4]) - p[1] * state->velocity.y;
        *torque = -p[2] * state->angular_velocity;
        break;
    case 3: /* (p0, p1, p2) once the centre is below p3 */
        if (state->center.y < p[3]) {
            force->x = p[0];
            force->y = p[1];
            *torque = p[2];
        }
        break;
    default:
        break;
    }
}

/* ---- the three worlds ---------------------------------------------------------- */

enum { FZ_A, FZ_B, FZ_C, FZ_WORLDS };
static const char *const fz_world_names[FZ_WORLDS] = {"A", "B", "C"};

typedef struct fz_world {
    carom_world *w;
    unsigned char *mem;
    fz_cb_user user;
} fz_world;

typedef struct fz_state {
    fz_world W[FZ_WORLDS];
    carom_world_def def;
    fz_cb_params params;
    int ids[FZ_MAX_BODIES];
    int types[FZ_MAX_BODIES];
    int n;                 /* bodies added (the same in every world) */
    int max_events;        /* event capacity */
    int callback;          /* a force callback is installed */
    int steps_left;
    int momentum;          /* 1 while no external force acts (see
                              fz_check_momentum) */
    char last_failure[768]; /* the last call that failed in A (for C) */
} fz_state;

/* Snapshots of the three worlds. */
static void fz_snap3(const fz_state *S, fz_snap snap[FZ_WORLDS])
{
    int k;
    for (k = 0; k < FZ_WORLDS; ++k)
        fz_snap_take(S->W[k].w, S->ids, S->n, &snap[k]);
}

/*
 * After a call made on A and B (and on C if it succeeded on A):
 * determinism (A == B), failed calls leave A unchanged, C == A.
 */
static void fz_after_call(fz_state *S, const fz_snap *before_a,
                          carom_status sa, carom_status sb, const char *what)
{
    fz_snap now[FZ_WORLDS];
    char detail[1024];
    if (sa != sb)
        fz_fail("determinism", "%s returned %s in world A, %s in world B",
                what, carom_status_string(sa), carom_status_string(sb));
    fz_snap3(S, now);
    fz_expect_same(&now[FZ_A], &now[FZ_B], "determinism", "worlds A and B");
    if (sa != CAROM_OK) {
        snprintf(detail, sizeof detail, "%s returned %s", what,
                 carom_status_string(sa));
        fz_expect_same(before_a, &now[FZ_A],
                       "failed call leaves the world unchanged", detail);
        snprintf(S->last_failure, sizeof S->last_failure, "%s", fz_where);
    } else {
        fz_check_world_ok(S->W[FZ_A].w, S->ids, S->n, S->def.dt, what);
    }
    snprintf(detail, sizeof detail, "world A (with failed calls) vs world C "
             "(without them); last failed call: %s",
             S->last_failure[0] ? S->last_failure : "none");
    fz_expect_same(&now[FZ_A], &now[FZ_C],
                   "failed call leaves no hidden state", detail);
}

/* ---- operations ----------------------------------------------------------------- */

static void fz_read_polygon(fz_reader *r, carom_body_def *d, int regular)
{
    int i, n;
    if (regular) {
        float radius, phase;
        n = 3 + (int)(fz_u8(r) % 6u);
        radius = fz_float(r);
        phase = fz_float(r);
        for (i = 0; i < n; ++i) {
            carom_rot q = carom_rot_from_angle(phase + 2.0f * FZ_PI *
                                               (float)i / (float)n);
            d->vertices[i].x = radius * q.c;
            d->vertices[i].y = radius * q.s;
        }
    } else {
        n = (int)(fz_u8(r) & 15u); /* 9..15: too many */
        for (i = 0; i < n && i < CAROM_MAX_POLYGON_VERTICES; ++i) {
            d->vertices[i].x = fz_float(r);
            d->vertices[i].y = fz_float(r);
        }
    }
    d->shape = CAROM_SHAPE_POLYGON;
    d->vertex_count = n;
}

static void fz_op_add(fz_state *S, fz_reader *r)
{
    carom_body_def d = carom_default_body_def();
    unsigned mask = fz_u16(r), shape = fz_u8(r), type = fz_u8(r);
    carom_status sa, sb, sc = CAROM_OK, valid;
    fz_snap before;
    int id[FZ_WORLDS] = {-7, -7, -7}, k;
    char verts[8 * 34 + 1];

    switch (shape & 3u) {
    case 0:
        if (mask & 1u)
            d.radius = fz_float(r);
        break;
    case 1: {
        float hx = 0.5f, hy = 0.5f;
        if (mask & 1u) {
            hx = fz_float(r);
            hy = fz_float(r);
        }
        carom_body_def_set_box(&d, hx, hy); /* a bad box stays a circle */
        break;
    }
    default:
        fz_read_polygon(r, &d, (shape & 3u) == 3u);
        break;
    }
    if ((shape & 0xF0u) == 0xF0u)
        d.shape = (carom_shape_type)(int)shape; /* not a shape */
    d.type = (type & 3u) == 3u ? (carom_body_type)(int)type
                               : (carom_body_type)(int)(type & 3u);
    if (mask & 2u) {
        d.position.x = fz_float(r);
        d.position.y = fz_float(r);
    } else { /* a grid, so that bodies need not overlap */
        d.position.x = -7.0f + 2.0f * (float)(S->n % 8);
        d.position.y = 1.0f + 2.0f * (float)(S->n / 8);
    }
    if (mask & 4u) {
        if (fz_u8(r) & 1u) {
            d.rotation.c = fz_float(r);
            d.rotation.s = fz_float(r);
        } else {
            d.rotation = carom_rot_from_angle(fz_float(r));
        }
    }
    if (mask & 8u) {
        d.velocity.x = fz_float(r);
        d.velocity.y = fz_float(r);
    }
    if (mask & 16u)
        d.angular_velocity = fz_float(r);
    if (mask & 32u)
        d.density = fz_float(r);
    if (mask & 64u)
        d.mass = fz_float(r);
    if (mask & 128u)
        d.restitution = fz_float(r);
    if (mask & 256u)
        d.friction = fz_float(r);
    if (mask & 512u) {
        d.force.x = fz_float(r);
        d.force.y = fz_float(r);
    }
    if (mask & 1024u)
        d.torque = fz_float(r);
    if (S->n >= FZ_MAX_BODIES)
        return; /* the harness's own bound */

    verts[0] = '\0';
    if (d.shape == CAROM_SHAPE_POLYGON) {
        size_t at = 0;
        int v;
        for (v = 0; v < d.vertex_count && v < CAROM_MAX_POLYGON_VERTICES; ++v)
            at += (size_t)snprintf(verts + at, sizeof verts - at, "%s%.9g,%.9g",
                                   v ? ";" : " ", (double)d.vertices[v].x,
                                   (double)d.vertices[v].y);
    }
    fz_set_where("carom_world_add_body #%d: type %d shape %d (%d vertices%s) "
                 "r %g pos %g %g rot %g %g vel %g %g w %g density %g mass %g "
                 "e %g mu %g force %g %g torque %g",
                 S->n, (int)d.type, (int)d.shape, d.vertex_count, verts,
                 (double)d.radius, (double)d.position.x, (double)d.position.y,
                 (double)d.rotation.c, (double)d.rotation.s,
                 (double)d.velocity.x, (double)d.velocity.y,
                 (double)d.angular_velocity, (double)d.density,
                 (double)d.mass, (double)d.restitution, (double)d.friction,
                 (double)d.force.x, (double)d.force.y, (double)d.torque);
    valid = carom_body_def_validate(&d);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    for (k = 0; k < FZ_WORLDS; ++k)
        S->W[k].user.limit = S->n;
    sa = carom_world_add_body(S->W[FZ_A].w, &d, &id[FZ_A]);
    sb = carom_world_add_body(S->W[FZ_B].w, &d, &id[FZ_B]);
    if (sa == CAROM_OK)
        sc = carom_world_add_body(S->W[FZ_C].w, &d, &id[FZ_C]);

    if (valid != CAROM_OK && sa != valid)
        fz_fail("add_body agrees with validate", "carom_body_def_validate "
                "says %s, carom_world_add_body %s",
                carom_status_string(valid), carom_status_string(sa));
    if (valid == CAROM_OK && sa != CAROM_OK && sa != CAROM_ERR_WORLD_FULL &&
        !(S->callback &&
          (sa == CAROM_ERR_NOT_FINITE || sa == CAROM_ERR_OUT_OF_RANGE)))
        fz_fail("add_body agrees with validate", "a valid body (callback %s)"
                " was refused with %s", S->callback ? "on" : "off",
                carom_status_string(sa));
    if ((sa == CAROM_ERR_WORLD_FULL) != (valid == CAROM_OK &&
                                         S->n >= S->def.max_bodies))
        fz_fail("world full", "%s with %d of %d bodies",
                carom_status_string(sa), S->n, S->def.max_bodies);
    if (sa == CAROM_OK) {
        if (sc != CAROM_OK)
            fz_fail("failed call leaves no hidden state", "add_body is OK in "
                    "world A but %s in world C (last failed call: %s)",
                    carom_status_string(sc), S->last_failure);
        if (id[FZ_A] != S->n || id[FZ_B] != S->n || id[FZ_C] != S->n)
            fz_fail("ids 0, 1, 2, ... in a fresh world", "body %d got ids "
                    "%d/%d/%d", S->n, id[FZ_A], id[FZ_B], id[FZ_C]);
        if (d.type != CAROM_BODY_DYNAMIC || d.force.x != 0.0f ||
            d.force.y != 0.0f || d.torque != 0.0f)
            S->momentum = 0;
        S->ids[S->n] = id[FZ_A];
        S->types[S->n++] = (int)d.type;
        fz_check_mass(S->W[FZ_A].w, id[FZ_A], (int)d.type);
    }
    for (k = 0; k < FZ_WORLDS; ++k)
        S->W[k].user.limit = S->n - 1;
    fz_after_call(S, &before, sa, sb, "carom_world_add_body");
}

static int fz_pick_id(const fz_state *S, fz_reader *r)
{
    unsigned b = fz_u8(r);
    static const int edge[16] = {-1, 0, 1, INT_MAX, INT_MIN, 1 << 20,
                                 (1 << 20) + 1, 0x7ff00000, 1 << 19,
                                 (1 << 21) + 2, 64, 65, -2, 1000, 255, 3};
    if (S->n > 0 && b < 0xF0u)
        return S->ids[b % (unsigned)S->n];
    return b >= 0xF0u ? edge[b - 0xF0u] : (int)b - 0x78;
}

static int fz_is_id(const fz_state *S, int id)
{
    int i;
    for (i = 0; i < S->n; ++i)
        if (S->ids[i] == id)
            return 1;
    return 0;
}

static void fz_op_set_force(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r);
    carom_vec2 f;
    float tq;
    carom_status sa, sb, sc;
    fz_snap before;
    f.x = fz_float(r);
    f.y = fz_float(r);
    tq = fz_float(r);
    fz_set_where("carom_body_set_force(id %d, force %g %g, torque %g)", id,
                 (double)f.x, (double)f.y, (double)tq);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    sa = carom_body_set_force(S->W[FZ_A].w, id, f, tq);
    sb = carom_body_set_force(S->W[FZ_B].w, id, f, tq);
    if (sa == CAROM_OK) {
        sc = carom_body_set_force(S->W[FZ_C].w, id, f, tq);
        if (sc != CAROM_OK)
            fz_fail("failed call leaves no hidden state", "set_force is OK "
                    "in world A but %s in world C (last failed call: %s)",
                    carom_status_string(sc), S->last_failure);
    }
    if (sa == CAROM_OK && (f.x != 0.0f || f.y != 0.0f || tq != 0.0f))
        S->momentum = 0;
    if (sa == CAROM_OK && !fz_is_id(S, id))
        fz_fail("bad ids refused", "set_force on id %d (no such body) "
                "returned CAROM_OK", id);
    fz_after_call(S, &before, sa, sb, "carom_body_set_force");
}

static void fz_op_set_method(fz_state *S, fz_reader *r)
{
    unsigned b = fz_u8(r);
    static const int edge[16] = {3, -1, 4, 100, INT_MAX, INT_MIN, 255, -2,
                                 0, 1, 2, 3, 3, 1 << 16, -3, 5};
    int m = b < 0xF0u ? (int)(b % 3u) : edge[b - 0xF0u];
    carom_status sa, sb;
    fz_snap before;
    fz_set_where("carom_world_set_method(%d)", m);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    sa = carom_world_set_method(S->W[FZ_A].w, (carom_method)m);
    sb = carom_world_set_method(S->W[FZ_B].w, (carom_method)m);
    if (sa == CAROM_OK) {
        carom_world_set_method(S->W[FZ_C].w, (carom_method)m);
        if ((int)carom_world_get_method(S->W[FZ_A].w) != m)
            fz_fail("set_method", "set %d, get_method says %d", m,
                    (int)carom_world_get_method(S->W[FZ_A].w));
    } else if (m >= 0 && m < (int)CAROM_METHOD_COUNT && CAROM_ENABLE_EVENTS) {
        fz_fail("set_method", "a known method %d refused: %s", m,
                carom_status_string(sa));
    }
    fz_after_call(S, &before, sa, sb, "carom_world_set_method");
}

/*
 * Linear momentum: with zero gravity, no force callback, no sleep, only
 * dynamic bodies and no constant forces, every impulse carom applies is one
 * of an equal and opposite pair, so sum m v is kept up to rounding.
 */
static void fz_check_momentum(const fz_state *S, const fz_snap *before,
                              const fz_snap *after)
{
    double p0x = 0, p0y = 0, p1x = 0, p1y = 0, scale = 0, tol;
    int i;
    if (!S->momentum)
        return;
    for (i = 0; i < before->n; ++i) {
        double m = (double)before->b[i].mass;
        p0x += m * (double)before->b[i].st.velocity.x;
        p0y += m * (double)before->b[i].st.velocity.y;
        p1x += m * (double)after->b[i].st.velocity.x;
        p1y += m * (double)after->b[i].st.velocity.y;
        scale += m * ((double)fz_abs(before->b[i].st.velocity.x) +
                      (double)fz_abs(before->b[i].st.velocity.y) +
                      (double)fz_abs(after->b[i].st.velocity.x) +
                      (double)fz_abs(after->b[i].st.velocity.y));
    }
    tol = 1.0e-4 * scale + 1.0e-30;
    if (!(p1x - p0x <= tol && p0x - p1x <= tol && p1y - p0y <= tol &&
          p0y - p1y <= tol))
        fz_fail("momentum conserved without external forces",
                "sum m v (%.9g, %.9g) -> (%.9g, %.9g), tolerance %.3g",
                p0x, p0y, p1x, p1y, tol);
}

static void fz_op_steps(fz_state *S, fz_reader *r)
{
    int count = 1 + (int)(fz_u8(r) & 7u), k;
    for (k = 0; k < count && S->steps_left > 0; ++k) {
        fz_snap before;
        carom_status sa, sb, sc;
        float t0;
        --S->steps_left;
        fz_set_where("carom_world_step #%ld (method %s, %d bodies, callback "
                     "mode %d)", carom_world_step_count(S->W[FZ_A].w) + 1,
                     carom_method_name(carom_world_get_method(S->W[FZ_A].w)),
                     S->n, S->callback ? S->params.mode : -1);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
        t0 = carom_world_time(S->W[FZ_A].w);
        sa = carom_world_step(S->W[FZ_A].w);
        sb = carom_world_step(S->W[FZ_B].w);
        if (carom_world_error_body(S->W[FZ_A].w) !=
            carom_world_error_body(S->W[FZ_B].w))
            fz_fail("determinism", "error bodies %d vs %d",
                    carom_world_error_body(S->W[FZ_A].w),
                    carom_world_error_body(S->W[FZ_B].w));
        fz_check_same_events(S->W[FZ_A].w, S->W[FZ_B].w, "determinism");
        if (sa == CAROM_OK) {
            sc = carom_world_step(S->W[FZ_C].w);
            if (sc != CAROM_OK)
                fz_fail("failed call leaves no hidden state", "the step is OK"
                        " in world A, %s in world C (last failed call: %s)",
                        carom_status_string(sc), S->last_failure);
            fz_check_same_events(S->W[FZ_A].w, S->W[FZ_C].w,
                                 "failed call leaves no hidden state");
            fz_check_events(S->W[FZ_A].w, S->ids, S->n, S->max_events, t0,
                            carom_world_time(S->W[FZ_A].w));
            {
                fz_snap after;
                fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
                fz_check_motion(&before, &after, S->types, S->def.dt,
                                S->def.sleep_time);
                fz_check_momentum(S, &before, &after);
            }
            {
                carom_stats st;
                carom_world_get_stats(S->W[FZ_A].w, &st);
                if (st.impacts > FZ_MAX_TOTAL_IMPACTS)
                    S->steps_left = 0;
            }
        } else {
            int count_ev = -1, eb = carom_world_error_body(S->W[FZ_A].w);
            carom_world_events(S->W[FZ_A].w, &count_ev);
            if (count_ev != 0)
                fz_fail("failed step has no events", "%s, %d events",
                        carom_status_string(sa), count_ev);
            if ((sa == CAROM_ERR_NOT_FINITE ||
                 sa == CAROM_ERR_OUT_OF_RANGE) && !fz_is_id(S, eb))
                fz_fail("error body named", "%s but carom_world_error_body "
                        "is %d", carom_status_string(sa), eb);
        }
        fz_after_call(S, &before, sa, sb, "carom_world_step");
        if (sa != CAROM_OK)
            break; /* the same step again would fail the same way */
    }
}

static void fz_op_callback(fz_state *S, fz_reader *r)
{
    int k;
    S->params.mode = (int)(fz_u8(r) & 3u);
    for (k = 0; k < 6; ++k)
        S->params.p[k] = fz_float(r);
}

static void fz_op_query(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), valid = fz_is_id(S, id), k;
    float angle = fz_float(r);
    carom_body_state st;
    carom_tolerances tol;
    float m, I;
    carom_status a, b, c;
    carom_rot q;

    fz_set_where("queries on id %d, angle %g", id, (double)angle);
    a = carom_body_get_state(S->W[FZ_A].w, id, &st);
    b = carom_body_get_mass(S->W[FZ_A].w, id, &m, &I);
    c = carom_body_get_mass(S->W[FZ_A].w, id, NULL, NULL);
    k = carom_body_is_awake(S->W[FZ_A].w, id);
    if ((a == CAROM_OK) != valid || (b == CAROM_OK) != valid ||
        (c == CAROM_OK) != valid || (!valid && k != 0))
        fz_fail("bad ids refused, good ids accepted", "id %d (%s): "
                "get_state %s, get_mass %s, is_awake %d", id,
                valid ? "a body" : "no body", carom_status_string(a),
                carom_status_string(b), k);
    if (carom_world_get_tolerances(S->W[FZ_A].w, &tol) != CAROM_OK ||
        !fz_finite(tol.length_unit) || !(tol.length_unit > 0.0f) ||
        !fz_finite(tol.linear_slop) || !(tol.linear_slop >= 0.0f) ||
        !fz_finite(tol.rest_speed) || !(tol.rest_speed >= 0.0f) ||
        !fz_finite(tol.sleep_speed) || !(tol.sleep_speed >= 0.0f))
        fz_fail("tolerances finite", "length %g slop %g rest %g sleep %g",
                (double)tol.length_unit, (double)tol.linear_slop,
                (double)tol.rest_speed, (double)tol.sleep_speed);
    /* the rotation helpers: bounded and unit inside their range */
    q = carom_rot_from_angle(angle);
    if (fz_finite(angle) && fz_abs(angle) <= 1.0e5f) {
        float len = q.c * q.c + q.s * q.s, back = carom_rot_angle(q);
        if (!(fz_abs(len - 1.0f) <= 1.0e-5f) || !fz_finite(back) ||
            !(fz_abs(back) <= FZ_PI + 1.0e-6f))
            fz_fail("rotation helpers", "carom_rot_from_angle(%.9g) = (%.9g,"
                    " %.9g), angle back %.9g", (double)angle, (double)q.c,
                    (double)q.s, (double)back);
    }
    (void)carom_rot_angle(q);
}

/* ---- the world definition -------------------------------------------------------- */

static void fz_read_world_def(fz_reader *r, carom_world_def *d, unsigned flags)
{
    *d = carom_default_world_def();
    d->max_bodies = 16;
    d->max_impacts = FZ_DEFAULT_MAX_IMPACTS;
    if (flags & 1u) {
        d->gravity.x = fz_float(r);
        d->gravity.y = fz_float(r);
    }
    if (flags & 2u)
        d->dt = fz_float(r);
    if (flags & 4u)
        d->method = (carom_method)fz_int(r, 0, 2);
    if (flags & 8u) {
        d->max_bodies = fz_int(r, 1, FZ_MAX_BODIES);
        d->max_pairs = fz_int(r, 0, 64);
        d->max_contacts = fz_int(r, 0, 64);
        d->max_events = fz_int(r, 0, 16);
        d->max_impacts = fz_int(r, 0, 64);
        if (d->max_impacts == 0 || d->max_impacts > FZ_DEFAULT_MAX_IMPACTS)
            d->max_impacts = FZ_DEFAULT_MAX_IMPACTS;
    }
    if (flags & 16u) {
        d->length_unit = fz_float(r);
        d->rest_speed = fz_float(r);
        d->linear_slop = fz_float(r);
    }
    if (flags & 32u) {
        d->substeps = fz_int(r, 1, 8);
        d->iterations = fz_int(r, 1, 8);
        d->relax_iterations = fz_int(r, 0, 8);
        d->enable_sleep = fz_int(r, 0, 1);
        d->sleep_time = fz_float(r);
    }
}

static int fz_capacity_events(const carom_world_def *d)
{
    long n = (long)CAROM_DEFAULT_EVENTS_PER_BODY * d->max_bodies;
    if (d->max_events > 0)
        return d->max_events;
    return n > CAROM_MIN_EVENTS ? (int)(n < INT_MAX ? n : INT_MAX)
                                : CAROM_MIN_EVENTS;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_state S; /* large: keep it off the stack */
    fz_reader r;
    unsigned flags, misalign = 0;
    carom_status valid, init;
    size_t bytes;
    int k, ops;

    r.p = data;
    r.n = size;
    r.i = 0;
    memset(&S, 0, sizeof S);
    S.steps_left = FZ_MAX_TOTAL_STEPS;
    flags = fz_u8(&r);
    fz_read_world_def(&r, &S.def, flags);
    if (flags & 128u)
        misalign = fz_u8(&r) & 15u;
    S.callback = (flags & 64u) != 0;
    if (S.callback)
        S.def.force_fn = fz_force;
    S.max_events = fz_capacity_events(&S.def);
    S.momentum = S.def.gravity.x == 0.0f && S.def.gravity.y == 0.0f &&
                 !S.callback && !S.def.enable_sleep;

    fz_set_where("world definition: gravity %g %g dt %g method %d bodies %d "
                 "pairs %d contacts %d events %d impacts %d length %g rest %g "
                 "slop %g substeps %d iterations %d relax %d sleep %d/%g",
                 (double)S.def.gravity.x, (double)S.def.gravity.y,
                 (double)S.def.dt, (int)S.def.method, S.def.max_bodies,
                 S.def.max_pairs, S.def.max_contacts, S.def.max_events,
                 S.def.max_impacts, (double)S.def.length_unit,
                 (double)S.def.rest_speed, (double)S.def.linear_slop,
                 S.def.substeps, S.def.iterations, S.def.relax_iterations,
                 S.def.enable_sleep, (double)S.def.sleep_time);
    valid = carom_world_def_validate(&S.def);
    bytes = carom_world_buffer_size(&S.def);
    if ((valid == CAROM_OK) != (bytes > 0))
        fz_fail("buffer size agrees with validate", "validate says %s, "
                "carom_world_buffer_size %zu", carom_status_string(valid),
                bytes);
    if (valid != CAROM_OK) {
        unsigned char small[64];
        carom_world *w = NULL;
        init = carom_world_init(&w, &S.def, small, sizeof small);
        if (init != valid)
            fz_fail("init agrees with validate", "validate says %s, "
                    "carom_world_init %s", carom_status_string(valid),
                    carom_status_string(init));
        return 0;
    }
    if (bytes > FZ_MAX_BUFFER)
        return 0;

    for (k = 0; k < FZ_WORLDS; ++k) {
        fz_world *W = &S.W[k];
        carom_world_def d = S.def;
        size_t off = k == FZ_B ? misalign : 0;
        W->user.params = &S.params;
        W->user.limit = -1;
        W->user.world = fz_world_names[k];
        d.force_user = &W->user;
        W->mem = (unsigned char *)malloc(bytes + 16);
        if (!W->mem)
            abort();
        if (k == FZ_A) {
            init = carom_world_init(&W->w, &d, W->mem, bytes - 1);
            if (init != CAROM_OK && init != CAROM_ERR_BUFFER_TOO_SMALL)
                fz_fail("init", "a buffer one byte short: %s",
                        carom_status_string(init));
        }
        init = carom_world_init(&W->w, &d, W->mem + off, bytes);
        if (init != CAROM_OK)
            fz_fail("init", "a valid definition in a buffer of "
                    "carom_world_buffer_size() bytes (offset %zu): %s", off,
                    carom_status_string(init));
    }
    fz_check_world_ok(S.W[FZ_A].w, S.ids, 0, S.def.dt, "carom_world_init");

    for (ops = 0; ops < FZ_MAX_OPS && fz_more(&r); ++ops) {
        switch (fz_u8(&r) & 7u) {
        case 0:
        case 1:
            fz_op_add(&S, &r);
            break;
        case 2:
            fz_op_set_force(&S, &r);
            break;
        case 3:
            fz_op_set_method(&S, &r);
            break;
        case 4:
        case 5:
            fz_op_steps(&S, &r);
            break;
        case 6:
            fz_op_callback(&S, &r);
            break;
        default:
            fz_op_query(&S, &r);
            break;
        }
    }
    for (k = 0; k < FZ_WORLDS; ++k)
        free(S.W[k].mem);
    return 0;
}
