/* Receive ring buffer between a UART interrupt and the main loop (see uart_ring.h). */
#include "uart_ring.h"

/* Keep the compiler from moving buffer accesses across an index update (the
 * interrupt and the main loop run on one core: no hardware barrier needed). */
#if defined(__GNUC__)
#define COMPILER_BARRIER() __asm__ volatile("" ::: "memory")
#else
#define COMPILER_BARRIER() ((void)0)
#endif

void uart_ring_init(uart_ring *r)
{
    r->head = 0u;
    r->tail = 0u;
    r->overruns = 0u;
}

void uart_ring_put(uart_ring *r, uint8_t byte)
{
    uint32_t head = r->head;
    if (head - r->tail >= UART_RING_SIZE) {
        r->overruns++;
        return;
    }
    r->buf[head & (UART_RING_SIZE - 1u)] = byte;
    COMPILER_BARRIER();
    r->head = head + 1u; /* publish the byte after storing it */
}

size_t uart_ring_peek(const uart_ring *r, const uint8_t **data)
{
    uint32_t tail = r->tail;
    uint32_t used = r->head - tail;
    uint32_t start = tail & (UART_RING_SIZE - 1u);
    uint32_t span = UART_RING_SIZE - start;
    *data = &r->buf[start];
    return (size_t)(used < span ? used : span);
}

void uart_ring_consume(uart_ring *r, size_t n)
{
    COMPILER_BARRIER(); /* the bytes are read before they are released */
    r->tail += (uint32_t)n;
}
