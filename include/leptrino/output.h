/* Recording writer (OS layer): the one writer of CSV and JSON-lines
 * recordings that every front end uses, so that the same samples give the
 * same bytes from the C tool and from Python.
 *
 * A writer owns a file descriptor (a path it opened, or one it was given,
 * e.g. 1 for standard output) and a buffer; it uses no FILE*, so FFI callers
 * pass paths, fds, numbers and flat arrays only. Rows come from the arrays
 * lep_session_read fills, events from the arrays lep_session_next_event
 * fills; several sensors can share one file (a sensor column) on one time
 * base.
 *
 * The bytes (docs/session.md has the reference):
 *  - CSV: one `# leptrino-metadata: {json}` comment line per sensor, then a
 *    header line, then one line per sample. Events are comment lines:
 *      # gap from=T to=T lost=N reason=gap|disconnected|no-data
 *      # disconnected at=T reason=disconnected|no-data
 *      # tare at=T fx=C fy=C fz=C mx=C my=C mz=C
 *      # overload begin at=T axes=A status=S  /  # overload end at=T
 *    (with a sensor column, `sensor=NAME` follows the event word).
 *  - JSON lines: a first {"metadata": {...}} object per sensor, then one
 *    object per sample with the same keys as the CSV header, and events as
 *    {"event":"gap","from":T,"to":T,"lost":N,"reason":"..."} and so on.
 *  - Columns, in this order: time (t_s | t_mono_s | t_utc_s), sensor,
 *    fx_counts..mz_counts, fx_zeroed_counts..mz_zeroed_counts,
 *    fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm, status, flags, seq.
 *  - Numbers: times %.6f (s), raw counts as integers, zeroed counts %.3f,
 *    SI values %.6f, status/flags/seq as unsigned integers; C locale.
 *
 * Not thread-safe: one thread uses a writer. Errors are LEP_E_* codes. */
#ifndef LEPTRINO_OUTPUT_H
#define LEPTRINO_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "session.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Column bits (the columns argument of lep_output_open). */
enum lep_output_column {
    LEP_COL_RAW = 0x01,    /* fx_counts..mz_counts */
    LEP_COL_ZEROED = 0x02, /* fx_zeroed_counts..mz_zeroed_counts */
    LEP_COL_SI = 0x04,     /* fx_N..mz_Nm */
    LEP_COL_STATUS = 0x08, /* status */
    LEP_COL_FLAGS = 0x10,  /* flags (LEP_SF_*) */
    LEP_COL_SEQ = 0x20,    /* seq (the reserved bytes) */
    LEP_COL_SENSOR = 0x40, /* sensor (the name given to lep_output_add_*) */
    LEP_COL_DEFAULT = 0x0C /* LEP_COL_SI | LEP_COL_STATUS */
};

enum lep_output_format { LEP_OUTPUT_CSV = 0, LEP_OUTPUT_JSONL = 1 };

enum lep_output_time {
    LEP_TIME_REL = 0,  /* t_s: seconds since t0_mono (default: the first sensor's start) */
    LEP_TIME_MONO = 1, /* t_mono_s: the monotonic clock */
    LEP_TIME_UTC = 2   /* t_utc_s: seconds since 1970-01-01 UTC */
};

typedef struct lep_output lep_output;

/* Create path for writing: format (enum lep_output_format), time (enum
 * lep_output_time), columns (LEP_COL_* bits; the time column is always
 * there), t0_mono (the origin of t_s; 0: start_mono of the first sensor
 * added). An existing file is refused (LEP_E_ARG, "PATH: already exists
 * ...", the file untouched) unless overwrite is 1. NULL or "-" is standard
 * output. Other failures: LEP_E_ARG for a bad format, time or columns,
 * LEP_E_NOT_FOUND (no such directory), LEP_E_PERMISSION, LEP_E_IO; err gets
 * a one-line message naming the path. */
LEP_API int lep_output_open(const char *path, int format, int time, int columns, double t0_mono,
                            int overwrite, lep_output **out, char *err, size_t errlen);

/* Write to fd (not closed by lep_output_close). LEP_E_ARG for fd < 0. */
LEP_API int lep_output_open_fd(int fd, int format, int time, int columns, double t0_mono,
                               lep_output **out, char *err, size_t errlen);

/* Add a sensor before the first write; returns its index (>= 0) for
 * lep_output_write, or LEP_E_ARG / LEP_E_STATE (after the first write).
 * name: the sensor column's value (copied; NULL = "sensor<index>").
 * _add_session reads the session's metadata when the header is written (at
 * the first lep_output_write or at close): the session must stay open until
 * then. _add_sensor takes the metadata JSON object (copied) and the
 * session's start_mono, for writing a recording after its session closed. */
LEP_API int lep_output_add_session(lep_output *w, lep_session *s, const char *name);
LEP_API int lep_output_add_sensor(lep_output *w, const char *name, const char *metadata_json,
                                  double start_mono);

/* Write n rows of sensor `sensor` from the arrays of lep_session_read (the
 * same layout; t_mono is needed, t_utc for LEP_TIME_UTC, and the arrays of
 * the chosen columns: LEP_E_ARG otherwise), and nev events from `events`:
 * nev rows of ev_fields doubles each, as lep_session_next_event fills them
 * (ev_fields >= LEP_EVF_TARE + 6; the caller's LEP_EVF_COUNT), written where
 * they belong: an event whose sample field is k comes just before that
 * sensor's row k (rows are numbered per sensor from 0 as they are written),
 * events beyond the last row after it. Writes the header first if not yet
 * done. When the bytes reach the fd: the header (metadata lines) before any
 * row; into a pipe, a terminal or any fd that is not a regular file, at the
 * end of every call; into a regular file, at the end of the call that finds
 * the oldest unwritten row 100 ms old or more (and when the buffer fills, at
 * lep_output_flush and at close): a writer that calls lep_output_flush when
 * its source goes quiet loses at most the last 100 ms to a crash. LEP_E_IO
 * when a write failed (lep_output_errno says why; later calls fail the same
 * way). */
LEP_API int lep_output_write(lep_output *w, int sensor, size_t n, const double *t_mono,
                             const double *t_utc, const double *si, const int16_t *raw,
                             const double *zeroed, const uint8_t *status, const uint8_t *flags,
                             const uint16_t *seq, const double *events, size_t nev,
                             size_t ev_fields);

/* Write buffered bytes now (nothing to do, no system call, when none are). */
LEP_API int lep_output_flush(lep_output *w);

/* errno of the first failed write (EPIPE when a pipe's reader went away), 0 if none. */
LEP_API int lep_output_errno(const lep_output *w);

/* Write the header if nothing was written yet, flush, close the file when
 * lep_output_open opened it, free. Returns LEP_OK or the first write error.
 * NULL is fine. */
LEP_API int lep_output_close(lep_output *w);

#ifdef __cplusplus
}
#endif

#endif
