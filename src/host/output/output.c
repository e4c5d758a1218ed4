/* Recording writer: CSV or JSON lines from session batches (output.h). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "errmsg.h"
#include "fd_write.h"
#include "leptrino/error.h"
#include "leptrino/output.h"
#include "leptrino/serial.h"
#include "struct_api.h"

#define OUT_BUF 65536u
/* Longest time a row written to a regular file waits in the buffer (docs/session.md:
 * what a crash can lose). */
#define OUT_FILE_FLUSH_S 0.1
#define OUT_ROW_MAX 1024u /* longest row or event line, with margin */
#define OUT_SENSORS 16
#define OUT_NAME 64u
#define OUT_META 8192u

typedef struct out_sensor {
    char name[OUT_NAME];
    lep_session *session; /* metadata read at header time, or ... */
    char *meta;           /* ... this copy */
    double start_mono;
    uint64_t rows;
} out_sensor;

struct lep_output {
    int fd;
    bool own_fd;
    bool regular;       /* a regular file: flushed every OUT_FILE_FLUSH_S; else every write */
    double unflushed_t; /* when the oldest byte still in buf was put there (0: none) */
    bool header_done;
    int err_no;
    lep_output_options o;
    double t0;
    int n_sensors;
    out_sensor sensors[OUT_SENSORS];
    size_t len;
    char buf[OUT_BUF];
};

static const char *const AXES[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };
static const char *const SI_NAMES[LEP_AXES] = { "fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm" };
static const char *const TIME_NAMES[3] = { "t_s", "t_mono_s", "t_utc_s" };

void lep_output_options_init(lep_output_options *o)
{
    if (o == NULL)
        return;
    memset(o, 0, sizeof *o);
    o->format = LEP_OUTPUT_CSV;
    o->time = LEP_TIME_REL;
    o->columns = LEP_COL_DEFAULT;
}

/* ---- bytes ---- */

static int flush_buf(lep_output *w)
{
    if (w->err_no != 0)
        return LEP_E_IO;
    if (lep_priv_write_all(w->fd, w->buf, w->len, -1) != LEP_PRIV_WRITE_OK) {
        w->err_no = errno != 0 ? errno : EIO;
        w->len = 0;
        return LEP_E_IO;
    }
    w->len = 0;
    w->unflushed_t = 0.0;
    return LEP_OK;
}

static void put(lep_output *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void put(lep_output *w, const char *fmt, ...)
{
    va_list ap;
    int n;
    size_t room = OUT_BUF - w->len;
    va_start(ap, fmt);
    n = vsnprintf(w->buf + w->len, room, fmt, ap);
    va_end(ap);
    if (n > 0 && (size_t)n < room) {
        w->len += (size_t)n;
        return;
    }
    /* Does not fit: flush and format again (a single piece is never near 64 KiB). */
    if (n < 0 || flush_buf(w) != LEP_OK)
        return;
    va_start(ap, fmt);
    n = vsnprintf(w->buf, OUT_BUF, fmt, ap);
    va_end(ap);
    if (n > 0 && (size_t)n < OUT_BUF)
        w->len = (size_t)n;
}

/* Room for one more row or event line. */
static void reserve(lep_output *w)
{
    if (w->len > OUT_BUF - OUT_ROW_MAX)
        (void)flush_buf(w);
}

/* ---- open, sensors, close ---- */

static bool options_ok(const lep_output_options *o, char *err, size_t errlen)
{
    if (o == NULL)
        return true;
    if ((o->format != LEP_OUTPUT_CSV && o->format != LEP_OUTPUT_JSONL) || o->time < LEP_TIME_REL ||
        o->time > LEP_TIME_UTC || (o->columns & ~0x7Fu) != 0u || !(o->t0_mono >= 0.0)) {
        lep_priv_set_err(err, errlen, "output: bad options (format, time, columns or t0_mono)");
        return false;
    }
    return true;
}

static int new_writer(int fd, bool own, const lep_output_options *o, lep_output **out, char *err,
                      size_t errlen)
{
    lep_output *w;
    lep_output_options d;
    if (o == NULL) {
        lep_output_options_init(&d);
        o = &d;
    }
    if (!options_ok(o, err, errlen))
        return LEP_E_ARG;
    w = calloc(1, sizeof *w);
    if (w == NULL) {
        lep_priv_set_err(err, errlen, "output: out of memory");
        return LEP_E_IO;
    }
    w->fd = fd;
    w->own_fd = own;
    {
        struct stat sb;
        w->regular = fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode);
    }
    w->o = *o;
    *out = w;
    return LEP_OK;
}

int lep_output_open_fd_opts(int fd, const lep_output_options *o, lep_output **out, char *err,
                            size_t errlen)
{
    if (out != NULL)
        *out = NULL;
    if (out == NULL || fd < 0) {
        lep_priv_set_err(err, errlen, "output: bad file descriptor %d", fd);
        return LEP_E_ARG;
    }
    return new_writer(fd, false, o, out, err, errlen);
}

int lep_output_open_opts(const char *path, const lep_output_options *o, lep_output **out, char *err,
                         size_t errlen)
{
    int fd, flags, rc;
    if (out != NULL)
        *out = NULL;
    if (out == NULL) {
        lep_priv_set_err(err, errlen, "output: NULL result pointer");
        return LEP_E_ARG;
    }
    if (path == NULL || strcmp(path, "-") == 0)
        return new_writer(STDOUT_FILENO, false, o, out, err, errlen);
    if (!options_ok(o, err, errlen))
        return LEP_E_ARG; /* before anything is created */
    if (path[0] == '\0') {
        lep_priv_set_err(err, errlen, "output: empty file name");
        return LEP_E_ARG;
    }
    flags = O_WRONLY | O_CREAT | O_CLOEXEC | (o != NULL && o->overwrite ? O_TRUNC : O_EXCL);
    fd = open(path, flags, 0666);
    if (fd < 0) {
        int e = errno;
        switch (e) {
        case EEXIST:
            lep_priv_set_err(err, errlen,
                             "%s: already exists; not overwritten (choose another name, or allow "
                             "overwriting)",
                             path);
            return LEP_E_ARG;
        case ENOENT:
        case ENOTDIR:
            lep_priv_set_err(err, errlen, "%s: no such directory", path);
            return LEP_E_NOT_FOUND;
        case EACCES:
        case EPERM:
        case EROFS:
            lep_priv_set_err(err, errlen, "%s: cannot create: %s", path, strerror(e));
            return LEP_E_PERMISSION;
        case EISDIR:
            lep_priv_set_err(err, errlen, "%s: is a directory", path);
            return LEP_E_ARG;
        default:
            lep_priv_set_err(err, errlen, "%s: cannot create: %s", path, strerror(e));
            return LEP_E_IO;
        }
    }
    rc = new_writer(fd, true, o, out, err, errlen);
    if (rc != LEP_OK)
        close(fd);
    return rc;
}

/* Names go into CSV cells and event lines unquoted: printable, no separators. */
static bool name_ok(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n >= OUT_NAME)
        return false;
    for (; *name != '\0'; name++) {
        unsigned char c = (unsigned char)*name;
        if (c <= 0x20u || c >= 0x7Fu || c == ',' || c == '"' || c == '\\' || c == '=' || c == '#')
            return false;
    }
    return true;
}

static int add(lep_output *w, const char *name)
{
    out_sensor *s;
    if (w == NULL)
        return LEP_E_ARG;
    if (w->header_done)
        return LEP_E_STATE;
    if (w->n_sensors == OUT_SENSORS || (name != NULL && !name_ok(name)))
        return LEP_E_ARG;
    s = &w->sensors[w->n_sensors];
    memset(s, 0, sizeof *s);
    if (name != NULL)
        snprintf(s->name, sizeof s->name, "%s", name);
    else
        snprintf(s->name, sizeof s->name, "sensor%d", w->n_sensors);
    return w->n_sensors++;
}

int lep_output_add_session(lep_output *w, lep_session *s, const char *name)
{
    int i;
    if (s == NULL)
        return LEP_E_ARG;
    i = add(w, name);
    if (i >= 0)
        w->sensors[i].session = s;
    return i;
}

int lep_output_add_sensor(lep_output *w, const char *name, const char *metadata_json,
                          double start_mono)
{
    int i;
    size_t n;
    if (metadata_json == NULL || metadata_json[0] != '{' || start_mono < 0.0)
        return LEP_E_ARG;
    n = strlen(metadata_json);
    if (n >= OUT_META)
        return LEP_E_ARG;
    i = add(w, name);
    if (i < 0)
        return i;
    w->sensors[i].meta = malloc(n + 1u);
    if (w->sensors[i].meta == NULL) {
        w->n_sensors--;
        return LEP_E_IO;
    }
    memcpy(w->sensors[i].meta, metadata_json, n + 1u);
    w->sensors[i].start_mono = start_mono;
    return i;
}

/* ---- header ---- */

static void write_metadata(lep_output *w, const out_sensor *s, const char *json)
{
    bool named = (w->o.columns & LEP_COL_SENSOR) != 0u;
    /* With a sensor column the object says which sensor it describes. */
    const char *rest = json + 1;
    if (w->o.format == LEP_OUTPUT_CSV)
        put(w, "# leptrino-metadata: ");
    else
        put(w, "{\"metadata\":");
    if (named)
        put(w, "{\"sensor\":\"%s\"%s%s", s->name, rest[0] == '}' ? "" : ",", rest);
    else
        put(w, "%s", json);
    put(w, w->o.format == LEP_OUTPUT_CSV ? "\n" : "}\n");
}

static void write_header(lep_output *w)
{
    unsigned c = w->o.columns;
    int i, k;
    bool csv = w->o.format == LEP_OUTPUT_CSV;

    w->header_done = true;
    for (i = 0; i < w->n_sensors; i++) {
        out_sensor *s = &w->sensors[i];
        const char *js = s->meta;
        char local[OUT_META];
        if (s->session != NULL) {
            lep_session_meta m;
            size_t len = 0;
            lep_session_get_metadata(s->session, &m);
            s->start_mono = m.start_mono;
            if (lep_session_metadata_json(s->session, local, sizeof local, &len) == LEP_OK)
                js = local;
            else
                js = NULL;
        }
        if (i == 0)
            w->t0 = w->o.t0_mono > 0.0 ? w->o.t0_mono : s->start_mono;
        if (js != NULL)
            write_metadata(w, s, js);
    }
    if (w->n_sensors == 0)
        w->t0 = w->o.t0_mono;
    if (!csv)
        return;
    put(w, "%s", TIME_NAMES[w->o.time]);
    if (c & LEP_COL_SENSOR)
        put(w, ",sensor");
    if (c & LEP_COL_RAW)
        for (k = 0; k < LEP_AXES; k++)
            put(w, ",%s_counts", AXES[k]);
    if (c & LEP_COL_ZEROED)
        for (k = 0; k < LEP_AXES; k++)
            put(w, ",%s_zeroed_counts", AXES[k]);
    if (c & LEP_COL_SI)
        for (k = 0; k < LEP_AXES; k++)
            put(w, ",%s", SI_NAMES[k]);
    if (c & LEP_COL_STATUS)
        put(w, ",status");
    if (c & LEP_COL_FLAGS)
        put(w, ",flags");
    if (c & LEP_COL_SEQ)
        put(w, ",seq");
    put(w, "\n");
}

/* ---- rows and events ---- */

/* A monotonic instant in the chosen time base (utc_off: UTC - monotonic). */
static double when(const lep_output *w, double t_mono, double utc_off)
{
    switch (w->o.time) {
    case LEP_TIME_MONO:
        return t_mono;
    case LEP_TIME_UTC:
        return t_mono + utc_off;
    default:
        return t_mono - w->t0;
    }
}

static void write_row(lep_output *w, const out_sensor *s, const lep_session_batch *b, size_t i)
{
    unsigned c = w->o.columns;
    bool csv = w->o.format == LEP_OUTPUT_CSV;
    double t = w->o.time == LEP_TIME_UTC ? b->t_utc[i] : when(w, b->t_mono[i], 0.0);
    int k;

    reserve(w);
    if (csv)
        put(w, "%.6f", t);
    else
        put(w, "{\"%s\":%.6f", TIME_NAMES[w->o.time], t);
    if (c & LEP_COL_SENSOR)
        put(w, csv ? ",%s" : ",\"sensor\":\"%s\"", s->name);
    if (c & LEP_COL_RAW)
        for (k = 0; k < LEP_AXES; k++) {
            int v = b->raw[i * LEP_AXES + (size_t)k];
            if (csv)
                put(w, ",%d", v);
            else
                put(w, ",\"%s_counts\":%d", AXES[k], v);
        }
    if (c & LEP_COL_ZEROED)
        for (k = 0; k < LEP_AXES; k++) {
            double v = b->zeroed[i * LEP_AXES + (size_t)k];
            if (csv)
                put(w, ",%.3f", v);
            else
                put(w, ",\"%s_zeroed_counts\":%.3f", AXES[k], v);
        }
    if (c & LEP_COL_SI)
        for (k = 0; k < LEP_AXES; k++) {
            double v = b->si[i * LEP_AXES + (size_t)k];
            if (csv)
                put(w, ",%.6f", v);
            else
                put(w, ",\"%s\":%.6f", SI_NAMES[k], v);
        }
    if (c & LEP_COL_STATUS)
        put(w, csv ? ",%u" : ",\"status\":%u", (unsigned)b->status[i]);
    if (c & LEP_COL_FLAGS)
        put(w, csv ? ",%u" : ",\"flags\":%u", (unsigned)b->flags[i]);
    if (c & LEP_COL_SEQ)
        put(w, csv ? ",%u" : ",\"seq\":%u", (unsigned)b->seq[i]);
    put(w, csv ? "\n" : "}\n");
}

static const char *loss_reason(int error)
{
    return error == LEP_E_TIMEOUT ? "no-data" : "disconnected";
}

static void write_event(lep_output *w, const out_sensor *s, const lep_session_event *ev)
{
    bool csv = w->o.format == LEP_OUTPUT_CSV;
    bool named = (w->o.columns & LEP_COL_SENSOR) != 0u;
    double off = ev->t_utc - ev->t_mono;
    double at = when(w, ev->t_mono, off);
    const char *word;
    int k;

    reserve(w);
    switch (ev->type) {
    case LEP_EV_GAP:
    case LEP_EV_RECONNECTED:
        word = "gap";
        break;
    case LEP_EV_DISCONNECTED:
        word = "disconnected";
        break;
    case LEP_EV_TARE:
        word = "tare";
        break;
    case LEP_EV_OVERLOAD_BEGIN:
        word = csv ? "overload begin" : "overload_begin";
        break;
    case LEP_EV_OVERLOAD_END:
        word = csv ? "overload end" : "overload_end";
        break;
    case LEP_EV_LIMIT_EXCEEDED:
        word = csv ? "limit exceeded" : "limit_exceeded";
        break;
    case LEP_EV_LIMIT_CLEARED:
        word = csv ? "limit cleared" : "limit_cleared";
        break;
    default:
        return;
    }
    if (csv) {
        put(w, "# %s", word);
        if (named)
            put(w, " sensor=%s", s->name);
    } else {
        put(w, "{\"event\":\"%s\"", word);
        if (named)
            put(w, ",\"sensor\":\"%s\"", s->name);
    }
    switch (ev->type) {
    case LEP_EV_GAP:
    case LEP_EV_RECONNECTED: {
        const char *reason = ev->type == LEP_EV_GAP ? "gap" : loss_reason(ev->error);
        double from = when(w, ev->gap_from, off), to = when(w, ev->gap_to, off);
        if (csv)
            put(w, " from=%.6f to=%.6f lost=%u reason=%s\n", from, to, (unsigned)ev->lost, reason);
        else
            put(w, ",\"from\":%.6f,\"to\":%.6f,\"lost\":%u,\"reason\":\"%s\"}\n", from, to,
                (unsigned)ev->lost, reason);
        break;
    }
    case LEP_EV_DISCONNECTED:
        if (csv)
            put(w, " at=%.6f reason=%s\n", at, loss_reason(ev->error));
        else
            put(w, ",\"at\":%.6f,\"reason\":\"%s\"}\n", at, loss_reason(ev->error));
        break;
    case LEP_EV_TARE:
        put(w, csv ? " at=%.6f" : ",\"at\":%.6f,\"offset_counts\":[", at);
        for (k = 0; k < LEP_AXES; k++) {
            if (csv)
                put(w, " %s=%.6f", AXES[k], ev->tare[k]);
            else
                put(w, "%s%.6f", k > 0 ? "," : "", ev->tare[k]);
        }
        put(w, csv ? "\n" : "]}\n");
        break;
    case LEP_EV_OVERLOAD_BEGIN:
        if (csv)
            put(w, " at=%.6f axes=%u status=%u\n", at, (unsigned)ev->axes, (unsigned)ev->status);
        else
            put(w, ",\"at\":%.6f,\"axes\":%u,\"status\":%u}\n", at, (unsigned)ev->axes,
                (unsigned)ev->status);
        break;
    case LEP_EV_LIMIT_EXCEEDED:
        put(w, csv ? " at=%.6f axes=%u" : ",\"at\":%.6f,\"axes\":%u,\"wrench\":[", at,
            (unsigned)ev->axes);
        for (k = 0; k < LEP_AXES; k++) {
            if (csv)
                put(w, " %s=%.6f", SI_NAMES[k], ev->wrench[k]);
            else
                put(w, "%s%.6f", k > 0 ? "," : "", ev->wrench[k]);
        }
        put(w, csv ? "\n" : "]}\n");
        break;
    default: /* LEP_EV_OVERLOAD_END, LEP_EV_LIMIT_CLEARED */
        put(w, csv ? " at=%.6f\n" : ",\"at\":%.6f}\n", at);
        break;
    }
}

int lep_output_write_batch(lep_output *w, int sensor, const lep_session_batch *b, size_t from,
                           const lep_session_event *ev, size_t nev)
{
    unsigned c;
    out_sensor *s;
    size_t i, e = 0;

    if (w == NULL || sensor < 0 || sensor >= w->n_sensors || (ev == NULL && nev > 0))
        return LEP_E_ARG;
    c = w->o.columns;
    if (b != NULL &&
        (b->n > b->cap || from > b->n ||
         (b->n > from &&
          (b->t_mono == NULL || (w->o.time == LEP_TIME_UTC && b->t_utc == NULL) ||
           ((c & LEP_COL_RAW) && b->raw == NULL) || ((c & LEP_COL_ZEROED) && b->zeroed == NULL) ||
           ((c & LEP_COL_SI) && b->si == NULL) || ((c & LEP_COL_STATUS) && b->status == NULL) ||
           ((c & LEP_COL_FLAGS) && b->flags == NULL) || ((c & LEP_COL_SEQ) && b->seq == NULL)))))
        return LEP_E_ARG;
    if (w->err_no != 0)
        return LEP_E_IO;
    if (!w->header_done) {
        write_header(w);
        (void)flush_buf(w); /* the metadata is on disk before the first row */
    }
    if (w->len == 0)
        w->unflushed_t = lep_monotonic_seconds();
    s = &w->sensors[sensor];
    if (b != NULL) {
        for (i = from; i < b->n; i++) {
            while (e < nev && ev[e].sample <= s->rows)
                write_event(w, s, &ev[e++]);
            write_row(w, s, b, i);
            s->rows++;
        }
    }
    while (e < nev)
        write_event(w, s, &ev[e++]);
    /* A pipe or a terminal gets each batch at once (a reader acts on it); a
     * file at least every OUT_FILE_FLUSH_S (what a crash can lose). */
    if (w->len > 0 && (!w->regular || lep_monotonic_seconds() - w->unflushed_t >= OUT_FILE_FLUSH_S))
        (void)flush_buf(w);
    return w->err_no != 0 ? LEP_E_IO : LEP_OK;
}

int lep_output_flush(lep_output *w)
{
    if (w == NULL)
        return LEP_E_ARG;
    if (w->len == 0)
        return w->err_no != 0 ? LEP_E_IO : LEP_OK;
    return flush_buf(w);
}

int lep_output_errno(const lep_output *w)
{
    return w != NULL ? w->err_no : 0;
}

int lep_output_close(lep_output *w)
{
    int rc, i;
    if (w == NULL)
        return LEP_OK;
    if (!w->header_done && w->err_no == 0)
        write_header(w);
    rc = flush_buf(w);
    if (w->own_fd && close(w->fd) != 0 && rc == LEP_OK) {
        w->err_no = errno;
        rc = LEP_E_IO;
    }
    for (i = 0; i < w->n_sensors; i++)
        free(w->sensors[i].meta);
    free(w);
    return rc;
}

/* ---- the flat form (leptrino/output.h) ---- */

static int flat_options(lep_output_options *o, int format, int time, int columns, double t0_mono,
                        int overwrite, char *err, size_t errlen)
{
    lep_output_options_init(o);
    if (format != LEP_OUTPUT_CSV && format != LEP_OUTPUT_JSONL) {
        lep_priv_set_err(err, errlen, "output: format %d: expected 0 (CSV) or 1 (JSON lines)",
                         format);
        return LEP_E_ARG;
    }
    if (time < LEP_TIME_REL || time > LEP_TIME_UTC) {
        lep_priv_set_err(err, errlen, "output: time %d: expected 0 (rel), 1 (mono) or 2 (utc)",
                         time);
        return LEP_E_ARG;
    }
    if (columns < 0 || columns > 0x7F) {
        lep_priv_set_err(err, errlen, "output: columns 0x%x: expected LEP_COL_* bits", columns);
        return LEP_E_ARG;
    }
    if (!(t0_mono >= 0.0) || t0_mono > 1e15) { /* also NaN */
        lep_priv_set_err(err, errlen, "output: t0_mono %g: expected 0 or a monotonic time",
                         t0_mono);
        return LEP_E_ARG;
    }
    o->format = format;
    o->time = time;
    o->columns = (unsigned)columns;
    o->t0_mono = t0_mono;
    o->overwrite = overwrite != 0;
    return LEP_OK;
}

int lep_output_open(const char *path, int format, int time, int columns, double t0_mono,
                    int overwrite, lep_output **out, char *err, size_t errlen)
{
    lep_output_options o;
    int rc = flat_options(&o, format, time, columns, t0_mono, overwrite, err, errlen);
    if (rc != LEP_OK) {
        if (out != NULL)
            *out = NULL;
        return rc;
    }
    return lep_output_open_opts(path, &o, out, err, errlen);
}

int lep_output_open_fd(int fd, int format, int time, int columns, double t0_mono, lep_output **out,
                       char *err, size_t errlen)
{
    lep_output_options o;
    int rc = flat_options(&o, format, time, columns, t0_mono, 0, err, errlen);
    if (rc != LEP_OK) {
        if (out != NULL)
            *out = NULL;
        return rc;
    }
    return lep_output_open_fd_opts(fd, &o, out, err, errlen);
}

int lep_output_write(lep_output *w, int sensor, size_t n, const double *t_mono, const double *t_utc,
                     const double *si, const int16_t *raw, const double *zeroed,
                     const uint8_t *status, const uint8_t *flags, const uint16_t *seq,
                     const double *events, size_t nev, size_t ev_fields)
{
    lep_session_batch b;
    lep_session_event few[16];
    lep_session_event *ev = few;
    double f[LEP_EVF_COUNT];
    size_t k, take = ev_fields < LEP_EVF_COUNT ? ev_fields : LEP_EVF_COUNT;
    int rc;
    if (nev > 0 && (events == NULL || ev_fields < (size_t)LEP_EVF_TARE + 6u))
        return LEP_E_ARG;
    if (nev > sizeof few / sizeof few[0]) {
        ev = malloc(nev * sizeof *ev);
        if (ev == NULL)
            return LEP_E_IO;
    }
    for (k = 0; k < nev; k++) {
        memset(f, 0, sizeof f);
        memcpy(f, events + k * ev_fields, sizeof(double) * take);
        lep_event_from_fields(f, &ev[k]);
    }
    /* The batch is only read (its members are not const for the session's sake). */
    memset(&b, 0, sizeof b);
    b.cap = b.n = n;
    b.t_mono = (double *)t_mono;
    b.t_utc = (double *)t_utc;
    b.si = (double *)si;
    b.raw = (int16_t *)raw;
    b.zeroed = (double *)zeroed;
    b.status = (uint8_t *)status;
    b.flags = (uint8_t *)flags;
    b.seq = (uint16_t *)seq;
    rc = lep_output_write_batch(w, sensor, &b, 0, nev > 0 ? ev : NULL, nev);
    if (ev != few)
        free(ev);
    return rc;
}
