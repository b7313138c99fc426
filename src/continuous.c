/*
 * continuous.c -- the step's continuous guard against static and
 * kinematic bodies.
 *
 * The contact solver stops a body at a static body through the
 * speculative contacts made at the step's start: their anchors and normal
 * are those of the start pose, and the solver moves them with the body.
 * A body that turns farther in a substep than that linear picture follows
 * (a thin rod spinning at hundreds of rad/s, 1.7 rad a substep) can end
 * the step in a wall, or past it, while its contacts read a gap; so can a
 * body that meets several bodies in one step (bounced off one into the
 * next), or one an impulse drives off the path its contacts were made for
 * (a ball under a box 10^6 times heavier landing on it, whose squeeze no
 * solver holds). The events methods time impacts on the bodies' paths and
 * meet fewer of these; the discrete method met them all.
 *
 * So, once every body is at its end pose: a dynamic body whose step could
 * carry a point farther than half the thinner half-width of the two (it
 * is "fast": by its translation and, for a polygon, its turn times its
 * extent; Box2D v3 takes half the smallest extent too; the wall's counts
 * for a body already deep in a thin wall) is swept against each static body
 * of its candidate pairs (and, if it ended outside the box its pairs were
 * found with, against every static body the grid holds around it), along
 * the path from its start pose to its end pose (uniform motion, the turn
 * the shorter way round plus the whole turns of its mean spin), by the
 * time of impact of toi.c. Where that path meets the static body, the
 * normal n there (static towards body) and the end pose tell what the
 * step did:
 *
 *   into     at its end pose the body overlaps the static body deeper
 *            than where the path met it, by more than
 *            max(CR_THROUGH_SLOPS slops, CR_THROUGH_WIDTH half-widths):
 *            more than the solver leaves when it stops a body;
 *   through  at its end pose the body lies wholly on the static body's
 *            far side along n, and across n the two still overlap there
 *            or where its way first cleared the far side;
 *   out the far side
 *            at its end pose the body overlaps the static body by more
 *            than a slop, and the static body's least way out for it
 *            points against n (a body driven nearly through a thin wall
 *            in one step, which the next step's contact would push out
 *            of the wall's far side);
 *   centre through
 *            the straight way of its centre from the meeting to the end
 *            pose goes deeper into the static body than the smaller of
 *            the "into" threshold and CR_CENTRE_DEPTH of the static
 *            body's half-width (a body crossing a wall's corner
 *            slantwise, out of its end face).
 *
 * Any of these, and the body is put back at the pose where its path met
 * the static body, with the velocity of the meeting's time, and the
 * meeting takes Newton's frictionless impulse there (cr_meet_static); the
 * next step's contacts take it from there. A body that touched the static
 * body at the step's start meets it at the start pose, and the part that
 * went in may be another: the points where it lies in the static body at
 * its end pose, carried back to the start pose, take the impulse too;
 * one put back where it started two steps running is still. A path that
 * met the static body and left it (a bounce within the step, a body
 * sliding off a ledge) is none of them and changes nothing, so in a step
 * with no stop every bit is as without this guard.
 *
 * Kinematic bodies are held against the same way: no impulse moves them
 * either. One moves uniformly through the step, so the body's path is
 * swept against its path, and the tests are made at its end pose with
 * the meeting carried along with it (against a turning one, the centre's
 * way as seen from it is a curve, followed in pieces, and "through",
 * whose normal turned, is left out). A body that went in takes the
 * impulse at the meeting, relative to the kinematic body's point there,
 * and flies on to the step's end (cr_fly_off), or, if that leaves it in
 * the kinematic body or the flight meets another static or kinematic
 * body, is put at the carried meeting and takes it there. Last, a body
 * carried or sent flying is swept again, from its start pose to where
 * it was taken, against the static bodies on its way, with every test
 * but "into" (cr_continuous_carried): nothing moves a static body.
 */
#include "continuous.h"

#include "broadphase.h"
#include "narrowphase.h"
#include "solver.h"
#include "toi.h"

#if CR_CONTINUOUS

/* fast: the step could carry a point farther than this much of the
 * body's half-width (Box2D v3 uses half its smallest extent too) */
#define CR_FAST_FRACTION 0.5f
/* into: deeper than the meeting by more than the larger of these */
#define CR_THROUGH_SLOPS 4.0f
#define CR_THROUGH_WIDTH 0.5f
/* out the far side: the way out of the end pose points against the
 * meeting's normal by more than 60 degrees past square (a wedge's tip,
 * whose faces are closer than that, is not taken for a far side) */
#define CR_FAR_SIDE_DOT -0.5f
/* through by the centre: deeper into the static body than the smaller
 * of the threshold of "into" and this much of the static body's
 * half-width (for a wall thinner than the body, half-way to its middle) */
#define CR_CENTRE_DEPTH 0.5f
/* the centre's way as seen from a turning kinematic body: straight
 * pieces (over a turn of 1.7 rad, a piece's middle is within 0.5 % of
 * the way's radius of the curve) */
#define CR_TURNING_PIECES 8
/* |angle| <= pi/2 * chord for |angle| <= pi: a bound of the turn from
 * its chord |q1 - q0|, without the arctangent */
#define CR_HALF_PI 1.57079632679489662f
#define CR_TWO_PI 6.28318530717958648f
#define CR_INV_TWO_PI 0.159154943091895336f
/* whole turns a step beyond which a spin is not followed (the float cast
 * stays far inside a long) */
#define CR_MAX_TURNS 1.0e6f

/* The farthest shape s at pose (x, q) reaches along unit direction d. */
static float cr_reach_along(const cr_shape *s, cr_v2 x, cr_rot q, cr_v2 d)
{
#if CAROM_ENABLE_POLYGONS
    if (!CR_KIND_CIRCLE(s->kind)) {
        cr_v2 dl = cr_inv_rotate(q, d);
        float far = cr_vdot(dl, s->verts[0]);
        int k;
        for (k = 1; k < s->count; ++k)
            far = cr_max(far, cr_vdot(dl, s->verts[k]));
        return cr_add(cr_vdot(d, x), far);
    }
#endif
    (void)q;
    return cr_add(cr_vdot(d, x), s->radius);
}

/* Grow box b to hold box c too. */
static void cr_box_merge(cr_box *b, const cr_box *c)
{
    b->lo_x = cr_min(b->lo_x, c->lo_x);
    b->lo_y = cr_min(b->lo_y, c->lo_y);
    b->hi_x = cr_max(b->hi_x, c->hi_x);
    b->hi_y = cr_max(b->hi_y, c->hi_y);
}

/* Whether the two overlap across n, t = n turned right: on
 * [-reach(-t), reach(t)] of each. */
static int cr_overlap_across(const cr_shape *sd, cr_v2 x, cr_rot q, const cr_shape *ss,
                             cr_v2 xs, cr_rot qs, cr_v2 t)
{
    return cr_lt(cr_neg(cr_reach_along(sd, x, q, cr_vneg(t))), cr_reach_along(ss, xs, qs, t)) &&
           cr_lt(cr_neg(cr_reach_along(ss, xs, qs, cr_vneg(t))), cr_reach_along(sd, x, q, t));
}

/* Whether the body at (x, q) lies wholly past static body S along n, the
 * normal from S towards where the body met it at xt, and went through S
 * to get there: the two overlap across n at the end pose, or where the
 * straight way from xt to x (turned as at the end) first lies wholly
 * past S (a body crossing a wall slantwise and past its end within one
 * step, as a 2 cm body at 20 km/s did). */
static int cr_went_through(const cr_shape *sd, cr_v2 xt, cr_v2 x, cr_rot q,
                           const cr_shape *ss, cr_v2 xs, cr_rot qs, cr_v2 n)
{
    cr_v2 t = cr_vright(n);
    float far = cr_neg(cr_reach_along(ss, xs, qs, cr_vneg(n)));
    float end = cr_reach_along(sd, x, q, n), meet;
    if (!cr_lt(end, far))
        return 0;
    if (cr_overlap_across(sd, x, q, ss, xs, qs, t))
        return 1;
    /* where along the way its reach along n crosses S's far side: the
     * reach is linear in the way's fraction f, from meet (f = 0) to end */
    meet = cr_reach_along(sd, xt, q, n);
    if (!cr_gt(meet, far))
        return 0; /* (past already at the meeting, as turned at the end) */
    {
        float f = cr_div(cr_sub(meet, far), cr_sub(meet, end));
        cr_v2 xf = cr_vmadd(xt, f, cr_vsub(x, xt));
        return cr_overlap_across(sd, xf, q, ss, xs, qs, t);
    }
}

/* Whether the straight way of the body's centre from p0, outside static
 * body S (shape ss at xs, qs), to p1 goes deeper into S than `depth`:
 * the centre inside S, the body overlaps it by more than its own inner
 * size, which no solver leaves. A body crossing a wall's corner
 * slantwise within one step (a 15 cm ball at 9 km/s came out of a thick
 * wall's end face) is neither deeper at its end pose than where it met
 * the wall nor wholly past the face it met. A path bent round S within
 * the step (a bounce) keeps the centre on the outer side of the face it
 * met, and so does its straight way. */
static int cr_centre_through_local(const cr_shape *ss, cr_v2 a, cr_v2 d, float depth,
                                   int from_outside)
{
#if CAROM_ENABLE_POLYGONS
    if (!CR_KIND_CIRCLE(ss->kind)) {
        /* clip the way to S's faces moved in by depth */
        float lo = 0.0f, hi = 1.0f;
        int k, outside = !from_outside;
        for (k = 0; k < ss->count; ++k) {
            /* g(f) = n.(a + f d) - n.v + depth: inside while g <= 0 */
            float h0 = cr_sub(cr_vdot(ss->norms[k], a), cr_vdot(ss->norms[k], ss->verts[k]));
            float g0 = cr_add(h0, depth);
            float gd = cr_vdot(ss->norms[k], d);
            if (cr_gt(h0, 0.0f))
                outside = 1;
            if (cr_eq(gd, 0.0f)) {
                if (cr_gt(g0, 0.0f))
                    return 0; /* parallel to the face, outside it */
            } else if (cr_lt(gd, 0.0f)) {
                lo = cr_max(lo, cr_div(cr_neg(g0), gd));
            } else {
                hi = cr_min(hi, cr_div(cr_neg(g0), gd));
            }
        }
        return outside && cr_lt(lo, hi);
    }
#endif
    {
        /* a circle: the way's nearest point to its centre, within its
         * radius less depth */
        float r = cr_sub(ss->radius, depth), dd, f;
        cr_v2 c;
        if (from_outside && !cr_gt(cr_vlen2(a), cr_mul(ss->radius, ss->radius)))
            return 0;
        dd = cr_vlen2(d);
        if (!cr_gt(dd, 0.0f))
            return 0;
        f = cr_clamp(cr_div(cr_neg(cr_vdot(a, d)), dd), 0.0f, 1.0f);
        c = cr_vmadd(a, f, d);
        return cr_lt(cr_vlen2(c), cr_mul(r, r));
    }
}

static int cr_centre_through(const cr_shape *ss, cr_v2 xs, cr_rot qs, cr_v2 p0, cr_v2 p1,
                             float depth)
{
#if CAROM_ENABLE_POLYGONS
    if (!CR_KIND_CIRCLE(ss->kind))
        return cr_centre_through_local(ss, cr_inv_rotate(qs, cr_vsub(p0, xs)),
                                       cr_inv_rotate(qs, cr_vsub(p1, p0)), depth, 1);
#endif
    (void)qs;
    return cr_centre_through_local(ss, cr_vsub(p0, xs), cr_vsub(p1, p0), depth, 1);
}

#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
/* Whether point p, in S's frame, lies outside S. */
static int cr_local_outside(const cr_shape *ss, cr_v2 p)
{
#if CAROM_ENABLE_POLYGONS
    if (!CR_KIND_CIRCLE(ss->kind)) {
        int k;
        for (k = 0; k < ss->count; ++k)
            if (cr_gt(cr_vdot(ss->norms[k], cr_vsub(p, ss->verts[k])), 0.0f))
                return 1;
        return 0;
    }
#endif
    return cr_gt(cr_vlen2(p), cr_mul(ss->radius, ss->radius));
}

/* A body's centre, tau after a meeting at toi: on its course `path`
 * (uniform, read with a still drift), or, if path is 0, on a flight from
 * centre xm with velocity v and acceleration a. */
typedef struct cr_way {
    const cr_body *path;
    cr_v2 xm, v, a;
} cr_way;

static cr_v2 cr_way_at(const cr_way *way, const cr_drift *still, float toi, float tau)
{
    cr_v2 x;
    cr_rot q;
    if (!way->path)
        return cr_vadd(way->xm, cr_drift_offset(way->v, way->a, tau));
    cr_pose_at(way->path, still, cr_add(toi, tau), &x, &q);
    return x;
}

/* The same against a kinematic body S that turns (start pose S0): the
 * centre's way as seen from S, from the meeting at toi over `rest`, is a
 * curve, followed in CR_TURNING_PIECES straight pieces. A body leaving a
 * spinning blade goes round its tip in the blade's frame, and the straight
 * way would cut through the blade; a body a blade sends off on a straight
 * line is caught again by the blade's turn, which it would pass through (a
 * 0.125 m box off a 9 m bar turning at 50 rad/s ended on its trailing
 * side). With from_outside, a way whose meeting's centre is already in S
 * does not cut through it. */
static int cr_way_through_turning(const cr_shape *ss, const cr_body *S0, const cr_way *way,
                                  float toi, float rest, float depth, int from_outside)
{
    float h = cr_div(rest, (float)CR_TURNING_PIECES);
    cr_v2 prev, xs;
    cr_rot qs;
    cr_drift still;
    int k;
    cr_drift_still(&still);
    cr_pose_at(S0, &still, toi, &xs, &qs);
    prev = cr_inv_rotate(qs, cr_vsub(cr_way_at(way, &still, toi, 0.0f), xs));
    if (from_outside && !cr_local_outside(ss, prev))
        return 0;
    for (k = 1; k <= CR_TURNING_PIECES; ++k) {
        float tau = cr_mul((float)k, h);
        cr_v2 cur;
        cr_pose_at(S0, &still, cr_add(toi, tau), &xs, &qs);
        cur = cr_inv_rotate(qs, cr_vsub(cr_way_at(way, &still, toi, tau), xs));
        if (cr_centre_through_local(ss, prev, cr_vsub(cur, prev), depth, 0))
            return 1;
        prev = cur;
    }
    return 0;
}
#endif

/* Whether the body at (x, q), overlapping static body S (sep1 < 0),
 * would be pushed out of S's far side: S's least way out for it points
 * against n, the normal where its path met S. A body that crossed most
 * of a thin wall in one step overlaps it less through the far face than
 * the near one, so it is neither deeper than the meeting nor wholly past
 * it, and the next step's contact would finish taking it through. */
static int cr_out_far_side(const cr_shape *sd, cr_v2 x, cr_rot q, const cr_shape *ss,
                           const cr_body *S, float sep1, float slop, float face_tol, cr_v2 n)
{
    cr_manifold end;
    if (!cr_lt(sep1, cr_neg(slop)))
        return 0; /* (the solver's own overlap) */
    if (!cr_collide(ss, S->x, S->q, sd, x, q, 0.0f, face_tol,
                    cr_mul(CAROM_CORNER_SLOPS, slop), &end))
        return 0;
    return cr_lt(cr_vdot(end.n, n), CR_FAR_SIDE_DOT);
}

/*
 * The meeting itself, at the pose where the path met static body s (the
 * manifold m, normal from s towards body i): each point still
 * approaching takes Newton's impulse, frictionless, -(1 + e) vn over the
 * point's effective mass, e the pair's restitution (0 below the rest
 * speed), the most approaching point first and each once more after the
 * other. Kept as it was, the velocity that took the body in would take
 * it in again at the next step, and the body would hang at the meeting
 * pose while gravity added to it (a rod spinning at 3000 rad/s stayed
 * above a floor for 2 s, falling at 22 m/s). Against a body that cannot
 * move, one frictionless impulse with e <= 1 takes energy or keeps it.
 */
static void cr_meet_static(carom_world *w, int i, int s, const cr_manifold *m, int moving,
                           cr_v2 centre)
{
    cr_body *b = &w->bodies[i];
    const cr_body *K = &w->bodies[s];
    float e = cr_max(w->info[i].restitution, w->info[s].restitution);
    float rest = cr_rest_speed(w, i, s);
    int pass, k;
    (void)K;
    (void)moving;
    (void)centre;
    for (pass = 0; pass < 2 * m->count; ++pass) {
        int worst = -1;
        float vn_worst = 0.0f;
        for (k = 0; k < m->count; ++k) {
            cr_v2 r = cr_vsub(m->pts[k].p, b->x);
            cr_v2 v = cr_vadd(b->v, cr_vcross_sv(b->w, r));
            float vn;
#if CAROM_ENABLE_KINEMATIC
            if (moving) /* relative to the kinematic body's point there */
                v = cr_vsub(v, cr_vadd(K->v, cr_vcross_sv(K->w, cr_vsub(m->pts[k].p, centre))));
#endif
            vn = cr_vdot(v, m->n);
            if (cr_lt(vn, vn_worst)) {
                worst = k;
                vn_worst = vn;
            }
        }
        if (worst < 0)
            break; /* no point approaches */
        {
            cr_v2 r = cr_vsub(m->pts[worst].p, b->x);
            float lever = cr_vcross(r, m->n);
            float k_n = cr_add(b->inv_m, cr_mul(b->inv_I, cr_mul(lever, lever)));
            float target = cr_gt(cr_neg(vn_worst), rest) ? cr_mul(e, cr_neg(vn_worst)) : 0.0f;
            float p = cr_div(cr_sub(target, vn_worst), k_n);
            b->v = cr_vmadd(b->v, cr_mul(p, b->inv_m), m->n);
            b->w = cr_add(b->w, cr_mul(cr_mul(p, b->inv_I), lever));
        }
    }
    /* a spin can carry every point of the meeting away while the centre
     * still goes in: then the other corners meet the static body within
     * the next step, faster than its contacts follow, and the body would
     * be put back again, step after step. The centre's approach is
     * answered as a whole (Newton's law on the centre's normal speed, the
     * spin kept: no energy made) */
    {
        float vn = cr_vdot(b->v, m->n);
#if CAROM_ENABLE_KINEMATIC
        if (moving)
            vn = cr_sub(vn, cr_vdot(cr_vadd(K->v, cr_vcross_sv(K->w, cr_vsub(b->x, centre))), m->n));
#endif
        if (cr_lt(vn, 0.0f)) {
            float target = cr_gt(cr_neg(vn), rest) ? cr_mul(e, cr_neg(vn)) : 0.0f;
            b->v = cr_vmadd(b->v, cr_sub(target, vn), m->n);
        }
    }
}

/* A bound of the fast test of cr_sweep_static, without its arctangent:
 * 0 if body i's step cannot carry a point half its half-width. */
static int cr_may_be_fast(const carom_world *w, int i, float dt)
{
    const cr_body *b0 = &w->backup[i], *b1 = &w->bodies[i];
    const cr_shape *sd = &w->info[i].shape;
    cr_v2 dx = cr_vsub(b1->x, b0->x);
    float limit = cr_mul(CR_FAST_FRACTION, sd->half_width);
    if (cr_gt(cr_vlen2(dx), cr_mul(limit, limit)))
        return 1;
#if CAROM_ENABLE_ROTATION
    if (!CR_KIND_CIRCLE(sd->kind)) {
        float chord = cr_vlen(cr_v(cr_sub(b1->q.c, b0->q.c), cr_sub(b1->q.s, b0->q.s)));
        float spun = cr_mul(cr_mul(0.5f, cr_add(b0->w, b1->w)), dt);
        return cr_gt(cr_mul(sd->extent, cr_mul(CR_HALF_PI, chord)), limit) ||
               cr_gt(cr_mul(sd->extent, cr_abs(spun)), limit);
    }
#else
    (void)dt;
#endif
    return 0;
}

/* The turn q1 q0^-1 from rotation q0 to q1. */
static cr_rot cr_turn_between(cr_rot q0, cr_rot q1)
{
    return cr_r(cr_add(cr_mul(q1.c, q0.c), cr_mul(q1.s, q0.s)),
                cr_sub(cr_mul(q1.s, q0.c), cr_mul(q1.c, q0.s)));
}

/* The turn r the shorter way round, then the whole turns a spin of
 * `spun` radians over the step made besides (the turn nearest it): a rod
 * spinning 8 turns a step is swept on its spin, so that where it meets
 * the static body its tip is coming down. */
static float cr_path_turn(cr_rot r, float spun)
{
    float turn = cr_rot_angle(r);
    float turns = cr_mul(cr_sub(spun, turn), CR_INV_TWO_PI);
    float whole = (float)(long)(cr_ge(turns, 0.0f) ? cr_add(turns, 0.5f) : cr_sub(turns, 0.5f));
    if (cr_lt(cr_abs(turns), CR_MAX_TURNS))
        turn = cr_add(turn, cr_mul(whole, CR_TWO_PI));
    return turn;
}

/* What the guard holds bodies against: static bodies and kinematic
 * ones, which no impulse moves either. */
static int cr_is_wall(const cr_body *b)
{
#if CAROM_ENABLE_KINEMATIC
    if (b->type == CAROM_BODY_KINEMATIC)
        return 1;
#endif
    return b->type == CAROM_BODY_STATIC;
}

#if CAROM_ENABLE_KINEMATIC
/* A flight's search of the grid: does the straight flight `path` over
 * [0, h] meet a static or kinematic body other than body `skip`? */
typedef struct cr_flight {
    carom_world *w;
    int body, skip;
    const cr_body *path;
    const cr_drift *still;
    float h;
    int blocked;
} cr_flight;

static int cr_flight_meets(void *ctx, int other)
{
    cr_flight *f = (cr_flight *)ctx;
    carom_world *w = f->w;
    const cr_body *O = &w->bodies[other];
    const cr_shape *so = &w->info[other].shape, *sd = &w->info[f->body].shape;
    float tol = cr_mul(CAROM_TOI_TOLERANCE, w->scale.slop), t = 0.0f;
    cr_mover A, B;
    cr_v2 x;
    cr_rot q;
    if (other == f->body || other == f->skip || !cr_is_wall(O) || (O->flags & CR_BODY_SENSOR) ||
        !cr_may_touch(w, f->body, other))
        return 1;
    A.s = so; /* (a kinematic one taken where it ends) */
    A.b = O;
    A.d = f->still;
    B.s = sd;
    B.b = f->path;
    B.d = f->still;
    if (cr_le(cr_separation(so, O->x, O->q, sd, f->path->x, f->path->q), tol)) {
        /* touching at the flight's start (a ball on the floor a wall
         * sweeps on): blocked only if the flight ends in it */
        cr_pose_at(f->path, f->still, f->h, &x, &q);
        if (!cr_lt(cr_separation(so, O->x, O->q, sd, x, q), cr_neg(w->scale.slop)))
            return 1;
    } else if (!cr_time_of_impact(&A, &B, 0.0f, f->h, tol, &t)) {
        return 1;
    }
    f->blocked = 1;
    return 0;
}

/*
 * Body i met kinematic body s at pose (xm, qm), the manifold m, while s's
 * centre was at xs, at time toi, with rest_of_step left of the step: it
 * takes the impulse there (s's velocity at that time) and flies on
 * ballistically to the step's end, as a body a wall or a blade sends off.
 * Kept (1) if the flight ends clear of s, does not pass through s as s
 * turns on (cr_way_through_turning), and meets no other static or
 * kinematic body on the way (the grid is searched along it: a light body
 * sent off at 9 m/s in a 3 cm box flew through its wall); otherwise its
 * velocity is put back as it was (0), and the caller holds it at the
 * meeting carried along with s.
 */
static int cr_fly_off(carom_world *w, int i, int s, cr_v2 xm, cr_rot qm, const cr_manifold *m,
                      cr_v2 xs, float toi, float rest_of_step)
{
    cr_body *b = &w->bodies[i];
    const cr_body *S = &w->bodies[s];
    const cr_shape *sd = &w->info[i].shape;
    cr_v2 v = b->v, x;
    float spin = b->w, turn = 0.0f;
    cr_rot q;
    cr_body path;
    cr_drift still;
    cr_flight f;
    cr_box box, end;
#if CAROM_ENABLE_COMPENSATED
    cr_v2 vc = b->vc;
    float wc = b->wc;
#endif
    if (!w->grid_valid || !cr_gt(rest_of_step, 0.0f))
        return 0;
    b->x = xm;
    b->q = qm;
    cr_meet_static(w, i, s, m, 1, xs);
    x = cr_vadd(xm, cr_drift_offset(b->v, b->a, rest_of_step));
#if CAROM_ENABLE_ROTATION
    turn = cr_drift_angle(b->w, b->alpha, rest_of_step);
    q = cr_rot_advance(qm, turn);
#else
    q = qm;
#endif
    f.blocked = cr_lt(cr_separation(&w->info[s].shape, S->x, S->q, sd, x, q),
                      cr_neg(w->scale.slop));
#if CAROM_ENABLE_ROTATION
    if (!f.blocked && !cr_eq(S->w, 0.0f)) {
        /* a turning one may catch it again on the way, and pass it */
        const cr_shape *ss = &w->info[s].shape;
        float thr = cr_max(cr_mul(CR_THROUGH_SLOPS, w->scale.slop),
                           cr_mul(CR_THROUGH_WIDTH, sd->half_width));
        cr_way way;
        way.path = 0;
        way.xm = xm;
        way.v = b->v;
        way.a = b->a;
        f.blocked = cr_way_through_turning(ss, &w->backup[s], &way, toi, rest_of_step,
                                           cr_min(thr, cr_mul(CR_CENTRE_DEPTH, ss->half_width)),
                                           0);
    }
#else
    (void)toi;
#endif
    if (!f.blocked) {
        /* the flight, straight and turning uniformly, through the grid */
        path = *b;
        path.v = cr_vscale(cr_div(1.0f, rest_of_step), cr_vsub(x, xm));
        path.w = cr_div(turn, rest_of_step);
        cr_drift_still(&still);
        f.w = w;
        f.body = i;
        f.skip = s;
        f.path = &path;
        f.still = &still;
        f.h = rest_of_step;
        cr_shape_box(sd, xm, qm, &box);
        cr_shape_box(sd, x, q, &end);
        cr_box_merge(&box, &end);
        (void)cr_broadphase_query(&w->bp, w->boxes, &box, cr_flight_meets, &f);
    }
    if (f.blocked) {
        b->v = v;
        b->w = spin;
#if CAROM_ENABLE_COMPENSATED
        b->vc = vc;
        b->wc = wc;
#endif
        return 0;
    }
    b->x = x;
    b->q = q;
    cr_add_velocity(b, cr_vscale(rest_of_step, b->a));
#if CAROM_ENABLE_ROTATION
    cr_add_angular(b, cr_mul(rest_of_step, b->alpha));
#endif
    return 1;
}
#endif

/*
 * Body i swept against body s, static or kinematic, over the step; 1 if
 * it was put back. A kinematic body moves on uniformly through the step
 * (its start pose in w->backup, its end pose in w->bodies): the body's
 * path is swept against its path, the tests below are made in its end
 * pose with the meeting carried along with it (the meeting pose, the
 * normal and the points, moved rigidly from where it was at the meeting
 * to where it ends), and the impulse answers the approach relative to
 * its points.
 */
static int cr_sweep_static(carom_world *w, int i, int s, float dt)
{
    const cr_body *b0 = &w->backup[i];
    cr_body *b1 = &w->bodies[i], path;
    const cr_body *S = &w->bodies[s], *S0 = S; /* its end pose; start pose */
    const cr_shape *sd = &w->info[i].shape, *ss = &w->info[s].shape;
    float slop = w->scale.slop, tol = cr_mul(CAROM_TOI_TOLERANCE, slop), inv_dt;
    float turn = 0.0f, toi = 0.0f, sep0, sep1, thr, rest_of_step;
    cr_v2 dx = cr_vsub(b1->x, b0->x), xt, xs;
    int touching = 0;
    cr_manifold late;
    cr_rot qt, qs;
    cr_drift still;
    cr_mover A, B;
    cr_manifold m;
#if CAROM_ENABLE_KINEMATIC
    cr_v2 xm = cr_v(0.0f, 0.0f); /* a kinematic body's meeting, not carried */
    cr_rot qm = cr_rot_identity();
    cr_manifold mm;
    mm.count = 0;
#endif
    int moving = 0;
    /* fast: the step could carry a point of the body past half the
     * thinner half-width of the two (a big body already deep in a thin
     * wall, pushed on by others, crosses the wall's middle with a move
     * far smaller than its own size, and the wall's far face then
     * pushes it out) */
    const float limit = cr_mul(CR_FAST_FRACTION, cr_min(sd->half_width, ss->half_width));

#if CAROM_ENABLE_KINEMATIC
    if (S->type == CAROM_BODY_KINEMATIC && cr_body_moves(S)) {
        if (b1->flags & CR_BODY_CARRIED)
            return 0; /* (put back against a kinematic body already) */
        /* fast against the kinematic body: its motion as seen from it */
        cr_v2 l0, l1;
        float spun = cr_mul(cr_mul(0.5f, cr_add(b0->w, b1->w)), dt);
        int turns = CAROM_ENABLE_ROTATION && !CR_KIND_CIRCLE(sd->kind);
        S0 = &w->backup[s];
        moving = 1;
        l0 = cr_inv_rotate(S0->q, cr_vsub(b0->x, S0->x));
        l1 = cr_inv_rotate(S->q, cr_vsub(b1->x, S->x));
        if (!cr_gt(cr_vlen(cr_vsub(l1, l0)), limit) &&
            !(turns && cr_gt(cr_mul(sd->extent, cr_abs(cr_sub(spun, cr_mul(S->w, dt)))), limit)))
            return 0;
        if (turns)
            turn = cr_path_turn(cr_turn_between(b0->q, b1->q), spun);
    } else
#endif
    if (CR_KIND_CIRCLE(sd->kind) || !CAROM_ENABLE_ROTATION) {
        /* a circle's surface is where it is, however it turns (squared:
         * no root for the many bodies that move little) */
        if (!cr_gt(cr_vlen2(dx), cr_mul(limit, limit)))
            return 0;
    }
#if CAROM_ENABLE_ROTATION
    else {
        /* the turn from the start pose to the end pose, q1 q0^-1, bounded
         * first by its chord |q1 - q0| (no arctangent for the many bodies
         * that turn little) */
        cr_rot r = cr_turn_between(b0->q, b1->q);
        float chord = cr_vlen(cr_v(cr_sub(b1->q.c, b0->q.c), cr_sub(b1->q.s, b0->q.s)));
        float move = cr_vlen(dx);
        float spun = cr_mul(cr_mul(0.5f, cr_add(b0->w, b1->w)), dt);
        if (!cr_gt(move, limit) &&
            !cr_gt(cr_mul(sd->extent, cr_mul(CR_HALF_PI, chord)), limit) &&
            !cr_gt(cr_mul(sd->extent, cr_abs(spun)), limit))
            return 0; /* moves too little to outrun its contacts */
        turn = cr_path_turn(r, spun);
        if (!cr_gt(cr_add(move, cr_mul(sd->extent, cr_abs(turn))), limit))
            return 0;
    }
#endif
    /* the path: from the start pose, uniform motion to the end pose */
    inv_dt = cr_div(1.0f, dt);
    path = *b0;
    path.v = cr_vscale(inv_dt, dx);
    path.w = cr_mul(turn, inv_dt);
    cr_drift_still(&still);
    A.s = ss;
    A.b = S0; /* (a kinematic body: its start pose and its motion) */
    A.d = &still;
    B.s = sd;
    B.b = &path;
    B.d = &still;
    /* already touching at the step's start: the meeting is the start
     * pose (the search below wants the two apart, and would read a spin
     * leaving the touching point as a graze while the body's centre went
     * on in: a spinning splinter crept through a wall, a few slops a
     * step) */
    sep0 = cr_separation(ss, S0->x, S0->q, sd, b0->x, b0->q);
    xs = S0->x;
    qs = S0->q;
    if (cr_le(sep0, tol)) {
        xt = b0->x;
        qt = b0->q;
        touching = 1;
    } else {
        if (!cr_time_of_impact(&A, &B, 0.0f, dt, tol, &toi))
            return 0;
        cr_pose_at(&path, &still, toi, &xt, &qt);
#if CAROM_ENABLE_KINEMATIC
        if (moving)
            cr_pose_at(S0, &still, toi, &xs, &qs);
#endif
    }
    /* where it met: the normal from the static body towards it */
    sep0 = cr_separation(ss, xs, qs, sd, xt, qt);
    if (!cr_finite(sep0) ||
        !cr_collide(ss, xs, qs, sd, xt, qt, cr_add(cr_max(sep0, 0.0f), cr_add(tol, slop)),
                    w->scale.face_tol, w->scale.corner, &m))
        return 0;
#if CAROM_ENABLE_KINEMATIC
    if (moving) {
        /* the meeting carried along with the kinematic body to its end
         * pose (by its turn since, u = q_end q_meet^-1, about its centre),
         * where the tests below are made; the meeting itself is kept */
        cr_rot u = cr_turn_between(qs, S->q);
        int k;
        xm = xt;
        qm = qt;
        mm = m;
        xt = cr_vadd(S->x, cr_rotate(u, cr_vsub(xt, xs)));
        qt = cr_rot_mul(u, qt);
        m.n = cr_rotate(u, m.n);
        for (k = 0; k < m.count; ++k)
            m.pts[k].p = cr_vadd(S->x, cr_rotate(u, cr_vsub(m.pts[k].p, xs)));
    }
#endif
    sep1 = cr_separation(ss, S->x, S->q, sd, b1->x, b1->q);
    thr = cr_max(cr_mul(CR_THROUGH_SLOPS, slop), cr_mul(CR_THROUGH_WIDTH, sd->half_width));
#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
    if (moving && !cr_eq(S->w, 0.0f)) {
        /* a turning kinematic body: the ways as seen from it are curves */
        cr_way way;
        way.path = &path;
        way.xm = way.v = way.a = cr_v(0.0f, 0.0f);
        /* into it by a few slops: a blade turning fast into a body that
         * moves little sweeps past the contact the solver made at the
         * substep's start, whose normal and arms were another part of the
         * turn (a paddle at 10 to 40 rad/s left a resting ball 4 to 9 cm
         * inside it, then threw it out at up to 2.2 times Newton's
         * energy); the meeting is answered as the events method does */
        if (!cr_lt(sep1, cr_sub(cr_min(sep0, 0.0f), cr_mul(CR_THROUGH_SLOPS, slop))) &&
            !cr_out_far_side(sd, b1->x, b1->q, ss, S, sep1, slop, w->scale.face_tol, m.n) &&
            !cr_way_through_turning(ss, S0, &way, toi, cr_sub(dt, toi),
                                    cr_min(thr, cr_mul(CR_CENTRE_DEPTH, ss->half_width)), 1))
            return 0;
    } else
#endif
    /* a body a kinematic body carried here: only what would take it
     * through the wall (the contact solver pushes it out of an overlap
     * from the side it is on; the flight's turn may leave a corner in) */
    if ((!cr_lt(sep1, cr_sub(cr_min(sep0, 0.0f), thr)) || (b1->flags & CR_BODY_CARRIED)) &&
        !cr_went_through(sd, xt, b1->x, b1->q, ss, S->x, S->q, m.n) &&
        !cr_out_far_side(sd, b1->x, b1->q, ss, S, sep1, slop, w->scale.face_tol, m.n) &&
        !cr_centre_through(ss, S->x, S->q, xt, b1->x,
                           cr_min(thr, cr_mul(CR_CENTRE_DEPTH, ss->half_width))))
        return 0;
#if CAROM_ENABLE_COMPENSATED
    b1->xc = cr_v(0.0f, 0.0f);
#endif
    /* at the meeting's time, toi: without what its forces would have
     * given it over the rest of the step (kept, a body falling onto a
     * floor would gain g (dt - toi) |v_y| of kinetic energy a unit mass,
     * 2e-4 of it at 1000 m/s, with no fall to pay for it) */
    rest_of_step = cr_sub(dt, toi);
    /* (a carried body's is taken off; one that touched at the step's
     * start was the contact solver's from then on, and its velocity is
     * the solver's answer, its bounce included: taking the step's
     * gravity off it too, a rod 1 m x 2 mm bouncing on one corner with
     * e = 1, put back where it started, left 2 % richer) */
    if (!(b1->flags & CR_BODY_CARRIED) && !touching) {
        cr_add_velocity(b1, cr_vscale(cr_neg(rest_of_step), b1->a));
#if CAROM_ENABLE_ROTATION
        cr_add_angular(b1, cr_mul(cr_neg(rest_of_step), b1->alpha));
#endif
    }
#if CAROM_ENABLE_KINEMATIC
    if (moving) {
        b1->flags |= CR_BODY_CARRIED;
        ++w->carried_count;
        if (cr_fly_off(w, i, s, xm, qm, &mm, xs, toi, rest_of_step))
            return 1;
    }
#endif
    /* met where it touched at the step's start: the part of it that went
     * in may be another (a thin plank standing on one end, spinning its
     * far end down onto the floor; put back with the touching end alone,
     * which rises, it kept its spin and was put back again every step,
     * frozen in the air). The points where it lies in the static body at
     * its end pose, carried back to the start pose with it, take the
     * meeting too */
    late.count = 0;
    if (touching && !moving &&
        cr_collide(ss, S->x, S->q, sd, b1->x, b1->q, cr_add(tol, slop), w->scale.face_tol,
                   w->scale.corner, &late)) {
        int k;
        for (k = 0; k < late.count; ++k)
            late.pts[k].p = cr_vadd(xt, cr_rotate(qt, cr_inv_rotate(b1->q,
                                                                   cr_vsub(late.pts[k].p, b1->x))));
    }
    b1->x = xt;
    b1->q = qt;
    cr_meet_static(w, i, s, &m, moving, S->x);
    if (late.count > 0) {
        cr_meet_static(w, i, s, &late, moving, S->x);
        cr_meet_static(w, i, s, &m, moving, S->x);
    }
    if (touching && !moving) {
        /* put back where it started two steps running: it has not moved
         * since the last step, whatever its velocity says (a plate 1 mm
         * thick lying on a floor, which gravity and its spin drove 0.8 mm
         * into the floor every step, with no point approaching it): it
         * is still, and says so */
        if (b1->flags & CR_BODY_PUT_BACK_LAST) {
            b1->v = cr_v(0.0f, 0.0f);
            b1->w = 0.0f;
        }
        b1->flags = (unsigned short)(b1->flags | CR_BODY_PUT_BACK);
    }
    return 1;
}

/* A body pushed off the path its grid box was swept along (an impulse
 * sent it where the step's start did not look): its pairs do not hold
 * the static bodies it went for. They are found in the grid, around its
 * start and end poses. */
typedef struct cr_escape_sweep {
    carom_world *w;
    int body;
    float dt;
    int carriers; /* -1: every wall; 0: the walls that hold still */
} cr_escape_sweep;

static int cr_carries(const cr_body *s);

static int cr_escape_static(void *ctx, int other)
{
    cr_escape_sweep *e = (cr_escape_sweep *)ctx;
    const cr_body *S = &e->w->bodies[other];
    if (cr_is_wall(S) && (e->carriers < 0 || cr_carries(S) == e->carriers) &&
        !(S->flags & CR_BODY_SENSOR) &&
        cr_may_touch(e->w, e->body, other) && cr_sweep_static(e->w, e->body, other, e->dt))
        ++e->w->stats.continuous_stops;
    return 1;
}

static int cr_box_holds(const cr_box *outer, const cr_box *inner)
{
    return cr_ge(inner->lo_x, outer->lo_x) && cr_le(inner->hi_x, outer->hi_x) &&
           cr_ge(inner->lo_y, outer->lo_y) && cr_le(inner->hi_y, outer->hi_y);
}

/* Body i swept against the walls the grid holds around its start pose
 * and its end pose (whose box is *end), of kind `carriers` (as in
 * cr_escape_sweep). */
static void cr_sweep_around(carom_world *w, int i, float dt, const cr_box *end, int carriers)
{
    cr_box around;
    cr_escape_sweep e;
    cr_shape_box(&w->info[i].shape, w->backup[i].x, w->backup[i].q, &around);
    cr_box_merge(&around, end);
    e.w = w;
    e.body = i;
    e.dt = dt;
    e.carriers = carriers;
    (void)cr_broadphase_query(&w->bp, w->boxes, &around, cr_escape_static, &e);
}

/* Body i, if the step left it outside its box: swept against the static
 * bodies around its start and end poses. */
static void cr_escape_check(carom_world *w, int i, float dt)
{
    const cr_body *b = &w->bodies[i];
    const cr_shape *sh = &w->info[i].shape;
    const cr_box *g = &w->boxes[i];
    cr_box end;
    if (!cr_may_be_fast(w, i, dt))
        return; /* (cr_sweep_static would find it too slow to tunnel) */
    /* its circle first (no vertex turned): inside, so is it */
    if (cr_ge(cr_sub(b->x.x, sh->extent), g->lo_x) && cr_le(cr_add(b->x.x, sh->extent), g->hi_x) &&
        cr_ge(cr_sub(b->x.y, sh->extent), g->lo_y) && cr_le(cr_add(b->x.y, sh->extent), g->hi_y))
        return;
    cr_shape_box(sh, b->x, b->q, &end);
    if (cr_box_holds(g, &end))
        return;
    cr_sweep_around(w, i, dt, &end, -1);
}

/* Only an impulse moves a body off the path its box was swept along, and
 * impulses act through the pairs that touched or met (as for
 * cr_note_escapes): their dynamic bodies are checked. A body in several
 * such pairs is checked once for each (a few comparisons; the grid is
 * searched again only for a body that did escape, and a body put back
 * by the first search is not put back again). */
static void cr_continuous_escapes(carom_world *w, float dt)
{
    int k, j;
    if (!w->grid_valid)
        return;
    for (k = 0; k < w->pair_count; ++k) {
        const cr_pair *p = &w->pairs[k];
        if (p->contact < 0 && !p->met)
            continue;
        for (j = 0; j < 2; ++j) {
            int i = j == 0 ? p->a : p->b;
            const cr_body *b = &w->bodies[i];
            if (b->type == CAROM_BODY_DYNAMIC && !(b->flags & CR_BODY_SENSOR) &&
                (b->flags & CR_BODY_AWAKE))
                cr_escape_check(w, i, dt);
        }
    }
}

/* Is wall s one the guard carries bodies along with (a moving
 * kinematic body), rather than holds them at? */
static int cr_carries(const cr_body *s)
{
#if CAROM_ENABLE_KINEMATIC
    return s->type == CAROM_BODY_KINEMATIC && cr_body_moves(s);
#else
    (void)s;
    return 0;
#endif
}

#if CAROM_ENABLE_KINEMATIC
/*
 * The bodies a kinematic body carried along or sent flying, held at the
 * walls that hold still on their way, found in the grid around their
 * start and end poses (the pair of a body and a static wall is not a
 * candidate pair when the step's start saw nothing take it there).
 * Nothing moves a static body: a body crushed between a kinematic
 * piston and a thin static wall is kept on the wall's near side, and
 * the piston goes over it (carried along, it was taken out of the
 * wall's far side, the container's outside).
 */
static void cr_continuous_carried(carom_world *w, float dt)
{
    int k, j;
    for (k = 0; k < w->pair_count; ++k)
        for (j = 0; j < 2; ++j) {
            int i = j == 0 ? w->pairs[k].a : w->pairs[k].b;
            cr_body *b = &w->bodies[i];
            cr_box end;
            if (!(b->flags & CR_BODY_CARRIED))
                continue;
            cr_shape_box(&w->info[i].shape, b->x, b->q, &end);
            cr_sweep_around(w, i, dt, &end, 0);
            /* once; and every carried body is in a pair, so this also
             * clears the flags for the next step */
            b->flags &= (unsigned short)~CR_BODY_CARRIED;
        }
    w->carried_count = 0;
}
#endif

void cr_continuous_statics(carom_world *w, float dt)
{
    int k;

    for (k = 0; k < w->awake_count; ++k) {
        cr_body *b = &w->bodies[w->awake[k]];
        unsigned f = b->flags & ~(unsigned)(CR_BODY_PUT_BACK | CR_BODY_PUT_BACK_LAST);
        if (b->flags & CR_BODY_PUT_BACK)
            f |= CR_BODY_PUT_BACK_LAST;
        b->flags = (unsigned short)f;
    }

    for (k = 0; k < w->pair_count; ++k) {
        const cr_pair *p = &w->pairs[k];
        const cr_body *A = &w->bodies[p->a], *B = &w->bodies[p->b];
        int i, s;
        if (cr_is_wall(A) && B->type == CAROM_BODY_DYNAMIC) {
            s = p->a;
            i = p->b;
        } else if (cr_is_wall(B) && A->type == CAROM_BODY_DYNAMIC) {
            s = p->b;
            i = p->a;
        } else {
            continue;
        }
        if (((A->flags | B->flags) & CR_BODY_SENSOR) || !(w->bodies[i].flags & CR_BODY_AWAKE))
            continue;
        if (cr_sweep_static(w, i, s, dt))
            ++w->stats.continuous_stops;
    }
    cr_continuous_escapes(w, dt);
#if CAROM_ENABLE_KINEMATIC
    if (w->carried_count > 0)
        cr_continuous_carried(w, dt);
#endif
}

#else
/* ISO C forbids an empty translation unit */
typedef int cr_continuous_disabled;
#endif /* CR_CONTINUOUS */
