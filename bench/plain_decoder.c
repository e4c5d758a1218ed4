/* The baseline: a plain byte-at-a-time state machine, written from the
 * protocol text (spec 2.3) the way host drivers for this sensor commonly
 * decode: a parse function called for every received byte (plain_step, in
 * its own file as a driver's parser is, so the read loop calls it per byte),
 * one switch per byte, BCC accumulated per byte, each message byte appended
 * with a bounds check. It knows DLE STX, DLE DLE, DLE ETX and the BCC;
 * anything else makes it hunt for the next DLE STX. plain_feed is the same
 * machine with the loop around it in this file, so the compiler can keep the
 * state in registers: a second, stronger baseline. leptrino-bench runs both
 * on the same bytes as lep_frame_decoder_feed and reports the ratios. */
#include "bench.h"

enum { P_HUNT, P_HUNT_DLE, P_DATA, P_DATA_DLE, P_BCC };

void plain_init(plain_decoder *p)
{
    p->state = P_HUNT;
    p->n = 0;
    p->bcc = 0;
}

static int step(plain_decoder *p, uint8_t b)
{
    switch (p->state) {
    case P_HUNT:
        if (b == 0x10) {
            p->state = P_HUNT_DLE;
        }
        break;
    case P_HUNT_DLE:
        if (b == 0x02) {
            p->n = 0;
            p->bcc = 0;
            p->state = P_DATA;
        } else if (b != 0x10) {
            p->state = P_HUNT;
        }
        break;
    case P_DATA:
        if (b == 0x10) {
            p->state = P_DATA_DLE;
        } else if (p->n < 128) {
            p->buf[p->n++] = b;
            p->bcc ^= b;
        } else {
            p->state = P_HUNT;
        }
        break;
    case P_DATA_DLE:
        if (b == 0x10 && p->n < 128) {
            p->buf[p->n++] = b;
            p->bcc ^= b;
            p->state = P_DATA;
        } else if (b == 0x03) {
            p->bcc ^= 0x03;
            p->state = P_BCC;
        } else if (b == 0x02) {
            p->n = 0;
            p->bcc = 0;
            p->state = P_DATA;
        } else {
            p->state = P_HUNT;
        }
        break;
    default: /* P_BCC */
        p->state = P_HUNT;
        return b == p->bcc && p->n >= 3;
    }
    return 0;
}

int plain_step(plain_decoder *p, uint8_t b)
{
    return step(p, b);
}

size_t plain_feed(plain_decoder *p, const uint8_t *data, size_t len, uint32_t *sink)
{
    size_t msgs = 0;
    size_t i;
    for (i = 0; i < len; i++) {
        if (step(p, data[i])) {
            *sink += p->buf[2];
            msgs++;
        }
    }
    return msgs;
}
