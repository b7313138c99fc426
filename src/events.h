/*
 * events.h -- the events methods: impacts at their instants, in time order
 * (internal).
 */
#ifndef CAROM_EVENTS_H
#define CAROM_EVENTS_H

#include "world.h"

/* Never: an impact time past any step. */
#define CR_NEVER 3.0e38f

/* Link every pair into its two bodies' lists (pair_head / next_a,b). */
void cr_pairs_link(carom_world *w);

/* Start of the step: every awake body drifts from local time 0 with the
 * acceleration of its forces (static and sleeping bodies: none). */
void cr_drifts_begin(carom_world *w);

/* Events methods, start of the step: the impact queue of every pair. */
void cr_events_begin(carom_world *w);

/* At a substep boundary t: the active bodies' drifts changed and the
 * contacts' classes may have: search their pairs again from t. */
void cr_events_refresh(carom_world *w, float t);

/*
 * Take the impacts up to local time t_end in time order. Each instant's
 * impacts are solved together with the resting contacts that link their
 * bodies (one small simultaneous problem), the rest of the substep keeps
 * touching bodies from closing in, and the pairs of the bodies involved
 * are searched again. Returns CAROM_OK, or a capacity status if a pair or
 * contact the impacts call for does not fit.
 */
carom_status cr_events_advance(carom_world *w, float t_end);

/* At substep boundary t: contacts for the pairs that met during the last
 * substep and had none. */
carom_status cr_events_add_contacts(carom_world *w, float t);

/* Bring the bodies to local time t. */
void cr_sync_all(carom_world *w, float t);

#endif /* CAROM_EVENTS_H */
