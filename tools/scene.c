/*
 * scene.c -- parser of carom scene files. See docs/scene-format.md.
 */
#include "scene.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define SCENE_MAX_LINE 4096
#define SCENE_DEFAULT_STEPS 600L
#define SCENE_MAX_STEPS 1000000000L
#define SCENE_MAX_BYTES (64L << 20)

typedef struct parser {
    const char *name;
    int line;
    char *err;
    size_t errlen;
} parser;

/* s for a message: control bytes (below 0x20, and 0x7f) as \xNN, cut to
 * fit buf; UTF-8 passes as it is */
static const char *printable(const char *s, char *buf, size_t len)
{
    size_t o = 0;
    for (; *s && o + 5 < len; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20u && c != 0x7fu)
            buf[o++] = (char)c;
        else
            o += (size_t)snprintf(buf + o, len - o, "\\x%02x", c);
    }
    if (*s && o + 4 <= len) {
        memcpy(buf + o, "...", 3);
        o += 3;
    }
    buf[o] = '\0';
    return buf;
}

static int fail(parser *p, const char *fmt, ...)
{
    va_list ap;
    char msg[1024];
    int n = snprintf(p->err, p->errlen, "%s:%d: ", p->name, p->line);
    if (n < 0 || (size_t)n >= p->errlen)
        return -1;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* the scene's own text quoted in it: control and other non-printing
     * bytes as \xNN (a vertical tab or form feed printed raw hid itself) */
    printable(msg, p->err + n, p->errlen - (size_t)n);
    return -1;
}

/* A finite float written in full (no trailing junk). */
static int parse_float(parser *p, const char *key, const char *s, float *out)
{
    char *end;
    double d;
    if (*s == '\0')
        return fail(p, "%s: missing number", key);
    if (isspace((unsigned char)*s))
        return fail(p, "%s: malformed number '%s'", key, s);
    errno = 0;
    d = strtod(s, &end);
    if (end == s || *end != '\0')
        return fail(p, "%s: malformed number '%s'", key, s);
    /* underflow to (near) zero is fine; overflow and nan/inf are not */
    if (!isfinite(d) || (errno == ERANGE && fabs(d) >= 1.0) || fabs(d) > 3.0e38)
        return fail(p, "%s: '%s' is not a finite float", key, s);
    *out = (float)d;
    return 0;
}

static int parse_long(parser *p, const char *key, const char *s, long *out)
{
    char *end;
    long v;
    if (*s == '\0')
        return fail(p, "%s: missing integer", key);
    if (isspace((unsigned char)*s))
        return fail(p, "%s: malformed integer '%s'", key, s);
    errno = 0;
    v = strtol(s, &end, 10);
    if (end == s || *end != '\0')
        return fail(p, "%s: malformed integer '%s'", key, s);
    if (errno == ERANGE)
        return fail(p, "%s: '%s' is out of range", key, s);
    *out = v;
    return 0;
}

/* "x,y" */
static int parse_vec(parser *p, const char *key, const char *s, carom_vec2 *out)
{
    char buf[256];
    char *comma;
    size_t n = strlen(s);
    if (n >= sizeof buf)
        return fail(p, "%s: vector too long", key);
    if (n == 0)
        return fail(p, "%s: missing value (want x,y)", key);
    memcpy(buf, s, n + 1);
    comma = strchr(buf, ',');
    if (!comma || strchr(comma + 1, ','))
        return fail(p, "%s: malformed vector '%s' (want x,y)", key, s);
    *comma = '\0';
    if (parse_float(p, key, buf, &out->x) || parse_float(p, key, comma + 1, &out->y))
        return -1;
    return 0;
}

/* "x,y;x,y;..." */
static int parse_vertices(parser *p, const char *s, carom_body_def *d)
{
    char buf[SCENE_MAX_LINE];
    char *tok, *save = NULL;
    int n = 0;
    size_t len = strlen(s);
    if (len >= sizeof buf)
        return fail(p, "vertices: too long");
    memcpy(buf, s, len + 1);
    if (len == 0 || buf[len - 1] == ';' || buf[0] == ';' || strstr(buf, ";;"))
        return fail(p, "vertices: malformed list '%s' (want x,y;x,y;...)", s);
    for (tok = strtok_r(buf, ";", &save); tok; tok = strtok_r(NULL, ";", &save)) {
        if (n >= CAROM_MAX_POLYGON_VERTICES)
            return fail(p, "vertices: more than %d vertices",
                        CAROM_MAX_POLYGON_VERTICES);
        if (parse_vec(p, "vertices", tok, &d->vertices[n]))
            return -1;
        ++n;
    }
    if (n < 3)
        return fail(p, "vertices: a polygon needs at least 3 vertices, got %d", n);
    d->vertex_count = n;
    return 0;
}

/* Split "key=value"; returns 0 and points key/value into tok. */
static int split_kv(parser *p, char *tok, char **key, char **value)
{
    char *eq = strchr(tok, '=');
    if (!eq)
        return fail(p, "expected key=value, got '%s'", tok);
    *eq = '\0';
    *key = tok;
    *value = eq + 1;
    if (**key == '\0')
        return fail(p, "empty key in '=%s'", *value);
    return 0;
}

static int seen_before(parser *p, unsigned *mask, unsigned bit, const char *key)
{
    if (*mask & bit)
        return fail(p, "%s given twice", key);
    *mask |= bit;
    return 0;
}

/* A tolerance: a number >= 0, or "auto" (CAROM_AUTO: derived). */
static int parse_auto(parser *p, const char *key, const char *val, float *out)
{
    if (strcmp(val, "auto") == 0) {
        *out = CAROM_AUTO;
        return 0;
    }
    if (parse_float(p, key, val, out))
        return -1;
    if (*out < 0.0f)
        return fail(p, "%s: must be >= 0 or auto, got %s", key, val);
    return 0;
}

/* The integer keys of the world line: name, field, range. */
typedef struct world_int_key {
    const char *name;
    size_t offset; /* of an int in carom_world_def */
    long lo, hi;
} world_int_key;

static const world_int_key world_int_keys[] = {
    {"substeps", offsetof(carom_world_def, substeps), 1, 64},
    {"max-substeps", offsetof(carom_world_def, max_substeps), 0, 64},
    {"iterations", offsetof(carom_world_def, iterations), 1, 64},
    {"relax-iterations", offsetof(carom_world_def, relax_iterations), 0, 64},
    {"max-pairs", offsetof(carom_world_def, max_pairs), 0, 1L << 26},
    {"max-contacts", offsetof(carom_world_def, max_contacts), 0, 1L << 26},
    {"max-events", offsetof(carom_world_def, max_events), 0, 1L << 26},
    {"max-impacts", offsetof(carom_world_def, max_impacts), 0, 1L << 30},
};

static int parse_world(parser *p, char *rest, scene *s)
{
    char *tok, *save = NULL;
    unsigned seen = 0;
    size_t k;
    for (tok = strtok_r(rest, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        char *key = NULL, *val = NULL;
        if (split_kv(p, tok, &key, &val))
            return -1;
        for (k = 0; k < sizeof world_int_keys / sizeof world_int_keys[0]; ++k)
            if (strcmp(key, world_int_keys[k].name) == 0)
                break;
        if (k < sizeof world_int_keys / sizeof world_int_keys[0]) {
            const world_int_key *wk = &world_int_keys[k];
            long v;
            if (seen_before(p, &seen, 1024u << k, key) || parse_long(p, key, val, &v))
                return -1;
            if (v < wk->lo || v > wk->hi)
                return fail(p, "%s: must be in [%ld, %ld], got %s", key, wk->lo, wk->hi, val);
            *(int *)(void *)((char *)&s->world + wk->offset) = (int)v;
        } else if (strcmp(key, "gravity") == 0) {
            if (seen_before(p, &seen, 1u, key) || parse_vec(p, key, val, &s->world.gravity))
                return -1;
        } else if (strcmp(key, "dt") == 0) {
            if (seen_before(p, &seen, 2u, key) || parse_float(p, key, val, &s->world.dt))
                return -1;
            if (!(s->world.dt > 0.0f))
                return fail(p, "dt: must be > 0, got %s", val);
        } else if (strcmp(key, "steps") == 0) {
            if (seen_before(p, &seen, 4u, key) || parse_long(p, key, val, &s->steps))
                return -1;
            if (s->steps < 0 || s->steps > SCENE_MAX_STEPS)
                return fail(p, "steps: must be in [0, %ld], got %s", SCENE_MAX_STEPS, val);
        } else if (strcmp(key, "method") == 0) {
            if (seen_before(p, &seen, 8u, key))
                return -1;
            if (carom_method_from_name(val, &s->world.method) != CAROM_OK)
                return fail(p, "method: unknown method '%s' (events, discrete, first-impact)", val);
        } else if (strcmp(key, "rest-speed") == 0) {
            if (seen_before(p, &seen, 16u, key) || parse_auto(p, key, val, &s->world.rest_speed))
                return -1;
        } else if (strcmp(key, "slop") == 0) {
            if (seen_before(p, &seen, 32u, key) || parse_auto(p, key, val, &s->world.linear_slop))
                return -1;
        } else if (strcmp(key, "length-unit") == 0) {
            if (seen_before(p, &seen, 64u, key) || parse_auto(p, key, val, &s->world.length_unit))
                return -1;
            if (s->world.length_unit == 0.0f)
                return fail(p, "length-unit: must be > 0 or auto, got %s", val);
        } else if (strcmp(key, "sleep") == 0) {
            if (seen_before(p, &seen, 128u, key))
                return -1;
            if (strcmp(val, "on") == 0)
                s->world.enable_sleep = 1;
            else if (strcmp(val, "off") == 0)
                s->world.enable_sleep = 0;
            else
                return fail(p, "sleep: want on or off, got '%s'", val);
        } else if (strcmp(key, "sleep-time") == 0) {
            if (seen_before(p, &seen, 256u, key) || parse_float(p, key, val, &s->world.sleep_time))
                return -1;
            if (s->world.sleep_time < 0.0f)
                return fail(p, "sleep-time: must be >= 0, got %s", val);
        } else if (strcmp(key, "velocity-iterations") == 0 ||
                   strcmp(key, "position-iterations") == 0) {
            return fail(p, "%s: no longer a setting; the contact solver takes "
                           "substeps=, iterations= and relax-iterations= "
                           "(docs/scene-format.md)", key);
        } else {
            return fail(p, "world: unknown key '%s'", key);
        }
    }
    return 0;
}

enum {
    K_RADIUS = 1u << 0, K_HALF = 1u << 1, K_VERTS = 1u << 2, K_POS = 1u << 3,
    K_ANGLE = 1u << 4, K_VEL = 1u << 5, K_OMEGA = 1u << 6, K_DENSITY = 1u << 7,
    K_MASS = 1u << 8, K_REST = 1u << 9, K_FRIC = 1u << 10, K_FORCE = 1u << 11,
    K_TORQUE = 1u << 12, K_CAT = 1u << 13, K_MASK = 1u << 14, K_GROUP = 1u << 15
};

/* A 32-bit unsigned value, decimal or 0x hex. */
static int parse_bits(parser *p, const char *key, const char *s, uint32_t *out)
{
    char *end;
    unsigned long v;
    int hex = s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
    errno = 0;
    /* base 10 unless 0x: a leading 0 is not octal (010 is ten) */
    v = strtoul(hex ? s + 2 : s, &end, hex ? 16 : 10);
    if (*s == '\0' || (hex && !isxdigit((unsigned char)s[2])) || !isalnum((unsigned char)*s) ||
        *end != '\0' || errno == ERANGE || v > 0xffffffffUL)
        return fail(p, "%s: want a 32-bit unsigned number (decimal or 0x hex), got '%s'", key,
                    s);
    *out = (uint32_t)v;
    return 0;
}

/* Which value of a body definition is outside carom's documented range
 * (carom_config.h CAROM_LIMIT_*), for a message naming it. */
static const char *range_hint(const carom_body_def *d, char *buf, size_t len)
{
    float m = d->mass > 0.0f ? d->mass : 0.0f;
    if (fabsf(d->position.x) > CAROM_LIMIT_MAX_LENGTH ||
        fabsf(d->position.y) > CAROM_LIMIT_MAX_LENGTH)
        snprintf(buf, len, "position beyond %g m (CAROM_LIMIT_MAX_LENGTH)",
                 (double)CAROM_LIMIT_MAX_LENGTH);
    else if (fabsf(d->velocity.x) > CAROM_LIMIT_MAX_SPEED ||
             fabsf(d->velocity.y) > CAROM_LIMIT_MAX_SPEED)
        snprintf(buf, len, "velocity beyond %g m/s (CAROM_LIMIT_MAX_SPEED)",
                 (double)CAROM_LIMIT_MAX_SPEED);
    else if (d->angular_velocity != 0.0f)
        snprintf(buf, len,
                 "angular-velocity times the body's extent beyond %g m/s "
                 "(CAROM_LIMIT_MAX_SPEED), or force/torque over mass beyond %g m/s^2 "
                 "(CAROM_LIMIT_MAX_ACCEL)",
                 (double)CAROM_LIMIT_MAX_SPEED, (double)CAROM_LIMIT_MAX_ACCEL);
    else if (d->force.x != 0.0f || d->force.y != 0.0f || d->torque != 0.0f)
        snprintf(buf, len,
                 "force over mass (or torque over inertia, times the extent) beyond %g m/s^2 "
                 "(CAROM_LIMIT_MAX_ACCEL)%s",
                 (double)CAROM_LIMIT_MAX_ACCEL, m > 0.0f ? "" : "; the mass is from density");
    else
        snprintf(buf, len, "a size beyond [%g, %g] m (CAROM_LIMIT_MIN_SIZE, _MAX_LENGTH)",
                 (double)CAROM_LIMIT_MIN_SIZE, (double)CAROM_LIMIT_MAX_LENGTH);
    return buf;
}

/* A float in the fewest significant digits (6 to 9) that read back as
 * the same float: 10.000001 as itself, not 10 (%g) or 9.99999983e+12 for
 * -1e13 (%.9g). buf: 32 bytes. */
static const char *shortest(float v, char *buf)
{
    int digits;
    for (digits = 6; digits < 9; ++digits) {
        snprintf(buf, 32, "%.*g", digits, (double)v);
        if ((float)strtod(buf, NULL) == v)
            return buf;
    }
    snprintf(buf, 32, "%.9g", (double)v);
    return buf;
}

/* Which world value is outside carom's range, with its scene key and
 * the limit: each tried alone on a default world (1 if found). */
static int world_range_hint(const carom_world_def *wd, char *buf, size_t len)
{
    char a[32], b[32];
    carom_world_def t = carom_default_world_def();
    t.dt = wd->dt;
    if (carom_world_def_validate(&t) != CAROM_OK) {
        snprintf(buf, len, "dt=%s: the time step must be in [%g, %g] s "
                 "(CAROM_LIMIT_MIN_DT, _MAX_DT)", shortest(wd->dt, a),
                 (double)CAROM_LIMIT_MIN_DT, (double)CAROM_LIMIT_MAX_DT);
        return 1;
    }
    t = carom_default_world_def();
    t.gravity = wd->gravity;
    if (carom_world_def_validate(&t) != CAROM_OK) {
        snprintf(buf, len, "gravity=%s,%s: each component must be within %g m/s^2 "
                 "(CAROM_LIMIT_MAX_ACCEL)", shortest(wd->gravity.x, a), shortest(wd->gravity.y, b),
                 (double)CAROM_LIMIT_MAX_ACCEL);
        return 1;
    }
    t = carom_default_world_def();
    t.length_unit = wd->length_unit;
    if (carom_world_def_validate(&t) != CAROM_OK) {
        snprintf(buf, len, "length-unit=%s: must be auto or in [%g, %g] m "
                 "(CAROM_LIMIT_MIN_SIZE, _MAX_LENGTH)", shortest(wd->length_unit, a),
                 (double)CAROM_LIMIT_MIN_SIZE, (double)CAROM_LIMIT_MAX_LENGTH);
        return 1;
    }
    t = carom_default_world_def();
    t.linear_slop = wd->linear_slop;
    if (carom_world_def_validate(&t) != CAROM_OK) {
        snprintf(buf, len, "slop=%s: must be auto or in [0, %g] m (CAROM_LIMIT_MAX_LENGTH)",
                 shortest(wd->linear_slop, a), (double)CAROM_LIMIT_MAX_LENGTH);
        return 1;
    }
    t = carom_default_world_def();
    t.rest_speed = wd->rest_speed;
    if (carom_world_def_validate(&t) != CAROM_OK) {
        snprintf(buf, len, "rest-speed=%s: must be auto or in [0, %g] m/s "
                 "(CAROM_LIMIT_MAX_SPEED)", shortest(wd->rest_speed, a),
                 (double)CAROM_LIMIT_MAX_SPEED);
        return 1;
    }
    return 0;
}

static int parse_body(parser *p, char *rest, scene *s)
{
    char *tok, *save = NULL;
    unsigned seen = 0;
    scene_body sb;
    carom_body_def *d = &sb.def;
    carom_vec2 half = {0.0f, 0.0f};
    carom_status st;
    const char *mass_key = "density", *mass_value = "1 (the default)"; /* for messages */

    memset(&sb, 0, sizeof sb);
    *d = carom_default_body_def();
    sb.line = p->line;

    tok = strtok_r(rest, " \t", &save);
    if (!tok)
        return fail(p, "body: missing shape (circle, box or polygon)");
    if (strcmp(tok, "circle") == 0) {
        sb.kind = "circle";
        d->shape = CAROM_SHAPE_CIRCLE;
    } else if (strcmp(tok, "box") == 0) {
        sb.kind = "box";
        d->shape = CAROM_SHAPE_POLYGON;
    } else if (strcmp(tok, "polygon") == 0) {
        sb.kind = "polygon";
        d->shape = CAROM_SHAPE_POLYGON;
    } else {
        return fail(p, "body: unknown shape '%s' (circle, box or polygon)", tok);
    }

    for (tok = strtok_r(NULL, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        char *key = NULL, *val = NULL;
        if (strcmp(tok, "static") == 0) {
            d->type = CAROM_BODY_STATIC;
            continue;
        }
        if (strcmp(tok, "dynamic") == 0) {
            d->type = CAROM_BODY_DYNAMIC;
            continue;
        }
        if (strcmp(tok, "kinematic") == 0) {
            d->type = CAROM_BODY_KINEMATIC;
            continue;
        }
        if (strcmp(tok, "sensor") == 0) {
            d->is_sensor = 1;
            continue;
        }
        if (split_kv(p, tok, &key, &val))
            return -1;
        if (strcmp(key, "radius") == 0) {
            if (sb.kind[0] != 'c')
                return fail(p, "radius: only circles have a radius");
            if (seen_before(p, &seen, K_RADIUS, key) || parse_float(p, key, val, &d->radius))
                return -1;
            if (!(d->radius > 0.0f))
                return fail(p, "radius: must be > 0, got %s", val);
        } else if (strcmp(key, "half-extents") == 0) {
            if (sb.kind[0] != 'b')
                return fail(p, "half-extents: only boxes have half-extents");
            if (seen_before(p, &seen, K_HALF, key) || parse_vec(p, key, val, &half))
                return -1;
            if (!(half.x > 0.0f) || !(half.y > 0.0f))
                return fail(p, "half-extents: both must be > 0, got %s", val);
        } else if (strcmp(key, "vertices") == 0) {
            if (sb.kind[0] != 'p')
                return fail(p, "vertices: only polygons have vertices");
            if (seen_before(p, &seen, K_VERTS, key) || parse_vertices(p, val, d))
                return -1;
        } else if (strcmp(key, "position") == 0) {
            if (seen_before(p, &seen, K_POS, key) || parse_vec(p, key, val, &d->position))
                return -1;
        } else if (strcmp(key, "angle") == 0) {
            if (seen_before(p, &seen, K_ANGLE, key) || parse_float(p, key, val, &sb.angle))
                return -1;
            if (fabsf(sb.angle) > 1.0e5f)
                return fail(p, "angle: |angle| must be <= 1e5 rad, got %s", val);
        } else if (strcmp(key, "velocity") == 0) {
            if (seen_before(p, &seen, K_VEL, key) || parse_vec(p, key, val, &d->velocity))
                return -1;
        } else if (strcmp(key, "angular-velocity") == 0) {
            if (seen_before(p, &seen, K_OMEGA, key) ||
                parse_float(p, key, val, &d->angular_velocity))
                return -1;
        } else if (strcmp(key, "density") == 0) {
            if (seen_before(p, &seen, K_DENSITY, key) || parse_float(p, key, val, &d->density))
                return -1;
            if (!(d->density > 0.0f))
                return fail(p, "density: must be > 0, got %s", val);
            mass_value = val;
        } else if (strcmp(key, "mass") == 0) {
            if (seen_before(p, &seen, K_MASS, key) || parse_float(p, key, val, &d->mass))
                return -1;
            if (!(d->mass > 0.0f))
                return fail(p, "mass: must be > 0, got %s", val);
            mass_key = "mass";
            mass_value = val;
        } else if (strcmp(key, "restitution") == 0) {
            if (seen_before(p, &seen, K_REST, key) || parse_float(p, key, val, &d->restitution))
                return -1;
            if (!(d->restitution >= 0.0f && d->restitution <= 1.0f))
                return fail(p, "restitution: must be in [0, 1], got %s", val);
        } else if (strcmp(key, "friction") == 0) {
            if (seen_before(p, &seen, K_FRIC, key) || parse_float(p, key, val, &d->friction))
                return -1;
            if (!(d->friction >= 0.0f) || d->friction > CAROM_LIMIT_MAX_FRICTION)
                return fail(p, "friction: must be in [0, %g], got %s",
                            (double)CAROM_LIMIT_MAX_FRICTION, val);
        } else if (strcmp(key, "force") == 0) {
            if (seen_before(p, &seen, K_FORCE, key) || parse_vec(p, key, val, &d->force))
                return -1;
        } else if (strcmp(key, "torque") == 0) {
            if (seen_before(p, &seen, K_TORQUE, key) || parse_float(p, key, val, &d->torque))
                return -1;
        } else if (strcmp(key, "category") == 0) {
            if (seen_before(p, &seen, K_CAT, key) || parse_bits(p, key, val, &d->category_bits))
                return -1;
        } else if (strcmp(key, "mask") == 0) {
            if (seen_before(p, &seen, K_MASK, key) || parse_bits(p, key, val, &d->mask_bits))
                return -1;
        } else if (strcmp(key, "group") == 0) {
            long g;
            if (seen_before(p, &seen, K_GROUP, key) || parse_long(p, key, val, &g))
                return -1;
            if (g < -32768 || g > 32767)
                return fail(p, "group: must be in [-32768, 32767], got %s", val);
            d->group_index = (int)g;
        } else {
            return fail(p, "body: unknown key '%s'", key);
        }
    }
    if ((seen & K_DENSITY) && (seen & K_MASS))
        return fail(p, "give density= or mass=, not both");
    if (sb.kind[0] == 'b') {
        if (!(seen & K_HALF))
            return fail(p, "box: missing half-extents=");
        carom_body_def_set_box(d, half.x, half.y);
    }
    if (sb.kind[0] == 'p' && !(seen & K_VERTS))
        return fail(p, "polygon: missing vertices=");
#if CAROM_ENABLE_ANGLES
    d->rotation = carom_rot_from_angle(sb.angle);
#else
    if (sb.angle != 0.0f)
        return fail(p, "angle=: this carom was built without CAROM_ENABLE_ANGLES "
                       "(give the body no angle, or build with it on)");
#endif
    st = carom_body_def_validate(d);
    if (st == CAROM_ERR_OUT_OF_RANGE) {
        char hint[200];
        return fail(p, "body %d: %s: %s", s->body_count, carom_status_string(st),
                    range_hint(d, hint, sizeof hint));
    }
    /* (mass <= 0 and density <= 0 were refused above: here the mass or
     * the inertia that follows from mass= or density= and the size is out
     * of range; the status string would give the range a second time) */
    if (st == CAROM_ERR_BAD_MASS)
        return fail(p, "body %d: %s=%s: a dynamic body's mass and moment of inertia must be "
                       "in [%g, %g] (kg, kg m^2; CAROM_LIMIT_MIN_MASS, _MAX_MASS)",
                    s->body_count, mass_key, mass_value, (double)CAROM_LIMIT_MIN_MASS,
                    (double)CAROM_LIMIT_MAX_MASS);
    if (st != CAROM_OK)
        return fail(p, "body %d: %s", s->body_count, carom_status_string(st));

    if (s->body_count == s->body_capacity) {
        int cap = s->body_capacity ? 2 * s->body_capacity : 16;
        scene_body *nb = (scene_body *)realloc(s->bodies, (size_t)cap * sizeof *nb);
        if (!nb)
            return fail(p, "out of memory");
        s->bodies = nb;
        s->body_capacity = cap;
    }
    s->bodies[s->body_count++] = sb;
    return 0;
}

int scene_parse(const char *name, const char *text, scene *s, char *err,
                size_t errlen)
{
    parser p;
    const char *cur = text;
    int have_header = 0, have_world = 0;
    char line[SCENE_MAX_LINE];

    memset(s, 0, sizeof *s);
    s->world = carom_default_world_def();
    s->steps = SCENE_DEFAULT_STEPS;
    p.name = name;
    p.line = 0;
    p.err = err;
    p.errlen = errlen;

    while (*cur) {
        /* a line ends at LF, CR LF or a lone CR (old Mac files) */
        size_t len = strcspn(cur, "\r\n");
        char *hash, *start, *end, *word, *rest;
        ++p.line;
        if (len >= sizeof line) {
            fail(&p, "line longer than %d characters", SCENE_MAX_LINE - 1);
            goto error;
        }
        memcpy(line, cur, len);
        line[len] = '\0';
        cur += len;
        if (cur[0] == '\r' && cur[1] == '\n')
            cur += 2;
        else if (*cur != '\0')
            ++cur;

        hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        for (start = line; *start && isspace((unsigned char)*start); ++start) {}
        end = start + strlen(start);
        while (end > start && isspace((unsigned char)end[-1]))
            *--end = '\0';
        if (*start == '\0')
            continue;
        for (word = start; *word; ++word)
            if (*word == '\t')
                *word = ' ';
        word = start;
        rest = strchr(start, ' ');
        if (rest)
            *rest++ = '\0';
        else
            rest = start + strlen(start);

        if (!have_header) {
            char *extra;
            if (strcmp(word, "carom-scene") != 0) {
                fail(&p, "expected header 'carom-scene 1', got '%s'", word);
                goto error;
            }
            while (*rest == ' ')
                ++rest;
            extra = strchr(rest, ' ');
            if (extra) {
                *extra++ = '\0';
                while (*extra == ' ')
                    ++extra;
            }
            if (*rest == '\0') {
                fail(&p, "the header line has no version (want 'carom-scene 1')");
                goto error;
            }
            if (strcmp(rest, "1") != 0) {
                fail(&p, "unsupported scene version '%s' (this reader knows 1)", rest);
                goto error;
            }
            if (extra) {
                fail(&p, "the header line has trailing text after the version: '%s' "
                         "(want 'carom-scene 1' alone)", extra);
                goto error;
            }
            have_header = 1;
        } else if (strcmp(word, "world") == 0) {
            if (have_world) {
                fail(&p, "second world line");
                goto error;
            }
            if (s->body_count > 0) {
                fail(&p, "the world line must come before the bodies");
                goto error;
            }
            have_world = 1;
            if (parse_world(&p, rest, s))
                goto error;
        } else if (strcmp(word, "body") == 0) {
            if (parse_body(&p, rest, s))
                goto error;
        } else {
            fail(&p, "unknown line type '%s' (world, body)", word);
            goto error;
        }
    }
    if (!have_header) {
        p.line = p.line > 0 ? p.line : 1;
        fail(&p, "empty scene: missing header 'carom-scene 1'");
        goto error;
    }
    return 0;
error:
    scene_free(s);
    return -1;
}

/* Read all of f (a file, a pipe or a terminal: no seeking) into a fresh
 * NUL-terminated buffer; *len gets its length. NULL with a message in err
 * on a read error, past SCENE_MAX_BYTES or out of memory. */
static char *read_all(FILE *f, const char *name, size_t *len, char *err,
                      size_t errlen)
{
    size_t cap = 65536, n = 0;
    char *text = (char *)malloc(cap + 1);
    while (text) {
        size_t got = fread(text + n, 1, cap - n, f);
        n += got;
        if (n > (size_t)SCENE_MAX_BYTES) {
            snprintf(err, errlen, "%s: larger than %ld bytes", name, SCENE_MAX_BYTES);
            free(text);
            return NULL;
        }
        if (got == 0)
            break;
        if (n == cap) {
            char *bigger = (char *)realloc(text, 2 * cap + 1);
            if (!bigger)
                break;
            text = bigger;
            cap *= 2;
        }
    }
    if (!text || n == cap) {
        snprintf(err, errlen, "%s: out of memory", name);
        free(text);
        return NULL;
    }
    if (ferror(f)) {
        snprintf(err, errlen, "%s: read error: %s", name, strerror(errno));
        free(text);
        return NULL;
    }
    text[n] = '\0';
    *len = n;
    return text;
}

int scene_load_stream(FILE *f, const char *name, scene *s, char *err,
                      size_t errlen)
{
    size_t len;
    const unsigned char *u;
    char *text;
    int rc;
    memset(s, 0, sizeof *s);
    text = read_all(f, name, &len, err, errlen);
    if (!text)
        return -1;
    u = (const unsigned char *)text;
    if (len >= 2 && ((u[0] == 0xFF && u[1] == 0xFE) || (u[0] == 0xFE && u[1] == 0xFF))) {
        snprintf(err, errlen, "%s: UTF-16 text; save the scene as UTF-8 or ASCII", name);
        free(text);
        return -1;
    }
    if (strlen(text) != len) {
        snprintf(err, errlen, "%s: contains a NUL byte (not a text file?)", name);
        free(text);
        return -1;
    }
    /* a UTF-8 byte-order mark is how some editors start a file, not part of
     * the format; line ends (LF, CR LF, CR) are scene_parse's */
    rc = scene_parse(name, len >= 3 && u[0] == 0xEF && u[1] == 0xBB && u[2] == 0xBF
                               ? text + 3 : text,
                     s, err, errlen);
    free(text);
    return rc;
}

int scene_load(const char *path, scene *s, char *err, size_t errlen)
{
    struct stat st;
    FILE *f;
    int rc;
    memset(s, 0, sizeof *s);
    f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    /* fopen opens a directory for reading on POSIX; say what it is */
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: is a directory, not a scene file", path);
        fclose(f);
        return -1;
    }
    rc = scene_load_stream(f, path, s, err, errlen);
    fclose(f);
    return rc;
}

void scene_free(scene *s)
{
    free(s->bodies);
    s->bodies = NULL;
    s->body_count = s->body_capacity = 0;
}

#if CAROM_ENABLE_GROW
static void *scene_grow_alloc(void *user, size_t bytes)
{
    (void)user;
    return malloc(bytes);
}

static void scene_grow_release(void *user, void *block)
{
    (void)user;
    free(block);
}
#endif

void scene_free_world(carom_world *w, void *mem)
{
    if (w)
        (void)carom_world_release(w);
    free(mem);
}

int scene_build_world(const scene *s, carom_world **w, void **mem, char *err,
                      size_t errlen)
{
    carom_world_def wd = s->world;
    size_t bytes;
    carom_status st;
    int i;
    wd.max_bodies = s->body_count > 0 ? s->body_count : 1;
#if CAROM_ENABLE_GROW
    if (wd.max_pairs == 0 && wd.max_contacts == 0) {
        wd.grow.alloc = scene_grow_alloc;
        wd.grow.release = scene_grow_release;
        wd.grow.user = NULL;
    }
#endif
    st = carom_world_def_validate(&wd);
    if (st == CAROM_ERR_DISABLED) {
        /* name the switch: the status name may be compiled out */
        const char *sw = !CAROM_ENABLE_DISCRETE && wd.method == CAROM_METHOD_DISCRETE
                             ? "CAROM_ENABLE_DISCRETE"
                             : !CAROM_ENABLE_EVENTS && wd.method != CAROM_METHOD_DISCRETE
                                   ? "CAROM_ENABLE_EVENTS"
                                   : NULL;
        if (sw) {
            snprintf(err, errlen, "world: method=%s: this carom was built without %s",
                     carom_method_name(wd.method), sw);
            return -1;
        }
    }
    if (st != CAROM_OK) {
        char hint[160];
        if (world_range_hint(&wd, hint, sizeof hint))
            snprintf(err, errlen, "world: %s", hint);
        else
            snprintf(err, errlen, "world: %s", carom_status_string(st));
        return -1;
    }
    bytes = carom_world_buffer_size(&wd);
    *mem = malloc(bytes ? bytes : 1);
    if (!*mem) {
        snprintf(err, errlen, "out of memory (%zu bytes)", bytes);
        return -1;
    }
    st = carom_world_init(w, &wd, *mem, bytes);
    for (i = 0; st == CAROM_OK && i < s->body_count; ++i) {
        st = carom_world_add_body(*w, &s->bodies[i].def, NULL);
        if (st != CAROM_OK) {
            snprintf(err, errlen, "line %d: body %d: %s", s->bodies[i].line, i,
                     carom_status_string(st));
            free(*mem);
            *mem = NULL;
            return -1;
        }
    }
    if (st != CAROM_OK) {
        snprintf(err, errlen, "world: %s", carom_status_string(st));
        free(*mem);
        *mem = NULL;
        return -1;
    }
    return 0;
}

float scene_rot_angle(carom_rot r)
{
#if CAROM_ENABLE_ANGLES
    return carom_rot_angle(r);
#else
    return (float)atan2((double)r.s, (double)r.c);
#endif
}
