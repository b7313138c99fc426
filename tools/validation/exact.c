/*
 * exact.c -- exact answers, in double precision and closed form, from the
 * scene alone (never from an engine's output), and how far a trace is from
 * them. docs/physics.md derives the formulas.
 *
 * Each model first checks that the scene is what it assumes (body order,
 * shapes, directions), so that a check table row applied to the wrong
 * scene is an error rather than a meaningless number.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "validate.h"

#define PI 3.14159265358979323846

/* A sample within this of an instant is at that instant (trace times are
 * float products k dt printed with 9 digits). */
#define SAME_INSTANT 1e-9

/* Two bodies are "apart" once this far from each other (m). */
#define APART 0.01

/* A body rises (a flight) while its upward velocity exceeds this (m/s). */
#define RISING 0.01

/* The larger; on a tie the first (so that -0 never replaces 0). */
static double maxd(double a, double b) { return b > a ? b : a; }

double wrap_angle(double a)
{
    while (a > PI)
        a -= 2.0 * PI;
    while (a <= -PI)
        a += 2.0 * PI;
    return a;
}

/* ---- masses ------------------------------------------------------------------------------ */

void exact_body_props(const scene_body *sb, body_props *out)
{
    const carom_body_def *d = &sb->def;
    memset(out, 0, sizeof *out);
    if (d->type != CAROM_BODY_DYNAMIC)
        return;
    if (d->shape == CAROM_SHAPE_CIRCLE) {
        double r = (double)d->radius;
        out->mass = d->mass > 0.0f ? (double)d->mass : (double)d->density * PI * r * r;
        out->inertia = out->mass * r * r / 2.0;
    } else {
        /* a fan of triangles from the frame origin: signed area, first and
         * second moments; the sign of the area takes care of clockwise input */
        double a = 0.0, mx = 0.0, my = 0.0, j = 0.0, rho;
        int i, n = d->vertex_count;
        for (i = 0; i < n; ++i) {
            double x0 = (double)d->vertices[i].x, y0 = (double)d->vertices[i].y;
            double x1 = (double)d->vertices[(i + 1) % n].x, y1 = (double)d->vertices[(i + 1) % n].y;
            double cr = x0 * y1 - x1 * y0;
            a += cr / 2.0;
            mx += cr * (x0 + x1) / 6.0;
            my += cr * (y0 + y1) / 6.0;
            j += cr * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
        }
        out->cx = mx / a;
        out->cy = my / a;
        out->mass = d->mass > 0.0f ? (double)d->mass : (double)d->density * fabs(a);
        rho = out->mass / fabs(a);
        /* about the origin, then moved to the centroid (parallel axes) */
        out->inertia = rho * fabs(j) - out->mass * (out->cx * out->cx + out->cy * out->cy);
    }
}

int scene_is_free(const vscene *s)
{
    int i;
    if (s->gx != 0.0 || s->gy != 0.0)
        return 0;
    for (i = 0; i < s->sc.body_count; ++i)
        if (s->sc.bodies[i].def.type != CAROM_BODY_DYNAMIC)
            return 0;
    return 1;
}

/* Restitution of a contact: the larger of the two (Box2D's and carom's rule). */
static double mixed_e(const vscene *s, int a, int b)
{
    return maxd((double)s->sc.bodies[a].def.restitution, (double)s->sc.bodies[b].def.restitution);
}

/* Newton's law along the line of two bodies, momentum form (docs/physics.md):
 * velocities ua, ub before, va, vb after. */
static void newton(double ma, double mb, double ua, double ub, double e, double *va, double *vb)
{
    double pa = ma * ua, pb = mb * ub, m = ma + mb;
    *va = (ma * (pa + pb) + e * (ma * pb - mb * pa)) / m / ma;
    *vb = (mb * (pa + pb) + e * (mb * pa - ma * pb)) / m / mb;
}

double late_impulse_error(double e, double approach, double ts, double dt, double share,
                          double k)
{
    double lost = (floor(ts / dt) + 1.0) * dt - ts;
    return (e + k) * approach * lost * share;
}

/* Body i is a dynamic circle; or a message. */
static int is_dynamic(const vscene *s, int i, const char *shape, char *why, size_t n)
{
    const scene_body *b;
    if (i >= s->sc.body_count) {
        snprintf(why, n, "has no body %d", i);
        return 0;
    }
    b = &s->sc.bodies[i];
    if (shape && strcmp(b->kind, shape) != 0) {
        snprintf(why, n, "body %d is a %s, not a %s", i, b->kind, shape);
        return 0;
    }
    if (b->def.type != CAROM_BODY_DYNAMIC) {
        snprintf(why, n, "body %d is not dynamic", i);
        return 0;
    }
    return 1;
}

/* ---- head-on pairs ----------------------------------------------------------------------- */

int headon_fit(const vscene *s, headon *h, char *why, size_t n)
{
    const carom_body_def *a, *b;
    memset(h, 0, sizeof *h);
    if (s->sc.body_count != 2 || !is_dynamic(s, 0, "circle", why, n) ||
        !is_dynamic(s, 1, "circle", why, n)) {
        if (s->sc.body_count != 2)
            snprintf(why, n, "has %d bodies, not 2 circles", s->sc.body_count);
        return -1;
    }
    a = &s->sc.bodies[0].def;
    b = &s->sc.bodies[1].def;
    if (s->gx != 0.0 || s->gy != 0.0 || a->position.y != 0.0f || b->position.y != 0.0f ||
        a->velocity.y != 0.0f || b->velocity.y != 0.0f || !(a->position.x < b->position.x) ||
        !(a->velocity.x > b->velocity.x) || a->force.x != 0.0f || b->force.x != 0.0f ||
        a->force.y != 0.0f || b->force.y != 0.0f) {
        snprintf(why, n, "is not two free circles closing along the x axis (body 0 left)");
        return -1;
    }
    h->e = mixed_e(s, 0, 1);
    h->ma = s->exact[0].mass;
    h->mb = s->exact[1].mass;
    h->xa = (double)a->position.x;
    h->xb = (double)b->position.x;
    h->ua = (double)a->velocity.x;
    h->ub = (double)b->velocity.x;
    h->ts = (h->xb - h->xa - (double)a->radius - (double)b->radius) / (h->ua - h->ub);
    if (h->ua - h->ub > s->rest_speed) {
        newton(h->ma, h->mb, h->ua, h->ub, h->e, &h->va, &h->vb);
    } else {
        /* slower than the rest speed: a resting contact, no restitution */
        h->resting = 1;
        h->va = h->vb = (h->ma * h->ua + h->mb * h->ub) / (h->ma + h->mb);
    }
    return 0;
}

void headon_measure(const headon *h, const trace *tr, headon_err *out)
{
    long k;
    int b;
    memset(out, 0, sizeof *out);
    for (k = 0; k < tr->samples; ++k) {
        double t = tr->t[k];
        for (b = 0; b < 2; ++b) {
            const double *st = TRACE_AT(tr, k, b);
            double x0 = b == 0 ? h->xa : h->xb, u = b == 0 ? h->ua : h->ub;
            double v = b == 0 ? h->va : h->vb;
            double xe = t <= h->ts ? x0 + u * t : x0 + u * h->ts + v * (t - h->ts);
            double ve = t < h->ts ? u : v;
            out->dx = maxd(out->dx, fabs(st[SX] - xe) + fabs(st[SY]));
            if (fabs(t - h->ts) > SAME_INSTANT)
                out->dv = maxd(out->dv, hypot(st[SVX] - ve, st[SVY]));
            if (k == tr->samples - 1)
                out->dv_end = maxd(out->dv_end, fabs(st[SVX] - v));
        }
    }
}

double headon_dke(const headon *h)
{
    return h->ma * (h->va * h->va - h->ua * h->ua) / 2.0 +
           h->mb * (h->vb * h->vb - h->ub * h->ub) / 2.0;
}

/* ---- bullets ----------------------------------------------------------------------------- */

int bullet_fit(const vscene *s, bullet *bu, char *why, size_t n)
{
    const scene_body *w, *c;
    double hx = 0.0;
    int i;
    memset(bu, 0, sizeof *bu);
    if (s->sc.body_count != 2 || !is_dynamic(s, 1, "circle", why, n)) {
        if (s->sc.body_count != 2)
            snprintf(why, n, "has %d bodies, not a wall and a bullet", s->sc.body_count);
        return -1;
    }
    w = &s->sc.bodies[0];
    c = &s->sc.bodies[1];
    if (strcmp(w->kind, "box") != 0 || w->angle != 0.0f || s->gx != 0.0 || s->gy != 0.0 ||
        c->def.position.y != w->def.position.y || c->def.velocity.y != 0.0f ||
        w->def.velocity.x != 0.0f || w->def.velocity.y != 0.0f ||
        !(c->def.position.x < w->def.position.x) || !(c->def.velocity.x > 0.0f)) {
        snprintf(why, n, "is not a level box wall (body 0) and a circle (body 1) fired at it "
                         "along x, without gravity");
        return -1;
    }
    for (i = 0; i < w->def.vertex_count; ++i)
        hx = maxd(hx, fabs((double)w->def.vertices[i].x));
    bu->static_wall = w->def.type != CAROM_BODY_DYNAMIC;
    bu->e = mixed_e(s, 0, 1);
    bu->mb = s->exact[1].mass;
    bu->mw = s->exact[0].mass;
    bu->ub = (double)c->def.velocity.x;
    bu->uw = 0.0;
    /* the bullet's front meets the wall's near face */
    bu->ts = ((double)w->def.position.x - hx -
              ((double)c->def.position.x + (double)c->def.radius)) / (bu->ub - bu->uw);
    if (bu->static_wall) {
        bu->vb = -bu->e * bu->ub;
        bu->vw = 0.0;
    } else {
        newton(bu->mb, bu->mw, bu->ub, bu->uw, bu->e, &bu->vb, &bu->vw);
    }
    return 0;
}

void bullet_measure(const vscene *s, const bullet *bu, const trace *tr, bullet_err *out)
{
    long k;
    int b;
    memset(out, 0, sizeof *out);
    out->first = V_NAN;
    for (k = 0; k < tr->samples; ++k) {
        double t = tr->t[k];
        for (b = 0; b < 2; ++b) {
            const double *st = TRACE_AT(tr, k, b);
            double x0 = (double)s->sc.bodies[b].def.position.x;
            double u = b == 1 ? bu->ub : bu->uw, v = b == 1 ? bu->vb : bu->vw;
            double xe = t <= bu->ts ? x0 + u * t : x0 + u * bu->ts + v * (t - bu->ts);
            out->dx = maxd(out->dx, fabs(st[SX] - xe));
        }
    }
    if (tr->samples > 1)
        out->first = TRACE_AT(tr, 1, 1)[SVX];
    out->fv = TRACE_AT(tr, tr->samples - 1, 1)[SVX];
    out->wv = TRACE_AT(tr, tr->samples - 1, 0)[SVX];
}

double bullet_dke(const bullet *bu)
{
    if (bu->static_wall)
        return bu->mb * (bu->e * bu->e - 1.0) * bu->ub * bu->ub / 2.0;
    return (bu->mb * (bu->vb * bu->vb - bu->ub * bu->ub) +
            bu->mw * (bu->vw * bu->vw - bu->uw * bu->uw)) / 2.0;
}

/* ---- a spinning kinematic blade ---------------------------------------------------------- */

/*
 * The blade's leading face (it turns counter-clockwise, w > 0) meets the
 * ball of radius r at distance d from its centre, at polar angle phi,
 * when the blade's line passes r + h from the ball's centre (h the
 * blade's half thickness): at angle theta = phi - asin((r + h) / d). The
 * face point under the ball, rho = sqrt(d^2 - (r + h)^2) from the centre,
 * moves at w rho along the face's normal n = (-sin theta, cos theta); the
 * blade cannot be moved, so Newton's law (frictionless, through the
 * ball's centre) sends the ball off at (1 + e) w rho n.
 */
int blade_fit(const vscene *s, blade *b, char *why, size_t n)
{
    const scene_body *k, *c;
    double hx = 0.0, hy = 0.0, px, py, d, r, w, phi, theta, rho, speed;
    int i;
    memset(b, 0, sizeof *b);
    if (s->sc.body_count != 2 || !is_dynamic(s, 1, "circle", why, n)) {
        if (s->sc.body_count != 2)
            snprintf(why, n, "has %d bodies, not a blade and a ball", s->sc.body_count);
        return -1;
    }
    k = &s->sc.bodies[0];
    c = &s->sc.bodies[1];
    if (strcmp(k->kind, "box") != 0 || k->def.type != CAROM_BODY_KINEMATIC || k->angle != 0.0f ||
        k->def.velocity.x != 0.0f || k->def.velocity.y != 0.0f ||
        !(k->def.angular_velocity > 0.0f) || s->gx != 0.0 || s->gy != 0.0 ||
        c->def.velocity.x != 0.0f || c->def.velocity.y != 0.0f ||
        c->def.angular_velocity != 0.0f) {
        snprintf(why, n, "is not a kinematic box at angle 0 spinning counter-clockwise (body 0) "
                         "and a circle at rest (body 1), without gravity");
        return -1;
    }
    for (i = 0; i < k->def.vertex_count; ++i) {
        hx = maxd(hx, fabs((double)k->def.vertices[i].x));
        hy = maxd(hy, fabs((double)k->def.vertices[i].y));
    }
    px = (double)c->def.position.x - (double)k->def.position.x;
    py = (double)c->def.position.y - (double)k->def.position.y;
    d = sqrt(px * px + py * py);
    r = (double)c->def.radius;
    w = (double)k->def.angular_velocity;
    phi = atan2(py, px);
    if (!(d > r + hy) || !(phi > 0.0))
        goto unsupported;
    theta = phi - asin((r + hy) / d);
    rho = sqrt(d * d - (r + hy) * (r + hy));
    if (!(theta > 0.0) || !(rho < hx))
        goto unsupported;
    b->e = mixed_e(s, 0, 1);
    b->mb = s->exact[1].mass;
    b->ts = theta / w;
    b->x0 = (double)c->def.position.x;
    b->y0 = (double)c->def.position.y;
    speed = (1.0 + b->e) * w * rho;
    b->vx = -speed * sin(theta);
    b->vy = speed * cos(theta);
    return 0;
unsupported:
    snprintf(why, n, "has no strike of the blade's face on the ball after t = 0 (the ball "
                     "within the blade's sweep, above its positive arm)");
    return -1;
}

void blade_measure(const blade *b, const trace *tr, blade_err *out)
{
    long k;
    const double *st;
    memset(out, 0, sizeof *out);
    for (k = 0; k < tr->samples; ++k) {
        double t = tr->t[k], h = t > b->ts ? t - b->ts : 0.0;
        st = TRACE_AT(tr, k, 1);
        out->dx = maxd(out->dx, hypot(st[SX] - (b->x0 + b->vx * h), st[SY] - (b->y0 + b->vy * h)));
    }
    st = TRACE_AT(tr, tr->samples - 1, 1);
    out->vx = st[SVX];
    out->vy = st[SVY];
    out->dv = hypot(st[SVX] - b->vx, st[SVY] - b->vy);
}

/* ---- the restitution drop ---------------------------------------------------------------- */

int drop_fit(const vscene *s, drop *d, char *why, size_t n)
{
    int i, floors = 0;
    memset(d, 0, sizeof *d);
    if (s->gx != 0.0 || !(s->gy < 0.0)) {
        snprintf(why, n, "has no downward gravity");
        return -1;
    }
    d->g = -s->gy;
    d->dt = s->dt;
    d->tend = (double)s->steps * s->dt;
    d->rest = s->rest_speed;
    d->balls = (drop_ball *)calloc((size_t)s->sc.body_count + 1, sizeof *d->balls);
    if (!d->balls) {
        snprintf(why, n, "out of memory");
        return -1;
    }
    for (i = 0; i < s->sc.body_count; ++i) {
        const scene_body *b = &s->sc.bodies[i];
        if (b->def.type != CAROM_BODY_DYNAMIC) {
            double hy = 0.0;
            int k;
            if (strcmp(b->kind, "box") != 0 || b->angle != 0.0f) {
                snprintf(why, n, "body %d: the floor must be a level box", i);
                drop_free(d);
                return -1;
            }
            for (k = 0; k < b->def.vertex_count; ++k)
                hy = maxd(hy, (double)b->def.vertices[k].y);
            d->floor = (double)b->def.position.y + hy;
            ++floors;
        } else if (strcmp(b->kind, "circle") != 0 || b->def.velocity.x != 0.0f ||
                   b->def.velocity.y != 0.0f || b->def.force.x != 0.0f ||
                   b->def.force.y != 0.0f) {
            snprintf(why, n, "body %d: the balls must be circles dropped from rest", i);
            drop_free(d);
            return -1;
        }
    }
    if (floors != 1) {
        snprintf(why, n, "has %d static bodies, not one floor", floors);
        drop_free(d);
        return -1;
    }
    for (i = 0; i < s->sc.body_count; ++i) {
        const scene_body *b = &s->sc.bodies[i];
        drop_ball *ball;
        double t, u;
        if (b->def.type != CAROM_BODY_DYNAMIC)
            continue;
        ball = &d->balls[d->count++];
        ball->body = i;
        ball->e = (double)b->def.restitution; /* the floor of a drop has e = 0 */
        ball->r = (double)b->def.radius;
        ball->h0 = (double)b->def.position.y - ball->r - d->floor;
        ball->T[0] = sqrt(2.0 * ball->h0 / d->g);
        ball->U[0] = sqrt(2.0 * d->g * ball->h0);
        ball->n = 1;
        /* the bounce after an impact at speed U takes 2 e U / g */
        while (ball->n < DROP_MAX_IMPACTS && ball->U[ball->n - 1] > d->rest && ball->e > 0.0 &&
               ball->T[ball->n - 1] < d->tend) {
            int k = ball->n++;
            ball->T[k] = ball->T[k - 1] + 2.0 * ball->e * ball->U[k - 1] / d->g;
            ball->U[k] = ball->e * ball->U[k - 1];
        }
        /* at rest from the first arrival at or below the rest speed (at
         * once for e = 0) */
        t = ball->T[0];
        u = ball->U[0];
        while (u > d->rest && t < d->tend) {
            t += 2.0 * ball->e * u / d->g;
            u *= ball->e;
        }
        ball->rest_t = t < d->tend ? t : -1.0;
    }
    for (i = 0; i < s->sc.body_count; ++i)
        if (s->sc.bodies[i].def.type != CAROM_BODY_DYNAMIC &&
            maxd((double)s->sc.bodies[i].def.restitution, 0.0) > 0.0) {
            snprintf(why, n, "the floor's restitution must be 0 (each ball's decides)");
            drop_free(d);
            return -1;
        }
    return 0;
}

void drop_free(drop *d)
{
    free(d->balls);
    d->balls = NULL;
    d->count = 0;
}

double drop_height(const drop *d, const drop_ball *b, double t)
{
    int k;
    if (t <= b->T[0])
        return b->h0 - d->g * t * t / 2.0;
    for (k = 0; k + 1 < b->n && t > b->T[k + 1]; ++k) {}
    if (!(b->U[k] > d->rest) || b->e == 0.0)
        return 0.0;
    t -= b->T[k];
    return maxd(0.0, b->e * b->U[k] * t - d->g * t * t / 2.0);
}

double drop_apex(const drop *d, const drop_ball *b, int k)
{
    double v;
    if (k >= b->n - 1 || !(b->U[k] > d->rest))
        return -1.0;
    v = b->e * b->U[k];
    return v * v / (2.0 * d->g);
}

void drop_measure(const drop *d, const trace *tr, drop_err *out)
{
    int i;
    for (i = 0; i < d->count; ++i) {
        const drop_ball *b = &d->balls[i];
        drop_err *o = &out[i];
        double top = 0.0, y0 = TRACE_AT(tr, 0, b->body)[SY];
        int up = 0;
        long k;
        memset(o, 0, sizeof *o);
        o->last_top = -(double)INFINITY;
        for (k = 0; k < tr->samples; ++k) {
            const double *st = TRACE_AT(tr, k, b->body);
            double t = tr->t[k], h = st[SY] - b->r - d->floor;
            o->merr = maxd(o->merr, fabs(h - drop_height(d, b, t)));
            o->below = maxd(o->below, -h);
            if (b->rest_t >= 0.0 && t >= b->rest_t - SAME_INSTANT) {
                o->rest_h = maxd(o->rest_h, fabs(h));
                o->rest_v = maxd(o->rest_v, hypot(st[SVX], st[SVY]));
            }
            if (t > d->tend - 1.0 - 1e-6)
                o->last_top = maxd(o->last_top, h);
            if (t < b->T[0]) {
                /* free fall: the exact drop is g t^2 / 2 */
                o->fall_t = t;
                o->fall_err = fabs((st[SY] - y0) + d->g * t * t / 2.0);
            }
            /* a flight's apex: its highest sample (the last going up or the
             * first going down) */
            if (st[SVY] > RISING) {
                if (!up)
                    top = h;
                up = 1;
                top = maxd(top, h);
            } else if (up) {
                if (o->napex < 3)
                    o->apex[o->napex] = maxd(top, h);
                ++o->napex;
                up = 0;
            }
        }
        if (o->napex > 3)
            o->napex = 3;
    }
}

double drop_dE(const vscene *s, const drop *d)
{
    double de = 0.0;
    int i, k;
    for (i = 0; i < d->count; ++i) {
        const drop_ball *b = &d->balls[i];
        double m = s->exact[b->body].mass;
        for (k = -1; k + 1 < b->n && b->T[k + 1] <= d->tend; ++k) {}
        if (k < 0)
            continue; /* still falling: free fall keeps the energy */
        if (b->U[k] > d->rest && b->e > 0.0)
            de += m * (b->e * b->U[k]) * (b->e * b->U[k]) / 2.0 - m * d->g * b->h0;
        else
            de -= m * d->g * b->h0;
    }
    return de;
}

int drop_late_impacts(const drop *d, const drop_ball *b, const events *ev)
{
    int i, n = 0;
    if (b->rest_t < 0.0)
        return 0;
    for (i = 0; i < ev->count; ++i)
        if ((ev->rows[i].b == b->body || ev->rows[i].a == b->body) &&
            ev->rows[i].t > b->rest_t + 2.0 * d->dt)
            ++n;
    return n;
}

const event_row *drop_first_impact(const drop_ball *b, const events *ev)
{
    int i;
    for (i = 0; i < ev->count; ++i)
        if (ev->rows[i].b == b->body || ev->rows[i].a == b->body)
            return &ev->rows[i];
    return NULL;
}

void drop_match_impacts(const drop *d, const events *ev, drop_impacts *out)
{
    int i, j;
    size_t used = 0;
    memset(out, 0, sizeof *out);
    for (j = 0; j < d->count; ++j) {
        const drop_ball *b = &d->balls[j];
        double t = 0.0, u = 0.0;
        int n = 0;
        for (i = 0; i < ev->count; ++i) {
            const event_row *r = &ev->rows[i];
            if (r->b != b->body && r->a != b->body)
                continue;
            /* the n-th row against the n-th impact of the sequence, each
             * computed from the exact one before it */
            if (n == 0) {
                t = b->T[0];
                u = b->U[0];
            } else {
                t += 2.0 * b->e * u / d->g;
                u *= b->e;
            }
            ++n;
            if (!(u > d->rest)) {
                ++out->slow;
                if (used + 1 < sizeof out->slow_text)
                    used += (size_t)snprintf(out->slow_text + used, sizeof out->slow_text - used,
                                             "%sball %d (e = %g): row t = %.6f s, approach %.6f "
                                             "m/s; exact arrival t = %.6f s at %.6f m/s",
                                             out->slow > 1 ? "; " : "", b->body, b->e, r->t,
                                             r->approach, t, u);
                continue;
            }
            out->dt_rel = maxd(out->dt_rel, fabs(r->t - t) / t);
            out->du_rel = maxd(out->du_rel, fabs(r->approach - u) / u);
            ++out->matched;
        }
        /* the impacts faster than the rest speed within the run */
        t = b->T[0];
        u = b->U[0];
        while (t <= d->tend && u > d->rest) {
            ++out->wanted;
            if (b->e == 0.0)
                break;
            t += 2.0 * b->e * u / d->g;
            u *= b->e;
        }
    }
}

/* ---- polygon hits polygon off-centre ----------------------------------------------------- */

int poly_fit(const vscene *s, poly *p, char *why, size_t n)
{
    const scene_body *A, *B;
    double ha[2] = {0.0, 0.0}, hb[2] = {0.0, 0.0}, c, sn, best = (double)INFINITY, qy = 0.0, e;
    double ray, rby, K;
    int i, j;
    memset(p, 0, sizeof *p);
    if (s->sc.body_count != 2 || !is_dynamic(s, 0, "box", why, n) ||
        !is_dynamic(s, 1, "box", why, n)) {
        if (s->sc.body_count != 2)
            snprintf(why, n, "has %d bodies, not two boxes", s->sc.body_count);
        return -1;
    }
    A = &s->sc.bodies[0];
    B = &s->sc.bodies[1];
    if (A->angle != 0.0f || s->gx != 0.0 || s->gy != 0.0 || A->def.velocity.y != 0.0f ||
        B->def.velocity.y != 0.0f || A->def.angular_velocity != 0.0f ||
        B->def.angular_velocity != 0.0f || !(A->def.velocity.x > B->def.velocity.x)) {
        snprintf(why, n, "is not a level box sliding along x into a turned box, without "
                         "gravity or spin");
        return -1;
    }
    for (i = 0; i < 4; ++i) {
        ha[0] = maxd(ha[0], fabs((double)A->def.vertices[i].x));
        ha[1] = maxd(ha[1], fabs((double)A->def.vertices[i].y));
        hb[0] = maxd(hb[0], fabs((double)B->def.vertices[i].x));
        hb[1] = maxd(hb[1], fabs((double)B->def.vertices[i].y));
    }
    /* B's leftmost corner, from B's centre */
    c = cos((double)B->angle);
    sn = sin((double)B->angle);
    for (i = -1; i <= 1; i += 2)
        for (j = -1; j <= 1; j += 2) {
            double x = i * hb[0] * c - j * hb[1] * sn, y = i * hb[0] * sn + j * hb[1] * c;
            if (x < best) {
                best = x;
                qy = y;
            }
        }
    e = mixed_e(s, 0, 1);
    p->ts = ((double)B->def.position.x + best - ((double)A->def.position.x + ha[0])) /
            ((double)A->def.velocity.x - (double)B->def.velocity.x);
    ray = (double)B->def.position.y + qy - (double)A->def.position.y; /* from A's centre */
    rby = qy;                                                        /* from B's */
    if (!(fabs(ray) <= ha[1])) {
        snprintf(why, n, "B's corner misses A's right face");
        return -1;
    }
    /* n = (1, 0): r x n = -r_y */
    K = 1.0 / s->exact[0].mass + 1.0 / s->exact[1].mass + ray * ray / s->exact[0].inertia +
        rby * rby / s->exact[1].inertia;
    p->P = (1.0 + e) * ((double)A->def.velocity.x - (double)B->def.velocity.x) / K;
    p->v[0] = (double)A->def.velocity.x - p->P / s->exact[0].mass;
    p->w[0] = p->P * ray / s->exact[0].inertia;
    p->v[1] = (double)B->def.velocity.x + p->P / s->exact[1].mass;
    p->w[1] = -p->P * rby / s->exact[1].inertia;
    for (i = 0; i < 2; ++i) {
        const scene_body *b = i == 0 ? A : B;
        p->x0[i] = (double)b->def.position.x + (double)b->def.velocity.x * p->ts;
        p->y0[i] = (double)b->def.position.y;
        p->a0[i] = (double)b->angle;
    }
    return 0;
}

long poly_compare_step(const vscene *s)
{
    static const int engs[] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    long lo = 0, hi = -1;
    size_t i;
    for (i = 0; i < sizeof engs / sizeof engs[0]; ++i) {
        const run *r = &s->runs[engs[i]];
        long first, last = 1000000;
        if (!r->ok || r->ev.count < 1)
            return -1;
        /* events: impacts at their instants inside steps; discrete and
         * Box2D: an impact reported at the end of step k changes the state
         * of step k */
        if (engs[i] == ENG_EVENTS) {
            first = (long)floor(r->ev.rows[0].t / s->dt) + 1;
            if (r->ev.count > 1)
                last = (long)floor(r->ev.rows[1].t / s->dt);
        } else {
            first = (long)floor(r->ev.rows[0].t / s->dt + 0.5);
            if (r->ev.count > 1)
                last = (long)floor(r->ev.rows[1].t / s->dt + 0.5) - 1;
        }
        lo = first > lo ? first : lo;
        hi = hi < 0 || last < hi ? last : hi;
    }
    if (hi > s->steps)
        hi = s->steps;
    return lo <= hi ? hi : -1;
}

void poly_measure(const poly *p, const trace *tr, long step, poly_err *out)
{
    int b;
    memset(out, 0, sizeof *out);
    out->t = tr->t[step];
    for (b = 0; b < 2; ++b) {
        const double *st = TRACE_AT(tr, step, b);
        double dt = out->t - p->ts;
        out->dv = maxd(out->dv, hypot(st[SVX] - p->v[b], st[SVY]));
        out->dw = maxd(out->dw, fabs(st[SW] - p->w[b]));
        out->dx = maxd(out->dx, hypot(st[SX] - (p->x0[b] + p->v[b] * dt), st[SY] - p->y0[b]));
        out->da = maxd(out->da, fabs(wrap_angle(st[SA] - p->a0[b] - p->w[b] * dt)));
        out->vel[b][0] = st[SVX];
        out->vel[b][1] = st[SVY];
        out->vel[b][2] = st[SW];
    }
}

/* ---- nothing moves ----------------------------------------------------------------------- */

void still_measure(const trace *tr, still_err *out)
{
    long k;
    int b;
    memset(out, 0, sizeof *out);
    for (k = 1; k < tr->samples; ++k)
        for (b = 0; b < tr->bodies; ++b) {
            const double *s0 = TRACE_AT(tr, 0, b), *st = TRACE_AT(tr, k, b);
            double d = hypot(st[SX] - s0[SX], st[SY] - s0[SY]);
            out->move = maxd(out->move, d);
            out->move_x = maxd(out->move_x, fabs(st[SX] - s0[SX]));
            out->move_y = maxd(out->move_y, fabs(st[SY] - s0[SY]));
            out->rot = maxd(out->rot, fabs(wrap_angle(st[SA])));
            if (k == tr->samples - 1)
                out->end_move = maxd(out->end_move, d);
        }
    if (tr->bodies > 0 && tr->samples > 0)
        out->rise = TRACE_AT(tr, tr->samples - 1, tr->bodies - 1)[SY] -
                    TRACE_AT(tr, 0, tr->bodies - 1)[SY];
}

/* ---- conserved quantities ---------------------------------------------------------------- */

void conservation_measure(const vscene *s, const trace *tr, conserved *out)
{
    long k;
    double p0x = 0.0, p0y = 0.0, l0 = 0.0;
    memset(out, 0, sizeof *out);
    for (k = 0; k < tr->samples; ++k) {
        double ke = 0.0, pe = 0.0, px = 0.0, py = 0.0, l = 0.0, de;
        int b;
        for (b = 0; b < tr->bodies; ++b) {
            const body_props *bp = &s->exact[b];
            const double *st = TRACE_AT(tr, k, b);
            double c = cos(st[SA]), sn = sin(st[SA]);
            double cx = st[SX] + c * bp->cx - sn * bp->cy, cy = st[SY] + sn * bp->cx + c * bp->cy;
            if (bp->mass == 0.0)
                continue;
            ke += bp->mass * (st[SVX] * st[SVX] + st[SVY] * st[SVY]) / 2.0 +
                  bp->inertia * st[SW] * st[SW] / 2.0;
            pe -= bp->mass * (s->gx * cx + s->gy * cy);
            px += bp->mass * st[SVX];
            py += bp->mass * st[SVY];
            l += bp->inertia * st[SW] + bp->mass * (cx * st[SVY] - cy * st[SVX]);
            if (k == 0)
                out->p_scale += bp->mass * hypot(st[SVX], st[SVY]);
        }
        if (k == 0) {
            out->e0 = ke + pe;
            out->ke0 = ke;
            p0x = px;
            p0y = py;
            l0 = l;
        }
        de = ke + pe - out->e0;
        out->de_max = maxd(out->de_max, fabs(de));
        out->dp_max = maxd(out->dp_max, hypot(px - p0x, py - p0y));
        out->dl_max = maxd(out->dl_max, fabs(l - l0));
        out->de_end = de;
        out->ke_end = ke;
    }
}

/* ---- two traces -------------------------------------------------------------------------- */

int deviation_measure(const trace *a, const trace *b, double tskip, deviation *out)
{
    long k;
    int i;
    memset(out, 0, sizeof *out);
    out->t_apart = -1.0;
    if (a->samples != b->samples || a->bodies != b->bodies)
        return -1;
    for (k = 0; k < a->samples; ++k) {
        if (fabs(a->t[k] - b->t[k]) > SAME_INSTANT)
            return -1;
        for (i = 0; i < a->bodies; ++i) {
            const double *p = TRACE_AT(a, k, i), *q = TRACE_AT(b, k, i);
            double dx = hypot(p[SX] - q[SX], p[SY] - q[SY]);
            out->dx = maxd(out->dx, dx);
            if (dx > APART && out->t_apart < 0.0)
                out->t_apart = a->t[k];
            out->da = maxd(out->da, fabs(wrap_angle(p[SA] - q[SA])));
            if (tskip < 0.0 || fabs(a->t[k] - tskip) > SAME_INSTANT) {
                out->dv = maxd(out->dv, hypot(p[SVX] - q[SVX], p[SVY] - q[SVY]));
                out->dw = maxd(out->dw, fabs(p[SW] - q[SW]));
            }
        }
    }
    return 0;
}

double deviation_skip(const vscene *s)
{
    headon h;
    char why[V_NOTE_MAX];
    return headon_fit(s, &h, why, sizeof why) == 0 ? h.ts : -1.0;
}
