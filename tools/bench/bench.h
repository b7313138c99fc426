/*
 * bench.h -- the benchmark driver's scenes and engines (tools/bench/).
 *
 * A scene is generated here (scenes.c), never read from a file, so every
 * engine gets the same bodies: the same positions, sizes, velocities,
 * densities, restitutions and frictions, as floats. An engine (carom with
 * one of its methods, Box2D 2.4.1, Box2D v3) builds its own world from a
 * scene, steps it, and reports what it can (awake bodies, impacts, memory).
 *
 * A tool, not part of the core: it allocates, and uses POSIX and libm.
 */
#ifndef CAROM_BENCH_H
#define CAROM_BENCH_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- scenes -------------------------------------------------------------- */

typedef enum bench_kind {
    BENCH_GAS = 0,  /* elastic gas: circles in a closed box, no gravity */
    BENCH_PILE = 1  /* circles and boxes dropped into a container */
} bench_kind;

typedef struct bench_body {
    int is_static;
    int is_box;            /* 1: box of half extents hx, hy; 0: circle */
    float hx, hy, radius;  /* m */
    float x, y;            /* position of the body origin (= centroid), m */
    float vx, vy;          /* m/s */
    float density;         /* kg/m^2 (dynamic bodies) */
    float restitution, friction;
} bench_body;

typedef struct bench_scene {
    bench_kind kind;
    int n;                 /* dynamic bodies */
    int body_count;        /* n + the static walls */
    bench_body *bodies;    /* walls first */
    float gx, gy, dt;
    /* carom's world rest_speed: a value, or < 0 for CAROM_AUTO */
    float rest_speed;
    /* Box2D's restitution threshold, m/s (< 0: Box2D's default) */
    float b2_threshold;
} bench_scene;

/* Build the scene of kind with n dynamic bodies (deterministic). Returns 0,
 * or -1 (out of memory, or n outside [1, 10^6]). */
int bench_scene_make(bench_scene *s, bench_kind kind, int n);
void bench_scene_free(bench_scene *s);
const char *bench_kind_name(bench_kind kind);
int bench_kind_from_name(const char *name, bench_kind *out);
/* Write the scene as a carom scene file (docs/scene-format.md). */
int bench_scene_write(const bench_scene *s, const char *path);

/* ---- engines ------------------------------------------------------------- */

/* How a world is made. */
typedef struct bench_config {
    int sleep;             /* let bodies sleep */
    int substeps;          /* Box2D v3 substeps (4) */
    /* carom capacities, 0 = default; set after a capacity failure */
    int max_pairs, max_contacts, max_impacts, max_events;
} bench_config;

/* What an engine can say about its world; -1 where it cannot. */
typedef struct bench_info {
    long impacts;          /* carom: stats.impacts since the start */
    int awake;             /* awake dynamic bodies */
    int contacts;          /* touching pairs (carom: stats.contacts) */
    long heap_bytes;       /* Box2D: bytes allocated (v3: its own count;
                              2.4.1: malloc in use, from mallinfo2) */
    /* carom */
    long buffer_bytes;     /* carom_world_buffer_size of the world made */
    int max_pairs_used, max_contacts_used, max_impacts_used;
    long budget_steps;
    int cap_pairs, cap_contacts, cap_impacts, cap_events; /* resolved */
} bench_info;

typedef struct bench_engine {
    const char *name;      /* "events", "discrete", "first-impact",
                              "box2d", "box2d-v3" */
    int method;            /* carom: carom_method; else -1 */
    /* NULL on failure, with a message in err */
    void *(*make)(const bench_scene *s, const bench_config *c, int method,
                  char *err, size_t errlen);
    /* 0, or -1 with a message in err (the world is then unusable) */
    int (*step)(void *world, char *err, size_t errlen);
    void (*info)(void *world, bench_info *out);
    void (*destroy)(void *world);
} bench_engine;

/* engine_carom.c: the carom methods; status of the last failed step */
extern const bench_engine bench_carom_events, bench_carom_discrete,
    bench_carom_first_impact;
int bench_carom_last_status(void *world);
/* attach a carom_profile (0), or -1 if this library counts nothing */
int bench_carom_attach_profile(void *world, void *profile);
/* carom's world memory for a scene: capacities as given (0 = default) */
long bench_carom_buffer_size(const bench_scene *s, int max_pairs,
                             int max_contacts, int max_impacts,
                             int max_events);
int bench_carom_is_capacity_error(int status);

/* engine_box2d.cpp (Box2D 2.4.1), engine_box2d_v3.c (when built) */
extern const bench_engine bench_box2d;
extern const bench_engine bench_box2d_v3;
/* 1 if the engine was compiled in */
int bench_box2d_available(void);
int bench_box2d_v3_available(void);
const char *bench_box2d_v3_version(void);

#ifdef __cplusplus
}
#endif

#endif
