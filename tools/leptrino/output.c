/* Sample output of the leptrino tool: CSV (header t,fx,fy,fz,mx,my,mz,status)
 * or JSON lines, in SI units (N, N m) or raw counts, with optional tare. */
#include <math.h>
#include <string.h>

#include "cli.h"

static const char *const AXIS_NAMES[LEP_AXES] = {"fx", "fy", "fz", "mx", "my", "mz"};

bool cli_parse_format(const char *s, cli_format *out)
{
    if (strcmp(s, "csv") == 0)
        *out = CLI_FORMAT_CSV;
    else if (strcmp(s, "jsonl") == 0)
        *out = CLI_FORMAT_JSONL;
    else
        return false;
    return true;
}

bool cli_parse_units(const char *s, bool *si)
{
    if (strcmp(s, "si") == 0)
        *si = true;
    else if (strcmp(s, "raw") == 0)
        *si = false;
    else
        return false;
    return true;
}

void cli_write_header(cli_writer *w)
{
    if (w->format == CLI_FORMAT_CSV)
        fputs("t,fx,fy,fz,mx,my,mz,status\n", w->f);
}

/* Values of one sample in the chosen units, tare applied. */
static void values(const cli_writer *w, const lep_sample *s, double v[LEP_AXES], long r[LEP_AXES])
{
    int i;
    for (i = 0; i < LEP_AXES; ++i) {
        double raw = (double)s->raw[i] - (w->tared ? w->offset[i] : 0.0);
        if (w->si)
            v[i] = raw * (double)w->rated.axis[i] / (double)LEP_RAW_FULL_SCALE;
        else
            r[i] = lround(raw);
    }
}

void cli_write_sample(cli_writer *w, double t, const lep_sample *s)
{
    double v[LEP_AXES];
    long r[LEP_AXES];
    int i;

    values(w, s, v, r);
    if (w->format == CLI_FORMAT_CSV) {
        fprintf(w->f, "%.6f", t);
        for (i = 0; i < LEP_AXES; ++i) {
            if (w->si)
                fprintf(w->f, ",%.6f", v[i]);
            else
                fprintf(w->f, ",%ld", r[i]);
        }
        fprintf(w->f, ",%u\n", (unsigned)s->status);
    } else {
        fprintf(w->f, "{\"t\":%.6f", t);
        for (i = 0; i < LEP_AXES; ++i) {
            if (w->si)
                fprintf(w->f, ",\"%s\":%.6f", AXIS_NAMES[i], v[i]);
            else
                fprintf(w->f, ",\"%s\":%ld", AXIS_NAMES[i], r[i]);
        }
        fprintf(w->f, ",\"status\":%u}\n", (unsigned)s->status);
    }
}

void cli_write_gap(cli_writer *w, double from, double to, const char *reason)
{
    if (w->format == CLI_FORMAT_CSV) {
        if (to >= 0.0)
            fprintf(w->f, "# gap from=%.6f to=%.6f reason=%s\n", from, to, reason);
        else
            fprintf(w->f, "# gap from=%.6f to= reason=%s\n", from, reason);
    } else {
        if (to >= 0.0)
            fprintf(w->f, "{\"gap\":{\"from\":%.6f,\"to\":%.6f,\"reason\":\"%s\"}}\n", from, to,
                    reason);
        else
            fprintf(w->f, "{\"gap\":{\"from\":%.6f,\"to\":null,\"reason\":\"%s\"}}\n", from, reason);
    }
}
