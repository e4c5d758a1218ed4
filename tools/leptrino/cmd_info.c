/* `leptrino info`: identity, rated values and filter of a sensor, as the
 * session read them at start-up, and the port's latency settings. */
#include "cli.h"

static void help(void)
{
    fputs("Usage: leptrino info PORT|--sim [options]\n"
          "\n"
          "Show the sensor's model, serial number, firmware, output rate (when the\n"
          "sensor reports it), protocol variant, rated values (N, N m), filter code\n"
          "with its label, and the latency settings applied to the port (low-latency\n"
          "flag; FTDI latency timer on FTDI adapters). A sensor that refuses the filter query (or "
          "does not\n"
          "answer it) shows \"filter: not supported by this sensor\"; the rest stands.\n"
          "Text from the sensor is printed with any control or non-ASCII byte\n"
          "escaped as \\xNN.\n"
          "\n"
          "Options:\n"
          "  -h, --help               show this help\n"
          "\n",
          stdout);
    cli_print_help_end(stdout, 1);
}

/* "key:          value" with the sensor's text escaped. */
static void field(const char *key, const char *sensor_text)
{
    char text[4 * 64 + 1];
    cli_safe_text(sensor_text, text, sizeof text);
    printf("%-14s%s\n", key, text);
}

int cli_cmd_info(int argc, char **argv)
{
    cli_args a;
    cli_port_opts po;
    lep_session_options so;
    static lep_session_meta m;
    lep_serial_info si;
    int code;

    cli_args_init(&a, argc, argv, "info");
    cli_port_opts_init(&po, false);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return CLI_OK;
        }
        if (!cli_port_option(&po, &a))
            cli_args_unknown(&a);
    }
    if (a.failed || !cli_port_check(&po, &a))
        return CLI_USAGE;

    lep_session_options_init(&so);
    code = cli_sensors_open(&po, &so, "info");
    if (code != CLI_OK)
        return code;
    lep_session_get_metadata(po.sensor[0].session, &m);

    printf("%-14s%s%s\n", "port:", m.port, m.sim ? " (virtual sensor)" : "");
    field("model:", m.info.model);
    field("serial:", m.info.serial);
    field("firmware:", m.info.firmware);
    if (m.info.has_output_rate) {
        if (m.info.output_rate_hz != 0)
            printf("%-14s%lu Hz\n", "output rate:", (unsigned long)m.info.output_rate_hz);
        else
            field("output rate:", m.info.output_rate);
    } else {
        printf("%-14s%s\n", "output rate:", "not reported");
    }
    field("protocol:", m.protocol);
    printf("%-14sFx %g N, Fy %g N, Fz %g N, Mx %g N m, My %g N m, Mz %g N m\n",
           "rated:", (double)m.rated.axis[LEP_FX], (double)m.rated.axis[LEP_FY],
           (double)m.rated.axis[LEP_FZ], (double)m.rated.axis[LEP_MX], (double)m.rated.axis[LEP_MY],
           (double)m.rated.axis[LEP_MZ]);
    if (m.sensor_filter >= 0)
        printf("%-14s%d (%s)\n", "filter:", m.sensor_filter, m.sensor_filter_label);
    else
        printf("%-14s%s\n", "filter:", "not supported by this sensor");
    if (lep_session_get_serial_info(po.sensor[0].session, &si) == LEP_OK) {
        printf("%-14slow-latency flag %s", "latency:", si.low_latency ? "set" : "not set");
        if (si.ftdi_latency_ms >= 0)
            printf(", FTDI latency timer %d ms%s", si.ftdi_latency_ms,
                   si.ftdi_lowered ? " (lowered)" : "");
        printf("\n");
    }
    cli_sensors_close(&po);
    return CLI_OK;
}
