/*
 * reference.c -- exact answers for the accuracy scenes (reference.h).
 *
 * Everything here is double precision and independent of the library:
 * free flight is evaluated in closed form from the last impact, impact
 * instants are closed form (line, bounce) or roots of a smooth gap found by
 * a fine scan and bisection to the last bit (rotating polygon, ball under
 * gravity against a circle), and impulses are the textbook frictionless
 * Newton impulse at the contact point.
 */
#include "accuracy/reference.h"

#include <math.h>
#include <string.h>

/* ---- bodies on a line --------------------------------------------------- */

void ref_line_init(ref_line *s)
{
    memset(s, 0, sizeof *s);
}

void ref_line_add(ref_line *s, int id, double x, double v, double half,
                  double inv_mass, double e)
{
    int k = s->n++;
    s->id[k] = id;
    s->x[k] = x;
    s->v[k] = v;
    s->half[k] = half;
    s->w[k] = inv_mass;
    s->e[k] = e;
}

static void line_move(ref_line *s, double t)
{
    int k;
    for (k = 0; k < s->n; ++k)
        s->x[k] += s->v[k] * (t - s->t);
    s->t = t;
}

int ref_line_advance(ref_line *s, double t)
{
    for (;;) {
        double best = t;
        int k, hit = -1;
        for (k = 0; k + 1 < s->n; ++k) {
            double closing = s->v[k] - s->v[k + 1], gap, tc;
            if (!(closing > 0.0))
                continue;
            gap = (s->x[k + 1] - s->half[k + 1]) - (s->x[k] + s->half[k]);
            tc = s->t + (gap > 0.0 ? gap / closing : 0.0);
            if (tc <= best && (hit < 0 || tc < best)) {
                best = tc;
                hit = k;
            }
        }
        if (hit < 0) {
            line_move(s, t);
            return 0;
        }
        line_move(s, best);
        {
            double closing = s->v[hit] - s->v[hit + 1];
            double e = s->e[hit] > s->e[hit + 1] ? s->e[hit] : s->e[hit + 1];
            double j = (1.0 + e) * closing / (s->w[hit] + s->w[hit + 1]);
            ref_impact *im;
            s->v[hit] -= j * s->w[hit];
            s->v[hit + 1] += j * s->w[hit + 1];
            if (s->impact_count >= REF_MAX_IMPACTS)
                return -1;
            im = &s->impacts[s->impact_count++];
            im->t = best;
            im->a = s->id[hit] < s->id[hit + 1] ? s->id[hit] : s->id[hit + 1];
            im->b = s->id[hit] < s->id[hit + 1] ? s->id[hit + 1] : s->id[hit];
            im->approach = closing;
        }
    }
}

void ref_line_get(const ref_line *s, int id, double *x, double *v)
{
    int k;
    for (k = 0; k < s->n; ++k)
        if (s->id[k] == id) {
            *x = s->x[k];
            *v = s->v[k];
            return;
        }
    *x = *v = 0.0;
}

/* ---- the bouncing ball -------------------------------------------------- */

void ref_bounce_init(ref_bounce *b, double g, double e, double y0,
                     double y_touch, double t_end)
{
    double t, v;
    memset(b, 0, sizeof *b);
    b->g = g;
    b->e = e;
    b->h0 = y0 - y_touch;
    b->y_touch = y_touch;
    t = sqrt(2.0 * b->h0 / g);
    v = g * t;
    while (t < t_end && b->count < 64) {
        b->t[b->count] = t;
        b->v[b->count] = v;
        ++b->count;
        t += 2.0 * e * v / g;
        v *= e;
    }
}

void ref_bounce_at(const ref_bounce *b, double t, double *y, double *vy)
{
    int k = b->count - 1;
    double s, u;
    while (k >= 0 && b->t[k] > t)
        --k;
    if (k < 0) {
        *y = b->y_touch + b->h0 - 0.5 * b->g * t * t;
        *vy = -b->g * t;
        return;
    }
    s = t - b->t[k];
    u = b->e * b->v[k];
    *y = b->y_touch + u * s - 0.5 * b->g * s * s;
    *vy = u - b->g * s;
}

/* ---- a spinning polygon between two walls -------------------------------- */

void ref_spin_init(ref_spin *s, int nv, const double *px, const double *py,
                   double m, double I, double e, double x_lo, double x_hi,
                   double cx, double cy, double vx, double vy, double th,
                   double w)
{
    double reach = 0.0, speed;
    int k;
    memset(s, 0, sizeof *s);
    s->nv = nv;
    for (k = 0; k < nv; ++k) {
        s->px[k] = px[k];
        s->py[k] = py[k];
        if (hypot(px[k], py[k]) > reach)
            reach = hypot(px[k], py[k]);
    }
    s->m = m;
    s->inv_m = 1.0 / m;
    s->I = I;
    s->inv_I = 1.0 / I;
    s->e = e;
    s->x_lo = x_lo;
    s->x_hi = x_hi;
    s->cx = cx;
    s->cy = cy;
    s->vx = vx;
    s->vy = vy;
    s->th = th;
    s->w = w;
    /* scan step: a vertex moves at most about 1e-5 of the reach per scan
     * step, so a penetration hidden between two samples would be far
     * below float resolution */
    speed = hypot(vx, vy) + fabs(w) * reach + 1e-30;
    s->dt_scan = 1e-5 * reach / speed;
    if (s->dt_scan > 1e-4)
        s->dt_scan = 1e-4;
}

/* Gap of vertex k to wall side (0: left, 1: right) a time h after s->t:
 * negative while apart. */
static double spin_gap(const ref_spin *s, int k, int side, double h)
{
    double th = s->th + s->w * h;
    double x = s->cx + s->vx * h + cos(th) * s->px[k] - sin(th) * s->py[k];
    return side ? x - s->x_hi : s->x_lo - x;
}

static void spin_move(ref_spin *s, double h)
{
    s->cx += s->vx * h;
    s->cy += s->vy * h;
    s->th += s->w * h;
    s->t += h;
}

int ref_spin_advance(ref_spin *s, double t)
{
    double prev[2 * REF_MAX_VERTS];
    int k;
    for (k = 0; k < 2 * s->nv; ++k)
        prev[k] = spin_gap(s, k / 2, k % 2, 0.0);
    while (s->t < t) {
        double ha = 0.0, hb, best = -1.0;
        int hit = -1;
        for (;;) {
            double cur[2 * REF_MAX_VERTS];
            hb = ha + s->dt_scan;
            if (s->t + hb > t)
                hb = t - s->t;
            for (k = 0; k < 2 * s->nv; ++k) {
                cur[k] = spin_gap(s, k / 2, k % 2, hb);
                if (prev[k] < 0.0 && cur[k] >= 0.0) {
                    /* bisect [lo, hi]: gap < 0 at lo, >= 0 at hi */
                    double lo = ha, hi = hb;
                    int it;
                    for (it = 0; it < 200 && hi - lo > 0.0; ++it) {
                        double mid = 0.5 * (lo + hi);
                        if (mid <= lo || mid >= hi)
                            break;
                        if (spin_gap(s, k / 2, k % 2, mid) < 0.0)
                            lo = mid;
                        else
                            hi = mid;
                    }
                    if (hit < 0 || hi < best) {
                        best = hi;
                        hit = k;
                    }
                }
            }
            if (hit >= 0 || s->t + hb >= t) {
                if (hit < 0) {
                    spin_move(s, hb);
                    memcpy(prev, cur, sizeof(double) * 2 * (size_t)s->nv);
                }
                break;
            }
            memcpy(prev, cur, sizeof(double) * 2 * (size_t)s->nv);
            ha = hb;
        }
        if (hit < 0)
            break;
        spin_move(s, best);
        {
            int v = hit / 2, side = hit % 2;
            double c = cos(s->th), sn = sin(s->th);
            double ry = sn * s->px[v] + c * s->py[v];
            double nx = side ? -1.0 : 1.0; /* from the wall into the body */
            double vpx = s->vx - s->w * ry;
            double vn = vpx * nx;           /* n = (nx, 0) */
            double rxn = -ry * nx;          /* r x n */
            if (vn < 0.0) {
                double j = -(1.0 + s->e) * vn / (s->inv_m + rxn * rxn * s->inv_I);
                ref_impact *im;
                s->vx += j * nx * s->inv_m;
                s->w += rxn * j * s->inv_I;
                if (s->impact_count >= REF_MAX_IMPACTS)
                    return -1;
                im = &s->impacts[s->impact_count++];
                im->t = s->t;
                im->a = side;
                im->b = v;
                im->approach = -vn;
            }
        }
        for (k = 0; k < 2 * s->nv; ++k)
            prev[k] = spin_gap(s, k / 2, k % 2, 0.0);
    }
    return 0;
}

void ref_spin_state(const ref_spin *s, double *cx, double *cy, double *vx,
                    double *vy, double *th, double *w)
{
    *cx = s->cx;
    *cy = s->cy;
    *vx = s->vx;
    *vy = s->vy;
    *th = s->th;
    *w = s->w;
}

/* ---- a ball against a static circle under gravity ------------------------ */

void ref_ball_init(ref_ball *b, double g, double e, double R, double ox,
                   double oy, double x, double y, double vx, double vy)
{
    memset(b, 0, sizeof *b);
    b->g = g;
    b->e = e;
    b->R = R;
    b->ox = ox;
    b->oy = oy;
    b->x = x;
    b->y = y;
    b->vx = vx;
    b->vy = vy;
}

static double ball_gap(const ref_ball *b, double h)
{
    double dx = b->x - b->ox + b->vx * h;
    double dy = b->y - b->oy + b->vy * h - 0.5 * b->g * h * h;
    return hypot(dx, dy) - b->R;
}

static void ball_move(ref_ball *b, double h)
{
    b->x += b->vx * h;
    b->y += b->vy * h - 0.5 * b->g * h * h;
    b->vy -= b->g * h;
    b->t += h;
}

int ref_ball_advance(ref_ball *b, double t)
{
    const double scan = 1e-5;
    while (b->t < t) {
        double ha = 0.0, hb, ga = ball_gap(b, 0.0), gb;
        int hit = 0;
        for (;;) {
            hb = ha + scan;
            if (b->t + hb > t)
                hb = t - b->t;
            gb = ball_gap(b, hb);
            if (ga > 0.0 && gb <= 0.0) {
                hit = 1;
                break;
            }
            if (b->t + hb >= t)
                break;
            ha = hb;
            ga = gb;
        }
        if (!hit) {
            ball_move(b, hb);
            break;
        }
        {
            double lo = ha, hi = hb, dx, dy, d, nx, ny, vn;
            int it;
            for (it = 0; it < 200; ++it) {
                double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi)
                    break;
                if (ball_gap(b, mid) > 0.0)
                    lo = mid;
                else
                    hi = mid;
            }
            ball_move(b, hi);
            dx = b->x - b->ox;
            dy = b->y - b->oy;
            d = hypot(dx, dy);
            nx = dx / d;
            ny = dy / d;
            vn = b->vx * nx + b->vy * ny;
            if (vn < 0.0) {
                ref_impact *im;
                b->vx -= (1.0 + b->e) * vn * nx;
                b->vy -= (1.0 + b->e) * vn * ny;
                if (b->impact_count >= 64)
                    return -1;
                im = &b->impacts[b->impact_count++];
                im->t = b->t;
                im->a = 0;
                im->b = 1;
                im->approach = -vn;
            }
        }
    }
    return 0;
}

void ref_ball_state(const ref_ball *b, double *x, double *y, double *vx,
                    double *vy)
{
    *x = b->x;
    *y = b->y;
    *vx = b->vx;
    *vy = b->vy;
}
