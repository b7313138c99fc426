/*
 * bench.c -- build/carom-bench: carom's methods, Box2D 2.4.1 and Box2D v3
 * timed side by side on generated scenes (tools/bench/scenes.c), in one
 * process, runs alternated (issue 12). `make bench` runs it and writes
 * docs/benchmarks.md from its records (tools/bench/report.py).
 *
 * Every measurement makes a fresh world from the same scene, takes
 * --warmup untimed steps, then times each step with CLOCK_MONOTONIC around
 * the engine's step call only. A run's figure is its mean time per step;
 * a measurement is the median over --reps runs, and in each repetition
 * the engines take turns in a rotated order.
 *
 * Output: one record per line on stdout, "KIND key=value ...", with a
 * free-text msg= last where there is one (tools/bench/report.py reads
 * them). Progress goes to stderr.
 *
 * Exit status: 0 ok (failures of an engine are records, not errors),
 * 1 a run could not be made at all, 2 bad usage.
 */
#include "bench.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "carom.h"

#define MAX_LIST 16

static const char usage[] =
    "usage: carom-bench [options]                   the timing suite\n"
    "       carom-bench --run KIND N ENGINE [options] one run (for callgrind)\n"
    "       carom-bench --write-scene KIND N FILE   the scene as a carom scene file\n"
    "       carom-bench --help\n"
    "\n"
    "KIND: gas or pile (tools/bench/scenes.c). ENGINE: events, discrete,\n"
    "first-impact (carom's methods), box2d (2.4.1), box2d-v3 (when built).\n"
    "\n"
    "suite options:\n"
    "  --scenes LIST      comma-separated kinds (default gas,pile)\n"
    "  --sizes LIST       body counts (default 100,1000,10000,100000)\n"
    "  --engines LIST     default: every engine built (first-impact on the gas only)\n"
    "  --reps R           runs per measurement (default 9; 3 from 10^4 bodies)\n"
    "  --steps S          timed steps per run (default: gas 120, pile 60;\n"
    "                     10 from 10^5 bodies)\n"
    "  --warmup W         untimed steps first (default 1)\n"
    "  --budget SEC       a run stops timing after SEC s (default 60) and an\n"
    "                     engine takes no more repetitions of that size\n"
    "  --quick            sizes 100,1000 and 3 repetitions unless given\n"
    "  --settle LIST      also: piles of these sizes with sleeping on, moving\n"
    "                     (first second) against settled (after every body\n"
    "                     sleeps); '-' for none (default 1000,10000)\n"
    "  --settle-max S     give up settling after S steps (default 3600) or\n"
    "  --settle-budget SEC  after SEC s of one engine's settling run (default 120)\n"
    "  --ops              operation counts per body-step (needs the profiling\n"
    "                     build, carom-bench-ops); times nothing\n"
    "  --sleep            sleeping on in the timing suite (default off, as for\n"
    "                     the Box2D engines)\n"
    "\n"
    "--run options: --steps S (default 30), --warmup W (default 0), --sleep,\n"
    "--count (carom-bench-ops: count operations while timing, the profiler's\n"
    "cost).\n"
    "The timed steps run inside bench_timed_steps(), so\n"
    "  valgrind --tool=callgrind --toggle-collect=bench_timed_steps ...\n"
    "counts them alone.\n"
    "\n"
    "records (stdout): machine, time, fail, memory, layout, settle, ops.\n"
    "exit status: 0 ok, 1 a world could not be made, 2 bad usage\n";

/* ---- helpers ------------------------------------------------------------- */

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* CPU time of this thread: on a shared machine, what the step cost
 * without the time other processes held the CPU (a system call here, too
 * slow to take around every step: it is taken around a run's timed steps). */
static double cpu_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    if (n <= 0)
        return -1.0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int bad_usage(const char *what, const char *arg)
{
    fprintf(stderr, "carom-bench: %s '%s' (try --help)\n", what, arg);
    return 2;
}

static int parse_int(const char *v, long lo, long hi, long *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || errno || x < lo || x > hi)
        return -1;
    *out = x;
    return 0;
}

/* "a,b,c" -> up to MAX_LIST words (pointers into a copy kept in buf) */
static int split_list(const char *v, char *buf, size_t buflen, char **items)
{
    int n = 0;
    char *p;
    if (strlen(v) + 1 > buflen)
        return -1;
    strcpy(buf, v);
    for (p = strtok(buf, ","); p; p = strtok(NULL, ",")) {
        if (n == MAX_LIST)
            return -1;
        items[n++] = p;
    }
    return n;
}

static const bench_engine *engine_by_name(const char *name)
{
    static const bench_engine *all[] = { &bench_carom_events, &bench_carom_discrete,
                                         &bench_carom_first_impact, &bench_box2d,
                                         &bench_box2d_v3 };
    size_t i;
    for (i = 0; i < sizeof all / sizeof all[0]; ++i)
        if (strcmp(all[i]->name, name) == 0)
            return all[i];
    return NULL;
}

static int engine_built(const bench_engine *e)
{
    if (e == &bench_box2d)
        return bench_box2d_available();
    if (e == &bench_box2d_v3)
        return bench_box2d_v3_available();
    return 1;
}

/* ---- one run ------------------------------------------------------------- */

typedef struct run_result {
    int ok;            /* 1: every step taken */
    long steps;        /* timed steps taken */
    double ns_mean;    /* mean wall time per timed step */
    double cpu_mean;   /* mean thread CPU time per timed step */
    double ns_median;  /* median of the timed steps */
    double wall_s;     /* the whole run, s */
    bench_info before, after; /* at the start and end of the timed steps */
    int status;        /* carom status of a failed step, else 0 */
    long fail_step;    /* which step failed (1-based, warm-up included) */
    char err[512];
} run_result;

/* The timed steps, apart so that callgrind can count them alone
 * (--toggle-collect=bench_timed_steps). Per-step times go to ns[]. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
long bench_timed_steps(const bench_engine *e, void *world, long steps, double *ns,
                       double budget_ns, char *err, size_t errlen);
long bench_timed_steps(const bench_engine *e, void *world, long steps, double *ns,
                       double budget_ns, char *err, size_t errlen)
{
    double spent = 0.0;
    long k;
    for (k = 0; k < steps; ++k) {
        const double t0 = now_ns();
        const int rc = e->step(world, err, errlen);
        const double dt = now_ns() - t0;
        if (rc != 0)
            return -(k + 1);
        ns[k] = dt;
        spent += dt;
        if (spent > budget_ns && k + 1 < steps)
            return k + 1;
    }
    return steps;
}

/* A carom_profile to attach after the warm-up (--run --count), or NULL. */
static void *g_count_profile;

static void run_once(const bench_engine *e, const bench_scene *s, const bench_config *c,
                     long warmup, long steps, double budget_s, run_result *r)
{
    double *ns = (double *)malloc((size_t)(steps > 0 ? steps : 1) * sizeof *ns);
    const double t_start = now_ns();
    void *w;
    long k, done;
    memset(r, 0, sizeof *r);
    if (!ns) {
        snprintf(r->err, sizeof r->err, "out of memory");
        return;
    }
    w = e->make(s, c, e->method, r->err, sizeof r->err);
    if (!w) {
        free(ns);
        return;
    }
    for (k = 0; k < warmup; ++k) {
        if (e->step(w, r->err, sizeof r->err) != 0) {
            r->status = e->method >= 0 ? bench_carom_last_status(w) : -1;
            r->fail_step = k + 1;
            e->info(w, &r->after);
            e->destroy(w);
            free(ns);
            return;
        }
    }
    if (g_count_profile && bench_carom_attach_profile(w, g_count_profile) != 0) {
        snprintf(r->err, sizeof r->err, "--count: this carom-bench counts nothing (use "
                 "carom-bench-ops, linked with the profiling library)");
        e->destroy(w);
        free(ns);
        return;
    }
    e->info(w, &r->before);
    r->cpu_mean = cpu_ns();
    done = bench_timed_steps(e, w, steps, ns, budget_s * 1e9, r->err, sizeof r->err);
    r->cpu_mean = done > 0 ? (cpu_ns() - r->cpu_mean) / (double)done : 0.0;
    if (done < 0) {
        r->status = e->method >= 0 ? bench_carom_last_status(w) : -1;
        r->fail_step = warmup - done;
        e->info(w, &r->after);
        e->destroy(w);
        free(ns);
        return;
    }
    e->info(w, &r->after);
    e->destroy(w);
    r->ok = 1;
    r->steps = done;
    {
        double sum = 0.0;
        for (k = 0; k < done; ++k)
            sum += ns[k];
        r->ns_mean = done > 0 ? sum / (double)done : 0.0;
    }
    r->ns_median = median(ns, (int)done);
    r->wall_s = (now_ns() - t_start) * 1e-9;
    free(ns);
}

/* ---- the suite ----------------------------------------------------------- */

typedef struct suite {
    char *kinds[MAX_LIST];
    int kind_count;
    long sizes[MAX_LIST];
    int size_count;
    const bench_engine *engines[MAX_LIST];
    int engine_count;
    int engines_given;
    long reps, steps, warmup, budget;
    long settle_sizes[MAX_LIST];
    int settle_count;
    long settle_max, settle_budget;
    int ops;
    int sleep;
} suite;

static long default_steps(bench_kind k, long n)
{
    if (n >= 100000)
        return 10;
    return k == BENCH_GAS ? 120 : 60;
}

static void print_machine(void)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[256], cpu[200] = "unknown";
    int cpus = 0;
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (strncmp(line, "model name", 10) == 0) {
                char *p = strchr(line, ':');
                if (p && cpus == 0) {
                    p += 1 + (p[1] == ' ');
                    p[strcspn(p, "\n")] = '\0';
                    snprintf(cpu, sizeof cpu, "%s", p);
                }
                ++cpus;
            }
        }
        fclose(f);
    }
    printf("machine cpus=%d carom=%s box2d=%s box2d_v3=%s msg=%s\n", cpus, carom_version(),
           bench_box2d_available() ? "2.4.1" : "not-built", bench_box2d_v3_version(), cpu);
}

static void print_info_fields(const bench_info *a, const bench_info *b, long steps)
{
    printf(" awake=%d contacts=%d", b->awake, b->contacts);
    if (b->impacts >= 0 && steps > 0)
        printf(" impacts_per_step=%.2f", (double)(b->impacts - a->impacts) / (double)steps);
    if (b->heap_bytes >= 0)
        printf(" heap_bytes=%ld", b->heap_bytes);
    if (b->buffer_bytes >= 0)
        printf(" buffer_bytes=%ld max_pairs_used=%d max_contacts_used=%d "
               "max_impacts_used=%d budget_steps=%ld cap_pairs=%d cap_contacts=%d",
               b->buffer_bytes, b->max_pairs_used, b->max_contacts_used,
               b->max_impacts_used, b->budget_steps, b->cap_pairs, b->cap_contacts);
}

static void print_fail(const char *what, const bench_scene *s, const bench_engine *e,
                       const bench_config *c, const run_result *r)
{
    printf("fail what=%s scene=%s n=%d engine=%s status=%d step=%ld caps=%s", what,
           bench_kind_name(s->kind), s->n, e->name, r->status, r->fail_step,
           c->max_pairs || c->max_contacts ? "raised" : "default");
    if (e->method >= 0)
        printf(" cap_pairs=%d cap_contacts=%d max_pairs_used=%d max_contacts_used=%d",
               r->after.cap_pairs, r->after.cap_contacts, r->after.max_pairs_used,
               r->after.max_contacts_used);
    printf(" msg=%s\n", r->err);
    fflush(stdout);
}

/* Time one scene size with every engine; alternated repetitions. */
static void time_size(const suite *su, const bench_scene *s)
{
    const long steps = su->steps > 0 ? su->steps : default_steps(s->kind, s->n);
    const long reps = su->reps > 0 ? su->reps : (s->n >= 10000 ? 3 : 9);
    bench_config cfg[MAX_LIST];
    double means[MAX_LIST][64], walls[MAX_LIST][64];
    int got[MAX_LIST], stopped[MAX_LIST], dead[MAX_LIST];
    run_result last[MAX_LIST];
    int i, rep;
    memset(cfg, 0, sizeof cfg);
    memset(got, 0, sizeof got);
    memset(stopped, 0, sizeof stopped);
    memset(dead, 0, sizeof dead);
    for (i = 0; i < su->engine_count; ++i) {
        cfg[i].sleep = su->sleep;
        cfg[i].substeps = 4;
    }
    for (rep = 0; rep < reps && rep < 64; ++rep) {
        int j;
        for (j = 0; j < su->engine_count; ++j) {
            /* rotate the order every repetition */
            const int e_i = (j + rep) % su->engine_count;
            const bench_engine *e = su->engines[e_i];
            run_result r;
            if (dead[e_i] || stopped[e_i])
                continue;
            if (s->kind == BENCH_PILE && e == &bench_carom_first_impact && !su->engines_given)
                continue;
            fprintf(stderr, "carom-bench: %s %d %s rep %d/%ld ...", bench_kind_name(s->kind),
                    s->n, e->name, rep + 1, reps);
            fflush(stderr);
            run_once(e, s, &cfg[e_i], su->warmup, steps, (double)su->budget, &r);
            /* a capacity failure with default capacities: say so, then
             * double the capacity that ran out until the run goes through */
            while (!r.ok && e->method >= 0 && bench_carom_is_capacity_error(r.status)) {
                int tries = 0;
                print_fail("time", s, e, &cfg[e_i], &r);
                if (r.status == CAROM_ERR_PAIR_CAPACITY)
                    cfg[e_i].max_pairs = 2 * r.after.cap_pairs;
                else
                    cfg[e_i].max_contacts = 2 * r.after.cap_contacts;
                if (cfg[e_i].max_pairs == 0)
                    cfg[e_i].max_pairs = r.after.cap_pairs;
                if (cfg[e_i].max_contacts == 0)
                    cfg[e_i].max_contacts = r.after.cap_contacts;
                fprintf(stderr, " %s; again with max_pairs %d, max_contacts %d ...",
                        carom_status_string((carom_status)r.status), cfg[e_i].max_pairs,
                        cfg[e_i].max_contacts);
                run_once(e, s, &cfg[e_i], su->warmup, steps, (double)su->budget, &r);
                if (++tries > 8)
                    break;
            }
            if (!r.ok) {
                fprintf(stderr, " failed: %s\n", r.err);
                print_fail("time", s, e, &cfg[e_i], &r);
                dead[e_i] = 1;
                continue;
            }
            fprintf(stderr, " %.1f us/step CPU, %.1f us/step wall (%.1f s)\n",
                    r.cpu_mean * 1e-3, r.ns_mean * 1e-3, r.wall_s);
            walls[e_i][got[e_i]] = r.ns_mean;
            means[e_i][got[e_i]++] = r.cpu_mean;
            last[e_i] = r;
            if (r.steps < steps || r.wall_s > (double)su->budget)
                stopped[e_i] = 1;
        }
    }
    for (i = 0; i < su->engine_count; ++i) {
        const bench_engine *e = su->engines[i];
        double lo, hi, med, wall;
        if (got[i] == 0)
            continue;
        qsort(means[i], (size_t)got[i], sizeof means[i][0], cmp_double);
        lo = means[i][0];
        hi = means[i][got[i] - 1];
        med = median(means[i], got[i]);
        wall = median(walls[i], got[i]);
        printf("time scene=%s n=%d bodies=%d engine=%s steps=%ld warmup=%ld reps=%d "
               "ns_step=%.1f ns_min=%.1f ns_max=%.1f wall_step=%.1f caps=%s sleep=%d",
               bench_kind_name(s->kind), s->n, s->body_count, e->name, last[i].steps,
               su->warmup, got[i], med, lo, hi, wall,
               cfg[i].max_pairs || cfg[i].max_contacts ? "raised" : "default", su->sleep);
        print_info_fields(&last[i].before, &last[i].after, last[i].steps);
        if (e->method >= 0) {
            const bench_info *a = &last[i].after;
            const int ev = a->max_impacts_used > 0 ? a->max_impacts_used : 1;
            printf(" bytes_default=%ld bytes_needed=%ld",
                   bench_carom_buffer_size(s, 0, 0, 0, 0),
                   bench_carom_buffer_size(s, a->max_pairs_used > 0 ? a->max_pairs_used : 1,
                                           a->max_contacts_used > 0 ? a->max_contacts_used : 1,
                                           ev, ev));
        }
        putchar('\n');
        fflush(stdout);
    }
}

/* carom's memory layout from the public API alone: bytes per body slot,
 * per candidate pair, per contact and per recorded event, as differences
 * of carom_world_buffer_size. */
static void print_layout(const bench_scene *s)
{
    const int p = 100000, c = 100000, e = 100000, im = 100000;
    const long base = bench_carom_buffer_size(s, p, c, im, e);
    const long dp = bench_carom_buffer_size(s, 2 * p, c, im, e) - base;
    const long dc = bench_carom_buffer_size(s, p, 2 * c, im, e) - base;
    const long de = bench_carom_buffer_size(s, p, c, im, 2 * e) - base;
    const long di = bench_carom_buffer_size(s, p, c, 2 * im, e) - base;
    printf("layout bytes_per_pair=%.1f bytes_per_contact=%.1f bytes_per_event=%.1f "
           "bytes_per_impact=%.1f pairs_per_body=%d contacts_per_body=%d "
           "events_per_body=%d\n",
           (double)dp / p, (double)dc / c, (double)de / e, (double)di / im,
           CAROM_DEFAULT_PAIRS_PER_BODY, CAROM_DEFAULT_CONTACTS_PER_BODY,
           CAROM_DEFAULT_EVENTS_PER_BODY);
}

/* A pile with sleeping on: the first second (moving), then steps until
 * every body sleeps (or settle_max), then the same number of steps again
 * (settled). Times are medians of the steps of one run. */
static void settle_size(const suite *su, const bench_scene *s)
{
    int i;
    for (i = 0; i < su->engine_count; ++i) {
        const bench_engine *e = su->engines[i];
        bench_config c;
        bench_info info;
        char err[512];
        double ns[60], moving, settled, t0;
        long k, done, settle_steps = 0;
        void *w;
        if (e == &bench_carom_first_impact)
            continue;
        memset(&c, 0, sizeof c);
        c.sleep = 1;
        c.substeps = 4;
        fprintf(stderr, "carom-bench: settle pile %d %s ...", s->n, e->name);
        fflush(stderr);
        t0 = now_ns();
        w = e->make(s, &c, e->method, err, sizeof err);
        if (!w) {
            fprintf(stderr, " %s\n", err);
            continue;
        }
        done = e->step(w, err, sizeof err) == 0 ? 1 : -1;
        moving = cpu_ns();
        if (done > 0)
            done = bench_timed_steps(e, w, 60, ns, 1e18, err, sizeof err);
        moving = (cpu_ns() - moving) / 60.0;
        if (done != 60) {
            fprintf(stderr, " failed: %s\n", err);
            printf("fail what=settle scene=pile n=%d engine=%s status=%d step=%ld msg=%s\n",
                   s->n, e->name, e->method >= 0 ? bench_carom_last_status(w) : -1,
                   done < 0 ? -done : 0L, err);
            e->destroy(w);
            continue;
        }
        settle_steps = 61;
        e->info(w, &info);
        while (info.awake > 0 && settle_steps < su->settle_max &&
               (now_ns() - t0) * 1e-9 < (double)su->settle_budget) {
            for (k = 0; k < 10; ++k)
                if (e->step(w, err, sizeof err) != 0)
                    break;
            if (k < 10)
                break;
            settle_steps += 10;
            e->info(w, &info);
        }
        if (info.awake > 0) {
            fprintf(stderr, " not asleep after %ld steps (%d awake)", settle_steps, info.awake);
        }
        settled = cpu_ns();
        done = bench_timed_steps(e, w, 60, ns, 1e18, err, sizeof err);
        settled = done == 60 ? (cpu_ns() - settled) / 60.0 : -1.0;
        e->info(w, &info);
        e->destroy(w);
        fprintf(stderr, " moving %.1f us, settled %.1f us (%ld steps)\n", moving * 1e-3,
                settled * 1e-3, settle_steps);
        printf("settle scene=pile n=%d engine=%s ns_moving=%.1f ns_settled=%.1f "
               "settle_steps=%ld awake_after=%d\n",
               s->n, e->name, moving, settled, settle_steps, info.awake);
        fflush(stdout);
    }
}

/* Operation counts per body-step of the carom methods (profiling build). */
static int ops_size(const suite *su, const bench_scene *s)
{
    const long steps = su->steps > 0 ? su->steps : default_steps(s->kind, s->n);
    int i;
    for (i = 0; i < su->engine_count; ++i) {
        const bench_engine *e = su->engines[i];
        carom_profile prof;
        bench_config c;
        run_result r;
        int ph, op;
        if (e->method < 0)
            continue;
        if (s->kind == BENCH_PILE && e == &bench_carom_first_impact && !su->engines_given)
            continue;
        memset(&c, 0, sizeof c);
        c.sleep = su->sleep;
        c.substeps = 4;
        carom_profile_reset(&prof);
        fprintf(stderr, "carom-bench: ops %s %d %s ...", bench_kind_name(s->kind), s->n,
                e->name);
        fflush(stderr);
        memset(&r, 0, sizeof r);
        {
            /* the same warm-up as the timing, then count the timed steps */
            void *w = e->make(s, &c, e->method, r.err, sizeof r.err);
            long k;
            int st = 0;
            if (!w) {
                fprintf(stderr, " failed: %s\n", r.err);
                continue;
            }
            for (k = 0; k < su->warmup + steps && st == 0; ++k) {
                if (k == su->warmup && bench_carom_attach_profile(w, &prof) != 0) {
                    e->destroy(w);
                    fprintf(stderr, " failed: this build counts nothing\n");
                    return -1;
                }
                st = e->step(w, r.err, sizeof r.err);
            }
            e->destroy(w);
            if (st != 0) {
                fprintf(stderr, " failed: %s\n", r.err);
                printf("fail what=ops scene=%s n=%d engine=%s msg=%s\n",
                       bench_kind_name(s->kind), s->n, e->name, r.err);
                continue;
            }
        }
        fprintf(stderr, " done\n");
        printf("ops scene=%s n=%d engine=%s steps=%lu body_steps=%lu impacts=%lu",
               bench_kind_name(s->kind), s->n, e->name, (unsigned long)prof.steps,
               (unsigned long)prof.body_steps, (unsigned long)prof.impacts);
        for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph) {
            uint64_t sum = 0;
            for (op = 0; op < CAROM_OP_COUNT; ++op)
                sum += prof.ops[ph][op];
            printf(" %s=%lu", carom_phase_name((carom_phase)ph), (unsigned long)sum);
        }
        for (op = 0; op < CAROM_OP_COUNT; ++op) {
            uint64_t sum = 0;
            for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph)
                sum += prof.ops[ph][op];
            printf(" op_%s=%lu", carom_op_name((carom_op)op), (unsigned long)sum);
        }
        putchar('\n');
        fflush(stdout);
    }
    return 0;
}

/* ---- main ---------------------------------------------------------------- */

static int cmd_write_scene(int argc, char **argv)
{
    bench_kind k;
    long n;
    bench_scene s;
    if (argc != 3)
        return bad_usage("--write-scene wants KIND N FILE, got", argc > 0 ? argv[0] : "");
    if (bench_kind_from_name(argv[0], &k) != 0)
        return bad_usage("unknown scene kind", argv[0]);
    if (parse_int(argv[1], 1, 1000000, &n) != 0)
        return bad_usage("N must be an integer in [1, 10^6], got", argv[1]);
    if (bench_scene_make(&s, k, (int)n) != 0) {
        fprintf(stderr, "carom-bench: out of memory\n");
        return 1;
    }
    if (bench_scene_write(&s, argv[2]) != 0) {
        fprintf(stderr, "carom-bench: cannot write '%s': %s\n", argv[2], strerror(errno));
        bench_scene_free(&s);
        return 1;
    }
    bench_scene_free(&s);
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    bench_kind k;
    long n, steps = 30, warmup = 0;
    const bench_engine *e;
    bench_scene s;
    bench_config c;
    run_result r;
    int i;
    memset(&c, 0, sizeof c);
    c.substeps = 4;
    if (argc < 3)
        return bad_usage("--run wants KIND N ENGINE, got", argc > 0 ? argv[0] : "");
    if (bench_kind_from_name(argv[0], &k) != 0)
        return bad_usage("unknown scene kind", argv[0]);
    if (parse_int(argv[1], 1, 1000000, &n) != 0)
        return bad_usage("N must be an integer in [1, 10^6], got", argv[1]);
    e = engine_by_name(argv[2]);
    if (!e)
        return bad_usage("unknown engine", argv[2]);
    if (!engine_built(e))
        return bad_usage("engine not built into this carom-bench:", argv[2]);
    for (i = 3; i < argc; ++i) {
        if (strcmp(argv[i], "--sleep") == 0) {
            c.sleep = 1;
        } else if (strcmp(argv[i], "--count") == 0) {
            static carom_profile prof;
            carom_profile_reset(&prof);
            g_count_profile = &prof;
        } else if (strcmp(argv[i], "--steps") == 0 || strcmp(argv[i], "--warmup") == 0) {
            if (i + 1 >= argc || parse_int(argv[i + 1], 0, 100000000, argv[i][2] == 's'
                                                                         ? &steps
                                                                         : &warmup) != 0)
                return bad_usage("want an integer after", argv[i]);
            ++i;
        } else {
            return bad_usage("unknown --run option", argv[i]);
        }
    }
    if (bench_scene_make(&s, k, (int)n) != 0) {
        fprintf(stderr, "carom-bench: out of memory\n");
        return 1;
    }
    if (g_count_profile && e->method < 0)
        return bad_usage("--count counts carom's operations, not those of", argv[2]);
    run_once(e, &s, &c, warmup, steps, 1e9, &r);
    if (!r.ok) {
        print_fail("run", &s, e, &c, &r);
        bench_scene_free(&s);
        return 1;
    }
    printf("time scene=%s n=%d bodies=%d engine=%s steps=%ld warmup=%ld reps=1 ns_step=%.1f "
           "wall_step=%.1f wall_median=%.1f sleep=%d",
           bench_kind_name(s.kind), s.n, s.body_count, e->name, r.steps, warmup, r.cpu_mean,
           r.ns_mean, r.ns_median, c.sleep);
    print_info_fields(&r.before, &r.after, r.steps);
    putchar('\n');
    bench_scene_free(&s);
    return 0;
}

int main(int argc, char **argv)
{
    suite su;
    char kbuf[256], sbuf[256], ebuf[256];
    char *items[MAX_LIST];
    int i, j, quick = 0, sizes_given = 0, reps_given = 0;

    if (argc > 1 && strcmp(argv[1], "--write-scene") == 0)
        return cmd_write_scene(argc - 2, argv + 2);
    if (argc > 1 && strcmp(argv[1], "--run") == 0)
        return cmd_run(argc - 2, argv + 2);

    memset(&su, 0, sizeof su);
    su.kinds[0] = "gas";
    su.kinds[1] = "pile";
    su.kind_count = 2;
    su.sizes[0] = 100;
    su.sizes[1] = 1000;
    su.sizes[2] = 10000;
    su.sizes[3] = 100000;
    su.size_count = 4;
    su.warmup = 1;
    su.budget = 60;
    su.settle_sizes[0] = 1000;
    su.settle_sizes[1] = 10000;
    su.settle_count = 2;
    su.settle_max = 3600;
    su.settle_budget = 120;

    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--quick") == 0) {
            quick = 1;
        } else if (strcmp(a, "--ops") == 0) {
            su.ops = 1;
        } else if (strcmp(a, "--sleep") == 0) {
            su.sleep = 1;
        } else if (!v) {
            return bad_usage("unknown option or missing value after", a);
        } else if (strcmp(a, "--scenes") == 0) {
            int n = split_list(v, kbuf, sizeof kbuf, su.kinds);
            bench_kind k;
            if (n <= 0)
                return bad_usage("bad list", v);
            for (j = 0; j < n; ++j)
                if (bench_kind_from_name(su.kinds[j], &k) != 0)
                    return bad_usage("unknown scene kind", su.kinds[j]);
            su.kind_count = n;
            ++i;
        } else if (strcmp(a, "--sizes") == 0 || strcmp(a, "--settle") == 0) {
            const int settle = a[2] == 's' && a[3] == 'e';
            long *dst = settle ? su.settle_sizes : su.sizes;
            int n;
            if (settle && strcmp(v, "-") == 0) {
                su.settle_count = 0;
                ++i;
                continue;
            }
            n = split_list(v, sbuf, sizeof sbuf, items);
            if (n <= 0)
                return bad_usage("bad list", v);
            for (j = 0; j < n; ++j)
                if (parse_int(items[j], 1, 1000000, &dst[j]) != 0)
                    return bad_usage("body counts must be integers in [1, 10^6], got", items[j]);
            if (settle)
                su.settle_count = n;
            else {
                su.size_count = n;
                sizes_given = 1;
            }
            ++i;
        } else if (strcmp(a, "--engines") == 0) {
            int n = split_list(v, ebuf, sizeof ebuf, items);
            if (n <= 0)
                return bad_usage("bad list", v);
            for (j = 0; j < n; ++j) {
                su.engines[j] = engine_by_name(items[j]);
                if (!su.engines[j])
                    return bad_usage("unknown engine", items[j]);
                if (!engine_built(su.engines[j]))
                    return bad_usage("engine not built into this carom-bench:", items[j]);
            }
            su.engine_count = n;
            su.engines_given = 1;
            ++i;
        } else if (strcmp(a, "--reps") == 0 || strcmp(a, "--steps") == 0 ||
                   strcmp(a, "--warmup") == 0 || strcmp(a, "--budget") == 0 ||
                   strcmp(a, "--settle-max") == 0 || strcmp(a, "--settle-budget") == 0) {
            long *dst = strcmp(a, "--reps") == 0         ? &su.reps
                        : strcmp(a, "--steps") == 0      ? &su.steps
                        : strcmp(a, "--warmup") == 0     ? &su.warmup
                        : strcmp(a, "--budget") == 0     ? &su.budget
                        : strcmp(a, "--settle-max") == 0 ? &su.settle_max
                                                         : &su.settle_budget;
            if (parse_int(v, strcmp(a, "--warmup") == 0 ? 0 : 1, dst == &su.reps ? 64 : 100000000,
                          dst) != 0)
                return bad_usage("want a positive integer (reps at most 64), got", v);
            if (dst == &su.reps)
                reps_given = 1;
            ++i;
        } else {
            return bad_usage("unknown option", a);
        }
    }
    if (quick) {
        if (!sizes_given) {
            su.sizes[0] = 100;
            su.sizes[1] = 1000;
            su.size_count = 2;
        }
        if (!reps_given)
            su.reps = 3;
    }
    if (!su.engines_given) {
        const bench_engine *all[] = { &bench_carom_events, &bench_carom_discrete,
                                      &bench_carom_first_impact, &bench_box2d,
                                      &bench_box2d_v3 };
        for (j = 0; j < 5; ++j)
            if (engine_built(all[j]) && !(su.ops && all[j]->method < 0))
                su.engines[su.engine_count++] = all[j];
    }

    print_machine();
    for (i = 0; i < su.kind_count; ++i) {
        bench_kind k;
        bench_kind_from_name(su.kinds[i], &k);
        for (j = 0; j < su.size_count; ++j) {
            bench_scene s;
            if (bench_scene_make(&s, k, (int)su.sizes[j]) != 0) {
                fprintf(stderr, "carom-bench: out of memory\n");
                return 1;
            }
            if (su.ops) {
                if (ops_size(&su, &s) != 0) {
                    fprintf(stderr, "carom-bench: --ops needs the profiling build "
                                    "(carom-bench-ops, linked with build/profile/libcarom.a)\n");
                    bench_scene_free(&s);
                    return 1;
                }
            } else {
                if (i == 0 && j == 0)
                    print_layout(&s);
                time_size(&su, &s);
            }
            bench_scene_free(&s);
        }
    }
    if (!su.ops) {
        for (j = 0; j < su.settle_count; ++j) {
            bench_scene s;
            if (bench_scene_make(&s, BENCH_PILE, (int)su.settle_sizes[j]) != 0) {
                fprintf(stderr, "carom-bench: out of memory\n");
                return 1;
            }
            settle_size(&su, &s);
            bench_scene_free(&s);
        }
    }
    return 0;
}
