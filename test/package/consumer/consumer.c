/* A program outside the tree using the installed leptrino. */
#include <leptrino/leptrino.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv)
{
    static const uint8_t want[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    lep_command cmd = { LEP_CMD_PRODUCT_INFO, 0 };
    uint8_t frame[LEP_MAX_FRAME];
    size_t n = 0;
    if (argc < 2 || strcmp(argv[1], lep_version()) != 0 ||
        strcmp(LEP_VERSION_STRING, lep_version()) != 0) {
        fprintf(stderr, "consumer: version mismatch: header %s, library %s\n", LEP_VERSION_STRING,
                lep_version());
        return 1;
    }
    if (lep_command_frame(&cmd, frame, sizeof(frame), &n) != LEP_OK || n != sizeof(want) ||
        memcmp(frame, want, n) != 0) {
        fprintf(stderr, "consumer: wrong product-info frame\n");
        return 1;
    }
    printf("consumer: leptrino %s, product-info frame OK\n", lep_version());
    return 0;
}
