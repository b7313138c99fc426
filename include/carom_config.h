/*
 * carom_config.h -- every compile-time switch, limit and default of carom.
 * Override any of them with -DNAME=VALUE when building the library, and use
 * the same values when compiling code that includes carom.h.
 *
 * Switches are 0 (off) or 1 (on). A switch that is off removes the code of
 * that capability from the library; asking for it at run time returns
 * CAROM_ERR_DISABLED instead of silently doing something else.
 * `build/carom lean SCENE` prints the smallest set that gives the same
 * results on a scene.
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
                                     contacts are frictionless (a body
                                     definition's friction is kept and
                                     unused, so a scene measured by
                                     `carom lean` loads; setting a
                                     friction > 0 after creation asks for
                                     what is not there:
                                     CAROM_ERR_DISABLED) */
#endif

#ifndef CAROM_ENABLE_FORCES
#define CAROM_ENABLE_FORCES 1 /**< per-body constant force/torque, one-step
                                   forces and the user force callback; off:
                                   gravity only */
#endif

#ifndef CAROM_ENABLE_EVENTS
#define CAROM_ENABLE_EVENTS 1 /**< in-step impact timing (methods "events"
                                   and "first-impact"); off: only the
                                   "discrete" method */
#endif

#ifndef CAROM_ENABLE_DISCRETE
#define CAROM_ENABLE_DISCRETE 1 /**< the "discrete" method (contacts at the
                                     step's end, one restitution pass);
                                     off: only the events methods (needs
                                     CAROM_ENABLE_EVENTS), about 1.5 KB
                                     less code */
#endif

#if !CAROM_ENABLE_DISCRETE && !CAROM_ENABLE_EVENTS
#error "carom: CAROM_ENABLE_DISCRETE and CAROM_ENABLE_EVENTS are both 0: no method is left (turn one on)"
#endif

#ifndef CAROM_ENABLE_CONTINUOUS
#define CAROM_ENABLE_CONTINUOUS 1 /**< the step's last guard against a
                                       tunnel: a dynamic body whose step
                                       carried it into or through a static
                                       or kinematic body (a spin faster
                                       than the contact solver follows,
                                       several bodies met in a step, an
                                       impulse past its box, a kinematic
                                       wall or blade faster than its
                                       contacts) is put back where its path
                                       met that body and takes Newton's
                                       impulse there (docs/physics.md,
                                       "Continuous collision against
                                       static bodies"); and a body another
                                       may push into a static or kinematic
                                       one has its pairs with it (world.c,
                                       "Pushed reach"); off: no check, no
                                       such pairs, 10.8 KB less code
                                       (Cortex-M4F) */
#endif

#ifndef CAROM_ENABLE_SLEEP
#define CAROM_ENABLE_SLEEP 1 /**< islands of touching bodies fall asleep when
                                  they stay slow (world def enable_sleep);
                                  off: every body is simulated every step */
#endif

#ifndef CAROM_ENABLE_COMPENSATED
#define CAROM_ENABLE_COMPENSATED 1 /**< positions and velocities carry a
                                        compensation term (Kahan), so the
                                        rounding of x += v dt does not pile
                                        up as dt shrinks (docs/accuracy.md);
                                        off: plain float sums */
#endif

#ifndef CAROM_ENABLE_KINEMATIC
#define CAROM_ENABLE_KINEMATIC 1 /**< kinematic bodies: moved by the velocity
                                      the program sets, push dynamic bodies,
                                      unaffected by them */
#endif

#ifndef CAROM_ENABLE_FILTERING
#define CAROM_ENABLE_FILTERING 1 /**< collision filter: category and mask
                                      bits and a group index per body */
#endif

#ifndef CAROM_ENABLE_SENSORS
#define CAROM_ENABLE_SENSORS 1 /**< sensor bodies: report overlaps, exert no
                                    impulses */
#endif

#ifndef CAROM_ENABLE_QUERIES
#define CAROM_ENABLE_QUERIES 1 /**< box overlap, ray cast and point queries */
#endif

#ifndef CAROM_ENABLE_BODY_EDITS
#define CAROM_ENABLE_BODY_EDITS 1 /**< changing a body after it is added:
                                       carom_world_remove_body and the
                                       carom_body_set_* / carom_body_apply_*
                                       calls (not user data); off: they
                                       return CAROM_ERR_DISABLED, about
                                       2 KB less code, for programs that
                                       only add bodies and step */
#endif

#ifndef CAROM_ENABLE_TOUCH_EVENTS
#define CAROM_ENABLE_TOUCH_EVENTS 1 /**< begin-touch / end-touch reports */
#endif

#ifndef CAROM_ENABLE_STACKING
#define CAROM_ENABLE_STACKING 1 /**< support order, priming of new stacks,
                                     the warm start's unloading and
                                     shock propagation: what keeps tall
                                     stacks and heavy-on-light piles standing
                                     under gravity; off: smaller code for
                                     scenes without gravity, where these
                                     passes do nothing */
#endif

#ifndef CAROM_ENABLE_GRID
#define CAROM_ENABLE_GRID 1 /**< the uniform grid of the broadphase: pairs
                                 and queries in time linear in the bodies;
                                 off: every box is tested against every
                                 other (n^2 / 2 tests, the same pairs in
                                 the same order), about 4 KB less code and
                                 no grid arrays: for worlds of a few dozen
                                 bodies (`carom lean` turns it off up to
                                 64) */
#endif

#ifndef CAROM_ENABLE_ANGLES
#define CAROM_ENABLE_ANGLES 1 /**< the angle helpers carom_rot_from_angle()
                                   and carom_rot_angle(); off: they are not
                                   declared (programs give rotations as
                                   (cos, sin) pairs), about 0.9 KB less
                                   code when rotation is off too */
#endif

#ifndef CAROM_ENABLE_STATUS_NAMES
#define CAROM_ENABLE_STATUS_NAMES 1 /**< carom_status_string() names every
                                         status; off: one generic string
                                         (saves the table, about 1 KB) */
#endif

#ifndef CAROM_ENABLE_GROW
#define CAROM_ENABLE_GROW 1 /**< memory on demand (carom_world_def.grow): a
                                 step short of pair or contact capacity
                                 takes a larger pool from the program's
                                 allocator; off: a world given an
                                 allocator is refused (CAROM_ERR_DISABLED)
                                 and capacities are hard limits */
#endif

#ifndef CAROM_ENABLE_PROFILE
#define CAROM_ENABLE_PROFILE 0 /**< count every float operation by kind and
                                    phase; off: the arithmetic layer is plain
                                    float code and no counter exists */
#endif

/* Finer cuts for lean builds (`carom lean`): shape pairs a scene never
 * meets. Each is implied off when CAROM_ENABLE_POLYGONS is 0. */
#ifndef CAROM_ENABLE_POLYGON_POLYGON
#define CAROM_ENABLE_POLYGON_POLYGON 1 /**< polygon-polygon contacts (SAT and
                                            clipping); off: polygons meet
                                            only circles */
#endif

#ifndef CAROM_ENABLE_DYNAMIC_POLYGONS
#define CAROM_ENABLE_DYNAMIC_POLYGONS 1 /**< dynamic (and kinematic) polygons;
                                             off: polygons may only be
                                             static (walls, floors) */
#endif

/* ---- limits ------------------------------------------------------------ */

#ifndef CAROM_MAX_POLYGON_VERTICES
#define CAROM_MAX_POLYGON_VERTICES 8 /**< vertices per convex polygon */
#endif

#ifndef CAROM_MAX_MANIFOLD_POINTS
#define CAROM_MAX_MANIFOLD_POINTS 2 /**< contact points per body pair (2 is
                                         what 2D convex shapes need) */
#endif

/* Body ids carry the slot index in their low CAROM_ID_INDEX_BITS bits and a
 * generation count above it, so an id of a removed body is rejected
 * (CAROM_ERR_STALE_ID) instead of naming whoever reuses the slot. A fresh
 * world numbers bodies 0, 1, 2, ... (generation 0). */
#ifndef CAROM_ID_INDEX_BITS
#define CAROM_ID_INDEX_BITS 20 /**< so max_bodies <= 2^20 (1,048,576); the
                                    generation wraps after 2^11 reuses of a
                                    slot */
#endif

/* Ranges carom guarantees (docs/robustness.md). Inputs outside them are
 * refused with CAROM_ERR_OUT_OF_RANGE (or the field's own status), so that
 * every derived quantity (inverse mass and inertia, v dt, a dt^2, squared
 * distances) stays a finite, normal float. */
#ifndef CAROM_LIMIT_MAX_LENGTH
#define CAROM_LIMIT_MAX_LENGTH 1.0e8f /**< m: |position| components, vertex
                                           coordinates, radius, half-extents */
#endif
#ifndef CAROM_LIMIT_MIN_SIZE
#define CAROM_LIMIT_MIN_SIZE 1.0e-6f /**< m: smallest radius or half-width of
                                          a body; smaller bodies' inertia
                                          underflows */
#endif
#ifndef CAROM_LIMIT_MAX_SPEED
#define CAROM_LIMIT_MAX_SPEED 1.0e8f /**< m/s: |velocity| components, and
                                          |angular velocity| times the body's
                                          extent */
#endif
#ifndef CAROM_LIMIT_MAX_ACCEL
#define CAROM_LIMIT_MAX_ACCEL 1.0e12f /**< m/s^2: |gravity| components and
                                           every force / mass (also torque
                                           times extent / inertia) */
#endif
#ifndef CAROM_LIMIT_MIN_MASS
#define CAROM_LIMIT_MIN_MASS 1.0e-20f /**< kg (and kg m^2 for inertia) */
#endif
#ifndef CAROM_LIMIT_MAX_MASS
#define CAROM_LIMIT_MAX_MASS 1.0e20f /**< kg (and kg m^2 for inertia) */
#endif
#ifndef CAROM_LIMIT_MAX_FRICTION
#define CAROM_LIMIT_MAX_FRICTION 1.0e6f /**< largest friction coefficient
                                             (real ones are below 2; at
                                             1e20 the friction impulses
                                             overflowed in the first step) */
#endif
#ifndef CAROM_LIMIT_MIN_DT
#define CAROM_LIMIT_MIN_DT 1.0e-7f /**< s: smallest time step */
#endif
#ifndef CAROM_LIMIT_MAX_DT
#define CAROM_LIMIT_MAX_DT 10.0f /**< s: largest time step */
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
#define CAROM_DEFAULT_PAIRS_PER_BODY 6 /**< candidate pair capacity (bounding
                                            boxes that overlap) is this times
                                            max_bodies; a pile of equal
                                            circles needs about 3.5 */
#endif

#ifndef CAROM_DEFAULT_CONTACTS_PER_BODY
#define CAROM_DEFAULT_CONTACTS_PER_BODY 3 /**< contact capacity (pairs within
                                               contact distance, with a
                                               manifold) is this times
                                               max_bodies; a pile of 10^4
                                               circles and boxes needs 1.9 */
#endif

#ifndef CAROM_DEFAULT_EVENTS_PER_BODY
#define CAROM_DEFAULT_EVENTS_PER_BODY 2 /**< impacts recorded per step (for
                                             carom_world_events) is this times
                                             max_bodies, at least
                                             CAROM_MIN_EVENTS; more are
                                             counted, not an error */
#endif

#ifndef CAROM_MIN_EVENTS
#define CAROM_MIN_EVENTS 64
#endif

#ifndef CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY
#define CAROM_DEFAULT_TOUCH_EVENTS_PER_BODY 1 /**< begin/end-touch events
                                                   recorded per step is this
                                                   times max_bodies, at least
                                                   CAROM_MIN_EVENTS */
#endif

#ifndef CAROM_DEFAULT_IMPACTS_PER_BODY
#define CAROM_DEFAULT_IMPACTS_PER_BODY 64 /**< impacts the events methods take
                                               one at a time per step: this
                                               times the body count, at least
                                               CAROM_MIN_IMPACTS; past it the
                                               rest of the step's contacts
                                               are solved together */
#endif

#ifndef CAROM_MIN_IMPACTS
#define CAROM_MIN_IMPACTS 16384
#endif

#ifndef CAROM_DEFAULT_SUBSTEPS
#define CAROM_DEFAULT_SUBSTEPS 4 /**< contact substeps per step: resting
                                      contacts are solved this many times a
                                      step (docs/physics.md) */
#endif

#ifndef CAROM_DEFAULT_MAX_SUBSTEPS
#define CAROM_DEFAULT_MAX_SUBSTEPS 64 /**< most substeps a step takes on its
                                           own (carom_world_def.max_substeps,
                                           at most 64): more than `substeps`
                                           where gravity would move a body
                                           from rest by more than
                                           CAROM_SUBSTEP_FALL_SLOPS in one
                                           substep (small bodies, long steps)
                                           or where unlike masses touch
                                           (docs/physics.md); only those
                                           steps pay for it */
#endif

#ifndef CAROM_SUBSTEP_FALL_SLOPS
#define CAROM_SUBSTEP_FALL_SLOPS 1.0f /**< how far (in linear slops of the
                                           length unit, CAROM_SLOP_PER_LENGTH
                                           x L) a body may fall from rest in
                                           one substep: g h^2 / 2 <= this x
                                           slop sets the substep count */
#endif

#ifndef CAROM_SUBSTEP_MASS_RATIO
#define CAROM_SUBSTEP_MASS_RATIO 2.0f /**< a step whose touching contacts
                                           join dynamic bodies of masses R >
                                           this apart lets a body fall only
                                           1 / R as far per substep: up to
                                           max_substeps where heavy bodies
                                           rest on light ones (stacks and
                                           ball pits of mixed densities;
                                           docs/physics.md) */
#endif

#ifndef CAROM_DEFAULT_ITERATIONS
#define CAROM_DEFAULT_ITERATIONS 1 /**< contact sweeps per substep */
#endif

#ifndef CAROM_DEFAULT_RELAX_ITERATIONS
#define CAROM_DEFAULT_RELAX_ITERATIONS 2 /**< velocity sweeps per substep
                                              after the bodies moved (a
                                              500-body pour: worst overlap
                                              3.3 mm with two, 139 mm with
                                              none) */
#endif

#ifndef CAROM_DEFAULT_SLEEP_TIME
#define CAROM_DEFAULT_SLEEP_TIME 0.5f /**< s an island must stay slow before
                                           it sleeps (as Box2D) */
#endif

/* Body defaults (carom_default_body_def) */
#ifndef CAROM_DEFAULT_RADIUS
#define CAROM_DEFAULT_RADIUS 0.5f /**< m: a circle of unit diameter */
#endif
#ifndef CAROM_DEFAULT_DENSITY
#define CAROM_DEFAULT_DENSITY 1.0f /**< kg/m^2 (2D: mass per area) */
#endif
#ifndef CAROM_DEFAULT_FRICTION
#define CAROM_DEFAULT_FRICTION 0.6f /**< Coulomb coefficient (as Box2D) */
#endif
#ifndef CAROM_DEFAULT_RESTITUTION
#define CAROM_DEFAULT_RESTITUTION 0.0f /**< Newton's coefficient: plastic */
#endif

/* ---- scale: tolerances derived from a length unit and |a| dt ------------ */
/*
 * carom has no absolute tolerance in metres or m/s. With the world's
 * length_unit L (CAROM_AUTO: the mean equivalent radius sqrt(area / pi) of
 * the dynamic bodies, so a scene scaled by 100 in lengths and gravity
 * behaves the same) and each body's acceleration |a| (gravity plus force /
 * mass):
 *   linear slop        CAROM_SLOP_PER_LENGTH x L, at least
 *                      CAROM_SLOP_SPACINGS float spacings of the body
 *                      centre farthest from the origin
 *   speculative reach  CAROM_SPECULATIVE_SLOPS x slop, plus the motion of
 *                      the pair in the step
 *   push-out speed     CAROM_PUSH_SPEED_PER_LENGTH x L per second
 *   rest speed         CAROM_REST_SPEED_PER_ACCEL_DT x |a| dt (0 in zero
 *                      gravity: every impact then bounces)
 *   sleep speed        CAROM_SLEEP_SPEED_PER_LENGTH x L per second
 * Each can be fixed instead in the world definition.
 */
#ifndef CAROM_SLOP_PER_LENGTH
#define CAROM_SLOP_PER_LENGTH 1.0e-3f /**< contact distance per length unit:
                                           0.56 mm for unit boxes */
#endif

#ifndef CAROM_SLOP_SPACINGS
#define CAROM_SLOP_SPACINGS 8.0f /**< the automatic slop is at least this
                                      many float spacings (FLT_EPSILON x
                                      |x|) of the body centre farthest from
                                      the origin, so that the positions
                                      resolve it (a pyramid at y = 1e4,
                                      where floats are 1 mm apart, crept
                                      0.5 m a minute with a 0.56 mm slop);
                                      it binds beyond about 1,000 length
                                      units from the origin */
#endif

#ifndef CAROM_SPECULATIVE_SLOPS
#define CAROM_SPECULATIVE_SLOPS 4.0f /**< contacts are kept up to this many
                                          slops apart (plus the step's
                                          motion), so they exist before they
                                          touch */
#endif

#ifndef CAROM_PUSH_SPEED_PER_LENGTH
#define CAROM_PUSH_SPEED_PER_LENGTH 6.0f /**< 1/s: fastest speed an overlap is
                                              pushed apart (3.4 m/s for unit
                                              boxes, whose equivalent radius
                                              is 0.56 m; Box2D v3 uses 3) */
#endif

#ifndef CAROM_REST_SPEED_PER_ACCEL_DT
#define CAROM_REST_SPEED_PER_ACCEL_DT 2.0f /**< approaches slower than this
                                                times |a| dt are resting
                                                contact, not impacts */
#endif

#ifndef CAROM_SLEEP_SPEED_PER_LENGTH
#define CAROM_SLEEP_SPEED_PER_LENGTH 0.1f /**< 1/s: bodies slower than this
                                               times L (points of a rotating
                                               body included) count as still */
#endif

#ifndef CAROM_SLEEP_SPEEDUP
#define CAROM_SLEEP_SPEEDUP 0.1f /**< a slow body whose speed has grown by
                                      this fraction of the sleep speed since
                                      it became slow is starting to move (a
                                      leaning tower tipping over), not
                                      still: its still time starts again */
#endif

#ifndef CAROM_SLEEP_SPEEDUP_PER_G
#define CAROM_SLEEP_SPEEDUP_PER_G 0.001f /**< under gravity, at most this
                                              fraction of |g| x sleep_time
                                              (5 mm/s at 10 m/s^2, 0.5 s):
                                              big bodies tip slowly */
#endif

#ifndef CAROM_SLEEP_WINDOW
#define CAROM_SLEEP_WINDOW 8.0f /**< sleep times: a body that has stayed
                                     within the sleep speed times this
                                     window of where it was for a whole
                                     window (its mean speed under the
                                     sleep speed) counts as still too: a
                                     box rocking on a rolling circle, which
                                     no contact damps, keeps a pile awake
                                     for ever otherwise (docs/physics.md) */
#endif

/* ---- the contact solver (docs/physics.md) ------------------------------- */

#ifndef CAROM_POSITION_CORRECTION
#define CAROM_POSITION_CORRECTION 0.2f /**< fraction of an overlap removed per
                                            substep, on positions only (at
                                            most the push-out speed times
                                            the substep) */
#endif

#ifndef CAROM_SOFT_DEEP_CONTACTS
#define CAROM_SOFT_DEEP_CONTACTS 0 /**< 1: in a jam of unlike densities
                                        (two dynamic bodies of densities
                                        more than 2 times apart overlapping
                                        deeper than 10 slops at rest), the
                                        overlap past 10 slops of a resting
                                        contact with a body of unlike mass
                                        is pushed out by a soft damped
                                        spring in the velocity sweeps (Box2D
                                        v3's soft contact) instead of the
                                        position correction. It settles
                                        mixed piles the rigid correction
                                        keeps churning, with deeper
                                        overlaps (docs/physics.md, "Deep
                                        overlaps of unlike bodies") */
#endif

#ifndef CAROM_EXACT_PILE_IMPACTS
#define CAROM_EXACT_PILE_IMPACTS 0 /**< 1: the events methods take every
                                        impact at its instant, also an
                                        inelastic meeting on a resting
                                        body of like mass (a body landing
                                        on a pile), which by default is
                                        the contact solver's, as in the
                                        discrete method: no bounce to
                                        time, 1.5 to 2 times faster on a
                                        falling pile (docs/events.md,
                                        "Inelastic meetings on resting
                                        bodies") */
#endif

#ifndef CAROM_FACE_TOL_PER_SLOP
#define CAROM_FACE_TOL_PER_SLOP 0.1f /**< two polygons' faces whose
                                          separations differ by less than
                                          this many slops count as equal: the
                                          manifold keeps its reference face,
                                          so aligned edges never flip it */
#endif

#ifndef CAROM_CORNER_SLOPS
#define CAROM_CORNER_SLOPS 2.0f /**< seams: a polygon overlapping a static
                                     body's face only this many linear
                                     slops near one end, and dipping no
                                     deeper below the face that meets it
                                     there, grazes the corner; where
                                     another contact with a static body
                                     holds it on that face's plane
                                     (static tiles whose tops meet
                                     flush), the graze makes no contact,
                                     so a body slides over the seam
                                     instead of striking the next tile's
                                     side (docs/physics.md, "Seams"); 0:
                                     every graze makes its contact */
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
                                      the linear slop */
#endif

#ifndef CAROM_SIMULTANEOUS_TIME_TOL
#define CAROM_SIMULTANEOUS_TIME_TOL 1.0e-7f /**< impacts whose times differ by
                                                 less than this fraction of
                                                 dt are simultaneous: solved
                                                 together */
#endif

#ifndef CAROM_IMPACT_ISLAND_MAX_BODIES
#define CAROM_IMPACT_ISLAND_MAX_BODIES 256 /**< bodies one simultaneous impact
                                                solve reaches through resting
                                                contacts (a stack struck from
                                                above) */
#endif

#ifndef CAROM_IMPACT_ISLAND_ITERATIONS
#define CAROM_IMPACT_ISLAND_ITERATIONS 128 /**< most sweeps of a simultaneous
                                                impact solve; it stops
                                                earlier once converged */
#endif

#ifndef CAROM_IMPACT_ROWS_MAX
#define CAROM_IMPACT_ROWS_MAX 1024 /**< contact rows (pairs) one simultaneous
                                        impact solve holds, at most; the
                                        world holds min(this, 4 x the
                                        island's bodies, max_pairs) rows of
                                        144 bytes. An instant with more
                                        impacts takes the rest right after;
                                        an island grows no further. `carom
                                        lean` sets it to what the scene
                                        used (1 at least) */
#endif

#ifndef CAROM_IMPACT_DIRECT_MAX
#define CAROM_IMPACT_DIRECT_MAX 24 /**< an impact solve whose sweeps converge
                                        slowly solves its acting rows
                                        exactly when they are at most this
                                        many impulses; the world buffer
                                        holds its N x N matrix (2.4 KB at
                                        24, less in worlds of few pairs);
                                        0: sweeps only */
#endif

#ifndef CAROM_POLYGON_ANGLE_TOL
#define CAROM_POLYGON_ANGLE_TOL 1.0e-4f /**< smallest turn (sine of the angle)
                                             at a polygon vertex: flatter
                                             vertices are degenerate */
#endif

#endif /* CAROM_CONFIG_H */
