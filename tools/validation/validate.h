/*
 * validate.h -- build/validate: carom against Box2D 2.4.1 and against exact
 * answers, on the scenes of tools/scenes/validation (docs/validation.md).
 *
 * The pieces, in the order a run uses them:
 *   runs.c     the engines as child processes, and their CSV outputs read
 *              back (traces, events, Box2D's mass table);
 *   exact.c    exact answers in double precision and closed form (masses,
 *              head-on pairs, bullets, the restitution drop, the off-centre
 *              polygon impact), and how far a trace is from them;
 *   checks.c   the check table (tools/validation/checks.txt): one row per
 *              scene pattern, engine(s), quantity, tolerance and reason;
 *   report.c   docs/validation.md and its figure;
 *   validate.c options, the order of work, the exit status.
 *
 * Scenes are read with the project's one scene parser (tools/scene.c).
 */
#ifndef CAROM_VALIDATE_H
#define CAROM_VALIDATE_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "scene.h"

#define V_EXIT_PASS 0  /* every check within its tolerance */
#define V_EXIT_FAIL 1  /* a check failed */
#define V_EXIT_USAGE 2 /* bad usage, bad input, a tool missing */

#define V_NAME_MAX 128
#define V_PATH_MAX 1024
#define V_NOTE_MAX 2048

/* "Could not be measured" (NAN is a float in C99). */
#define V_NAN ((double)NAN)

/* ---- engines ----------------------------------------------------------------------------- */

typedef enum engine {
    ENG_CAROM,         /* the library itself (masses): no run */
    ENG_EVENTS,        /* build/carom --method events */
    ENG_DISCRETE,      /* build/carom --method discrete */
    ENG_BOX2D,         /* build/carom-box2d */
    ENG_BOX2D_BULLETS, /* build/carom-box2d --bullets */
    ENG_COUNT
} engine;

extern const char *const engine_names[ENG_COUNT];

/* The engine called `name`, or -1. */
int engine_from_name(const char *name);

/* ---- what a run leaves ------------------------------------------------------------------- */

/* Every body's state at step 0 and after every step. */
enum { SX, SY, SA, SVX, SVY, SW, S_FIELDS };

typedef struct trace {
    int bodies;
    long samples;  /* steps + 1 */
    double *t;     /* [samples], s */
    double *st;    /* [samples][bodies][S_FIELDS]: x, y, angle, vx, vy, omega */
} trace;

/* The state of body b at sample k. */
#define TRACE_AT(tr, k, b) \
    ((tr)->st + ((size_t)(k) * (size_t)(tr)->bodies + (size_t)(b)) * S_FIELDS)

typedef struct event_row {
    double t;
    int a, b;
    double nx, ny, impulse, approach;
} event_row;

typedef struct events {
    int count;
    event_row *rows;
} events;

typedef struct run {
    int wanted;
    int status;              /* exit status; 127: could not be started; 128 + N:
                                killed by signal N; -1: not run */
    char message[V_NOTE_MAX]; /* its first line on stderr that is not a note */
    int ok;                  /* exit status 0 and its outputs read */
    trace tr;
    events ev;
} run;

/* ---- scenes ------------------------------------------------------------------------------ */

/* Mass properties in double, from the shape alone (0 for a static body). */
typedef struct body_props {
    double mass;    /* kg */
    double inertia; /* kg m^2, about the centre of mass */
    double cx, cy;  /* centre of mass in the body frame, m */
} body_props;

typedef struct vscene {
    char name[V_NAME_MAX];  /* file name without .scene */
    char path[V_PATH_MAX];
    scene sc;
    double gx, gy, dt;
    long steps;
    double rest_speed;      /* as the scene gives it, or carom's resolved
                               value where it says auto */
    body_props *exact;      /* [body_count] */
    double *carom_mass, *carom_inertia; /* carom_body_get_mass */
    double *b2_mass, *b2_inertia;       /* carom-box2d --masses, or NULL */
    run runs[ENG_COUNT];
} vscene;

typedef struct suite {
    vscene *scenes;
    int count;
} suite;

/* The scene called `name`, or NULL. */
const vscene *suite_find(const suite *su, const char *name);

/* ---- runs.c ------------------------------------------------------------------------------ */

typedef struct run_options {
    const char *carom;   /* build/carom */
    const char *box2d;   /* build/carom-box2d */
    const char *workdir; /* where the outputs go */
    int jobs;            /* engines at once */
    int verbose;
} run_options;

/* Run every wanted (scene, engine) and read back what they wrote. Returns
 * 0, or -1 after a message if nothing could be run at all. */
int runs_execute(suite *su, const run_options *o);

/* The path of a run's output: kind is "trace", "events", "masses", "out"
 * or "err". */
void run_file(char *buf, size_t n, const char *workdir, const vscene *s, int eng,
              const char *kind);

/* Run argv (argv[0] looked up in PATH when it has no '/') with stdout to
 * out_path and stderr to err_path (NULL: /dev/null) and wait. Returns its
 * exit status as run.status has it. */
int spawn_wait(char *const argv[], const char *out_path, const char *err_path);

/* The first line argv writes on stdout (stripped), or "" with -1. */
int capture_line(char *const argv[], const char *workdir, char *buf, size_t n);

void run_free(run *r);

/* ---- exact.c: exact answers -------------------------------------------------------------- */

double wrap_angle(double a);
void exact_body_props(const scene_body *sb, body_props *out);

/* Scenes with no gravity and no static body: momentum is conserved. */
int scene_is_free(const vscene *s);

/* Two dynamic circles on the x axis, moving along it towards each other,
 * no gravity: the corrected Newton formula of docs/physics.md. */
typedef struct headon {
    double ts;        /* s, the instant the surfaces touch */
    double e, ma, mb; /* restitution (max), masses */
    double xa, xb, ua, ub; /* start positions and velocities */
    double va, vb;    /* velocities after */
    int resting;      /* approach at most the rest speed: no restitution */
} headon;

typedef struct headon_err {
    double dx;   /* largest |x - exact| + |y| over samples and both bodies */
    double dv;   /* largest velocity error, the sample at ts left out */
    double dv_end; /* velocity error at the end */
} headon_err;

int headon_fit(const vscene *s, headon *h, char *why, size_t n);
void headon_measure(const headon *h, const trace *tr, headon_err *out);
double headon_dke(const headon *h);
/* The position error of an impulse applied late, at the end of the step
 * holding ts (docs/events.md): (e + k) v (dt - t*) m_B / M, k = 0 when the
 * overlap is projected away, 1 when it is not. */
double late_impulse_error(double e, double approach, double ts, double dt, double share,
                          double k);

/* A circle (body 1) fired along x at a box wall (body 0), static or free. */
typedef struct bullet {
    double ts, e, mw, mb; /* instant of contact, restitution, wall and bullet mass */
    double uw, ub;        /* velocities before */
    double vw, vb;        /* and after */
    int static_wall;
} bullet;

typedef struct bullet_err {
    double dx;          /* largest |x - exact| over samples, both bodies */
    double first;       /* bullet velocity after step 1 */
    double fv, wv;      /* final bullet and wall velocity */
} bullet_err;

int bullet_fit(const vscene *s, bullet *b, char *why, size_t n);
void bullet_measure(const vscene *s, const bullet *b, const trace *tr, bullet_err *out);
double bullet_dke(const bullet *b);

/* A kinematic box (body 0) spinning about its centre, at angle 0 at
 * t = 0, strikes a circle (body 1) at rest with its leading face. */
typedef struct blade {
    double ts, e;   /* instant of the strike, restitution */
    double x0, y0;  /* the ball's centre before */
    double vx, vy;  /* and its velocity after: (1 + e) w rho n */
    double mb;      /* the ball's mass */
} blade;

typedef struct blade_err {
    double dx; /* largest |position - exact| of the ball over the samples */
    double dv; /* |velocity - exact| of the ball at the end */
    double vx, vy; /* its final velocity */
} blade_err;

int blade_fit(const vscene *s, blade *b, char *why, size_t n);
void blade_measure(const blade *b, const trace *tr, blade_err *out);

/* Dynamic circles dropped from rest onto a static axis-aligned box:
 * the bounce sequence, until an arrival at or below the rest speed (or
 * e = 0) ends the bouncing. */
#define DROP_MAX_IMPACTS 60

typedef struct drop_ball {
    int body;
    double e, r, h0;          /* restitution, radius, start height of the lowest point */
    int n;                    /* impacts of the sequence */
    double T[DROP_MAX_IMPACTS], U[DROP_MAX_IMPACTS]; /* their instants and speeds */
    double rest_t;            /* from when the ball rests, or -1 */
} drop_ball;

typedef struct drop {
    double floor, g, tend, dt, rest;
    int count;
    drop_ball *balls;
} drop;

typedef struct drop_err {
    double merr;     /* largest |height - exact| */
    double below;    /* deepest below the floor's top (>= 0) */
    double apex[3];  /* measured heights of the first three bounces */
    int napex;
    double rest_h;   /* from rest_t on: largest |height| */
    double rest_v;   /* and largest speed */
    double fall_err; /* |height error| at the last sample before the first impact */
    double fall_t;   /* that sample's t */
    double last_top; /* highest point in the last second of the run */
} drop_err;

/* The engine's impacts on the balls (its events) against the sequence. */
typedef struct drop_impacts {
    int matched, wanted;   /* impacts faster than the rest speed: found, exact */
    double dt_rel, du_rel; /* their largest relative time and speed errors */
    int slow;              /* rows for arrivals at or below the rest speed */
    char slow_text[512];
} drop_impacts;

int drop_fit(const vscene *s, drop *d, char *why, size_t n);
void drop_free(drop *d);
double drop_height(const drop *d, const drop_ball *b, double t);
double drop_apex(const drop *d, const drop_ball *b, int k); /* exact k-th bounce, or -1 */
void drop_measure(const drop *d, const trace *tr, drop_err *out /* [d->count] */);
void drop_match_impacts(const drop *d, const events *ev, drop_impacts *out);
/* The exact change of the energy over the run (J): a ball that came to
 * rest lost m g h0, one still bouncing has the energy of its last bounce. */
double drop_dE(const vscene *s, const drop *d);
/* The rows of ev on the ball after it has come to rest (+ 2 dt). */
int drop_late_impacts(const drop *d, const drop_ball *b, const events *ev);
/* The first row of ev on the ball's body, or NULL. */
const event_row *drop_first_impact(const drop_ball *b, const events *ev);

/* A box (body 0, level) slides along x into a turned box (body 1): one
 * point, normal (1, 0), B's leftmost corner on A's right face. */
typedef struct poly {
    double ts, P;
    double v[2], w[2];  /* x velocity and angular velocity after */
    double x0[2], y0[2], a0[2]; /* poses at ts */
} poly;

typedef struct poly_err {
    double dv, dw, dx, da; /* largest over both bodies */
    double vel[2][3];      /* vx, vy, omega of each body */
    double t;
} poly_err;

int poly_fit(const vscene *s, poly *p, char *why, size_t n);
/* A step after every engine's first impact and before any second one
 * (events, discrete, box2d), or -1. */
long poly_compare_step(const vscene *s);
void poly_measure(const poly *p, const trace *tr, long step, poly_err *out);

/* Nothing should move (a stack placed at rest). */
typedef struct still_err {
    double move, end_move, rot, rise;
    double move_x, move_y; /* largest horizontal and vertical displacement */
} still_err;

void still_measure(const trace *tr, still_err *out);

/* Energy (kinetic + potential of the scene's gravity), momentum P and
 * angular momentum L about the origin, with the exact masses. */
typedef struct conserved {
    double e0, ke0, de_end, de_max, ke_end, dp_max, dl_max;
    double p_scale; /* sum of m |v| at t = 0 */
} conserved;

void conservation_measure(const vscene *s, const trace *tr, conserved *out);

/* Two traces of one scene: largest position, velocity, angle and angular
 * velocity difference; the first t at which a body is 1 cm apart (-1:
 * never). Velocity samples at t = tskip are left out (tskip < 0: none). */
typedef struct deviation {
    double dx, dv, da, dw, t_apart;
} deviation;

int deviation_measure(const trace *a, const trace *b, double tskip, deviation *out);
/* tskip for deviation_measure: the exact impact instant of a head-on
 * scene (on a step boundary the velocity jumps there), else -1. */
double deviation_skip(const vscene *s);

/* ---- checks.c ---------------------------------------------------------------------------- */

typedef struct check_row {
    int line;
    char pattern[V_NAME_MAX];
    int engines[8][2];  /* engine, second engine of a pair or -1 */
    int engine_count;
    char engine_text[64];
    int quantity;
    double tol;
    char reason[1024];
} check_row;

typedef struct check_result {
    int row, scene;
    int a, b;
    double value;     /* NaN: could not be measured */
    int pass;
    char why[V_NOTE_MAX]; /* why not measured */
} check_result;

typedef struct check_table {
    check_row *rows;
    int count;
    check_result *results;
    int result_count;
    int failed;
} check_table;

/* Read the table; returns 0, or -1 after a message (file:line). */
int checks_load(const char *path, check_table *t);
/* Expand the rows over the suite's scenes and mark the runs they need.
 * Returns 0, or -1 after a message (a quantity that does not fit a scene,
 * a pattern that matches nothing). */
int checks_expand(check_table *t, suite *su, const char *path);
void checks_evaluate(check_table *t, const suite *su);
void checks_free(check_table *t);

const char *quantity_name(int q);
const char *quantity_unit(int q);
/* What the quantity measures, one sentence. */
const char *quantity_what(int q);
int quantity_count(void);
/* The measured value of a result, formatted for the report ("failed" if
 * it could not be measured). */
void format_value(char *buf, size_t n, double v);

/* The --help list of quantities. */
void checks_print_quantities(FILE *f);

/* ---- report.c ---------------------------------------------------------------------------- */

typedef struct report_info {
    const char *out;       /* the report */
    const char *figure;    /* its figure (NULL: none) */
    const char *build;     /* how the engines were built (free text) */
    const char *checks_path;
    const char *scene_dir;
    const char *workdir;
    const char *carom;     /* build/carom, asked for its --version */
} report_info;

/* Write the report (and the figure with gnuplot; *figure_drawn says
 * whether it was: not when the drop's runs failed). Returns 0; 1 after a
 * message if the figure could not be drawn (the report is written); -1
 * after a message if the report could not be written. */
int report_write(const suite *su, const check_table *t, const report_info *ri,
                 int *figure_drawn);

#endif /* CAROM_VALIDATE_H */
