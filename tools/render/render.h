/*
 * render.h -- draw a recorded carom run: an animated SVG, or PNG frames
 * through gnuplot (`carom render`, tools/carom_cli.c).
 *
 * A tool, not part of the core: it allocates, uses libm and POSIX. It
 * calls no carom function: the CLI runs the world and hands over plain
 * data (shapes, poses per frame, impact points), so this module only
 * draws.
 */
#ifndef CAROM_RENDER_H
#define CAROM_RENDER_H

#include <stddef.h>
#include <stdio.h>

#include "carom.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A body's shape, in its body frame. */
typedef struct render_shape {
    int circle;       /**< 1: a circle of `radius` centred on the origin;
                           0: the polygon `vertices` */
    int fixed;        /**< 1: a static body (drawn grey) */
    float radius;
    int vertex_count;
    carom_vec2 vertices[CAROM_MAX_POLYGON_VERTICES];
} render_shape;

/** Where a body is: its origin (m, world frame) and angle (rad). */
typedef struct render_pose {
    float x, y, angle;
} render_pose;

/** An impact marker: the instant and the world point of contact. */
typedef struct render_impact {
    double t;
    float x, y;
} render_impact;

/** A recorded run. Poses are frame-major: poses[f * body_count + b]. */
typedef struct render_movie {
    const char *title;      /**< shown in the SVG's <title> (the scene) */
    const char *generator;  /**< e.g. "carom 0.2.0", in the SVG's <desc> */
    int body_count;
    const render_shape *shapes;
    int frame_count;        /**< >= 1 */
    const double *times;    /**< simulated time of each frame, s */
    const long *steps;      /**< step number of each frame */
    const render_pose *poses;
    int impact_count;
    const render_impact *impacts;
    const char *note;       /**< drawn under the time label, or NULL (for
                                 "partial: ..." when the run failed) */
} render_movie;

typedef struct render_options {
    int size;               /**< pixels of the longer side of the view */
    int impacts;            /**< 1: draw the impact markers */
    int fixed_view;         /**< 1: show `view` instead of fitting the bodies */
    double view[4];         /**< xmin, ymin, xmax, ymax, m */
} render_options;

/** Rough size in bytes of the SVG of `frames` frames of `bodies` bodies
 * (to refuse absurd outputs before running). */
double render_svg_estimate(long frames, int bodies, long impacts);

/** Write the animated SVG (SMIL, discrete frames at the recorded times,
 * looping). Returns 0, or -1 if writing failed. */
int render_svg(FILE *f, const render_movie *m, const render_options *o);

/** 1 if a `gnuplot` executable is on PATH. */
int render_have_gnuplot(void);

/* Make directory `dir` for --png frames if it is missing; 0, or -1 with a
 * message in err when it cannot be made or is not a directory. */
int render_png_dir(const char *dir, char *err, size_t errlen);

/** Write DIR/frame-00000.png ... one per frame with gnuplot (DIR is made
 * if missing). Returns 0, or -1 with a message in err. */
int render_png(const char *dir, const render_movie *m, const render_options *o,
               char *err, size_t errlen);

/** The world point where two touching bodies meet, for an impact marker:
 * the support feature of each body along the normal (a vertex, a circle's
 * point, or a face), the point if either is one, else the middle of the
 * faces' overlap. `normal` points from a to b. */
carom_vec2 render_contact_point(const render_shape *a, const render_pose *pa,
                                const render_shape *b, const render_pose *pb,
                                carom_vec2 normal);

#ifdef __cplusplus
}
#endif

#endif /* CAROM_RENDER_H */
