/*
 * body.h -- bodies: the hot state every step reads and writes, the cold
 * definition (shape, mass, material) fixed at creation, and the helpers
 * that read shapes (internal).
 */
#ifndef CAROM_BODY_H
#define CAROM_BODY_H

#include "arith.h"

/* Flags of cr_body.flags */
#define CR_BODY_ALIVE 1u    /* the slot holds a body */
#define CR_BODY_AWAKE 2u    /* simulated this step (not asleep) */
#define CR_BODY_SENSOR 4u   /* reports overlaps, no contact impulses */
#define CR_BODY_FILTERED 8u /* has a collision filter other than the
                               default (category 1, every mask bit, no
                               group): pairs read its info */
#define CR_BODY_ONCE 16u    /* has a force or torque for the next step
                               only (carom_body_apply_force/torque) */
#define CR_BODY_CIRCLE 32u  /* its shape is a circle (read in the solver's
                               hot loops without touching the cold info) */
#define CR_BODY_ESCAPED 64u /* ended the last step outside its grid box
                               (pushed by an impulse past its swept box):
                               queries and sensors test its pose directly */
#define CR_BODY_REGROWN 128u /* its box grew during this step (an impact):
                                the grid filed it by its first box, so it
                                counts as escaped (queries, sensors) */
#define CR_BODY_CARRIED 256u /* the continuous guard put it back against a
                                kinematic body in this step: its end pose
                                is the guard's, not a path to sweep again
                                (set and cleared within the guard) */
#define CR_BODY_NEW 512u /* added since the last step: the step primes the
                            solver only if a contact holds a new body */
#define CR_BODY_PUT_BACK 1024u /* the continuous guard put it back at its
                                  start pose, where it touched a static
                                  body, in this step ... */
#define CR_BODY_PUT_BACK_LAST 2048u /* ... and in the last step */
#define CR_BODY_TELEPORTED 4096u /* set_transform since the last step: its
                                    touches are found anew, none carried */
#define CR_BODY_CAPPED 8192u /* touches a static body above it (a ceiling):
                                the shock sweeps of its supports never push
                                it up (cr_solver_levels, every step) */
#define CR_BODY_SHIFTED 16384u /* the position sweep moved it more than a
                                  slop in a substep of this step: pushed
                                  out of an overlap, not at rest
                                  (cr_solver_correct, cr_island_sleep) */
#define CR_BODY_RESTS 32768u /* events methods: dynamic, and touching a
                                body at this step's start without closing
                                on it faster than the impact bound
                                (cr_solver_levels), or left touching one by
                                an impact of this step (events.c): what
                                lands on it inelastically is the solver's
                                (cr_onto_rest) */

/*
 * Hot state of a body, compact so that the step's loops touch little
 * memory. A copy of the whole array is kept at the start of each step, so
 * a failed step can be undone exactly.
 */
/* Is a shape kind, or a body, a circle? Always, in a build without
 * polygons (so the polygon branches compile away). */
#define CR_KIND_CIRCLE(kind) (!CAROM_ENABLE_POLYGONS || (kind) == CAROM_SHAPE_CIRCLE)
#define CR_BODY_IS_CIRCLE(b) (!CAROM_ENABLE_POLYGONS || ((b)->flags & CR_BODY_CIRCLE))

typedef struct cr_body {
    cr_v2 x;      /* centre of mass, world */
    cr_rot q;     /* rotation */
    cr_v2 v;      /* velocity of the centre of mass */
    float w;      /* angular velocity */
    cr_v2 a;      /* acceleration of the forces at the current state (a0) */
    float alpha;  /* angular acceleration of the torques at the current state */
#if CAROM_ENABLE_COMPENSATED
    cr_v2 xc, vc; /* compensation terms of x and v (cr_kadd) */
    float wc;     /* and of w */
#endif
    float inv_m, inv_I; /* 0 for static and kinematic bodies */
    float still_time;   /* s the body has been below the sleep speed */
    int sleep_island;   /* asleep: the island it fell asleep with (here, not
                           in the cold info, so a failed step's undo puts it
                           back with the rest) */
    unsigned short type;  /* carom_body_type */
    unsigned short flags; /* CR_BODY_* */
} cr_body;

/* Geometry, in the body frame with the centre of mass at the origin. */
typedef struct cr_shape {
    int kind;           /* carom_shape_type */
    int count;          /* polygon vertex count */
    float radius;       /* circle */
    float extent;       /* largest distance from the centre of mass */
    float half_width;   /* half the smallest width (circle: the radius) */
    float size;         /* equivalent radius sqrt(area / pi): the body's
                           contribution to the world's length unit */
    cr_v2 local_center; /* centre of mass in the definition's frame */
#if CAROM_ENABLE_POLYGONS
    cr_v2 verts[CAROM_MAX_POLYGON_VERTICES]; /* counter-clockwise */
    cr_v2 norms[CAROM_MAX_POLYGON_VERTICES]; /* outward unit edge normals */
#endif
} cr_shape;

/* Cold data: set when the body is made (and by the setters). */
typedef struct cr_body_info {
    cr_shape shape;
    float m, I;                /* mass and inertia (0 if not dynamic) */
    float restitution, friction;
    cr_v2 force;               /* constant force at the centre */
    float torque;              /* constant torque */
    cr_v2 force_once;          /* force for the next step only */
    float torque_once;         /* torque for the next step only */
    uint32_t category, mask;   /* collision filter */
    int group;
    void *user_data;
    unsigned generation;       /* of the id that names this slot */
    cr_v2 sleep_x;             /* sleep (island.c): the pose at the start */
    cr_rot sleep_q;            /* of the window of its mean speed, */
    float sleep_window;        /* the window's length so far */
    float sleep_travel;        /* how far it had gone in it last step */
    float sleep_away;          /* s it has gone further every step */
    float still_speed;         /* the slowest speed since still_time began */
    float still_max;           /* and the fastest */
} cr_body_info;

/* Do bodies with infos a and b (either CR_BODY_FILTERED) collide? */
int cr_filter_pass(const cr_body_info *a, const cr_body_info *b);

/* Validate `def` completely and build the body; *hot and *info are
 * written only on success. */
carom_status cr_body_build(const carom_body_def *def, cr_body *hot,
                           cr_body_info *info);

/* Axis-aligned box of the shape at pose (x, q). */
typedef struct cr_box {
    float lo_x, lo_y, hi_x, hi_y;
} cr_box;

void cr_shape_box(const cr_shape *s, cr_v2 x, cr_rot q, cr_box *out);

/* World position of the definition's origin: centre minus rotated offset. */
cr_v2 cr_body_origin(const cr_body *b, const cr_body_info *info);

#if CAROM_ENABLE_FORCES
/* The acceleration limit check of a force and torque on a body: 0 if
 * a = F / m or alpha times extent is beyond CAROM_LIMIT_MAX_ACCEL. */
int cr_accel_in_range(const cr_body_info *info, cr_v2 force, float torque);
#endif

/* The smallest c^2 + s^2 of a rotation pair that normalizes to a unit
 * pair (FLT_MIN: below it the square is denormal and the square root too
 * coarse); shorter pairs, and pairs whose square overflows, are refused
 * with CAROM_ERR_BAD_ROTATION. */
#define CR_ROT_MIN_LEN2 1.17549435e-38f

/* |x| <= limit for both components, x finite. */
CR_INLINE int cr_v2_within(cr_v2 x, float limit)
{
    return cr_le(cr_abs(x.x), limit) && cr_le(cr_abs(x.y), limit);
}

/* Can the body move this step: an awake dynamic body, or a kinematic body
 * given a velocity? Static bodies, sleeping bodies and kinematic bodies at
 * rest stand still: two such bodies never pair, and a sleeping body
 * touching only such bodies stays asleep. */
int cr_body_moves(const cr_body *b);

#endif /* CAROM_BODY_H */
