/*
 * fw_main.c -- the suite firmware: runs the scene suite (suite.c) in a
 * static world buffer, measures the stack of carom_world_step by painting,
 * reports over semihosting and exits through it.
 *
 * Build-time settings: FW_WORLD_BYTES (world buffer), FW_SMALL (1: the
 * reduced suite only), FW_BOARD (a name printed first), FW_SIZES (print
 * what worlds cost in memory, sizes.c, instead of running the suite),
 * FW_PHASES (the calibration's phase markers, below).
 */
#include <stdint.h>

#include "fw.h"
#include "suite.h"

#ifndef FW_WORLD_BYTES
#error "define FW_WORLD_BYTES"
#endif
#ifndef FW_SMALL
#define FW_SMALL 0
#endif
#ifndef FW_BOARD
#define FW_BOARD "unknown"
#endif

#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
#define ADP_STOPPED_APPLICATION_EXIT 0x20026
#define ADP_STOPPED_RUNTIME_ERROR 0x20023

static int semihost(int op, const void *arg)
{
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void fw_write(const char *s) { (void)semihost(SYS_WRITE0, s); }

void fw_exit(int status)
{
    /* On 32-bit ARM the argument is the stop reason itself. */
    (void)semihost(SYS_EXIT, (const void *)(uintptr_t)(status == 0
                                   ? ADP_STOPPED_APPLICATION_EXIT
                                   : ADP_STOPPED_RUNTIME_ERROR));
    for (;;) {
    }
}

void platform_out(const char *s) { fw_write(s); }

/* ---- stack painting ------------------------------------------------------------ */

extern uint32_t __stack_bottom[], __stack_top[];
#define PAINT 0xA5C3E17Bu

static uintptr_t read_sp(void)
{
    uintptr_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

/* Everything below this function's own stack pointer is free: paint it. */
__attribute__((noinline)) void platform_stack_paint(void)
{
    volatile uint32_t *p = __stack_bottom;
    uintptr_t sp = read_sp();
    while ((uintptr_t)p < sp)
        *p++ = PAINT;
}

/* The lowest word that no longer holds the paint is the deepest the stack
 * went since the paint. */
long platform_stack_peak(uintptr_t sp_at_call)
{
    const volatile uint32_t *p = __stack_bottom;
    while (p < __stack_top && *p == PAINT)
        ++p;
    if (p == __stack_bottom)
        return -2;
    return (long)(sp_at_call - (uintptr_t)p);
}

/* The instruction-counting plugin (insn_count.c) watches this address. */
__attribute__((noinline)) void platform_mark(int what)
{
    __asm__ volatile("" : : "r"(what) : "memory");
}

/* ---- phases, for the instruction counter (FW_PHASES) ---------------------------------
 *
 * Built with FW_PHASES and a profiling library (CAROM_ENABLE_PROFILE), and
 * linked with --wrap=cr_prof_phase --wrap=carom_world_step: every phase
 * switch of the library and every step's start and end calls one of the
 * marker functions below, each at its own address, which the QEMU plugin
 * watches (phase=ADDR0:...:ADDR7). Markers 0 to 5 are the profiler's
 * phases, 6 is carom_world_step outside any phase, 7 is outside a step.
 * This code lives in its own section, .fwmeta, so that the plugin counts
 * its instructions apart (meta=START:END). */
#ifdef FW_PHASES
#include "carom.h"

#define FW_META __attribute__((noinline, section(".fwmeta")))
#define FW_MARKER(k)                                                           \
    FW_META void fw_phase_##k(void) { __asm__ volatile("" : : : "memory"); }
FW_MARKER(0)
FW_MARKER(1)
FW_MARKER(2)
FW_MARKER(3)
FW_MARKER(4)
FW_MARKER(5)
FW_MARKER(6)
FW_MARKER(7)

void __real_cr_prof_phase(const carom_world *w, int phase);
void __wrap_cr_prof_phase(const carom_world *w, int phase);
carom_status __real_carom_world_step(carom_world *w);
carom_status __wrap_carom_world_step(carom_world *w);

FW_META void __wrap_cr_prof_phase(const carom_world *w, int phase)
{
    switch (phase) {
    case 0: fw_phase_0(); break;
    case 1: fw_phase_1(); break;
    case 2: fw_phase_2(); break;
    case 3: fw_phase_3(); break;
    case 4: fw_phase_4(); break;
    case 5: fw_phase_5(); break;
    default: fw_phase_6(); break;
    }
    __real_cr_prof_phase(w, phase);
}

FW_META carom_status __wrap_carom_world_step(carom_world *w)
{
    carom_status st;
    fw_phase_6();
    st = __real_carom_world_step(w);
    fw_phase_7();
    return st;
}
#endif

/* ---- main --------------------------------------------------------------------------- */

static unsigned char world_mem[FW_WORLD_BYTES] __attribute__((aligned(16)));

int main(void)
{
    fw_write("board " FW_BOARD "\n");
#ifdef FW_SIZES
    (void)world_mem;
    return sizes_run();
#else
    return suite_run(world_mem, sizeof world_mem, FW_SMALL) == 0 ? 0 : 1;
#endif
}
