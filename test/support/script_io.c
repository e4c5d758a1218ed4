/* Scripted in-memory sensor for client tests (see script_io.h). */
#include "script_io.h"

#include <string.h>

#include "unity.h"

void script_io_init(script_io *s)
{
    lep_product_info info;
    lep_rated rated = { { 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 8.0f } };
    memset(s, 0, sizeof(*s));
    memset(&info, 0, sizeof(info));
    strcpy(info.model, "PFS055YA501U6");
    strcpy(info.serial, "12345678");
    strcpy(info.firmware, "1.13");
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_init(&s->dev, &info, &rated, 0));
    s->endless_stream = true;
}

void script_push(script_io *s, const uint8_t *data, size_t len)
{
    if (s->in_pos == s->in_len) {
        s->in_pos = s->in_len = 0;
    }
    TEST_ASSERT_TRUE_MESSAGE(s->in_len + len <= sizeof(s->in), "script input overflow");
    memcpy(s->in + s->in_len, data, len);
    s->in_len += len;
}

void script_push_msg(script_io *s, const uint8_t *msg, size_t len)
{
    uint8_t frame[LEP_MAX_FRAME];
    size_t n;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(msg, len, frame, sizeof(frame), &n));
    script_push(s, frame, n);
}

void script_push_data(script_io *s)
{
    lep_sample smp;
    uint8_t frame[LEP_MAX_FRAME];
    size_t n;
    memset(&smp, 0, sizeof(smp));
    smp.raw[LEP_FZ] = (int16_t)(s->seq % 100u);
    smp.reserved = s->seq++;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_stream_frame(&smp, frame, sizeof(frame), &n));
    script_push(s, frame, n);
}

size_t script_pending(const script_io *s)
{
    return s->in_len - s->in_pos;
}

static uint32_t script_now(void *user)
{
    script_io *s = user;
    s->now += s->tick;
    return s->now;
}

static int script_write(void *user, const uint8_t *data, size_t len)
{
    script_io *s = user;
    size_t pos = 0;
    if (s->write_error != 0) {
        return s->write_error;
    }
    s->writes++;
    TEST_ASSERT_TRUE_MESSAGE(s->out_len + len <= sizeof(s->out), "script output overflow");
    memcpy(s->out + s->out_len, data, len);
    s->out_len += len;
    if (s->lose_commands > 0) {
        s->lose_commands--;
        return 0;
    }
    while (pos < len && !s->silent) {
        lep_device_event ev;
        uint8_t reply[LEP_MAX_FRAME];
        size_t n = 0;
        bool was_streaming = lep_device_streaming(&s->dev);
        lep_device before = s->dev;
        unsigned i;
        pos += lep_device_feed(&s->dev, data + pos, len - pos, &ev, reply, sizeof(reply), &n);
        if (ev.type == LEP_DEVICE_NONE || ev.type == LEP_DEVICE_REJECTED) {
            continue;
        }
        if (ev.type == LEP_DEVICE_COMMAND && s->naks_left > 0) {
            static const uint8_t nak[2] = { LEP_DLE, LEP_NAK };
            s->naks_left--;
            s->dev = before; /* a NAKed command changes nothing */
            script_push(s, nak, sizeof(nak));
            continue;
        }
        if (was_streaming) {
            for (i = 0; i < s->inflight; i++) {
                script_push_data(s);
            }
        }
        s->commands++;
        if (s->lose_answers > 0) {
            s->lose_answers--;
        } else if (s->forced_len > 0) {
            script_push(s, s->forced, s->forced_len);
            s->forced_len = 0;
        } else {
            script_push(s, reply, n);
        }
    }
    return 0;
}

static int script_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    script_io *s = user;
    size_t n;
    s->reads++;
    s->last_timeout = timeout_ms;
    if (s->reads > SCRIPT_MAX_READS) {
        return LEP_E_IO; /* the client never stopped reading: fail instead of hanging */
    }
    if (s->read_error != 0) {
        return s->read_error;
    }
    if (script_pending(s) == 0 && s->stall_reads > 0) {
        s->stall_reads--;
    } else if (script_pending(s) == 0 && s->noise) {
        uint8_t junk[64];
        memset(junk, 0x55, sizeof(junk));
        s->now += 1;
        script_push(s, junk, sizeof(junk));
    } else if (script_pending(s) == 0 && s->endless_stream && lep_device_streaming(&s->dev)) {
        s->now += 1;
        script_push_data(s);
    }
    if (script_pending(s) == 0) {
        s->now += (uint32_t)(timeout_ms < 0 ? 1000 : timeout_ms);
        return 0;
    }
    n = script_pending(s);
    if (n > cap) {
        n = cap;
    }
    if (s->max_chunk > 0 && n > s->max_chunk) {
        n = s->max_chunk;
    }
    memcpy(buf, s->in + s->in_pos, n);
    s->in_pos += n;
    s->total_read += n;
    return (int)n + s->overclaim;
}

lep_io script_io_table(script_io *s)
{
    lep_io io;
    io.write = script_write;
    io.read = script_read;
    io.now_ms = script_now;
    io.user = s;
    return io;
}

size_t script_take_data(script_io *s, unsigned n, uint8_t *wire, size_t cap)
{
    size_t len;
    s->endless_stream = false;
    while (n-- > 0u) {
        script_push_data(s);
    }
    len = script_pending(s);
    TEST_ASSERT_TRUE(len <= cap);
    memcpy(wire, s->in + s->in_pos, len);
    return len;
}

void script_io_client(script_io *s, lep_client *c)
{
    lep_io io;
    script_io_init(s);
    io = script_io_table(s);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(c, &io));
}
