/*
 * broadphase.h -- candidate pairs: bodies whose boxes overlap (internal).
 */
#ifndef CAROM_BROADPHASE_H
#define CAROM_BROADPHASE_H

#include "body.h"

/* A candidate pair of the step. */
typedef struct cr_pair {
    int a, b;      /* body slots, a < b */
    int contact;   /* this step's contact, or -1 */
    int next_a, next_b; /* next pair of body a, of body b (lists per body) */
    int stamp;     /* events: bumped each time toi is recomputed */
    int va, vb;    /* events: drift versions of a and b it was computed with */
    int mark;      /* events: island stamp */
    float toi;     /* events: next impact, local step time (CR_NEVER: none) */
    unsigned char met;    /* events: CR_PAIR_* bits */
    unsigned char solved; /* events: its contact was the solver's when
                             searched */
} cr_pair;

/* A new pair record of bodies a < b: no contact, on no body's list, never
 * searched (the one place a pair's fields are first written: the
 * broadphase, the events method's regrown boxes, the pushed reach). */
CR_INLINE void cr_pair_init(cr_pair *p, int a, int b)
{
    p->a = a;
    p->b = b;
    p->contact = -1;
    p->next_a = p->next_b = -1;
    p->stamp = 0;
    p->va = p->vb = -1;
    p->mark = 0;
    p->toi = 0.0f;
    p->met = 0;
    p->solved = 0;
}

#define CR_PAIR_MET 1 /* met in this substep: needs a contact */
#define CR_PAIR_HIT 2 /* an impact of this step */
#define CR_PAIR_RESUME 4 /* its time is where an unfinished impact search
                            stopped (CR_TOI_RESUME), not a meeting */

/* Worlds of at most this many bodies in the broadphase sweep their boxes
 * along one axis instead of filling the grid: cheaper for a hundred
 * bodies; a grid for thousands (a 500-body pour: 146 M instructions of
 * pair finding in 300 steps with the grid, 192 M swept). */
#ifndef CR_SWEEP_MAX
#define CR_SWEEP_MAX 128
#endif

/* A body's box in the grid. */
typedef struct cr_proxy {
    cr_box box;
    int body;
    int cx, cy;    /* cell of the box centre */
} cr_proxy;

/*
 * A uniform grid rebuilt every step: cells a little larger than the
 * typical body, mapped into buckets (a patch of cells tiling the plane),
 * filled by a counting sort, so finding
 * pairs is linear in the bodies whatever their layout (a sweep on one axis
 * is quadratic in a pile, where everything shares x ranges). Bodies larger
 * than a cell (walls, floors) are kept apart and tested against the cells
 * their box covers.
 */
typedef struct cr_broadphase {
    cr_proxy *proxies, *tmp; /* capacity bodies each: grid ones, then big */
    int *start;              /* bucket_cap + 1 bucket offsets */
    int *count;              /* capacity + 1: sort counters (building:
                                each item's bucket) */
    int capacity, bucket_cap;
    int grid_count, big_count, buckets;
    int xbits;               /* the table is 2^xbits cells wide */
    int sweep_max;           /* at most this many bodies: no grid, a sweep
                                (a world: CR_SWEEP_MAX) */
    int sweep;               /* the last build swept: no grid; the boxes
                                sorted along one axis */
    int sweep_axis;          /* sweep: 0 along x, 1 along y */
    int order_n;             /* sweep: start[0..order_n) holds the last
                                sorted order of body slots */
    unsigned xmask, ymask;   /* cell coordinate masks of its width, height */
    float cell, inv_cell;
} cr_broadphase;

/* Memory: bytes of each array for `capacity` bodies (world layout). */
int cr_broadphase_bucket_cap(int capacity);

/* Put the boxes of bodies[0..n) into the grid (or, for at most sweep_max
 * of them, sort them for the sweep). The bodies come in increasing slots,
 * as the step lists them: the pairs of the build without the grid come
 * sorted so, and the sweep's queries keep that order. */
void cr_broadphase_build(cr_broadphase *bp, const cr_box *boxes,
                         const int *bodies, int n);

/* Decide whether two bodies may pair (static with static never does). */
typedef int (*cr_pair_accept_fn)(void *ctx, int a, int b);

/* All overlapping pairs the filter accepts, into out[0..cap); returns how
 * many were stored, or cap + 1 if there were more (the count saturates). */
long cr_broadphase_pairs(const cr_broadphase *bp, const cr_box *boxes,
                         cr_pair_accept_fn accept, void *ctx, cr_pair *out,
                         int cap);

/* Calls fn(ctx, body) for every body in the grid whose box (boxes[]) may
 * overlap q; returns 0 if fn returned 0 (stop), else 1. */
typedef int (*cr_query_fn)(void *ctx, int body);
int cr_broadphase_query(const cr_broadphase *bp, const cr_box *boxes,
                        const cr_box *q, cr_query_fn fn, void *ctx);

/* Sort pairs by (a, b) in linear time (two counting passes over body
 * slots; an insertion sort when the pairs are few for the slots); tmp and
 * count as in cr_broadphase. */
void cr_pairs_sort(cr_pair *pairs, cr_pair *tmp, int n, int *count, int slots);

/* The same, with all four comparisons made and none of them a branch: in
 * the grid's scans, whose candidates overlap or not at random, a branch
 * per comparison is mispredicted often; this leaves one branch per
 * candidate (emit or not), nearly always not taken. */
CR_INLINE int cr_boxes_overlap_flat(const cr_box *p, const cr_box *q)
{
    return !(cr_lt(q->hi_x, p->lo_x) | cr_lt(p->hi_x, q->lo_x) | cr_lt(q->hi_y, p->lo_y) |
             cr_lt(p->hi_y, q->lo_y));
}

CR_INLINE int cr_boxes_overlap(const cr_box *p, const cr_box *q)
{
    return !(cr_lt(q->hi_x, p->lo_x) || cr_lt(p->hi_x, q->lo_x) ||
             cr_lt(q->hi_y, p->lo_y) || cr_lt(p->hi_y, q->lo_y));
}

#endif /* CAROM_BROADPHASE_H */
