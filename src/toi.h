/*
 * toi.h -- time of impact of two bodies on their drifts (internal).
 */
#ifndef CAROM_TOI_H
#define CAROM_TOI_H

#include "integrate.h"

/* A body on its drift: what the time of impact reads. */
typedef struct cr_mover {
    const cr_shape *s;
    const cr_body *b;
    const cr_drift *d;
} cr_mover;

/* Earliest s in [0, hi] with c0 + c1 s + c2 s^2 = 0 where the function is
 * decreasing (an approach, not a graze or a separation); needs c0 > 0.
 * Returns 0 if none (also for non-finite coefficients). */
int cr_first_down_root2(float c0, float c1, float c2, float hi, float *out);

/* Earliest root of c0 + c1 s + ... + c4 s^4 in [0, hi], c0 > 0; bounded
 * work and storage whatever the input (non-finite: no root). May return
 * an instant before the root (never after) when its budget runs out. */
int cr_first_root4(const float c[5], float hi, float *out);

/* The box a body's shape sweeps over local times [t0, t1], grown by
 * margin. */
void cr_swept_box(const cr_mover *m, float t0, float t1, float margin,
                  cr_box *out);

/* The same when the drift holds only until t_mid (an impact's hold, or
 * the solver's, lasts to the substep's end, where the step puts the body
 * back on the free motion of its forces): the drift's box over
 * [t0, t_mid] joined to the free motion's from the drift's state at t_mid
 * to t1. Swept whole, the hold's acceleration (a velocity change over
 * what is left of a substep, 10^6 m/s^2 when an impact falls a
 * microsecond before its end) made boxes across a whole pile. */
void cr_swept_box_until(const cr_mover *m, float t0, float t_mid, float t1,
                        float margin, cr_box *out);

/* The note's early-out: 1 if the bodies' bounding circles cannot meet over
 * [t0, t1] (their centres' distance at the time of closest approach,
 * minus what acceleration can bend, exceeds their extents plus margin). */
int cr_cannot_meet(const cr_mover *A, const cr_mover *B, float t0, float t1,
                   float margin);

/* Fastest normal approach of A and B at local time t over the points of
 * their manifold within `reach` (0 if none), and in *scale the speed scale
 * of the pair (linear speeds plus spin times extent); in *recede (unless
 * NULL) the slowest separation speed over those points (0 if none; < 0 if
 * one approaches). */
float cr_approach_speed(const cr_mover *A, const cr_mover *B, float t,
                        float reach, float *scale, float *recede);

/*
 * First instant in [t0, t1] (local step time) at which A and B, apart at
 * t0, come within `tol` of touching while approaching. Exact closed forms
 * for non-rotating pairs; conservative advancement (never past the impact)
 * when a polygon rotates. Returns 1 and the time in *toi; or
 * CR_TOI_RESUME and the time the advancement reached when it ran out of
 * iterations still apart (search again from there); 0 if they do not meet.
 */
#define CR_TOI_RESUME 2
int cr_time_of_impact(const cr_mover *A, const cr_mover *B, float t0, float t1,
                      float tol, float *toi);

/*
 * The same for a pair that touches at t0 on a pivot: a corner a
 * fast-turning polygon turns on after a plastic impact, touching but not
 * approaching. The pivot lifts off or slides; the search looks past it
 * for the next part of the pair to come down, which may arrive while the
 * pivot still touches: then the impact is where the separation is
 * between -depth / 2 and -depth. Only rotating polygon pairs (otherwise
 * 0: nothing found).
 */
int cr_time_of_impact_pivot(const cr_mover *A, const cr_mover *B, float t0, float t1,
                            float tol, float depth, float *toi);

#endif /* CAROM_TOI_H */
