/*
 * test_broadphase.c -- the grid finds exactly the pairs that the all-pairs
 * box test finds, whatever the mix of sizes (walls larger than a cell,
 * tiny and huge coordinates), and the pair sort gives (a, b) order; so
 * does the sweep that takes the place of the grid for few bodies. Built
 * with CAROM_ENABLE_GRID=0 (make unit-nogrid) the same tests check that
 * testing every box against every other gives the same pairs, sorted.
 */
#include <string.h>

#include "test_util.h"

#include "broadphase.h"
#include "world.h"

#define N_MAX 400

static unsigned lcg(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float uniform(unsigned *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)(lcg(s) & 0xffff) / 65535.0f;
}

typedef struct bp_fixture {
    cr_box boxes[N_MAX];
    int bodies[N_MAX];
    int is_static[N_MAX];
    cr_proxy proxies[N_MAX], tmp[N_MAX];
    int start[2 * 1024 + 1], count[N_MAX + 1];
    cr_pair pairs[N_MAX * N_MAX / 2], pair_tmp[N_MAX * N_MAX / 2];
    cr_broadphase bp;
} bp_fixture;

static int accept_not_both_static(void *ctx, int a, int b)
{
    const bp_fixture *f = (const bp_fixture *)ctx;
    return !(f->is_static[a] && f->is_static[b]);
}

static void fixture_init(bp_fixture *f, int n)
{
    int i;
    f->bp.proxies = f->proxies;
    f->bp.tmp = f->tmp;
    f->bp.start = f->start;
    f->bp.count = f->count;
    f->bp.capacity = n;
    f->bp.bucket_cap = cr_broadphase_bucket_cap(n);
    ck_assert_int_le(f->bp.bucket_cap, 2 * 1024);
    for (i = 0; i < n; ++i)
        f->bodies[i] = i;
}

/* Compare the grid's pairs, sorted, with the all-pairs test. */
static void check_against_all_pairs(bp_fixture *f, int n)
{
    long found;
    int a, b, k = 0, expected = 0;
    cr_broadphase_build(&f->bp, f->boxes, f->bodies, n);
    found = cr_broadphase_pairs(&f->bp, f->boxes, accept_not_both_static, f,
                                f->pairs, N_MAX * N_MAX / 2);
    ck_assert_int_le(found, N_MAX * N_MAX / 2);
#if CAROM_ENABLE_GRID
    cr_pairs_sort(f->pairs, f->pair_tmp, (int)found, f->count, n);
#endif /* without the grid (every box against every other) they come sorted */
    for (a = 0; a < n; ++a)
        for (b = a + 1; b < n; ++b) {
            const cr_box *p = &f->boxes[a], *q = &f->boxes[b];
            int overlap = p->lo_x <= q->hi_x && q->lo_x <= p->hi_x &&
                          p->lo_y <= q->hi_y && q->lo_y <= p->hi_y &&
                          !(f->is_static[a] && f->is_static[b]);
            if (!overlap)
                continue;
            ++expected;
            ck_assert_msg(k < found, "missing pair (%d, %d)", a, b);
            ck_assert_msg(f->pairs[k].a == a && f->pairs[k].b == b,
                          "pair %d is (%d, %d), expected (%d, %d)", k,
                          f->pairs[k].a, f->pairs[k].b, a, b);
            ++k;
        }
    ck_assert_int_eq(found, expected);
}

static void random_boxes(bp_fixture *f, int n, unsigned seed, float spread,
                         float size_lo, float size_hi)
{
    int i;
    for (i = 0; i < n; ++i) {
        float x = uniform(&seed, -spread, spread), y = uniform(&seed, -spread, spread);
        float hx = uniform(&seed, size_lo, size_hi), hy = uniform(&seed, size_lo, size_hi);
        f->boxes[i].lo_x = x - hx;
        f->boxes[i].hi_x = x + hx;
        f->boxes[i].lo_y = y - hy;
        f->boxes[i].hi_y = y + hy;
        f->is_static[i] = i % 17 == 0;
    }
}

START_TEST(test_grid_equals_all_pairs_for_mixed_sizes)
{
    static bp_fixture f;
    int n = 300;
    fixture_init(&f, n);
    random_boxes(&f, n, 12345u, 10.0f, 0.05f, 0.8f);
    check_against_all_pairs(&f, n);
}
END_TEST

START_TEST(test_grid_finds_pairs_of_walls_larger_than_a_cell)
{
    static bp_fixture f;
    int n = 200;
    fixture_init(&f, n);
    random_boxes(&f, n, 777u, 5.0f, 0.05f, 0.15f);
    /* a floor and two walls, far larger than the cell */
    f.boxes[0].lo_x = -6.0f; f.boxes[0].hi_x = 6.0f; f.boxes[0].lo_y = -5.2f; f.boxes[0].hi_y = -4.9f;
    f.boxes[1].lo_x = -5.2f; f.boxes[1].hi_x = -4.9f; f.boxes[1].lo_y = -6.0f; f.boxes[1].hi_y = 6.0f;
    f.boxes[2].lo_x = 4.9f; f.boxes[2].hi_x = 5.2f; f.boxes[2].lo_y = -6.0f; f.boxes[2].hi_y = 6.0f;
    f.is_static[0] = f.is_static[1] = f.is_static[2] = 1;
    check_against_all_pairs(&f, n);
}
END_TEST

/* Boxes larger than a cell, of every size from 1.5 to 12 cells, among
 * small ones spread wider than the table (so the cells a big box covers
 * wrap around the table's edges, on one axis or both, or cover whole
 * rows): a big box reads only the buckets of the cells near it, and must
 * still find every box it overlaps. Several layouts. */
START_TEST(test_big_boxes_find_their_pairs_where_the_table_wraps)
{
    static bp_fixture f;
    int n = 180, i, layout;
    for (layout = 0; layout < 12; ++layout) {
        unsigned seed = 1000u + 7u * (unsigned)layout;
        fixture_init(&f, n);
        random_boxes(&f, n, seed, 8.0f + (float)layout, 0.05f, 0.15f);
        for (i = 0; i < 24; ++i) {
            /* cells are about 0.4 here (twice the mean small box) */
            float x = uniform(&seed, -12.0f, 12.0f), y = uniform(&seed, -12.0f, 12.0f);
            float hx = uniform(&seed, 0.3f, 2.4f), hy = uniform(&seed, 0.05f, 2.4f);
            if (i % 2) { /* as wide as high, or the other way round */
                float t = hx;
                hx = hy;
                hy = t;
            }
            f.boxes[i].lo_x = x - hx;
            f.boxes[i].hi_x = x + hx;
            f.boxes[i].lo_y = y - hy;
            f.boxes[i].hi_y = y + hy;
            f.is_static[i] = i % 3 == 0;
        }
        check_against_all_pairs(&f, n);
#if CAROM_ENABLE_GRID
        ck_assert_int_gt(f.bp.big_count, 12);
#endif
    }
}
END_TEST

/* A sparse layout (fewer pairs than slots: the pair sort's insertion
 * path) and a dense one (its counting passes) give the same (a, b)
 * order as the all-pairs test. */
START_TEST(test_pair_sort_orders_few_and_many_pairs)
{
    static bp_fixture f;
    int n = 300;
    fixture_init(&f, n);
    random_boxes(&f, n, 31u, 60.0f, 0.05f, 0.4f);
    check_against_all_pairs(&f, n);
    random_boxes(&f, n, 32u, 3.0f, 0.05f, 0.4f);
    check_against_all_pairs(&f, n);
}
END_TEST

/* Four walls 100 times the size of 20 small boxes: the walls are not
 * what a cell is sized for. The mean of all sizes is (20 * 0.1 + 4 * 10)
 * / 24 = 1.75; only the small boxes are within 4 times it, and they are all
 * of one size, so the cell is their size, 0.1 (with the walls counted it
 * would be 3.5, and every body would be compared with most of the
 * others). */
START_TEST(test_walls_do_not_set_the_cell)
{
    static bp_fixture f;
    int n = 24, i;
    fixture_init(&f, n);
    for (i = 0; i < 20; ++i) {
        f.boxes[i].lo_x = -4.0f + 0.35f * (float)i;
        f.boxes[i].hi_x = f.boxes[i].lo_x + 0.1f;
        f.boxes[i].lo_y = (i % 2) ? 0.05f : 0.0f; /* neighbours never touch */
        f.boxes[i].hi_y = f.boxes[i].lo_y + 0.1f;
        f.is_static[i] = 0;
    }
    for (i = 20; i < 24; ++i) {
        int side = i - 20;
        f.boxes[i].lo_x = side == 0 ? -5.3f : side == 1 ? 5.0f : -5.0f;
        f.boxes[i].hi_x = side == 0 ? -5.0f : side == 1 ? 5.3f : 5.0f;
        f.boxes[i].lo_y = side == 2 ? -5.3f : side == 3 ? 5.0f : -5.0f;
        f.boxes[i].hi_y = side == 2 ? -5.0f : side == 3 ? 5.3f : 5.0f;
        f.is_static[i] = 1;
    }
    check_against_all_pairs(&f, n);
#if CAROM_ENABLE_GRID
    ck_assert_float_eq_tol(f.bp.cell, 0.1f, 1e-6f);
    ck_assert_int_eq(f.bp.grid_count, 20);
    ck_assert_int_eq(f.bp.big_count, 4);
#endif
}
END_TEST

/* The cell is the largest box that is not big, but never more than twice
 * the mean: 19 boxes of side 0.1 and one of 0.3 have a mean of 0.11, so
 * the cell is 0.22 and the 0.3 box is a big item, tested against the
 * buckets it covers; 19 boxes of 0.1 and one of 0.15, a cell of 0.15 and
 * no big item. The same pairs as every box against every other, both. */
START_TEST(test_cell_is_the_largest_box_within_twice_the_mean)
{
    static bp_fixture f;
    int n = 20, i, round;
    for (round = 0; round < 2; ++round) {
        float odd = round == 0 ? 0.3f : 0.15f;
        fixture_init(&f, n);
        for (i = 0; i < n; ++i) {
            float side = i == 7 ? odd : 0.1f;
            f.boxes[i].lo_x = 0.08f * (float)(i % 5);
            f.boxes[i].lo_y = 0.09f * (float)(i / 5);
            f.boxes[i].hi_x = f.boxes[i].lo_x + side;
            f.boxes[i].hi_y = f.boxes[i].lo_y + side;
            f.is_static[i] = 0;
        }
        check_against_all_pairs(&f, n);
#if CAROM_ENABLE_GRID
        if (round == 0) {
            ck_assert_float_eq_tol(f.bp.cell, 0.22f, 1e-6f);
            ck_assert_int_eq(f.bp.big_count, 1);
        } else {
            ck_assert_float_eq_tol(f.bp.cell, 0.15f, 1e-6f);
            ck_assert_int_eq(f.bp.big_count, 0);
        }
#endif
    }
}
END_TEST

START_TEST(test_grid_handles_huge_and_negative_coordinates)
{
    static bp_fixture f;
    int n = 100;
    fixture_init(&f, n);
    random_boxes(&f, n, 99u, 5.0e7f, 1.0e6f, 2.0e7f);
    check_against_all_pairs(&f, n);
    random_boxes(&f, n, 98u, 0.001f, 1.0e-5f, 2.0e-4f);
    check_against_all_pairs(&f, n);
}
END_TEST

/* Past the capacity nothing is written and the count saturates at cap + 1
 * (a count of all overlapping pairs of 10^5 bodies would overflow). */
START_TEST(test_pair_overflow_is_counted_not_written)
{
    static bp_fixture f;
    int i, n = 4;
    long found;
    fixture_init(&f, n);
    for (i = 0; i < n; ++i) { /* all overlap: 6 pairs */
        f.boxes[i].lo_x = 0.1f * (float)i;
        f.boxes[i].hi_x = 0.1f * (float)i + 1.0f;
        f.boxes[i].lo_y = 0.0f;
        f.boxes[i].hi_y = 1.0f;
        f.is_static[i] = 0;
    }
    f.pairs[2].a = -7; /* a guard just past the capacity */
    cr_broadphase_build(&f.bp, f.boxes, f.bodies, n);
    found = cr_broadphase_pairs(&f.bp, f.boxes, accept_not_both_static, &f, f.pairs, 2);
    ck_assert_int_eq(found, 3);
    ck_assert_int_eq(f.pairs[2].a, -7);
}
END_TEST

/* Boxes in one column of cells, up to 60 cells high: the 16-bucket table
 * is a patch of 4 by 4 cells tiling the plane, so cells with the same x
 * and y a multiple of 4 apart share a bucket (here all eight), and must
 * still be told apart. The same along a row. */
START_TEST(test_grid_tells_apart_cells_that_share_a_bucket)
{
    static bp_fixture f;
    int i, n = 8;
    fixture_init(&f, n);
    for (i = 0; i < n; ++i) { /* 0.5 wide: cell 1; centres 8 cells apart */
        float y = 8.0f * (float)i + 0.5f * (float)(i % 3);
        f.boxes[i].lo_x = 0.1f;
        f.boxes[i].hi_x = 0.6f;
        f.boxes[i].lo_y = y;
        f.boxes[i].hi_y = y + 0.5f;
        f.is_static[i] = 0;
    }
    f.boxes[5].lo_y = f.boxes[4].lo_y + 0.2f; /* one overlapping pair */
    f.boxes[5].hi_y = f.boxes[5].lo_y + 0.5f;
    check_against_all_pairs(&f, n);
    for (i = 0; i < n; ++i) {
        float lo_x = f.boxes[i].lo_y, hi_x = f.boxes[i].hi_y;
        f.boxes[i].lo_y = 0.1f;
        f.boxes[i].hi_y = 0.6f;
        f.boxes[i].lo_x = lo_x;
        f.boxes[i].hi_x = hi_x;
    }
    check_against_all_pairs(&f, n);
}
END_TEST

/* Degenerate layouts: no body at all; bodies that are points (boxes of
 * size 0, so the mean size gives no cell), some of them coincident. */
START_TEST(test_grid_handles_no_bodies_and_point_boxes)
{
    static bp_fixture f;
    int i, n = 40;
    long found;
    fixture_init(&f, n);
    cr_broadphase_build(&f.bp, f.boxes, f.bodies, 0);
    found = cr_broadphase_pairs(&f.bp, f.boxes, accept_not_both_static, &f, f.pairs, 10);
    ck_assert_int_eq(found, 0);
    for (i = 0; i < n; ++i) {
        float x = (float)(i % 7) * 0.25f, y = (float)(i % 5) * 0.5f;
        f.boxes[i].lo_x = f.boxes[i].hi_x = x;
        f.boxes[i].lo_y = f.boxes[i].hi_y = y;
        f.is_static[i] = 0;
    }
    check_against_all_pairs(&f, n);
}
END_TEST

/* Tiny boxes far out on the negative side: cell coordinates beyond the
 * grid's clamp (1e9 cells) on both sides, and still the exact pairs. */
START_TEST(test_grid_clamps_cells_beyond_its_range_on_both_sides)
{
    static bp_fixture f;
    int i, n = 60;
    fixture_init(&f, n);
    random_boxes(&f, n, 4242u, 1.0f, 1e-4f, 2e-4f);
    for (i = 0; i < 6; ++i) { /* cell 4e-4: 8e7 / 4e-4 = 2e11 cells out */
        float x = (i % 2 ? 1.0f : -1.0f) * 8.0e7f, y = (i < 3 ? -1.0f : 1.0f) * 8.0e7f;
        f.boxes[i].lo_x = x;
        f.boxes[i].hi_x = x + (i == 1 ? 8.0f : 0.0f);
        f.boxes[i].lo_y = y;
        f.boxes[i].hi_y = y;
    }
    check_against_all_pairs(&f, n);
}
END_TEST

/* A query callback that records the bodies it is given and stops after
 * `stop_after` of them (0: never stops). */
typedef struct q_ctx {
    int seen[N_MAX];
    int count, stop_after;
} q_ctx;

static int record(void *ctx, int body)
{
    q_ctx *q = (q_ctx *)ctx;
    q->seen[q->count++] = body;
    return q->stop_after == 0 || q->count < q->stop_after;
}

static int box_overlap(const cr_box *p, const cr_box *q)
{
    return p->lo_x <= q->hi_x && q->lo_x <= p->hi_x && p->lo_y <= q->hi_y &&
           q->lo_y <= p->hi_y;
}

/* The query gives each body whose box overlaps the query box exactly once,
 * through the cells it covers, through all items when that is fewer, and
 * through the large boxes; a callback returning 0 stops it at once. */
START_TEST(test_query_gives_every_overlapping_body_once_and_stops_on_request)
{
    static bp_fixture f;
    static q_ctx q;
    int n = 200, i, k, j;
    cr_box boxes_q[3];
    fixture_init(&f, n);
    random_boxes(&f, n, 31337u, 8.0f, 0.05f, 0.3f);
    /* a floor larger than a cell */
    f.boxes[0].lo_x = -9.0f; f.boxes[0].hi_x = 9.0f; f.boxes[0].lo_y = -9.0f; f.boxes[0].hi_y = -8.5f;
    cr_broadphase_build(&f.bp, f.boxes, f.bodies, n);
#if CAROM_ENABLE_GRID
    ck_assert_int_ge(f.bp.big_count, 1);
#endif
    /* a small query (its cells), a huge one (all items), one over the floor only */
    boxes_q[0].lo_x = -1.0f; boxes_q[0].hi_x = 1.0f; boxes_q[0].lo_y = -1.0f; boxes_q[0].hi_y = 1.0f;
    boxes_q[1].lo_x = -50.0f; boxes_q[1].hi_x = 50.0f; boxes_q[1].lo_y = -50.0f; boxes_q[1].hi_y = 50.0f;
    boxes_q[2].lo_x = 8.6f; boxes_q[2].hi_x = 8.8f; boxes_q[2].lo_y = -8.8f; boxes_q[2].hi_y = -8.7f;
    for (k = 0; k < 3; ++k) {
        int expected = 0;
        memset(&q, 0, sizeof q);
        ck_assert_int_eq(cr_broadphase_query(&f.bp, f.boxes, &boxes_q[k], record, &q), 1);
        for (i = 0; i < n; ++i) {
            int times = 0;
            for (j = 0; j < q.count; ++j)
                times += q.seen[j] == i;
            if (box_overlap(&f.boxes[i], &boxes_q[k])) {
                ++expected;
                ck_assert_msg(times == 1, "query %d: body %d given %d times", k, i, times);
            } else {
                ck_assert_msg(times == 0, "query %d: body %d does not overlap", k, i);
            }
        }
        ck_assert_int_eq(q.count, expected);
        ck_assert_int_ge(expected, 1);
        /* stop at the first body */
        memset(&q, 0, sizeof q);
        q.stop_after = 1;
        ck_assert_int_eq(cr_broadphase_query(&f.bp, f.boxes, &boxes_q[k], record, &q), 0);
        ck_assert_int_eq(q.count, 1);
    }
}
END_TEST

/* ---- the sweep (few bodies) ----------------------------------------------- */

/* The pairs of the bodies in list[0..m) (increasing slots), built and
 * sorted, against the all-pairs test over those bodies. */
static void check_listed(bp_fixture *f, const int *list, int m)
{
    long found;
    int a, b, k = 0, expected = 0;
    cr_broadphase_build(&f->bp, f->boxes, list, m);
    found = cr_broadphase_pairs(&f->bp, f->boxes, accept_not_both_static, f, f->pairs,
                                N_MAX * N_MAX / 2);
    ck_assert_int_le(found, N_MAX * N_MAX / 2);
#if CAROM_ENABLE_GRID
    cr_pairs_sort(f->pairs, f->pair_tmp, (int)found, f->count, list[m - 1] + 1);
#endif
    for (a = 0; a < m; ++a)
        for (b = a + 1; b < m; ++b) {
            int i = list[a], j = list[b];
            if (!box_overlap(&f->boxes[i], &f->boxes[j]) || (f->is_static[i] && f->is_static[j]))
                continue;
            ++expected;
            ck_assert_msg(k < found, "missing pair (%d, %d)", i, j);
            ck_assert_msg(f->pairs[k].a == i && f->pairs[k].b == j,
                          "pair %d is (%d, %d), expected (%d, %d)", k, f->pairs[k].a,
                          f->pairs[k].b, i, j);
            ++k;
        }
    ck_assert_int_eq(found, expected);
}

/* Few bodies are swept instead of filed in the grid: the same pairs as the
 * all-pairs test among bodies and walls, again and again as the boxes move
 * (each sort starts from the last order) and as bodies leave and join (a
 * slot the last order holds is gone, a new one is not in it yet). */
START_TEST(test_sweep_equals_all_pairs_as_boxes_move_and_bodies_come_and_go)
{
    static bp_fixture f;
    static int list[N_MAX];
    unsigned seed = 4242u;
    int n = 120, i, round, m;
    fixture_init(&f, n);
    f.bp.sweep_max = N_MAX;
    random_boxes(&f, n, 99u, 4.0f, 0.05f, 0.4f);
    f.boxes[0].lo_x = -5.0f; f.boxes[0].hi_x = 5.0f; f.boxes[0].lo_y = -4.5f; f.boxes[0].hi_y = -4.2f;
    f.boxes[1].lo_x = -4.5f; f.boxes[1].hi_x = -4.2f; f.boxes[1].lo_y = -5.0f; f.boxes[1].hi_y = 5.0f;
    f.boxes[2].lo_x = 4.2f; f.boxes[2].hi_x = 4.5f; f.boxes[2].lo_y = -5.0f; f.boxes[2].hi_y = 5.0f;
    f.is_static[0] = f.is_static[1] = f.is_static[2] = 1;
    for (round = 0; round < 8; ++round) {
        /* rounds 2, 3, 6: every third body away (a different third each
         * time), the rest all there */
        for (i = 0, m = 0; i < n; ++i)
            if (!((round == 2 || round == 3 || round == 6) && (i + round) % 3 == 0))
                list[m++] = i;
        check_listed(&f, list, m);
#if CAROM_ENABLE_GRID
        ck_assert_int_eq(f.bp.sweep, 1);
        ck_assert_int_eq(f.bp.grid_count, m);
#endif
        for (i = 3; i < n; ++i) {
            float dx = uniform(&seed, -0.3f, 0.3f), dy = uniform(&seed, -0.3f, 0.3f);
            f.boxes[i].lo_x += dx;
            f.boxes[i].hi_x += dx;
            f.boxes[i].lo_y += dy;
            f.boxes[i].hi_y += dy;
        }
    }
    /* past sweep_max the grid takes over, and back */
#if CAROM_ENABLE_GRID
    f.bp.sweep_max = n - 1;
    check_against_all_pairs(&f, n);
    ck_assert_int_eq(f.bp.sweep, 0);
    f.bp.sweep_max = N_MAX;
    check_against_all_pairs(&f, n);
    ck_assert_int_eq(f.bp.sweep, 1);
#endif
}
END_TEST

/* The sweep runs along the axis the bodies spread along: a tower of boxes
 * along y (along x every box would meet every other), a row along x; the
 * pairs are the same either way, and switching axis starts the order
 * afresh. */
START_TEST(test_sweep_runs_along_the_longer_spread)
{
    static bp_fixture f;
    int n = 60, i, layout;
    fixture_init(&f, n);
    f.bp.sweep_max = N_MAX;
    for (layout = 0; layout < 3; ++layout) {
        for (i = 0; i < n; ++i) {
            /* boxes 1 m wide, touching their neighbours (pairs i, i + 1) */
            float along = (float)i, across = 0.01f * (float)(i % 3);
            float x = layout == 1 ? along : across, y = layout == 1 ? across : along;
            f.boxes[i].lo_x = x - 0.5f;
            f.boxes[i].hi_x = x + 0.5f;
            f.boxes[i].lo_y = y - 0.5f;
            f.boxes[i].hi_y = y + 0.5f;
            f.is_static[i] = 0;
        }
        check_against_all_pairs(&f, n);
#if CAROM_ENABLE_GRID
        ck_assert_int_eq(f.bp.sweep, 1);
        ck_assert_int_eq(f.bp.sweep_axis, layout == 1 ? 0 : 1);
#endif
    }
}
END_TEST

/* A query of the sweep gives the bodies in slot order, as the build
 * without the grid does (callers that act on each body in turn then act
 * in the same order in both builds). */
START_TEST(test_sweep_query_gives_bodies_in_slot_order)
{
    static bp_fixture f;
    static q_ctx q;
    cr_box all;
    int n = 100, i, expected = 0;
    fixture_init(&f, n);
    f.bp.sweep_max = N_MAX;
    random_boxes(&f, n, 2024u, 5.0f, 0.05f, 0.5f);
    cr_broadphase_build(&f.bp, f.boxes, f.bodies, n);
    all.lo_x = -2.0f; all.hi_x = 3.0f; all.lo_y = -1.0f; all.hi_y = 2.0f;
    memset(&q, 0, sizeof q);
    ck_assert_int_eq(cr_broadphase_query(&f.bp, f.boxes, &all, record, &q), 1);
    for (i = 0; i < n; ++i)
        if (box_overlap(&f.boxes[i], &all))
            ck_assert_int_eq(q.seen[expected++], i);
    ck_assert_int_eq(q.count, expected);
    ck_assert_int_ge(expected, 5);
}
END_TEST

/* A world of 100 bodies (circles and boxes falling into a box of walls,
 * some of them bouncing, some spinning) sweeps; the same world with the
 * sweep turned off fills the grid. Both methods: every body's state the
 * same bits after 2 s, for the pairs are the same and sorted alike. */
static tw sweep_world(carom_method method, int sweep_max)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    tw t;
    unsigned seed = 555u;
    int i;
    wd.method = method;
    wd.max_bodies = 104;
    t = tw_make(&wd);
    t.w->bp.sweep_max = sweep_max;
    bd.type = CAROM_BODY_STATIC;
    bd.shape = CAROM_SHAPE_POLYGON;
    bd.vertex_count = 4;
    for (i = 0; i < 4; ++i) {
        /* floor, ceiling, left and right walls of a 6 m box */
        float hx = i < 2 ? 3.2f : 0.2f, hy = i < 2 ? 0.2f : 3.2f;
        bd.vertices[0] = (carom_vec2){-hx, -hy};
        bd.vertices[1] = (carom_vec2){hx, -hy};
        bd.vertices[2] = (carom_vec2){hx, hy};
        bd.vertices[3] = (carom_vec2){-hx, hy};
        bd.position = i < 2 ? (carom_vec2){0.0f, i == 0 ? -3.0f : 3.0f}
                            : (carom_vec2){i == 2 ? -3.0f : 3.0f, 0.0f};
        tw_add(&t, &bd);
    }
    bd.type = CAROM_BODY_DYNAMIC;
    for (i = 0; i < 100; ++i) {
        bd.shape = i % 2 ? CAROM_SHAPE_CIRCLE : CAROM_SHAPE_POLYGON;
        bd.radius = uniform(&seed, 0.1f, 0.2f);
        bd.vertices[0] = (carom_vec2){-0.15f, -0.1f};
        bd.vertices[1] = (carom_vec2){0.15f, -0.1f};
        bd.vertices[2] = (carom_vec2){0.15f, 0.1f};
        bd.vertices[3] = (carom_vec2){-0.15f, 0.1f};
        bd.position = (carom_vec2){-2.5f + 0.5f * (float)(i % 10), -2.4f + 0.5f * (float)(i / 10)};
        bd.velocity = (carom_vec2){uniform(&seed, -2.0f, 2.0f), uniform(&seed, -2.0f, 2.0f)};
        bd.angular_velocity = uniform(&seed, -3.0f, 3.0f);
        bd.restitution = i % 3 == 0 ? 0.8f : 0.0f;
        tw_add(&t, &bd);
    }
    return t;
}

START_TEST(test_world_sweep_and_grid_give_the_same_bits)
{
    int m, i;
    for (m = 0; m < 2; ++m) {
        carom_method method = m ? CAROM_METHOD_DISCRETE : CAROM_METHOD_EVENTS;
        tw a = sweep_world(method, CR_SWEEP_MAX), b = sweep_world(method, 0);
        tw_steps(&a, 120);
        tw_steps(&b, 120);
#if CAROM_ENABLE_GRID
        ck_assert_int_eq(a.w->bp.sweep, 1);
        ck_assert_int_eq(b.w->bp.sweep, 0);
#endif
        for (i = 0; i < 104; ++i) {
            carom_body_state sa = tw_state(&a, i), sb = tw_state(&b, i);
            ck_assert_msg(memcmp(&sa, &sb, sizeof sa) == 0, "method %d: body %d differs", m, i);
        }
        tw_free(&a);
        tw_free(&b);
    }
}
END_TEST

/* Through the world: a pile denser than the default pair capacity fails
 * with CAROM_ERR_PAIR_CAPACITY and leaves the world as it was. */
START_TEST(test_world_pair_capacity_is_a_clean_failure)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_body_state before, after;
    tw t;
    int i;
    wd.max_bodies = 10;
    wd.max_pairs = 5;
    t = tw_make(&wd);
    for (i = 0; i < 10; ++i) {
        bd.position.x = 0.1f * (float)i; /* all 45 pairs overlap */
        tw_add(&t, &bd);
    }
    before = tw_state(&t, 3);
    ck_assert_int_eq(carom_world_step(t.w), CAROM_ERR_PAIR_CAPACITY);
    after = tw_state(&t, 3);
    ck_assert(memcmp(&before, &after, sizeof before) == 0);
    ck_assert_int_eq(carom_world_step_count(t.w), 0);
    tw_free(&t);
}
END_TEST

Suite *suite_broadphase(void)
{
    Suite *s = suite_create("broadphase");
    TCase *tc = tcase_create("grid");
    tcase_add_test(tc, test_grid_equals_all_pairs_for_mixed_sizes);
    tcase_add_test(tc, test_grid_finds_pairs_of_walls_larger_than_a_cell);
    tcase_add_test(tc, test_walls_do_not_set_the_cell);
    tcase_add_test(tc, test_cell_is_the_largest_box_within_twice_the_mean);
    tcase_add_test(tc, test_big_boxes_find_their_pairs_where_the_table_wraps);
    tcase_add_test(tc, test_pair_sort_orders_few_and_many_pairs);
    tcase_add_test(tc, test_grid_handles_huge_and_negative_coordinates);
    tcase_add_test(tc, test_pair_overflow_is_counted_not_written);
    tcase_add_test(tc, test_world_pair_capacity_is_a_clean_failure);
    tcase_add_test(tc, test_grid_tells_apart_cells_that_share_a_bucket);
    tcase_add_test(tc, test_grid_handles_no_bodies_and_point_boxes);
    tcase_add_test(tc, test_grid_clamps_cells_beyond_its_range_on_both_sides);
    tcase_add_test(tc, test_query_gives_every_overlapping_body_once_and_stops_on_request);
    suite_add_tcase(s, tc);
    tc = tcase_create("sweep");
    tcase_add_test(tc, test_sweep_equals_all_pairs_as_boxes_move_and_bodies_come_and_go);
    tcase_add_test(tc, test_sweep_runs_along_the_longer_spread);
    tcase_add_test(tc, test_sweep_query_gives_bodies_in_slot_order);
    tcase_add_test(tc, test_world_sweep_and_grid_give_the_same_bits);
    suite_add_tcase(s, tc);
    return s;
}
