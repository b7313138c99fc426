/*
 * test_broadphase.c -- the grid finds exactly the pairs that the all-pairs
 * box test finds, whatever the mix of sizes (walls larger than a cell,
 * tiny and huge coordinates), and the pair sort gives (a, b) order. Built
 * with CAROM_ENABLE_GRID=0 (make unit-nogrid) the same tests check that
 * testing every box against every other gives the same pairs, sorted.
 */
#include <string.h>

#include "test_util.h"

#include "broadphase.h"

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
    return s;
}
