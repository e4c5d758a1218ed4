/* Host session, rows: processed samples waiting for lep_session_read (a ring
 * of two reads' worth), the newest held back while a hole is suspected, and
 * their delivery into the caller's batch. */
#include <string.h>

#include "session_priv.h"

void lep_priv_rows_clear(session_rows *r)
{
    r->head = r->len = 0;
    r->held = 0;
}

session_row *lep_priv_rows_slot(session_rows *r)
{
    if (r->len >= SESSION_ROWS)
        return NULL;
    return &r->pending[(r->head + r->len) % SESSION_ROWS];
}

void lep_priv_rows_push(session_rows *r)
{
    r->len++;
}

session_row *lep_priv_rows_back(session_rows *r, size_t back)
{
    return &r->pending[(r->head + r->len - 1u - back) % SESSION_ROWS];
}

void lep_priv_rows_append(lep_session_batch *b, const session_row *r)
{
    size_t i = b->n, k;
    if (b->t_mono != NULL)
        b->t_mono[i] = r->t_mono;
    if (b->t_utc != NULL)
        b->t_utc[i] = r->t_utc;
    if (b->raw != NULL)
        memcpy(&b->raw[i * LEP_AXES], r->raw, sizeof r->raw);
    if (b->zeroed != NULL)
        for (k = 0; k < LEP_AXES; k++)
            b->zeroed[i * LEP_AXES + k] = r->zeroed[k];
    if (b->si != NULL)
        for (k = 0; k < LEP_AXES; k++)
            b->si[i * LEP_AXES + k] = r->si[k];
    if (b->status != NULL)
        b->status[i] = r->status;
    if (b->flags != NULL)
        b->flags[i] = r->flags;
    if (b->seq != NULL)
        b->seq[i] = r->seq;
    b->n = i + 1u;
}

void lep_priv_rows_deliver(session_rows *r, lep_session_batch *b, double *first)
{
    while (r->len > r->held && b->n < b->cap) {
        const session_row *row = &r->pending[r->head];
        if (*first < 0.0)
            *first = row->t_mono;
        lep_priv_rows_append(b, row);
        r->head = (r->head + 1u) % SESSION_ROWS;
        r->len--;
    }
    if (r->len == 0)
        r->head = 0;
}
