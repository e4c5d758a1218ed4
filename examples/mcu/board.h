/* What the gateway needs from a board: a UART to the sensor, a millisecond
 * tick and somewhere to send the samples. Two boards come with the example:
 * board_cmsdk.c (registers of an Arm CMSDK APB UART, the UART of Cortex-M0+
 * reference designs) and board_qemu_sensor.c (QEMU mps2-an385 with a scripted
 * sensor in the same image, for CI). */
#ifndef MCU_BOARD_H
#define MCU_BOARD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/message.h"
#include "uart_ring.h"

/* Bytes received from the sensor, filled by the board's UART RX interrupt. */
extern uart_ring board_uart_rx;

/* Clocks, UART at 460800 8N1 with its RX interrupt, a 1 kHz tick interrupt. */
void board_init(void);

/* Milliseconds since board_init, from the tick interrupt (wraps at 2^32). */
uint32_t board_millis(void);

/* Send bytes to the sensor; returns when they are in the transmitter. */
void board_uart_write(const uint8_t *data, size_t len);

/* Sleep until the next interrupt (a received byte or the tick). */
void board_idle(void);

/* Forward one sample: raw counts and, per axis, N or N m. */
void board_publish(const lep_sample *s, const float si[LEP_AXES]);

/* Something worth reporting happened: a state change, or an error (value is
 * then its LEP_E_* code, for lep_strerror if the board has room for the
 * strings); text is static. */
void board_log(const char *text, int value);

/* The board decides when the example ends (true: main returns); a real
 * gateway never ends. */
bool board_should_stop(void);

#endif
