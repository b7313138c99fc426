/*
 * status.c -- names of statuses and methods.
 */
#include <string.h>

#include "internal.h"

static const char *const cr_status_names[CAROM_STATUS_COUNT] = {
    "ok",
    "null pointer",
    "not finite (NaN or infinity)",
    "time step must be > 0",
    "capacity must be > 0 and fit in memory",
    "buffer too small",
    "bad parameter (rest speed or slop < 0, or iterations outside 0..1000)",
    "unknown method",
    "bad body type",
    "bad shape type",
    "radius must be > 0, with an area that fits a float",
    "density must be > 0",
    "mass must be >= 0 (0: from density), with mass and inertia that fit a float",
    "restitution must be in [0, 1]",
    "friction must be >= 0",
    "rotation must be a non-zero (cos, sin) pair",
    "polygon needs at least 3 vertices",
    "polygon has more than CAROM_MAX_POLYGON_VERTICES vertices",
    "degenerate polygon (repeated or collinear vertices, or no area)",
    "self-intersecting polygon",
    "polygon is not convex",
    "world is full (max_bodies)",
    "no such body",
    "more touching pairs than max_pairs",
    "more impacts in one step than max_events",
    "capability compiled out (see carom_config.h)",
};

const char *carom_status_string(carom_status status)
{
    if ((unsigned)status >= (unsigned)CAROM_STATUS_COUNT)
        return "unknown status";
    return cr_status_names[status];
}

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
