/*
 * reference.h -- exact answers for the accuracy scenes, in double precision
 * and closed form, computed from the scene's inputs alone (never from
 * carom's results). docs/accuracy.md describes each model.
 *
 * Every model starts from the scene's float inputs converted exactly to
 * double, so the reference answers the question "what does this scene do
 * in exact arithmetic", the same question both engines are asked.
 *
 * A model is advanced with nondecreasing times (ref_*_advance) and read
 * at the time reached; impacts are listed as they are passed.
 */
#ifndef CAROM_ACCURACY_REFERENCE_H
#define CAROM_ACCURACY_REFERENCE_H

#define REF_MAX_BODIES 16
#define REF_MAX_IMPACTS 4096
#define REF_MAX_VERTS 8

typedef struct ref_impact {
    double t;        /* instant, s */
    int a, b;        /* bodies (scene numbering) */
    double approach; /* normal approach speed before, m/s */
} ref_impact;

/* ---- bodies on a line: circles (and static boxes as walls) along x, no
 * gravity; impacts are central, frictionless, Newton restitution with the
 * pair's larger coefficient (as carom and Box2D mix it). Neighbours in x
 * order are the only pairs that can meet. */
typedef struct ref_line {
    int n;
    int id[REF_MAX_BODIES];  /* scene body of each slot, slots in x order */
    double x[REF_MAX_BODIES], v[REF_MAX_BODIES];
    double half[REF_MAX_BODIES]; /* half length along x */
    double w[REF_MAX_BODIES];    /* inverse mass, 0 for static */
    double e[REF_MAX_BODIES];
    double t;
    int impact_count;
    ref_impact impacts[REF_MAX_IMPACTS];
} ref_line;

/* Slots must be given in increasing x, not overlapping. */
void ref_line_init(ref_line *s);
void ref_line_add(ref_line *s, int id, double x, double v, double half,
                  double inv_mass, double e);
/* 0, or -1 if more than REF_MAX_IMPACTS impacts happen before t. */
int ref_line_advance(ref_line *s, double t);
/* Position and velocity of scene body `id` at the time reached. */
void ref_line_get(const ref_line *s, int id, double *x, double *v);

/* ---- a ball dropped on a floor under gravity g (> 0, downwards), from
 * rest, its centre at height h0 above its touching height. */
typedef struct ref_bounce {
    double g, e, h0, y_touch;
    int count;                  /* impacts listed */
    double t[64], v[64];        /* impact instants and approach speeds */
} ref_bounce;

/* Lists the impacts before t_end (all faster than min_speed). */
void ref_bounce_init(ref_bounce *b, double g, double e, double y0,
                     double y_touch, double t_end);
/* Height of the centre and vertical velocity at t. */
void ref_bounce_at(const ref_bounce *b, double t, double *y, double *vy);

/* ---- a rigid convex polygon with no gravity between two static walls
 * x = x_lo (left) and x = x_hi (right): frictionless vertex impacts. */
typedef struct ref_spin {
    int nv;
    double px[REF_MAX_VERTS], py[REF_MAX_VERTS]; /* about the centroid */
    double m, inv_m, I, inv_I, e;
    double x_lo, x_hi;
    double cx, cy, vx, vy, th, w; /* state at time t */
    double t;
    double t_end, dt_scan;
    int impact_count;
    ref_impact impacts[REF_MAX_IMPACTS];
} ref_spin;

void ref_spin_init(ref_spin *s, int nv, const double *px, const double *py,
                   double m, double I, double e, double x_lo, double x_hi,
                   double cx, double cy, double vx, double vy, double th,
                   double w);
/* 0, or -1 on more than REF_MAX_IMPACTS impacts. */
int ref_spin_advance(ref_spin *s, double t);
/* State at the time reached (centre, velocity, angle, angular velocity). */
void ref_spin_state(const ref_spin *s, double *cx, double *cy, double *vx,
                    double *vy, double *th, double *w);

/* ---- a ball under gravity (0, -g) against one static circle: frictionless
 * impacts along the line of centres. */
typedef struct ref_ball {
    double g, e, R;       /* R: sum of the radii */
    double ox, oy;        /* centre of the static circle */
    double x, y, vx, vy;  /* state at time t */
    double t;
    int impact_count;
    ref_impact impacts[64];
} ref_ball;

void ref_ball_init(ref_ball *b, double g, double e, double R, double ox,
                   double oy, double x, double y, double vx, double vy);
int ref_ball_advance(ref_ball *b, double t);
void ref_ball_state(const ref_ball *b, double *x, double *y, double *vx,
                    double *vy);

#endif /* CAROM_ACCURACY_REFERENCE_H */
