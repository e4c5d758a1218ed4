/* A sensor gateway on a microcontroller: keeps a Leptrino sensor streaming
 * and forwards every sample (board_publish), without threads or blocking.
 *
 * It drives leptrino's step API from the main loop: bytes come from the UART
 * RX ring buffer, time from the board's millisecond tick. At start-up, and
 * whenever the stream stalls (the client's watchdog: LEP_E_STALLED) or a
 * transaction fails, it runs the client's non-blocking recovery
 * (lep_client_recover: stop a stale stream, drain, identify), reads the rated
 * values and starts the stream again. */
#ifndef MCU_GATEWAY_H
#define MCU_GATEWAY_H

#include <stdint.h>

#include "leptrino/leptrino.h"

/* No sample for this long while streaming: the stream is taken as stalled
 * (lep_client_set_watchdog). */
#define GATEWAY_WATCHDOG_MS 100u
/* Recovery: the line must stay quiet this long after the stop (lep_client_recover). */
#define GATEWAY_QUIET_MS 20u

typedef struct gateway_counts {
    uint32_t samples;    /* samples forwarded */
    uint32_t recoveries; /* recoveries begun (the first one at start-up) */
    uint32_t stalls;     /* stream watchdog expiries */
    uint32_t errors;     /* transactions that failed (timeout, NAKs, sensor error) */
} gateway_counts;

typedef struct gateway {
    lep_client client;
    lep_rated rated;
    gateway_counts counts;
    uint8_t state;
} gateway;

/* Bind the client to the board's UART and tick, and begin the recovery. */
void gateway_init(gateway *g);

/* Feed what the UART received since the last call (or only check the
 * clock); never blocks. Call it from the main loop, at least once per tick. */
void gateway_poll(gateway *g);

#endif
