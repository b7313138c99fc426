/*
 * island.h -- islands of touching bodies, and sleep (internal).
 */
#ifndef CAROM_ISLAND_H
#define CAROM_ISLAND_H

#include "world.h"

/* The list of bodies the step simulates (w->awake). */
void cr_island_awake_list(carom_world *w);

/* Wake body `slot` and every body that fell asleep with it. */
void cr_island_wake(carom_world *w, int slot);

/* Start of a step, after the pairs are known: wake the sleeping islands
 * that a moving body reaches. Returns 1 if any woke (the step then looks
 * for pairs again). */
int cr_island_wake_touched(carom_world *w);

/* End of a step: update each body's still time; islands (bodies linked by
 * touching contacts) whose every body has been still for sleep_time fall
 * asleep. */
void cr_island_sleep(carom_world *w, float dt);

#endif /* CAROM_ISLAND_H */
