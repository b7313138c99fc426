/*
 * integrate.c -- velocity Verlet, as the design note writes it:
 *
 *   x1 = x0 + v0 dt + a0 dt^2 / 2
 *   a1 = (1/m) sum f(x1)
 *   v1 = v0 + (a0 + a1) dt / 2
 *
 * and the same for rotation, with the angle carried as a unit (cos, sin)
 * pair: it advances by the angle increment through the library's own
 * trigonometry, then is renormalised.
 *
 * Inside a step a body follows drifts (integrate.h): Verlet's position
 * update with a constant acceleration, which is exact; contact substeps and
 * impacts only change the velocity and the acceleration of the drift at
 * known instants. The step finishes the velocity with the force at the new
 * position (world.c).
 *
 * Positions and velocities are sums of many small increments: x += v dt
 * every step rounds every step, and the error grows with the number of
 * steps, so it grows as dt shrinks (docs/accuracy.md). With
 * CAROM_ENABLE_COMPENSATED each body keeps the rounding it lost (Kahan), and
 * the sum is as accurate as one rounding of the exact total.
 */
#include "integrate.h"

#if CAROM_ENABLE_ROTATION
cr_rot cr_rot_turn(cr_rot q, float angle)
{
    return cr_rot_normalize(cr_rot_mul(cr_rot_from_angle(angle), q));
}
#endif

void cr_pose_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *x,
                cr_rot *q)
{
    float h = cr_sub(s, d->t);
    *x = cr_vadd(b->x, cr_drift_offset(b->v, d->a, h));
#if CAROM_ENABLE_ROTATION
    *q = cr_rot_advance(b->q, cr_drift_angle(b->w, d->alpha, h));
#else
    *q = b->q;
#endif
}

void cr_velocity_at(const cr_body *b, const cr_drift *d, float s, cr_v2 *v,
                    float *w)
{
    float h = cr_sub(s, d->t);
    *v = cr_vmadd(b->v, h, d->a);
    *w = cr_add(b->w, cr_mul(h, d->alpha));
}

carom_status cr_body_accel_all(const carom_world_def *def, int id,
                               const cr_body *b, const cr_body_info *info,
                               cr_v2 *a, float *alpha)
{
    if (b->type != CAROM_BODY_DYNAMIC) {
        *a = cr_v(0.0f, 0.0f);
        *alpha = 0.0f;
        return CAROM_OK;
    }
#if CAROM_ENABLE_FORCES
    {
        cr_v2 f = info->force;
        float tq = info->torque;
        if (b->flags & CR_BODY_ONCE) {
            f = cr_vadd(f, info->force_once);
            tq = cr_add(tq, info->torque_once);
        }
        if (def->force_fn) {
            carom_body_state st;
            cr_v2 uf = cr_v(0.0f, 0.0f);
            float ut = 0.0f;
            st.center = b->x;
            st.position = cr_body_origin(b, info);
            st.rotation = b->q;
            st.velocity = b->v;
            st.angular_velocity = b->w;
            def->force_fn(def->force_user, id, &st, &uf, &ut);
            if (!cr_finite(uf.x) || !cr_finite(uf.y) || !cr_finite(ut))
                return CAROM_ERR_NOT_FINITE;
            if (!cr_accel_in_range(info, uf, ut))
                return CAROM_ERR_OUT_OF_RANGE;
            f = cr_vadd(f, uf);
            tq = cr_add(tq, ut);
        }
        cr_accel_of(def, b, f, tq, a, alpha);
    }
#else
    (void)id;
    (void)info;
    (void)b;
    *a = def->gravity;
    *alpha = 0.0f;
#endif
    return CAROM_OK;
}
