/*
 * engine_box2d_v3.c -- Box2D v3 (upstream erincatto/box2d, built outside
 * the project: tools/box2d_v3/BUILDING.md) as a benchmark engine
 * (tools/bench/bench.h). The world is made as tools/box2d_v3/
 * carom_box2d_v3.c makes it: one worker and no task system (single
 * threaded), the scene's gravity, shapes (polygons without rounding),
 * densities, restitution, friction, velocities; 4 substeps unless
 * configured; restitution threshold from the scene (Box2D's 1 m/s when the
 * scene leaves it); sleeping as configured.
 *
 * Compiled as C17 with -DNDEBUG (tools/bench/bench.mk), only when Box2D v3
 * is given (B2V3_DIR); otherwise engine_none_v3.c stands in.
 */
#include <box2d/box2d.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

typedef struct v3_world {
    b2WorldId world;
    float dt;
    int substeps;
} v3_world;

static void *v3_make(const bench_scene *s, const bench_config *c, int method, char *err,
                     size_t errlen)
{
    v3_world *vw = (v3_world *)calloc(1, sizeof *vw);
    b2WorldDef wd;
    int i;
    (void)method;
    if (!vw) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    wd = b2DefaultWorldDef();
    wd.gravity.x = s->gx;
    wd.gravity.y = s->gy;
    if (s->b2_threshold >= 0.0f)
        wd.restitutionThreshold = s->b2_threshold;
    wd.enableSleep = c && c->sleep;
    wd.workerCount = 1;
    wd.enqueueTask = NULL;
    wd.finishTask = NULL;
    vw->world = b2CreateWorld(&wd);
    vw->dt = s->dt;
    vw->substeps = c && c->substeps > 0 ? c->substeps : 4;
    if (!b2World_IsValid(vw->world)) {
        snprintf(err, errlen, "b2CreateWorld failed");
        free(vw);
        return NULL;
    }
    for (i = 0; i < s->body_count; ++i) {
        const bench_body *b = &s->bodies[i];
        b2BodyDef bd = b2DefaultBodyDef();
        b2ShapeDef sd = b2DefaultShapeDef();
        b2BodyId id;
        bd.type = b->is_static ? b2_staticBody : b2_dynamicBody;
        bd.position.x = b->x;
        bd.position.y = b->y;
        bd.linearVelocity.x = b->vx;
        bd.linearVelocity.y = b->vy;
        bd.enableSleep = c && c->sleep;
        sd.density = b->is_static ? 0.0f : b->density;
        sd.material.friction = b->friction;
        sd.material.restitution = b->restitution;
        id = b2CreateBody(vw->world, &bd);
        if (b->is_box) {
            b2Polygon p = b2MakeBox(b->hx, b->hy);
            b2CreatePolygonShape(id, &sd, &p);
        } else {
            b2Circle circle;
            circle.center.x = 0.0f;
            circle.center.y = 0.0f;
            circle.radius = b->radius;
            b2CreateCircleShape(id, &sd, &circle);
        }
    }
    return vw;
}

static int v3_step(void *world, char *err, size_t errlen)
{
    v3_world *vw = (v3_world *)world;
    (void)err;
    (void)errlen;
    b2World_Step(vw->world, vw->dt, vw->substeps);
    return 0;
}

static void v3_info(void *world, bench_info *out)
{
    v3_world *vw = (v3_world *)world;
    b2Counters k = b2World_GetCounters(vw->world);
    memset(out, 0, sizeof *out);
    out->impacts = -1;
    out->buffer_bytes = -1;
    out->awake = b2World_GetAwakeBodyCount(vw->world);
    out->contacts = k.contactCount;
    out->heap_bytes = (long)k.byteCount;
}

static void v3_destroy(void *world)
{
    v3_world *vw = (v3_world *)world;
    if (!vw)
        return;
    b2DestroyWorld(vw->world);
    free(vw);
}

const bench_engine bench_box2d_v3 = { "box2d-v3", -1, v3_make, v3_step, v3_info, v3_destroy };

int bench_box2d_v3_available(void)
{
    return 1;
}

const char *bench_box2d_v3_version(void)
{
    static char v[32];
    b2Version ver = b2GetVersion();
    snprintf(v, sizeof v, "%d.%d.%d", ver.major, ver.minor, ver.revision);
    return v;
}
