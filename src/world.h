/*
 * world.h -- the world: every array lives in the caller's buffer, laid out
 * once by world.c (internal).
 *
 * The step (world.c, carom_world_step) runs these stages, each in its own
 * module:
 *   broadphase.c   candidate pairs from the bodies' swept boxes (a grid)
 *   contact.c      contacts: manifolds (narrowphase.c) of the pairs within
 *                  reach, impulses carried over from the last step
 *   solver.c       the contact solver's substeps: soft push-out, relax,
 *                  restitution at the end of the step
 *   events.c       between the solver's passes: bodies drift, impacts at
 *                  their instants in time order (toi.c), simultaneous ones
 *                  solved together
 *   integrate.c    drifts and the Verlet finish
 *   island.c       islands of touching bodies, sleeping
 */
#ifndef CAROM_WORLD_H
#define CAROM_WORLD_H

#include "body.h"
#include "broadphase.h"
#include "contact.h"
#include "integrate.h"
#include "profile.h"

/* Per-body scratch of the contact solver. */
typedef struct cr_solver_body {
    cr_v2 v0;   /* velocity at the start of the substep */
    float w0;
    cr_v2 dp;   /* displacement since the start of the step */
    cr_rot dq;  /* rotation since the start of the step */
    cr_v2 vp;   /* pseudo-velocity of the position correction */
    float wp;
    union {
        float load;     /* priming (cr_solver_prime, before the substeps):
                           weight carried, as an impulse per substep */
        int hold_group; /* events, while held: the mark stamp of the hold
                           whose impulses its drift carries, 0 if none
                           (cr_hold_keep) */
    } u;
    int level;  /* support level: 0 rests on a static body, n + 1 on a
                   level-n body; -1 not supported (or no gravity) */
    cr_v2 a_held; /* events: its drift before the first hold of this */
    float alpha_held; /* substep that changed it */
    float push;   /* how far a body it may touch could push it this step,
                     beyond its own motion (cr_push_reach in world.c) */
    unsigned char active; /* has a contact solved this substep */
    unsigned char held;   /* events: an impact's hold changed its drift
                             this substep */
    unsigned char walk;   /* a flag of one walk over the bodies: the warm
                             start's unloading reduced a contact of what
                             rests on it (cr_solver_unload); shock
                             propagation holds it where it is, anchored
                             (cr_solver_shock); the position sweep's deep
                             sweeps take its rows (cr_solver_correct) */
#if CAROM_SOFT_DEEP_CONTACTS
    unsigned char mixed;  /* in a deep resting overlap with a body of unlike
                             density at the step's start (cr_mark_mixed) */
#endif
    unsigned char keep;   /* events: its drift keeps what is left of its
                             holds' impulses (cr_hold_keep) */
    unsigned char braced; /* cannot turn under a load: rests on a braced
                             body and is held at two points or more (a
                             circle: one); shock propagation holds only
                             braced bodies fixed (cr_solver_mark_shocks) */
} cr_solver_body;

/* An entry of the impact queue: a pair's next impact as computed when the
 * pair's stamp was `stamp`. */
typedef struct cr_heap_entry {
    float t;
    int pair;
    int stamp;
} cr_heap_entry;

/* A contact of a simultaneous impact solve (events.c). */
typedef struct cr_impact_row {
    int a, b;        /* body slots */
    int pair;        /* candidate pair */
    cr_v2 n;
    int count;
    float friction, restitution;
    cr_v2 ra[CR_MANIFOLD_POINTS], rb[CR_MANIFOLD_POINTS];
    float mass_n[CR_MANIFOLD_POINTS], mass_t[CR_MANIFOLD_POINTS];
    float target[CR_MANIFOLD_POINTS]; /* normal velocity aimed for */
    float approach;                          /* fastest approach before */
    float pn[CR_MANIFOLD_POINTS], pt[CR_MANIFOLD_POINTS];
    float la[CR_MANIFOLD_POINTS], lb[CR_MANIFOLD_POINTS];
                     /* normal lever arms r x n (0 for circles) */
    float k11, k12, k22; /* 2 points: the normal effective-mass matrix */
    float impulse_full; /* sum of pn as first solved, while the energy
                           limit (events.c) solves the instant again */
    unsigned char block;  /* 2 points solved as one 2x2 problem */
    unsigned char impact; /* approaching faster than the rest speed */
} cr_impact_row;

/* A touching pair (touch.c): slots a < b; CR_TOUCH_SENSOR in b if one of
 * them is a sensor. */
typedef struct cr_touch {
    int a, b;
} cr_touch;
#define CR_TOUCH_SENSOR (1 << 30)

/* The scale the tolerances follow (carom_config.h). */
typedef struct cr_scale {
    float length;     /* length unit, m */
    float slop;       /* m */
    float spec;       /* speculative distance, m */
    float push;       /* largest push-out speed, m/s */
    float face_tol;   /* polygon reference face tolerance, m */
    float corner;     /* polygon corners rounded off for contacts, m */
    float sleep_speed;/* m/s */
    int substeps;     /* of a step: def.substeps, or more under gravity */
} cr_scale;

struct carom_world {
    carom_world_def def;    /* capacities resolved */
    carom_method method;
    long steps;

    /* bodies */
    cr_body *bodies, *backup; /* hot state, and its copy at the step start */
    cr_body_info *info;
    int slot_count;           /* slots ever used */
    int body_count;           /* bodies alive */
    int prime;                /* bodies were added: the next step has no
                                 warm start, so it solves longer */

    /* per step */
    cr_scale scale;
    int scale_valid;          /* scale is that of the bodies now (a body added
                                 or removed clears it) */
    int *awake;               /* slots simulated this step */
    int awake_count;
    cr_box *boxes;            /* each body's box over the step */
    cr_broadphase bp;
    cr_pair *pairs, *pair_tmp;
    int pair_count;
    int *pair_head;           /* per body: its first pair (cr_pair.next_*) */
    cr_contact *contacts;
    int contact_count;
    cr_warm *warm;            /* impulses of the last step (cr_contacts_store
                                 overwrites them at the end of this one) */
    int warm_count;
    float warm_h;             /* the substep those impulses were for: each is
                                 an impulse per substep (0: not yet) */
    cr_solver_body *sbody;
    int *active;              /* bodies the solver takes this substep */
    int active_count;
    int *solve_order;         /* the contacts the solver takes, in order */
    int solve_count;
    int *support;             /* supported bodies, bottom up (breadth first
                                 from the static ones) */
    int support_count;
    int turning_contacts;     /* contacts with a turning kinematic body
                                 (CR_CONTACT_TURNS) this step */
    unsigned contact_edits;   /* contacts made or remade during steps */
    unsigned shock_marked;    /* contact_edits when cr_solver_mark_shocks
                                 last ran */
    int heavy_supports;       /* of the contacts it marked, those under a
                                 body CR_UNLOAD_MASS_RATIO times heavier
                                 than the dynamic body below (0: the warm
                                 start's unloading has nothing to do) */
    int sep_cached;           /* every solved point's separation at the
                                 current poses is in its pp (no position
                                 changed since the last velocity sweep) */

    /* events methods */
    cr_drift *drift;
    cr_heap_entry *heap;
    int heap_count, heap_cap;
    int *mark;                /* per body: island membership stamp */
    int mark_stamp;
    int *island;              /* bodies of an impact island */
    cr_v2 *island_v;          /* their velocities just after the impact */
    float *island_w;
    int island_cap;
    int *regrown;             /* bodies whose box grew during the step */
    int regrown_count;
    cr_impact_row *rows;      /* contacts of an impact island */
    int row_cap;
    float *direct_k, *direct_x; /* the exact solve of a small island: its */
    int *direct_u;              /* matrix, right-hand side and unknowns */
    int direct_cap;             /* (row * 8 + kind), at most this many */
    int impacts_this_step;
    float instant_t;          /* time of the last impact instant this step */
    int instant_stamp;        /* mark stamp of the first instant at it */
    int instant_unsettled;    /* an instant at it ended unsettled */
    int instant_rehits;       /* pairs taken again at it (CR_INSTANT_REHITS) */
    int rows_settled;         /* the island solve settled (cr_rows_solve) */
    int budget_hit;
    int resumed_searches;     /* impact searches resumed this step after an
                                 instant found the pair still apart */
    int pivot_searches;       /* searches past a pivot this step */
    int reorder;              /* the event loop (its searches, its impacts)
                                 handed contacts to the solver since the
                                 sweep order was last made */

    /* results */
    carom_event *events;
    int event_count, events_dropped;
    carom_stats stats;
    int error_body;

    /* touches (touch.c): the pairs touching after the last step, sorted,
     * and the events of the last step; touch_next, where the step's end
     * builds the new list, is the impact heap's memory (free then) */
    cr_touch *touch, *touch_next;
    int touch_count, touch_cap;
    carom_touch_event *touch_events;
    int touch_event_count, touch_events_dropped, max_touch_events;

    /* queries: the broadphase grid still holds every body (no body was
     * added, removed or moved by the program since it was built); the
     * bodies that ended the step outside their grid box are listed in
     * regrown[0 .. escaped_count) (free between steps) and flagged
     * CR_BODY_ESCAPED */
    int grid_valid;
    int carried_count; /* continuous guard: bodies flagged CR_BODY_CARRIED
                          in this step (cleared within it) */
    int escaped_count;
    int teleported;   /* a body was teleported since the last touch update */
    int sensor_count;         /* sensor bodies in the world */

    carom_profile *profile;   /* attached counters, or NULL */

    /* memory: the pool arrays (pairs, contacts, heap, rows, events,
     * touches) are in the caller's buffer at buf_pool, for buf_pairs pairs
     * and buf_contacts contacts, or, once the world grew
     * (carom_world_def.grow), in pool_mem, a block of grow.alloc's */
    void *pool_mem;
    unsigned char *buf_pool;
    int buf_pairs, buf_contacts;
};

/* The bodies that left their grid box during the step, after it (the
 * grid and w->boxes are the step's): list and flag them. */
void cr_note_escapes(carom_world *w);

/* A body's id: its slot and the slot's generation. */
int cr_body_id(const carom_world *w, int slot);

/* The slot an id names, or CAROM_ERR_BAD_BODY_ID / CAROM_ERR_STALE_ID. */
carom_status cr_slot_of(const carom_world *w, int id, int *slot);

/* The scale the tolerances follow, from the bodies now in the world. */
void cr_scale_compute(const carom_world *w, cr_scale *s);

/* May bodies a and b collide: one of them moves, they are not two sensors,
 * and their filter lets them. */
int cr_may_collide(const carom_world *w, int a, int b);
/* Has body a a pair with body b this step (through the pair lists)? */
int cr_has_pair(const carom_world *w, int a, int b);

/* The same whether or not either can move now (a body that moved this step
 * may have fallen asleep at its end). */
int cr_may_touch(const carom_world *w, int a, int b);

/* Count an impact of bodies a and b at local step time t, and record it
 * in the event list if there is room (else count it as dropped). */
void cr_record_impact(carom_world *w, int a, int b, float t, cr_v2 n,
                      float impulse, float approach);

#endif /* CAROM_WORLD_H */
