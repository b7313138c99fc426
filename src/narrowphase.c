/*
 * narrowphase.c -- contact manifolds for circle-circle, polygon-circle and
 * polygon-polygon pairs, through a table indexed by the two shape kinds.
 *
 * A manifold holds the unit normal from shape A to shape B and up to two
 * points; each point lies midway between the two surfaces and carries the
 * signed separation along the normal (negative: overlap) and a feature id
 * that stays the same while the same features touch, so the solver can
 * reuse last step's impulses (warm starting). Ids read (feature of A << 8 |
 * feature of B), whichever shape gave the reference face.
 *
 * Everything is computed in A's frame (B's pose relative to A's), so the
 * manifold of a pair does not depend on where in the world it sits: a stack
 * at x = 7.77 gets the same contacts as at x = 0.
 *
 * Polygon pairs use the separating axis test over both polygons' face
 * normals. The face of least penetration is the reference face; B's face
 * is taken only when it is better than A's by more than a tolerance, so
 * aligned edges (equal separations up to rounding) never flip the choice
 * from step to step. The most anti-parallel face of the other polygon is
 * the incident face, and its ends are clamped to the reference face's span
 * (the side planes). Both points are kept as long as they are within reach:
 * a point beyond it is speculative and the solver ignores it until the
 * surfaces close in.
 */
#include "narrowphase.h"

/* Feature ids of a circle, and of a clipped polygon point whose incident
 * end was cut by a side plane (its position is then the reference vertex's
 * side, the id names the reference vertex). */
#define CR_ID(a, b) (((unsigned)(a) << 8) | (unsigned)(b))

typedef int (*cr_collide_fn)(const cr_shape *A, const cr_shape *B, cr_v2 p,
                             cr_rot q, float reach, float face_tol, float corner,
                             cr_manifold *m);

static cr_v2 cr_midpoint(cr_v2 p, cr_v2 q)
{
    return cr_vscale(0.5f, cr_vadd(p, q));
}

/* Relative rotation qa^-1 qb. */
static cr_rot cr_rot_relative(cr_rot qa, cr_rot qb)
{
    return cr_r(cr_add(cr_mul(qa.c, qb.c), cr_mul(qa.s, qb.s)),
                cr_sub(cr_mul(qa.c, qb.s), cr_mul(qa.s, qb.c)));
}

/* ---- circle - circle (in A's frame: A at the origin) ---------------------- */

static int cr_circles(const cr_shape *A, const cr_shape *B, cr_v2 p, cr_rot q,
                      float reach, float face_tol, float corner, cr_manifold *m)
{
    float r = cr_add(A->radius, B->radius);
    float far = cr_add(r, reach);
    float dist2 = cr_vlen2(p), dist;
    cr_v2 n;
    (void)q;
    (void)face_tol;
    (void)corner;
    if (cr_gt(dist2, cr_mul(far, far)))
        return 0;
    dist = cr_sqrt(dist2);
    /* Concentric circles: any normal is right; pick +y deterministically.
     * A squared distance below FLT_MIN counts as concentric: it is
     * subnormal, and p / sqrt of it is not of unit length. */
    n = cr_lt(dist2, CR_ROT_MIN_LEN2) ? cr_v(0.0f, 1.0f) : cr_vscale(cr_div(1.0f, dist), p);
    m->n = n;
    m->count = 1;
    m->pts[0].sep = cr_sub(dist, r);
    m->pts[0].p = cr_midpoint(cr_vscale(A->radius, n),
                              cr_vmadd(p, cr_neg(B->radius), n));
    m->pts[0].id = 0u;
    return 1;
}

#if CAROM_ENABLE_POLYGONS

/* ---- polygon - circle (normal from the polygon to the circle) ------------ */

/* Polygon P at the origin of the frame, circle centre c in that frame. */
static int cr_polygon_circle_at(const cr_shape *P, cr_v2 c, float r,
                                float reach, cr_manifold *m, int flip)
{
    float far = cr_add(r, reach), s, sep;
    int i, face = 0, n = P->count, vertex;
    cr_v2 v1, v2, normal, surface;

    s = cr_vdot(P->norms[0], cr_vsub(c, P->verts[0]));
    for (i = 1; i < n; ++i) {
        float si = cr_vdot(P->norms[i], cr_vsub(c, P->verts[i]));
        if (cr_gt(si, s)) {
            s = si;
            face = i;
        }
    }
    if (cr_gt(s, far))
        return 0;
    v1 = P->verts[face];
    v2 = P->verts[(face + 1) % n];
    vertex = -1;
    if (cr_gt(s, 0.0f)) {
        float u1 = cr_vdot(cr_vsub(c, v1), cr_vsub(v2, v1));
        float u2 = cr_vdot(cr_vsub(c, v2), cr_vsub(v1, v2));
        if (cr_le(u1, 0.0f))
            vertex = face;
        else if (cr_le(u2, 0.0f))
            vertex = (face + 1) % n;
    }
    if (vertex >= 0) {
        /* the centre is beyond a vertex: the normal points from it */
        cr_v2 v = P->verts[vertex];
        cr_v2 d = cr_vsub(c, v);
        float dist2 = cr_vlen2(d), dist;
        if (cr_gt(dist2, cr_mul(far, far)))
            return 0;
        if (cr_lt(dist2, CR_ROT_MIN_LEN2)) {
            /* the centre within sqrt(FLT_MIN) of the vertex: d / |d| would
             * not be of unit length (|d|^2 subnormal); the face normal is
             * as right, and s <= |d| is as small */
            vertex = -1;
        } else {
            dist = cr_sqrt(dist2);
            normal = cr_vscale(cr_div(1.0f, dist), d);
            sep = cr_sub(dist, r);
            surface = v;
        }
    }
    if (vertex < 0) {
        /* face region, or the centre inside: out through the face of least
         * penetration */
        normal = P->norms[face];
        sep = cr_sub(s, r);
        surface = cr_vmadd(c, cr_neg(s), normal);
    }
    m->count = 1;
    m->n = flip ? cr_vneg(normal) : normal;
    m->pts[0].sep = sep;
    m->pts[0].p = cr_midpoint(surface, cr_vmadd(c, cr_neg(r), normal));
    m->pts[0].id = vertex >= 0 ? CR_ID(vertex, 0) : CR_ID(16 + face, 0);
    if (flip)
        m->pts[0].id = (m->pts[0].id >> 8) | ((m->pts[0].id & 0xffu) << 8);
    return 1;
}

/* A polygon, B circle at p (A's frame). */
static int cr_polygon_circle(const cr_shape *A, const cr_shape *B, cr_v2 p,
                             cr_rot q, float reach, float face_tol, float corner,
                             cr_manifold *m)
{
    (void)q;
    (void)face_tol;
    (void)corner; /* a disc's contact with a corner is kept: where it only
                     grazes (rolling flush over a seam) is not told by the
                     pose from where it falls onto the corner */
    return cr_polygon_circle_at(A, p, B->radius, reach, m, 0);
}

/* A circle, B polygon at (p, q) in A's frame: solved in B's frame. */
static int cr_circle_polygon(const cr_shape *A, const cr_shape *B, cr_v2 p,
                             cr_rot q, float reach, float face_tol, float corner,
                             cr_manifold *m)
{
    int k, hit;
    cr_v2 c = cr_inv_rotate(q, cr_vneg(p)); /* A's centre in B's frame */
    (void)face_tol;
    (void)corner;
    hit = cr_polygon_circle_at(B, c, A->radius, reach, m, 1);
    if (!hit)
        return 0;
    m->n = cr_rotate(q, m->n);
    for (k = 0; k < m->count; ++k)
        m->pts[k].p = cr_vadd(p, cr_rotate(q, m->pts[k].p));
    return hit;
}

/* ---- polygon - polygon ----------------------------------------------------- */

#if CAROM_ENABLE_POLYGON_POLYGON
/* Largest separation of the points w[] from polygon P (its own frame) over
 * P's face normals, and that face. */
static float cr_max_separation(const cr_shape *P, const cr_v2 *w, int count,
                               int *face)
{
    float best = 0.0f;
    int i, j;
    for (i = 0; i < P->count; ++i) {
        float si = cr_vdot(P->norms[i], cr_vsub(w[0], P->verts[i]));
        for (j = 1; j < count; ++j)
            si = cr_min(si, cr_vdot(P->norms[i], cr_vsub(w[j], P->verts[i])));
        if (i == 0 || cr_gt(si, best)) {
            best = si;
            *face = i;
        }
    }
    return best;
}

/* Index of the edge of the polygon with normals nrm[] most anti-parallel to
 * n. */
static int cr_incident_edge(const cr_v2 *nrm, int count, cr_v2 n)
{
    int j, best = 0;
    float low = cr_vdot(n, nrm[0]);
    for (j = 1; j < count; ++j) {
        float d = cr_vdot(n, nrm[j]);
        if (cr_lt(d, low)) {
            low = d;
            best = j;
        }
    }
    return best;
}

/* How far u lies outside the span [0, upper] along a reference face. */
static float cr_lateral_excess(float u, float upper)
{
    if (cr_lt(u, 0.0f))
        return cr_neg(u);
    return cr_gt(u, upper) ? cr_sub(u, upper) : 0.0f;
}

/* A graze (docs/physics.md, "Seams"): the incident polygon overlaps the
 * reference face only within `corner` of one of its ends, and dips no
 * deeper than `corner` below the plane of the face that meets the
 * reference face there. Returns that face, or -1. The manifold is made as
 * ever and marked; whether a graze is a seam's ghost (a flush neighbour
 * carries the body across) is for the world to tell (contact.c). */
static int cr_sliver(const cr_v2 *rv, const cr_v2 *rn, int rc, int ref, const cr_v2 *iv,
                     int ic, float lower2, float upper2, float upper1, float corner)
{
    float s;
    int adj, j;
    if (!cr_gt(corner, 0.0f))
        return -1;
    if (!cr_lt(lower2, cr_sub(upper1, corner)))
        adj = (ref + 1) % rc; /* only within `corner` of the far end, v12 */
    else if (!cr_gt(upper2, corner))
        adj = (ref + rc - 1) % rc; /* only within it of the near end, v11 */
    else
        return -1;
    s = cr_vdot(rn[adj], cr_vsub(iv[0], rv[adj]));
    for (j = 1; j < ic; ++j)
        s = cr_min(s, cr_vdot(rn[adj], cr_vsub(iv[j], rv[adj])));
    return !cr_gt(s, 0.0f) && !cr_lt(s, cr_neg(corner)) ? adj : -1;
}

static int cr_polygons(const cr_shape *A, const cr_shape *B, cr_v2 p, cr_rot q,
                       float reach, float face_tol, float corner, cr_manifold *m)
{
    cr_v2 bv[CAROM_MAX_POLYGON_VERTICES], bn[CAROM_MAX_POLYGON_VERTICES];
    cr_v2 av[CAROM_MAX_POLYGON_VERTICES]; /* A's vertices in B's frame */
    const cr_v2 *rv, *rn, *iv, *in;
    int ea = 0, eb = 0, j, flip, ref, inc, rc, ic, i11, i12, i21, i22, k;
    float sa, sb, upper1, upper2, lower2, span;
    cr_v2 v11, v12, v21, v22, nref, t, lo, hi, pts[2];
    unsigned ids[2];
    float seps[2];

    /* (do-while: a polygon has at least 3 vertices, and so the compiler
     * can see bv[0] is set; a for loop gave -O3 a maybe-uninitialized) */
    j = 0;
    do {
        bv[j] = cr_vadd(p, cr_rotate(q, B->verts[j]));
        bn[j] = cr_rotate(q, B->norms[j]);
    } while (++j < B->count);
    sa = cr_max_separation(A, bv, B->count, &ea);
    if (cr_gt(sa, reach))
        return 0;
    j = 0;
    do
        av[j] = cr_inv_rotate(q, cr_vsub(A->verts[j], p));
    while (++j < A->count);
    sb = cr_max_separation(B, av, A->count, &eb);
    if (cr_gt(sb, reach))
        return 0;

    /* A's face unless B's is clearly better */
    flip = cr_gt(sb, cr_add(sa, face_tol));
    if (flip) {
        rv = bv; rn = bn; rc = B->count; ref = eb;
        iv = A->verts; in = A->norms; ic = A->count;
    } else {
        rv = A->verts; rn = A->norms; rc = A->count; ref = ea;
        iv = bv; in = bn; ic = B->count;
    }
    nref = rn[ref];
    i11 = ref;
    i12 = (ref + 1) % rc;
    v11 = rv[i11];
    v12 = rv[i12];
    inc = cr_incident_edge(in, ic, nref);
    i21 = inc;
    i22 = (inc + 1) % ic;
    v21 = iv[i21];
    v22 = iv[i22];

    /* Along the reference edge (tangent t, from v11 to v12) the reference
     * face spans [0, upper1]; the incident edge runs the other way, from
     * v21 (upper2) to v22 (lower2). Clamp its ends into the span. */
    t = cr_v(cr_neg(nref.y), nref.x);
    upper1 = cr_vdot(t, cr_vsub(v12, v11));
    upper2 = cr_vdot(t, cr_vsub(v21, v11));
    lower2 = cr_vdot(t, cr_vsub(v22, v11));
    span = cr_sub(upper2, lower2);
    if (cr_lt(upper2, 0.0f) || cr_gt(lower2, upper1) || !cr_gt(span, 0.0f)) {
        /* no lateral overlap (a corner passing a corner): the end nearer
         * the reference face along it (the deeper on a tie), at the
         * separation along this axis, the deeper end's (a bound on the
         * distance, as the axis test gave) */
        float d21 = cr_vdot(nref, cr_vsub(v21, v11));
        float d22 = cr_vdot(nref, cr_vsub(v22, v11));
        float x21 = cr_lateral_excess(upper2, upper1);
        float x22 = cr_lateral_excess(lower2, upper1);
        int near22 = cr_lt(x22, x21) || (cr_eq(x22, x21) && cr_lt(d22, d21));
        lo = hi = near22 ? v22 : v21;
        pts[0] = lo;
        ids[0] = near22 ? CR_ID(i11, i22) : CR_ID(i12, i21);
        seps[0] = cr_min(d21, d22);
        k = 1;
    } else {
        int adj = cr_sliver(rv, rn, rc, ref, iv, ic, lower2, upper2, upper1, corner);
        if (adj >= 0) {
            /* a graze of the reference polygon's corner (A's frame here) */
            m->graze = flip ? 1 : 2;
            m->graze_n = rn[adj];
            m->graze_d = cr_vdot(rn[adj], rv[adj]);
        }
        /* an end cut by a side plane lies on that plane exactly (at the
         * reference vertex, moved along the normal to the incident face),
         * so a symmetric pair gets symmetric points to the last bit and a
         * face impact gives no spurious spin */
        if (cr_lt(lower2, 0.0f)) {
            cr_v2 cut = cr_vmadd(v22, cr_div(cr_neg(lower2), span), cr_vsub(v21, v22));
            lo = cr_vmadd(v11, cr_vdot(nref, cr_vsub(cut, v11)), nref);
        } else {
            lo = v22;
        }
        if (cr_gt(upper2, upper1)) {
            cr_v2 cut = cr_vmadd(v22, cr_div(cr_sub(upper1, lower2), span),
                                 cr_vsub(v21, v22));
            hi = cr_vmadd(v12, cr_vdot(nref, cr_vsub(cut, v11)), nref);
        } else {
            hi = v21;
        }
        pts[0] = lo;
        ids[0] = CR_ID(i11, i22);
        seps[0] = cr_vdot(nref, cr_vsub(lo, v11));
        pts[1] = hi;
        ids[1] = CR_ID(i12, i21);
        seps[1] = cr_vdot(nref, cr_vsub(hi, v11));
        k = 2;
    }

    m->count = 0;
    for (j = 0; j < k; ++j) {
        cr_manifold_point *mp;
        if (cr_gt(seps[j], reach))
            continue;
        mp = &m->pts[m->count++];
        mp->sep = seps[j];
        /* midway between the surfaces */
        mp->p = cr_vmadd(pts[j], cr_mul(-0.5f, seps[j]), nref);
        /* ids read (A's feature, B's feature) */
        mp->id = flip ? ((ids[j] >> 8) | ((ids[j] & 0xffu) << 8)) : ids[j];
    }
    if (m->count == 0)
        return 0;
    /* every vector above is in A's frame; the normal goes from A to B */
    m->n = flip ? cr_vneg(nref) : nref;
    return m->count;
}
#endif /* CAROM_ENABLE_POLYGON_POLYGON */
#endif /* CAROM_ENABLE_POLYGONS */

/* Shape-pair dispatch: [kind of A][kind of B]; NULL: the pair never
 * collides in this build. */
static const cr_collide_fn cr_collide_table[2][2] = {
    {cr_circles,
#if CAROM_ENABLE_POLYGONS
     cr_circle_polygon},
    {cr_polygon_circle,
#if CAROM_ENABLE_POLYGON_POLYGON
     cr_polygons},
#else
     0},
#endif
#else
     0},
    {0, 0},
#endif
};

int cr_collide(const cr_shape *A, cr_v2 xa, cr_rot qa, const cr_shape *B,
               cr_v2 xb, cr_rot qb, float reach, float face_tol, float corner,
               cr_manifold *m)
{
    cr_collide_fn fn = cr_collide_table[A->kind][B->kind];
    cr_v2 p;
    cr_rot q;
    int k, hit;
    m->count = 0;
    m->graze = 0;
    if (!fn)
        return 0;
    /* B relative to A, in A's frame */
    p = cr_inv_rotate(qa, cr_vsub(xb, xa));
    q = cr_rot_relative(qa, qb);
    hit = fn(A, B, p, q, reach, face_tol, corner, m);
    if (!hit)
        return 0;
    m->n = cr_rotate(qa, m->n);
    for (k = 0; k < m->count; ++k)
        m->pts[k].p = cr_vadd(xa, cr_rotate(qa, m->pts[k].p));
    if (m->graze) {
        m->graze_n = cr_rotate(qa, m->graze_n);
        m->graze_d = cr_add(m->graze_d, cr_vdot(m->graze_n, xa));
    }
    return m->count;
}

/* A margin larger than any distance: collide at any range. */
#define CR_FAR 3.0e38f

float cr_separation(const cr_shape *A, cr_v2 xa, cr_rot qa, const cr_shape *B,
                    cr_v2 xb, cr_rot qb)
{
    if (CR_KIND_CIRCLE(A->kind) && CR_KIND_CIRCLE(B->kind))
        return cr_sub(cr_vlen(cr_vsub(xb, xa)), cr_add(A->radius, B->radius));
#if !CAROM_ENABLE_POLYGONS
    (void)qa;
    (void)qb;
#else
    {
        cr_manifold m;
        cr_v2 p = cr_inv_rotate(qa, cr_vsub(xb, xa));
        cr_rot q = cr_rot_relative(qa, qb);
        if (A->kind == CAROM_SHAPE_POLYGON && B->kind == CAROM_SHAPE_CIRCLE) {
            cr_polygon_circle_at(A, p, B->radius, CR_FAR, &m, 0);
            return m.pts[0].sep;
        }
        if (A->kind == CAROM_SHAPE_CIRCLE) {
            cr_v2 c = cr_inv_rotate(q, cr_vneg(p));
            cr_polygon_circle_at(B, c, A->radius, CR_FAR, &m, 1);
            return m.pts[0].sep;
        }
#if CAROM_ENABLE_POLYGON_POLYGON
        {
            cr_v2 w[CAROM_MAX_POLYGON_VERTICES];
            int j, fa, fb;
            float sa, sb;
            for (j = 0; j < B->count; ++j)
                w[j] = cr_vadd(p, cr_rotate(q, B->verts[j]));
            sa = cr_max_separation(A, w, B->count, &fa);
            for (j = 0; j < A->count; ++j)
                w[j] = cr_inv_rotate(q, cr_vsub(A->verts[j], p));
            sb = cr_max_separation(B, w, A->count, &fb);
            return cr_max(sa, sb);
        }
#endif
    }
#endif
    return CR_FAR;
}
