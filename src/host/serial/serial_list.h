/* Private: port discovery under given roots (so tests can use a fake tree). */
#ifndef LEPTRINO_SERIAL_LIST_H
#define LEPTRINO_SERIAL_LIST_H

#include <stddef.h>

#include "leptrino/serial.h"
#include "struct_api.h"

typedef struct lep_serial_roots {
    const char *sys_class_tty; /* /sys/class/tty */
    const char *by_id;         /* /dev/serial/by-id */
    const char *dev;           /* /dev */
} lep_serial_roots;

/* lep_serial_list over the given roots. */
int lep_priv_serial_list_in(const lep_serial_roots *roots, lep_port_info *out, size_t max,
                            size_t *n);

#endif
