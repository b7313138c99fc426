/*
 * scenes.c -- the benchmark scenes, generated (tools/bench/bench.h).
 *
 * gas N   N circles (radius 0.1 m, e = 1, no friction) in a closed square
 *         box of static walls (e = 1, no friction), no gravity, 0.4 m^2
 *         per circle (so the collision rate per body does not change
 *         with N), on a grid, velocities uniform in [-1.5, 1.5]^2 m/s;
 *         carom's rest speed 0 and Box2D's restitution threshold 0, so
 *         every meeting bounces.
 * pile N  N bodies, circles of radius 0.25 m and 0.5 x 0.5 m boxes
 *         alternating, released at rest from a grid (0.55 m pitch, so
 *         5 cm gaps, +-2 cm horizontal jitter) into a container of static
 *         walls, gravity (0, -10), density 1, friction 0.6, restitution 0;
 *         each engine's default restitution threshold.
 *
 * The layouts are those tools/bench-box2d.sh generated for the issue-12
 * figures. The random numbers are Park-Miller (16807, seed 12345), in
 * integers, so every machine draws the same bodies.
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct pm_rng {
    long long seed;
} pm_rng;

static double pm_next(pm_rng *r)
{
    r->seed = (r->seed * 16807LL) % 2147483647LL;
    return (double)r->seed / 2147483647.0;
}

const char *bench_kind_name(bench_kind kind)
{
    return kind == BENCH_GAS ? "gas" : "pile";
}

int bench_kind_from_name(const char *name, bench_kind *out)
{
    if (strcmp(name, "gas") == 0)
        *out = BENCH_GAS;
    else if (strcmp(name, "pile") == 0)
        *out = BENCH_PILE;
    else
        return -1;
    return 0;
}

static bench_body wall(float hx, float hy, double x, double y, float e, float mu)
{
    bench_body b;
    memset(&b, 0, sizeof b);
    b.is_static = 1;
    b.is_box = 1;
    b.hx = hx;
    b.hy = hy;
    b.x = (float)x;
    b.y = (float)y;
    b.density = 1.0f;
    b.restitution = e;
    b.friction = mu;
    return b;
}

int bench_scene_make(bench_scene *s, bench_kind kind, int n)
{
    pm_rng rng;
    int k, i, walls;
    bench_body *b;

    memset(s, 0, sizeof *s);
    if (n < 1 || n > 1000000)
        return -1;
    rng.seed = 12345;
    k = (int)sqrt((double)n);
    if (k * k < n)
        ++k;
    walls = kind == BENCH_GAS ? 4 : 3;
    s->bodies = (bench_body *)calloc((size_t)(n + walls), sizeof *s->bodies);
    if (!s->bodies)
        return -1;
    s->kind = kind;
    s->n = n;
    s->body_count = n + walls;
    s->dt = 1.0f / 60.0f;
    b = s->bodies;
    if (kind == BENCH_GAS) {
        const double L = sqrt(0.4 * n), h = L / 2.0, sp = L / k;
        const float hw = (float)(h + 1.0);
        s->gx = 0.0f;
        s->gy = 0.0f;
        s->rest_speed = 0.0f;
        s->b2_threshold = 0.0f;
        b[0] = wall(hw, 0.5f, 0.0, -h - 0.5, 1.0f, 0.0f);
        b[1] = wall(hw, 0.5f, 0.0, h + 0.5, 1.0f, 0.0f);
        b[2] = wall(0.5f, hw, -h - 0.5, 0.0, 1.0f, 0.0f);
        b[3] = wall(0.5f, hw, h + 0.5, 0.0, 1.0f, 0.0f);
        for (i = 0; i < n; ++i) {
            bench_body *c = &b[walls + i];
            c->radius = 0.1f;
            c->x = (float)(-h + sp * (i / k + 0.5));
            c->y = (float)(-h + sp * (i % k + 0.5));
            c->vx = (float)(3.0 * pm_next(&rng) - 1.5);
            c->vy = (float)(3.0 * pm_next(&rng) - 1.5);
            c->density = 1.0f;
            c->restitution = 1.0f;
            c->friction = 0.0f;
        }
    } else {
        const double sp = 0.55, W = k * sp, h = W / 2.0;
        s->gx = 0.0f;
        s->gy = -10.0f;
        s->rest_speed = -1.0f;
        s->b2_threshold = -1.0f;
        b[0] = wall((float)(h + 1.0), 0.5f, 0.0, -0.5, 0.0f, 0.6f);
        b[1] = wall(0.5f, (float)W, -h - 0.5, W, 0.0f, 0.6f);
        b[2] = wall(0.5f, (float)W, h + 0.5, W, 0.0f, 0.6f);
        for (i = 0; i < n; ++i) {
            bench_body *c = &b[walls + i];
            c->x = (float)(-h + sp * (i % k + 0.5) + 0.04 * pm_next(&rng) - 0.02);
            c->y = (float)(0.275 + sp * (i / k));
            if (i % 2 == 0) {
                c->radius = 0.25f;
            } else {
                c->is_box = 1;
                c->hx = 0.25f;
                c->hy = 0.25f;
            }
            c->density = 1.0f;
            c->restitution = 0.0f;
            c->friction = 0.6f;
        }
    }
    return 0;
}

void bench_scene_free(bench_scene *s)
{
    free(s->bodies);
    s->bodies = NULL;
    s->body_count = 0;
}

int bench_scene_write(const bench_scene *s, const char *path)
{
    FILE *f = strcmp(path, "-") == 0 ? stdout : fopen(path, "w");
    int i, ok;
    if (!f)
        return -1;
    fprintf(f, "carom-scene 1\n");
    fprintf(f, "# %s of %d bodies, written by carom-bench --write-scene\n",
            bench_kind_name(s->kind), s->n);
    fprintf(f, "world gravity=%.9g,%.9g dt=%.9g steps=120", (double)s->gx, (double)s->gy,
            (double)s->dt);
    if (s->rest_speed >= 0.0f)
        fprintf(f, " rest-speed=%.9g", (double)s->rest_speed);
    fputc('\n', f);
    for (i = 0; i < s->body_count; ++i) {
        const bench_body *b = &s->bodies[i];
        fprintf(f, "body %s%s", b->is_box ? "box" : "circle", b->is_static ? " static" : "");
        if (b->is_box)
            fprintf(f, " half-extents=%.9g,%.9g", (double)b->hx, (double)b->hy);
        else
            fprintf(f, " radius=%.9g", (double)b->radius);
        fprintf(f, " position=%.9g,%.9g", (double)b->x, (double)b->y);
        if (b->vx != 0.0f || b->vy != 0.0f)
            fprintf(f, " velocity=%.9g,%.9g", (double)b->vx, (double)b->vy);
        if (!b->is_static)
            fprintf(f, " density=%.9g", (double)b->density);
        fprintf(f, " restitution=%.9g friction=%.9g\n", (double)b->restitution,
                (double)b->friction);
    }
    ok = !ferror(f);
    if (f != stdout)
        ok = fclose(f) == 0 && ok;
    else
        ok = fflush(f) == 0 && ok;
    return ok ? 0 : -1;
}
