/* `leptrino read`: N samples, one command each (handshake mode). */
#include <string.h>

#include "cli.h"

static void help(void)
{
    fputs("Usage: leptrino read PORT|--sim [-n N] [options]\n"
          "\n"
          "Ask the sensor for N samples, one command each (handshake mode), and print\n"
          "them in the same columns as 'leptrino stream': t,fx,fy,fz,mx,my,mz,status\n"
          "(t in s since the first request, forces in N, torques in N m).\n"
          "\n"
          "Options:\n"
          "  -n, --count N           number of samples (default 1)\n"
          "  -f, --format csv|jsonl  output format (default csv)\n"
          "  -u, --units si|raw      N and N m (default), or raw counts\n"
          "  -h, --help              show this help\n",
          stdout);
    cli_port_help(stdout);
    fputc('\n', stdout);
    cli_print_exit_codes(stdout);
}

int cli_cmd_read(int argc, char **argv)
{
    cli_args a;
    cli_port_opts po;
    cli_conn c;
    cli_writer w;
    uint64_t count = 1, i;
    double t0 = 0.0;
    int rc, code = CLI_OK;
    const char *v;

    cli_args_init(&a, argc, argv, "read");
    cli_port_opts_init(&po);
    memset(&w, 0, sizeof w);
    w.f = stdout;
    w.format = CLI_FORMAT_CSV;
    w.si = true;
    while (cli_args_next(&a)) {
        if (cli_args_is(&a, "-h", "--help")) {
            cli_args_flag(&a);
            if (a.failed)
                break;
            help();
            return CLI_OK;
        } else if (cli_args_is(&a, "-n", "--count")) {
            count = cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, "-f", "--format")) {
            v = cli_args_value(&a);
            if (v != NULL && !cli_parse_format(v, &w.format))
                cli_args_error(&a, "unknown format '%s' (csv or jsonl)", v);
        } else if (cli_args_is(&a, "-u", "--units")) {
            v = cli_args_value(&a);
            if (v != NULL && !cli_parse_units(v, &w.si))
                cli_args_error(&a, "unknown units '%s' (si or raw)", v);
        } else if (cli_port_option(&po, &a)) {
        } else if (a.positional && po.port == NULL) {
            po.port = a.cur;
        } else {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(&po, &a))
        return CLI_USAGE;

    code = cli_conn_open(&c, &po, "read");
    if (code != CLI_OK)
        return code;
    rc = lep_client_rated(&c.client, &w.rated);
    if (rc != LEP_OK) {
        code = cli_conn_fail(&c, "rated values", rc);
        cli_conn_close(&c);
        return code;
    }
    cli_write_header(&w);
    for (i = 0; i < count; ++i) {
        lep_sample s;
        double t;
        if (i == 0)
            t0 = lep_monotonic_seconds();
        rc = lep_client_sample(&c.client, &s);
        t = lep_monotonic_seconds() - t0;
        if (rc != LEP_OK) {
            fflush(stdout);
            code = cli_conn_fail(&c, "sample", rc);
            break;
        }
        cli_write_sample(&w, t, &s);
    }
    if (fflush(stdout) != 0 && code == CLI_OK) {
        fprintf(stderr, "leptrino: read: cannot write the output\n");
        code = CLI_FAIL;
    }
    cli_conn_close(&c);
    return code;
}
