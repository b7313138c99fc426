/*
 * integrate.c -- velocity Verlet, exactly as the design note writes it:
 *
 *   x1 = x0 + v0 dt + a0 dt^2 / 2
 *   a1 = (1/m) sum f(x1)
 *   v1 = v0 + (a0 + a1) dt / 2
 *
 * and the same for rotation (angle, angular velocity, torque / inertia),
 * with the angle carried as a unit (cos, sin) pair: the rotation advances by
 * the angle increment w0 dt + alpha0 dt^2 / 2 through the library's own
 * trigonometry, then is renormalised.
 *
 * Every body moves before any force is evaluated, because a force callback
 * may depend on the positions of other bodies.
 *
 * Resting contacts are forces, not impacts: the drift includes the
 * acceleration acc_c that last step's resting contact impulses amount to
 * (solver.c). Without it every resting body would drift |g| dt^2 / 2 into
 * its support each step and rely on projection to come back out; with it a
 * resting stack does not move at all. The velocity update leaves acc_c out,
 * because the solver applies the contact impulses to velocities itself.
 */
#include "internal.h"

cr_rot cr_rot_advance(cr_rot q, float angle)
{
#if CAROM_ENABLE_ROTATION
    if (cr_eq(angle, 0.0f))
        return q;
    return cr_rot_normalize(cr_rot_mul(carom_rot_from_angle(angle), q));
#else
    (void)angle;
    return q;
#endif
}

/*
 * Acceleration and angular acceleration of body `id` at its current
 * position: gravity plus (constant force + callback force) / m. Returns 0
 * if the callback gave a non-finite value (which is then ignored).
 */
static int cr_forces(const carom_world *w, int id, const cr_body *b,
                     cr_v2 *acc, float *alpha)
{
    int ok = 1;
#if CAROM_ENABLE_FORCES
    cr_v2 f = b->force;
    float tq = b->torque;
    if (w->def.force_fn) {
        carom_body_state st;
        cr_v2 uf = cr_v(0.0f, 0.0f);
        float ut = 0.0f;
        st.center = b->x;
        st.position = cr_body_origin(b);
        st.rotation = b->q;
        st.velocity = b->vel;
        st.angular_velocity = b->w;
        w->def.force_fn(w->def.force_user, id, &st, &uf, &ut);
        if (cr_finite(uf.x) && cr_finite(uf.y) && cr_finite(ut)) {
            f = cr_vadd(f, uf);
            tq = cr_add(tq, ut);
        } else {
            ok = 0;
        }
    }
    *acc = cr_vadd(w->def.gravity, cr_vscale(b->inv_m, f));
#if CAROM_ENABLE_ROTATION
    *alpha = cr_mul(b->inv_I, tq);
#else
    (void)tq;
    *alpha = 0.0f;
#endif
#else
    (void)id;
    (void)b;
    *acc = w->def.gravity;
    *alpha = 0.0f;
#endif
    return ok;
}

int cr_body_forces(const carom_world *w, int id, const cr_body *b,
                   cr_v2 *acc, float *alpha)
{
    return cr_forces(w, id, b, acc, alpha);
}

/* Advance every dynamic body by dt. Returns 0 if some force callback value
 * was not finite (that force was ignored). */
int cr_integrate(carom_world *w, float dt)
{
    int i, ok = 1;
    float half_dt = cr_mul(0.5f, dt);
    float half_dt2 = cr_mul(half_dt, dt);

    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        b->x = cr_vadd(cr_vadd(b->x, cr_vscale(dt, b->vel)),
                       cr_vscale(half_dt2, cr_vadd(b->acc, b->acc_c)));
#if CAROM_ENABLE_ROTATION
        b->q = cr_rot_advance(b->q, cr_add(cr_mul(b->w, dt),
                                           cr_mul(cr_add(b->alpha, b->alpha_c),
                                                  half_dt2)));
#endif
    }
    for (i = 0; i < w->body_count; ++i) {
        cr_body *b = &w->bodies[i];
        cr_v2 acc1;
        float alpha1;
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        if (!cr_forces(w, i, b, &acc1, &alpha1))
            ok = 0;
        b->vel_saved = b->vel; /* start-of-step velocity, for the solver */
        b->w_saved = b->w;
        b->vel = cr_vadd(b->vel, cr_vscale(half_dt, cr_vadd(b->acc, acc1)));
        b->acc = acc1;
#if CAROM_ENABLE_ROTATION
        b->w = cr_add(b->w, cr_mul(half_dt, cr_add(b->alpha, alpha1)));
        b->alpha = alpha1;
#endif
    }
    return ok;
}
