/*
 * calibrate.c -- fit `carom profile --calibration` to instructions counted
 * on the emulated Cortex-M4F (tools/embedded/calibrate.sh gathers the
 * data; tools/embedded/README.md explains the model).
 *
 *   calibrate DATA [-o FILE.cal]
 *
 * DATA has one line per suite run:
 *   NAME METHOD PLAIN B0 .. B7 META OPS0 .. OPS5 JSON
 * PLAIN: instructions the run's steps executed in the plain M4F firmware;
 * B0..B5: instructions of the phase firmware (the same run, profiling
 * library) inside each profiler phase, B6 inside carom_world_step outside
 * any phase, B7 outside the step, META the measurement code; OPS0..5 the
 * float operations the phase firmware counted per phase; JSON: `carom
 * profile --json` of the same scene, method and steps (on this host).
 *
 * The phase firmware runs the counters, which add instructions. Per run
 * they add c = (B0 + .. + B7 - PLAIN) / (OPS0 + .. + OPS5) per operation,
 * so phase p of the plain firmware is estimated as Bp - c OPSp.
 *
 * Model, per row r (the six phases, and "step": B6 + B7):
 *   instructions_r = per_op ops_r + per_step steps + per_body_step
 *                    body_steps + per_awake_body_step awake_body_steps +
 *                    per_contact_step contact_steps
 * (ops_r: the phase's float operations; for "step" every operation), and
 * a phase that counted no operation did not run: 0. Each row is fitted
 * separately by non-negative least squares on the relative error (every
 * run weighs 1 / PLAIN). Prints, per run, the instructions, the preset's
 * prediction (cortex-m4f cycles, unchanged) and the calibrated one, fitted
 * on every run and fitted without the run's scene (leave one scene out).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PHASES 6
#define ROWS (PHASES + 1)
#define FEATURES 5
#define MAX_RUNS 256

static const char *const row_names[ROWS] = {
    "integration", "broadphase", "narrowphase", "impact_timing",
    "impulse_resolution", "resting_contacts", "step"
};
static const char *const kinds[6] = {"add", "sub", "mul", "div", "cmp", "sqrt"};
/* The preset the table compares with (src/profile.c "cortex-m4f"). */
static const double m4f_weights[6] = {1, 1, 1, 14, 1, 14};
static const char *const feature_names[FEATURES] = {
    "per_op", "per_step", "per_body_step", "per_awake_body_step", "per_contact_step"
};

typedef struct run {
    char name[64], method[32];
    double plain, bucket[9], fw_ops[PHASES];
    double steps, body_steps, awake, contacts;
    double ops[PHASES][6];
    double target[ROWS];
} run;

static run runs[MAX_RUNS];
static int nruns;

static void die(const char *msg, const char *arg)
{
    fprintf(stderr, "calibrate: %s%s%s\n", msg, arg ? ": " : "", arg ? arg : "");
    exit(1);
}

/* The number after "KEY": in the JSON text s (after position `from`). */
static double json_num(const char *s, const char *key, const char *line)
{
    char pat[64];
    const char *p;
    char *end;
    double v;
    snprintf(pat, sizeof pat, "\"%s\":", key);
    p = strstr(s, pat);
    if (!p)
        die("a profile lacks a key", key[0] ? key : line);
    v = strtod(p + strlen(pat), &end);
    if (end == p + strlen(pat))
        die("a profile has a bad number for", key);
    return v;
}

static void read_data(const char *path)
{
    FILE *f = fopen(path, "r");
    static char line[1 << 16];
    if (!f)
        die("cannot read", path);
    while (fgets(line, sizeof line, f)) {
        run *r;
        int n, k, ph;
        char *json;
        if (line[0] == '#' || line[0] == '\n')
            continue;
        if (nruns == MAX_RUNS)
            die("too many runs in", path);
        r = &runs[nruns];
        memset(r, 0, sizeof *r);
        if (sscanf(line, "%63s %31s %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %n",
                   r->name, r->method, &r->plain, &r->bucket[0], &r->bucket[1],
                   &r->bucket[2], &r->bucket[3], &r->bucket[4], &r->bucket[5],
                   &r->bucket[6], &r->bucket[7], &r->bucket[8], &r->fw_ops[0],
                   &r->fw_ops[1], &r->fw_ops[2], &r->fw_ops[3], &r->fw_ops[4],
                   &r->fw_ops[5], &n) != 18)
            die("malformed line in", path);
        json = line + n;
        if (*json != '{')
            die("no profile JSON on a line of", path);
        r->steps = json_num(json, "steps", line);
        r->body_steps = json_num(json, "body_steps", line);
        r->awake = json_num(json, "awake_body_steps", line);
        r->contacts = json_num(json, "contact_steps", line);
        for (ph = 0; ph < PHASES; ++ph) {
            char pat[64];
            const char *p;
            double total = 0.0;
            snprintf(pat, sizeof pat, "\"%s\": {", row_names[ph]);
            p = strstr(json, pat);
            if (!p)
                die("a profile lacks the phase", row_names[ph]);
            for (k = 0; k < 6; ++k) {
                r->ops[ph][k] = json_num(p, kinds[k], line);
                total += r->ops[ph][k];
            }
            if (total != r->fw_ops[ph]) {
                fprintf(stderr, "calibrate: %s %s %s: the firmware counted %.0f operations, "
                                "carom profile %.0f (not the same run?)\n",
                        r->name, r->method, row_names[ph], r->fw_ops[ph], total);
                exit(1);
            }
        }
        if (!(r->plain > 0.0))
            die("a run with no instructions in", path);
        nruns++;
    }
    fclose(f);
    if (nruns == 0)
        die("no runs in", path);
}

static double phase_ops(const run *r, int ph)
{
    double t = 0.0;
    int k;
    for (k = 0; k < 6; ++k)
        t += r->ops[ph][k];
    return t;
}

/* Features of row `row` for run r; 0 everywhere if that phase did not run. */
static int features(const run *r, int row, double x[FEATURES])
{
    double ops = 0.0;
    int ph;
    if (row < PHASES) {
        ops = phase_ops(r, row);
        if (ops == 0.0) {
            memset(x, 0, FEATURES * sizeof x[0]);
            return 0;
        }
    } else {
        for (ph = 0; ph < PHASES; ++ph)
            ops += phase_ops(r, ph);
    }
    x[0] = ops;
    x[1] = r->steps;
    x[2] = r->body_steps;
    x[3] = r->awake;
    x[4] = r->contacts;
    return 1;
}

/* Solve the n x n system a x = b (Gaussian elimination, partial pivoting);
 * 0 if singular. */
static int solve(int n, double a[FEATURES][FEATURES], double b[FEATURES], double x[FEATURES])
{
    int i, j, k;
    for (i = 0; i < n; ++i) {
        int p = i;
        for (j = i + 1; j < n; ++j)
            if (fabs(a[j][i]) > fabs(a[p][i]))
                p = j;
        if (fabs(a[p][i]) < 1e-300)
            return 0;
        if (p != i) {
            double t;
            for (k = 0; k < n; ++k) {
                t = a[i][k];
                a[i][k] = a[p][k];
                a[p][k] = t;
            }
            t = b[i];
            b[i] = b[p];
            b[p] = t;
        }
        for (j = 0; j < n; ++j) {
            double f;
            if (j == i)
                continue;
            f = a[j][i] / a[i][i];
            for (k = i; k < n; ++k)
                a[j][k] -= f * a[i][k];
            b[j] -= f * b[i];
        }
    }
    for (i = 0; i < n; ++i)
        x[i] = b[i] / a[i][i];
    return 1;
}

/* Non-negative least squares over every subset of the features (2^5 - 1
 * of them): the feasible subset with the least residual. Runs whose scene
 * is `skip` are left out. Rows are weighted by 1 / plain. */
static void fit_row(int row, const char *skip, double coef[FEATURES])
{
    unsigned mask;
    double best = -1.0;
    memset(coef, 0, FEATURES * sizeof coef[0]);
    for (mask = 1; mask < (1u << FEATURES); ++mask) {
        int idx[FEATURES], n = 0, i, j, k, ok = 1;
        double a[FEATURES][FEATURES], b[FEATURES], x[FEATURES], res = 0.0;
        for (i = 0; i < FEATURES; ++i)
            if (mask & (1u << i))
                idx[n++] = i;
        memset(a, 0, sizeof a);
        memset(b, 0, sizeof b);
        for (k = 0; k < nruns; ++k) {
            double f[FEATURES], w = 1.0 / runs[k].plain;
            if ((skip && strcmp(runs[k].name, skip) == 0) || !features(&runs[k], row, f))
                continue;
            for (i = 0; i < n; ++i) {
                for (j = 0; j < n; ++j)
                    a[i][j] += f[idx[i]] * w * f[idx[j]] * w;
                b[i] += f[idx[i]] * w * runs[k].target[row] * w;
            }
        }
        if (!solve(n, a, b, x))
            continue;
        for (i = 0; i < n; ++i)
            if (x[i] < 0.0)
                ok = 0;
        if (!ok)
            continue;
        for (k = 0; k < nruns; ++k) {
            double f[FEATURES], w = 1.0 / runs[k].plain, p = 0.0;
            if ((skip && strcmp(runs[k].name, skip) == 0) || !features(&runs[k], row, f))
                continue;
            for (i = 0; i < n; ++i)
                p += x[i] * f[idx[i]];
            res += (p - runs[k].target[row]) * w * (p - runs[k].target[row]) * w;
        }
        if (best < 0.0 || res < best) {
            best = res;
            memset(coef, 0, FEATURES * sizeof coef[0]);
            for (i = 0; i < n; ++i)
                coef[idx[i]] = x[i];
        }
    }
}

static double predict(const run *r, double coef[ROWS][FEATURES])
{
    double t = 0.0, f[FEATURES];
    int row, i;
    for (row = 0; row < ROWS; ++row)
        if (features(r, row, f))
            for (i = 0; i < FEATURES; ++i)
                t += coef[row][i] * f[i];
    return t;
}

int main(int argc, char **argv)
{
    const char *data = NULL, *out = NULL;
    double coef[ROWS][FEATURES], loso[MAX_RUNS], worst_fit = 0.0, worst_loso = 0.0,
        worst_preset = 0.0, sum_insn = 0.0, sum_preset = 0.0, sum_fit = 0.0;
    int i, k, row;
    FILE *f;

    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            printf("usage: calibrate DATA [-o FILE.cal]\n"
                   "Fit carom profile's calibration to counted instructions "
                   "(see the comment at the top of tools/embedded/calibrate.c).\n");
            return 0;
        } else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            out = argv[++i];
        } else if (argv[i][0] != '-' && !data) {
            data = argv[i];
        } else {
            fprintf(stderr, "calibrate: bad argument '%s' (try --help)\n", argv[i]);
            return 2;
        }
    }
    if (!data) {
        fprintf(stderr, "usage: calibrate DATA [-o FILE.cal]\n");
        return 2;
    }
    read_data(data);

    /* targets: each phase of the plain firmware, the counters taken out */
    for (k = 0; k < nruns; ++k) {
        run *r = &runs[k];
        double ops = 0.0, counted = 0.0, c;
        for (i = 0; i < PHASES; ++i)
            ops += r->fw_ops[i];
        for (i = 0; i < 8; ++i)
            counted += r->bucket[i];
        c = ops > 0.0 ? (counted - r->plain) / ops : 0.0;
        for (i = 0; i < PHASES; ++i)
            r->target[i] = r->bucket[i] - c * r->fw_ops[i];
        r->target[PHASES] = r->bucket[6] + r->bucket[7];
    }
    for (row = 0; row < ROWS; ++row)
        fit_row(row, NULL, coef[row]);
    for (k = 0; k < nruns; ++k) {
        double c2[ROWS][FEATURES];
        for (row = 0; row < ROWS; ++row)
            fit_row(row, runs[k].name, c2[row]);
        loso[k] = predict(&runs[k], c2);
    }

    if (out) {
        f = fopen(out, "w");
        if (!f)
            die("cannot write", out);
        fprintf(f, "# Calibration of `carom profile --calibration FILE`: instructions executed\n"
                   "# by carom_world_step on a Cortex-M4F (the plain M4F firmware of\n"
                   "# tools/embedded under qemu-system-arm -machine mps2-an386, counted by the\n"
                   "# insn_count plugin). Written by `make embedded-calibrate` from %d runs of\n"
                   "# the embedded suite; tools/embedded/README.md explains the model.\n"
                   "# Per row: instructions = per_op x the phase's float operations (step:\n"
                   "# all of them) + per_step x steps + per_body_step x body-steps +\n"
                   "# per_awake_body_step x awake body-steps + per_contact_step x\n"
                   "# contact-steps; a phase that counted no operation adds nothing.\n"
                   "carom-calibration 1\n"
                   "name cortex-m4f-measured\n"
                   "unit instructions\n"
                   "#%-19s", nruns, "row");
        for (i = 0; i < FEATURES; ++i)
            fprintf(f, " %19s", feature_names[i]);
        fputc('\n', f);
        for (row = 0; row < ROWS; ++row) {
            fprintf(f, "%-20s", row_names[row]);
            for (i = 0; i < FEATURES; ++i)
                fprintf(f, " %19.6g", coef[row][i]);
            fputc('\n', f);
        }
        if (fclose(f) != 0)
            die("error writing", out);
    }

    printf("%-8s %-8s %12s %12s %7s %12s %7s %7s\n", "scene", "method", "instructions",
           "m4f preset", "error", "calibrated", "error", "LOSO");
    for (k = 0; k < nruns; ++k) {
        const run *r = &runs[k];
        double preset = 0.0, p = predict(r, coef), e1, e2, e3;
        int ph;
        for (ph = 0; ph < PHASES; ++ph)
            for (i = 0; i < 6; ++i)
                preset += r->ops[ph][i] * m4f_weights[i];
        e1 = preset / r->plain - 1.0;
        e2 = p / r->plain - 1.0;
        e3 = loso[k] / r->plain - 1.0;
        if (fabs(e1) > worst_preset)
            worst_preset = fabs(e1);
        if (fabs(e2) > worst_fit)
            worst_fit = fabs(e2);
        if (fabs(e3) > worst_loso)
            worst_loso = fabs(e3);
        sum_insn += r->plain;
        sum_preset += preset;
        sum_fit += p;
        printf("%-8s %-8s %12.0f %12.0f %+6.0f%% %12.0f %+6.1f%% %+6.1f%%\n", r->name,
               r->method, r->plain, preset, 100.0 * e1, p, 100.0 * e2, 100.0 * e3);
    }
    printf("%-17s %12.0f %12.0f %+6.0f%% %12.0f %+6.1f%%\n", "all", sum_insn, sum_preset,
           100.0 * (sum_preset / sum_insn - 1.0), sum_fit, 100.0 * (sum_fit / sum_insn - 1.0));
    printf("largest error: preset %.0f %%, calibrated %.1f %% (fitted on every run), "
           "%.1f %% (leave one scene out)\n", 100.0 * worst_preset, 100.0 * worst_fit,
           100.0 * worst_loso);
    return 0;
}
