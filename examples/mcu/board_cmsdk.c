/* The example's board for real hardware: a Cortex-M0+ system with an Arm
 * CMSDK APB UART (the UART of Arm's Cortex-M0/M0+ reference designs and of
 * the MPS2 boards) at UART0_BASE wired to the sensor, its RX interrupt on
 * IRQ 0, and SysTick as the millisecond tick. Port it by changing the
 * register block, the clock and the IRQ number; the gateway stays as it is.
 * Register layout: Arm Cortex-M System Design Kit TRM (DDI 0479), APB UART. */
#include "board.h"
#include "systick.h"

#ifndef BOARD_CPU_HZ
#define BOARD_CPU_HZ 25000000u
#endif
#define UART0_BASE 0x40004000u
#define SENSOR_BAUD 460800u

typedef struct cmsdk_uart {
    volatile uint32_t data;    /* 0x00 received / to send byte */
    volatile uint32_t state;   /* 0x04 bit 0 TX full, bit 1 RX full, bits 2-3 overruns */
    volatile uint32_t ctrl;    /* 0x08 bit 0 TX enable, bit 1 RX enable, bit 3 RX interrupt */
    volatile uint32_t intsts;  /* 0x0C interrupt status; write 1 to clear */
    volatile uint32_t bauddiv; /* 0x10 clock / baud rate, >= 16 */
} cmsdk_uart;

#define UART0 ((cmsdk_uart *)UART0_BASE)
#define UART_STATE_TX_FULL 0x1u
#define UART_STATE_RX_FULL 0x2u
#define UART_CTRL_TX_EN 0x1u
#define UART_CTRL_RX_EN 0x2u
#define UART_CTRL_RX_INT 0x8u
#define UART_INT_RX 0x2u

#define NVIC_ISER (*(volatile uint32_t *)0xE000E100u)
#define UART0_RX_IRQ 0u

void UART0_RX_Handler(void);
void SysTick_Handler(void);

uart_ring board_uart_rx;
static volatile uint32_t ticks;

/* The latest sample, for the application's forwarding task (CAN, Ethernet...). */
volatile struct {
    uint32_t count;
    lep_sample sample;
    float si[LEP_AXES];
} board_latest;

void UART0_RX_Handler(void)
{
    UART0->intsts = UART_INT_RX;
    while ((UART0->state & UART_STATE_RX_FULL) != 0u) {
        uart_ring_put(&board_uart_rx, (uint8_t)UART0->data);
    }
}

void SysTick_Handler(void)
{
    ticks = ticks + 1u;
}

void board_init(void)
{
    uart_ring_init(&board_uart_rx);
    UART0->bauddiv = BOARD_CPU_HZ / SENSOR_BAUD;
    UART0->ctrl = UART_CTRL_TX_EN | UART_CTRL_RX_EN | UART_CTRL_RX_INT;
    NVIC_ISER = 1u << UART0_RX_IRQ;
    systick_start_1khz(BOARD_CPU_HZ);
}

uint32_t board_millis(void)
{
    return ticks;
}

void board_uart_write(const uint8_t *data, size_t len)
{
    size_t i;
    for (i = 0; i < len; i++) {
        while ((UART0->state & UART_STATE_TX_FULL) != 0u) {
        }
        UART0->data = data[i];
    }
}

void board_idle(void)
{
    __asm__ volatile("wfi");
}

void board_publish(const lep_sample *s, const float si[LEP_AXES])
{
    size_t i;
    board_latest.sample = *s;
    for (i = 0; i < LEP_AXES; i++) {
        board_latest.si[i] = si[i];
    }
    board_latest.count = board_latest.count + 1u;
}

void board_log(const char *text, int value)
{
    (void)text;
    (void)value;
}

bool board_should_stop(void)
{
    return false;
}
