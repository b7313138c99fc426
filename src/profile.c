/*
 * profile.c -- the op counters of the profiling build (CAROM_ENABLE_PROFILE).
 *
 * The default build compiles this file to nothing: the arithmetic layer
 * then has no counter to touch.
 */
#include "internal.h"

#if CAROM_ENABLE_PROFILE
uint64_t *carom__op_row = 0;
#else
/* ISO C forbids an empty translation unit */
typedef int cr_profile_disabled;
#endif
