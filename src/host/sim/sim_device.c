/* Virtual sensor: the device side of the core fed with the commands that
 * reach it (the input's NAK fault may withhold one), its answers sent through
 * the faults, the start of a stream, power cycles, and the device set up from
 * the options. Called by the serving thread and the API; calls the faults,
 * the pty's queue and the trace. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <stdio.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "sim_priv.h"

/* The stream starts now: sample deadlines count from here. */
static void stream_begins(lep_sim *s, int64_t now)
{
    s->streaming = true;
    s->t0 = now;
    s->k = 0;
    lep_priv_sim_trace_mark(s->trace, LEP_SIM_TRACE_START, now);
}

static void check_streaming(lep_sim *s)
{
    bool on = lep_device_streaming(&s->dev);
    if (on && !s->streaming)
        stream_begins(s, lep_priv_monotonic_ns());
    s->streaming = on;
}

/* Feed bytes to the device and send what it answers. */
static void feed_device(lep_sim *s, const uint8_t *p, size_t len)
{
    while (len > 0) {
        lep_device_event ev;
        uint8_t ans[LEP_MAX_FRAME];
        size_t ans_len = 0;
        size_t used = lep_device_feed(&s->dev, p, len, &ev, ans, sizeof ans, &ans_len);
        if (used == 0)
            used = len; /* never spin */
        p += used;
        len -= used;
        if (ev.type == LEP_DEVICE_COMMAND) {
            s->st.commands++;
            if (ans_len > 0)
                lep_priv_sim_emit(s, ans, ans_len, false, 0);
            check_streaming(s);
        } else if (ev.type == LEP_DEVICE_NAK) {
            lep_priv_sim_send_nak(s);
        }
    }
}

static void handshake_sample(lep_sim *s)
{
    lep_sample smp;
    int64_t since = lep_priv_monotonic_ns() - s->power_on;
    uint64_t n = since > 0 ? (uint64_t)((double)since / s->period_ns) : 0u;
    lep_priv_fir_sample(&s->fir[lep_device_filter(&s->dev)], &s->sig, n, &smp);
    lep_device_set_sample(&s->dev, &smp);
}

static void flush_pend(lep_sim *s)
{
    if (s->pend_len > 0)
        feed_device(s, s->pend, s->pend_len);
    s->pend_len = 0;
}

void lep_priv_sim_handle_input(lep_sim *s, const uint8_t *p, size_t len)
{
    while (len > 0) {
        lep_frame_event ev;
        size_t used = lep_frame_decoder_feed(&s->shadow, p, len, &ev);
        if (s->pend_len + used > PEND_SIZE)
            flush_pend(s);
        if (used > PEND_SIZE) { /* cannot happen: frames are bounded */
            feed_device(s, p, used);
        } else {
            memcpy(s->pend + s->pend_len, p, used);
            s->pend_len += used;
        }
        p += used;
        len -= used;
        if (ev.type == LEP_FRAME_MESSAGE) {
            if (ev.len >= 3 && ev.msg[2] == LEP_CMD_SAMPLE)
                handshake_sample(s);
            if (lep_priv_sim_nak_fault(s))
                s->pend_len = 0; /* the device never sees it */
            else
                flush_pend(s);
        } else if (ev.type != LEP_FRAME_NONE || !lep_frame_decoder_busy(&s->shadow)) {
            flush_pend(s);
        }
    }
}

void lep_priv_sim_power_off(lep_sim *s)
{
    lep_device_power_cycle(&s->dev);
    lep_frame_decoder_init(&s->shadow);
    s->pend_len = 0;
    s->streaming = false;
    lep_priv_sim_queue_clear(s); /* bytes in flight die with the power */
    lep_priv_sim_trace_discard(s->trace);
}

void lep_priv_sim_power_cycle(lep_sim *s)
{
    lep_priv_sim_power_off(s);
    s->power_on = lep_priv_monotonic_ns();
    s->st.power_cycles++;
}

static void copy_field(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

int lep_priv_sim_init_device(lep_sim *s, char *err, size_t errlen)
{
    const lep_sim_options *o = &s->opt;
    int rc;
    memset(&s->info, 0, sizeof s->info);
    copy_field(s->info.model, sizeof s->info.model, o->model);
    copy_field(s->info.serial, sizeof s->info.serial, o->serial);
    copy_field(s->info.firmware, sizeof s->info.firmware, o->firmware);
    if (o->output_rate_field) {
        s->info.has_output_rate = true;
        s->info.output_rate_hz = (uint32_t)(o->rate_hz + 0.5);
        snprintf(s->info.output_rate, sizeof s->info.output_rate, "%u",
                 (unsigned)s->info.output_rate_hz);
    }
    rc = lep_device_init(&s->dev, &s->info, &s->rated, o->filter);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "cannot set up the device: %s", lep_strerror(rc));
        return rc;
    }
    if (o->start_streaming) {
        /* A stream left running by an earlier program: start it ourselves. */
        static const lep_command start = { LEP_CMD_START, 0 };
        uint8_t frame[LEP_MAX_FRAME], ans[LEP_MAX_FRAME];
        size_t len = 0, ans_len = 0, off = 0;
        lep_device_event ev;
        if (lep_command_frame(&start, frame, sizeof frame, &len) == LEP_OK) {
            while (off < len)
                off += lep_device_feed(&s->dev, frame + off, len - off, &ev, ans, sizeof ans,
                                       &ans_len);
        }
        if (lep_device_streaming(&s->dev))
            stream_begins(s, lep_priv_monotonic_ns());
    }
    return LEP_OK;
}
