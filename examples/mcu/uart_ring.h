/* Receive ring buffer between a UART interrupt and the main loop.
 *
 * One producer (the RX interrupt: uart_ring_put), one consumer (the main
 * loop: uart_ring_peek + uart_ring_consume). No lock: each side writes only
 * its own index, and 32-bit loads and stores are atomic on a Cortex-M. The
 * consumer reads the bytes in place (no copy), in at most two spans when
 * they wrap around the end of the buffer. */
#ifndef MCU_UART_RING_H
#define MCU_UART_RING_H

#include <stddef.h>
#include <stdint.h>

/* Capacity in bytes, a power of two. At 460800 baud (46 bytes/ms) 256 bytes
 * give the main loop 5 ms of slack. */
#define UART_RING_SIZE 256u

typedef struct uart_ring {
    volatile uint32_t head;     /* written by the interrupt: bytes ever put */
    volatile uint32_t tail;     /* written by the main loop: bytes ever consumed */
    volatile uint32_t overruns; /* bytes the interrupt dropped because the ring was full */
    uint8_t buf[UART_RING_SIZE];
} uart_ring;

/* Empty the ring (before the interrupt is enabled). */
void uart_ring_init(uart_ring *r);

/* Interrupt side: store one received byte; a full ring drops it and counts it. */
void uart_ring_put(uart_ring *r, uint8_t byte);

/* Main-loop side: the contiguous bytes waiting at the tail (*data points into
 * the ring); returns their count, 0 when empty. */
size_t uart_ring_peek(const uart_ring *r, const uint8_t **data);

/* Main-loop side: release n bytes returned by uart_ring_peek. */
void uart_ring_consume(uart_ring *r, size_t n);

#endif
