/* Fuzz target: the sensor side fed arbitrary bytes, in chunks the input
 * chooses. Invariants: feed always makes progress; every answer is a frame
 * that the host side decodes to a well-formed response for the command
 * answered (or a DLE NAK); the device's streaming state follows start/stop;
 * streaming data frames stay valid. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "leptrino/leptrino.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void answer_is_valid(const lep_device_event *ev, const uint8_t *out, size_t len)
{
    lep_frame_decoder dec;
    lep_frame_event fev;
    lep_response r;
    size_t used;
    int rc;
    lep_frame_decoder_init(&dec);
    used = lep_frame_decoder_feed(&dec, out, len, &fev);
    check(used == len);
    if (ev->type == LEP_DEVICE_NAK) {
        check(fev.type == LEP_FRAME_NAK);
        return;
    }
    check(fev.type == LEP_FRAME_MESSAGE);
    rc = lep_response_decode(fev.msg, fev.len, &r);
    check(r.code == ev->code && r.result == ev->result);
    check(
        rc == (ev->result == LEP_RESULT_OK ? LEP_OK : LEP_E_SENSOR) ||
        (ev->result != LEP_RESULT_OK && rc == LEP_E_UNEXPECTED)); /* unknown codes answered 0x02 */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lep_device dev;
    lep_product_info info;
    lep_rated rated = { { 500.0f, 500.0f, 1000.0f, 40.0f, 40.0f, 30.0f } };
    lep_sample s;
    size_t pos = 0;
    unsigned k = 0;
    memset(&info, 0, sizeof(info));
    strcpy(info.model, "PFS080YS102U6");
    strcpy(info.serial, "0001234");
    strcpy(info.firmware, "1.31");
    strcpy(info.output_rate, "1200");
    info.has_output_rate = true;
    check(lep_device_init(&dev, &info, &rated, 1) == LEP_OK);
    memset(&s, 0, sizeof(s));
    while (pos < size) {
        uint8_t out[LEP_MAX_FRAME];
        size_t out_len = 99;
        lep_device_event ev;
        size_t chunk = 1u + (size_t)(data[pos] % 40u);
        size_t used;
        bool was = lep_device_streaming(&dev);
        if (chunk > size - pos) {
            chunk = size - pos;
        }
        /* A small output buffer now and then: the answer is dropped, never overrun. */
        used = lep_device_feed(&dev, data + pos, chunk, &ev, out,
                               (k % 17u == 3u) ? 5u : sizeof(out), &out_len);
        check(used >= 1 && used <= chunk);
        pos += used;
        k++;
        if (ev.type == LEP_DEVICE_COMMAND || ev.type == LEP_DEVICE_NAK) {
            if (out_len > 0) {
                answer_is_valid(&ev, out, out_len);
            }
        } else {
            check(out_len == 0);
        }
        if (ev.type == LEP_DEVICE_COMMAND && ev.result == LEP_RESULT_OK) {
            if (ev.code == LEP_CMD_START) {
                check(lep_device_streaming(&dev));
            } else if (ev.code == LEP_CMD_STOP) {
                check(!lep_device_streaming(&dev));
            }
        } else {
            check(lep_device_streaming(&dev) == was);
        }
        check(lep_device_filter(&dev) <= LEP_FILTER_MAX &&
              lep_device_filter_pending(&dev) <= LEP_FILTER_MAX);
        if (lep_device_streaming(&dev)) {
            size_t n;
            s.raw[k % LEP_AXES] = (int16_t)((int)(data[pos - 1] * 250u) - 32000); /* up to 31750 */
            s.reserved = (uint16_t)k;
            check(lep_device_stream_frame(&s, out, sizeof(out), &n) == LEP_OK);
        }
        if (k % 97u == 0u) {
            lep_device_power_cycle(&dev);
            check(!lep_device_streaming(&dev));
        }
    }
    return 0;
}
