/* Host session, the port: open it, the start-up recovery and identity of the
 * sensor on it, close it; and whether a reconnect found the same sensor. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "session_priv.h"

int lep_priv_session_connect(lep_session *s, char *err, size_t errlen)
{
    lep_product_info info;
    int rc = lep_serial_open(s->opt.port, &s->serial, err, errlen);
    if (rc != LEP_OK) {
        s->serial = NULL;
        return rc;
    }
    rc = lep_serial_client_init(&s->client, s->serial);
    if (rc == LEP_OK)
        rc = lep_client_set_timeout(&s->client, s->opt.timeout_ms);
    if (rc == LEP_OK)
        rc = lep_client_set_retries(&s->client, s->opt.retries);
    if (rc == LEP_OK)
        rc =
            lep_client_sync(&s->client, s->opt.sync_quiet_ms > 0 ? s->opt.sync_quiet_ms : 1, &info);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "%s: start-up recovery (stop, drain, product info): %s",
                         s->opt.port, lep_strerror(rc));
        lep_priv_session_disconnect(s);
        return rc;
    }
    pthread_mutex_lock(&s->mu); /* the metadata may be read from another thread */
    s->info = info;
    pthread_mutex_unlock(&s->mu);
    s->conn = CONN_UP;
    return LEP_OK;
}

void lep_priv_session_disconnect(lep_session *s)
{
    lep_serial_close(s->serial);
    s->serial = NULL;
    s->conn = CONN_DOWN;
}

int lep_session_get_serial_info(const lep_session *s, lep_serial_info *out)
{
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (s == NULL || out == NULL)
        return LEP_E_ARG;
    if (s->conn != CONN_UP)
        return LEP_E_DISCONNECTED;
    lep_serial_get_latency_info(s->serial, out);
    return LEP_OK;
}

bool lep_priv_session_same_sensor(lep_session *s)
{
    bool same;
    pthread_mutex_lock(&s->mu);
    same = strcmp(s->info.model, s->first_info.model) == 0 &&
           strcmp(s->info.serial, s->first_info.serial) == 0;
    pthread_mutex_unlock(&s->mu);
    return same;
}
