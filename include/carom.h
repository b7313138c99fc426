/*
 * carom.h -- 2D rigid-body collision simulation on a fixed time step.
 *
 * carom is an allocation-free, float-only C99 library. Circles and convex
 * polygons (up to CAROM_MAX_POLYGON_VERTICES vertices) move under uniform
 * gravity, constant per-body forces and an optional force callback,
 * integrated with velocity Verlet; they collide with Newton restitution and
 * Coulomb friction, and rest on each other as contact constraints.
 *
 * THE IMPORTANT PARTS
 *  - Memory: the caller owns all of it. Ask carom_world_buffer_size() how
 *    many bytes a world needs, hand that buffer to carom_world_init(), and
 *    keep it alive as long as the world. The library never calls malloc.
 *    A program that can give more memory sets carom_world_def.grow: a step
 *    that would need more candidate pairs or contacts than the capacities
 *    asks it for a larger block and is taken again, instead of failing
 *    (then call carom_world_release() before dropping the buffer).
 *  - Definitions: worlds and bodies are made from definition structs that
 *    start from carom_default_world_def() / carom_default_body_def(), so new
 *    fields never break callers and every default is written down once.
 *  - Status: every call that can fail returns a carom_status, and on failure
 *    the world is as it was before the call (for carom_world_step: see its
 *    comment for the one exception, the event list). carom_status_string()
 *    names it.
 *  - Rotation is a unit (cos, sin) pair. The library computes no libm
 *    trigonometry: carom_rot_from_angle() and carom_rot_angle() are its own,
 *    built from + - * / and sqrt, so results match bit for bit across CPUs
 *    with IEEE single precision and no fused multiply-add.
 *  - Methods: "events" (default) finds every impact at its instant inside
 *    the step and takes impacts in time order; "discrete" resolves contacts
 *    with the contact solver only; "first-impact" is the design note's
 *    method (docs/events.md). Resting contact is the same in all three: a
 *    substepping contact solver (speculative contacts, block solver, split
 *    position correction, shock propagation; docs/physics.md).
 *  - Scale: no tolerance is in absolute metres. They derive from a length
 *    unit (the bodies' mean equivalent radius unless the world sets one)
 *    and from |gravity| dt, so a scene scaled by 100 behaves the same.
 *  - Profiling: a library built with CAROM_ENABLE_PROFILE (build/profile/
 *    libcarom.a) counts every float operation by kind and pipeline phase
 *    (docs/cost-model.md).
 *  - Switches, limits and the valid input ranges: carom_config.h.
 *
 * SECTIONS: types -- status -- rotation helpers -- world life cycle --
 *           bodies -- stepping -- reading results -- queries -- profiling.
 *
 * A minimal program (a ball dropped on a floor; prints "ball at 0 0.5"):
 *
 *     static unsigned char mem[1 << 16];          // or malloc'd by you
 *     carom_world_def wd = carom_default_world_def();
 *     carom_body_def floor = carom_default_body_def();
 *     carom_body_def ball = carom_default_body_def();
 *     carom_body_state s;
 *     carom_world *w;
 *     int id, i;
 *     wd.max_bodies = 8;                          // capacities decide size
 *     if (carom_world_init(&w, &wd, mem, sizeof mem) != CAROM_OK) return 1;
 *     floor.type = CAROM_BODY_STATIC;
 *     carom_body_def_set_box(&floor, 10.0f, 0.5f);
 *     floor.position.y = -0.5f;
 *     carom_world_add_body(w, &floor, NULL);
 *     ball.radius = 0.5f; ball.position.y = 5.0f;
 *     carom_world_add_body(w, &ball, &id);
 *     for (i = 0; i < 300; ++i) carom_world_step(w);
 *     carom_body_get_state(w, id, &s);
 *     printf("ball at %.3g %.3g\n", (double)s.position.x, (double)s.position.y);
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

/** Library version (also carom_version()). */
#define CAROM_VERSION_MAJOR 0
#define CAROM_VERSION_MINOR 2
#define CAROM_VERSION_PATCH 0

/** Pass in a world definition field to have carom derive the value
 * (length_unit, rest_speed, linear_slop: exactly this value; any other
 * negative value is refused with CAROM_ERR_OUT_OF_RANGE). */
#define CAROM_AUTO (-1.0f)

typedef struct carom_vec2 {
    float x, y;
} carom_vec2;

/** A rotation as a unit complex number: (c, s) = (cos angle, sin angle). */
typedef struct carom_rot {
    float c, s;
} carom_rot;

typedef enum carom_body_type {
    CAROM_BODY_DYNAMIC = 0,  /**< moved by forces and contacts */
    CAROM_BODY_STATIC = 1,   /**< never moves (infinite mass) */
    CAROM_BODY_KINEMATIC = 2 /**< moves with the velocity the program sets,
                                  pushes dynamic bodies, is not pushed
                                  (CAROM_ENABLE_KINEMATIC) */
} carom_body_type;

typedef enum carom_shape_type {
    CAROM_SHAPE_CIRCLE = 0,
    CAROM_SHAPE_POLYGON = 1
} carom_shape_type;

/** How a step resolves collisions. */
typedef enum carom_method {
    CAROM_METHOD_DISCRETE = 0, /**< the contact solver alone: contacts kept
                                    a little before they touch
                                    (speculative), restitution applied once
                                    per step (like most game engines) */
    CAROM_METHOD_EVENTS = 1,   /**< every impact at its exact instant inside
                                    the step, in time order, simultaneous
                                    impacts together (default) */
    CAROM_METHOD_FIRST_IMPACT = 2, /**< the design note's method: each pair's
                                    first impact in the step, found once at
                                    the start of the step, taken at its
                                    instant; later impacts of the step are
                                    left to the contact solver */
    CAROM_METHOD_COUNT
} carom_method;

/** Body state as the caller sees it. */
typedef struct carom_body_state {
    carom_vec2 position; /**< body origin (the point the definition placed),
                              m */
    carom_rot rotation;
    carom_vec2 velocity; /**< velocity of the centre of mass, m/s */
    float angular_velocity; /**< rad/s, counter-clockwise */
    carom_vec2 center;   /**< centre of mass, world frame, m */
} carom_body_state;

/**
 * User force callback: the force (N, at the centre of mass) and torque
 * (N m) on body `body` in the state `state`; both start at zero. It is
 * called when a body is added or its force set (for the step's first
 * acceleration) and once per awake dynamic body per step at the step's new
 * positions (velocity Verlet needs a(x1)); there `state` holds the new
 * position and rotation and the velocity v0 + a0 dt, since the new velocity
 * depends on the force. A non-finite or out-of-range result fails the step
 * (CAROM_ERR_NOT_FINITE / CAROM_ERR_OUT_OF_RANGE), or the call that asked
 * for it, and the world keeps its state from before.
 */
typedef void (*carom_force_fn)(void *user, int body,
                               const carom_body_state *state,
                               carom_vec2 *force, float *torque);

/**
 * An impact: two bodies meeting faster than the rest speed (so their
 * restitution applies). Slower meetings are resting contact, which makes no
 * event. One per impacting body pair and instant; impacts solved together
 * (simultaneous) share their t.
 */
typedef struct carom_event {
    float t;              /**< absolute time of the impact, s */
    int body_a, body_b;   /**< ids; body_a has the smaller slot index */
    carom_vec2 normal;    /**< unit normal, from body_a towards body_b */
    float impulse;        /**< normal impulse of the impact, N s (>= 0) */
    float approach_speed; /**< normal approach speed before it, m/s (>= 0) */
} carom_event;

/**
 * Two bodies began or ended touching (within the contact slop, or an
 * impact during the step), or a body began or ended overlapping a sensor.
 * Reported after the step in which it happened; a body's touches end
 * without an event when it is removed. A body that crosses a sensor
 * within one step (apart from it at the step's start and end) gets a
 * begin and an end in that step.
 */
typedef struct carom_touch_event {
    int body_a, body_b;   /**< ids; body_a has the smaller slot index */
    int begin;            /**< 1: began touching; 0: ended */
    int sensor;           /**< 1: one of the two is a sensor (overlap) */
} carom_touch_event;

/** A ray's hit (carom_world_raycast). */
typedef struct carom_ray_hit {
    int body;             /**< id of the body hit */
    carom_vec2 point;     /**< where the ray enters its shape, m */
    carom_vec2 normal;    /**< unit outward normal of the shape there */
    float fraction;       /**< along the ray, from 0 (from) to 1 (to) */
} carom_ray_hit;

/** Query callback: one body found; return 0 to stop the query. */
typedef int (*carom_query_fn)(void *ctx, int body);

/**
 * Memory on demand (carom_world_def.grow): alloc returns `bytes` bytes
 * (any alignment) or NULL; release takes back what alloc gave. The library
 * calls them only inside carom_world_step() and carom_world_release(), and
 * holds at most one block at a time.
 */
typedef struct carom_allocator {
    void *(*alloc)(void *user, size_t bytes);
    void (*release)(void *user, void *block);
    void *user;
} carom_allocator;

typedef struct carom_world_def {
    carom_vec2 gravity;       /**< m/s^2, default (0, -10) */
    float dt;                 /**< fixed step, s, in [CAROM_LIMIT_MIN_DT,
                                   CAROM_LIMIT_MAX_DT]; default 1/60 */
    carom_method method;      /**< default CAROM_METHOD_EVENTS (DISCRETE if
                                   CAROM_ENABLE_EVENTS is 0) */
    int max_bodies;           /**< body capacity, default 256, at most
                                   2^CAROM_ID_INDEX_BITS */
    int max_pairs;            /**< candidate pairs (overlapping bounding
                                   boxes); 0 = CAROM_DEFAULT_PAIRS_PER_BODY
                                   x max_bodies */
    int max_contacts;         /**< pairs within contact distance (with a
                                   manifold); 0 = CAROM_DEFAULT_CONTACTS_PER_
                                   BODY x max_bodies */
    int max_events;           /**< impacts recorded per step for
                                   carom_world_events(); 0 = default (more
                                   are counted in carom_world_events_dropped,
                                   not an error) */
    int max_impacts;          /**< impacts taken at their instants, with
                                   restitution, per step (events methods);
                                   past it the step's further impacts are
                                   plastic at their instants and its later
                                   substeps are solved like the discrete
                                   method (counted in stats.budget_steps);
                                   0 = default (CAROM_DEFAULT_IMPACTS_PER_
                                   BODY x max_bodies, at least
                                   CAROM_MIN_IMPACTS) */
    float length_unit;        /**< m; CAROM_AUTO (default): the mean
                                   equivalent radius sqrt(area / pi) of the
                                   dynamic bodies (asleep or awake); with
                                   no dynamic body, that of all the bodies
                                   (static and kinematic); with no body at
                                   all, 1 m. Taken anew at every step (and
                                   by carom_world_get_tolerances), so it
                                   follows bodies added and removed.
                                   Scales every distance tolerance
                                   (carom_config.h) */
    float rest_speed;         /**< approach speed (m/s) below which contacts
                                   are resting, not impacts (no restitution,
                                   no event); CAROM_AUTO (default):
                                   CAROM_REST_SPEED_PER_ACCEL_DT x |a| dt, so
                                   0 in zero gravity */
    float linear_slop;        /**< contact distance, m; CAROM_AUTO (default):
                                   CAROM_SLOP_PER_LENGTH x length_unit */
    int substeps;             /**< contact substeps per step, 1..64; default
                                   CAROM_DEFAULT_SUBSTEPS (4): the fewest */
    int max_substeps;         /**< 0..64; 0 = CAROM_DEFAULT_MAX_SUBSTEPS
                                   (64). A step takes more than `substeps`,
                                   up to this, where gravity would move a
                                   body from rest by more than one linear
                                   slop of the length unit in a substep:
                                   n = ceil(dt sqrt(|g| / (2
                                   CAROM_SUBSTEP_FALL_SLOPS
                                   CAROM_SLOP_PER_LENGTH L))), L the length
                                   unit (small bodies, long steps: a pile
                                   of 1 cm bodies under 10 m/s^2 at
                                   dt 1/60 takes 12); and where touching
                                   contacts join dynamic bodies of masses
                                   R > CAROM_SUBSTEP_MASS_RATIO apart,
                                   with |g| R for |g|. At or below
                                   `substeps`: always `substeps`.
                                   carom_world_get_tolerances() reports the
                                   count of the first rule;
                                   carom_stats.substeps the last step's */
    int iterations;           /**< contact sweeps per substep, 1..64;
                                   default 1 */
    int relax_iterations;     /**< relaxing sweeps per substep, 0..64;
                                   default CAROM_DEFAULT_RELAX_ITERATIONS
                                   (2) */
    int enable_sleep;         /**< 1 (default): quiet islands sleep
                                   (CAROM_ENABLE_SLEEP); 0: never */
    float sleep_time;         /**< s an island must stay still to sleep;
                                   default CAROM_DEFAULT_SLEEP_TIME */
    carom_force_fn force_fn;  /**< optional; needs CAROM_ENABLE_FORCES */
    void *force_user;         /**< passed to force_fn */
    int max_touch_events;     /**< begin/end-touch events recorded per step
                                   (CAROM_ENABLE_TOUCH_EVENTS); 0 = default
                                   (CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY x
                                   max_bodies, at least CAROM_MIN_EVENTS);
                                   more are counted as dropped */
    carom_allocator grow;     /**< optional (both functions or none;
                                   default none): when a step needs more
                                   candidate pairs or contacts than
                                   max_pairs / max_contacts, the world
                                   takes a block twice as large from
                                   grow.alloc, moves its pair and contact
                                   arrays there and takes the step again,
                                   from the same state (the discrete
                                   method's result is that of the larger
                                   capacities from the start).
                                   Without it, or if alloc returns NULL,
                                   the step fails with
                                   CAROM_ERR_PAIR_CAPACITY or
                                   CAROM_ERR_CONTACT_CAPACITY */
} carom_world_def;

typedef struct carom_body_def {
    carom_body_type type;     /**< default dynamic */
    carom_shape_type shape;   /**< default circle */
    float radius;             /**< circle radius, m, > 0; default 0.5 */
    int vertex_count;         /**< polygon: 3..CAROM_MAX_POLYGON_VERTICES */
    carom_vec2 vertices[CAROM_MAX_POLYGON_VERTICES]; /**< polygon, body frame,
                                   m. Clockwise input is reversed to counter-
                                   clockwise; anything not strictly convex
                                   and simple is rejected. */
    carom_vec2 position;      /**< origin of the body frame, world, m */
    carom_rot rotation;       /**< default (1, 0); normalised on add */
    carom_vec2 velocity;      /**< of the centre of mass, m/s */
    float angular_velocity;   /**< rad/s */
    float density;            /**< kg/m^2, > 0 (unless mass is given); default 1 */
    float mass;               /**< kg; 0: from density; > 0 overrides density */
    float restitution;        /**< [0, 1]; default 0. A contact uses the
                                   larger of its two bodies' values */
    float friction;           /**< 0 ... CAROM_LIMIT_MAX_FRICTION (1e6);
                                   default 0.6. A contact uses
                                   sqrt(friction_a friction_b) */
    carom_vec2 force;         /**< constant force at the centre, N */
    float torque;             /**< constant torque, N m */
    uint32_t category_bits;   /**< collision filter: the categories this body
                                   is in; default 1 (CAROM_ENABLE_FILTERING) */
    uint32_t mask_bits;       /**< the categories it collides with; default
                                   all. Two bodies collide when each one's
                                   category_bits meet the other's mask_bits */
    int group_index;          /**< 0 (default): no group. Two bodies of the
                                   same nonzero group always collide if it
                                   is positive, never if it is negative,
                                   whatever their bits (as in Box2D) */
    int is_sensor;            /**< 1: the body exerts and feels no contact
                                   impulse; its overlaps with other
                                   (non-sensor) bodies are reported as touch
                                   events (CAROM_ENABLE_SENSORS) */
    void *user_data;          /**< the program's pointer, kept for it */
} carom_body_def;

typedef struct carom_world carom_world; /* opaque; lives in caller memory */

/* ======================================================================
 * Status
 * ====================================================================== */

typedef enum carom_status {
    CAROM_OK = 0,
    CAROM_ERR_NULL,               /**< a required pointer is NULL */
    CAROM_ERR_NOT_FINITE,         /**< NaN or infinity in the input, or in a
                                       body's state at the end of a step
                                       (carom_world_error_body names it) */
    CAROM_ERR_BAD_DT,             /**< dt outside [CAROM_LIMIT_MIN_DT,
                                       CAROM_LIMIT_MAX_DT] */
    CAROM_ERR_BAD_CAPACITY,       /**< a capacity < 0, 0 where one is needed, or too large */
    CAROM_ERR_BUFFER_TOO_SMALL,   /**< caller buffer smaller than needed */
    CAROM_ERR_BAD_PARAMETER,      /**< substeps, max_substeps, iterations
                                       or relax_iterations out of range,
                                       sleep_time < 0, grow.alloc without
                                       grow.release or the reverse; an
                                       unknown carom_op_weights_preset
                                       name */
    CAROM_ERR_BAD_METHOD,         /**< unknown method */
    CAROM_ERR_BAD_BODY_TYPE,      /**< not static, dynamic or kinematic */
    CAROM_ERR_BAD_SHAPE,          /**< neither circle nor polygon */
    CAROM_ERR_BAD_RADIUS,         /**< radius outside [CAROM_LIMIT_MIN_SIZE,
                                       CAROM_LIMIT_MAX_LENGTH] */
    CAROM_ERR_BAD_DENSITY,        /**< density <= 0 */
    CAROM_ERR_BAD_MASS,           /**< mass < 0, or mass or inertia outside
                                       [CAROM_LIMIT_MIN_MASS,
                                       CAROM_LIMIT_MAX_MASS] */
    CAROM_ERR_BAD_RESTITUTION,    /**< restitution outside [0, 1] */
    CAROM_ERR_BAD_FRICTION,       /**< friction < 0 or above
                                       CAROM_LIMIT_MAX_FRICTION (1e6) */
    CAROM_ERR_BAD_ROTATION,       /**< rotation pair (0, 0), or too short
                                       or long to normalize (c^2 + s^2
                                       below FLT_MIN or not finite) */
    CAROM_ERR_TOO_FEW_VERTICES,   /**< polygon with < 3 vertices */
    CAROM_ERR_TOO_MANY_VERTICES,  /**< > CAROM_MAX_POLYGON_VERTICES */
    CAROM_ERR_DEGENERATE_POLYGON, /**< repeated or collinear vertices, (near)
                                       zero area, or thinner than
                                       CAROM_LIMIT_MIN_SIZE */
    CAROM_ERR_SELF_INTERSECTING,  /**< two edges cross */
    CAROM_ERR_NOT_CONVEX,         /**< a reflex vertex */
    CAROM_ERR_WORLD_FULL,         /**< max_bodies reached */
    CAROM_ERR_BAD_BODY_ID,        /**< no such body */
    CAROM_ERR_PAIR_CAPACITY,      /**< more candidate pairs than max_pairs,
                                       or more touching pairs (the step's
                                       candidates and the touches of
                                       bodies asleep, which the touch list
                                       of max_pairs entries also holds);
                                       the step was not taken */
    CAROM_ERR_CONTACT_CAPACITY,   /**< more contacts than max_contacts; the
                                       step was not taken */
    CAROM_ERR_DISABLED,           /**< capability compiled out */
    CAROM_ERR_OUT_OF_RANGE,       /**< a value outside carom's documented
                                       range (carom_config.h CAROM_LIMIT_*);
                                       at the end of a step:
                                       carom_world_error_body names it */
    CAROM_ERR_STALE_ID,           /**< the body of that id was removed */
    CAROM_STATUS_COUNT
} carom_status;

/** Stable, human-readable name of a status ("ok", "not finite", ...). */
const char *carom_status_string(carom_status status);

/** "MAJOR.MINOR.PATCH" of the library (may differ from the header's). */
const char *carom_version(void);

/* ======================================================================
 * Rotation helpers (library's own trigonometry; no libm)
 * ====================================================================== */

#if CAROM_ENABLE_ANGLES
/** Unit rotation of `angle` radians: sin and cos of the float angle to
 * 3e-7 for |angle| up to 1e5; beyond, whole turns are taken off with 2 pi
 * a float (3e-2 off at 1e6, where angles themselves are 0.06 rad apart);
 * beyond 1e9, and for NaN or an infinity, the identity (no status: check
 * the angle first if it may not be finite). */
carom_rot carom_rot_from_angle(float angle);

/** Angle of a rotation in [-pi, pi]: (-pi, pi] to within rounding (a
 * rotation of angle pi rounded to float may give the float of -pi). */
float carom_rot_angle(carom_rot r);
#endif /* CAROM_ENABLE_ANGLES (off: pass (cos, sin) pairs) */

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

/** Make `def` a box of half extents (hx, hy) centred on the body origin:
 * CAROM_ERR_DEGENERATE_POLYGON below CAROM_LIMIT_MIN_SIZE, as
 * carom_world_add_body would say. */
carom_status carom_body_def_set_box(carom_body_def *def, float hx, float hy);

/** Check a body definition without adding it. */
carom_status carom_body_def_validate(const carom_body_def *def);

/** Add a body; its id goes to *id (0, 1, 2, ... in a fresh world). */
carom_status carom_world_add_body(carom_world *w, const carom_body_def *def,
                                  int *id);

/** Number of bodies in the world. */
int carom_world_body_count(const carom_world *w);

carom_status carom_body_get_state(const carom_world *w, int id,
                                  carom_body_state *out);

/** Mass (kg) and rotational inertia about the centre (kg m^2); 0 if not
 * dynamic. */
carom_status carom_body_get_mass(const carom_world *w, int id, float *mass,
                                 float *inertia);

/** Replace a dynamic body's constant force (N) and torque (N m)
 * (CAROM_ENABLE_FORCES). Wakes the body. A static or kinematic body:
 * CAROM_ERR_BAD_BODY_TYPE (forces move dynamic bodies only). */
carom_status carom_body_set_force(carom_world *w, int id, carom_vec2 force,
                                  float torque);

/** 1 if the body is awake (simulated), 0 if asleep (CAROM_ENABLE_SLEEP). */
int carom_body_is_awake(const carom_world *w, int id);

/**
 * Remove a body. Its slot is reused by a later carom_world_add_body, with
 * a new id: the old id is refused from then on with CAROM_ERR_STALE_ID (the
 * id carries the slot's generation; after 2^(31 - CAROM_ID_INDEX_BITS)
 * removals of one slot the generation wraps). Its contacts, warm starts
 * and touches go with it; a sleeping island it belonged to wakes.
 */
carom_status carom_world_remove_body(carom_world *w, int id);

/** 1 if `id` names a body of the world now, else 0. */
int carom_body_is_valid(const carom_world *w, int id);

/** Body type (CAROM_BODY_DYNAMIC, STATIC or KINEMATIC). A body's type,
 * shape and mass are fixed when it is added (no setter): to change them,
 * remove it and add a new body with the new definition (a new id; its
 * touches end without an event, and a sleeping island it belonged to
 * wakes). */
carom_status carom_body_get_type(const carom_world *w, int id,
                                 carom_body_type *out);

/** Velocity of the centre of mass (m/s) and angular velocity (rad/s);
 * either pointer may be NULL. */
carom_status carom_body_get_velocity(const carom_world *w, int id,
                                     carom_vec2 *velocity, float *angular);

/** Set the velocity of the centre of mass (m/s) of a dynamic or kinematic
 * body (CAROM_ERR_BAD_BODY_TYPE for a static one). Wakes it. */
carom_status carom_body_set_velocity(carom_world *w, int id,
                                     carom_vec2 velocity);

/** Set the angular velocity (rad/s) of a dynamic or kinematic body. */
carom_status carom_body_set_angular_velocity(carom_world *w, int id,
                                             float angular);

/**
 * Teleport: place the body origin at `position` with `rotation`
 * (normalised; velocities kept). Any body type. Its warm starts are
 * dropped (its contacts are found anew next step) and it wakes, with its
 * island and whatever it now touches.
 */
carom_status carom_body_set_transform(carom_world *w, int id,
                                      carom_vec2 position, carom_rot rotation);

/** Apply an impulse (N s) at a world point (m) to a dynamic body: its
 * velocity and angular velocity change at once. Wakes it. */
carom_status carom_body_apply_impulse(carom_world *w, int id,
                                      carom_vec2 impulse, carom_vec2 point);

/** Apply an angular impulse (N m s) to a dynamic body. */
carom_status carom_body_apply_angular_impulse(carom_world *w, int id,
                                              float impulse);

/** Apply a force (N) at a world point (m) during the next step only,
 * besides the constant force (CAROM_ENABLE_FORCES). Calls add up. */
carom_status carom_body_apply_force(carom_world *w, int id, carom_vec2 force,
                                    carom_vec2 point);

/** Apply a torque (N m) during the next step only. Calls add up. */
carom_status carom_body_apply_torque(carom_world *w, int id, float torque);

/** Restitution in [0, 1] and friction in [0, CAROM_LIMIT_MAX_FRICTION]
 * after creation (the same rules as in the definition). */
carom_status carom_body_set_restitution(carom_world *w, int id, float e);
carom_status carom_body_set_friction(carom_world *w, int id, float mu);

/** The program's pointer for the body (NULL for a bad id). */
carom_status carom_body_set_user_data(carom_world *w, int id, void *data);
void *carom_body_get_user_data(const carom_world *w, int id);

/** Collision filter after creation (carom_body_def's category_bits,
 * mask_bits, group_index; CAROM_ENABLE_FILTERING). Wakes the body. */
carom_status carom_body_set_filter(carom_world *w, int id, uint32_t category,
                                   uint32_t mask, int group);

/* ======================================================================
 * Stepping
 * ====================================================================== */

/**
 * Advance the world by one dt. On any status but CAROM_OK the bodies,
 * contacts, counters and time are exactly as before the call (the step is
 * rolled back); only the event list then holds no events. With
 * carom_world_def.grow set, a step short of pair or contact capacity grows
 * the world's arrays (see there) and is taken again.
 */
carom_status carom_world_step(carom_world *w);

/**
 * Give back the memory the world took through carom_world_def.grow (none:
 * nothing happens). The world returns to the capacities of its own buffer
 * and stays usable; the last step's warm starts and touching pairs are kept
 * if they fit, else dropped. Call it before freeing the buffer of a world
 * made with grow set: the memory is always given back.
 * Returns CAROM_OK, CAROM_ERR_NULL, or CAROM_ERR_PAIR_CAPACITY when the
 * touching pairs did not fit and were dropped: the next step then reports
 * a begin-touch again for every pair still touching, with no end-touch
 * before it, and none for the pairs that parted (reset any count of
 * touches kept from the touch events).
 */
carom_status carom_world_release(carom_world *w);

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

/** Impacts of the last step, in time order; *count gets how many. The
 * array lives in the world's memory: what it holds is good until the next
 * carom_world_step, which writes that step's impacts over it (none if the
 * step fails). In a world that has grown (carom_world_def.grow), that step
 * or carom_world_release (which empties the list) may also move or free
 * the array: call this again after either, and copy what you keep. */
const carom_event *carom_world_events(const carom_world *w, int *count);

/** Impacts of the last step that did not fit in max_events. */
int carom_world_events_dropped(const carom_world *w);

/** Touches that began or ended in the last step (CAROM_ENABLE_TOUCH_EVENTS;
 * otherwise none); *count gets how many. The array holds as long as
 * carom_world_events' does. */
const carom_touch_event *carom_world_touch_events(const carom_world *w,
                                                  int *count);

/** Touch events of the last step that did not fit in max_touch_events. */
int carom_world_touch_events_dropped(const carom_world *w);

/* ======================================================================
 * Queries (CAROM_ENABLE_QUERIES): exact against the shapes, through the
 * broadphase grid of the last step (or every body, if bodies were added,
 * removed or moved by the program since). Sensors are found too.
 * ====================================================================== */

/** Every body whose shape overlaps the box [lo, hi] (m), to fn. The box
 *  is the one lo and hi span: a coordinate of lo above hi's is swapped
 *  with it, not an error. */
carom_status carom_world_query_box(const carom_world *w, carom_vec2 lo,
                                   carom_vec2 hi, carom_query_fn fn,
                                   void *ctx);

/** Every body whose shape contains the point p (m), to fn. */
carom_status carom_world_query_point(const carom_world *w, carom_vec2 p,
                                     carom_query_fn fn, void *ctx);

/** The first shape the segment from `from` to `to` enters (a ray starting
 * inside a shape does not hit it). *found: 1 if hit, else 0. Both ends
 * within CAROM_LIMIT_MAX_LENGTH of the origin in x and y, else
 * CAROM_ERR_OUT_OF_RANGE (CAROM_ERR_NOT_FINITE if not finite). */
carom_status carom_world_raycast(const carom_world *w, carom_vec2 from,
                                 carom_vec2 to, carom_ray_hit *hit,
                                 int *found);

/** Every shape the segment enters, nearest first, into hits[0..cap);
 * *count gets how many there are (more than cap: the rest were not
 * stored). */
carom_status carom_world_raycast_all(const carom_world *w, carom_vec2 from,
                                     carom_vec2 to, carom_ray_hit *hits,
                                     int cap, int *count);

/** The body whose state failed the last step's end check
 * (CAROM_ERR_NOT_FINITE or CAROM_ERR_OUT_OF_RANGE), or -1. */
int carom_world_error_body(const carom_world *w);

/** The tolerances in use, after CAROM_AUTO is resolved (they follow the
 * bodies' sizes, so they may change as bodies are added). */
typedef struct carom_tolerances {
    float length_unit;   /**< m */
    float linear_slop;   /**< m */
    float rest_speed;    /**< m/s, for a body under gravity alone */
    float sleep_speed;   /**< m/s */
    int substeps;        /**< substeps a step takes (carom_world_def.
                              substeps and max_substeps) */
} carom_tolerances;

carom_status carom_world_get_tolerances(const carom_world *w,
                                        carom_tolerances *out);

/** Counters accumulated since the world was made, and the largest needs
 * met (what `carom lean` reports as capacities). */
typedef struct carom_stats {
    long steps;
    long impacts;        /**< impacts taken (events methods) or restitution
                              contacts (discrete) */
    long impact_solves;  /**< simultaneous solves (one per impact instant) */
    long toi_queries;    /**< pair time-of-impact searches (events methods) */
    long toi_early_outs; /**< of which ruled out by the closest-approach
                              test before any root finding */
    long budget_steps;   /**< steps that met more impacts than max_impacts
                              and solved the rest of their contacts
                              together */
    long bounce_limits;  /**< discrete method: steps whose bounces would
                              have added kinetic energy to an island, and
                              were scaled back (docs/physics.md) */
    long continuous_stops; /**< bodies put back where their path met a
                              static or kinematic body they went into or
                              through (CAROM_ENABLE_CONTINUOUS,
                              docs/physics.md) */
    int max_pairs_used;  /**< most candidate pairs in one step */
    int max_contacts_used; /**< most contacts in one step */
    int max_impacts_used;  /**< most impacts in one step */
    int max_direct_used;   /**< most impulses of an exact island solve
                                (CAROM_IMPACT_DIRECT_MAX; 0: none tried) */
    int max_rows_used;     /**< most contact rows one simultaneous impact
                                solve had to have room for to look at
                                every contact it would with more (a
                                build whose CAROM_IMPACT_ROWS_MAX is this
                                takes the same path to the last bit) */
    int awake_bodies;    /**< bodies simulated in the last step */
    int contacts;        /**< contacts in the last step */
    int substeps;        /**< substeps the last step took: the tolerances'
                              count, or more where touching contacts join
                              bodies of unlike masses
                              (CAROM_SUBSTEP_MASS_RATIO) */
    int grows;           /**< times a step took a larger pool from
                              carom_world_def.grow */
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
    CAROM_PHASE_BROADPHASE,    /**< "broadphase": boxes, grid, pairs */
    CAROM_PHASE_NARROWPHASE,   /**< "narrowphase": contact manifolds */
    CAROM_PHASE_IMPACT_TIMING, /**< "impact_timing": time of impact, early-out */
    CAROM_PHASE_IMPULSES,      /**< "impulse_resolution": impact impulses */
    CAROM_PHASE_RESTING,       /**< "resting_contacts": the contact solver */
    CAROM_PHASE_COUNT
} carom_phase;

/** Counters; the caller owns it, resets it, and attaches it to a world.
 * They accumulate over the steps taken while attached: reset before a step
 * to read that step's counts, or divide by steps for the average. */
typedef struct carom_profile {
    uint64_t ops[CAROM_PHASE_COUNT][CAROM_OP_COUNT];
    uint64_t steps;      /**< steps taken while attached */
    uint64_t body_steps; /**< sum over those steps of the body count */
    uint64_t impacts;    /**< impacts while attached */
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

/** Weighted sum of the counts of one phase (0 .. CAROM_PHASE_COUNT - 1),
 * or of all phases if phase is CAROM_PHASE_COUNT; 0 for any other phase,
 * a NULL argument, or a library built without CAROM_ENABLE_PROFILE (whose
 * steps count nothing). Summed in order, in float. */
float carom_profile_cost(const carom_profile *p, const carom_op_weights *wt,
                         int phase);

/** "add", "sub", ... and "integration", "broadphase", ... */
const char *carom_op_name(carom_op op);
const char *carom_phase_name(carom_phase phase);

#ifdef __cplusplus
}
#endif

#endif /* CAROM_H */
