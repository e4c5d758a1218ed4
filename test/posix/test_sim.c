/* Client <-> virtual sensor through a real pty (in-process lep_sim). */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

static lep_sim *sim;
static lep_serial *port;
static lep_client client;
static char err[256];
static char tmpdir[64];
static lep_product_info scratch_info;

void setUp(void)
{
    sim = NULL;
    port = NULL;
    err[0] = '\0';
    tmpdir[0] = '\0';
}

void tearDown(void)
{
    lep_serial_close(port);
    lep_sim_stop(sim);
    if (tmpdir[0] != '\0') {
        char lock[96];
        snprintf(lock, sizeof lock, "%s/port.lock", tmpdir);
        (void)unlink(lock); /* a test that failed midway */
        snprintf(lock, sizeof lock, "%s/port", tmpdir);
        (void)unlink(lock);
        (void)rmdir(tmpdir);
    }
}

/* A failure bound on waiting for a sample that is due (every 0.8 ms): a
 * loaded machine delivers late, and a test waits for it, never times it. */
#define SAMPLE_WAIT_MS 5000
/* A long timeout, so that a wait a hang-up cuts short is told from one
 * run out by a wide margin (half of it), whatever the load. */
#define HANGUP_WAIT_MS 20000

static void sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    nanosleep(&ts, NULL);
}

static void start_sim(const lep_sim_options *o)
{
    int rc = lep_sim_start_so(o, &sim, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
}

static void open_client(void)
{
    int rc = lep_serial_open(lep_sim_port(sim), &port, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
}

static void start_default(void)
{
    lep_sim_options o;
    lep_sim_options_init(&o);
    start_sim(&o);
    open_client();
}

static lep_sim_counters stats_now(void)
{
    lep_sim_counters st;
    lep_sim_get_stats(sim, &st);
    return st;
}

/* ---- raw frames, for the answers a client never asks for ---- */

static void send_message(const uint8_t *msg, size_t len, bool bad_bcc)
{
    uint8_t frame[LEP_MAX_FRAME];
    size_t n = 0;
    lep_io io;
    lep_serial_get_io(port, &io);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(msg, len, frame, sizeof frame, &n));
    if (bad_bcc)
        frame[n - 1] ^= 0x5A;
    TEST_ASSERT_EQUAL_INT(LEP_OK, io.write(io.user, frame, n));
}

/* Read frames until a NAK (returns 1) or a message other than stream data
 * (returns 2, with its code and result stored) arrives; 0 on timeout. */
static int read_event(uint8_t *code, uint8_t *result, int timeout_ms)
{
    lep_frame_decoder d;
    lep_io io;
    uint32_t start = lep_monotonic_ms();
    uint8_t buf[256];
    lep_frame_decoder_init(&d);
    lep_serial_get_io(port, &io);
    while ((int)(lep_monotonic_ms() - start) < timeout_ms) {
        int n = io.read(io.user, buf, sizeof buf, 50);
        size_t off = 0;
        TEST_ASSERT_TRUE(n >= 0);
        while (off < (size_t)n) {
            lep_frame_event ev;
            off += lep_frame_decoder_feed(&d, buf + off, (size_t)n - off, &ev);
            if (ev.type == LEP_FRAME_NAK)
                return 1;
            if (ev.type == LEP_FRAME_MESSAGE && ev.len >= 4) {
                if (ev.msg[2] == LEP_CMD_START && ev.len == LEP_LEN_SAMPLE)
                    continue; /* stream data */
                /* spec 3.2: Length, 0xFF, code, result */
                TEST_ASSERT_EQUAL_HEX8(ev.len, ev.msg[0]);
                TEST_ASSERT_EQUAL_HEX8(0xFF, ev.msg[1]);
                *code = ev.msg[2];
                *result = ev.msg[3];
                if (ev.msg[3] != 0)
                    TEST_ASSERT_EQUAL_size_t(4, ev.len); /* no data with an error */
                return 2;
            }
        }
    }
    return 0;
}

/* ---- tests ---- */

static void test_every_command(void)
{
    lep_sim_options o;
    lep_product_info info;
    lep_rated rated, want;
    lep_sample smp;
    uint8_t code = 0xFF;
    lep_sim_options_init(&o);
    snprintf(o.model, sizeof o.model, "%s", "PFS080YS102U6");
    snprintf(o.serial, sizeof o.serial, "%s", "12345678");
    snprintf(o.firmware, sizeof o.firmware, "%s", "1.31");
    o.filter = 2;
    start_sim(&o);
    open_client();

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_STRING("PFS080YS102U6", info.model);
    TEST_ASSERT_EQUAL_STRING("12345678", info.serial);
    TEST_ASSERT_EQUAL_STRING("1.31", info.firmware);
    TEST_ASSERT_FALSE(info.has_output_rate);

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f("PFS080YS102U6", &want));
    TEST_ASSERT_EQUAL_MEMORY(&want, &rated, sizeof want);
    TEST_ASSERT_EQUAL_FLOAT(1000.0f, rated.axis[LEP_FZ]);

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(2, code);

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sample(&client, &smp));
    TEST_ASSERT_EQUAL_UINT16(0, smp.reserved);
    /* default waveform: 0.2 of rated plus a little noise */
    TEST_ASSERT_TRUE(smp.raw[LEP_FX] > -2100 && smp.raw[LEP_FX] < 2100);

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_set(&client, 1));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(2, code); /* not before a power cycle */
}

static void test_product_info_with_output_rate(void)
{
    lep_sim_options o;
    lep_product_info info;
    lep_sim_options_init(&o);
    o.output_rate_field = true;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_TRUE(info.has_output_rate);
    TEST_ASSERT_EQUAL_UINT32(1200, info.output_rate_hz);
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
}

static void test_result_codes_and_nak(void)
{
    static const uint8_t bad_length[] = { 0x05, 0xFF, 0x2A, 0x00, 0x00 };
    static const uint8_t unknown[] = { 0x04, 0xFF, 0x77, 0x00 };
    static const uint8_t bad_filter[] = { 0x08, 0xFF, 0xA6, 0x00, 0x09, 0x00, 0x00, 0x00 };
    static const uint8_t start[] = { 0x04, 0xFF, 0x32, 0x00 };
    static const uint8_t info[] = { 0x04, 0xFF, 0x2A, 0x00 };
    uint8_t code = 0, result = 0xEE;
    start_default();

    send_message(info, sizeof info, true);
    TEST_ASSERT_EQUAL_INT(1, read_event(&code, &result, 1000)); /* DLE NAK */

    send_message(bad_length, sizeof bad_length, false);
    TEST_ASSERT_EQUAL_INT(2, read_event(&code, &result, 1000));
    TEST_ASSERT_EQUAL_HEX8(0x2A, code);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_LENGTH, result);

    send_message(unknown, sizeof unknown, false);
    TEST_ASSERT_EQUAL_INT(2, read_event(&code, &result, 1000));
    TEST_ASSERT_EQUAL_HEX8(0x77, code);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_UNDEFINED, result);

    send_message(bad_filter, sizeof bad_filter, false);
    TEST_ASSERT_EQUAL_INT(2, read_event(&code, &result, 1000));
    TEST_ASSERT_EQUAL_HEX8(0xA6, code);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_VALUE, result);

    /* 0x04: start while already streaming */
    send_message(start, sizeof start, false);
    TEST_ASSERT_EQUAL_INT(2, read_event(&code, &result, 1000));
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_OK, result);
    send_message(start, sizeof start, false);
    TEST_ASSERT_EQUAL_INT(2, read_event(&code, &result, 1000));
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_START, code);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_STATE, result);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, NULL));
}

/* 2400 samples (2 s at 1200 Hz): every sample accounted for by its sequence
 * number, and every sample the sensor sent by the client: delivered, or
 * still in flight when the stop came (skipped before its answer). Counted,
 * not timed: a loaded machine delivers late, never fewer. */
static void test_stream_exact_accounting(void)
{
    lep_sample smp;
    lep_client_stats cs;
    lep_sim_counters st;
    unsigned received = 0, gaps = 0;
    uint16_t expect = 0;
    start_default();
    /* no command sent twice (its second answer could come after the stop's,
     * unread): the transactions' timeout a failure bound too */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, SAMPLE_WAIT_MS));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    while (received < 2400) {
        /* (the timeout is a failure bound: the sensor sends every 0.8 ms) */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, 5000));
        if (smp.reserved != expect)
            gaps += (uint16_t)(smp.reserved - expect);
        expect = (uint16_t)(smp.reserved + 1u);
        received++;
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    lep_client_get_stats(&client, &cs);
    st = stats_now();
    {
        char msg[200];
        snprintf(msg, sizeof msg,
                 "received %u, gaps %u, sim sent %llu and %llu answers, client saw %u messages",
                 received, gaps, (unsigned long long)st.samples_sent,
                 (unsigned long long)st.responses, (unsigned)cs.messages);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(0, gaps, msg);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(0, cs.bcc_errors, msg);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(received, cs.samples, msg);
        /* what was not received was still in flight when stop came, and
         * read before the stop's answer: the client saw every message sent */
        TEST_ASSERT_TRUE_MESSAGE(st.samples_sent >= received, msg);
        TEST_ASSERT_EQUAL_UINT64_MESSAGE(st.samples_sent + st.responses, cs.messages, msg);
        TEST_ASSERT_EQUAL_UINT64_MESSAGE(2, st.responses, msg); /* the start's, the stop's */
    }
    TEST_ASSERT_EQUAL_UINT64(0, st.samples_skipped + st.samples_blocked);
    TEST_ASSERT_FALSE(st.streaming);
}

static void test_nak_retries(void)
{
    lep_sim_options o;
    lep_product_info info;
    lep_client_stats cs;
    lep_sim_counters st;
    int i;
    lep_sim_options_init(&o);
    o.p_nak = 0.3;
    o.seed = 7;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 12));
    for (i = 0; i < 30; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    lep_client_get_stats(&client, &cs);
    st = stats_now();
    TEST_ASSERT_TRUE(st.faked_naks > 0);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)st.faked_naks, cs.naks);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)st.faked_naks, cs.retries);
    TEST_ASSERT_EQUAL_UINT64(30, st.commands);

    /* past the limit: a clear NAK error */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 0));
    for (i = 0; i < 40; i++) {
        int rc = lep_client_product_info(&client, &info);
        TEST_ASSERT_TRUE(rc == LEP_OK || rc == LEP_E_NAK);
        if (rc == LEP_E_NAK)
            return;
    }
    TEST_FAIL_MESSAGE("no NAK error in 40 tries at p_nak 0.3");
}

static void test_stale_stream_recovery(void)
{
    lep_sim_options o;
    lep_product_info info;
    lep_rated rated;
    lep_client_stats cs;
    lep_sim_options_init(&o);
    o.start_streaming = true;
    start_sim(&o);
    TEST_ASSERT_TRUE(stats_now().streaming);
    open_client();
    sleep_ms(100); /* the stale stream piles up */
    TEST_ASSERT_TRUE(stats_now().samples_sent > 50);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, &info));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(500.0f, rated.axis[LEP_FX]);
    TEST_ASSERT_FALSE(stats_now().streaming);
    lep_client_get_stats(&client, &cs);
    TEST_ASSERT_EQUAL_UINT32(0, cs.bcc_errors);
}

/* A stream nobody reads fills the pty and the queue: the samples due then are
 * counted as blocked (not computed, no wake-up each), every index accounted
 * for; a client that comes later recovers. */
static void test_nobody_reading_blocks(void)
{
    lep_sim_options o;
    lep_sim_counters st;
    int i;
    lep_sim_options_init(&o);
    o.start_streaming = true;
    o.rate_hz = 10000;
    start_sim(&o);
    for (i = 0; i < 2000; i++) { /* 20 s bound the wait */
        st = stats_now();
        if (st.samples_blocked > 1000)
            break;
        sleep_ms(10);
    }
    TEST_ASSERT_TRUE(st.samples_blocked > 1000);
    TEST_ASSERT_TRUE(st.samples_sent > 100);
    TEST_ASSERT_EQUAL_UINT64(0, st.samples_dropped);
    /* every index of the stream is sent, blocked or skipped (the published
     * sequence is the next index, mod 65536) */
    TEST_ASSERT_EQUAL_UINT16(st.sequence,
                             (uint16_t)(st.samples_sent + st.samples_blocked + st.samples_skipped));
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, &scratch_info));
    TEST_ASSERT_FALSE(stats_now().streaming);
}

static void wait_power_cycles(uint64_t n)
{
    int i;
    for (i = 0; i < 4000 && stats_now().power_cycles < n; i++) /* 20 s bound */
        sleep_ms(5);
    TEST_ASSERT_EQUAL_UINT64(n, stats_now().power_cycles);
}

static void test_filter_after_power_cycle(void)
{
    uint8_t code = 0xFF;
    start_default();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(0, code);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_set(&client, 3));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(0, code);
    TEST_ASSERT_EQUAL_UINT8(3, stats_now().filter_pending);
    lep_sim_power_cycle(sim);
    wait_power_cycles(1);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(3, code);
    TEST_ASSERT_EQUAL_UINT8(3, stats_now().filter);
}

static void test_hangup_is_disconnected(void)
{
    lep_sample smp;
    uint32_t t;
    int rc = LEP_OK, i;
    start_default();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
    lep_sim_hangup(sim);
    /* Each wait is cut short by the hang-up, never run out: it returns
     * LEP_E_DISCONNECTED (not LEP_E_TIMEOUT) well within its timeout,
     * whatever the load (the timeout is long, so that "within" has room). */
    t = lep_monotonic_ms();
    for (i = 0; i < 10000 && rc == LEP_OK; i++)
        rc = lep_client_next_sample(&client, &smp, HANGUP_WAIT_MS);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, rc);
    TEST_ASSERT_TRUE(lep_monotonic_ms() - t < (uint32_t)HANGUP_WAIT_MS / 2u);
    /* it stays so: no hang, no stream of timeouts */
    t = lep_monotonic_ms();
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED,
                          lep_client_next_sample(&client, &smp, HANGUP_WAIT_MS));
    TEST_ASSERT_TRUE_MESSAGE(lep_monotonic_ms() - t < (uint32_t)HANGUP_WAIT_MS / 2u,
                             "next sample after a hang-up");
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, HANGUP_WAIT_MS));
    t = lep_monotonic_ms();
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_client_product_info(&client, &scratch_info));
    TEST_ASSERT_TRUE_MESSAGE(lep_monotonic_ms() - t < (uint32_t)HANGUP_WAIT_MS / 2u,
                             "query after a hang-up");
    TEST_ASSERT_EQUAL_UINT64(1, stats_now().hangups);
}

static void test_hangup_after_and_reopen_at_link(void)
{
    lep_sim_options o;
    lep_product_info info;
    lep_sample smp;
    char link[128];
    int rc = LEP_OK, i;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/lep-sim-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(tmpdir));
    snprintf(link, sizeof link, "%s/port", tmpdir);
    lep_sim_options_init(&o);
    o.hangup_after_s = 0.3;
    o.reopen_after_ms = 200;
    snprintf(o.link, sizeof o.link, "%s", link);
    start_sim(&o);
    TEST_ASSERT_EQUAL_STRING(link, lep_sim_port(sim));
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 100000 && rc == LEP_OK; i++)
        rc = lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, rc);
    lep_serial_close(port);
    port = NULL;
    /* the link comes back, pointing at a new pty */
    for (i = 0; i < 2000; i++) { /* 20 s bound the wait */
        rc = lep_serial_open(link, &port, err, sizeof err);
        if (rc == LEP_OK)
            break;
        sleep_ms(10);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, &info));
    TEST_ASSERT_EQUAL_UINT64(1, stats_now().reopens);
    TEST_ASSERT_FALSE(stats_now().streaming); /* replugged: powered up idle */
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    TEST_ASSERT_NOT_EQUAL(0, access(link, F_OK)); /* link removed at stop */
    (void)unlink(link);
}

static void make_tmpdir(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/lep-sim-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(tmpdir));
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(text, f);
    fclose(f);
}

static bool file_is(const char *path, const char *text)
{
    char buf[256];
    size_t n;
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return false;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strcmp(buf, text) == 0;
}

/* The start is refused with LEP_E_BUSY, one line naming the path and needle. */
static void expect_link_refused(const char *link, const char *needle)
{
    lep_sim_options o;
    lep_sim *other = NULL;
    lep_sim_options_init(&o);
    snprintf(o.link, sizeof o.link, "%s", link);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_BUSY, lep_sim_start_so(&o, &other, err, sizeof err), err);
    TEST_ASSERT_NULL(other);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, link), err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, needle), err);
    TEST_ASSERT_NULL_MESSAGE(strchr(err, '\n'), err);
}

/* --link never deletes what is not a stale link to a pty (issue 8, item 8). */
static void test_link_keeps_what_is_not_a_stale_pty_link(void)
{
    char path[160], target[160], lock[176];
    make_tmpdir();
    /* a recording */
    snprintf(path, sizeof path, "%s/forces.csv", tmpdir);
    write_file(path, "t_s,fx_N\n0.1,2.0\n");
    expect_link_refused(path, "regular file");
    TEST_ASSERT_TRUE(file_is(path, "t_s,fx_N\n0.1,2.0\n"));
    (void)unlink(path);
    /* a directory */
    snprintf(path, sizeof path, "%s/dir", tmpdir);
    TEST_ASSERT_EQUAL_INT(0, mkdir(path, 0700));
    expect_link_refused(path, "directory");
    TEST_ASSERT_EQUAL_INT(0, rmdir(path));
    /* a FIFO (a special file like a device node) */
    snprintf(path, sizeof path, "%s/fifo", tmpdir);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(path, 0600));
    expect_link_refused(path, "FIFO");
    TEST_ASSERT_EQUAL_INT(0, unlink(path));
    /* a symlink to a device that is not a pty, and one to a file */
    snprintf(path, sizeof path, "%s/ttyUSB", tmpdir);
    TEST_ASSERT_EQUAL_INT(0, symlink("/dev/null", path));
    expect_link_refused(path, "not to a pseudo-terminal");
    TEST_ASSERT_EQUAL_INT(0, unlink(path)); /* still a symlink: it survived */
    snprintf(target, sizeof target, "%s/data.csv", tmpdir);
    write_file(target, "1,2,3,4,5,6\n");
    TEST_ASSERT_EQUAL_INT(0, symlink(target, path));
    expect_link_refused(path, "not to a pseudo-terminal");
    TEST_ASSERT_TRUE(file_is(path, "1,2,3,4,5,6\n"));
    TEST_ASSERT_EQUAL_INT(0, unlink(path));
    /* someone's own file where the lock would go */
    snprintf(lock, sizeof lock, "%s.lock", path);
    write_file(lock, "my notes\n");
    expect_link_refused(path, "not a leptrino-sim lock file");
    TEST_ASSERT_NOT_EQUAL(0, access(path, F_OK));
    TEST_ASSERT_TRUE(file_is(lock, "my notes\n"));
    TEST_ASSERT_EQUAL_INT(0, unlink(lock));
    TEST_ASSERT_EQUAL_INT(0, unlink(target));
}

/* A link left by a sensor that is gone (dangling, or to a pty nobody owns)
 * is replaced; the lock file of a dead sensor is reused. */
static void test_link_replaces_a_stale_pty_link(void)
{
    lep_sim_options o;
    char path[160], lock[176], target[512];
    ssize_t n;
    make_tmpdir();
    snprintf(path, sizeof path, "%s/port", tmpdir);
    snprintf(lock, sizeof lock, "%s.lock", path);
    TEST_ASSERT_EQUAL_INT(0, symlink("/dev/pts/987654", path));
    write_file(lock, "leptrino-sim link lock\npid 999999\n"); /* its owner died */
    lep_sim_options_init(&o);
    snprintf(o.link, sizeof o.link, "%s", path);
    start_sim(&o);
    n = readlink(path, target, sizeof target - 1);
    TEST_ASSERT_TRUE(n > 0);
    target[n] = '\0';
    TEST_ASSERT_EQUAL_STRING(lep_sim_pty_path(sim), target);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &scratch_info));
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    /* gone at stop, lock file too */
    TEST_ASSERT_NOT_EQUAL(0, access(path, F_OK));
    TEST_ASSERT_NOT_EQUAL(0, access(lock, F_OK));
}

/* Another running sensor's link is refused, also while it is hung up. */
static void test_link_of_a_running_sensor_is_refused(void)
{
    lep_sim_options o;
    char path[160], target[512], msg[64];
    ssize_t n;
    int i;
    make_tmpdir();
    snprintf(path, sizeof path, "%s/port", tmpdir);
    lep_sim_options_init(&o);
    snprintf(o.link, sizeof o.link, "%s", path);
    o.reopen_after_ms = 60000;
    start_sim(&o);
    snprintf(msg, sizeof msg, "pid %ld", (long)getpid());
    expect_link_refused(path, "running virtual sensor");
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, msg), err);
    n = readlink(path, target, sizeof target - 1);
    TEST_ASSERT_TRUE(n > 0);
    target[n] = '\0';
    TEST_ASSERT_EQUAL_STRING(lep_sim_pty_path(sim), target); /* untouched */
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &scratch_info));
    /* hung up, the link is gone, but the name is still the sensor's */
    lep_sim_hangup(sim);
    /* (the sensor publishes hung_up first, then removes the link: both
     * awaited, 20 s bound the wait) */
    for (i = 0; i < 2000 && (!stats_now().hung_up || access(path, F_OK) == 0); i++)
        sleep_ms(10);
    TEST_ASSERT_TRUE(stats_now().hung_up);
    TEST_ASSERT_NOT_EQUAL(0, access(path, F_OK));
    expect_link_refused(path, "running virtual sensor");
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    /* now it is free */
    start_sim(&o);
    TEST_ASSERT_EQUAL_STRING(path, lep_sim_port(sim));
}

static void test_exclusive_open(void)
{
    lep_serial *second = NULL;
    int rc;
    start_default();
    rc = lep_serial_open(lep_sim_port(sim), &second, err, sizeof err);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUSY, rc);
    TEST_ASSERT_NULL(second);
    TEST_ASSERT_NOT_NULL(strstr(err, "in use by another program"));
    TEST_ASSERT_NOT_NULL(strstr(err, lep_sim_port(sim)));
    /* the first user is unharmed */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &scratch_info));
    lep_serial_close(port);
    port = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_open(lep_sim_port(sim), &port, err, sizeof err));
}

/* A stalled sensor: reads return after their timeout, not before, not much later. */
static void test_timeouts_honoured(void)
{
    lep_io io;
    uint8_t buf[64];
    double t, dt;
    int rc;
    start_default();
    lep_serial_get_io(port, &io);
    t = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(0, io.read(io.user, buf, sizeof buf, 250));
    dt = lep_monotonic_seconds() - t;
    /* never early; the upper bound catches a timeout ignored or taken as
     * seconds, not a loaded machine's lateness */
    TEST_ASSERT_TRUE_MESSAGE(dt >= 0.250 && dt < 0.250 + 5.0, "silent read");

    lep_sim_stall(sim, 3000);
    sleep_ms(20);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, 300));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 0)); /* one attempt: 300 ms */
    t = lep_monotonic_seconds();
    rc = lep_client_product_info(&client, &scratch_info);
    dt = lep_monotonic_seconds() - t;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, rc);
    TEST_ASSERT_TRUE_MESSAGE(dt >= 0.299 && dt < 0.300 + 0.7, "transaction during a stall");

    /* a read that does not wait: one that did would wait out the stall (3 s) */
    t = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(0, io.read(io.user, buf, sizeof buf, 0));
    TEST_ASSERT_TRUE(lep_monotonic_seconds() - t < 1.5);

    lep_sim_stall(sim, 0); /* end it: the buffered command is answered */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, NULL));
}

static void test_stall_option_skips_samples(void)
{
    lep_sim_options o;
    lep_sample smp;
    uint16_t last = 0;
    unsigned got = 0, jumps = 0, after = 0;
    lep_sim_options_init(&o);
    o.stall_ms = 200;
    o.stall_after_s = 0.3;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    /* until 200 samples after the first jump: the stall's, counted, not timed
     * (at most 0.3 s of samples come before it; 3000 bound the wait) */
    while (after < 200) {
        TEST_ASSERT_TRUE_MESSAGE(got < 3000, "no jump in the sequence numbers");
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        if (got > 0 && smp.reserved != (uint16_t)(last + 1u))
            jumps++;
        after += jumps > 0 ? 1u : 0u;
        last = smp.reserved;
        got++;
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_EQUAL_UINT(1, jumps);
    TEST_ASSERT_EQUAL_UINT64(1, stats_now().stalls);
    TEST_ASSERT_TRUE(stats_now().samples_skipped > 100);
}

/* Start a stream by the protocol, read stop_after data frames, stop it,
 * and read on until the answer to the stop: everything sent before it.
 * Timing-free: the stop's answer is queued behind every sample sent before
 * it, and nothing is sent after it. Sequence gaps (from 0, the first sample
 * of a stream) go to *gaps; returns the number of data frames. */
static unsigned stream_and_stop(unsigned stop_after, uint16_t *expect, uint64_t *gaps,
                                unsigned *bad_frames)
{
    static const uint8_t start[] = { 0x04, 0xFF, LEP_CMD_START, 0x00 };
    static const uint8_t stop[] = { 0x04, 0xFF, LEP_CMD_STOP, 0x00 };
    lep_frame_decoder d;
    lep_io io;
    uint8_t buf[512];
    unsigned frames = 0;
    int idle = 0;
    bool stopping = false;
    lep_frame_decoder_init(&d);
    lep_serial_get_io(port, &io);
    send_message(start, sizeof start, false);
    while (idle < 20) { /* 20 silent seconds: something is lost, fail */
        int n = io.read(io.user, buf, sizeof buf, 1000);
        size_t off = 0;
        TEST_ASSERT_TRUE(n >= 0);
        idle = n == 0 ? idle + 1 : 0;
        while (off < (size_t)n) {
            lep_frame_event ev;
            lep_response r;
            off += lep_frame_decoder_feed(&d, buf + off, (size_t)n - off, &ev);
            if (ev.type != LEP_FRAME_MESSAGE) {
                if (ev.type != LEP_FRAME_NONE)
                    (*bad_frames)++;
                continue;
            }
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_decode(ev.msg, ev.len, &r));
            if (r.code == LEP_CMD_STOP)
                return frames;
            if (!r.stream)
                continue; /* the answer to start */
            *gaps += (uint16_t)(r.u.sample.reserved - *expect);
            *expect = (uint16_t)(r.u.sample.reserved + 1u);
            if (++frames == stop_after && !stopping) {
                send_message(stop, sizeof stop, false);
                stopping = true;
            }
        }
    }
    TEST_FAIL_MESSAGE("no answer to stop");
    return frames;
}

/* Drops and garbage: every sequence number the sensor generated is either
 * delivered or accounted for by a fault counter, exactly, however slow the
 * machine (valgrind included): no tolerance. */
static void test_drop_and_garbage_accounting(void)
{
    lep_sim_options o;
    lep_sim_counters st;
    uint16_t expect = 0;
    uint64_t gaps = 0;
    unsigned got, bad = 0;
    lep_sim_options_init(&o);
    o.p_drop = 0.05;
    o.p_garbage = 0.2;
    o.seed = 42;
    start_sim(&o);
    open_client();
    got = stream_and_stop(1200, &expect, &gaps, &bad);
    st = stats_now();
    TEST_ASSERT_FALSE(st.streaming);
    /* samples generated after the last one delivered, never sent */
    gaps += (uint16_t)(st.sequence - expect);
    {
        char msg[200];
        snprintf(msg, sizeof msg,
                 "delivered %u, gaps %llu; sim sent %llu, dropped %llu, skipped %llu, "
                 "blocked %llu, garbage bytes %llu, bad frames %u",
                 got, (unsigned long long)gaps, (unsigned long long)st.samples_sent,
                 (unsigned long long)st.samples_dropped, (unsigned long long)st.samples_skipped,
                 (unsigned long long)st.samples_blocked, (unsigned long long)st.garbage_bytes, bad);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(got >= 1200, msg);
        TEST_ASSERT_EQUAL_UINT64_MESSAGE(st.samples_sent, got, msg);
        TEST_ASSERT_EQUAL_UINT64_MESSAGE(
            st.samples_dropped + st.samples_skipped + st.samples_blocked, gaps, msg);
        TEST_ASSERT_TRUE_MESSAGE(st.samples_dropped > 20, msg);
        TEST_ASSERT_TRUE_MESSAGE(st.garbage_bytes > 0, msg);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(0, bad, msg); /* garbage never breaks a frame */
    }
}

static void test_corruption_is_caught(void)
{
    lep_sim_options o;
    lep_sample smp;
    lep_client_stats cs;
    unsigned got = 0;
    lep_sim_options_init(&o);
    o.p_corrupt = 0.1;
    o.seed = 3;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 10));
    /* the start answer may itself be corrupted: try again (idempotent via sync) */
    while (lep_client_start(&client) != LEP_OK)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, NULL));
    while (got < 600) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        got++;
    }
    lep_client_get_stats(&client, &cs);
    TEST_ASSERT_TRUE(cs.bcc_errors + cs.frame_errors + cs.invalid > 0);
    TEST_ASSERT_TRUE(stats_now().bytes_corrupted > 0);
}

static void test_overload_saturates(void)
{
    lep_sim_options o;
    lep_sample smp;
    unsigned over = 0, saturated = 0, got = 0;
    lep_sim_options_init(&o);
    o.overload_every_s = 0.2;
    o.overload_duration_s = 0.05;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    while (got < 600) { /* 0.5 s: two episodes */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        /* episode j: sample numbers 240 j to 240 j + 59 (0.2 s and 0.05 s at 1.2 kHz) */
        bool in = smp.reserved >= 240u && smp.reserved % 240u < 60u;
        TEST_ASSERT_EQUAL_INT(in, (smp.status & LEP_STATUS_OVERLOAD) != 0u);
        if (smp.status & LEP_STATUS_OVERLOAD)
            over++;
        if (lep_sample_saturated(&smp, LEP_SATURATION_V113))
            saturated++;
        got++;
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_TRUE(over >= 100 && over <= 120); /* 2 x 60 samples, less any skipped */
    TEST_ASSERT_EQUAL_UINT(over, saturated);
}

static void test_replay_and_determinism(void)
{
    lep_sim_options o;
    lep_sample smp, first[50];
    char file[64];
    FILE *f;
    unsigned i;
    snprintf(file, sizeof file, "/tmp/lep-replay-%ld.csv", (long)getpid());
    f = fopen(file, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs("fx,fy,fz,mx,my,mz\n1,2,3,4,5,6\n-10,-20,-30,-40,-50,-60\n# comment\n12000,0,0,0,0,0,1\n",
          f);
    fclose(f);
    lep_sim_options_init(&o);
    snprintf(o.replay_csv, sizeof o.replay_csv, "%s", file);
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 6; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        TEST_ASSERT_EQUAL_UINT16(i, smp.reserved);
        if (i % 3 == 0)
            TEST_ASSERT_EQUAL_INT16(1, smp.raw[0]);
        if (i % 3 == 1)
            TEST_ASSERT_EQUAL_INT16(-60, smp.raw[5]);
        if (i % 3 == 2) {
            TEST_ASSERT_EQUAL_INT16(12000, smp.raw[0]);
            TEST_ASSERT_EQUAL_HEX8(LEP_STATUS_CALIBRATION | LEP_STATUS_OVERLOAD, smp.status);
        } else {
            TEST_ASSERT_EQUAL_HEX8(0, smp.status);
        }
    }
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    (void)unlink(file);

    /* a missing replay file is a clear error */
    snprintf(o.replay_csv, sizeof o.replay_csv, "%s", "/nonexistent/replay.csv");
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "/nonexistent/replay.csv"));

    /* same seed, same stream */
    lep_sim_options_init(&o);
    o.seed = 99;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 50; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &first[i], SAMPLE_WAIT_MS));
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    start_sim(&o);
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 50; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        TEST_ASSERT_EQUAL_MEMORY(&first[i], &smp, sizeof smp);
    }
}

static void replay_file(char *file, size_t cap, const char *text)
{
    FILE *f;
    snprintf(file, cap, "/tmp/lep-replay2-%ld.csv", (long)getpid());
    f = fopen(file, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(text, f);
    fclose(f);
}

static int start_replay(const char *file)
{
    lep_sim_options o;
    lep_sim_options_init(&o);
    snprintf(o.replay_csv, sizeof o.replay_csv, "%s", file);
    return lep_sim_start_so(&o, &sim, err, sizeof err);
}

/* The leptrino tool's own raw recordings replay: comments skipped, columns
 * picked by name wherever they stand, the first sensor of several. */
static void test_replay_of_a_raw_recording(void)
{
    char file[64];
    lep_sample smp;
    static const int16_t want[3][6] = { { 1, 2, 3, 4, 5, 6 },
                                        { -10, -20, -30, -40, -50, -60 },
                                        { 32000, 0, -32000, 7, 8, 9 } };
    static const uint8_t want_status[3] = { 0, 0x01, LEP_STATUS_OVERLOAD };
    unsigned i;
    int a;
    replay_file(file, sizeof file,
                "# leptrino-metadata: {\"model\":\"PFS055YA501U6\",\"serial\":\"00000001\"}\r\n"
                "# leptrino-metadata: {\"model\":\"CFS018CA201U\"}\n"
                "t_s,sensor,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,mz_counts,my_counts,mx_counts,"
                "fz_counts,fy_counts,fx_counts,status,seq\r\n"
                "0.000833,left,0.1,0.2,0.3,0.004,0.005,0.006,6,5,4,3,2,1,0,0\r\n"
                "0.000833,right,9,9,9,9,9,9,99,99,99,99,99,99,0,0\n"
                "# gap from=0.001 to=0.002 lost=1 reason=gap\n"
                "0.002500,left,-0.5,-1,-1.5,-0.04,-0.05,-0.06,-60,-50,-40,-30,-20,-10,1,2\n"
                "\n"
                "0.003333, left ,1600,0,-1600,0.07,0.08,0.09, 9 , 8,7,-32000,0,32000,0,3\n");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, start_replay(file), err);
    for (i = 0; i < 6; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, i, 0, &smp));
        for (a = 0; a < 6; a++)
            TEST_ASSERT_EQUAL_INT16(want[i % 3][a], smp.raw[a]);
        TEST_ASSERT_EQUAL_HEX8(want_status[i % 3], smp.status);
    }
    /* and on the wire */
    open_client();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 3; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, SAMPLE_WAIT_MS));
        TEST_ASSERT_EQUAL_INT16(want[i][0], smp.raw[0]);
    }
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;

    /* the old headerless form with a status column, and CRLF */
    replay_file(file, sizeof file, "1,2,3,4,5,6,4\r\n-1,-2,-3,-4,-5,-6\r\n");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, start_replay(file), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, 0, 0, &smp));
    TEST_ASSERT_EQUAL_HEX8(LEP_STATUS_OVERLOAD, smp.status);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, 1, 0, &smp));
    TEST_ASSERT_EQUAL_INT16(-6, smp.raw[5]);
    lep_sim_stop(sim);
    sim = NULL;

    /* an SI recording cannot be replayed: say what is missing */
    replay_file(file, sizeof file,
                "# x\nt_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status\n0.1,1,2,3,4,5,6,0\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, start_replay(file));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, ":2: the header has no fx_counts column"), err);
    TEST_ASSERT_NULL(sim);
    /* a value that is not a count names its line and column */
    replay_file(file, sizeof file,
                "fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts\n"
                "1,2,3,4,5,6\n1,2,3.5,4,5,6\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, start_replay(file));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, ":3: column fz_counts: '3.5'"), err);
    replay_file(file, sizeof file,
                "fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts\n"
                "1,2,3,4,5,40000\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, start_replay(file));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "mz_counts: '40000'"), err);
    replay_file(file, sizeof file, "fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, start_replay(file));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "no samples"), err);
    replay_file(file, sizeof file, "1,2,3,4,5\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, start_replay(file));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, ":1: expected 6 or 7 integers"), err);
    (void)unlink(file);
}

static void test_bad_options(void)
{
    lep_sim_options o;
    lep_sim_options_init(&o);
    snprintf(o.model, sizeof o.model, "%s", "XYZ");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "XYZ"));
    lep_sim_options_init(&o);
    o.rate_hz = 0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    lep_sim_options_init(&o);
    o.filter = 4;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    lep_sim_options_init(&o);
    snprintf(o.serial, sizeof o.serial, "%s", "12a");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    lep_sim_options_init(&o);
    o.p_nak = 1.5;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    lep_sim_options_init(&o);
    o.reopen_after_ms = 100; /* needs a link */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NULL(sim);
}

static void test_models(void)
{
    const char *const *m = lep_sim_models();
    lep_rated r;
    size_t n = 0;
    while (m[n] != NULL)
        n++;
    TEST_ASSERT_EQUAL_size_t(4, n);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f("CFS018CA201U", &r));
    TEST_ASSERT_EQUAL_FLOAT(200.0f, r.axis[LEP_FZ]);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, r.axis[LEP_MZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f("CFS034CA301U", &r));
    TEST_ASSERT_EQUAL_FLOAT(4.0f, r.axis[LEP_MX]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f("PFS055YA501U6", &r));
    TEST_ASSERT_EQUAL_FLOAT(8.0f, r.axis[LEP_MZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f("PFS080YS102U6", &r));
    TEST_ASSERT_EQUAL_FLOAT(30.0f, r.axis[LEP_MZ]);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_model_rated_f("nope", &r));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_models);
    RUN_TEST(test_bad_options);
    RUN_TEST(test_every_command);
    RUN_TEST(test_product_info_with_output_rate);
    RUN_TEST(test_result_codes_and_nak);
    RUN_TEST(test_stream_exact_accounting);
    RUN_TEST(test_nak_retries);
    RUN_TEST(test_stale_stream_recovery);
    RUN_TEST(test_nobody_reading_blocks);
    RUN_TEST(test_filter_after_power_cycle);
    RUN_TEST(test_hangup_is_disconnected);
    RUN_TEST(test_hangup_after_and_reopen_at_link);
    RUN_TEST(test_link_keeps_what_is_not_a_stale_pty_link);
    RUN_TEST(test_link_replaces_a_stale_pty_link);
    RUN_TEST(test_link_of_a_running_sensor_is_refused);
    RUN_TEST(test_exclusive_open);
    RUN_TEST(test_timeouts_honoured);
    RUN_TEST(test_stall_option_skips_samples);
    RUN_TEST(test_drop_and_garbage_accounting);
    RUN_TEST(test_corruption_is_caught);
    RUN_TEST(test_overload_saturates);
    RUN_TEST(test_replay_and_determinism);
    RUN_TEST(test_replay_of_a_raw_recording);
    return UNITY_END();
}
