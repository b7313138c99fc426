/*
 * test_status.c -- the names of methods (src/status.c) at and past
 * their ends, and the refusal of a missing output.
 */
#include <string.h>

#include "test_util.h"

Suite *suite_status(void);

START_TEST(test_every_method_name_round_trips_and_others_are_unknown)
{
    int i;
    for (i = 0; i < CAROM_METHOD_COUNT; ++i) {
        carom_method m = (carom_method)-1;
        const char *name = carom_method_name((carom_method)i);
        ck_assert_str_ne(name, "unknown");
        ck_assert_int_eq(carom_method_from_name(name, &m), CAROM_OK);
        ck_assert_int_eq(m, i);
    }
    ck_assert_str_eq(carom_method_name((carom_method)CAROM_METHOD_COUNT), "unknown");
    ck_assert_str_eq(carom_method_name((carom_method)-1), "unknown");
    ck_assert_int_eq(carom_method_from_name("events", NULL), CAROM_ERR_NULL);
    ck_assert_int_eq(carom_method_from_name("Events", &(carom_method){CAROM_METHOD_EVENTS}),
                     CAROM_ERR_BAD_METHOD);
    ck_assert_int_eq(carom_method_from_name("", &(carom_method){CAROM_METHOD_EVENTS}),
                     CAROM_ERR_BAD_METHOD);
}
END_TEST

Suite *suite_status(void)
{
    Suite *s = suite_create("status");
    TCase *tc = tcase_create("names");
    tcase_add_test(tc, test_every_method_name_round_trips_and_others_are_unknown);
    suite_add_tcase(s, tc);
    return s;
}
