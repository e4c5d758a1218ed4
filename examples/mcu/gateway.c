/* A sensor gateway on a microcontroller (see gateway.h). */
#include "gateway.h"

#include <string.h>

#include "board.h"

enum gateway_state {
    GW_STOPPING,   /* recovery: a stop was sent (its answer, a timeout or a refusal all go on) */
    GW_DRAINING,   /* recovery: dropping stale bytes until the line is quiet */
    GW_IDENTIFYING,/* recovery: product info asked */
    GW_RATING,     /* rated values asked */
    GW_STARTING,   /* start of the stream sent */
    GW_STREAMING   /* forwarding samples */
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
    lep_command cmd = {code, 0};
    g->state = next;
    if (lep_client_send(&g->client, &cmd) != LEP_OK) {
        board_log("write failed", 0);
    }
}

/* Start-up recovery: stop a stream left running, drain, identify. */
static void recover(gateway *g)
{
    g->counts.recoveries++;
    board_log("recovering the line", (int)g->counts.recoveries);
    send(g, LEP_CMD_STOP, GW_STOPPING);
}

static void on_response(gateway *g)
{
    lep_response resp;
    const lep_response *r = &resp;
    if (lep_client_response(&g->client, &resp) != LEP_OK)
        resp.code = 0;
    switch (g->state) {
    case GW_STOPPING:
        g->state = GW_DRAINING;
        g->since_ms = board_millis();
        break;
    case GW_IDENTIFYING:
        board_log(r->u.info.model, 0);
        send(g, LEP_CMD_RATED, GW_RATING);
        break;
    case GW_RATING:
        g->rated = r->u.rated;
        send(g, LEP_CMD_START, GW_STARTING);
        break;
    case GW_STARTING:
        board_log("streaming", 0);
        g->state = GW_STREAMING;
        g->since_ms = board_millis();
        break;
    default:
        break;
    }
}

static void on_sample(gateway *g)
{
    float si[LEP_AXES];
    lep_sample smp;
    const lep_sample *s = &smp;
    size_t i;
    if (lep_client_get_sample(&g->client, &smp) != LEP_OK)
        return;
    for (i = 0; i < LEP_AXES; i++) {
        si[i] = (float)s->raw[i] * g->rated.axis[i] / (float)LEP_RAW_FULL_SCALE;
    }
    g->counts.samples++;
    g->since_ms = board_millis();
    board_publish(s, si);
}

static void on_outcome(gateway *g, int rc)
{
    if (rc == LEP_STEP_RESPONSE) {
        on_response(g);
    } else if (rc == LEP_STEP_SAMPLE) {
        on_sample(g);
    } else if (rc < 0) {
        if (g->state == GW_STOPPING) {
            /* a stop that times out or is refused does not end the recovery */
            g->state = GW_DRAINING;
            g->since_ms = board_millis();
            return;
        }
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
    recover(g);
}

void gateway_poll(gateway *g)
{
    const uint8_t *data;
    size_t n = uart_ring_peek(&board_uart_rx, &data);
    uint32_t now = board_millis();

    if (g->state == GW_DRAINING) {
        if (n > 0) {
            uart_ring_consume(&board_uart_rx, n); /* stale bytes: dropped */
            g->since_ms = now;
        } else if (now - g->since_ms >= GATEWAY_QUIET_MS) {
            send(g, LEP_CMD_PRODUCT_INFO, GW_IDENTIFYING);
        }
        return;
    }
    if (g->state == GW_STREAMING && now - g->since_ms >= GATEWAY_WATCHDOG_MS) {
        g->counts.stalls++;
        board_log("stream stalled", (int)g->counts.stalls);
        recover(g);
        return;
    }
    if (n == 0) {
        size_t used;
        on_outcome(g, lep_client_step(&g->client, NULL, 0, &used)); /* deadlines */
        return;
    }
    while (n > 0) {
        size_t used = 0;
        int rc = lep_client_step(&g->client, data, n, &used);
        uart_ring_consume(&board_uart_rx, used);
        on_outcome(g, rc);
        if (g->state == GW_DRAINING) {
            return;
        }
        n = uart_ring_peek(&board_uart_rx, &data); /* the rest, or the wrapped part */
    }
}
