/* The options handle's layout and its two tables (private). */
#ifndef LEPTRINO_OPTIONS_PRIV_H
#define LEPTRINO_OPTIONS_PRIV_H

#include <stddef.h>

#include "option_rows.h"
#include "struct_api.h"

/* A serial path's room, NUL included (lep_session's port_buf too). */
#define LEP_PORT_PATH_SIZE 256u

struct lep_options {
    lep_session_options so; /* so.port points at port (or is NULL when port is "") */
    char port[LEP_PORT_PATH_SIZE];
};

/* The session's rows (offsets into struct lep_options) and the virtual
 * sensor's (offsets into lep_sim_options, i.e. into so.sim). */
const opt_row *lep_priv_session_rows(size_t *n);
const opt_row *lep_priv_sim_rows(size_t *n);

/* The row called name in either table, and the base its offsets apply to in
 * o (NULL o: just the row). NULL when unknown. */
const opt_row *lep_priv_options_find(const lep_options *o, const char *name, const void **base);

/* The session's checks of how its options combine (session.c): what
 * lep_session_open refuses, but for the port (opening tells about it). */
int lep_priv_session_options_check(const lep_session_options *o, char *err, size_t errlen);

/* Fill o from a session's options struct (port copied). */
void lep_priv_options_from(lep_options *o, const lep_session_options *so);

#endif
