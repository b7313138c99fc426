/*
 * narrowphase.c -- contact manifolds for circle-circle, polygon-circle and
 * polygon-polygon pairs.
 *
 * A manifold holds the unit normal from body a to body b and up to two
 * points; each point lies midway between the two surfaces and carries the
 * signed separation along the normal (negative: overlap) and a feature id
 * that stays the same while the same features touch, so the solver can
 * reuse last step's impulses (warm starting).
 *
 * Polygon pairs use the separating axis test over both polygons' face
 * normals; the face of least penetration is the reference face, the most
 * anti-parallel face of the other polygon the incident face, and the
 * incident face is clipped to the reference face's side planes.
 */
#include "internal.h"

/* Prefer body a's face unless body b's is clearly better: flipping between
 * nearly equal faces from step to step would spoil warm starting. */
#define CR_FACE_TOL_FRACTION 0.1f

/* A margin larger than any distance: collide at any range. */
#define CR_FAR 3.0e38f

static cr_v2 cr_midpoint(cr_v2 p, cr_v2 q)
{
    return cr_vscale(0.5f, cr_vadd(p, q));
}

/* ---- circle - circle ----------------------------------------------------- */

static int cr_circle_circle(const cr_body *A, const cr_body *B, float margin,
                            cr_manifold *m)
{
    cr_v2 d = cr_vsub(B->x, A->x);
    float r = cr_add(A->radius, B->radius);
    float reach = cr_add(r, margin);
    float dist2 = cr_vlen2(d), dist;
    cr_v2 n;
    if (cr_gt(dist2, cr_mul(reach, reach)))
        return 0;
    dist = cr_sqrt(dist2);
    /* concentric circles: any normal is right; pick +y deterministically */
    n = cr_gt(dist, 0.0f) ? cr_vscale(cr_div(1.0f, dist), d) : cr_v(0.0f, 1.0f);
    m->n = n;
    m->count = 1;
    m->pts[0].sep = cr_sub(dist, r);
    m->pts[0].p = cr_midpoint(cr_vmadd(A->x, A->radius, n),
                              cr_vmadd(B->x, cr_neg(B->radius), n));
    m->pts[0].id = 0u;
    return 1;
}

/* ---- polygon - circle (normal from the polygon to the circle) ------------ */

#if CAROM_ENABLE_POLYGONS
static int cr_polygon_circle(const cr_body *P, const cr_body *C, float margin,
                             cr_manifold *m)
{
    cr_v2 c = cr_inv_rotate(P->q, cr_vsub(C->x, P->x)); /* polygon frame */
    float r = C->radius, reach = cr_add(r, margin), s, sep;
    int i, face = 0, n = P->count;
    unsigned id;
    cr_v2 v1, v2, normal, surface;

    s = cr_vdot(P->norms[0], cr_vsub(c, P->verts[0]));
    for (i = 1; i < n; ++i) {
        float si = cr_vdot(P->norms[i], cr_vsub(c, P->verts[i]));
        if (cr_gt(si, s)) {
            s = si;
            face = i;
        }
    }
    if (cr_gt(s, reach))
        return 0;
    v1 = P->verts[face];
    v2 = P->verts[(face + 1) % n];

    if (cr_le(s, 0.0f)) {
        /* centre inside: push out through the face of least penetration */
        normal = P->norms[face];
        sep = cr_sub(s, r);
        surface = cr_vmadd(c, cr_neg(s), normal);
        id = (unsigned)face;
    } else {
        float u1 = cr_vdot(cr_vsub(c, v1), cr_vsub(v2, v1));
        float u2 = cr_vdot(cr_vsub(c, v2), cr_vsub(v1, v2));
        if (cr_le(u1, 0.0f) || cr_le(u2, 0.0f)) {
            /* vertex region */
            cr_v2 v = cr_le(u1, 0.0f) ? v1 : v2;
            cr_v2 d = cr_vsub(c, v);
            float dist2 = cr_vlen2(d), dist;
            if (cr_gt(dist2, cr_mul(reach, reach)))
                return 0;
            dist = cr_sqrt(dist2);
            normal = cr_vscale(cr_div(1.0f, dist), d);
            sep = cr_sub(dist, r);
            surface = v;
            id = 16u + (unsigned)(cr_le(u1, 0.0f) ? face : (face + 1) % n);
        } else {
            normal = P->norms[face];
            sep = cr_sub(s, r);
            surface = cr_vmadd(c, cr_neg(s), normal);
            id = (unsigned)face;
        }
    }
    m->count = 1;
    m->n = cr_rotate(P->q, normal);
    m->pts[0].sep = sep;
    m->pts[0].p = cr_vadd(P->x, cr_rotate(P->q, cr_midpoint(
                      surface, cr_vmadd(c, cr_neg(r), normal))));
    m->pts[0].id = id;
    return 1;
}

/* ---- polygon - polygon ----------------------------------------------------- */

/* Largest separation of B from A over A's face normals, and that face. */
static float cr_max_separation(const cr_body *A, const cr_body *B, int *face)
{
    cr_v2 bv[CAROM_MAX_POLYGON_VERTICES];
    cr_v2 off = cr_inv_rotate(A->q, cr_vsub(B->x, A->x));
    cr_rot rel = cr_r(cr_add(cr_mul(A->q.c, B->q.c), cr_mul(A->q.s, B->q.s)),
                      cr_sub(cr_mul(A->q.c, B->q.s), cr_mul(A->q.s, B->q.c)));
    float best = 0.0f;
    int i, j;
    for (j = 0; j < B->count; ++j)
        bv[j] = cr_vadd(off, cr_rotate(rel, B->verts[j]));
    for (i = 0; i < A->count; ++i) {
        float si = cr_vdot(A->norms[i], cr_vsub(bv[0], A->verts[i]));
        for (j = 1; j < B->count; ++j)
            si = cr_min(si, cr_vdot(A->norms[i], cr_vsub(bv[j], A->verts[i])));
        if (i == 0 || cr_gt(si, best)) {
            best = si;
            *face = i;
        }
    }
    return best;
}

typedef struct cr_clip_vertex {
    cr_v2 p;
    unsigned id;
} cr_clip_vertex;

/* Keep the part of segment in[0..1] with dot(n, p) <= offset. */
static int cr_clip(const cr_clip_vertex in[2], cr_clip_vertex out[2],
                   cr_v2 n, float offset, unsigned clip_id)
{
    int count = 0;
    float d0 = cr_sub(cr_vdot(n, in[0].p), offset);
    float d1 = cr_sub(cr_vdot(n, in[1].p), offset);
    if (cr_le(d0, 0.0f))
        out[count++] = in[0];
    if (cr_le(d1, 0.0f))
        out[count++] = in[1];
    if (cr_lt(cr_mul(d0, d1), 0.0f) && count < 2) {
        float u = cr_div(d0, cr_sub(d0, d1));
        out[count].p = cr_vmadd(in[0].p, u, cr_vsub(in[1].p, in[0].p));
        out[count].id = clip_id;
        ++count;
    }
    return count;
}

static int cr_polygon_polygon(const cr_body *A, const cr_body *B, float margin,
                              cr_manifold *m)
{
    int ea = 0, eb = 0, edge, flip, i, j, inc = 0, count = 0;
    float sa, sb, best, front, side1, side2;
    const cr_body *R, *I;
    cr_v2 v1, v2, nref, t;
    cr_clip_vertex in[2], c1[2], c2[2];

    sa = cr_max_separation(A, B, &ea);
    if (cr_gt(sa, margin))
        return 0;
    sb = cr_max_separation(B, A, &eb);
    if (cr_gt(sb, margin))
        return 0;

    if (cr_gt(sb, cr_add(sa, cr_mul(CR_FACE_TOL_FRACTION, margin)))) {
        R = B; I = A; edge = eb; flip = 1;
    } else {
        R = A; I = B; edge = ea; flip = 0;
    }

    v1 = cr_vadd(R->x, cr_rotate(R->q, R->verts[edge]));
    v2 = cr_vadd(R->x, cr_rotate(R->q, R->verts[(edge + 1) % R->count]));
    nref = cr_rotate(R->q, R->norms[edge]);

    /* incident face: the most anti-parallel to the reference normal */
    best = 0.0f;
    for (j = 0; j < I->count; ++j) {
        float d = cr_vdot(nref, cr_rotate(I->q, I->norms[j]));
        if (j == 0 || cr_lt(d, best)) {
            best = d;
            inc = j;
        }
    }
    in[0].p = cr_vadd(I->x, cr_rotate(I->q, I->verts[inc]));
    in[0].id = (unsigned)inc;
    in[1].p = cr_vadd(I->x, cr_rotate(I->q, I->verts[(inc + 1) % I->count]));
    in[1].id = (unsigned)((inc + 1) % I->count);

    /* side planes of the reference face */
    t = cr_v(cr_neg(nref.y), nref.x);
    side1 = cr_neg(cr_vdot(t, v1));
    side2 = cr_vdot(t, v2);
    if (cr_clip(in, c1, cr_vneg(t), side1, 8u) < 2)
        return 0;
    if (cr_clip(c1, c2, t, side2, 9u) < 2)
        return 0;

    front = cr_vdot(nref, v1);
    for (i = 0; i < 2; ++i) {
        float sep = cr_sub(cr_vdot(nref, c2[i].p), front);
        if (cr_gt(sep, margin))
            continue;
        m->pts[count].sep = sep;
        m->pts[count].p = cr_vmadd(c2[i].p, cr_mul(-0.5f, sep), nref);
        m->pts[count].id = (unsigned)edge | (c2[i].id << 4) |
                           ((unsigned)flip << 8);
        ++count;
    }
    if (count == 0)
        return 0;
    m->count = count;
    m->n = flip ? cr_vneg(nref) : nref;
    return 1;
}
#endif /* CAROM_ENABLE_POLYGONS */

/* Manifold of bodies A (index a) and B (index b > a); 0 if not touching. */
int cr_collide(const cr_body *A, const cr_body *B, float margin, cr_manifold *m)
{
    m->count = 0;
    if (A->shape == CAROM_SHAPE_CIRCLE && B->shape == CAROM_SHAPE_CIRCLE)
        return cr_circle_circle(A, B, margin, m);
#if CAROM_ENABLE_POLYGONS
    if (A->shape == CAROM_SHAPE_POLYGON && B->shape == CAROM_SHAPE_CIRCLE)
        return cr_polygon_circle(A, B, margin, m);
    if (A->shape == CAROM_SHAPE_CIRCLE && B->shape == CAROM_SHAPE_POLYGON) {
        int hit = cr_polygon_circle(B, A, margin, m);
        if (hit)
            m->n = cr_vneg(m->n);
        return hit;
    }
    return cr_polygon_polygon(A, B, margin, m);
#else
    return 0;
#endif
}

/*
 * A lower bound of the distance between two shapes (negative: overlap), for
 * conservative advancement: exact for pairs with a circle; for polygons the
 * separating-axis separation, which is the distance whenever the closest
 * features are a vertex and an edge and never more than it.
 */
float cr_separation(const cr_body *A, const cr_body *B)
{
    cr_manifold m;
    if (A->shape == CAROM_SHAPE_CIRCLE && B->shape == CAROM_SHAPE_CIRCLE)
        return cr_sub(cr_vlen(cr_vsub(B->x, A->x)), cr_add(A->radius, B->radius));
#if CAROM_ENABLE_POLYGONS
    if (A->shape == CAROM_SHAPE_POLYGON && B->shape == CAROM_SHAPE_CIRCLE) {
        cr_polygon_circle(A, B, CR_FAR, &m);
        return m.pts[0].sep;
    }
    if (A->shape == CAROM_SHAPE_CIRCLE) {
        cr_polygon_circle(B, A, CR_FAR, &m);
        return m.pts[0].sep;
    }
    {
        int fa, fb;
        (void)m;
        return cr_max(cr_max_separation(A, B, &fa), cr_max_separation(B, A, &fb));
    }
#else
    (void)m;
    return 0.0f;
#endif
}
