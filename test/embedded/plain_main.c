/* Built by plain_build.sh with nothing but a C compiler and the tree (no
 * CMake, no generated header): the version is the one CMake was given, and a
 * query answered by the sensor side goes through the host side's step API. */
#include <stdio.h>
#include <string.h>

#include "leptrino/leptrino.h"

static uint8_t wire[LEP_MAX_FRAME];
static size_t wire_len;

static int capture(void *user, const uint8_t *data, size_t len)
{
    (void)user;
    if (len > sizeof wire) {
        return LEP_E_BUFFER;
    }
    memcpy(wire, data, len);
    wire_len = len;
    return LEP_OK;
}

static uint32_t clock_ms(void *user)
{
    (void)user;
    return 0u;
}

int main(int argc, char **argv)
{
    static lep_client client;
    static lep_device device;
    lep_product_info info;
    lep_rated rated = { { 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 8.0f } };
    lep_io io = { capture, NULL, clock_ms, NULL };
    lep_command cmd = { LEP_CMD_PRODUCT_INFO, 0 };
    lep_device_event ev;
    uint8_t answer[LEP_MAX_FRAME];
    size_t answer_len = 0, used = 0, pos = 0;
    lep_client_stats stats;
    int rc = LEP_STEP_NONE;

    if (argc != 2 || strcmp(argv[1], lep_version()) != 0 ||
        strcmp(LEP_VERSION_STRING, lep_version()) != 0) {
        fprintf(stderr, "version: header %s, library %s, expected %s\n", LEP_VERSION_STRING,
                lep_version(), argc > 1 ? argv[1] : "?");
        return 1;
    }
    memset(&info, 0, sizeof info);
    strcpy(info.model, "PFS055YA501U6");
    strcpy(info.serial, "12345678");
    strcpy(info.firmware, "1.13");
    if (lep_device_init(&device, &info, &rated, 0) != LEP_OK ||
        lep_client_init(&client, &io) != LEP_OK || lep_client_send(&client, &cmd) != LEP_OK) {
        fprintf(stderr, "init/send failed\n");
        return 1;
    }
    while (pos < wire_len) {
        pos += lep_device_feed(&device, wire + pos, wire_len - pos, &ev, answer, sizeof answer,
                               &answer_len);
    }
    for (pos = 0; pos < answer_len && rc == LEP_STEP_NONE; pos += used) {
        rc = lep_client_step(&client, answer + pos, answer_len - pos, &used);
    }
    lep_client_get_stats(&client, &stats);
    if (rc != LEP_STEP_RESPONSE || stats.messages != 1u || stats.bytes_discarded != 0u) {
        fprintf(stderr, "the query was not answered (%d)\n", rc);
        return 1;
    }
    printf("leptrino %s built without CMake: product info answered\n", lep_version());
    return 0;
}
