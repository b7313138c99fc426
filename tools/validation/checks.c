/*
 * checks.c -- the check table (tools/validation/checks.txt) and the
 * quantities it can name.
 *
 * A row is
 *
 *   SCENES  ENGINES  QUANTITY  TOLERANCE  REASON...
 *
 * SCENES is a comma-separated list of patterns over the scene names
 * (fnmatch: *, ?, [..]);
 * ENGINES a comma-separated list of engines (carom, events, discrete,
 * box2d, box2d-bullets) or pairs A:B for the quantities that compare two;
 * QUANTITY one of the names below; TOLERANCE a number >= 0; REASON the
 * rest of the line, why that tolerance (required). A check passes when the
 * measured value is at most the tolerance; a value that could not be
 * measured (a run failed) fails. '#' starts a comment.
 */
#include <ctype.h>
#include <errno.h>
#include <fnmatch.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "validate.h"

/* ---- the quantities ---------------------------------------------------------------------- */

enum form { SINGLE = 1, PAIR = 2 };

typedef struct quantity {
    const char *name;
    unsigned forms;     /* SINGLE, PAIR or both */
    int needs_run;      /* 0: also for the engine "carom" (no run) */
    const char *unit;
    const char *what;
    /* Does the scene fit the quantity's model? 0, or -1 with a reason. */
    int (*fits)(const vscene *s, char *why, size_t n);
    /* The value, or NaN with a reason. */
    double (*measure)(const vscene *s, int a, int b, char *why, size_t n);
} quantity;

static int fits_any(const vscene *s, char *why, size_t n)
{
    (void)s;
    (void)why;
    (void)n;
    return 0;
}

static int fits_headon(const vscene *s, char *why, size_t n)
{
    headon h;
    return headon_fit(s, &h, why, n);
}

static int fits_bullet(const vscene *s, char *why, size_t n)
{
    bullet b;
    return bullet_fit(s, &b, why, n);
}

static int fits_blade(const vscene *s, char *why, size_t n)
{
    blade b;
    return blade_fit(s, &b, why, n);
}

static int fits_drop(const vscene *s, char *why, size_t n)
{
    drop d;
    int rc = drop_fit(s, &d, why, n);
    drop_free(&d);
    return rc;
}

static int fits_poly(const vscene *s, char *why, size_t n)
{
    poly p;
    return poly_fit(s, &p, why, n);
}

static int fits_free(const vscene *s, char *why, size_t n)
{
    if (scene_is_free(s))
        return 0;
    snprintf(why, n, "has gravity or a static body: momentum is not conserved");
    return -1;
}

/* The run's trace and events, or NULL with a reason. */
static const run *need_run(const vscene *s, int eng, char *why, size_t n)
{
    const run *r = &s->runs[eng];
    if (r->ok)
        return r;
    if (r->status < 0)
        snprintf(why, n, "%s was not run", engine_names[eng]);
    else if (r->status != 0)
        snprintf(why, n, "%s exited with status %d%s%s", engine_names[eng], r->status,
                 r->message[0] ? ": " : "", r->message);
    else
        snprintf(why, n, "%s: %s", engine_names[eng], r->message);
    return NULL;
}

static double m_exit(const vscene *s, int a, int b, char *why, size_t n)
{
    const run *r = &s->runs[a];
    (void)b;
    if (r->status != 0) {
        snprintf(why, n, "%s", r->message);
        return r->status < 0 ? V_NAN : (double)r->status;
    }
    if (!r->ok) {
        snprintf(why, n, "%s", r->message);
        return V_NAN;
    }
    return 0.0;
}

/* The mass (what = 0) or inertia (1) table of an engine: carom's from the
 * library, Box2D's from its --masses file. */
static const double *mass_table(const vscene *s, int eng, int what, char *why, size_t n)
{
    if (eng == ENG_CAROM)
        return what ? s->carom_inertia : s->carom_mass;
    if (eng == ENG_BOX2D || eng == ENG_BOX2D_BULLETS) {
        if (!s->b2_mass) {
            snprintf(why, n, "no Box2D mass table (the box2d run failed)");
            return NULL;
        }
        return what ? s->b2_inertia : s->b2_mass;
    }
    snprintf(why, n, "masses are compared for carom and box2d");
    return NULL;
}

static double mass_diff(const vscene *s, int a, int b, int what, char *why, size_t n)
{
    const double *x = mass_table(s, a, what, why, n), *y = NULL;
    double worst = 0.0;
    int i;
    if (!x || (b >= 0 && !(y = mass_table(s, b, what, why, n))))
        return V_NAN;
    for (i = 0; i < s->sc.body_count; ++i) {
        double ref = y ? y[i] : (what ? s->exact[i].inertia : s->exact[i].mass);
        double rel;
        if (s->sc.bodies[i].def.type != CAROM_BODY_DYNAMIC)
            continue;
        /* against the second engine's value, or the exact one */
        if (y)
            rel = fabs(ref - x[i]) / x[i];
        else
            rel = fabs(x[i] - ref) / ref;
        if (!(rel <= worst))
            worst = rel;
    }
    return worst;
}

static double m_mass(const vscene *s, int a, int b, char *why, size_t n)
{
    return mass_diff(s, a, b, 0, why, n);
}

static double m_inertia(const vscene *s, int a, int b, char *why, size_t n)
{
    return mass_diff(s, a, b, 1, why, n);
}

static double headon_value(const vscene *s, int a, int dv, char *why, size_t n)
{
    headon h;
    headon_err e;
    const run *r = need_run(s, a, why, n);
    if (!r || headon_fit(s, &h, why, n) != 0)
        return V_NAN;
    headon_measure(&h, &r->tr, &e);
    return dv ? e.dv : e.dx;
}

static double m_headon_dx(const vscene *s, int a, int b, char *why, size_t n)
{
    (void)b;
    return headon_value(s, a, 0, why, n);
}

/* |position error - the late-impulse error docs/events.md predicts for
 * the engine| (discrete: bounce at the end of the step, k = 0; Box2D:
 * impulse at the start of the next, k = 1). */
static double m_headon_late(const vscene *s, int a, int b, char *why, size_t n)
{
    headon h;
    headon_err e;
    const run *r = need_run(s, a, why, n);
    double k = a == ENG_DISCRETE ? 0.0 : 1.0;
    (void)b;
    if (!r || headon_fit(s, &h, why, n) != 0)
        return V_NAN;
    if (a != ENG_DISCRETE && a != ENG_BOX2D) {
        snprintf(why, n, "headon.late predicts discrete and box2d only");
        return V_NAN;
    }
    headon_measure(&h, &r->tr, &e);
    return fabs(e.dx - late_impulse_error(h.e, h.ua - h.ub, h.ts, s->dt,
                                          (h.ma > h.mb ? h.ma : h.mb) / (h.ma + h.mb), k));
}

static double m_headon_dv(const vscene *s, int a, int b, char *why, size_t n)
{
    (void)b;
    return headon_value(s, a, 1, why, n);
}

static double dev_value(const vscene *s, int a, int b, int dv, char *why, size_t n)
{
    deviation d;
    const run *ra = need_run(s, a, why, n), *rb = ra ? need_run(s, b, why, n) : NULL;
    if (!ra || !rb)
        return V_NAN;
    if (deviation_measure(&ra->tr, &rb->tr, deviation_skip(s), &d) != 0) {
        snprintf(why, n, "the traces of %s and %s are out of step", engine_names[a],
                 engine_names[b]);
        return V_NAN;
    }
    return dv ? d.dv : d.dx;
}

static double m_dev_dx(const vscene *s, int a, int b, char *why, size_t n)
{
    return dev_value(s, a, b, 0, why, n);
}

static double m_dev_dv(const vscene *s, int a, int b, char *why, size_t n)
{
    return dev_value(s, a, b, 1, why, n);
}

enum drop_what {
    D_IMPACT_TIME, D_IMPACT_SPEED, D_IMPACT_COUNT, D_HEIGHT, D_BELOW, D_REST_HEIGHT,
    D_REST_SPEED
};

static double drop_value(const vscene *s, int a, enum drop_what what, char *why, size_t n)
{
    drop d;
    drop_err *err;
    drop_impacts im;
    double v = 0.0;
    int i;
    const run *r = need_run(s, a, why, n);
    if (!r || drop_fit(s, &d, why, n) != 0)
        return V_NAN;
    if (what <= D_IMPACT_COUNT) {
        drop_match_impacts(&d, &r->ev, &im);
        v = what == D_IMPACT_TIME    ? im.dt_rel
            : what == D_IMPACT_SPEED ? im.du_rel
                                     : fabs((double)(im.matched - im.wanted));
        drop_free(&d);
        return v;
    }
    err = (drop_err *)calloc((size_t)d.count + 1, sizeof *err);
    if (!err) {
        snprintf(why, n, "out of memory");
        drop_free(&d);
        return V_NAN;
    }
    drop_measure(&d, &r->tr, err);
    for (i = 0; i < d.count; ++i) {
        double x = what == D_HEIGHT        ? err[i].merr
                   : what == D_BELOW       ? err[i].below
                   : what == D_REST_HEIGHT ? err[i].rest_h
                                           : err[i].rest_v;
        v = x > v ? x : v;
    }
    free(err);
    drop_free(&d);
    return v;
}

#define DROP_MEASURE(fn, what)                                              \
    static double fn(const vscene *s, int a, int b, char *why, size_t n)   \
    {                                                                       \
        (void)b;                                                            \
        return drop_value(s, a, what, why, n);                              \
    }
DROP_MEASURE(m_drop_time, D_IMPACT_TIME)
DROP_MEASURE(m_drop_speed, D_IMPACT_SPEED)
DROP_MEASURE(m_drop_count, D_IMPACT_COUNT)
DROP_MEASURE(m_drop_height, D_HEIGHT)
DROP_MEASURE(m_drop_below, D_BELOW)
DROP_MEASURE(m_drop_rest_height, D_REST_HEIGHT)
DROP_MEASURE(m_drop_rest_speed, D_REST_SPEED)

static double poly_value(const vscene *s, int a, int what, char *why, size_t n)
{
    poly p;
    poly_err e;
    long step;
    const run *r = need_run(s, a, why, n);
    if (!r || poly_fit(s, &p, why, n) != 0)
        return V_NAN;
    step = poly_compare_step(s);
    if (step < 0) {
        snprintf(why, n, "no step lies after every engine's first impact and before any "
                         "second one (or a run failed)");
        return V_NAN;
    }
    poly_measure(&p, &r->tr, step, &e);
    return what == 0 ? e.dv : what == 1 ? e.dw : what == 2 ? e.dx : e.da;
}

#define POLY_MEASURE(fn, what)                                              \
    static double fn(const vscene *s, int a, int b, char *why, size_t n)   \
    {                                                                       \
        (void)b;                                                            \
        return poly_value(s, a, what, why, n);                              \
    }
POLY_MEASURE(m_poly_dv, 0)
POLY_MEASURE(m_poly_dw, 1)
POLY_MEASURE(m_poly_dx, 2)
POLY_MEASURE(m_poly_da, 3)

static double m_bullet_dx(const vscene *s, int a, int b, char *why, size_t n)
{
    bullet bu;
    bullet_err e;
    const run *r = need_run(s, a, why, n);
    (void)b;
    if (!r || bullet_fit(s, &bu, why, n) != 0)
        return V_NAN;
    bullet_measure(s, &bu, &r->tr, &e);
    return e.dx;
}

static double blade_value(const vscene *s, int a, int what, char *why, size_t n)
{
    blade bl;
    blade_err e;
    const run *r = need_run(s, a, why, n);
    if (!r || blade_fit(s, &bl, why, n) != 0)
        return V_NAN;
    blade_measure(&bl, &r->tr, &e);
    return what == 0 ? e.dx : e.dv;
}

static double m_blade_dx(const vscene *s, int a, int b, char *why, size_t n)
{
    (void)b;
    return blade_value(s, a, 0, why, n);
}

static double m_blade_dv(const vscene *s, int a, int b, char *why, size_t n)
{
    (void)b;
    return blade_value(s, a, 1, why, n);
}

static double m_still_move(const vscene *s, int a, int b, char *why, size_t n)
{
    still_err e;
    const run *r = need_run(s, a, why, n);
    (void)b;
    if (!r)
        return V_NAN;
    still_measure(&r->tr, &e);
    return e.move;
}

static double m_energy_rel(const vscene *s, int a, int b, char *why, size_t n)
{
    conserved c;
    const run *r = need_run(s, a, why, n);
    (void)b;
    if (!r)
        return V_NAN;
    conservation_measure(s, &r->tr, &c);
    if (!(c.ke0 > 0.0)) {
        snprintf(why, n, "no kinetic energy at t = 0");
        return V_NAN;
    }
    return c.de_max / c.ke0;
}

static double m_momentum_rel(const vscene *s, int a, int b, char *why, size_t n)
{
    conserved c;
    const run *r = need_run(s, a, why, n);
    (void)b;
    if (!r)
        return V_NAN;
    conservation_measure(s, &r->tr, &c);
    if (!(c.p_scale > 0.0)) {
        snprintf(why, n, "nothing moves at t = 0");
        return V_NAN;
    }
    return c.dp_max / c.p_scale;
}

static const quantity quantities[] = {
    {"exit", SINGLE, 1, "", "exit status of the run (its trace and events read back whole)",
     fits_any, m_exit},
    {"mass", SINGLE | PAIR, 0, "relative",
     "largest relative difference of a body's mass from the exact one (A:B: between the two "
     "engines)", fits_any, m_mass},
    {"inertia", SINGLE | PAIR, 0, "relative",
     "the same for the rotational inertia about the centre of mass", fits_any, m_inertia},
    {"headon.dx", SINGLE, 1, "m",
     "head-on pair: largest |x - exact| + |y| over all samples, both bodies", fits_headon,
     m_headon_dx},
    {"headon.dv", SINGLE, 1, "m/s",
     "head-on pair: largest velocity error over all samples but the one at the impact "
     "instant", fits_headon, m_headon_dv},
    {"headon.late", SINGLE, 1, "m",
     "head-on pair: |largest position error - the late-impulse error predicted for the "
     "engine (docs/events.md: discrete e v (dt - t*) m_B/M, Box2D (1 + e) v (dt - t*) m_B/M)|",
     fits_headon, m_headon_late},
    {"dev.dx", PAIR, 1, "m", "largest distance between the engines' positions of a body",
     fits_any, m_dev_dx},
    {"dev.dv", PAIR, 1, "m/s",
     "largest difference of their velocities (for a head-on pair without the sample at the "
     "impact instant)", fits_any, m_dev_dv},
    {"drop.impact-time", SINGLE, 1, "relative",
     "drop: largest relative error of an impact's instant (--events) against the bounce "
     "sequence", fits_drop, m_drop_time},
    {"drop.impact-speed", SINGLE, 1, "relative",
     "drop: the same for the approach speed", fits_drop, m_drop_speed},
    {"drop.impact-count", SINGLE, 1, "impacts",
     "drop: |impacts faster than the rest speed reported - exact ones|", fits_drop,
     m_drop_count},
    {"drop.height", SINGLE, 1, "m", "drop: largest |height - exact| of a ball's lowest point",
     fits_drop, m_drop_height},
    {"drop.below", SINGLE, 1, "m", "drop: deepest a ball goes below the floor's top", fits_drop,
     m_drop_below},
    {"drop.rest-height", SINGLE, 1, "m",
     "drop: largest |height| once the exact ball rests (from the instant it lands for good)",
     fits_drop, m_drop_rest_height},
    {"drop.rest-speed", SINGLE, 1, "m/s", "drop: largest speed once the exact ball rests",
     fits_drop, m_drop_rest_speed},
    {"poly.dv", SINGLE, 1, "m/s",
     "off-centre polygon impact: largest velocity error after the first impact", fits_poly,
     m_poly_dv},
    {"poly.dw", SINGLE, 1, "rad/s", "the same for the angular velocity", fits_poly, m_poly_dw},
    {"poly.dx", SINGLE, 1, "m", "the same for the position", fits_poly, m_poly_dx},
    {"poly.da", SINGLE, 1, "rad", "the same for the angle", fits_poly, m_poly_da},
    {"bullet.dx", SINGLE, 1, "m", "bullet: largest |x - exact| over all samples, both bodies",
     fits_bullet, m_bullet_dx},
    {"blade.dx", SINGLE, 1, "m",
     "blade: largest |ball position - exact| over all samples (at rest, then Newton's "
     "velocity from the strike)", fits_blade, m_blade_dx},
    {"blade.dv", SINGLE, 1, "m/s", "blade: |ball velocity - exact| at the end", fits_blade,
     m_blade_dv},
    {"still.move", SINGLE, 1, "m", "largest distance of a body from where it started",
     fits_any, m_still_move},
    {"energy.rel", SINGLE, 1, "relative",
     "largest change of the energy (kinetic + potential) over the run / the kinetic energy "
     "at t = 0", fits_any, m_energy_rel},
    {"momentum.rel", SINGLE, 1, "relative",
     "largest change of the linear momentum / the sum of m |v| at t = 0 (no external force)",
     fits_free, m_momentum_rel},
};

#define QUANTITY_COUNT ((int)(sizeof quantities / sizeof quantities[0]))

int quantity_count(void) { return QUANTITY_COUNT; }
const char *quantity_name(int q) { return quantities[q].name; }
const char *quantity_unit(int q) { return quantities[q].unit; }
const char *quantity_what(int q) { return quantities[q].what; }

void checks_print_quantities(FILE *f)
{
    int q;
    for (q = 0; q < QUANTITY_COUNT; ++q)
        fprintf(f, "  %-18s %s%s%s%s\n", quantities[q].name, quantities[q].what,
                quantities[q].unit[0] ? " (" : "", quantities[q].unit,
                quantities[q].unit[0] ? ")" : "");
}

void format_value(char *buf, size_t n, double v)
{
    if (isnan(v))
        snprintf(buf, n, "failed");
    else if (v == 0.0)
        snprintf(buf, n, "0");
    else if (v == floor(v) && fabs(v) < 1e6)
        snprintf(buf, n, "%.0f", v);
    else
        snprintf(buf, n, "%.2e", v);
}

/* Does `name` match one of the comma-separated patterns? */
static int matches(const char *patterns, const char *name)
{
    char buf[V_NAME_MAX], *item, *save = NULL;
    snprintf(buf, sizeof buf, "%s", patterns);
    for (item = strtok_r(buf, ",", &save); item; item = strtok_r(NULL, ",", &save))
        if (fnmatch(item, name, 0) == 0)
            return 1;
    return 0;
}

/* ---- reading the table ------------------------------------------------------------------- */

static int table_error(const char *path, int line, const char *fmt, const char *arg)
{
    fprintf(stderr, "validate: %s:%d: ", path, line);
    fprintf(stderr, fmt, arg);
    fputc('\n', stderr);
    return -1;
}

/* The next whitespace-separated word of *p (NUL-terminated in place). */
static char *next_word(char **p)
{
    char *s = *p, *w;
    while (*s && isspace((unsigned char)*s))
        ++s;
    if (!*s)
        return NULL;
    w = s;
    while (*s && !isspace((unsigned char)*s))
        ++s;
    if (*s)
        *s++ = '\0';
    *p = s;
    return w;
}

static int parse_engines(const char *path, int line, char *list, check_row *r)
{
    char *item, *save = NULL;
    snprintf(r->engine_text, sizeof r->engine_text, "%s", list);
    for (item = strtok_r(list, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
        char *colon = strchr(item, ':');
        int a, b = -1;
        if (r->engine_count == (int)(sizeof r->engines / sizeof r->engines[0]))
            return table_error(path, line, "too many engines in '%s'", r->engine_text);
        if (colon)
            *colon = '\0';
        a = engine_from_name(item);
        if (colon)
            b = engine_from_name(colon + 1);
        if (a < 0 || (colon && b < 0))
            return table_error(path, line,
                               "unknown engine in '%s' (carom, events, discrete, box2d, "
                               "box2d-bullets; A:B for a pair)", r->engine_text);
        r->engines[r->engine_count][0] = a;
        r->engines[r->engine_count][1] = b;
        ++r->engine_count;
    }
    if (r->engine_count == 0)
        return table_error(path, line, "no engine in '%s'", r->engine_text);
    return 0;
}

static int parse_row(const char *path, int line, char *text, check_row *r)
{
    char *p = text, *pattern, *engines, *qname, *tol, *end;
    const quantity *q;
    int i;
    memset(r, 0, sizeof *r);
    r->line = line;
    pattern = next_word(&p);
    engines = next_word(&p);
    qname = next_word(&p);
    tol = next_word(&p);
    if (!tol)
        return table_error(path, line, "%s", "want: SCENES ENGINES QUANTITY TOLERANCE REASON");
    while (*p && isspace((unsigned char)*p))
        ++p;
    if (!*p)
        return table_error(path, line, "a tolerance needs its reason (after '%s')", tol);
    snprintf(r->pattern, sizeof r->pattern, "%s", pattern);
    snprintf(r->reason, sizeof r->reason, "%s", p);
    for (i = 0; i < QUANTITY_COUNT && strcmp(quantities[i].name, qname) != 0; ++i) {}
    if (i == QUANTITY_COUNT)
        return table_error(path, line, "unknown quantity '%s' (validate --help lists them)",
                           qname);
    r->quantity = i;
    q = &quantities[i];
    errno = 0;
    r->tol = strtod(tol, &end);
    if (*end || errno || !isfinite(r->tol) || r->tol < 0.0)
        return table_error(path, line, "tolerance '%s': want a number >= 0", tol);
    if (parse_engines(path, line, engines, r) != 0)
        return -1;
    for (i = 0; i < r->engine_count; ++i) {
        int pair = r->engines[i][1] >= 0;
        if (!(q->forms & (pair ? PAIR : SINGLE)))
            return table_error(path, line,
                               pair ? "quantity '%s' takes one engine, not a pair A:B"
                                    : "quantity '%s' compares two engines: write A:B",
                               q->name);
        if (q->needs_run && (r->engines[i][0] == ENG_CAROM || r->engines[i][1] == ENG_CAROM))
            return table_error(path, line,
                               "quantity '%s' needs a run: carom is events or discrete",
                               q->name);
        if ((q->measure == m_mass || q->measure == m_inertia) &&
            (r->engines[i][0] == ENG_EVENTS || r->engines[i][0] == ENG_DISCRETE ||
             r->engines[i][1] == ENG_EVENTS || r->engines[i][1] == ENG_DISCRETE))
            return table_error(path, line,
                               "quantity '%s' is carom's (both methods share the masses) or "
                               "box2d's", q->name);
    }
    return 0;
}

int checks_load(const char *path, check_table *t)
{
    FILE *f = fopen(path, "r");
    char text[4096];
    int line = 0, cap = 0;
    memset(t, 0, sizeof *t);
    if (!f) {
        fprintf(stderr, "validate: cannot open the check table %s: %s\n", path, strerror(errno));
        return -1;
    }
    while (fgets(text, sizeof text, f)) {
        char *hash = strchr(text, '#'), *p = text;
        ++line;
        if (!strchr(text, '\n') && !feof(f)) {
            fclose(f);
            return table_error(path, line, "%s", "line too long");
        }
        if (hash)
            *hash = '\0';
        text[strcspn(text, "\r\n")] = '\0';
        while (*p && isspace((unsigned char)*p))
            ++p;
        if (!*p)
            continue;
        if (t->count == cap) {
            check_row *bigger;
            cap = cap ? 2 * cap : 64;
            bigger = (check_row *)realloc(t->rows, (size_t)cap * sizeof *bigger);
            if (!bigger) {
                fclose(f);
                return table_error(path, line, "%s", "out of memory");
            }
            t->rows = bigger;
        }
        if (parse_row(path, line, p, &t->rows[t->count]) != 0) {
            fclose(f);
            return -1;
        }
        ++t->count;
    }
    fclose(f);
    if (t->count == 0) {
        fprintf(stderr, "validate: %s: no checks\n", path);
        return -1;
    }
    return 0;
}

int checks_expand(check_table *t, suite *su, const char *path)
{
    int r, i, k, n = 0, cap = 256;
    t->results = (check_result *)malloc((size_t)cap * sizeof *t->results);
    if (!t->results)
        return table_error(path, 0, "%s", "out of memory");
    for (r = 0; r < t->count; ++r) {
        const check_row *row = &t->rows[r];
        const quantity *q = &quantities[row->quantity];
        int matched = 0;
        for (i = 0; i < su->count; ++i) {
            vscene *s = &su->scenes[i];
            char why[V_NOTE_MAX];
            if (!matches(row->pattern, s->name))
                continue;
            ++matched;
            if (q->fits(s, why, sizeof why) != 0) {
                fprintf(stderr, "validate: %s:%d: %s does not apply to scene %s: it %s\n", path,
                        row->line, q->name, s->name, why);
                return -1;
            }
            for (k = 0; k < row->engine_count; ++k) {
                check_result *c;
                int a = row->engines[k][0], b = row->engines[k][1];
                if (n == cap) {
                    check_result *bigger;
                    cap *= 2;
                    bigger = (check_result *)realloc(t->results, (size_t)cap * sizeof *bigger);
                    if (!bigger)
                        return table_error(path, row->line, "%s", "out of memory");
                    t->results = bigger;
                }
                c = &t->results[n++];
                memset(c, 0, sizeof *c);
                c->row = r;
                c->scene = i;
                c->a = a;
                c->b = b;
                c->value = V_NAN;
                if (a != ENG_CAROM)
                    s->runs[a].wanted = 1;
                if (b > ENG_CAROM)
                    s->runs[b].wanted = 1;
                /* Box2D's mass table comes with its plain run */
                if ((q->measure == m_mass || q->measure == m_inertia) &&
                    (a >= ENG_BOX2D || b >= ENG_BOX2D))
                    s->runs[ENG_BOX2D].wanted = 1;
            }
        }
        if (!matched)
            return table_error(path, row->line, "'%s' matches no scene", row->pattern);
    }
    t->result_count = n;
    return 0;
}

void checks_evaluate(check_table *t, const suite *su)
{
    int i;
    t->failed = 0;
    for (i = 0; i < t->result_count; ++i) {
        check_result *c = &t->results[i];
        const check_row *row = &t->rows[c->row];
        c->why[0] = '\0';
        c->value = quantities[row->quantity].measure(&su->scenes[c->scene], c->a, c->b, c->why,
                                                     sizeof c->why);
        c->pass = !isnan(c->value) && c->value <= row->tol;
        t->failed += !c->pass;
    }
}

void checks_free(check_table *t)
{
    free(t->rows);
    free(t->results);
    memset(t, 0, sizeof *t);
}
