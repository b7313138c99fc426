/*
 * test_world_def.c -- the world definition's validation field by field,
 * with the statuses carom.h documents for each, and the version string.
 */
#include <stdio.h>
#include <string.h>

#include "test_util.h"

Suite *suite_world_def(void);

/* Every float field is checked for NaN and infinity; every capacity and
 * count against its range; lengths and speeds against the CAROM_LIMIT_*
 * of carom_config.h (CAROM_AUTO, negative, stays allowed). A refused
 * definition has no buffer size. */
START_TEST(test_every_world_field_out_of_its_range_gets_its_status)
{
    carom_world_def d;
#define EXPECT(stmt, status)                                                   \
    d = carom_default_world_def();                                             \
    stmt;                                                                      \
    ck_assert_msg(carom_world_def_validate(&d) == (status), "%s: %s, expected %s", \
                  #stmt, carom_status_string(carom_world_def_validate(&d)),     \
                  carom_status_string(status));                                \
    ck_assert((carom_world_buffer_size(&d) > 0) == ((status) == CAROM_OK))
    EXPECT(d.gravity.x = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(d.gravity.x = -INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(d.rest_speed = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(d.linear_slop = INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(d.length_unit = NAN, CAROM_ERR_NOT_FINITE);
    EXPECT(d.sleep_time = INFINITY, CAROM_ERR_NOT_FINITE);
    EXPECT(d.dt = 2.0f * CAROM_LIMIT_MAX_DT, CAROM_ERR_BAD_DT);
    EXPECT(d.dt = 0.5f * CAROM_LIMIT_MIN_DT, CAROM_ERR_BAD_DT);
    EXPECT(d.gravity.x = 2.0f * CAROM_LIMIT_MAX_ACCEL, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(d.max_pairs = (1 << 30), CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_contacts = (1 << 30), CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_events = (1 << 30), CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_impacts = -1, CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_touch_events = -1, CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_touch_events = (1 << 30), CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.max_bodies = -3, CAROM_ERR_BAD_CAPACITY);
    EXPECT(d.iterations = 1000, CAROM_ERR_BAD_PARAMETER);
    EXPECT(d.relax_iterations = 1000, CAROM_ERR_BAD_PARAMETER);
    EXPECT(d.substeps = -1, CAROM_ERR_BAD_PARAMETER);
    EXPECT(d.length_unit = 2.0f * CAROM_LIMIT_MAX_LENGTH, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(d.linear_slop = 2.0f * CAROM_LIMIT_MAX_LENGTH, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(d.rest_speed = 2.0f * CAROM_LIMIT_MAX_SPEED, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(d.length_unit = 0.0f, CAROM_ERR_OUT_OF_RANGE);
    EXPECT(d.method = (carom_method)-1, CAROM_ERR_BAD_METHOD);
    /* within range, and CAROM_AUTO */
    EXPECT((d.length_unit = 2.0f, d.linear_slop = 0.01f, d.rest_speed = 0.5f), CAROM_OK);
    EXPECT((d.length_unit = CAROM_AUTO, d.linear_slop = CAROM_AUTO), CAROM_OK);
    EXPECT((d.dt = CAROM_LIMIT_MIN_DT, d.iterations = 64, d.substeps = 64), CAROM_OK);
    EXPECT(d.dt = CAROM_LIMIT_MAX_DT, CAROM_OK);
#undef EXPECT
    ck_assert_uint_eq(carom_world_buffer_size(NULL), 0);
}
END_TEST

/* The library is the one these headers describe: "MAJOR.MINOR.PATCH". */
START_TEST(test_version_string_is_the_headers_version)
{
    char expected[64];
    snprintf(expected, sizeof expected, "%d.%d.%d", CAROM_VERSION_MAJOR,
             CAROM_VERSION_MINOR, CAROM_VERSION_PATCH);
    ck_assert_ptr_nonnull(carom_version());
    ck_assert_str_eq(carom_version(), expected);
}
END_TEST

Suite *suite_world_def(void)
{
    Suite *s = suite_create("world_def");
    TCase *tc = tcase_create("definition");
    tcase_add_test(tc, test_every_world_field_out_of_its_range_gets_its_status);
    tcase_add_test(tc, test_version_string_is_the_headers_version);
    suite_add_tcase(s, tc);
    return s;
}
