/*
 * profile.c -- operation counts by kind and phase (CAROM_ENABLE_PROFILE),
 * weight tables, and the names the tools print.
 *
 * The arithmetic layer (arith.h) increments carom__op_row[kind]; the step
 * points carom__op_row at the row of the phase it is in (cr_prof_phase),
 * or at nothing when no profile is attached. The default build compiles
 * none of the counting: no counter symbol exists in it (make check-symbols
 * proves this from the archive).
 */
#include <string.h>

#include "world.h"

#if CAROM_ENABLE_PROFILE
uint64_t *carom__op_row = 0;

void cr_prof_phase(const carom_world *w, int phase)
{
    carom__op_row = w->profile ? w->profile->ops[phase] : 0;
}
#endif

static const char *const cr_op_names[CAROM_OP_COUNT] = {
    "add", "sub", "mul", "div", "cmp", "sqrt"
};

static const char *const cr_phase_names[CAROM_PHASE_COUNT] = {
    "integration", "broadphase", "narrowphase", "impact_timing",
    "impulse_resolution", "resting_contacts"
};

const char *carom_op_name(carom_op op)
{
    return (unsigned)op < (unsigned)CAROM_OP_COUNT ? cr_op_names[op] : "unknown";
}

const char *carom_phase_name(carom_phase phase)
{
    return (unsigned)phase < (unsigned)CAROM_PHASE_COUNT ? cr_phase_names[phase]
                                                        : "unknown";
}

void carom_profile_reset(carom_profile *p)
{
    if (p)
        memset(p, 0, sizeof *p);
}

carom_status carom_world_set_profile(carom_world *w, carom_profile *p)
{
    if (!w)
        return CAROM_ERR_NULL;
#if CAROM_ENABLE_PROFILE
    w->profile = p;
    return CAROM_OK;
#else
    (void)p;
    return CAROM_ERR_DISABLED;
#endif
}

/* Weights, in the unit of each table (docs/cost-model.md):
 *  seed        the design note's cost table, in add units;
 *  cortex-m4f  FPv4-SP cycles (Cortex-M4F FPU instruction table: VADD,
 *              VSUB, VMUL, VCMP 1 cycle, VDIV and VSQRT 14);
 *  cortex-m0   soft-float cycles of GCC's library on a Cortex-M0 (averages
 *              measured on an LPC11U68, published with Qfplib-M0-full);
 *              compare is not in that table: 30 is an estimate. */
static const struct {
    const char *name;
    float w[CAROM_OP_COUNT];
} cr_presets[] = {
    {"seed", {1.0f, 1.0f, 1.5f, 4.0f, 1.0f, 6.0f}},
    {"cortex-m4f", {1.0f, 1.0f, 1.0f, 14.0f, 1.0f, 14.0f}},
    {"cortex-m0", {102.0f, 108.0f, 166.0f, 475.0f, 30.0f, 460.0f}},
};

carom_status carom_op_weights_preset(const char *name, carom_op_weights *out)
{
    size_t i;
    int k;
    if (!name || !out)
        return CAROM_ERR_NULL;
    for (i = 0; i < sizeof cr_presets / sizeof cr_presets[0]; ++i) {
        if (strcmp(name, cr_presets[i].name) == 0) {
            for (k = 0; k < CAROM_OP_COUNT; ++k)
                out->w[k] = cr_presets[i].w[k];
            return CAROM_OK;
        }
    }
    return CAROM_ERR_BAD_PARAMETER;
}

float carom_profile_cost(const carom_profile *p, const carom_op_weights *wt,
                         int phase)
{
#if CAROM_ENABLE_PROFILE
    float total = 0.0f;
    int ph, k;
    if (!p || !wt || phase < 0 || phase > CAROM_PHASE_COUNT)
        return 0.0f;
    for (ph = 0; ph < CAROM_PHASE_COUNT; ++ph) {
        if (phase != CAROM_PHASE_COUNT && ph != phase)
            continue;
        for (k = 0; k < CAROM_OP_COUNT; ++k)
            total = cr_add(total, cr_mul((float)p->ops[ph][k], wt->w[k]));
    }
    return total;
#else
    /* nothing was counted: no profile can hold counts of this build */
    (void)p;
    (void)wt;
    (void)phase;
    return 0.0f;
#endif
}
