/*
 * test_scene.c -- the scene file parser (tools/scene.c), against the format
 * of docs/scene-format.md.
 *
 * Scenes are parsed from in-memory strings with scene_parse() under the name
 * "s.scene"; the file-level cases (missing file, directory, NUL byte,
 * UTF-16, byte-order mark, CR LF and CR line ends) go through scene_load()
 * on temporary files, and scene_load_stream() on a pipe. Every error must return -1, leave nothing
 * to free, and produce "s.scene:LINE: problem" with the right 1-based line.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"
#include "test_util.h"

#define NAME "s.scene"
#define HDR "carom-scene 1\n"

/* The example of the format specification. */
static const char spec_example[] =
    "carom-scene 1\n"
    "world gravity=0,-10 dt=0.016666667 steps=600 method=discrete\n"
    "body circle radius=0.5 position=0,10 velocity=0,0 density=1 "
    "restitution=0.8 friction=0\n"
    "body box static half-extents=10,0.5 position=0,-0.5 restitution=0.8\n"
    "body polygon vertices=-1,0;1,0;0,1 position=0,3 angle=0.3 "
    "angular-velocity=2 mass=2\n";

/* Parse `text`, which must succeed. */
static void parse_ok(const char *text, scene *s)
{
    char err[512] = "";
    int rc = scene_parse(NAME, text, s, err, sizeof err);
    ck_assert_msg(rc == 0, "scene_parse failed (%d): %s\n--- text:\n%s", rc,
                  err, text);
}

/*
 * Parse `text`, which must fail with "s.scene:LINE:" at the start of the
 * message and `needle` somewhere in it.
 */
static void expect_error(const char *text, int line, const char *needle)
{
    char err[512];
    char prefix[64];
    scene s;
    int rc;
    memset(err, 'x', sizeof err - 1);
    err[sizeof err - 1] = '\0';
    rc = scene_parse(NAME, text, &s, err, sizeof err);
    ck_assert_msg(rc == -1, "accepted (rc %d), expected '%s'\n--- text:\n%s",
                  rc, needle, text);
    snprintf(prefix, sizeof prefix, NAME ":%d: ", line);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0,
                  "message '%s' does not start with '%s'\n--- text:\n%s", err,
                  prefix, text);
    ck_assert_msg(strstr(err, needle) != NULL,
                  "message '%s' does not mention '%s'\n--- text:\n%s", err,
                  needle, text);
    /* nothing to free after a failure */
    ck_assert_ptr_null(s.bodies);
    ck_assert_int_eq(s.body_count, 0);
}

/* A one-body scene "HDR body <body>" must fail on line 2 with `needle`. */
static void expect_body_error(const char *body, const char *needle)
{
    char text[1024];
    snprintf(text, sizeof text, HDR "body %s\n", body);
    expect_error(text, 2, needle);
}

/* A scene "HDR world <world>" must fail on line 2 with `needle`. */
static void expect_world_error(const char *world, const char *needle)
{
    char text[1024];
    snprintf(text, sizeof text, HDR "world %s\n", world);
    expect_error(text, 2, needle);
}

static int has_vertex(const carom_body_def *d, float x, float y)
{
    int i;
    for (i = 0; i < d->vertex_count; ++i)
        if (d->vertices[i].x == x && d->vertices[i].y == y)
            return 1;
    return 0;
}

/* ---- the specification example ----------------------------------------- */

START_TEST(test_scene_spec_example_world)
{
    scene s;
    parse_ok(spec_example, &s);
    ck_assert_float_eq(s.world.gravity.x, 0.0f);
    ck_assert_float_eq(s.world.gravity.y, -10.0f);
    ck_assert_float_eq(s.world.dt, 0.016666667f);
    ck_assert_int_eq(s.steps, 600);
    ck_assert_int_eq(s.world.method, CAROM_METHOD_DISCRETE);
    ck_assert_int_eq(s.body_count, 3);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_spec_example_circle)
{
    scene s;
    const scene_body *b;
    parse_ok(spec_example, &s);
    b = &s.bodies[0];
    ck_assert_str_eq(b->kind, "circle");
    ck_assert_int_eq(b->line, 3);
    ck_assert_int_eq(b->def.type, CAROM_BODY_DYNAMIC);
    ck_assert_int_eq(b->def.shape, CAROM_SHAPE_CIRCLE);
    ck_assert_float_eq(b->def.radius, 0.5f);
    ck_assert_float_eq(b->def.position.x, 0.0f);
    ck_assert_float_eq(b->def.position.y, 10.0f);
    ck_assert_float_eq(b->def.velocity.x, 0.0f);
    ck_assert_float_eq(b->def.velocity.y, 0.0f);
    ck_assert_float_eq(b->def.density, 1.0f);
    ck_assert_float_eq(b->def.mass, 0.0f);
    ck_assert_float_eq(b->def.restitution, 0.8f);
    ck_assert_float_eq(b->def.friction, 0.0f);
    ck_assert_float_eq(b->def.rotation.c, 1.0f);
    ck_assert_float_eq(b->def.rotation.s, 0.0f);
    ck_assert_int_eq(carom_body_def_validate(&b->def), CAROM_OK);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_spec_example_static_box_is_four_vertex_polygon)
{
    scene s;
    const scene_body *b;
    parse_ok(spec_example, &s);
    b = &s.bodies[1];
    ck_assert_str_eq(b->kind, "box");
    ck_assert_int_eq(b->line, 4);
    ck_assert_int_eq(b->def.type, CAROM_BODY_STATIC);
    ck_assert_int_eq(b->def.shape, CAROM_SHAPE_POLYGON);
    ck_assert_int_eq(b->def.vertex_count, 4);
    ck_assert(has_vertex(&b->def, -10.0f, -0.5f));
    ck_assert(has_vertex(&b->def, 10.0f, -0.5f));
    ck_assert(has_vertex(&b->def, 10.0f, 0.5f));
    ck_assert(has_vertex(&b->def, -10.0f, 0.5f));
    ck_assert_float_eq(b->def.position.x, 0.0f);
    ck_assert_float_eq(b->def.position.y, -0.5f);
    ck_assert_float_eq(b->def.restitution, 0.8f);
    /* not given: library defaults */
    ck_assert_float_eq(b->def.friction, 0.6f);
    ck_assert_float_eq(b->def.density, 1.0f);
    ck_assert_int_eq(carom_body_def_validate(&b->def), CAROM_OK);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_spec_example_polygon_mass_and_angle)
{
    scene s;
    const scene_body *b;
    parse_ok(spec_example, &s);
    b = &s.bodies[2];
    ck_assert_str_eq(b->kind, "polygon");
    ck_assert_int_eq(b->line, 5);
    ck_assert_int_eq(b->def.type, CAROM_BODY_DYNAMIC);
    ck_assert_int_eq(b->def.shape, CAROM_SHAPE_POLYGON);
    ck_assert_int_eq(b->def.vertex_count, 3);
    ck_assert_float_eq(b->def.vertices[0].x, -1.0f);
    ck_assert_float_eq(b->def.vertices[0].y, 0.0f);
    ck_assert_float_eq(b->def.vertices[1].x, 1.0f);
    ck_assert_float_eq(b->def.vertices[1].y, 0.0f);
    ck_assert_float_eq(b->def.vertices[2].x, 0.0f);
    ck_assert_float_eq(b->def.vertices[2].y, 1.0f);
    ck_assert_float_eq(b->def.position.x, 0.0f);
    ck_assert_float_eq(b->def.position.y, 3.0f);
    ck_assert_float_eq(b->angle, 0.3f);
    ck_assert_close(b->def.rotation.c, cos(0.3), 1e-6);
    ck_assert_close(b->def.rotation.s, sin(0.3), 1e-6);
    ck_assert_float_eq(b->def.angular_velocity, 2.0f);
    /* mass= replaces density=: mass set, density left at its default */
    ck_assert_float_eq(b->def.mass, 2.0f);
    ck_assert_float_eq(b->def.density, 1.0f);
    ck_assert_int_eq(carom_body_def_validate(&b->def), CAROM_OK);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_spec_example_builds_a_world)
{
    scene s;
    carom_world *w = NULL;
    void *mem = NULL;
    char err[256] = "";
    float m, inertia;
    parse_ok(spec_example, &s);
    ck_assert_msg(scene_build_world(&s, &w, &mem, err, sizeof err) == 0, "%s",
                  err);
    ck_assert_int_eq(carom_world_body_count(w), 3);
    ck_assert_int_eq(carom_body_get_mass(w, 2, &m, &inertia), CAROM_OK);
    ck_assert_close(m, 2.0, 1e-6);
    scene_free_world(w, mem);
    scene_free(&s);
}
END_TEST

/* ---- defaults, flags, optional keys ------------------------------------ */

START_TEST(test_scene_header_only_gives_defaults)
{
    scene s;
    carom_world_def wd = carom_default_world_def();
    parse_ok("carom-scene 1\n", &s);
    ck_assert_int_eq(s.body_count, 0);
    ck_assert_int_eq(s.steps, 600);
    ck_assert_float_eq(s.world.gravity.x, wd.gravity.x);
    ck_assert_float_eq(s.world.gravity.y, wd.gravity.y);
    ck_assert_float_eq(s.world.dt, wd.dt);
    ck_assert_int_eq(s.world.method, wd.method);
    ck_assert_int_eq(s.world.max_events, wd.max_events);
    ck_assert_int_eq(s.world.max_pairs, wd.max_pairs);
    ck_assert_float_eq(s.world.rest_speed, wd.rest_speed);
    ck_assert_float_eq(s.world.linear_slop, wd.linear_slop);
    ck_assert_int_eq(s.world.substeps, wd.substeps);
    ck_assert_int_eq(s.world.iterations, wd.iterations);
    ck_assert_int_eq(s.world.relax_iterations, wd.relax_iterations);
    ck_assert_int_eq(s.world.max_contacts, wd.max_contacts);
    ck_assert_int_eq(s.world.max_impacts, wd.max_impacts);
    ck_assert_float_eq(s.world.length_unit, wd.length_unit);
    ck_assert_int_eq(s.world.enable_sleep, wd.enable_sleep);
    ck_assert_float_eq(s.world.sleep_time, wd.sleep_time);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_body_without_keys_gets_library_defaults)
{
    scene s;
    carom_body_def bd = carom_default_body_def();
    const carom_body_def *d;
    parse_ok(HDR "body circle\n", &s);
    ck_assert_int_eq(s.body_count, 1);
    d = &s.bodies[0].def;
    ck_assert_int_eq(d->type, CAROM_BODY_DYNAMIC);
    ck_assert_float_eq(d->radius, bd.radius);
    ck_assert_float_eq(d->density, bd.density);
    ck_assert_float_eq(d->mass, bd.mass);
    ck_assert_float_eq(d->restitution, bd.restitution);
    ck_assert_float_eq(d->friction, bd.friction);
    ck_assert_float_eq(d->position.x, 0.0f);
    ck_assert_float_eq(d->position.y, 0.0f);
    ck_assert_float_eq(d->rotation.c, 1.0f);
    ck_assert_float_eq(d->rotation.s, 0.0f);
    ck_assert_float_eq(s.bodies[0].angle, 0.0f);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_bodies_numbered_in_file_order)
{
    scene s;
    int i;
    parse_ok(HDR "body circle radius=1\n"
                 "body circle radius=2\n"
                 "# a comment\n"
                 "body circle radius=3\n"
                 "body circle radius=4\n",
             &s);
    ck_assert_int_eq(s.body_count, 4);
    for (i = 0; i < 4; ++i)
        ck_assert_float_eq(s.bodies[i].def.radius, (float)(i + 1));
    ck_assert_int_eq(s.bodies[0].line, 2);
    ck_assert_int_eq(s.bodies[1].line, 3);
    ck_assert_int_eq(s.bodies[2].line, 5);
    ck_assert_int_eq(s.bodies[3].line, 6);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_many_bodies_grow_the_array)
{
    char text[8192];
    size_t n = 0;
    int i;
    scene s;
    n += (size_t)snprintf(text + n, sizeof text - n, HDR);
    for (i = 0; i < 40; ++i)
        n += (size_t)snprintf(text + n, sizeof text - n,
                              "body circle position=%d,0\n", 2 * i);
    parse_ok(text, &s);
    ck_assert_int_eq(s.body_count, 40);
    for (i = 0; i < 40; ++i) {
        ck_assert_float_eq(s.bodies[i].def.position.x, (float)(2 * i));
        ck_assert_int_eq(s.bodies[i].line, i + 2);
    }
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_static_and_dynamic_flags)
{
    scene s;
    parse_ok(HDR "body circle static\n"
                 "body circle dynamic\n"
                 "body circle static dynamic\n"
                 "body circle dynamic static radius=1\n",
             &s);
    ck_assert_int_eq(s.body_count, 4);
    ck_assert_int_eq(s.bodies[0].def.type, CAROM_BODY_STATIC);
    ck_assert_int_eq(s.bodies[1].def.type, CAROM_BODY_DYNAMIC);
    ck_assert_int_eq(s.bodies[2].def.type, CAROM_BODY_DYNAMIC);
    ck_assert_int_eq(s.bodies[3].def.type, CAROM_BODY_STATIC);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_kinematic_sensor_and_filter_keys)
{
    scene s;
    parse_ok(HDR "body box kinematic half-extents=1,0.2 velocity=2,0\n"
                 "body circle sensor static\n"
                 "body circle category=0x4 mask=5 group=-3\n",
             &s);
    ck_assert_int_eq(s.bodies[0].def.type, CAROM_BODY_KINEMATIC);
    ck_assert(s.bodies[0].def.velocity.x == 2.0f);
    ck_assert_int_eq(s.bodies[1].def.is_sensor, 1);
    ck_assert_int_eq(s.bodies[1].def.type, CAROM_BODY_STATIC);
    ck_assert_uint_eq(s.bodies[2].def.category_bits, 4u);
    ck_assert_uint_eq(s.bodies[2].def.mask_bits, 5u);
    ck_assert_int_eq(s.bodies[2].def.group_index, -3);
    ck_assert_int_eq(s.bodies[0].def.is_sensor, 0);
    ck_assert_uint_eq(s.bodies[0].def.mask_bits, 0xffffffffu);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_bad_filter_values_are_named)
{
    scene s;
    char err[256];
    ck_assert_int_eq(scene_parse("f.scene", HDR "body circle mask=-1\n", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "f.scene:2") && strstr(err, "mask"), "%s", err);
    ck_assert_int_eq(scene_parse("f.scene", HDR "body circle category=0x100000000\n", &s, err,
                                 sizeof err),
                     -1);
    ck_assert_msg(strstr(err, "category"), "%s", err);
    ck_assert_int_eq(scene_parse("f.scene", HDR "body circle group=40000\n", &s, err, sizeof err),
                     -1);
    ck_assert_msg(strstr(err, "group"), "%s", err);
    /* a value beyond the limits names the limit */
    ck_assert_int_eq(scene_parse("f.scene", HDR "body circle velocity=1e9,0\n", &s, err, sizeof err),
                     -1);
    ck_assert_msg(strstr(err, "CAROM_LIMIT_MAX_SPEED"), "%s", err);
}
END_TEST

START_TEST(test_scene_optional_world_keys)
{
    scene s;
    parse_ok(HDR "world rest-speed=0.25 slop=0.001 substeps=8 iterations=3 "
                 "relax-iterations=0 max-events=7 max-pairs=0 max-contacts=9 "
                 "max-impacts=11 length-unit=0.2 sleep=off sleep-time=1.5 "
                 "steps=0 gravity=1.5,2 dt=0.5\n",
             &s);
    ck_assert_float_eq(s.world.rest_speed, 0.25f);
    ck_assert_float_eq(s.world.linear_slop, 0.001f);
    ck_assert_int_eq(s.world.substeps, 8);
    ck_assert_int_eq(s.world.iterations, 3);
    ck_assert_int_eq(s.world.relax_iterations, 0);
    ck_assert_int_eq(s.world.max_contacts, 9);
    ck_assert_int_eq(s.world.max_impacts, 11);
    ck_assert_float_eq(s.world.length_unit, 0.2f);
    ck_assert_int_eq(s.world.enable_sleep, 0);
    ck_assert_float_eq(s.world.sleep_time, 1.5f);
    ck_assert_int_eq(s.world.max_events, 7);
    ck_assert_int_eq(s.world.max_pairs, 0);
    ck_assert_int_eq(s.steps, 0);
    ck_assert_float_eq(s.world.gravity.x, 1.5f);
    ck_assert_float_eq(s.world.gravity.y, 2.0f);
    ck_assert_float_eq(s.world.dt, 0.5f);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_force_and_torque_keys)
{
    scene s;
    parse_ok(HDR "body circle force=3,-4 torque=0.5\n", &s);
    ck_assert_float_eq(s.bodies[0].def.force.x, 3.0f);
    ck_assert_float_eq(s.bodies[0].def.force.y, -4.0f);
    ck_assert_float_eq(s.bodies[0].def.torque, 0.5f);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_negative_angle_gives_rotation)
{
    scene s;
    parse_ok(HDR "body box half-extents=1,2 angle=-2.5\n", &s);
    ck_assert_float_eq(s.bodies[0].angle, -2.5f);
    ck_assert_close(s.bodies[0].def.rotation.c, cos(-2.5), 1e-6);
    ck_assert_close(s.bodies[0].def.rotation.s, sin(-2.5), 1e-6);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_number_syntax_accepted)
{
    scene s;
    parse_ok(HDR "body circle radius=2.5e-1 position=-3,+4 velocity=.5,-0. "
                 "restitution=1 friction=0E0\n",
             &s);
    ck_assert_float_eq(s.bodies[0].def.radius, 0.25f);
    ck_assert_float_eq(s.bodies[0].def.position.x, -3.0f);
    ck_assert_float_eq(s.bodies[0].def.position.y, 4.0f);
    ck_assert_float_eq(s.bodies[0].def.velocity.x, 0.5f);
    ck_assert_float_eq(s.bodies[0].def.velocity.y, 0.0f);
    ck_assert_float_eq(s.bodies[0].def.restitution, 1.0f);
    ck_assert_float_eq(s.bodies[0].def.friction, 0.0f);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_clockwise_polygon_accepted)
{
    scene s;
    parse_ok(HDR "body polygon vertices=0,0;0,1;1,1;1,0\n"
                 "body polygon vertices=0,0;0,1;1,0\n",
             &s);
    ck_assert_int_eq(s.body_count, 2);
    ck_assert_int_eq(s.bodies[0].def.vertex_count, 4);
    ck_assert_int_eq(s.bodies[1].def.vertex_count, 3);
    ck_assert_int_eq(carom_body_def_validate(&s.bodies[0].def), CAROM_OK);
    ck_assert_int_eq(carom_body_def_validate(&s.bodies[1].def), CAROM_OK);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_polygon_with_8_vertices_accepted)
{
    scene s;
    /* a regular-ish octagon, counter-clockwise */
    parse_ok(HDR "body polygon vertices=2,0;1.4,1.4;0,2;-1.4,1.4;-2,0;"
                 "-1.4,-1.4;0,-2;1.4,-1.4\n",
             &s);
    ck_assert_int_eq(s.bodies[0].def.vertex_count, 8);
    ck_assert_int_eq(carom_body_def_validate(&s.bodies[0].def), CAROM_OK);
    scene_free(&s);
}
END_TEST

/* ---- comments, blank lines, whitespace --------------------------------- */

START_TEST(test_scene_comments_and_blank_lines_ignored)
{
    scene s;
    parse_ok("# leading comment\n"
             "\n"
             "carom-scene 1   # trailing comment on the header\n"
             "   \t\n"
             "# world gravity=1,1\n"
             "world gravity=0,-3 # dt=5\n"
             "\n"
             "body circle radius=0.25 # radius=2 bogus=1\n"
             "    # indented comment\n",
             &s);
    ck_assert_float_eq(s.world.gravity.y, -3.0f);
    ck_assert_float_eq(s.world.dt, carom_default_world_def().dt);
    ck_assert_int_eq(s.body_count, 1);
    ck_assert_float_eq(s.bodies[0].def.radius, 0.25f);
    ck_assert_int_eq(s.bodies[0].line, 8);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_error_line_counts_comments_and_blank_lines)
{
    expect_error("# comment\n"
                 "\n"
                 "carom-scene 1\n"
                 "# another\n"
                 "\n"
                 "body circle radius=1 # fine\n"
                 "   # indented\n"
                 "body circle colour=red\n",
                 8, "colour");
}
END_TEST

START_TEST(test_scene_tabs_extra_spaces_and_crlf_accepted)
{
    scene s;
    parse_ok("carom-scene 1\r\n"
             "world\tgravity=0,-2\t\tdt=0.25\r\n"
             "\tbody   circle \t radius=0.75   static  \r\n"
             "body circle radius=0.5",   /* no final newline */
             &s);
    ck_assert_float_eq(s.world.gravity.y, -2.0f);
    ck_assert_float_eq(s.world.dt, 0.25f);
    ck_assert_int_eq(s.body_count, 2);
    ck_assert_float_eq(s.bodies[0].def.radius, 0.75f);
    ck_assert_int_eq(s.bodies[0].def.type, CAROM_BODY_STATIC);
    ck_assert_int_eq(s.bodies[1].line, 4);
    scene_free(&s);
}
END_TEST

/* ---- header ------------------------------------------------------------- */

START_TEST(test_scene_rejects_missing_header)
{
    expect_error("world gravity=0,-10\n", 1, "carom-scene 1");
    expect_error("# only a comment\n\nbody circle\n", 3, "expected header");
    expect_error("carom-scen 1\n", 1, "expected header");
    expect_error("CAROM-SCENE 1\n", 1, "expected header");
}
END_TEST

START_TEST(test_scene_rejects_empty_text)
{
    expect_error("", 1, "missing header");
    expect_error("# nothing\n\n   \n", 3, "missing header");
}
END_TEST

START_TEST(test_scene_rejects_unsupported_version)
{
    expect_error("carom-scene 2\n", 1, "unsupported scene version '2'");
    expect_error("\ncarom-scene 1.0\n", 2, "unsupported scene version");
    expect_error("carom-scene\n", 1, "the header line has no version");
    expect_error("carom-scene 2 extra\n", 1, "unsupported scene version '2' (");
}
END_TEST

START_TEST(test_scene_header_with_trailing_text_names_it_not_the_version)
{
    char err[512];
    scene s;
    expect_error("carom-scene 1 extra\n", 1,
                 "the header line has trailing text after the version: 'extra'");
    expect_error("\ncarom-scene 1\t extra words # comment\n", 2,
                 "trailing text after the version: 'extra words'");
    ck_assert_int_eq(scene_parse(NAME, "carom-scene 1 extra\n", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "unsupported") == NULL, "message '%s' calls 1 unsupported", err);
    parse_ok("carom-scene 1   # the version, then a comment\n", &s);
    scene_free(&s);
}
END_TEST

START_TEST(test_scene_rejects_second_header)
{
    expect_error(HDR HDR, 2, "unknown line type 'carom-scene'");
}
END_TEST

/* ---- line types ---------------------------------------------------------- */

START_TEST(test_scene_rejects_unknown_line_type)
{
    expect_error(HDR "bodies circle\n", 2, "unknown line type 'bodies'");
    expect_error(HDR "body circle\nWorld dt=1\n", 3, "unknown line type 'World'");
    expect_error(HDR "radius=1\n", 2, "unknown line type");
}
END_TEST

START_TEST(test_scene_rejects_second_world_line)
{
    expect_error(HDR "world dt=0.5\nworld steps=3\n", 3, "second world line");
    expect_error(HDR "world\nworld\n", 3, "second world line");
}
END_TEST

START_TEST(test_scene_rejects_world_line_after_bodies)
{
    expect_error(HDR "body circle\nworld dt=0.5\n", 3,
                 "world line must come before the bodies");
}
END_TEST

/* ---- keys ---------------------------------------------------------------- */

START_TEST(test_scene_rejects_unknown_world_key)
{
    expect_world_error("gravity=0,-10 gravty=0,-1", "world: unknown key 'gravty'");
    expect_world_error("radius=1", "world: unknown key 'radius'");
}
END_TEST

START_TEST(test_scene_rejects_unknown_body_key)
{
    expect_body_error("circle radius=1 colour=red", "body: unknown key 'colour'");
    expect_body_error("circle Radius=1", "body: unknown key 'Radius'");
    expect_body_error("circle steps=1", "body: unknown key 'steps'");
}
END_TEST

START_TEST(test_scene_rejects_token_without_equals)
{
    expect_body_error("circle radius", "expected key=value, got 'radius'");
    expect_body_error("circle fixed", "expected key=value");
    expect_world_error("dt", "expected key=value");
}
END_TEST

START_TEST(test_scene_rejects_empty_key)
{
    expect_body_error("circle =1", "empty key");
    expect_world_error("=1", "empty key");
}
END_TEST

START_TEST(test_scene_rejects_unknown_shape)
{
    expect_body_error("triangle vertices=0,0;1,0;0,1",
                      "body: unknown shape 'triangle'");
    expect_body_error("radius=1", "unknown shape");
    expect_body_error("static circle", "unknown shape 'static'");
    expect_error(HDR "body\n", 2, "missing shape");
}
END_TEST

START_TEST(test_scene_rejects_key_given_twice)
{
    expect_body_error("circle radius=1 radius=2", "radius given twice");
    expect_body_error("circle position=0,0 position=1,1", "position given twice");
    expect_body_error("box half-extents=1,1 half-extents=1,1",
                      "half-extents given twice");
    expect_body_error("polygon vertices=0,0;1,0;0,1 vertices=0,0;1,0;0,1",
                      "vertices given twice");
    expect_body_error("circle angle=1 angle=1", "angle given twice");
    expect_body_error("circle density=1 density=1", "density given twice");
    expect_body_error("circle mass=1 mass=1", "mass given twice");
    expect_body_error("circle friction=1 friction=1", "friction given twice");
    expect_world_error("dt=0.5 dt=0.5", "dt given twice");
    expect_world_error("gravity=0,0 gravity=0,0", "gravity given twice");
    expect_world_error("steps=1 steps=1", "steps given twice");
    expect_world_error("method=discrete method=discrete", "method given twice");
}
END_TEST

START_TEST(test_scene_rejects_density_and_mass_together)
{
    expect_body_error("circle density=2 mass=1", "density= or mass=, not both");
    expect_body_error("circle mass=1 density=2", "not both");
}
END_TEST

START_TEST(test_scene_rejects_key_on_wrong_shape)
{
    expect_body_error("box half-extents=1,1 radius=1",
                      "radius: only circles have a radius");
    expect_body_error("polygon vertices=0,0;1,0;0,1 radius=1",
                      "only circles have a radius");
    expect_body_error("circle half-extents=1,1",
                      "half-extents: only boxes have half-extents");
    expect_body_error("polygon half-extents=1,1 vertices=0,0;1,0;0,1",
                      "only boxes have half-extents");
    expect_body_error("circle vertices=0,0;1,0;0,1",
                      "vertices: only polygons have vertices");
    expect_body_error("box vertices=0,0;1,0;0,1 half-extents=1,1",
                      "only polygons have vertices");
}
END_TEST

START_TEST(test_scene_rejects_box_without_half_extents)
{
    expect_body_error("box", "box: missing half-extents=");
    expect_body_error("box static position=0,0", "missing half-extents=");
}
END_TEST

START_TEST(test_scene_rejects_polygon_without_vertices)
{
    expect_body_error("polygon", "polygon: missing vertices=");
    expect_body_error("polygon position=1,1 mass=2", "missing vertices=");
}
END_TEST

/* ---- values -------------------------------------------------------------- */

START_TEST(test_scene_rejects_malformed_number)
{
    static const char *const bad[] = {"1.2.3", "abc", "1e", "0.5x", "1,0",
                                      "--1", "1e+", "0x"};
    char body[128];
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(body, sizeof body, "circle radius=%s", bad[i]);
        expect_body_error(body, "radius: malformed number");
    }
    expect_body_error("circle radius=1.2.3", "'1.2.3'");
    expect_body_error("circle angle=abc", "angle: malformed number 'abc'");
    expect_body_error("circle friction=1e", "friction: malformed number '1e'");
    expect_body_error("circle friction=1e20", "friction: must be in [0, 1e+06], got 1e20");
    expect_body_error("circle torque=1.2.3", "torque: malformed number");
    expect_world_error("dt=1e", "dt: malformed number '1e'");
    expect_world_error("rest-speed=abc", "rest-speed: malformed number");
    expect_body_error("circle position=1.2.3,0", "position: malformed number");
    expect_body_error("circle velocity=0,abc", "velocity: malformed number");
    expect_body_error("polygon vertices=0,0;1,x;0,1", "vertices: malformed number");
}
END_TEST

START_TEST(test_scene_rejects_empty_number)
{
    expect_body_error("circle radius=", "radius: missing number");
    expect_body_error("circle density=", "density: missing number");
    expect_body_error("circle position=,1", "position: missing number");
    expect_body_error("circle position=1,", "position: missing number");
    expect_world_error("dt=", "dt: missing number");
}
END_TEST

START_TEST(test_scene_rejects_malformed_integer)
{
    expect_world_error("steps=1.5", "steps: malformed integer '1.5'");
    expect_world_error("steps=1e3", "steps: malformed integer");
    expect_world_error("steps=ten", "steps: malformed integer");
    expect_world_error("steps=", "steps: missing integer");
    expect_world_error("max-events=2x", "max-events: malformed integer");
    expect_world_error("steps=99999999999999999999999", "steps: '99999999999999999999999' is out of range");
}
END_TEST

START_TEST(test_scene_rejects_nan_and_inf)
{
    static const char *const bad[] = {"nan", "NaN", "inf", "-inf", "Infinity",
                                      "1e39", "-1e39", "1e999"};
    char body[128];
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(body, sizeof body, "circle position=0,%s", bad[i]);
        expect_body_error(body, "is not a finite float");
    }
    expect_body_error("circle radius=nan", "radius: 'nan' is not a finite float");
    expect_body_error("circle angle=inf", "angle: 'inf' is not a finite float");
    expect_body_error("circle angular-velocity=nan", "not a finite float");
    expect_body_error("circle force=inf,0", "not a finite float");
    expect_body_error("polygon vertices=0,0;1,0;nan,1", "not a finite float");
    expect_world_error("gravity=0,nan", "gravity: 'nan' is not a finite float");
    expect_world_error("dt=inf", "dt: 'inf' is not a finite float");
    expect_world_error("slop=nan", "slop: 'nan' is not a finite float");
}
END_TEST

START_TEST(test_scene_rejects_malformed_vector)
{
    expect_body_error("circle position=1", "position: malformed vector '1'");
    expect_body_error("circle position=1,2,3", "position: malformed vector '1,2,3'");
    expect_body_error("circle velocity=", "velocity: missing value (want x,y)");
    expect_body_error("circle force=1;2", "force: malformed vector");
    expect_body_error("box half-extents=1", "half-extents: malformed vector");
    expect_world_error("gravity=-10", "gravity: malformed vector '-10'");
    expect_world_error("gravity=0,-10,0", "gravity: malformed vector");
    expect_body_error("polygon vertices=0,0;1;0,1", "vertices: malformed vector '1'");
    expect_body_error("polygon vertices=0,0;1,0,0;0,1", "vertices: malformed vector");
}
END_TEST

START_TEST(test_scene_rejects_malformed_vertex_list)
{
    expect_body_error("polygon vertices=", "vertices: malformed list");
    expect_body_error("polygon vertices=0,0;1,0;0,1;", "vertices: malformed list");
    expect_body_error("polygon vertices=;0,0;1,0;0,1", "vertices: malformed list");
    expect_body_error("polygon vertices=0,0;;1,0;0,1", "vertices: malformed list");
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_radius)
{
    expect_body_error("circle radius=0", "radius: must be > 0, got 0");
    expect_body_error("circle radius=-1", "radius: must be > 0, got -1");
    expect_body_error("circle radius=-0", "radius: must be > 0");
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_density_and_mass)
{
    expect_body_error("circle density=0", "density: must be > 0, got 0");
    expect_body_error("circle density=-2", "density: must be > 0");
    expect_body_error("circle mass=0", "mass: must be > 0, got 0");
    expect_body_error("circle mass=-1", "mass: must be > 0");
}
END_TEST

/* Count the occurrences of `needle` in `hay`. */
static int count_of(const char *hay, const char *needle)
{
    int n = 0;
    for (hay = strstr(hay, needle); hay; hay = strstr(hay + 1, needle))
        ++n;
    return n;
}

START_TEST(test_scene_mass_out_of_range_names_key_value_and_range_once)
{
    /* mass= or density= in range of the parser, but the mass or the moment
     * of inertia they give outside [CAROM_LIMIT_MIN_MASS, _MAX_MASS] */
    static const struct {
        const char *body, *key_value;
    } cases[] = {
        {"circle density=1e30", "body 0: density=1e30: "},
        {"circle mass=1e-30", "body 0: mass=1e-30: "},
        {"circle mass=1e30", "body 0: mass=1e30: "},
        {"circle radius=1e-6 mass=1e-12", "body 0: mass=1e-12: "}, /* inertia 5e-25 */
        {"circle radius=1e8", "body 0: density=1 (the default): "}, /* inertia 1.6e32 */
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[256], err[512];
        scene s;
        snprintf(text, sizeof text, HDR "body %s\n", cases[i].body);
        expect_body_error(cases[i].body, cases[i].key_value);
        ck_assert_int_eq(scene_parse(NAME, text, &s, err, sizeof err), -1);
        ck_assert_msg(count_of(err, "[1e-20, 1e+20]") == 1 &&
                          count_of(err, "CAROM_LIMIT_MIN_MASS") == 1,
                      "'%s': the range not given exactly once: %s", cases[i].body, err);
        ck_assert_msg(strstr(err, "mass and moment of inertia must be in [1e-20, 1e+20]"),
                      "'%s': %s", cases[i].body, err);
    }
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_restitution_and_friction)
{
    expect_body_error("circle restitution=1.5", "restitution: must be in [0, 1], got 1.5");
    expect_body_error("circle restitution=-0.1", "restitution: must be in [0, 1]");
    expect_body_error("circle restitution=1.0001", "restitution: must be in [0, 1]");
    expect_body_error("circle friction=-0.1", "friction: must be in [0, 1e+06], got -0.1");
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_half_extents)
{
    expect_body_error("box half-extents=0,1", "half-extents: both must be > 0");
    expect_body_error("box half-extents=1,0", "half-extents: both must be > 0");
    expect_body_error("box half-extents=1,-1", "half-extents: both must be > 0, got 1,-1");
    expect_body_error("box half-extents=-1,-1", "half-extents: both must be > 0");
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_angle)
{
    expect_body_error("circle angle=100001", "angle: |angle| must be <= 1e5");
    expect_body_error("circle angle=-2e5", "angle: |angle| must be <= 1e5");
}
END_TEST

START_TEST(test_scene_rejects_out_of_range_world_values)
{
    expect_world_error("dt=0", "dt: must be > 0, got 0");
    expect_world_error("dt=-0.01", "dt: must be > 0, got -0.01");
    expect_world_error("steps=-1", "steps: must be in [0, ");
    expect_world_error("steps=1000000001", "steps: must be in [0, ");
    expect_world_error("rest-speed=-1", "rest-speed: must be >= 0 or auto");
    expect_world_error("slop=-0.1", "slop: must be >= 0 or auto");
    expect_world_error("length-unit=0", "length-unit: must be > 0 or auto");
    expect_world_error("substeps=0", "substeps: must be in [1, 64], got 0");
    expect_world_error("substeps=65", "substeps: must be in [1, 64]");
    expect_world_error("iterations=0", "iterations: must be in [1, 64]");
    expect_world_error("relax-iterations=-1", "relax-iterations: must be in [0, 64]");
    expect_world_error("sleep=maybe", "sleep: want on or off, got 'maybe'");
    expect_world_error("sleep-time=-1", "sleep-time: must be >= 0");
    expect_world_error("max-events=-1", "max-events: must be in [0, 67108864]");
    expect_world_error("max-pairs=-1", "max-pairs: must be in [0, 67108864]");
    expect_world_error("max-contacts=67108865", "max-contacts: must be in [0, 67108864]");
    expect_world_error("max-impacts=-2", "max-impacts: must be in [0, 1073741824]");
    /* the old solver's keys say what replaced them */
    expect_world_error("velocity-iterations=10",
                       "velocity-iterations: no longer a setting; the contact solver "
                       "takes substeps=, iterations= and relax-iterations=");
    expect_world_error("position-iterations=3", "position-iterations: no longer a setting");
}
END_TEST

START_TEST(test_scene_rejects_unknown_method)
{
    expect_world_error("method=bogus", "method: unknown method 'bogus'");
    expect_world_error("method=Discrete", "unknown method");
    expect_world_error("method=", "unknown method");
}
END_TEST

/* ---- polygons ------------------------------------------------------------ */

START_TEST(test_scene_rejects_polygon_with_2_vertices)
{
    expect_body_error("polygon vertices=0,0;1,0",
                      "vertices: a polygon needs at least 3 vertices, got 2");
    expect_body_error("polygon vertices=0,0", "at least 3 vertices, got 1");
}
END_TEST

START_TEST(test_scene_rejects_polygon_with_9_vertices)
{
    expect_body_error("polygon vertices=2,0;1.5,1.3;0.5,1.9;-0.7,1.9;-1.7,1;"
                      "-2,-0.3;-1.2,-1.6;0.2,-2;1.5,-1.3",
                      "vertices: more than 8 vertices");
}
END_TEST

START_TEST(test_scene_rejects_non_convex_polygon)
{
    /* an arrow: the vertex (1, 0.2) is reflex; the body number is the
       0-based index it would have had */
    expect_error(HDR "body circle\n"
                     "body polygon vertices=0,0;2,0;1,0.2;2,2;0,2\n",
                 3, "body 1: polygon is not convex");
}
END_TEST

START_TEST(test_scene_rejects_self_intersecting_polygon)
{
    expect_body_error("polygon vertices=0,0;1,1;1,0;0,1",
                      "body 0: self-intersecting polygon");
}
END_TEST

START_TEST(test_scene_rejects_degenerate_polygon)
{
    expect_body_error("polygon vertices=0,0;1,0;2,0", "body 0: degenerate polygon");
    expect_body_error("polygon vertices=0,0;1,0;1,0;0,1", "degenerate polygon");
    expect_body_error("polygon vertices=0,0;1,0;2,0;1,1", "degenerate polygon");
}
END_TEST

/* ---- limits and buffers ------------------------------------------------- */

START_TEST(test_scene_rejects_overlong_line)
{
    size_t n = 5000;
    char *text = malloc(n + 64);
    ck_assert_ptr_nonnull(text);
    strcpy(text, HDR "body circle ");
    memset(text + strlen(text), ' ', n);
    text[strlen(HDR "body circle ") + n] = '\0';
    strcat(text, "radius=1\n");
    expect_error(text, 2, "line longer than");
    free(text);
}
END_TEST

START_TEST(test_scene_small_error_buffer_is_truncated_safely)
{
    char err[8];
    scene s;
    memset(err, 'x', sizeof err);
    ck_assert_int_eq(scene_parse(NAME, HDR "body circle bogus=1\n", &s, err,
                                 sizeof err), -1);
    ck_assert_ptr_nonnull(memchr(err, '\0', sizeof err));
    ck_assert_int_eq(strncmp(err, "s.scene", 7), 0);
    ck_assert_ptr_null(s.bodies);
}
END_TEST

START_TEST(test_scene_error_uses_given_name)
{
    char err[256];
    scene s;
    ck_assert_int_eq(scene_parse("dir/other name.txt", HDR "\nbody box\n", &s,
                                 err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "dir/other name.txt:3: "));
    ck_assert_int_eq(strncmp(err, "dir/other name.txt:3: ", 22), 0);
}
END_TEST

/* ---- scene_load ---------------------------------------------------------- */

/* Write `len` bytes to a fresh temporary file; its name goes to path. */
static void write_temp(char *path, size_t pathlen, const char *data, size_t len)
{
    int fd;
    FILE *f;
    snprintf(path, pathlen, "/tmp/carom_test_scene_XXXXXX");
    fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    f = fdopen(fd, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(data, 1, len, f), len);
    ck_assert_int_eq(fclose(f), 0);
}

START_TEST(test_scene_load_reads_file)
{
    char path[64], err[256] = "";
    scene s;
    write_temp(path, sizeof path, spec_example, strlen(spec_example));
    ck_assert_msg(scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.body_count, 3);
    ck_assert_int_eq(s.bodies[1].def.type, CAROM_BODY_STATIC);
    scene_free(&s);
    unlink(path);
}
END_TEST

START_TEST(test_scene_load_error_names_file_and_line)
{
    static const char text[] = HDR "# c\nbody circle radius=nan\n";
    char path[64], err[256], prefix[80];
    scene s;
    write_temp(path, sizeof path, text, strlen(text));
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    snprintf(prefix, sizeof prefix, "%s:3: ", path);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "%s", err);
    ck_assert_ptr_nonnull(strstr(err, "not a finite float"));
    ck_assert_ptr_null(s.bodies);
    unlink(path);
}
END_TEST

START_TEST(test_scene_load_rejects_missing_file)
{
    char err[256];
    scene s;
    const char *path = "/nonexistent-carom-dir/missing.scene";
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, path));
    ck_assert_ptr_nonnull(strstr(err, "cannot open"));
    ck_assert_ptr_null(s.bodies);
    ck_assert_int_eq(s.body_count, 0);
}
END_TEST

START_TEST(test_scene_load_rejects_nul_byte)
{
    static const char text[] = "carom-scene 1\nbody circle\0radius=1\n";
    char path[64], err[256];
    scene s;
    write_temp(path, sizeof path, text, sizeof text - 1);
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, path));
    ck_assert_ptr_nonnull(strstr(err, "NUL byte"));
    ck_assert_ptr_null(s.bodies);
    unlink(path);
}
END_TEST

START_TEST(test_scene_load_rejects_empty_file)
{
    char path[64], err[256], prefix[80];
    scene s;
    write_temp(path, sizeof path, "", 0);
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    snprintf(prefix, sizeof prefix, "%s:1: ", path);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "%s", err);
    ck_assert_ptr_nonnull(strstr(err, "missing header"));
    unlink(path);
}
END_TEST

/* Each line end of the spec example written as `eol`, after an optional
 * UTF-8 byte-order mark, must load as the example does. */
static void expect_loads_like_example(const char *bom, const char *eol)
{
    char text[1024], path[64], err[256] = "";
    const char *r;
    size_t n = 0;
    scene s;
    n += (size_t)snprintf(text, sizeof text, "%s", bom);
    for (r = spec_example; *r; ++r) {
        if (*r == '\n')
            n += (size_t)snprintf(text + n, sizeof text - n, "%s", eol);
        else
            text[n++] = *r;
        ck_assert_uint_lt(n, sizeof text - 4);
    }
    write_temp(path, sizeof path, text, n);
    ck_assert_msg(scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.body_count, 3);
    ck_assert_int_eq(s.world.method, CAROM_METHOD_DISCRETE);
    ck_assert_float_eq(s.bodies[0].def.restitution, 0.8f);
    ck_assert_float_eq(s.bodies[1].def.restitution, 0.8f);
    ck_assert_float_eq(s.bodies[2].def.mass, 2.0f);
    ck_assert_int_eq(s.bodies[0].line, 3);
    ck_assert_int_eq(s.bodies[2].line, 5);
    scene_free(&s);
    unlink(path);
}

START_TEST(test_scene_load_accepts_crlf_and_cr_line_ends)
{
    expect_loads_like_example("", "\r\n");
    expect_loads_like_example("", "\r");
}
END_TEST

START_TEST(test_scene_load_skips_utf8_byte_order_mark)
{
    expect_loads_like_example("\xEF\xBB\xBF", "\n");
    expect_loads_like_example("\xEF\xBB\xBF", "\r\n");
}
END_TEST

START_TEST(test_scene_load_error_line_counts_cr_and_crlf_line_ends)
{
    /* line 2 ends CR LF, line 3 a lone CR: the error is on line 4 */
    static const char text[] = "\xEF\xBB\xBF" HDR "# c\r\n\r"
                               "body circle radius=-1\r\n";
    char path[64], err[256], prefix[80];
    scene s;
    write_temp(path, sizeof path, text, strlen(text));
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    snprintf(prefix, sizeof prefix, "%s:4: ", path);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "%s", err);
    ck_assert_ptr_nonnull(strstr(err, "radius"));
    unlink(path);
}
END_TEST

START_TEST(test_scene_parse_counts_lone_cr_as_a_line_end)
{
    scene s;
    parse_ok(HDR "world dt=0.25\rbody circle radius=2\r\rbody circle\r", &s);
    ck_assert_float_eq(s.world.dt, 0.25f);
    ck_assert_int_eq(s.body_count, 2);
    ck_assert_float_eq(s.bodies[0].def.radius, 2.0f);
    ck_assert_int_eq(s.bodies[0].line, 3);
    ck_assert_int_eq(s.bodies[1].line, 5);
    scene_free(&s);
    expect_error(HDR "\r\r\nbody circle radius=0\n", 4, "radius");
}
END_TEST

START_TEST(test_scene_load_rejects_directory)
{
    char dir[64], err[256];
    scene s;
    snprintf(dir, sizeof dir, "/tmp/carom_test_scene_dir_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    ck_assert_int_eq(scene_load(dir, &s, err, sizeof err), -1);
    ck_assert_msg(strncmp(err, dir, strlen(dir)) == 0, "%s", err);
    ck_assert_msg(strstr(err, "is a directory") != NULL, "%s", err);
    ck_assert_ptr_null(s.bodies);
    ck_assert_int_eq(s.body_count, 0);
    rmdir(dir);
}
END_TEST

START_TEST(test_scene_load_rejects_utf16)
{
    static const char text[] = "\xFF\xFE" "c\0a\0";
    char path[64], err[256];
    scene s;
    write_temp(path, sizeof path, text, sizeof text - 1);
    ck_assert_int_eq(scene_load(path, &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "UTF-16") != NULL, "%s", err);
    unlink(path);
}
END_TEST

START_TEST(test_scene_load_stream_reads_a_pipe)
{
    char err[256] = "";
    scene s;
    int fd[2];
    FILE *f;
    ck_assert_int_eq(pipe(fd), 0);
    ck_assert_int_eq(write(fd[1], spec_example, strlen(spec_example)),
                     (ssize_t)strlen(spec_example));
    close(fd[1]);
    f = fdopen(fd[0], "rb");
    ck_assert_ptr_nonnull(f);
    ck_assert_msg(scene_load_stream(f, "<pipe>", &s, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.body_count, 3);
    scene_free(&s);
    fclose(f);
}
END_TEST

Suite *suite_scene(void)
{
    Suite *s = suite_create("scene");
    TCase *tc = tcase_create("example");
    tcase_add_test(tc, test_scene_spec_example_world);
    tcase_add_test(tc, test_scene_spec_example_circle);
    tcase_add_test(tc, test_scene_spec_example_static_box_is_four_vertex_polygon);
    tcase_add_test(tc, test_scene_spec_example_polygon_mass_and_angle);
    tcase_add_test(tc, test_scene_spec_example_builds_a_world);
    suite_add_tcase(s, tc);

    tc = tcase_create("accepts");
    tcase_add_test(tc, test_scene_header_only_gives_defaults);
    tcase_add_test(tc, test_scene_body_without_keys_gets_library_defaults);
    tcase_add_test(tc, test_scene_bodies_numbered_in_file_order);
    tcase_add_test(tc, test_scene_many_bodies_grow_the_array);
    tcase_add_test(tc, test_scene_static_and_dynamic_flags);
    tcase_add_test(tc, test_scene_kinematic_sensor_and_filter_keys);
    tcase_add_test(tc, test_scene_bad_filter_values_are_named);
    tcase_add_test(tc, test_scene_optional_world_keys);
    tcase_add_test(tc, test_scene_force_and_torque_keys);
    tcase_add_test(tc, test_scene_negative_angle_gives_rotation);
    tcase_add_test(tc, test_scene_number_syntax_accepted);
    tcase_add_test(tc, test_scene_clockwise_polygon_accepted);
    tcase_add_test(tc, test_scene_polygon_with_8_vertices_accepted);
    tcase_add_test(tc, test_scene_comments_and_blank_lines_ignored);
    tcase_add_test(tc, test_scene_error_line_counts_comments_and_blank_lines);
    tcase_add_test(tc, test_scene_tabs_extra_spaces_and_crlf_accepted);
    suite_add_tcase(s, tc);

    tc = tcase_create("rejects");
    tcase_add_test(tc, test_scene_rejects_missing_header);
    tcase_add_test(tc, test_scene_rejects_empty_text);
    tcase_add_test(tc, test_scene_rejects_unsupported_version);
    tcase_add_test(tc, test_scene_header_with_trailing_text_names_it_not_the_version);
    tcase_add_test(tc, test_scene_rejects_second_header);
    tcase_add_test(tc, test_scene_rejects_unknown_line_type);
    tcase_add_test(tc, test_scene_rejects_second_world_line);
    tcase_add_test(tc, test_scene_rejects_world_line_after_bodies);
    tcase_add_test(tc, test_scene_rejects_unknown_world_key);
    tcase_add_test(tc, test_scene_rejects_unknown_body_key);
    tcase_add_test(tc, test_scene_rejects_token_without_equals);
    tcase_add_test(tc, test_scene_rejects_empty_key);
    tcase_add_test(tc, test_scene_rejects_unknown_shape);
    tcase_add_test(tc, test_scene_rejects_key_given_twice);
    tcase_add_test(tc, test_scene_rejects_density_and_mass_together);
    tcase_add_test(tc, test_scene_rejects_key_on_wrong_shape);
    tcase_add_test(tc, test_scene_rejects_box_without_half_extents);
    tcase_add_test(tc, test_scene_rejects_polygon_without_vertices);
    tcase_add_test(tc, test_scene_rejects_malformed_number);
    tcase_add_test(tc, test_scene_rejects_empty_number);
    tcase_add_test(tc, test_scene_rejects_malformed_integer);
    tcase_add_test(tc, test_scene_rejects_nan_and_inf);
    tcase_add_test(tc, test_scene_rejects_malformed_vector);
    tcase_add_test(tc, test_scene_rejects_malformed_vertex_list);
    tcase_add_test(tc, test_scene_rejects_out_of_range_radius);
    tcase_add_test(tc, test_scene_rejects_out_of_range_density_and_mass);
    tcase_add_test(tc, test_scene_mass_out_of_range_names_key_value_and_range_once);
    tcase_add_test(tc, test_scene_rejects_out_of_range_restitution_and_friction);
    tcase_add_test(tc, test_scene_rejects_out_of_range_half_extents);
    tcase_add_test(tc, test_scene_rejects_out_of_range_angle);
    tcase_add_test(tc, test_scene_rejects_out_of_range_world_values);
    tcase_add_test(tc, test_scene_rejects_unknown_method);
    tcase_add_test(tc, test_scene_rejects_polygon_with_2_vertices);
    tcase_add_test(tc, test_scene_rejects_polygon_with_9_vertices);
    tcase_add_test(tc, test_scene_rejects_non_convex_polygon);
    tcase_add_test(tc, test_scene_rejects_self_intersecting_polygon);
    tcase_add_test(tc, test_scene_rejects_degenerate_polygon);
    tcase_add_test(tc, test_scene_rejects_overlong_line);
    tcase_add_test(tc, test_scene_small_error_buffer_is_truncated_safely);
    tcase_add_test(tc, test_scene_error_uses_given_name);
    suite_add_tcase(s, tc);

    tc = tcase_create("load");
    tcase_add_test(tc, test_scene_load_reads_file);
    tcase_add_test(tc, test_scene_load_error_names_file_and_line);
    tcase_add_test(tc, test_scene_load_rejects_missing_file);
    tcase_add_test(tc, test_scene_load_rejects_nul_byte);
    tcase_add_test(tc, test_scene_load_rejects_empty_file);
    tcase_add_test(tc, test_scene_load_accepts_crlf_and_cr_line_ends);
    tcase_add_test(tc, test_scene_load_skips_utf8_byte_order_mark);
    tcase_add_test(tc, test_scene_load_error_line_counts_cr_and_crlf_line_ends);
    tcase_add_test(tc, test_scene_parse_counts_lone_cr_as_a_line_end);
    tcase_add_test(tc, test_scene_load_rejects_directory);
    tcase_add_test(tc, test_scene_load_rejects_utf16);
    tcase_add_test(tc, test_scene_load_stream_reads_a_pipe);
    suite_add_tcase(s, tc);
    return s;
}
