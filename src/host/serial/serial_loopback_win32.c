/* Windows: in-process loopback ports (serial_loopback.h), the list of them
 * and the host's reads and writes on one.
 *
 * Sockets (Microsoft docs, Winsock): the listed socket is non-blocking
 * (ioctlsocket FIONBIO, set by the sensor); a read is recv of what is there,
 * and with nothing there WSAPoll for POLLRDNORM up to what is left of the
 * timeout, then recv again; recv returning 0 (the sensor closed its end: a
 * hang-up) or failing is LEP_E_DISCONNECTED from then on. A write is send,
 * and WSAPoll for POLLWRNORM while the sensor does not read, for at most
 * WRITE_STALL_MS as the COM port's WriteTotalTimeoutConstant. Opening a port
 * first reads out and drops what an earlier host left unread (PurgeComm on a
 * COM port). Every listed socket holds its own WSAStartup reference, so a
 * sensor that stops (WSACleanup) never closes a socket a host still holds. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <winsock2.h>
#include <windows.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "serial_loopback.h"

#define WRITE_STALL_MS 2000
#define SLOTS 32
#define NAME_MAX_LEN 260

typedef struct {
    char name[NAME_MAX_LEN];
    SOCKET sock;
    const void *owner;
    bool used;   /* the slot holds a socket */
    bool listed; /* its sensor lists it (opens find it) */
    bool open;   /* a host has it open */
} slot;

static slot slots[SLOTS];
static SRWLOCK slots_lock = SRWLOCK_INIT;

struct lep_loopback_port {
    int slot;
    SOCKET sock;
    bool dead;
};

/* Close a slot's socket and free it (under the lock). */
static void slot_free(slot *e)
{
    closesocket(e->sock);
    (void)WSACleanup();
    memset(e, 0, sizeof *e);
    e->sock = INVALID_SOCKET;
}

static slot *find_listed(const char *name)
{
    int i;
    for (i = 0; i < SLOTS; i++)
        if (slots[i].used && slots[i].listed && strcmp(slots[i].name, name) == 0)
            return &slots[i];
    return NULL;
}

int lep_priv_loopback_add(const char *name, SOCKET host_end, const void *owner)
{
    WSADATA wsa;
    int i, rc = LEP_E_BUSY;
    if (strlen(name) >= NAME_MAX_LEN || WSAStartup(MAKEWORD(2, 2), &wsa) != 0)
        return LEP_E_ARG;
    AcquireSRWLockExclusive(&slots_lock);
    if (find_listed(name) == NULL) {
        for (i = 0; i < SLOTS && slots[i].used; i++) {
        }
        if (i < SLOTS) {
            memcpy(slots[i].name, name, strlen(name) + 1);
            slots[i].sock = host_end;
            slots[i].owner = owner;
            slots[i].used = slots[i].listed = true;
            slots[i].open = false;
            rc = LEP_OK;
        } else {
            rc = LEP_E_IO;
        }
    }
    ReleaseSRWLockExclusive(&slots_lock);
    if (rc != LEP_OK)
        (void)WSACleanup();
    return rc;
}

bool lep_priv_loopback_listed(const char *name)
{
    bool listed;
    AcquireSRWLockShared(&slots_lock);
    listed = find_listed(name) != NULL;
    ReleaseSRWLockShared(&slots_lock);
    return listed;
}

void lep_priv_loopback_remove(const void *owner)
{
    int i;
    AcquireSRWLockExclusive(&slots_lock);
    for (i = 0; i < SLOTS; i++) {
        if (!slots[i].used || !slots[i].listed || slots[i].owner != owner)
            continue;
        slots[i].listed = false;
        if (!slots[i].open)
            slot_free(&slots[i]);
    }
    ReleaseSRWLockExclusive(&slots_lock);
}

/* Read out and drop what is queued (what an earlier host left unread). */
static void purge(SOCKET sock)
{
    char junk[512];
    while (recv(sock, junk, (int)sizeof junk, 0) > 0) {
    }
}

int lep_priv_loopback_open(const char *name, lep_loopback_port **out, char *err, size_t errlen)
{
    lep_loopback_port *p;
    slot *e;
    int rc = LEP_OK;
    *out = NULL;
    p = calloc(1, sizeof *p);
    if (p == NULL) {
        lep_priv_set_err(err, errlen, "%s: out of memory", name);
        return LEP_E_IO;
    }
    AcquireSRWLockExclusive(&slots_lock);
    e = find_listed(name);
    if (e == NULL) {
        if (strncmp(name, LEP_LOOPBACK_PREFIX, sizeof LEP_LOOPBACK_PREFIX - 1) == 0) {
            lep_priv_set_err(err, errlen,
                             "%s: no such port (no virtual sensor of this program lists it: "
                             "hung up or stopped)",
                             name);
            rc = LEP_E_NOT_FOUND;
        }
    } else if (e->open) {
        lep_priv_set_err(err, errlen, "%s: in use (the virtual sensor's port is open already)",
                         name);
        rc = LEP_E_BUSY;
    } else {
        e->open = true;
        p->slot = (int)(e - slots);
        p->sock = e->sock;
        purge(p->sock);
        *out = p;
    }
    ReleaseSRWLockExclusive(&slots_lock);
    if (*out == NULL)
        free(p);
    return rc;
}

void lep_priv_loopback_close(lep_loopback_port *p)
{
    slot *e;
    if (p == NULL)
        return;
    AcquireSRWLockExclusive(&slots_lock);
    e = &slots[p->slot];
    e->open = false;
    if (!e->listed)
        slot_free(e);
    ReleaseSRWLockExclusive(&slots_lock);
    free(p);
}

static int gone(lep_loopback_port *p)
{
    p->dead = true;
    return LEP_E_DISCONNECTED;
}

/* WSAPoll on the port for events, at most ms (< 0: without end): 1 ready
 * (or hung up: the next call says), 0 not, -1 failed. */
static int wait_for(lep_loopback_port *p, short events, int ms)
{
    WSAPOLLFD f;
    int rc;
    f.fd = p->sock;
    f.events = events;
    f.revents = 0;
    rc = WSAPoll(&f, 1, ms);
    if (rc < 0)
        return -1;
    return rc > 0 ? 1 : 0;
}

int lep_priv_loopback_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    lep_loopback_port *p = user;
    int64_t deadline = 0;
    if (p == NULL || (buf == NULL && cap > 0))
        return LEP_E_ARG;
    if (p->dead)
        return LEP_E_DISCONNECTED;
    if (cap == 0)
        return 0;
    if (cap > (size_t)INT_MAX)
        cap = (size_t)INT_MAX;
    if (timeout_ms > 0)
        deadline = lep_priv_monotonic_ns() + (int64_t)timeout_ms * 1000000;
    for (;;) {
        int n = recv(p->sock, (char *)buf, (int)cap, 0), ms;
        if (n > 0)
            return n;
        if (n == 0 || WSAGetLastError() != WSAEWOULDBLOCK)
            return gone(p); /* the sensor hung up */
        if (timeout_ms == 0)
            return 0;
        ms = -1;
        if (timeout_ms > 0) {
            ms = lep_priv_ms_left(deadline);
            if (ms <= 0)
                return 0;
        }
        if (wait_for(p, POLLRDNORM, ms) < 0)
            return gone(p);
    }
}

int lep_priv_loopback_write(void *user, const uint8_t *data, size_t len)
{
    lep_loopback_port *p = user;
    int64_t deadline = lep_priv_monotonic_ns() + (int64_t)WRITE_STALL_MS * 1000000;
    size_t off = 0;
    if (p == NULL || (data == NULL && len > 0))
        return LEP_E_ARG;
    if (p->dead)
        return LEP_E_DISCONNECTED;
    while (off < len) {
        int chunk = (int)(len - off > 65536u ? 65536u : len - off);
        int n = send(p->sock, (const char *)data + off, chunk, 0), ms;
        if (n > 0) {
            off += (size_t)n;
            continue;
        }
        if (n < 0 && WSAGetLastError() != WSAEWOULDBLOCK)
            return gone(p);
        ms = lep_priv_ms_left(deadline);
        if (ms <= 0)
            return LEP_E_TIMEOUT; /* the sensor does not read */
        if (wait_for(p, POLLWRNORM, ms) < 0)
            return gone(p);
    }
    return LEP_OK;
}
