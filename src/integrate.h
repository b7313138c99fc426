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

/* A drift with no acceleration from local time 0: uniform motion on a
 * body's velocity (the ways the continuous guard sweeps, and the sensor
 * search's). */
CR_INLINE void cr_drift_still(cr_drift *d)
{
    d->t = 0.0f;
    d->a = cr_v(0.0f, 0.0f);
    d->alpha = 0.0f;
    d->version = 0;
    d->v_pre = cr_v(0.0f, 0.0f);
    d->w_pre = 0.0f;
}

/* Pose and velocity of the body at local time s on its drift. */
void cr_pose_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *x,
                cr_rot *q);
void cr_velocity_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *v,
                    float *w);

/* q turned by a nonzero `angle` (the library's own trigonometry,
 * renormalised). */
cr_rot cr_rot_turn(cr_rot q, float angle);

/* q turned by `angle`; inline, for the usual no turn at all (a body that
 * does not spin: every body of an elastic gas without friction), which
 * leaves q as it is without a call. */
CR_INLINE cr_rot cr_rot_advance(cr_rot q, float angle)
{
#if CAROM_ENABLE_ROTATION
    if (cr_eq(angle, 0.0f))
        return q;
    return cr_rot_turn(q, angle);
#else
    (void)angle;
    return q;
#endif
}

/* Inline below: called per body in the step's loops. */

/* Add dx to the position (compensated sum when enabled). */
CR_INLINE void cr_add_position(cr_body *b, cr_v2 dx)
{
#if CAROM_ENABLE_COMPENSATED
    cr_kadd(&b->x.x, &b->xc.x, dx.x);
    cr_kadd(&b->x.y, &b->xc.y, dx.y);
#else
    b->x = cr_vadd(b->x, dx);
#endif
}

/* Add dv to the velocity (compensated sum when enabled). */
CR_INLINE void cr_add_velocity(cr_body *b, cr_v2 dv)
{
#if CAROM_ENABLE_COMPENSATED
    cr_kadd(&b->v.x, &b->vc.x, dv.x);
    cr_kadd(&b->v.y, &b->vc.y, dv.y);
#else
    b->v = cr_vadd(b->v, dv);
#endif
}

/* w += dw, compensated like the velocity. */
CR_INLINE void cr_add_angular(cr_body *b, float dw)
{
#if CAROM_ENABLE_COMPENSATED
    cr_kadd(&b->w, &b->wc, dw);
#else
    b->w = cr_add(b->w, dw);
#endif
}

/* Displacement v h + a h^2 / 2 of a drift over h. */
CR_INLINE cr_v2 cr_drift_offset(cr_v2 v, cr_v2 a, float h)
{
    return cr_vadd(cr_vscale(h, v), cr_vscale(cr_mul(0.5f, cr_mul(h, h)), a));
}

#if CAROM_ENABLE_ROTATION
/* Turn w h + alpha h^2 / 2 of a drift over h. */
CR_INLINE float cr_drift_angle(float w, float alpha, float h)
{
    return cr_add(cr_mul(w, h), cr_mul(cr_mul(0.5f, cr_mul(h, h)), alpha));
}
#endif

/* Move the body's state along its drift to local time s (compensated). */
CR_INLINE void cr_sync(cr_body *b, cr_drift *d, float s)
{
    float h = cr_sub(s, d->t);
    cr_v2 a;
    d->t = s;
    if (b->type == CAROM_BODY_STATIC || cr_eq(h, 0.0f))
        return;
    /* (the drift read once: the stores into *b could otherwise be stores
     * into *d, and it would be read again after each) */
    a = d->a;
    cr_add_position(b, cr_drift_offset(b->v, a, h));
    cr_add_velocity(b, cr_vscale(h, a));
#if CAROM_ENABLE_ROTATION
    {
        float alpha = d->alpha;
        b->q = cr_rot_advance(b->q, cr_drift_angle(b->w, alpha, h));
        cr_add_angular(b, cr_mul(h, alpha));
    }
#endif
}

/*
 * Acceleration of the forces on a body at its current state: gravity plus
 * (constant force + callback force) / m, and torque / I. Returns
 * CAROM_ERR_NOT_FINITE or CAROM_ERR_OUT_OF_RANGE if the callback's result
 * is not finite or beyond CAROM_LIMIT_MAX_ACCEL (*a, *alpha untouched).
 * cr_body_accel_all computes every case; cr_body_accel is inline for the
 * usual one, a dynamic body without a force callback or a one-step force
 * (the same operations): the Verlet finish asks every awake body, and the
 * call and the body's id cost more than the acceleration (out of line it
 * was 2.5 % of a 100-body gas step).
 */
carom_status cr_body_accel_all(const carom_world_def *def, int id,
                               const cr_body *b, const cr_body_info *info,
                               cr_v2 *a, float *alpha);

/* Gravity plus force f over the mass, and torque tq over the inertia, of
 * dynamic body b. */
CR_INLINE void cr_accel_of(const carom_world_def *def, const cr_body *b, cr_v2 f, float tq,
                           cr_v2 *a, float *alpha)
{
    *a = cr_vadd(def->gravity, cr_vscale(b->inv_m, f));
#if CAROM_ENABLE_ROTATION
    *alpha = cr_mul(b->inv_I, tq);
#else
    (void)tq;
    *alpha = 0.0f;
#endif
}

CR_INLINE carom_status cr_body_accel(const carom_world_def *def, int id,
                                     const cr_body *b, const cr_body_info *info,
                                     cr_v2 *a, float *alpha)
{
#if CAROM_ENABLE_FORCES
    if (b->type == CAROM_BODY_DYNAMIC && !def->force_fn && !(b->flags & CR_BODY_ONCE)) {
        cr_accel_of(def, b, info->force, info->torque, a, alpha);
        return CAROM_OK;
    }
#endif
    return cr_body_accel_all(def, id, b, info, a, alpha);
}

#endif /* CAROM_INTEGRATE_H */
