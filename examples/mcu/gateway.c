/* A sensor gateway on a microcontroller (see gateway.h). */
#include "gateway.h"

#include <string.h>

#include "board.h"

enum gateway_state {
    GW_RECOVERING, /* lep_client_recover: stop a stale stream, drain, identify */
    GW_RATING,     /* rated values asked */
    GW_STARTING,   /* start of the stream sent */
    GW_STREAMING   /* forwarding samples; the client's watchdog is armed */
};

/* ---- the client's I/O: the board's UART and tick ---------------------- */

static int uart_write(void *user, const uint8_t *data, size_t len)
{
    (void)user;
    board_uart_write(data, len);
    return LEP_OK;
}

static uint32_t tick_ms(void *user)
{
    (void)user;
    return board_millis();
}

/* ---- state changes ----------------------------------------------------- */

static void send(gateway *g, uint8_t code, uint8_t next)
{
    lep_command cmd = { code, 0 };
    g->state = next;
    if (lep_client_send(&g->client, &cmd) != LEP_OK) {
        board_log("write failed", 0);
    }
}

/* Start-up recovery, run by lep_client_step like a transaction. */
static void recover(gateway *g)
{
    g->counts.recoveries++;
    board_log("recovering the line", (int)g->counts.recoveries);
    g->state = GW_RECOVERING;
    if (lep_client_recover(&g->client, GATEWAY_QUIET_MS) != LEP_OK) {
        board_log("write failed", 0);
    }
}

static void on_response(gateway *g)
{
    lep_response r;
    switch (g->state) {
    case GW_RECOVERING:
        if (lep_client_response(&g->client, &r) == LEP_OK) {
            board_log(r.u.info.model, 0);
        }
        send(g, LEP_CMD_RATED, GW_RATING);
        break;
    case GW_RATING:
        if (lep_client_response(&g->client, &r) != LEP_OK) {
            recover(g);
            break;
        }
        g->rated = r.u.rated;
        send(g, LEP_CMD_START, GW_STARTING);
        break;
    case GW_STARTING:
        board_log("streaming", 0);
        g->state = GW_STREAMING;
        break;
    default:
        break;
    }
}

static void on_sample(gateway *g)
{
    lep_response r; /* the sample's message, decoded (r.u.sample) */
    float si[LEP_AXES];
    if (lep_client_response(&g->client, &r) != LEP_OK) {
        return;
    }
    lep_sample_to_si_f(&r.u.sample, &g->rated, si);
    g->counts.samples++;
    board_publish(&r.u.sample, si);
}

static void on_outcome(gateway *g, int rc)
{
    if (rc == LEP_STEP_RESPONSE) {
        on_response(g);
    } else if (rc == LEP_STEP_SAMPLE) {
        on_sample(g);
    } else if (rc == LEP_E_STALLED) {
        g->counts.stalls++;
        board_log("stream stalled", rc);
        recover(g);
    } else if (rc < 0) {
        g->counts.errors++;
        board_log("transaction failed", rc);
        recover(g);
    }
}

/* ---- public ------------------------------------------------------------ */

void gateway_init(gateway *g)
{
    lep_io io;
    memset(g, 0, sizeof *g);
    io.write = uart_write;
    io.read = NULL; /* the step API never reads: the ring buffer is fed in */
    io.now_ms = tick_ms;
    io.user = g;
    (void)lep_client_init(&g->client, &io);
    (void)lep_client_set_watchdog(&g->client, GATEWAY_WATCHDOG_MS);
    recover(g);
}

void gateway_poll(gateway *g)
{
    const uint8_t *data;
    size_t used = 0;
    size_t n = uart_ring_peek(&board_uart_rx, &data);
    if (n == 0) {
        /* an idle line: deadlines, the recovery's quiet time, the watchdog */
        on_outcome(g, lep_client_step(&g->client, NULL, 0, &used));
        return;
    }
    while (n > 0) {
        int rc = lep_client_step(&g->client, data, n, &used);
        uart_ring_consume(&board_uart_rx, used);
        on_outcome(g, rc);
        n = uart_ring_peek(&board_uart_rx, &data); /* the rest, or the wrapped part */
    }
}
