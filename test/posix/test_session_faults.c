/* The session when things go wrong, against the virtual sensor: a stall
 * shorter than the data timeout, dropped samples counted exactly, another
 * reader stealing bytes from the port, a hang-up with and without
 * reconnection, a data timeout, overload episodes; holes found from arrival
 * times on a port, a reader that lags and a sender running late. */
#define _POSIX_C_SOURCE 200809L

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "host_os.h"
#include "session_test.h"
#include "sim_trace_file.h"
#include "struct_api.h"
#include "unity.h"

void setUp(void)
{
}

void tearDown(void)
{
}

/* CLOCK_MONOTONIC, seconds. */
static double now_s(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Samples missing between the delivered sequence numbers (no wrap here), and
 * rows flagged LEP_SF_GAP where none is missing: a gap reported where none was. */
static uint64_t missing_and_false_gaps(const st_batch *b, size_t *false_gaps)
{
    uint64_t lost = 0;
    size_t i;
    *false_gaps = 0;
    for (i = 1; i < b->b.n; i++) {
        uint16_t d = (uint16_t)(b->seq[i] - b->seq[i - 1]);
        lost += d - 1u;
        *false_gaps += d == 1u && (b->flags[i] & LEP_SF_GAP) != 0u;
    }
    return lost;
}

/* Read until b holds want samples; returns the last return code. */
static int read_until(lep_session *s, st_batch *b, size_t want)
{
    int rc = LEP_OK;
    while (b->b.n < want) {
        rc = lep_session_read_batch(s, &b->b, 3000);
        if (rc != LEP_OK)
            break;
    }
    return rc;
}

/* Samples missing between the delivered sequence numbers (no wrap here). */
static uint64_t missing(const st_batch *b, size_t *holes)
{
    uint64_t m = 0;
    size_t i;
    *holes = 0;
    for (i = 1; i < b->b.n; i++) {
        uint16_t d = (uint16_t)(b->seq[i] - b->seq[i - 1]);
        if (d > 1) {
            m += d - 1u;
            (*holes)++;
            TEST_ASSERT_TRUE_MESSAGE(b->flags[i] & LEP_SF_GAP, "sample after a hole not flagged");
        } else {
            TEST_ASSERT_FALSE(b->flags[i] & LEP_SF_GAP);
        }
    }
    return m;
}

static void test_a_stall_shorter_than_the_data_timeout_is_a_gap(void)
{
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    st_batch b;
    lep_session_health_info h;
    lep_session_event ev;
    size_t holes, i, after = 0;
    bool seen = false;

    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 200));
    lep_sim_stall(lep_session_sim(s), 1000); /* data timeout is 2000 ms */
    /* read until the row after the hole and 200 more, not to a count: on a
     * loaded machine the sensor's thread may begin the stall only after more
     * samples than that were read */
    while (b.b.n + 100 <= 3800 && (after == 0 || b.b.n < after + 200)) {
        size_t from = b.b.n;
        TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, b.b.n + 100));
        for (i = from; i < b.b.n && after == 0; i++)
            if (b.flags[i] & LEP_SF_GAP)
                after = i;
    }
    after = 0;
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(1, h.gaps);
    TEST_ASSERT_EQUAL_UINT64(missing(&b, &holes), h.lost);
    TEST_ASSERT_EQUAL_size_t(1, holes);
    TEST_ASSERT_UINT64_WITHIN(120, 1200, h.lost); /* about one second of samples */
    TEST_ASSERT_TRUE(h.max_gap_s > 0.5);
    TEST_ASSERT_EQUAL_UINT64(0, h.disconnects);
    while (lep_session_pop_event(s, &ev)) {
        if (ev.type != LEP_EV_GAP)
            continue;
        seen = true;
        TEST_ASSERT_EQUAL_UINT32(h.lost, ev.lost);
        TEST_ASSERT_TRUE(ev.gap_to - ev.gap_from > 0.5);
        for (i = 0; i < b.b.n; i++)
            if (b.flags[i] & LEP_SF_GAP)
                after = i;
        TEST_ASSERT_EQUAL_UINT64(after, ev.sample);
    }
    TEST_ASSERT_TRUE(seen);
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_dropped_samples_are_counted_exactly(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    lep_session_health_info h;
    lep_session_event ev;
    size_t holes, events = 0, i;
    uint64_t lost_in_events = 0, m;
    lep_session_options_init(&o);
    o.sim.p_drop = 0.02;
    o.sim.seed = 7;
    o.lowpass_hz = 100.0; /* settles again after every hole */
    s = open_sim(&o, &o);
    st_batch_init(&b, 2400);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 2400));
    lep_session_get_health(s, &h);
    m = missing(&b, &holes);
    TEST_ASSERT_TRUE(m > 10);
    /* the health counts the samples processed, which on a loaded machine run
     * ahead of the rows read: at least what is missing among those read */
    TEST_ASSERT_TRUE(h.lost >= m);
    TEST_ASSERT_TRUE(h.gaps >= holes);
    /* the events before the rows read: exactly their holes */
    while (lep_session_pop_event(s, &ev))
        if (ev.type == LEP_EV_GAP && ev.sample < b.b.n) {
            events++;
            lost_in_events += ev.lost;
        }
    TEST_ASSERT_EQUAL_size_t(holes, events);
    TEST_ASSERT_EQUAL_UINT64(m, lost_in_events);
    for (i = 0; i < b.b.n; i++)
        if (b.flags[i] & LEP_SF_GAP)
            TEST_ASSERT_TRUE(b.flags[i] & LEP_SF_SETTLING);
    lep_session_close(s);
    st_batch_free(&b);
}

typedef struct thief {
    int fd;
    st_flag stop;
    pthread_mutex_t mu;
    size_t stolen; /* under mu */
} thief;

static size_t thief_stolen(thief *t)
{
    size_t n;
    pthread_mutex_lock(&t->mu);
    n = t->stolen;
    pthread_mutex_unlock(&t->mu);
    return n;
}

/* Steals in bursts: races the session for every byte during 50 ms of each
 * 150 ms and leaves the port alone otherwise. A thief that never paused could
 * win nearly every race on a loaded machine, so that the session saw no
 * sample for its whole data timeout (a lost stream, not the holes tested). */
static void *steal(void *arg)
{
    thief *t = arg;
    uint8_t buf[256];
    unsigned tick = 0;
    while (!st_flag_is_up(&t->stop)) {
        struct pollfd p;
        if (tick++ % 15u >= 5u) {
            (void)poll(NULL, 0, 10); /* idle for 10 ms */
            continue;
        }
        p.fd = t->fd;
        p.events = POLLIN;
        p.revents = 0;
        if (poll(&p, 1, 10) > 0) {
            ssize_t n = read(t->fd, buf, sizeof buf);
            if (n > 0) {
                pthread_mutex_lock(&t->mu);
                t->stolen += (size_t)n;
                pthread_mutex_unlock(&t->mu);
            }
        }
    }
    return NULL;
}

/* Bytes the thief takes while the session holds off: more than ten frames,
 * a hole well beyond the gap threshold (3 periods) wherever it begins. */
#define THEFT_WHILE_AWAY 300u
/* A failure bound, never a measure: the thief's burst comes within 150 ms. */
#define THEFT_DEADLINE_S 20.0

/* Another program reading the same port takes bytes the session never sees:
 * it must show up as gaps (and broken frames as errors), not "0 gaps".
 * on_port: the sensor behind a port path (holes found from arrival times)
 * instead of the in-process one (sequence numbers).
 * The thief races the session's reads; and once, the session holds off until
 * the thief has taken THEFT_WHILE_AWAY bytes (a handshake, not a hope that
 * the thief's thread wins some race in time on a loaded machine: it may win
 * none, or only pieces too small to be told from transit jitter on a port). */
static void steal_from(bool on_port)
{
    lep_session_options o;
    lep_sim *sim = NULL;
    lep_session *s = NULL;
    st_batch b;
    lep_session_health_info h;
    thief t;
    pthread_t th;
    size_t holes, before;
    double deadline;

    if (on_port) {
        lep_session_options_init(&o);
        s = open_on_port(&sim, NULL, &o);
    } else {
        s = open_sim(&o, NULL);
        sim = lep_session_sim(s);
    }

    st_batch_init(&b, 6000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 100));
    memset(&t, 0, sizeof t);
    st_flag_init(&t.stop);
    pthread_mutex_init(&t.mu, NULL);
    /* A second open of the pty works for root despite TIOCEXCL; otherwise
     * share the session's descriptor, as a forked program would. */
    t.fd = open(lep_sim_pty_path(sim), O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (t.fd < 0)
        t.fd = dup(lep_session_fd(s));
    TEST_ASSERT_TRUE(t.fd >= 0);
    TEST_ASSERT_EQUAL_INT(0, pthread_create(&th, NULL, steal, &t));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 300)); /* racing */
    before = thief_stolen(&t);
    deadline = now_s() + THEFT_DEADLINE_S;
    while (thief_stolen(&t) < before + THEFT_WHILE_AWAY && now_s() < deadline)
        (void)poll(NULL, 0, 5); /* the session away: the thief's bytes */
    TEST_ASSERT_TRUE_MESSAGE(thief_stolen(&t) >= before + THEFT_WHILE_AWAY,
                             "the thief took too little while the session was away");
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, b.b.n + 400)); /* racing again */
    st_flag_raise(&t.stop);
    pthread_join(th, NULL);
    close(t.fd);
    /* the last hole judged: reads well after it */
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, b.b.n + 200));
    lep_session_get_health(s, &h);
    TEST_ASSERT_TRUE_MESSAGE(h.gaps > 0, "bytes stolen by another reader were not reported");
    TEST_ASSERT_TRUE(h.lost > 0);
    if (!on_port)
        TEST_ASSERT_EQUAL_UINT64(missing(&b, &holes), h.lost); /* exact from sequence numbers */
    lep_session_close(s);
    if (on_port)
        lep_sim_stop(sim);
    pthread_mutex_destroy(&t.mu);
    st_batch_free(&b);
}

static void test_another_reader_stealing_bytes_is_reported(void)
{
    steal_from(false);
}

static void test_another_reader_on_a_port_is_reported(void)
{
    steal_from(true);
}

static void test_hangup_without_reconnect_is_reported(void)
{
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    st_batch b;
    lep_session_event ev;
    lep_session_health_info h;
    int rc;
    bool seen = false;

    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 100));
    lep_sim_hangup(lep_session_sim(s));
    rc = read_until(s, &b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, rc);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_session_read_batch(s, &b.b, 10)); /* and stays */
    while (lep_session_pop_event(s, &ev))
        if (ev.type == LEP_EV_DISCONNECTED) {
            seen = true;
            TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, ev.error);
        }
    TEST_ASSERT_TRUE(seen);
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(1, h.disconnects);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_stop(s)); /* the port is gone: nothing to stop */
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_hangup_with_reconnect_resumes_and_marks_the_gap(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    lep_session_event ev;
    lep_session_health_info h;
    size_t i, resumed = 0;
    int order = 0;
    lep_session_options_init(&o);
    o.reconnect = true;
    o.sim.reopen_after_ms = 300; /* the session makes the link the port comes back under */
    s = open_sim(&o, &o);
    st_batch_init(&b, 3000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 200));
    lep_sim_hangup(lep_session_sim(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 1000));
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(1, h.disconnects);
    TEST_ASSERT_EQUAL_UINT64(1, h.reconnects);
    /* the stream restarted: sequence numbers begin at 0 again, flagged */
    for (i = 1; i < b.b.n; i++)
        if (b.seq[i] != (uint16_t)(b.seq[i - 1] + 1u)) {
            TEST_ASSERT_EQUAL_size_t(0, resumed);
            resumed = i;
        }
    TEST_ASSERT_TRUE(resumed > 0);
    TEST_ASSERT_EQUAL_UINT16(0, b.seq[resumed]);
    TEST_ASSERT_TRUE(b.flags[resumed] & LEP_SF_GAP);
    TEST_ASSERT_TRUE(b.t_mono[resumed] - b.t_mono[resumed - 1] > 0.25);
    while (lep_session_pop_event(s, &ev)) {
        if (ev.type == LEP_EV_DISCONNECTED) {
            TEST_ASSERT_EQUAL_INT(0, order++);
            TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, ev.error);
        } else if (ev.type == LEP_EV_RECONNECTED) {
            TEST_ASSERT_EQUAL_INT(1, order++);
            TEST_ASSERT_EQUAL_UINT64(resumed, ev.sample);
            TEST_ASSERT_EQUAL_DOUBLE(b.t_mono[resumed - 1], ev.gap_from);
            TEST_ASSERT_EQUAL_DOUBLE(b.t_mono[resumed], ev.gap_to);
            TEST_ASSERT_TRUE(ev.lost > 200);
        }
    }
    TEST_ASSERT_EQUAL_INT(2, order);
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_data_timeout_without_reconnect(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    lep_session_event ev;
    bool seen = false;
    lep_session_options_init(&o);
    o.data_timeout_ms = 300;
    s = open_sim(&o, &o);
    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 100));
    lep_sim_stall(lep_session_sim(s), 1500);
    /* lost, not "nothing yet": LEP_E_LOST then and on later calls */
    TEST_ASSERT_EQUAL_INT(LEP_E_LOST, read_until(s, &b, 4000));
    TEST_ASSERT_EQUAL_INT(LEP_E_LOST, lep_session_read_batch(s, &b.b, 10));
    TEST_ASSERT_EQUAL_INT(LEP_E_LOST, lep_session_read_batch(s, &b.b, 0));
    while (lep_session_pop_event(s, &ev))
        if (ev.type == LEP_EV_DISCONNECTED) {
            seen = true;
            TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, ev.error);
        }
    TEST_ASSERT_TRUE(seen);
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_overload_episodes_are_events(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    lep_session_event ev;
    lep_session_health_info h;
    size_t i, flagged = 0;
    int begins = 0, ends = 0;
    lep_session_options_init(&o);
    o.sim.overload_every_s = 0.2;
    o.sim.overload_duration_s = 0.05;
    s = open_sim(&o, &o);
    st_batch_init(&b, 1200);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 1200));
    for (i = 0; i < b.b.n; i++) {
        bool over = (b.status[i] & 0x04u) != 0u;
        TEST_ASSERT_EQUAL(over, (b.flags[i] & LEP_SF_OVERLOAD) != 0u);
        flagged += over;
    }
    TEST_ASSERT_TRUE(flagged > 0);
    while (lep_session_pop_event(s, &ev)) {
        if (ev.type == LEP_EV_OVERLOAD_BEGIN) {
            TEST_ASSERT_EQUAL_INT(begins, ends);
            begins++;
            if (ev.sample >= b.b.n)
                continue; /* for a sample received but not read yet */
            TEST_ASSERT_TRUE(b.flags[ev.sample] & LEP_SF_OVERLOAD);
            TEST_ASSERT_FALSE(ev.sample > 0 && (b.flags[ev.sample - 1] & LEP_SF_OVERLOAD));
        } else if (ev.type == LEP_EV_OVERLOAD_END) {
            ends++;
            TEST_ASSERT_EQUAL_INT(begins, ends);
        }
    }
    lep_session_get_health(s, &h);
    TEST_ASSERT_TRUE(begins >= 3);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)begins, h.overloads);
    lep_session_close(s);
    st_batch_free(&b);
}

/* A sensor without sequence numbers (a port path, not the in-process
 * virtual sensor): the hole is found from arrival times and its size
 * estimated from the elapsed time. */
static void test_a_stall_on_a_port_is_found_from_arrival_times(void)
{
    lep_sim *sim = NULL;
    lep_session_options o;
    lep_session *s = NULL;
    st_batch b;
    lep_session_health_info h;
    lep_session_event ev;
    bool seen = false;
    size_t i, flagged = 0;

    lep_session_options_init(&o);
    s = open_on_port(&sim, NULL, &o);
    TEST_ASSERT_NULL(lep_session_sim(s));
    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 200));
    lep_sim_stall(sim, 1000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 1000));
    lep_session_get_health(s, &h);
    TEST_ASSERT_TRUE(h.gaps >= 1);
    TEST_ASSERT_UINT64_WITHIN(400, 1200, h.lost); /* estimated from arrival times */
    while (lep_session_pop_event(s, &ev))
        if (ev.type == LEP_EV_GAP && ev.lost > 600) {
            seen = true;
            TEST_ASSERT_TRUE(ev.gap_to - ev.gap_from > 0.8);
            TEST_ASSERT_TRUE(ev.sample < b.b.n);
            TEST_ASSERT_TRUE(b.flags[ev.sample] & LEP_SF_GAP);
        }
    TEST_ASSERT_TRUE(seen);
    for (i = 0; i < b.b.n; i++)
        flagged += (b.flags[i] & LEP_SF_GAP) != 0u;
    TEST_ASSERT_EQUAL_size_t(h.gaps, flagged);
    lep_session_close(s);
    lep_sim_stop(sim);
    st_batch_free(&b);
}

/* A reader that falls behind (a caller busy for 0.55 s between reads, the
 * sensor on time): the kernel holds the samples, and the reads that catch up
 * take them a tty buffer (4 KiB, about 146 samples) at a time. Nothing is
 * lost and no hole is reported: the suspected holes are refuted by the reads
 * that bring more than was due, and the rows held meanwhile are all
 * delivered. The backlog (660 samples, 18 kB) stays within what a pty holds
 * (about 20 kB), as a real port's kernel buffer holds it: beyond that the
 * virtual sensor queues the rest itself and sends it when its thread next
 * runs, which a loaded machine may delay, a silence no real port has. (A
 * virtual sensor starved on a loaded machine skips samples: those are real
 * holes, and may be reported.) */
static void test_a_reader_behind_by_several_buffers_loses_nothing(void)
{
    lep_sim *sim = NULL;
    lep_session_options o;
    lep_session *s = NULL;
    st_batch b;
    lep_session_health_info h;
    lep_sim_counters st;
    size_t false_gaps = 0;
    uint64_t lost;

    lep_session_options_init(&o);
    /* a hole is 0.2 s here: the reader's 0.55 s leaves the stream late by
     * more after each of the first two reads (without the lag rule, the
     * second confirms a gap); the virtual sensor's own lateness on a loaded
     * machine (or under valgrind) stays below it */
    o.gap_periods = 240.0;
    s = open_on_port(&sim, NULL, &o);
    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 100));
    {
        struct timespec busy = { 0, 550000000L };
        nanosleep(&busy, NULL);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 2000));
    lost = missing_and_false_gaps(&b, &false_gaps);
    lep_session_get_health(s, &h);
    lep_sim_get_stats(sim, &st);
    printf("reader 0.55 s behind: %zu samples read, %llu missing (the virtual sensor skipped "
           "%llu), %llu gaps reported, %zu where none was\n",
           b.b.n, (unsigned long long)lost,
           (unsigned long long)(st.samples_skipped + st.samples_blocked),
           (unsigned long long)h.gaps, false_gaps);
    /* the sensor's counts, taken after the last row, may include samples it
     * skipped since: missing ones are at most those */
    TEST_ASSERT_TRUE(lost <= st.samples_skipped + st.samples_blocked);
    TEST_ASSERT_EQUAL_size_t(0, false_gaps);
    TEST_ASSERT_EQUAL_UINT64(b.b.n, h.delivered);
    lep_session_close(s);
    lep_sim_stop(sim);
    st_batch_free(&b);
}

/* The longest the sensor wrote nothing between two data messages of the
 * first `read` of its stream (its write trace at path), in seconds. */
static double longest_write_silence(const char *path, size_t read)
{
    size_t n, i;
    lep_sim_trace_record *r = lep_test_load_trace(path, &n);
    double most = 0.0;
    for (i = 1; i < n; i++) {
        const lep_sim_trace_record *a = &r[i - 1], *z = &r[i];
        if (a->k >= LEP_SIM_TRACE_END || z->k >= LEP_SIM_TRACE_END || z->k >= read)
            continue;
        if ((double)(z->t_call_ns - a->t_return_ns) * 1e-9 > most)
            most = (double)(z->t_call_ns - a->t_return_ns) * 1e-9;
    }
    free(r);
    return most;
}

/* A sender running late (the virtual sensor holds its output 200 ms, then
 * sends it together, as an adapter or a busy host would): the stream falls
 * behind and catches up, which is not a hole. Nothing is lost and no gap is
 * reported, though the port was silent for longer than a hole (100 ms here)
 * and the catch-up may take more than one read. That the sensor held its
 * output among the samples read is taken from its write trace (when it took
 * the request is up to its thread, on a loaded machine later than asked). */
static void test_a_sender_running_late_is_not_a_hole(void)
{
    lep_sim *sim = NULL;
    lep_session_options o;
    lep_session *s = NULL;
    st_batch b;
    lep_session_health_info h;
    lep_sim_counters st;
    size_t n0, false_gaps = 0;
    uint64_t lost;
    double t0, silent, held;
    int rc;
    char dir[64], path[96], err[256] = "";

    snprintf(dir, sizeof dir, "/tmp/lep-late-XXXXXX");
    TEST_ASSERT_NOT_NULL(lep_test_mkdtemp(dir));
    snprintf(path, sizeof path, "%s/writes.bin", dir);
    lep_session_options_init(&o);
    o.gap_periods = 120.0;
    s = open_on_port(&sim, NULL, &o);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 200));
    lep_sim_hold(sim, 200);
    {
        struct timespec taken = { 0, 5000000L }; /* the sensor takes the request */
        nanosleep(&taken, NULL);
    }
    do /* what was written before the hold */
        rc = lep_session_read_batch(s, &b.b, 0);
    while (rc == LEP_OK && b.b.n < b.b.cap);
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, rc);
    n0 = b.b.n;
    t0 = now_s();
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, n0 + 1));
    silent = now_s() - t0; /* (printed: on a loaded machine the hold may begin later) */
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 1200));
    lost = missing_and_false_gaps(&b, &false_gaps);
    lep_session_get_health(s, &h);
    lep_session_close(s);
    lep_sim_get_stats(sim, &st);
    lep_sim_stop(sim); /* (the rest of the trace written) */
    held = longest_write_silence(path, b.b.n);
    (void)unlink(path);
    (void)rmdir(dir);
    printf("sender 200 ms late: held %.0f ms, silent %.0f ms after the drain, %zu samples read, "
           "%llu missing, %llu gaps\n",
           held * 1e3, silent * 1e3, b.b.n, (unsigned long long)lost, (unsigned long long)h.gaps);
    TEST_ASSERT_TRUE_MESSAGE(held >= 0.2, "the hold did not hold the output");
    TEST_ASSERT_TRUE(lost <= st.samples_skipped + st.samples_blocked);
    TEST_ASSERT_EQUAL_UINT64(0, h.gaps);
    TEST_ASSERT_EQUAL_size_t(0, false_gaps);
    st_batch_free(&b);
}

/* The port comes back with another sensor (another serial number): the
 * session does not take its data as the same recording. */
static void test_another_sensor_after_a_reconnect_is_refused(void)
{
    lep_sim_options so;
    lep_sim *sim = NULL;
    lep_session_options o;
    lep_session *s = NULL;
    st_batch b;
    char err[256] = "", link[96];
    int rc = LEP_OK, i;

    snprintf(link, sizeof link, "/tmp/lep-test-replug-%ld", (long)getpid());
    lep_sim_options_init(&so);
    snprintf(so.link, sizeof so.link, "%s", link);
    lep_session_options_init(&o);
    o.reconnect = true;
    s = open_on_port(&sim, &so, &o); /* the port is the link */
    st_batch_init(&b, 4000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, read_until(s, &b, 100));
    lep_sim_stop(sim); /* unplugged ... */
    snprintf(so.serial, sizeof so.serial, "%s", "77");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(&so, &sim, err, sizeof err), err);
    for (i = 0; i < 100 && (rc == LEP_OK || rc == LEP_E_TIMEOUT); i++) /* ... another plugged in */
        rc = lep_session_read_batch(s, &b.b, 100);
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, rc);
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, lep_session_read_batch(s, &b.b, 10));
    lep_session_close(s);
    lep_sim_stop(sim);
    st_batch_free(&b);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_stall_shorter_than_the_data_timeout_is_a_gap);
    RUN_TEST(test_dropped_samples_are_counted_exactly);
    RUN_TEST(test_another_reader_stealing_bytes_is_reported);
    RUN_TEST(test_hangup_without_reconnect_is_reported);
    RUN_TEST(test_hangup_with_reconnect_resumes_and_marks_the_gap);
    RUN_TEST(test_data_timeout_without_reconnect);
    RUN_TEST(test_overload_episodes_are_events);
    RUN_TEST(test_a_stall_on_a_port_is_found_from_arrival_times);
    RUN_TEST(test_another_reader_on_a_port_is_reported);
    RUN_TEST(test_a_reader_behind_by_several_buffers_loses_nothing);
    RUN_TEST(test_a_sender_running_late_is_not_a_hole);
    RUN_TEST(test_another_sensor_after_a_reconnect_is_refused);
    return UNITY_END();
}
