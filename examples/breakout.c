/*
 * breakout.c -- a headless breakout game loop on carom: a kinematic paddle
 * that follows the ball (found with a ray cast), a ball with e = 1 in a box
 * of static walls, and 40 bricks removed when the ball hits them (impact
 * events). Runs a fixed number of steps and prints what happened:
 *
 *     build/examples/breakout [steps]
 *
 * Exit status 0 if the game ran as a game should (bricks broke, the ball
 * never left the field, every call succeeded), 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>

#include "carom.h"

#define ROWS 4
#define COLS 10
#define BRICKS (ROWS * COLS)
#define MAX_BODIES (BRICKS + 8)

static int check(carom_status st, const char *what)
{
    if (st != CAROM_OK) {
        fprintf(stderr, "breakout: %s: %s\n", what, carom_status_string(st));
        exit(1);
    }
    return 0;
}

static int add_wall(carom_world *w, float hx, float hy, float x, float y)
{
    carom_body_def d = carom_default_body_def();
    int id;
    d.type = CAROM_BODY_STATIC;
    check(carom_body_def_set_box(&d, hx, hy), "wall shape");
    d.position.x = x;
    d.position.y = y;
    d.restitution = 1.0f;
    d.friction = 0.0f;
    check(carom_world_add_body(w, &d, &id), "add wall");
    return id;
}

int main(int argc, char **argv)
{
    static unsigned char memory[1 << 20]; /* the program owns the memory */
    long steps = argc > 1 ? strtol(argv[1], NULL, 10) : 3600;
    carom_world_def wd = carom_default_world_def();
    carom_body_def d;
    carom_world *w;
    int brick[BRICKS], alive = BRICKS, paddle, ball, floor_sensor, i, r, c;
    long k, lost = 0, hits = 0, paddle_hits = 0;
    size_t need;

    wd.gravity.y = 0.0f; /* a breakout ball flies straight */
    wd.max_bodies = MAX_BODIES;
    wd.rest_speed = 0.0f;
    need = carom_world_buffer_size(&wd);
    if (need == 0 || need > sizeof memory) {
        fprintf(stderr, "breakout: the world needs %lu bytes\n", (unsigned long)need);
        return 1;
    }
    check(carom_world_init(&w, &wd, memory, sizeof memory), "world");

    /* the field: 12 m wide, 16 m tall, walls left, right and top */
    add_wall(w, 0.5f, 9.0f, -6.5f, 8.0f);
    add_wall(w, 0.5f, 9.0f, 6.5f, 8.0f);
    add_wall(w, 7.0f, 0.5f, 0.0f, 16.5f);
    /* below the paddle, a sensor: the ball falling through is a lost ball */
    d = carom_default_body_def();
    d.type = CAROM_BODY_STATIC;
    d.is_sensor = 1;
    check(carom_body_def_set_box(&d, 6.0f, 0.5f), "sensor shape");
    d.position.y = -1.5f;
    check(carom_world_add_body(w, &d, &floor_sensor), "add sensor");

    for (r = 0; r < ROWS; ++r)
        for (c = 0; c < COLS; ++c) {
            d = carom_default_body_def();
            d.type = CAROM_BODY_STATIC;
            check(carom_body_def_set_box(&d, 0.5f, 0.2f), "brick shape");
            d.position.x = -5.4f + 1.2f * (float)c;
            d.position.y = 11.0f + 0.6f * (float)r;
            d.restitution = 1.0f;
            d.friction = 0.0f;
            check(carom_world_add_body(w, &d, &brick[r * COLS + c]), "add brick");
        }

    d = carom_default_body_def();
    d.type = CAROM_BODY_KINEMATIC;
    check(carom_body_def_set_box(&d, 1.0f, 0.2f), "paddle shape");
    d.restitution = 1.0f;
    d.friction = 0.0f;
    check(carom_world_add_body(w, &d, &paddle), "add paddle");

    d = carom_default_body_def();
    d.radius = 0.2f;
    d.position.y = 2.0f;
    d.velocity.x = 4.0f;
    d.velocity.y = 9.0f;
    d.restitution = 1.0f;
    d.friction = 0.0f;
    check(carom_world_add_body(w, &d, &ball), "add ball");

    for (k = 0; k < steps && alive > 0; ++k) {
        const carom_event *ev;
        const carom_touch_event *te;
        carom_body_state b, p;
        carom_ray_hit hit;
        int n, found;
        check(carom_body_get_state(w, ball, &b), "ball state");
        check(carom_body_get_state(w, paddle, &p), "paddle state");
        /* aim: where does the ball cross the paddle's line? A ray along its
         * velocity, down to y = 0.2 */
        if (b.velocity.y < 0.0f) {
            float tt = (0.2f - b.position.y) / b.velocity.y;
            carom_vec2 to;
            to.x = b.position.x + b.velocity.x * tt;
            to.y = 0.2f;
            check(carom_world_raycast(w, b.position, to, &hit, &found), "ray cast");
            if (found && hit.body != paddle) /* a wall first: aim at the ball */
                to.x = b.position.x;
            {
                carom_vec2 v = {0.0f, 0.0f};
                float dx = to.x - p.position.x;
                v.x = dx * 8.0f; /* a proportional servo, capped */
                if (v.x > 12.0f)
                    v.x = 12.0f;
                if (v.x < -12.0f)
                    v.x = -12.0f;
                if (p.position.x > 4.8f && v.x > 0.0f)
                    v.x = 0.0f;
                if (p.position.x < -4.8f && v.x < 0.0f)
                    v.x = 0.0f;
                check(carom_body_set_velocity(w, paddle, v), "paddle velocity");
            }
        } else {
            check(carom_body_set_velocity(w, paddle, (carom_vec2){0.0f, 0.0f}), "paddle stop");
        }

        check(carom_world_step(w), "step");

        ev = carom_world_events(w, &n);
        for (i = 0; i < n; ++i) {
            int other = ev[i].body_a == ball ? ev[i].body_b : ev[i].body_a;
            if (other == paddle)
                ++paddle_hits;
            for (r = 0; r < BRICKS; ++r)
                if (brick[r] == other) {
                    check(carom_world_remove_body(w, other), "remove brick");
                    brick[r] = -1;
                    --alive;
                    ++hits;
                }
        }
        te = carom_world_touch_events(w, &n);
        for (i = 0; i < n; ++i)
            if (te[i].begin && te[i].sensor) {
                /* lost: serve again from the paddle */
                carom_body_state ps;
                carom_vec2 at, v = {3.0f, 9.0f};
                check(carom_body_get_state(w, paddle, &ps), "paddle state");
                at.x = ps.position.x;
                at.y = 1.0f;
                check(carom_body_set_transform(w, ball, at, carom_rot_from_angle(0.0f)), "serve");
                check(carom_body_set_velocity(w, ball, v), "serve velocity");
                ++lost;
            }
        check(carom_body_get_state(w, ball, &b), "ball state");
        if (b.position.x < -6.0f || b.position.x > 6.0f || b.position.y > 16.0f) {
            fprintf(stderr, "breakout: the ball left the field at (%g, %g)\n",
                    (double)b.position.x, (double)b.position.y);
            return 1;
        }
    }
    printf("breakout: %ld steps (%.1f s): %ld bricks broken, %d left, %ld paddle hits, "
           "%ld balls lost\n",
           k, (double)carom_world_time(w), hits, alive, paddle_hits, lost);
    return hits > 0 && paddle_hits > 0 ? 0 : 1;
}
