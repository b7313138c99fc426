/*
 * report.c -- `carom-accuracy report`: docs/accuracy.md and its figures
 * from the records of `carom-accuracy sweep` and `bound` (accuracy.h).
 *
 * Every number in the report comes from the records it is given; the text
 * around them states what was measured and how. Figures are drawn with
 * gnuplot (pngcairo), from data files written to a temporary directory.
 */
#include "accuracy/accuracy.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- the records ----------------------------------------------------------- */

static rec *recs;
static int nrec, caprec;

static int load(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[8192];
    if (!f) {
        fprintf(stderr, "carom-accuracy: report: cannot open %s: %s\n", path, strerror(errno));
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        if (nrec == caprec) {
            caprec = caprec ? 2 * caprec : 256;
            recs = realloc(recs, (size_t)caprec * sizeof *recs);
            if (!recs) {
                fprintf(stderr, "carom-accuracy: out of memory\n");
                exit(2);
            }
        }
        if (rec_parse(line, &recs[nrec]) == 0)
            ++nrec;
    }
    fclose(f);
    return 0;
}

static int is(const rec *r, const char *key, const char *val)
{
    const char *v = rec_get(r, key);
    return v && strcmp(v, val) == 0;
}

static const rec *find_run(const char *scene, const char *build, const char *method, int den)
{
    int k;
    for (k = 0; k < nrec; ++k) {
        const rec *r = &recs[k];
        if (strcmp(r->kind, "run") == 0 && is(r, "scene", scene) && is(r, "build", build) &&
            is(r, "method", method) && (int)rec_getd(r, "den") == den)
            return r;
    }
    return NULL;
}

static const rec *find_meta(const char *build)
{
    int k;
    for (k = 0; k < nrec; ++k)
        if (strcmp(recs[k].kind, "meta") == 0 && is(&recs[k], "build", build))
            return &recs[k];
    return NULL;
}

static int dens[32], ndens;

static void collect_dens(void)
{
    int k, j;
    for (k = 0; k < nrec; ++k) {
        int d;
        if (strcmp(recs[k].kind, "run") != 0 || !is(&recs[k], "build", "on"))
            continue;
        d = (int)rec_getd(&recs[k], "den");
        for (j = 0; j < ndens && dens[j] != d; ++j)
            ;
        if (j == ndens && ndens < 32)
            dens[ndens++] = d;
    }
    for (k = 1; k < ndens; ++k)
        for (j = k; j > 0 && dens[j] < dens[j - 1]; --j) {
            int t = dens[j];
            dens[j] = dens[j - 1];
            dens[j - 1] = t;
        }
}

/* wall-clock seconds per simulated second, op cost per simulated second */
static double time_per_s(const rec *r)
{
    return rec_getd(r, "ns") * 1e-9 / rec_getd(r, "dt");
}

static double cost_per_s(const rec *r)
{
    return rec_getd(r, "cost") / (rec_getd(r, "steps") * rec_getd(r, "dt"));
}

/* ---- formatting ------------------------------------------------------------ */

static const char *fmt_num(double v, char *buf, size_t n)
{
    if (isnan(v))
        snprintf(buf, n, "—");
    else if (v == 0.0)
        snprintf(buf, n, "0");
    else if (fabs(v) >= 0.01 && fabs(v) < 1000.0)
        snprintf(buf, n, "%.3g", v);
    else {
        char tmp[40], *e;
        snprintf(tmp, sizeof tmp, "%.2e", v);
        e = strchr(tmp, 'e');
        if (e) {
            int ex = atoi(e + 1);
            *e = '\0';
            snprintf(buf, n, "%se%d", tmp, ex);
        } else {
            snprintf(buf, n, "%s", tmp);
        }
    }
    return buf;
}

/* A formatted number that stays valid for the next 15 calls (several
 * per printf). */
static const char *num(double v)
{
    static char buf[16][48];
    static int next;
    next = (next + 1) % 16;
    return fmt_num(v, buf[next], sizeof buf[next]);
}
#define NUM(v) num(v)

static const char *fail_or(const rec *r, const char *key)
{
    if (!r)
        return "—";
    if (rec_get(r, "fail"))
        return "failed";
    return NUM(rec_getd(r, key));
}

/* Least-squares slope of ln err against ln dt over the points with a
 * positive error: the observed order p in err ~ dt^p. */
static double fit_order(const char *scene, const char *build, const char *method,
                        const char *key, int *used)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k, n = 0;
    for (k = 0; k < ndens; ++k) {
        const rec *r = find_run(scene, build, method, dens[k]);
        double e, x, y;
        if (!r || rec_get(r, "fail"))
            continue;
        e = rec_getd(r, key);
        if (!(e > 0.0) || isinf(e))
            continue;
        x = log(rec_getd(r, "dt"));
        y = log(e);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        ++n;
    }
    *used = n;
    if (n < 3)
        return NAN;
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* ---- the scenes, as the report describes them -------------------------- */

typedef struct scene_doc {
    const char *name, *title, *exact, *error, *extra_keys, *extra_names, *notes;
} scene_doc;

static const scene_doc scenes[] = {
    {"bounce", "Bounce sequence",
     "a ball (radius 0.5 m, e = 0.8) dropped from rest 10 m above a static floor, 10.5 s: "
     "impacts at t₁ = √(2h/g), then every 2eᵏv₁/g, approach speeds eᵏv₁, heights e²ᵏh "
     "(8 impacts)",
     "largest \\|y − y_exact\\| + \\|x − x₀\\| over every step, relative to the 10 m drop",
     "t_err,v_err", "Impact times (largest relative error of the 8);Approach speeds (largest relative error)",
     "events and first-impact take each impact at its instant: what is left is float "
     "rounding, at every dt. discrete and Box2D take it where the bodies are at the end of "
     "the step: first order in dt."},
    {"pi-billiard", "Two-block π billiard",
     "a light circle (1 kg) between a wall and a heavy one (10⁴ kg, coming at 1 m/s), "
     "e = 1, 4 s: ⌊100π⌋ = 314 impacts (the last at 3.85 s), simulated impact by impact "
     "in double",
     "largest position error of either circle over every step, relative to the heavy "
     "circle's 1.1 m start",
     "imp,E_err", "Impacts (314 in the exact solution);Final energy (relative error)",
     "events takes all 314 impacts at their instants at every dt; what is left is the "
     "rounding of 314 impulses. first-impact gives each pair one impact per step "
     "(docs/events.md): when the trapped light circle should strike both neighbours many "
     "times within one step, the overlap it builds is left to the contact solver, which "
     "does not bounce it back (see the final energy). Box2D's continuous collision acts "
     "against static bodies only, so the fast light circle can pass through the heavy "
     "one."},
    {"cradle", "Newton's cradle",
     "five balls 1 cm apart struck by a sixth at 1 m/s, e = 1, no gravity, 2 s: each "
     "ball stops and passes the speed on; simulated impact by impact in double",
     "largest position error of any ball over every step, relative to a ball's diameter",
     "V_err,E_err", "Final velocities (largest error / 1 m/s);Final energy (relative error)",
     "Each impact of the chain is a different pair, so first-impact takes them at their "
     "instants like events; discrete and Box2D resolve them at step ends: first order."},
    {"spinbox", "Spinning box between walls",
     "a 1 × 0.5 box spinning at 4 rad/s and moving at (2, 0.25) m/s between two walls "
     "3 m apart, e = 1, no friction, 2 s (one impact on each wall): vertex impacts as "
     "roots of the vertex-wall gap in double, frictionless impulse at the vertex",
     "largest \\|centre error\\| + reach × \\|angle error\\| over every step, relative to the "
     "reach (half diagonal, 0.56 m)",
     "L_err,P_err,E_err,t_err",
     "Final angular momentum (relative error);Final linear momentum (relative error);Final energy (relative error);Impact times (largest relative error)",
     "For events and first-impact the error does not depend on dt: it is set by the "
     "conservative-advancement tolerance (see the tolerance study below). Box2D's polygons "
     "carry a skin (b2_polygonRadius, 1 cm) and touch that much early, whatever dt."},
    {"circle-on-circle", "Circle on a circle at an angle",
     "a ball (radius 0.25, e = 0.9) falling from rest onto a static circle (radius 1) "
     "whose centre is 0.5 m off its path, 1.5 s: the impact is the root of \\|d(t)\\| = 1.25 "
     "(d a parabola), the rebound reflects the normal velocity",
     "largest position error over every step, relative to the ball's radius",
     "t_err,V_err", "Impact time (relative error);Final velocity (relative error)",
     "The impact time of two circles under gravity is solved in closed form by events "
     "and first-impact; discrete and Box2D are first order."},
    {"projectile", "Projectile under gravity and a constant force",
     "a box (1 kg) thrown at (3, 8) m/s spinning at 1 rad/s, with force (2, 1) N and "
     "torque 0.1 N m, 2 s, no impacts: x = x₀ + v₀t + at²/2, angle = θ₀ + ω₀t + αt²/2 "
     "(velocity Verlet is exact here: only rounding is left)",
     "largest \\|position error\\| + reach × \\|angle error\\| over every step, relative to the "
     "distance travelled (10.2 m)",
     "pos_err,ang_err,W_err",
     "Position error / distance travelled;Angle error (rad);Final angular velocity (relative error)",
     "No impacts: carom's three methods integrate alike (velocity Verlet, exact for "
     "constant acceleration, so the error is rounding; the angle is not compensated, see "
     "below). Box2D integrates with symplectic Euler: first order."},
    {"gas", "Elastic gas",
     "64 circles (e = 1, no walls, no gravity) on a grid with fixed pseudo-random "
     "velocities, 2 s: kinetic energy and momentum are kept exactly",
     "largest of \\|E − E₀\\| / E₀ and \\|P − P₀\\| / Σm\\|v\\| at the end",
     "E_err,P_err,imp", "Energy drift (relative);Momentum drift (/ Σm\\|v\\|);Impacts taken",
     "Momentum is kept to rounding by every method (impulses are equal and opposite). "
     "Energy: events keeps it to rounding; first-impact where no pair meets twice in a "
     "step; discrete applies restitution once per step to whatever touches then."},
    {"stack", "Stack settling",
     "five unit boxes (friction 0.6, e = 0) dropped 1 cm onto each other and a floor, "
     "3 s: at rest they stand exactly on each other, centres at y = 0.5, 1.5, …, 4.5",
     "largest position (or reach × angle) error of a box over the last second, relative "
     "to the box height (1 m)",
     "", "",
     "carom's position correction stops a resting contact's overlap within one linear "
     "slop (0.56 mm here; docs/physics.md), so a box of the column may rest up to five "
     "slops, 2.8 mm, below its exact place. Where in that band each contact stops depends "
     "on how deep its landing pushed it, less with smaller steps: the error falls with dt "
     "to rounding. Box2D's boxes rest on their 1 cm skins, less its contact slop."},
};
#define SCENE_COUNT ((int)(sizeof scenes / sizeof scenes[0]))

static const char *methods[] = {"events", "first-impact", "discrete"};

/* ---- plots ----------------------------------------------------------------- */

static char tmpd[256];

static int ndata;
static char datafiles[256][320];

/* Our own directory (mkdtemp): its files, then it (at exit). */
static void tmpd_clean(void)
{
    static const char *names[] = {"plot.gp", "gp.err"};
    char path[400];
    int k;
    if (!tmpd[0])
        return;
    for (k = 0; k < ndata; ++k)
        unlink(datafiles[k]);
    for (k = 0; k < 2; ++k) {
        snprintf(path, sizeof path, "%s/%s", tmpd, names[k]);
        unlink(path);
    }
    rmdir(tmpd);
    tmpd[0] = '\0';
}

/* Write one curve: x (time or cost per simulated second, by column),
 * err; returns the file name or NULL if no point. */
static const char *curve_file(const char *scene, const char *build, const char *method,
                              const char *key, int xcol)
{
    char *p;
    FILE *f;
    int k, n = 0;
    if (ndata >= 256)
        return NULL;
    p = datafiles[ndata];
    snprintf(p, sizeof datafiles[0], "%s/d%03d.dat", tmpd, ndata);
    f = fopen(p, "w");
    if (!f)
        return NULL;
    for (k = 0; k < ndens; ++k) {
        const rec *r = find_run(scene, build, method, dens[k]);
        double x, e;
        if (!r || rec_get(r, "fail"))
            continue;
        x = xcol == 0 ? time_per_s(r) : xcol == 1 ? cost_per_s(r) : rec_getd(r, "dt");
        e = rec_getd(r, key);
        if (!(x > 0.0) || isnan(e))
            continue;
        if (e < 1e-10)
            e = 1e-10;
        fprintf(f, "%.6g %.6g %d\n", x, e, dens[k]);
        ++n;
    }
    fclose(f);
    ++ndata;
    return n ? p : NULL;
}

static int gnuplot(const char *script)
{
    char path[320], errp[320];
    FILE *f;
    int st;
    pid_t pid;
    snprintf(path, sizeof path, "%s/plot.gp", tmpd);
    snprintf(errp, sizeof errp, "%s/gp.err", tmpd);
    f = fopen(path, "w");
    if (!f || fputs(script, f) < 0 || fclose(f) != 0) {
        fprintf(stderr, "carom-accuracy: report: cannot write %s\n", path);
        return -1;
    }
    pid = fork();
    if (pid == 0) {
        FILE *e = freopen(errp, "w", stderr);
        (void)e;
        execlp("gnuplot", "gnuplot", path, (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        char line[200] = "";
        FILE *e = fopen(errp, "r");
        if (e) {
            if (!fgets(line, sizeof line, e))
                line[0] = '\0';
            fclose(e);
        }
        fprintf(stderr, "carom-accuracy: report: gnuplot failed%s%s\n", line[0] ? ": " : "",
                line);
        return -1;
    }
    return 0;
}

/* Growable text for gnuplot scripts. */
typedef struct text {
    char *s;
    size_t len, cap;
} text;

static void tput(text *t, const char *fmt, ...)
{
    va_list ap;
    int n;
    for (;;) {
        size_t room = t->cap - t->len;
        va_start(ap, fmt);
        n = vsnprintf(t->s ? t->s + t->len : NULL, t->s ? room : 0, fmt, ap);
        va_end(ap);
        if (n < 0)
            return;
        if (t->s && (size_t)n < room) {
            t->len += (size_t)n;
            return;
        }
        t->cap = t->cap * 2 + (size_t)n + 256;
        t->s = realloc(t->s, t->cap);
        if (!t->s) {
            fprintf(stderr, "carom-accuracy: out of memory\n");
            exit(2);
        }
    }
}

static const char *curve_style[] = {
    "lc rgb '#1f77b4' pt 7 lw 2", /* events */
    "lc rgb '#2ca02c' pt 5 lw 2", /* first-impact */
    "lc rgb '#d62728' pt 9 lw 2", /* discrete */
    "lc rgb '#7f7f7f' pt 13 lw 2", /* box2d */
    "lc rgb '#1f77b4' pt 6 lw 1 dt 2", /* events, compensation off */
};

static int plot_scene(const scene_doc *sd, const char *figdir)
{
    text t = {NULL, 0, 0};
    int panel, rc;
    tput(&t, "set terminal pngcairo size 1200,460 font 'sans,10'\n");
    tput(&t, "set output '%s/accuracy-%s.png'\n", figdir, sd->name);
    tput(&t, "set multiplot layout 1,2 title \"%s: error against cost (each point a dt)\"\n",
         sd->title);
    tput(&t, "set logscale xy\nset format y '10^{%%L}'\nset format x '10^{%%L}'\n"
             "set grid\nset key below\nset ylabel 'error (relative)'\n");
    for (panel = 0; panel < 2; ++panel) {
        int m, first = 1;
        tput(&t, "set xlabel '%s'\n",
             panel == 0 ? "wall-clock seconds per simulated second"
                        : "operations (seed weights) per simulated second");
        tput(&t, "plot ");
        for (m = 0; m < 5; ++m) {
            const char *build = m == 3 ? "box2d" : m == 4 ? "off" : "on";
            const char *method = m == 3 ? "box2d" : m == 4 ? "events" : methods[m];
            const char *f;
            if (panel == 1 && m == 3)
                continue; /* Box2D has no operation counter */
            f = curve_file(sd->name, build, method, "err", panel);
            if (!f)
                continue;
            tput(&t, "%s'%s' using 1:2 with linespoints %s title '%s%s'", first ? "" : ", ", f,
                 curve_style[m], m == 3 ? "Box2D 2.4.1" : method,
                 m == 4 ? " (compensation off)" : "");
            first = 0;
        }
        if (first)
            tput(&t, "1/0 notitle");
        tput(&t, "\n");
    }
    tput(&t, "unset multiplot\n");
    rc = gnuplot(t.s);
    free(t.s);
    return rc;
}

static int plot_compensated(const char *figdir)
{
    text t = {NULL, 0, 0};
    int m, first, rc;
    static const char *titles[] = {"events", "first-impact"};
    tput(&t, "set terminal pngcairo size 1200,460 font 'sans,10'\n");
    tput(&t, "set output '%s/accuracy-compensated.png'\n", figdir);
    tput(&t, "set multiplot layout 1,2 title 'Compensated summation on and off'\n");
    tput(&t, "set logscale xy\nset format y '10^{%%L}'\nset grid\nset key top right\n"
             "set xlabel 'dt (s)'\n");
    tput(&t, "set title 'bounce: impact times, largest relative error'\n"
             "set ylabel 'relative error'\nplot 2e-6 with lines lc rgb 'black' dt 3 "
             "title 'target 2e-6'");
    for (m = 0; m < 2; ++m) {
        const char *on = curve_file("bounce", "on", titles[m], "t_err", 2);
        const char *off = curve_file("bounce", "off", titles[m], "t_err", 2);
        if (on)
            tput(&t, ", '%s' using 1:2 with linespoints %s title '%s, on'", on, curve_style[m],
                 titles[m]);
        if (off)
            tput(&t, ", '%s' using 1:2 with linespoints %s dt 2 title '%s, off'", off,
                 curve_style[m], titles[m]);
    }
    tput(&t, "\nset title 'projectile (no impacts): position and angle errors, events'\n"
             "set ylabel 'error'\nplot ");
    first = 1;
    {
        static const char *keys[] = {"pos_err", "ang_err"};
        static const char *names[] = {"position / distance", "angle (rad)"};
        for (m = 0; m < 2; ++m) {
            const char *on = curve_file("projectile", "on", "events", keys[m], 2);
            const char *off = curve_file("projectile", "off", "events", keys[m], 2);
            if (on) {
                tput(&t, "%s'%s' using 1:2 with linespoints %s title '%s, on'", first ? "" : ", ",
                     on, curve_style[m == 0 ? 0 : 2], names[m]);
                first = 0;
            }
            if (off) {
                tput(&t, "%s'%s' using 1:2 with linespoints %s dt 2 title '%s, off'",
                     first ? "" : ", ", off, curve_style[m == 0 ? 0 : 2], names[m]);
                first = 0;
            }
        }
    }
    if (first)
        tput(&t, "1/0 notitle");
    tput(&t, "\nunset multiplot\n");
    rc = gnuplot(t.s);
    free(t.s);
    return rc;
}

/* ---- the report --------------------------------------------------------------- */

static FILE *out;

static void p(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(out, fmt, ap);
    va_end(ap);
}

static const char *tol_builds[16];
static int ntol;

static void collect_tols(void)
{
    int k, j;
    for (k = 0; k < nrec; ++k) {
        const char *b = rec_get(&recs[k], "build");
        if (strcmp(recs[k].kind, "meta") != 0 || !b || strncmp(b, "tol-", 4) != 0)
            continue;
        for (j = 0; j < ntol && strcmp(tol_builds[j], b) != 0; ++j)
            ;
        if (j == ntol && ntol < 16)
            tol_builds[ntol++] = b;
    }
    /* largest tolerance first */
    for (k = 1; k < ntol; ++k)
        for (j = k; j > 0 && atof(tol_builds[j] + 4) > atof(tol_builds[j - 1] + 4); --j) {
            const char *t = tol_builds[j];
            tol_builds[j] = tol_builds[j - 1];
            tol_builds[j - 1] = t;
        }
}

static void section_machine(void)
{
    const rec *on = find_meta("on"), *off = find_meta("off");
    p("Regenerated by `make accuracy` (rules: tools/accuracy/accuracy.mk; program: "
      "tools/accuracy/, built as `build/accuracy/carom-accuracy`); every number and figure "
      "below comes from that run. `make accuracy-check` runs a fast subset with tolerances "
      "(`carom-accuracy check`). ");
    if (on) {
        p("Machine: %s (%s CPUs online). ", rec_get(on, "cpu") ? rec_get(on, "cpu") : "?",
          rec_get(on, "cpus") ? rec_get(on, "cpus") : "?");
        p("Compiler: %s; flags `%s`. ", rec_get(on, "compiler") ? rec_get(on, "compiler") : "?",
          rec_get(on, "cflags") ? rec_get(on, "cflags") : "?");
    }
    p("Builds: the library as configured (`CAROM_ENABLE_COMPENSATED=%s`, "
      "`CAROM_TOI_TOLERANCE=%s`)",
      on ? rec_get(on, "compensated") : "?", on ? NUM(rec_getd(on, "toi_tol")) : "?");
    if (off)
        p("; the same with `CAROM_ENABLE_COMPENSATED=0` (\"compensation off\")");
    if (ntol) {
        int k;
        p("; and with `CAROM_TOI_TOLERANCE` =");
        for (k = 0; k < ntol; ++k)
            p("%s %s", k ? "," : "", tol_builds[k] + 4);
        p(" for the tolerance study");
    }
    p(". Box2D 2.4.1 runs through `build/carom-box2d` (8 velocity and 3 position "
      "iterations, sleeping off).\n\n");
}

static void section_method(void)
{
    int k;
    p("## What is measured\n\n");
    p("Each scene runs with carom's three methods (`events`, `first-impact`, `discrete`, "
      "docs/events.md) and with Box2D 2.4.1 at dt = 1/N s for N =");
    for (k = 0; k < ndens; ++k)
        p("%s %d", k ? "," : "", dens[k]);
    p(", sleeping off. The error of a run is measured against the scene's exact answer, "
      "which `carom-accuracy` computes in double precision or closed form from the scene's "
      "inputs alone (tools/accuracy/reference.c), never from carom's output. The inputs are "
      "the float numbers both engines receive, so the answer is exact for the scene as "
      "given.\n\n");
    p("- **Wall-clock time per simulated second**: the time spent in `carom_world_step` "
      "(in-process, `CLOCK_MONOTONIC` around each step), or in Box2D's `Step()` "
      "(`carom-box2d --time`), divided by dt. Each run is timed three times (short runs "
      "until 30 ms of steps were timed) and the fastest kept. Box2D and carom were timed in "
      "the same run on the same machine; the ratios matter, not the absolute numbers.\n");
    p("- **Operation cost per simulated second**: `carom profile --json` `total_cost` of the "
      "same run (every float operation counted, weighted by the design note's table: add, "
      "sub, compare 1, mul 1.5, div 4, sqrt 6; docs/cost-model.md), divided by the "
      "simulated time. Box2D has no operation counter, so it appears in the time plots "
      "only.\n");
    p("- **Convergence order**: the least-squares slope p of ln(error) against ln(dt) over "
      "the sweep (error ∝ dtᵖ). p ≈ 1 is a first-order method; p ≈ 0 means the error does "
      "not depend on dt (rounding, or a fixed tolerance); p < 0 means the error grows as "
      "dt shrinks.\n\n");
}

static void section_scenes(void)
{
    int s;
    p("## The scenes and their exact answers\n\n");
    p("Scene files: `tools/scenes/accuracy/`. Errors are relative, as stated.\n\n");
    p("| scene | exact answer | error measured |\n|---|---|---|\n");
    for (s = 0; s < SCENE_COUNT; ++s)
        p("| `%s`: %s | %s | %s |\n", scenes[s].name, scenes[s].title, scenes[s].exact,
          scenes[s].error);
    p("\n");
}

static void section_orders(void)
{
    int s, m;
    p("## Convergence orders\n\n");
    p("Fitted p in error ∝ dtᵖ over dt = 1/%d … 1/%d (the error of each run is the one in "
      "the scene's table below).\n\n",
      dens[0], dens[ndens - 1]);
    p("| scene | events | first-impact | discrete | Box2D 2.4.1 | events, compensation off "
      "|\n|---|---|---|---|---|---|\n");
    for (s = 0; s < SCENE_COUNT; ++s) {
        p("| %s", scenes[s].name);
        for (m = 0; m < 5; ++m) {
            const char *build = m == 3 ? "box2d" : m == 4 ? "off" : "on";
            const char *method = m == 3 ? "box2d" : m == 4 ? "events" : methods[m];
            int used;
            double o = fit_order(scenes[s].name, build, method, "err", &used);
            if (isnan(o))
                p(" | —");
            else
                p(" | %.2f", o);
        }
        p(" |\n");
    }
    p("\n");
}

/* 1 if the run of dens[k] and those of every smaller dt are at or below
 * target: the error is reached and kept, not met by luck at one dt. */
static int holds_from(const char *scene, const char *build, const char *method, int k,
                      double target)
{
    for (; k < ndens; ++k) {
        const rec *r = find_run(scene, build, method, dens[k]);
        if (!r || rec_get(r, "fail") || !(rec_getd(r, "err") <= target))
            return 0;
    }
    return 1;
}

static void cheapest(const char *scene, double target, int by_cost, char *buf, size_t n)
{
    const char *best_m = NULL;
    double best = INFINITY;
    int best_den = 0, m, k;
    for (m = 0; m < 4; ++m) {
        const char *build = m == 3 ? "box2d" : "on";
        const char *method = m == 3 ? "box2d" : methods[m];
        if (by_cost && m == 3)
            continue;
        for (k = 0; k < ndens; ++k) {
            const rec *r = find_run(scene, build, method, dens[k]);
            double c;
            if (!r || !holds_from(scene, build, method, k, target))
                continue;
            c = by_cost ? cost_per_s(r) : time_per_s(r);
            if (c < best) {
                best = c;
                best_m = m == 3 ? "Box2D" : methods[m];
                best_den = dens[k];
            }
        }
    }
    if (!best_m)
        snprintf(buf, n, "none reaches it");
    else if (by_cost)
        snprintf(buf, n, "%s, dt 1/%d: %s ops/s", best_m, best_den, NUM(best));
    else
        snprintf(buf, n, "%s, dt 1/%d: %s s/s", best_m, best_den, NUM(best));
}

/* Cheapest run of one method at or below target: its time per simulated
 * second, or NaN; *den gets its dt. */
static double cheapest_of(const char *scene, const char *build, const char *method,
                          double target, int *den)
{
    double best = NAN;
    int k;
    for (k = 0; k < ndens; ++k) {
        const rec *r = find_run(scene, build, method, dens[k]);
        double c;
        if (!r || !holds_from(scene, build, method, k, target))
            continue;
        c = time_per_s(r);
        if (isnan(best) || c < best) {
            best = c;
            *den = dens[k];
        }
    }
    return best;
}

static void section_cheapest(void)
{
    int s, t;
    p("## Which method reaches an error cheapest\n\n");
    p("For each scene and error target, the cheapest run (method and dt of the sweep) that "
      "reaches the target and keeps it: its error, and that of every smaller dt of the "
      "same method, is at or below the target. Cost is wall-clock time per simulated "
      "second (Box2D included) or operation cost per simulated second (carom only).\n\n");
    p("| scene | 1e-3, by time | 1e-3, by operations | 1e-5, by time | 1e-5, by operations "
      "|\n|---|---|---|---|---|\n");
    for (s = 0; s < SCENE_COUNT; ++s) {
        char a[128], b[128], c[128], d[128];
        cheapest(scenes[s].name, 1e-3, 0, a, sizeof a);
        cheapest(scenes[s].name, 1e-3, 1, b, sizeof b);
        cheapest(scenes[s].name, 1e-5, 0, c, sizeof c);
        cheapest(scenes[s].name, 1e-5, 1, d, sizeof d);
        p("| %s | %s | %s | %s | %s |\n", scenes[s].name, a, b, c, d);
    }
    p("\n");
    for (t = 0; t < 2; ++t) {
        double target = t ? 1e-5 : 1e-3;
        p("Per method, the cheapest run that reaches and keeps %s (wall-clock seconds per "
          "simulated second, and its dt; \"—\": no dt of the sweep does):\n\n",
          t ? "1e-5" : "1e-3");
        p("| scene | events | first-impact | discrete | Box2D 2.4.1 |\n|---|---|---|---|---|\n");
        for (s = 0; s < SCENE_COUNT; ++s) {
            int m;
            p("| %s", scenes[s].name);
            for (m = 0; m < 4; ++m) {
                int den = 0;
                double c = cheapest_of(scenes[s].name, m == 3 ? "box2d" : "on",
                                       m == 3 ? "box2d" : methods[m], target, &den);
                if (isnan(c))
                    p(" | —");
                else
                    p(" | %s (1/%d)", NUM(c), den);
            }
            p(" |\n");
        }
        p("\n");
    }
}

static void scene_tables(const scene_doc *sd)
{
    int k, m;
    p("### %s (`%s`)\n\n", sd->title, sd->name);
    p("%s. Error: %s.\n\n", sd->exact, sd->error);
    p("![%s: error against time and operations](accuracy-%s.png)\n\n", sd->title, sd->name);
    p("%s\n\n", sd->notes);
    p("| dt | events | first-impact | discrete | Box2D | events, off | first-impact, off "
      "|\n|---|---|---|---|---|---|---|\n");
    for (k = 0; k < ndens; ++k) {
        p("| 1/%d", dens[k]);
        for (m = 0; m < 6; ++m) {
            const char *build = m < 3 ? "on" : m == 3 ? "box2d" : "off";
            const char *method = m < 3 ? methods[m] : m == 3 ? "box2d" : methods[m - 4];
            p(" | %s", fail_or(find_run(sd->name, build, method, dens[k]), "err"));
        }
        p(" |\n");
    }
    p("\nCost per simulated second: wall-clock seconds (carom and Box2D) and thousands of "
      "weighted operations (carom).\n\n");
    p("| dt | events s | first-impact s | discrete s | Box2D s | events kops | first-impact "
      "kops | discrete kops |\n|---|---|---|---|---|---|---|---|\n");
    for (k = 0; k < ndens; ++k) {
        p("| 1/%d", dens[k]);
        for (m = 0; m < 4; ++m) {
            const rec *r = find_run(sd->name, m == 3 ? "box2d" : "on",
                                    m == 3 ? "box2d" : methods[m], dens[k]);
            p(" | %s", r ? NUM(time_per_s(r)) : "—");
        }
        for (m = 0; m < 3; ++m) {
            const rec *r = find_run(sd->name, "on", methods[m], dens[k]);
            p(" | %s", r ? NUM(cost_per_s(r) / 1e3) : "—");
        }
        p(" |\n");
    }
    p("\n");
    if (sd->extra_keys[0]) {
        char keys[8][32], names[8][96];
        int nk = 0, j;
        const char *a = sd->extra_keys, *b = sd->extra_names;
        while (*a && nk < 8) {
            size_t la = strcspn(a, ","), lb = strcspn(b, ";");
            memcpy(keys[nk], a, la);
            keys[nk][la] = '\0';
            memcpy(names[nk], b, lb);
            names[nk][lb] = '\0';
            ++nk;
            a += la + (a[la] == ',');
            b += lb + (b[lb] == ';');
        }
        for (j = 0; j < nk; ++j) {
            int box = !(strcmp(keys[j], "t_err") == 0 || strcmp(keys[j], "v_err") == 0 ||
                        strcmp(keys[j], "imp") == 0);
            p("%s, compensation on:\n\n| dt | events | first-impact | discrete |%s\n"
              "|---|---|---|---|%s\n",
              names[j], box ? " Box2D |" : "", box ? "---|" : "");
            for (k = 0; k < ndens; ++k) {
                p("| 1/%d |", dens[k]);
                for (m = 0; m < 3 + box; ++m)
                    p(" %s |", fail_or(find_run(sd->name, m == 3 ? "box2d" : "on",
                                                m == 3 ? "box2d" : methods[m], dens[k]),
                                       keys[j]));
                p("\n");
            }
            p("\n");
        }
    }
}

/* Returns the largest |measured / derived - 1| over the records of method. */
static double bound_table(const char *method, const char *measured, const char *derived)
{
    double worst = 0.0;
    int k;
    p("| dt | impact at (fraction of the step) | late by τ | measured | derived | measured "
      "/ derived | bound | measured / bound |\n|---|---|---|---|---|---|---|---|\n");
    for (k = 0; k < nrec; ++k) {
        const rec *r = &recs[k];
        double m, d, b, ratio;
        if (strcmp(r->kind, "bound") != 0 || !is(r, "method", method))
            continue;
        m = rec_getd(r, measured);
        d = rec_getd(r, derived);
        b = rec_getd(r, strcmp(derived, "late_e") == 0 ? "bound_e" : "bound_1pe");
        ratio = m / d;
        if (fabs(ratio - 1.0) > worst || isnan(ratio))
            worst = isnan(ratio) ? (double)INFINITY : fabs(ratio - 1.0);
        p("| 1/%d | %.2f | %s | %s | %s | %.4f | %s | %.3f |\n", (int)rec_getd(r, "den"),
          rec_getd(r, "phase"), NUM(rec_getd(r, "tau")), NUM(m), NUM(d), ratio, NUM(b), m / b);
    }
    p("\n");
    return worst;
}

typedef struct findings {
    int have_bound;
    double bound_discrete, bound_first;  /* largest |measured/derived - 1| */
    double discrete_late_max;            /* largest ratio at the late step */
    int target_met;
    double t_err_on[2], t_err_off[2];    /* largest over dt: events, first-impact */
    double kahan_ops, kahan_share;       /* per body-step (projectile), share */
    double gas_kahan_ops, gas_kahan_share;
    double ang_first, ang_last, w_first, w_last;
    int have_toi;
    double toi_default_l, toi_best_l, toi_best_tol, toi_extra_ops, toi_floor_tol;
} findings;

static findings fd;

static void section_bound(void)
{
    double w3;
    int any = 0, k;
    for (k = 0; k < nrec; ++k)
        if (strcmp(recs[k].kind, "bound") == 0)
            any = 1;
    if (!any)
        return;
    fd.have_bound = 1;
    p("## The error of stepping past an impact\n\n");
    p("How large can the error get when an impact that happens inside a step is treated as "
      "if it happened at the end of the step? (The question the design note leaves open: "
      "[docs/design-note.md](design-note.md), section 3.) Take two bodies A and B on a line, approaching "
      "at relative speed v, with masses m_A and m_B (M = m_A + m_B) and restitution e. They "
      "touch at t\\* inside a step that ends at t\\* + τ (0 ≤ τ < dt). The impact changes A's "
      "velocity by Δv_A = −(1 + e) v m_B / M. The exact path has that velocity for the "
      "last τ of the step; a method that takes the impact late moves A with its old "
      "velocity instead, so at the end of the step A is off by\n\n"
      "    |Δx_A| = (1 + e) v τ m_B / M  ≤  (1 + e) v dt m_B / M\n\n"
      "(and B by the same with m_A). From then on both bodies have the right velocities, so "
      "the error is carried unchanged: it does not decay, it is first order in dt, and the "
      "errors of later impacts add to it. The bound is reached as the impact moves to the "
      "very start of a step (τ → dt). A method that also projects the overlap away (moves "
      "the bodies apart by the overlap v τ, shared by inverse mass) removes v τ m_B / M of "
      "it, leaving e v τ m_B / M ≤ e v dt m_B / M.\n\n");
    p("carom's `discrete` method takes every impact at the end of its step and projects the "
      "overlap away, so its error is e v τ m_B / M. `events` takes every impact at its "
      "instant and has none. `first-impact` takes each pair's first impact of the step at "
      "its instant, and a pair's *second* impact in the same step (A strikes B, B strikes "
      "C, B comes back to A) at the end of the step: there its error is the full "
      "(1 + e) v τ m_B / M; afterwards the contact solver's position correction pushes part "
      "of the remaining overlap out, so the lasting error lies between e v τ m_B / M and "
      "(1 + e) v τ m_B / M.\n\n");
    p("Measured (`carom-accuracy bound`): positions against the exact solution of the same "
      "scene (computed impact by impact in double), no gravity, radius 0.5 m. The gaps "
      "scale with dt, so at small dt they are far below the default contact distance (the "
      "linear slop, 0.5 mm here), which would then count the bodies as touching from the "
      "start; these scenes set `slop=1e-7`.\n\n");
    p("**discrete**: A (1 kg, 0.5 m/s) meets B (3 kg, −0.3 m/s), e = 0.6, v = 0.8 m/s, "
      "m_B / M = 3/4; A's error at t = 1 s against e v τ m_B / M, and against the bound "
      "e v dt m_B / M:\n\n");
    fd.bound_discrete = bound_table("discrete", "at_end", "late_e");
    p("Where the impact falls in the first contact substep of the step (its first quarter "
      "with the default 4 substeps), the bodies end that step still overlapping: the "
      "contact does not stop them exactly where they touch (its target closes the gap with "
      "the substep's mean velocity, so a gap shorter than the substep's motion turns partly "
      "into overlap), and the split position correction removes only a fraction "
      "(`CAROM_POSITION_CORRECTION` = 0.2) of an overlap per substep. The restitution pass "
      "then sends the bodies apart with what is left of the overlap still in their "
      "positions, which adds overlap × m_B / M to A's error: up to %.0f %% here, so that "
      "an impact at the very start of a step ends slightly above e v dt m_B / M. Later in "
      "the step the measurement agrees with e v τ m_B / M to float rounding. Either way it "
      "stays well below (1 + e) v dt m_B / M.\n\n",
      100.0 * fd.bound_discrete);
    p("**first-impact**: A (1 kg, 1 m/s) strikes B (1 kg), B strikes C (3 kg), A and B "
      "meet again (v = 0.36 m/s, m_B / M = 1/2) in the same step; e = 0.6. A's error at the "
      "end of that step against (1 + e) v τ m_B / M and the bound (1 + e) v dt m_B / M:\n\n");
    fd.bound_first = bound_table("first-impact", "at_late", "late_1pe");
    p("The same runs at t = 1 s, after the solver's position correction, against "
      "(1 + e) v τ m_B / M (the ratio must lie between e / (1 + e) = 0.375 and 1):\n\n");
    w3 = bound_table("first-impact", "at_end", "late_1pe");
    (void)w3;
    p("Largest deviation of the measured error from its derivation: discrete %.2g %%, "
      "first-impact (at the end of the late step) %.2g %% — %s the 10 %% asked for.\n\n",
      100.0 * fd.bound_discrete, 100.0 * fd.bound_first,
      (fd.bound_discrete <= 0.1 && fd.bound_first <= 0.1) ? "within" : "**not** within");
}

static double worst_over_dens(const char *scene, const char *build, const char *method,
                              const char *key, int *failed)
{
    double w = 0.0;
    int k;
    *failed = 0;
    for (k = 0; k < ndens; ++k) {
        const rec *r = find_run(scene, build, method, dens[k]);
        double v;
        if (!r)
            continue;
        v = rec_getd(r, key);
        if (rec_get(r, "fail") || isnan(v))
            *failed = 1;
        else if (v > w)
            w = v;
    }
    return w;
}

static void section_compensated(void)
{
    int k, m, failed_any = 0;
    const rec *pon = NULL, *poff = NULL, *first, *last;
    p("## Accuracy as dt shrinks: compensated summation\n\n");
    p("Positions and velocities are sums of many small increments (x += v dt every step). "
      "In float each addition rounds to half a unit in the last place of x, so over "
      "T / dt steps the rounding grows like 1/dt: halving dt doubles the error, and an "
      "integrator that is exact in exact arithmetic gets *worse* as dt shrinks. With "
      "`CAROM_ENABLE_COMPENSATED` (the default) each body carries the part of every sum "
      "that rounding dropped (Kahan summation) and feeds it back into the next addition, "
      "so the sum is about as accurate as one rounding of the exact total, whatever the "
      "number of steps.\n\n");
    p("![Compensated summation on and off](accuracy-compensated.png)\n\n");
    p("Target: bounce impact times within 2e-6 (relative) at every dt from 1/15 to 1/3840 "
      "in both events methods.\n\n");
    p("| dt | events, on | events, off | first-impact, on | first-impact, off |\n"
      "|---|---|---|---|---|\n");
    for (k = 0; k < ndens; ++k) {
        p("| 1/%d", dens[k]);
        for (m = 0; m < 2; ++m) {
            p(" | %s", fail_or(find_run("bounce", "on", methods[m], dens[k]), "t_err"));
            p(" | %s", fail_or(find_run("bounce", "off", methods[m], dens[k]), "t_err"));
        }
        p(" |\n");
    }
    fd.target_met = 1;
    for (m = 0; m < 2; ++m) {
        int failed, f2;
        fd.t_err_on[m] = worst_over_dens("bounce", "on", methods[m], "t_err", &failed);
        fd.t_err_off[m] = worst_over_dens("bounce", "off", methods[m], "t_err", &f2);
        if (failed || !(fd.t_err_on[m] <= 2e-6))
            fd.target_met = 0;
        failed_any |= failed;
        p("%s%s: largest %s", m ? "; " : "\nWith compensation: ", methods[m],
          NUM(fd.t_err_on[m]));
    }
    p(" — target **%s**%s. Without it the error doubles with every halving of dt, as the "
      "rounding argument says.\n\n",
      fd.target_met ? "met" : "missed", failed_any ? " (a run failed)" : "");
    p("The integrator alone (`projectile`, no impacts; velocity Verlet is exact for a "
      "constant acceleration, so all of this is rounding), method events:\n\n");
    p("| dt | position / distance, on | position, off | angle (rad), on | angle, off | "
      "angular velocity (rel.), on | angular velocity, off |\n|---|---|---|---|---|---|---|\n");
    for (k = 0; k < ndens; ++k) {
        const rec *on = find_run("projectile", "on", "events", dens[k]);
        const rec *off = find_run("projectile", "off", "events", dens[k]);
        p("| 1/%d | %s | %s | %s | %s | %s | %s |\n", dens[k], fail_or(on, "pos_err"),
          fail_or(off, "pos_err"), fail_or(on, "ang_err"), fail_or(off, "ang_err"),
          fail_or(on, "W_err"), fail_or(off, "W_err"));
    }
    first = find_run("projectile", "on", "events", dens[0]);
    last = find_run("projectile", "on", "events", dens[ndens - 1]);
    if (first && last) {
        fd.ang_first = rec_getd(first, "ang_err");
        fd.ang_last = rec_getd(last, "ang_err");
        fd.w_first = rec_getd(first, "W_err");
        fd.w_last = rec_getd(last, "W_err");
        p("\nThe switch covers positions and velocities only. The rotation (a unit "
          "(cos, sin) pair turned by ω h and renormalised at every synchronisation) and the "
          "angular velocity (ω += α h) are plain float updates, so their rounding still "
          "piles up: the angle error grows from %s rad at dt = 1/%d to %s rad at 1/%d, the "
          "angular velocity's from %s to %s (relative), the same with the switch on or off. "
          "The same rounding is what remains of the spinning box's angular-momentum error "
          "once the TOI tolerance is small (next section).\n",
          NUM(fd.ang_first), dens[0], NUM(fd.ang_last), dens[ndens - 1], NUM(fd.w_first),
          NUM(fd.w_last));
    }
    p("\n");
    /* cost per body-step: the projectile (one body, no contacts) both ways */
    for (k = ndens - 1; k >= 0 && !(pon && poff); --k) {
        pon = find_run("projectile", "on", "events", dens[k]);
        poff = find_run("projectile", "off", "events", dens[k]);
    }
    if (pon && poff && rec_get(pon, "op_add") && rec_get(poff, "op_add")) {
        static const char *kinds[] = {"add", "sub", "mul", "div", "cmp", "sqrt"};
        static const double wt[] = {1.0, 1.0, 1.5, 4.0, 1.0, 6.0};
        double bs = rec_getd(pon, "body_steps"), c = 0.0;
        p("Cost (`carom profile`): on `projectile` (one body, no contacts, %.0f body-steps, "
          "events) the compensated sums add, per body-step,",
          bs);
        for (k = 0; k < 6; ++k) {
            char key[16];
            double d;
            snprintf(key, sizeof key, "op_%s", kinds[k]);
            d = (rec_getd(pon, key) - rec_getd(poff, key)) / bs;
            c += wt[k] * d;
            if (d != 0.0)
                p(" %+.2f %s", d, kinds[k]);
        }
        fd.kahan_ops = c;
        fd.kahan_share = c / (rec_getd(poff, "cost") / bs);
        p(" (weighted %+.2f, seed weights; 3 operations per component of x and v at each of "
          "their updates), %.1f %% of that scene's %s per body-step.",
          c, 100.0 * fd.kahan_share, NUM(rec_getd(poff, "cost") / bs));
        {
            const rec *gon = find_run("gas", "on", "events", 60);
            const rec *goff = find_run("gas", "off", "events", 60);
            if (gon && goff) {
                double gbs = rec_getd(gon, "body_steps");
                fd.gas_kahan_ops = (rec_getd(gon, "cost") - rec_getd(goff, "cost")) / gbs;
                fd.gas_kahan_share =
                    (rec_getd(gon, "cost") - rec_getd(goff, "cost")) / rec_getd(goff, "cost");
                p(" In the elastic gas (events, dt 1/60, %s impacts: every impact "
                  "synchronises two bodies, one more update each) it is %s weighted operations "
                  "per body-step, %.1f %% of the total.",
                  NUM(rec_getd(gon, "imp")), NUM(fd.gas_kahan_ops), 100.0 * fd.gas_kahan_share);
            }
        }
        p("\n\n");
    }
}

/* 1 if two builds gave the same spinbox results at every dt. */
static int same_toi(const char *a, const char *b)
{
    int k;
    for (k = 0; k < ndens; ++k) {
        const rec *ra = find_run("spinbox", a, "events", dens[k]);
        const rec *rb = find_run("spinbox", b, "events", dens[k]);
        if (!ra || !rb)
            continue;
        if (rec_getd(ra, "err") != rec_getd(rb, "err") ||
            rec_getd(ra, "c_toi") != rec_getd(rb, "c_toi"))
            return 0;
    }
    return 1;
}

static void section_toi(void)
{
    int k, j;
    static const int tden[] = {15, 60, 240, 960, 3840};
    const rec *def60 = find_run("spinbox", "on", "events", 60);
    double base_toi;
    if (ntol == 0 || !def60)
        return;
    fd.have_toi = 1;
    base_toi = rec_getd(def60, "c_toi") / rec_getd(def60, "imp");
    p("## The conservative-advancement tolerance\n\n");
    p("A rotating polygon's time of impact is found by conservative advancement (docs/"
      "events.md): it stops once the separation is below `CAROM_TOI_TOLERANCE` × linear "
      "slop. The impact is then taken up to that distance before the bodies really touch, "
      "with the pose of that instant, so the impulse acts at a slightly wrong lever arm. "
      "On `spinbox` (linear slop %s m; method events; angular momentum error = "
      "|ω − ω_exact| / |ω₀| at the end, after one impact on each wall):\n\n",
      NUM(rec_getd(def60, "slop")));
    p("| tolerance (× slop) | stops within (m) |");
    for (j = 0; j < 5; ++j)
        p(" ang. momentum, 1/%d |", tden[j]);
    p(" impact times (largest) | impact-timing ops per impact, 1/60 | more than at 0.1 | "
      "total ops per simulated s, 1/60 |\n|---|---|");
    for (j = 0; j < 5; ++j)
        p("---|");
    p("---|---|---|---|\n");
    fd.toi_default_l = rec_getd(def60, "L_err");
    fd.toi_best_l = fd.toi_default_l;
    fd.toi_best_tol = rec_getd(def60, "toi_tol");
    fd.toi_floor_tol = NAN;
    for (k = -1; k < ntol; ++k) {
        const char *build = k < 0 ? "on" : tol_builds[k];
        const rec *r60 = find_run("spinbox", build, "events", 60);
        double tol, tmax = 0.0, ci;
        int failed;
        if (!r60)
            continue;
        tol = rec_getd(r60, "toi_tol");
        tmax = worst_over_dens("spinbox", build, "events", "t_err", &failed);
        ci = rec_getd(r60, "c_toi") / rec_getd(r60, "imp");
        p("| %s | %s |", NUM(tol), NUM(tol * rec_getd(r60, "slop")));
        for (j = 0; j < 5; ++j)
            p(" %s |", fail_or(find_run("spinbox", build, "events", tden[j]), "L_err"));
        p(" %s | %s | %+.0f %% | %s |\n", NUM(tmax), NUM(ci), 100.0 * (ci / base_toi - 1.0),
          NUM(cost_per_s(r60)));
        if (k >= 0 && rec_getd(r60, "L_err") < fd.toi_best_l) {
            fd.toi_best_l = rec_getd(r60, "L_err");
            fd.toi_best_tol = tol;
            fd.toi_extra_ops = ci - base_toi;
        }
        if (k >= 1 && isnan(fd.toi_floor_tol) && same_toi(tol_builds[k - 1], build))
            fd.toi_floor_tol = rec_getd(find_run("spinbox", tol_builds[k - 1], "events", 60),
                                        "toi_tol");
    }
    p("\n");
    p("(The tolerance builds link the counting library, so only their operation counts "
      "are reported, not their times.) The error falls with the tolerance: the impact is "
      "taken within tolerance × slop of the true contact, and the lever arm and spin it "
      "acts with are off in proportion. ");
    if (!isnan(fd.toi_floor_tol))
        p("At %s × slop (%s m) and below the results are identical: that separation is "
          "below the float spacing of the positions (1.2e-7 m at 1.5 m from the origin), so "
          "conservative advancement ends on its other stops (its time no longer advances, "
          "or `CAROM_TOI_MAX_ITERATIONS`) and the tolerance no longer binds; that is as "
          "small as it can usefully be made. ",
          NUM(fd.toi_floor_tol), NUM(fd.toi_floor_tol * rec_getd(def60, "slop")));
    p("The search costs little more: at dt = 1/60 the impact-timing operations per impact "
      "grow by %s (%+.0f %%) from the default to %s × slop. What is left of the error at "
      "small tolerances grows as dt shrinks: it is the rounding of the rotation (previous "
      "section), not the impact.\n\n",
      NUM(fd.toi_extra_ops), 100.0 * fd.toi_extra_ops / base_toi, NUM(fd.toi_best_tol));
}

static void section_findings(void)
{
    p("## Findings\n\n");
    p("- **Impact times as dt shrinks** (bounce, 8 impacts): largest relative error over "
      "dt = 1/%d … 1/%d is %s (events) and %s (first-impact) with compensated sums, %s and "
      "%s without. Target 2e-6: **%s**.\n",
      dens[0], dens[ndens - 1], NUM(fd.t_err_on[0]), NUM(fd.t_err_on[1]), NUM(fd.t_err_off[0]),
      NUM(fd.t_err_off[1]), fd.target_met ? "met" : "missed");
    if (fd.kahan_ops > 0.0)
        p("- **Cost of the compensated sums**: %+.1f weighted operations per body-step "
          "(%.1f %%) on a free body, %s (%.1f %%) in the elastic gas.\n",
          fd.kahan_ops, 100.0 * fd.kahan_share, NUM(fd.gas_kahan_ops),
          100.0 * fd.gas_kahan_share);
    p("- **Rotation is not compensated**: on the projectile the angle error grows from %s "
      "rad (dt 1/%d) to %s rad (1/%d), the angular velocity's from %s to %s.\n",
      NUM(fd.ang_first), dens[0], NUM(fd.ang_last), dens[ndens - 1], NUM(fd.w_first),
      NUM(fd.w_last));
    if (fd.have_bound)
        p("- **Stepping past an impact**: the measured errors of discrete and first-impact "
          "agree with the derivation within %.1f %% and %.2f %% (asked: 10 %%).\n",
          100.0 * fd.bound_discrete, 100.0 * fd.bound_first);
    if (fd.have_toi)
        p("- **TOI tolerance**: spinning box angular-momentum error (dt 1/60) %s at the "
          "default 0.1 × slop, %s at %s × slop, for %s more impact-timing operations per "
          "impact.\n",
          NUM(fd.toi_default_l), NUM(fd.toi_best_l), NUM(fd.toi_best_tol),
          NUM(fd.toi_extra_ops));
    p("\n");
}

int report_main(int argc, char **argv)
{
    const char *outpath = NULL, *figdir = NULL;
    int i, s;
    for (i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            outpath = argv[++i];
        else if (strcmp(argv[i], "--figures") == 0 && i + 1 < argc)
            figdir = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "carom-accuracy: report: unknown option %s\n", argv[i]);
            return 2;
        } else if (load(argv[i]) != 0)
            return 2;
    }
    if (!outpath || !figdir) {
        fprintf(stderr, "carom-accuracy: report: --out FILE and --figures DIR are needed\n");
        return 2;
    }
    collect_dens();
    collect_tols();
    if (ndens < 2 || !find_meta("on")) {
        fprintf(stderr, "carom-accuracy: report: no sweep records of build 'on' given\n");
        return 2;
    }
    {
        const char *base = getenv("TMPDIR");
        snprintf(tmpd, sizeof tmpd, "%s/carom-report.XXXXXX", base && *base ? base : "/tmp");
        if (!mkdtemp(tmpd)) {
            fprintf(stderr, "carom-accuracy: report: cannot make a temporary directory\n");
            return 2;
        }
        atexit(tmpd_clean);
    }
    for (s = 0; s < SCENE_COUNT; ++s) {
        progress("report: figure %s", scenes[s].name);
        if (plot_scene(&scenes[s], figdir) != 0)
            return 2;
    }
    if (plot_compensated(figdir) != 0)
        return 2;
    progress_done();
    {
        char *body = NULL;
        size_t body_len = 0;
        FILE *doc = fopen(outpath, "w");
        if (!doc) {
            fprintf(stderr, "carom-accuracy: report: cannot write %s: %s\n", outpath,
                    strerror(errno));
            return 2;
        }
        /* the sections first, into memory: the findings at the top need
         * their numbers */
        out = open_memstream(&body, &body_len);
        if (!out) {
            fprintf(stderr, "carom-accuracy: out of memory\n");
            return 2;
        }
        section_method();
        section_scenes();
        section_orders();
        section_cheapest();
        p("## Per-scene results\n\n");
        p("Each figure: error against wall-clock time (left) and operations (right) per "
          "simulated second, log-log, one curve per method; each point one dt (the smallest "
          "dt is the most expensive point). Errors below 1e-10 (or 0) are drawn at 1e-10. "
          "\"failed\": the run stopped with an error; \"—\": not measured. \"off\": "
          "compensated sums off.\n\n");
        for (s = 0; s < SCENE_COUNT; ++s)
            scene_tables(&scenes[s]);
        section_bound();
        section_compensated();
        section_toi();
        fclose(out);
        out = doc;
        p("# Accuracy: error against run time\n\n");
        section_machine();
        p("Contents: [findings](#findings) · [what is measured](#what-is-measured) · "
          "[scenes](#the-scenes-and-their-exact-answers) · [orders](#convergence-orders) · "
          "[cheapest](#which-method-reaches-an-error-cheapest) · [per scene](#per-scene-"
          "results) · [stepping past an impact](#the-error-of-stepping-past-an-impact) · "
          "[compensated sums](#accuracy-as-dt-shrinks-compensated-summation) · [TOI "
          "tolerance](#the-conservative-advancement-tolerance)\n\n");
        section_findings();
        fwrite(body, 1, body_len, out);
        free(body);
    }
    if (fclose(out) != 0) {
        fprintf(stderr, "carom-accuracy: report: error writing %s\n", outpath);
        return 2;
    }
    return 0;
}
