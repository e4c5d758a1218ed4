/* lep_response_decode's two builds held to each other on seeded random messages.
 *
 * The library's message.c (in a speed build, the sample message takes its own
 * path ahead of the general checks) decodes every message; the reference is
 * the same message.c built with LEPTRINO_CODEC_SMALL (one path for every
 * message, as size builds have it) under other names (lep_small_*, see
 * test/CMakeLists.txt). The result and the whole lep_response, byte for
 * byte, must agree. Messages are random bytes steered towards the sample
 * message: its length, header bytes and counts near the +/-32000 limit. */
#include <stdio.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "leptrino/message.h"
#include "rng.h"
#include "unity.h"

/* The reference build's entry point (message.c compiled under this name). */
int lep_small_response_decode(const uint8_t *msg, size_t len, lep_response *r);

#define MESSAGES 200000u

void setUp(void)
{
}

void tearDown(void)
{
}

/* A random message of at most LEP_MAX_MESSAGE bytes into msg; its length.
 * Half are a sample message's header (code 0x30 or 0x32), a quarter of those
 * with one header byte or the length changed; half have counts near the
 * limit (-32050..32049); the rest is random. */
static size_t random_message(uint32_t *seed, uint8_t *msg)
{
    static const uint8_t codes[] = { LEP_CMD_SAMPLE, LEP_CMD_START, 0x31, LEP_CMD_STOP,
                                     LEP_CMD_RATED };
    uint32_t k = rng_next(seed);
    size_t len = (size_t)(rng_next(seed) % 41u);
    size_t i;
    for (i = 0; i < LEP_MAX_MESSAGE; i++) {
        msg[i] = (uint8_t)rng_next(seed);
    }
    if ((k & 1u) != 0u) {
        len = LEP_LEN_SAMPLE;
        msg[0] = LEP_LEN_SAMPLE;
        msg[1] = 0xFF;
        msg[2] = (k & 2u) != 0u ? LEP_CMD_START : LEP_CMD_SAMPLE;
        msg[3] = LEP_RESULT_OK;
        if ((k & 12u) == 0u) { /* one change */
            uint32_t w = rng_next(seed) % 5u;
            if (w == 4u) {
                len = (size_t)(rng_next(seed) % 41u);
            } else if (w == 2u) {
                msg[2] = codes[rng_next(seed) % sizeof(codes)];
            } else {
                msg[w] = (uint8_t)(w == 3u ? LEP_RESULT_STATE : rng_next(seed));
            }
        }
    }
    if ((k & 16u) != 0u) {
        for (i = 4; i < 16; i += 2) {
            uint32_t v = (uint32_t)(rng_next(seed) % 64100u) + 0x10000u - 32050u;
            msg[i] = (uint8_t)(v & 0xFFu);
            msg[i + 1] = (uint8_t)((v >> 8) & 0xFFu);
        }
    }
    return len;
}

static void test_response_decode_builds_agree(void)
{
    uint32_t seed = 0x5EED1234u;
    unsigned long samples = 0;
    unsigned long n;
    for (n = 0; n < MESSAGES; n++) {
        uint8_t msg[LEP_MAX_MESSAGE];
        size_t len = random_message(&seed, msg);
        lep_response got;
        lep_response want;
        int rc_got;
        int rc_want;
        char ctx[64];
        memset(&got, 0x5A, sizeof(got));
        memset(&want, 0xC3, sizeof(want));
        rc_got = lep_response_decode(msg, len, &got);
        rc_want = lep_small_response_decode(msg, len, &want);
        snprintf(ctx, sizeof(ctx), "message %lu (seed 0x5EED1234), length %u", n, (unsigned)len);
        TEST_ASSERT_EQUAL_INT_MESSAGE(rc_want, rc_got, ctx);
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(&want, &got, sizeof(want), ctx);
        if (rc_got == LEP_OK && len == LEP_LEN_SAMPLE) {
            samples++;
        }
    }
    /* the steering reached the sample path often (about one message in 8) */
    TEST_ASSERT_GREATER_THAN_UINT32((uint32_t)(MESSAGES / 16u), (uint32_t)samples);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_response_decode_builds_agree);
    return UNITY_END();
}
