/* The example's board for CI: QEMU mps2-an385 (run as ARMv6-M code with
 * unaligned-access traps, see cmake/toolchains/qemu-mps2-an385-armv6m.cmake),
 * with a scripted sensor in the same image instead of a real UART.
 *
 * The SysTick interrupt (1 kHz) is both the millisecond tick and the "UART":
 * each millisecond the sensor (leptrino's own device side) takes what the
 * gateway wrote, answers it, streams 1.2 frames while streaming, and up to
 * 46 bytes (460800 baud) arrive in the RX ring buffer, as a UART RX interrupt
 * would put them. The timeline:
 *     0 ms  the sensor is already streaming (left on by an earlier run);
 *   400 ms  one data frame arrives corrupted (counted, not forwarded);
 *   700 ms  the sensor falls silent for 300 ms (no data, no answers);
 *  1600 ms  the run ends and checks what the gateway did.
 * Output and the exit status go through semihosting. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "board.h"
#include "systick.h"
#include "leptrino/leptrino.h"

#define CPU_HZ 25000000u /* mps2-an385 */

#define BYTES_PER_MS 46u /* 460800 baud, 10 bits a byte */
#define STALE_SEQ 60000u /* sequence numbers of the stale stream */
#define CORRUPT_AT_MS 400u
#define SILENT_FROM_MS 700u
#define SILENT_UNTIL_MS 1000u
#define END_MS 1600u

void SysTick_Handler(void);

uart_ring board_uart_rx;

static volatile uint32_t ticks;

/* Host -> sensor bytes (written by the main loop, taken by the tick). */
static uint8_t to_sensor[64];
static volatile uint32_t to_sensor_len;

/* Sensor -> host bytes not yet "on the wire". */
static uint8_t wire[2048];
static uint32_t wire_len, wire_pos;

static lep_device sensor;
static uint16_t seq = STALE_SEQ;
static uint32_t frame_credit; /* in fifths of a frame: 6 frames per 5 ms */

/* What the gateway did, as seen from outside it. */
static struct {
    uint32_t published, published_after_silence, stale_published, bad_si;
    uint32_t starts, stops, queries;
    uint16_t last_seq;
} seen;

static void wire_put(const uint8_t *data, size_t len)
{
    if (wire_pos == wire_len) {
        wire_pos = wire_len = 0;
    }
    if (wire_len + len <= sizeof wire) {
        memcpy(wire + wire_len, data, len);
        wire_len += (uint32_t)len;
    }
}

static void sensor_tick(uint32_t now)
{
    bool silent = now >= SILENT_FROM_MS && now < SILENT_UNTIL_MS;
    uint32_t i, n = to_sensor_len;
    size_t pos = 0;

    /* Commands from the gateway (dropped unanswered while silent). */
    while (pos < n) {
        lep_device_event ev;
        uint8_t answer[LEP_MAX_FRAME];
        size_t len = 0;
        pos += lep_device_feed(&sensor, to_sensor + pos, n - pos, &ev, answer, sizeof answer, &len);
        if (ev.type == LEP_DEVICE_COMMAND) {
            if (ev.code == LEP_CMD_START && ev.result == LEP_RESULT_OK) {
                seen.starts++;
                seq = 0; /* a stream started by the gateway, not the stale one */
            }
            seen.stops += ev.code == LEP_CMD_STOP;
            seen.queries += ev.code == LEP_CMD_PRODUCT_INFO;
        }
        if (len > 0 && !silent) {
            wire_put(answer, len);
        }
    }
    to_sensor_len = 0;

    /* 1200 frames a second while streaming. */
    if (lep_device_streaming(&sensor) && !silent) {
        frame_credit += 6u;
        while (frame_credit >= 5u) {
            lep_sample s;
            uint8_t frame[LEP_MAX_FRAME];
            size_t len = 0;
            frame_credit -= 5u;
            memset(&s, 0, sizeof s);
            s.reserved = seq++;
            s.raw[LEP_FX] = (int16_t)(s.reserved % 2000u) - 1000;
            s.raw[LEP_MZ] = 2500;
            if (lep_device_stream_frame(&s, frame, sizeof frame, &len) == LEP_OK) {
                if (now == CORRUPT_AT_MS) {
                    frame[len / 2u] ^= 0x5Au;
                }
                wire_put(frame, len);
            }
        }
    }

    /* The UART: what 1 ms of line time delivers, as the RX interrupt would. */
    for (i = 0; i < BYTES_PER_MS && wire_pos < wire_len; i++) {
        uart_ring_put(&board_uart_rx, wire[wire_pos++]);
    }
}

void SysTick_Handler(void)
{
    uint32_t now = ticks + 1u;
    ticks = now;
    sensor_tick(now);
}

void board_init(void)
{
    static const lep_rated rated = { { 500.0f, 500.0f, 1000.0f, 10.0f, 10.0f, 8.0f } };
    const lep_command start_cmd = { LEP_CMD_START, 0 };
    uint8_t start[LEP_MAX_FRAME];
    size_t start_len = 0;
    lep_product_info info;
    lep_device_event ev;
    uint8_t answer[LEP_MAX_FRAME];
    size_t len;

    memset(&info, 0, sizeof info);
    strcpy(info.model, "PFS055YA501U6");
    strcpy(info.serial, "12345678");
    strcpy(info.firmware, "1.13");
    if (lep_device_init(&sensor, &info, &rated, 0) != LEP_OK) {
        puts("FAIL: sensor init");
        exit(1);
    }
    /* An earlier run left the stream on. */
    (void)lep_command_frame(&start_cmd, start, sizeof start, &start_len);
    (void)lep_device_feed(&sensor, start, start_len, &ev, answer, sizeof answer, &len);
    if (!lep_device_streaming(&sensor)) {
        puts("FAIL: the scripted sensor did not start streaming");
        exit(1);
    }
    uart_ring_init(&board_uart_rx);
    systick_start_1khz(CPU_HZ);
}

uint32_t board_millis(void)
{
    return ticks;
}

void board_uart_write(const uint8_t *data, size_t len)
{
    __asm__ volatile("cpsid i" ::: "memory");
    if (to_sensor_len + len <= sizeof to_sensor) {
        memcpy(to_sensor + to_sensor_len, data, len);
        to_sensor_len += (uint32_t)len;
    }
    __asm__ volatile("cpsie i" ::: "memory");
}

void board_idle(void)
{
    __asm__ volatile("wfi");
}

void board_publish(const lep_sample *s, const float si[LEP_AXES])
{
    float fx = (float)s->raw[LEP_FX] * 500.0f / 10000.0f;
    seen.published++;
    if (s->reserved >= STALE_SEQ) {
        seen.stale_published++;
    }
    if (ticks >= SILENT_UNTIL_MS) {
        seen.published_after_silence++;
    }
    if (si[LEP_FX] != fx || si[LEP_MZ] != 2.0f) {
        seen.bad_si++;
    }
    seen.last_seq = s->reserved;
}

void board_log(const char *text, int value)
{
    printf("%5lu ms  %s (%d%s%s)\n", (unsigned long)ticks, text, value, value < 0 ? ": " : "",
           value < 0 ? lep_strerror(value) : "");
}

bool board_should_stop(void)
{
    int ok;
    if (ticks < END_MS) {
        return false;
    }
    systick_stop();
    printf("published %lu samples (%lu after the silence), stale %lu, wrong SI %lu; "
           "sensor saw %lu stops, %lu starts, %lu product-info queries; ring overruns %lu\n",
           (unsigned long)seen.published, (unsigned long)seen.published_after_silence,
           (unsigned long)seen.stale_published, (unsigned long)seen.bad_si,
           (unsigned long)seen.stops, (unsigned long)seen.starts, (unsigned long)seen.queries,
           (unsigned long)board_uart_rx.overruns);
    /* Streaming before the silence (~550 ms) and after it (~500 ms) at 1.2 kHz. */
    ok = seen.published >= 900u && seen.published_after_silence >= 400u &&
         seen.stale_published == 0u && seen.bad_si == 0u && seen.stops >= 2u && seen.starts >= 2u &&
         board_uart_rx.overruns == 0u;
    puts(ok ? "mcu example: OK" : "mcu example: FAIL");
    exit(ok ? 0 : 1);
}
