/*
 * test_narrowphase.c -- manifolds of each shape pair against geometry
 * worked out by hand: normal (from body a to body b), separation, points.
 */
#include "test_util.h"

#include "narrowphase.h"

/* A shape at a pose. */
typedef struct tshape {
    cr_body b;
    cr_body_info info;
} tshape;

static tshape make_circle(float x, float y, float r)
{
    carom_body_def bd = carom_default_body_def();
    tshape t;
    bd.radius = r;
    bd.position.x = x;
    bd.position.y = y;
    ck_assert_int_eq(cr_body_build(&bd, &t.b, &t.info), CAROM_OK);
    return t;
}

static tshape make_box(float x, float y, float hx, float hy, float angle)
{
    carom_body_def bd = carom_default_body_def();
    tshape t;
    carom_body_def_set_box(&bd, hx, hy);
    bd.position.x = x;
    bd.position.y = y;
    bd.rotation = carom_rot_from_angle(angle);
    ck_assert_int_eq(cr_body_build(&bd, &t.b, &t.info), CAROM_OK);
    return t;
}

/* The manifold of a and b with reach `margin`; no face tolerance. */
static int collide(const tshape *a, const tshape *b, float margin, cr_manifold *m)
{
    return cr_collide(&a->info.shape, a->b.x, a->b.q, &b->info.shape, b->b.x,
                      b->b.q, margin, 0.0f, 0.0f, m) > 0;
}

START_TEST(test_circle_circle_overlap_normal_and_midpoint)
{
    tshape a = make_circle(0, 0, 1), b = make_circle(3, 4, 4.5f);
    cr_manifold m;
    ck_assert_int_eq(collide(&a, &b, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 1);
    ck_assert_close(m.n.x, 0.6, 1e-6);
    ck_assert_close(m.n.y, 0.8, 1e-6);
    ck_assert_close(m.pts[0].sep, 5.0 - 5.5, 1e-6);
    /* surfaces at 1 * n and (5 - 4.5) * n: midpoint at 0.75 n */
    ck_assert_close(m.pts[0].p.x, 0.75 * 0.6, 1e-6);
    ck_assert_close(m.pts[0].p.y, 0.75 * 0.8, 1e-6);
}
END_TEST

START_TEST(test_circle_circle_apart_beyond_margin_is_no_contact)
{
    tshape a = make_circle(0, 0, 1), b = make_circle(2.1f, 0, 1);
    cr_manifold m;
    ck_assert_int_eq(collide(&a, &b, 0.05f, &m), 0);
    ck_assert_int_eq(collide(&a, &b, 0.2f, &m), 1);
    ck_assert_close(m.pts[0].sep, 0.1, 1e-6);
}
END_TEST

START_TEST(test_box_circle_face_region)
{
    tshape box = make_box(0, 0, 1, 1, 0), c = make_circle(0.3f, 1.4f, 0.5f);
    cr_manifold m;
    ck_assert_int_eq(collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 0.0, 1e-6);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.1, 1e-6);
    ck_assert_close(m.pts[0].p.x, 0.3, 1e-6);
    ck_assert_close(m.pts[0].p.y, 0.95, 1e-6);
}
END_TEST

START_TEST(test_box_circle_vertex_region)
{
    /* corner (1, 1); centre at (1.3, 1.4): distance 0.5 along (0.6, 0.8) */
    tshape box = make_box(0, 0, 1, 1, 0), c = make_circle(1.3f, 1.4f, 0.45f);
    cr_manifold m;
    ck_assert_int_eq(collide(&box, &c, 0.0f, &m), 0); /* gap 0.05 */
    c = make_circle(1.3f, 1.4f, 0.55f);
    ck_assert_int_eq(collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 0.6, 1e-6);
    ck_assert_close(m.n.y, 0.8, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.05, 1e-6);
}
END_TEST

START_TEST(test_circle_box_order_reverses_the_normal)
{
    tshape box = make_box(0, 0, 1, 1, 0), c = make_circle(0.3f, 1.4f, 0.5f);
    cr_manifold m;
    ck_assert_int_eq(collide(&c, &box, 0.0f, &m), 1);
    ck_assert_close(m.n.y, -1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.1, 1e-6);
}
END_TEST

START_TEST(test_circle_centre_inside_box_pushes_out_of_nearest_face)
{
    tshape box = make_box(0, 0, 2, 1, 0), c = make_circle(1.8f, 0.1f, 0.1f);
    cr_manifold m;
    ck_assert_int_eq(collide(&box, &c, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.2 - 0.1, 1e-6);
}
END_TEST

START_TEST(test_box_on_box_gives_two_points_on_the_face)
{
    tshape ground = make_box(0, 0, 2, 0.5f, 0), top = make_box(0.3f, 0.9f, 0.5f, 0.5f, 0);
    cr_manifold m;
    int i;
    ck_assert_int_eq(collide(&ground, &top, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 2);
    ck_assert_close(m.n.x, 0.0, 1e-6);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    for (i = 0; i < 2; ++i) {
        ck_assert_close(m.pts[i].sep, -0.1, 1e-6);
        ck_assert_close(m.pts[i].p.y, 0.45, 1e-6);
        ck_assert_close(fabs(m.pts[i].p.x - 0.3), 0.5, 1e-6);
    }
    ck_assert_uint_ne(m.pts[0].id, m.pts[1].id);
}
END_TEST

START_TEST(test_tilted_box_corner_gives_one_point)
{
    /* square of half side 0.5 at 45 deg: corner 0.7071 below its centre */
    tshape ground = make_box(0, 0, 2, 0.5f, 0);
    tshape top = make_box(0, 0.5f + 0.70710678f - 0.02f, 0.5f, 0.5f, 0.78539816f);
    cr_manifold m;
    ck_assert_int_eq(collide(&ground, &top, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 1);
    ck_assert_close(m.n.y, 1.0, 1e-6);
    ck_assert_close(m.pts[0].sep, -0.02, 1e-5);
    ck_assert_close(m.pts[0].p.x, 0.0, 1e-5);
}
END_TEST

START_TEST(test_separated_polygons_are_no_contact)
{
    tshape a = make_box(0, 0, 1, 1, 0), b = make_box(2.5f, 0, 1, 1, 0.3f);
    cr_manifold m;
    ck_assert_int_eq(collide(&a, &b, 0.0f, &m), 0);
}
END_TEST

START_TEST(test_box_box_side_by_side_normal_points_from_a_to_b)
{
    tshape a = make_box(0, 0, 1, 1, 0), b = make_box(1.95f, 0.2f, 1, 1, 0);
    cr_manifold m;
    ck_assert_int_eq(collide(&a, &b, 0.0f, &m), 1);
    ck_assert_close(m.n.x, 1.0, 1e-6);
    ck_assert_int_eq(m.count, 2);
    ck_assert_close(m.pts[0].sep, -0.05, 1e-5);
    ck_assert_int_eq(collide(&b, &a, 0.0f, &m), 1);
    ck_assert_close(m.n.x, -1.0, 1e-6);
}
END_TEST

/* The manifold depends on the relative pose only: the same stacked pair at
 * x = 0 and x = 7.77 gives the same normal, separations and ids (to the
 * rounding of the relative position), so a stack placed anywhere behaves
 * the same. */
START_TEST(test_manifold_does_not_depend_on_where_the_pair_sits)
{
    const float xs[3] = {0.0f, 1.85f, 7.77f};
    cr_manifold ref, m;
    int i, k;
    for (i = 0; i < 3; ++i) {
        tshape low = make_box(xs[i], 0.5f, 0.5f, 0.5f, 0);
        tshape up = make_box(xs[i], 1.5f, 0.5f, 0.5f, 0);
        ck_assert(collide(&low, &up, 0.01f, &m));
        ck_assert_int_eq(m.count, 2);
        if (i == 0) {
            ref = m;
            continue;
        }
        ck_assert(m.n.x == ref.n.x && m.n.y == ref.n.y);
        for (k = 0; k < 2; ++k) {
            ck_assert_uint_eq(m.pts[k].id, ref.pts[k].id);
            ck_assert_close(m.pts[k].sep, ref.pts[k].sep, 1e-6);
            ck_assert_close(m.pts[k].p.x - xs[i], ref.pts[k].p.x, 1e-6);
        }
    }
}
END_TEST

/* Exactly aligned equal faces: both SAT separations are equal, and the
 * reference face is A's in both orders, so the feature ids read the same
 * (feature of a, feature of b) whichever body is first. */
START_TEST(test_aligned_faces_keep_the_first_body_as_reference)
{
    tshape low = make_box(3.7f, 0.5f, 0.5f, 0.5f, 0);
    tshape up = make_box(3.7f, 1.5f, 0.5f, 0.5f, 0);
    cr_manifold m1, m2;
    ck_assert(collide(&low, &up, 0.01f, &m1));
    ck_assert(collide(&up, &low, 0.01f, &m2));
    ck_assert_int_eq(m1.count, 2);
    ck_assert_int_eq(m2.count, 2);
    ck_assert(m1.n.y == 1.0f && m2.n.y == -1.0f);
    /* ids of m2 are (feature of up, feature of low): byte-swapped m1 ids */
    ck_assert(((m1.pts[0].id >> 8) | ((m1.pts[0].id & 0xffu) << 8)) == m2.pts[0].id ||
              ((m1.pts[0].id >> 8) | ((m1.pts[0].id & 0xffu) << 8)) == m2.pts[1].id);
}
END_TEST

/* A small box's face inside a larger box's face: the incident face is cut
 * by the reference face's side planes, and the two points must be mirror
 * images of each other to the last bit (a head-on face impact must give no
 * spin from rounding: the pi billiard with boxes depends on it). */
START_TEST(test_clipped_points_of_a_symmetric_pair_are_exact_mirrors)
{
    tshape small = make_box(40.05f, 0, 0.05f, 0.05f, 0);
    tshape big = make_box(40.2f, 0, 0.1f, 0.1f, 0);
    cr_manifold m;
    ck_assert(collide(&small, &big, 0.01f, &m));
    ck_assert_int_eq(m.count, 2);
    ck_assert(m.n.x == 1.0f && m.n.y == 0.0f);
    ck_assert(m.pts[0].p.y == -m.pts[1].p.y);
    ck_assert(m.pts[0].p.x == m.pts[1].p.x);
    ck_assert(m.pts[0].sep == m.pts[1].sep);
    /* and the body's centre is exactly its box centre */
    ck_assert(small.b.x.y == 0.0f && small.info.shape.local_center.y == 0.0f);
}
END_TEST

/* Speculative points: polygons apart by less than the reach give a
 * manifold with positive separations (the solver stops them exactly where
 * they meet); beyond the reach, none. */
START_TEST(test_polygons_within_reach_give_speculative_points)
{
    tshape low = make_box(0, 0, 1, 0.5f, 0), up = make_box(0.2f, 1.05f, 0.5f, 0.5f, 0);
    cr_manifold m;
    ck_assert(!collide(&low, &up, 0.01f, &m)); /* gap 0.05 */
    ck_assert(collide(&low, &up, 0.1f, &m));
    ck_assert_int_eq(m.count, 2);
    ck_assert_close(m.pts[0].sep, 0.05, 1e-6);
    ck_assert_close(m.pts[1].sep, 0.05, 1e-6);
}
END_TEST

/* The separation bound for conservative advancement: exact for pairs with
 * a circle, the SAT separation (never more than the distance) for two
 * polygons. */
START_TEST(test_separation_is_a_lower_bound_of_the_distance)
{
    tshape a = make_circle(0, 0, 0.5f), b = make_circle(3, 4, 1);
    tshape box = make_box(0, 0, 1, 1, 0), far = make_box(3, 3, 0.5f, 0.5f, 0);
    ck_assert_close(cr_separation(&a.info.shape, a.b.x, a.b.q, &b.info.shape, b.b.x, b.b.q),
                    5.0 - 1.5, 1e-6);
    /* corners (1, 1) and (2.5, 2.5): distance 1.5 sqrt 2 = 2.12; the SAT
     * separation along the faces is 1.5 */
    ck_assert_close(cr_separation(&box.info.shape, box.b.x, box.b.q, &far.info.shape,
                                  far.b.x, far.b.q),
                    1.5, 1e-6);
}
END_TEST

/* Concentric circles: every direction separates them equally, so the
 * normal is any unit vector; the depth is the sum of the radii. */
START_TEST(test_concentric_circles_have_a_unit_normal_and_full_depth)
{
    tshape a = make_circle(2, -1, 0.75f), b = make_circle(2, -1, 0.5f);
    cr_manifold m;
    ck_assert_int_eq(collide(&a, &b, 0.0f, &m), 1);
    ck_assert_int_eq(m.count, 1);
    ck_assert_close(hypot(m.n.x, m.n.y), 1.0, 1e-7);
    ck_assert_close(m.pts[0].sep, -1.25, 1e-7);
    /* the point lies on the common centres' normal line, within a */
    ck_assert(hypot(m.pts[0].p.x - 2.0, m.pts[0].p.y + 1.0) <= 0.75 + 1e-6);
}
END_TEST

/* Centres apart by less than sqrt(FLT_MIN) ~ 1.1e-19: the squared distance
 * is subnormal (or zero), so p / sqrt(|p|^2) is not of unit length (up to
 * 1.017 long before this was guarded; found by fuzz_scene_run). The normal
 * must still be a unit vector, the depth the sum of the radii to float
 * precision. Each offset is checked in x and in y, in both orders. */
START_TEST(test_nearly_concentric_circles_have_a_unit_normal)
{
    static const float offsets[] = {8.50962e-23f, 1e-20f, 1.0e-30f, 1e-38f,
                                    1e-45f, -8.50962e-23f};
    size_t i;
    int axis, order;
    for (i = 0; i < sizeof offsets / sizeof offsets[0]; ++i)
        for (axis = 0; axis < 2; ++axis)
            for (order = 0; order < 2; ++order) {
                float dx = axis == 0 ? offsets[i] : 0.0f;
                float dy = axis == 1 ? offsets[i] : 0.0f;
                tshape a = make_circle(0, 0, 0.5f);
                tshape b = make_circle(dx, dy, 0.5f);
                cr_manifold m;
                ck_assert_int_eq(order ? collide(&b, &a, 0.0f, &m)
                                       : collide(&a, &b, 0.0f, &m), 1);
                ck_assert_close(hypot(m.n.x, m.n.y), 1.0, 1e-7);
                ck_assert_close(m.pts[0].sep, -1.0, 1e-7);
            }
}
END_TEST

/* A circle centre exactly on a polygon vertex (polygon at the origin, not
 * turned, so the centre in the polygon's frame is the vertex itself). A
 * rounding can make the centre test as just outside a face, beyond that
 * vertex, where d = centre - vertex = 0 and d / |d| is 0/0. The normal
 * must be a finite unit vector and the depth the radius. Every vertex of
 * several irregular polygons, in both orders. */
START_TEST(test_circle_centre_on_a_polygon_vertex_has_a_unit_normal)
{
    static const float polys[][5][2] = {
        {{0.0f, 0.0f}, {2.0f, 0.1f}, {0.3f, 1.7f}, {0.0f, 0.0f}, {0.0f, 0.0f}},
        {{-0.7f, -0.3f}, {0.9f, -0.6f}, {1.1f, 0.7f}, {-0.2f, 1.3f}, {-1.0f, 0.4f}},
        {{0.1f, 0.2f}, {3.3f, 0.7f}, {1.9f, 2.9f}, {0.0f, 0.0f}, {0.0f, 0.0f}},
        {{-1.3f, -0.7f}, {0.6f, -1.1f}, {1.7f, 0.2f}, {0.0f, 1.9f}, {0.0f, 0.0f}}};
    static const int counts[] = {3, 5, 3, 4};
    size_t k;
    int i, order;
    for (k = 0; k < sizeof counts / sizeof counts[0]; ++k) {
        carom_body_def bd = carom_default_body_def();
        tshape poly;
        bd.shape = CAROM_SHAPE_POLYGON;
        bd.vertex_count = counts[k];
        for (i = 0; i < counts[k]; ++i) {
            bd.vertices[i].x = polys[k][i][0];
            bd.vertices[i].y = polys[k][i][1];
        }
        ck_assert_int_eq(cr_body_build(&bd, &poly.b, &poly.info), CAROM_OK);
        poly.b.x = cr_v(0.0f, 0.0f);
        for (i = 0; i < counts[k]; ++i)
            for (order = 0; order < 2; ++order) {
                cr_v2 v = poly.info.shape.verts[i];
                tshape c = make_circle(v.x, v.y, 0.25f);
                cr_manifold m;
                ck_assert_int_eq(order ? collide(&c, &poly, 0.0f, &m)
                                       : collide(&poly, &c, 0.0f, &m), 1);
                ck_assert(isfinite(m.n.x) && isfinite(m.n.y));
                ck_assert_close(hypot(m.n.x, m.n.y), 1.0, 1e-6);
                ck_assert_close(m.pts[0].sep, -0.25, 1e-6);
            }
    }
}
END_TEST

/* Two boxes corner to corner, apart by gx along x and gy < gx along y, in
 * each of the four diagonal directions and both orders: no face overlaps
 * the other sideways, so there is one point, the nearer corner; its
 * separation is the separating-axis gap gx (never more than the corners'
 * distance sqrt(gx^2 + gy^2)) along the normal +-x, from a to b. */
START_TEST(test_boxes_corner_to_corner_give_one_point_at_the_axis_gap)
{
    const double gx = 0.1, gy = 0.05;
    int sx, sy, order;
    for (sx = -1; sx <= 1; sx += 2)
        for (sy = -1; sy <= 1; sy += 2)
            for (order = 0; order < 2; ++order) {
                tshape big = make_box(0, 0, 1, 1, 0);
                tshape small = make_box((float)(sx * (1.5 + gx)), (float)(sy * (1.5 + gy)),
                                        0.5f, 0.5f, 0);
                const tshape *a = order ? &small : &big, *b = order ? &big : &small;
                double dir = order ? -sx : sx; /* from a to b along x */
                cr_manifold m;
                ck_assert_msg(collide(a, b, 0.3f, &m), "(%d, %d, %d): no contact", sx, sy, order);
                ck_assert_int_eq(m.count, 1);
                ck_assert_msg(fabs(m.n.x - dir) < 1e-6 && fabs(m.n.y) < 1e-6,
                              "(%d, %d, %d): normal (%g, %g)", sx, sy, order,
                              (double)m.n.x, (double)m.n.y);
                ck_assert_close(m.pts[0].sep, gx, 1e-6);
                ck_assert(m.pts[0].sep <= hypot(gx, gy));
                /* the point is midway across the gap */
                ck_assert_close(m.pts[0].p.x, sx * (1.0 + 0.5 * gx), 1e-5);
                /* out of reach: nothing */
                ck_assert(!collide(a, b, 0.05f, &m));
            }
}
END_TEST

/* A tilted square whose lowest corner hangs past the end of a face, above
 * it by 0.01, while the rest of its bottom edge rises over the face: the
 * distance between the two is from the face's end corner (1, 1) to that
 * edge, worked out here in double; within a reach below it there is no
 * point, above it there is one within reach. */
START_TEST(test_corner_hanging_past_a_face_end_counts_its_true_distance)
{
    const double phi = 0.2, h = 0.5, lx = 1.1, ly = 1.01;
    /* centre of the square turned by phi whose corner (h, -h) is lowest
     * after turning by -phi... choose the turn -phi: corner (h, -h) goes
     * to (h cos + h sin, -h cos + h sin) */
    double c = cos(phi), s = sin(phi);
    double kx = h * c - h * s, ky = -h * s - h * c; /* corner (h, -h) turned by -phi */
    double cx = lx - kx, cy = ly - ky;
    /* the other end of the bottom edge: corner (-h, -h) turned by -phi */
    double ox = cx + (-h * c - h * s), oy = cy + (h * s - h * c);
    /* distance from (1, 1) to the segment (lx, ly)-(ox, oy) */
    double ex = ox - lx, ey = oy - ly, u = ((1.0 - lx) * ex + (1.0 - ly) * ey) / (ex * ex + ey * ey);
    double dist = hypot(lx + u * ex - 1.0, ly + u * ey - 1.0);
    tshape ground = make_box(0, 0, 1, 1, 0);
    tshape tilt = make_box((float)cx, (float)cy, (float)h, (float)h, (float)-phi);
    cr_manifold m;
    ck_assert(oy > ly && u > 0.0 && u < 1.0);
    ck_assert(dist > 0.02 && dist < 0.04);
    ck_assert(cr_collide(&ground.info.shape, ground.b.x, ground.b.q, &tilt.info.shape,
                         tilt.b.x, tilt.b.q, (float)(dist - 0.005), 0.05f, 0.0f, &m) == 0);
    ck_assert(cr_collide(&ground.info.shape, ground.b.x, ground.b.q, &tilt.info.shape,
                         tilt.b.x, tilt.b.q, (float)(dist + 0.005), 0.05f, 0.0f, &m) > 0);
    ck_assert(m.pts[0].sep <= dist + 0.005);
}
END_TEST

/*
 * A unit box b sliding right at height -d (one slop deep, as a resting
 * body sits in the tile under it) towards tile t, whose top is flush at
 * y = 0 and whose left face is at x = 1; the box's right face is at
 * x = 1 - g. With corners rounded off by `corner` = 0.002 > d = 0.001 the
 * box only grazes the tile's corner while it approaches (g > 0) or has
 * crossed the seam by less than the corner (-0.002 < g): the manifold is
 * the face's as ever, marked as a graze of the box (body b) with the plane
 * of the tile's face that meets the contact's face at that corner: the
 * top (normal (0, 1), y = 0) while the side face makes the contact, the
 * side (normal (-1, 0), x = 1) once the top does. Whether it is a seam's
 * ghost is the world's to tell (a flush neighbour carrying the box). Past
 * the corner, the tile's top face holds it with no graze. A real step,
 * d = 0.005 > corner, is no graze, nor is anything with corner 0.
 */
START_TEST(test_box_grazes_a_flush_seam_but_meets_a_step)
{
    static const double gaps[4] = {0.01, 0.0005, -0.0015, -0.01};
    const float reach = 0.05f, face_tol = 1e-4f, corner = 0.002f;
    int i;
    for (i = 0; i < 4; ++i) {
        double g = gaps[i], d = 0.001;
        tshape tile = make_box(2.0f, -0.5f, 1.0f, 0.5f, 0.0f);
        tshape box = make_box((float)(0.5 - g), (float)(0.5 - d), 0.5f, 0.5f, 0.0f);
        cr_manifold m;
        int n = cr_collide(&tile.info.shape, tile.b.x, tile.b.q, &box.info.shape, box.b.x,
                           box.b.q, reach, face_tol, corner, &m);
        ck_assert_int_ge(n, 1);
        if (g > 0.0) {
            ck_assert_int_eq(m.graze, 2);
            ck_assert(m.n.x == -1.0f && m.n.y == 0.0f);
            ck_assert_close(m.pts[0].sep, g, 1e-6);
            ck_assert(m.graze_n.x == 0.0f && m.graze_n.y == 1.0f);
            ck_assert_close(m.graze_d, 0.0, 1e-7);
        } else if (g > -0.002) {
            ck_assert_int_eq(m.graze, 2);
            ck_assert(m.n.x == 0.0f && m.n.y == 1.0f);
            ck_assert(m.graze_n.x == -1.0f && m.graze_n.y == 0.0f);
            ck_assert_close(m.graze_d, -1.0, 1e-7);
        } else {
            ck_assert_int_eq(m.graze, 0);
            ck_assert(m.n.x == 0.0f && m.n.y == 1.0f);
            ck_assert_close(m.pts[0].sep, -d, 1e-6);
        }
        /* sharp corners: no graze */
        n = cr_collide(&tile.info.shape, tile.b.x, tile.b.q, &box.info.shape, box.b.x, box.b.q,
                       reach, face_tol, 0.0f, &m);
        ck_assert_int_ge(n, 1);
        ck_assert_int_eq(m.graze, 0);
    }
    {
        /* a step 5 mm high: met, no graze */
        tshape tile = make_box(2.0f, -0.5f, 1.0f, 0.5f, 0.0f);
        tshape box = make_box(0.5f - 0.0005f, 0.5f - 0.005f, 0.5f, 0.5f, 0.0f);
        cr_manifold m;
        ck_assert_int_ge(cr_collide(&tile.info.shape, tile.b.x, tile.b.q, &box.info.shape,
                                    box.b.x, box.b.q, reach, face_tol, corner, &m),
                         1);
        ck_assert_int_eq(m.graze, 0);
        ck_assert(m.n.x == -1.0f && m.n.y == 0.0f);
        ck_assert_close(m.pts[0].sep, 0.0005, 1e-6);
    }
}
END_TEST

/* Two boxes corner to corner (gaps 0.1 along x, 0.05 along y): the one
 * speculative point lies between the two facing corners, whichever
 * diagonal and order (for parallel edges both ends of the incident edge
 * are equally deep: the end nearer the reference face along it is the
 * corner). */
START_TEST(test_corner_to_corner_point_lies_between_the_corners)
{
    const double gx = 0.1, gy = 0.05;
    int sx, sy, order;
    for (sx = -1; sx <= 1; sx += 2)
        for (sy = -1; sy <= 1; sy += 2)
            for (order = 0; order < 2; ++order) {
                carom_body_def d = carom_default_body_def();
                cr_body bb, sb;
                cr_body_info bi, si;
                cr_manifold m;
                int hit;
                carom_body_def_set_box(&d, 1.0f, 1.0f);
                ck_assert_int_eq(cr_body_build(&d, &bb, &bi), CAROM_OK);
                carom_body_def_set_box(&d, 0.5f, 0.5f);
                d.position.x = (float)(sx * (1.5 + gx));
                d.position.y = (float)(sy * (1.5 + gy));
                ck_assert_int_eq(cr_body_build(&d, &sb, &si), CAROM_OK);
                hit = order ? cr_collide(&si.shape, sb.x, sb.q, &bi.shape, bb.x, bb.q, 0.3f, 0.0f, 0.0f, &m)
                            : cr_collide(&bi.shape, bb.x, bb.q, &si.shape, sb.x, sb.q, 0.3f, 0.0f, 0.0f, &m);
                ck_assert_int_eq(hit, 1);
                /* the big box's corner is at (sx, sy), the small one's at
                 * (sx (1 + gx), sy (1 + gy)) */
                ck_assert_msg(fabs(m.pts[0].p.y) >= 1.0 - 1e-6 &&
                                  fabs(m.pts[0].p.y) <= 1.0 + gy + 1e-6 &&
                                  m.pts[0].p.y * sy > 0.0,
                              "(%d, %d, %d): point (%g, %g), not between (%d, %d) and (%g, %g)",
                              sx, sy, order, (double)m.pts[0].p.x, (double)m.pts[0].p.y,
                              sx, sy, sx * (1.0 + gx), sy * (1.0 + gy));
            }
}
END_TEST

Suite *suite_narrowphase(void)
{
    Suite *s = suite_create("narrowphase");
    TCase *tc = tcase_create("manifolds");
    tcase_add_test(tc, test_circle_circle_overlap_normal_and_midpoint);
    tcase_add_test(tc, test_circle_circle_apart_beyond_margin_is_no_contact);
    tcase_add_test(tc, test_box_circle_face_region);
    tcase_add_test(tc, test_box_circle_vertex_region);
    tcase_add_test(tc, test_circle_box_order_reverses_the_normal);
    tcase_add_test(tc, test_circle_centre_inside_box_pushes_out_of_nearest_face);
    tcase_add_test(tc, test_box_on_box_gives_two_points_on_the_face);
    tcase_add_test(tc, test_tilted_box_corner_gives_one_point);
    tcase_add_test(tc, test_separated_polygons_are_no_contact);
    tcase_add_test(tc, test_corner_to_corner_point_lies_between_the_corners);
    tcase_add_test(tc, test_box_box_side_by_side_normal_points_from_a_to_b);
    tcase_add_test(tc, test_manifold_does_not_depend_on_where_the_pair_sits);
    tcase_add_test(tc, test_aligned_faces_keep_the_first_body_as_reference);
    tcase_add_test(tc, test_clipped_points_of_a_symmetric_pair_are_exact_mirrors);
    tcase_add_test(tc, test_polygons_within_reach_give_speculative_points);
    tcase_add_test(tc, test_separation_is_a_lower_bound_of_the_distance);
    tcase_add_test(tc, test_concentric_circles_have_a_unit_normal_and_full_depth);
    tcase_add_test(tc, test_nearly_concentric_circles_have_a_unit_normal);
    tcase_add_test(tc, test_circle_centre_on_a_polygon_vertex_has_a_unit_normal);
    tcase_add_test(tc, test_boxes_corner_to_corner_give_one_point_at_the_axis_gap);
    tcase_add_test(tc, test_corner_hanging_past_a_face_end_counts_its_true_distance);
    tcase_add_test(tc, test_box_grazes_a_flush_seam_but_meets_a_step);
    suite_add_tcase(s, tc);
    return s;
}
