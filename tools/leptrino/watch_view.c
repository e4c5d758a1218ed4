/* The screen of `leptrino watch`: one frame drawn from a cli_watch_view into
 * a buffer and written with one write(), so it never flickers or tears.
 *
 * Layout (shrinks to the window; below 40x17 only a "too small" line):
 *   title: model, serial, firmware, port
 *   rated values, sensor filter, host processing
 *   six rows: axis, value, unit, a bar centred on zero against the rated
 *             range ('<' or '>' at the end when beyond it), percent
 *   status bits and overloaded axes, rate against nominal, counters,
 *   tare state (and the payload compensated, if any), the last event, the keys */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#define SCREEN_CAP 16384

typedef struct screen {
    char buf[SCREEN_CAP];
    size_t used;
    int cols;
    int rows;
    int line;
} screen;

static void put(screen *s, const char *text, size_t n)
{
    if (s->used + n >= SCREEN_CAP)
        n = SCREEN_CAP - 1 - s->used;
    memcpy(s->buf + s->used, text, n);
    s->used += n;
}

static void puts_s(screen *s, const char *text)
{
    put(s, text, strlen(text));
}

/* One line: clipped to the width, then "erase to end of line". */
static void line(screen *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void line(screen *s, const char *fmt, ...)
{
    char text[1024];
    va_list ap;
    int n, shown = 0, i;
    if (s->line >= s->rows)
        return;
    va_start(ap, fmt);
    n = vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (n < 0)
        n = 0;
    if ((size_t)n >= sizeof text)
        n = (int)sizeof text - 1;
    if (s->line > 0)
        puts_s(s, "\r\n");
    /* Clip to the width, counting only what shows: escape sequences
     * (ESC [ ... letter) are always copied, so an attribute is always reset. */
    for (i = 0; i < n; ++i) {
        if (text[i] == '\033') {
            int j = i + 1;
            while (j < n && !isalpha((unsigned char)text[j]))
                j++;
            put(s, text + i, (size_t)(j < n ? j + 1 - i : n - i));
            i = j;
        } else if (shown < s->cols) {
            put(s, text + i, 1);
            shown++;
        }
    }
    puts_s(s, "\033[K");
    s->line++;
}

/* A bar of width w (odd, >= 5) for fraction f of the rated range. */
static void bar(char *out, int w, double f)
{
    int half = (w - 3) / 2; /* cells on each side of the centre */
    int i, fill;
    double a = fabs(f);
    bool beyond = a > 1.0;
    fill = (int)lround((beyond ? 1.0 : a) * half);
    out[0] = '[';
    for (i = 1; i < w - 1; ++i)
        out[i] = ' ';
    out[w - 1] = ']';
    out[1 + half] = '|';
    for (i = 1; i <= fill; ++i) {
        if (f < 0)
            out[1 + half - i] = '=';
        else
            out[1 + half + i] = '=';
    }
    if (beyond) {
        if (f < 0)
            out[1] = '<';
        else
            out[w - 2] = '>';
    }
    out[w] = '\0';
}

/* The whole frame, however the terminal takes it (a tty may write less). */
static void write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return;
        p += w;
        n -= (size_t)w;
    }
}

static const char *const AXIS[LEP_AXES] = { "Fx", "Fy", "Fz", "Mx", "My", "Mz" };

void cli_watch_draw(int fd, const cli_watch_view *v, int cols, int rows)
{
    static screen s;
    char model[4 * LEP_MODEL_LEN + 1], serial[4 * LEP_SERIAL_LEN + 1];
    char firmware[4 * LEP_FIRMWARE_LEN + 1];
    const lep_session_meta *m = &v->meta;
    const lep_session_health_info *h = &v->health;
    int i, bw;

    s.used = 0;
    s.line = 0;
    s.cols = cols < 1 ? 1 : (cols > 400 ? 400 : cols);
    s.rows = rows < 1 ? 1 : rows;
    puts_s(&s, "\033[H");
    if (cols < 40 || rows < 17) {
        line(&s, "too small: %dx%d, need 40x17 (q quits)", cols, rows);
        puts_s(&s, "\033[J");
        write_all(fd, s.buf, s.used);
        return;
    }
    cli_safe_text(m->info.model, model, sizeof model);
    cli_safe_text(m->info.serial, serial, sizeof serial);
    cli_safe_text(m->info.firmware, firmware, sizeof firmware);
    line(&s, "leptrino watch  %s  serial %s  firmware %s  %s%s", model, serial, firmware, m->port,
         m->sim ? " (virtual)" : "");
    line(&s, "rated %g %g %g N, %g %g %g N m   filter %s   low-pass %s", (double)m->rated.axis[0],
         (double)m->rated.axis[1], (double)m->rated.axis[2], (double)m->rated.axis[3],
         (double)m->rated.axis[4], (double)m->rated.axis[5], m->sensor_filter_label,
         v->lowpass_text);
    line(&s, "%s", "");
    /* "  Fx  -123.456 N   " = 19 columns, then the bar, then " -100.0 %" */
    bw = cols - 19 - 10;
    if (bw > 121)
        bw = 121;
    if (bw % 2 == 0)
        bw--;
    for (i = 0; i < LEP_AXES; ++i) {
        char b[128];
        double rated = (double)m->rated.axis[i];
        double f = rated > 0.0 ? v->si[i] / rated : 0.0;
        bool over = (v->overload_axes & (1u << i)) != 0;
        bar(b, bw, v->have_sample ? f : 0.0);
        if (!v->have_sample)
            line(&s, "  %s  %9s %-3s %s", AXIS[i], "-", i < 3 ? "N" : "N m", b);
        else
            line(&s, "%s  %s  %9.3f %-3s %s %6.1f %%%s", over ? "\033[7m" : "", AXIS[i], v->si[i],
                 i < 3 ? "N" : "N m", b, 100.0 * f, over ? "\033[0m" : "");
    }
    line(&s, "%s", "");
    if (!v->have_sample)
        line(&s, "status    waiting for data");
    else
        line(&s, "status    %s%s%s%s", v->status == 0 && v->overload_axes == 0 ? "ok" : "",
             (v->status & LEP_STATUS_OVERLOAD) != 0 || v->overload_axes != 0 ? "OVERLOAD " : "",
             (v->status & LEP_STATUS_CALIBRATION) != 0 ? "CALIBRATION-DATA-ERROR " : "",
             (v->status & LEP_STATUS_SENSOR_FAULT) != 0 ? "SENSOR-FAULT" : "");
    line(&s, "rate      %.1f Hz now, %.1f Hz mean, nominal %.0f Hz%s", h->recent_hz, h->measured_hz,
         h->nominal_hz, h->shortfall ? "  SHORTFALL" : "");
    line(&s,
         "counts    %llu samples  %llu errors  %llu gaps (%llu lost)  %llu overloads  "
         "%llu reconnects",
         (unsigned long long)h->received, (unsigned long long)h->errors,
         (unsigned long long)h->gaps, (unsigned long long)h->lost, (unsigned long long)h->overloads,
         (unsigned long long)h->reconnects);
    if (m->payload.mass_kg > 0.0)
        line(&s, "tare      %-12s payload %g kg at %g %g %g m, gravity %g %g %g m/s^2",
             v->taring  ? "averaging..."
             : m->tared ? "on"
                        : "off",
             m->payload.mass_kg, m->payload.com_m[0], m->payload.com_m[1], m->payload.com_m[2],
             m->gravity[0], m->gravity[1], m->gravity[2]);
    else
        line(&s, "tare      %s", v->taring ? "averaging..." : m->tared ? "on" : "off");
    line(&s, "last      %s", v->message);
    line(&s, "%s", "");
    line(&s, "keys      t tare   u untare   q quit");
    puts_s(&s, "\033[J");
    write_all(fd, s.buf, s.used);
}
