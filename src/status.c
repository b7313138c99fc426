/*
 * status.c -- names of statuses and methods.
 */
#include <string.h>

#include "carom.h"

#if CAROM_ENABLE_STATUS_NAMES
static const char *const cr_status_names[CAROM_STATUS_COUNT] = {
    "ok",
    "null pointer",
    "not finite (NaN or infinity)",
    "time step outside [CAROM_LIMIT_MIN_DT, CAROM_LIMIT_MAX_DT]",
    "capacity out of range: negative, 0 where one is needed, or too large for memory",
    "buffer too small",
    "bad parameter (substeps or iterations outside 1..64, max substeps or "
    "relax 0..64, sleep time < 0, grow alloc without release or the reverse)",
    "unknown method",
    "bad body type",
    "bad shape type",
    "radius outside [CAROM_LIMIT_MIN_SIZE, CAROM_LIMIT_MAX_LENGTH]",
    "density must be > 0",
    "mass must be >= 0 (0: from density), with mass and inertia in "
    "[CAROM_LIMIT_MIN_MASS, CAROM_LIMIT_MAX_MASS]",
    "restitution must be in [0, 1]",
    "friction must be >= 0 and <= CAROM_LIMIT_MAX_FRICTION (1e6)",
    "rotation must be a (cos, sin) pair of length about 1 (c^2 + s^2 between FLT_MIN and FLT_MAX)",
    "polygon needs at least 3 vertices",
    "polygon has more than CAROM_MAX_POLYGON_VERTICES vertices",
    "degenerate polygon (repeated or collinear vertices, no area, or "
    "thinner than CAROM_LIMIT_MIN_SIZE)",
    "self-intersecting polygon",
    "polygon is not convex",
    "world is full (max_bodies)",
    "no such body",
    "more candidate or touching pairs than max_pairs",
    "more contacts than max_contacts",
    "capability compiled out (see carom_config.h)",
    "value outside carom's range (carom_config.h CAROM_LIMIT_*)",
    "stale body id (that body was removed)",
};

const char *carom_status_string(carom_status status)
{
    if ((unsigned)status >= (unsigned)CAROM_STATUS_COUNT)
        return "unknown status";
    return cr_status_names[status];
}
#else
const char *carom_status_string(carom_status status)
{
    /* names compiled out: the number is in carom.h's carom_status */
    return status == CAROM_OK ? "ok" : "carom error (CAROM_ENABLE_STATUS_NAMES is 0)";
}
#endif

static const char *const cr_method_names[CAROM_METHOD_COUNT] = {
    "discrete",
    "events",
    "first-impact",
};

const char *carom_method_name(carom_method method)
{
    if ((unsigned)method >= (unsigned)CAROM_METHOD_COUNT)
        return "unknown";
    return cr_method_names[method];
}

carom_status carom_method_from_name(const char *name, carom_method *out)
{
    int i;
    if (!name || !out)
        return CAROM_ERR_NULL;
    for (i = 0; i < CAROM_METHOD_COUNT; ++i) {
        if (strcmp(name, cr_method_names[i]) == 0) {
            *out = (carom_method)i;
            return CAROM_OK;
        }
    }
    return CAROM_ERR_BAD_METHOD;
}
