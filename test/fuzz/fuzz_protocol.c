/* Fuzz entry: arbitrary bytes into every receiving path of the core (frame
 * decoder in two chunkings and through feed_byte, response decoder, command
 * decoder, device, client step, and the client's blocking calls over a port
 * serving the input).
 * Invariants: no crash or UB, chunking never changes the outcome, every input
 * byte is accounted for by the decoder's counters, and the blocking calls
 * return (their reads stay bounded) with the sample counter exact. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "leptrino/leptrino.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint32_t fixed_clock(void *user)
{
    (void)user;
    return 0;
}

static int sink_write(void *user, const uint8_t *d, size_t n)
{
    (void)user;
    (void)d;
    (void)n;
    return 0;
}

/* A port serving the input in uneven chunks, 1 ms per chunk, then silence;
 * its clock starts just before the 32-bit wrap. */
typedef struct fuzz_port {
    const uint8_t *data;
    size_t len;
    size_t pos;
    uint32_t now;
    size_t reads;
} fuzz_port;

static uint32_t port_clock(void *user)
{
    return ((fuzz_port *)user)->now;
}

static int port_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    fuzz_port *p = user;
    size_t n;
    p->reads++;
    /* Every read either hands over input or lets time pass: a client that
     * keeps reading past this bound ignores its timeouts. */
    check(p->reads <= p->len + 10000u);
    if (p->pos >= p->len) {
        p->now += (uint32_t)(timeout_ms < 0 ? 1000 : timeout_ms);
        return 0;
    }
    n = 1u + (size_t)((p->data[p->pos] + p->reads) % 37u);
    if (n > cap) {
        n = cap;
    }
    if (n > p->len - p->pos) {
        n = p->len - p->pos;
    }
    memcpy(buf, p->data + p->pos, n);
    p->pos += n;
    p->now += 1u;
    return (int)n;
}

/* The blocking calls over the input: recovery, a query, then a stream read
 * to the end. Every call must return, and the counters must stay consistent. */
static void blocking_client(const uint8_t *data, size_t size)
{
    static const uint8_t start_answer[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    fuzz_port port = { data, size, 0, 0xFFFFFF00u, 0 };
    lep_io io = { sink_write, port_read, port_clock, &port };
    lep_client c;
    lep_command start = { LEP_CMD_START, 0 };
    lep_client_stats st;
    lep_sample batch[8];
    lep_rated rated;
    size_t used;
    size_t n;
    size_t rounds;
    uint32_t delivered = 0;
    uint32_t t0;
    check(lep_client_init(&c, &io) == LEP_OK);
    check(lep_client_set_timeout(&c, 5) == LEP_OK);
    /* Time is honoured: 1 ms passes per chunk read, so a call that kept
     * reading past its deadline would show here. Bounds: 4 attempts (3 NAK
     * retries) of 5 ms + 1 ms each; a drain of 20 timeouts + quiet time. */
    t0 = port.now;
    (void)lep_client_sync(&c, 3, NULL);
    check(port.now - t0 <= 4u * 6u + (20u * 5u + 3u + 1u) + 4u * 6u);
    t0 = port.now;
    (void)lep_client_rated(&c, &rated);
    check(port.now - t0 <= 4u * 6u);
    /* Enter streaming through the step API with a canned start answer. */
    check(lep_client_send(&c, &start) == LEP_OK);
    if (lep_client_step(&c, start_answer, sizeof(start_answer), &used) != LEP_STEP_RESPONSE) {
        return; /* the input left the decoder inside a frame */
    }
    check(lep_client_streaming(&c));
    for (rounds = 0; rounds <= size; rounds++) {
        int rc;
        t0 = port.now;
        rc = lep_client_next_samples(&c, batch, 8, &n, 5);
        check(port.now - t0 <= 5u + 2u + 2u * 8u);
        check(n <= 8);
        delivered += (uint32_t)n;
        if (rc != LEP_OK) {
            break;
        }
        check(n >= 1);
    }
    check(rounds <= size);
    lep_client_get_stats(&c, &st);
    check(st.samples == delivered);
    (void)lep_client_stop(&c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lep_frame_decoder whole;
    lep_frame_decoder bytewise;
    lep_frame_decoder by_byte; /* bytewise's twin, fed through lep_frame_decoder_feed_byte */
    lep_frame_event ev;
    lep_frame_event ev1;
    size_t pos = 0;
    size_t pos1 = 0;
    uint32_t delivered = 0;
    size_t shared_dle = (size_t)-1; /* position of a 0x10 BCC just delivered */
    lep_device dev;
    lep_product_info info;
    lep_rated rated = { { 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f } };
    lep_client client;
    lep_io io = { sink_write, NULL, fixed_clock, NULL };
    lep_command probe = { LEP_CMD_RATED, 0 };

    lep_frame_decoder_init(&whole);
    lep_frame_decoder_init(&bytewise);
    lep_frame_decoder_init(&by_byte);
    while (pos < size) {
        size_t fsize;
        pos += lep_frame_decoder_feed(&whole, data + pos, size - pos, &ev);
        if (ev.type == LEP_FRAME_NONE) {
            break;
        }
        /* The byte-at-a-time decoder must reach the same event at the same byte. */
        do {
            lep_frame_event ev2;
            check(lep_frame_decoder_feed_byte(&by_byte, data[pos1], &ev2) == LEP_OK);
            pos1 += lep_frame_decoder_feed(&bytewise, data + pos1, 1, &ev1);
            check(ev2.type == ev1.type && (ev2.type != LEP_FRAME_ERROR || ev2.error == ev1.error));
            check(memcmp(&by_byte, &bytewise, sizeof(by_byte)) == 0);
        } while (ev1.type == LEP_FRAME_NONE && pos1 < pos);
        check(ev1.type == ev.type && pos1 == pos && ev1.error == ev.error);
        if (ev.type == LEP_FRAME_MESSAGE) {
            lep_response r;
            lep_command cmd;
            uint8_t result;
            uint8_t again[LEP_MAX_MESSAGE];
            size_t n;
            check(ev.len == ev1.len && memcmp(ev.msg, ev1.msg, ev.len) == 0);
            check(ev.len >= 1 && ev.len <= LEP_MAX_MESSAGE);
            /* A BCC of 0x10 may double as the DLE that opens the next frame or NAK
             * (frame.h: resync after a lost BCC): count that byte once. */
            fsize = lep_frame_size(ev.msg, ev.len);
            delivered += (uint32_t)(pos - fsize == shared_dle ? fsize - 1u : fsize);
            shared_dle = data[pos - 1] == LEP_DLE ? pos - 1 : (size_t)-1;
            /* A message that decodes has a canonical form (space padding, last
             * reserved byte 0) that decodes to the same and encodes to itself. */
            if (lep_response_decode(ev.msg, ev.len, &r) == LEP_OK) {
                lep_response r2;
                uint8_t twice[LEP_MAX_MESSAGE];
                size_t n2;
                check(lep_response_encode(&r, again, sizeof(again), &n) == LEP_OK);
                check(n == ev.len);
                check(lep_response_decode(again, n, &r2) == LEP_OK);
                check(lep_response_encode(&r2, twice, sizeof(twice), &n2) == LEP_OK);
                check(n2 == n && memcmp(again, twice, n) == 0);
            }
            (void)lep_command_decode(ev.msg, ev.len, &cmd, &result);
        } else if (ev.type == LEP_FRAME_NAK) {
            delivered += pos - 2u == shared_dle ? 1u : 2u;
            shared_dle = (size_t)-1;
        } else {
            shared_dle = (size_t)-1;
        }
    }
    /* Every byte is in a delivered frame, a NAK, discarded, or in the frame still open. */
    check(whole.stats.bytes_discarded + delivered <= size);

    memset(&info, 0, sizeof(info));
    if (lep_device_init(&dev, &info, &rated, 0) == LEP_OK) {
        uint8_t out[LEP_MAX_FRAME];
        size_t out_len;
        lep_device_event dev_ev;
        pos = 0;
        while (pos < size) {
            size_t used =
                lep_device_feed(&dev, data + pos, size - pos, &dev_ev, out, sizeof(out), &out_len);
            check(used > 0 && out_len <= sizeof(out));
            pos += used;
        }
    }

    if (lep_client_init(&client, &io) == LEP_OK && lep_client_send(&client, &probe) == LEP_OK) {
        pos = 0;
        while (pos < size) {
            size_t used = 0;
            int rc = lep_client_step(&client, data + pos, size - pos, &used);
            check(used <= size - pos);
            pos += used;
            if (rc < 0 || (used == 0 && rc == LEP_STEP_NONE)) {
                break;
            }
        }
    }
    blocking_client(data, size);
    return 0;
}
