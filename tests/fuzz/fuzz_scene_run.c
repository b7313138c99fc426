/*
 * fuzz_scene_run.c -- libFuzzer harness: parse a scene, build its world
 * (scene_build_world) and step it, once per method (events, discrete,
 * first-impact).
 *
 * Bounded so that every input runs fast: at most FZ_MAX_BODIES bodies (the
 * rest of the scene is dropped), FZ_MAX_STEPS steps (a scene's steps= is
 * clamped to [1, FZ_MAX_STEPS]) and FZ_MAX_TOTAL_IMPACTS impacts, and
 * max-impacts= is at most FZ_SCENE_MAX_IMPACTS. dt, gravity and every
 * body value are the scene's: the library's own limits (carom_config.h)
 * decide what is accepted.
 *
 * Each method builds two worlds from the scene and steps them in lockstep:
 *   - determinism: same status, same state and events, bit for bit;
 *   - after CAROM_OK: finite, in-range state; consistent time and events;
 *     static bodies still, kinematic ones at their velocity, sleeping
 *     ones unchanged;
 *   - after an error: the world exactly as before the step, no events,
 *     carom_world_error_body naming a body for NOT_FINITE / OUT_OF_RANGE;
 *     a second attempt fails the same way (the failed step left nothing
 *     behind that changes the next one).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"
#include "scene.h"

#ifndef FZ_MAX_STEPS
#define FZ_MAX_STEPS 200
#endif
/* Impacts per method: past it no more steps. */
#define FZ_MAX_TOTAL_IMPACTS 5000L
/* max-impacts, at most (0, the library's default, included). The
 * library's default (at least CAROM_MIN_IMPACTS = 16384 instants, then as
 * many plastic ones) lets 40 circles take seconds per step (tests/fuzz/
 * README.md, "Bounds"; tests/fuzz/slow/). */
#define FZ_SCENE_MAX_IMPACTS 256

static const carom_method fz_methods[] = {
    CAROM_METHOD_EVENTS, CAROM_METHOD_DISCRETE, CAROM_METHOD_FIRST_IMPACT};

static void fz_check_failed_step(carom_world *w, const int *ids, int n,
                                 const fz_snap *before, carom_status rc)
{
    fz_snap after;
    int count = -1, eb;
    carom_world_events(w, &count);
    fz_snap_take(w, ids, n, &after);
    fz_expect_same(before, &after, "failed call leaves the world unchanged",
                   carom_status_string(rc));
    if (count != 0)
        fz_fail("failed step has no events", "%s, %d events",
                carom_status_string(rc), count);
    eb = carom_world_error_body(w);
    if (rc == CAROM_ERR_NOT_FINITE || rc == CAROM_ERR_OUT_OF_RANGE) {
        int i, found = 0;
        for (i = 0; i < n; ++i)
            found |= ids[i] == eb;
        if (!found)
            fz_fail("error body named", "%s but carom_world_error_body is "
                    "%d", carom_status_string(rc), eb);
    }
}

static void fz_run_method(const scene *s, carom_method method, long steps)
{
    scene sc = *s;
    carom_world *wa = NULL, *wb = NULL;
    void *ma = NULL, *mb = NULL;
    char ea[512], eb[512];
    int ids[FZ_MAX_BODIES], types[FZ_MAX_BODIES], n = sc.body_count, i, ra,
        rb, max_events;
    long k;

    sc.world.method = method;
    /* the capacity scene_build_world's world gets (carom.h, max_events) */
    max_events = sc.world.max_events;
    if (max_events <= 0) {
        int b = n > 0 ? n : 1;
        max_events = CAROM_DEFAULT_EVENTS_PER_BODY * b > CAROM_MIN_EVENTS
                         ? CAROM_DEFAULT_EVENTS_PER_BODY * b
                         : CAROM_MIN_EVENTS;
    }
    fz_set_where("%s: building the world", carom_method_name(method));
    ra = scene_build_world(&sc, &wa, &ma, ea, sizeof ea);
    rb = scene_build_world(&sc, &wb, &mb, eb, sizeof eb);
    if (ra != rb || (ra != 0 && strcmp(ea, eb) != 0))
        fz_fail("determinism", "building the same scene twice: %d '%s' vs "
                "%d '%s'", ra, ra ? ea : "", rb, rb ? eb : "");
    if (ra != 0)
        return;
    for (i = 0; i < n; ++i) {
        ids[i] = i; /* a fresh world numbers bodies 0, 1, 2, ... */
        types[i] = (int)sc.bodies[i].def.type;
        fz_check_mass(wa, ids[i], types[i]);
    }
    if (carom_world_get_method(wa) != method)
        fz_fail("method", "built with %s, world says %s",
                carom_method_name(method),
                carom_method_name(carom_world_get_method(wa)));
    fz_check_world_ok(wa, ids, n, sc.world.dt, "scene_build_world");

    for (k = 0; k < steps; ++k) {
        fz_snap before, after_a, after_b;
        float t0;
        carom_status sa, sb;
        fz_set_where("%s: step %ld of %ld (%d bodies, dt %g)",
                     carom_method_name(method), k + 1, steps, n,
                     (double)sc.world.dt);
        fz_snap_take(wa, ids, n, &before);
        t0 = carom_world_time(wa);
        sa = carom_world_step(wa);
        sb = carom_world_step(wb);
        if (sa != sb)
            fz_fail("determinism", "the same step returned %s and %s",
                    carom_status_string(sa), carom_status_string(sb));
        fz_snap_take(wa, ids, n, &after_a);
        fz_snap_take(wb, ids, n, &after_b);
        fz_expect_same(&after_a, &after_b, "determinism",
                       "two worlds of one scene");
        if (carom_world_error_body(wa) != carom_world_error_body(wb))
            fz_fail("determinism", "error bodies %d vs %d",
                    carom_world_error_body(wa), carom_world_error_body(wb));
        fz_check_same_events(wa, wb, "determinism");
        if (sa == CAROM_OK) {
            fz_check_world_ok(wa, ids, n, sc.world.dt, "carom_world_step");
            fz_check_motion(&before, &after_a, types, sc.world.dt,
                            sc.world.sleep_time);
            fz_check_events(wa, ids, n, max_events, t0,
                            carom_world_time(wa));
            {
                carom_stats st;
                carom_world_get_stats(wa, &st);
                if (st.impacts > FZ_MAX_TOTAL_IMPACTS)
                    break;
            }
            continue;
        }
        fz_check_failed_step(wa, ids, n, &before, sa);
        /* the world is as before: the same step fails the same way */
        fz_set_where("%s: step %ld again after %s", carom_method_name(method),
                     k + 1, carom_status_string(sa));
        {
            int first_err = carom_world_error_body(wa);
            carom_status again = carom_world_step(wa);
            if (again != sa || carom_world_error_body(wa) != first_err)
                fz_fail("failed call leaves the world unchanged",
                        "step failed with %s (error body %d); stepping again "
                        "returned %s (error body %d)",
                        carom_status_string(sa), first_err,
                        carom_status_string(again),
                        carom_world_error_body(wa));
            fz_check_failed_step(wa, ids, n, &before, again);
        }
        break;
    }
    scene_free_world(wa, ma);
    scene_free_world(wb, mb);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = (char *)malloc(size + 1);
    char err[512];
    scene s;
    long steps;
    size_t m;

    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    fz_set_where("scene_parse");
    if (scene_parse("fuzz.scene", text, &s, err, sizeof err) != 0) {
        free(text);
        return 0;
    }
    free(text);
    if (s.body_count > FZ_MAX_BODIES)
        s.body_count = FZ_MAX_BODIES; /* scene_free frees them all */
    steps = s.steps < 1 ? 1 : s.steps > FZ_MAX_STEPS ? FZ_MAX_STEPS : s.steps;
    if (s.world.max_impacts == 0 || s.world.max_impacts > FZ_SCENE_MAX_IMPACTS)
        s.world.max_impacts = FZ_SCENE_MAX_IMPACTS;
    for (m = 0; m < sizeof fz_methods / sizeof fz_methods[0]; ++m)
        fz_run_method(&s, fz_methods[m], steps);
    scene_free(&s);
    return 0;
}
