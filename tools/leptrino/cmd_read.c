/* `leptrino read`: N samples, one command each (handshake mode), written by
 * the same writer as `stream` (leptrino/output.h). */
#define _POSIX_C_SOURCE 200809L

#include <string.h>
#include <unistd.h>

#include "cli.h"

static void help(void)
{
    fputs("Usage: leptrino read PORT|--sim [-n N] [options]\n"
          "\n"
          "Ask the sensor for N samples, one command each (handshake mode), and print\n"
          "them as 'leptrino stream' does (metadata header, then t_s and the columns;\n"
          "t_s in s since the first request, forces in N, torques in N m).\n"
          "\n"
          "Options:\n"
          "  -n, --count N            number of samples (default 1)\n"
          "  -f, --format csv|jsonl   output format (default csv)\n"
          "  -u, --units si|raw       N and N m (default), or raw counts\n"
          "  -h, --help               show this help\n"
          "\n",
          stdout);
    cli_print_help_end(stdout, 1);
}

int cli_cmd_read(int argc, char **argv)
{
    static char meta[8192];
    cli_args a;
    cli_port_opts po;
    lep_session_options so;
    lep_output_options oo;
    lep_session *s;
    lep_output *w = NULL;
    uint64_t count = 1, i;
    int rc, code = CLI_OK, idx = 0;
    size_t meta_len = 0;
    const char *v;
    char err[512];

    cli_args_init(&a, argc, argv, "read");
    cli_port_opts_init(&po, false);
    lep_output_options_init(&oo);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return CLI_OK;
        } else if (cli_args_is(&a, "-n", "--count")) {
            count = cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, "-f", "--format")) {
            v = cli_args_value(&a);
            if (v != NULL && strcmp(v, "csv") == 0)
                oo.format = LEP_OUTPUT_CSV;
            else if (v != NULL && strcmp(v, "jsonl") == 0)
                oo.format = LEP_OUTPUT_JSONL;
            else if (v != NULL)
                cli_args_error(&a, "unknown format '%s' (csv or jsonl)", v);
        } else if (cli_args_is(&a, "-u", "--units")) {
            v = cli_args_value(&a);
            if (v != NULL && strcmp(v, "si") == 0)
                oo.columns = LEP_COL_SI | LEP_COL_STATUS;
            else if (v != NULL && strcmp(v, "raw") == 0)
                oo.columns = LEP_COL_RAW | LEP_COL_STATUS;
            else if (v != NULL)
                cli_args_error(&a, "unknown units '%s' (si or raw)", v);
        } else if (!cli_port_option(&po, &a)) {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(&po, &a))
        return CLI_USAGE;

    lep_session_options_init(&so);
    code = cli_sensors_open(&po, &so, "read");
    if (code != CLI_OK)
        return code;
    s = po.sensor[0].session;
    rc = lep_session_metadata_json(s, meta, sizeof meta, &meta_len);
    oo.t0_mono = lep_monotonic_seconds();
    err[0] = '\0';
    if (rc == LEP_OK)
        rc = lep_output_open_fd_opts(STDOUT_FILENO, &oo, &w, err, sizeof err);
    if (rc == LEP_OK)
        rc = idx = lep_output_add_sensor(w, po.sensor[0].name, meta, oo.t0_mono);
    if (rc < 0) {
        fprintf(stderr, "leptrino: read: %s\n", err[0] != '\0' ? err : lep_strerror(rc));
        lep_output_close(w);
        cli_sensors_close(&po);
        return CLI_FAIL;
    }
    for (i = 0; i < count && code == CLI_OK; ++i) {
        /* the session's units and processing: tare, rotation, shift */
        int16_t raw[LEP_AXES];
        double t, si[LEP_AXES];
        uint8_t status, flags;
        lep_session_batch b;
        memset(&b, 0, sizeof b);
        b.cap = 1;
        b.t_mono = &t;
        b.raw = raw;
        b.si = si;
        b.status = &status;
        b.flags = &flags;
        rc = lep_session_read_one_batch(s, &b);
        if (rc != LEP_OK) {
            lep_output_flush(w);
            code = cli_session_fail(s, "read", lep_session_port(s), "sample", rc);
            break;
        }
        if (lep_output_write_batch(w, idx, &b, 0, NULL, 0) != LEP_OK)
            break;
    }
    if (lep_output_close(w) != LEP_OK && code == CLI_OK) {
        fprintf(stderr, "leptrino: read: cannot write the output\n");
        code = CLI_FAIL;
    }
    cli_sensors_close(&po);
    return code;
}
