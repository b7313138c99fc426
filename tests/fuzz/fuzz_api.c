/*
 * fuzz_api.c -- libFuzzer harness: the whole public API of carom driven by
 * a byte program (world definition, adding and removing bodies, velocities,
 * teleports, impulses, constant and one-step forces, material, filters,
 * user data, sensors, kinematic bodies, a force callback, method changes,
 * steps, impact and touch events, box / point / ray queries, and the
 * helpers: names, version, profiling), every float of which may be
 * anything: NaN, infinities, denormals, huge, -0.
 *
 * THE INPUT (tests/fuzz/README.md has the same in a table)
 *
 *   byte 0        world flags; bit i set: the group is read from the input,
 *                 else carom_default_world_def()'s values (but max_bodies
 *                 16; max_impacts is at most 256, 0 included):
 *                   0 gravity (2 floats)        1 dt (float)
 *                   2 method (int)              3 capacities: max_bodies,
 *                   4 length_unit, rest_speed,    max_pairs, max_contacts,
 *                     linear_slop (floats)        max_events, max_impacts
 *                   5 substeps, iterations, relax_iterations,
 *                     enable_sleep (ints), sleep_time (float); and
 *                     max_substeps = (7 iterations + relax) mod 17
 *                   6 install the force callback
 *                   7 one more byte X: world B's buffer is misaligned
 *                     by X & 15; max_touch_events is X >> 4 (0: the
 *                     default); and the operations are those of the
 *                     second table
 *   then operations until the input ends. Without flag 7, op byte & 7
 *   (the first version of this harness; its inputs keep their meaning):
 *     0, 1  add a body       2 set_force        3 set_method
 *     4, 5  1..8 steps       6 force callback parameters
 *     7     reads with an arbitrary id, and the rotation helpers
 *   With flag 7, op byte % 32:
 *     0, 1, 26, 29  add a body          2 set_force     3 set_method
 *     4, 5, 25, 28  1..8 steps          6 force callback parameters
 *     7  reads                          8, 27 remove a body
 *     9, 30 set_velocity                10 set_angular_velocity
 *     11, 31 set_transform              12 apply_impulse
 *     13 apply_angular_impulse          14 apply_force (one step)
 *     15 apply_torque (one step)        16 set_restitution
 *     17 set_friction                   18 set_user_data
 *     19 set_filter                     20 query_box
 *     21 query_point                    22 raycast
 *     23 raycast_all                    24 names, version, profiling,
 *                                          NULL arguments
 *
 *   float: one byte b; b < 0x30: a table of edge values (0, -0, 1e-45,
 *          FLT_MIN, 1e-6, 1e8 and its neighbour, 1e12, 1e20, 1e38,
 *          FLT_MAX, inf, -inf, NaN, ...); b < 0xC0: (b - 0x78) / 8, a
 *          sensible value in [-9, 9); else the next 4 bytes, little-endian,
 *          are the float's bits.
 *   int:   one byte b; b < 0xF0: lo + b % (hi - lo + 1) for the field's
 *          usual range; else an edge value (0, -1, INT_MAX, INT_MIN, 2^20,
 *          2^26 + 1, 65, ...).
 *   id:    one byte b; b < 0xE0: a body of the world (b % bodies); b <
 *          0xF0: a removed body's id (a body of the world if none was
 *          removed); else an edge value (-1, INT_MAX, 2^20, ...).
 *   Reading past the end gives zero bytes.
 *
 * THREE WORLDS are built from the definition and driven in lockstep:
 *   A   the world under test;
 *   B   the same calls, in another buffer (possibly misaligned): every
 *       status, state, event, touch event and query answer must be bit for
 *       bit those of A (determinism);
 *   C   the same calls except those that failed in A: since a failed call
 *       must leave the world as it was, C must stay bit for bit equal to A.
 *       A difference that appears later means a failed call changed state
 *       the snapshot cannot see (contacts, warm starts, sleep bookkeeping).
 *   Each buffer is filled with a different byte (0xA5, 0x5A, 0xFF) before
 *   carom_world_init, so a read of memory the library never wrote makes
 *   the worlds differ too.
 * After a call that fails in A, A's snapshot (every body's state, awake
 * flag, mass, type, velocity, user data; body count, time, step count,
 * stats, method, tolerances; for calls other than the step also the last
 * step's error body, impact and touch events) must equal the one taken
 * before the call. After a call that returns CAROM_OK every body state
 * must be finite, in range and with a unit rotation, and each call's
 * documented effect must be there (and no other body changed but for
 * being woken). Removed bodies' ids are refused with CAROM_ERR_STALE_ID
 * and never name a body again. Query answers are checked against the
 * shapes, recomputed here in double precision from the definitions. The
 * force callback's outputs come from the input (so they may be
 * non-finite); it is a pure function of its parameters, the body and the
 * state, so the three worlds see the same forces.
 */
#include <limits.h>
#include <math.h>
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
/* removed ids remembered (to check that they stay refused) */
#define FZ_MAX_STALE 64
/* touching pairs followed from the touch events */
#define FZ_MAX_TOUCHING (FZ_MAX_BODIES * (FZ_MAX_BODIES - 1) / 2)
/* bodies a query may report (more: a violation by itself) */
#define FZ_MAX_FOUND (2 * FZ_MAX_BODIES)
/* relative tolerance of the geometric checks of query answers (the
 * library computes in float, the harness in double) */
#define FZ_GEOM_TOL 4.0e-5

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

/* Collision filter bits: b < 0x80: a few categories (b & 15, 0 included);
 * b < 0xC0: all but a few; else 4 bytes. */
static uint32_t fz_filter_bits(fz_reader *r)
{
    unsigned b = fz_u8(r);
    if (b < 0x80u)
        return (uint32_t)(b & 15u);
    if (b < 0xC0u)
        return 0xffffffffu ^ (uint32_t)(b & 15u);
    return fz_u32(r);
}

/* The program's pointer for a body: NULL or a made-up address, never
 * dereferenced (only compared). */
static void *fz_user_pointer(unsigned b)
{
    return b == 0u ? NULL : (void *)(uintptr_t)(0x10000u + 16u * b);
}

/* ---- the force callback ----------------------------------------------------- */

typedef struct fz_cb_params {
    int mode;  /* 0 none, 1 constant, 2 spring, 3 below a height */
    float p[6];
} fz_cb_params;

struct fz_state;

typedef struct fz_cb_user {
    const fz_cb_params *params;
    const struct fz_state *S;
    int adding;    /* a body is being added: its new id is allowed */
    int added_id;  /* the id the callback got for it (-1: not called) */
    const char *world;
} fz_cb_user;

static int fz_is_id(const struct fz_state *S, int id);

static void fz_force(void *user, int body, const carom_body_state *state,
                     carom_vec2 *force, float *torque)
{
    fz_cb_user *u = (fz_cb_user *)user;
    const float *p = u->params->p;
    if (!state || !force || !torque)
        fz_fail("force callback arguments", "world %s: NULL state, force or "
                "torque", u->world);
    if (!fz_is_id(u->S, body)) {
        /* only the body being added may have an id the harness has not
         * seen yet, and only one */
        if (!u->adding || body < 0 ||
            (u->added_id >= 0 && u->added_id != body))
            fz_fail("force callback arguments", "world %s: body %d is not a "
                    "body of the world%s", u->world, body,
                    u->adding ? " (nor the one being added)" : "");
        u->added_id = body;
    }
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

/* What the harness knows of a body from its definition and the calls. */
typedef struct fz_body_rec {
    int kind;              /* CAROM_SHAPE_CIRCLE or _POLYGON */
    float radius;
    int count;             /* polygon vertices, body frame, as defined */
    carom_vec2 v[CAROM_MAX_POLYGON_VERTICES];
    int sensor;
    uint32_t category, mask;
    int group;
    void *user;            /* the program's pointer */
    int forced;            /* a constant force or torque may act */
    int once;              /* a one-step force or torque is pending */
} fz_body_rec;

typedef struct fz_state {
    fz_world W[FZ_WORLDS];
    carom_world_def def;
    fz_cb_params params;
    int ids[FZ_MAX_BODIES];   /* the bodies of the world now */
    int types[FZ_MAX_BODIES];
    fz_body_rec rec[FZ_MAX_BODIES];
    int n;                    /* bodies (the same in every world) */
    int removed;              /* a body was removed (ids no longer 0, 1..) */
    int stale[FZ_MAX_STALE];  /* ids of removed bodies */
    int n_stale;
    int touching[FZ_MAX_TOUCHING][2]; /* pairs touching, from the events */
    int n_touching;
    int touch_known;          /* the touch events so far were all kept */
    int max_events;           /* event capacity */
    int max_touch_events;     /* touch event capacity */
    int callback;             /* a force callback is installed */
    int v2;                   /* world flag 7: the second operation table
                                 (and the body fields of add's mask bits
                                 11..13) */
    int steps_left;
    int momentum;             /* 1 while no external force acts (see
                                 fz_check_momentum) */
    char last_failure[768];   /* the last call that failed in A (for C) */
} fz_state;

static int fz_index_of(const fz_state *S, int id)
{
    int i;
    for (i = 0; i < S->n; ++i)
        if (S->ids[i] == id)
            return i;
    return -1;
}

static int fz_is_id(const fz_state *S, int id) { return fz_index_of(S, id) >= 0; }

static int fz_is_stale(const fz_state *S, int id)
{
    int i;
    for (i = 0; i < S->n_stale; ++i)
        if (S->stale[i] == id)
            return 1;
    return 0;
}

static int fz_pick_id(const fz_state *S, fz_reader *r)
{
    unsigned b = fz_u8(r);
    static const int edge[16] = {-1, 0, 1, INT_MAX, INT_MIN, 1 << 20,
                                 (1 << 20) + 1, 0x7ff00000, 1 << 19,
                                 (1 << 21) + 2, 64, 65, -2, 1000, 255, 3};
    if (b >= 0xE0u && b < 0xF0u && S->n_stale > 0)
        return S->stale[(b - 0xE0u) % (unsigned)S->n_stale];
    if (S->n > 0 && b < 0xF0u)
        return S->ids[b % (unsigned)S->n];
    return b >= 0xF0u ? edge[b - 0xF0u] : (int)b - 0x78;
}

/* The status of a call on `id` says what the id is (carom.h,
 * carom_world_remove_body: a removed body's id is refused with
 * CAROM_ERR_STALE_ID; CAROM_ERR_BAD_BODY_ID: no such body). */
static void fz_check_id_status(const fz_state *S, int id, carom_status st,
                               const char *what)
{
    int live = fz_is_id(S, id);
    if (live && (st == CAROM_ERR_BAD_BODY_ID || st == CAROM_ERR_STALE_ID))
        fz_fail("good ids accepted", "%s on id %d (a body of the world) "
                "returned %s", what, id, carom_status_string(st));
    if (!live && fz_is_stale(S, id) && st != CAROM_ERR_STALE_ID)
        fz_fail("stale id refused with CAROM_ERR_STALE_ID", "%s on id %d (a "
                "removed body) returned %s", what, id,
                carom_status_string(st));
    if (!live && st != CAROM_ERR_BAD_BODY_ID && st != CAROM_ERR_STALE_ID &&
        st != CAROM_ERR_NULL)
        fz_fail("bad ids refused", "%s on id %d (no such body) returned %s",
                what, id, carom_status_string(st));
}

/* Snapshots of the three worlds. */
static void fz_snap3(const fz_state *S, fz_snap snap[FZ_WORLDS])
{
    int k;
    for (k = 0; k < FZ_WORLDS; ++k)
        fz_snap_take(S->W[k].w, S->ids, S->n, &snap[k]);
}

/* The ids of removed bodies stay refused, by every call that reads a body
 * (carom.h, carom_world_remove_body, carom_body_get_user_data). */
static void fz_check_stale(const fz_state *S, const carom_world *w)
{
    int k;
    for (k = 0; k < S->n_stale; ++k) {
        int id = S->stale[k];
        carom_body_state st;
        carom_body_type t;
        carom_vec2 v;
        float m, I, a;
        carom_status s1 = carom_body_get_state(w, id, &st);
        carom_status s2 = carom_body_get_mass(w, id, &m, &I);
        carom_status s3 = carom_body_get_type(w, id, &t);
        carom_status s4 = carom_body_get_velocity(w, id, &v, &a);
        if (fz_is_id(S, id))
            continue; /* named a new body (reported where it happened) */
        if (carom_body_is_valid(w, id) != 0 ||
            carom_body_is_awake(w, id) != 0 ||
            carom_body_get_user_data(w, id) != NULL)
            fz_fail("stale id refused", "removed id %d: is_valid %d, "
                    "is_awake %d, user data %p", id,
                    carom_body_is_valid(w, id), carom_body_is_awake(w, id),
                    carom_body_get_user_data(w, id));
        if (s1 != CAROM_ERR_STALE_ID || s2 != CAROM_ERR_STALE_ID ||
            s3 != CAROM_ERR_STALE_ID || s4 != CAROM_ERR_STALE_ID)
            fz_fail("stale id refused with CAROM_ERR_STALE_ID", "removed id "
                    "%d: get_state %s, get_mass %s, get_type %s, "
                    "get_velocity %s", id, carom_status_string(s1),
                    carom_status_string(s2), carom_status_string(s3),
                    carom_status_string(s4));
    }
}

/* After a call that returned CAROM_OK, what the reading calls say of each
 * body agrees with each other and with the harness's records. */
static void fz_check_bodies_read(const fz_state *S, const fz_snap *s,
                                 const char *what)
{
    int i;
    for (i = 0; i < s->n; ++i) {
        const fz_body_snap *b = &s->b[i];
        if (b->valid != 1 || b->type_status != CAROM_OK ||
            b->type != S->types[i] || b->vel_status != CAROM_OK ||
            b->mass_status != CAROM_OK)
            fz_fail("body readable", "%s: body #%d (id %d): is_valid %d, "
                    "get_type %s (%d, added as %d), get_velocity %s, "
                    "get_mass %s", what, i, S->ids[i], b->valid,
                    carom_status_string((carom_status)b->type_status),
                    b->type, S->types[i],
                    carom_status_string((carom_status)b->vel_status),
                    carom_status_string((carom_status)b->mass_status));
        if (fz_bits(b->vel.x) != fz_bits(b->st.velocity.x) ||
            fz_bits(b->vel.y) != fz_bits(b->st.velocity.y) ||
            fz_bits(b->angvel) != fz_bits(b->st.angular_velocity))
            fz_fail("get_velocity agrees with get_state", "%s: body #%d: "
                    "(%.9g, %.9g) w %.9g vs (%.9g, %.9g) w %.9g", what, i,
                    (double)b->vel.x, (double)b->vel.y, (double)b->angvel,
                    (double)b->st.velocity.x, (double)b->st.velocity.y,
                    (double)b->st.angular_velocity);
        if (b->user != (uintptr_t)S->rec[i].user)
            fz_fail("user data kept", "%s: body #%d (id %d): "
                    "carom_body_get_user_data %p, set %p", what, i,
                    S->ids[i], (void *)b->user, S->rec[i].user);
    }
}

/*
 * After a call made on A and B (and on C if it succeeded on A):
 * determinism (A == B), failed calls leave A unchanged, C == A. `step`:
 * the call was carom_world_step (whose failure empties the event list and
 * sets the error body); every other call keeps the last step's results.
 */
static void fz_after_call(fz_state *S, const fz_snap *before_a,
                          carom_status sa, carom_status sb, const char *what,
                          int step)
{
    fz_snap now[FZ_WORLDS];
    char detail[1024];
    fz_check_status_named(sa, what);
    if (sa != sb)
        fz_fail("determinism", "%s returned %s in world A, %s in world B",
                what, carom_status_string(sa), carom_status_string(sb));
    fz_snap3(S, now);
    fz_expect_same(&now[FZ_A], &now[FZ_B], "determinism", "worlds A and B");
    fz_expect_same_results(&now[FZ_A], &now[FZ_B], "determinism",
                           "worlds A and B");
    if (!step)
        fz_expect_same_results(before_a, &now[FZ_A],
                               "a call other than the step keeps the last "
                               "step's results", what);
    if (sa != CAROM_OK) {
        snprintf(detail, sizeof detail, "%s returned %s", what,
                 carom_status_string(sa));
        fz_expect_same(before_a, &now[FZ_A],
                       "failed call leaves the world unchanged", detail);
        snprintf(S->last_failure, sizeof S->last_failure, "%s", fz_where);
    } else {
        fz_check_world_ok(S->W[FZ_A].w, S->ids, S->n, S->def.dt, what);
        fz_check_bodies_read(S, &now[FZ_A], what);
    }
    fz_check_stale(S, S->W[FZ_A].w);
    snprintf(detail, sizeof detail, "world A (with failed calls) vs world C "
             "(without them); last failed call: %s",
             S->last_failure[0] ? S->last_failure : "none");
    fz_expect_same(&now[FZ_A], &now[FZ_C],
                   "failed call leaves no hidden state", detail);
}

/* Call CALL (an expression of the world pointer w_) on worlds A and B,
 * and on C if it succeeded on A; sa, sb get A's and B's statuses. */
#define FZ_CALL3(S, sa, sb, CALL)                                              \
    do {                                                                       \
        carom_world *w_ = (S)->W[FZ_A].w;                                      \
        carom_status sc_;                                                      \
        (sa) = (CALL);                                                         \
        w_ = (S)->W[FZ_B].w;                                                   \
        (sb) = (CALL);                                                         \
        if ((sa) == CAROM_OK) {                                                \
            w_ = (S)->W[FZ_C].w;                                               \
            sc_ = (CALL);                                                      \
            if (sc_ != CAROM_OK)                                               \
                fz_fail("failed call leaves no hidden state", "%s is OK in "   \
                        "world A but %s in world C (last failed call: %s)",    \
                        #CALL, carom_status_string(sc_), (S)->last_failure);   \
        }                                                                      \
    } while (0)

/* What a call on body index j (or -1) may change besides waking bodies. */
#define FZ_MAY_VELOCITY 1
#define FZ_MAY_POSE 2
#define FZ_MAY_USER 4

/* After a call on body index j returned CAROM_OK: every other body is as
 * it was but for being woken, and j changed only in `may`. */
static void fz_check_others_kept(const fz_state *S, const fz_snap *before,
                                 const fz_snap *after, int j, unsigned may,
                                 const char *what)
{
    char msg[256];
    int i;
    (void)S;
    for (i = 0; i < before->n && i < after->n; ++i) {
        fz_body_snap x = before->b[i], y = after->b[i];
        if (i == j) {
            if (may & FZ_MAY_VELOCITY) {
                y.st.velocity = x.st.velocity;
                y.st.angular_velocity = x.st.angular_velocity;
                y.vel = x.vel;
                y.angvel = x.angvel;
            }
            if (may & FZ_MAY_POSE) {
                y.st.position = x.st.position;
                y.st.rotation = x.st.rotation;
                y.st.center = x.st.center;
            }
            if (may & FZ_MAY_USER)
                y.user = x.user;
        }
        if (fz_snap_diff_body_but_awake(&x, &y, i, msg, sizeof msg))
            fz_fail("a call changes only its body", "%s (body #%d): %s",
                    what, j, msg);
    }
}

/* ---- shapes in double precision (to check query answers) ----------------------- */

typedef struct fz_d2 {
    double x, y;
} fz_d2;

/* A body's shape in the world frame: a circle (centre, radius) or a convex
 * polygon, counter-clockwise, with unit outward normals. `scale` is the
 * size of the numbers involved (for tolerances). */
typedef struct fz_geom {
    int circle;
    fz_d2 c;
    double r;
    int n;
    fz_d2 v[CAROM_MAX_POLYGON_VERTICES], nrm[CAROM_MAX_POLYGON_VERTICES];
    double scale;
} fz_geom;

static double fz_dabs(double x) { return x < 0 ? -x : x; }
static double fz_dmax(double a, double b) { return a > b ? a : b; }
static double fz_dmin(double a, double b) { return a < b ? a : b; }
static double fz_dot(fz_d2 a, fz_d2 b) { return a.x * b.x + a.y * b.y; }
static fz_d2 fz_sub(fz_d2 a, fz_d2 b)
{
    fz_d2 c;
    c.x = a.x - b.x;
    c.y = a.y - b.y;
    return c;
}
static fz_d2 fz_d2_of(carom_vec2 v)
{
    fz_d2 c;
    c.x = (double)v.x;
    c.y = (double)v.y;
    return c;
}
static double fz_len(fz_d2 a) { return sqrt(fz_dot(a, a)); }

static void fz_geom_of(const fz_body_rec *rec, const carom_body_state *st,
                       fz_geom *g)
{
    double c = (double)st->rotation.c, s = (double)st->rotation.s;
    double q = sqrt(c * c + s * s), px = (double)st->position.x,
           py = (double)st->position.y, area = 0, ext = 0;
    int i;
    if (q > 0) {
        c /= q;
        s /= q;
    }
    g->circle = rec->kind == CAROM_SHAPE_CIRCLE;
    g->n = 0;
    if (g->circle) {
        g->c = fz_d2_of(st->center);
        g->r = (double)rec->radius;
        ext = g->r;
    } else {
        g->n = rec->count;
        for (i = 0; i < g->n; ++i) {
            double x = (double)rec->v[i].x, y = (double)rec->v[i].y;
            g->v[i].x = px + c * x - s * y;
            g->v[i].y = py + s * x + c * y;
            ext = fz_dmax(ext, fz_dabs(x) + fz_dabs(y));
        }
        for (i = 0; i < g->n; ++i) {
            fz_d2 a = g->v[i], b = g->v[(i + 1) % g->n];
            area += a.x * b.y - a.y * b.x;
        }
        if (area < 0) { /* clockwise: reverse */
            for (i = 0; i < g->n / 2; ++i) {
                fz_d2 t = g->v[i];
                g->v[i] = g->v[g->n - 1 - i];
                g->v[g->n - 1 - i] = t;
            }
        }
        for (i = 0; i < g->n; ++i) {
            fz_d2 e = fz_sub(g->v[(i + 1) % g->n], g->v[i]);
            double l = fz_len(e);
            g->nrm[i].x = l > 0 ? e.y / l : 0;
            g->nrm[i].y = l > 0 ? -e.x / l : 0;
        }
        g->c.x = px;
        g->c.y = py;
    }
    g->scale = fz_dabs(px) + fz_dabs(py) + fz_dabs((double)st->center.x) +
               fz_dabs((double)st->center.y) + ext;
}

/* Signed distance of p to the shape (exact for circles; for polygons the
 * largest distance to an edge line: exact inside and on the boundary, at
 * most the distance outside). */
static double fz_point_sep(const fz_geom *g, fz_d2 p)
{
    double best = -1e300;
    int i;
    if (g->circle)
        return fz_len(fz_sub(p, g->c)) - g->r;
    for (i = 0; i < g->n; ++i)
        best = fz_dmax(best, fz_dot(g->nrm[i], fz_sub(p, g->v[i])));
    return best;
}

/* Projection of the shape on a unit axis. */
static void fz_project(const fz_geom *g, fz_d2 axis, double *lo, double *hi)
{
    int i;
    if (g->circle) {
        double m = fz_dot(axis, g->c);
        *lo = m - g->r;
        *hi = m + g->r;
        return;
    }
    *lo = *hi = fz_dot(axis, g->v[0]);
    for (i = 1; i < g->n; ++i) {
        double m = fz_dot(axis, g->v[i]);
        *lo = fz_dmin(*lo, m);
        *hi = fz_dmax(*hi, m);
    }
}

/* Separation of two convex shapes along the separating axes (face
 * normals; for a circle the axis to the other shape's closest vertex, or
 * between the centres): > 0 gives a lower bound of their distance, < 0
 * the depth of their overlap. Up to 2 * 8 + 2 axes. */
static double fz_sep_axes(const fz_geom *a, const fz_geom *b,
                          const fz_d2 *axes, int n_axes)
{
    double best = -1e300;
    int k;
    for (k = 0; k < n_axes; ++k) {
        double alo, ahi, blo, bhi;
        fz_project(a, axes[k], &alo, &ahi);
        fz_project(b, axes[k], &blo, &bhi);
        best = fz_dmax(best, fz_dmax(blo - ahi, alo - bhi));
    }
    return best;
}

static int fz_circle_axis(const fz_geom *circle, const fz_geom *other,
                          fz_d2 *axis)
{
    fz_d2 best = other->c, d;
    double bd = 1e300, l;
    int i;
    if (!other->circle)
        for (i = 0; i < other->n; ++i) {
            double e = fz_len(fz_sub(other->v[i], circle->c));
            if (e < bd) {
                bd = e;
                best = other->v[i];
            }
        }
    d = fz_sub(best, circle->c);
    l = fz_len(d);
    if (!(l > 0))
        return 0;
    axis->x = d.x / l;
    axis->y = d.y / l;
    return 1;
}

static double fz_shape_sep(const fz_geom *a, const fz_geom *b)
{
    fz_d2 axes[2 * CAROM_MAX_POLYGON_VERTICES + 2];
    int n = 0, i;
    for (i = 0; i < a->n; ++i)
        axes[n++] = a->nrm[i];
    for (i = 0; i < b->n; ++i)
        axes[n++] = b->nrm[i];
    if (a->circle && fz_circle_axis(a, b, &axes[n]))
        ++n;
    if (b->circle && fz_circle_axis(b, a, &axes[n]))
        ++n;
    if (n == 0) /* two circles with the same centre */
        return -fz_dmin(a->r, b->r);
    return fz_sep_axes(a, b, axes, n);
}

/* A box as a polygon shape. */
static void fz_geom_box(double lx, double ly, double hx, double hy, fz_geom *g)
{
    g->circle = 0;
    g->n = 4;
    g->v[0].x = lx; g->v[0].y = ly;
    g->v[1].x = hx; g->v[1].y = ly;
    g->v[2].x = hx; g->v[2].y = hy;
    g->v[3].x = lx; g->v[3].y = hy;
    g->nrm[0].x = 0; g->nrm[0].y = -1;
    g->nrm[1].x = 1; g->nrm[1].y = 0;
    g->nrm[2].x = 0; g->nrm[2].y = 1;
    g->nrm[3].x = -1; g->nrm[3].y = 0;
    g->c.x = 0.5 * (lx + hx);
    g->c.y = 0.5 * (ly + hy);
    g->r = 0;
    g->scale = fz_dabs(lx) + fz_dabs(ly) + fz_dabs(hx) + fz_dabs(hy);
}

/* Clip the segment p0 + t d, t in [0, 1], to the shape grown by `grow`
 * (negative: shrunk). Returns 1 with the interval [*t0, *t1] if it meets
 * it. */
static int fz_clip(const fz_geom *g, fz_d2 p0, fz_d2 d, double grow,
                   double *t0, double *t1)
{
    double lo = 0, hi = 1;
    int i;
    if (g->circle) {
        fz_d2 f = fz_sub(p0, g->c);
        double r = g->r + grow, a = fz_dot(d, d), b = fz_dot(f, d),
               c = fz_dot(f, f) - r * r, disc, s;
        if (r <= 0)
            return 0;
        if (!(a > 0)) {
            if (c > 0)
                return 0;
            *t0 = 0;
            *t1 = 1;
            return 1;
        }
        disc = b * b - a * c;
        if (disc < 0)
            return 0;
        s = sqrt(disc);
        lo = fz_dmax(0, (-b - s) / a);
        hi = fz_dmin(1, (-b + s) / a);
        if (lo > hi)
            return 0;
        *t0 = lo;
        *t1 = hi;
        return 1;
    }
    for (i = 0; i < g->n; ++i) {
        /* n . (p0 + t d - v) <= grow */
        double num = grow - fz_dot(g->nrm[i], fz_sub(p0, g->v[i]));
        double den = fz_dot(g->nrm[i], d);
        if (den == 0) {
            if (num < 0)
                return 0;
        } else if (den > 0) {
            hi = fz_dmin(hi, num / den);
        } else {
            lo = fz_dmax(lo, num / den);
        }
        if (lo > hi)
            return 0;
    }
    *t0 = lo;
    *t1 = hi;
    return 1;
}

/* ---- adding bodies ---------------------------------------------------------------- */

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

static void fz_set_adding(fz_state *S, int adding)
{
    int k;
    for (k = 0; k < FZ_WORLDS; ++k) {
        S->W[k].user.adding = adding;
        S->W[k].user.added_id = -1;
    }
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
    if (S->v2 && (mask & 2048u))
        d.is_sensor = 1;
    if (S->v2 && (mask & 4096u)) {
        d.category_bits = fz_filter_bits(r);
        d.mask_bits = fz_filter_bits(r);
        d.group_index = fz_int(r, -3, 3);
    }
    if (S->v2 && (mask & 8192u))
        d.user_data = fz_user_pointer(fz_u8(r));
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
                 "e %g mu %g force %g %g torque %g sensor %d filter %#lx %#lx "
                 "%d user %p",
                 S->n, (int)d.type, (int)d.shape, d.vertex_count, verts,
                 (double)d.radius, (double)d.position.x, (double)d.position.y,
                 (double)d.rotation.c, (double)d.rotation.s,
                 (double)d.velocity.x, (double)d.velocity.y,
                 (double)d.angular_velocity, (double)d.density,
                 (double)d.mass, (double)d.restitution, (double)d.friction,
                 (double)d.force.x, (double)d.force.y, (double)d.torque,
                 d.is_sensor, (unsigned long)d.category_bits,
                 (unsigned long)d.mask_bits, d.group_index, d.user_data);
    valid = carom_body_def_validate(&d);
    fz_check_status_named(valid, "carom_body_def_validate");
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    fz_set_adding(S, 1);
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
        fz_body_rec *rec = &S->rec[S->n];
        if (sc != CAROM_OK)
            fz_fail("failed call leaves no hidden state", "add_body is OK in "
                    "world A but %s in world C (last failed call: %s)",
                    carom_status_string(sc), S->last_failure);
        if (id[FZ_A] != id[FZ_B] || id[FZ_A] != id[FZ_C])
            fz_fail("determinism", "body %d got ids %d/%d/%d", S->n,
                    id[FZ_A], id[FZ_B], id[FZ_C]);
        if (!S->removed && id[FZ_A] != S->n)
            fz_fail("ids 0, 1, 2, ... in a fresh world", "body %d got id %d",
                    S->n, id[FZ_A]);
        if (id[FZ_A] < 0 || fz_is_id(S, id[FZ_A]))
            fz_fail("a new body has a new id", "id %d", id[FZ_A]);
        if (fz_is_stale(S, id[FZ_A])) {
            fz_fail("stale id never names a new body", "the new body got id "
                    "%d, the id of a removed body", id[FZ_A]);
            /* (going on past it: that id names a body again) */
            for (k = 0; k < S->n_stale; ++k)
                if (S->stale[k] == id[FZ_A])
                    S->stale[k] = S->stale[--S->n_stale];
        }
        for (k = 0; k < FZ_WORLDS; ++k)
            if (S->W[k].user.added_id >= 0 &&
                S->W[k].user.added_id != id[FZ_A])
                fz_fail("force callback arguments", "world %s: the callback "
                        "got id %d for the body added as %d",
                        fz_world_names[k], S->W[k].user.added_id, id[FZ_A]);
        if (d.type != CAROM_BODY_DYNAMIC || d.force.x != 0.0f ||
            d.force.y != 0.0f || d.torque != 0.0f)
            S->momentum = 0;
        memset(rec, 0, sizeof *rec);
        rec->kind = (int)d.shape;
        rec->radius = d.radius;
        rec->count = d.shape == CAROM_SHAPE_POLYGON ? d.vertex_count : 0;
        for (k = 0; k < rec->count; ++k)
            rec->v[k] = d.vertices[k];
        rec->sensor = d.is_sensor;
        rec->category = d.category_bits;
        rec->mask = d.mask_bits;
        rec->group = d.group_index;
        rec->user = d.user_data;
        rec->forced = d.force.x != 0.0f || d.force.y != 0.0f ||
                      d.torque != 0.0f;
        S->ids[S->n] = id[FZ_A];
        S->types[S->n++] = (int)d.type;
        fz_check_mass(S->W[FZ_A].w, id[FZ_A], (int)d.type);
    }
    fz_set_adding(S, 0);
    fz_after_call(S, &before, sa, sb, "carom_world_add_body", 0);
}

/* ---- removing bodies ------------------------------------------------------------ */

static void fz_forget_touches(fz_state *S, int id)
{
    int k, m = 0;
    for (k = 0; k < S->n_touching; ++k)
        if (S->touching[k][0] != id && S->touching[k][1] != id) {
            S->touching[m][0] = S->touching[k][0];
            S->touching[m][1] = S->touching[k][1];
            ++m;
        }
    S->n_touching = m;
}

static void fz_op_remove(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id), i;
    carom_status sa, sb;
    fz_snap before, after;
    fz_set_where("carom_world_remove_body(id %d%s)", id,
                 j >= 0 ? "" : ", not a body of the world");
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    FZ_CALL3(S, sa, sb, carom_world_remove_body(w_, id));
    fz_check_id_status(S, id, sa, "carom_world_remove_body");
    if (j >= 0 && sa != CAROM_OK)
        fz_fail("remove_body", "removing id %d, a body of the world, "
                "returned %s", id, carom_status_string(sa));
    if (sa == CAROM_OK) {
        char msg[256];
        /* the harness's records: the body goes, its id becomes stale */
        for (i = j; i + 1 < S->n; ++i) {
            S->ids[i] = S->ids[i + 1];
            S->types[i] = S->types[i + 1];
            S->rec[i] = S->rec[i + 1];
        }
        --S->n;
        S->removed = 1;
        if (S->n_stale < FZ_MAX_STALE)
            S->stale[S->n_stale++] = id;
        fz_forget_touches(S, id); /* "end without an event" */
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        if (after.body_count != before.body_count - 1)
            fz_fail("remove_body", "body count %d -> %d", before.body_count,
                    after.body_count);
        /* the others are as they were (a sleeping island may wake) */
        for (i = 0; i < S->n; ++i)
            if (fz_snap_diff_body_but_awake(&before.b[i < j ? i : i + 1],
                                            &after.b[i], i, msg, sizeof msg))
                fz_fail("a call changes only its body", "remove_body(%d): %s",
                        id, msg);
    }
    fz_after_call(S, &before, sa, sb, "carom_world_remove_body", 0);
}

/* ---- forces and the method ---------------------------------------------------- */

static void fz_expect_awake(const fz_state *S, int id, const char *what)
{
    if (carom_body_is_awake(S->W[FZ_A].w, id) != 1)
        fz_fail("the call wakes the body", "%s returned CAROM_OK but id %d "
                "is asleep", what, id);
}

static void fz_op_set_force(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    carom_vec2 f;
    float tq;
    carom_status sa, sb;
    fz_snap before, after;
    f.x = fz_float(r);
    f.y = fz_float(r);
    tq = fz_float(r);
    fz_set_where("carom_body_set_force(id %d, force %g %g, torque %g)", id,
                 (double)f.x, (double)f.y, (double)tq);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    FZ_CALL3(S, sa, sb, carom_body_set_force(w_, id, f, tq));
    if (sa != CAROM_ERR_DISABLED)
        fz_check_id_status(S, id, sa, "carom_body_set_force");
    if (sa == CAROM_OK) {
        if (!fz_finite(f.x) || !fz_finite(f.y) || !fz_finite(tq))
            fz_fail("non-finite input refused", "set_force(%g, %g, %g) "
                    "returned CAROM_OK", (double)f.x, (double)f.y,
                    (double)tq);
        if (f.x != 0.0f || f.y != 0.0f || tq != 0.0f)
            S->momentum = 0;
        S->rec[j].forced = f.x != 0.0f || f.y != 0.0f || tq != 0.0f;
        fz_expect_awake(S, id, "carom_body_set_force");
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        fz_check_others_kept(S, &before, &after, j, 0u,
                             "carom_body_set_force");
    }
    fz_after_call(S, &before, sa, sb, "carom_body_set_force", 0);
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
    fz_after_call(S, &before, sa, sb, "carom_world_set_method", 0);
}

/* ---- the program's controls between steps --------------------------------------- */

/* How far a body's shape reaches from its origin (for tolerances). */
static double fz_rec_extent(const fz_body_rec *rec)
{
    double e = 0;
    int i;
    if (rec->kind == CAROM_SHAPE_CIRCLE)
        return (double)rec->radius;
    for (i = 0; i < rec->count; ++i)
        e = fz_dmax(e, fz_dabs((double)rec->v[i].x) +
                           fz_dabs((double)rec->v[i].y));
    return e;
}

/* |got - want| <= tol, else a violation. */
static void fz_expect_near(const char *invariant, const char *what,
                           double got, double want, double tol)
{
    if (!(fz_dabs(got - want) <= tol))
        fz_fail(invariant, "%s: %.9g, expected %.9g (tolerance %.3g)", what,
                got, want, tol);
}

/* A point for an impulse or a force: the body's centre plus an offset
 * (mode bit 0), else anywhere. */
static carom_vec2 fz_read_point(const fz_state *S, fz_reader *r, int j)
{
    unsigned mode = fz_u8(r);
    carom_vec2 p;
    p.x = fz_float(r);
    p.y = fz_float(r);
    if ((mode & 1u) && j >= 0) {
        carom_body_state st;
        if (carom_body_get_state(S->W[FZ_A].w, S->ids[j], &st) == CAROM_OK) {
            p.x += st.center.x;
            p.y += st.center.y;
        }
    }
    return p;
}

static void fz_op_set_velocity(fz_state *S, fz_reader *r, int angular)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = angular ? "carom_body_set_angular_velocity"
                               : "carom_body_set_velocity";
    carom_vec2 v;
    float w = 0.0f;
    carom_status sa, sb;
    fz_snap before, after;
    v.x = v.y = 0.0f;
    if (angular) {
        w = fz_float(r);
        fz_set_where("%s(id %d, %g)", what, id, (double)w);
    } else {
        v.x = fz_float(r);
        v.y = fz_float(r);
        fz_set_where("%s(id %d, %g %g)", what, id, (double)v.x, (double)v.y);
    }
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    if (angular)
        FZ_CALL3(S, sa, sb, carom_body_set_angular_velocity(w_, id, w));
    else
        FZ_CALL3(S, sa, sb, carom_body_set_velocity(w_, id, v));
    fz_check_id_status(S, id, sa, what);
    if (j >= 0 && S->types[j] == CAROM_BODY_STATIC &&
        (angular ? sa == CAROM_OK : sa != CAROM_ERR_BAD_BODY_TYPE))
        fz_fail("a static body's velocity is refused", "%s on a static body "
                "returned %s", what, carom_status_string(sa));
    if (sa == CAROM_OK) {
        const fz_body_snap *x = &before.b[j], *y;
        if (!fz_finite(v.x) || !fz_finite(v.y) || !fz_finite(w))
            fz_fail("non-finite input refused", "%s returned CAROM_OK", what);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        y = &after.b[j];
        if (angular ? !(y->angvel == w &&
                        fz_bits(y->vel.x) == fz_bits(x->vel.x) &&
                        fz_bits(y->vel.y) == fz_bits(x->vel.y))
                    : !(y->vel.x == v.x && y->vel.y == v.y &&
                        fz_bits(y->angvel) == fz_bits(x->angvel)))
            fz_fail("the velocity set is the velocity read", "%s: velocity "
                    "(%.9g, %.9g) w %.9g -> (%.9g, %.9g) w %.9g", what,
                    (double)x->vel.x, (double)x->vel.y, (double)x->angvel,
                    (double)y->vel.x, (double)y->vel.y, (double)y->angvel);
        if (!angular)
            fz_expect_awake(S, id, what);
        fz_check_others_kept(S, &before, &after, j, FZ_MAY_VELOCITY, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

static void fz_op_set_transform(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = "carom_body_set_transform";
    carom_vec2 p;
    carom_rot q;
    carom_status sa, sb;
    fz_snap before, after;
    p.x = fz_float(r);
    p.y = fz_float(r);
    if (fz_u8(r) & 1u) {
        q.c = fz_float(r);
        q.s = fz_float(r);
    } else {
        q = carom_rot_from_angle(fz_float(r));
    }
    fz_set_where("%s(id %d, position %.9g %.9g, rotation %.9g %.9g)", what,
                 id, (double)p.x, (double)p.y, (double)q.c, (double)q.s);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    FZ_CALL3(S, sa, sb, carom_body_set_transform(w_, id, p, q));
    fz_check_id_status(S, id, sa, what);
    if (sa == CAROM_OK) {
        const fz_body_snap *x = &before.b[j], *y;
        double len = sqrt((double)q.c * (double)q.c + (double)q.s * (double)q.s);
        double tol = 1.0e-5 * (fz_dabs((double)p.x) + fz_dabs((double)p.y) +
                               fz_rec_extent(&S->rec[j])) + 1.0e-30;
        if (!fz_finite(p.x) || !fz_finite(p.y) || !fz_finite(q.c) ||
            !fz_finite(q.s) || (q.c == 0.0f && q.s == 0.0f))
            fz_fail("bad input refused", "%s returned CAROM_OK", what);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        y = &after.b[j];
        fz_expect_near("the pose set is the pose read", "position.x",
                       (double)y->st.position.x, (double)p.x, tol);
        fz_expect_near("the pose set is the pose read", "position.y",
                       (double)y->st.position.y, (double)p.y, tol);
#if CAROM_ENABLE_ROTATION
        fz_expect_near("the pose set is the pose read", "rotation.c",
                       (double)y->st.rotation.c, (double)q.c / len, 1.0e-5);
        fz_expect_near("the pose set is the pose read", "rotation.s",
                       (double)y->st.rotation.s, (double)q.s / len, 1.0e-5);
#else
        (void)len;
#endif
        if (fz_bits(y->vel.x) != fz_bits(x->vel.x) ||
            fz_bits(y->vel.y) != fz_bits(x->vel.y) ||
            fz_bits(y->angvel) != fz_bits(x->angvel))
            fz_fail("a teleport keeps the velocities", "(%.9g, %.9g) w %.9g "
                    "-> (%.9g, %.9g) w %.9g", (double)x->vel.x,
                    (double)x->vel.y, (double)x->angvel, (double)y->vel.x,
                    (double)y->vel.y, (double)y->angvel);
        fz_expect_awake(S, id, what);
        fz_check_others_kept(S, &before, &after, j, FZ_MAY_POSE, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

/* The arguments of an impulse or a one-step force: a scalar (angular
 * impulse, torque) or a vector at a point (`label` names it in messages). */
static void fz_read_push(fz_state *S, fz_reader *r, int j, int scalar, const char *what,
                         const char *label, int id, carom_vec2 *v, carom_vec2 *p,
                         float *s)
{
    v->x = v->y = p->x = p->y = 0.0f;
    *s = 0.0f;
    if (scalar) {
        *s = fz_float(r);
        fz_set_where("%s(id %d, %g)", what, id, (double)*s);
    } else {
        v->x = fz_float(r);
        v->y = fz_float(r);
        *p = fz_read_point(S, r, j);
        fz_set_where("%s(id %d, %s %g %g at %.9g %.9g)", what, id, label, (double)v->x,
                     (double)v->y, (double)p->x, (double)p->y);
    }
}

static void fz_op_impulse(fz_state *S, fz_reader *r, int angular)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = angular ? "carom_body_apply_angular_impulse"
                               : "carom_body_apply_impulse";
    carom_vec2 J, p;
    float L;
    carom_status sa, sb;
    fz_snap before, after;
    fz_read_push(S, r, j, angular, what, "impulse", id, &J, &p, &L);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    if (angular)
        FZ_CALL3(S, sa, sb, carom_body_apply_angular_impulse(w_, id, L));
    else
        FZ_CALL3(S, sa, sb, carom_body_apply_impulse(w_, id, J, p));
    fz_check_id_status(S, id, sa, what);
    if (j >= 0 && S->types[j] != CAROM_BODY_DYNAMIC && sa == CAROM_OK)
        fz_fail("impulses only on dynamic bodies", "%s on a body of type %d "
                "returned CAROM_OK", what, S->types[j]);
    if (sa == CAROM_OK) {
        const fz_body_snap *x = &before.b[j], *y;
        double m = (double)x->mass, I = (double)x->inertia;
        double cx = (double)x->st.center.x, cy = (double)x->st.center.y;
        double jx = (double)J.x, jy = (double)J.y, px = (double)p.x,
               py = (double)p.y, w0 = (double)x->angvel, dw, dwmag;
        if (!fz_finite(J.x) || !fz_finite(J.y) || !fz_finite(p.x) ||
            !fz_finite(p.y) || !fz_finite(L))
            fz_fail("non-finite input refused", "%s returned CAROM_OK", what);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        y = &after.b[j];
        if (angular) {
            dw = (double)L / I;
            dwmag = fz_dabs(dw);
            if (fz_bits(y->vel.x) != fz_bits(x->vel.x) ||
                fz_bits(y->vel.y) != fz_bits(x->vel.y))
                fz_fail("an impulse changes the velocity by impulse / mass",
                        "angular impulse changed the velocity");
        } else {
            double vx = (double)x->vel.x, vy = (double)x->vel.y;
            fz_expect_near("an impulse changes the velocity by impulse / mass",
                           "velocity.x", (double)y->vel.x, vx + jx / m,
                           1.0e-5 * (fz_dabs(vx) + fz_dabs(jx / m)) + 1.0e-37);
            fz_expect_near("an impulse changes the velocity by impulse / mass",
                           "velocity.y", (double)y->vel.y, vy + jy / m,
                           1.0e-5 * (fz_dabs(vy) + fz_dabs(jy / m)) + 1.0e-37);
            dw = ((px - cx) * jy - (py - cy) * jx) / I;
            dwmag = ((fz_dabs(px) + fz_dabs(cx)) * fz_dabs(jy) +
                     (fz_dabs(py) + fz_dabs(cy)) * fz_dabs(jx)) / I;
        }
#if CAROM_ENABLE_ROTATION
        fz_expect_near("an impulse changes the angular velocity by "
                       "(r x impulse) / inertia", "angular_velocity",
                       (double)y->angvel, w0 + dw,
                       1.0e-5 * (fz_dabs(w0) + dwmag) + 1.0e-37);
#else
        (void)w0;
        (void)dw;
        (void)dwmag;
#endif
        if (!angular)
            fz_expect_awake(S, id, what);
        fz_check_others_kept(S, &before, &after, j, FZ_MAY_VELOCITY, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

static void fz_op_once(fz_state *S, fz_reader *r, int torque_only)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = torque_only ? "carom_body_apply_torque"
                                   : "carom_body_apply_force";
    carom_vec2 F, p;
    float T;
    carom_status sa, sb;
    fz_snap before, after;
    fz_read_push(S, r, j, torque_only, what, "force", id, &F, &p, &T);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    if (torque_only)
        FZ_CALL3(S, sa, sb, carom_body_apply_torque(w_, id, T));
    else
        FZ_CALL3(S, sa, sb, carom_body_apply_force(w_, id, F, p));
    if (sa != CAROM_ERR_DISABLED)
        fz_check_id_status(S, id, sa, what);
    if (j >= 0 && S->types[j] != CAROM_BODY_DYNAMIC && sa == CAROM_OK)
        fz_fail("forces only on dynamic bodies", "%s on a body of type %d "
                "returned CAROM_OK", what, S->types[j]);
    if (sa == CAROM_OK) {
        if (!fz_finite(F.x) || !fz_finite(F.y) || !fz_finite(p.x) ||
            !fz_finite(p.y) || !fz_finite(T))
            fz_fail("non-finite input refused", "%s returned CAROM_OK", what);
        S->rec[j].once = 1;
        if (F.x != 0.0f || F.y != 0.0f)
            S->momentum = 0;
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        fz_check_others_kept(S, &before, &after, j, 0u, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

/* Restitution or friction: the same rules as in the definition (carom.h),
 * so the same status as carom_body_def_validate of a default body with
 * that value. */
static void fz_op_material(fz_state *S, fz_reader *r, int friction)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = friction ? "carom_body_set_friction"
                                : "carom_body_set_restitution";
    float x = fz_float(r);
    carom_body_def d = carom_default_body_def();
    carom_status sa, sb, want;
    fz_snap before, after;
    fz_set_where("%s(id %d, %.9g)", what, id, (double)x);
    if (friction)
        d.friction = x;
    else
        d.restitution = x;
    want = carom_body_def_validate(&d);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    if (friction)
        FZ_CALL3(S, sa, sb, carom_body_set_friction(w_, id, x));
    else
        FZ_CALL3(S, sa, sb, carom_body_set_restitution(w_, id, x));
    fz_check_id_status(S, id, sa, what);
    if (j >= 0 && sa != want &&
        !(friction && !CAROM_ENABLE_FRICTION && sa == CAROM_ERR_DISABLED))
        fz_fail("the same rules as in the definition", "%s(%.9g) returned "
                "%s, carom_body_def_validate of that value %s", what,
                (double)x, carom_status_string(sa),
                carom_status_string(want));
    if (sa == CAROM_OK) {
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        fz_check_others_kept(S, &before, &after, j, 0u, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

static void fz_op_user_data(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = "carom_body_set_user_data";
    void *data = fz_user_pointer(fz_u8(r));
    carom_status sa, sb;
    fz_snap before, after;
    fz_set_where("%s(id %d, %p)", what, id, data);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    FZ_CALL3(S, sa, sb, carom_body_set_user_data(w_, id, data));
    fz_check_id_status(S, id, sa, what);
    if (sa == CAROM_OK) {
        if (carom_body_get_user_data(S->W[FZ_A].w, id) != data)
            fz_fail("user data kept", "set %p, got %p", data,
                    carom_body_get_user_data(S->W[FZ_A].w, id));
        S->rec[j].user = data;
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        fz_check_others_kept(S, &before, &after, j, FZ_MAY_USER, what);
    } else if (carom_body_get_user_data(S->W[FZ_A].w, id) !=
               (j >= 0 ? S->rec[j].user : NULL)) {
        fz_fail("user data kept", "after a failed %s: %p", what,
                carom_body_get_user_data(S->W[FZ_A].w, id));
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

static void fz_op_filter(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), j = fz_index_of(S, id);
    const char *what = "carom_body_set_filter";
    uint32_t cat = fz_filter_bits(r), mask = fz_filter_bits(r);
    int group = fz_int(r, -3, 3);
    carom_status sa, sb;
    fz_snap before, after;
    fz_set_where("%s(id %d, category %#lx, mask %#lx, group %d)", what, id,
                 (unsigned long)cat, (unsigned long)mask, group);
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
    FZ_CALL3(S, sa, sb, carom_body_set_filter(w_, id, cat, mask, group));
    if (sa != CAROM_ERR_DISABLED)
        fz_check_id_status(S, id, sa, what);
    if (j >= 0 && sa != CAROM_OK && CAROM_ENABLE_FILTERING)
        fz_fail("set_filter", "%s on a body of the world returned %s", what,
                carom_status_string(sa));
    if (sa == CAROM_OK) {
        S->rec[j].category = cat;
        S->rec[j].mask = mask;
        S->rec[j].group = group;
        fz_expect_awake(S, id, what);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
        fz_check_others_kept(S, &before, &after, j, 0u, what);
    }
    fz_after_call(S, &before, sa, sb, what, 0);
}

/* ---- steps ------------------------------------------------------------------------ */

/*
 * Linear momentum: with zero gravity, no force callback, no sleep, only
 * dynamic bodies and no constant or one-step forces, every impulse carom
 * applies is one of an equal and opposite pair, so sum m v is kept up to
 * rounding.
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

/* Do bodies i and j pass each other's collision filter (carom.h,
 * carom_body_def: category/mask bits, groups as in Box2D)? */
static int fz_filter_pass(const fz_body_rec *a, const fz_body_rec *b)
{
#if CAROM_ENABLE_FILTERING
    if (a->group != 0 && a->group == b->group)
        return a->group > 0;
    return (a->category & b->mask) != 0u && (b->category & a->mask) != 0u;
#else
    (void)a;
    (void)b;
    return 1;
#endif
}

/* Impacts (beyond fz_check_events): between two bodies that collide, so
 * never with a sensor ("exerts and feels no contact impulse"), never
 * between two bodies that are not dynamic, never across the filter. */
static void fz_check_impacts(const fz_state *S)
{
    int count = 0, k;
    const carom_event *ev = carom_world_events(S->W[FZ_A].w, &count);
    for (k = 0; k < count; ++k) {
        int a = fz_index_of(S, ev[k].body_a), b = fz_index_of(S, ev[k].body_b);
        if (a < 0 || b < 0)
            continue; /* fz_check_events reports it */
        if (S->rec[a].sensor || S->rec[b].sensor)
            fz_fail("sensors make no impacts", "impact %d between ids %d and "
                    "%d (sensor %d, %d)", k, ev[k].body_a, ev[k].body_b,
                    S->rec[a].sensor, S->rec[b].sensor);
        if (S->types[a] != CAROM_BODY_DYNAMIC &&
            S->types[b] != CAROM_BODY_DYNAMIC)
            fz_fail("impacts involve a dynamic body", "impact %d between "
                    "ids %d and %d (types %d, %d)", k, ev[k].body_a,
                    ev[k].body_b, S->types[a], S->types[b]);
        if (!fz_filter_pass(&S->rec[a], &S->rec[b]))
            fz_fail("filtered bodies do not collide", "impact %d between ids "
                    "%d (category %#lx mask %#lx group %d) and %d (category "
                    "%#lx mask %#lx group %d)", k, ev[k].body_a,
                    (unsigned long)S->rec[a].category,
                    (unsigned long)S->rec[a].mask, S->rec[a].group,
                    ev[k].body_b, (unsigned long)S->rec[b].category,
                    (unsigned long)S->rec[b].mask, S->rec[b].group);
    }
}

static int fz_touching_at(const fz_state *S, int a, int b)
{
    int k;
    for (k = 0; k < S->n_touching; ++k)
        if ((S->touching[k][0] == a && S->touching[k][1] == b) ||
            (S->touching[k][0] == b && S->touching[k][1] == a))
            return k;
    return -1;
}

/*
 * Touch events of a step that returned CAROM_OK (carom.h,
 * carom_touch_event): at most max_touch_events, bodies of the world with
 * body_a's slot first, begin and sensor 0 or 1, sensor set exactly when
 * one of the two is a sensor, never two sensors. While none was dropped,
 * the events pair up: a pair begins touching only when it was not
 * touching, ends only when it was (removal ends touches silently).
 */
static void fz_check_touch_events(fz_state *S)
{
    int count = -1, k;
    const carom_touch_event *te = carom_world_touch_events(S->W[FZ_A].w,
                                                           &count);
    int dropped = carom_world_touch_events_dropped(S->W[FZ_A].w);
    if (count < 0 || (count > 0 && !te) || count > S->max_touch_events ||
        dropped < 0)
        fz_fail("touch event list", "%d touch events (capacity %d), %d "
                "dropped", count, S->max_touch_events, dropped);
    if (dropped > 0)
        S->touch_known = 0;
    for (k = 0; k < count; ++k) {
        const carom_touch_event *e = &te[k];
        int a = fz_index_of(S, e->body_a), b = fz_index_of(S, e->body_b);
        int sensor;
        if (a < 0 || b < 0 ||
            !((e->body_a & FZ_SLOT_MASK) < (e->body_b & FZ_SLOT_MASK)))
        {
            fz_fail("touch event body ids", "touch event %d: body_a %d, "
                    "body_b %d (not two bodies of the world with body_a's "
                    "slot first)", k, e->body_a, e->body_b);
            if (a < 0 || b < 0)
                continue; /* (CAROM_FUZZ_IGNORE) */
        }
        if (fz_trace)
            fprintf(stderr, "carom-fuzz:   touch %s: ids %d, %d%s\n",
                    e->begin ? "begins" : "ends", e->body_a, e->body_b,
                    e->sensor ? " (sensor)" : "");
        sensor = S->rec[a].sensor || S->rec[b].sensor;
        if ((e->begin != 0 && e->begin != 1) ||
            (e->sensor != 0 && e->sensor != 1) || e->sensor != sensor ||
            (S->rec[a].sensor && S->rec[b].sensor))
            fz_fail("touch event fields", "touch event %d (ids %d, %d): "
                    "begin %d, sensor %d; the bodies' sensor flags %d, %d",
                    k, e->body_a, e->body_b, e->begin, e->sensor,
                    S->rec[a].sensor, S->rec[b].sensor);
        if (!S->touch_known)
            continue;
        {
            int at = fz_touching_at(S, e->body_a, e->body_b);
            if (e->begin && at >= 0)
                fz_fail("touch events pair up", "touch event %d: ids %d and "
                        "%d begin touching, but they began before and never "
                        "ended", k, e->body_a, e->body_b);
            if (!e->begin && at < 0)
                fz_fail("touch events pair up", "touch event %d: ids %d and "
                        "%d end touching, but they were not touching", k,
                        e->body_a, e->body_b);
            if (e->begin && S->n_touching < FZ_MAX_TOUCHING) {
                S->touching[S->n_touching][0] = e->body_a;
                S->touching[S->n_touching][1] = e->body_b;
                ++S->n_touching;
            } else if (!e->begin && at >= 0) {
                S->touching[at][0] = S->touching[S->n_touching - 1][0];
                S->touching[at][1] = S->touching[S->n_touching - 1][1];
                --S->n_touching;
            }
        }
    }
}

/* Did body i move in this step: dynamic and awake before or after it, or
 * kinematic with a velocity (a kinematic body at rest pairs like a static
 * one: src/body.c, cr_body_moves)? */
static int fz_moved(const fz_state *S, const fz_snap *before,
                    const fz_snap *after, int i)
{
    const carom_body_state *x = &before->b[i].st;
    if (S->types[i] == CAROM_BODY_DYNAMIC)
        return before->b[i].awake || after->b[i].awake;
    return S->types[i] == CAROM_BODY_KINEMATIC &&
           (x->velocity.x != 0.0f || x->velocity.y != 0.0f ||
            x->angular_velocity != 0.0f);
}

/*
 * A sensor's touches are its overlaps (carom.h, carom_body_def.is_sensor;
 * src/touch.c: at the end of the step). Checked for pairs the step looked
 * at -- one of the two moved in it -- whose filter lets them meet, when no
 * touch event was dropped: clearly overlapping means touching, clearly
 * apart means not. (Overlaps between bodies that never move are never
 * reported; the header does not say, so that is not checked.)
 */
static void fz_check_sensor_overlaps(const fz_state *S, const fz_snap *before,
                                     const fz_snap *after)
{
    int i, j;
    if (!S->touch_known || !CAROM_ENABLE_SENSORS)
        return;
    for (i = 0; i < S->n; ++i) {
        if (!S->rec[i].sensor)
            continue;
        for (j = 0; j < S->n; ++j) {
            fz_geom gi, gj;
            double sep, tol;
            int touching;
            if (S->rec[j].sensor || !fz_filter_pass(&S->rec[i], &S->rec[j]))
                continue;
            if (!fz_moved(S, before, after, i) &&
                !fz_moved(S, before, after, j))
                continue;
            fz_geom_of(&S->rec[i], &after->b[i].st, &gi);
            fz_geom_of(&S->rec[j], &after->b[j].st, &gj);
            sep = fz_shape_sep(&gi, &gj);
            tol = FZ_GEOM_TOL * (gi.scale + gj.scale) + 1.0e-30;
            touching = fz_touching_at(S, S->ids[i], S->ids[j]) >= 0;
            if ((sep < -tol && !touching) || (sep > tol && touching))
                fz_fail("a sensor's touches are its overlaps", "sensor id %d "
                        "(type %d, awake %d -> %d, centre %.9g %.9g) and id "
                        "%d (type %d, awake %d -> %d, centre %.9g %.9g): "
                        "separation %.9g (tolerance %.3g), touching by the "
                        "events: %d", S->ids[i], S->types[i],
                        before->b[i].awake, after->b[i].awake,
                        (double)after->b[i].st.center.x,
                        (double)after->b[i].st.center.y, S->ids[j],
                        S->types[j], before->b[j].awake, after->b[j].awake,
                        (double)after->b[j].st.center.x,
                        (double)after->b[j].st.center.y, sep, tol,
                        touching);
        }
    }
}

/* A dynamic sensor feels no contact impulse: with no force but gravity
 * acting, one step changes its velocity by gravity x dt. */
static void fz_check_sensor_flight(const fz_state *S, const fz_snap *before,
                                   const fz_snap *after, const int *once)
{
    double gx = (double)S->def.gravity.x * (double)S->def.dt;
    double gy = (double)S->def.gravity.y * (double)S->def.dt;
    int i;
    if (S->callback || !CAROM_ENABLE_SENSORS)
        return;
    for (i = 0; i < S->n; ++i) {
        const carom_body_state *x = &before->b[i].st, *y = &after->b[i].st;
        double vx = (double)x->velocity.x, vy = (double)x->velocity.y;
        if (!S->rec[i].sensor || S->types[i] != CAROM_BODY_DYNAMIC ||
            S->rec[i].forced || once[i] || !before->b[i].awake ||
            !after->b[i].awake)
            continue;
        fz_expect_near("a sensor feels no contact impulse", "velocity.x",
                       (double)y->velocity.x, vx + gx,
                       1.0e-5 * (fz_dabs(vx) + fz_dabs(gx)) + 1.0e-30);
        fz_expect_near("a sensor feels no contact impulse", "velocity.y",
                       (double)y->velocity.y, vy + gy,
                       1.0e-5 * (fz_dabs(vy) + fz_dabs(gy)) + 1.0e-30);
        fz_expect_near("a sensor feels no contact impulse", "angular_velocity",
                       (double)y->angular_velocity,
                       (double)x->angular_velocity,
                       1.0e-5 * fz_dabs((double)x->angular_velocity) + 1.0e-30);
    }
}

static void fz_op_steps(fz_state *S, fz_reader *r)
{
    int count = 1 + (int)(fz_u8(r) & 7u), k, i;
    for (k = 0; k < count && S->steps_left > 0; ++k) {
        fz_snap before;
        carom_status sa, sb, sc;
        float t0;
        int once[FZ_MAX_BODIES];
        --S->steps_left;
        fz_set_where("carom_world_step #%ld (method %s, %d bodies, callback "
                     "mode %d)", carom_world_step_count(S->W[FZ_A].w) + 1,
                     carom_method_name(carom_world_get_method(S->W[FZ_A].w)),
                     S->n, S->callback ? S->params.mode : -1);
        fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &before);
        for (i = 0; i < S->n; ++i)
            once[i] = S->rec[i].once;
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
            fz_check_impacts(S);
            fz_check_touch_events(S);
            {
                fz_snap after;
                fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &after);
                fz_check_motion(&before, &after, S->types, S->def.dt,
                                S->def.sleep_time);
                fz_check_momentum(S, &before, &after);
                fz_check_sensor_overlaps(S, &before, &after);
                fz_check_sensor_flight(S, &before, &after, once);
            }
            for (i = 0; i < S->n; ++i)
                S->rec[i].once = 0; /* one-step forces acted */
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
        fz_after_call(S, &before, sa, sb, "carom_world_step", 1);
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

/* ---- reading ------------------------------------------------------------------------ */

static void fz_op_read(fz_state *S, fz_reader *r)
{
    int id = fz_pick_id(S, r), valid = fz_is_id(S, id), k;
    float angle = fz_float(r);
    carom_body_state st;
    carom_tolerances tol;
    carom_body_type type;
    carom_vec2 v;
    float m, I, w;
    carom_status a, b, c, d, e, f;
    carom_rot q;
    void *user;

    fz_set_where("reads on id %d, angle %g", id, (double)angle);
    a = carom_body_get_state(S->W[FZ_A].w, id, &st);
    b = carom_body_get_mass(S->W[FZ_A].w, id, &m, &I);
    c = carom_body_get_mass(S->W[FZ_A].w, id, NULL, NULL);
    d = carom_body_get_type(S->W[FZ_A].w, id, &type);
    e = carom_body_get_velocity(S->W[FZ_A].w, id, &v, NULL);
    f = carom_body_get_velocity(S->W[FZ_A].w, id, NULL, &w);
    k = carom_body_is_awake(S->W[FZ_A].w, id);
    user = carom_body_get_user_data(S->W[FZ_A].w, id);
    fz_check_id_status(S, id, a, "carom_body_get_state");
    fz_check_id_status(S, id, b, "carom_body_get_mass");
    fz_check_id_status(S, id, c, "carom_body_get_mass (NULL outputs)");
    fz_check_id_status(S, id, d, "carom_body_get_type");
    fz_check_id_status(S, id, e, "carom_body_get_velocity");
    fz_check_id_status(S, id, f, "carom_body_get_velocity");
    if ((a == CAROM_OK) != valid || (b == CAROM_OK) != valid ||
        (c == CAROM_OK) != valid || (d == CAROM_OK) != valid ||
        (e == CAROM_OK) != valid || (f == CAROM_OK) != valid ||
        (!valid && k != 0) || carom_body_is_valid(S->W[FZ_A].w, id) != valid ||
        (!valid && user != NULL))
        fz_fail("bad ids refused, good ids accepted", "id %d (%s): "
                "get_state %s, get_mass %s, get_type %s, get_velocity %s, "
                "is_awake %d, is_valid %d, user data %p", id,
                valid ? "a body" : "no body", carom_status_string(a),
                carom_status_string(b), carom_status_string(d),
                carom_status_string(e), k,
                carom_body_is_valid(S->W[FZ_A].w, id), user);
    if (carom_body_get_state(S->W[FZ_A].w, id, NULL) != CAROM_ERR_NULL ||
        carom_body_get_type(S->W[FZ_A].w, id, NULL) != CAROM_ERR_NULL)
        fz_fail("NULL refused", "get_state / get_type with a NULL output");
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

/* ---- queries ------------------------------------------------------------------------ */

/* What a query's callback saw. */
typedef struct fz_found {
    int ids[FZ_MAX_FOUND];
    int count;
    int stop_after;  /* return 0 at this call (0: never) */
    int stopped;
    int after_stop;  /* called again after returning 0 */
} fz_found;

static int fz_query_fn(void *ctx, int body)
{
    fz_found *f = (fz_found *)ctx;
    if (f->stopped) {
        f->after_stop = 1;
        return 0;
    }
    if (f->count < FZ_MAX_FOUND)
        f->ids[f->count] = body;
    ++f->count;
    if (f->stop_after > 0 && f->count >= f->stop_after) {
        f->stopped = 1;
        return 0;
    }
    return 1;
}

/* The bodies a query reported: of the world, each once, the callback
 * obeyed, the same in worlds A and B. */
static void fz_check_found(const fz_state *S, const fz_found *fa,
                           const fz_found *fb, const char *what)
{
    int k, l;
    if (fa->after_stop)
        fz_fail("a query stops when its callback returns 0", "%s called the "
                "callback again", what);
    if (fa->count > FZ_MAX_FOUND)
        fz_fail("a query reports each body once", "%s reported %d bodies of "
                "%d", what, fa->count, S->n);
    if (fa->count != fb->count ||
        memcmp(fa->ids, fb->ids, (size_t)fa->count * sizeof fa->ids[0]) != 0)
        fz_fail("determinism", "%s: %d bodies in world A, %d in world B (or "
                "others)", what, fa->count, fb->count);
    for (k = 0; k < fa->count; ++k) {
        if (!fz_is_id(S, fa->ids[k]))
            fz_fail("query results are bodies of the world", "%s reported id "
                    "%d", what, fa->ids[k]);
        for (l = 0; l < k; ++l)
            if (fa->ids[l] == fa->ids[k])
                fz_fail("a query reports each body once", "%s reported id %d "
                        "twice", what, fa->ids[k]);
    }
}

static int fz_found_has(const fz_found *f, int id)
{
    int k;
    for (k = 0; k < f->count && k < FZ_MAX_FOUND; ++k)
        if (f->ids[k] == id)
            return 1;
    return 0;
}

/* A point from the input: a body's centre plus an offset (mode bit), else
 * raw. */
static carom_vec2 fz_query_point(const fz_state *S, const fz_snap *s,
                                 fz_reader *r, int relative)
{
    carom_vec2 p;
    unsigned b = relative ? fz_u8(r) : 0u;
    p.x = fz_float(r);
    p.y = fz_float(r);
    if (relative && S->n > 0) {
        const carom_body_state *st = &s->b[b % (unsigned)S->n].st;
        p.x += st->center.x;
        p.y += st->center.y;
    }
    return p;
}

static int fz_vec_finite(carom_vec2 v) { return fz_finite(v.x) && fz_finite(v.y); }

/* Beyond carom's documented range of lengths (a query may refuse it with
 * CAROM_ERR_OUT_OF_RANGE). */
static int fz_vec_huge(carom_vec2 v)
{
    return !(fz_abs(v.x) <= CAROM_LIMIT_MAX_LENGTH &&
             fz_abs(v.y) <= CAROM_LIMIT_MAX_LENGTH);
}

/* query_box / query_point (kind 0 / 1): mode bit 0: around a body; bit 1:
 * a NULL callback; bits 2..4: stop after that many bodies. */
static void fz_op_query_area(fz_state *S, fz_reader *r, int point)
{
    unsigned mode = fz_u8(r);
    const char *what = point ? "carom_world_query_point"
                             : "carom_world_query_box";
    carom_vec2 lo, hi;
    fz_snap s;
    fz_found fa, fb;
    carom_query_fn fn = (mode & 2u) ? NULL : fz_query_fn;
    carom_status sa, sb;
    int finite, i;
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &s);
    lo = fz_query_point(S, &s, r, (int)(mode & 1u));
    hi = lo;
    if (!point) {
        carom_vec2 h;
        h.x = fz_float(r);
        h.y = fz_float(r);
        if (mode & 1u) { /* centre and half extents */
            lo.x -= h.x;
            lo.y -= h.y;
            hi.x += h.x;
            hi.y += h.y;
        } else {
            hi = h;
        }
    }
    memset(&fa, 0, sizeof fa);
    fa.stop_after = (int)((mode >> 2) & 7u);
    fb = fa;
    finite = fz_vec_finite(lo) && fz_vec_finite(hi);
    fz_set_where("%s([%.9g, %.9g] - [%.9g, %.9g], fn %s, stop after %d)",
                 what, (double)lo.x, (double)lo.y, (double)hi.x, (double)hi.y,
                 fn ? "set" : "NULL", fa.stop_after);
    if (point) {
        sa = carom_world_query_point(S->W[FZ_A].w, lo, fn, &fa);
        sb = carom_world_query_point(S->W[FZ_B].w, lo, fn, &fb);
    } else {
        sa = carom_world_query_box(S->W[FZ_A].w, lo, hi, fn, &fa);
        sb = carom_world_query_box(S->W[FZ_B].w, lo, hi, fn, &fb);
    }
    fz_check_status_named(sa, what);
    if (sa != sb)
        fz_fail("determinism", "%s: %s in world A, %s in world B", what,
                carom_status_string(sa), carom_status_string(sb));
    if (!CAROM_ENABLE_QUERIES) {
        if (sa != CAROM_ERR_DISABLED)
            fz_fail("capability compiled out", "%s returned %s", what,
                    carom_status_string(sa));
        return;
    }
    if (sa != (!fn ? CAROM_ERR_NULL
                   : !finite ? CAROM_ERR_NOT_FINITE : CAROM_OK) &&
        !(fn && finite && sa == CAROM_ERR_OUT_OF_RANGE &&
          (fz_vec_huge(lo) || fz_vec_huge(hi))))
        fz_fail("query status", "%s returned %s (callback %s, input %s)",
                what, carom_status_string(sa), fn ? "set" : "NULL",
                finite ? "finite" : "not finite");
    if (sa != CAROM_OK) {
        if (fa.count != 0)
            fz_fail("a failed query reports nothing", "%s returned %s after "
                    "reporting %d bodies", what, carom_status_string(sa),
                    fa.count);
        return;
    }
    fz_check_found(S, &fa, &fb, what);
    if (fz_trace)
        fprintf(stderr, "carom-fuzz:   -> %d bodies%s\n", fa.count,
                fa.stopped ? " (stopped)" : "");
    if (!point && (lo.x > hi.x || lo.y > hi.y))
        return; /* the header says nothing of an inverted box */
    for (i = 0; i < S->n; ++i) {
        fz_geom g, box;
        double sep, tol;
        int found = fz_found_has(&fa, S->ids[i]);
        fz_geom_of(&S->rec[i], &s.b[i].st, &g);
        if (point) {
            fz_d2 p = fz_d2_of(lo);
            sep = fz_point_sep(&g, p);
            tol = FZ_GEOM_TOL * (g.scale + fz_dabs(p.x) + fz_dabs(p.y)) +
                  1.0e-30;
        } else {
            fz_geom_box((double)lo.x, (double)lo.y, (double)hi.x,
                        (double)hi.y, &box);
            sep = fz_shape_sep(&g, &box);
            tol = FZ_GEOM_TOL * (g.scale + box.scale) + 1.0e-30;
        }
        if (found && sep > tol)
            fz_fail("query results overlap the query", "%s reported id %d at "
                    "separation %.9g (tolerance %.3g)", what, S->ids[i], sep,
                    tol);
        if (!found && !fa.stopped && sep < -tol)
            fz_fail("a query finds every body", "%s missed id %d, overlapping "
                    "by %.9g (tolerance %.3g)", what, S->ids[i], -sep, tol);
    }
}

/* How a segment meets body i: 2 clearly hits it (starts outside, passes
 * inside), 0 clearly misses it (passes outside, or starts inside), 1 in
 * between; *t: where it enters the shape. */
static int fz_ray_meets(const fz_geom *g, fz_d2 p0, fz_d2 d, double tol,
                        double *t)
{
    double t0, t1, start = fz_point_sep(g, p0);
    *t = 0;
    if (start < -tol || !fz_clip(g, p0, d, tol, &t0, &t1))
        return 0;
    if (fz_clip(g, p0, d, 0.0, &t0, &t1))
        *t = t0;
    if (start > tol && fz_clip(g, p0, d, -tol, &t0, &t1))
        return 2;
    return 1;
}

/* A ray hit of body index j: a proper point of entry. */
static void fz_check_hit(const fz_state *S, const fz_snap *s,
                         const carom_ray_hit *h, carom_vec2 from,
                         carom_vec2 to, const char *what)
{
    int j = fz_index_of(S, h->body);
    fz_geom g;
    fz_d2 p0 = fz_d2_of(from), d = fz_sub(fz_d2_of(to), p0), at;
    double tol, t, nn;
    if (j < 0) {
        fz_fail("query results are bodies of the world", "%s hit id %d",
                what, h->body);
        return;
    }
    fz_geom_of(&S->rec[j], &s->b[j].st, &g);
    tol = FZ_GEOM_TOL * (g.scale + fz_dabs(p0.x) + fz_dabs(p0.y) +
                         fz_dabs((double)to.x) + fz_dabs((double)to.y)) +
          1.0e-30;
    nn = (double)h->normal.x * (double)h->normal.x +
         (double)h->normal.y * (double)h->normal.y;
    if (!fz_finite(h->fraction) || !(h->fraction >= 0.0f) ||
        !(h->fraction <= 1.0f) || !fz_finite(h->point.x) ||
        !fz_finite(h->point.y) || !(fz_dabs(nn - 1) <= 1.0e-3)) {
        fz_fail("ray hit fields", "%s: id %d fraction %.9g point (%.9g, "
                "%.9g) normal (%.9g, %.9g)", what, h->body,
                (double)h->fraction, (double)h->point.x, (double)h->point.y,
                (double)h->normal.x, (double)h->normal.y);
        if (!fz_finite(h->fraction) || !fz_finite(h->point.x) ||
            !fz_finite(h->point.y))
            return; /* (CAROM_FUZZ_IGNORE: nothing more to check) */
    }
    at.x = p0.x + (double)h->fraction * d.x;
    at.y = p0.y + (double)h->fraction * d.y;
    if (!(fz_len(fz_sub(at, fz_d2_of(h->point))) <= tol))
        fz_fail("ray hit fields", "%s: id %d: point (%.9g, %.9g) is not "
                "from + fraction (to - from) = (%.9g, %.9g)", what, h->body,
                (double)h->point.x, (double)h->point.y, at.x, at.y);
    if (!(fz_dabs(fz_point_sep(&g, fz_d2_of(h->point))) <= tol))
        fz_fail("ray hits are on the shape", "%s: id %d hit at (%.9g, %.9g),"
                " %.9g from its boundary (tolerance %.3g)", what, h->body,
                (double)h->point.x, (double)h->point.y,
                fz_point_sep(&g, fz_d2_of(h->point)), tol);
    if (!(fz_dot(fz_d2_of(h->normal), d) <= 1.0e-3 * fz_len(d)))
        fz_fail("ray hits enter the shape", "%s: id %d: normal (%.9g, %.9g) "
                "along the ray", what, h->body, (double)h->normal.x,
                (double)h->normal.y);
    if (fz_ray_meets(&g, p0, d, tol, &t) == 0)
        fz_fail("ray hits are on the shape", "%s: id %d hit at fraction "
                "%.9g, but the segment misses it or starts inside it "
                "(start separation %.9g, tolerance %.3g)", what, h->body,
                (double)h->fraction, fz_point_sep(&g, p0), tol);
}

/* Every body the segment clearly enters before distance `limit` along it
 * (in world units; a huge limit: every one) is among the hits. Returns
 * how many bodies it clearly enters; *maybe gets how many it may enter. */
static int fz_ray_expect(const fz_state *S, const fz_snap *s, carom_vec2 from,
                         carom_vec2 to, const carom_ray_hit *hits, int n_hits,
                         double limit, int *maybe, const char *what)
{
    fz_d2 p0 = fz_d2_of(from), d = fz_sub(fz_d2_of(to), p0);
    double len = fz_len(d);
    int i, k, sure = 0;
    *maybe = 0;
    for (i = 0; i < S->n; ++i) {
        fz_geom g;
        double tol, t;
        int m, found = 0;
        fz_geom_of(&S->rec[i], &s->b[i].st, &g);
        tol = FZ_GEOM_TOL * (g.scale + fz_dabs(p0.x) + fz_dabs(p0.y) +
                             fz_dabs((double)to.x) + fz_dabs((double)to.y)) +
              1.0e-30;
        m = fz_ray_meets(&g, p0, d, tol, &t);
        if (m > 0)
            ++*maybe;
        if (m < 2)
            continue;
        ++sure;
        for (k = 0; k < n_hits; ++k)
            if (hits[k].body == S->ids[i])
                found = 1;
        if (!found && t * len < limit - 2 * tol)
            fz_fail("a ray cast finds the nearest shapes", "%s missed id %d, "
                    "entered at fraction %.9g (distance %.9g, the hits kept "
                    "reach %.9g)", what, S->ids[i], t, t * len, limit);
    }
    return sure;
}

/* raycast (all = 0) or raycast_all: mode bit 0: from near a body; bit 1:
 * to near a body; bit 2: hits NULL (raycast_all); then the capacity. */
static void fz_op_raycast(fz_state *S, fz_reader *r, int all)
{
    static const int edge[16] = {-1, INT_MIN, 0, 1, 64, 65, 2, 3,
                                 -2, 4, 5, 6, 7, 8, 1000, INT_MAX};
    unsigned mode = fz_u8(r), cb;
    const char *what = all ? "carom_world_raycast_all" : "carom_world_raycast";
    carom_vec2 from, to;
    fz_snap s;
    carom_ray_hit *ha = NULL, *hb = NULL, one_a, one_b;
    int cap = 1, na = -7, nb = -7, finite, k, use_null;
    carom_status sa, sb;
    fz_snap_take(S->W[FZ_A].w, S->ids, S->n, &s);
    from = fz_query_point(S, &s, r, (int)(mode & 1u));
    to = fz_query_point(S, &s, r, (int)(mode & 2u));
    cb = fz_u8(r);
    if (all)
        cap = cb < 0xF0u ? (int)(cb % 6u) : edge[cb - 0xF0u];
    use_null = all && (mode & 4u);
    finite = fz_vec_finite(from) && fz_vec_finite(to);
    fz_set_where("%s(%.9g %.9g -> %.9g %.9g, capacity %d%s)", what,
                 (double)from.x, (double)from.y, (double)to.x, (double)to.y,
                 cap, use_null ? ", hits NULL" : "");
    if (all && !use_null && cap > 0 && cap <= 64) {
        /* exactly cap entries: a write past them is an ASan report */
        ha = (carom_ray_hit *)malloc((size_t)cap * sizeof *ha);
        hb = (carom_ray_hit *)malloc((size_t)cap * sizeof *hb);
        if (!ha || !hb)
            abort();
    } else if (!use_null) {
        ha = &one_a;
        hb = &one_b;
        if (all && cap > 1)
            cap = 0; /* (a huge capacity with a one-entry buffer would be
                        the harness's own overflow) */
    }
    if (all) {
        sa = carom_world_raycast_all(S->W[FZ_A].w, from, to, ha, cap, &na);
        sb = carom_world_raycast_all(S->W[FZ_B].w, from, to, hb, cap, &nb);
    } else {
        sa = carom_world_raycast(S->W[FZ_A].w, from, to, ha, &na);
        sb = carom_world_raycast(S->W[FZ_B].w, from, to, hb, &nb);
    }
    fz_check_status_named(sa, what);
    if (sa != sb)
        fz_fail("determinism", "%s: %s in world A, %s in world B", what,
                carom_status_string(sa), carom_status_string(sb));
    if (!CAROM_ENABLE_QUERIES) {
        if (sa != CAROM_ERR_DISABLED)
            fz_fail("capability compiled out", "%s returned %s", what,
                    carom_status_string(sa));
        goto done;
    }
    if (all && (cap < 0 || (use_null && cap > 0))) {
        if (sa == CAROM_OK)
            fz_fail("bad capacity refused", "%s with capacity %d%s returned "
                    "CAROM_OK", what, cap, use_null ? " and NULL hits" : "");
        goto done;
    }
    if (sa != (finite ? CAROM_OK : CAROM_ERR_NOT_FINITE) &&
        !(finite && sa == CAROM_ERR_OUT_OF_RANGE &&
          (fz_vec_huge(from) || fz_vec_huge(to))))
        fz_fail("query status", "%s returned %s (input %s)", what,
                carom_status_string(sa), finite ? "finite" : "not finite");
    if (sa != CAROM_OK)
        goto done;
    if (na != nb || (all ? na < 0 : (na != 0 && na != 1)))
        fz_fail(na != nb ? "determinism" : "ray hit count", "%s: %d hits in "
                "world A, %d in world B", what, na, nb);
    {
        int stored = na < cap ? na : cap, maybe = 0, sure;
        fz_d2 d = fz_sub(fz_d2_of(to), fz_d2_of(from));
        double limit = 1e300;
        if (!all)
            stored = na;
        if (fz_trace)
            fprintf(stderr, "carom-fuzz:   -> %d hits (first: id %d at "
                    "%.9g)\n", na, stored > 0 ? ha[0].body : -1,
                    stored > 0 ? (double)ha[0].fraction : -1.0);
        for (k = 0; k < stored; ++k) {
            if (memcmp(&ha[k], &hb[k], sizeof ha[k]) != 0)
                fz_fail("determinism", "%s: hit %d differs in worlds A and B",
                        what, k);
            fz_check_hit(S, &s, &ha[k], from, to, what);
            if (k > 0 && !(ha[k - 1].fraction <= ha[k].fraction))
                fz_fail("ray hits nearest first", "%s: hit %d at %.9g after "
                        "hit %d at %.9g", what, k, (double)ha[k].fraction,
                        k - 1, (double)ha[k - 1].fraction);
            {
                int l;
                for (l = 0; l < k; ++l)
                    if (ha[l].body == ha[k].body)
                        fz_fail("a query reports each body once", "%s: id %d "
                                "hit twice", what, ha[k].body);
            }
        }
        /* the hits kept reach this far; every body entered before is kept */
        if ((all && na > cap) || (!all && na == 1))
            limit = stored > 0 ? (double)ha[stored - 1].fraction * fz_len(d)
                               : -1e300;
        sure = fz_ray_expect(S, &s, from, to, ha, stored, limit, &maybe,
                             what);
        if (all && (na < sure || na > maybe))
            fz_fail("a ray cast counts every shape it enters", "%s counted "
                    "%d, but it surely enters %d and may enter %d", what, na,
                    sure, maybe);
        if (!all && (na == 0) != (sure == 0) && sure > 0)
            fz_fail("a ray cast finds the nearest shapes", "%s found nothing"
                    ", but the segment surely enters %d shapes", what, sure);
        if (all) {
            /* raycast agrees with raycast_all */
            carom_ray_hit h;
            int found = -1;
            if (carom_world_raycast(S->W[FZ_A].w, from, to, &h, &found) !=
                    CAROM_OK ||
                found != (na > 0) ||
                (found && stored > 0 &&
                 fz_bits(h.fraction) != fz_bits(ha[0].fraction)))
                fz_fail("raycast agrees with raycast_all", "raycast found %d "
                        "(fraction %.9g), raycast_all %d hits (first at "
                        "%.9g)", found, (double)h.fraction, na,
                        stored > 0 ? (double)ha[0].fraction : -1.0);
        }
    }
done:
    if (ha != &one_a) {
        free(ha);
        free(hb);
    }
}

/* ---- names, version, profiling, NULL arguments ------------------------------------ */

static void fz_op_misc(fz_state *S, fz_reader *r)
{
    unsigned b = fz_u8(r), k;
    char name[17];
    carom_method m = CAROM_METHOD_COUNT;
    carom_status st;
    carom_op_weights wt;
    carom_profile prof;
    static const char *const presets[5] = {"seed", "cortex-m4f", "cortex-m0",
                                           "", "cortex"};
    const char *s;
    int id = -1;

    /* a name from the input (one of the methods' if the byte says so) */
    for (k = 0; k < 16; ++k)
        name[k] = (char)fz_u8(r);
    name[16] = '\0';
    if (b & 1u)
        snprintf(name, sizeof name, "%s",
                 carom_method_name((carom_method)(int)(b >> 1 & 3u)));
    fz_set_where("names, version, profiling, NULL arguments (byte %#x, name "
                 "\"%s\")", b, name);
    for (k = 0; k < (unsigned)CAROM_STATUS_COUNT; ++k)
        fz_check_status_named((carom_status)k, "carom_status_string");
    s = carom_status_string((carom_status)(int)(b + CAROM_STATUS_COUNT));
    if (!s)
        fz_fail("named status", "carom_status_string of %u is NULL",
                b + (unsigned)CAROM_STATUS_COUNT);
    s = carom_version();
    if (!s || !*s)
        fz_fail("version", "carom_version() is empty");
    st = carom_method_from_name(name, &m);
    fz_check_status_named(st, "carom_method_from_name");
    if (st == CAROM_OK ? strcmp(carom_method_name(m), name) != 0
                       : st != CAROM_ERR_BAD_METHOD)
        fz_fail("method names", "carom_method_from_name(\"%s\") = %s, %d "
                "(\"%s\")", name, carom_status_string(st), (int)m,
                st == CAROM_OK ? carom_method_name(m) : "");
    for (k = 0; k < (unsigned)CAROM_METHOD_COUNT; ++k)
        if (carom_method_from_name(carom_method_name((carom_method)k), &m) !=
                CAROM_OK ||
            (unsigned)m != k)
            fz_fail("method names", "method %u does not come back from its "
                    "name \"%s\"", k, carom_method_name((carom_method)k));
    if (!carom_method_name((carom_method)(int)b))
        fz_fail("method names", "carom_method_name(%u) is NULL", b);
    if (carom_method_from_name(NULL, &m) != CAROM_ERR_NULL ||
        carom_method_from_name(name, NULL) != CAROM_ERR_NULL)
        fz_fail("NULL refused", "carom_method_from_name with NULL");
    for (k = 0; k < (unsigned)CAROM_OP_COUNT; ++k)
        if (!carom_op_name((carom_op)k) || !*carom_op_name((carom_op)k))
            fz_fail("profile names", "carom_op_name(%u)", k);
    for (k = 0; k < (unsigned)CAROM_PHASE_COUNT; ++k)
        if (!carom_phase_name((carom_phase)k) ||
            !*carom_phase_name((carom_phase)k))
            fz_fail("profile names", "carom_phase_name(%u)", k);
    if (!carom_op_name((carom_op)(int)b) ||
        !carom_phase_name((carom_phase)(int)b))
        fz_fail("profile names", "a name of %u is NULL", b);
    /* profiling: presets, a zero profile costs 0, attach and detach */
    st = carom_op_weights_preset(presets[b % 5u], &wt);
    fz_check_status_named(st, "carom_op_weights_preset");
    if ((st == CAROM_OK) != (b % 5u < 3u))
        fz_fail("profile presets", "carom_op_weights_preset(\"%s\") = %s",
                presets[b % 5u], carom_status_string(st));
    if (carom_op_weights_preset(NULL, &wt) != CAROM_ERR_NULL ||
        carom_op_weights_preset("seed", NULL) != CAROM_ERR_NULL)
        fz_fail("NULL refused", "carom_op_weights_preset with NULL");
    if (carom_op_weights_preset("seed", &wt) == CAROM_OK) {
        for (k = 0; k < (unsigned)CAROM_OP_COUNT; ++k)
            if (!fz_finite(wt.w[k]) || !(wt.w[k] > 0.0f))
                fz_fail("profile presets", "weight %u is %g", k,
                        (double)wt.w[k]);
        carom_profile_reset(&prof);
        for (k = 0; k <= (unsigned)CAROM_PHASE_COUNT + 1u; ++k)
            if (fz_bits(carom_profile_cost(&prof, &wt, (int)k)) != 0u)
                fz_fail("profile cost", "a reset profile costs %g in phase "
                        "%u", (double)carom_profile_cost(&prof, &wt, (int)k),
                        k);
        if (fz_bits(carom_profile_cost(NULL, &wt, 0)) != 0u ||
            fz_bits(carom_profile_cost(&prof, NULL, 0)) != 0u ||
            fz_bits(carom_profile_cost(&prof, &wt, -1)) != 0u)
            fz_fail("profile cost", "NULL or a bad phase does not cost 0");
    }
    carom_profile_reset(&prof);
    st = carom_world_set_profile(S->W[FZ_A].w, &prof);
    fz_check_status_named(st, "carom_world_set_profile");
    if (st != (CAROM_ENABLE_PROFILE ? CAROM_OK : CAROM_ERR_DISABLED))
        fz_fail("profiling", "carom_world_set_profile returned %s",
                carom_status_string(st));
    st = carom_world_set_profile(S->W[FZ_A].w, NULL);
    if (st != (CAROM_ENABLE_PROFILE ? CAROM_OK : CAROM_ERR_DISABLED))
        fz_fail("profiling", "carom_world_set_profile(NULL) returned %s",
                carom_status_string(st));
    /* NULL worlds and definitions: refused, nothing else touched */
    if (carom_world_def_validate(NULL) != CAROM_ERR_NULL ||
        carom_world_buffer_size(NULL) != 0u ||
        carom_body_def_validate(NULL) != CAROM_ERR_NULL ||
        carom_body_def_set_box(NULL, 1.0f, 1.0f) != CAROM_ERR_NULL ||
        carom_world_step(NULL) != CAROM_ERR_NULL ||
        carom_world_add_body(NULL, NULL, &id) != CAROM_ERR_NULL ||
        carom_world_remove_body(NULL, 0) != CAROM_ERR_NULL ||
        carom_world_get_stats(NULL, NULL) != CAROM_ERR_NULL ||
        carom_world_get_tolerances(S->W[FZ_A].w, NULL) != CAROM_ERR_NULL ||
        carom_world_set_method(NULL, CAROM_METHOD_DISCRETE) != CAROM_ERR_NULL)
        fz_fail("NULL refused", "a call with a NULL world or definition");
    if (id != -1)
        fz_fail("NULL refused", "carom_world_add_body(NULL, ...) wrote id %d",
                id);
    {
        int count = -1;
        const carom_touch_event *te = carom_world_touch_events(S->W[FZ_A].w,
                                                               &count);
        if (count < 0 || count > S->max_touch_events || (count > 0 && !te) ||
            carom_world_touch_events_dropped(S->W[FZ_A].w) < 0)
            fz_fail("touch event list", "%d touch events", count);
        (void)carom_world_touch_events(S->W[FZ_A].w, NULL);
        (void)carom_world_events(S->W[FZ_A].w, NULL);
    }
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
        /* no byte of its own (older inputs keep their meaning): 0 (the
         * default cap), below substeps (fixed), or up to 16 */
        d->max_substeps = (int)((7u * (unsigned)d->iterations +
                                 (unsigned)d->relax_iterations) % 17u);
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

static int fz_capacity_touch_events(const carom_world_def *d)
{
    long n = (long)CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY * d->max_bodies;
    if (d->max_touch_events > 0)
        return d->max_touch_events;
    return n > CAROM_MIN_EVENTS ? (int)(n < INT_MAX ? n : INT_MAX)
                                : CAROM_MIN_EVENTS;
}

/* The operations of an input whose world flags have bit 7: op % 32. */
static void fz_op_v2(fz_state *S, fz_reader *r, unsigned op)
{
    switch (op % 32u) {
    case 0: case 1: case 26: case 29: fz_op_add(S, r); break;
    case 2: fz_op_set_force(S, r); break;
    case 3: fz_op_set_method(S, r); break;
    case 6: fz_op_callback(S, r); break;
    case 7: fz_op_read(S, r); break;
    case 8: case 27: fz_op_remove(S, r); break;
    case 9: case 30: fz_op_set_velocity(S, r, 0); break;
    case 10: fz_op_set_velocity(S, r, 1); break;
    case 11: case 31: fz_op_set_transform(S, r); break;
    case 12: fz_op_impulse(S, r, 0); break;
    case 13: fz_op_impulse(S, r, 1); break;
    case 14: fz_op_once(S, r, 0); break;
    case 15: fz_op_once(S, r, 1); break;
    case 16: fz_op_material(S, r, 0); break;
    case 17: fz_op_material(S, r, 1); break;
    case 18: fz_op_user_data(S, r); break;
    case 19: fz_op_filter(S, r); break;
    case 20: fz_op_query_area(S, r, 0); break;
    case 21: fz_op_query_area(S, r, 1); break;
    case 22: fz_op_raycast(S, r, 0); break;
    case 23: fz_op_raycast(S, r, 1); break;
    case 24: fz_op_misc(S, r); break;
    default: fz_op_steps(S, r); break; /* 4, 5, 25, 28 */
    }
}

/* (not under MemorySanitizer, which then sees the reads themselves:
 * build replay_main.c with clang -fsanitize=memory) */
#if defined(__has_feature)
#if __has_feature(memory_sanitizer)
#define FZ_MSAN 1
#endif
#endif
#ifndef FZ_MSAN
#define FZ_MSAN 0
#endif
static const unsigned char fz_fill[FZ_WORLDS] = {0xA5u, 0x5Au, 0xFFu};

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
    if (flags & 128u) {
        unsigned b = fz_u8(&r);
        misalign = b & 15u;
        S.def.max_touch_events = (int)(b >> 4);
    }
    S.callback = (flags & 64u) != 0;
    S.v2 = (flags & 128u) != 0;
    if (S.callback)
        S.def.force_fn = fz_force;
    S.max_events = fz_capacity_events(&S.def);
    S.max_touch_events = fz_capacity_touch_events(&S.def);
    S.touch_known = 1;
    S.momentum = S.def.gravity.x == 0.0f && S.def.gravity.y == 0.0f &&
                 !S.callback && !S.def.enable_sleep;

    fz_set_where("world definition: gravity %g %g dt %g method %d bodies %d "
                 "pairs %d contacts %d events %d impacts %d length %g rest %g "
                 "slop %g substeps %d (max %d) iterations %d relax %d sleep %d/%g "
                 "touch events %d",
                 (double)S.def.gravity.x, (double)S.def.gravity.y,
                 (double)S.def.dt, (int)S.def.method, S.def.max_bodies,
                 S.def.max_pairs, S.def.max_contacts, S.def.max_events,
                 S.def.max_impacts, (double)S.def.length_unit,
                 (double)S.def.rest_speed, (double)S.def.linear_slop,
                 S.def.substeps, S.def.max_substeps, S.def.iterations,
                 S.def.relax_iterations, S.def.enable_sleep, (double)S.def.sleep_time,
                 S.def.max_touch_events);
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
        W->user.S = &S;
        W->user.adding = 0;
        W->user.added_id = -1;
        W->user.world = fz_world_names[k];
        d.force_user = &W->user;
        W->mem = (unsigned char *)malloc(bytes + 16);
        if (!W->mem)
            abort();
        /* a different byte in each buffer: memory the library reads
         * before writing it makes the worlds differ (determinism, hidden
         * state) in every run, not only when malloc hands back an earlier
         * input's worlds */
#if !FZ_MSAN
        memset(W->mem, fz_fill[k], bytes + 16);
#endif
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
        unsigned op = fz_u8(&r);
        if (flags & 128u) {
            fz_op_v2(&S, &r, op);
            continue;
        }
        switch (op & 7u) {
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
            fz_op_read(&S, &r);
            break;
        }
    }
    for (k = 0; k < FZ_WORLDS; ++k)
        free(S.W[k].mem);
    return 0;
}
