/* The virtual sensor's replay file: raw counts per line, from the leptrino
 * tool's own raw recordings (CSV: comment lines, a header naming the
 * columns; JSON lines: a metadata object, then flat objects whose names are
 * the columns) or a plain headerless fx,fy,fz,mx,my,mz[,status] list. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "sim_signal.h"

#define MAX_FIELDS 64
#define MAX_LINE 4096

static const char *const axis_names[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };

/* Where the values are: column indexes from a header, or -1. */
typedef struct layout {
    bool header; /* columns by name (from a header line) */
    bool seen_header;
    int axis[LEP_AXES]; /* fx_counts..mz_counts (or fx..mz) */
    int status, sensor; /* optional */
    char first_sensor[64];
    bool have_sensor;
} layout;

/* Split line into trimmed fields at ',' or ';' (in place). Returns the count,
 * or -1 for more than MAX_FIELDS. */
static int split(char *line, char *field[MAX_FIELDS])
{
    int n = 0;
    char *p = line;
    for (;;) {
        char *start, *end;
        while (*p == ' ' || *p == '\t')
            p++;
        if (n == MAX_FIELDS)
            return -1;
        start = p;
        while (*p != '\0' && *p != ',' && *p != ';' && *p != '\n' && *p != '\r')
            p++;
        end = p;
        while (end > start && (end[-1] == ' ' || end[-1] == '\t'))
            end--;
        if (end - start >= 2 && start[0] == '"' && end[-1] == '"') {
            start++;
            end--;
        }
        field[n++] = start;
        if (*p == ',' || *p == ';') {
            *end = '\0';
            p++;
            continue;
        }
        *end = '\0';
        return n;
    }
}

/* A header line names the columns: fx_counts..mz_counts (the project's
 * CSV names) or fx..mz, and optionally status and sensor. */
static int read_header(layout *l, char **field, int n, const char *file, size_t lineno, char *err,
                       size_t errlen)
{
    int i, a;
    for (a = 0; a < LEP_AXES; a++)
        l->axis[a] = -1;
    l->status = l->sensor = -1;
    for (i = 0; i < n; i++) {
        for (a = 0; a < LEP_AXES; a++) {
            size_t k = strlen(axis_names[a]);
            if (strncmp(field[i], axis_names[a], k) == 0 &&
                (field[i][k] == '\0' || strcmp(field[i] + k, "_counts") == 0))
                l->axis[a] = i;
        }
        if (strcmp(field[i], "status") == 0)
            l->status = i;
        if (strcmp(field[i], "sensor") == 0)
            l->sensor = i;
    }
    for (a = 0; a < LEP_AXES; a++) {
        if (l->axis[a] < 0) {
            lep_priv_set_err(err, errlen,
                             "%s:%zu: the header has no %s_counts column (replay needs raw "
                             "counts: fx_counts,fy_counts,fz_counts,mx_counts,my_counts,"
                             "mz_counts)",
                             file, lineno, axis_names[a]);
            return LEP_E_VALUE;
        }
    }
    /* the old form's optional header, fx,fy,fz,mx,my,mz: rows may still
     * carry a 7th column, the status */
    l->header = true;
    if (n == LEP_AXES) {
        for (a = 0; a < LEP_AXES && strcmp(field[a], axis_names[a]) == 0; a++) {
        }
        l->header = a < LEP_AXES;
    }
    l->seen_header = true;
    return LEP_OK;
}

/* A line of the tool's JSON-lines recordings, split in place into names and
 * values (strings unquoted). Returns the count for a data row (a flat
 * object), 0 for a line that is not one ({"metadata":{...}}, an
 * {"event":...} mark), or -1 when it is not such a JSON object. */
static int split_json(char *p, char *name[MAX_FIELDS], char *value[MAX_FIELDS])
{
    int n = 0;
    while (*p == ' ' || *p == '\t')
        p++;
    if (*p++ != '{')
        return -1;
    for (;;) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '}')
            return n;
        if (*p++ != '"' || n == MAX_FIELDS)
            return -1;
        name[n] = p;
        while (*p != '"' && *p != '\0' && *p != '\\')
            p++;
        if (*p != '"')
            return -1;
        *p++ = '\0';
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p++ != ':')
            return -1;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '{' || *p == '[' || strcmp(name[n], "event") == 0)
            return 0; /* metadata (nested), or an event mark */
        if (*p == '"') {
            value[n] = ++p;
            while (*p != '"' && *p != '\0' && *p != '\\')
                p++;
            if (*p != '"')
                return -1;
            *p++ = '\0';
        } else {
            value[n] = p;
            while (*p != ',' && *p != '}' && *p != ' ' && *p != '\0')
                p++;
        }
        n++;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == ',') {
            *p++ = '\0';
        } else if (*p == '}') {
            *p = '\0';
            return n;
        } else {
            return -1;
        }
    }
}

static bool parse_int(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    if (*s == '\0')
        return false;
    errno = 0;
    v = strtol(s, &end, 10);
    if (*end != '\0' || errno != 0 || v < lo || v > hi)
        return false;
    *out = v;
    return true;
}

/* One data line. Returns 1 for a row, 0 for a row of another sensor, or a
 * LEP_E_* code with a message. */
static int read_row(layout *l, char **field, int n, lep_sample *row, int16_t *status,
                    const char *file, size_t lineno, char *err, size_t errlen)
{
    long v;
    int a;
    memset(row, 0, sizeof *row);
    *status = -1;
    if (!l->header) {
        /* headerless: fx,fy,fz,mx,my,mz[,status] */
        if (n < 6 || n > 7) {
            lep_priv_set_err(err, errlen,
                             "%s:%zu: expected 6 or 7 integers fx,fy,fz,mx,my,mz[,status] "
                             "(int16, status 0..255)",
                             file, lineno);
            return LEP_E_VALUE;
        }
        for (a = 0; a < n; a++) {
            if (!parse_int(field[a], a < 6 ? -32768 : 0, a < 6 ? 32767 : 255, &v)) {
                lep_priv_set_err(err, errlen,
                                 "%s:%zu: expected 6 or 7 integers fx,fy,fz,mx,my,mz[,status] "
                                 "(int16, status 0..255)",
                                 file, lineno);
                return LEP_E_VALUE;
            }
            if (a < 6)
                row->raw[a] = (int16_t)v;
            else
                *status = (int16_t)v;
        }
        return 1;
    }
    if (l->sensor >= 0 && l->sensor < n) {
        /* several sensors in one file: replay the first one */
        if (!l->have_sensor) {
            snprintf(l->first_sensor, sizeof l->first_sensor, "%s", field[l->sensor]);
            l->have_sensor = true;
        } else if (strcmp(l->first_sensor, field[l->sensor]) != 0) {
            return 0;
        }
    }
    for (a = 0; a < LEP_AXES; a++) {
        int c = l->axis[a];
        if (c >= n || !parse_int(field[c], -32768, 32767, &v)) {
            lep_priv_set_err(err, errlen,
                             "%s:%zu: column %s_counts: '%s' is not a count (an "
                             "integer -32768..32767)",
                             file, lineno, axis_names[a], c < n ? field[c] : "");
            return LEP_E_VALUE;
        }
        row->raw[a] = (int16_t)v;
    }
    if (l->status >= 0) {
        if (l->status >= n || !parse_int(field[l->status], 0, 255, &v)) {
            lep_priv_set_err(err, errlen, "%s:%zu: column status: '%s' is not 0..255", file, lineno,
                             l->status < n ? field[l->status] : "");
            return LEP_E_VALUE;
        }
        *status = (int16_t)v;
    }
    return 1;
}

static int append(lep_sim_signal *g, size_t *cap, const lep_sample *row, int16_t status)
{
    if (g->replay_rows == *cap) {
        size_t ncap = *cap ? *cap * 2 : 256;
        lep_sample *nr = realloc(g->replay, ncap * sizeof *nr);
        int16_t *ns;
        if (nr == NULL)
            return LEP_E_IO;
        g->replay = nr;
        ns = realloc(g->replay_status, ncap * sizeof *ns);
        if (ns == NULL)
            return LEP_E_IO;
        g->replay_status = ns;
        *cap = ncap;
    }
    g->replay[g->replay_rows] = *row;
    g->replay_status[g->replay_rows] = status;
    g->replay_rows++;
    return LEP_OK;
}

int lep_priv_replay_load(lep_sim_signal *g, const char *file, char *err, size_t errlen)
{
    char *field[MAX_FIELDS];
    size_t cap = 0, lineno = 0, cut = 0;
    layout l;
    int rc = LEP_OK;
    FILE *f = fopen(file, "r");
    if (f == NULL) {
        lep_priv_set_err(err, errlen, "%s: cannot open replay file: %s", file, strerror(errno));
        return errno == ENOENT ? LEP_E_NOT_FOUND : LEP_E_IO;
    }
    memset(&l, 0, sizeof l);
    for (;;) {
        char buf[MAX_LINE + 2];
        const char *p;
        size_t len;
        int n;
        if (fgets(buf, sizeof buf, f) == NULL)
            break;
        lineno++;
        len = strlen(buf);
        if (len > 0 && buf[len - 1] != '\n' && len < sizeof buf - 1 && feof(f)) {
            /* The last line has no end: a recording cut by a crash or a
             * kill (its writer ends every line). Its values may be cut too:
             * replay up to the row before, and say so (below). */
            cut = lineno;
            break;
        }
        if (len == sizeof buf - 1 && buf[len - 1] != '\n') {
            lep_priv_set_err(err, errlen, "%s:%zu: line longer than %d bytes", file, lineno,
                             MAX_LINE);
            rc = LEP_E_VALUE;
            break;
        }
        p = buf;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '\0' || *p == '\n' || *p == '\r' || *p == '#')
            continue;    /* blank, or a comment (metadata, events) */
        if (*p == '{') { /* JSON lines: the names make the header, the values a row */
            char *value[MAX_FIELDS];
            n = split_json(buf, field, value);
            if (n < 0) {
                lep_priv_set_err(err, errlen,
                                 "%s:%zu: not a flat JSON object of the leptrino "
                                 "tool's recordings",
                                 file, lineno);
                rc = LEP_E_VALUE;
                break;
            }
            if (n == 0)
                continue;
            if (!l.seen_header) {
                rc = read_header(&l, field, n, file, lineno, err, errlen);
                if (rc != LEP_OK)
                    break;
            }
            memcpy(field, value, (size_t)n * sizeof field[0]);
        } else {
            n = split(buf, field);
        }
        if (n < 0) {
            lep_priv_set_err(err, errlen, "%s:%zu: more than %d columns", file, lineno, MAX_FIELDS);
            rc = LEP_E_VALUE;
            break;
        }
        if (*p != '{' && (isalpha((unsigned char)*p) || *p == '"')) {
            if (l.seen_header || g->replay_rows > 0) {
                lep_priv_set_err(err, errlen, "%s:%zu: a second header line", file, lineno);
                rc = LEP_E_VALUE;
                break;
            }
            rc = read_header(&l, field, n, file, lineno, err, errlen);
            if (rc != LEP_OK)
                break;
            continue;
        }
        {
            lep_sample row;
            int16_t status;
            int r = read_row(&l, field, n, &row, &status, file, lineno, err, errlen);
            if (r < 0) {
                rc = r;
                break;
            }
            if (r == 1 && append(g, &cap, &row, status) != LEP_OK) {
                lep_priv_set_err(err, errlen, "%s: out of memory", file);
                rc = LEP_E_IO;
                break;
            }
        }
    }
    fclose(f);
    if (rc == LEP_OK && g->replay_rows == 0) {
        lep_priv_set_err(err, errlen, "%s: no samples in replay file", file);
        rc = LEP_E_VALUE;
    }
    if (rc == LEP_OK && cut > 0) /* a warning: err on success (sim.h, lep_sim_start) */
        lep_priv_set_err(err, errlen,
                         "%s:%zu: the last line is cut (no end of line: a crash or a kill while "
                         "recording?): replaying the %zu whole rows before it",
                         file, cut, g->replay_rows);
    return rc;
}
