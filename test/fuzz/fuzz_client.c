/* Fuzz target: the host client driven by an input that scripts the line.
 *
 * The first bytes set the timeout, retry limit, watchdog and whether the
 * blocking calls get a read buffer. The rest feeds a port whose every read
 * takes a control byte: deliver the next few bytes (often stream data while
 * a query waits), time out, fail (LEP_E_IO or LEP_E_DISCONNECTED), or make the
 * clock jump by an arbitrary amount (backwards too). Writes fail on a
 * schedule the input chooses. The client runs the blocking calls (recovery,
 * queries, start, batches of samples, a query while streaming, stop) and the
 * step API (recovery, a transaction, samples) over it.
 * Invariants: no crash or UB; every call returns (reads are bounded); only
 * documented errors come back; nothing is busy after a blocking call; the
 * sample counter equals the samples delivered; a delivered sample satisfies
 * the message rules (|raw| <= 32000). */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "leptrino/leptrino.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct line {
    const uint8_t *data;
    size_t len;
    size_t pos;
    uint32_t now;
    unsigned reads;
    unsigned writes;
    uint8_t fail_every; /* writes: every Nth fails (0: never) */
} line;

static uint8_t next_byte(line *l)
{
    return l->pos < l->len ? l->data[l->pos++] : 0u;
}

static uint32_t line_clock(void *user)
{
    return ((line *)user)->now;
}

static int line_write(void *user, const uint8_t *d, size_t n)
{
    line *l = user;
    (void)d;
    check(n > 0 && n <= LEP_MAX_FRAME);
    l->writes++;
    if (l->fail_every != 0u && l->writes % l->fail_every == 0u) {
        return (l->writes & 1u) ? LEP_E_IO : LEP_E_DISCONNECTED;
    }
    return 0;
}

static int line_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    line *l = user;
    uint8_t ctl;
    size_t n;
    l->reads++;
    /* Each read consumes input or lets time pass: a client that keeps reading
     * past this bound ignores its deadlines. */
    check(l->reads <= 4u * l->len + 20000u);
    check(cap >= 1);
    if (l->pos >= l->len) {
        l->now += (uint32_t)(timeout_ms < 0 ? 1000 : timeout_ms);
        return 0;
    }
    ctl = next_byte(l);
    switch (ctl >> 5) {
    case 0: /* time out */
        l->now += (uint32_t)(timeout_ms < 0 ? 1000 : timeout_ms);
        return 0;
    case 1: { /* the clock jumps */
        uint32_t j = (uint32_t)next_byte(l) << 24 | (uint32_t)next_byte(l) << 16 |
                     (uint32_t)next_byte(l) << 8 | next_byte(l);
        l->now += j;
        return 0;
    }
    case 2: /* a failing read, rarely */
        if ((ctl & 0x1Fu) == 0u) {
            return (ctl & 1u) ? LEP_E_IO : LEP_E_DISCONNECTED;
        }
        /* fall through */
    default: /* deliver bytes */
        n = 1u + (ctl & 0x1Fu);
        if (n > cap) {
            n = cap;
        }
        if (n > l->len - l->pos) {
            n = l->len - l->pos;
        }
        memcpy(buf, l->data + l->pos, n);
        l->pos += n;
        l->now += 1u;
        return (int)n;
    }
}

static bool documented(int rc)
{
    switch (rc) {
    case LEP_OK:
    case LEP_E_SENSOR:
    case LEP_E_NAK:
    case LEP_E_TIMEOUT:
    case LEP_E_IO:
    case LEP_E_DISCONNECTED:
    case LEP_E_STATE:
    case LEP_E_NO_SYNC:
    case LEP_E_STALLED:
        return true;
    default:
        return false;
    }
}

static void done(const lep_client *c, int rc)
{
    check(documented(rc));
    check(!lep_client_busy(c));
}

static void sample_ok(const lep_sample *s)
{
    size_t i;
    for (i = 0; i < LEP_AXES; i++) {
        check(s->raw[i] >= -32000 && s->raw[i] <= 32000);
    }
}

static void blocking(lep_client *c, uint32_t *delivered)
{
    lep_product_info info;
    lep_rated rated;
    lep_sample batch[8];
    uint8_t filter;
    unsigned rounds;
    size_t n = 0;
    int rc;
    done(c, lep_client_sync(c, 3, &info));
    done(c, lep_client_product_info(c, &info));
    done(c, lep_client_rated(c, &rated));
    done(c, lep_client_filter_get(c, &filter));
    done(c, lep_client_sample(c, &batch[0]));
    rc = lep_client_start(c);
    done(c, rc);
    for (rounds = 0; rounds < 64u && lep_client_streaming(c); rounds++) {
        size_t i;
        rc = lep_client_next_samples(c, batch, 8, &n, (int)(rounds % 7u));
        check(documented(rc) && n <= 8);
        for (i = 0; i < n; i++) {
            sample_ok(&batch[i]);
        }
        *delivered += (uint32_t)n;
        if (rounds % 5u == 2u) {
            done(c, lep_client_rated(c, &rated)); /* samples arrive while it waits */
        }
        if (rc == LEP_E_IO || rc == LEP_E_DISCONNECTED) {
            break;
        }
    }
    done(c, lep_client_stop(c));
}

static void stepping(lep_client *c, line *l, uint32_t *delivered)
{
    lep_command cmds[3] = { { LEP_CMD_RATED, 0 }, { LEP_CMD_START, 0 }, { LEP_CMD_FILTER_SET, 2 } };
    unsigned k;
    if (lep_client_recover(c, 5) != LEP_OK) {
        return;
    }
    for (k = 0; l->pos < l->len && k < 100000u; k++) {
        uint8_t b = next_byte(l);
        size_t used = 0;
        int rc;
        if (b == 0xFEu) {
            l->now += (uint32_t)next_byte(l) * 7u; /* time passes on an idle line */
            rc = lep_client_step(c, NULL, 0, &used);
            check(used == 0);
        } else {
            rc = lep_client_step(c, &b, 1, &used);
            check(used == 1);
        }
        check(rc >= 0 ? rc <= LEP_STEP_SAMPLE : documented(rc));
        if (rc == LEP_STEP_SAMPLE) {
            lep_sample s;
            lep_response r;
            check(lep_client_get_sample(c, &s) == LEP_OK);
            sample_ok(&s);
            /* the sample kept at the outcome is the message's, decoded again */
            check(lep_client_response(c, &r) == LEP_OK && r.stream);
            check(memcmp(r.u.sample.raw, s.raw, sizeof(s.raw)) == 0 &&
                  r.u.sample.reserved == s.reserved && r.u.sample.status == s.status);
            (*delivered)++;
        }
        if (rc != LEP_STEP_NONE && rc != LEP_STEP_SAMPLE && !lep_client_busy(c)) {
            lep_response r;
            if (rc == LEP_STEP_RESPONSE) {
                check(lep_client_response(c, &r) == LEP_OK);
            }
            (void)lep_client_send(c, &cmds[k % 3u]);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lep_client_rx rx;
    line l;
    lep_io io;
    lep_client c;
    lep_client_stats st;
    uint32_t delivered = 0;
    uint8_t cfg;
    memset(&l, 0, sizeof(l));
    l.data = data;
    l.len = size;
    l.now = 0xFFFFFF00u;
    cfg = next_byte(&l);
    l.fail_every = (uint8_t)(next_byte(&l) % 9u);
    io.write = line_write;
    io.read = line_read;
    io.now_ms = line_clock;
    io.user = &l;
    check(lep_client_init(&c, &io) == LEP_OK);
    check(lep_client_set_timeout(&c, 1 + (cfg & 7u)) == LEP_OK);
    check(lep_client_set_retries(&c, (int)((cfg >> 3) & 3u)) == LEP_OK);
    check(lep_client_set_watchdog(&c, (uint16_t)((cfg & 0x20u) ? 4u : 0u)) == LEP_OK);
    check(lep_client_set_rx(&c, (cfg & 0x40u) ? &rx : NULL) == LEP_OK);
    if (cfg & 0x80u) {
        stepping(&c, &l, &delivered);
    } else {
        blocking(&c, &delivered);
    }
    lep_client_get_stats(&c, &st);
    check(st.samples == delivered);
    return 0;
}
