/* Start-up of the test images on QEMU mps2-an385: vector table, reset (data,
 * bss, semihosting handles, optional unaligned-access trap), fault report.
 *
 * Output, exit status and the vector files go through semihosting (newlib's
 * librdimon): run with -semihosting-config enable=on,target=native. A fault
 * prints the fault status registers and exits with status 3. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(void);
void lep_reset_handler(void);
void lep_fault_handler(void);
void initialise_monitor_handles(void);
void _init(void);
void _fini(void);

/* Called by newlib around main (no C++ constructors here): nothing to do. */
void _init(void)
{
}
void _fini(void)
{
}

extern uint32_t __stack_top;
extern uint32_t __data_load, __data_start, __data_end;
extern uint32_t __bss_start__, __bss_end__;

#define SCB_CCR (*(volatile uint32_t *)0xE000ED14u)
#define SCB_CFSR (*(volatile uint32_t *)0xE000ED28u)
#define SCB_HFSR (*(volatile uint32_t *)0xE000ED2Cu)
#define SCB_BFAR (*(volatile uint32_t *)0xE000ED38u)
#define SCB_CCR_UNALIGN_TRP (1u << 3)
#define SCB_CCR_DIV_0_TRP (1u << 4)

typedef void (*lep_vector)(void);

/* A program with a tick (the MCU example) defines its own; unexpected otherwise. */
void SysTick_Handler(void) __attribute__((weak, alias("lep_fault_handler")));

/* Initial stack pointer, reset, NMI, HardFault, MemManage, BusFault,
 * UsageFault, 4 reserved, SVCall, DebugMonitor, reserved, PendSV, SysTick. */
__attribute__((section(".vectors"), used)) const lep_vector lep_vectors[16] = {
    (lep_vector)(uintptr_t)&__stack_top,
    lep_reset_handler,
    lep_fault_handler,
    lep_fault_handler,
    lep_fault_handler,
    lep_fault_handler,
    lep_fault_handler,
    0,
    0,
    0,
    0,
    lep_fault_handler,
    lep_fault_handler,
    0,
    lep_fault_handler,
    SysTick_Handler,
};

void lep_reset_handler(void)
{
    uint32_t *src = &__data_load;
    uint32_t *dst = &__data_start;
    if (src != dst) {
        while (dst < &__data_end) {
            *dst++ = *src++;
        }
    }
    for (dst = &__bss_start__; dst < &__bss_end__; dst++) {
        *dst = 0;
    }
#ifdef LEP_TEST_TRAP_UNALIGNED
    /* ARMv6-M faults on every unaligned access; the Cortex-M3 does so only
     * with CCR.UNALIGN_TRP set (QEMU honours it), so ARMv6-M code run here
     * behaves as on a Cortex-M0/M0+. */
    SCB_CCR |= SCB_CCR_UNALIGN_TRP;
#endif
    SCB_CCR |= SCB_CCR_DIV_0_TRP;
    initialise_monitor_handles();
    exit(main());
}

void lep_fault_handler(void)
{
    printf("\nFAULT: HFSR=0x%08lx CFSR=0x%08lx BFAR=0x%08lx%s\n", (unsigned long)SCB_HFSR,
           (unsigned long)SCB_CFSR, (unsigned long)SCB_BFAR,
           (SCB_CFSR & (1u << 24)) != 0u ? " (unaligned access)" : "");
    fflush(stdout);
    _Exit(3);
}
