/*
 * carom.h -- 2D rigid-body collision simulation on a fixed time step.
 *
 * carom is an allocation-free, float-only C99 library. Circles and convex
 * polygons (up to CAROM_MAX_POLYGON_VERTICES vertices) move under uniform
 * gravity, constant per-body forces and an optional force callback,
 * integrated with velocity Verlet; they collide with Newton restitution and
 * Coulomb friction.
 *
 * THE IMPORTANT PARTS
 *  - Memory: the caller owns all of it. Ask carom_world_buffer_size() how
 *    many bytes a world needs, hand that buffer to carom_world_init(), and
 *    keep it alive as long as the world. The library never calls malloc.
 *  - Definitions: worlds and bodies are made from definition structs that
 *    start from carom_default_world_def() / carom_default_body_def(), so new
 *    fields never break callers and every default is written down once.
 *  - Status: every call that can fail returns a carom_status; on failure
 *    nothing was changed. carom_status_string() names it.
 *  - Rotation is a unit (cos, sin) pair. The library computes no libm
 *    trigonometry: carom_rot_from_angle() and carom_rot_angle() are its own,
 *    built from + - * / and sqrt, so results can match bit for bit across
 *    CPUs with IEEE single precision and no fused multiply-add.
 *  - Methods: "events" (default) finds every impact at its instant inside
 *    the step and takes impacts in time order; "discrete" resolves contacts
 *    at the end of the step; "first-impact" is the design note's method
 *    (docs/events.md).
 *  - Profiling: a library built with CAROM_ENABLE_PROFILE counts every float
 *    operation by kind and pipeline phase (docs/cost-model.md).
 *  - Switches and limits: carom_config.h.
 *
 * SECTIONS: types -- status -- rotation helpers -- world life cycle --
 *           bodies -- stepping -- reading results -- profiling.
 *
 * A minimal program:
 *
 *     carom_world_def wd = carom_default_world_def();
 *     static unsigned char mem[1 << 16];          // or malloc'd by you
 *     carom_world *w;
 *     if (carom_world_buffer_size(&wd) > sizeof mem) return 1;
 *     carom_world_init(&w, &wd, mem, sizeof mem);
 *     carom_body_def bd = carom_default_body_def();
 *     bd.radius = 0.5f; bd.position.y = 10.0f;
 *     int ball; carom_world_add_body(w, &bd, &ball);
 *     for (int i = 0; i < 60; ++i) carom_world_step(w);
 */
#ifndef CAROM_H
#define CAROM_H

#include <stddef.h>
#include <stdint.h>

#include "carom_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================
 * Types
 * ====================================================================== */

typedef struct carom_vec2 {
    float x, y;
} carom_vec2;

/** A rotation as a unit complex number: (c, s) = (cos angle, sin angle). */
typedef struct carom_rot {
    float c, s;
} carom_rot;

typedef enum carom_body_type {
    CAROM_BODY_DYNAMIC = 0,
    CAROM_BODY_STATIC = 1
} carom_body_type;

typedef enum carom_shape_type {
    CAROM_SHAPE_CIRCLE = 0,
    CAROM_SHAPE_POLYGON = 1
} carom_shape_type;

/** How a step resolves collisions. */
typedef enum carom_method {
    CAROM_METHOD_DISCRETE = 0, /**< contacts found and resolved at the end
                                    of the step (overlap-based, like most
                                    game engines) */
    CAROM_METHOD_EVENTS = 1,   /**< every impact at its exact instant inside
                                    the step, in time order (default) */
    CAROM_METHOD_FIRST_IMPACT = 2, /**< the design note's method: each pair's
                                    first impact in the step, found once at
                                    the start of the step, sub-stepped to
                                    its instant; later impacts of the step
                                    are left to the end-of-step solver */
    CAROM_METHOD_COUNT
} carom_method;

/** Body state as the caller sees it. */
typedef struct carom_body_state {
    carom_vec2 position; /**< body origin (the point the definition placed) */
    carom_rot rotation;
    carom_vec2 velocity; /**< velocity of the centre of mass */
    float angular_velocity;
    carom_vec2 center; /**< centre of mass, world frame */
} carom_body_state;

/**
 * User force callback, evaluated once per dynamic body per step at the
 * step's new positions (velocity Verlet needs a(x1)). `state` holds the new
 * position and rotation and the velocity at the start of the step (the new
 * velocity depends on the force, so it is not known yet). Write the force
 * (applied at the centre of mass, N) and torque (N m); both start at zero.
 */
typedef void (*carom_force_fn)(void *user, int body,
                               const carom_body_state *state,
                               carom_vec2 *force, float *torque);

/** An impact: one per colliding body pair and impact instant. */
typedef struct carom_event {
    float t;              /**< absolute time of the impact, s */
    int body_a, body_b;   /**< body_a < body_b */
    carom_vec2 normal;    /**< unit normal, from body_a towards body_b */
    float impulse;        /**< total normal impulse applied, N s (>= 0) */
    float approach_speed; /**< normal approach speed before it, m/s (>= 0) */
} carom_event;

typedef struct carom_world_def {
    carom_vec2 gravity;       /**< m/s^2, default (0, -10) */
    float dt;                 /**< fixed step, s, > 0; default 1/60 */
    carom_method method;      /**< default CAROM_METHOD_EVENTS (DISCRETE if
                                   CAROM_ENABLE_EVENTS is 0) */
    int max_bodies;           /**< body capacity, default 256 */
    int max_pairs;            /**< broadphase pairs / contacts per step;
                                   0 = CAROM_DEFAULT_PAIRS_PER_BODY *
                                   max_bodies */
    int max_events;           /**< impacts per step (recorded; processed by
                                   the events methods); 0 = 8 per body, at
                                   least 256 */
    float rest_speed;         /**< approach speed (m/s) below which contacts
                                   get no restitution; default 0.5 */
    float linear_slop;        /**< contact distance (m); default 0.0005 */
    int velocity_iterations;  /**< default 10 */
    int position_iterations;  /**< default 6 */
    carom_force_fn force_fn;  /**< optional; needs CAROM_ENABLE_FORCES */
    void *force_user;         /**< passed to force_fn */
} carom_world_def;

typedef struct carom_body_def {
    carom_body_type type;     /**< default dynamic */
    carom_shape_type shape;   /**< default circle */
    float radius;             /**< circle radius, > 0; default 0.5 */
    int vertex_count;         /**< polygon: 3..CAROM_MAX_POLYGON_VERTICES */
    carom_vec2 vertices[CAROM_MAX_POLYGON_VERTICES]; /**< polygon, body frame.
                                   Clockwise input is reversed to counter-
                                   clockwise; anything not strictly convex
                                   and simple is rejected. */
    carom_vec2 position;      /**< origin of the body frame, world */
    carom_rot rotation;       /**< default (1, 0); normalised on add */
    carom_vec2 velocity;      /**< of the centre of mass */
    float angular_velocity;   /**< rad/s */
    float density;            /**< kg/m^2, > 0; default 1 */
    float mass;               /**< 0: from density; > 0 overrides density */
    float restitution;        /**< [0, 1]; default 0 */
    float friction;           /**< >= 0; default 0.6 */
    carom_vec2 force;         /**< constant force at the centre, N */
    float torque;             /**< constant torque, N m */
} carom_body_def;

typedef struct carom_world carom_world; /* opaque; lives in caller memory */

/* ======================================================================
 * Status
 * ====================================================================== */

typedef enum carom_status {
    CAROM_OK = 0,
    CAROM_ERR_NULL,               /**< a required pointer is NULL */
    CAROM_ERR_NOT_FINITE,         /**< NaN or infinity in the input */
    CAROM_ERR_BAD_DT,             /**< dt <= 0 */
    CAROM_ERR_BAD_CAPACITY,       /**< a capacity <= 0 or too large */
    CAROM_ERR_BUFFER_TOO_SMALL,   /**< caller buffer smaller than needed */
    CAROM_ERR_BAD_PARAMETER,      /**< rest_speed, slop or iterations < 0 */
    CAROM_ERR_BAD_METHOD,         /**< unknown method */
    CAROM_ERR_BAD_BODY_TYPE,      /**< neither static nor dynamic */
    CAROM_ERR_BAD_SHAPE,          /**< neither circle nor polygon */
    CAROM_ERR_BAD_RADIUS,         /**< radius <= 0 */
    CAROM_ERR_BAD_DENSITY,        /**< density <= 0 */
    CAROM_ERR_BAD_MASS,           /**< mass < 0 */
    CAROM_ERR_BAD_RESTITUTION,    /**< restitution outside [0, 1] */
    CAROM_ERR_BAD_FRICTION,       /**< friction < 0 */
    CAROM_ERR_BAD_ROTATION,       /**< rotation pair (0, 0) */
    CAROM_ERR_TOO_FEW_VERTICES,   /**< polygon with < 3 vertices */
    CAROM_ERR_TOO_MANY_VERTICES,  /**< > CAROM_MAX_POLYGON_VERTICES */
    CAROM_ERR_DEGENERATE_POLYGON, /**< repeated or collinear vertices, or
                                       (near) zero area */
    CAROM_ERR_SELF_INTERSECTING,  /**< two edges cross */
    CAROM_ERR_NOT_CONVEX,         /**< a reflex vertex */
    CAROM_ERR_WORLD_FULL,         /**< max_bodies reached */
    CAROM_ERR_BAD_BODY_ID,        /**< no such body */
    CAROM_ERR_PAIR_CAPACITY,      /**< more touching pairs than max_pairs:
                                       the step completed with the first
                                       max_pairs (in body order) only */
    CAROM_ERR_EVENT_CAPACITY,     /**< more impacts in the step than
                                       max_events (see the method's docs) */
    CAROM_ERR_DISABLED,           /**< capability compiled out */
    CAROM_STATUS_COUNT
} carom_status;

/** Stable, human-readable name of a status ("ok", "not finite", ...). */
const char *carom_status_string(carom_status status);

/* ======================================================================
 * Rotation helpers (library's own trigonometry; no libm)
 * ====================================================================== */

/** Unit rotation of `angle` radians (|angle| up to about 1e5 is accurate). */
carom_rot carom_rot_from_angle(float angle);

/** Angle of a rotation in (-pi, pi]. */
float carom_rot_angle(carom_rot r);

/* ======================================================================
 * World life cycle
 * ====================================================================== */

carom_world_def carom_default_world_def(void);

/** Bytes of caller memory a world made from `def` needs (0 if def is bad). */
size_t carom_world_buffer_size(const carom_world_def *def);

/**
 * Build a world in `buffer` (any alignment; `bytes` at least
 * carom_world_buffer_size(def)). *out points into the buffer.
 */
carom_status carom_world_init(carom_world **out, const carom_world_def *def,
                              void *buffer, size_t bytes);

/** Check a world definition without building anything. */
carom_status carom_world_def_validate(const carom_world_def *def);

/* ======================================================================
 * Bodies
 * ====================================================================== */

carom_body_def carom_default_body_def(void);

/** Make `def` a box of half extents (hx, hy) centred on the body origin. */
carom_status carom_body_def_set_box(carom_body_def *def, float hx, float hy);

/** Check a body definition without adding it. */
carom_status carom_body_def_validate(const carom_body_def *def);

/** Add a body; its id (0, 1, 2, ... in order of addition) goes to *id. */
carom_status carom_world_add_body(carom_world *w, const carom_body_def *def,
                                  int *id);

int carom_world_body_count(const carom_world *w);

carom_status carom_body_get_state(const carom_world *w, int id,
                                  carom_body_state *out);

/** Mass (kg) and rotational inertia about the centre (kg m^2); 0 if static */
carom_status carom_body_get_mass(const carom_world *w, int id, float *mass,
                                 float *inertia);

/** Replace a body's constant force and torque (CAROM_ENABLE_FORCES). */
carom_status carom_body_set_force(carom_world *w, int id, carom_vec2 force,
                                  float torque);

/* ======================================================================
 * Stepping
 * ====================================================================== */

/** Advance the world by one dt. */
carom_status carom_world_step(carom_world *w);

carom_status carom_world_set_method(carom_world *w, carom_method method);
carom_method carom_world_get_method(const carom_world *w);

/** "discrete" / "events" / "first-impact" -> method; CAROM_ERR_BAD_METHOD
 * if unknown (a known method compiled out is CAROM_ERR_DISABLED when used). */
carom_status carom_method_from_name(const char *name, carom_method *out);
const char *carom_method_name(carom_method method);

/* ======================================================================
 * Reading results
 * ====================================================================== */

/** Simulated time (s): steps taken times dt (one float product, so it does
 * not drift the way a running sum would). */
float carom_world_time(const carom_world *w);
long carom_world_step_count(const carom_world *w);

/** Impacts of the last step, in time order; *count gets how many. */
const carom_event *carom_world_events(const carom_world *w, int *count);

/** Number of impacts of the last step that did not fit in max_events. */
int carom_world_events_dropped(const carom_world *w);

/** Counters accumulated since the world was made. */
typedef struct carom_stats {
    long steps;
    long impacts;        /**< events recorded */
    long toi_queries;    /**< pair time-of-impact searches (events methods) */
    long toi_early_outs; /**< of which ruled out by the closest-approach
                              test before any root finding */
} carom_stats;

carom_status carom_world_get_stats(const carom_world *w, carom_stats *out);

/* ======================================================================
 * Profiling: floating-point operations by kind and pipeline phase
 * (needs CAROM_ENABLE_PROFILE; otherwise the calls that need counting
 * return CAROM_ERR_DISABLED and the library contains no counter)
 * ====================================================================== */

/** Operation kinds (docs/cost-model.md says what counts as what). */
typedef enum carom_op {
    CAROM_OP_ADD, CAROM_OP_SUB, CAROM_OP_MUL, CAROM_OP_DIV, CAROM_OP_CMP,
    CAROM_OP_SQRT, CAROM_OP_COUNT
} carom_op;

/** Pipeline phases. */
typedef enum carom_phase {
    CAROM_PHASE_INTEGRATION,   /**< "integration": Verlet drift and kick */
    CAROM_PHASE_BROADPHASE,    /**< "broadphase": boxes, sort and sweep */
    CAROM_PHASE_NARROWPHASE,   /**< "narrowphase": contact manifolds */
    CAROM_PHASE_IMPACT_TIMING, /**< "impact_timing": time of impact, early-out */
    CAROM_PHASE_IMPULSES,      /**< "impulse_resolution": impact impulses */
    CAROM_PHASE_RESTING,       /**< "resting_contacts": resting forces, projection */
    CAROM_PHASE_COUNT
} carom_phase;

/** Counters; the caller owns it, resets it, and attaches it to a world.
 * They accumulate over the steps taken while attached: reset before a step
 * to read that step's counts, or divide by steps for the average. */
typedef struct carom_profile {
    uint64_t ops[CAROM_PHASE_COUNT][CAROM_OP_COUNT];
    uint64_t steps;      /**< steps taken while attached */
    uint64_t body_steps; /**< sum over those steps of the body count */
    uint64_t impacts;    /**< events recorded while attached */
} carom_profile;

/** A cost per operation kind, in the caller's unit ("add units" for the
 * design note's table, cycles for the Cortex-M presets). */
typedef struct carom_op_weights {
    float w[CAROM_OP_COUNT];
} carom_op_weights;

void carom_profile_reset(carom_profile *p);

/** Count the operations of this world's steps into p (NULL detaches).
 * Counting is per library, not per world: attach to one world at a time. */
carom_status carom_world_set_profile(carom_world *w, carom_profile *p);

/** Presets: "seed" (the design note: add 1, sub 1, mul 1.5, div 4, cmp 1,
 * sqrt 6), "cortex-m4f", "cortex-m0" (docs/cost-model.md gives sources). */
carom_status carom_op_weights_preset(const char *name, carom_op_weights *out);

/** Weighted sum of the counts of one phase, or of all if phase < 0. */
float carom_profile_cost(const carom_profile *p, const carom_op_weights *wt,
                         int phase);

/** "add", "sub", ... and "integration", "broadphase", ... */
const char *carom_op_name(carom_op op);
const char *carom_phase_name(carom_phase phase);

#ifdef __cplusplus
}
#endif

#endif /* CAROM_H */
