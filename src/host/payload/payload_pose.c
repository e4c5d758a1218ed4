/* One pose for a payload identification: the mean wrench of a CSV recording
 * made by the leptrino tool, brought back to what the sensor measured (the
 * sensor frame, no tare). Reads the metadata line, the header, the tare
 * events and the rows that src/host/output/output.c writes. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/payload.h"
#include "struct_api.h"

#define META_PREFIX "# leptrino-metadata: "
#define MAX_COLS 64

static const char *const si_names[LEP_AXES] = { "fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm" };
static const char *const raw_names[LEP_AXES] = { "fx_counts", "fy_counts", "fz_counts",
                                                 "mx_counts", "my_counts", "mz_counts" };
static const char *const tare_keys[LEP_AXES] = { " fx=", " fy=", " fz=", " mx=", " my=", " mz=" };

typedef struct pose_reader {
    const char *path;
    size_t line;
    char *err;
    size_t errlen;
    /* from the metadata */
    bool have_meta;
    double rated[LEP_AXES];
    double rot[9], shift[3];
    double tare[LEP_AXES]; /* in force now (counts) */
    /* from the header */
    bool have_header;
    int col[LEP_AXES]; /* value columns */
    bool si;           /* they are SI (else raw counts) */
    int status, flags, ncols;
    /* sums */
    double sum[LEP_AXES];
    uint64_t rows;
} pose_reader;

static int fail(pose_reader *r, const char *what)
{
    if (r->line > 0)
        lep_priv_set_err(r->err, r->errlen, "%s:%zu: %s", r->path, r->line, what);
    else
        lep_priv_set_err(r->err, r->errlen, "%s: %s", r->path, what);
    return LEP_E_VALUE;
}

/* A finite number at s, followed by one of the characters in stop or, when
 * stop is NULL, by the end of the text. */
static bool number(const char *s, const char *stop, double *out, const char **end)
{
    char *e;
    errno = 0;
    *out = strtod(s, &e);
    if (e == s || errno == ERANGE || !isfinite(*out))
        return false;
    if (stop == NULL ? *e != '\0' : (*e == '\0' || strchr(stop, *e) == NULL))
        return false;
    if (end != NULL)
        *end = e;
    return true;
}

/* n numbers after "key": in a metadata object, as an array [..] (or, for an
 * object {"a":1,...}, its n values in order). */
static bool meta_numbers(const char *json, const char *key, double *out, int n)
{
    const char *p = strstr(json, key);
    int i;
    if (p == NULL)
        return false;
    p += strlen(key);
    if (*p != '[' && *p != '{')
        return false;
    p++;
    for (i = 0; i < n; i++) {
        if (*p == '"') { /* "name": */
            p = strchr(p + 1, '"');
            if (p == NULL || p[1] != ':')
                return false;
            p += 2;
        }
        if (!number(p, i + 1 < n ? "," : "]}", &out[i], &p))
            return false;
        p++;
    }
    return true;
}

static int read_meta(pose_reader *r, const char *json)
{
    int k;
    if (r->have_meta)
        return fail(r, "a second sensor's metadata: a pose is a recording of one sensor "
                       "(record each with its own file, --split)");
    if (!meta_numbers(json, "\"rated\":", r->rated, LEP_AXES) ||
        !meta_numbers(json, "\"rotation\":", r->rot, 9) ||
        !meta_numbers(json, "\"shift_m\":", r->shift, 3) ||
        !meta_numbers(json, "\"tare_counts\":", r->tare, LEP_AXES))
        return fail(r, "metadata without rated, rotation, shift_m or tare_counts");
    for (k = 0; k < LEP_AXES; k++)
        if (!(r->rated[k] > 0.0))
            return fail(r, "metadata with a rated value that is not positive");
    if (strstr(json, "\"payload\":") != NULL && strstr(json, "\"payload\":null") == NULL)
        return fail(r, "recorded with a payload compensated: record poses without --payload");
    r->have_meta = true;
    return LEP_OK;
}

/* "# tare at=T fx=.. fy=.. ...": the offsets from here on. */
static int read_tare(pose_reader *r, const char *line)
{
    double t[LEP_AXES];
    int k;
    for (k = 0; k < LEP_AXES; k++) {
        const char *p = strstr(line, tare_keys[k]);
        if (p == NULL || (!number(p + strlen(tare_keys[k]), " \r\n", &t[k], NULL) &&
                          !number(p + strlen(tare_keys[k]), NULL, &t[k], NULL)))
            return fail(r, "a tare line without its six offsets");
    }
    memcpy(r->tare, t, sizeof t);
    return LEP_OK;
}

/* Split a CSV line in place at commas. */
static int split(char *line, char *field[MAX_COLS])
{
    int n = 0;
    char *p = line;
    for (;;) {
        if (n == MAX_COLS)
            return -1;
        field[n++] = p;
        p += strcspn(p, ",\r\n");
        if (*p != ',') {
            *p = '\0';
            return n;
        }
        *p++ = '\0';
    }
}

static int read_header(pose_reader *r, char **field, int n)
{
    int i, k, si = 0, raw = 0;
    int si_col[LEP_AXES], raw_col[LEP_AXES];
    r->status = r->flags = -1;
    for (i = 0; i < n; i++) {
        for (k = 0; k < LEP_AXES; k++) {
            if (strcmp(field[i], si_names[k]) == 0) {
                si_col[k] = i;
                si |= 1 << k;
            }
            if (strcmp(field[i], raw_names[k]) == 0) {
                raw_col[k] = i;
                raw |= 1 << k;
            }
        }
        if (strcmp(field[i], "status") == 0)
            r->status = i;
        if (strcmp(field[i], "flags") == 0)
            r->flags = i;
        if (strcmp(field[i], "sensor") == 0)
            return fail(r, "a sensor column: a pose is a recording of one sensor");
    }
    if (si == 0x3F) {
        memcpy(r->col, si_col, sizeof r->col);
        r->si = true;
    } else if (raw == 0x3F) {
        memcpy(r->col, raw_col, sizeof r->col);
        r->si = false;
    } else {
        return fail(r, "the header has neither the SI columns (fx_N .. mz_Nm) nor the raw "
                       "counts (fx_counts .. mz_counts)");
    }
    r->ncols = n;
    r->have_header = true;
    return LEP_OK;
}

/* v (a row's six values) as the sensor measured them, N and N m. */
static void to_sensor(const pose_reader *r, const double v[LEP_AXES], double out[LEP_AXES])
{
    int i, k;
    if (!r->si) {
        for (k = 0; k < LEP_AXES; k++)
            out[k] = v[k] * r->rated[k] / LEP_RAW_FULL_SCALE;
        return;
    }
    {
        /* undo the moment point (m' = R m - s x f') and the rotation (f' = R f) */
        const double *f = v, *s = r->shift;
        double m[3];
        m[0] = v[3] + (s[1] * f[2] - s[2] * f[1]);
        m[1] = v[4] + (s[2] * f[0] - s[0] * f[2]);
        m[2] = v[5] + (s[0] * f[1] - s[1] * f[0]);
        for (i = 0; i < 3; i++) {
            out[i] = out[3 + i] = 0.0;
            for (k = 0; k < 3; k++) {
                out[i] += r->rot[k * 3 + i] * f[k];
                out[3 + i] += r->rot[k * 3 + i] * m[k];
            }
        }
    }
    for (k = 0; k < LEP_AXES; k++)
        out[k] += r->tare[k] * r->rated[k] / LEP_RAW_FULL_SCALE;
}

static int read_row(pose_reader *r, char **field, int n)
{
    double v[LEP_AXES], s[LEP_AXES];
    int k;
    if (n != r->ncols)
        return fail(r, "a row with another number of fields than the header");
    if (r->status >= 0 || r->flags >= 0) {
        double st = 0.0, fl = 0.0;
        if ((r->status >= 0 && !number(field[r->status], NULL, &st, NULL)) ||
            (r->flags >= 0 && !number(field[r->flags], NULL, &fl, NULL)))
            return fail(r, "a status or flags field that is not a number");
        if (st < 0.0 || st > 255.0 || fl < 0.0 || fl > 255.0)
            return fail(r, "a status or flags field out of 0..255");
        if (((unsigned)st & LEP_STATUS_OVERLOAD) != 0 || ((unsigned)fl & 0x02u) != 0)
            return fail(r, "an overloaded sample: the mean would be wrong (record the pose "
                           "again with a load within the rated range)");
    }
    for (k = 0; k < LEP_AXES; k++)
        if (!number(field[r->col[k]], NULL, &v[k], NULL))
            return fail(r, "a value that is not a number");
    to_sensor(r, v, s);
    for (k = 0; k < LEP_AXES; k++)
        r->sum[k] += s[k];
    r->rows++;
    return LEP_OK;
}

static int read_line(pose_reader *r, char *line)
{
    char *field[MAX_COLS];
    int n;
    if (strncmp(line, META_PREFIX, strlen(META_PREFIX)) == 0)
        return read_meta(r, line + strlen(META_PREFIX));
    if (line[0] == '#')
        return strncmp(line, "# tare ", 7) == 0 ? read_tare(r, line) : LEP_OK;
    if (line[0] == '{')
        return fail(r, "JSON lines: a pose is read from a CSV recording (leptrino stream's "
                       "default format)");
    if (line[strspn(line, " \t\r\n")] == '\0')
        return LEP_OK;
    if (!r->have_meta)
        return fail(r, "no '# leptrino-metadata:' line before the data: not a recording made "
                       "by leptrino stream");
    n = split(line, field);
    if (n < 0)
        return fail(r, "more than 64 columns");
    if (!r->have_header)
        return read_header(r, field, n);
    return read_row(r, field, n);
}

int lep_payload_pose_read(const char *path, double mean[LEP_AXES], uint64_t *samples, char *err,
                          size_t errlen)
{
    pose_reader r;
    FILE *f;
    char *line = NULL;
    size_t cap = 0;
    int rc = LEP_OK, k;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (path == NULL || mean == NULL) {
        lep_priv_set_err(err, errlen, "no file or result given");
        return LEP_E_ARG;
    }
    memset(&r, 0, sizeof r);
    r.path = path;
    r.err = err;
    r.errlen = errlen;
    f = fopen(path, "r");
    if (f == NULL) {
        int e = errno;
        lep_priv_set_err(err, errlen, "%s: %s", path, strerror(e));
        return e == ENOENT ? LEP_E_NOT_FOUND : LEP_E_IO;
    }
    while (rc == LEP_OK) {
        ssize_t len = getline(&line, &cap, f);
        if (len < 0)
            break;
        r.line++;
        if ((size_t)len != strlen(line)) {
            rc = fail(&r, "a NUL byte: not a text file");
            break;
        }
        rc = read_line(&r, line);
    }
    if (rc == LEP_OK && ferror(f)) {
        lep_priv_set_err(err, errlen, "%s: read error", path);
        rc = LEP_E_IO;
    }
    free(line);
    fclose(f);
    if (rc != LEP_OK)
        return rc;
    r.line = 0;
    if (r.rows == 0)
        return fail(&r, r.have_meta ? "no data rows to average"
                                    : "empty, or not a recording made by leptrino stream");
    for (k = 0; k < LEP_AXES; k++)
        mean[k] = r.sum[k] / (double)r.rows;
    if (samples != NULL)
        *samples = r.rows;
    return LEP_OK;
}
