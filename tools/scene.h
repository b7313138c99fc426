/*
 * scene.h -- the carom scene file format (docs/scene-format.md).
 *
 * A tool, not part of the core: it allocates. Shared by build/carom and the
 * Box2D harness, so both engines read every scene the same way.
 */
#ifndef CAROM_SCENE_H
#define CAROM_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "carom.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct scene_body {
    carom_body_def def;
    float angle;   /* radians, as written (def.rotation is derived) */
    int line;      /* line number in the file */
    const char *kind; /* "circle", "box" or "polygon" */
} scene_body;

typedef struct scene {
    carom_world_def world;
    long steps;           /* steps= (default 600) */
    scene_body *bodies;
    int body_count;
    int body_capacity;
} scene;

/* Parse the file `path` into *s. Returns 0 on success; otherwise fills err
 * with "FILE:LINE: problem" (or "FILE: problem": a directory, not
 * readable, UTF-16, a NUL byte, larger than 64 MiB) and returns -1
 * (nothing to free). A UTF-8 byte-order mark is skipped; lines may end
 * with LF, CR LF or CR (line numbers count any of them). */
int scene_load(const char *path, scene *s, char *err, size_t errlen);

/* The same for an open stream (stdin, a pipe), read to its end; `name` is
 * used in messages. The stream is not closed. */
int scene_load_stream(FILE *f, const char *name, scene *s, char *err,
                      size_t errlen);

/* Parse from a string; `name` is used in messages. Lines end with LF,
 * CR LF or CR. */
int scene_parse(const char *name, const char *text, scene *s, char *err,
                size_t errlen);

void scene_free(scene *s);

/* Build a world for the scene in freshly allocated memory (*mem; give
 * both back with scene_free_world). Returns 0, or -1 with a message in
 * err. A scene that sets neither max-pairs nor max-contacts gets a world
 * that grows (carom_world_def.grow, malloc), so no pile or fast gas stops
 * short of capacity; one that sets either keeps its capacities as limits. */
int scene_build_world(const scene *s, carom_world **w, void **mem, char *err,
                      size_t errlen);

/* carom_world_release(w), then free(mem); either may be NULL. */
void scene_free_world(carom_world *w, void *mem);

/* Angle of a rotation in [-pi, pi]: carom's own carom_rot_angle(), or, in
 * a build without CAROM_ENABLE_ANGLES, libm's atan2 (the same at angle 0,
 * the only angle `carom lean` leaves such a build). */
float scene_rot_angle(carom_rot r);

#ifdef __cplusplus
}
#endif

#endif /* CAROM_SCENE_H */
