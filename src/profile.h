/*
 * profile.h -- which phase's counters the arithmetic layer counts into
 * (internal; docs/cost-model.md).
 */
#ifndef CAROM_PROFILE_H
#define CAROM_PROFILE_H

#include "carom.h"

#if CAROM_ENABLE_PROFILE
/* Count what follows into the row of this phase of w's profile. */
void cr_prof_phase(const carom_world *w, int phase);
#define CR_PHASE(w, phase) cr_prof_phase((w), (phase))
#define CR_PHASE_OFF() (carom__op_row = 0)
#else
#define CR_PHASE(w, phase) ((void)0)
#define CR_PHASE_OFF() ((void)0)
#endif

#endif /* CAROM_PROFILE_H */
