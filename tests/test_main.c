/*
 * test_main.c -- runs every unit-test suite (Check). Exit status is
 * non-zero if any test fails. CK_RUN_SUITE / CK_RUN_CASE select a subset.
 */
#include "test_util.h"

int main(void)
{
    SRunner *sr = srunner_create(suite_trig());
    int failed;
    srunner_add_suite(sr, suite_shape());
    srunner_add_suite(sr, suite_integrate());
    srunner_add_suite(sr, suite_broadphase());
    srunner_add_suite(sr, suite_narrowphase());
    srunner_add_suite(sr, suite_solver());
    srunner_add_suite(sr, suite_toi());
    srunner_add_suite(sr, suite_events());
    srunner_add_suite(sr, suite_world());
    srunner_add_suite(sr, suite_island());
    srunner_add_suite(sr, suite_continuous());
    srunner_add_suite(sr, suite_profile());
    srunner_add_suite(sr, suite_scene());
    srunner_add_suite(sr, suite_robust());
    srunner_add_suite(sr, suite_api());
    srunner_add_suite(sr, suite_contact());
    srunner_add_suite(sr, suite_status());
    srunner_add_suite(sr, suite_kinematic());
    srunner_add_suite(sr, suite_world_def());
    srunner_run_all(sr, CK_NORMAL);
    failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
