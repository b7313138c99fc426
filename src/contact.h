/*
 * contact.h -- contacts: pairs of bodies within contact distance, each with
 * a manifold of up to two points, the solver's constraint data and the
 * impulses carried from step to step (internal).
 */
#ifndef CAROM_CONTACT_H
#define CAROM_CONTACT_H

#include "body.h"

/* Contact points per pair: a build without polygons has only circles,
 * which touch at one point, so its manifolds, contacts, warm starts and
 * impact rows hold one, and the two-point code (block solves, friction
 * of a face) compiles away. */
#if CAROM_ENABLE_POLYGONS
#define CR_MANIFOLD_POINTS CAROM_MAX_MANIFOLD_POINTS
#else
#define CR_MANIFOLD_POINTS 1
#endif
#define CR_TWO_POINTS (CR_MANIFOLD_POINTS > 1)

/* No feature id: a point slot that holds nothing. */
#define CR_NO_ID 0xffffffffu

/* A manifold as narrowphase computes it at one pose. */
typedef struct cr_manifold_point {
    cr_v2 p;        /* world point, midway between the two surfaces */
    float sep;      /* signed distance along the normal (< 0: overlap) */
    unsigned id;    /* feature id, the same while the same features touch */
} cr_manifold_point;

typedef struct cr_manifold {
    cr_v2 n;        /* unit normal from body a towards body b */
    int count;      /* 0..CR_MANIFOLD_POINTS */
    cr_manifold_point pts[CR_MANIFOLD_POINTS];
    /* a polygon grazing a corner of the other (cr_polygons): 0 no; 1 body
     * a grazes body b's corner, 2 body b grazes a's. Then the face that
     * meets the contact's face at that corner: its outward unit normal
     * and its plane (dot(graze_n, x) = graze_d), world frame. Such a
     * contact is a seam's ghost if a flush neighbour carries the grazing
     * body across (contact.c, cr_ghost) */
    int graze;
    cr_v2 graze_n;
    float graze_d;
} cr_manifold;

/* One point of a contact constraint. */
typedef struct cr_contact_point {
    cr_v2 ra, rb;    /* from each centre of mass to the point, world frame,
                        at the start of the step */
    float base_sep;  /* separation at the start of the step minus
                        n.(rb - ra): the current separation is
                        base_sep + n.(x_b + Rb rb - x_a - Ra ra) */
    float pn, pt;    /* accumulated normal and tangent impulses */
    float pp;        /* pseudo-impulse of the position correction */
    float max_pn;    /* largest normal impulse of the step */
    float mass_n, mass_t; /* effective masses along n and the tangent */
    float rel_vn;    /* normal relative velocity for restitution: at the
                        start of the step (discrete) or when the point first
                        pushes (events methods) */
#if CAROM_ENABLE_FRICTION
    float pt_bounce; /* tangent impulse of the restitution pass (its
                        friction, within mu times the bounce's impulse) */
#endif
    unsigned id;
} cr_contact_point;

/* Flags of cr_contact.flags */
#define CR_CONTACT_SOLVE 1u    /* solved by the contact solver this substep
                                  (not an impact waiting for its instant) */
#define CR_CONTACT_TOUCHING 2u /* within the speculative distance (a few
                                  slops) at the step start */
#define CR_CONTACT_NEW 4u      /* made during the step, after an impact */
#define CR_CONTACT_RESTING 8u  /* touching and pushing already last step:
                                  a resting contact, the solver's whatever
                                  its approach (no micro-collisions) */
#define CR_CONTACT_SHOCK_A 16u /* shock propagation: a support of body a */
#define CR_CONTACT_SHOCK_B 32u /* ... of body b (cr_solver_mark_shocks) */
#define CR_CONTACT_ROUND_A 64u  /* body a is a circle: its normal lever arm is
                                   0 (cr_contact_lever_a) */
#define CR_CONTACT_ROUND_B 128u /* ... body b */
#define CR_CONTACT_UNSETTLED 256u /* events methods: an impact solve left it
                                     approaching (cr_pair_to_solver): the
                                     solver's to the step's end, not an
                                     impact again at the next substep */
#define CR_CONTACT_SOFT 512u /* CAROM_SOFT_DEEP_CONTACTS: a contact of a body
                                in a jam of unlike densities with a body of
                                unlike mass (cr_mark_mixed); soft while
                                resting */
#define CR_CONTACT_GRAZE 1024u /* made from a manifold of a polygon grazing a
                                  corner, with no flush neighbour carrying
                                  it across (contact.c, cr_ghost): not one
                                  that shows a seam is a ghost */
#define CR_CONTACT_TURNS 2048u /* touching at the step's start, and a body
                                  of it is kinematic and turns: its normal
                                  and points are made again during the
                                  step (cr_contacts_turn) */
#define CR_CONTACT_SPANNED 4096u /* shock propagation: the body resting
                                    on this contact presses the one below
                                    within the span of what holds that
                                    one (cr_solver_mark_shocks) */

typedef struct cr_contact {
    int a, b;          /* body slots, a < b */
    int pair;          /* the candidate pair it belongs to */
    cr_v2 n;           /* unit normal a -> b at the start of the step */
    unsigned char count;
    unsigned char block; /* 2 points: solved as one 2x2 problem (K well
                            conditioned) */
    unsigned short flags;
    float friction, restitution;
    float reach;       /* speculative distance of this pair in the step */
    float k11, k12, k22; /* 2 points: the normal effective-mass matrix K */
    cr_contact_point pts[CR_MANIFOLD_POINTS];
} cr_contact;

/* The normal lever arms r x n of contact c's bodies at arm r, 0 for a
 * circle (cr_lever in contact.c), from the contact's flags: the solver's
 * sweeps need not read the bodies' shapes. */
CR_INLINE float cr_contact_lever_a(const cr_contact *c, cr_v2 r)
{
    return (c->flags & CR_CONTACT_ROUND_A) ? 0.0f : cr_vcross(r, c->n);
}
CR_INLINE float cr_contact_lever_b(const cr_contact *c, cr_v2 r)
{
    return (c->flags & CR_CONTACT_ROUND_B) ? 0.0f : cr_vcross(r, c->n);
}

/* Impulses kept from one step to warm-start the next, sorted by (a, b). */
typedef struct cr_warm {
    int a, b;
    unsigned id[CR_MANIFOLD_POINTS];
    float pn[CR_MANIFOLD_POINTS], pt[CR_MANIFOLD_POINTS];
} cr_warm;

/* 1 / (1/m_a + 1/m_b + la^2 / I_a + lb^2 / I_b) for lever arms la, lb
 * (inline: the solvers' sweeps call these for every contact point). */
CR_INLINE float cr_effective_mass(const cr_body *A, const cr_body *B, float la, float lb)
{
    float k = cr_add(cr_add(A->inv_m, B->inv_m),
                     cr_add(cr_mul(A->inv_I, cr_mul(la, la)),
                            cr_mul(B->inv_I, cr_mul(lb, lb))));
    return cr_gt(k, 0.0f) ? cr_div(1.0f, k) : 0.0f;
}

/*
 * How a contact anchor taken at pose b0 has turned at pose b: q q0^-1 for
 * a polygon, whose contact point is a material point (a vertex, a point
 * of a face); none for a circle, whose contact point is where its surface
 * faces the other body, wherever the spin has carried the material
 * (turned with the spin, the anchor of a ball spinning at 100 rad/s into
 * a wall swung away from the wall within the step, the solver saw a gap,
 * and the ball went half its radius into the wall: discrete method,
 * test_solver's spinning ball).
 */
CR_INLINE cr_rot cr_anchor_turn(const cr_body *b, const cr_body *b0)
{
    if (b->flags & CR_BODY_CIRCLE)
        return cr_rot_identity();
    return cr_r(cr_add(cr_mul(b->q.c, b0->q.c), cr_mul(b->q.s, b0->q.s)),
                cr_sub(cr_mul(b->q.s, b0->q.c), cr_mul(b->q.c, b0->q.s)));
}

/* Velocity of the material point at r from a centre moving at (v, w). */
CR_INLINE cr_v2 cr_point_velocity(cr_v2 v, float w, cr_v2 r)
{
    return cr_vadd(v, cr_vcross_sv(w, r));
}

/* How far bodies a and b can close in over time h, plus the speculative
 * distance: the reach of their contact. */
float cr_pair_reach(const carom_world *w, int a, int b, float h);

/* The sum of the two bodies' speeds and spins times extents: the most
 * their surfaces can close in per second (cr_pair_reach), and the scale
 * of the rounding in their approach (cr_solver_classify). */
float cr_pair_speed(const carom_world *w, int a, int b);

/* Is manifold m of bodies a and b (cr_collide) a seam's ghost: a polygon
 * grazing a corner of the other while a flush neighbour carries it
 * across? Then no contact or impact row is made of it (contact.c). */
int cr_ghost(const carom_world *w, int a, int b, const cr_manifold *m);

/* Constraint data of contact c (a, b set) from manifold m at the bodies'
 * current poses; impulses start at zero. */
void cr_contact_from_manifold(const carom_world *w, cr_contact *c,
                              const cr_manifold *m);

/* The step's contacts from its candidate pairs, warm-started from the last
 * step's impulses. CAROM_ERR_CONTACT_CAPACITY if they do not fit. */
carom_status cr_contacts_build(carom_world *w, float dt);

/* A contact for candidate pair `pair` made now (after an impact); its
 * index, -1 if the pair is out of reach, -2 if the contacts are full. */
int cr_contact_add(carom_world *w, int pair);

/* Contact c again at the bodies' current poses (synchronised): after an
 * impact changed the bodies' course the step-start normal and points are
 * stale. Impulses start at zero; no points if the pair is out of reach. */
void cr_contact_remake(carom_world *w, cr_contact *c);

/* The solver's contacts with a turning kinematic body that touched at
 * the step's start (CR_CONTACT_TURNS), made again at the bodies' current
 * poses, their impulses kept point by point: before each position sweep,
 * for it and for the next substep's velocity sweeps. The solver holds the
 * normal a contact was made with; a kinematic bar turning a sixth of a
 * radian a step turns its face under a body sliding along it, which read
 * the slide as separation and sank 13 to 32 cm into the bar, and through
 * it. (One that touched only later, a ball a turning blade strikes from
 * afar, is the impacts' or the continuous guard's, at the strike's
 * instant.) */
void cr_contacts_turn(carom_world *w);

#if CR_TWO_POINTS
/*
 * The 2x2 linear complementarity problem of a 2-point row:
 *     find x >= 0 with y = K x + b >= 0 and x_i y_i = 0,
 * K = [k11 k12; k12 k22] symmetric positive definite, by trying its four
 * cases in turn (both points pushing, only one, none). 0 if none fits
 * (rounding at a degenerate K). Inline: the solvers' sweeps solve one
 * for every 2-point contact.
 */
CR_INLINE int cr_lcp2(float k11, float k12, float k22, float b1, float b2, float *x1,
                      float *x2)
{
    float det = cr_sub(cr_mul(k11, k22), cr_mul(k12, k12));
    float y1 = cr_div(cr_sub(cr_mul(k12, b2), cr_mul(k22, b1)), det);
    float y2 = cr_div(cr_sub(cr_mul(k12, b1), cr_mul(k11, b2)), det);
    if (cr_ge(y1, 0.0f) && cr_ge(y2, 0.0f)) {
        *x1 = y1;
        *x2 = y2;
        return 1;
    }
    y1 = cr_div(cr_neg(b1), k11);
    if (cr_ge(y1, 0.0f) && cr_ge(cr_add(cr_mul(k12, y1), b2), 0.0f)) {
        *x1 = y1;
        *x2 = 0.0f;
        return 1;
    }
    y2 = cr_div(cr_neg(b2), k22);
    if (cr_ge(y2, 0.0f) && cr_ge(cr_add(cr_mul(k12, y2), b1), 0.0f)) {
        *x1 = 0.0f;
        *x2 = y2;
        return 1;
    }
    if (cr_ge(b1, 0.0f) && cr_ge(b2, 0.0f)) {
        *x1 = 0.0f;
        *x2 = 0.0f;
        return 1;
    }
    return 0;
}
#endif /* CR_TWO_POINTS */

/* The impulses to warm-start the next step, into w->warm (over the last
 * step's: call it when the step can no longer fail). */
void cr_contacts_store(carom_world *w);

#endif /* CAROM_CONTACT_H */
