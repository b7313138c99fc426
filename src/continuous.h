/*
 * continuous.h -- the step's continuous guard against static bodies
 * (internal).
 */
#ifndef CAROM_CONTINUOUS_H
#define CAROM_CONTINUOUS_H

#include "world.h"

/*
 * After the step has put every body at its end pose (local time dt): a
 * dynamic body whose path over the step, from its pose at the step's
 * start to its end pose, meets a static body, and which ends reaching
 * past the line where it met it by more than the contact solver ever
 * leaves (it went into or through the static body), is put back at the
 * pose where its path met it, with its velocity. Counts each such stop in
 * stats.continuous_stops. Nothing else changes: a step with no stop
 * leaves every bit as it was. Needs the step's start poses in w->backup.
 */
void cr_continuous_statics(carom_world *w, float dt);

#endif /* CAROM_CONTINUOUS_H */
