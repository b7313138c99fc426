/*
 * test_profile.c -- the op-count profiler. In the profiling build: exact
 * operation counts, each derived operation by operation from the code in
 * docs/cost-model.md (the expected numbers below are those derivations, not
 * measurements). In the default build: the profiler is absent and says so.
 */
#include <string.h>

#include "test_util.h"

#include "toi.h"

#if CAROM_ENABLE_PROFILE
typedef struct counts {
    unsigned long add, sub, mul, div, cmp, sqrt_;
} counts;

static void expect_row(const uint64_t *row, counts c, const char *what)
{
    ck_assert_msg(row[CAROM_OP_ADD] == c.add && row[CAROM_OP_SUB] == c.sub &&
                      row[CAROM_OP_MUL] == c.mul && row[CAROM_OP_DIV] == c.div &&
                      row[CAROM_OP_CMP] == c.cmp && row[CAROM_OP_SQRT] == c.sqrt_,
                  "%s: add %lu sub %lu mul %lu div %lu cmp %lu sqrt %lu, derived "
                  "add %lu sub %lu mul %lu div %lu cmp %lu sqrt %lu",
                  what, (unsigned long)row[0], (unsigned long)row[1],
                  (unsigned long)row[2], (unsigned long)row[3], (unsigned long)row[4],
                  (unsigned long)row[5], c.add, c.sub, c.mul, c.div, c.cmp, c.sqrt_);
}

#endif

START_TEST(test_seed_preset_is_the_design_notes_table)
{
    carom_op_weights w;
    ck_assert_int_eq(carom_op_weights_preset("seed", &w), CAROM_OK);
    ck_assert(w.w[CAROM_OP_ADD] == 1.0f && w.w[CAROM_OP_SUB] == 1.0f &&
              w.w[CAROM_OP_MUL] == 1.5f && w.w[CAROM_OP_DIV] == 4.0f &&
              w.w[CAROM_OP_CMP] == 1.0f && w.w[CAROM_OP_SQRT] == 6.0f);
    ck_assert_int_eq(carom_op_weights_preset("cortex-m4f", &w), CAROM_OK);
    ck_assert(w.w[CAROM_OP_DIV] == 14.0f && w.w[CAROM_OP_MUL] == 1.0f);
    ck_assert_int_eq(carom_op_weights_preset("cortex-m0", &w), CAROM_OK);
    ck_assert_int_eq(carom_op_weights_preset("pentium", &w), CAROM_ERR_BAD_PARAMETER);
    ck_assert_int_eq(carom_op_weights_preset(NULL, &w), CAROM_ERR_NULL);
}
END_TEST

START_TEST(test_cost_is_the_weighted_sum_of_counts)
{
#if !CAROM_ENABLE_PROFILE
    /* nothing is counted without the profiler: the cost is 0 */
    carom_profile q;
    carom_op_weights v;
    carom_profile_reset(&q);
    carom_op_weights_preset("seed", &v);
    q.ops[0][0] = 5;
    ck_assert(carom_profile_cost(&q, &v, CAROM_PHASE_COUNT) == 0.0f);
    return;
#endif
    carom_profile p;
    carom_op_weights w;
    carom_profile_reset(&p);
    carom_op_weights_preset("seed", &w);
    p.ops[CAROM_PHASE_INTEGRATION][CAROM_OP_MUL] = 10;  /* 15 */
    p.ops[CAROM_PHASE_INTEGRATION][CAROM_OP_SQRT] = 2;  /* 12 */
    p.ops[CAROM_PHASE_RESTING][CAROM_OP_DIV] = 3;       /* 12 */
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_INTEGRATION) == 27.0f);
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_RESTING) == 12.0f);
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_COUNT) == 39.0f);
    ck_assert(carom_profile_cost(&p, &w, -1) == 0.0f);
    ck_assert(carom_profile_cost(&p, &w, CAROM_PHASE_COUNT + 1) == 0.0f);
    ck_assert_str_eq(carom_phase_name(CAROM_PHASE_INTEGRATION), "integration");
    ck_assert_str_eq(carom_op_name(CAROM_OP_SQRT), "sqrt");
}
END_TEST

#if CAROM_ENABLE_PROFILE




/* The stable root of a gap c0 + c1 s (+ c2 s^2): the note's 1D impact time.
 * Linear: 4 cmp, 1 sub (negation), 1 div. Quadratic: 10 cmp, 6 mul, 2 sub,
 * 2 add, 2 div, 1 sqrt. */
START_TEST(test_root_of_linear_and_quadratic_gap_counts)
{
    uint64_t row[CAROM_OP_COUNT] = {0};
    counts lin = {0, 1, 0, 1, 4, 0}, quad = {2, 2, 6, 2, 10, 1};
    float s;
    carom__op_row = row;
    ck_assert(cr_first_down_root2(2.0f, -3.0f, 0.0f, 1.0f, &s));
    carom__op_row = 0;
    ck_assert_close(s, 2.0 / 3.0, 1e-7);
    expect_row(row, lin, "linear root");
    memset(row, 0, sizeof row);
    carom__op_row = row;
    /* 2 - 3 s + 0.5 s^2 = 0: s = 3 - sqrt(5) */
    ck_assert(cr_first_down_root2(2.0f, -3.0f, 0.5f, 1.0f, &s));
    carom__op_row = 0;
    ck_assert_close(s, 3.0 - sqrt(5.0), 1e-6);
    expect_row(row, quad, "quadratic root");
}
END_TEST



#else /* !CAROM_ENABLE_PROFILE */

START_TEST(test_default_build_has_no_profiler)
{
    carom_world_def wd = carom_default_world_def();
    carom_profile p;
    tw t;
    wd.max_bodies = 1;
    t = tw_make(&wd);
    ck_assert_int_eq(carom_world_set_profile(t.w, &p), CAROM_ERR_DISABLED);
    tw_free(&t);
}
END_TEST

#endif

/* Every build names the operation kinds and phases the tools print, each
 * distinct, and says "unknown" past the end; missing pointers are refused
 * or ignored. */
START_TEST(test_op_and_phase_names_are_distinct_and_bounded)
{
    carom_op_weights w;
    int i, j;
    for (i = 0; i < CAROM_OP_COUNT; ++i) {
        ck_assert(strlen(carom_op_name((carom_op)i)) > 0);
        ck_assert_str_ne(carom_op_name((carom_op)i), "unknown");
        for (j = 0; j < i; ++j)
            ck_assert_str_ne(carom_op_name((carom_op)i), carom_op_name((carom_op)j));
    }
    for (i = 0; i < CAROM_PHASE_COUNT; ++i) {
        ck_assert(strlen(carom_phase_name((carom_phase)i)) > 0);
        ck_assert_str_ne(carom_phase_name((carom_phase)i), "unknown");
        for (j = 0; j < i; ++j)
            ck_assert_str_ne(carom_phase_name((carom_phase)i),
                             carom_phase_name((carom_phase)j));
    }
    ck_assert_str_eq(carom_op_name(CAROM_OP_ADD), "add");
    ck_assert_str_eq(carom_op_name((carom_op)CAROM_OP_COUNT), "unknown");
    ck_assert_str_eq(carom_op_name((carom_op)-1), "unknown");
    ck_assert_str_eq(carom_phase_name(CAROM_PHASE_BROADPHASE), "broadphase");
    ck_assert_str_eq(carom_phase_name((carom_phase)CAROM_PHASE_COUNT), "unknown");
    ck_assert_str_eq(carom_phase_name((carom_phase)-3), "unknown");
    carom_profile_reset(NULL); /* nothing to clear: no crash */
    ck_assert_int_eq(carom_world_set_profile(NULL, NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_op_weights_preset("seed", NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_op_weights_preset("cortex-m4f", &w), CAROM_OK);
    ck_assert(carom_profile_cost(NULL, &w, CAROM_PHASE_COUNT) == 0.0f);
}
END_TEST

Suite *suite_profile(void)
{
    Suite *s = suite_create("profile");
    TCase *tc = tcase_create("counts");
    tcase_add_test(tc, test_seed_preset_is_the_design_notes_table);
    tcase_add_test(tc, test_cost_is_the_weighted_sum_of_counts);
    tcase_add_test(tc, test_op_and_phase_names_are_distinct_and_bounded);
#if CAROM_ENABLE_PROFILE
    tcase_add_test(tc, test_root_of_linear_and_quadratic_gap_counts);
#else
    tcase_add_test(tc, test_default_build_has_no_profiler);
#endif
    suite_add_tcase(s, tc);
    return s;
}
