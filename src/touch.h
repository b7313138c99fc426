/*
 * touch.h -- which pairs touch, step to step, and the begin/end-touch
 * events (contact reporting beyond impacts; sensors) (internal).
 */
#ifndef CAROM_TOUCH_H
#define CAROM_TOUCH_H

#include "world.h"

/* End of a successful step: the pairs touching now (contacts within the
 * contact slop at the step start, pairs that met in an impact during the
 * step, and sensor overlaps at the step's end), compared with the last
 * step's: begin and end events. Pairs of bodies that could not move
 * (asleep or static) keep their state. */
void cr_touch_update(carom_world *w);

/* Near the end of a step, before anything the step cannot undo: will the
 * touch list (max_pairs entries) hold the step's candidate pairs and the
 * touches carried over for bodies that did not move? 0: the step must
 * fail with CAROM_ERR_PAIR_CAPACITY (and the world may grow) rather than
 * lose a touch, which would end and begin again though nothing moved. */
int cr_touch_fits(const carom_world *w);

/* Body slot s is removed: its touches end without event. */
void cr_touch_forget(carom_world *w, int s);

#endif /* CAROM_TOUCH_H */
