/*
 * suite.h -- the embedded scene suite (tools/embedded/README.md).
 *
 * One runner, three hosts: the x86-64 program (host_main.c), the
 * semihosting firmware (fw_main.c) and the generator that writes the
 * suite's data (gen_suite.c). The data (build/embedded/suite_data.c) is
 * generated from the scene files listed in tools/embedded/suite.list, so
 * every target steps exactly the same bodies.
 */
#ifndef CAROM_EMBEDDED_SUITE_H
#define CAROM_EMBEDDED_SUITE_H

#include <stddef.h>
#include <stdint.h>

#include "carom.h"

/* Scene flag: part of the reduced suite (boards with little RAM). */
#define SUITE_SMALL 1

/* Most bodies a suite scene may have (ids are kept in a fixed array). */
#define SUITE_MAX_BODIES 64

/* One body as the scene file gave it. The rotation is rebuilt on every
 * target from the angle with carom_rot_from_angle(), so the library's own
 * trigonometry is part of what is compared. */
typedef struct suite_body {
    int type, shape, vertex_count;
    float radius, angle;
    float px, py, vx, vy, w;
    float density, mass, restitution, friction;
    float fx, fy, torque;
    const float *vertices; /* 2 * vertex_count floats (x, y), or NULL */
} suite_body;

typedef struct suite_scene {
    const char *name;
    int flags;   /* SUITE_SMALL */
    long steps;
    float gx, gy, dt, length_unit, rest_speed, linear_slop, sleep_time;
    int substeps, iterations, relax_iterations, enable_sleep;
    /* Capacities: the most the host measured over both methods, plus a
     * margin (gen_suite.c); the same on every target. */
    int max_pairs, max_contacts, max_events, max_impacts;
    int body_count;
    const suite_body *bodies;
} suite_scene;

/* The generated data. */
extern const suite_scene suite_scenes[];
extern const int suite_scene_count;

/* Body and world definitions of a suite scene (identical on every target). */
void suite_body_def(const suite_body *b, carom_body_def *out);
void suite_world_def(const suite_scene *s, carom_method method,
                     carom_world_def *out);

/* Run every scene (only the SUITE_SMALL ones if small_only) with the
 * events method and the discrete method, printing one line per run:
 *   result NAME METHOD steps=N bodies=N hash=HEX16 impacts=N
 * and, where the platform measures them, "stack" and "insn" lines.
 * Returns the number of failed runs. */
int suite_run(void *world_mem, size_t world_bytes, int small_only);

/* Print what a world costs in memory (sizes.c): "size KEY VALUE" lines. */
int sizes_run(void);

/* ---- what each platform provides ---------------------------------------- */

/* Write a string (no newline added). */
void platform_out(const char *s);
/* Paint the unused stack below the caller (no-op where not measured). */
void platform_stack_paint(void);
/* Bytes of stack used below `sp_at_call` since the last paint, or -1 if
 * not measured (-2: the painted region was exhausted). */
long platform_stack_peak(uintptr_t sp_at_call);
/* Marks the start (0) and end (1) of a run's steps for an instruction
 * counter (an empty function the QEMU plugin watches). */
void platform_mark(int what);

#endif /* CAROM_EMBEDDED_SUITE_H */
