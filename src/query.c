/*
 * query.c -- questions a program asks the world between steps: which
 * bodies overlap a box, contain a point, or lie along a ray. Each answer is
 * exact against the shapes; candidates come from the broadphase grid of
 * the last step, whose boxes hold every body's motion over that step (so
 * its end pose too), or from every body when the program has added,
 * removed or moved bodies since (w->grid_valid).
 */
#include "world.h"

#if CAROM_ENABLE_QUERIES

/* World vertex i and outward normal i of polygon body slot s. */
#if CAROM_ENABLE_POLYGONS
static cr_v2 cr_vertex(const cr_body *b, const cr_shape *sh, int i)
{
    return cr_vadd(b->x, cr_rotate(b->q, sh->verts[i]));
}

static cr_v2 cr_normal(const cr_body *b, const cr_shape *sh, int i)
{
    return cr_rotate(b->q, sh->norms[i]);
}
#else
/* (no polygons: never called; the shape has no vertices) */
static cr_v2 cr_vertex(const cr_body *b, const cr_shape *sh, int i)
{
    (void)sh;
    (void)i;
    return b->x;
}

static cr_v2 cr_normal(const cr_body *b, const cr_shape *sh, int i)
{
    (void)b;
    (void)sh;
    (void)i;
    return cr_v(1.0f, 0.0f);
}
#endif

typedef struct cr_grid_visit {
    const carom_world *w;
    cr_query_fn fn;
    void *ctx;
} cr_grid_visit;

/* The grid's answer, but for the bodies that left their grid box. */
static int cr_unless_escaped(void *ctx, int s)
{
    const cr_grid_visit *g = (const cr_grid_visit *)ctx;
    return (g->w->bodies[s].flags & CR_BODY_ESCAPED) ? 1 : g->fn(g->ctx, s);
}

/* Calls fn for each body whose box may overlap q: from the grid (and the
 * few bodies the last step pushed out of their grid box), or from every
 * body. */
static int cr_candidates(const carom_world *w, const cr_box *q, cr_query_fn fn, void *ctx)
{
    int i;
    if (w->grid_valid && w->escaped_count == 0)
        return cr_broadphase_query(&w->bp, w->boxes, q, fn, ctx);
    if (w->grid_valid) {
        cr_grid_visit g;
        g.w = w;
        g.fn = fn;
        g.ctx = ctx;
        if (!cr_broadphase_query(&w->bp, w->boxes, q, cr_unless_escaped, &g))
            return 0;
        for (i = 0; i < w->escaped_count; ++i) {
            int s = w->regrown[i];
            cr_box b;
            cr_shape_box(&w->info[s].shape, w->bodies[s].x, w->bodies[s].q, &b);
            if (cr_boxes_overlap(q, &b) && !fn(ctx, s))
                return 0;
        }
        return 1;
    }
    for (i = 0; i < w->slot_count; ++i) {
        cr_box b;
        if (!(w->bodies[i].flags & CR_BODY_ALIVE))
            continue;
        cr_shape_box(&w->info[i].shape, w->bodies[i].x, w->bodies[i].q, &b);
        if (cr_boxes_overlap(q, &b) && !fn(ctx, i))
            return 0;
    }
    return 1;
}

static int cr_valid_box(carom_vec2 lo, carom_vec2 hi)
{
    return cr_finite(lo.x) && cr_finite(lo.y) && cr_finite(hi.x) && cr_finite(hi.y);
}

/* ---- box ------------------------------------------------------------------ */

typedef struct cr_box_query {
    const carom_world *w;
    cr_box q;
    carom_query_fn fn;
    void *ctx;
} cr_box_query;

static int cr_shape_overlaps_box(const carom_world *w, int s, const cr_box *q)
{
    const cr_body *b = &w->bodies[s];
    const cr_shape *sh = &w->info[s].shape;
    int i, k;
    if (sh->kind == CAROM_SHAPE_CIRCLE) {
        cr_v2 c = cr_v(cr_clamp(b->x.x, q->lo_x, q->hi_x), cr_clamp(b->x.y, q->lo_y, q->hi_y));
        cr_v2 d = cr_vsub(b->x, c);
        return cr_le(cr_vdot(d, d), cr_mul(sh->radius, sh->radius));
    }
    {
        cr_box pb;
        cr_shape_box(sh, b->x, b->q, &pb);
        if (!cr_boxes_overlap(&pb, q))
            return 0;
    }
    /* separated along an edge normal if every box corner is outside it */
    for (i = 0; i < sh->count; ++i) {
        cr_v2 v = cr_vertex(b, sh, i), n = cr_normal(b, sh, i);
        float least = 0.0f;
        for (k = 0; k < 4; ++k) {
            cr_v2 c = cr_v((k & 1) ? q->hi_x : q->lo_x, (k & 2) ? q->hi_y : q->lo_y);
            float d = cr_vdot(n, cr_vsub(c, v));
            least = k == 0 ? d : cr_min(least, d);
        }
        if (cr_gt(least, 0.0f))
            return 0;
    }
    return 1;
}

static int cr_box_visit(void *ctx, int s)
{
    cr_box_query *c = (cr_box_query *)ctx;
    if (!cr_shape_overlaps_box(c->w, s, &c->q))
        return 1;
    return c->fn(c->ctx, cr_body_id(c->w, s));
}

carom_status carom_world_query_box(const carom_world *w, carom_vec2 lo, carom_vec2 hi,
                                   carom_query_fn fn, void *ctx)
{
    cr_box_query c;
    if (!w || !fn)
        return CAROM_ERR_NULL;
    if (!cr_valid_box(lo, hi))
        return CAROM_ERR_NOT_FINITE;
    c.w = w;
    c.q.lo_x = cr_min(lo.x, hi.x);
    c.q.lo_y = cr_min(lo.y, hi.y);
    c.q.hi_x = cr_max(lo.x, hi.x);
    c.q.hi_y = cr_max(lo.y, hi.y);
    c.fn = fn;
    c.ctx = ctx;
    cr_candidates(w, &c.q, cr_box_visit, &c);
    return CAROM_OK;
}

/* ---- point ------------------------------------------------------------------ */

typedef struct cr_point_query {
    const carom_world *w;
    cr_v2 p;
    carom_query_fn fn;
    void *ctx;
} cr_point_query;

static int cr_shape_contains(const carom_world *w, int s, cr_v2 p)
{
    const cr_body *b = &w->bodies[s];
    const cr_shape *sh = &w->info[s].shape;
    int i;
    if (sh->kind == CAROM_SHAPE_CIRCLE) {
        cr_v2 d = cr_vsub(p, b->x);
        return cr_le(cr_vdot(d, d), cr_mul(sh->radius, sh->radius));
    }
    for (i = 0; i < sh->count; ++i)
        if (cr_gt(cr_vdot(cr_normal(b, sh, i), cr_vsub(p, cr_vertex(b, sh, i))), 0.0f))
            return 0;
    return 1;
}

static int cr_point_visit(void *ctx, int s)
{
    cr_point_query *c = (cr_point_query *)ctx;
    if (!cr_shape_contains(c->w, s, c->p))
        return 1;
    return c->fn(c->ctx, cr_body_id(c->w, s));
}

carom_status carom_world_query_point(const carom_world *w, carom_vec2 p, carom_query_fn fn,
                                     void *ctx)
{
    cr_point_query c;
    cr_box q;
    if (!w || !fn)
        return CAROM_ERR_NULL;
    if (!cr_finite(p.x) || !cr_finite(p.y))
        return CAROM_ERR_NOT_FINITE;
    c.w = w;
    c.p = p;
    c.fn = fn;
    c.ctx = ctx;
    q.lo_x = q.hi_x = p.x;
    q.lo_y = q.hi_y = p.y;
    cr_candidates(w, &q, cr_point_visit, &c);
    return CAROM_OK;
}

/* ---- rays ----------------------------------------------------------------------- */

/* Where the segment p0 + t d, t in [0, 1], enters body s's shape. */
static int cr_ray_shape(const carom_world *w, int s, cr_v2 p0, cr_v2 d, float *t_out,
                        cr_v2 *n_out)
{
    const cr_body *b = &w->bodies[s];
    const cr_shape *sh = &w->info[s].shape;
    if (sh->kind == CAROM_SHAPE_CIRCLE) {
        /* From the closest approach m of the line to the centre, not from
         * b^2 - a c, which cancels when the ray is long against the
         * radius; the normal is the centre-to-hit vector m - h u, made
         * unit. */
        cr_v2 f = cr_vsub(p0, b->x), m, u, n;
        float a = cr_vdot(d, d), r2 = cr_mul(sh->radius, sh->radius);
        float len, tc, h, nn;
        if (cr_lt(a, CR_ROT_MIN_LEN2) || cr_lt(cr_vdot(f, f), r2))
            return 0; /* no length (|d|^2 zero or subnormal: d / |d| would
                         not be a unit vector), or starting inside */
        len = cr_sqrt(a);
        u = cr_vscale(cr_div(1.0f, len), d);
        tc = cr_neg(cr_vdot(f, u)); /* distance along u to the closest approach */
        m = cr_vadd(f, cr_vscale(tc, u));
        h = cr_sub(r2, cr_vdot(m, m)); /* squared half chord */
        if (cr_lt(h, 0.0f))
            return 0;
        h = cr_sqrt(h);
        *t_out = cr_div(cr_sub(tc, h), len);
        if (cr_lt(*t_out, 0.0f) || cr_gt(*t_out, 1.0f))
            return 0;
        n = cr_vsub(m, cr_vscale(h, u));
        nn = cr_vlen(n);
        if (!cr_gt(nn, 0.0f))
            return 0;
        *n_out = cr_vscale(cr_div(1.0f, nn), n);
        return 1;
    }
    {
        /* clip the segment by each edge's half-plane (Cyrus-Beck) */
        float lower = 0.0f, upper = 1.0f;
        int i, index = -1;
        for (i = 0; i < sh->count; ++i) {
            cr_v2 n = cr_normal(b, sh, i);
            float num = cr_vdot(n, cr_vsub(cr_vertex(b, sh, i), p0));
            float den = cr_vdot(n, d);
            if (cr_eq(den, 0.0f)) {
                if (cr_lt(num, 0.0f))
                    return 0; /* parallel, outside this edge */
            } else if (cr_lt(den, 0.0f) && cr_lt(num, cr_mul(lower, den))) {
                lower = cr_div(num, den); /* entering */
                index = i;
            } else if (cr_gt(den, 0.0f) && cr_lt(num, cr_mul(upper, den))) {
                upper = cr_div(num, den); /* leaving */
            }
            if (cr_lt(upper, lower))
                return 0;
        }
        if (index < 0)
            return 0; /* starting inside */
        *t_out = lower;
        *n_out = cr_normal(b, sh, index);
        return 1;
    }
}

typedef struct cr_ray_query {
    const carom_world *w;
    cr_v2 p0, d;
    carom_ray_hit *hits;
    int cap, count, all;
} cr_ray_query;

static int cr_ray_earlier(const carom_ray_hit *x, const carom_ray_hit *y)
{
    return cr_lt(x->fraction, y->fraction) ||
           (cr_eq(x->fraction, y->fraction) && x->body < y->body);
}

static int cr_ray_visit(void *ctx, int s)
{
    cr_ray_query *c = (cr_ray_query *)ctx;
    carom_ray_hit h;
    float t;
    cr_v2 n;
    int i;
    if (!cr_ray_shape(c->w, s, c->p0, c->d, &t, &n))
        return 1;
    h.body = cr_body_id(c->w, s);
    h.fraction = t;
    h.point = cr_vadd(c->p0, cr_vscale(t, c->d));
    h.normal = n;
    if (!c->all) {
        /* the closest only */
        if (c->count == 0 || cr_ray_earlier(&h, &c->hits[0]))
            c->hits[0] = h;
        c->count = 1;
        return 1;
    }
    /* the nearest cap hits, in order; every hit counted */
    i = c->count < c->cap ? c->count : c->cap;
    ++c->count;
    if (i == c->cap && (c->cap == 0 || !cr_ray_earlier(&h, &c->hits[c->cap - 1])))
        return 1;
    if (i == c->cap)
        --i;
    while (i > 0 && cr_ray_earlier(&h, &c->hits[i - 1])) {
        c->hits[i] = c->hits[i - 1];
        --i;
    }
    c->hits[i] = h;
    return 1;
}

static carom_status cr_raycast(const carom_world *w, carom_vec2 from, carom_vec2 to,
                               carom_ray_hit *hits, int cap, int all, int *count)
{
    cr_ray_query c;
    cr_box q;
    if (!cr_valid_box(from, to))
        return CAROM_ERR_NOT_FINITE;
    /* |to - from|^2 must stay finite (a hit's fields are then finite) */
    if (!cr_v2_within(from, CAROM_LIMIT_MAX_LENGTH) || !cr_v2_within(to, CAROM_LIMIT_MAX_LENGTH))
        return CAROM_ERR_OUT_OF_RANGE;
    c.w = w;
    c.p0 = from;
    c.d = cr_vsub(to, from);
    c.hits = hits;
    c.cap = cap;
    c.count = 0;
    c.all = all;
    q.lo_x = cr_min(from.x, to.x);
    q.lo_y = cr_min(from.y, to.y);
    q.hi_x = cr_max(from.x, to.x);
    q.hi_y = cr_max(from.y, to.y);
    cr_candidates(w, &q, cr_ray_visit, &c);
    *count = c.count;
    return CAROM_OK;
}

carom_status carom_world_raycast(const carom_world *w, carom_vec2 from, carom_vec2 to,
                                 carom_ray_hit *hit, int *found)
{
    if (!w || !hit || !found)
        return CAROM_ERR_NULL;
    return cr_raycast(w, from, to, hit, 1, 0, found);
}

carom_status carom_world_raycast_all(const carom_world *w, carom_vec2 from, carom_vec2 to,
                                     carom_ray_hit *hits, int cap, int *count)
{
    if (!w || !count || (!hits && cap > 0))
        return CAROM_ERR_NULL;
    if (cap < 0)
        return CAROM_ERR_BAD_CAPACITY;
    return cr_raycast(w, from, to, hits, cap, 1, count);
}

#else /* !CAROM_ENABLE_QUERIES */

carom_status carom_world_query_box(const carom_world *w, carom_vec2 lo, carom_vec2 hi,
                                   carom_query_fn fn, void *ctx)
{
    (void)w; (void)lo; (void)hi; (void)fn; (void)ctx;
    return CAROM_ERR_DISABLED;
}

carom_status carom_world_query_point(const carom_world *w, carom_vec2 p, carom_query_fn fn,
                                     void *ctx)
{
    (void)w; (void)p; (void)fn; (void)ctx;
    return CAROM_ERR_DISABLED;
}

carom_status carom_world_raycast(const carom_world *w, carom_vec2 from, carom_vec2 to,
                                 carom_ray_hit *hit, int *found)
{
    (void)w; (void)from; (void)to; (void)hit;
    if (found)
        *found = 0;
    return CAROM_ERR_DISABLED;
}

carom_status carom_world_raycast_all(const carom_world *w, carom_vec2 from, carom_vec2 to,
                                     carom_ray_hit *hits, int cap, int *count)
{
    (void)w; (void)from; (void)to; (void)hits; (void)cap;
    if (count)
        *count = 0;
    return CAROM_ERR_DISABLED;
}

#endif /* CAROM_ENABLE_QUERIES */
