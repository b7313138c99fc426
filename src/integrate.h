/*
 * integrate.h -- motion inside a step: drifts, forces, the Verlet finish
 * (internal).
 */
#ifndef CAROM_INTEGRATE_H
#define CAROM_INTEGRATE_H

#include "body.h"

/*
 * A body's path over part of a step: from its state (x, q, v, w at local
 * step time t) with the constant acceleration (a, alpha) until something
 * changes it (a substep boundary for a body in contact, an impact):
 *     x(s) = x + v (s - t) + a (s - t)^2 / 2
 *     angle(s) = w (s - t) + alpha (s - t)^2 / 2
 * This is velocity Verlet's drift, exact for constant acceleration.
 * `version` counts the changes, so impact times computed with an older
 * path are known to be stale.
 */
typedef struct cr_drift {
    float t;
    cr_v2 a;
    float alpha;
    int version;
    cr_v2 v_pre;  /* events: velocity just before the impacts of the
                     current instant (set when the body joins the island) */
    float w_pre;
} cr_drift;

/* Pose and velocity of the body at local time s on its drift. */
void cr_pose_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *x,
                cr_rot *q);
void cr_velocity_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *v,
                    float *w);

/* Move the body's state along its drift to local time s (compensated). */
void cr_sync(cr_body *b, cr_drift *d, float s);

/* q turned by `angle` (the library's own trigonometry, renormalised). */
cr_rot cr_rot_advance(cr_rot q, float angle);

/* Add dv to the velocity (compensated sum when enabled). */
void cr_add_velocity(cr_body *b, cr_v2 dv);

/* w += dw, compensated like the velocity. */
void cr_add_angular(cr_body *b, float dw);

/* Add dx to the position (compensated sum when enabled). */
void cr_add_position(cr_body *b, cr_v2 dx);

/*
 * Acceleration of the forces on a body at its current state: gravity plus
 * (constant force + callback force) / m, and torque / I. Returns
 * CAROM_ERR_NOT_FINITE or CAROM_ERR_OUT_OF_RANGE if the callback's result
 * is not finite or beyond CAROM_LIMIT_MAX_ACCEL (*a, *alpha untouched).
 */
carom_status cr_body_accel(const carom_world_def *def, int id,
                           const cr_body *b, const cr_body_info *info,
                           cr_v2 *a, float *alpha);

#endif /* CAROM_INTEGRATE_H */
