/*
 * carom_config.h -- every compile-time switch and limit of carom, with its
 * default. Override any of them with -DNAME=VALUE when building the library
 * (and use the same values when compiling code that includes carom.h).
 *
 * Switches are 0 (off) or 1 (on). A switch that is off removes the code of
 * that capability from the library; asking for it at run time returns
 * CAROM_ERR_DISABLED instead of silently doing something else.
 */
#ifndef CAROM_CONFIG_H
#define CAROM_CONFIG_H

/* ---- capabilities ------------------------------------------------------ */

#ifndef CAROM_ENABLE_POLYGONS
#define CAROM_ENABLE_POLYGONS 1 /**< convex polygons; off: circles only */
#endif

#ifndef CAROM_ENABLE_ROTATION
#define CAROM_ENABLE_ROTATION 1 /**< angular motion; off: bodies keep their
                                     initial orientation (infinite inertia) */
#endif

#ifndef CAROM_ENABLE_FRICTION
#define CAROM_ENABLE_FRICTION 1 /**< Coulomb friction at contacts; off: all
                                     contacts are frictionless */
#endif

#ifndef CAROM_ENABLE_FORCES
#define CAROM_ENABLE_FORCES 1 /**< per-body constant force/torque and the
                                   user force callback; off: gravity only */
#endif

#ifndef CAROM_ENABLE_EVENTS
#define CAROM_ENABLE_EVENTS 1 /**< in-step impact timing (method "events");
                                   off: only the "discrete" method */
#endif

#ifndef CAROM_ENABLE_PROFILE
#define CAROM_ENABLE_PROFILE 0 /**< count every float operation by kind and
                                    phase; off: the arithmetic layer is plain
                                    float code and no counter exists */
#endif

/* ---- limits ------------------------------------------------------------ */

#ifndef CAROM_MAX_POLYGON_VERTICES
#define CAROM_MAX_POLYGON_VERTICES 8 /**< vertices per convex polygon */
#endif

#ifndef CAROM_MAX_MANIFOLD_POINTS
#define CAROM_MAX_MANIFOLD_POINTS 2 /**< contact points per body pair */
#endif

/* ---- defaults of carom_world_def (see carom_default_world_def) ---------- */

#ifndef CAROM_DEFAULT_DT
#define CAROM_DEFAULT_DT (1.0f / 60.0f) /**< fixed time step, seconds */
#endif

#ifndef CAROM_DEFAULT_GRAVITY_Y
#define CAROM_DEFAULT_GRAVITY_Y (-10.0f) /**< gravity (0, g_y), m/s^2 */
#endif

#ifndef CAROM_DEFAULT_MAX_BODIES
#define CAROM_DEFAULT_MAX_BODIES 256 /**< body capacity of a world */
#endif

#ifndef CAROM_DEFAULT_PAIRS_PER_BODY
#define CAROM_DEFAULT_PAIRS_PER_BODY 4 /**< broadphase pair capacity is this
                                            times max_bodies */
#endif

#ifndef CAROM_DEFAULT_EVENTS_PER_BODY
#define CAROM_DEFAULT_EVENTS_PER_BODY 8 /**< default event capacity (impacts
                                             recorded and, for the events
                                             methods, processed per step) is
                                             this times max_bodies... */
#endif

#ifndef CAROM_MIN_EVENTS
#define CAROM_MIN_EVENTS 256 /**< ...but at least this many */
#endif

#ifndef CAROM_DEFAULT_REST_SPEED
#define CAROM_DEFAULT_REST_SPEED 0.5f /**< approach speed (m/s) below which a
                                           contact is resting: restitution is
                                           not applied, so a ball with e < 1
                                           comes to rest instead of bouncing
                                           ever lower (docs/physics.md) */
#endif

#ifndef CAROM_DEFAULT_LINEAR_SLOP
#define CAROM_DEFAULT_LINEAR_SLOP 0.0005f /**< contact distance (m): pairs
                                               closer than this are touching */
#endif

#ifndef CAROM_DEFAULT_VELOCITY_ITERATIONS
#define CAROM_DEFAULT_VELOCITY_ITERATIONS 10 /**< sequential impulse sweeps */
#endif

#ifndef CAROM_DEFAULT_POSITION_ITERATIONS
#define CAROM_DEFAULT_POSITION_ITERATIONS 6 /**< penetration projection sweeps */
#endif

/* ---- numerical constants (not meant to be tuned per scene) -------------- */

#ifndef CAROM_TOI_MAX_ITERATIONS
#define CAROM_TOI_MAX_ITERATIONS 64 /**< conservative advancement steps per
                                         time-of-impact query (rotating
                                         polygons); always terminates */
#endif

#ifndef CAROM_TOI_TOLERANCE
#define CAROM_TOI_TOLERANCE 0.1f /**< conservative advancement stops when the
                                      separation is below this fraction of
                                      linear_slop (0.05 mm by default) */
#endif

#ifndef CAROM_POSITION_BETA
#define CAROM_POSITION_BETA 0.8f /**< fraction of a penetration removed per
                                      projection sweep (1 overshoots in
                                      stacks, small values let them sink) */
#endif

#ifndef CAROM_MAX_LINEAR_CORRECTION
#define CAROM_MAX_LINEAR_CORRECTION 0.2f /**< cap (m) of one projection, so a
                                              deep overlap is undone over a
                                              few steps instead of exploding */
#endif

#ifndef CAROM_POLYGON_ANGLE_TOL
#define CAROM_POLYGON_ANGLE_TOL 1.0e-4f /**< smallest turn (sine of the angle)
                                             at a polygon vertex: flatter
                                             vertices are degenerate */
#endif

#endif /* CAROM_CONFIG_H */
