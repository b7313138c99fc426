/*
 * balance.c -- a fixed-step control loop on carom: a tall box stands on a
 * kinematic platform that shakes from side to side; a PD controller reads
 * the box's tilt each step and applies a horizontal impulse at its top to
 * keep it upright. Run once without the controller (the box topples) and
 * once with it (it stays up), and print both:
 *
 *     build/examples/balance [seconds]
 *
 * Exit status 0 if the controlled box stayed within 10 degrees of upright
 * and the uncontrolled one fell, 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>

#include "carom.h"

static void check(carom_status st, const char *what)
{
    if (st != CAROM_OK) {
        fprintf(stderr, "balance: %s: %s\n", what, carom_status_string(st));
        exit(1);
    }
}

/* Runs the scene for `steps` steps; returns the largest tilt (rad). */
static float run(int controlled, long steps)
{
    static unsigned char memory[1 << 16];
    carom_world_def wd = carom_default_world_def();
    carom_body_def d = carom_default_body_def();
    carom_world *w;
    int platform, box;
    long k;
    float worst = 0.0f, mass, inertia;
    const float dt = 1.0f / 60.0f, half_h = 0.75f;

    wd.max_bodies = 2;
    wd.dt = dt;
    wd.enable_sleep = 0;
    check(carom_world_init(&w, &wd, memory, sizeof memory), "world");
    d.type = CAROM_BODY_KINEMATIC;
    check(carom_body_def_set_box(&d, 3.0f, 0.2f), "platform shape");
    d.friction = 1.0f;
    check(carom_world_add_body(w, &d, &platform), "add platform");
    d = carom_default_body_def();
    check(carom_body_def_set_box(&d, 0.15f, half_h), "box shape");
    d.position.y = 0.2f + half_h;
    d.friction = 1.0f;
    check(carom_world_add_body(w, &d, &box), "add box");
    check(carom_body_get_mass(w, box, &mass, &inertia), "mass");

    for (k = 0; k < steps; ++k) {
        carom_body_state s, p;
        float t = (float)k * dt, tilt, v;
        /* the platform shakes: x(t) = 0.3 sin(4 t), v = 1.2 cos(4 t) */
        v = 1.2f * carom_rot_from_angle(4.0f * t).c;
        check(carom_body_set_velocity(w, platform, (carom_vec2){v, 0.0f}), "shake");
        check(carom_body_get_state(w, box, &s), "box state");
        check(carom_body_get_state(w, platform, &p), "platform state");
        tilt = carom_rot_angle(s.rotation);
        if (tilt > worst)
            worst = tilt;
        if (-tilt > worst)
            worst = -tilt;
        if (controlled) {
            /* PD on the tilt and its rate: a horizontal impulse at the top
             * (positive tilt leans left: push the top right) */
            float j = (150.0f * tilt + 20.0f * s.angular_velocity) * inertia * dt / half_h;
            carom_vec2 top;
            top.x = s.center.x - s.rotation.s * half_h;
            top.y = s.center.y + s.rotation.c * half_h;
            check(carom_body_apply_impulse(w, box, (carom_vec2){j, 0.0f}, top), "impulse");
        }
        check(carom_world_step(w), "step");
    }
    return worst;
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? strtod(argv[1], NULL) : 10.0;
    long steps = (long)(seconds * 60.0);
    float free_tilt = run(0, steps), held_tilt = run(1, steps);
    printf("balance: %.1f s on a shaking platform: without control the box tilts to "
           "%.0f degrees, with it at most %.1f degrees\n",
           seconds, (double)free_tilt * 57.29578, (double)held_tilt * 57.29578);
    return held_tilt < 0.1745f && free_tilt > 0.5f ? 0 : 1;
}
