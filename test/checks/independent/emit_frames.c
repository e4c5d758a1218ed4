/* Print the wire bytes libleptrino produces for every command and a set of
 * responses, one frame per line: "<name>\t<hex>". check_frames.py decodes
 * them with its own implementation of the spec and compares the contents. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "leptrino/device.h"
#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "leptrino/message.h"

static int failures;

static void emit(const char *name, int rc, const uint8_t *wire, size_t len)
{
    size_t i;
    if (rc != LEP_OK) {
        fprintf(stderr, "%s: %s\n", name, lep_strerror(rc));
        failures++;
        return;
    }
    printf("%s\t", name);
    for (i = 0; i < len; i++) {
        printf(i == 0 ? "%02X" : " %02X", (unsigned)wire[i]);
    }
    printf("\n");
}

static void command(const char *name, uint8_t code, uint8_t filter)
{
    lep_command c;
    uint8_t wire[LEP_MAX_FRAME];
    size_t n = 0;
    c.code = code;
    c.filter = filter;
    int rc = lep_command_frame(&c, wire, sizeof(wire), &n);
    emit(name, rc, wire, n);
}

static void response(const char *name, const lep_response *r)
{
    uint8_t wire[LEP_MAX_FRAME];
    size_t n = 0;
    int rc = lep_response_frame(r, wire, sizeof(wire), &n);
    emit(name, rc, wire, n);
}

static void sample(const char *name, uint8_t code, bool stream, const int16_t raw[LEP_AXES],
                   uint16_t reserved, uint8_t status)
{
    lep_response r;
    memset(&r, 0, sizeof(r));
    r.code = code;
    r.stream = stream;
    memcpy(r.u.sample.raw, raw, sizeof(r.u.sample.raw));
    r.u.sample.reserved = reserved;
    r.u.sample.status = status;
    response(name, &r);
}

static void info(const char *name, const char *model, const char *serial, const char *fw,
                 const char *rate)
{
    lep_response r;
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_PRODUCT_INFO;
    strcpy(r.u.info.model, model);
    strcpy(r.u.info.serial, serial);
    strcpy(r.u.info.firmware, fw);
    if (rate != NULL) {
        strcpy(r.u.info.output_rate, rate);
        r.u.info.has_output_rate = true;
    }
    response(name, &r);
}

static void rated(const char *name, const float v[LEP_AXES])
{
    lep_response r;
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_RATED;
    memcpy(r.u.rated.axis, v, sizeof(r.u.rated.axis));
    response(name, &r);
}

static void simple(const char *name, uint8_t code, uint8_t result)
{
    lep_response r;
    memset(&r, 0, sizeof(r));
    r.code = code;
    r.result = result;
    response(name, &r);
}

int main(void)
{
    static const int16_t spec_raw[LEP_AXES] = { 16, -16, 10000, -10000, 4112, 32000 };
    static const int16_t dle_raw[LEP_AXES] = { 0x1010, 0x1010, 0x1010, 0x1010, 0x1010, 0x1010 };
    static const int16_t bcc10_raw[LEP_AXES] = { 201, 1, 2, 3, 4, 5 };
    static const int16_t ctl_raw[LEP_AXES] = { 0x0210, 0x0310, 0x1510, 0x1010, 0, 0 };
    static const int16_t ext_raw[LEP_AXES] = { 32000, -32000, -1, 1, 15000, -15000 };
    static const float pfs055[LEP_AXES] = { 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 8.0f };
    static const float cfs018[LEP_AXES] = { 100.0f, 100.0f, 200.0f, 1.0f, 1.0f, 1.0f };
    static const float fractions[LEP_AXES] = { 0.5f, 2.25f, 1234.5f, 0.125f, 3.75f, 1e-3f };
    lep_sample s;
    uint8_t wire[LEP_MAX_FRAME];
    size_t n = 0;
    int rc;
    uint8_t f;

    command("cmd_product_info", LEP_CMD_PRODUCT_INFO, 0);
    command("cmd_rated", LEP_CMD_RATED, 0);
    command("cmd_filter_get", LEP_CMD_FILTER_GET, 0);
    command("cmd_sample", LEP_CMD_SAMPLE, 0);
    command("cmd_start", LEP_CMD_START, 0);
    command("cmd_stop", LEP_CMD_STOP, 0);
    for (f = 0; f <= LEP_FILTER_MAX; f++) {
        char name[32];
        snprintf(name, sizeof(name), "cmd_filter_set_%u", (unsigned)f);
        command(name, LEP_CMD_FILTER_SET, f);
    }

    info("rsp_info_32", "PFS055YA501U6", "12345678", "1.13", NULL);
    info("rsp_info_38", "PFS080YS102U6", "00012345", "1.31", "1200");
    rated("rsp_rated_pfs055", pfs055);
    rated("rsp_rated_cfs018", cfs018);
    rated("rsp_rated_fractions", fractions);
    for (f = 0; f <= LEP_FILTER_MAX; f++) {
        lep_response r;
        char name[32];
        memset(&r, 0, sizeof(r));
        r.code = LEP_CMD_FILTER_GET;
        r.u.filter = f;
        snprintf(name, sizeof(name), "rsp_filter_%u", (unsigned)f);
        response(name, &r);
    }
    sample("rsp_sample_spec", LEP_CMD_SAMPLE, false, spec_raw, 0, LEP_STATUS_OVERLOAD);
    sample("rsp_sample_dle", LEP_CMD_SAMPLE, false, dle_raw, 0x1010, 0x10);
    sample("rsp_sample_bcc10", LEP_CMD_SAMPLE, false, bcc10_raw, 0, 0);
    sample("rsp_sample_ctl", LEP_CMD_SAMPLE, false, ctl_raw, 0, 0);
    sample("rsp_stream_ext", LEP_CMD_START, true, ext_raw, 0xBEEF, 0x07);
    simple("rsp_start_ack", LEP_CMD_START, LEP_RESULT_OK);
    simple("rsp_stop_ack", LEP_CMD_STOP, LEP_RESULT_OK);
    simple("rsp_filter_set_ack", LEP_CMD_FILTER_SET, LEP_RESULT_OK);
    simple("rsp_result_1", LEP_CMD_PRODUCT_INFO, LEP_RESULT_LENGTH);
    simple("rsp_result_2", LEP_CMD_RATED, LEP_RESULT_UNDEFINED);
    simple("rsp_result_3", LEP_CMD_FILTER_SET, LEP_RESULT_VALUE);
    simple("rsp_result_4", LEP_CMD_START, LEP_RESULT_STATE);

    /* The sensor side's continuous-output frame. */
    memset(&s, 0, sizeof(s));
    memcpy(s.raw, spec_raw, sizeof(s.raw));
    s.reserved = 7;
    rc = lep_device_stream_frame(&s, wire, sizeof(wire), &n);
    emit("dev_stream_spec", rc, wire, n);

    return failures == 0 ? 0 : 1;
}
