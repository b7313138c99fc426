/*
 * carom_box2d_v3.c -- build/carom-box2d-v3: run carom scene files through
 * Box2D v3 (upstream erincatto/box2d, built outside the project: see
 * tools/box2d_v3/BUILDING.md), to time and compare it side by side with
 * build/carom and build/carom-box2d (Box2D 2.4.1).
 *
 * The scene is read by carom's own parser (tools/scene.c) and the carom
 * world is built too, so a scene is checked exactly as build/carom checks
 * it and carom's masses (mass= becomes density = mass / area) are the ones
 * Box2D gets. The output formats are those of build/carom (final state,
 * --trace); --time prints the time of b2World_Step.
 *
 * What Box2D v3 cannot express is never silently changed: it is a note on
 * stderr, or an error with exit status 2 (a polygon Box2D's hull would
 * weld, reorder away or reject).
 *
 * A tool, not part of the core: C17, POSIX, libm, Box2D v3.
 *
 * Exit status: 0 ok, 1 simulation error (non-finite state, or an output
 * file could not be written), 2 bad usage or bad scene.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include <box2d/box2d.h>
#include <box2d/constants.h> /* B2_LINEAR_SLOP */

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "carom.h"
#include "scene.h"

#define EXIT_SIM 1
#define EXIT_USAGE 2

#define PROG "carom-box2d-v3"
static const double PI = 3.14159265358979323846;

/* Per-step times are kept for the median up to this many timed steps. */
#define MAX_SAMPLES 50000000L

static const char usage[] =
    "usage: " PROG " run SCENE [options]\n"
    "       " PROG " --help\n"
    "\n"
    "Step a carom scene file (docs/scene-format.md) with Box2D v3 and write\n"
    "the final state of every body to stdout in build/carom's CSV format:\n"
    "body,x,y,angle,vx,vy,omega (x, y: body origin; angle in [-pi, pi];\n"
    "vx, vy: velocity of the centre of mass; omega: angular velocity).\n"
    "\n"
    "The Box2D world gets the scene's gravity, dt, shapes (polygons as given,\n"
    "in the body frame, with no rounding radius), densities (mass= becomes\n"
    "density = mass / area, carom's mass), restitution, friction, poses,\n"
    "velocities and constant forces (applied before every step). Box2D mixes\n"
    "restitution (max) and friction (sqrt) as carom does. One worker, no task\n"
    "system (single-threaded); sleeping off unless --sleep.\n"
    "\n"
    "options:\n"
    "  --steps N                  number of steps after the warm-up\n"
    "                             (overrides steps=)\n"
    "  --dt DT                    time step in seconds (overrides dt=)\n"
    "  --substeps N               Box2D sub-steps per step (default 4)\n"
    "  --restitution-threshold V  m/s; contacts approaching slower than V do\n"
    "                             not bounce. Default: Box2D's (1 m/s);\n"
    "                             'scene' uses the scene's rest-speed=\n"
    "  --sleep                    let bodies sleep (Box2D's default, off here)\n"
    "  --bullets                  make every dynamic body a Box2D bullet\n"
    "                             (continuous collision against dynamic bodies\n"
    "                             too; by default only against static ones)\n"
    "  --warmup N                 N untimed steps before the N of --steps\n"
    "                             (they are in --trace and the final state)\n"
    "  --trace FILE               every body's state at step 0 and after every\n"
    "                             step: step,t,body,x,y,angle,vx,vy,omega\n"
    "  --time                     print the b2World_Step time of the steps\n"
    "                             after the warm-up to stderr:\n"
    "                             '" PROG ": time: N steps, X ns/step,\n"
    "                             median Y ns/step' (X: mean; CLOCK_MONOTONIC\n"
    "                             around b2World_Step only)\n"
    "  --profile                  with --time: Box2D's own b2World_GetProfile,\n"
    "                             mean ms per timed step of each phase, to stderr\n"
    "  --quiet                    no notes on stderr (errors still go there)\n"
    "  -h, --help                 show this help\n"
    "\n"
    "Notes on stderr name the differences Box2D v3 cannot avoid: one method\n"
    "(a soft-step solver with sub-steps, speculative contacts, continuous\n"
    "collision against static bodies and for bullets), contact slop\n"
    "B2_LINEAR_SLOP = 0.005 m, soft contacts (30 Hz, damping ratio 10, push-out\n"
    "at most 3 m/s), a speed cap of 400 m/s. A polygon Box2D's hull would\n"
    "alter (vertices closer than 4 B2_LINEAR_SLOP = 0.02 m are welded, those\n"
    "within 2 B2_LINEAR_SLOP of an edge dropped) is an error.\n"
    "\n"
    "exit status: 0 ok, 1 simulation error, 2 bad usage or bad scene\n";

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, PROG ": ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(try '" PROG " --help')\n");
    return EXIT_USAGE;
}

static bool parse_long(const char *v, long lo, long hi, long *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || errno || x < lo || x > hi)
        return false;
    *out = x;
    return true;
}

static bool parse_double(const char *v, double *out)
{
    char *end;
    double x;
    errno = 0;
    x = strtod(v, &end);
    if (*v == '\0' || *end != '\0' || errno || !isfinite(x))
        return false;
    *out = x;
    return true;
}

/* Angle of a rotation in [-pi, pi], by carom's own carom_rot_angle, so
 * that both engines' CSVs convert (cos, sin) pairs to angles the same way
 * (a double atan2 can differ from it in the last float bit). */
static double wrap_angle(b2Rot q)
{
    carom_rot r;
    r.c = q.c;
    r.s = q.s;
    return (double)carom_rot_angle(r);
}

/* ---- building the Box2D world ------------------------------------------ */

static double polygon_area(const carom_body_def *d)
{
    double a = 0.0;
    int i;
    for (i = 0; i < d->vertex_count; ++i) {
        const carom_vec2 p = d->vertices[i];
        const carom_vec2 q = d->vertices[(i + 1) % d->vertex_count];
        a += (double)p.x * (double)q.y - (double)q.x * (double)p.y;
    }
    return fabs(a) / 2.0;
}

/* Box2D's polygon of a scene polygon, or why Box2D cannot represent it
 * unchanged (b2ComputeHull welds vertices closer than 4 B2_LINEAR_SLOP and
 * drops those within 2 B2_LINEAR_SLOP of the line through their
 * neighbours; it returns an empty hull when too little is left). Returns
 * false with a message in err. */
static bool make_polygon(const carom_body_def *d, b2Polygon *out, char *err, size_t errlen)
{
    const int n = d->vertex_count;
    b2Vec2 pts[B2_MAX_POLYGON_VERTICES];
    b2Hull hull;
    int i, j;
    if (n > B2_MAX_POLYGON_VERTICES) {
        snprintf(err, errlen, "polygon with %d vertices: Box2D allows at most %d "
                 "(B2_MAX_POLYGON_VERTICES)", n, B2_MAX_POLYGON_VERTICES);
        return false;
    }
    for (i = 0; i < n; ++i) {
        pts[i].x = d->vertices[i].x;
        pts[i].y = d->vertices[i].y;
    }
    hull = b2ComputeHull(pts, n);
    if (hull.count == 0) {
        snprintf(err, errlen, "Box2D's b2ComputeHull rejects this polygon (after welding "
                 "vertices closer than %.3g m and dropping nearly collinear ones, too "
                 "little is left): too thin or too small for Box2D",
                 (double)(4.0f * B2_LINEAR_SLOP));
        return false;
    }
    bool same = hull.count == n;
    for (i = 0; same && i < n; ++i) {
        bool found = false;
        for (j = 0; j < hull.count; ++j)
            if (hull.points[j].x == pts[i].x && hull.points[j].y == pts[i].y)
                found = true;
        same = found;
    }
    if (!same) {
        snprintf(err, errlen, "Box2D's convex hull of this polygon has %d of its %d "
                 "vertices (it welds vertices closer than %.3g m and drops nearly "
                 "collinear ones): Box2D cannot represent it unchanged", hull.count, n,
                 (double)(4.0f * B2_LINEAR_SLOP));
        return false;
    }
    if (!b2ValidateHull(&hull)) {
        snprintf(err, errlen, "Box2D's b2ValidateHull rejects this polygon (nearly "
                 "collinear vertices)");
        return false;
    }
    *out = b2MakePolygon(&hull, 0.0f);
    return true;
}

struct options {
    const char *scene_path;
    const char *trace_path;
    long steps;
    double dt;
    long substeps;
    long warmup;
    int threshold_mode; /* 0 Box2D's default, 1 the scene's rest-speed, 2 value */
    double threshold;
    bool sleep;
    bool bullets;
    bool timing;
    bool profile;
    bool quiet;
};

/* Box2D's step profile (b2World_GetProfile), in ms: the phases reported. */
#define PROFILE_FIELD(f) { #f, offsetof(b2Profile, f) }
static const struct {
    const char *name;
    size_t offset;
} profile_fields[] = {
    PROFILE_FIELD(step), PROFILE_FIELD(pairs), PROFILE_FIELD(collide),
    PROFILE_FIELD(solve), PROFILE_FIELD(solverSetup), PROFILE_FIELD(constraints),
    PROFILE_FIELD(prepareConstraints), PROFILE_FIELD(integrateVelocities),
    PROFILE_FIELD(warmStart), PROFILE_FIELD(solveImpulses),
    PROFILE_FIELD(integratePositions), PROFILE_FIELD(relaxImpulses),
    PROFILE_FIELD(applyRestitution), PROFILE_FIELD(storeImpulses),
    PROFILE_FIELD(splitIslands), PROFILE_FIELD(transforms), PROFILE_FIELD(refit),
    PROFILE_FIELD(bullets), PROFILE_FIELD(sleepIslands), PROFILE_FIELD(sensors),
};
#define PROFILE_COUNT ((int)(sizeof profile_fields / sizeof profile_fields[0]))

static float profile_value(const b2Profile *p, int i)
{
    float v;
    memcpy(&v, (const char *)p + profile_fields[i].offset, sizeof v);
    return v;
}

static FILE *open_out(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, PROG ": cannot write '%s': %s\n", path, strerror(errno));
    return f;
}

/* Box2D's linear velocity is the centre of mass's; a body without mass
 * (kinematic) has its centre at the origin, so for those the velocity of
 * the shape's centroid (carom's centre) is reported instead. */
static b2Vec2 centre_velocity(b2BodyId b, b2Vec2 centroid)
{
    if (b2Body_GetType(b) != b2_kinematicBody)
        return b2Body_GetLinearVelocity(b);
    return b2Body_GetWorldPointVelocity(b, b2Body_GetWorldPoint(b, centroid));
}

static void write_state(FILE *f, b2BodyId b, b2Vec2 centroid, int i, const char *prefix)
{
    const b2Pos p = b2Body_GetPosition(b);
    const b2Vec2 v = centre_velocity(b, centroid);
    fprintf(f, "%s%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", prefix, i, (double)p.x,
            (double)p.y, wrap_angle(b2Body_GetRotation(b)), (double)v.x, (double)v.y,
            (double)b2Body_GetAngularVelocity(b));
}

static void write_trace(FILE *f, const b2BodyId *bodies, const b2Vec2 *centroids, int n,
                        long step, float t)
{
    char prefix[64];
    int i;
    snprintf(prefix, sizeof prefix, "%ld,%.9g,", step, (double)t);
    for (i = 0; i < n; ++i)
        write_state(f, bodies[i], centroids[i], i, prefix);
}

static bool finite_state(b2BodyId b)
{
    const b2Pos p = b2Body_GetPosition(b);
    const b2Rot q = b2Body_GetRotation(b);
    const b2Vec2 v = b2Body_GetLinearVelocity(b);
    return isfinite((double)p.x) && isfinite((double)p.y) && isfinite(q.c) && isfinite(q.s) &&
           isfinite(v.x) && isfinite(v.y) && isfinite(b2Body_GetAngularVelocity(b));
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The scene's rest speed and contact slop as carom uses them. A carom with
 * CAROM_AUTO derives them when a field is CAROM_AUTO (< 0): ask the world. */
static void scene_tolerances(const scene *s, const carom_world *cw, double *rest,
                             double *slop)
{
    *rest = s->world.rest_speed;
    *slop = s->world.linear_slop;
#ifdef CAROM_AUTO
    {
        carom_tolerances t;
        if (carom_world_get_tolerances(cw, &t) == CAROM_OK) {
            *rest = t.rest_speed;
            *slop = t.linear_slop;
        }
    }
#else
    (void)cw;
#endif
}

/* Centroid of a polygon in its body frame (area-weighted). */
static b2Vec2 polygon_centroid(const carom_body_def *d)
{
    double a = 0.0, cx = 0.0, cy = 0.0;
    b2Vec2 c;
    int i;
    for (i = 0; i < d->vertex_count; ++i) {
        const carom_vec2 p = d->vertices[i];
        const carom_vec2 q = d->vertices[(i + 1) % d->vertex_count];
        const double cr = (double)p.x * (double)q.y - (double)q.x * (double)p.y;
        a += cr;
        cx += ((double)p.x + (double)q.x) * cr;
        cy += ((double)p.y + (double)q.y) * cr;
    }
    c.x = (float)(cx / (3.0 * a));
    c.y = (float)(cy / (3.0 * a));
    return c;
}

static int parse_options(int argc, char **argv, struct options *o, bool *help)
{
    int i;
    for (i = 0; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            *help = true;
            return 0;
        } else if (!strcmp(a, "--sleep")) {
            o->sleep = true;
        } else if (!strcmp(a, "--bullets")) {
            o->bullets = true;
        } else if (!strcmp(a, "--time")) {
            o->timing = true;
        } else if (!strcmp(a, "--profile")) {
            o->profile = true;
        } else if (!strcmp(a, "--quiet")) {
            o->quiet = true;
        } else if (!strcmp(a, "--steps") || !strcmp(a, "--dt") || !strcmp(a, "--trace") ||
                   !strcmp(a, "--substeps") || !strcmp(a, "--warmup") ||
                   !strcmp(a, "--restitution-threshold")) {
            const char *v;
            if (i + 1 >= argc)
                return usage_error("%s needs a value", a);
            v = argv[++i];
            if (!strcmp(a, "--steps")) {
                if (!parse_long(v, 0, 1000000000L, &o->steps))
                    return usage_error("--steps: want an integer in [0, 1e9], got '%s'", v);
            } else if (!strcmp(a, "--warmup")) {
                if (!parse_long(v, 0, 1000000000L, &o->warmup))
                    return usage_error("--warmup: want an integer in [0, 1e9], got '%s'", v);
            } else if (!strcmp(a, "--substeps")) {
                if (!parse_long(v, 1, 1000, &o->substeps))
                    return usage_error("--substeps: want an integer in [1, 1000], got '%s'", v);
            } else if (!strcmp(a, "--dt")) {
                if (!parse_double(v, &o->dt) || !(o->dt > 0.0) || o->dt > 1.0e30)
                    return usage_error("--dt: want a finite number > 0, got '%s'", v);
            } else if (!strcmp(a, "--restitution-threshold")) {
                if (!strcmp(v, "scene")) {
                    o->threshold_mode = 1;
                } else {
                    if (!parse_double(v, &o->threshold) || o->threshold < 0.0 ||
                        o->threshold > 1.0e30)
                        return usage_error("--restitution-threshold: want a finite number "
                                           ">= 0 or 'scene', got '%s'", v);
                    o->threshold_mode = 2;
                }
            } else {
                o->trace_path = v;
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else if (!o->scene_path) {
            o->scene_path = a;
        } else {
            return usage_error("more than one scene given ('%s')", a);
        }
    }
    if (!o->scene_path)
        return usage_error("%s", "run: missing SCENE");
    if (o->profile && !o->timing)
        return usage_error("%s", "--profile needs --time");
    return 0;
}

static void print_notes(const struct options *o, const scene *s, float threshold,
                        double rest_speed, double slop, bool any_polygon, double max_speed)
{
    fprintf(stderr, PROG ": note: Box2D v%d.%d.%d has one method (soft-step solver, %ld "
            "sub-steps, speculative contacts, continuous collision only %s); the scene's "
            "method=%s and velocity/position iterations are not used\n",
            b2GetVersion().major, b2GetVersion().minor, b2GetVersion().revision,
            o->substeps,
            o->bullets ? "for bullets and against static bodies" : "against static bodies",
            carom_method_name(s->world.method));
    fprintf(stderr, PROG ": note: Box2D's contact slop is B2_LINEAR_SLOP = %g m "
            "(compiled in); the scene's slop=%g m is not used; contacts are soft "
            "(30 Hz, damping ratio 10, push-out at most 3 m/s)\n",
            (double)B2_LINEAR_SLOP, slop);
    fprintf(stderr, PROG ": note: restitution threshold %g m/s (%s); the scene's "
            "rest-speed=%g m/s\n", (double)threshold,
            o->threshold_mode == 0 ? "Box2D's default"
                                   : o->threshold_mode == 1 ? "the scene's rest-speed"
                                                            : "--restitution-threshold",
            rest_speed);
    if (any_polygon)
        fprintf(stderr, PROG ": note: polygons have no rounding radius (no skin, unlike "
                "Box2D 2.4.1)\n");
    if (max_speed > 400.0)
        fprintf(stderr, PROG ": note: a body starts at %g m/s: Box2D clamps speeds to "
                "b2WorldDef.maximumLinearSpeed = 400 m/s\n", max_speed);
}

static int cmd_run(int argc, char **argv)
{
    struct options o;
    bool help = false;
    scene s;
    char err[512];
    carom_world *cw = NULL;
    void *cmem = NULL;
    b2BodyId *bodies = NULL;
    b2Vec2 *centroids = NULL;
    double *samples = NULL;
    FILE *trace = NULL;
    int rc = 0, i;
    long k, total, timed = 0;
    double spent = 0.0, max_speed = 0.0;
    double prof[PROFILE_COUNT] = { 0.0 };
    bool any_polygon = false;
    const char *path;
    float dt, threshold;
    double rest_speed, slop;
    b2WorldDef wd;
    b2WorldId world;

    memset(&o, 0, sizeof o);
    o.steps = -1;
    o.dt = -1.0;
    o.substeps = 4;
    rc = parse_options(argc, argv, &o, &help);
    if (help) {
        fputs(usage, stdout);
        return 0;
    }
    if (rc != 0)
        return rc;

    if (scene_load(o.scene_path, &s, err, sizeof err) != 0) {
        fprintf(stderr, PROG ": %s\n", err);
        return EXIT_USAGE;
    }
    if (o.steps >= 0)
        s.steps = o.steps;
    if (o.dt > 0.0)
        s.world.dt = (float)o.dt;
    path = o.scene_path;

    /* The carom world: the same checks as build/carom, and carom's masses. */
    if (scene_build_world(&s, &cw, &cmem, err, sizeof err) != 0) {
        fprintf(stderr, PROG ": %s: %s\n", path, err);
        scene_free(&s);
        return EXIT_USAGE;
    }

    dt = s.world.dt;
    wd = b2DefaultWorldDef();
    wd.gravity.x = s.world.gravity.x;
    wd.gravity.y = s.world.gravity.y;
    scene_tolerances(&s, cw, &rest_speed, &slop);
    if (o.threshold_mode == 1)
        wd.restitutionThreshold = (float)rest_speed;
    else if (o.threshold_mode == 2)
        wd.restitutionThreshold = (float)o.threshold;
    threshold = wd.restitutionThreshold;
    wd.enableSleep = o.sleep;
    wd.workerCount = 1;     /* no task system: everything on this thread */
    wd.enqueueTask = NULL;
    wd.finishTask = NULL;
    world = b2CreateWorld(&wd);
    if (!b2World_IsValid(world)) {
        fprintf(stderr, PROG ": b2CreateWorld failed\n");
        scene_free_world(cw, cmem);
        scene_free(&s);
        return EXIT_SIM;
    }

    bodies = calloc((size_t)(s.body_count > 0 ? s.body_count : 1), sizeof *bodies);
    centroids = calloc((size_t)(s.body_count > 0 ? s.body_count : 1), sizeof *centroids);
    if (!bodies || !centroids) {
        fprintf(stderr, PROG ": out of memory\n");
        rc = EXIT_SIM;
        goto done;
    }
    for (i = 0; i < s.body_count; ++i) {
        const scene_body *sb = &s.bodies[i];
        const carom_body_def *d = &sb->def;
        const bool dyn = d->type == CAROM_BODY_DYNAMIC;
        /* a carom with kinematic bodies has a third type */
        const bool kin = !dyn && d->type != CAROM_BODY_STATIC;
        b2BodyDef bd = b2DefaultBodyDef();
        b2ShapeDef sd = b2DefaultShapeDef();
        b2Polygon poly;
        b2BodyId b;
        double area;
        float cmass = 0.0f, cinertia = 0.0f;

        bd.type = dyn ? b2_dynamicBody : kin ? b2_kinematicBody : b2_staticBody;
        bd.position.x = d->position.x;
        bd.position.y = d->position.y;
        {
            /* carom's own rotation pair for the angle (scene.c), so both
             * engines start from the same numbers; normalised in double
             * as Box2D requires a unit pair. */
            const double c = d->rotation.c, sn = d->rotation.s;
            const double len = sqrt(c * c + sn * sn);
            bd.rotation.c = (float)(c / len);
            bd.rotation.s = (float)(sn / len);
        }
        bd.enableSleep = o.sleep;
        bd.isBullet = dyn && o.bullets;

        if (d->shape == CAROM_SHAPE_POLYGON) {
            if (!make_polygon(d, &poly, err, sizeof err)) {
                fprintf(stderr, PROG ": %s:%d: body %d: %s\n", path, sb->line, i, err);
                rc = EXIT_USAGE;
                goto done;
            }
            area = polygon_area(d);
            centroids[i] = polygon_centroid(d);
            any_polygon = true;
        } else {
            area = PI * (double)d->radius * (double)d->radius;
        }
        carom_body_get_mass(cw, i, &cmass, &cinertia);
        sd.density = dyn ? (float)((double)cmass / area) : 0.0f;
        sd.material.friction = d->friction;
        sd.material.restitution = d->restitution;

        b = b2CreateBody(world, &bd);
        if (d->shape == CAROM_SHAPE_POLYGON) {
            b2CreatePolygonShape(b, &sd, &poly);
        } else {
            b2Circle c;
            c.center.x = 0.0f;
            c.center.y = 0.0f;
            c.radius = d->radius;
            b2CreateCircleShape(b, &sd, &c);
        }
        if (kin) {
            /* Box2D moves a kinematic body's origin with its linear
             * velocity; carom's velocity is the centroid's. */
            const b2Vec2 r = b2RotateVector(bd.rotation, centroids[i]);
            b2Vec2 v;
            v.x = d->velocity.x + d->angular_velocity * r.y;
            v.y = d->velocity.y - d->angular_velocity * r.x;
            b2Body_SetLinearVelocity(b, v);
            b2Body_SetAngularVelocity(b, d->angular_velocity);
        }
        if (dyn) {
            /* carom's velocity is the centre of mass's, as is Box2D's
             * linear velocity: set once the shape has fixed the centre. */
            b2Vec2 v;
            double sp;
            v.x = d->velocity.x;
            v.y = d->velocity.y;
            b2Body_SetLinearVelocity(b, v);
            b2Body_SetAngularVelocity(b, d->angular_velocity);
            sp = hypot((double)v.x, (double)v.y);
            if (sp > max_speed)
                max_speed = sp;
            if (!o.quiet) {
                const double bm = b2Body_GetMass(b), bi = b2Body_GetRotationalInertia(b);
                if (fabs(bm - (double)cmass) > 1e-5 * (double)cmass ||
                    fabs(bi - (double)cinertia) > 1e-4 * (double)cinertia)
                    fprintf(stderr, PROG ": note: body %d: Box2D mass %.9g, inertia %.9g; "
                            "carom %.9g, %.9g\n", i, bm, bi, (double)cmass,
                            (double)cinertia);
            }
        }
        bodies[i] = b;
    }
    scene_free_world(cw, cmem);
    cmem = NULL;
    cw = NULL;

    if (!o.quiet)
        print_notes(&o, &s, threshold, rest_speed, slop, any_polygon, max_speed);

    if (o.trace_path) {
        if (!(trace = open_out(o.trace_path))) {
            rc = EXIT_USAGE;
            goto done;
        }
        fputs("step,t,body,x,y,angle,vx,vy,omega\n", trace);
        write_trace(trace, bodies, centroids, s.body_count, 0, 0.0f);
    }
    if (o.timing && s.steps > 0 && s.steps <= MAX_SAMPLES)
        samples = malloc((size_t)s.steps * sizeof *samples);

    total = o.warmup + s.steps;
    for (k = 0; k < total; ++k) {
        const bool timed_step = o.timing && k >= o.warmup;
        float t;
        bool ok = true;
        for (i = 0; i < s.body_count; ++i) {
            const carom_body_def *d = &s.bodies[i].def;
            if (d->type != CAROM_BODY_DYNAMIC)
                continue;
            if (d->force.x != 0.0f || d->force.y != 0.0f) {
                b2Vec2 f;
                f.x = d->force.x;
                f.y = d->force.y;
                b2Body_ApplyForceToCenter(bodies[i], f, true);
            }
            if (d->torque != 0.0f)
                b2Body_ApplyTorque(bodies[i], d->torque, true);
        }
        if (timed_step) {
            const double t0 = now_ns();
            double ns;
            b2World_Step(world, dt, (int)o.substeps);
            ns = now_ns() - t0;
            spent += ns;
            if (samples)
                samples[timed] = ns;
            ++timed;
            if (o.profile) {
                const b2Profile p = b2World_GetProfile(world);
                for (i = 0; i < PROFILE_COUNT; ++i)
                    prof[i] += (double)profile_value(&p, i);
            }
        } else {
            b2World_Step(world, dt, (int)o.substeps);
        }
        /* carom_world_time: steps times dt, in float */
        t = (float)(k + 1) * dt;
        if (trace)
            write_trace(trace, bodies, centroids, s.body_count, k + 1, t);
        for (i = 0; ok && i < s.body_count; ++i)
            ok = finite_state(bodies[i]);
        if (!ok) {
            fprintf(stderr, PROG ": %s: step %ld (t = %.9g s): Box2D produced a "
                    "non-finite state (body %d)\n", path, k + 1, (double)t, i - 1);
            rc = EXIT_SIM;
            break;
        }
    }
    if (o.timing) {
        double median = 0.0;
        if (samples && timed > 0) {
            qsort(samples, (size_t)timed, sizeof *samples, cmp_double);
            median = timed % 2 ? samples[timed / 2]
                               : 0.5 * (samples[timed / 2 - 1] + samples[timed / 2]);
        }
        if (samples || timed == 0)
            fprintf(stderr, PROG ": time: %ld steps, %.1f ns/step, median %.1f ns/step\n",
                    timed, timed > 0 ? spent / (double)timed : 0.0, median);
        else
            fprintf(stderr, PROG ": time: %ld steps, %.1f ns/step\n", timed,
                    spent / (double)timed);
        if (o.profile && timed > 0) {
            fprintf(stderr, PROG ": profile (b2World_GetProfile, mean ms/step):");
            for (i = 0; i < PROFILE_COUNT; ++i)
                fprintf(stderr, " %s=%.4f", profile_fields[i].name, prof[i] / (double)timed);
            fputc('\n', stderr);
        }
    }
    if (rc == 0) {
        puts("body,x,y,angle,vx,vy,omega");
        for (i = 0; i < s.body_count; ++i)
            write_state(stdout, bodies[i], centroids[i], i, "");
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, PROG ": error writing the final state\n");
            rc = EXIT_SIM;
        }
    }
    if (trace && fclose(trace) != 0 && rc == 0) {
        fprintf(stderr, PROG ": error writing '%s'\n", o.trace_path);
        rc = EXIT_SIM;
    }
    trace = NULL;

done:
    if (trace)
        fclose(trace);
    free(samples);
    free(bodies);
    free(centroids);
    scene_free_world(cw, cmem);
    b2DestroyWorld(world);
    scene_free(&s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage, stderr);
        return EXIT_USAGE;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        fputs(usage, stdout);
        return 0;
    }
    if (!strcmp(argv[1], "run"))
        return cmd_run(argc - 2, argv + 2);
    return usage_error("unknown command '%s' (run)", argv[1]);
}
