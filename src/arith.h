/*
 * arith.h -- the one arithmetic layer of carom (internal).
 *
 * Every float operation in src/ is written as a call to one of these
 * functions, so that a profiling build can count it by kind and pipeline
 * phase (the cost table of the design note). With CAROM_ENABLE_PROFILE off
 * each function is a plain float expression that the compiler inlines; the
 * library then contains no counter at all.
 *
 * What counts as what (kept in step with docs/cost-model.md):
 *   add: a + b             sub: a - b, and negation -a (it is 0 - a)
 *   mul: a * b             div: a / b
 *   cmp: a < b, <=, >, >=, ==, and min, max, abs (a compare and a select)
 *   sqrt: sqrtf(a)
 * There are no fused operations (the build uses -ffp-contract=off).
 * Integer and index arithmetic is not counted.
 */
#ifndef CAROM_ARITH_H
#define CAROM_ARITH_H

#include <float.h>
#include <math.h>

#include "carom.h"

/* The results are the same bits on every target only if each float
 * operation is rounded to float once: no wider intermediates, no fused or
 * reassociated arithmetic. (-ffp-contract=off cannot be checked here: the
 * Makefile passes it.) */
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0
#error "carom needs FLT_EVAL_METHOD == 0 (float arithmetic evaluated in float): on 32-bit x86 build with -msse2 -mfpmath=sse, not the x87 FPU"
#endif
#if defined(__FAST_MATH__)
#error "carom must not be built with -ffast-math (it reorders and contracts float arithmetic; results would differ between targets)"
#endif

#if defined(__GNUC__)
#define CR_INLINE static inline __attribute__((always_inline))
#else
#define CR_INLINE static inline
#endif

/* pi, to float precision (circle areas, angles) */
#define CR_PI 3.14159265358979323846f

/* ---- counting ---------------------------------------------------------- */

#if CAROM_ENABLE_PROFILE
/* Row of counters of the phase being executed, or NULL when not counting.
 * Set by cr_prof_phase(); one per library instance (profiling builds are
 * single-threaded measurement builds). */
extern uint64_t *carom__op_row;
#define CR_COUNT(kind)                                                        \
    do {                                                                      \
        if (carom__op_row) carom__op_row[kind] += 1u;                         \
    } while (0)
#else
#define CR_COUNT(kind) ((void)0)
#endif

/* ---- scalar ops ---------------------------------------------------------- */

#if defined(CR_ARITH_PLAIN) && !CAROM_ENABLE_PROFILE
/* Reference build for `make bench` (tools/bench.sh): the same operations as
 * bare C operators. The default build executes the same instructions (the
 * bench compares their callgrind counts). */
#define cr_add(a, b) ((a) + (b))
#define cr_sub(a, b) ((a) - (b))
#define cr_neg(a) (-(a))
#define cr_mul(a, b) ((a) * (b))
#define cr_div(a, b) ((a) / (b))
#define cr_sqrt(a) sqrtf(a)
#define cr_lt(a, b) ((a) < (b))
#define cr_le(a, b) ((a) <= (b))
#define cr_gt(a, b) ((a) > (b))
#define cr_ge(a, b) ((a) >= (b))
#define cr_eq(a, b) ((a) == (b))
CR_INLINE float cr_min(float a, float b) { return a < b ? a : b; }
CR_INLINE float cr_max(float a, float b) { return a > b ? a : b; }
CR_INLINE float cr_abs(float a) { return a < 0.0f ? -a : a; }
#else

CR_INLINE float cr_add(float a, float b) { CR_COUNT(CAROM_OP_ADD); return a + b; }
CR_INLINE float cr_sub(float a, float b) { CR_COUNT(CAROM_OP_SUB); return a - b; }
CR_INLINE float cr_neg(float a) { CR_COUNT(CAROM_OP_SUB); return -a; }
CR_INLINE float cr_mul(float a, float b) { CR_COUNT(CAROM_OP_MUL); return a * b; }
CR_INLINE float cr_div(float a, float b) { CR_COUNT(CAROM_OP_DIV); return a / b; }
CR_INLINE float cr_sqrt(float a) { CR_COUNT(CAROM_OP_SQRT); return sqrtf(a); }

CR_INLINE int cr_lt(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a < b; }
CR_INLINE int cr_le(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a <= b; }
CR_INLINE int cr_gt(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a > b; }
CR_INLINE int cr_ge(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a >= b; }
CR_INLINE int cr_eq(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a == b; }

CR_INLINE float cr_min(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a < b ? a : b; }
CR_INLINE float cr_max(float a, float b) { CR_COUNT(CAROM_OP_CMP); return a > b ? a : b; }
CR_INLINE float cr_abs(float a) { CR_COUNT(CAROM_OP_CMP); return a < 0.0f ? -a : a; }
#endif
CR_INLINE float cr_clamp(float a, float lo, float hi) { return cr_min(cr_max(a, lo), hi); }

/* Finite test without libm: NaN fails a == a, infinities fail a - a == 0.
 * Input validation, not counted (it runs outside the step). */
CR_INLINE int cr_finite(float a)
{
    return (a - a) == 0.0f;
}

/* ---- 2D vectors ----------------------------------------------------------- */

typedef carom_vec2 cr_v2;

CR_INLINE cr_v2 cr_v(float x, float y) { cr_v2 r; r.x = x; r.y = y; return r; }
CR_INLINE cr_v2 cr_vadd(cr_v2 a, cr_v2 b) { return cr_v(cr_add(a.x, b.x), cr_add(a.y, b.y)); }
CR_INLINE cr_v2 cr_vsub(cr_v2 a, cr_v2 b) { return cr_v(cr_sub(a.x, b.x), cr_sub(a.y, b.y)); }
CR_INLINE cr_v2 cr_vneg(cr_v2 a) { return cr_v(cr_neg(a.x), cr_neg(a.y)); }
CR_INLINE cr_v2 cr_vscale(float s, cr_v2 a) { return cr_v(cr_mul(s, a.x), cr_mul(s, a.y)); }
/* a + s b */
CR_INLINE cr_v2 cr_vmadd(cr_v2 a, float s, cr_v2 b) { return cr_vadd(a, cr_vscale(s, b)); }
CR_INLINE float cr_vdot(cr_v2 a, cr_v2 b) { return cr_add(cr_mul(a.x, b.x), cr_mul(a.y, b.y)); }
/* z of a x b */
CR_INLINE float cr_vcross(cr_v2 a, cr_v2 b) { return cr_sub(cr_mul(a.x, b.y), cr_mul(a.y, b.x)); }
/* w x r for scalar angular velocity w: (-w r.y, w r.x) */
CR_INLINE cr_v2 cr_vcross_sv(float w, cr_v2 r) { return cr_v(cr_neg(cr_mul(w, r.y)), cr_mul(w, r.x)); }
/* the unit normal rotated -90 degrees: the tangent of a contact */
CR_INLINE cr_v2 cr_vright(cr_v2 a) { return cr_v(a.y, cr_neg(a.x)); }
CR_INLINE float cr_vlen2(cr_v2 a) { return cr_vdot(a, a); }
CR_INLINE float cr_vlen(cr_v2 a) { return cr_sqrt(cr_vdot(a, a)); }

/*
 * Compensated (Kahan) accumulation: *sum += x, with *comp carrying the low
 * bits the float sum dropped, so a long run of small increments (x += v dt
 * over many steps) rounds once, not once per step. 4 operations.
 */
CR_INLINE void cr_kadd(float *sum, float *comp, float x)
{
    float y = cr_sub(x, *comp);
    float t = cr_add(*sum, y);
    *comp = cr_sub(cr_sub(t, *sum), y);
    *sum = t;
}

/* ---- rotations (unit complex numbers) ------------------------------------ */

typedef carom_rot cr_rot;

CR_INLINE cr_rot cr_r(float c, float s) { cr_rot r; r.c = c; r.s = s; return r; }
CR_INLINE cr_rot cr_rot_identity(void) { return cr_r(1.0f, 0.0f); }
/* q v */
CR_INLINE cr_v2 cr_rotate(cr_rot q, cr_v2 v)
{
    return cr_v(cr_sub(cr_mul(q.c, v.x), cr_mul(q.s, v.y)),
                cr_add(cr_mul(q.s, v.x), cr_mul(q.c, v.y)));
}
/* q^-1 v */
CR_INLINE cr_v2 cr_inv_rotate(cr_rot q, cr_v2 v)
{
    return cr_v(cr_add(cr_mul(q.c, v.x), cr_mul(q.s, v.y)),
                cr_sub(cr_mul(q.c, v.y), cr_mul(q.s, v.x)));
}
/* q p (compose: first p, then q) */
CR_INLINE cr_rot cr_rot_mul(cr_rot q, cr_rot p)
{
    return cr_r(cr_sub(cr_mul(q.c, p.c), cr_mul(q.s, p.s)),
                cr_add(cr_mul(q.s, p.c), cr_mul(q.c, p.s)));
}
/* back onto the unit circle (rounding drifts |q| away from 1) */
CR_INLINE cr_rot cr_rot_normalize(cr_rot q)
{
    float inv = cr_div(1.0f, cr_sqrt(cr_add(cr_mul(q.c, q.c), cr_mul(q.s, q.s))));
    return cr_r(cr_mul(q.c, inv), cr_mul(q.s, inv));
}

/* Unit rotation of `angle` radians by carom's own trigonometry (trig.c;
 * carom_rot_from_angle is this, for programs) */
carom_rot cr_rot_from_angle(float angle);

/* The continuous guard (continuous.c). */
#define CR_CONTINUOUS CAROM_ENABLE_CONTINUOUS

/* The angle of r in (-pi, pi] (trig.c; needs CAROM_ENABLE_ANGLES, or the
 * continuous guard with rotation on). */
float cr_rot_angle(carom_rot r);

#endif /* CAROM_ARITH_H */
