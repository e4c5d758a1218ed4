/* Port discovery: serial ports with by-id names and USB identity. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"
#include "serial_list.h"

static void copy_str(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

/* First line of a small text file, trailing space removed; 0 on success. */
static int read_line(const char *dir, const char *name, char *out, size_t cap)
{
    char path[PATH_MAX];
    FILE *f;
    size_t n;
    int k = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (k < 0 || (size_t)k >= sizeof path)
        return -1;
    f = fopen(path, "re");
    if (f == NULL)
        return -1;
    if (fgets(out, (int)cap, f) == NULL) {
        fclose(f);
        return -1;
    }
    fclose(f);
    n = strlen(out);
    while (n > 0 && (out[n - 1] == '\n' || out[n - 1] == '\r' || out[n - 1] == ' '))
        out[--n] = '\0';
    return 0;
}

static int read_hex16(const char *dir, const char *name, uint16_t *v)
{
    char buf[16];
    char *end;
    unsigned long x;
    if (read_line(dir, name, buf, sizeof buf) != 0)
        return -1;
    x = strtoul(buf, &end, 16);
    if (end == buf || x > 0xFFFFu)
        return -1;
    *v = (uint16_t)x;
    return 0;
}

static bool is_likely_sensor(uint16_t vid, uint16_t pid)
{
    return (vid == 0x0483 && pid == 0x5740) || (vid == 0x0403 && pid == 0x6001);
}

/* Walk up from the tty's device directory to the USB device that carries
 * idVendor/idProduct, and fill the USB fields of p. */
static void usb_identity(const char *devdir, lep_port_info *p)
{
    char dir[PATH_MAX];
    int depth;
    if (realpath(devdir, dir) == NULL)
        return;
    for (depth = 0; depth < 8; depth++) {
        char *slash;
        uint16_t vid, pid;
        if (read_hex16(dir, "idVendor", &vid) == 0 && read_hex16(dir, "idProduct", &pid) == 0) {
            char product[64] = "", maker[64] = "";
            p->vid = vid;
            p->pid = pid;
            (void)read_line(dir, "product", product, sizeof product);
            (void)read_line(dir, "manufacturer", maker, sizeof maker);
            if (maker[0] && product[0])
                snprintf(p->description, sizeof p->description, "%s %s", maker, product);
            else
                copy_str(p->description, sizeof p->description, product[0] ? product : maker);
            p->likely_sensor = is_likely_sensor(vid, pid);
            return;
        }
        slash = strrchr(dir, '/');
        if (slash == NULL || slash == dir)
            return;
        *slash = '\0';
    }
}

/* Legacy placeholders (ttyS0..31 of the 8250 driver with no hardware) sit
 * on the platform bus; real ports are on usb, pci, pnp, amba, ... */
static bool placeholder(const char *devdir, const char *name)
{
    char sub[PATH_MAX];
    int k = snprintf(sub, sizeof sub, "%s/subsystem", devdir);
    char real[PATH_MAX];
    const char *base;
    if (strncmp(name, "ttyS", 4) != 0)
        return false;
    if (k < 0 || (size_t)k >= sizeof sub || realpath(sub, real) == NULL)
        return false;
    base = strrchr(real, '/');
    return base != NULL && strcmp(base + 1, "platform") == 0;
}

static void find_by_id(const char *by_id_dir, const char *dev_path, char *out, size_t cap)
{
    DIR *d = opendir(by_id_dir);
    struct dirent *e;
    char target[PATH_MAX];
    if (d == NULL)
        return;
    if (realpath(dev_path, target) == NULL)
        copy_str(target, sizeof target, dev_path);
    while ((e = readdir(d)) != NULL) {
        char link[PATH_MAX], real[PATH_MAX];
        int k;
        if (e->d_name[0] == '.')
            continue;
        k = snprintf(link, sizeof link, "%s/%s", by_id_dir, e->d_name);
        if (k < 0 || (size_t)k >= sizeof link)
            continue;
        if (realpath(link, real) != NULL && strcmp(real, target) == 0) {
            copy_str(out, cap, link);
            break;
        }
    }
    closedir(d);
}

static int by_path(const void *a, const void *b)
{
    const lep_port_info *x = a, *y = b;
    return strcmp(x->path, y->path);
}

int lep_priv_serial_list_in(const lep_serial_roots *roots, lep_port_info *out, size_t max,
                            size_t *n)
{
    DIR *d;
    struct dirent *e;
    size_t count = 0;
    if (n == NULL || roots == NULL || (out == NULL && max > 0))
        return LEP_E_ARG;
    *n = 0;
    d = opendir(roots->sys_class_tty);
    if (d == NULL)
        return LEP_OK; /* no sysfs: nothing to list */
    while ((e = readdir(d)) != NULL) {
        char devdir[PATH_MAX];
        lep_port_info p;
        struct stat st;
        int k;
        if (e->d_name[0] == '.')
            continue;
        k = snprintf(devdir, sizeof devdir, "%s/%s/device", roots->sys_class_tty, e->d_name);
        if (k < 0 || (size_t)k >= sizeof devdir || stat(devdir, &st) != 0)
            continue; /* virtual terminals and ptys have no device */
        if (placeholder(devdir, e->d_name))
            continue;
        memset(&p, 0, sizeof p);
        k = snprintf(p.path, sizeof p.path, "%s/%s", roots->dev, e->d_name);
        if (k < 0 || (size_t)k >= sizeof p.path)
            continue;
        usb_identity(devdir, &p);
        find_by_id(roots->by_id, p.path, p.by_id, sizeof p.by_id);
        if (count < max)
            out[count] = p;
        count++;
    }
    closedir(d);
    if (out != NULL)
        qsort(out, count < max ? count : max, sizeof *out, by_path);
    *n = count;
    return LEP_OK;
}

#if defined(__APPLE__)
/* macOS: the call-out devices /dev/cu.*; no USB identity from here. */
static int list_darwin(lep_port_info *out, size_t max, size_t *n)
{
    DIR *d = opendir("/dev");
    struct dirent *e;
    size_t count = 0;
    if (n == NULL || (out == NULL && max > 0))
        return LEP_E_ARG;
    *n = 0;
    if (d == NULL)
        return LEP_E_IO;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, "cu.", 3) != 0)
            continue;
        if (count < max) {
            memset(&out[count], 0, sizeof out[count]);
            snprintf(out[count].path, sizeof out[count].path, "/dev/%s", e->d_name);
            out[count].likely_sensor = strstr(e->d_name, "usbmodem") != NULL;
        }
        count++;
    }
    closedir(d);
    if (out != NULL)
        qsort(out, count < max ? count : max, sizeof *out, by_path);
    *n = count;
    return LEP_OK;
}
#endif

int lep_serial_list(lep_port_info *out, size_t max, size_t *n)
{
#if defined(__APPLE__)
    return list_darwin(out, max, n);
#else
    static const lep_serial_roots roots = { "/sys/class/tty", "/dev/serial/by-id", "/dev" };
    return lep_priv_serial_list_in(&roots, out, max, n);
#endif
}

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
