/*
 * fuzz_scene_parse.c -- libFuzzer harness: scene_parse() (tools/scene.c) on
 * arbitrary text.
 *
 * The input is the scene text (a NUL ends it early, as for any C string).
 * Invariants beyond "no crash, no sanitizer report":
 *   - scene_parse returns 0 or -1; on -1 the message is a NUL-terminated
 *     "NAME:LINE: ..." and the scene holds nothing (scene_free is still
 *     safe); on 0 the counts are consistent and every body definition
 *     passes carom_body_def_validate() (the parser promises it checked
 *     each one);
 *   - parsing the same text twice gives the same scene, bit for bit.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"
#include "scene.h"

#define FZ_NAME "fuzz.scene"

/* Field by field: carom_world_def has padding before its pointers. */
static int fz_same_world(const carom_world_def *x, const carom_world_def *y)
{
    return fz_bits(x->gravity.x) == fz_bits(y->gravity.x) &&
           fz_bits(x->gravity.y) == fz_bits(y->gravity.y) &&
           fz_bits(x->dt) == fz_bits(y->dt) && x->method == y->method &&
           x->max_bodies == y->max_bodies && x->max_pairs == y->max_pairs &&
           x->max_contacts == y->max_contacts &&
           x->max_events == y->max_events &&
           x->max_impacts == y->max_impacts &&
           fz_bits(x->length_unit) == fz_bits(y->length_unit) &&
           fz_bits(x->rest_speed) == fz_bits(y->rest_speed) &&
           fz_bits(x->linear_slop) == fz_bits(y->linear_slop) &&
           x->substeps == y->substeps && x->max_substeps == y->max_substeps &&
           x->iterations == y->iterations &&
           x->relax_iterations == y->relax_iterations &&
           x->enable_sleep == y->enable_sleep &&
           fz_bits(x->sleep_time) == fz_bits(y->sleep_time) &&
           x->force_fn == y->force_fn && x->force_user == y->force_user;
}

static void fz_same_scene(const scene *a, const scene *b)
{
    int i;
    if (a->body_count != b->body_count || a->steps != b->steps ||
        !fz_same_world(&a->world, &b->world))
        fz_fail("parse determinism", "two parses of one text differ (world "
                "line or body count %d vs %d)", a->body_count, b->body_count);
    for (i = 0; i < a->body_count; ++i) {
        const scene_body *x = &a->bodies[i], *y = &b->bodies[i];
        if (memcmp(&x->def, &y->def, sizeof x->def) != 0 ||
            fz_bits(x->angle) != fz_bits(y->angle) || x->line != y->line ||
            strcmp(x->kind, y->kind) != 0)
            fz_fail("parse determinism", "body %d differs between two "
                    "parses of one text", i);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = (char *)malloc(size + 1);
    char err[512], err2[512];
    scene s, s2;
    int rc, rc2, i;

    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    fz_set_where("scene_parse of %zu bytes", size);

    memset(err, 0x55, sizeof err);
    rc = scene_parse(FZ_NAME, text, &s, err, sizeof err);
    if (rc != 0 && rc != -1)
        fz_fail("scene_parse result", "returned %d (want 0 or -1)", rc);
    if (rc == -1) {
        if (!memchr(err, '\0', sizeof err))
            fz_fail("error message", "not NUL-terminated");
        if (strncmp(err, FZ_NAME ":", strlen(FZ_NAME ":")) != 0)
            fz_fail("error message", "'%s' does not start with '" FZ_NAME
                    ":'", err);
        if (s.bodies != NULL || s.body_count != 0)
            fz_fail("nothing to free after an error",
                    "bodies %p, body_count %d", (void *)s.bodies,
                    s.body_count);
    } else {
        if (s.body_count < 0 || s.body_count > s.body_capacity ||
            (s.body_count > 0 && !s.bodies))
            fz_fail("scene counts", "body_count %d, capacity %d",
                    s.body_count, s.body_capacity);
        if (s.steps < 0)
            fz_fail("scene steps", "steps %ld", s.steps);
        for (i = 0; i < s.body_count; ++i) {
            carom_status st = carom_body_def_validate(&s.bodies[i].def);
            if (st != CAROM_OK)
                fz_fail("parsed bodies are valid", "body %d (line %d) "
                        "accepted by the parser but carom_body_def_validate "
                        "says %s", i, s.bodies[i].line,
                        carom_status_string(st));
        }
    }

    rc2 = scene_parse(FZ_NAME, text, &s2, err2, sizeof err2);
    if (rc2 != rc)
        fz_fail("parse determinism", "results %d then %d", rc, rc2);
    if (rc == -1) {
        if (strcmp(err, err2) != 0)
            fz_fail("parse determinism", "messages '%s' then '%s'", err,
                    err2);
    } else {
        fz_same_scene(&s, &s2);
    }
    scene_free(&s);
    scene_free(&s2);
    free(text);
    return 0;
}
