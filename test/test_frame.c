/* Frame codec tests driven by test/vectors/frames.json: exact wire bytes for
 * every encode vector, and identical decoder events and counters for every
 * chunking of every stream (whole, byte by byte, seeded random splits). */
#include <stdio.h>
#include <string.h>

#include "hex.h"
#include "json.h"
#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "rng.h"
#include "unity.h"
#include "vectors.h"

#define MAX_EVENTS 256u
#define MAX_INPUT 4096u
#define RANDOM_SPLIT_SEEDS 64u

static lep_json *g_vectors;

void setUp(void)
{
}

void tearDown(void)
{
}

/* ---- helpers --------------------------------------------------------------- */

typedef struct recorded_event {
    int type;
    int error;
    uint8_t msg[LEP_MAX_MESSAGE];
    size_t len;
} recorded_event;

typedef struct run_result {
    recorded_event ev[MAX_EVENTS];
    size_t n;
    lep_frame_stats stats;
    bool busy;
} run_result;

/* Which entry point run() feeds chunks through. */
/* API_BYTE: every byte through lep_frame_decoder_feed_byte, held to a second
 * decoder fed the same byte through lep_frame_decoder_feed. */
enum api { API_FEED, API_FEED_ALL, API_MIXED, API_BYTE };
static enum api g_api = API_FEED;
/* API_BYTE's second decoder. */
static lep_frame_decoder g_twin;

static void record_event(run_result *r, const lep_frame_event *ev)
{
    TEST_ASSERT_LESS_THAN_size_t_MESSAGE(MAX_EVENTS, r->n, "too many events");
    r->ev[r->n].type = ev->type;
    r->ev[r->n].error = ev->type == LEP_FRAME_ERROR ? ev->error : 0;
    r->ev[r->n].len = 0;
    if (ev->type == LEP_FRAME_MESSAGE) {
        TEST_ASSERT_NOT_NULL(ev->msg);
        TEST_ASSERT_LESS_OR_EQUAL_size_t(LEP_MAX_MESSAGE, ev->len);
        if (ev->len > 0) {
            memcpy(r->ev[r->n].msg, ev->msg, ev->len);
        }
        r->ev[r->n].len = ev->len;
    }
    r->n++;
}

/* The handler of lep_frame_decoder_feed_all. */
static void on_event(void *user, const lep_frame_event *ev)
{
    TEST_ASSERT_NOT_EQUAL_INT_MESSAGE(LEP_FRAME_NONE, ev->type, "handler called without an event");
    record_event((run_result *)user, ev);
}

/* Feed one chunk, draining every event it completes. */
static void feed_chunk(lep_frame_decoder *d, const uint8_t *p, size_t len, run_result *r)
{
    static unsigned calls;
    calls++;
    if (g_api == API_FEED_ALL || (g_api == API_MIXED && calls % 2u == 0u)) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_all(d, p, len, on_event, r));
        return;
    }
    if (g_api == API_BYTE) {
        for (; len > 0; len--) { /* the same event, counters and state as feed of one byte */
            lep_frame_event ev;
            lep_frame_event want;
            TEST_ASSERT_EQUAL_size_t(1u, lep_frame_decoder_feed(&g_twin, p, 1, &want));
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_byte(d, *p++, &ev));
            TEST_ASSERT_EQUAL_INT(want.type, ev.type);
            if (ev.type != LEP_FRAME_NONE) {
                TEST_ASSERT_EQUAL_INT(want.error, ev.error);
                TEST_ASSERT_EQUAL_size_t(want.len, ev.len);
                TEST_ASSERT_TRUE(ev.msg == (ev.type == LEP_FRAME_MESSAGE ? d->buf : NULL));
                record_event(r, &ev);
            }
            TEST_ASSERT_EQUAL_MEMORY(&g_twin, d, sizeof(*d));
        }
        return;
    }
    do {
        lep_frame_event ev;
        size_t used = lep_frame_decoder_feed(d, p, len, &ev);
        TEST_ASSERT_LESS_OR_EQUAL_size_t(len, used);
        if (ev.type == LEP_FRAME_NONE) {
            TEST_ASSERT_EQUAL_size_t_MESSAGE(len, used, "no event but input left over");
            return;
        }
        TEST_ASSERT_GREATER_THAN_size_t_MESSAGE(0u, used, "event without consuming input");
        record_event(r, &ev);
        p += used;
        len -= used;
    } while (len > 0);
}

enum split_mode { SPLIT_WHOLE, SPLIT_BYTES, SPLIT_RANDOM };

static void run(const uint8_t *in, size_t len, enum split_mode mode, uint32_t seed, run_result *r)
{
    lep_frame_decoder d;
    size_t off = 0;
    memset(r, 0, sizeof(*r));
    lep_frame_decoder_init(&d);
    lep_frame_decoder_init(&g_twin);
    while (off < len) {
        size_t chunk = 0;
        switch (mode) {
        case SPLIT_WHOLE:
            chunk = len - off;
            break;
        case SPLIT_BYTES:
            chunk = 1;
            break;
        case SPLIT_RANDOM: {
            uint32_t pick = rng_next(&seed);
            /* Mostly short chunks, sometimes long ones, sometimes empty feeds. */
            if (pick % 7u == 0u) {
                feed_chunk(&d, NULL, 0, r);
            }
            chunk = (pick >> 8) % 4u == 0u ? 1u + (pick >> 12) % 200u : 1u + (pick >> 12) % 9u;
            break;
        }
        }
        if (chunk > len - off) {
            chunk = len - off;
        }
        feed_chunk(&d, in + off, chunk, r);
        off += chunk;
    }
    lep_frame_decoder_get_stats(&d, &r->stats);
    r->busy = lep_frame_decoder_busy(&d);
}

static void expect_same(const run_result *want, const run_result *got, const char *what)
{
    size_t i;
    TEST_ASSERT_EQUAL_size_t_MESSAGE(want->n, got->n, what);
    for (i = 0; i < want->n; i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(want->ev[i].type, got->ev[i].type, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(want->ev[i].error, got->ev[i].error, what);
        TEST_ASSERT_EQUAL_size_t_MESSAGE(want->ev[i].len, got->ev[i].len, what);
        if (want->ev[i].len > 0) {
            TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(want->ev[i].msg, got->ev[i].msg, want->ev[i].len,
                                                 what);
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.messages, got->stats.messages, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.naks, got->stats.naks, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.bcc_errors, got->stats.bcc_errors, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.escape_errors, got->stats.escape_errors, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.overruns, got->stats.overruns, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.restarts, got->stats.restarts, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->stats.bytes_discarded, got->stats.bytes_discarded, what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(want->busy, got->busy, what);
}

/* Expected events and stats of a decode vector. */
static void expected_of(const lep_json *v, run_result *r)
{
    const lep_json *events = lep_json_get(v, "events");
    const lep_json *stats = lep_json_get(v, "stats");
    size_t i;
    memset(r, 0, sizeof(*r));
    TEST_ASSERT_EQUAL_INT(LEP_JSON_ARRAY, lep_json_type(events));
    TEST_ASSERT_EQUAL_INT(LEP_JSON_OBJECT, lep_json_type(stats));
    TEST_ASSERT_LESS_OR_EQUAL_size_t(MAX_EVENTS, lep_json_len(events));
    for (i = 0; i < lep_json_len(events); i++) {
        const lep_json *e = lep_json_at(events, i);
        const char *type = lep_json_get_str(e, "type");
        TEST_ASSERT_NOT_NULL(type);
        if (strcmp(type, "message") == 0) {
            r->ev[i].type = LEP_FRAME_MESSAGE;
            r->ev[i].len =
                lep_vectors_hex(lep_json_get_str(e, "message"), r->ev[i].msg, LEP_MAX_MESSAGE);
        } else if (strcmp(type, "nak") == 0) {
            r->ev[i].type = LEP_FRAME_NAK;
        } else if (strcmp(type, "error") == 0) {
            r->ev[i].type = LEP_FRAME_ERROR;
            r->ev[i].error = lep_vectors_error(lep_json_get_str(e, "error"));
        } else {
            TEST_FAIL_MESSAGE(type);
        }
    }
    r->n = lep_json_len(events);
    r->stats.messages = (uint32_t)lep_json_get_int(stats, "messages", -1);
    r->stats.naks = (uint32_t)lep_json_get_int(stats, "naks", -1);
    r->stats.bcc_errors = (uint32_t)lep_json_get_int(stats, "bcc_errors", -1);
    r->stats.escape_errors = (uint32_t)lep_json_get_int(stats, "escape_errors", -1);
    r->stats.overruns = (uint32_t)lep_json_get_int(stats, "overruns", -1);
    r->stats.restarts = (uint32_t)lep_json_get_int(stats, "restarts", -1);
    r->stats.bytes_discarded = (uint32_t)lep_json_get_int(stats, "bytes_discarded", -1);
    r->busy = false;
}

static run_result g_want;
static run_result g_got;

/* ---- encoder ----------------------------------------------------------------- */

static void test_spec_worked_frames_are_in_the_vectors(void)
{
    const lep_json *enc = lep_vectors_section(g_vectors, "encode");
    size_t i;
    size_t spec = 0;
    for (i = 0; i < lep_json_len(enc); i++) {
        const char *name = lep_json_get_str(lep_json_at(enc, i), "name");
        TEST_ASSERT_NOT_NULL(name);
        if (strncmp(name, "spec: ", 6) == 0) {
            spec++;
        }
    }
    /* Six bare commands, set filter 0x01, the data response with status 0x04. */
    TEST_ASSERT_EQUAL_size_t(8u, spec);
}

static void test_encode_vectors_give_exact_wire_bytes(void)
{
    const lep_json *enc = lep_vectors_section(g_vectors, "encode");
    size_t i;
    for (i = 0; i < lep_json_len(enc); i++) {
        const lep_json *v = lep_json_at(enc, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t msg[LEP_MAX_MESSAGE];
        uint8_t wire[LEP_MAX_FRAME];
        uint8_t out[LEP_MAX_FRAME + 8];
        size_t mlen = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        size_t wlen = lep_vectors_hex(lep_json_get_str(v, "wire"), wire, sizeof(wire));
        size_t n = 0;
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_frame_encode(msg, mlen, out, sizeof(out), &n),
                                      lep_vectors_ctx(name, "encode"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(wlen, n, lep_vectors_ctx(name, "encoded size"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(wire, out, wlen, lep_vectors_ctx(name, "wire bytes"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(wlen, lep_frame_size(msg, mlen),
                                         lep_vectors_ctx(name, "lep_frame_size"));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(wire[wlen - 1], lep_bcc(msg, mlen),
                                       lep_vectors_ctx(name, "lep_bcc"));

        /* Exactly enough room works; one byte less is LEP_E_BUFFER. */
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_frame_encode(msg, mlen, out, wlen, &n),
                                      lep_vectors_ctx(name, "exact capacity"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(wire, out, wlen,
                                             lep_vectors_ctx(name, "exact capacity bytes"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_BUFFER, lep_frame_encode(msg, mlen, out, wlen - 1u, &n),
                                      lep_vectors_ctx(name, "capacity one short"));
    }
}

static void test_encode_vectors_decode_back(void)
{
    const lep_json *enc = lep_vectors_section(g_vectors, "encode");
    size_t i;
    for (i = 0; i < lep_json_len(enc); i++) {
        const lep_json *v = lep_json_at(enc, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t wire[LEP_MAX_FRAME];
        size_t wlen = lep_vectors_hex(lep_json_get_str(v, "wire"), wire, sizeof(wire));
        uint32_t seed;
        memset(&g_want, 0, sizeof(g_want));
        g_want.n = 1;
        g_want.ev[0].type = LEP_FRAME_MESSAGE;
        g_want.ev[0].len =
            lep_vectors_hex(lep_json_get_str(v, "message"), g_want.ev[0].msg, LEP_MAX_MESSAGE);
        g_want.stats.messages = 1;
        run(wire, wlen, SPLIT_WHOLE, 0, &g_got);
        expect_same(&g_want, &g_got, lep_vectors_ctx(name, "decode whole"));
        run(wire, wlen, SPLIT_BYTES, 0, &g_got);
        expect_same(&g_want, &g_got, lep_vectors_ctx(name, "decode byte by byte"));
        for (seed = 1; seed <= 8u; seed++) {
            run(wire, wlen, SPLIT_RANDOM, seed * 2654435761u, &g_got);
            expect_same(&g_want, &g_got, lep_vectors_ctx(name, "decode random splits"));
        }
    }
}

static void test_encode_error_vectors(void)
{
    const lep_json *errs = lep_vectors_section(g_vectors, "encode_errors");
    size_t i;
    for (i = 0; i < lep_json_len(errs); i++) {
        const lep_json *v = lep_json_at(errs, i);
        uint8_t msg[LEP_MAX_MESSAGE + 8];
        uint8_t out[2 * LEP_MAX_FRAME];
        size_t mlen = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        size_t n = 0;
        TEST_ASSERT_EQUAL_INT_MESSAGE(lep_vectors_error(lep_json_get_str(v, "error")),
                                      lep_frame_encode(msg, mlen, out, sizeof(out), &n),
                                      lep_vectors_ctx(lep_json_get_str(v, "name"), "encode error"));
    }
}

static void test_encode_bounds(void)
{
    uint8_t msg[LEP_MAX_MESSAGE + 1];
    uint8_t out[LEP_MAX_FRAME + 4];
    size_t n = 0;
    memset(msg, LEP_DLE, sizeof(msg));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_encode(NULL, 4, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_encode(msg, 4, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_encode(msg, 4, out, sizeof(out), NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_encode(msg, 0, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_TOO_LONG,
                          lep_frame_encode(msg, LEP_MAX_MESSAGE + 1u, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_frame_encode(msg, 4, out, 0, &n));
    /* The worst case fits LEP_MAX_FRAME exactly. */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(msg, LEP_MAX_MESSAGE, out, LEP_MAX_FRAME, &n));
    TEST_ASSERT_EQUAL_size_t(LEP_MAX_FRAME, n);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER,
                          lep_frame_encode(msg, LEP_MAX_MESSAGE, out, LEP_MAX_FRAME - 1u, &n));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_size(NULL, 4));
    TEST_ASSERT_EQUAL_size_t(LEP_MAX_FRAME, lep_frame_size(msg, LEP_MAX_MESSAGE));
    TEST_ASSERT_EQUAL_HEX8(LEP_ETX, lep_bcc(msg, 0));
    TEST_ASSERT_EQUAL_HEX8(LEP_ETX, lep_bcc(NULL, 4));
    TEST_ASSERT_EQUAL_HEX8(0x13u, lep_bcc(msg, 1));
}

/* ---- decoder ----------------------------------------------------------------- */

static void check_stream_api(const lep_json *v, enum split_mode mode, const char *how);

/* Every stream through feed, through feed_all, and through both in turn. */
static void check_stream(const lep_json *v, enum split_mode mode, const char *how)
{
    static const char *const names[] = { "feed", "feed_all", "feed and feed_all in turn",
                                         "feed_byte" };
    char what[128];
    int api;
    for (api = API_FEED; api <= API_BYTE; api++) {
        g_api = (enum api)api;
        snprintf(what, sizeof what, "%s, %s", how, names[api]);
        check_stream_api(v, mode, what);
    }
    g_api = API_FEED;
}

static void check_stream_api(const lep_json *v, enum split_mode mode, const char *how)
{
    static uint8_t in[MAX_INPUT];
    const char *name = lep_json_get_str(v, "name");
    size_t len = lep_vectors_hex(lep_json_get_str(v, "input"), in, sizeof(in));
    expected_of(v, &g_want);
    if (mode != SPLIT_RANDOM) {
        run(in, len, mode, 0, &g_got);
        expect_same(&g_want, &g_got, lep_vectors_ctx(name, how));
    } else {
        uint32_t seed;
        for (seed = 1; seed <= RANDOM_SPLIT_SEEDS; seed++) {
            run(in, len, mode, seed * 0x9E3779B9u, &g_got);
            expect_same(&g_want, &g_got, lep_vectors_ctx(name, how));
        }
    }
}

static void test_decode_streams_whole(void)
{
    const lep_json *dec = lep_vectors_section(g_vectors, "decode");
    size_t i;
    for (i = 0; i < lep_json_len(dec); i++) {
        check_stream(lep_json_at(dec, i), SPLIT_WHOLE, "whole");
    }
}

static void test_decode_streams_byte_by_byte(void)
{
    const lep_json *dec = lep_vectors_section(g_vectors, "decode");
    size_t i;
    for (i = 0; i < lep_json_len(dec); i++) {
        check_stream(lep_json_at(dec, i), SPLIT_BYTES, "byte by byte");
    }
}

static void test_decode_streams_random_splits(void)
{
    const lep_json *dec = lep_vectors_section(g_vectors, "decode");
    size_t i;
    for (i = 0; i < lep_json_len(dec); i++) {
        check_stream(lep_json_at(dec, i), SPLIT_RANDOM, "random splits");
    }
}

/* All streams end between frames, so one decoder fed all of them in a row
 * gives the concatenated events and the summed counters. */
static void test_decode_streams_concatenated(void)
{
    static uint8_t all[16u * MAX_INPUT];
    static run_result want_all;
    const lep_json *dec = lep_vectors_section(g_vectors, "decode");
    size_t total = 0;
    size_t i;
    memset(&want_all, 0, sizeof(want_all));
    for (i = 0; i < lep_json_len(dec); i++) {
        const lep_json *v = lep_json_at(dec, i);
        size_t j;
        total += lep_vectors_hex(lep_json_get_str(v, "input"), all + total, sizeof(all) - total);
        expected_of(v, &g_want);
        for (j = 0; j < g_want.n && want_all.n < MAX_EVENTS; j++) {
            want_all.ev[want_all.n++] = g_want.ev[j];
        }
        want_all.stats.messages += g_want.stats.messages;
        want_all.stats.naks += g_want.stats.naks;
        want_all.stats.bcc_errors += g_want.stats.bcc_errors;
        want_all.stats.escape_errors += g_want.stats.escape_errors;
        want_all.stats.overruns += g_want.stats.overruns;
        want_all.stats.restarts += g_want.stats.restarts;
        want_all.stats.bytes_discarded += g_want.stats.bytes_discarded;
    }
    if (want_all.n >= MAX_EVENTS) {
        TEST_IGNORE_MESSAGE("more events than MAX_EVENTS: raise it");
    }
    run(all, total, SPLIT_WHOLE, 0, &g_got);
    expect_same(&want_all, &g_got, "all streams in a row (whole)");
    run(all, total, SPLIT_RANDOM, 12345u, &g_got);
    expect_same(&want_all, &g_got, "all streams in a row (random splits)");
}

static void test_decoder_busy_and_empty_feed(void)
{
    static const uint8_t start[] = { 0x10, 0x02, 0x04, 0xFF };
    static const uint8_t rest[] = { 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    lep_frame_decoder d;
    lep_frame_event ev;
    lep_frame_stats st;
    lep_frame_decoder_init(&d);
    TEST_ASSERT_FALSE(lep_frame_decoder_busy(&d));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(&d, NULL, 0, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_NONE, ev.type);
    TEST_ASSERT_EQUAL_size_t(sizeof(start), lep_frame_decoder_feed(&d, start, sizeof(start), &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_NONE, ev.type);
    TEST_ASSERT_TRUE(lep_frame_decoder_busy(&d));
    TEST_ASSERT_EQUAL_size_t(sizeof(rest), lep_frame_decoder_feed(&d, rest, sizeof(rest), &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, ev.type);
    TEST_ASSERT_EQUAL_size_t(4u, ev.len);
    TEST_ASSERT_EQUAL_HEX8(0x2A, ev.msg[2]);
    TEST_ASSERT_FALSE(lep_frame_decoder_busy(&d));
    lep_frame_decoder_get_stats(&d, &st);
    TEST_ASSERT_EQUAL_UINT32(1u, st.messages);
    /* init resets the counters. */
    lep_frame_decoder_init(&d);
    lep_frame_decoder_get_stats(&d, &st);
    TEST_ASSERT_EQUAL_UINT32(0u, st.messages);
    lep_frame_decoder_init(NULL); /* does nothing */
    TEST_ASSERT_FALSE(lep_frame_decoder_busy(NULL));
    /* NULL: nothing is read or written */
    st.messages = 7u;
    lep_frame_decoder_get_stats(NULL, &st);
    TEST_ASSERT_EQUAL_UINT32(7u, st.messages);
    lep_frame_decoder_get_stats(&d, NULL);
    /* what a binding allocates */
    TEST_ASSERT_EQUAL_size_t(sizeof(lep_frame_decoder), lep_frame_decoder_sizeof());
}

/* Bad arguments consume nothing, return 0 and say LEP_E_ARG in the event;
 * the decoder is left as it was. */
static void test_decoder_feed_bad_arguments(void)
{
    static const uint8_t start[] = { 0x10, 0x02, 0x04 };
    static const uint8_t rest[] = { 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    lep_frame_decoder d;
    lep_frame_event ev;
    lep_frame_decoder_init(&d);
    TEST_ASSERT_EQUAL_size_t(sizeof(start), lep_frame_decoder_feed(&d, start, sizeof(start), &ev));
    memset(&ev, 0x5A, sizeof(ev));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(NULL, start, sizeof(start), &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_ERROR, ev.type);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, ev.error);
    TEST_ASSERT_NULL(ev.msg);
    TEST_ASSERT_EQUAL_size_t(0u, ev.len);
    memset(&ev, 0x5A, sizeof(ev));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(NULL, NULL, 0, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_ERROR, ev.type);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, ev.error);
    memset(&ev, 0x5A, sizeof(ev));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(&d, NULL, 3, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_ERROR, ev.type);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, ev.error);
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(&d, rest, sizeof(rest), NULL));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(NULL, NULL, 0, NULL));
    /* None of it touched the frame in progress. */
    TEST_ASSERT_TRUE(lep_frame_decoder_busy(&d));
    TEST_ASSERT_EQUAL_UINT32(0u, d.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_size_t(sizeof(rest), lep_frame_decoder_feed(&d, rest, sizeof(rest), &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, ev.type);
    TEST_ASSERT_EQUAL_size_t(4u, ev.len);
    TEST_ASSERT_EQUAL_HEX8(0x2A, ev.msg[2]);
}

/* feed_byte's bad arguments: LEP_E_ARG, the event feed gives for the same
 * call with one byte, and the decoder left as it was. */
static void test_decoder_feed_byte_bad_arguments(void)
{
    static const uint8_t start[] = { 0x10, 0x02, 0x04 };
    static const uint8_t rest[] = { 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    static const uint8_t b = 0xFF;
    lep_frame_decoder d;
    lep_frame_decoder before;
    lep_frame_event ev;
    lep_frame_event want;
    size_t i;
    lep_frame_decoder_init(&d);
    TEST_ASSERT_EQUAL_size_t(sizeof(start), lep_frame_decoder_feed(&d, start, sizeof(start), &ev));
    before = d;
    memset(&ev, 0x5A, sizeof(ev));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_decoder_feed_byte(NULL, b, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_ERROR, ev.type);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, ev.error);
    TEST_ASSERT_NULL(ev.msg);
    TEST_ASSERT_EQUAL_size_t(0u, ev.len);
    memset(&want, 0x5A, sizeof(want));
    TEST_ASSERT_EQUAL_size_t(0u, lep_frame_decoder_feed(NULL, &b, 1, &want));
    TEST_ASSERT_EQUAL_MEMORY(&want, &ev, sizeof(ev));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_decoder_feed_byte(&d, b, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_decoder_feed_byte(NULL, b, NULL));
    /* None of it touched the frame in progress. */
    TEST_ASSERT_EQUAL_MEMORY(&before, &d, sizeof(d));
    for (i = 0; i < sizeof(rest); i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_byte(&d, rest[i], &ev));
        TEST_ASSERT_EQUAL_INT(i + 1u < sizeof(rest) ? LEP_FRAME_NONE : LEP_FRAME_MESSAGE, ev.type);
    }
    TEST_ASSERT_EQUAL_size_t(4u, ev.len);
    TEST_ASSERT_EQUAL_HEX8(0x2A, ev.msg[2]);
    TEST_ASSERT_EQUAL_UINT32(1u, d.stats.messages);
    TEST_ASSERT_EQUAL_UINT32(0u, d.stats.bytes_discarded);
}

static void count_events(void *user, const lep_frame_event *ev)
{
    (void)ev;
    (*(unsigned *)user)++;
}

/* feed_all: bad arguments are LEP_E_ARG and change nothing; an empty feed is
 * fine; the handler sees each event once, in order, and the message only
 * during the call. */
static void test_decoder_feed_all_arguments(void)
{
    static const uint8_t two[] = {
        0x10, 0x02, 0x04, 0xFF, 0x33, 0x00, 0x10, 0x03, 0xCB, 0x10, 0x15
    };
    lep_frame_decoder d;
    unsigned n = 0;
    lep_frame_decoder_init(&d);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG,
                          lep_frame_decoder_feed_all(NULL, two, sizeof(two), count_events, &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_decoder_feed_all(&d, two, sizeof(two), NULL, &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_frame_decoder_feed_all(&d, NULL, 3, count_events, &n));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_all(&d, NULL, 0, count_events, &n));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_decoder_feed_all(&d, two, 0, count_events, &n));
    TEST_ASSERT_EQUAL_UINT(0u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, d.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_decoder_feed_all(&d, two, sizeof(two), count_events, &n));
    TEST_ASSERT_EQUAL_UINT(2u, n);
    TEST_ASSERT_EQUAL_UINT32(1u, d.stats.messages);
    TEST_ASSERT_EQUAL_UINT32(1u, d.stats.naks);
}

/* After a frame whose BCC is 0x10 the decoder is between frames (not busy),
 * though that byte may still open the next frame. */
static void test_decoder_not_busy_after_bcc_0x10(void)
{
    const lep_json *enc = lep_vectors_section(g_vectors, "encode");
    size_t i;
    size_t found = 0;
    for (i = 0; i < lep_json_len(enc); i++) {
        uint8_t wire[LEP_MAX_FRAME];
        size_t wlen =
            lep_vectors_hex(lep_json_get_str(lep_json_at(enc, i), "wire"), wire, sizeof(wire));
        lep_frame_decoder d;
        lep_frame_event ev;
        if (wire[wlen - 1u] != LEP_DLE) {
            continue;
        }
        found++;
        lep_frame_decoder_init(&d);
        TEST_ASSERT_EQUAL_size_t(wlen, lep_frame_decoder_feed(&d, wire, wlen, &ev));
        TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, ev.type);
        TEST_ASSERT_FALSE(lep_frame_decoder_busy(&d));
    }
    TEST_ASSERT_GREATER_THAN_size_t(0u, found);
}

/* A frame of 130 stuffed DLEs is over-long at the 129th, however it is split,
 * and the frame after it still comes through. */
static void test_overlong_run_of_stuffed_dles(void)
{
    static const uint8_t pi[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    static uint8_t in[2u + 2u * 130u + 3u + sizeof(pi)];
    size_t len = 0;
    size_t i;
    in[len++] = LEP_DLE;
    in[len++] = LEP_STX;
    for (i = 0; i < 130u; i++) {
        in[len++] = LEP_DLE;
        in[len++] = LEP_DLE;
    }
    in[len++] = LEP_DLE;
    in[len++] = LEP_ETX;
    in[len++] = 0x13;
    memcpy(in + len, pi, sizeof(pi));
    len += sizeof(pi);
    memset(&g_want, 0, sizeof(g_want));
    g_want.n = 2;
    g_want.ev[0].type = LEP_FRAME_ERROR;
    g_want.ev[0].error = LEP_E_TOO_LONG;
    g_want.ev[1].type = LEP_FRAME_MESSAGE;
    g_want.ev[1].len = 4;
    memcpy(g_want.ev[1].msg, pi + 2, 4);
    g_want.stats.messages = 1;
    g_want.stats.overruns = 1;
    g_want.stats.bytes_discarded = (uint32_t)(len - sizeof(pi));
    for (i = 0; i <= API_MIXED; i++) {
        uint32_t seed;
        g_api = (enum api)i;
        run(in, len, SPLIT_WHOLE, 0, &g_got);
        expect_same(&g_want, &g_got, "130 stuffed DLEs, whole");
        run(in, len, SPLIT_BYTES, 0, &g_got);
        expect_same(&g_want, &g_got, "130 stuffed DLEs, byte by byte");
        for (seed = 1; seed <= 16u; seed++) {
            run(in, len, SPLIT_RANDOM, seed * 0x9E3779B9u, &g_got);
            expect_same(&g_want, &g_got, "130 stuffed DLEs, random splits");
        }
    }
    g_api = API_FEED;
}

/* The event for a frame is returned as soon as its last byte is consumed:
 * bytes after it are left to the next call. */
static void test_decoder_stops_after_each_event(void)
{
    static const uint8_t two[] = { 0x10, 0x02, 0x04, 0xFF, 0x33, 0x00, 0x10, 0x03, 0xCB, 0x10,
                                   0x15, 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    lep_frame_decoder d;
    lep_frame_event ev;
    size_t used;
    lep_frame_decoder_init(&d);
    used = lep_frame_decoder_feed(&d, two, sizeof(two), &ev);
    TEST_ASSERT_EQUAL_size_t(9u, used);
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, ev.type);
    TEST_ASSERT_EQUAL_HEX8(0x33, ev.msg[2]);
    used += lep_frame_decoder_feed(&d, two + used, sizeof(two) - used, &ev);
    TEST_ASSERT_EQUAL_size_t(11u, used);
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_NAK, ev.type);
    used += lep_frame_decoder_feed(&d, two + used, sizeof(two) - used, &ev);
    TEST_ASSERT_EQUAL_size_t(sizeof(two), used);
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, ev.type);
    TEST_ASSERT_EQUAL_HEX8(0x2A, ev.msg[2]);
}

/* The event contract says a message is 1..128 bytes: an empty frame
 * (DLE STX DLE ETX BCC=0x03) must not be delivered as a message. */
static void test_empty_frame_is_not_delivered(void)
{
    static const uint8_t empty[] = { 0x10, 0x02, 0x10, 0x03, 0x03 };
    size_t i;
    run(empty, sizeof(empty), SPLIT_WHOLE, 0, &g_got);
    for (i = 0; i < g_got.n; i++) {
        TEST_ASSERT_NOT_EQUAL_MESSAGE(LEP_FRAME_MESSAGE, g_got.ev[i].type,
                                      "empty frame delivered as a message");
    }
    TEST_ASSERT_EQUAL_UINT32(0u, g_got.stats.messages);
    TEST_ASSERT_EQUAL_UINT32(5u, g_got.stats.bytes_discarded);
}

/* Random messages (rich in DLE, ETX, STX, NAK bytes) framed with garbage
 * between them come back exactly, whatever the chunking. */
static void test_random_messages_round_trip(void)
{
    static const uint8_t alphabet[] = { 0x10, 0x10, 0x02, 0x03, 0x15, 0x00, 0xFF, 0x7E };
    static uint8_t stream[MAX_INPUT];
    uint32_t seed = 0xC0FFEEu;
    int round;
    for (round = 0; round < 200; round++) {
        size_t len = 0;
        size_t k;
        memset(&g_want, 0, sizeof(g_want));
        for (k = 0; k < 6; k++) {
            recorded_event *e = &g_want.ev[g_want.n++];
            size_t n = 0;
            size_t j;
            size_t garbage = rng_next(&seed) % 4u;
            /* Garbage without DLE cannot start anything. */
            for (j = 0; j < garbage; j++) {
                stream[len++] = (uint8_t)(0x20u + rng_next(&seed) % 0x50u);
            }
            g_want.stats.bytes_discarded += (uint32_t)garbage;
            e->type = LEP_FRAME_MESSAGE;
            e->len = 1u + rng_next(&seed) % LEP_MAX_MESSAGE;
            for (j = 0; j < e->len; j++) {
                uint32_t r = rng_next(&seed);
                e->msg[j] = (r & 1u) ? alphabet[(r >> 1) % sizeof(alphabet)] : (uint8_t)(r >> 8);
            }
            TEST_ASSERT_EQUAL_INT(
                LEP_OK, lep_frame_encode(e->msg, e->len, stream + len, sizeof(stream) - len, &n));
            len += n;
        }
        g_want.stats.messages = 6;
        run(stream, len, SPLIT_RANDOM, seed, &g_got);
        expect_same(&g_want, &g_got, "random messages, random splits");
        run(stream, len, SPLIT_BYTES, 0, &g_got);
        expect_same(&g_want, &g_got, "random messages, byte by byte");
        g_api = API_FEED_ALL;
        run(stream, len, SPLIT_RANDOM, seed, &g_got);
        expect_same(&g_want, &g_got, "random messages, random splits, feed_all");
        run(stream, len, SPLIT_WHOLE, 0, &g_got);
        expect_same(&g_want, &g_got, "random messages, whole, feed_all");
        g_api = API_FEED;
    }
}

/* Arbitrary bytes: whatever the decoder makes of them, every chunking agrees. */
static void test_random_noise_is_chunking_invariant(void)
{
    static const uint8_t alphabet[] = { 0x10, 0x10, 0x10, 0x02, 0x03, 0x15, 0x00, 0x13 };
    static uint8_t noise[MAX_INPUT];
    static run_result whole;
    uint32_t seed = 0xBADC0DEu;
    int round;
    for (round = 0; round < 100; round++) {
        size_t len = 64u + rng_next(&seed) % 1024u;
        size_t j;
        for (j = 0; j < len; j++) {
            uint32_t r = rng_next(&seed);
            noise[j] = (r & 3u) ? alphabet[(r >> 2) % sizeof(alphabet)] : (uint8_t)(r >> 8);
        }
        run(noise, len, SPLIT_WHOLE, 0, &whole);
        if (whole.n >= MAX_EVENTS - 1u) {
            continue; /* too eventful to record: skip this round */
        }
        run(noise, len, SPLIT_BYTES, 0, &g_got);
        expect_same(&whole, &g_got, "noise, byte by byte");
        run(noise, len, SPLIT_RANDOM, seed, &g_got);
        expect_same(&whole, &g_got, "noise, random splits");
        g_api = API_FEED_ALL;
        run(noise, len, SPLIT_WHOLE, 0, &g_got);
        expect_same(&whole, &g_got, "noise, whole, feed_all");
        run(noise, len, SPLIT_RANDOM, seed, &g_got);
        expect_same(&whole, &g_got, "noise, random splits, feed_all");
        g_api = API_MIXED;
        run(noise, len, SPLIT_RANDOM, seed ^ 0x55u, &g_got);
        expect_same(&whole, &g_got, "noise, random splits, feed and feed_all in turn");
        g_api = API_FEED;
    }
}

int main(void)
{
    int failures;
    g_vectors = lep_vectors_load("frames.json");
    UNITY_BEGIN();
    RUN_TEST(test_spec_worked_frames_are_in_the_vectors);
    RUN_TEST(test_encode_vectors_give_exact_wire_bytes);
    RUN_TEST(test_encode_vectors_decode_back);
    RUN_TEST(test_encode_error_vectors);
    RUN_TEST(test_encode_bounds);
    RUN_TEST(test_decode_streams_whole);
    RUN_TEST(test_decode_streams_byte_by_byte);
    RUN_TEST(test_decode_streams_random_splits);
    RUN_TEST(test_decode_streams_concatenated);
    RUN_TEST(test_decoder_busy_and_empty_feed);
    RUN_TEST(test_decoder_feed_bad_arguments);
    RUN_TEST(test_decoder_feed_byte_bad_arguments);
    RUN_TEST(test_decoder_feed_all_arguments);
    RUN_TEST(test_decoder_not_busy_after_bcc_0x10);
    RUN_TEST(test_overlong_run_of_stuffed_dles);
    RUN_TEST(test_decoder_stops_after_each_event);
    RUN_TEST(test_empty_frame_is_not_delivered);
    RUN_TEST(test_random_messages_round_trip);
    RUN_TEST(test_random_noise_is_chunking_invariant);
    failures = UNITY_END();
    lep_json_free(g_vectors);
    return failures;
}
