/* `leptrino info`: identity, rated values and filter of a sensor. */
#include "cli.h"

static void help(void)
{
    fputs("Usage: leptrino info PORT|--sim [options]\n"
          "\n"
          "Show the sensor's model, serial number, firmware, output rate (when the\n"
          "sensor reports it), protocol variant, rated values (N, N m), filter code\n"
          "and its label, and the latency settings applied to the port.\n"
          "\n"
          "Options:\n"
          "  -h, --help              show this help\n",
          stdout);
    cli_port_help(stdout);
    fputc('\n', stdout);
    cli_print_exit_codes(stdout);
}

int cli_cmd_info(int argc, char **argv)
{
    cli_args a;
    cli_port_opts po;
    cli_conn c;
    lep_rated rated;
    lep_serial_info si;
    uint8_t filter = 0;
    char text[4 * LEP_MODEL_LEN + 1];
    int rc, code;

    cli_args_init(&a, argc, argv, "info");
    cli_port_opts_init(&po);
    while (cli_args_next(&a)) {
        if (cli_args_is(&a, "-h", "--help")) {
            cli_args_flag(&a);
            if (a.failed)
                break;
            help();
            return CLI_OK;
        }
        if (cli_port_option(&po, &a))
            continue;
        if (a.positional && po.port == NULL) {
            po.port = a.cur;
            continue;
        }
        cli_args_unknown(&a);
    }
    if (a.failed || !cli_port_check(&po, &a))
        return CLI_USAGE;

    code = cli_conn_open(&c, &po, "info");
    if (code != CLI_OK)
        return code;
    rc = lep_client_rated(&c.client, &rated);
    if (rc != LEP_OK) {
        code = cli_conn_fail(&c, "rated values", rc);
        cli_conn_close(&c);
        return code;
    }
    /* Some sensors refuse the filter query (result 0x02) or do not answer
     * it: the rest of the information stands. */
    rc = lep_client_filter_get(&c.client, &filter);
    if (rc != LEP_OK && rc != LEP_E_SENSOR && rc != LEP_E_TIMEOUT && rc != LEP_E_NAK) {
        code = cli_conn_fail(&c, "filter query", rc);
        cli_conn_close(&c);
        return code;
    }
    lep_serial_get_info(c.serial, &si);

    printf("port:         %s%s\n", c.path, po.sim ? " (virtual sensor)" : "");
    /* Text from the sensor never reaches the terminal with a control byte. */
    cli_safe_text(c.info.model, text, sizeof text);
    printf("model:        %s\n", text);
    cli_safe_text(c.info.serial, text, sizeof text);
    printf("serial:       %s\n", text);
    cli_safe_text(c.info.firmware, text, sizeof text);
    printf("firmware:     %s\n", text);
    if (c.info.has_output_rate) {
        if (c.info.output_rate_hz != 0)
            printf("output rate:  %lu Hz\n", (unsigned long)c.info.output_rate_hz);
        else
        {
            cli_safe_text(c.info.output_rate, text, sizeof text);
            printf("output rate:  %s\n", text);
        }
        printf("protocol:     38-byte product info (with output rate)\n");
    } else {
        printf("output rate:  not reported\n");
        printf("protocol:     32-byte product info (v1.13)\n");
    }
    printf("rated:        Fx %g N, Fy %g N, Fz %g N, Mx %g N m, My %g N m, Mz %g N m\n",
           (double)rated.axis[LEP_FX], (double)rated.axis[LEP_FY], (double)rated.axis[LEP_FZ],
           (double)rated.axis[LEP_MX], (double)rated.axis[LEP_MY], (double)rated.axis[LEP_MZ]);
    if (rc == LEP_OK)
        printf("filter:       %u (%s)\n", (unsigned)filter, lep_filter_label(filter));
    else
        printf("filter:       not supported by this sensor\n");
    printf("latency:      low-latency flag %s", si.low_latency ? "set" : "not set");
    if (si.ftdi_latency_ms >= 0)
        printf(", FTDI latency timer %d ms%s", si.ftdi_latency_ms,
               si.ftdi_lowered ? " (lowered)" : "");
    printf("\n");
    cli_conn_close(&c);
    return CLI_OK;
}
