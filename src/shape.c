/*
 * shape.c -- body definitions: validation, polygon repair, mass properties
 * and bounding boxes.
 *
 * Polygons are stored about their centroid, so the body's position is its
 * centre of mass and rotation happens about it; local_center remembers where
 * the definition's origin was, to report positions in the caller's frame.
 */
#include "internal.h"

#define CR_PI 3.14159265358979323846f

static int cr_vec_finite(cr_v2 v) { return cr_finite(v.x) && cr_finite(v.y); }

/* ---- polygon checks -------------------------------------------------------- */

#if CAROM_ENABLE_POLYGONS

/* Do segments p1p2 and q1q2 cross at a point interior to both? */
static int cr_segments_cross(cr_v2 p1, cr_v2 p2, cr_v2 q1, cr_v2 q2)
{
    cr_v2 r = cr_vsub(p2, p1), s = cr_vsub(q2, q1);
    float d1 = cr_vcross(r, cr_vsub(q1, p1));
    float d2 = cr_vcross(r, cr_vsub(q2, p1));
    float d3 = cr_vcross(s, cr_vsub(p1, q1));
    float d4 = cr_vcross(s, cr_vsub(p2, q1));
    return cr_lt(cr_mul(d1, d2), 0.0f) && cr_lt(cr_mul(d3, d4), 0.0f);
}

/*
 * Validate a polygon and write it counter-clockwise into out[] (n vertices).
 * Order of the checks: counts, finiteness, repeated vertices, crossing
 * edges, orientation (clockwise input is reversed), then every vertex must
 * turn left by more than CAROM_POLYGON_ANGLE_TOL and every vertex must lie
 * inside every edge (which rejects star polygons that wind twice).
 */
static carom_status cr_polygon_check(const cr_v2 *in, int n, cr_v2 *out)
{
    int i, j;
    float area2 = 0.0f;

    if (n < 3)
        return CAROM_ERR_TOO_FEW_VERTICES;
    if (n > CAROM_MAX_POLYGON_VERTICES)
        return CAROM_ERR_TOO_MANY_VERTICES;
    for (i = 0; i < n; ++i)
        if (!cr_vec_finite(in[i]))
            return CAROM_ERR_NOT_FINITE;
    for (i = 0; i < n; ++i)
        for (j = i + 1; j < n; ++j)
            if (cr_eq(in[i].x, in[j].x) && cr_eq(in[i].y, in[j].y))
                return CAROM_ERR_DEGENERATE_POLYGON;
    for (i = 0; i < n; ++i) {
        for (j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1)
                continue; /* adjacent through the wrap */
            if (cr_segments_cross(in[i], in[(i + 1) % n], in[j],
                                  in[(j + 1) % n]))
                return CAROM_ERR_SELF_INTERSECTING;
        }
    }
    for (i = 0; i < n; ++i)
        area2 = cr_add(area2, cr_vcross(in[i], in[(i + 1) % n]));
    if (!cr_finite(area2))
        return CAROM_ERR_NOT_FINITE;
    if (cr_eq(area2, 0.0f))
        return CAROM_ERR_DEGENERATE_POLYGON;
    for (i = 0; i < n; ++i)
        out[i] = cr_gt(area2, 0.0f) ? in[i] : in[n - 1 - i];

    for (i = 0; i < n; ++i) {
        cr_v2 e1 = cr_vsub(out[(i + 1) % n], out[i]);
        cr_v2 e2 = cr_vsub(out[(i + 2) % n], out[(i + 1) % n]);
        float turn = cr_vcross(e1, e2);
        float scale = cr_mul(cr_vlen(e1), cr_vlen(e2));
        if (cr_lt(turn, 0.0f))
            return CAROM_ERR_NOT_CONVEX;
        if (cr_le(turn, cr_mul(CAROM_POLYGON_ANGLE_TOL, scale)))
            return CAROM_ERR_DEGENERATE_POLYGON;
    }
    for (i = 0; i < n; ++i) {
        cr_v2 e = cr_vsub(out[(i + 1) % n], out[i]);
        for (j = 0; j < n; ++j)
            if (cr_lt(cr_vcross(e, cr_vsub(out[j], out[i])), 0.0f))
                return CAROM_ERR_NOT_CONVEX;
    }
    return CAROM_OK;
}

/*
 * Area, centroid and polar moment (about the centroid, per unit density) of
 * a counter-clockwise polygon: a fan of triangles from vertex 0, each
 * triangle's second moment integrated exactly, then moved to the centroid
 * with the parallel-axis theorem.
 */
static void cr_polygon_mass(const cr_v2 *v, int n, float *area, cr_v2 *center,
                            float *inertia)
{
    int i;
    float a = 0.0f, j0 = 0.0f;
    cr_v2 c = cr_v(0.0f, 0.0f);
    cr_v2 o = v[0];
    for (i = 1; i + 1 < n; ++i) {
        cr_v2 e1 = cr_vsub(v[i], o), e2 = cr_vsub(v[i + 1], o);
        float d = cr_vcross(e1, e2);
        float ta = cr_mul(0.5f, d);
        float ix = cr_add(cr_add(cr_mul(e1.x, e1.x), cr_mul(e2.x, e1.x)),
                          cr_mul(e2.x, e2.x));
        float iy = cr_add(cr_add(cr_mul(e1.y, e1.y), cr_mul(e2.y, e1.y)),
                          cr_mul(e2.y, e2.y));
        a = cr_add(a, ta);
        c = cr_vadd(c, cr_vscale(cr_div(ta, 3.0f), cr_vadd(e1, e2)));
        j0 = cr_add(j0, cr_mul(cr_div(d, 12.0f), cr_add(ix, iy)));
    }
    c = cr_vscale(cr_div(1.0f, a), c); /* relative to o */
    *area = a;
    *inertia = cr_sub(j0, cr_mul(a, cr_vdot(c, c)));
    *center = cr_vadd(o, c);
}

#endif /* CAROM_ENABLE_POLYGONS */

/* ---- public definition helpers ------------------------------------------- */

carom_body_def carom_default_body_def(void)
{
    carom_body_def d;
    int i;
    d.type = CAROM_BODY_DYNAMIC;
    d.shape = CAROM_SHAPE_CIRCLE;
    d.radius = 0.5f;
    d.vertex_count = 0;
    for (i = 0; i < CAROM_MAX_POLYGON_VERTICES; ++i)
        d.vertices[i] = cr_v(0.0f, 0.0f);
    d.position = cr_v(0.0f, 0.0f);
    d.rotation = cr_rot_identity();
    d.velocity = cr_v(0.0f, 0.0f);
    d.angular_velocity = 0.0f;
    d.density = 1.0f;
    d.mass = 0.0f;
    d.restitution = 0.0f;
    d.friction = 0.6f;
    d.force = cr_v(0.0f, 0.0f);
    d.torque = 0.0f;
    return d;
}

carom_status carom_body_def_set_box(carom_body_def *def, float hx, float hy)
{
    if (!def)
        return CAROM_ERR_NULL;
    if (!cr_finite(hx) || !cr_finite(hy))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_gt(hx, 0.0f) || !cr_gt(hy, 0.0f))
        return CAROM_ERR_DEGENERATE_POLYGON;
    def->shape = CAROM_SHAPE_POLYGON;
    def->vertex_count = 4;
    def->vertices[0] = cr_v(cr_neg(hx), cr_neg(hy));
    def->vertices[1] = cr_v(hx, cr_neg(hy));
    def->vertices[2] = cr_v(hx, hy);
    def->vertices[3] = cr_v(cr_neg(hx), hy);
    return CAROM_OK;
}

carom_status carom_body_def_validate(const carom_body_def *def)
{
    cr_body scratch;
    return cr_body_build(def, &scratch);
}

/*
 * Validate `def` completely and build the body in *out. *out is written
 * only on success, so a failed add leaves the world untouched.
 */
carom_status cr_body_build(const carom_body_def *def, cr_body *out)
{
    cr_body b;
    int i;
    float area, unit_inertia, qlen;
    cr_v2 center = cr_v(0.0f, 0.0f);

    if (!def || !out)
        return CAROM_ERR_NULL;
    if (def->type != CAROM_BODY_DYNAMIC && def->type != CAROM_BODY_STATIC)
        return CAROM_ERR_BAD_BODY_TYPE;
    if (def->shape != CAROM_SHAPE_CIRCLE && def->shape != CAROM_SHAPE_POLYGON)
        return CAROM_ERR_BAD_SHAPE;
    if (!cr_vec_finite(def->position) || !cr_vec_finite(def->velocity) ||
        !cr_finite(def->rotation.c) || !cr_finite(def->rotation.s) ||
        !cr_finite(def->angular_velocity) || !cr_finite(def->density) ||
        !cr_finite(def->mass) || !cr_finite(def->restitution) ||
        !cr_finite(def->friction) || !cr_vec_finite(def->force) ||
        !cr_finite(def->torque) || !cr_finite(def->radius))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_le(0.0f, def->restitution) || !cr_le(def->restitution, 1.0f))
        return CAROM_ERR_BAD_RESTITUTION;
    if (cr_lt(def->friction, 0.0f))
        return CAROM_ERR_BAD_FRICTION;
    if (cr_lt(def->mass, 0.0f))
        return CAROM_ERR_BAD_MASS;
    if (!cr_gt(def->density, 0.0f))
        return CAROM_ERR_BAD_DENSITY;
    qlen = cr_add(cr_mul(def->rotation.c, def->rotation.c),
                  cr_mul(def->rotation.s, def->rotation.s));
    if (!cr_gt(qlen, 0.0f) || !cr_finite(qlen))
        return CAROM_ERR_BAD_ROTATION;
#if !CAROM_ENABLE_FORCES
    if (!cr_eq(def->force.x, 0.0f) || !cr_eq(def->force.y, 0.0f) ||
        !cr_eq(def->torque, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
#if !CAROM_ENABLE_ROTATION
    if (!cr_eq(def->angular_velocity, 0.0f))
        return CAROM_ERR_DISABLED;
#endif

    b.type = def->type;
    b.shape = def->shape;
    b.radius = 0.0f;
    b.count = 0;
    for (i = 0; i < CAROM_MAX_POLYGON_VERTICES; ++i) {
        b.verts[i] = cr_v(0.0f, 0.0f);
        b.norms[i] = cr_v(0.0f, 0.0f);
    }

    if (def->shape == CAROM_SHAPE_CIRCLE) {
        if (!cr_gt(def->radius, 0.0f))
            return CAROM_ERR_BAD_RADIUS;
        b.radius = def->radius;
        area = cr_mul(CR_PI, cr_mul(b.radius, b.radius));
        unit_inertia = cr_mul(cr_mul(0.5f, area), cr_mul(b.radius, b.radius));
        b.extent = b.radius;
        if (!cr_finite(area) || !cr_gt(area, 0.0f) || !cr_finite(unit_inertia))
            return CAROM_ERR_BAD_RADIUS;
    } else {
#if CAROM_ENABLE_POLYGONS
        cr_v2 ccw[CAROM_MAX_POLYGON_VERTICES];
        int n = def->vertex_count;
        carom_status st = cr_polygon_check(def->vertices, n, ccw);
        if (st != CAROM_OK)
            return st;
        cr_polygon_mass(ccw, n, &area, &center, &unit_inertia);
        if (!cr_finite(area) || !cr_gt(area, 0.0f) ||
            !cr_finite(unit_inertia) || !cr_gt(unit_inertia, 0.0f) ||
            !cr_vec_finite(center))
            return CAROM_ERR_DEGENERATE_POLYGON;
        b.count = n;
        b.extent = 0.0f;
        for (i = 0; i < n; ++i) {
            b.verts[i] = cr_vsub(ccw[i], center);
            b.extent = cr_max(b.extent, cr_vlen(b.verts[i]));
        }
        for (i = 0; i < n; ++i) {
            cr_v2 e = cr_vsub(b.verts[(i + 1) % n], b.verts[i]);
            float len = cr_vlen(e);
            b.norms[i] = cr_v(cr_div(e.y, len), cr_div(cr_neg(e.x), len));
        }
#else
        return CAROM_ERR_DISABLED;
#endif
    }

    b.local_center = center;
    b.q = cr_rot_normalize(def->rotation);
    b.x = cr_vadd(def->position, cr_rotate(b.q, center));
    b.vel = def->velocity;
    b.w = def->angular_velocity;
    b.restitution = def->restitution;
    b.friction = def->friction;
    b.force = def->force;
    b.torque = def->torque;
    b.acc = cr_v(0.0f, 0.0f);
    b.alpha = 0.0f;
    b.acc_c = cr_v(0.0f, 0.0f);
    b.alpha_c = 0.0f;
    b.dx = cr_v(0.0f, 0.0f);
    b.dtheta = 0.0f;
    b.vel_saved = cr_v(0.0f, 0.0f);
    b.w_saved = 0.0f;

    if (def->type == CAROM_BODY_STATIC) {
        b.m = b.inv_m = b.I = b.inv_I = 0.0f;
        b.vel = cr_v(0.0f, 0.0f);
        b.w = 0.0f;
    } else {
        float density = def->density;
        if (cr_gt(def->mass, 0.0f))
            density = cr_div(def->mass, area);
        b.m = cr_gt(def->mass, 0.0f) ? def->mass : cr_mul(density, area);
        b.I = cr_mul(density, unit_inertia);
        if (!cr_finite(b.m) || !cr_gt(b.m, 0.0f))
            return CAROM_ERR_BAD_MASS;
        if (!cr_finite(b.I) || !cr_gt(b.I, 0.0f))
            return CAROM_ERR_BAD_MASS;
        b.inv_m = cr_div(1.0f, b.m);
#if CAROM_ENABLE_ROTATION
        b.inv_I = cr_div(1.0f, b.I);
#else
        b.inv_I = 0.0f;
#endif
    }
    *out = b;
    return CAROM_OK;
}

/* World position of the definition's origin: centre minus rotated offset. */
carom_vec2 cr_body_origin(const cr_body *b)
{
    return cr_vsub(b->x, cr_rotate(b->q, b->local_center));
}

/* Axis-aligned box around the body's shape, grown by `margin`. */
void cr_body_bounds(const cr_body *b, float margin, cr_proxy *out)
{
    if (b->shape == CAROM_SHAPE_CIRCLE) {
        float r = cr_add(b->radius, margin);
        out->lo_x = cr_sub(b->x.x, r);
        out->hi_x = cr_add(b->x.x, r);
        out->lo_y = cr_sub(b->x.y, r);
        out->hi_y = cr_add(b->x.y, r);
    } else {
        int i;
        cr_v2 p = cr_vadd(b->x, cr_rotate(b->q, b->verts[0]));
        out->lo_x = out->hi_x = p.x;
        out->lo_y = out->hi_y = p.y;
        for (i = 1; i < b->count; ++i) {
            p = cr_vadd(b->x, cr_rotate(b->q, b->verts[i]));
            out->lo_x = cr_min(out->lo_x, p.x);
            out->hi_x = cr_max(out->hi_x, p.x);
            out->lo_y = cr_min(out->lo_y, p.y);
            out->hi_y = cr_max(out->hi_y, p.y);
        }
        out->lo_x = cr_sub(out->lo_x, margin);
        out->hi_x = cr_add(out->hi_x, margin);
        out->lo_y = cr_sub(out->lo_y, margin);
        out->hi_y = cr_add(out->hi_y, margin);
    }
}
