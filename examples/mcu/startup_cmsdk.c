/* Start-up of the example firmware on a CMSDK-based Cortex-M0+ system:
 * vector table (UART0 RX on IRQ 0), .data copied from flash, .bss zeroed. */
#include <stdint.h>

int main(void);
void Reset_Handler(void);
void Default_Handler(void);
void UART0_RX_Handler(void);
void SysTick_Handler(void);

extern uint32_t __stack_top, __data_load, __data_start, __data_end, __bss_start, __bss_end;

typedef void (*vector)(void);

__attribute__((section(".vectors"), used)) const vector vectors[16 + 1] = {
    (vector)(uintptr_t)&__stack_top,
    Reset_Handler,
    Default_Handler,
    Default_Handler,
    0,
    0,
    0,
    0,
    0,
    0,
    0,
    Default_Handler,
    0,
    0,
    Default_Handler,
    SysTick_Handler,
    UART0_RX_Handler, /* IRQ 0 */
};

void Reset_Handler(void)
{
    uint32_t *src = &__data_load, *dst = &__data_start;
    while (dst < &__data_end) {
        *dst++ = *src++;
    }
    for (dst = &__bss_start; dst < &__bss_end; dst++) {
        *dst = 0u;
    }
    (void)main();
    for (;;) {
    }
}

void Default_Handler(void)
{
    for (;;) {
    }
}
