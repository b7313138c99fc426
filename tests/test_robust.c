/*
 * test_robust.c -- what carom does with hostile input: every value from
 * 1e-38 to 1e38 in every body and world parameter, the crash and NaN
 * findings of the fuzzing campaign as regression tests (API and scene
 * form), large time steps, failed steps that must leave the world as it
 * was, and the final-state hashes that pin the results of each method.
 */
#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "test_util.h"

/* ---- helpers ------------------------------------------------------------ */

static int finite_state(const carom_body_state *s)
{
    return isfinite(s->position.x) && isfinite(s->position.y) &&
           isfinite(s->rotation.c) && isfinite(s->rotation.s) &&
           isfinite(s->velocity.x) && isfinite(s->velocity.y) &&
           isfinite(s->angular_velocity);
}

/* Everything a program can observe of a world, for byte comparison. */
#define SNAP_MAX 16
typedef struct snapshot {
    int count;
    carom_body_state s[SNAP_MAX];
    carom_stats stats;
    float time;
} snapshot;

static void snap(const carom_world *w, snapshot *out)
{
    int i;
    memset(out, 0, sizeof *out);
    out->count = carom_world_body_count(w);
    for (i = 0; i < out->count && i < SNAP_MAX; ++i)
        ck_assert_int_eq(carom_body_get_state(w, i, &out->s[i]), CAROM_OK);
    ck_assert_int_eq(carom_world_get_stats(w, &out->stats), CAROM_OK);
    out->time = carom_world_time(w);
}

/* Same observable world: states bit for bit, every counter, the time. */
static int snap_equal(const snapshot *a, const snapshot *b)
{
    const carom_stats *x = &a->stats, *y = &b->stats;
    return a->count == b->count &&
           memcmp(a->s, b->s, (size_t)a->count * sizeof a->s[0]) == 0 &&
           memcmp(&a->time, &b->time, sizeof a->time) == 0 && x->steps == y->steps &&
           x->impacts == y->impacts && x->impact_solves == y->impact_solves &&
           x->toi_queries == y->toi_queries && x->toi_early_outs == y->toi_early_outs &&
           x->budget_steps == y->budget_steps && x->max_pairs_used == y->max_pairs_used &&
           x->max_contacts_used == y->max_contacts_used &&
           x->max_impacts_used == y->max_impacts_used &&
           x->awake_bodies == y->awake_bodies && x->contacts == y->contacts;
}

/* FNV-1a over bytes. */
static uint32_t fnv1a(uint32_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    size_t i;
    for (i = 0; i < n; ++i) {
        h ^= b[i];
        h *= 16777619u;
    }
    return h;
}

/* Hash of every body's state bits (position, rotation, velocity, angular
 * velocity, in that order, as stored floats). */
static uint32_t state_hash(const carom_world *w)
{
    uint32_t h = 2166136261u;
    int i, n = carom_world_body_count(w);
    for (i = 0; i < n; ++i) {
        carom_body_state s;
        float f[7];
        ck_assert_int_eq(carom_body_get_state(w, i, &s), CAROM_OK);
        f[0] = s.position.x;
        f[1] = s.position.y;
        f[2] = s.rotation.c;
        f[3] = s.rotation.s;
        f[4] = s.velocity.x;
        f[5] = s.velocity.y;
        f[6] = s.angular_velocity;
        h = fnv1a(h, f, sizeof f);
    }
    return h;
}

static const carom_method methods[] = {CAROM_METHOD_EVENTS, CAROM_METHOD_DISCRETE,
                                       CAROM_METHOD_FIRST_IMPACT};
#define N_METHODS 3

/* ---- every parameter from 1e-38 to 1e38 --------------------------------- */

enum param {
    P_MASS, P_DENSITY, P_RADIUS, P_HALF, P_VX, P_VY_DOWN, P_OMEGA, P_FORCE_DOWN,
    P_TORQUE, P_GRAVITY, P_DT, P_COUNT
};
static const char *param_names[P_COUNT] = {
    "mass", "density", "radius", "half-extent", "velocity x", "velocity -y",
    "angular velocity", "force -y", "torque", "gravity -y", "dt"};

/*
 * A small world (a static ground, a dynamic circle and a dynamic box above
 * it) with parameter `p` set to `v` on both dynamic bodies (or the world):
 * every call either succeeds or returns a named error; a refused body is
 * not added; every step either succeeds with finite states or fails with
 * the world exactly as before the step.
 */
static void hostile_world(carom_method m, enum param p, float v)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def g = carom_default_body_def(), bd[2];
    carom_status st;
    void *mem;
    carom_world *w;
    size_t n;
    int i, k;
    wd.method = m;
    wd.max_bodies = 3;
    if (p == P_GRAVITY)
        wd.gravity.y = -v;
    if (p == P_DT)
        wd.dt = v;
    st = carom_world_def_validate(&wd);
    ck_assert_msg(st == CAROM_OK || st == CAROM_ERR_BAD_DT || st == CAROM_ERR_OUT_OF_RANGE ||
                      st == CAROM_ERR_NOT_FINITE,
                  "%s = %g: %s", param_names[p], (double)v, carom_status_string(st));
    if (st != CAROM_OK) {
        ck_assert_int_eq(carom_world_buffer_size(&wd), 0);
        return;
    }
    n = carom_world_buffer_size(&wd);
    mem = malloc(n);
    ck_assert_int_eq(carom_world_init(&w, &wd, mem, n), CAROM_OK);
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 5.0f, 0.5f);
    g.position.y = -0.5f;
    ck_assert_int_eq(carom_world_add_body(w, &g, NULL), CAROM_OK);
    bd[0] = carom_default_body_def();
    bd[0].position.y = 1.0f;
    bd[1] = carom_default_body_def();
    ck_assert_int_eq(carom_body_def_set_box(&bd[1], 0.4f, 0.3f), CAROM_OK);
    bd[1].position.x = 1.5f;
    bd[1].position.y = 0.5f;
    for (i = 0; i < 2; ++i) {
        carom_body_def *d = &bd[i];
        int before = carom_world_body_count(w);
        switch (p) {
        case P_MASS: d->mass = v; break;
        case P_DENSITY: d->density = v; break;
        case P_RADIUS:
            if (i == 0)
                d->radius = v;
            break;
        case P_HALF:
            if (i == 1 && carom_body_def_set_box(d, v, v) != CAROM_OK) {
                continue;
            }
            break;
        case P_VX: d->velocity.x = v; break;
        case P_VY_DOWN: d->velocity.y = -v; break;
        case P_OMEGA: d->angular_velocity = v; break;
        case P_FORCE_DOWN: d->force.y = -v; break;
        case P_TORQUE: d->torque = v; break;
        default: break;
        }
        st = carom_world_add_body(w, d, NULL);
        ck_assert_msg(st == CAROM_OK || st == CAROM_ERR_OUT_OF_RANGE ||
                          st == CAROM_ERR_BAD_RADIUS || st == CAROM_ERR_BAD_DENSITY ||
                          st == CAROM_ERR_BAD_MASS || st == CAROM_ERR_NOT_FINITE ||
                          st == CAROM_ERR_DEGENERATE_POLYGON,
                      "%s = %g: add: %s", param_names[p], (double)v,
                      carom_status_string(st));
        ck_assert_int_eq(carom_world_body_count(w), before + (st == CAROM_OK));
    }
    for (k = 0; k < 5; ++k) {
        snapshot s0, s1;
        snap(w, &s0);
        st = carom_world_step(w);
        snap(w, &s1);
        if (st != CAROM_OK) {
            /* a named error, and nothing changed */
            ck_assert_msg(st == CAROM_ERR_NOT_FINITE || st == CAROM_ERR_OUT_OF_RANGE ||
                              st == CAROM_ERR_PAIR_CAPACITY || st == CAROM_ERR_CONTACT_CAPACITY,
                          "%s = %g: step: %s", param_names[p], (double)v,
                          carom_status_string(st));
            ck_assert_msg(snap_equal(&s0, &s1),
                          "%s = %g: a failed step changed the world", param_names[p],
                          (double)v);
            if (st == CAROM_ERR_NOT_FINITE || st == CAROM_ERR_OUT_OF_RANGE) {
                int e = carom_world_error_body(w);
                ck_assert_msg(e >= 0 && e < carom_world_body_count(w),
                              "%s = %g: no error body", param_names[p], (double)v);
            }
            break;
        }
        for (i = 0; i < s1.count; ++i)
            ck_assert_msg(finite_state(&s1.s[i]), "%s = %g: body %d not finite with status OK",
                          param_names[p], (double)v, i);
    }
    free(mem);
}

START_TEST(test_every_parameter_from_1e_minus38_to_1e38_is_refused_or_simulated)
{
    int p, m, e;
    for (m = 0; m < N_METHODS; ++m)
        for (p = 0; p < P_COUNT; ++p)
            for (e = -38; e <= 38; e += 2) {
                float v = (float)pow(10.0, (double)e);
                hostile_world(methods[m], (enum param)p, v);
                if (p == P_VX || p == P_OMEGA || p == P_TORQUE)
                    hostile_world(methods[m], (enum param)p, -v);
            }
    /* the edges: denormals, FLT_MAX, infinities and NaN */
    for (m = 0; m < N_METHODS; ++m)
        for (p = 0; p < P_COUNT; ++p) {
            hostile_world(methods[m], (enum param)p, 1.0e-45f);
            hostile_world(methods[m], (enum param)p, FLT_MAX);
            hostile_world(methods[m], (enum param)p, INFINITY);
            hostile_world(methods[m], (enum param)p, NAN);
            hostile_world(methods[m], (enum param)p, 0.0f);
        }
}
END_TEST

/* ---- the findings, one by one ------------------------------------------- */

/* Runs scene text for `steps` steps with method m: returns the status of
 * the build (-1: refused, with a message) or of the first failing step;
 * every state after a successful step is finite. */
static int run_scene_text(const char *text, carom_method m, int steps, char *msg,
                          size_t len)
{
    scene s;
    carom_world *w;
    void *mem;
    int k, i, rc = 0;
    if (scene_parse("t.scene", text, &s, msg, len) != 0)
        return -1; /* refused with a message naming the line */
    s.world.method = m;
    if (scene_build_world(&s, &w, &mem, msg, len) != 0) {
        scene_free(&s);
        return -1;
    }
    for (k = 0; k < steps && rc == 0; ++k) {
        carom_status st = carom_world_step(w);
        if (st != CAROM_OK) {
            rc = (int)st;
            break;
        }
        for (i = 0; i < carom_world_body_count(w); ++i) {
            carom_body_state b;
            carom_body_get_state(w, i, &b);
            ck_assert_msg(finite_state(&b), "body %d not finite after step %d", i, k);
        }
    }
    scene_free_world(w, mem);
    scene_free(&s);
    return rc;
}

/* The 3-line scene that overflowed the quartic root finder's stack: a
 * force of 1e38 is refused with a message, never a crash; at the largest
 * accepted force the step runs or fails with a named status. */
START_TEST(test_finding_force_1e38_over_a_static_circle_does_not_crash)
{
    char msg[256];
    int m;
    for (m = 0; m < N_METHODS; ++m) {
        int rc = run_scene_text("carom-scene 1\n"
                                "body circle static position=0,7\n"
                                "body circle force=0,1e38\n",
                                methods[m], 10, msg, sizeof msg);
        ck_assert_int_eq(rc, -1);
        ck_assert_msg(strstr(msg, "t.scene:3") != NULL, "message: %s", msg);
        rc = run_scene_text("carom-scene 1\n"
                            "body circle static position=0,7\n"
                            "body circle force=0,1e11\n",
                            methods[m], 10, msg, sizeof msg);
        ck_assert_msg(rc == 0 || rc == CAROM_ERR_OUT_OF_RANGE, "rc %d", rc);
    }
}
END_TEST

/* Inputs whose derived quantities overflow (inverse mass, inverse
 * inertia, dt) are refused at the door with their status. */
START_TEST(test_finding_tiny_masses_sizes_and_steps_are_refused)
{
    carom_body_def bd = carom_default_body_def();
    carom_world_def wd = carom_default_world_def();
    bd.mass = 1.0e-40f;
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_ERR_BAD_MASS);
    bd = carom_default_body_def();
    bd.density = 1.0e-39f;
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_ERR_BAD_MASS);
    bd = carom_default_body_def();
    bd.radius = 1.0e-10f;
    ck_assert_int_ne(carom_body_def_validate(&bd), CAROM_OK);
    bd = carom_default_body_def();
    bd.torque = 1.0e38f;
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_ERR_OUT_OF_RANGE);
    bd = carom_default_body_def();
    bd.mass = 1.0e38f;
    ck_assert_int_eq(carom_body_def_validate(&bd), CAROM_ERR_BAD_MASS);
    wd.dt = 1.0e-45f;
    ck_assert_int_eq(carom_world_def_validate(&wd), CAROM_ERR_BAD_DT);
    wd.dt = 1.0e18f;
    ck_assert_int_eq(carom_world_def_validate(&wd), CAROM_ERR_BAD_DT);
}
END_TEST

/* A random scene of the kinematic-rotor hunt (2026-11-28; reduced): three
 * kinematic rotors crossing one another in a 0.5 m box, and 0.1 g
 * bodies caught between them. An impact instant's rows, a body held
 * between two blades closing on it, made a nearly singular system whose
 * exact solve sent a body off at 10^10 m/s, and the step failed with
 * CAROM_ERR_OUT_OF_RANGE at step 96 (of the 100 run here). A solve
 * whose impulses exceed ten times the momentum its bodies could need is
 * now left to the sweeps: every state finite, status OK. */
START_TEST(test_finding_bodies_between_crossing_kinematic_rotors_stay_finite)
{
    static const char *const text =
        "carom-scene 1\n"
        "world gravity=0,0 dt=0.0333333333 steps=240 substeps=8 sleep=off\n"
        "body box static half-extents=0.247198887,0.000530957125 position=0,-0.17777712"
        "5 restitution=0.7 friction=0.3\n"
        "body box static half-extents=0.247198887,0.000530957125 position=0,0.177777125"
        " restitution=0.7 friction=0\n"
        "body box static half-extents=0.000530957125,0.178308083 position=-0.247198887,"
        "0 restitution=0.7 friction=0.8\n"
        "body box static half-extents=0.000530957125,0.178308083 position=0.247198887,0"
        " restitution=0 friction=0.3\n"
        "body box kinematic half-extents=0.059587893,0.00963484726 position=0.098004745"
        "6,0.0572658337 angle=-1.79864575 angular-velocity=-6.88741528 restitution=0.7 "
        "friction=0.8\n"
        "body box kinematic half-extents=0.0492229481,0.00816571581 position=0.11303955"
        "3,0.0383380007 angle=-1.20630333 angular-velocity=8.55445539 restitution=0 fri"
        "ction=0.3\n"
        "body box kinematic half-extents=0.0782520349,0.00467002638 position=0.05234391"
        "96,0.00347292923 angle=0.599580901 angular-velocity=141.598246 restitution=0.7"
        " friction=0.8\n"
        "body polygon vertices=0.0105805748,0.0129954405;-0.0059640942,0.0156607668;-0."
        "016544669,0.0026653263;-0.0105805748,-0.0129954405;0.0059640942,-0.0156607668;"
        "0.016544669,-0.0026653263 position=-0.135609727,-0.0758012767 velocity=0.25529"
        "9131,-0.976474078 density=9.3693449 restitution=1 friction=0\n"
        "body polygon vertices=-0.00511203529,0.00142170702;0.00132478325,-0.0051380059"
        "3;0.00378725204,0.00371629892 position=-0.202514086,0.0507227266 velocity=0.04"
        "4520892,0.149264682 density=7.7510192 restitution=0 friction=0\n"
        "body box half-extents=0.011719095,0.0100053235 angle=-1.19152433 position=-0.1"
        "45707785,-0.026672654 velocity=-0.0228158198,0.0172537074 density=0.269519295 "
        "restitution=0.7 friction=0.8\n"
        "body circle radius=0.00520130369 position=0.238170979,0.0141171674 velocity=-0"
        ".0053565606,-0.00257407725 density=0.307882744 restitution=1 friction=0\n"
        "body polygon vertices=0.00374728145,-0.00858911905;0.00858911905,0.00374728145"
        ";-0.00374728145,0.00858911905;-0.00858911905,-0.00374728145 position=-0.045283"
        "4813,0.036718226 velocity=-0.0860619109,0.0506612637 density=51.8407495 restit"
        "ution=0.3 friction=0\n"
        "body circle radius=0.00599596545 position=-0.0631127422,0.0437664967 velocity="
        "0.0216448331,-0.113706666 density=1.13810144 restitution=0.3 friction=0.8\n"
        "body polygon vertices=-0.00329456213,0.00413718456;-0.00528870702,3.69998882e-"
        "06;-0.00330034766,-0.00413257075;0.0011732408,-0.00515693142;0.00476335501,-0."
        "00229801755;0.00476656574,0.0022913504;0.00118045525,0.00515528477 position=-0"
        ".138790507,0.152592315 velocity=-0.0131613128,-0.00642497962 density=0.4919730"
        "96 restitution=0.7 friction=0\n"
        "body circle radius=0.00754868528 position=-0.0312880101,0.0831222542 velocity="
        "-0.145549781,0.102659745 density=0.711537876 restitution=0.7 friction=0\n"
        "body polygon vertices=-0.006344237,0.00601733181;-0.00203904371,-0.00850293631"
        ";0.0083832807,0.0024856045 position=-0.045774467,-0.0640496851 velocity=-0.588"
        "845603,-0.0328879051 density=31.7260656 restitution=0.3 friction=0\n";
    char msg[256];
    int rc = run_scene_text(text, CAROM_METHOD_EVENTS, 100, msg, sizeof msg);
    ck_assert_msg(rc == 0, "rc %d (%s)", rc, rc < 0 ? msg : carom_status_string((carom_status)rc));
}
END_TEST

/* Found by the same hunt, as small: two kinematic rotors crossing each
 * other in a 5 cm box, two 1.3 mm boxes. A box pinched where the blades
 * cross was sent from one blade straight back into the other at the same
 * instant, again and again, each hit 6 % faster (the rotors do work):
 * 10^17 m/s within one step, and the step failed with
 * CAROM_ERR_OUT_OF_RANGE at step 22. Past 32 such returns of a pair at
 * one instant, the rest of the instant is the solver's: every state
 * finite, status OK. */
START_TEST(test_finding_box_pinched_between_crossing_blades_stays_finite)
{
    static const char *const text =
        "carom-scene 1\n"
        "world gravity=0,0 dt=0.0333333333 steps=60 substeps=4 sleep=off\n"
        "body box static half-extents=0.025,0.001 position=0,-0.024 restitution=1 frict"
        "ion=0.8\n"
        "body box static half-extents=0.025,0.001 position=0,0.024 restitution=1 fricti"
        "on=0.8\n"
        "body box static half-extents=0.001,0.025 position=-0.024,0 restitution=1 frict"
        "ion=0.8\n"
        "body box static half-extents=0.001,0.025 position=0.024,0 restitution=1 fricti"
        "on=0.8\n"
        "body box kinematic half-extents=0.0087907,0.000904682 position=0.00194522,-0.0"
        "0643909 angle=-2.20502 angular-velocity=230.279 restitution=0 friction=0.8\n"
        "body box kinematic half-extents=0.0094933,0.00111334 position=0.00684528,-0.00"
        "737796 angle=-1.87448 angular-velocity=-125.065 restitution=0 friction=0.8\n"
        "body box half-extents=0.000594275,0.000738729 position=0.00393055,0.0065062 an"
        "gle=-1.94165 density=93.3541 restitution=1 friction=0.8\n"
        "body box half-extents=0.000663809,0.000633731 position=0.00594665,0.00224772 a"
        "ngle=2.50537 density=45.4458 restitution=1 friction=0.8\n";
    char msg[256];
    int rc = run_scene_text(text, CAROM_METHOD_EVENTS, 60, msg, sizeof msg);
    ck_assert_msg(rc == 0, "rc %d (%s)", rc, rc < 0 ? msg : carom_status_string((carom_status)rc));
}
END_TEST

/* A triangle spinning at the largest accepted rate over a static box:
 * the static box never moves, and every state stays finite (or the step
 * fails with a named status, the world unchanged). */
START_TEST(test_finding_fast_spinning_triangle_leaves_static_box_still)
{
    char msg[256];
    int m;
    for (m = 0; m < N_METHODS; ++m) {
        int rc = run_scene_text("carom-scene 1\n"
                                "body polygon vertices=0,0;1,0;0,1 angular-velocity=-4.4e19 "
                                "position=0,1.2\n"
                                "body box static half-extents=5,0.5\n",
                                methods[m], 5, msg, sizeof msg);
        ck_assert_int_eq(rc, -1); /* beyond CAROM_LIMIT_MAX_SPEED */
        rc = run_scene_text("carom-scene 1\n"
                            "body polygon vertices=0,0;1,0;0,1 angular-velocity=-1e6 "
                            "position=0,1.2\n"
                            "body box static half-extents=5,0.5\n",
                            methods[m], 5, msg, sizeof msg);
        ck_assert_msg(rc == 0 || rc == CAROM_ERR_OUT_OF_RANGE, "rc %d", rc);
    }
}
END_TEST

/* A ball dropped 2 m onto a static floor with e = 0 at very large steps
 * (dt up to 0.5 s) or very strong gravity (1e4 m/s^2 at 1/60 s) stops on
 * the floor and stays there: the contact found inside a step holds to its
 * end, in every method. */
START_TEST(test_finding_large_dt_and_gravity_keep_the_ball_on_the_floor)
{
    static const float dts[] = {0.5f, 0.4f, 0.25f, 1.0f / 60.0f};
    static const float gs[] = {10.0f, 10.0f, 10.0f, 1.0e4f};
    int m, c, k;
    for (m = 0; m < N_METHODS; ++m)
        for (c = 0; c < 4; ++c) {
            carom_world_def wd = carom_default_world_def();
            carom_body_def g = carom_default_body_def(), b = carom_default_body_def();
            tw t;
            float lowest = 1e9f;
            carom_body_state s;
            wd.method = methods[m];
            wd.dt = dts[c];
            wd.gravity.y = -gs[c];
            wd.max_bodies = 2;
            t = tw_make(&wd);
            g.type = CAROM_BODY_STATIC;
            carom_body_def_set_box(&g, 5.0f, 0.5f);
            g.position.y = -0.5f;
            tw_add(&t, &g);
            b.radius = 0.5f;
            b.position.y = 2.5f;
            b.restitution = 0.0f;
            tw_add(&t, &b);
            for (k = 0; k < 40; ++k) {
                ck_assert_int_eq(carom_world_step(t.w), CAROM_OK);
                s = tw_state(&t, 1);
                if (s.position.y < lowest)
                    lowest = s.position.y;
            }
            /* on the floor (top at y = 0), within a few slops, at rest */
            ck_assert_msg(lowest > 0.5f - 0.02f, "method %d dt %g g %g: ball at %g",
                          m, (double)dts[c], (double)gs[c], (double)lowest);
            ck_assert_close(s.position.y, 0.5, 0.02);
            ck_assert_msg(fabs(s.velocity.y) < 0.05 * gs[c] * dts[c] + 1e-3,
                          "method %d dt %g: still moving at %g", m, (double)dts[c],
                          (double)s.velocity.y);
            tw_free(&t);
        }
}
END_TEST

/* ---- a failed step leaves the world as it was ---------------------------- */

static int poison;

/* Gravity-like force, NaN while `poison` is set. */
static void maybe_nan(void *user, int body, const carom_body_state *st, carom_vec2 *f,
                      float *torque)
{
    (void)user;
    (void)body;
    (void)st;
    (void)torque;
    f->x = poison ? NAN : 0.0f;
}

/* A pile of boxes and circles, stepped with a force callback. */
static tw pile_world(carom_method m)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def g = carom_default_body_def();
    tw t;
    int i;
    wd.method = m;
    wd.max_bodies = 13;
    wd.force_fn = maybe_nan;
    t = tw_make(&wd);
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 5.0f, 0.5f);
    g.position.y = -0.5f;
    tw_add(&t, &g);
    for (i = 0; i < 12; ++i) {
        carom_body_def bd = carom_default_body_def();
        if (i % 3 == 0)
            carom_body_def_set_box(&bd, 0.3f, 0.25f);
        else
            bd.radius = 0.2f + 0.03f * (float)(i % 4);
        bd.position.x = -1.0f + 0.37f * (float)(i % 6);
        bd.position.y = 0.4f + 0.6f * (float)(i / 6) + 0.05f * (float)i;
        bd.restitution = 0.2f * (float)(i % 3);
        tw_add(&t, &bd);
    }
    return t;
}

/* A step that fails (a NaN force) changes nothing: stepping on afterwards
 * gives bit for bit what a world that never failed gives. */
START_TEST(test_failed_step_is_undone_bit_for_bit)
{
    int m, k;
    for (m = 0; m < N_METHODS; ++m) {
        tw a = pile_world(methods[m]), b = pile_world(methods[m]);
        snapshot sa, sb, before;
        poison = 0;
        tw_steps(&a, 20);
        tw_steps(&b, 20);
        snap(a.w, &before);
        poison = 1;
        ck_assert_int_eq(carom_world_step(a.w), CAROM_ERR_NOT_FINITE);
        ck_assert_int_ge(carom_world_error_body(a.w), 1);
        snap(a.w, &sa);
        ck_assert(snap_equal(&before, &sa));
        poison = 0;
        for (k = 0; k < 40; ++k) {
            int na, nb;
            const carom_event *ea, *eb;
            ck_assert_int_eq(carom_world_step(a.w), CAROM_OK);
            ck_assert_int_eq(carom_world_step(b.w), CAROM_OK);
            ea = carom_world_events(a.w, &na);
            eb = carom_world_events(b.w, &nb);
            ck_assert_int_eq(na, nb);
            ck_assert(na == 0 || memcmp(ea, eb, (size_t)na * sizeof *ea) == 0);
        }
        snap(a.w, &sa);
        snap(b.w, &sb);
        ck_assert(snap_equal(&sa, &sb));
        ck_assert_int_eq(carom_world_error_body(a.w), -1);
        tw_free(&a);
        tw_free(&b);
    }
}
END_TEST

/* Capacity failures (pairs, contacts) are as clean: the world as before. */
START_TEST(test_capacity_failure_changes_nothing)
{
    int m, k, cap;
    for (m = 0; m < N_METHODS; ++m)
        for (cap = 0; cap < 2; ++cap) {
            carom_world_def wd = carom_default_world_def();
            carom_body_def bd = carom_default_body_def();
            tw t;
            int i;
            carom_status st = CAROM_OK;
            snapshot s0, s1;
            wd.method = methods[m];
            wd.max_bodies = 6;
            wd.gravity.y = 0.0f;
            if (cap == 0)
                wd.max_pairs = 3;
            else
                wd.max_contacts = 2;
            t = tw_make(&wd);
            for (i = 0; i < 6; ++i) {
                /* six balls converging on the origin */
                float a = 1.0471976f * (float)i;
                bd.position.x = 3.0f * cosf(a);
                bd.position.y = 3.0f * sinf(a);
                bd.velocity.x = -2.0f * cosf(a);
                bd.velocity.y = -2.0f * sinf(a);
                tw_add(&t, &bd);
            }
            for (k = 0; k < 120 && st == CAROM_OK; ++k) {
                snap(t.w, &s0);
                st = carom_world_step(t.w);
            }
            ck_assert_int_eq(st, cap == 0 ? CAROM_ERR_PAIR_CAPACITY : CAROM_ERR_CONTACT_CAPACITY);
            snap(t.w, &s1);
            ck_assert(snap_equal(&s0, &s1));
            /* and it fails the same way again: nothing was lost */
            ck_assert_int_eq(carom_world_step(t.w), st);
            snap(t.w, &s1);
            ck_assert(snap_equal(&s0, &s1));
            tw_free(&t);
        }
}
END_TEST

/* A step that woke a sleeping stack and then failed puts the stack back to
 * sleep as one island: waking one of its boxes afterwards wakes both. */
START_TEST(test_failed_step_restores_sleeping_islands)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def(), g = carom_default_body_def();
    carom_status st = CAROM_OK;
    tw t;
    int box[2], ball, k;
    wd.max_bodies = 4;
    wd.max_pairs = 2;
    t = tw_make(&wd);
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 5.0f, 0.5f);
    g.position.y = -0.5f;
    tw_add(&t, &g);
    carom_body_def_set_box(&bd, 0.5f, 0.5f);
    bd.position.y = 0.5f;
    box[0] = tw_add(&t, &bd);
    bd.position.y = 1.5f;
    box[1] = tw_add(&t, &bd);
    tw_steps(&t, 120);
    ck_assert(!carom_body_is_awake(t.w, box[0]) && !carom_body_is_awake(t.w, box[1]));
    bd = carom_default_body_def();
    bd.radius = 0.25f;
    bd.position.y = 3.5f;
    ball = tw_add(&t, &bd);
    for (k = 0; k < 120 && st == CAROM_OK; ++k)
        st = carom_world_step(t.w);
    ck_assert_int_eq(st, CAROM_ERR_PAIR_CAPACITY);
    ck_assert(!carom_body_is_awake(t.w, box[0]) && !carom_body_is_awake(t.w, box[1]));
    ck_assert_int_eq(carom_body_set_force(t.w, box[1], (carom_vec2){0.0f, 0.0f}, 0.0f), CAROM_OK);
    ck_assert(carom_body_is_awake(t.w, box[0]) && carom_body_is_awake(t.w, box[1]));
    (void)ball;
    tw_free(&t);
}
END_TEST

/* Fuzz findings: with sleep_time 0 an island sleeps after its first still
 * step, never while it moves (two touching circles falling together keep
 * falling); a body arriving fast wakes a sleeping one and the two do not
 * fall asleep in mid-flight. */
START_TEST(test_sleep_time_zero_never_sleeps_a_moving_island)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def(), g = carom_default_body_def();
    tw t;
    int a, b, k;
    wd.max_bodies = 3;
    wd.sleep_time = 0.0f;
    t = tw_make(&wd);
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 5.0f, 0.5f);
    g.position.y = -0.5f;
    tw_add(&t, &g);
    bd.radius = 0.5f;
    bd.position.y = 10.0f;
    a = tw_add(&t, &bd);
    bd.position.x = 0.99f;
    b = tw_add(&t, &bd);
    for (k = 1; k <= 30; ++k) {
        tw_steps(&t, 1);
        ck_assert_msg(carom_body_is_awake(t.w, a) && carom_body_is_awake(t.w, b),
                      "fell asleep in mid-air at step %d", k);
    }
    /* free fall, exactly: 10 - 5 t^2 (they only touch sideways) */
    ck_assert_close(tw_state(&t, a).position.y, 10.0 - 5.0 * 0.25, 1e-4);
    tw_free(&t);
}
END_TEST

/* ---- determinism pinned --------------------------------------------------- */

static void add_ground(tw *t)
{
    carom_body_def g = carom_default_body_def();
    g.type = CAROM_BODY_STATIC;
    carom_body_def_set_box(&g, 10.0f, 0.5f);
    g.position.y = -0.5f;
    tw_add(t, &g);
}

/* The scenes whose final state hashes are pinned. */
static tw pinned_scene(int which, carom_method m)
{
    carom_world_def wd = carom_default_world_def();
    tw t;
    int i;
    wd.method = m;
    wd.max_bodies = 64;
    if (which == 1) { /* gas */
        wd.gravity.y = 0.0f;
        wd.rest_speed = 0.0f;
    }
    t = tw_make(&wd);
    switch (which) {
    case 0: /* a stack of 8 boxes */
        add_ground(&t);
        for (i = 0; i < 8; ++i) {
            carom_body_def bd = carom_default_body_def();
            carom_body_def_set_box(&bd, 0.5f, 0.5f);
            bd.position.y = 0.5f + (float)i;
            tw_add(&t, &bd);
        }
        break;
    case 1: { /* a gas of 40 circles in a box */
        unsigned seed = 3u;
        carom_body_def g = carom_default_body_def();
        g.type = CAROM_BODY_STATIC;
        g.restitution = 1.0f;
        g.friction = 0.0f;
        for (i = 0; i < 4; ++i) {
            carom_body_def_set_box(&g, i < 2 ? 5.5f : 0.5f, i < 2 ? 0.5f : 5.5f);
            g.position.x = i < 2 ? 0.0f : (i == 2 ? -5.5f : 5.5f);
            g.position.y = i < 2 ? (i == 0 ? -5.5f : 5.5f) : 0.0f;
            tw_add(&t, &g);
        }
        for (i = 0; i < 40; ++i) {
            carom_body_def bd = carom_default_body_def();
            seed = seed * 1664525u + 1013904223u;
            bd.radius = 0.2f;
            bd.restitution = 1.0f;
            bd.friction = 0.0f;
            bd.position.x = -4.0f + (float)(i % 8);
            bd.position.y = -4.0f + 2.0f * (float)(i / 8);
            bd.velocity.x = (float)(seed >> 8) / 16777216.0f * 4.0f - 2.0f;
            seed = seed * 1664525u + 1013904223u;
            bd.velocity.y = (float)(seed >> 8) / 16777216.0f * 4.0f - 2.0f;
            tw_add(&t, &bd);
        }
        break;
    }
    case 2: { /* a bouncing ball */
        carom_body_def bd = carom_default_body_def();
        add_ground(&t);
        bd.radius = 0.5f;
        bd.position.y = 10.0f;
        bd.restitution = 0.8f;
        tw_add(&t, &bd);
        break;
    }
    default: /* a pile of polygons */
        add_ground(&t);
        for (i = 0; i < 24; ++i) {
            carom_body_def bd = carom_default_body_def();
            int j, n = 3 + i % 4;
            bd.shape = CAROM_SHAPE_POLYGON;
            bd.vertex_count = n;
            for (j = 0; j < n; ++j) {
                carom_rot r = carom_rot_from_angle(6.2831853f * (float)j / (float)n);
                bd.vertices[j].x = 0.3f * r.c;
                bd.vertices[j].y = 0.3f * r.s;
            }
            bd.position.x = -2.0f + 0.8f * (float)(i % 6);
            bd.position.y = 0.5f + 0.9f * (float)(i / 6);
            bd.rotation = carom_rot_from_angle(0.3f * (float)i);
            bd.restitution = 0.1f;
            tw_add(&t, &bd);
        }
        break;
    }
    return t;
}

/*
 * The FNV-1a hash of the final state bits after 300 steps, per scene and
 * method. These pin the results: a change that alters any bit of them
 * fails here, and the commit that updates them must say why the results
 * changed. (They are the same in the plain and the profiling build, and
 * under every optimisation level: the arithmetic is strict IEEE float.)
 */
static const uint32_t pinned[4][N_METHODS] = {
    /* events      discrete    first-impact */
    {0x7f5382b5u, 0x7f5382b5u, 0x7f5382b5u}, /* stack */
    {0xd927484fu, 0x2f419a00u, 0xcd2b366bu}, /* gas */
    {0x99714b88u, 0xff575915u, 0x99714b88u}, /* bounce */
    {0x227dfc88u, 0x351a8616u, 0xbfa4368fu}, /* polygon pile */
};

START_TEST(test_final_state_hashes_are_pinned)
{
    static const char *names[4] = {"stack", "gas", "bounce", "polygon pile"};
    int s, m, bad = 0;
    for (s = 0; s < 4; ++s)
        for (m = 0; m < N_METHODS; ++m) {
            tw t = pinned_scene(s, methods[m]);
            uint32_t h;
            tw_steps(&t, 300);
            h = state_hash(t.w);
            if (h != pinned[s][m]) {
                fprintf(stderr, "pinned hash: %s, %s: 0x%08xu, pinned 0x%08xu\n", names[s],
                        carom_method_name(methods[m]), (unsigned)h, (unsigned)pinned[s][m]);
                bad = 1;
            }
            tw_free(&t);
        }
    ck_assert_msg(!bad, "final state hashes changed (see stderr)");
}
END_TEST

Suite *suite_robust(void)
{
    Suite *s = suite_create("robust");
    TCase *tc = tcase_create("hostile");
    TCase *tf = tcase_create("findings");
    TCase *tp = tcase_create("pinned");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_every_parameter_from_1e_minus38_to_1e38_is_refused_or_simulated);
    tcase_add_test(tf, test_finding_force_1e38_over_a_static_circle_does_not_crash);
    tcase_add_test(tf, test_finding_tiny_masses_sizes_and_steps_are_refused);
    tcase_add_test(tf, test_finding_fast_spinning_triangle_leaves_static_box_still);
    tcase_add_test(tf, test_finding_bodies_between_crossing_kinematic_rotors_stay_finite);
    tcase_add_test(tf, test_finding_box_pinched_between_crossing_blades_stays_finite);
    tcase_add_test(tf, test_finding_large_dt_and_gravity_keep_the_ball_on_the_floor);
    tcase_add_test(tf, test_failed_step_is_undone_bit_for_bit);
    tcase_add_test(tf, test_capacity_failure_changes_nothing);
    tcase_add_test(tf, test_failed_step_restores_sleeping_islands);
    tcase_add_test(tf, test_sleep_time_zero_never_sleeps_a_moving_island);
    tcase_add_test(tp, test_final_state_hashes_are_pinned);
    suite_add_tcase(s, tc);
    suite_add_tcase(s, tf);
    suite_add_tcase(s, tp);
    return s;
}
