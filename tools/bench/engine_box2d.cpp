/*
 * engine_box2d.cpp -- Box2D 2.4.1 (Debian's libbox2d-dev) as a benchmark
 * engine (tools/bench/bench.h). The world is made as tools/carom_box2d.cpp
 * makes it: the scene's gravity, shapes, densities, restitution (mixed by
 * max), friction (mixed by sqrt), velocities; 8 velocity and 3 position
 * iterations (Box2D's recommended counts); restitution threshold from the
 * scene (Box2D's 1 m/s when the scene leaves it); sleeping as configured.
 */
#include <box2d/box2d.h>

#include <cstdio>
#include <cstring>
#include <malloc.h>
#include <new>
#include <vector>

#include "bench.h"

namespace {

long heap_in_use()
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    struct mallinfo2 mi = mallinfo2();
    return (long)(mi.uordblks + mi.hblkhd);
#else
    return -1;
#endif
}

struct b2_bench_world {
    b2World *world;
    std::vector<b2Body *> bodies;
    float dt;
    long heap0;
};

void *b2_make(const bench_scene *s, const bench_config *c, int, char *err, size_t errlen)
{
    b2_bench_world *bw = new (std::nothrow) b2_bench_world;
    if (!bw) {
        std::snprintf(err, errlen, "out of memory");
        return nullptr;
    }
    bw->heap0 = heap_in_use();
    bw->dt = s->dt;
    bw->world = new b2World(b2Vec2(s->gx, s->gy));
    bw->world->SetAllowSleeping(c && c->sleep);
    bw->bodies.reserve((size_t)s->body_count);
    for (int i = 0; i < s->body_count; ++i) {
        const bench_body &b = s->bodies[i];
        b2BodyDef bd;
        bd.type = b.is_static ? b2_staticBody : b2_dynamicBody;
        bd.position.Set(b.x, b.y);
        bd.linearVelocity.Set(b.vx, b.vy);
        bd.allowSleep = c && c->sleep;
        b2Body *body = bw->world->CreateBody(&bd);
        b2FixtureDef fd;
        b2PolygonShape box;
        b2CircleShape circle;
        if (b.is_box) {
            box.SetAsBox(b.hx, b.hy);
            fd.shape = &box;
        } else {
            circle.m_radius = b.radius;
            fd.shape = &circle;
        }
        fd.density = b.is_static ? 0.0f : b.density;
        fd.friction = b.friction;
        fd.restitution = b.restitution;
        if (s->b2_threshold >= 0.0f)
            fd.restitutionThreshold = s->b2_threshold;
        body->CreateFixture(&fd);
        bw->bodies.push_back(body);
    }
    return bw;
}

int b2_step(void *world, char *, size_t)
{
    b2_bench_world *bw = static_cast<b2_bench_world *>(world);
    bw->world->Step(bw->dt, 8, 3);
    return 0;
}

void b2_info(void *world, bench_info *out)
{
    b2_bench_world *bw = static_cast<b2_bench_world *>(world);
    std::memset(out, 0, sizeof *out);
    out->impacts = -1;
    out->buffer_bytes = -1;
    int awake = 0;
    for (b2Body *b : bw->bodies)
        if (b->GetType() == b2_dynamicBody && b->IsAwake())
            ++awake;
    out->awake = awake;
    out->contacts = bw->world->GetContactCount();
    long h = heap_in_use();
    out->heap_bytes = h >= 0 && bw->heap0 >= 0 ? h - bw->heap0 : -1;
}

void b2_destroy(void *world)
{
    b2_bench_world *bw = static_cast<b2_bench_world *>(world);
    if (!bw)
        return;
    delete bw->world;
    delete bw;
}

} // namespace

extern "C" {
const bench_engine bench_box2d = { "box2d", -1, b2_make, b2_step, b2_info, b2_destroy };
int bench_box2d_available(void) { return 1; }
}
