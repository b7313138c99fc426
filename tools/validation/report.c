/*
 * report.c -- docs/validation.md and its figure (gnuplot), from one run of
 * the suite. Every number in the report is measured or computed in that
 * run; the prose around the tables explains the mechanisms, and where a
 * statement depends on a result it is written from the result.
 *
 * The sections name the scenes they describe (drop, gas, stack, ...): a
 * section whose scene is missing, or whose runs failed, says so.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "validate.h"

/* ---- formatting -------------------------------------------------------------------------- */

#define RING 64

/* A number in printf format `f`, or "n/a" for NaN; from a ring of buffers,
 * so that a dozen can be used in one printf. */
static const char *num(const char *f, double v)
{
    static char ring[RING][48];
    static int next;
    char *b = ring[next++ % RING];
    if (isnan(v))
        snprintf(b, sizeof ring[0], "n/a");
    else
        snprintf(b, sizeof ring[0], f, v);
    return b;
}

#define E1(v) num("%.1e", (v))
#define E2(v) num("%.2e", (v))
#define G3(v) num("%.3g", (v))
#define G6(v) num("%.6g", (v))
#define F4(v) num("%.4f", (v))
#define F6(v) num("%.6f", (v))

static double maxd(double a, double b)
{
    if (isnan(a))
        return b;
    if (isnan(b))
        return a;
    return a > b ? a : b;
}

static const run *ok_run(const vscene *s, int eng)
{
    return s && s->runs[eng].ok ? &s->runs[eng] : NULL;
}

/* The tolerance of the first table row naming this scene, engine and
 * quantity, or NaN. */
static double tolerance_of(const check_table *t, const suite *su, const char *scene,
                           int eng, const char *quantity)
{
    int i;
    for (i = 0; i < t->result_count; ++i) {
        const check_result *c = &t->results[i];
        const check_row *row = &t->rows[c->row];
        if (c->a == eng && c->b < 0 && !strcmp(su->scenes[c->scene].name, scene) &&
            !strcmp(quantity_name(row->quantity), quantity))
            return row->tol;
    }
    return V_NAN;
}

/* Did every check on this scene pass? */
static int scene_passed(const check_table *t, int scene)
{
    int i;
    for (i = 0; i < t->result_count; ++i)
        if (t->results[i].scene == scene && !t->results[i].pass)
            return 0;
    return 1;
}

/* Which of two errors is nearer the exact answer (0). */
static const char *nearer(double carom, double box2d)
{
    if (isnan(carom) || isnan(box2d))
        return "n/a (a run failed)";
    carom = fabs(carom);
    box2d = fabs(box2d);
    return carom < box2d ? "carom" : box2d < carom ? "Box2D" : "equal";
}

/* ---- what the summary gathers from the sections ------------------------------------------ */

/* The key numbers, by name; NaN until a section measures them. */
#define SUMMARY_FIELDS(X)                                                          \
    X(agree_dx) X(agree_c) X(agree_b) X(mid_events) X(mid_discrete) X(mid_box2d)   \
    X(fall_events) X(fall_box2d) X(fall_pred) X(u1_events) X(u1_box2d)             \
    X(settle_events) X(settle_box2d) X(drop_events) X(drop_box2d)                  \
    X(stack_events) X(stack_rise_events) X(stack_rise_box2d)                       \
    X(pyramid_events) X(pyramid_discrete) X(pyramid_box2d) X(pyramid_end_events)   \
    X(pyramid_time) X(pyramid_x) X(pyramid_y) X(poly_events) X(poly_box2d)         \
    X(bullet_events) X(bullet_box2d) X(bullet_step1)                               \
    X(bdyn_events) X(bdyn_box2d) X(bdyn_bullets) X(bdyn_exact)                     \
    X(blade_events) X(blade_discrete) X(blade_box2d)                               \
    X(gas_events) X(gas_discrete) X(gas_box2d)

#define SUMMARY_DECLARE(name) double name;
#define SUMMARY_UNSET(name) m->name = V_NAN;

typedef struct summary {
    SUMMARY_FIELDS(SUMMARY_DECLARE)
    int slow;
    char slow_text[512];
} summary;

static void summary_init(summary *m)
{
    SUMMARY_FIELDS(SUMMARY_UNSET)
    m->slow = 0;
    m->slow_text[0] = '\0';
}

/* ---- the header -------------------------------------------------------------------------- */

static void cpu_model(char *buf, size_t n)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    snprintf(buf, n, "unknown CPU");
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (!strncmp(line, "model name", 10) && colon) {
            colon += 1 + strspn(colon + 1, " \t");
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(buf, n, "%s", colon);
            break;
        }
    }
    fclose(f);
}

static void write_header(FILE *f, const suite *su, const check_table *t, const report_info *ri)
{
    struct utsname u;
    char cpu[256], carom_version[128], box2d_version[64];
    char *carom_argv[] = {(char *)ri->carom, (char *)"--version", NULL};
    char *pkg_argv[] = {(char *)"pkg-config", (char *)"--modversion", (char *)"box2d", NULL};
    double worst_m = V_NAN, worst_i = V_NAN, exact_cm = V_NAN, exact_bm = V_NAN, exact_ci = V_NAN,
           exact_bi = V_NAN;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    int i;

    cpu_model(cpu, sizeof cpu);
    if (uname(&u) != 0)
        memset(&u, 0, sizeof u);
    if (capture_line(carom_argv, ri->workdir, carom_version, sizeof carom_version) != 0)
        snprintf(carom_version, sizeof carom_version, "carom (version unknown)");
    if (capture_line(pkg_argv, ri->workdir, box2d_version, sizeof box2d_version) != 0)
        snprintf(box2d_version, sizeof box2d_version, "(version unknown)");
    /* the mass checks, over every scene */
    for (i = 0; i < t->result_count; ++i) {
        const check_result *c = &t->results[i];
        const char *q = quantity_name(t->rows[c->row].quantity);
        int mass = !strcmp(q, "mass"), inertia = !strcmp(q, "inertia");
        if (!mass && !inertia)
            continue;
        if (c->b >= 0) {
            if (mass)
                worst_m = maxd(worst_m, c->value);
            else
                worst_i = maxd(worst_i, c->value);
        } else if (c->a == ENG_CAROM) {
            if (mass)
                exact_cm = maxd(exact_cm, c->value);
            else
                exact_ci = maxd(exact_ci, c->value);
        } else {
            if (mass)
                exact_bm = maxd(exact_bm, c->value);
            else
                exact_bi = maxd(exact_bi, c->value);
        }
    }

    fprintf(f, "# Validation against Box2D\n\n"
               "<!-- Generated by build/validate (tools/validation/): do not edit.\n"
               "     Regenerate with `make validate`. -->\n\n");
    fprintf(f, "*This file is regenerated by `make validate` (tools/validation/validate.c,\n"
               "driven by the check table `%s`); every number below is\n"
               "computed from the engines' traces in that run, and every exact answer\n"
               "from the scene alone, in double precision.*\n\n",
            ri->checks_path);
    fprintf(f, "**This run:** %s, %s %s %s, %ld CPUs; %s, built with %s;\n"
               "Box2D %s (Debian's libbox2d-dev) through `carom-box2d`.\n\n",
            cpu, u.sysname, u.release, u.machine, cpus, carom_version, ri->build,
            box2d_version);
    fprintf(f, "**Checks:** %d over %d scenes, from %d rows of the check table: %s.\n\n",
            t->result_count, su->count, t->count,
            t->failed ? "SOME FAILED (listed at the end)" : "every one within its tolerance");
    fprintf(f,
            "carom (`build/carom`, methods `events` and `discrete`) and Box2D %s\n"
            "(`build/carom-box2d`, the same scene files through Box2D) run every scene\n"
            "of `%s/`, each writing the state of every body after every\n"
            "step (`--trace`) and its impacts (`--events`). Both engines read the scene\n"
            "with carom's parser and get the same gravity, time step, shapes, masses,\n"
            "restitution and friction (mixed the same way: max and sqrt), poses,\n"
            "velocities and restitution threshold (carom's rest speed for the scene);\n"
            "Box2D runs its recommended 8 velocity and 3 position iterations (carom's\n"
            "substeps and sweeps belong to its own solver). Sleeping is off in both:\n"
            "every validation scene says `sleep=off`, and the harness turns Box2D's\n"
            "off. What Box2D cannot take is not hidden: `carom-box2d` says so on\n"
            "stderr (one method, its compiled-in contact slop `b2_linearSlop` =\n"
            "0.005 m, the polygon skin `b2_polygonRadius` = 0.01 m).\n\n",
            box2d_version, ri->scene_dir);
    fprintf(f,
            "Masses agree: against the exact mass (density x area, or the given mass,\n"
            "in double) the largest relative error of a body's mass is %s in carom\n"
            "and %s in Box2D, of a rotational inertia %s and %s; between the two\n"
            "engines %s and %s.\n\n",
            G3(exact_cm), G3(exact_bm), G3(exact_ci), G3(exact_bi), G3(worst_m), G3(worst_i));
    fprintf(f, "Deviation between engines is the largest distance between the two\n"
               "positions of a body (velocity: the norm of the difference) over all\n"
               "bodies and all samples (every step). Times: `t` in the traces.\n");
}

/* ---- head-on pairs ----------------------------------------------------------------------- */

/* "m_B/m_A | e" of a head-on pair. */
static void headon_labels(const headon *h, char *buf, size_t n)
{
    snprintf(buf, n, "%s | %g", num("%g", h->mb / h->ma), h->e);
}

static void write_headon(FILE *f, const suite *su, const check_table *t, summary *m)
{
    double tol_x = tolerance_of(t, su, "headon-step-m1-e0", ENG_EVENTS, "headon.dx");
    double tol_v = tolerance_of(t, su, "headon-step-m1-e0", ENG_EVENTS, "headon.dv");
    int i;
    fprintf(f, "\n## Head-on pairs\n\n"
               "Two circles of radius 0.5 meet head-on at 2 m/s (1 m/s each), no gravity,\n"
               "no friction, dt = 1/64 s. Masses 1 : 1, 1 : 10, 1 : 100, restitution\n"
               "e = 0, 0.5, 1. The exact answer is the corrected Newton formula of\n"
               "docs/physics.md (momentum form), applied at the instant the surfaces\n"
               "touch; before and after, each body moves at constant velocity.\n\n");
    fprintf(f,
            "### Agreement cases: impact on a step boundary\n\n"
            "`headon-step-*`: every initial position is a multiple of dt = 1/64, so\n"
            "both engines move the circles without rounding until they touch exactly at\n"
            "t* = 8 dt = 0.125 s. carom's `events` method finds the impact at the end\n"
            "of step 8; Box2D finds the circles touching (not overlapping) at the start\n"
            "of step 9 and applies the Newton impulse with one contact point (its\n"
            "sequential impulses are exact for one point: the first iteration reaches\n"
            "the target velocity and later ones add nothing). Position correction does\n"
            "nothing at zero overlap. Both engines therefore apply the same impulse to\n"
            "the same state, and must agree to float rounding.\n\n"
            "Tolerance: positions %s m, velocities %s m/s, between the engines\n"
            "at every sample and for each engine against the exact answer (speeds and\n"
            "positions are of order 1, where a float's rounding unit is about 1e-7; a\n"
            "real difference here would be at least the distance of a step, 0.03 m, or\n"
            "Box2D's slop, 0.005 m). The sample at t* itself is left out of the\n"
            "velocity comparison: at an impact on a step boundary the velocity jumps\n"
            "there, carom reports the velocity after the impact and Box2D the one\n"
            "before it (it applies the impulse at the start of the next step).\n\n"
            "| scene | m_B/m_A | e | exact v_A', v_B' (m/s) | carom - Box2D: max dx, dv | "
            "carom - exact: dx, dv | Box2D - exact: dx, dv | within tolerance |\n"
            "|---|---|---|---|---|---|---|---|\n",
            G3(tol_x), G3(tol_v));
    for (i = 0; i < su->count; ++i) {
        const vscene *s = &su->scenes[i];
        const run *ev = ok_run(s, ENG_EVENTS), *b2 = ok_run(s, ENG_BOX2D);
        headon h;
        headon_err ce, be;
        deviation d;
        char why[V_NOTE_MAX], lab[64];
        if (strncmp(s->name, "headon-step-", 12) != 0 || headon_fit(s, &h, why, sizeof why) != 0)
            continue;
        headon_labels(&h, lab, sizeof lab);
        if (!ev || !b2) {
            fprintf(f, "| %s | %s | %s, %s | a run failed | | | NO |\n", s->name, lab,
                    F6(h.va), F6(h.vb));
            continue;
        }
        headon_measure(&h, &ev->tr, &ce);
        headon_measure(&h, &b2->tr, &be);
        if (deviation_measure(&ev->tr, &b2->tr, h.ts, &d) != 0)
            d.dx = d.dv = V_NAN;
        m->agree_dx = maxd(m->agree_dx, d.dx);
        m->agree_c = maxd(m->agree_c, ce.dx);
        m->agree_b = maxd(m->agree_b, be.dx);
        fprintf(f, "| %s | %s | %s, %s | %s, %s | %s, %s | %s, %s | %s |\n", s->name, lab,
                F6(h.va), F6(h.vb), E1(d.dx), E1(d.dv), E1(ce.dx), E1(ce.dv), E1(be.dx),
                E1(be.dv), scene_passed(t, i) ? "yes" : "NO");
    }

    fprintf(f,
            "\n### Impact inside a step\n\n"
            "`headon-mid-*`: the same pairs, but the circles touch at t* = 0.125 + dt/3\n"
            "s, a third into step 9. carom's `events` method applies the impulse at\n"
            "t*. carom's `discrete` method sees the gap close within step 9 (a\n"
            "speculative contact: the solver lets the circles close exactly the gap)\n"
            "and stops them touching at its end, where its restitution pass bounces\n"
            "them. Box2D finds them overlapping at the end of step 9 and applies the\n"
            "impulse at the start of step 10. Both have the exact velocities afterwards\n"
            "but carry a position error. The table gives each engine's largest\n"
            "position error against the exact answer over time (m) and its velocity\n"
            "error at the end (m/s). Tolerance for carom `events` (its claim: no\n"
            "time-step error): %s m, and %s m/s at every sample.\n\n"
            "| scene | m_B/m_A | e | carom events: dx, dv | carom discrete: dx, dv | "
            "(predicted) | Box2D: dx, dv | (predicted) | nearest the exact answer |\n"
            "|---|---|---|---|---|---|---|---|---|\n",
            G3(tolerance_of(t, su, "headon-mid-m1-e0", ENG_EVENTS, "headon.dx")),
            G3(tolerance_of(t, su, "headon-mid-m1-e0", ENG_EVENTS, "headon.dv")));
    for (i = 0; i < su->count; ++i) {
        const vscene *s = &su->scenes[i];
        static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
        headon h;
        headon_err e[3];
        char why[V_NOTE_MAX], lab[64], best[64] = "";
        double bestv = (double)INFINITY, share;
        int k;
        if (strncmp(s->name, "headon-mid-", 11) != 0 || headon_fit(s, &h, why, sizeof why) != 0)
            continue;
        headon_labels(&h, lab, sizeof lab);
        share = maxd(h.ma, h.mb) / (h.ma + h.mb);
        for (k = 0; k < 3; ++k) {
            const run *r = ok_run(s, engs[k]);
            if (!r) {
                e[k].dx = e[k].dv_end = V_NAN;
                continue;
            }
            headon_measure(&h, &r->tr, &e[k]);
            if (e[k].dx < bestv) {
                bestv = e[k].dx;
                snprintf(best, sizeof best, "%s", engine_names[engs[k]]);
            } else if (e[k].dx == bestv) {
                size_t used = strlen(best);
                snprintf(best + used, sizeof best - used, ", %s", engine_names[engs[k]]);
            }
        }
        m->mid_events = maxd(m->mid_events, e[0].dx);
        m->mid_discrete = maxd(m->mid_discrete, e[1].dx);
        m->mid_box2d = maxd(m->mid_box2d, e[2].dx);
        fprintf(f, "| %s | %s | %s, %s | %s, %s | %s | %s, %s | %s | %s |\n", s->name, lab,
                E1(e[0].dx), E1(e[0].dv_end), E1(e[1].dx), E1(e[1].dv_end),
                E1(late_impulse_error(h.e, h.ua - h.ub, h.ts, s->dt, share, 0.0)), E1(e[2].dx),
                E1(e[2].dv_end), E1(late_impulse_error(h.e, h.ua - h.ub, h.ts, s->dt, share, 1.0)),
                best[0] ? best : "n/a");
    }
    fprintf(f,
            "\ncarom `discrete` is left with `e v (dt - t*) m_B / M` (docs/events.md: the\n"
            "bounce starts at the end of the step instead of at t*, from touching; for\n"
            "e = 0 there is no bounce and no error); Box2D with\n"
            "`(1 + e) v (dt - t*) m_B / M` (contact detected only after overlap, at\n"
            "the start of the next step; its position correction only removes overlap\n"
            "beyond `b2_linearSlop` = 0.005 m, at 20 %% per iteration, and after the\n"
            "impact the bodies separate at once). Both errors never decay.\n");
}

/* ---- the restitution drop ---------------------------------------------------------------- */

/* The figure's data in the work directory: drop.exact.dat (t, then each
 * ball's exact height) and drop.ENGINE.dat (t, then per ball its height
 * and its error). */
static int write_drop_data(const vscene *s, const drop *d, const report_info *ri)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    char path[V_PATH_MAX];
    FILE *f;
    double t;
    int k, i;
    long j;
    snprintf(path, sizeof path, "%s/drop.exact.dat", ri->workdir);
    if (!(f = fopen(path, "w")))
        return -1;
    for (t = 0.0; t <= d->tend + 1e-9; t += 0.002) {
        fprintf(f, "%.5f", t);
        for (i = 0; i < d->count; ++i)
            fprintf(f, " %.6f", drop_height(d, &d->balls[i], t));
        fputc('\n', f);
    }
    if (fclose(f) != 0)
        return -1;
    for (k = 0; k < 3; ++k) {
        const run *r = ok_run(s, engs[k]);
        snprintf(path, sizeof path, "%s/drop.%s.dat", ri->workdir, engine_names[engs[k]]);
        if (!(f = fopen(path, "w")))
            return -1;
        for (j = 0; r && j < r->tr.samples; ++j) {
            fprintf(f, "%.5f", r->tr.t[j]);
            for (i = 0; i < d->count; ++i) {
                const drop_ball *b = &d->balls[i];
                double h = TRACE_AT(&r->tr, j, b->body)[SY] - b->r - d->floor;
                fprintf(f, " %.6f %.6f", h, h - drop_height(d, b, r->tr.t[j]));
            }
            fputc('\n', f);
        }
        if (fclose(f) != 0)
            return -1;
    }
    return 0;
}

static int draw_figure(const drop *d, const report_info *ri, char *why, size_t n)
{
    char script[V_PATH_MAX], errp[V_PATH_MAX];
    char *argv[3];
    FILE *f;
    int k, first = d->count > 3 ? d->count - 3 : 0, rc;
    snprintf(script, sizeof script, "%s/drop.gp", ri->workdir);
    snprintf(errp, sizeof errp, "%s/gnuplot.err", ri->workdir);
    if (!(f = fopen(script, "w"))) {
        snprintf(why, n, "cannot write %s", script);
        return -1;
    }
    fprintf(f, "set terminal pngcairo size 1200,960 font \"sans,10\"\n"
               "set output \"%s\"\n"
               "set multiplot layout %d,2 title \"Restitution drop from h = %g m, g = %g, dt = "
               "%.6g s: height of the ball's lowest point above the floor (left) and its error "
               "against the exact motion (right, cut at 0.15 m)\"\n"
               "set xlabel \"t (s)\"\nset grid\nset key top right\nset xrange [0:%g]\n",
            ri->figure, d->count - first, d->balls[0].h0, d->g, d->dt, d->tend);
    for (k = first; k < d->count; ++k) {
        int col = k + 2, hcol = 2 * k + 2, ecol = 2 * k + 3;
        fprintf(f,
                "set title \"e = %g\"\nset ylabel \"height (m)\"\nset yrange [-0.05:*]\n"
                "plot \"%s/drop.exact.dat\" using 1:%d with lines lw 2 lc rgb \"black\" title "
                "\"exact\", \\\n"
                "     \"%s/drop.events.dat\" using 1:%d with lines lw 1 lc rgb \"#1f77b4\" title "
                "\"carom events\", \\\n"
                "     \"%s/drop.discrete.dat\" using 1:%d with lines lw 1 dt 3 lc rgb "
                "\"#2ca02c\" title \"carom discrete\", \\\n"
                "     \"%s/drop.box2d.dat\" using 1:%d with lines lw 1 dt 2 lc rgb \"#d62728\" "
                "title \"Box2D 2.4.1\"\n",
                d->balls[k].e, ri->workdir, col, ri->workdir, hcol, ri->workdir, hcol, ri->workdir,
                hcol);
        fprintf(f,
                "set title \"e = %g: engine - exact\"\nset ylabel \"height error (m)\"\n"
                "set yrange [-0.15:0.15]\n"
                "plot \"%s/drop.events.dat\" using 1:%d with lines lw 1 lc rgb \"#1f77b4\" title "
                "\"carom events\", \\\n"
                "     \"%s/drop.discrete.dat\" using 1:%d with lines lw 1 dt 3 lc rgb "
                "\"#2ca02c\" title \"carom discrete\", \\\n"
                "     \"%s/drop.box2d.dat\" using 1:%d with lines lw 1 dt 2 lc rgb \"#d62728\" "
                "title \"Box2D 2.4.1\"\n",
                d->balls[k].e, ri->workdir, ecol, ri->workdir, ecol, ri->workdir, ecol);
    }
    fprintf(f, "unset multiplot\n");
    if (fclose(f) != 0) {
        snprintf(why, n, "cannot write %s", script);
        return -1;
    }
    argv[0] = (char *)"gnuplot";
    argv[1] = script;
    argv[2] = NULL;
    rc = spawn_wait(argv, NULL, errp);
    if (rc != 0) {
        FILE *e = fopen(errp, "r");
        char line[V_NOTE_MAX] = "";
        if (e) {
            /* the first line with something on it */
            while (fgets(line, sizeof line, e)) {
                line[strcspn(line, "\n")] = '\0';
                if (line[strspn(line, " \t^")])
                    break;
            }
            fclose(e);
        }
        snprintf(why, n, "gnuplot exited with status %d: %s", rc, line);
        return -1;
    }
    return 0;
}

static const char *figure_name(const report_info *ri)
{
    const char *slash = strrchr(ri->figure, '/');
    return slash ? slash + 1 : ri->figure;
}

static int write_drop(FILE *f, const suite *su, const check_table *t, const report_info *ri,
                      summary *m, int *figure_drawn)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    const vscene *s = suite_find(su, "drop");
    drop d;
    drop_err *errs[3] = {NULL, NULL, NULL};
    drop_impacts im;
    char why[V_NOTE_MAX];
    const event_row *b2first = NULL, *difirst = NULL;
    int i, k, rc = 0;
    double tol;

    fprintf(f, "\n## Restitution drop\n\n");
    if (!s || drop_fit(s, &d, why, sizeof why) != 0) {
        fprintf(f, "(No usable `drop` scene in this run.)\n");
        return 0;
    }
    for (k = 0; k < 3; ++k) {
        const run *r = ok_run(s, engs[k]);
        if (!r)
            continue;
        errs[k] = (drop_err *)calloc((size_t)d.count + 1, sizeof *errs[k]);
        if (errs[k])
            drop_measure(&d, &r->tr, errs[k]);
    }
    if (!errs[0] || !errs[1] || !errs[2]) {
        fprintf(f, "(A run of `drop` failed: see the checks.)\n");
        for (k = 0; k < 3; ++k)
            free(errs[k]);
        drop_free(&d);
        return 0;
    }
    fprintf(f,
            "%d balls (radius %g, e = ", d.count, d.balls[0].r);
    for (i = 0; i < d.count; ++i)
        fprintf(f, "%g%s", d.balls[i].e, i + 1 < d.count ? ", " : "");
    fprintf(f,
            ", no friction) fall from\n"
            "rest from h = %g m onto a static floor, g = %g, dt = %s s, %g s. Exact:\n"
            "first impact at t1 = sqrt(2h/g) = %s s at sqrt(2gh) = %s m/s; the n-th\n"
            "bounce reaches e^(2n) h; impacts slower than the rest speed (%g m/s) end\n"
            "the bouncing. Measured bounce height = the highest sample (every step) of\n"
            "each flight, so it can be low by up to g dt^2 / 8 = %s m.\n\n"
            "| e | exact bounces 1, 2, 3 (m) | carom events | carom discrete | Box2D | max "
            "height error over time (m): events, discrete, Box2D | deepest below the floor "
            "(m): events, discrete, Box2D |\n"
            "|---|---|---|---|---|---|---|\n",
            d.balls[0].h0, d.g, G6(s->dt), d.tend, F6(d.balls[0].T[0]), F6(d.balls[0].U[0]),
            d.rest, num("%.2g", d.g * s->dt * s->dt / 8.0));
    for (i = 0; i < d.count; ++i) {
        const drop_ball *b = &d.balls[i];
        fprintf(f, "| %g |", b->e);
        for (k = 0; k < 3; ++k) {
            double a = drop_apex(&d, b, k);
            fprintf(f, " %s%s", a < 0.0 ? "-" : F6(a), k < 2 ? "," : " |");
        }
        for (k = 0; k < 3; ++k) {
            int j;
            for (j = 0; j < 3; ++j)
                fprintf(f, " %s%s", j < errs[k][i].napex ? F6(errs[k][i].apex[j]) : "-",
                        j < 2 ? "," : " |");
        }
        fprintf(f, " %s, %s, %s | %s, %s, %s |\n", E2(errs[0][i].merr), E2(errs[1][i].merr),
                E2(errs[2][i].merr), E1(errs[0][i].below), E1(errs[1][i].below),
                E1(errs[2][i].below));
    }
    fprintf(f,
            "\nFirst impact (carom: the impact's instant from `--events`, `events` inside\n"
            "the step, `discrete` at its end; Box2D: the end of the step in which it\n"
            "found the contact), and the approach speed each engine bounced:\n\n"
            "| e | exact t1 (s), speed (m/s) | carom events | carom discrete | Box2D |\n"
            "|---|---|---|---|---|\n");
    for (i = 0; i < d.count; ++i) {
        const drop_ball *b = &d.balls[i];
        fprintf(f, "| %g | %s, %s |", b->e, F6(b->T[0]), F6(b->U[0]));
        for (k = 0; k < 3; ++k) {
            const event_row *r = drop_first_impact(b, &s->runs[engs[k]].ev);
            if (r)
                fprintf(f, " %s, %s |", F6(r->t), F6(r->approach));
            else
                fprintf(f, " - |");
            if (i == 0 && k == 1)
                difirst = r;
            if (i == 0 && k == 2)
                b2first = r;
        }
        fputc('\n', f);
    }
    drop_match_impacts(&d, &s->runs[ENG_EVENTS].ev, &im);
    tol = tolerance_of(t, su, "drop", ENG_EVENTS, "drop.impact-time");
    fprintf(f,
            "\ncarom `events`: its %d impacts (of %d exact ones) against the analytic "
            "sequence: largest relative error %s in time, %s in speed (tolerance %s).\n",
            im.matched, im.wanted, E1(im.dt_rel), E1(im.du_rel), G3(tol));
    if (im.slow)
        fprintf(f, "It also reports %d arrival(s) at or below the rest speed as impacts: %s. "
                   "See the findings below.\n", im.slow, im.slow_text);
    m->slow = im.slow;
    snprintf(m->slow_text, sizeof m->slow_text, "%s", im.slow_text);

    if (ri->figure) {
        char fig_why[V_NOTE_MAX];
        snprintf(fig_why, sizeof fig_why, "cannot write its data in %s", ri->workdir);
        if (write_drop_data(s, &d, ri) != 0 ||
            draw_figure(&d, ri, fig_why, sizeof fig_why) != 0) {
            fprintf(stderr, "validate: the figure %s: %s\n", ri->figure, fig_why);
            rc = 1;
        } else {
            *figure_drawn = 1;
        }
        fprintf(f, "\n![bounce height against time: exact, carom, Box2D](%s)\n\n"
                   "(The error plots are cut at 0.15 m; the largest errors are in the first "
                   "table.)\n", figure_name(ri));
    }

    /* free fall of the first ball, and the first impact speeds */
    m->fall_events = errs[0][0].fall_err;
    m->fall_box2d = errs[2][0].fall_err;
    m->fall_pred = d.g * s->dt * errs[2][0].fall_t / 2.0;
    m->drop_events = m->drop_box2d = 0.0;
    for (i = 0; i < d.count; ++i) {
        m->drop_events = maxd(m->drop_events, errs[0][i].merr);
        m->drop_box2d = maxd(m->drop_box2d, errs[2][i].merr);
    }
    {
        const event_row *e1 = drop_first_impact(&d.balls[0], &s->runs[ENG_EVENTS].ev);
        m->u1_events = e1 ? fabs(e1->approach - d.balls[0].U[0]) : V_NAN;
        m->u1_box2d = b2first ? fabs(b2first->approach - d.balls[0].U[0]) : V_NAN;
    }
    fprintf(f,
            "\nBox2D's balls bounce at the wrong times and heights. It integrates\n"
            "semi-implicit Euler (`v += g dt` then `x += v dt`), which after n steps\n"
            "of free fall has fallen `g dt^2 n (n + 1) / 2` instead of `g (n dt)^2 / 2`:\n"
            "`g dt t / 2` too far (%s m at t1; measured: %s m). Its continuous\n"
            "collision finds the impact with the static floor inside the step, but\n"
            "bounces the velocity the ball has at the end of the whole step (its\n"
            "`--events` approach speed, %s m/s, against the exact\n"
            "%s m/s); its polygon skin (`b2_polygonRadius` = 0.01 m) makes the\n"
            "floor 1 cm higher; and its restitution test takes the relative velocity\n"
            "after the step's gravity kick, so a ball that arrives slower than the rest\n"
            "speed still bounces when the kick makes it faster, and can keep hopping\n"
            "at about the rest speed. The table counts each engine's impacts after the\n"
            "exact ball has come to rest, and gives the ball's highest point in the\n"
            "last second (a resting Box2D ball sits on the floor's skin, a few mm up):\n\n"
            "| e | exact ball at rest from (s) | impacts after that (+2 dt): carom events, "
            "carom discrete, Box2D | highest point in the last second (m): carom events, carom "
            "discrete, Box2D |\n"
            "|---|---|---|---|\n",
            G3(m->fall_pred), G3(m->fall_box2d), b2first ? F6(b2first->approach) : "n/a",
            F6(d.balls[0].U[0]));
    m->settle_events = m->settle_box2d = 0.0;
    for (i = 0; i < d.count; ++i) {
        const drop_ball *b = &d.balls[i];
        int late[3];
        if (b->e == 0.0 || b->rest_t < 0.0)
            continue;
        for (k = 0; k < 3; ++k)
            late[k] = drop_late_impacts(&d, b, &s->runs[engs[k]].ev);
        m->settle_events += late[0];
        m->settle_box2d += late[2];
        fprintf(f, "| %g | %s | %d, %d, %d | %s, %s, %s |\n", b->e, F6(b->rest_t), late[0],
                late[1], late[2], E2(errs[0][i].last_top), E2(errs[1][i].last_top),
                E2(errs[2][i].last_top));
    }
    {
        const drop_ball *last = &d.balls[d.count - 1];
        const drop_err *le = &errs[1][d.count - 1];
        const char *last_apex = le->napex > 0 ? F6(le->apex[0]) : "n/a";
        double ratio = difirst ? difirst->approach / d.balls[0].U[0] : V_NAN;
        fprintf(f,
                "\ncarom's velocity Verlet is exact for constant gravity and the `events`\n"
                "method puts each bounce at its instant, so its bounces follow the exact\n"
                "curve. `discrete` finds the contact in the step it comes in (a speculative\n"
                "contact stops the ball on the floor at the step's end) and applies\n"
                "restitution once, at the end of that step, to the approach speed its\n"
                "solver recorded when the contact first pushed: %s m/s here, against the\n"
                "exact %s m/s at the instant of contact (the speed of a moment earlier,\n"
                "the start of the substep in which it pushes). So every bounce starts late\n"
                "and slow by that ratio, and a bounce reaches (%s)^2 = %s of its exact\n"
                "height (e = %g: %s m against %s m).\n",
                difirst ? F6(difirst->approach) : "n/a", F6(d.balls[0].U[0]), F4(ratio),
                F4(ratio * ratio), last->e, last_apex, F6(drop_apex(&d, last, 0)));
    }
    for (k = 0; k < 3; ++k)
        free(errs[k]);
    drop_free(&d);
    return rc;
}

/* ---- large time steps -------------------------------------------------------------------- */

static void write_large(FILE *f, const suite *su, const check_table *t)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    int i, k, any = 0;
    for (i = 0; i < su->count; ++i)
        any += !strncmp(su->scenes[i].name, "large-", 6);
    if (!any)
        return;
    fprintf(f,
            "\n## Large time steps and large gravity\n\n"
            "`large-*`: a ball (radius 0.5, e = 0) dropped from rest, its\n"
            "lowest point 2 m above a static floor 1 m thick, with the default gravity\n"
            "at dt = 0.5, 0.4 and 0.25 s, and with gravity 1e4 at dt = 1/60 s. The\n"
            "impact comes inside a step; there the ball stops, and the contact found\n"
            "inside the step must hold for the rest of it: a method that stopped the\n"
            "ball and then let gravity act for the rest of the step would drop it up to\n"
            "g dt^2 / 2 per step (1.25 m at dt = 0.5 s), through the floor. Exact: free\n"
            "fall to the floor at t1, then at rest on it. Checked for both carom\n"
            "methods (tolerances %s m below the floor, %s m from it and %s m/s once\n"
            "landed); Box2D is shown for comparison.\n\n"
            "| scene | dt (s) | g (m/s^2) | exact landing t1 (s), speed (m/s) | engine | deepest "
            "below the floor (m) | largest height error (m) | from t1 on: largest height "
            "(m), speed (m/s) | height at the end (m) |\n"
            "|---|---|---|---|---|---|---|---|---|\n",
            G3(tolerance_of(t, su, "large-dt-0.5", ENG_EVENTS, "drop.below")),
            G3(tolerance_of(t, su, "large-dt-0.5", ENG_EVENTS, "drop.rest-height")),
            G3(tolerance_of(t, su, "large-dt-0.5", ENG_EVENTS, "drop.rest-speed")));
    for (i = 0; i < su->count; ++i) {
        const vscene *s = &su->scenes[i];
        drop d;
        char why[V_NOTE_MAX];
        if (strncmp(s->name, "large-", 6) != 0 || drop_fit(s, &d, why, sizeof why) != 0)
            continue;
        for (k = 0; k < 3; ++k) {
            const run *r = ok_run(s, engs[k]);
            drop_err e;
            const drop_ball *b = &d.balls[0];
            if (k == 0)
                fprintf(f, "| %s | %s | %s | %s, %s |", s->name, G3(s->dt), G3(d.g), F4(b->T[0]),
                        F4(b->U[0]));
            else
                fprintf(f, "| | | | |");
            if (!r) {
                fprintf(f, " %s | failed | | | |\n", engine_names[engs[k]]);
                continue;
            }
            drop_measure(&d, &r->tr, &e);
            fprintf(f, " %s | %s | %s | %s, %s | %s |\n", engine_names[engs[k]], E1(e.below),
                    E1(e.merr), E1(e.rest_h), E1(e.rest_v),
                    G6(TRACE_AT(&r->tr, r->tr.samples - 1, b->body)[SY] - b->r - d.floor));
        }
        drop_free(&d);
    }
    fprintf(f, "\nBox2D rests its ball on the floor's skin (`b2_polygonRadius` = 0.01 m,\n"
               "less the `b2_linearSlop` it lets bodies overlap), a few mm above it.\n");
}

/* ---- polygons ---------------------------------------------------------------------------- */

static void write_poly(FILE *f, const suite *su, const check_table *t, summary *m)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    const vscene *s = suite_find(su, "polygon-offcentre");
    poly p;
    char why[V_NOTE_MAX];
    long at;
    int k;
    fprintf(f, "\n## Polygon hits polygon off-centre\n\n");
    if (!s || poly_fit(s, &p, why, sizeof why) != 0 || (at = poly_compare_step(s)) < 0) {
        fprintf(f, "(No usable `polygon-offcentre` run in this run: see the checks.)\n");
        return;
    }
    fprintf(f,
            "`polygon-offcentre`: a 2 x 1 box (2 kg) slides at 4 m/s into a unit box\n"
            "(1 kg) turned by 0.3 rad; the corner meets the face 0.3 m off A's centre\n"
            "line at t* = %s s, e = 0.5, no friction. Exact: one contact point,\n"
            "normal (1, 0), impulse `P = (1 + e) v / (1/m_A + 1/m_B + (r_A x n)^2/I_A\n"
            "+ (r_B x n)^2/I_B)` (docs/physics.md). Both engines find a second, glancing\n"
            "impact later (the boxes turn into each other), which has no closed form,\n"
            "so the state is compared at step %ld (t = %s s), after the first\n"
            "impact in every engine and before any second one.\n\n"
            "| engine | first impact t (s) | v_A (vx, vy, w) | v_B (vx, vy, w) | velocity error "
            "(m/s, rad/s) | pose error (m, rad) |\n"
            "|---|---|---|---|---|---|\n"
            "| exact | %s | %s, 0, %s | %s, 0, %s | | |\n",
            F6(p.ts), at, F4((double)at * s->dt), F6(p.ts), F6(p.v[0]), F6(p.w[0]), F6(p.v[1]),
            F6(p.w[1]));
    for (k = 0; k < 3; ++k) {
        const run *r = ok_run(s, engs[k]);
        poly_err e;
        poly_measure(&p, &r->tr, at, &e);
        fprintf(f, "| %s | %s | %s, %s, %s | %s, %s, %s | %s, %s | %s, %s |\n",
                engine_names[engs[k]], num("%.9g", r->ev.rows[0].t), F6(e.vel[0][0]),
                F6(e.vel[0][1]), F6(e.vel[0][2]), F6(e.vel[1][0]), F6(e.vel[1][1]),
                F6(e.vel[1][2]), E1(e.dv), E1(e.dw), E1(e.dx), E1(e.da));
        if (engs[k] == ENG_EVENTS)
            m->poly_events = maxd(e.dx, e.da);
        if (engs[k] == ENG_BOX2D)
            m->poly_box2d = maxd(e.dx, e.da);
    }
    fprintf(f,
            "\nBox2D's first impact is late: its polygons carry a skin of\n"
            "`b2_polygonRadius` = 0.01 m each, so they touch 0.02 m early\n"
            "(%s s at 4 m/s), but it finds the contact only at the start of a\n"
            "step after they overlap (the event time is the end of that step).\n"
            "Its impulse is right for the contact it finds: the velocities after the\n"
            "first impact agree with the exact ones to the figures in the table, the\n"
            "pose error is the time-step error of the late contact (carom `events`\n"
            "is tolerance-checked at %s). carom `discrete` stops the corner on the\n"
            "face at the end of the step it comes in and bounces there: the same\n"
            "velocities, a pose error of one late bounce.\n",
            F4(0.02 / 4.0), G3(tolerance_of(t, su, "polygon-offcentre", ENG_EVENTS, "poly.dx")));
}

/* ---- stack and pyramid ------------------------------------------------------------------- */

static void write_still(FILE *f, const suite *su, summary *m)
{
    static const char *const names[2] = {"stack", "pyramid"};
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    int i, k;
    fprintf(f, "\n## Stack and pyramid at rest\n\n"
               "`stack`: five unit boxes placed exactly touching on a static floor;\n"
               "`pyramid`: ten rows (55 boxes), rows exactly touching. Exact answer:\n"
               "nothing moves. g = 10, dt = 1/60 s, 10 s, friction 0.6.\n\n"
               "| scene | engine | max displacement over time (m) | at the end (m) | max rotation "
               "(rad) | rise of the top box (m) |\n"
               "|---|---|---|---|---|---|\n");
    for (i = 0; i < 2; ++i) {
        const vscene *s = suite_find(su, names[i]);
        for (k = 0; k < 3; ++k) {
            const run *r = ok_run(s, engs[k]);
            still_err e;
            if (!r) {
                if (s)
                    fprintf(f, "| %s | %s | failed | | | |\n", names[i], engine_names[engs[k]]);
                continue;
            }
            still_measure(&r->tr, &e);
            fprintf(f, "| %s | %s | %s | %s | %s | %s |\n", names[i], engine_names[engs[k]],
                    E2(e.move), E2(e.end_move), E2(e.rot), F4(e.rise));
            if (i == 0 && engs[k] == ENG_EVENTS) {
                m->stack_events = e.move;
                m->stack_rise_events = e.rise;
            }
            if (i == 0 && engs[k] == ENG_BOX2D)
                m->stack_rise_box2d = e.rise;
            if (i == 1 && engs[k] == ENG_EVENTS) {
                m->pyramid_end_events = e.end_move;
                m->pyramid_x = e.move_x;
                m->pyramid_y = e.move_y;
                m->pyramid_time = (double)s->steps * s->dt;
            }
            if (i == 1)
                *(engs[k] == ENG_EVENTS     ? &m->pyramid_events
                  : engs[k] == ENG_DISCRETE ? &m->pyramid_discrete
                                            : &m->pyramid_box2d) = e.move;
        }
    }
    fprintf(f, "\nBox2D cannot hold a stack where it is put: each box carries a skin of\n"
               "`b2_polygonRadius` = 0.01 m, so boxes that touch overlap by 0.02 m in\n"
               "Box2D's eyes, and position correction pushes them apart until the overlap\n"
               "is `b2_linearSlop` = 0.005 m: the stack grows by 0.015 m per contact\n"
               "(five contacts: 0.075 m), then rests. carom keeps the stack where it was\n"
               "placed (resting forces carried into the Verlet drift, warm-started\n"
               "contact impulses, docs/physics.md).\n");
}

/* ---- the elastic gas --------------------------------------------------------------------- */

static void write_gas(FILE *f, const suite *su, summary *m)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    const vscene *s = suite_find(su, "gas");
    deviation eb, ed;
    int k;
    fprintf(f, "\n## Elastic gas\n\n");
    if (!ok_run(s, ENG_EVENTS) || !ok_run(s, ENG_DISCRETE) || !ok_run(s, ENG_BOX2D)) {
        fprintf(f, "(A run of `gas` failed, or the scene is missing: see the checks.)\n");
        return;
    }
    fprintf(f, "`gas`: %d circles (radius 0.1, e = 1, no friction, rest speed 0) in a\n"
               "closed 20 x 20 m box, no gravity, %ld steps. The kinetic energy must stay\n"
               "what it was; the paths are chaotic, so the engines are compared by their\n"
               "energy and by how long their trajectories stay together.\n\n"
               "| engine | impacts (`--events` rows) | kinetic energy at t = 0 (J) | at the end: "
               "change (relative) | largest change (relative) |\n"
               "|---|---|---|---|---|\n",
            s->sc.body_count - 4, s->steps);
    for (k = 0; k < 3; ++k) {
        const run *r = ok_run(s, engs[k]);
        conserved c;
        conservation_measure(s, &r->tr, &c);
        fprintf(f, "| %s | %d | %s | %s | %s |\n", engine_names[engs[k]], r->ev.count,
                F6(c.ke0), num("%+.2e", c.de_end / c.ke0), E2(c.de_max / c.ke0));
        *(engs[k] == ENG_EVENTS     ? &m->gas_events
          : engs[k] == ENG_DISCRETE ? &m->gas_discrete
                                    : &m->gas_box2d) = c.de_max / c.ke0;
    }
    if (deviation_measure(&s->runs[ENG_EVENTS].tr, &s->runs[ENG_BOX2D].tr, -1.0, &eb) != 0)
        eb.t_apart = V_NAN;
    if (deviation_measure(&s->runs[ENG_EVENTS].tr, &s->runs[ENG_DISCRETE].tr, -1.0, &ed) != 0)
        ed.t_apart = V_NAN;
    fprintf(f,
            "\nA body of carom `events` and Box2D is first 1 cm apart at t = %s s\n"
            "(carom `events` and `discrete`: t = %s s): the first impacts inside a step\n"
            "already send the paths apart, and in a gas every difference grows. Box2D\n"
            "finds the contacts of a step where the circles overlap at its start and\n"
            "solves them together with iterated sequential impulses; carom `events`\n"
            "takes each impact alone at its instant, in time order, and keeps the\n"
            "kinetic energy to %s. carom `discrete` changes it by %s: an isolated pair\n"
            "keeps its energy under `discrete` (the head-on pairs below: its change of\n"
            "energy is the exact one), so the change comes from what a gas adds (many\n"
            "impacts per step, oblique ones, balls meeting several others in one step).\n"
            "Box2D's change (%s) depends on its iteration counts (8 velocity, 3\n"
            "position here).\n",
            eb.t_apart < 0.0 ? "never" : num("%.9g", eb.t_apart),
            ed.t_apart < 0.0 ? "never" : num("%.9g", ed.t_apart), E2(m->gas_events),
            E2(m->gas_discrete), E2(m->gas_box2d));
}

/* ---- bullets ----------------------------------------------------------------------------- */

static void write_bullets(FILE *f, const suite *su, const check_table *t, summary *m)
{
    static const char *const names[2] = {"bullet", "bullet-dynamic"};
    static const int engs[4] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D, ENG_BOX2D_BULLETS};
    int i, k;
    fprintf(f,
            "\n## Bullets\n\n"
            "A circle of radius 0.05 at 1000 m/s (16.7 m per step) meets a wall 2 cm\n"
            "thick at t* = 4.94 ms; e = 0.5. `bullet`: static wall; `bullet-dynamic`:\n"
            "a free wall (0.04 kg; the bullet 0.0079 kg), exact answer the Newton\n"
            "impulse. Box2D runs `bullet-dynamic` twice: as it comes (continuous\n"
            "collision only against static bodies) and with `--bullets` (every\n"
            "dynamic body a Box2D bullet). The predicted error of carom `discrete` is\n"
            "that of a bounce at the end of the step, `e v (dt - t*) m_wall / M`.\n\n"
            "| scene | engine | bullet velocity after step 1 (m/s) | final bullet velocity (m/s) "
            "| final wall velocity (m/s) | max position error (m) | (predicted) |\n"
            "|---|---|---|---|---|---|---|\n");
    for (i = 0; i < 2; ++i) {
        const vscene *s = suite_find(su, names[i]);
        bullet bu;
        char why[V_NOTE_MAX];
        double share;
        if (!s || bullet_fit(s, &bu, why, sizeof why) != 0)
            continue;
        share = bu.static_wall ? 1.0 : bu.mw / (bu.mw + bu.mb);
        fprintf(f, "| %s | exact | | %s | %s | | |\n", names[i], G6(bu.vb), G6(bu.vw));
        if (i == 1)
            m->bdyn_exact = bu.vb;
        for (k = 0; k < 4; ++k) {
            const run *r = ok_run(s, engs[k]);
            bullet_err e;
            if (!r) {
                if (s->runs[engs[k]].wanted)
                    fprintf(f, "| %s | %s | failed | | | | |\n", names[i], engine_names[engs[k]]);
                continue;
            }
            bullet_measure(s, &bu, &r->tr, &e);
            fprintf(f, "| %s | %s | %s | %s | %s | %s | %s |\n", names[i], engine_names[engs[k]],
                    G6(e.first), G6(e.fv), G6(e.wv), G3(e.dx),
                    engs[k] == ENG_DISCRETE
                        ? G3(late_impulse_error(bu.e, bu.ub - bu.uw, bu.ts, s->dt, share, 0.0))
                        : "");
            if (i == 0 && engs[k] == ENG_EVENTS)
                m->bullet_events = fabs(e.fv - bu.vb);
            if (i == 0 && engs[k] == ENG_BOX2D) {
                m->bullet_box2d = fabs(e.fv - bu.vb);
                m->bullet_step1 = e.first;
            }
            if (i == 1 && engs[k] == ENG_EVENTS)
                m->bdyn_events = e.fv;
            if (i == 1 && engs[k] == ENG_BOX2D)
                m->bdyn_box2d = e.fv;
            if (i == 1 && engs[k] == ENG_BOX2D_BULLETS)
                m->bdyn_bullets = e.fv;
        }
    }
    fprintf(f,
            "\nBox2D caps every body's motion at `b2_maxTranslation` = 2 m per step by\n"
            "scaling its velocity down (to 120 m/s at 60 Hz) and keeps the\n"
            "scaled velocity: the bullet loses 88 %% of its speed in its first step.\n"
            "Against the static wall its continuous collision then stops it at the\n"
            "wall; against the free wall, without `--bullets`, it passes through (no\n"
            "continuous collision between dynamic bodies). carom's `events` method\n"
            "finds the impact at its instant (tolerance for its position error: %s\n"
            "m, the float rounding of a 1000 m/s path). carom `discrete` reaches as\n"
            "far as the bodies move in a step when it looks for contacts (speculative\n"
            "contacts), so it stops the bullet at the wall and bounces it with the\n"
            "exact velocities, at the end of the step: its position error is the\n"
            "predicted one of a late bounce.\n",
            G3(tolerance_of(t, su, "bullet", ENG_EVENTS, "bullet.dx")));
}

/* ---- a spinning kinematic blade ---------------------------------------------------------- */

static void write_blade(FILE *f, const suite *su, summary *m)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    const vscene *s = suite_find(su, "blade");
    char why[V_NOTE_MAX];
    blade b;
    int k;
    if (!s || blade_fit(s, &b, why, sizeof why) != 0)
        return;
    fprintf(f,
            "\n## A spinning kinematic blade\n\n"
            "A kinematic blade 60 cm by 2 cm spinning at 90 rad/s (1.5 rad a step)\n"
            "about its centre strikes a ball of radius 2.5 cm at rest 20 cm above the\n"
            "centre (e = 0.5, frictionless, no gravity). Its leading face meets the\n"
            "ball at t* = %s s, the face point under the ball moving at w rho along\n"
            "the face's normal; Newton's law sends the ball off at (1 + e) w rho n.\n\n"
            "| engine | ball velocity at the end (m/s) | error (m/s) | largest position error (m) |\n"
            "|---|---|---|---|\n"
            "| exact | (%s, %s) | | |\n",
            G6(b.ts), G6(b.vx), G6(b.vy));
    for (k = 0; k < 3; ++k) {
        const run *r = ok_run(s, engs[k]);
        blade_err e;
        if (!r) {
            if (s->runs[engs[k]].wanted)
                fprintf(f, "| %s | failed | | |\n", engine_names[engs[k]]);
            continue;
        }
        blade_measure(&b, &r->tr, &e);
        fprintf(f, "| %s | (%s, %s) | %s | %s |\n", engine_names[engs[k]], G6(e.vx), G6(e.vy),
                G3(e.dv), G3(e.dx));
        if (engs[k] == ENG_EVENTS)
            m->blade_events = e.dv;
        else if (engs[k] == ENG_DISCRETE)
            m->blade_discrete = e.dv;
        else
            m->blade_box2d = e.dv;
    }
    fprintf(f,
            "\nBoth carom methods sweep the ball against the turning blade: `events`\n"
            "finds the strike as an impact at its instant, `discrete` through the\n"
            "step's continuous guard, which also holds bodies against kinematic ones\n"
            "(docs/physics.md); each then lets the ball fly on. Box2D sends the ball\n"
            "off in a direction about 0.025 rad off Newton's, as from a strike that\n"
            "much of the blade's turn late (its polygons also carry the skin\n"
            "`b2_polygonRadius`, 1 cm). Measured apart from this suite: with the blade\n"
            "at 100, 200 and 400 rad/s Box2D's ball leaves at the same (-27.64, 4.20)\n"
            "m/s, as if the blade turned at no more than its cap `b2_maxRotation` =\n"
            "pi/2 a step (94 rad/s at 60 Hz); carom's at Newton's velocity for each\n"
            "(`tests/test_continuous.c`).\n");
}

/* ---- energy, momentum, deviation --------------------------------------------------------- */

/* The exact change of energy of a scene over its run, or NaN where there
 * is no closed form. */
static double exact_de(const vscene *s)
{
    headon h;
    bullet bu;
    blade bl;
    drop d;
    char why[V_NOTE_MAX];
    int i, at_rest = 1, elastic = 1;
    if (headon_fit(s, &h, why, sizeof why) == 0) {
        double de = headon_dke(&h);
        return fabs(de) < 1e-12 ? 0.0 : de;
    }
    if (bullet_fit(s, &bu, why, sizeof why) == 0)
        return bullet_dke(&bu);
    if (blade_fit(s, &bl, why, sizeof why) == 0) /* (the blade does work) */
        return bl.mb * (bl.vx * bl.vx + bl.vy * bl.vy) / 2.0;
    if (drop_fit(s, &d, why, sizeof why) == 0) {
        double de = drop_dE(s, &d);
        drop_free(&d);
        return de;
    }
    for (i = 0; i < s->sc.body_count; ++i) {
        const carom_body_def *b = &s->sc.bodies[i].def;
        if (b->type != CAROM_BODY_DYNAMIC)
            continue;
        if (b->velocity.x != 0.0f || b->velocity.y != 0.0f || b->angular_velocity != 0.0f)
            at_rest = 0;
        if (b->restitution != 1.0f || b->friction != 0.0f)
            elastic = 0;
    }
    /* placed at rest: nothing moves; elastic and frictionless without
     * gravity: the kinetic energy stays */
    if (at_rest || (elastic && s->gx == 0.0 && s->gy == 0.0))
        return 0.0;
    return V_NAN;
}

static void write_energy(FILE *f, const suite *su)
{
    static const int engs[3] = {ENG_EVENTS, ENG_DISCRETE, ENG_BOX2D};
    int i, k;
    fprintf(f, "\n## Energy and momentum, every scene\n\n"
               "Energy = kinetic + potential of the scene's gravity, in J: its change from\n"
               "t = 0 to the end, next to the exact change where there is one (the\n"
               "head-on pairs and bullets from the exact velocities; the drops from the\n"
               "exact bounce sequence; nothing moves in the stack and pyramid; the gas is\n"
               "elastic). Momentum P and angular momentum L (about the origin): the\n"
               "largest change over the run, only where no external force acts (no\n"
               "gravity, no static body).\n\n"
               "| scene | exact dE | carom events: dE, dP, dL | carom discrete: dE, dP, dL | "
               "Box2D: dE, dP, dL |\n"
               "|---|---|---|---|---|\n");
    for (i = 0; i < su->count; ++i) {
        const vscene *s = &su->scenes[i];
        int free_ = scene_is_free(s);
        fprintf(f, "| %s | %s |", s->name, num("%+.6g", exact_de(s)));
        for (k = 0; k < 3; ++k) {
            const run *r = ok_run(s, engs[k]);
            conserved c;
            if (!r) {
                fprintf(f, " failed |");
                continue;
            }
            conservation_measure(s, &r->tr, &c);
            if (free_)
                fprintf(f, " %s, %s, %s |", num("%+.6g", c.de_end), E1(c.dp_max), E1(c.dl_max));
            else
                fprintf(f, " %s, -, - |", num("%+.6g", c.de_end));
        }
        fputc('\n', f);
    }

    fprintf(f, "\n## Deviation between the engines, every scene\n\n"
               "Largest difference over all bodies and samples, carom `events` against\n"
               "Box2D and against carom `discrete` (position m, velocity m/s; for the\n"
               "head-on pairs without the velocity sample at the impact instant), and the\n"
               "first time a body is 1 cm apart.\n\n"
               "| scene | events - Box2D: dx, dv | first 1 cm apart (s) | events - discrete: dx, "
               "dv | first 1 cm apart (s) |\n"
               "|---|---|---|---|---|\n");
    for (i = 0; i < su->count; ++i) {
        const vscene *s = &su->scenes[i];
        const run *ev = ok_run(s, ENG_EVENTS), *di = ok_run(s, ENG_DISCRETE),
                  *b2 = ok_run(s, ENG_BOX2D);
        deviation a, b;
        double skip = deviation_skip(s);
        if (!ev || !di || !b2 || deviation_measure(&ev->tr, &b2->tr, skip, &a) != 0 ||
            deviation_measure(&ev->tr, &di->tr, skip, &b) != 0)
            continue;
        fprintf(f, "| %s | %s, %s | %s | %s, %s | %s |\n", s->name, E1(a.dx), E1(a.dv),
                a.t_apart < 0.0 ? "never" : num("%.9g", a.t_apart), E1(b.dx), E1(b.dv),
                b.t_apart < 0.0 ? "never" : num("%.9g", b.t_apart));
    }
}

/* ---- summary and findings ---------------------------------------------------------------- */

static void row(FILE *f, const char *behaviour, const char *measure, double carom, double box2d,
                const char *verdict)
{
    fprintf(f, "| %s | %s | %s | %s | %s |\n", behaviour, measure, G3(carom), G3(box2d),
            verdict ? verdict : nearer(carom, box2d));
}

static void write_summary(FILE *f, const summary *m)
{
    char buf[512];
    fprintf(f, "\n## Where and why the engines differ\n\n"
               "Each row: a behaviour of Box2D, the number of this run that shows it, the\n"
               "value for carom (`events`) and for Box2D, and which is nearer the exact\n"
               "answer.\n\n"
               "| Box2D behaviour | measured (exact answer in brackets) | carom | Box2D | nearer "
               "the exact answer |\n"
               "|---|---|---|---|---|\n");
    snprintf(buf, sizeof buf, "`headon-step-*`: largest error against the exact answer, m (0); "
                              "the engines differ by at most %s m", G3(m->agree_dx));
    row(f, "the same Newton impulse on the same state", buf, m->agree_c, m->agree_b,
        "both, to float rounding");
    snprintf(buf, sizeof buf, "`headon-mid-*`: largest position error, m (0); carom `discrete`: "
                              "%s", G3(m->mid_discrete));
    row(f, "contact found only after overlap, impulse at the start of the next step", buf,
        m->mid_events, m->mid_box2d, NULL);
    snprintf(buf, sizeof buf, "drop: height error after free fall, just before the first "
                              "impact, m (0; Box2D predicted g dt t / 2 = %s)", G3(m->fall_pred));
    row(f, "semi-implicit Euler integration", buf, m->fall_events, m->fall_box2d, NULL);
    row(f, "continuous collision against static bodies: the impact inside the step, with the "
           "end-of-step velocity", "drop: error of the first impact speed, m/s (0)",
        m->u1_events, m->u1_box2d, NULL);
    row(f, "restitution tested on the velocity after the step's gravity kick",
        "drop: impacts after the exact balls have come to rest (0)", m->settle_events,
        m->settle_box2d, NULL);
    row(f, "all of these, and the polygon skin under the ball",
        "drop: largest height error over the run, m (0)", m->drop_events, m->drop_box2d, NULL);
    row(f, "polygon skin `b2_polygonRadius`, position correction down to `b2_linearSlop`",
        "stack: rise of the top box, m (0; Box2D predicted 5 x (2 x 0.01 - 0.005) = 0.075)",
        m->stack_rise_events, m->stack_rise_box2d, NULL);
    row(f, "the same", "pyramid: largest displacement, m (0)", m->pyramid_events,
        m->pyramid_box2d, NULL);
    row(f, "polygon skin and late contact",
        "`polygon-offcentre`: pose error after the first impact, m or rad (0)", m->poly_events,
        m->poly_box2d, NULL);
    snprintf(buf, sizeof buf, "`bullet`: bullet speed error at the end, m/s (0); Box2D's speed "
                              "after step 1: %s m/s = 2 m / dt", G3(m->bullet_step1));
    row(f, "velocity clamp `b2_maxTranslation` = 2 m per step", buf, m->bullet_events,
        m->bullet_box2d, NULL);
    snprintf(buf, sizeof buf, "`bullet-dynamic`: final bullet velocity, m/s (%s); Box2D with "
                              "`--bullets`: %s", G3(m->bdyn_exact), G3(m->bdyn_bullets));
    row(f, "no continuous collision between dynamic bodies that are not bullets", buf,
        m->bdyn_events, m->bdyn_box2d,
        nearer(m->bdyn_events - m->bdyn_exact, m->bdyn_box2d - m->bdyn_exact));
    row(f, "contact with a fast-turning kinematic body",
        "blade: error of the ball's velocity after a spinning blade's strike, m/s (0); carom "
        "`discrete` the same as `events`", m->blade_events, m->blade_box2d, NULL);
    row(f, "contacts of a step solved together by iterated impulses",
        "gas: largest relative change of the kinetic energy (0)", m->gas_events, m->gas_box2d,
        NULL);

    fprintf(f, "\n## Findings about carom in this run\n\n"
               "Measured, not judged by a tolerance (the checks are):\n\n");
    if (m->slow > 0)
        fprintf(f, "- **Slow arrivals in `events`.** %d ball arrival(s) of the drop slower\n"
                   "  than the rest speed are reported as impacts: %s.\n", m->slow, m->slow_text);
    fprintf(f, "- **Stack and pyramid.** carom keeps the five-box stack within %s m of\n"
               "  where it was put. The 55-box pyramid moves by up to %s m in %s s\n"
               "  (`discrete`: %s m), %s m at the end (%s m/s on average); the largest\n"
               "  horizontal displacement is %s m, the largest vertical %s m: its boxes\n"
               "  creep along the rows while they rest. (Sleeping is off in these runs; a\n"
               "  sleeping pyramid would stop being simulated, and stop creeping.)\n",
            G3(m->stack_events), G3(m->pyramid_events), G3(m->pyramid_time),
            G3(m->pyramid_discrete), G3(m->pyramid_end_events),
            G3(m->pyramid_end_events / m->pyramid_time), G3(m->pyramid_x), G3(m->pyramid_y));
    fprintf(f, "- **Elastic gas under `discrete`.** The largest relative change of the\n"
               "  kinetic energy is %s (`events`: %s).\n",
            G3(m->gas_discrete), G3(m->gas_events));
}

/* ---- the checks -------------------------------------------------------------------------- */

static void cell(FILE *f, const char *text)
{
    for (; *text; ++text) {
        if (*text == '|')
            fputs("\\|", f);
        else
            fputc(*text, f);
    }
}

static void write_checks(FILE *f, const suite *su, const check_table *t, const report_info *ri)
{
    int r, i;
    fprintf(f, "\n## The checks\n\n"
               "Every row of `%s`: the scenes it covers, the engines, the\n"
               "quantity, how many checks it makes (scenes x engines), the worst value\n"
               "measured over them, the tolerance, and why that tolerance. A check passes\n"
               "when the value is at most the tolerance; a value that cannot be measured\n"
               "(a run failed) fails.\n\n"
               "| scenes | engines | quantity | checks | worst | tolerance | result | reason |\n"
               "|---|---|---|---|---|---|---|---|\n",
            ri->checks_path);
    for (r = 0; r < t->count; ++r) {
        const check_row *row = &t->rows[r];
        double worst = 0.0;
        int n = 0, failed = 0, unmeasured = 0;
        char v[32];
        for (i = 0; i < t->result_count; ++i) {
            const check_result *c = &t->results[i];
            if (c->row != r)
                continue;
            ++n;
            failed += !c->pass;
            if (isnan(c->value))
                unmeasured = 1;
            else if (c->value > worst)
                worst = c->value;
        }
        format_value(v, sizeof v, unmeasured ? V_NAN : worst);
        const char *unit = quantity_unit(row->quantity);
        fprintf(f, "| `%s` | %s | `%s` (%s) | %d | %s | %g | %s", row->pattern, row->engine_text,
                quantity_name(row->quantity), unit[0] ? unit : "status", n, v, row->tol,
                failed ? "**FAIL**" : "pass");
        if (failed)
            fprintf(f, " (%d of %d)", failed, n);
        fputs(" | ", f);
        cell(f, row->reason);
        fputs(" |\n", f);
    }
    fprintf(f, "\nQuantities:\n\n");
    for (i = 0; i < quantity_count(); ++i)
        fprintf(f, "- `%s`: %s.\n", quantity_name(i), quantity_what(i));
    if (!t->failed) {
        fprintf(f, "\nEvery check of this run is within its stated tolerance.\n");
        return;
    }
    fprintf(f, "\n**Checks that failed in this run:**\n\n");
    for (i = 0; i < t->result_count; ++i) {
        const check_result *c = &t->results[i];
        const check_row *row = &t->rows[c->row];
        char v[32];
        if (c->pass)
            continue;
        format_value(v, sizeof v, c->value);
        fprintf(f, "- `%s`, %s%s%s, `%s`: %s > %g (line %d)%s", su->scenes[c->scene].name,
                engine_names[c->a], c->b >= 0 ? ":" : "", c->b >= 0 ? engine_names[c->b] : "",
                quantity_name(row->quantity), v, row->tol, row->line, c->why[0] ? ": " : "");
        cell(f, c->why);
        fputs("\n", f);
    }
}

/* ---- the whole report -------------------------------------------------------------------- */

int report_write(const suite *su, const check_table *t, const report_info *ri,
                 int *figure_drawn)
{
    char tmp[V_PATH_MAX];
    summary m;
    FILE *f;
    int rc = 0, bad;
    summary_init(&m);
    *figure_drawn = 0;
    snprintf(tmp, sizeof tmp, "%s.tmp", ri->out);
    if (!(f = fopen(tmp, "w"))) {
        fprintf(stderr, "validate: cannot write %s: %s\n", tmp, strerror(errno));
        return -1;
    }
    write_header(f, su, t, ri);
    write_headon(f, su, t, &m);
    rc = write_drop(f, su, t, ri, &m, figure_drawn);
    write_large(f, su, t);
    write_poly(f, su, t, &m);
    write_still(f, su, &m);
    write_gas(f, su, &m);
    write_bullets(f, su, t, &m);
    write_blade(f, su, &m);
    write_energy(f, su);
    write_summary(f, &m);
    write_checks(f, su, t, ri);
    bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        fprintf(stderr, "validate: error writing %s\n", tmp);
        unlink(tmp);
        return -1;
    }
    if (rename(tmp, ri->out) != 0) {
        fprintf(stderr, "validate: cannot rename %s to %s: %s\n", tmp, ri->out, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return rc;
}
