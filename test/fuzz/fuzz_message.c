/* Fuzz target: the message codec on exact-size copies of the input (so
 * AddressSanitizer sees any read past the message), both directions.
 * Invariants: a response that decodes has a canonical form (space padding,
 * last reserved byte 0) that decodes to the same fields and re-encodes to
 * itself; decoded text is printable ASCII; |raw| <= 32000; a command that
 * decodes re-encodes to the same bytes. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "leptrino/leptrino.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_text(const char *s, size_t cap)
{
    size_t i;
    for (i = 0; i < cap && s[i] != '\0'; i++) {
        check((unsigned char)s[i] >= 0x20u && (unsigned char)s[i] <= 0x7Eu);
    }
    check(i < cap);
    check(i == 0 || s[i - 1] != ' '); /* padding removed */
}

/* The fields of two decoded responses are the same (canonical comparison). */
static void same_fields(const lep_response *a, const lep_response *b)
{
    check(a->code == b->code && a->result == b->result && a->stream == b->stream);
    if (a->result != LEP_RESULT_OK) {
        return;
    }
    switch (a->code) {
    case LEP_CMD_PRODUCT_INFO:
        check(strcmp(a->u.info.model, b->u.info.model) == 0);
        check(strcmp(a->u.info.serial, b->u.info.serial) == 0);
        check(strcmp(a->u.info.firmware, b->u.info.firmware) == 0);
        check(strcmp(a->u.info.output_rate, b->u.info.output_rate) == 0);
        check(a->u.info.has_output_rate == b->u.info.has_output_rate);
        check(a->u.info.output_rate_hz == b->u.info.output_rate_hz);
        break;
    case LEP_CMD_RATED:
        check(memcmp(&a->u.rated, &b->u.rated, sizeof(a->u.rated)) == 0);
        break;
    case LEP_CMD_FILTER_GET:
        check(a->u.filter == b->u.filter);
        break;
    case LEP_CMD_SAMPLE:
    case LEP_CMD_START:
        check(memcmp(a->u.sample.raw, b->u.sample.raw, sizeof(a->u.sample.raw)) == 0);
        check(a->u.sample.reserved == b->u.sample.reserved &&
              a->u.sample.status == b->u.sample.status);
        break;
    default:
        break;
    }
}

static void response(const uint8_t *msg, size_t len)
{
    lep_response r;
    lep_response r2;
    uint8_t canon[LEP_MAX_MESSAGE];
    uint8_t again[LEP_MAX_MESSAGE];
    uint8_t frame[LEP_MAX_FRAME];
    size_t n;
    size_t n2;
    size_t i;
    int rc = lep_response_decode(msg, len, &r);
    if (rc != LEP_OK) {
        return;
    }
    if (r.code == LEP_CMD_PRODUCT_INFO) {
        check_text(r.u.info.model, sizeof(r.u.info.model));
        check_text(r.u.info.serial, sizeof(r.u.info.serial));
        check_text(r.u.info.firmware, sizeof(r.u.info.firmware));
        check_text(r.u.info.output_rate, sizeof(r.u.info.output_rate));
    }
    if (r.code == LEP_CMD_SAMPLE || r.stream) {
        for (i = 0; i < LEP_AXES; i++) {
            check(r.u.sample.raw[i] >= -32000 && r.u.sample.raw[i] <= 32000);
        }
    }
    check(lep_response_encode(&r, canon, sizeof(canon), &n) == LEP_OK);
    check(n == len);
    check(lep_response_encode(&r, canon, n - 1u, &n2) == LEP_E_BUFFER);
    check(lep_response_decode(canon, n, &r2) == LEP_OK);
    same_fields(&r, &r2);
    check(lep_response_encode(&r2, again, sizeof(again), &n2) == LEP_OK);
    check(n2 == n && memcmp(canon, again, n) == 0);
    check(lep_response_frame(&r, frame, sizeof(frame), &n2) == LEP_OK);
    check(n2 == lep_frame_size(canon, n));
}

static void command(const uint8_t *msg, size_t len)
{
    lep_command cmd;
    uint8_t result = 0xEE;
    uint8_t again[LEP_LEN_FILTER_SET_CMD];
    size_t n;
    int rc = lep_command_decode(msg, len, &cmd, &result);
    if (rc != LEP_OK) {
        check(result >= LEP_RESULT_LENGTH && result <= LEP_RESULT_VALUE);
        return;
    }
    check(result == LEP_RESULT_OK);
    check(lep_command_encode(&cmd, again, sizeof(again), &n) == LEP_OK);
    check(n == len && memcmp(again, msg, n) == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* The input is a sequence of messages, each prefixed with its length. */
    size_t pos = 0;
    while (pos < size) {
        size_t len = data[pos++] % (LEP_MAX_MESSAGE + 1u);
        uint8_t *copy;
        if (len > size - pos) {
            len = size - pos;
        }
        copy = malloc(len > 0 ? len : 1u);
        check(copy != NULL);
        memcpy(copy, data + pos, len);
        response(copy, len);
        command(copy, len);
        free(copy);
        pos += len;
    }
    return 0;
}
