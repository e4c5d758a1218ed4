/* Options by name (OS layer): how a session and a virtual sensor are
 * configured from any language.
 *
 * An options handle (lep_options) holds every setting of a session
 * (lep_session_open) and of an in-process virtual sensor (lep_sim_start,
 * or a session opened with "sim" = 1). It starts at the defaults; each
 * option is set and read by its name, as an integer, a double, a list of
 * doubles or text. Every option is described once, in one table that front
 * ends read to build their command lines and help (lep_option_* below): the
 * leptrino tool's --NAME options, leptrino-sim's, Python's keyword arguments
 * and the Rust builder all come from it. Adding an option adds a row: no
 * layout changes, nothing to mirror.
 *
 * Names are dash-separated ("data-timeout", "sim-rate"); an underscore
 * matches a dash ("data_timeout"), so keyword arguments map directly. The
 * virtual sensor's options all begin with "sim-".
 *
 * Types (lep_option_type) and the setters each accepts:
 *   FLAG     0 or 1: _set_int; text "1", "0", "true", "false"
 *   INT      an integer in [min, max]: _set_int; text in decimal
 *   DOUBLE   a finite number in [min, max] (or (min, max] when
 *            lep_option_min_exclusive): _set_double, _set_int; text
 *   STRING   text of min..max bytes: text only (a path, a serial number)
 *   CHOICE   one of lep_option_choice(i, 0..): text only
 *   NUMBERS  a fixed count (lep_option_numbers) of finite numbers, each in
 *            [min, max]: _set_doubles; text "a,b,c"
 * lep_options_set (text) accepts every type; getters work alike:
 * _get_int for FLAG and INT, _get_double for INT and DOUBLE, _get_doubles for
 * NUMBERS (and DOUBLE as one number), _get (text) for all.
 *
 * Errors: LEP_E_ARG for a NULL handle or name, an unknown name, a value out
 * of range or not of the option's type; a one-line message naming the option
 * and what it allows goes into err[0..errlen) when err is not NULL (e.g.
 * "lowpass '900': expected a number from 0 to 1000", "unknown option
 * 'lowpas'"). On an error nothing changes.
 *
 * Text results (lep_options_get, lep_session_info, ...) follow one rule:
 * the text and a NUL are written into buf[0..cap) when they fit; *len (when
 * not NULL) always gets the text's length without the NUL; LEP_E_BUFFER
 * when cap <= that length (buf then holds "" if cap > 0). Call with buf NULL
 * and cap 0 to ask how much room is needed.
 *
 * Ownership and threads: a handle belongs to its caller, who frees it with
 * lep_options_free; opening a session or starting a virtual sensor copies
 * what they need, so the handle may be changed or freed at once after. A
 * handle is not thread-safe: one thread at a time. The table functions are
 * re-entrant, never block and return static strings valid for the life of
 * the program. */
#ifndef LEPTRINO_OPTIONS_H
#define LEPTRINO_OPTIONS_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lep_options lep_options;

enum lep_option_type {
    LEP_OPT_FLAG = 0,
    LEP_OPT_INT = 1,
    LEP_OPT_DOUBLE = 2,
    LEP_OPT_STRING = 3,
    LEP_OPT_CHOICE = 4,
    LEP_OPT_NUMBERS = 5
};

/* Where an option applies (lep_option_scope). */
enum lep_option_scope {
    LEP_SCOPE_SESSION = 1, /* read when a session opens */
    LEP_SCOPE_LIVE = 2,    /* ... and may also be set on an open session (lep_session_set) */
    LEP_SCOPE_SIM = 3      /* the virtual sensor's ("sim-..."), read when it starts */
};

/* A new handle holding every option's default, or NULL when out of memory. */
LEP_API lep_options *lep_options_new(void);
/* A copy of o (NULL when o is NULL or out of memory). */
LEP_API lep_options *lep_options_copy(const lep_options *o);
/* Free a handle. NULL is fine. */
LEP_API void lep_options_free(lep_options *o);

/* Set an option from text (value NULL sets a FLAG to 1). */
LEP_API int lep_options_set(lep_options *o, const char *name, const char *value, char *err,
                            size_t errlen);
LEP_API int lep_options_set_int(lep_options *o, const char *name, int64_t value, char *err,
                                size_t errlen);
LEP_API int lep_options_set_double(lep_options *o, const char *name, double value, char *err,
                                   size_t errlen);
/* n must equal lep_option_numbers() of the option (1 for a DOUBLE). */
LEP_API int lep_options_set_doubles(lep_options *o, const char *name, const double *values,
                                    size_t n, char *err, size_t errlen);

/* The value as text that lep_options_set accepts (flags "1"/"0"; "" for an
 * unset STRING). See the text rule above. LEP_E_ARG: NULL o or name, unknown
 * name. */
LEP_API int lep_options_get(const lep_options *o, const char *name, char *buf, size_t cap,
                            size_t *len);
/* LEP_E_ARG also when the option is not of a type the getter reads, or when
 * an integer does not fit (sim-seed beyond 2^63 - 1: read it as text). */
LEP_API int lep_options_get_int(const lep_options *o, const char *name, int64_t *out);
LEP_API int lep_options_get_double(const lep_options *o, const char *name, double *out);
/* Writes min(cap, count) numbers; *n (when not NULL) gets the count. */
LEP_API int lep_options_get_doubles(const lep_options *o, const char *name, double *out, size_t cap,
                                    size_t *n);

/* Check how the options combine (what each setter cannot see alone:
 * overload duration below its period, reopen needs a link, ...): the one
 * validation lep_session_open and lep_sim_start run. LEP_OK or LEP_E_ARG
 * with one line in err. Does not look at files or ports. */
LEP_API int lep_options_check(const lep_options *o, char *err, size_t errlen);

/* ---- The table: one row per option ---- */

/* Number of rows. */
LEP_API size_t lep_option_count(void);
/* The row of name (any accepted spelling), or LEP_E_ARG (unknown, NULL). */
LEP_API int lep_option_index(const char *name);
/* The row's name ("data-timeout"), or NULL past the end. */
LEP_API const char *lep_option_name(size_t i);
/* enum lep_option_type, or LEP_E_ARG past the end. */
LEP_API int lep_option_type(size_t i);
/* enum lep_option_scope, or LEP_E_ARG past the end. */
LEP_API int lep_option_scope(size_t i);
/* The argument's name for help ("HZ", "PATH", "M,CX,CY,CZ"); "" for flags. */
LEP_API const char *lep_option_arg(size_t i);
/* One line of help, no trailing period, without range or default. */
LEP_API const char *lep_option_help(size_t i);
/* The default as text that lep_options_set accepts; "" when the option is
 * off or empty by default (flags, paths). */
LEP_API const char *lep_option_default(size_t i);
/* Numbers: the allowed range; STRING: its length in bytes; others 0. */
LEP_API double lep_option_min(size_t i);
LEP_API double lep_option_max(size_t i);
/* 1 when the value must be > min (not >=), else 0. */
LEP_API int lep_option_min_exclusive(size_t i);
/* How many numbers the option holds: NUMBERS its count, INT and DOUBLE 1,
 * others 0. */
LEP_API size_t lep_option_numbers(size_t i);
/* CHOICE: the j-th allowed name, NULL past the last; NULL for other types. */
LEP_API const char *lep_option_choice(size_t i, size_t j);

#ifdef __cplusplus
}
#endif

#endif
