/*
 * contact.c -- the step's contacts: which candidate pairs are within reach,
 * their manifolds, their constraint data, and the impulses carried from one
 * step to the next (warm starting).
 *
 * A pair's reach is the speculative distance (a few slops) plus how far the
 * two bodies can close in during the step (relative speed and spin times
 * reach, times dt). A contact therefore exists before the surfaces touch,
 * and the solver can stop them exactly where they meet: no tunnelling
 * through thin bodies, whether they translate or rotate.
 *
 * The anchors (from each centre of mass to the contact point), the normal
 * and the effective masses are computed once per step at the step's start
 * pose, and stay fixed through the substeps; only the separation is updated
 * from the bodies' displacements (solver.c), as in Box2D v3. Contacts with
 * a turning kinematic body are the exception: made again during the step
 * (cr_contacts_turn), whose face turns under a body sliding along it.
 *
 * Warm starting: last step's impulses are matched by body pair and feature
 * id. Both lists are sorted by (a, b), so one merge walk matches them.
 */
#include "narrowphase.h"
#include "world.h"

#include <string.h>

/* Smallest det(K) / (k11 k22) for which a 2-point manifold is solved as a
 * block (1 - cos^2 of the angle between the two points' impulse rows). */
#define CR_BLOCK_MIN_DET 1.0e-3f

/* Lever arm of an impulse along dir at r from the centre of a body: r x dir,
 * except for the normal of a circle, where it is 0 by geometry (rounding
 * would otherwise spin every circle a little at every contact). */
static float cr_lever(const cr_shape *s, cr_v2 r, cr_v2 dir, int normal)
{
    if (normal && CR_KIND_CIRCLE(s->kind))
        return 0.0f;
    return cr_vcross(r, dir);
}

/* How far two bodies can close in over time h: the sum of their speeds
 * (not their relative speed: two bodies falling side by side meet when the
 * lower one lands), plus each body's spin times its extent, plus h^2 / 2
 * times the larger of their relative acceleration and either body's own
 * (a body resting on a support does not fall: one dropped onto it falls
 * g h^2 / 2 closer, where the relative acceleration says 0; a 1 mm box
 * released 0.2 mm above another resting on the floor, under 9.81 m/s^2
 * at dt = 1/60, fell 1.4 mm into it in the step, unseen). */
float cr_pair_speed(const carom_world *w, int a, int b)
{
    const cr_body *A = &w->bodies[a], *B = &w->bodies[b];
    return cr_add(cr_add(cr_vlen(A->v), cr_vlen(B->v)),
                  cr_add(cr_mul(cr_abs(A->w), w->info[a].shape.extent),
                         cr_mul(cr_abs(B->w), w->info[b].shape.extent)));
}

float cr_pair_reach(const carom_world *w, int a, int b, float h)
{
    const cr_body *A = &w->bodies[a], *B = &w->bodies[b];
    float speed = cr_pair_speed(w, a, b);
    float acc = cr_max(cr_vlen(cr_vsub(B->a, A->a)), cr_max(cr_vlen(A->a), cr_vlen(B->a)));
    float reach = cr_add(w->scale.spec,
                         cr_add(cr_mul(speed, h), cr_mul(cr_mul(0.5f, acc), cr_mul(h, h))));
#if CR_CONTINUOUS
    /* a dynamic body another may push into a static or kinematic one,
     * inelastic (cr_push_reach in world.c) */
    if (cr_gt(cr_max(w->info[a].restitution, w->info[b].restitution), 0.0f))
        return reach;
    if (A->type != CAROM_BODY_DYNAMIC)
        reach = cr_add(reach, w->sbody[b].push);
    else if (B->type != CAROM_BODY_DYNAMIC)
        reach = cr_add(reach, w->sbody[a].push);
#endif
    return reach;
}

/* Constraint data of contact c from manifold m at the bodies' current
 * poses; impulses start at zero. */
void cr_contact_from_manifold(const carom_world *w, cr_contact *c,
                              const cr_manifold *m)
{
    const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    const cr_body_info *ia = &w->info[c->a], *ib = &w->info[c->b];
#if CAROM_ENABLE_FRICTION
    cr_v2 t = cr_vright(m->n); /* the friction direction */
#endif
    int k;
    c->n = m->n;
    c->count = m->count;
    c->restitution = cr_max(ia->restitution, ib->restitution);
#if CAROM_ENABLE_FRICTION
    c->friction = cr_sqrt(cr_mul(ia->friction, ib->friction));
#else
    c->friction = 0.0f;
#endif
    c->flags &= ~(CR_CONTACT_TOUCHING | CR_CONTACT_ROUND_A | CR_CONTACT_ROUND_B);
    if (CR_KIND_CIRCLE(ia->shape.kind))
        c->flags |= CR_CONTACT_ROUND_A;
    if (CR_KIND_CIRCLE(ib->shape.kind))
        c->flags |= CR_CONTACT_ROUND_B;
    for (k = 0; k < m->count; ++k) {
        cr_contact_point *p = &c->pts[k];
        const cr_manifold_point *mp = &m->pts[k];
        float rna, rnb;
        /* the arms reach the manifold point, midway across the gap, but
         * a circle's reach its surface: the point of it that the other
         * body meets (a disc bouncing off the floor from a gap of 5 cm
         * took its friction R + gap / 2 from its centre, and left at
         * 1.376 m/s and -2.621 rad/s instead of Newton's and Coulomb's
         * 4/3 and -8/3, still slipping) */
        p->ra = (c->flags & CR_CONTACT_ROUND_A) ? cr_vscale(ia->shape.radius, m->n)
                                                : cr_vsub(mp->p, A->x);
        p->rb = (c->flags & CR_CONTACT_ROUND_B) ? cr_vscale(cr_neg(ib->shape.radius), m->n)
                                                : cr_vsub(mp->p, B->x);
        p->base_sep = cr_sub(mp->sep, cr_vdot(m->n, cr_vsub(p->rb, p->ra)));
        rna = cr_lever(&ia->shape, p->ra, m->n, 1);
        rnb = cr_lever(&ib->shape, p->rb, m->n, 1);
        p->mass_n = cr_effective_mass(A, B, rna, rnb);
#if CAROM_ENABLE_FRICTION /* (only friction reads it) */
        p->mass_t = cr_effective_mass(A, B, cr_vcross(p->ra, t), cr_vcross(p->rb, t));
#else
        p->mass_t = 0.0f;
#endif
        /* the approach restitution uses: the discrete method starts from
         * the step's start (Box2D v3), the events methods only count one
         * captured when the point first pushes in a solve (their impacts
         * were taken at their instants already) */
        p->rel_vn = CAROM_ENABLE_DISCRETE && w->method == CAROM_METHOD_DISCRETE
                        ? cr_vdot(cr_vsub(cr_point_velocity(B->v, B->w, p->rb),
                                          cr_point_velocity(A->v, A->w, p->ra)),
                                  m->n)
                        : 0.0f;
        p->pn = 0.0f;
        p->pp = 0.0f;
        p->pt = 0.0f;
        p->max_pn = 0.0f;
        p->id = mp->id;
        if (cr_le(mp->sep, w->scale.spec))
            c->flags |= CR_CONTACT_TOUCHING;
    }
    c->block = 0;
    c->k11 = c->k12 = c->k22 = 0.0f;
    if (CR_TWO_POINTS && m->count == 2) {
        float l1a = cr_lever(&ia->shape, c->pts[0].ra, m->n, 1);
        float l1b = cr_lever(&ib->shape, c->pts[0].rb, m->n, 1);
        float l2a = cr_lever(&ia->shape, c->pts[1].ra, m->n, 1);
        float l2b = cr_lever(&ib->shape, c->pts[1].rb, m->n, 1);
        float lin = cr_add(A->inv_m, B->inv_m), det;
        c->k11 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(l1a, l1a)),
                                    cr_mul(B->inv_I, cr_mul(l1b, l1b))));
        c->k22 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(l2a, l2a)),
                                    cr_mul(B->inv_I, cr_mul(l2b, l2b))));
        c->k12 = cr_add(lin, cr_add(cr_mul(A->inv_I, cr_mul(l1a, l2a)),
                                    cr_mul(B->inv_I, cr_mul(l1b, l2b))));
        /* points too close together make K nearly singular: then solve
         * them one after the other */
        det = cr_sub(cr_mul(c->k11, c->k22), cr_mul(c->k12, c->k12));
        c->block = cr_gt(det, cr_mul(CR_BLOCK_MIN_DET, cr_mul(c->k11, c->k22)));
    }
}

/* Last step's impulses onto points with the same ids. */
static void cr_warm_match(cr_contact *c, const cr_warm *wm)
{
    int k, l;
    for (k = 0; k < c->count; ++k)
        for (l = 0; l < CR_MANIFOLD_POINTS; ++l)
            if (wm->id[l] == c->pts[k].id) {
                c->pts[k].pn = wm->pn[l];
                c->pts[k].pt = wm->pt[l];
            }
}

/*
 * A seam's ghost (docs/physics.md, "Seams"). Manifold m of bodies a and b
 * has one polygon grazing a corner of the other: it overlaps the face
 * only within CAROM_CORNER_SLOPS slops of the corner, and dips no deeper
 * below the face that meets it there (m->graze_n, m->graze_d). Where
 * another contact of the grazing body, with a third body, holds it on
 * that same plane (a normal along graze_n, its surface on the plane
 * within the rounding), the grazing body is carried flush across the
 * seam, and the graze is a ghost: the contact is not made. Without such a
 * neighbour it is a real corner (a box bridging a gap on millimetre
 * bearings, a box driven into a slot a millimetre too low for it, a box
 * falling past a ledge) and stays. Only contacts made from a full
 * manifold (no graze) count as the neighbour.
 */
#define CR_GHOST_PARALLEL 0.9999f /* cos of the largest angle between the
                                     planes (0.8 degree) */

int cr_ghost(const carom_world *w, int a, int b, const cr_manifold *m)
{
    int q = m->graze == 1 ? a : b, other = m->graze == 1 ? b : a, k;
    /* only seams of static tiles: in a pile, dynamic bodies' faces line
     * up by chance, and their grazes are left as they were; a kinematic
     * tile flush at the step's start can be a step away by the time the
     * body reaches the corner (a platform passing a ledge: the discrete
     * method let a box through the ledge's side) */
    if (!m->graze || w->bodies[other].type != CAROM_BODY_STATIC)
        return 0;
    for (k = w->pair_head[q]; k >= 0;) {
        const cr_pair *p = &w->pairs[k];
        int r = p->a == q ? p->b : p->a, next = p->a == q ? p->next_a : p->next_b;
        if (r != other && p->contact >= 0 && w->bodies[r].type == CAROM_BODY_STATIC &&
            !(w->contacts[p->contact].flags & CR_CONTACT_GRAZE)) {
            const cr_contact *c = &w->contacts[p->contact];
            /* the neighbour's normal, from it towards q */
            cr_v2 n = c->b == q ? c->n : cr_vneg(c->n);
            if (cr_ge(cr_vdot(n, m->graze_n), CR_GHOST_PARALLEL)) {
                int j;
                for (j = 0; j < c->count; ++j) {
                    const cr_contact_point *cp = &c->pts[j];
                    /* the neighbour's surface point at the step's start:
                     * the contact point (midway, where the arm of q, a
                     * polygon, reaches) less half the gap */
                    float sep = cr_add(cp->base_sep, cr_vdot(c->n, cr_vsub(cp->rb, cp->ra)));
                    cr_v2 mid = c->a == q ? cr_vadd(w->backup[c->a].x, cp->ra)
                                          : cr_vadd(w->backup[c->b].x, cp->rb);
                    cr_v2 x = cr_vmadd(mid, cr_mul(-0.5f, sep), n);
                    if (!cr_gt(cr_abs(cr_sub(cr_vdot(m->graze_n, x), m->graze_d)), w->scale.corner))
                        return 1;
                }
            }
        }
        k = next;
    }
    return 0;
}

#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
/* Is a or b a kinematic body that turns? */
static int cr_turning_kinematic(const cr_body *a, const cr_body *b)
{
    return (a->type == CAROM_BODY_KINEMATIC && !cr_eq(a->w, 0.0f)) ||
           (b->type == CAROM_BODY_KINEMATIC && !cr_eq(b->w, 0.0f));
}
#endif

/* Make contact c of pair i from manifold m (the step's start). */
static void cr_contact_make(carom_world *w, cr_contact *c, int i, const cr_manifold *m,
                            float dt, const cr_warm *wm)
{
    const cr_pair *pr = &w->pairs[i];
    c->a = pr->a;
    c->b = pr->b;
    c->pair = i;
    c->flags = m->graze ? CR_CONTACT_GRAZE : 0u;
    c->reach = cr_pair_reach(w, pr->a, pr->b, dt);
    cr_contact_from_manifold(w, c, m);
#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
    if ((c->flags & CR_CONTACT_TOUCHING) &&
        cr_turning_kinematic(&w->bodies[pr->a], &w->bodies[pr->b])) {
        c->flags |= CR_CONTACT_TURNS;
        ++w->turning_contacts;
    }
#endif
    if (wm) {
        int k;
        cr_warm_match(c, wm);
        for (k = 0; k < c->count; ++k)
            if (cr_gt(c->pts[k].pn, 0.0f) && (c->flags & CR_CONTACT_TOUCHING))
                c->flags |= CR_CONTACT_RESTING;
    }
}

/* Last step's impulses of pair (a, b), or NULL (binary search). */
static const cr_warm *cr_warm_of(const carom_world *w, int a, int b)
{
    int lo = 0, hi = w->warm_count;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        const cr_warm *x = &w->warm[mid];
        if (x->a < a || (x->a == a && x->b < b))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < w->warm_count && w->warm[lo].a == a && w->warm[lo].b == b ? &w->warm[lo] : 0;
}

#define CR_PAIR_GRAZING (-2) /* cr_contacts_build: a graze, decided last */

carom_status cr_contacts_build(carom_world *w, float dt)
{
    int i, j = 0, grazes = 0;
    w->contact_count = 0;
    w->turning_contacts = 0;
    for (i = 0; i < w->pair_count; ++i) {
        cr_pair *pr = &w->pairs[i];
        const cr_body *A = &w->bodies[pr->a], *B = &w->bodies[pr->b];
        cr_manifold m;
        const cr_warm *wm = 0;
        pr->contact = -1;
        if ((A->flags | B->flags) & CR_BODY_SENSOR)
            continue; /* overlaps only (touch.c) */
        if (!cr_collide(&w->info[pr->a].shape, A->x, A->q, &w->info[pr->b].shape,
                        B->x, B->q, cr_pair_reach(w, pr->a, pr->b, dt),
                        w->scale.face_tol, w->scale.corner, &m))
            continue;
        if (m.graze) {
            /* whether a neighbour carries it across needs every other
             * contact: after this loop */
            pr->contact = CR_PAIR_GRAZING;
            ++grazes;
            continue;
        }
        if (w->contact_count >= w->def.max_contacts)
            return CAROM_ERR_CONTACT_CAPACITY;
        /* warm start: last step's contacts are sorted like the pairs */
        while (j < w->warm_count &&
               (w->warm[j].a < pr->a || (w->warm[j].a == pr->a && w->warm[j].b < pr->b)))
            ++j;
        if (j < w->warm_count && w->warm[j].a == pr->a && w->warm[j].b == pr->b)
            wm = &w->warm[j];
        cr_contact_make(w, &w->contacts[w->contact_count], i, &m, dt, wm);
        pr->contact = w->contact_count++;
    }
    /* grazes: a ghost is not made; a real corner is, in its place in the
     * pairs' order (rare: the later contacts move up one) */
    for (i = 0; i < w->pair_count && grazes > 0; ++i) {
        cr_pair *pr = &w->pairs[i];
        const cr_body *A = &w->bodies[pr->a], *B = &w->bodies[pr->b];
        cr_manifold m;
        int at, k;
        if (pr->contact != CR_PAIR_GRAZING)
            continue;
        --grazes;
        pr->contact = -1;
        (void)cr_collide(&w->info[pr->a].shape, A->x, A->q, &w->info[pr->b].shape, B->x, B->q,
                         cr_pair_reach(w, pr->a, pr->b, dt), w->scale.face_tol,
                         w->scale.corner, &m);
        if (cr_ghost(w, pr->a, pr->b, &m))
            continue;
        if (w->contact_count >= w->def.max_contacts)
            return CAROM_ERR_CONTACT_CAPACITY;
        for (at = w->contact_count; at > 0 && w->contacts[at - 1].pair > i; --at)
            ;
        for (k = w->contact_count; k > at; --k) {
            w->contacts[k] = w->contacts[k - 1];
            w->pairs[w->contacts[k].pair].contact = k;
        }
        cr_contact_make(w, &w->contacts[at], i, &m, dt, cr_warm_of(w, pr->a, pr->b));
        pr->contact = at;
        ++w->contact_count;
    }
    return CAROM_OK;
}

/* Contact c of pair pr from manifold m at the bodies' current poses, its
 * separations measured from the step start like every other contact's. */
static void cr_contact_fill(carom_world *w, cr_contact *c, const cr_pair *pr,
                            const cr_manifold *m)
{
    const cr_body *A = &w->bodies[pr->a], *B = &w->bodies[pr->b];
    const cr_body *A0 = &w->backup[pr->a], *B0 = &w->backup[pr->b];
    cr_v2 dpa = cr_vsub(A->x, A0->x), dpb = cr_vsub(B->x, B0->x);
    cr_rot dqa = cr_anchor_turn(A, A0), dqb = cr_anchor_turn(B, B0);
    int k;
    cr_contact_from_manifold(w, c, m);
    /* the solver measures separation from the step start: count the
     * displacements so far in the base */
    for (k = 0; k < c->count; ++k) {
        cr_contact_point *p = &c->pts[k];
        cr_v2 d = cr_vsub(cr_vadd(dpb, cr_rotate(dqb, p->rb)),
                          cr_vadd(dpa, cr_rotate(dqa, p->ra)));
        p->base_sep = cr_sub(m->pts[k].sep, cr_vdot(c->n, d));
    }
}

int cr_contact_add(carom_world *w, int pair)
{
    cr_pair *pr = &w->pairs[pair];
    const cr_body *A = &w->bodies[pr->a], *B = &w->bodies[pr->b];
    cr_manifold m;
    cr_contact *c;
    float reach = cr_pair_reach(w, pr->a, pr->b, w->def.dt);
    if (pr->contact >= 0)
        return pr->contact;
    if ((A->flags | B->flags) & CR_BODY_SENSOR)
        return -1;
    if (!cr_collide(&w->info[pr->a].shape, A->x, A->q, &w->info[pr->b].shape,
                    B->x, B->q, reach, w->scale.face_tol, w->scale.corner, &m) ||
        cr_ghost(w, pr->a, pr->b, &m))
        return -1;
    if (w->contact_count >= w->def.max_contacts)
        return -2;
    c = &w->contacts[w->contact_count];
    ++w->contact_edits;
    c->a = pr->a;
    c->b = pr->b;
    c->pair = pair;
    c->flags = CR_CONTACT_NEW | (m.graze ? CR_CONTACT_GRAZE : 0u);
    c->reach = reach;
    cr_contact_fill(w, c, pr, &m);
    pr->contact = w->contact_count++;
    return pr->contact;
}

void cr_contact_remake(carom_world *w, cr_contact *c)
{
    const cr_pair *pr = &w->pairs[c->pair];
    const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
    cr_manifold m;
    ++w->contact_edits;
    c->flags &= ~CR_CONTACT_RESTING;
    if (!cr_collide(&w->info[c->a].shape, A->x, A->q, &w->info[c->b].shape,
                    B->x, B->q, c->reach, w->scale.face_tol, w->scale.corner, &m) ||
        cr_ghost(w, c->a, c->b, &m)) {
        c->count = 0;
        c->flags &= ~CR_CONTACT_TOUCHING;
        return;
    }
    c->flags = (unsigned short)((c->flags & ~CR_CONTACT_GRAZE) | (m.graze ? CR_CONTACT_GRAZE : 0u));
    cr_contact_fill(w, c, pr, &m);
}

#if CAROM_ENABLE_KINEMATIC && CAROM_ENABLE_ROTATION
void cr_contacts_turn(carom_world *w)
{
    int i, k, j;
    for (i = 0; i < w->contact_count; ++i) {
        cr_contact *c = &w->contacts[i];
        const cr_body *A = &w->bodies[c->a], *B = &w->bodies[c->b];
        cr_contact_point old[CR_MANIFOLD_POINTS];
        unsigned short keep;
        int n = c->count;
        cr_manifold m;
        if (!(c->flags & CR_CONTACT_TURNS) || !(c->flags & CR_CONTACT_SOLVE))
            continue;
        memcpy(old, c->pts, sizeof old);
        if (!cr_collide(&w->info[c->a].shape, A->x, A->q, &w->info[c->b].shape, B->x, B->q,
                        c->reach, w->scale.face_tol, w->scale.corner, &m) ||
            cr_ghost(w, c->a, c->b, &m)) {
            c->count = 0;
            c->flags &= (unsigned short)~CR_CONTACT_TOUCHING;
            continue;
        }
        keep = (unsigned short)(c->flags & ~(unsigned)(CR_CONTACT_GRAZE | CR_CONTACT_TOUCHING));
        cr_contact_fill(w, c, &w->pairs[c->pair], &m);
        c->flags = (unsigned short)(keep | (c->flags & CR_CONTACT_TOUCHING) |
                                    (m.graze ? CR_CONTACT_GRAZE : 0u));
        /* the impulses so far, point by point: the warm start of the
         * substep, and the restitution pass's record */
        for (k = 0; k < c->count; ++k)
            for (j = 0; j < n; ++j)
                if (c->pts[k].id == old[j].id) {
                    c->pts[k].pn = old[j].pn;
                    c->pts[k].pt = old[j].pt;
                    c->pts[k].max_pn = old[j].max_pn;
                    c->pts[k].rel_vn = old[j].rel_vn;
                    break;
                }
    }
}
#endif

/* Keep this step's impulses for the next, in (a, b) order: contacts made
 * during the step sit at the end of the list, so walk the pairs. They
 * overwrite the last step's, which only cr_contacts_build reads: the step
 * calls this after everything that can fail, so a failed step keeps the
 * last step's impulses (one array, not two). */
void cr_contacts_store(carom_world *w)
{
    int i, k, n = 0;
    for (i = 0; i < w->pair_count; ++i) {
        const cr_contact *c;
        cr_warm *wm;
        if (w->pairs[i].contact < 0)
            continue;
        c = &w->contacts[w->pairs[i].contact];
        wm = &w->warm[n++];
        wm->a = c->a;
        wm->b = c->b;
        for (k = 0; k < CR_MANIFOLD_POINTS; ++k) {
            wm->id[k] = k < c->count ? c->pts[k].id : CR_NO_ID;
            wm->pn[k] = k < c->count ? c->pts[k].pn : 0.0f;
            wm->pt[k] = k < c->count ? c->pts[k].pt : 0.0f;
        }
    }
    w->warm_count = n;
}


