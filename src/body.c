/*
 * body.c -- body definitions: validation against carom's documented ranges
 * (carom_config.h CAROM_LIMIT_*), polygon repair, mass properties and
 * bounding boxes.
 *
 * Polygons are stored about their centroid, so the body's position is its
 * centre of mass and rotation happens about it; local_center remembers where
 * the definition's origin was, to report positions in the caller's frame.
 */
#include "body.h"


static int cr_vec_finite(cr_v2 v) { return cr_finite(v.x) && cr_finite(v.y); }

int cr_body_moves(const cr_body *b)
{
    if (!(b->flags & CR_BODY_ALIVE) || !(b->flags & CR_BODY_AWAKE))
        return 0;
    if (b->type == CAROM_BODY_DYNAMIC)
        return 1;
#if CAROM_ENABLE_KINEMATIC
    return b->type == CAROM_BODY_KINEMATIC &&
           (!cr_eq(b->v.x, 0.0f) || !cr_eq(b->v.y, 0.0f) || !cr_eq(b->w, 0.0f));
#else
    return 0; /* static */
#endif
}

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
    for (i = 0; i < n; ++i) {
        if (!cr_vec_finite(in[i]))
            return CAROM_ERR_NOT_FINITE;
        if (!cr_v2_within(in[i], CAROM_LIMIT_MAX_LENGTH))
            return CAROM_ERR_OUT_OF_RANGE;
    }
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
 * a counter-clockwise polygon: a fan of triangles from the mean of the
 * vertices, each triangle's second moment integrated exactly, then moved to
 * the centroid with the parallel-axis theorem. Fanning from the mean (not
 * from a vertex) makes the contributions of a symmetric polygon cancel
 * exactly: a box's centroid is its centre to the last bit, so a head-on
 * face impact gives it no spin from rounding.
 */
static void cr_polygon_mass(const cr_v2 *v, int n, float *area, cr_v2 *center,
                            float *inertia)
{
    int i;
    float a = 0.0f, j0 = 0.0f;
    cr_v2 c = cr_v(0.0f, 0.0f), o = cr_v(0.0f, 0.0f);
    for (i = 0; i < n; ++i)
        o = cr_vadd(o, v[i]);
    o = cr_vscale(cr_div(1.0f, (float)n), o);
    for (i = 0; i < n; ++i) {
        cr_v2 e1 = cr_vsub(v[i], o), e2 = cr_vsub(v[(i + 1) % n], o);
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
    d.radius = CAROM_DEFAULT_RADIUS;
    d.vertex_count = 0;
    for (i = 0; i < CAROM_MAX_POLYGON_VERTICES; ++i)
        d.vertices[i] = cr_v(0.0f, 0.0f);
    d.position = cr_v(0.0f, 0.0f);
    d.rotation = cr_rot_identity();
    d.velocity = cr_v(0.0f, 0.0f);
    d.angular_velocity = 0.0f;
    d.density = CAROM_DEFAULT_DENSITY;
    d.mass = 0.0f;
    d.restitution = CAROM_DEFAULT_RESTITUTION;
    d.friction = CAROM_DEFAULT_FRICTION;
    d.force = cr_v(0.0f, 0.0f);
    d.torque = 0.0f;
    d.category_bits = 1u;
    d.mask_bits = 0xffffffffu;
    d.group_index = 0;
    d.is_sensor = 0;
    d.user_data = 0;
    return d;
}

int cr_filter_pass(const cr_body_info *a, const cr_body_info *b)
{
    if (a->group != 0 && a->group == b->group)
        return a->group > 0;
    return (a->category & b->mask) != 0u && (b->category & a->mask) != 0u;
}

carom_status carom_body_def_set_box(carom_body_def *def, float hx, float hy)
{
    if (!def)
        return CAROM_ERR_NULL;
    if (!CAROM_ENABLE_POLYGONS) /* a box is a polygon */
        return CAROM_ERR_DISABLED;
    if (!cr_finite(hx) || !cr_finite(hy))
        return CAROM_ERR_NOT_FINITE;
    /* the width carom_world_add_body asks of a polygon (a review found
     * 1e-7 accepted here and refused there) */
    if (!cr_ge(hx, CAROM_LIMIT_MIN_SIZE) || !cr_ge(hy, CAROM_LIMIT_MIN_SIZE))
        return CAROM_ERR_DEGENERATE_POLYGON;
    if (cr_gt(hx, CAROM_LIMIT_MAX_LENGTH) || cr_gt(hy, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
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
    cr_body hot;
    cr_body_info info;
    return cr_body_build(def, &hot, &info);
}

#if CAROM_ENABLE_FORCES
int cr_accel_in_range(const cr_body_info *info, cr_v2 force, float torque)
{
    float fmax = cr_mul(CAROM_LIMIT_MAX_ACCEL, info->m);
    float tmax = cr_mul(CAROM_LIMIT_MAX_ACCEL, info->I);
    if (!cr_gt(info->m, 0.0f))
        return 1; /* not dynamic: forces do nothing */
    if (!cr_le(cr_abs(force.x), fmax) || !cr_le(cr_abs(force.y), fmax))
        return 0;
    /* alpha times extent is the tangential acceleration of the rim */
    return cr_le(cr_mul(cr_abs(torque), info->shape.extent), tmax);
}
#endif

/* The shape of `def`, about its centroid; *area and *unit_inertia (polar
 * moment per unit density) for the mass. */
static carom_status cr_shape_build(const carom_body_def *def, cr_shape *s,
                                   float *area, float *unit_inertia)
{
#if CAROM_ENABLE_POLYGONS
    int i;
#endif
    s->kind = def->shape;
    s->radius = 0.0f;
    s->count = 0;
    s->local_center = cr_v(0.0f, 0.0f);
#if CAROM_ENABLE_POLYGONS
    for (i = 0; i < CAROM_MAX_POLYGON_VERTICES; ++i) {
        s->verts[i] = cr_v(0.0f, 0.0f);
        s->norms[i] = cr_v(0.0f, 0.0f);
    }
#endif
    if (def->shape == CAROM_SHAPE_CIRCLE) {
        float r = def->radius;
        if (!cr_ge(r, CAROM_LIMIT_MIN_SIZE) || !cr_le(r, CAROM_LIMIT_MAX_LENGTH))
            return CAROM_ERR_BAD_RADIUS;
        s->radius = r;
        s->extent = r;
        s->half_width = r;
        *area = cr_mul(CR_PI, cr_mul(r, r));
        *unit_inertia = cr_mul(cr_mul(0.5f, *area), cr_mul(r, r));
        return CAROM_OK;
    }
#if CAROM_ENABLE_POLYGONS
    {
        cr_v2 ccw[CAROM_MAX_POLYGON_VERTICES], center;
        int n = def->vertex_count, j;
        carom_status st = cr_polygon_check(def->vertices, n, ccw);
        if (st != CAROM_OK)
            return st;
        cr_polygon_mass(ccw, n, area, &center, unit_inertia);
        if (!cr_finite(*area) || !cr_gt(*area, 0.0f) ||
            !cr_finite(*unit_inertia) || !cr_gt(*unit_inertia, 0.0f) ||
            !cr_vec_finite(center))
            return CAROM_ERR_DEGENERATE_POLYGON;
        s->count = n;
        s->local_center = center;
        s->extent = 0.0f;
        for (i = 0; i < n; ++i) {
            s->verts[i] = cr_vsub(ccw[i], center);
            s->extent = cr_max(s->extent, cr_vlen(s->verts[i]));
        }
        for (i = 0; i < n; ++i) {
            cr_v2 e = cr_vsub(s->verts[(i + 1) % n], s->verts[i]);
            float len = cr_vlen(e);
            s->norms[i] = cr_v(cr_div(e.y, len), cr_div(cr_neg(e.x), len));
        }
        /* the smallest width: across each edge, to the farthest vertex */
        s->half_width = s->extent;
        for (i = 0; i < n; ++i) {
            float depth = 0.0f;
            for (j = 0; j < n; ++j)
                depth = cr_min(depth, cr_vdot(s->norms[i],
                                              cr_vsub(s->verts[j], s->verts[i])));
            s->half_width = cr_min(s->half_width, cr_mul(-0.5f, depth));
        }
        if (!cr_ge(s->half_width, CAROM_LIMIT_MIN_SIZE))
            return CAROM_ERR_DEGENERATE_POLYGON;
        return CAROM_OK;
    }
#else
    return CAROM_ERR_DISABLED;
#endif
}

/*
 * Validate `def` completely and build the body. Nothing is written unless
 * everything is valid, so a failed add leaves the world untouched.
 */
carom_status cr_body_build(const carom_body_def *def, cr_body *hot,
                           cr_body_info *info)
{
    cr_body b;
    cr_body_info in;
    float area = 0.0f, unit_inertia = 0.0f, qlen;
    carom_status st;

    if (!def || !hot || !info)
        return CAROM_ERR_NULL;
    if (def->type != CAROM_BODY_DYNAMIC && def->type != CAROM_BODY_STATIC &&
        def->type != CAROM_BODY_KINEMATIC)
        return CAROM_ERR_BAD_BODY_TYPE;
#if !CAROM_ENABLE_KINEMATIC
    if (def->type == CAROM_BODY_KINEMATIC)
        return CAROM_ERR_DISABLED;
#endif
    if (def->shape != CAROM_SHAPE_CIRCLE && def->shape != CAROM_SHAPE_POLYGON)
        return CAROM_ERR_BAD_SHAPE;
#if CAROM_ENABLE_POLYGONS && !CAROM_ENABLE_DYNAMIC_POLYGONS
    if (def->shape == CAROM_SHAPE_POLYGON && def->type != CAROM_BODY_STATIC)
        return CAROM_ERR_DISABLED;
#endif
    if (!cr_vec_finite(def->position) || !cr_vec_finite(def->velocity) ||
        !cr_finite(def->rotation.c) || !cr_finite(def->rotation.s) ||
        !cr_finite(def->angular_velocity) || !cr_finite(def->density) ||
        !cr_finite(def->mass) || !cr_finite(def->restitution) ||
        !cr_finite(def->friction) || !cr_vec_finite(def->force) ||
        !cr_finite(def->torque) || !cr_finite(def->radius))
        return CAROM_ERR_NOT_FINITE;
    if (!cr_le(0.0f, def->restitution) || !cr_le(def->restitution, 1.0f))
        return CAROM_ERR_BAD_RESTITUTION;
    if (cr_lt(def->friction, 0.0f) || cr_gt(def->friction, CAROM_LIMIT_MAX_FRICTION))
        return CAROM_ERR_BAD_FRICTION;
    if (cr_lt(def->mass, 0.0f))
        return CAROM_ERR_BAD_MASS;
    /* a mass given overrides the density, which is then not read (a
     * review found density 0 with mass 2 refused, against the header) */
    if (!cr_gt(def->mass, 0.0f) && !cr_gt(def->density, 0.0f))
        return CAROM_ERR_BAD_DENSITY;
    qlen = cr_add(cr_mul(def->rotation.c, def->rotation.c),
                  cr_mul(def->rotation.s, def->rotation.s));
    if (cr_lt(qlen, CR_ROT_MIN_LEN2) || !cr_finite(qlen))
        return CAROM_ERR_BAD_ROTATION;
    if (!cr_v2_within(def->position, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
#if !CAROM_ENABLE_FORCES
    if (!cr_eq(def->force.x, 0.0f) || !cr_eq(def->force.y, 0.0f) ||
        !cr_eq(def->torque, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
#if !CAROM_ENABLE_ROTATION
    if (!cr_eq(def->angular_velocity, 0.0f))
        return CAROM_ERR_DISABLED;
#endif
#if !CAROM_ENABLE_SENSORS
    if (def->is_sensor)
        return CAROM_ERR_DISABLED;
#endif
#if !CAROM_ENABLE_FILTERING
    if (def->category_bits != 1u || def->mask_bits != 0xffffffffu || def->group_index != 0)
        return CAROM_ERR_DISABLED;
#endif

    st = cr_shape_build(def, &in.shape, &area, &unit_inertia);
    if (st != CAROM_OK)
        return st;
    in.shape.size = cr_sqrt(cr_div(area, CR_PI));
    if (def->type != CAROM_BODY_STATIC &&
        (!cr_v2_within(def->velocity, CAROM_LIMIT_MAX_SPEED) ||
         cr_gt(cr_mul(cr_abs(def->angular_velocity), in.shape.extent),
               CAROM_LIMIT_MAX_SPEED)))
        return CAROM_ERR_OUT_OF_RANGE;

    b.q = cr_rot_normalize(def->rotation);
    b.x = cr_vadd(def->position, cr_rotate(b.q, in.shape.local_center));
    if (!cr_v2_within(b.x, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
    b.v = def->velocity;
    b.w = def->angular_velocity;
    b.a = cr_v(0.0f, 0.0f);
    b.alpha = 0.0f;
#if CAROM_ENABLE_COMPENSATED
    b.xc = cr_v(0.0f, 0.0f);
    b.vc = cr_v(0.0f, 0.0f);
    b.wc = 0.0f;
#endif
    b.inv_m = 0.0f;
    b.inv_I = 0.0f;
    b.still_time = 0.0f;
    b.type = (unsigned short)def->type;
    b.flags = CR_BODY_ALIVE | CR_BODY_AWAKE;
    if (def->is_sensor)
        b.flags |= CR_BODY_SENSOR;
    if (in.shape.kind == CAROM_SHAPE_CIRCLE)
        b.flags |= CR_BODY_CIRCLE;
    if (def->category_bits != 1u || def->mask_bits != 0xffffffffu || def->group_index != 0)
        b.flags |= CR_BODY_FILTERED;
    in.category = def->category_bits;
    in.mask = def->mask_bits;
    in.group = def->group_index;
    in.user_data = def->user_data;
    in.force_once = cr_v(0.0f, 0.0f);
    in.torque_once = 0.0f;
    in.restitution = def->restitution;
    in.friction = def->friction;
    in.force = def->force;
    in.torque = def->torque;
    in.generation = 0u;
    in.sleep_x = b.x;
    in.sleep_q = b.q;
    in.sleep_window = 0.0f;
    in.sleep_travel = 0.0f;
    in.sleep_away = 0.0f;
    in.still_speed = 0.0f;
    in.still_max = 0.0f;
    b.sleep_island = -1;
    in.m = 0.0f;
    in.I = 0.0f;

    if (def->type == CAROM_BODY_DYNAMIC) {
        float density = def->density;
        if (cr_gt(def->mass, 0.0f))
            density = cr_div(def->mass, area);
        in.m = cr_gt(def->mass, 0.0f) ? def->mass : cr_mul(density, area);
        in.I = cr_mul(density, unit_inertia);
        if (!cr_ge(in.m, CAROM_LIMIT_MIN_MASS) || !cr_le(in.m, CAROM_LIMIT_MAX_MASS) ||
            !cr_ge(in.I, CAROM_LIMIT_MIN_MASS) || !cr_le(in.I, CAROM_LIMIT_MAX_MASS))
            return CAROM_ERR_BAD_MASS;
        b.inv_m = cr_div(1.0f, in.m);
#if CAROM_ENABLE_ROTATION
        b.inv_I = cr_div(1.0f, in.I);
#endif
#if CAROM_ENABLE_FORCES /* (without, force and torque are 0: checked above) */
        if (!cr_accel_in_range(&in, def->force, def->torque))
            return CAROM_ERR_OUT_OF_RANGE;
#endif
    } else if (def->type == CAROM_BODY_STATIC) {
        b.v = cr_v(0.0f, 0.0f);
        b.w = 0.0f;
    }
    *hot = b;
    *info = in;
    return CAROM_OK;
}

cr_v2 cr_body_origin(const cr_body *b, const cr_body_info *info)
{
    return cr_vsub(b->x, cr_rotate(b->q, info->shape.local_center));
}

void cr_shape_box(const cr_shape *s, cr_v2 x, cr_rot q, cr_box *out)
{
    if (s->kind == CAROM_SHAPE_CIRCLE) {
        out->lo_x = cr_sub(x.x, s->radius);
        out->hi_x = cr_add(x.x, s->radius);
        out->lo_y = cr_sub(x.y, s->radius);
        out->hi_y = cr_add(x.y, s->radius);
    } else {
#if CAROM_ENABLE_POLYGONS
        int i;
        cr_v2 p = cr_vadd(x, cr_rotate(q, s->verts[0]));
        out->lo_x = out->hi_x = p.x;
        out->lo_y = out->hi_y = p.y;
        for (i = 1; i < s->count; ++i) {
            p = cr_vadd(x, cr_rotate(q, s->verts[i]));
            out->lo_x = cr_min(out->lo_x, p.x);
            out->hi_x = cr_max(out->hi_x, p.x);
            out->lo_y = cr_min(out->lo_y, p.y);
            out->hi_y = cr_max(out->hi_y, p.y);
        }
#else
        (void)q; /* (every shape is a circle) */
#endif
    }
}
