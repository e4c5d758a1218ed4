/* `leptrino list`: serial ports with their stable by-id names and USB ids. */
#include <stdlib.h>

#include "cli.h"

#define CLI_LIST_MAX 64

static void help(void)
{
    fputs("Usage: leptrino list [options]\n"
          "\n"
          "List the serial ports of this machine: device path, stable name under\n"
          "/dev/serial/by-id (use it as PORT: it survives re-plugging), USB VID:PID\n"
          "and description. '*' marks a likely sensor (STM virtual COM port 0483:5740,\n"
          "FTDI 0403:6001 for RS-422 units).\n"
          "\n"
          "Options:\n"
          "  -h, --help   show this help\n"
          "\n",
          stdout);
    cli_print_exit_codes(stdout);
}

int cli_cmd_list(int argc, char **argv)
{
    cli_args a;
    lep_port_info *ports;
    size_t n = 0, i, shown;
    bool any_likely = false;
    int rc;

    cli_args_init(&a, argc, argv, "list");
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return CLI_OK;
        }
        cli_args_unknown(&a);
    }
    if (a.failed)
        return CLI_USAGE;

    ports = calloc(CLI_LIST_MAX, sizeof *ports);
    if (ports == NULL) {
        fprintf(stderr, "leptrino: list: out of memory\n");
        return CLI_FAIL;
    }
    rc = lep_serial_list(ports, CLI_LIST_MAX, &n);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino: list: cannot list serial ports: %s\n", lep_strerror(rc));
        free(ports);
        return lep_exit_code(rc) == CLI_OK ? CLI_FAIL : lep_exit_code(rc);
    }
    if (n == 0) {
        printf("no serial ports found\n");
        free(ports);
        return CLI_OK;
    }
    shown = n < CLI_LIST_MAX ? n : CLI_LIST_MAX;
    printf("  %-20s %-9s %s\n", "PORT", "VID:PID", "DESCRIPTION / BY-ID");
    for (i = 0; i < shown; ++i) {
        const lep_port_info *p = &ports[i];
        char ids[16] = "-";
        if (p->vid != 0 || p->pid != 0)
            snprintf(ids, sizeof ids, "%04x:%04x", (unsigned)p->vid, (unsigned)p->pid);
        printf("%c %-20s %-9s %s\n", p->likely_sensor ? '*' : ' ', p->path, ids,
               p->description[0] != '\0' ? p->description : "-");
        any_likely = any_likely || p->likely_sensor;
        if (p->by_id[0] != '\0')
            printf("  %-20s %-9s %s\n", "", "", p->by_id);
    }
    if (n > shown)
        printf("(%lu more not shown)\n", (unsigned long)(n - shown));
    if (any_likely)
        printf("* likely a Leptrino sensor\n");
    free(ports);
    return CLI_OK;
}
