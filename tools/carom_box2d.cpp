/*
 * carom_box2d.cpp -- build/carom-box2d: run carom scene files through
 * Box2D 2.4.1 (Debian's libbox2d-dev), for validation against carom
 * (issue 5, tools/validation/, docs/validation.md).
 *
 * The scene is read by carom's own parser (tools/scene.c), so both engines
 * see the same numbers, and the carom world is built too: that checks the
 * scene exactly as build/carom does and gives carom's masses, inertias and
 * centres of mass to compare with Box2D's. The output formats are those of
 * build/carom (final state, --trace, --events).
 *
 * What Box2D cannot express is never silently changed: it is a note on
 * stderr (method, contact slop, polygon skin), or an error with exit status
 * 2 (a polygon Box2D would weld, reorder away or replace by a box).
 *
 * Exit status: 0 ok, 1 simulation error (non-finite state, or an output
 * file could not be written), 2 bad usage or bad scene.
 */
#include <box2d/box2d.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "carom.h"
#include "cli_options.h"
#include "scene.h"

namespace {

const char PROG[] = "carom-box2d";
const int EXIT_SIM = 1;
const int EXIT_USAGE = CLI_EXIT_USAGE;

const char usage[] =
    "usage: carom-box2d run SCENE [options]\n"
    "       carom-box2d --help\n"
    "\n"
    "Step a carom scene file (docs/scene-format.md) with Box2D 2.4.1 and write\n"
    "the final state of every body to stdout in build/carom's CSV format:\n"
    "body,x,y,angle,vx,vy,omega (x, y: body origin; angle in [-pi, pi];\n"
    "vx, vy: velocity of the centre of mass; omega: angular velocity).\n"
    "\n"
    "The Box2D world gets the scene's gravity, dt, iterations, shapes,\n"
    "densities (mass= becomes density = mass / area), restitution, friction,\n"
    "poses, velocities and constant forces; restitution threshold = the\n"
    "scene's rest-speed; sleeping off. Box2D mixes restitution (max) and\n"
    "friction (sqrt) as carom does.\n"
    "\n"
    "Options are written --opt VALUE or --opt=VALUE.\n"
    "\n"
    "options:\n"
    "  --steps N                  number of steps (overrides steps=)\n"
    "  --dt DT                    time step in seconds (overrides dt=)\n"
    "  --velocity-iterations N    Box2D velocity iterations (default 8)\n"
    "  --position-iterations N    Box2D position iterations (default 3)\n"
    "  --trace FILE               every body's state at step 0 and after every\n"
    "                             step: step,t,body,x,y,angle,vx,vy,omega\n"
    "  --events FILE              every contact that begins touching faster than\n"
    "                             the rest speed, one row per contact and step:\n"
    "                             t,body_a,body_b,nx,ny,impulse,approach_speed\n"
    "                             (t = end of the step; approach_speed = the\n"
    "                             relative normal velocity Box2D's restitution\n"
    "                             test uses: at the start of the step with the\n"
    "                             step's gravity and force kick, or when\n"
    "                             continuous collision finds the contact;\n"
    "                             impulse = total normal impulse of that step)\n"
    "  --masses FILE              carom's and Box2D's mass properties per body:\n"
    "                             body,carom_mass,box2d_mass,carom_inertia,\n"
    "                             box2d_inertia,cx,cy (inertia about the centre\n"
    "                             of mass; cx, cy: centre in the body frame)\n"
    "  --bullets                  make every dynamic body a Box2D bullet\n"
    "                             (continuous collision against dynamic bodies\n"
    "                             too; by default only against static ones)\n"
    "  --time                     print the Step() time to stderr:\n"
    "                             'carom-box2d: time: N steps, X ns/step'\n"
    "  --quiet                    no notes on stderr (errors still go there)\n"
    "  -h, --help                 show this help\n"
    "\n"
    "Notes on stderr name every difference Box2D cannot avoid: it has one\n"
    "method (contacts found where bodies overlap at the start of a step,\n"
    "continuous collision for bullets and against static bodies), a fixed\n"
    "contact slop b2_linearSlop = 0.005 m, and a skin b2_polygonRadius =\n"
    "0.01 m around every polygon. A polygon Box2D would alter (vertices\n"
    "closer than 0.0025 m are welded, collinear ones dropped) is an error.\n"
    "\n"
    "exit status: 0 ok, 1 simulation error, 2 bad usage or bad scene\n";

/* Angle of a rotation in [-pi, pi], like carom_rot_angle. */
double wrap_angle(const b2Rot &q)
{
    double a = std::atan2((double)q.s, (double)q.c);
    if (a <= -M_PI)
        a = M_PI;
    return a;
}

/* ---- contact events ----------------------------------------------------- */

struct pending_event {
    b2Contact *contact;
    int a, b;           /* body ids, a < b */
    double nx, ny;      /* from a to b */
    double approach;    /* m/s, > rest speed */
    double impulse;     /* sum of normal impulses reported this step */
};

/* Each body's state at the start of the step and the velocity change the
 * step's gravity and constant force give it before Box2D solves contacts
 * (b2Island::Solve integrates velocities first). */
struct body_snapshot {
    b2Vec2 p, v;
    float angle, w;
    b2Vec2 kick_v;
    float kick_w;
};

class event_listener : public b2ContactListener {
public:
    float rest_speed = 0.5f;
    std::vector<pending_event> pending;
    std::vector<body_snapshot> snap;

    static int id_of(b2Body *b)
    {
        return (int)b->GetUserData().pointer;
    }

    /* The velocity Box2D's contact solver starts from: for a contact found
     * at the start of the step (the body has not moved yet), the body's
     * velocity plus this step's kick; for one found later by continuous
     * collision, the velocity it has then. */
    void solver_velocity(b2Body *b, b2Vec2 *v, float *w) const
    {
        const body_snapshot &s = snap[(size_t)id_of(b)];
        *v = b->GetLinearVelocity();
        *w = b->GetAngularVelocity();
        if (b->GetPosition() == s.p && b->GetAngle() == s.angle && *v == s.v && *w == s.w) {
            *v += s.kick_v;
            *w += s.kick_w;
        }
    }

    /* PreSolve runs for every touching contact before it is solved; a
     * contact whose old manifold is empty has just begun touching. The
     * approach speed is the one Box2D's restitution test uses: the largest
     * relative normal velocity at the manifold points. */
    void PreSolve(b2Contact *contact, const b2Manifold *old) override
    {
        const b2Manifold *m = contact->GetManifold();
        if (old->pointCount != 0 || m->pointCount == 0 || snap.empty())
            return;
        b2Body *ba = contact->GetFixtureA()->GetBody();
        b2Body *bb = contact->GetFixtureB()->GetBody();
        b2WorldManifold wm;
        contact->GetWorldManifold(&wm);
        b2Vec2 va, vb;
        float wa, wb;
        solver_velocity(ba, &va, &wa);
        solver_velocity(bb, &vb, &wb);
        const b2Vec2 ca = ba->GetWorldCenter(), cb = bb->GetWorldCenter();
        double approach = 0.0;
        for (int i = 0; i < m->pointCount; ++i) {
            const b2Vec2 p = wm.points[i];
            const b2Vec2 dv = vb + b2Cross(wb, p - cb) - va - b2Cross(wa, p - ca);
            const double vn = (double)dv.x * wm.normal.x + (double)dv.y * wm.normal.y;
            approach = std::max(approach, -vn);
        }
        if (!(approach > (double)rest_speed))
            return;
        pending_event e;
        e.contact = contact;
        e.a = id_of(ba);
        e.b = id_of(bb);
        e.nx = wm.normal.x;
        e.ny = wm.normal.y;
        if (e.a > e.b) {
            std::swap(e.a, e.b);
            e.nx = -e.nx;
            e.ny = -e.ny;
        }
        e.approach = approach;
        e.impulse = 0.0;
        pending.push_back(e);
    }

    /* Box2D reports the accumulated impulses of every solved contact. A
     * contact can be solved twice in a step (regular solve, then a
     * time-of-impact sub-step with fresh impulses): the sum is the step's. */
    void PostSolve(b2Contact *contact, const b2ContactImpulse *imp) override
    {
        for (pending_event &e : pending) {
            if (e.contact != contact)
                continue;
            for (int i = 0; i < imp->count; ++i)
                e.impulse += imp->normalImpulses[i];
        }
    }
};

/* ---- building the Box2D world --------------------------------------------- */

double polygon_area(const carom_body_def &d)
{
    double a = 0.0;
    for (int i = 0; i < d.vertex_count; ++i) {
        const carom_vec2 &p = d.vertices[i];
        const carom_vec2 &q = d.vertices[(i + 1) % d.vertex_count];
        a += (double)p.x * q.y - (double)q.x * p.y;
    }
    return std::fabs(a) / 2.0;
}

/* Smallest width of a convex polygon (over its edge normals). */
double polygon_width(const carom_body_def &d)
{
    double best = INFINITY;
    int n = d.vertex_count;
    for (int i = 0; i < n; ++i) {
        const carom_vec2 &p = d.vertices[i];
        const carom_vec2 &q = d.vertices[(i + 1) % n];
        double ex = (double)q.x - p.x, ey = (double)q.y - p.y;
        double len = std::sqrt(ex * ex + ey * ey);
        double w = 0.0;
        for (int j = 0; j < n; ++j) {
            double dx = (double)d.vertices[j].x - p.x;
            double dy = (double)d.vertices[j].y - p.y;
            w = std::max(w, std::fabs(ex * dy - ey * dx) / len);
        }
        best = std::min(best, w);
    }
    return best;
}

/* Make Box2D's polygon of a scene polygon, or explain why Box2D cannot
 * represent it unchanged (b2PolygonShape::Set welds vertices closer than
 * 0.5 b2_linearSlop, drops collinear ones in its hull, and replaces what is
 * left degenerate by a 2 x 2 box). Returns false with a message in err. */
bool make_polygon(const carom_body_def &d, b2PolygonShape *shape, char *err,
                  size_t errlen)
{
    const int n = d.vertex_count;
    const float weld = 0.5f * b2_linearSlop;
    b2Vec2 pts[b2_maxPolygonVertices];
    if (n > b2_maxPolygonVertices) {
        std::snprintf(err, errlen, "polygon with %d vertices: Box2D allows at most %d "
                      "(b2_maxPolygonVertices)", n, b2_maxPolygonVertices);
        return false;
    }
    for (int i = 0; i < n; ++i)
        pts[i].Set(d.vertices[i].x, d.vertices[i].y);
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (b2DistanceSquared(pts[i], pts[j]) < weld * weld) {
                std::snprintf(err, errlen, "vertices %d and %d are %.3g m apart: Box2D welds "
                              "vertices closer than %.4g m (0.5 b2_linearSlop), so it cannot "
                              "represent this polygon (too thin or too small for Box2D)",
                              i, j, (double)b2Distance(pts[i], pts[j]), (double)weld);
                return false;
            }
    shape->Set(pts, n);
    /* Box2D's hull must hold exactly the scene's vertices. */
    bool same = shape->m_count == n;
    for (int i = 0; same && i < n; ++i) {
        bool found = false;
        for (int j = 0; j < shape->m_count; ++j)
            if (shape->m_vertices[j].x == pts[i].x && shape->m_vertices[j].y == pts[i].y)
                found = true;
        same = found;
    }
    if (!same) {
        std::snprintf(err, errlen, "Box2D's convex hull of this polygon has %d of its %d "
                      "vertices (it drops nearly collinear vertices): Box2D cannot "
                      "represent it unchanged", shape->m_count, n);
        return false;
    }
    return true;
}

/* ---- output and helpers ------------------------------------------------------ */

/* What the listener needs to know of the start of a step. Constant forces
 * have been applied already (GetMass etc. are public; the force is not, so
 * the kick of a body's constant force comes from the scene). */
void take_snapshot(std::vector<body_snapshot> &snap, const scene &sc,
                   const std::vector<b2Body *> &bodies, b2Vec2 gravity, float dt)
{
    snap.resize(bodies.size());
    for (size_t i = 0; i < bodies.size(); ++i) {
        b2Body *b = bodies[i];
        body_snapshot &s = snap[i];
        s.p = b->GetPosition();
        s.angle = b->GetAngle();
        s.v = b->GetLinearVelocity();
        s.w = b->GetAngularVelocity();
        s.kick_v.SetZero();
        s.kick_w = 0.0f;
        if (b->GetType() == b2_dynamicBody && b->GetMass() > 0.0f) {
            const carom_body_def &d = sc.bodies[i].def;
            const float inv_m = 1.0f / b->GetMass();
            s.kick_v = dt * (b->GetGravityScale() * gravity + inv_m * b2Vec2(d.force.x, d.force.y));
            /* GetInertia is about the origin; Box2D's invI is about the centre */
            const b2Vec2 lc = b->GetLocalCenter();
            const float ic = b->GetInertia() - b->GetMass() * b2Dot(lc, lc);
            s.kick_w = ic > 0.0f ? dt * d.torque / ic : 0.0f;
        }
    }
}

FILE *open_out(const char *path)
{
    FILE *f = std::fopen(path, "w");
    if (!f)
        std::fprintf(stderr, "carom-box2d: cannot write '%s': %s\n", path, std::strerror(errno));
    return f;
}

void write_state(FILE *f, const b2Body *b, int i, const char *prefix)
{
    const b2Vec2 p = b->GetPosition();
    const b2Vec2 v = b->GetLinearVelocity();
    std::fprintf(f, "%s%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", prefix, i, (double)p.x,
                 (double)p.y, wrap_angle(b->GetTransform().q), (double)v.x, (double)v.y,
                 (double)b->GetAngularVelocity());
}

void write_trace(FILE *f, const std::vector<b2Body *> &bodies, long step, float t)
{
    char prefix[64];
    std::snprintf(prefix, sizeof prefix, "%ld,%.9g,", step, (double)t);
    for (size_t i = 0; i < bodies.size(); ++i)
        write_state(f, bodies[i], (int)i, prefix);
}

bool finite_state(const b2Body *b)
{
    const b2Vec2 p = b->GetPosition();
    const b2Vec2 v = b->GetLinearVelocity();
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(b->GetAngle()) &&
           std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(b->GetAngularVelocity());
}

double now_ns()
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}


/* ---- the run command -------------------------------------------------------- */

struct options {
    const char *scene_path = nullptr;
    const char *trace_path = nullptr;
    const char *events_path = nullptr;
    const char *masses_path = nullptr;
    long steps = -1;
    double dt = -1.0;
    long vel_iters = -1;
    long pos_iters = -1;
    bool bullets = false;
    bool timing = false;
    bool quiet = false;
};

/* Go on with the run (not an exit status). */
const int CONTINUE = -1;

enum option_id {
    OPT_STEPS, OPT_DT, OPT_VEL_ITERS, OPT_POS_ITERS, OPT_TRACE, OPT_EVENTS, OPT_MASSES,
    OPT_BULLETS, OPT_TIME, OPT_QUIET, OPT_HELP
};

const unsigned CMD_RUN = 1u;

/* The options of `run`, as `usage` lists them. A value's name is "": the
 * messages name none ("--steps needs a value"). */
const cli_option run_options[] = {
    {OPT_STEPS, "steps", 0, "", CMD_RUN, nullptr},
    {OPT_DT, "dt", 0, "", CMD_RUN, nullptr},
    {OPT_VEL_ITERS, "velocity-iterations", 0, "", CMD_RUN, nullptr},
    {OPT_POS_ITERS, "position-iterations", 0, "", CMD_RUN, nullptr},
    {OPT_TRACE, "trace", 0, "", CMD_RUN, nullptr},
    {OPT_EVENTS, "events", 0, "", CMD_RUN, nullptr},
    {OPT_MASSES, "masses", 0, "", CMD_RUN, nullptr},
    {OPT_BULLETS, "bullets", 0, nullptr, CMD_RUN, nullptr},
    {OPT_TIME, "time", 0, nullptr, CMD_RUN, nullptr},
    {OPT_QUIET, "quiet", 0, nullptr, CMD_RUN, nullptr},
    {OPT_HELP, "help", 'h', nullptr, CMD_RUN, nullptr},
};

/* Option p.opt into *o: 0, or an exit status after a message. */
int set_option(options *o, const cli_parser &p)
{
    switch ((option_id)p.opt->id) {
    case OPT_STEPS: return cli_long(&p, 0, 1000000000L, "an integer in [0, 1e9]", &o->steps);
    case OPT_DT: return cli_double(&p, 0.0, CLI_OPEN, 1.0e30, "a finite number > 0", &o->dt);
    case OPT_VEL_ITERS: return cli_long(&p, 0, 1000, nullptr, &o->vel_iters);
    case OPT_POS_ITERS: return cli_long(&p, 0, 1000, nullptr, &o->pos_iters);
    case OPT_TRACE: o->trace_path = p.value; break;
    case OPT_EVENTS: o->events_path = p.value; break;
    case OPT_MASSES: o->masses_path = p.value; break;
    case OPT_BULLETS: o->bullets = true; break;
    case OPT_TIME: o->timing = true; break;
    case OPT_QUIET: o->quiet = true; break;
    case OPT_HELP: break;
    }
    return 0;
}

/* The options of `run`. Returns CONTINUE, or an exit status (0 after
 * --help). */
int parse_run_options(int argc, char **argv, options *o)
{
    cli_parser p;
    cli_start(&p, PROG, run_options, (int)(sizeof run_options / sizeof run_options[0]),
              CMD_RUN, argc, argv);
    cli_item item;
    while ((item = cli_next(&p)) != CLI_END) {
        if (item == CLI_ERROR)
            return EXIT_USAGE;
        if (item == CLI_OPERAND) {
            if (o->scene_path)
                return cli_usage_error(PROG, "more than one scene given ('%s')", p.value);
            o->scene_path = p.value;
        } else if (p.opt->id == OPT_HELP) {
            std::fputs(usage, stdout);
            return 0;
        } else if (const int rc = set_option(o, p)) {
            return rc;
        }
    }
    if (!o->scene_path)
        return cli_usage_error(PROG, "run: missing SCENE");
    return CONTINUE;
}

/* What a run owns: released on every way out. */
struct run_resources {
    scene s;
    bool have_scene = false;
    carom_world *cw = nullptr;
    void *carom_mem = nullptr;
    FILE *trace = nullptr;
    FILE *events = nullptr;

    run_resources() { std::memset(&s, 0, sizeof s); }
    ~run_resources()
    {
        if (trace)
            std::fclose(trace);
        if (events)
            std::fclose(events);
        scene_free_world(cw, carom_mem);
        if (have_scene)
            scene_free(&s);
    }
    run_resources(const run_resources &) = delete;
    run_resources &operator=(const run_resources &) = delete;
};

/* The scene with the command line's overrides, and its carom world (the
 * same checks as build/carom, and the reference mass properties). Returns
 * CONTINUE, or EXIT_USAGE after a message. */
int load_scene(const options &o, run_resources *r)
{
    char err[512];
    if (scene_load(o.scene_path, &r->s, err, sizeof err) != 0) {
        std::fprintf(stderr, "carom-box2d: %s\n", err);
        return EXIT_USAGE;
    }
    r->have_scene = true;
    if (o.steps >= 0)
        r->s.steps = o.steps;
    if (o.dt > 0.0)
        r->s.world.dt = (float)o.dt;
    if (scene_build_world(&r->s, &r->cw, &r->carom_mem, err, sizeof err) != 0) {
        std::fprintf(stderr, "carom-box2d: %s: %s\n", o.scene_path, err);
        return EXIT_USAGE;
    }
    return CONTINUE;
}

/* The thinnest polygon of the scene, for the note on Box2D's skin. */
struct polygon_summary {
    bool any = false;
    double thinnest = INFINITY;
    int thinnest_id = -1;
};

/* Body i of the scene in `world` (user data i), or nullptr after a message
 * if Box2D cannot represent its shape. */
b2Body *create_body(const options &o, const scene_body &sb, int i, carom_world *cw,
                    float rest, b2World &world, polygon_summary *polys)
{
    const carom_body_def &d = sb.def;
    const bool dyn = d.type == CAROM_BODY_DYNAMIC;
    b2BodyDef bd;
    if (d.category_bits > 0xffffu || (d.mask_bits > 0xffffu && d.mask_bits != 0xffffffffu)) {
        std::fprintf(stderr,
                     "carom-box2d: %s:%d: body %d: unsupported: Box2D 2.4.1 has 16 filter "
                     "bits (category 0x%x, mask 0x%x)\n",
                     o.scene_path, sb.line, i, (unsigned)d.category_bits, (unsigned)d.mask_bits);
        return nullptr;
    }
    bd.type = dyn ? b2_dynamicBody
                  : (d.type == CAROM_BODY_KINEMATIC ? b2_kinematicBody : b2_staticBody);
    if (d.type == CAROM_BODY_KINEMATIC) {
        bd.linearVelocity.Set(d.velocity.x, d.velocity.y);
        bd.angularVelocity = d.angular_velocity;
    }
    bd.position.Set(d.position.x, d.position.y);
    bd.angle = sb.angle;
    bd.allowSleep = false;
    bd.bullet = dyn && o.bullets;
    bd.userData.pointer = (uintptr_t)i;

    b2CircleShape circle;
    b2PolygonShape poly;
    b2FixtureDef fd;
    double area;
    if (d.shape == CAROM_SHAPE_CIRCLE) {
        circle.m_radius = d.radius;
        fd.shape = &circle;
        area = M_PI * (double)d.radius * (double)d.radius;
    } else {
        char err[512];
        if (!make_polygon(d, &poly, err, sizeof err)) {
            std::fprintf(stderr, "carom-box2d: %s:%d: body %d: %s\n", o.scene_path, sb.line, i,
                         err);
            return nullptr;
        }
        fd.shape = &poly;
        area = polygon_area(d);
        polys->any = true;
        double w = polygon_width(d);
        if (w < polys->thinnest) {
            polys->thinnest = w;
            polys->thinnest_id = i;
        }
    }
    float cmass = 0.0f, cinertia = 0.0f;
    carom_body_get_mass(cw, i, &cmass, &cinertia);
    fd.density = dyn ? (float)((double)cmass / area) : 0.0f;
    fd.friction = d.friction;
    fd.restitution = d.restitution;
    fd.restitutionThreshold = rest;
    /* filter and sensors map one to one (16 bits in Box2D 2.4.1) */
    fd.isSensor = d.is_sensor != 0;
    fd.filter.categoryBits = (uint16_t)d.category_bits;
    fd.filter.maskBits = (uint16_t)(d.mask_bits & 0xffffu);
    fd.filter.groupIndex = (int16_t)d.group_index;
    b2Body *b = world.CreateBody(&bd);
    b->CreateFixture(&fd);
    if (dyn) {
        /* carom's velocity is the centre of mass's, as is Box2D's linear
         * velocity: set after the fixture fixed the centre. */
        b->SetLinearVelocity(b2Vec2(d.velocity.x, d.velocity.y));
        b->SetAngularVelocity(d.angular_velocity);
        float bm = b->GetMass();
        if (std::fabs((double)bm - cmass) > 1e-5 * cmass && !o.quiet)
            std::fprintf(stderr, "carom-box2d: note: body %d: Box2D mass %.9g, carom %.9g\n", i,
                         (double)bm, (double)cmass);
    }
    return b;
}

/* Every difference Box2D cannot avoid, on stderr. */
void print_notes(const options &o, const scene &s, const carom_tolerances &tol,
                 const polygon_summary &polys)
{
    std::fprintf(stderr, "carom-box2d: note: Box2D has one method (contacts found where "
                 "bodies overlap at the start of a step; continuous collision only %s); "
                 "the scene's method=%s is not used\n",
                 o.bullets ? "for bullets and against static bodies" : "against static bodies",
                 carom_method_name(s.world.method));
    std::fprintf(stderr, "carom-box2d: note: Box2D's contact slop is b2_linearSlop = "
                 "%g m (compiled in); the scene's slop=%g m is not used\n",
                 (double)b2_linearSlop, (double)tol.linear_slop);
    if (polys.any)
        std::fprintf(stderr, "carom-box2d: note: every Box2D polygon has a skin of b2_polygonRadius "
                     "= %g m (it collides as if that much larger all round); thinnest polygon: body "
                     "%d, %.4g m wide%s\n", (double)b2_polygonRadius, polys.thinnest_id,
                     polys.thinnest,
                     polys.thinnest < 2.0 * b2_polygonRadius
                         ? " (less than twice the skin: Box2D's collision shape is more "
                           "than twice as thick)"
                         : "");
}

/* --masses: carom's and Box2D's mass properties per body. Returns
 * CONTINUE, EXIT_USAGE (cannot open) or EXIT_SIM (cannot write). */
int write_masses(const char *path, carom_world *cw, const std::vector<b2Body *> &bodies)
{
    FILE *mf = open_out(path);
    if (!mf)
        return EXIT_USAGE;
    std::fputs("body,carom_mass,box2d_mass,carom_inertia,box2d_inertia,cx,cy\n", mf);
    for (size_t i = 0; i < bodies.size(); ++i) {
        float cm = 0.0f, ci = 0.0f;
        carom_body_get_mass(cw, (int)i, &cm, &ci);
        const b2Body *b = bodies[i];
        b2Vec2 lc = b->GetLocalCenter();
        double bm = b->GetMass();
        /* GetInertia is about the body origin */
        double bi = (double)b->GetInertia() - bm * ((double)lc.x * lc.x + (double)lc.y * lc.y);
        std::fprintf(mf, "%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", i, (double)cm, bm, (double)ci, bi,
                     (double)lc.x, (double)lc.y);
    }
    if (std::fclose(mf) != 0) {
        std::fprintf(stderr, "carom-box2d: error writing '%s'\n", path);
        return EXIT_SIM;
    }
    return CONTINUE;
}

/* --trace and --events, with their headers and the trace's step 0.
 * Returns CONTINUE or EXIT_USAGE. */
int open_outputs(const options &o, const std::vector<b2Body *> &bodies, run_resources *r)
{
    if (o.trace_path && !(r->trace = open_out(o.trace_path)))
        return EXIT_USAGE;
    if (o.events_path && !(r->events = open_out(o.events_path)))
        return EXIT_USAGE;
    if (r->trace) {
        std::fputs("step,t,body,x,y,angle,vx,vy,omega\n", r->trace);
        write_trace(r->trace, bodies, 0, 0.0f);
    }
    if (r->events)
        std::fputs("t,body_a,body_b,nx,ny,impulse,approach_speed\n", r->events);
    return CONTINUE;
}

/* The scene's constant forces and torques, for the coming step (Box2D
 * clears applied forces after every Step). */
void apply_constant_forces(const scene &s, const std::vector<b2Body *> &bodies)
{
    for (int i = 0; i < s.body_count; ++i) {
        const carom_body_def &d = s.bodies[i].def;
        if (d.type != CAROM_BODY_DYNAMIC)
            continue;
        if (d.force.x != 0.0f || d.force.y != 0.0f)
            bodies[i]->ApplyForceToCenter(b2Vec2(d.force.x, d.force.y), true);
        if (d.torque != 0.0f)
            bodies[i]->ApplyTorque(d.torque, true);
    }
}

/* The step's impacts, ordered by body pair, stamped with the step's end. */
void write_step_events(FILE *f, std::vector<pending_event> &ev, float t)
{
    std::stable_sort(ev.begin(), ev.end(), [](const pending_event &x, const pending_event &y) {
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    for (const pending_event &e : ev)
        std::fprintf(f, "%.9g,%d,%d,%.9g,%.9g,%.9g,%.9g\n", (double)t, e.a, e.b, e.nx, e.ny,
                     e.impulse, e.approach);
}

bool all_finite(const std::vector<b2Body *> &bodies)
{
    bool ok = true;
    for (const b2Body *b : bodies)
        ok = ok && finite_state(b);
    return ok;
}

/* Step the world s.steps times, writing the trace and events as it goes.
 * Returns 0, or EXIT_SIM after a message if Box2D's state stops being
 * finite. */
int simulate(const options &o, const scene &s, b2World &world, event_listener &listener,
             const std::vector<b2Body *> &bodies, FILE *trace, FILE *events)
{
    /* Box2D's own recommended counts unless given: the scene's substeps
     * are carom's solver, not Box2D's */
    const int vel_iters = o.vel_iters >= 0 ? (int)o.vel_iters : 8;
    const int pos_iters = o.pos_iters >= 0 ? (int)o.pos_iters : 3;
    const float dt = s.world.dt;
    double spent = 0.0;
    int rc = 0;
    long k;
    for (k = 0; k < s.steps; ++k) {
        double t0 = o.timing ? now_ns() : 0.0;
        apply_constant_forces(s, bodies);
        listener.pending.clear();
        if (events)
            take_snapshot(listener.snap, s, bodies, world.GetGravity(), dt);
        world.Step(dt, vel_iters, pos_iters);
        if (o.timing)
            spent += now_ns() - t0;
        /* carom_world_time: steps times dt, in float */
        const float t = (float)(k + 1) * dt;
        if (events)
            write_step_events(events, listener.pending, t);
        if (trace)
            write_trace(trace, bodies, k + 1, t);
        if (!all_finite(bodies)) {
            std::fprintf(stderr, "carom-box2d: %s: step %ld (t = %.9g s): Box2D produced a "
                         "non-finite state\n", o.scene_path, k + 1, (double)t);
            rc = EXIT_SIM;
            ++k;
            break;
        }
    }
    if (o.timing)
        std::fprintf(stderr, "carom-box2d: time: %ld steps, %.1f ns/step\n", k,
                     k > 0 ? spent / (double)k : 0.0);
    return rc;
}

/* The final state on stdout. Returns 0 or EXIT_SIM. */
int write_final_state(const std::vector<b2Body *> &bodies)
{
    std::puts("body,x,y,angle,vx,vy,omega");
    for (size_t i = 0; i < bodies.size(); ++i)
        write_state(stdout, bodies[i], (int)i, "");
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::fprintf(stderr, "carom-box2d: error writing the final state\n");
        return EXIT_SIM;
    }
    return 0;
}

/* Close an output file (*f becomes null); a write error is EXIT_SIM unless
 * the run has failed already. */
int close_output(FILE **f, const char *path, int rc)
{
    if (*f && std::fclose(*f) != 0 && rc == 0) {
        std::fprintf(stderr, "carom-box2d: error writing '%s'\n", path);
        rc = EXIT_SIM;
    }
    *f = nullptr;
    return rc;
}

int cmd_run(int argc, char **argv)
{
    options o;
    int rc = parse_run_options(argc, argv, &o);
    if (rc != CONTINUE)
        return rc;
    run_resources r;
    if ((rc = load_scene(o, &r)) != CONTINUE)
        return rc;

    /* carom's rest speed as resolved for this scene (CAROM_AUTO: from
     * |gravity| dt) is Box2D's restitution threshold */
    carom_tolerances tol;
    carom_world_get_tolerances(r.cw, &tol);
    b2World world(b2Vec2(r.s.world.gravity.x, r.s.world.gravity.y));
    world.SetAllowSleeping(false);
    event_listener listener;
    listener.rest_speed = tol.rest_speed;
    if (o.events_path)
        world.SetContactListener(&listener);

    std::vector<b2Body *> bodies;
    polygon_summary polys;
    for (int i = 0; i < r.s.body_count; ++i) {
        b2Body *b = create_body(o, r.s.bodies[i], i, r.cw, tol.rest_speed, world, &polys);
        if (!b)
            return EXIT_USAGE;
        bodies.push_back(b);
    }
    if (!o.quiet)
        print_notes(o, r.s, tol, polys);
    if (o.masses_path && (rc = write_masses(o.masses_path, r.cw, bodies)) != CONTINUE)
        return rc;
    if ((rc = open_outputs(o, bodies, &r)) != CONTINUE)
        return rc;

    rc = simulate(o, r.s, world, listener, bodies, r.trace, r.events);
    if (rc == 0)
        rc = write_final_state(bodies);
    rc = close_output(&r.trace, o.trace_path, rc);
    return close_output(&r.events, o.events_path, rc);
}

} // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fputs(usage, stderr);
        return EXIT_USAGE;
    }
    if (!std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "--help") ||
        !std::strcmp(argv[1], "help")) {
        std::fputs(usage, stdout);
        return 0;
    }
    if (!std::strcmp(argv[1], "run"))
        return cmd_run(argc - 2, argv + 2);
    return cli_usage_error(PROG, "unknown command '%s' (run)", argv[1]);
}
