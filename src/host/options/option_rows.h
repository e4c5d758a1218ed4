/* One option table engine: rows that describe a member of a struct (its
 * name, type, range, default, help), parsed from text, range-checked and
 * written back as text. The virtual sensor's table (sim_options.c) and the
 * session's (session_options.c) are rows of this kind; options.c puts them
 * behind the public options handle. Re-entrant: rows are constant. */
#ifndef LEPTRINO_OPTION_ROWS_H
#define LEPTRINO_OPTION_ROWS_H

#include <stdbool.h>
#include <stddef.h>

#include "struct_api.h"

/* How a row's value is stored in its struct. */
enum opt_store {
    S_BOOL,     /* bool */
    S_INT,      /* int */
    S_UNSIGNED, /* unsigned */
    S_U8,       /* uint8_t */
    S_U64,      /* uint64_t */
    S_DOUBLE,   /* double */
    S_CHARS,    /* char[size], NUL-terminated */
    S_DOUBLES   /* double[size / sizeof(double)] */
};

/* Extra checks of a text value beyond its length. */
enum opt_text_rule { T_ANY, T_DIGITS, T_PRINTABLE, T_MODEL };

typedef struct opt_row {
    lep_sim_option_info info; /* first: lep_sim_option_at returns &row.info */
    const char *public_name;  /* the name in the public table ("sim-rate", "lowpass") */
    int scope;                /* enum lep_option_scope */
    const char *field;        /* the struct member's name (an accepted alias) */
    size_t offset, size;
    enum opt_store store;
    enum opt_text_rule rule;
} opt_row;

/* The row of rows[0..n) called name: its dash-separated name, the same with
 * underscores, its public name or its field name. NULL when none. */
const opt_row *lep_priv_row_find(const opt_row *rows, size_t n, const char *name);

/* Check the member of base that r describes (range, text rules). */
int lep_priv_row_check(const void *base, const opt_row *r, char *err, size_t errlen);

/* Parse value for r and store it in base (nothing changes on an error: the
 * message names the option by label, e.g. its public name). */
int lep_priv_row_set(void *base, const opt_row *r, const char *label, const char *value, char *err,
                     size_t errlen);

/* The member as text that lep_priv_row_set accepts; *len gets the length
 * needed (the text rule of leptrino/options.h). */
int lep_priv_row_get(const void *base, const opt_row *r, char *buf, size_t cap, size_t *len);

/* The text rule of leptrino/options.h: text and a NUL into buf[0..cap) when
 * they fit, *len (when not NULL) its length, else LEP_E_BUFFER and "". */
int lep_priv_text_out(const char *text, char *buf, size_t cap, size_t *len);

/* Range text for messages ("a number from 0 to 4"). */
void lep_priv_row_range(const opt_row *r, char *buf, size_t cap);

/* Whether v is in r's range. */
bool lep_priv_row_in_range(const opt_row *r, double v);

/* Member pointers. */
void *lep_priv_row_member(void *base, const opt_row *r);
const void *lep_priv_row_cmember(const void *base, const opt_row *r);

#endif
