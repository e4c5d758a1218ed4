/* Fuzz entry: arbitrary bytes into every receiving path of the core (frame
 * decoder in two chunkings, response decoder, command decoder, device, client
 * step). Invariants: no crash or UB, chunking never changes the outcome, and
 * every input byte is accounted for by the decoder's counters. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

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

static void check(int ok)
{
    if (!ok) {
        __builtin_trap();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lep_frame_decoder whole;
    lep_frame_decoder bytewise;
    lep_frame_event ev;
    lep_frame_event ev1;
    size_t pos = 0;
    size_t pos1 = 0;
    uint32_t delivered = 0;
    lep_device dev;
    lep_product_info info;
    lep_rated rated = {{1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f}};
    lep_client client;
    lep_io io = {sink_write, NULL, fixed_clock, NULL};
    lep_command probe = {LEP_CMD_RATED, 0};

    lep_frame_decoder_init(&whole);
    lep_frame_decoder_init(&bytewise);
    while (pos < size) {
        pos += lep_frame_decoder_feed(&whole, data + pos, size - pos, &ev);
        if (ev.type == LEP_FRAME_NONE) {
            break;
        }
        /* The byte-at-a-time decoder must reach the same event at the same byte. */
        do {
            pos1 += lep_frame_decoder_feed(&bytewise, data + pos1, 1, &ev1);
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
            delivered += (uint32_t)lep_frame_size(ev.msg, ev.len);
            /* A message that decodes must encode back to the same bytes. */
            if (lep_response_decode(ev.msg, ev.len, &r) == LEP_OK &&
                lep_response_encode(&r, again, sizeof(again), &n) == LEP_OK) {
                check(n == ev.len && memcmp(again, ev.msg, n) == 0);
            }
            (void)lep_command_decode(ev.msg, ev.len, &cmd, &result);
        } else if (ev.type == LEP_FRAME_NAK) {
            delivered += 2;
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
            size_t used = lep_device_feed(&dev, data + pos, size - pos, &dev_ev, out, sizeof(out), &out_len);
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
    return 0;
}
