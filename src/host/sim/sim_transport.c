/* Virtual sensor: the transport's packetising rule (contract in
 * sim_transport.h). No clock, no I/O, no malloc. */
#include "sim_transport.h"

#include <string.h>

#define F SIM_USB_FRAME_NS

/* The first frame boundary at or after t (t >= 0). */
static int64_t boundary_at_or_after(int64_t t)
{
    return (t + F - 1) / F * F;
}

static const sim_transport_entry *entry(const sim_transport *tr, size_t i)
{
    return &tr->e[(tr->head + i) % SIM_TRANSPORT_ENTRIES];
}

void lep_priv_sim_transport_init(sim_transport *tr, int mode, int ftdi_latency_ms)
{
    memset(tr, 0, sizeof *tr);
    tr->mode = mode;
    tr->latency_ns = (int64_t)ftdi_latency_ms * 1000000;
}

void lep_priv_sim_transport_clear(sim_transport *tr)
{
    tr->entered = tr->released = tr->written = 0;
    tr->head = tr->len = 0;
}

void lep_priv_sim_transport_in(sim_transport *tr, int64_t t, size_t n)
{
    sim_transport_entry *last;
    if (n == 0)
        return;
    tr->entered += n;
    if (tr->mode == SIM_TRANSPORT_NONE) {
        tr->released = tr->entered;
        return;
    }
    last = tr->len > 0 ? &tr->e[(tr->head + tr->len - 1u) % SIM_TRANSPORT_ENTRIES] : NULL;
    if (last != NULL && t < last->t)
        t = last->t; /* a FIFO: nothing overtakes what entered before it */
    if (last != NULL && (t == last->t || tr->len == SIM_TRANSPORT_ENTRIES)) {
        last->end = tr->entered;
        return;
    }
    tr->e[(tr->head + tr->len) % SIM_TRANSPORT_ENTRIES].t = t;
    tr->e[(tr->head + tr->len) % SIM_TRANSPORT_ENTRIES].end = tr->entered;
    tr->len++;
}

/* Bytes that entered at or before b. */
static uint64_t entered_by(const sim_transport *tr, int64_t b)
{
    uint64_t n = tr->released;
    size_t i;
    for (i = 0; i < tr->len && entry(tr, i)->t <= b; i++)
        n = entry(tr, i)->end;
    return n > tr->released ? n : tr->released;
}

static void release_to(sim_transport *tr, uint64_t to)
{
    tr->released = to;
    while (tr->len > 0 && entry(tr, 0)->end <= to) {
        tr->head = (tr->head + 1u) % SIM_TRANSPORT_ENTRIES;
        tr->len--;
    }
}

/* Frame boundary b happens, with bytes in the adapter. */
static void frame(sim_transport *tr, int64_t b)
{
    uint64_t held = entered_by(tr, b) - tr->released;
    if (tr->mode == SIM_TRANSPORT_USB) {
        release_to(tr, tr->released + held);
        return;
    }
    if (held >= SIM_FTDI_PAYLOAD) { /* full packets */
        release_to(tr, tr->released + held / SIM_FTDI_PAYLOAD * SIM_FTDI_PAYLOAD);
        tr->last_pkt = b;
    } else if (b - tr->last_pkt >= tr->latency_ns) { /* the timer ran out */
        release_to(tr, tr->released + held);
        tr->last_pkt = b;
    }
}

void lep_priv_sim_transport_advance(sim_transport *tr, int64_t now)
{
    int64_t b_last;
    if (tr->mode == SIM_TRANSPORT_NONE || now < 0)
        return;
    b_last = now / F * F;
    if (tr->done_to == 0) {
        /* the first look: frames start with the first bytes (or now) */
        int64_t from = tr->len > 0 ? boundary_at_or_after(entry(tr, 0)->t) - F : b_last;
        tr->done_to = from < b_last ? from : b_last;
        tr->last_pkt = tr->done_to;
    }
    while (tr->done_to < b_last) {
        int64_t b = tr->done_to + F;
        if (tr->len == 0 || entry(tr, 0)->t > b) {
            /* nothing in the adapter until the boundary before its next
             * bytes: skip there; an FTDI chip's timer meanwhile sends the
             * status bytes alone every latency, each restarting it */
            int64_t to = b_last;
            if (tr->len > 0 && boundary_at_or_after(entry(tr, 0)->t) - F < to)
                to = boundary_at_or_after(entry(tr, 0)->t) - F;
            if (to < b)
                to = b;
            if (tr->mode == SIM_TRANSPORT_FTDI && to - tr->last_pkt >= tr->latency_ns)
                tr->last_pkt += (to - tr->last_pkt) / tr->latency_ns * tr->latency_ns;
            tr->done_to = to;
            continue;
        }
        frame(tr, b);
        tr->done_to = b;
    }
}

size_t lep_priv_sim_transport_ready(const sim_transport *tr)
{
    return (size_t)(tr->released - tr->written);
}

void lep_priv_sim_transport_written(sim_transport *tr, size_t n)
{
    tr->written += n;
    if (tr->written > tr->released) /* never more than was released */
        tr->written = tr->released;
}

int64_t lep_priv_sim_transport_next(const sim_transport *tr)
{
    int64_t first, next;
    size_t i;
    if (tr->mode == SIM_TRANSPORT_NONE || tr->len == 0)
        return 0;
    first = boundary_at_or_after(entry(tr, 0)->t);
    if (tr->done_to == 0)
        return first; /* not advanced yet: look then */
    if (first <= tr->done_to)
        first = tr->done_to + F;
    if (tr->mode == SIM_TRANSPORT_USB)
        return first;
    /* FTDI: the timer's first expiry at or after the first boundary with
     * bytes (those before it sent the status bytes alone) ... */
    next = tr->last_pkt +
           (first - tr->last_pkt + tr->latency_ns - 1) / tr->latency_ns * tr->latency_ns;
    /* ... or a full packet, when one fills before that */
    for (i = 0; i < tr->len; i++) {
        const sim_transport_entry *e = entry(tr, i);
        if (e->end - tr->released >= SIM_FTDI_PAYLOAD) {
            int64_t full = boundary_at_or_after(e->t);
            if (full <= tr->done_to)
                full = tr->done_to + F;
            if (full < next)
                next = full;
            break;
        }
    }
    return next;
}
