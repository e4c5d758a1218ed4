/* The Cortex-M SysTick timer as the millisecond tick (Armv6-M/v7-M
 * architecture reference: SYST_CSR, SYST_RVR, SYST_CVR). */
#ifndef MCU_SYSTICK_H
#define MCU_SYSTICK_H

#include <stdint.h>

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

/* Interrupt (SysTick_Handler) every millisecond from the processor clock. */
static inline void systick_start_1khz(uint32_t cpu_hz)
{
    SYST_RVR = cpu_hz / 1000u - 1u;
    SYST_CVR = 0u;
    SYST_CSR = 7u; /* processor clock, interrupt, enable */
}

static inline void systick_stop(void)
{
    SYST_CSR = 0u;
}

#endif
