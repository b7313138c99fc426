/*
 * internal.h -- data structures shared by the pipeline modules (internal).
 *
 * Pipeline of one step (world.c, carom_world_step):
 *   integrate.c    velocity Verlet drift of every dynamic body
 *   broadphase.c   candidate pairs: sort and sweep over bounding boxes
 *   narrowphase.c  contact manifolds: circle/polygon pairs, SAT + clipping
 *   solver.c       impulses: restitution, friction, resting contacts,
 *                  penetration projection
 *   world.c        finish the step: events, time
 */
#ifndef CAROM_INTERNAL_H
#define CAROM_INTERNAL_H

#include "arith.h"
#include "carom.h"

/* ---- bodies ------------------------------------------------------------- */

typedef struct cr_proxy_box {
    float lo_x, hi_x, lo_y, hi_y;
} cr_proxy_box;

typedef struct cr_body {
    int type;  /* carom_body_type */
    int shape; /* carom_shape_type */
    float radius;                                /* circle */
    int count;                                   /* polygon */
    cr_v2 verts[CAROM_MAX_POLYGON_VERTICES];     /* body frame, about centroid */
    cr_v2 norms[CAROM_MAX_POLYGON_VERTICES];     /* outward unit edge normals */
    cr_v2 local_center; /* centroid in the frame of the definition's origin */
    float extent;       /* largest distance from the centroid to the shape */

    cr_v2 x;    /* centre of mass, world */
    cr_rot q;   /* rotation */
    cr_v2 vel;  /* velocity of the centre */
    float w;    /* angular velocity */
    cr_v2 acc;  /* acceleration from forces at the current state (a0) */
    float alpha;/* angular acceleration from torques at the current state */
    cr_v2 acc_c;   /* acceleration from last step's resting contact forces */
    float alpha_c; /* and its angular part (see solver.c) */

    /* events method: the state above is at local step time t_sync; the
     * drift acceleration (a0 + a_c) is constant through the step */
    float t_sync;
    cr_v2 acc_d;
    float alpha_d;
    cr_proxy_box sweep; /* box swept over the rest of the step */

    float m, inv_m, I, inv_I;
    float restitution, friction;
    cr_v2 force; /* constant force and torque */
    float torque;

    /* solver scratch: position projection accumulated this step, and the
     * velocities at the start of the step (before the force kick) */
    cr_v2 dx;
    float dtheta;
    cr_v2 vel_saved;
    float w_saved;
} cr_body;

/* ---- broadphase --------------------------------------------------------- */

typedef struct cr_proxy {
    float lo_x, hi_x, lo_y, hi_y;
    int body;
} cr_proxy;

typedef struct cr_pair {
    int a, b; /* a < b */
} cr_pair;

/* ---- contacts ----------------------------------------------------------- */

typedef struct cr_point {
    cr_v2 p;        /* world point, midway between the two surfaces */
    float sep;      /* signed distance along the normal (< 0: overlap) */
    unsigned id;    /* feature id, for matching across steps */
    cr_v2 ra, rb;   /* from each centre of mass to p */
    float rna, rnb; /* lever arms r x n of the normal impulse (exactly 0
                       for a circle: its normal passes through the centre) */
    float rta, rtb; /* lever arms r x t of the tangent impulse */
    float pn, pt;   /* accumulated normal and tangent impulses */
    float mass_n, mass_t;
    float target;   /* normal velocity the solver aims for (restitution) */
    float vn0;      /* normal velocity before the solve */
    float approach; /* approach speed at the instant of contact (>= 0) */
    float rest_frac;/* share of the impulse that is a resting force */
} cr_point;

typedef struct cr_manifold {
    int a, b;       /* body indices, a < b */
    cr_v2 n;        /* unit normal from a towards b */
    int count;      /* 0..CAROM_MAX_MANIFOLD_POINTS */
    cr_point pts[CAROM_MAX_MANIFOLD_POINTS];
    float restitution, friction;
    /* 2-point manifolds: normal effective-mass matrix [k11 k12; k12 k22],
     * and whether it is well enough conditioned to solve as a block */
    float k11, k12, k22;
    int block;
} cr_manifold;

/* ---- the world ---------------------------------------------------------- */

struct carom_world {
    carom_world_def def;
    carom_method method;
    long steps;

    cr_body *bodies;
    int body_count;

    cr_proxy *proxies, *proxy_tmp; /* max_bodies each */
    cr_pair *pairs, *pair_tmp;     /* max_pairs each */
    int pair_count;
    int pairs_dropped;

    float *pair_toi;               /* events method: next impact per pair */
    cr_manifold *manifolds, *prev_manifolds; /* max_pairs each */
    int manifold_count, prev_manifold_count;

    int needs_prime; /* bodies added since the contact forces were solved */
    long toi_queries, toi_early_outs; /* events method statistics */
    long impacts_total;

    carom_profile *profile; /* attached counters, or NULL */

    carom_event *events; /* max_events */
    int event_count;
    int events_dropped;
};

/* ---- module entry points ------------------------------------------------ */

/* profile.c: count what follows into the row of this phase */
#if CAROM_ENABLE_PROFILE
void cr_prof_phase(const carom_world *w, int phase);
#define CR_PHASE(w, phase) cr_prof_phase((w), (phase))
#define CR_PHASE_OFF() (carom__op_row = 0)
#else
#define CR_PHASE(w, phase) ((void)0)
#define CR_PHASE_OFF() ((void)0)
#endif

/* shape.c */
carom_status cr_body_build(const carom_body_def *def, cr_body *out);
void cr_body_bounds(const cr_body *b, float margin, cr_proxy *out);
carom_vec2 cr_body_origin(const cr_body *b);

/* integrate.c */
int cr_integrate(carom_world *w, float dt);
int cr_body_forces(const carom_world *w, int id, const cr_body *b,
                   cr_v2 *acc, float *alpha);
cr_rot cr_rot_advance(cr_rot q, float angle);

/* broadphase.c */
int cr_broadphase(carom_world *w, float margin);
int cr_broadphase_pairs(carom_world *w);

/* narrowphase.c */
int cr_collide(const cr_body *a, const cr_body *b, float margin,
               cr_manifold *m);
float cr_separation(const cr_body *a, const cr_body *b);

/* toi.c */
void cr_body_pose(const cr_body *b, float t, cr_v2 *x, cr_rot *q);
void cr_body_sync(cr_body *b, float t);
void cr_body_swept_bounds(const cr_body *b, float t0, float t1, float margin,
                          cr_proxy *out);
int cr_first_down_root2(float c0, float c1, float c2, float hi, float *out);
int cr_first_root4(const float c[5], float hi, float *out);
float cr_approach_speed_at(const cr_body *a, const cr_body *b, float t,
                           float margin, float dt);
float cr_impact_threshold(const cr_body *a, const cr_body *b, float rest_speed);
int cr_time_of_impact(const cr_body *a, const cr_body *b, float t0, float t1,
                      float tol, float dt, float *toi);

/* events.c */
carom_status cr_step_events(carom_world *w);

/* solver.c */
void cr_solver_prepare(carom_world *w, int resting_only);
void cr_solver_velocities(carom_world *w, int iterations);
void cr_solver_positions(carom_world *w);
void cr_solver_store(carom_world *w);
float cr_solver_impact(carom_world *w, cr_manifold *m, float *approach);
float cr_effective_approach(const cr_body *a, const cr_body *b, cr_v2 ra,
                            cr_v2 rb, cr_v2 n, float dt);

#endif /* CAROM_INTERNAL_H */
