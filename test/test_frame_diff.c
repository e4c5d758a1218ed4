/* The decoder's two builds held to each other on seeded random streams.
 *
 * The library's frame.c (the word-at-a-time decoder, unless this build
 * optimises for size) runs every stream at several chunkings through feed,
 * feed_all, the two in turn, and push1 + feed. The reference is the same
 * frame.c built with LEPTRINO_FRAME_SMALL (the one-byte machine only) under
 * other names (lep_small_*, see test/CMakeLists.txt), fed each whole stream
 * one event at a time; its feed of one byte and its feed_byte are held to each
 * other at every byte. The library's feed_byte runs every stream too (API_BYTE,
 * its counters and busy() checked after every byte). Events (type, error, message bytes, and through feed the
 * input position at which each completes) must agree, and so must the counters
 * when each event is handed over (from feed, or inside the feed_all handler)
 * and the counters and busy() at the end of every chunk: the reference's are
 * taken after every input byte. */
#include <stdio.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "rng.h"
#include "unity.h"

/* The reference build's entry points (frame.c compiled under these names). */
uint8_t lep_small_bcc(const uint8_t *msg, size_t len);
int lep_small_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap,
                           size_t *out_len);
void lep_small_frame_decoder_init(lep_frame_decoder *d);
size_t lep_small_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                                    lep_frame_event *ev);
bool lep_small_frame_decoder_busy(const lep_frame_decoder *d);
int lep_small_frame_decoder_feed_byte(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev);

#define MAX_INPUT 4096u
#define MAX_EVENTS 512u
#define STREAMS 300u

typedef struct diff_event {
    int type;
    int error;
    size_t pos; /* input bytes consumed when it completed (through feed), else 0 */
    size_t len;
    uint8_t msg[LEP_MAX_MESSAGE];
    lep_frame_stats stats; /* the decoder's counters when the event was handed over */
} diff_event;

typedef struct diff_run {
    diff_event ev[MAX_EVENTS];
    size_t n;
    size_t pos;
    bool overflow;
    lep_frame_stats stats;
    bool busy;
    const lep_frame_decoder *dec; /* the decoder being fed */
    size_t diverged; /* first chunk end where counters or busy() differed, or NO_DIVERGENCE */
} diff_run;

#define NO_DIVERGENCE ((size_t)-1)

enum chunking { CH_WHOLE, CH_BYTES, CH_SMALL, CH_LARGE, CH_32, CH_WORDISH, CH_MIXED, CH_COUNT };
enum api { API_FEED, API_FEED_ALL, API_MIXED, API_PUSH1, API_BYTE, API_COUNT };

static uint8_t g_in[MAX_INPUT];
static diff_run g_ref;
static diff_run g_got;
/* The reference's counters and busy() after the first i input bytes. */
static lep_frame_stats g_ref_stats[MAX_INPUT + 1u];
static bool g_ref_busy[MAX_INPUT + 1u];

void setUp(void)
{
}

void tearDown(void)
{
}

static void record(diff_run *r, const lep_frame_event *ev, bool with_pos)
{
    diff_event *e;
    if (r->n == MAX_EVENTS) {
        r->overflow = true;
        return;
    }
    e = &r->ev[r->n++];
    memset(e, 0, sizeof(*e));
    e->type = ev->type;
    e->error = ev->type == LEP_FRAME_ERROR ? ev->error : LEP_OK;
    e->pos = with_pos ? r->pos : 0u;
    if (ev->type == LEP_FRAME_MESSAGE) {
        e->len = ev->len;
        memcpy(e->msg, ev->msg, ev->len);
    }
    e->stats = r->dec->stats;
}

static void on_event(void *user, const lep_frame_event *ev)
{
    record(user, ev, false);
}

/* A stream rich in what the decoder must handle: noise full of DLE, STX, ETX
 * and NAK, frames of 0 to 160 message bytes (encoded, or by hand when the
 * encoder refuses them), wrong BCCs, bytes changed and bytes lost. */
static size_t make_stream(uint32_t *s)
{
    static const uint8_t alphabet[] = { 0x10, 0x10, 0x10, 0x02, 0x03, 0x15, 0x00, 0x13, 0x12 };
    const uint32_t mode = rng_next(s) % 4u;
    const size_t target = 1u + rng_next(s) % (MAX_INPUT - 400u);
    size_t len = 0;
    while (len < target) {
        const uint32_t k = rng_next(s) % 16u;
        if (mode == 0u || k < 3u) { /* noise */
            size_t n = 1u + rng_next(s) % 30u;
            while (n-- > 0u) {
                const uint32_t r = rng_next(s);
                g_in[len++] =
                    (r & 3u) != 0u ? alphabet[(r >> 2) % sizeof(alphabet)] : (uint8_t)(r >> 8);
            }
        } else { /* a frame, perhaps damaged */
            uint8_t msg[160];
            const uint32_t lk = rng_next(s) % 10u;
            const size_t ml = lk == 0u   ? 0u
                              : lk == 1u ? 120u + rng_next(s) % 40u
                              : lk < 5u  ? 1u + rng_next(s) % LEP_MAX_MESSAGE
                                         : 20u;
            size_t n = 0;
            size_t j;
            for (j = 0; j < ml; j++) {
                const uint32_t r = rng_next(s);
                msg[j] = (r & 1u) != 0u ? alphabet[(r >> 1) % sizeof(alphabet)] : (uint8_t)(r >> 8);
                if (rng_next(s) % 4u == 0u) {
                    msg[j] = LEP_DLE;
                }
            }
            if (ml == 0u || ml > LEP_MAX_MESSAGE || rng_next(s) % 8u == 0u) {
                /* by hand: empty, over-long, or a BCC that is likely wrong */
                g_in[len++] = LEP_DLE;
                g_in[len++] = LEP_STX;
                for (j = 0; j < ml; j++) {
                    g_in[len++] = msg[j];
                    if (msg[j] == LEP_DLE) {
                        g_in[len++] = LEP_DLE;
                    }
                }
                g_in[len++] = LEP_DLE;
                g_in[len++] = LEP_ETX;
                g_in[len++] =
                    (rng_next(s) & 1u) != 0u ? lep_small_bcc(msg, ml) : (uint8_t)rng_next(s);
                n = 2u * ml + 5u;
            } else {
                TEST_ASSERT_EQUAL_INT(
                    LEP_OK, lep_small_frame_encode(msg, ml, g_in + len, sizeof(g_in) - len, &n));
                len += n;
            }
            if (mode >= 2u && rng_next(s) % 3u == 0u) { /* change a few bytes */
                size_t m = 1u + rng_next(s) % 3u;
                while (m-- > 0u) {
                    const size_t at = len - 1u - rng_next(s) % (n < len ? n : len);
                    g_in[at] = (rng_next(s) & 1u) != 0u ? alphabet[rng_next(s) % sizeof(alphabet)]
                                                        : (uint8_t)rng_next(s);
                }
            }
            if (mode == 3u && rng_next(s) % 4u == 0u) { /* lose a byte or two */
                const size_t lost = 1u + rng_next(s) % 2u;
                len = lost < len ? len - lost : 0u;
            }
        }
    }
    return len;
}

/* The reference: the one-byte machine, the whole stream through feed. */
static void run_reference(size_t len, diff_run *r)
{
    lep_frame_decoder d;
    lep_frame_decoder twin;
    const uint8_t *p = g_in;
    size_t i;
    memset(r, 0, sizeof(*r));
    r->dec = &d;
    lep_small_frame_decoder_init(&d);
    while (p < g_in + len) {
        lep_frame_event ev;
        const size_t used = lep_small_frame_decoder_feed(&d, p, (size_t)(g_in + len - p), &ev);
        TEST_ASSERT_TRUE(used > 0u);
        p += used;
        r->pos = (size_t)(p - g_in);
        if (ev.type != LEP_FRAME_NONE) {
            record(r, &ev, true);
        }
    }
    r->stats = d.stats;
    r->busy = lep_small_frame_decoder_busy(&d);
    /* again byte by byte, for the counters and busy() after every byte, and
     * through feed_byte on a twin: the same event and decoder at every byte */
    lep_small_frame_decoder_init(&d);
    lep_small_frame_decoder_init(&twin);
    g_ref_stats[0] = d.stats;
    g_ref_busy[0] = lep_small_frame_decoder_busy(&d);
    for (i = 0; i < len; i++) {
        lep_frame_event ev;
        lep_frame_event ev_byte;
        TEST_ASSERT_EQUAL_size_t(1u, lep_small_frame_decoder_feed(&d, g_in + i, 1u, &ev));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_small_frame_decoder_feed_byte(&twin, g_in[i], &ev_byte));
        TEST_ASSERT_EQUAL_INT(ev.type, ev_byte.type);
        if (ev.type != LEP_FRAME_NONE) {
            TEST_ASSERT_EQUAL_INT(ev.error, ev_byte.error);
            TEST_ASSERT_EQUAL_size_t(ev.len, ev_byte.len);
            TEST_ASSERT_TRUE((ev.msg == NULL) == (ev_byte.msg == NULL));
        }
        TEST_ASSERT_EQUAL_MEMORY(&d, &twin, sizeof(d));
        g_ref_stats[i + 1u] = d.stats;
        g_ref_busy[i + 1u] = lep_small_frame_decoder_busy(&d);
    }
}

/* Note the first chunk end at which d's counters or busy() differ from the reference's. */
static void check_position(diff_run *r, const lep_frame_decoder *d, size_t off)
{
    if (r->diverged == NO_DIVERGENCE &&
        (memcmp(&d->stats, &g_ref_stats[off], sizeof(d->stats)) != 0 ||
         lep_frame_decoder_busy(d) != g_ref_busy[off])) {
        r->diverged = off;
    }
}

static size_t chunk_size(enum chunking how, size_t left, uint32_t *s)
{
    size_t c;
    switch (how) {
    case CH_WHOLE:
        c = left;
        break;
    case CH_BYTES:
        c = 1;
        break;
    case CH_SMALL:
        c = 1u + rng_next(s) % 9u;
        break;
    case CH_LARGE:
        c = 1u + rng_next(s) % 200u;
        break;
    case CH_32:
        c = 32;
        break;
    case CH_WORDISH:
        c = 7u + rng_next(s) % 3u;
        break;
    default:
        c = rng_next(s) % 4u == 0u ? 0u : 1u + rng_next(s) % 64u;
        break; /* empty feeds too */
    }
    return c < left ? c : left;
}

/* The library's decoder on the stream in chunks, through one api. */
static void run_library(size_t len, enum api api, enum chunking how, uint32_t seed, diff_run *r)
{
    lep_frame_decoder d;
    size_t off = 0;
    unsigned calls = 0;
    uint32_t s = seed | 1u;
    memset(r, 0, sizeof(*r));
    r->dec = &d;
    r->diverged = NO_DIVERGENCE;
    lep_frame_decoder_init(&d);
    while (off < len) {
        const size_t c = chunk_size(how, len - off, &s);
        const bool all = api == API_FEED_ALL || (api == API_MIXED && (calls++ & 1u) != 0u);
        const uint8_t *p = g_in + off;
        size_t left = c;
        if (all) {
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_all(&d, p, c, on_event, r));
            off += c;
            check_position(r, &d, off);
            continue;
        }
        if (api == API_PUSH1 && c == 1u && lep_frame_decoder_push1(&d, *p)) {
            off += 1u;
            check_position(r, &d, off);
            continue;
        }
        if (api == API_BYTE) { /* every byte of the chunk, each checked */
            for (; left > 0u; left--) {
                lep_frame_event ev;
                TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_byte(&d, *p++, &ev));
                r->pos = (size_t)(p - g_in);
                if (ev.type != LEP_FRAME_NONE) {
                    record(r, &ev, true);
                }
                check_position(r, &d, r->pos);
            }
            off += c;
            continue;
        }
        do { /* feed, every event drained */
            lep_frame_event ev;
            const size_t used = lep_frame_decoder_feed(&d, p, left, &ev);
            TEST_ASSERT_TRUE(used <= left);
            TEST_ASSERT_TRUE(left == 0u || used > 0u);
            TEST_ASSERT_TRUE(ev.type != LEP_FRAME_NONE || used == left);
            p += used;
            left -= used;
            r->pos = (size_t)(p - g_in);
            if (ev.type != LEP_FRAME_NONE) {
                record(r, &ev, api != API_MIXED);
            }
        } while (left > 0u);
        off += c;
        check_position(r, &d, off);
    }
    r->stats = d.stats;
    r->busy = lep_frame_decoder_busy(&d);
}

static void expect_same(const diff_run *want, const diff_run *got, bool with_pos, const char *what)
{
    size_t i;
    TEST_ASSERT_FALSE_MESSAGE(want->overflow || got->overflow, what);
    TEST_ASSERT_EQUAL_size_t_MESSAGE(want->n, got->n, what);
    for (i = 0; i < want->n; i++) {
        const diff_event *a = &want->ev[i];
        const diff_event *b = &got->ev[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(a->type, b->type, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(a->error, b->error, what);
        TEST_ASSERT_EQUAL_size_t_MESSAGE(a->len, b->len, what);
        if (a->len > 0u) {
            TEST_ASSERT_EQUAL_MEMORY_MESSAGE(a->msg, b->msg, a->len, what);
        }
        if (with_pos) {
            TEST_ASSERT_EQUAL_size_t_MESSAGE(a->pos, b->pos, what);
        }
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->stats, &b->stats, sizeof(a->stats), what);
    }
    if (got->diverged != NO_DIVERGENCE) {
        char at[200];
        snprintf(at, sizeof(at), "%s: counters or busy() differ after %lu input bytes", what,
                 (unsigned long)got->diverged);
        TEST_FAIL_MESSAGE(at);
    }
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&want->stats, &got->stats, sizeof(want->stats), what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(want->busy, got->busy, what);
}

static void test_library_decoder_matches_the_byte_machine(void)
{
    uint32_t seed = 0x5EEDF00Du;
    unsigned stream;
    size_t events = 0;
    for (stream = 0; stream < STREAMS; stream++) {
        const uint32_t stream_seed = seed;
        const size_t len = make_stream(&seed);
        int api;
        int how;
        run_reference(len, &g_ref);
        events += g_ref.n;
        for (api = 0; api < API_COUNT; api++) {
            for (how = 0; how < CH_COUNT; how++) {
                char what[96];
                snprintf(what, sizeof(what), "stream seed 0x%08lX, api %d, chunking %d",
                         (unsigned long)stream_seed, api, how);
                run_library(len, (enum api)api, (enum chunking)how, stream_seed ^ (uint32_t)how,
                            &g_got);
                /* feed_all hands events over at chunk ends: no position */
                expect_same(&g_ref, &g_got, api == API_FEED || api == API_PUSH1 || api == API_BYTE,
                            what);
            }
        }
    }
    TEST_ASSERT_TRUE(events > STREAMS); /* the streams were eventful */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_library_decoder_matches_the_byte_machine);
    return UNITY_END();
}
