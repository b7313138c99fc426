/*
 * startup.c -- reset and fault handling for the suite firmware (written for
 * this project; no vendor startup code). Cortex-M0/M3/M4: the core loads
 * the stack pointer and the reset handler from the vector table at 0.
 */
#include <stdint.h>

#include "fw.h"

extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];
extern uint32_t __stack_top[];

int main(void);
void fw_reset(void);
void fw_fault(void);

/* Copy .data from its load address, clear .bss, turn on the FPU where
 * there is one, run main, leave through semihosting. Touches no float. */
void fw_reset(void)
{
    uint32_t *src = __data_load, *dst = __data_start;
    while (dst < __data_end)
        *dst++ = *src++;
    for (dst = __bss_start; dst < __bss_end; ++dst)
        *dst = 0u;
#if defined(__ARM_FP)
    /* CPACR: full access to coprocessors 10 and 11 (the FPU). */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    fw_exit(main());
}

void fw_fault(void)
{
    fw_write("FAULT: the core took a fault or an unexpected exception\n");
    fw_exit(1);
}

typedef void (*fw_vector)(void);

/* The initial stack pointer, then reset and the 14 system exceptions; no
 * device interrupt is enabled, so none is listed. */
typedef struct fw_vector_table {
    uint32_t *initial_sp;
    fw_vector handler[15];
} fw_vector_table;

__attribute__((section(".vectors"), used))
const fw_vector_table fw_vectors = {
    __stack_top,
    {
        fw_reset,
        fw_fault, /* NMI */
        fw_fault, /* HardFault */
        fw_fault, /* MemManage */
        fw_fault, /* BusFault */
        fw_fault, /* UsageFault */
        0, 0, 0, 0,
        fw_fault, /* SVCall */
        fw_fault, /* DebugMonitor */
        0,
        fw_fault, /* PendSV */
        fw_fault, /* SysTick */
    },
};
