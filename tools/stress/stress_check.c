/*
 * stress_check.c -- build/stress_check: evaluate a stress scene's pass
 * criterion on an engine's output (tools/stress/, docs/stability.md).
 *
 *   stress_check SCENE FINAL.csv [TRACE.csv] [EVENTS.csv]
 *   stress_check --info SCENE
 *   stress_check --plot SCENE FILE
 *   stress_check --time SECONDS_FILE [--limit SEC] COMMAND [ARG...]
 *
 * The scene is read with the CLI's parser (tools/scene.c, scene_load) for
 * its bodies; the criterion comes from the scene's comment lines:
 *
 *   # family: NAME           report grouping (default: "other")
 *   # fast                   the scene is in the fast subset
 *   # engines: NAME ...      the criterion applies to these engines only
 *                            (events, discrete, box2d, v3); the others are
 *                            run but reported "n/a" (default: all). The pi
 *                            billiard's exact impact count is a claim of
 *                            the events method alone.
 *   # check: KIND KEY=VALUE ...   one criterion; all of them must pass
 *   # plot: QUANTITY KEY=VALUE ...  what the report's figure draws
 *
 * Check kinds (lengths in m, speeds in m/s; "dynamic" = not static; the
 * "lowest point" of a body is its lowest vertex, or centre y - radius for a
 * circle; "end" = the final state, "trace" = every row of the trace and the
 * final state):
 *
 *   stay body=N tol=L          |position - start| <= L at the end (start:
 *                              the position in the scene)
 *   still speed=V [body=N]     |velocity| < V at the end, every dynamic
 *                              body (or body N)
 *   above y=Y [body=N] [over=end|trace]
 *                              lowest point > Y, every dynamic body (or N)
 *   contain xmin=A xmax=B ymin=C [ymax=D]
 *                              every dynamic centre strictly inside, at the
 *                              end (measured: how many are not)
 *   overlap max=L              deepest pairwise penetration <= L at the end,
 *                              over all pairs with a dynamic body: exact
 *                              for circle-circle and circle-polygon, SAT
 *                              (minimum translation distance) for
 *                              polygon-polygon
 *   order upper=N lower=M [over=end|trace]
 *                              y of N - y of M > 0
 *   rest body=N y=Y tol=L speed=V
 *                              at the end body N lies on a surface at
 *                              height Y: |lowest point - Y| <= L, vertical
 *                              extent <= its smallest width + L (flat), and
 *                              |velocity| <= V
 *   impacts count=K | impacts [min=A] [max=B]
 *                              rows of EVENTS.csv (== K, or within [A, B])
 *
 * Plot quantities (--plot prints the series, whitespace-separated):
 *   dy body=N [scale=S]       t, (y - y_start) / S        (needs the trace)
 *   bottom body=N [scale=S]   t, lowest point / S         (needs the trace)
 *   impacts                   t, impacts so far           (needs the events)
 *   snapshot                  the final state: circles "x y r" (gnuplot
 *                             index 0), then polygon outlines (index 1)
 *
 * --info prints the scene's metadata as "KEY VALUE" lines: name, family,
 * fast, steps, dt, bodies, trace and events (1 if the checks need that
 * file), plot (the quantity or "none"), plot-input (final, trace, events
 * or none), engines ("all" or a comma-separated list) and, for an
 * "impacts count=K" check, plot-ref K.
 *
 * --time runs COMMAND (stdin, stdout and stderr inherited), writes its
 * wall-clock time in seconds (CLOCK_MONOTONIC) to SECONDS_FILE and exits
 * with its status (126/127 if it could not be run, 128 + N if killed by
 * signal N, 124 if --limit SEC passed and it was killed).
 *
 * Check mode prints one line
 *   PASS|FAIL NAME: LABEL VALUE OP LIMIT [(DETAIL)]; ...
 * where OP is the comparison that holds, and a failing check's LABEL is
 * marked with a leading '*' (its OP then shows the violated comparison). Exit status: 0 pass, 1 fail, 2 bad usage or bad input.
 * Everything is computed in double. FINAL.csv is build/carom's
 * "body,x,y,angle,vx,vy,omega" (x, y: body origin, angle in radians), the
 * trace "step,t,body,x,y,angle,vx,vy,omega", the events
 * "t,body_a,body_b,nx,ny,impulse,approach_speed".
 */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "scene.h"

#define EXIT_PASS 0
#define EXIT_FAIL 1
#define EXIT_BAD 2
#define MAX_CHECKS 32
#define MAX_KEYS 8
#define LINE_MAX_LEN 8192
#define MAXV CAROM_MAX_POLYGON_VERTICES

static const char usage_text[] =
    "usage: stress_check SCENE FINAL.csv [TRACE.csv] [EVENTS.csv]\n"
    "       stress_check --info SCENE\n"
    "       stress_check --plot SCENE FILE\n"
    "       stress_check --time SECONDS_FILE [--limit SEC] COMMAND [ARG...]\n"
    "Evaluates the scene's '# check:' criteria on an engine's output.\n"
    "exit status: 0 pass, 1 fail, 2 bad usage or bad input\n";

/* ---- geometry ---------------------------------------------------------------- */

typedef struct geo {
    int circle;   /* 1: circle of radius r; 0: polygon */
    int dynamic;
    double r;
    int n;
    double lx[MAXV], ly[MAXV]; /* vertices, body frame (about the origin) */
    double x0, y0;             /* start position */
    double min_width;          /* smallest width (circle: 2r) */
} geo;

typedef struct pose {
    double x, y, a, vx, vy, w;
    int seen;
} pose;

typedef struct shape {
    int circle;
    double cx, cy, r;
    int n;
    double x[MAXV], y[MAXV];
    double nx[MAXV], ny[MAXV]; /* outward unit edge normals */
    double minx, maxx, miny, maxy;
} shape;

static void make_shape(const geo *g, const pose *p, shape *s)
{
    int i;
    s->circle = g->circle;
    s->cx = p->x;
    s->cy = p->y;
    if (g->circle) {
        s->r = g->r;
        s->n = 0;
        s->minx = p->x - g->r;
        s->maxx = p->x + g->r;
        s->miny = p->y - g->r;
        s->maxy = p->y + g->r;
        return;
    } else {
        double c = cos(p->a), sn = sin(p->a), mx = 0.0, my = 0.0;
        s->r = 0.0;
        s->n = g->n;
        for (i = 0; i < g->n; ++i) {
            s->x[i] = p->x + c * g->lx[i] - sn * g->ly[i];
            s->y[i] = p->y + sn * g->lx[i] + c * g->ly[i];
            mx += s->x[i];
            my += s->y[i];
        }
        mx /= g->n;
        my /= g->n;
        s->minx = s->maxx = s->x[0];
        s->miny = s->maxy = s->y[0];
        for (i = 0; i < g->n; ++i) {
            int j = (i + 1) % g->n;
            double ex = s->x[j] - s->x[i], ey = s->y[j] - s->y[i];
            double len = sqrt(ex * ex + ey * ey);
            double nx = ey / len, ny = -ex / len;
            /* outward: away from the vertex mean (either winding) */
            if (nx * (s->x[i] - mx) + ny * (s->y[i] - my) < 0.0) {
                nx = -nx;
                ny = -ny;
            }
            s->nx[i] = nx;
            s->ny[i] = ny;
            if (s->x[i] < s->minx) s->minx = s->x[i];
            if (s->x[i] > s->maxx) s->maxx = s->x[i];
            if (s->y[i] < s->miny) s->miny = s->y[i];
            if (s->y[i] > s->maxy) s->maxy = s->y[i];
        }
    }
}

static void project(const shape *s, double nx, double ny, double *lo, double *hi)
{
    int i;
    if (s->circle) {
        double c = s->cx * nx + s->cy * ny;
        *lo = c - s->r;
        *hi = c + s->r;
        return;
    }
    *lo = *hi = s->x[0] * nx + s->y[0] * ny;
    for (i = 1; i < s->n; ++i) {
        double d = s->x[i] * nx + s->y[i] * ny;
        if (d < *lo) *lo = d;
        if (d > *hi) *hi = d;
    }
}

/* Penetration depth of two convex polygons: the smallest overlap over the
 * edge normals of both (separating axis theorem); 0 if separated. */
static double depth_poly_poly(const shape *a, const shape *b)
{
    double best = HUGE_VAL;
    const shape *s[2];
    int k, i;
    s[0] = a;
    s[1] = b;
    for (k = 0; k < 2; ++k) {
        for (i = 0; i < s[k]->n; ++i) {
            double alo, ahi, blo, bhi, d;
            project(a, s[k]->nx[i], s[k]->ny[i], &alo, &ahi);
            project(b, s[k]->nx[i], s[k]->ny[i], &blo, &bhi);
            d = ahi - blo < bhi - alo ? ahi - blo : bhi - alo;
            if (d <= 0.0)
                return 0.0;
            if (d < best)
                best = d;
        }
    }
    return best;
}

/* Circle (centre c, radius r) against a convex polygon: r - distance to the
 * polygon outside it, r + distance to the boundary inside it. */
static double depth_circle_poly(const shape *c, const shape *p)
{
    double inside_dist = HUGE_VAL, out_dist = HUGE_VAL, d;
    int i, inside = 1;
    for (i = 0; i < p->n; ++i) {
        double sd = p->nx[i] * (c->cx - p->x[i]) + p->ny[i] * (c->cy - p->y[i]);
        if (sd > 0.0)
            inside = 0;
        if (-sd < inside_dist)
            inside_dist = -sd;
    }
    if (inside) {
        d = c->r + inside_dist;
        return d;
    }
    for (i = 0; i < p->n; ++i) {
        int j = (i + 1) % p->n;
        double ex = p->x[j] - p->x[i], ey = p->y[j] - p->y[i];
        double qx = c->cx - p->x[i], qy = c->cy - p->y[i];
        double t = (qx * ex + qy * ey) / (ex * ex + ey * ey);
        double dx, dy, dist;
        if (t < 0.0) t = 0.0;
        if (t > 1.0) t = 1.0;
        dx = qx - t * ex;
        dy = qy - t * ey;
        dist = sqrt(dx * dx + dy * dy);
        if (dist < out_dist)
            out_dist = dist;
    }
    d = c->r - out_dist;
    return d > 0.0 ? d : 0.0;
}

static double depth(const shape *a, const shape *b)
{
    if (a->maxx < b->minx || b->maxx < a->minx || a->maxy < b->miny ||
        b->maxy < a->miny)
        return 0.0;
    if (a->circle && b->circle) {
        double dx = a->cx - b->cx, dy = a->cy - b->cy;
        double d = a->r + b->r - sqrt(dx * dx + dy * dy);
        return d > 0.0 ? d : 0.0;
    }
    if (a->circle)
        return depth_circle_poly(a, b);
    if (b->circle)
        return depth_circle_poly(b, a);
    return depth_poly_poly(a, b);
}

static double lowest_point(const geo *g, const pose *p)
{
    shape s;
    make_shape(g, p, &s);
    return s.miny;
}

/* ---- criteria ----------------------------------------------------------------- */

enum kind { K_STAY, K_STILL, K_ABOVE, K_CONTAIN, K_OVERLAP, K_ORDER, K_REST,
            K_IMPACTS };
static const char *const kind_names[] = {"stay", "still", "above", "contain",
                                         "overlap", "order", "rest", "impacts"};
enum plot_kind { P_NONE, P_DY, P_BOTTOM, P_IMPACTS, P_SNAPSHOT };
static const char *const plot_names[] = {"none", "dy", "bottom", "impacts",
                                         "snapshot"};

typedef struct check {
    int kind;
    int line;
    int body, body2;            /* body=, lower= ; -1 if not given */
    int trace;                  /* over=trace */
    double a, b, c, d;          /* kind-specific limits */
    int has_c, has_d;
    long count_lo, count_hi;
    /* results */
    double m1, m2, m3;          /* measured */
    int where1, where2;         /* bodies behind the measured value */
    double at_t;                /* time of the extreme (trace checks) */
} check;

typedef struct spec {
    const char *path;
    char name[256];
    char family[64];
    char engines[128];
    int fast;
    int nchecks;
    check checks[MAX_CHECKS];
    int plot;
    int plot_body;
    double plot_scale;
    int need_trace, need_events;
} spec;

typedef struct kv {
    char key[32];
    char val[64];
} kv;

static int bad(const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "stress_check: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n");
    return EXIT_BAD;
}

static int split_words(char *s, char **w, int max)
{
    int n = 0;
    char *save = NULL, *tok;
    for (tok = strtok_r(s, " \t\r\n", &save); tok && n < max;
         tok = strtok_r(NULL, " \t\r\n", &save))
        w[n++] = tok;
    return tok ? -1 : n;
}

/* Parse words[1..] as key=value; returns the count or -1. */
static int parse_kvs(char **w, int n, kv *out, const char *path, int line)
{
    int i, k = 0;
    for (i = 1; i < n; ++i) {
        char *eq = strchr(w[i], '=');
        if (!eq || eq == w[i] || strlen(eq + 1) == 0 ||
            (size_t)(eq - w[i]) >= sizeof out->key || strlen(eq + 1) >= sizeof out->val) {
            bad("%s:%d: expected key=value, got '%s'", path, line, w[i]);
            return -1;
        }
        if (k == MAX_KEYS) {
            bad("%s:%d: too many keys", path, line);
            return -1;
        }
        memcpy(out[k].key, w[i], (size_t)(eq - w[i]));
        out[k].key[eq - w[i]] = '\0';
        strcpy(out[k].val, eq + 1);
        ++k;
    }
    return k;
}

static int num_val(const char *path, int line, const char *key, const char *v,
                   double *out)
{
    char *end;
    errno = 0;
    *out = strtod(v, &end);
    if (end == v || *end != '\0' || errno == ERANGE || !isfinite(*out)) {
        bad("%s:%d: %s: not a finite number: '%s'", path, line, key, v);
        return -1;
    }
    return 0;
}

static int int_val(const char *path, int line, const char *key, const char *v,
                   long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    *out = strtol(v, &end, 10);
    if (end == v || *end != '\0' || errno == ERANGE || *out < lo || *out > hi) {
        bad("%s:%d: %s: want an integer in [%ld, %ld], got '%s'", path, line,
            key, lo, hi, v);
        return -1;
    }
    return 0;
}

/* The allowed and required keys of each kind. */
typedef struct kind_keys {
    const char *allowed;  /* space-separated */
    const char *required;
} kind_keys;
static const kind_keys keys_of[] = {
    {" body tol ", " body tol "},
    {" speed body ", " speed "},
    {" y body over ", " y "},
    {" xmin xmax ymin ymax ", " xmin xmax ymin "},
    {" max ", " max "},
    {" upper lower over ", " upper lower "},
    {" body y tol speed ", " body y tol speed "},
    {" count min max ", ""},
};

static int word_in(const char *list, const char *w)
{
    char buf[40];
    if (strlen(w) > 32)
        return 0;
    snprintf(buf, sizeof buf, " %s ", w);
    return strstr(list, buf) != NULL;
}

static int parse_check(spec *sp, char **w, int n, int line, int nbodies)
{
    kv kvs[MAX_KEYS];
    int nk, i, k;
    check *c;
    char req[64], *save = NULL, *tok;
    if (sp->nchecks == MAX_CHECKS)
        return bad("%s:%d: more than %d checks", sp->path, line, MAX_CHECKS);
    if (n < 1)
        return bad("%s:%d: check: missing kind", sp->path, line);
    for (k = 0; k <= K_IMPACTS; ++k)
        if (strcmp(w[0], kind_names[k]) == 0)
            break;
    if (k > K_IMPACTS)
        return bad("%s:%d: check: unknown kind '%s' (stay still above contain "
                   "overlap order rest impacts)", sp->path, line, w[0]);
    nk = parse_kvs(w, n, kvs, sp->path, line);
    if (nk < 0)
        return EXIT_BAD;
    c = &sp->checks[sp->nchecks];
    memset(c, 0, sizeof *c);
    c->kind = k;
    c->line = line;
    c->body = c->body2 = -1;
    c->count_lo = 0;
    c->count_hi = -1;
    for (i = 0; i < nk; ++i) {
        int j;
        const char *key = kvs[i].key, *v = kvs[i].val;
        long lv;
        if (!word_in(keys_of[k].allowed, key))
            return bad("%s:%d: check %s: unknown key '%s' (allowed:%s)", sp->path,
                       line, kind_names[k], key, keys_of[k].allowed);
        for (j = 0; j < i; ++j)
            if (strcmp(kvs[j].key, key) == 0)
                return bad("%s:%d: check %s: %s given twice", sp->path, line,
                           kind_names[k], key);
        if (strcmp(key, "body") == 0 || strcmp(key, "upper") == 0) {
            if (int_val(sp->path, line, key, v, 0, nbodies - 1, &lv))
                return EXIT_BAD;
            c->body = (int)lv;
        } else if (strcmp(key, "lower") == 0) {
            if (int_val(sp->path, line, key, v, 0, nbodies - 1, &lv))
                return EXIT_BAD;
            c->body2 = (int)lv;
        } else if (strcmp(key, "over") == 0) {
            if (strcmp(v, "trace") == 0)
                c->trace = 1;
            else if (strcmp(v, "end") != 0)
                return bad("%s:%d: over: want end or trace, got '%s'", sp->path,
                           line, v);
        } else if (strcmp(key, "count") == 0 || strcmp(key, "min") == 0 ||
                   (k == K_IMPACTS && strcmp(key, "max") == 0)) {
            if (int_val(sp->path, line, key, v, 0, 1000000000L, &lv))
                return EXIT_BAD;
            if (strcmp(key, "count") == 0)
                c->count_lo = c->count_hi = lv;
            else if (strcmp(key, "min") == 0)
                c->count_lo = lv;
            else
                c->count_hi = lv;
        } else {
            double d;
            if (num_val(sp->path, line, key, v, &d))
                return EXIT_BAD;
            /* a: tol / speed / y / xmin / max; b: speed (rest) / xmax;
             * c: ymin / tol (rest); d: ymax / y (rest) */
            if (k == K_REST) {
                if (strcmp(key, "y") == 0) c->d = d;
                else if (strcmp(key, "tol") == 0) c->c = d;
                else c->b = d; /* speed */
            } else if (strcmp(key, "xmax") == 0) {
                c->b = d;
            } else if (strcmp(key, "ymin") == 0) {
                c->c = d;
                c->has_c = 1;
            } else if (strcmp(key, "ymax") == 0) {
                c->d = d;
                c->has_d = 1;
            } else {
                c->a = d;
            }
            if ((strcmp(key, "tol") == 0 || strcmp(key, "speed") == 0 ||
                 strcmp(key, "max") == 0) && d < 0.0)
                return bad("%s:%d: %s: must be >= 0", sp->path, line, key);
        }
    }
    /* required keys */
    snprintf(req, sizeof req, "%s", keys_of[k].required);
    for (tok = strtok_r(req, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        for (i = 0; i < nk; ++i)
            if (strcmp(kvs[i].key, tok) == 0)
                break;
        if (i == nk)
            return bad("%s:%d: check %s: missing %s=", sp->path, line,
                       kind_names[k], tok);
    }
    if (k == K_IMPACTS) {
        int has_count = 0, has_range = 0;
        for (i = 0; i < nk; ++i) {
            if (strcmp(kvs[i].key, "count") == 0) has_count = 1;
            else has_range = 1;
        }
        if (has_count == has_range)
            return bad("%s:%d: check impacts: give count= or min=/max=", sp->path,
                       line);
    }
    if (k == K_CONTAIN && !(c->b > c->a))
        return bad("%s:%d: check contain: want xmin < xmax", sp->path, line);
    if (k == K_ORDER && c->body == c->body2)
        return bad("%s:%d: check order: upper and lower are the same body",
                   sp->path, line);
    if (c->trace)
        sp->need_trace = 1;
    if (k == K_IMPACTS)
        sp->need_events = 1;
    sp->nchecks++;
    return 0;
}

static int parse_plot(spec *sp, char **w, int n, int line, int nbodies)
{
    kv kvs[MAX_KEYS];
    int nk, i, k;
    if (sp->plot != P_NONE)
        return bad("%s:%d: second plot line", sp->path, line);
    if (n < 1)
        return bad("%s:%d: plot: missing quantity", sp->path, line);
    for (k = P_DY; k <= P_SNAPSHOT; ++k)
        if (strcmp(w[0], plot_names[k]) == 0)
            break;
    if (k > P_SNAPSHOT)
        return bad("%s:%d: plot: unknown quantity '%s' (dy bottom impacts "
                   "snapshot)", sp->path, line, w[0]);
    nk = parse_kvs(w, n, kvs, sp->path, line);
    if (nk < 0)
        return EXIT_BAD;
    sp->plot = k;
    sp->plot_body = -1;
    sp->plot_scale = 1.0;
    for (i = 0; i < nk; ++i) {
        long lv;
        if ((k == P_DY || k == P_BOTTOM) && strcmp(kvs[i].key, "body") == 0) {
            if (int_val(sp->path, line, "body", kvs[i].val, 0, nbodies - 1, &lv))
                return EXIT_BAD;
            sp->plot_body = (int)lv;
        } else if ((k == P_DY || k == P_BOTTOM) && strcmp(kvs[i].key, "scale") == 0) {
            if (num_val(sp->path, line, "scale", kvs[i].val, &sp->plot_scale))
                return EXIT_BAD;
            if (!(sp->plot_scale > 0.0))
                return bad("%s:%d: scale: must be > 0", sp->path, line);
        } else {
            return bad("%s:%d: plot %s: unknown key '%s'", sp->path, line,
                       plot_names[k], kvs[i].key);
        }
    }
    if ((k == P_DY || k == P_BOTTOM) && sp->plot_body < 0)
        return bad("%s:%d: plot %s: missing body=", sp->path, line, plot_names[k]);
    return 0;
}

/* Read the scene's comment lines into *sp. */
static int read_spec(const char *path, int nbodies, spec *sp)
{
    FILE *f = fopen(path, "r");
    char line[LINE_MAX_LEN];
    int lineno = 0;
    const char *base;
    size_t len;
    memset(sp, 0, sizeof *sp);
    sp->path = path;
    strcpy(sp->family, "other");
    strcpy(sp->engines, "all");
    base = strrchr(path, '/');
    base = base ? base + 1 : path;
    len = strlen(base);
    if (len > 6 && strcmp(base + len - 6, ".scene") == 0)
        len -= 6;
    if (len >= sizeof sp->name)
        len = sizeof sp->name - 1;
    memcpy(sp->name, base, len);
    sp->name[len] = '\0';
    if (!f)
        return bad("%s: cannot open: %s", path, strerror(errno));
    while (fgets(line, sizeof line, f)) {
        char *p = line, *w[64];
        int n, rc = 0;
        ++lineno;
        while (*p == ' ' || *p == '\t')
            ++p;
        if (*p != '#')
            continue;
        ++p;
        while (*p == ' ' || *p == '\t')
            ++p;
        if (strncmp(p, "check:", 6) == 0) {
            n = split_words(p + 6, w, 64);
            rc = n < 0 ? bad("%s:%d: too many words", path, lineno)
                       : parse_check(sp, w, n, lineno, nbodies);
        } else if (strncmp(p, "plot:", 5) == 0) {
            n = split_words(p + 5, w, 64);
            rc = n < 0 ? bad("%s:%d: too many words", path, lineno)
                       : parse_plot(sp, w, n, lineno, nbodies);
        } else if (strncmp(p, "engines:", 8) == 0) {
            int j;
            size_t used = 0;
            n = split_words(p + 8, w, 64);
            if (n < 1)
                rc = bad("%s:%d: engines: want at least one name", path, lineno);
            sp->engines[0] = '\0';
            for (j = 0; j < n && !rc; ++j) {
                size_t len = strlen(w[j]);
                if (strcmp(w[j], "events") && strcmp(w[j], "discrete") &&
                    strcmp(w[j], "box2d") && strcmp(w[j], "v3"))
                    rc = bad("%s:%d: engines: unknown engine '%s' (events, discrete, "
                             "box2d, v3)", path, lineno, w[j]);
                else if (used + len + 2 > sizeof sp->engines)
                    rc = bad("%s:%d: engines: too long", path, lineno);
                else {
                    if (used)
                        sp->engines[used++] = ',';
                    memcpy(sp->engines + used, w[j], len + 1);
                    used += len;
                }
            }
        } else if (strncmp(p, "family:", 7) == 0) {
            n = split_words(p + 7, w, 64);
            if (n != 1 || strlen(w[0]) >= sizeof sp->family)
                rc = bad("%s:%d: family: want one short word", path, lineno);
            else
                strcpy(sp->family, w[0]);
        } else {
            n = split_words(p, w, 64);
            if (n == 1 && strcmp(w[0], "fast") == 0)
                sp->fast = 1;
        }
        if (rc) {
            fclose(f);
            return rc;
        }
    }
    fclose(f);
    if (sp->nchecks == 0)
        return bad("%s: no '# check:' line", path);
    return 0;
}

static int load_geometry(const scene *s, geo *g)
{
    int i, k;
    for (i = 0; i < s->body_count; ++i) {
        const carom_body_def *d = &s->bodies[i].def;
        memset(&g[i], 0, sizeof g[i]);
        g[i].dynamic = d->type != CAROM_BODY_STATIC;
        g[i].x0 = (double)d->position.x;
        g[i].y0 = (double)d->position.y;
        if (d->shape == CAROM_SHAPE_CIRCLE) {
            g[i].circle = 1;
            g[i].r = (double)d->radius;
            g[i].min_width = 2.0 * g[i].r;
        } else {
            shape sh;
            pose p;
            g[i].n = d->vertex_count;
            for (k = 0; k < d->vertex_count; ++k) {
                g[i].lx[k] = (double)d->vertices[k].x;
                g[i].ly[k] = (double)d->vertices[k].y;
            }
            memset(&p, 0, sizeof p);
            make_shape(&g[i], &p, &sh);
            g[i].min_width = HUGE_VAL;
            for (k = 0; k < sh.n; ++k) {
                double lo, hi;
                project(&sh, sh.nx[k], sh.ny[k], &lo, &hi);
                if (hi - lo < g[i].min_width)
                    g[i].min_width = hi - lo;
            }
        }
    }
    return 0;
}

/* ---- CSV input ------------------------------------------------------------------ */

typedef struct csv {
    FILE *f;
    const char *path;
    long line;
    char buf[LINE_MAX_LEN];
} csv;

static int csv_open(csv *c, const char *path, const char *header)
{
    size_t n;
    c->path = path;
    c->line = 0;
    c->f = fopen(path, "r");
    if (!c->f)
        return bad("%s: cannot open: %s", path, strerror(errno));
    if (!fgets(c->buf, sizeof c->buf, c->f)) {
        fclose(c->f);
        return bad("%s: empty file (want the header '%s')", path, header);
    }
    c->line = 1;
    n = strlen(c->buf);
    while (n > 0 && (c->buf[n - 1] == '\n' || c->buf[n - 1] == '\r'))
        c->buf[--n] = '\0';
    if (strcmp(c->buf, header) != 0) {
        fclose(c->f);
        return bad("%s:1: want the header '%s', got '%s'", path, header, c->buf);
    }
    return 0;
}

/* Next row as `want` numbers: 1 row, 0 end, -1 error (reported). */
static int csv_row(csv *c, double *v, int want)
{
    char *p, *end;
    int k;
    size_t n;
    do {
        if (!fgets(c->buf, sizeof c->buf, c->f))
            return ferror(c->f) ? (bad("%s: read error", c->path), -1) : 0;
        ++c->line;
        n = strlen(c->buf);
        while (n > 0 && (c->buf[n - 1] == '\n' || c->buf[n - 1] == '\r'))
            c->buf[--n] = '\0';
    } while (n == 0);
    p = c->buf;
    for (k = 0; k < want; ++k) {
        errno = 0;
        v[k] = strtod(p, &end);
        if (end == p || !isfinite(v[k]) || (k < want - 1 && *end != ',') ||
            (k == want - 1 && *end != '\0')) {
            bad("%s:%ld: want %d comma-separated finite numbers", c->path,
                c->line, want);
            return -1;
        }
        p = end + 1;
    }
    return 1;
}

static int body_index(const csv *c, double v, int nbodies)
{
    if (v != floor(v) || v < 0.0 || v >= (double)nbodies) {
        bad("%s:%ld: no body %g in the scene (%d bodies)", c->path, c->line, v,
            nbodies);
        return -1;
    }
    return (int)v;
}

static void set_pose(pose *p, const double *v)
{
    p->x = v[0];
    p->y = v[1];
    p->a = v[2];
    p->vx = v[3];
    p->vy = v[4];
    p->w = v[5];
    p->seen = 1;
}

static int read_final(const char *path, pose *poses, int nbodies)
{
    csv c;
    double v[7];
    int rc, i;
    if (csv_open(&c, path, "body,x,y,angle,vx,vy,omega"))
        return EXIT_BAD;
    while ((rc = csv_row(&c, v, 7)) == 1) {
        int b = body_index(&c, v[0], nbodies);
        if (b < 0 || poses[b].seen) {
            if (b >= 0)
                bad("%s:%ld: body %d twice", path, c.line, b);
            fclose(c.f);
            return EXIT_BAD;
        }
        set_pose(&poses[b], v + 1);
    }
    fclose(c.f);
    if (rc < 0)
        return EXIT_BAD;
    for (i = 0; i < nbodies; ++i)
        if (!poses[i].seen)
            return bad("%s: no row for body %d (the scene has %d bodies)", path, i,
                       nbodies);
    return 0;
}

/* ---- evaluation ------------------------------------------------------------------ */

static void init_results(spec *sp)
{
    int i;
    for (i = 0; i < sp->nchecks; ++i) {
        check *c = &sp->checks[i];
        c->where1 = c->where2 = -1;
        c->at_t = -1.0;
        switch (c->kind) {
        case K_ABOVE: c->m1 = HUGE_VAL; break;
        case K_ORDER: c->m1 = HUGE_VAL; break;
        default: c->m1 = c->m2 = c->m3 = 0.0; break;
        }
    }
}

/* Checks that can run on every state (trace rows and the final state). */
static void eval_state_body(check *c, const geo *g, int b, const pose *p,
                            const pose *all, double t)
{
    if (c->kind == K_ABOVE) {
        if (c->body >= 0 ? b == c->body : g[b].dynamic) {
            double lo = lowest_point(&g[b], p);
            if (lo < c->m1) {
                c->m1 = lo;
                c->where1 = b;
                c->at_t = t;
            }
        }
    } else if (c->kind == K_ORDER) {
        if ((b == c->body || b == c->body2) && all[c->body].seen &&
            all[c->body2].seen) {
            double d = all[c->body].y - all[c->body2].y;
            if (d < c->m1) {
                c->m1 = d;
                c->at_t = t;
            }
        }
    }
}

static void eval_final(spec *sp, const geo *g, const pose *p, int nb, long events)
{
    int i, b, j;
    for (i = 0; i < sp->nchecks; ++i) {
        check *c = &sp->checks[i];
        switch (c->kind) {
        case K_ABOVE:
        case K_ORDER:
            for (b = 0; b < nb; ++b)
                eval_state_body(c, g, b, &p[b], p, -1.0);
            if (c->kind == K_ORDER && c->at_t < 0.0)
                c->at_t = -1.0;
            break;
        case K_STAY: {
            double dx = p[c->body].x - g[c->body].x0, dy = p[c->body].y - g[c->body].y0;
            c->m1 = sqrt(dx * dx + dy * dy);
            c->where1 = c->body;
            break;
        }
        case K_STILL:
            for (b = 0; b < nb; ++b) {
                double v;
                if (c->body >= 0 ? b != c->body : !g[b].dynamic)
                    continue;
                v = sqrt(p[b].vx * p[b].vx + p[b].vy * p[b].vy);
                if (c->where1 < 0 || v > c->m1) {
                    c->m1 = v;
                    c->where1 = b;
                }
            }
            break;
        case K_CONTAIN:
            c->m2 = HUGE_VAL; /* smallest margin */
            for (b = 0; b < nb; ++b) {
                double m;
                if (!g[b].dynamic)
                    continue;
                m = p[b].x - c->a;
                if (c->b - p[b].x < m) m = c->b - p[b].x;
                if (p[b].y - c->c < m) m = p[b].y - c->c;
                if (c->has_d && c->d - p[b].y < m) m = c->d - p[b].y;
                if (!(m > 0.0))
                    c->m1 += 1.0;
                if (m < c->m2) {
                    c->m2 = m;
                    c->where1 = b;
                }
            }
            break;
        case K_OVERLAP: {
            shape *sh = (shape *)malloc((size_t)nb * sizeof *sh);
            if (!sh) {
                c->m1 = HUGE_VAL;
                break;
            }
            for (b = 0; b < nb; ++b)
                make_shape(&g[b], &p[b], &sh[b]);
            for (b = 0; b < nb; ++b)
                for (j = b + 1; j < nb; ++j) {
                    double d;
                    if (!g[b].dynamic && !g[j].dynamic)
                        continue;
                    d = depth(&sh[b], &sh[j]);
                    if (d > c->m1) {
                        c->m1 = d;
                        c->where1 = b;
                        c->where2 = j;
                    }
                }
            free(sh);
            break;
        }
        case K_REST: {
            shape s;
            make_shape(&g[c->body], &p[c->body], &s);
            c->m1 = fabs(s.miny - c->d);                       /* gap */
            c->m2 = (s.maxy - s.miny) - g[c->body].min_width;  /* tilt */
            c->m3 = sqrt(p[c->body].vx * p[c->body].vx + p[c->body].vy * p[c->body].vy);
            break;
        }
        case K_IMPACTS:
            c->m1 = (double)events;
            break;
        default:
            break;
        }
    }
}

static int read_trace(const char *path, spec *sp, const geo *g, int nb)
{
    csv c;
    double v[9];
    int rc, i;
    pose *cur = (pose *)calloc((size_t)nb, sizeof *cur);
    long last_step = -1;
    if (!cur)
        return bad("out of memory");
    if (csv_open(&c, path, "step,t,body,x,y,angle,vx,vy,omega")) {
        free(cur);
        return EXIT_BAD;
    }
    while ((rc = csv_row(&c, v, 9)) == 1) {
        int b = body_index(&c, v[2], nb);
        if (b < 0) {
            rc = -1;
            break;
        }
        if ((long)v[0] != last_step) {
            for (i = 0; i < nb; ++i)
                cur[i].seen = 0;
            last_step = (long)v[0];
        }
        set_pose(&cur[b], v + 3);
        for (i = 0; i < sp->nchecks; ++i)
            if (sp->checks[i].trace)
                eval_state_body(&sp->checks[i], g, b, &cur[b], cur, v[1]);
    }
    fclose(c.f);
    free(cur);
    if (rc < 0)
        return EXIT_BAD;
    if (last_step < 0)
        return bad("%s: no rows", path);
    return 0;
}

static long count_events(const char *path)
{
    csv c;
    double v[7];
    int rc;
    long n = 0;
    if (csv_open(&c, path, "t,body_a,body_b,nx,ny,impulse,approach_speed"))
        return -1;
    while ((rc = csv_row(&c, v, 7)) == 1)
        ++n;
    fclose(c.f);
    return rc < 0 ? -1 : n;
}

static void append(char *out, size_t cap, const char *fmt, ...)
{
    va_list ap;
    size_t n = strlen(out);
    if (n >= cap - 1)
        return;
    va_start(ap, fmt);
    vsnprintf(out + n, cap - n, fmt, ap);
    va_end(ap);
}

static void seg(char *out, size_t cap, int *first, const char *label, double v,
                int ok, const char *op_ok, const char *op_bad, double lim,
                const char *detail)
{
    append(out, cap, "%s%s%s %.4g %s %.4g%s%s%s", *first ? "" : "; ",
           ok ? "" : "*", label, v, ok ? op_ok : op_bad, lim, detail[0] ? " (" : "", detail,
           detail[0] ? ")" : "");
    *first = 0;
}

/* Format the verdict; returns 1 if every check passed. */
static int verdict(const spec *sp, char *out, size_t cap)
{
    int i, all = 1, first = 1;
    char label[64], detail[128];
    out[0] = '\0';
    for (i = 0; i < sp->nchecks; ++i) {
        const check *c = &sp->checks[i];
        int ok;
        detail[0] = '\0';
        if (c->at_t >= 0.0)
            snprintf(detail, sizeof detail, "t=%.4g", c->at_t);
        switch (c->kind) {
        case K_STAY:
            snprintf(label, sizeof label, "stay[%d]", c->body);
            ok = c->m1 <= c->a;
            seg(out, cap, &first, label, c->m1, ok, "<=", ">", c->a, "");
            break;
        case K_STILL:
            ok = c->m1 < c->a;
            if (c->where1 >= 0)
                snprintf(detail, sizeof detail, "body %d", c->where1);
            seg(out, cap, &first, "speed", c->m1, ok, "<", ">=", c->a, detail);
            break;
        case K_ABOVE: {
            char d2[160];
            if (c->body >= 0)
                snprintf(label, sizeof label, "lowest[%d]", c->body);
            else
                snprintf(label, sizeof label, "lowest");
            ok = c->m1 > c->a;
            if (detail[0])
                snprintf(d2, sizeof d2, "trace, body %d, %s", c->where1, detail);
            else
                snprintf(d2, sizeof d2, "%s, body %d", c->trace ? "trace" : "end",
                         c->where1);
            seg(out, cap, &first, label, c->m1, ok, ">", "<=", c->a, d2);
            break;
        }
        case K_CONTAIN:
            ok = c->m1 == 0.0;
            snprintf(detail, sizeof detail, "smallest margin %.3g, body %d", c->m2,
                     c->where1);
            seg(out, cap, &first, "escaped", c->m1, ok, "==", ">", 0.0, detail);
            break;
        case K_OVERLAP:
            ok = c->m1 <= c->a;
            if (c->where1 >= 0)
                snprintf(detail, sizeof detail, "bodies %d,%d", c->where1, c->where2);
            seg(out, cap, &first, "overlap", c->m1, ok, "<=", ">", c->a, detail);
            break;
        case K_ORDER:
            snprintf(label, sizeof label, "y[%d]-y[%d]", c->body, c->body2);
            ok = c->m1 > 0.0;
            if (c->trace && c->at_t >= 0.0)
                snprintf(detail, sizeof detail, "trace, t=%.4g", c->at_t);
            else
                snprintf(detail, sizeof detail, "%s", c->trace ? "trace" : "end");
            seg(out, cap, &first, label, c->m1, ok, ">", "<=", 0.0, detail);
            break;
        case K_REST: {
            int ok1 = c->m1 <= c->c, ok2 = c->m2 <= c->c, ok3 = c->m3 <= c->b;
            snprintf(label, sizeof label, "rest[%d].gap", c->body);
            seg(out, cap, &first, label, c->m1, ok1, "<=", ">", c->c, "");
            snprintf(label, sizeof label, "rest[%d].tilt", c->body);
            seg(out, cap, &first, label, c->m2, ok2, "<=", ">", c->c, "");
            snprintf(label, sizeof label, "rest[%d].speed", c->body);
            seg(out, cap, &first, label, c->m3, ok3, "<=", ">", c->b, "");
            ok = ok1 && ok2 && ok3;
            break;
        }
        case K_IMPACTS:
            if (c->count_lo == c->count_hi) {
                ok = c->m1 == (double)c->count_lo;
                seg(out, cap, &first, "impacts", c->m1, ok, "==", "!=",
                    (double)c->count_lo, "");
            } else {
                ok = c->m1 >= (double)c->count_lo &&
                     (c->count_hi < 0 || c->m1 <= (double)c->count_hi);
                if (c->count_hi >= 0)
                    snprintf(detail, sizeof detail, "want %ld..%ld", c->count_lo,
                             c->count_hi);
                else
                    snprintf(detail, sizeof detail, "want >= %ld", c->count_lo);
                seg(out, cap, &first, "impacts", c->m1, ok, "in", "not in",
                    (double)c->count_lo, detail);
            }
            break;
        default:
            ok = 0;
            break;
        }
        if (!ok)
            all = 0;
    }
    return all;
}

/* ---- modes ------------------------------------------------------------------------- */

static int load_all(const char *path, scene *s, spec *sp, geo **g)
{
    char err[512];
    int rc;
    if (scene_load(path, s, err, sizeof err) != 0)
        return bad("%s", err);
    if (s->body_count == 0) {
        scene_free(s);
        return bad("%s: no bodies", path);
    }
    rc = read_spec(path, s->body_count, sp);
    if (rc) {
        scene_free(s);
        return rc;
    }
    *g = (geo *)calloc((size_t)s->body_count, sizeof **g);
    if (!*g) {
        scene_free(s);
        return bad("out of memory");
    }
    load_geometry(s, *g);
    return 0;
}

static int mode_info(const char *path)
{
    scene s;
    spec sp;
    geo *g;
    const char *input = "none";
    int i, rc = load_all(path, &s, &sp, &g);
    if (rc)
        return rc;
    if (sp.plot == P_DY || sp.plot == P_BOTTOM)
        input = "trace";
    else if (sp.plot == P_IMPACTS)
        input = "events";
    else if (sp.plot == P_SNAPSHOT)
        input = "final";
    printf("name %s\nfamily %s\nfast %d\nsteps %ld\ndt %.9g\nbodies %d\n"
           "trace %d\nevents %d\nplot %s\nplot-input %s\nengines %s\n",
           sp.name, sp.family, sp.fast, s.steps, (double)s.world.dt, s.body_count,
           sp.need_trace, sp.need_events, plot_names[sp.plot], input, sp.engines);
    for (i = 0; i < sp.nchecks; ++i)
        if (sp.checks[i].kind == K_IMPACTS &&
            sp.checks[i].count_lo == sp.checks[i].count_hi) {
            printf("plot-ref %ld\n", sp.checks[i].count_lo);
            break;
        }
    free(g);
    scene_free(&s);
    return 0;
}

static int mode_plot(const char *path, const char *file)
{
    scene s;
    spec sp;
    geo *g;
    int rc = load_all(path, &s, &sp, &g), nb;
    csv c;
    double v[9];
    if (rc)
        return rc;
    nb = s.body_count;
    rc = 0;
    if (sp.plot == P_NONE) {
        rc = bad("%s: no '# plot:' line", path);
    } else if (sp.plot == P_DY || sp.plot == P_BOTTOM) {
        int b = sp.plot_body, r;
        if (csv_open(&c, file, "step,t,body,x,y,angle,vx,vy,omega")) {
            rc = EXIT_BAD;
        } else {
            while ((r = csv_row(&c, v, 9)) == 1) {
                pose p;
                if (v[2] != (double)b)
                    continue;
                memset(&p, 0, sizeof p);
                set_pose(&p, v + 3);
                if (sp.plot == P_DY)
                    printf("%.9g %.9g\n", v[1], (p.y - g[b].y0) / sp.plot_scale);
                else
                    printf("%.9g %.9g\n", v[1], lowest_point(&g[b], &p) / sp.plot_scale);
            }
            fclose(c.f);
            if (r < 0)
                rc = EXIT_BAD;
        }
    } else if (sp.plot == P_IMPACTS) {
        int r;
        long n = 0;
        if (csv_open(&c, file, "t,body_a,body_b,nx,ny,impulse,approach_speed")) {
            rc = EXIT_BAD;
        } else {
            printf("0 0\n");
            while ((r = csv_row(&c, v, 7)) == 1)
                printf("%.9g %ld\n", v[0], ++n);
            printf("%.9g %ld\n", (double)s.steps * (double)s.world.dt, n);
            fclose(c.f);
            if (r < 0)
                rc = EXIT_BAD;
        }
    } else { /* snapshot */
        pose *p = (pose *)calloc((size_t)nb, sizeof *p);
        int b, k, any = 0;
        if (!p || read_final(file, p, nb)) {
            rc = p ? EXIT_BAD : bad("out of memory");
        } else {
            for (b = 0; b < nb; ++b)
                if (g[b].circle) {
                    printf("%.9g %.9g %.9g\n", p[b].x, p[b].y, g[b].r);
                    any = 1;
                }
            if (!any)
                printf("nan nan nan\n");
            printf("\n\n");
            for (b = 0; b < nb; ++b) {
                shape sh;
                if (g[b].circle)
                    continue;
                make_shape(&g[b], &p[b], &sh);
                for (k = 0; k <= sh.n; ++k)
                    printf("%.9g %.9g %d\n", sh.x[k % sh.n], sh.y[k % sh.n],
                           g[b].dynamic);
                printf("\n");
            }
        }
        free(p);
    }
    free(g);
    scene_free(&s);
    return rc;
}

static volatile sig_atomic_t timed_out;
static volatile pid_t timed_child;

static void on_alarm(int sig)
{
    (void)sig;
    timed_out = 1;
    if (timed_child > 0)
        kill(timed_child, SIGKILL);
}

static int mode_time(const char *out, double limit, char **argv)
{
    struct timespec t0, t1;
    pid_t pid;
    int status, code;
    FILE *f;
    fflush(NULL);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pid = fork();
    if (pid < 0)
        return bad("--time: fork: %s", strerror(errno));
    if (pid == 0) {
        execvp(argv[0], argv);
        fprintf(stderr, "stress_check: --time: cannot run '%s': %s\n", argv[0],
                strerror(errno));
        _exit(errno == ENOENT ? 127 : 126);
    }
    if (limit > 0.0) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_alarm;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGALRM, &sa, NULL);
        timed_child = pid;
        alarm((unsigned)ceil(limit));
    }
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR)
            return bad("--time: waitpid: %s", strerror(errno));
    }
    alarm(0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (timed_out)
        code = 124;
    else if (WIFEXITED(status))
        code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status))
        code = 128 + WTERMSIG(status);
    else
        code = 126;
    f = fopen(out, "w");
    if (!f)
        return bad("--time: cannot write '%s': %s", out, strerror(errno));
    fprintf(f, "%.6f\n", (double)(t1.tv_sec - t0.tv_sec) +
                             (double)(t1.tv_nsec - t0.tv_nsec) * 1e-9);
    if (fclose(f) != 0)
        return bad("--time: cannot write '%s'", out);
    return code;
}

static int mode_check(int argc, char **argv)
{
    scene s;
    spec sp;
    geo *g;
    pose *poses;
    long events = 0;
    char out[4096];
    int rc, pass, i;
    const char *trace = argc > 3 && argv[3][0] ? argv[3] : NULL;
    const char *evfile = argc > 4 && argv[4][0] ? argv[4] : NULL;
    rc = load_all(argv[1], &s, &sp, &g);
    if (rc)
        return rc;
    poses = (pose *)calloc((size_t)s.body_count, sizeof *poses);
    if (!poses)
        rc = bad("out of memory");
    if (!rc && sp.need_trace && !trace)
        rc = bad("%s: the criterion needs TRACE.csv", argv[1]);
    if (!rc && sp.need_events && !evfile)
        rc = bad("%s: the criterion needs EVENTS.csv", argv[1]);
    if (!rc)
        rc = read_final(argv[2], poses, s.body_count);
    if (!rc) {
        init_results(&sp);
        if (trace && sp.need_trace)
            rc = read_trace(trace, &sp, g, s.body_count);
    }
    if (!rc && evfile && sp.need_events) {
        events = count_events(evfile);
        if (events < 0)
            rc = EXIT_BAD;
    }
    if (!rc) {
        eval_final(&sp, g, poses, s.body_count, events);
        for (i = 0; i < sp.nchecks; ++i)
            if (sp.checks[i].kind == K_OVERLAP && sp.checks[i].m1 == HUGE_VAL)
                rc = bad("out of memory");
    }
    if (!rc) {
        pass = verdict(&sp, out, sizeof out);
        printf("%s %s: %s\n", pass ? "PASS" : "FAIL", sp.name, out);
        rc = pass ? EXIT_PASS : EXIT_FAIL;
    }
    free(poses);
    free(g);
    scene_free(&s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) {
        fputs(usage_text, stdout);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "--info")) {
        if (argc != 3)
            return bad("--info wants one SCENE\n%s", usage_text);
        return mode_info(argv[2]);
    }
    if (argc >= 2 && !strcmp(argv[1], "--plot")) {
        if (argc != 4)
            return bad("--plot wants SCENE FILE\n%s", usage_text);
        return mode_plot(argv[2], argv[3]);
    }
    if (argc >= 2 && !strcmp(argv[1], "--time")) {
        double limit = 0.0;
        int first = 3;
        if (argc >= 5 && !strcmp(argv[3], "--limit")) {
            char *end;
            limit = strtod(argv[4], &end);
            if (end == argv[4] || *end != '\0' || !(limit > 0.0) || limit > 1e6)
                return bad("--limit: want seconds in (0, 1e6], got '%s'", argv[4]);
            first = 5;
        }
        if (argc <= first)
            return bad("--time wants SECONDS_FILE [--limit SEC] COMMAND [ARG...]\n%s",
                       usage_text);
        return mode_time(argv[2], limit, argv + first);
    }
    if (argc < 3 || argc > 5 || argv[1][0] == '-')
        return bad("bad usage\n%s", usage_text);
    return mode_check(argc, argv);
}
