/*
 * solver.h -- the contact solver's passes over a substep (internal).
 */
#ifndef CAROM_SOLVER_H
#define CAROM_SOLVER_H

#include "world.h"

typedef struct cr_substep {
    float h, inv_h;
    float push;              /* largest push-out speed */
    float t;                 /* its start, s from the step's start */
} cr_substep;

void cr_substep_init(cr_substep *s, const carom_world *w, float h);

/* Start of the step: no displacement yet, no body active. */
void cr_solver_begin(carom_world *w);

/* Body i (if not static) takes part in this substep's solve: flagged and
 * listed in w->active. */
void cr_solver_activate(carom_world *w, int i);

/*
 * Start of a substep: decide which contacts the solver takes (all of them
 * in the discrete method; in the events methods those not approaching
 * faster than the rest speed: the others are impacts, taken at their
 * instant) and mark their bodies active. Returns the number of contacts
 * solved.
 */
int cr_solver_classify(carom_world *w, int events);

/* Start of the step: the support order of the bodies (levels up from the
 * static ones, along the touching contacts; none without gravity). */
void cr_solver_levels(carom_world *w);

/* Mark the contacts shock propagation takes (a support within 8 degrees
 * of the vertical, by a body lower in the order), with the side of the
 * upper body: cr_solver_levels does it for the step; the events methods
 * again after each substep's impacts, which remake and add contacts. */
void cr_solver_mark_shocks(carom_world *w);

/* After the relax sweeps: one sweep up the support order with every
 * supporting body below held fixed (shock propagation). */
void cr_solver_shock(carom_world *w, const cr_substep *s);

/* After the warm start: take back, down the support order, the impulses
 * that would lift a body off its support (an impact's, carried over). */
void cr_solver_unload(carom_world *w, const cr_substep *s);

/* Cold start (bodies were added): estimate the support impulses of the
 * contacts that have no warm start from the weights they carry. */
void cr_solver_prime(carom_world *w, const cr_substep *s);

/* The sweep order of the contacts the solver takes (after classify, and
 * again after impacts handed contacts back to the solver). */
void cr_solver_order(carom_world *w);

/* Active bodies: remember the substep's start velocity, add the forces'
 * kick a h, and re-apply the contacts' accumulated impulses. */
void cr_solver_kick_and_warm(carom_world *w, const cr_substep *s);

/* Velocity sweeps over the solved contacts; `first`: the sweeps before the
 * bodies move (the speculative target uses the substep's start velocity). */
void cr_solver_solve(carom_world *w, const cr_substep *s, int first,
                     int iterations);

/* Position sweeps: remove a fraction of the overlap left after the move,
 * on positions only. */
void cr_solver_correct(carom_world *w, const cr_substep *s, int iterations);

/* Active bodies: turn the solved velocity into the substep's drift
 * (constant acceleration from the start velocity to it), velocity back to
 * the start of the substep. */
void cr_solver_set_drifts(carom_world *w, const cr_substep *s);

/* Active bodies: displacement and rotation since the start of the step,
 * after they moved. */
void cr_solver_update_deltas(carom_world *w);

/* End of step, every method: Newton restitution for the contacts that
 * were hit faster than the rest speed. Returns how many points bounced. */
int cr_solver_restitution(carom_world *w);

/* After a substep's impacts (events methods): the solver's contacts that
 * an impact has turned into impacts to come are not its own for the rest
 * of the substep (solver.c). */
void cr_solver_release_struck(carom_world *w);

/* Fastest normal approach of contact c's points at the bodies' current
 * velocities (>= 0). */
float cr_contact_approach(const carom_world *w, const cr_contact *c);

/* The slowest speed at which the touching points of contact c leave each
 * other (negative: one approaches); 0 if none touches. */
float cr_contact_recede(const carom_world *w, const cr_contact *c);

/* The approach speed above which contact (a, b) is an impact. */
float cr_rest_speed(const carom_world *w, int a, int b);

/* An approach below this fraction of the bodies' speeds is rounding, not
 * an impact: the event search (events.c) and the solver's share of the
 * contacts (cr_solver_classify) use the same bound, or a pair could fall
 * between them. */
#define CR_IMPACT_REL_TOL 1.0e-4f

/* Kinetic energy of a body of info `in` at velocity (v, om). */
float cr_kinetic(const cr_body_info *in, cr_v2 v, float om);

/* The largest s in [0, 1] with lin s + quad s^2 <= room (quad > 0,
 * room >= 0): how much of a velocity change whose energy is
 * E(s) = E(0) + lin s + quad s^2 may be kept without passing
 * E(0) + room (the energy limits of solver.c and events.c). */
float cr_energy_share(float lin, float quad, float room);

#endif /* CAROM_SOLVER_H */
