/* The flat parts of leptrino/serial.h that are the same on every OS: the
 * port list handle over lep_serial_list (which serial_list_posix.c or
 * serial_list_win32.c gives), and the latency settings as ints over
 * lep_serial_get_latency_info (serial_posix.c or serial_win32.c). */
#include <stdlib.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"

/* ---- the port list handle (leptrino/serial.h) ---- */

struct lep_port_list {
    size_t n;
    lep_port_info *ports;
};

int lep_port_list_new(lep_port_list **out)
{
    lep_port_list *l;
    size_t want = 0, cap = 0;
    int rc;
    if (out == NULL)
        return LEP_E_ARG;
    *out = NULL;
    l = calloc(1, sizeof *l);
    if (l == NULL)
        return LEP_E_IO;
    /* Ports may come and go between two scans: grow until one scan fits. */
    for (;;) {
        rc = lep_serial_list(l->ports, cap, &want);
        if (rc != LEP_OK) {
            free(l->ports);
            free(l);
            return rc;
        }
        if (want <= cap)
            break;
        cap = want + 8u;
        free(l->ports);
        l->ports = calloc(cap, sizeof *l->ports);
        if (l->ports == NULL) {
            free(l);
            return LEP_E_IO;
        }
    }
    l->n = want;
    *out = l;
    return LEP_OK;
}

void lep_port_list_free(lep_port_list *l)
{
    if (l == NULL)
        return;
    free(l->ports);
    free(l);
}

size_t lep_port_list_count(const lep_port_list *l)
{
    return l != NULL ? l->n : 0u;
}

static const lep_port_info *port_at(const lep_port_list *l, size_t i)
{
    return l != NULL && i < l->n ? &l->ports[i] : NULL;
}

const char *lep_port_list_path(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL ? p->path : "";
}

const char *lep_port_list_by_id(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL ? p->by_id : "";
}

const char *lep_port_list_description(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL ? p->description : "";
}

int lep_port_list_vid(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL ? p->vid : 0;
}

int lep_port_list_pid(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL ? p->pid : 0;
}

int lep_port_list_likely_sensor(const lep_port_list *l, size_t i)
{
    const lep_port_info *p = port_at(l, i);
    return p != NULL && p->likely_sensor ? 1 : 0;
}

int lep_serial_get_info(const lep_serial *s, int *out, size_t n)
{
    lep_serial_info info;
    int f[LEP_SERIAL_INFO_COUNT];
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    lep_serial_get_latency_info(s, &info);
    f[LEP_SERIAL_LOW_LATENCY] = info.low_latency ? 1 : 0;
    f[LEP_SERIAL_FTDI_LATENCY_MS] = info.ftdi_latency_ms;
    f[LEP_SERIAL_FTDI_LOWERED] = info.ftdi_lowered ? 1 : 0;
    memcpy(out, f, sizeof(int) * (n < LEP_SERIAL_INFO_COUNT ? n : LEP_SERIAL_INFO_COUNT));
    return LEP_OK;
}
