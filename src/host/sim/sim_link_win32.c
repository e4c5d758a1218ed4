/* Virtual sensor on Windows: its port, the requests' wake-up channel, waiting
 * on both, the serving thread's start; instead of sim_pty.c and sim_link.c
 * (Windows has no pseudo-terminal).
 *
 * The port is a connected pair of TCP sockets on 127.0.0.1 (Microsoft docs,
 * Winsock: socket, bind to port 0, listen, connect, accept): the sensor keeps
 * one end, the other is listed under the port's name for the Win32 serial
 * backend (serial_loopback.h), which opens that name instead of a COM port.
 * The name is "sim:N", or the link option as given; it is listed again at a
 * reopen after a hang-up, so a host reconnects to the same name. A stranger
 * that connects to the listener first is refused: the accepted peer must be
 * our own connecting socket (getpeername against getsockname), and the
 * listener has SO_EXCLUSIVEADDRUSE. Both ends: TCP_NODELAY (a frame leaves at
 * once, not when Nagle's algorithm lets it), non-blocking, small buffers
 * (about a pty's, so a host that stops reading blocks the sensor as soon).
 *
 * Requests wake the serving thread through a UDP socket connected to itself
 * (WSAPoll waits on sockets only). Waiting is WSAPoll on both, to the same
 * absolute deadlines as the POSIX sensor, in whole milliseconds rounded up
 * (WSAPoll's resolution; the sensor then sends every sample that came due, so
 * the rate holds and no sample is lost). */
#include <stdio.h>
#include <string.h>
#include <winsock2.h>
#include <ws2tcpip.h>
#include <windows.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "serial_loopback.h"
#include "sim_priv.h"

/* About a Linux pty's buffer: a host that stops reading fills it soon. */
#define LOOP_BUF 4096

static volatile LONG port_count;

static SOCKET sock_of(uintptr_t v)
{
    return (SOCKET)v;
}

static void set_err_wsa(char *err, size_t errlen, const char *what)
{
    lep_priv_set_err(err, errlen, "virtual sensor: cannot %s: Winsock error %d", what,
                     WSAGetLastError());
}

static int non_blocking(SOCKET k)
{
    u_long on = 1;
    return ioctlsocket(k, (long)FIONBIO, &on) == 0 ? 0 : -1;
}

static void loopback_addr(struct sockaddr_in *a)
{
    memset(a, 0, sizeof *a);
    a->sin_family = AF_INET;
    a->sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a->sin_port = 0;
}

static bool same_addr(const struct sockaddr_in *a, const struct sockaddr_in *b)
{
    return a->sin_family == b->sin_family && a->sin_port == b->sin_port &&
           a->sin_addr.s_addr == b->sin_addr.s_addr;
}

static void tune(SOCKET k)
{
    int one = 1, size = LOOP_BUF;
    (void)setsockopt(k, IPPROTO_TCP, TCP_NODELAY, (const char *)&one, (int)sizeof one);
    (void)setsockopt(k, SOL_SOCKET, SO_SNDBUF, (const char *)&size, (int)sizeof size);
    (void)setsockopt(k, SOL_SOCKET, SO_RCVBUF, (const char *)&size, (int)sizeof size);
}

/* A connected pair on 127.0.0.1: *ours (accepted) and *theirs (connected). */
static int make_pair(SOCKET *ours, SOCKET *theirs, char *err, size_t errlen)
{
    struct sockaddr_in a, mine, peer;
    int len, one = 1;
    SOCKET l, c = INVALID_SOCKET, s = INVALID_SOCKET;
    *ours = *theirs = INVALID_SOCKET;
    l = socket(AF_INET, SOCK_STREAM, IPPROTO_TCP);
    if (l == INVALID_SOCKET) {
        set_err_wsa(err, errlen, "make a socket");
        return LEP_E_IO;
    }
    (void)setsockopt(l, SOL_SOCKET, SO_EXCLUSIVEADDRUSE, (const char *)&one, (int)sizeof one);
    loopback_addr(&a);
    len = (int)sizeof a;
    if (bind(l, (struct sockaddr *)&a, (int)sizeof a) != 0 || listen(l, 1) != 0 ||
        getsockname(l, (struct sockaddr *)&a, &len) != 0) {
        set_err_wsa(err, errlen, "listen on 127.0.0.1");
        closesocket(l);
        return LEP_E_IO;
    }
    c = socket(AF_INET, SOCK_STREAM, IPPROTO_TCP);
    if (c == INVALID_SOCKET || connect(c, (struct sockaddr *)&a, (int)sizeof a) != 0) {
        set_err_wsa(err, errlen, "connect on 127.0.0.1");
        goto fail;
    }
    len = (int)sizeof peer;
    s = accept(l, (struct sockaddr *)&peer, &len);
    if (s == INVALID_SOCKET) {
        set_err_wsa(err, errlen, "accept on 127.0.0.1");
        goto fail;
    }
    len = (int)sizeof mine;
    if (getsockname(c, (struct sockaddr *)&mine, &len) != 0 || !same_addr(&mine, &peer)) {
        lep_priv_set_err(err, errlen, "virtual sensor: another program connected to its port");
        goto fail;
    }
    closesocket(l);
    tune(s);
    tune(c);
    if (non_blocking(s) != 0 || non_blocking(c) != 0) {
        set_err_wsa(err, errlen, "make a socket non-blocking");
        closesocket(s);
        closesocket(c);
        return LEP_E_IO;
    }
    *ours = s;
    *theirs = c;
    return LEP_OK;
fail:
    closesocket(l);
    if (c != INVALID_SOCKET)
        closesocket(c);
    if (s != INVALID_SOCKET)
        closesocket(s);
    return LEP_E_IO;
}

void lep_priv_sim_port_init(lep_sim *s)
{
    s->master = s->slave = -1;
    s->wake[0] = s->wake[1] = -1;
    s->master_s = (uintptr_t)INVALID_SOCKET;
    s->wake_s = (uintptr_t)INVALID_SOCKET;
}

int lep_priv_sim_wake_open(lep_sim *s, char *err, size_t errlen)
{
    WSADATA wsa;
    struct sockaddr_in a;
    int len = (int)sizeof a;
    SOCKET k;
    if (WSAStartup(MAKEWORD(2, 2), &wsa) != 0) {
        lep_priv_set_err(err, errlen, "virtual sensor: Winsock does not start");
        return LEP_E_IO;
    }
    /* Connected to itself: it takes datagrams from itself only. */
    k = socket(AF_INET, SOCK_DGRAM, IPPROTO_UDP);
    loopback_addr(&a);
    if (k == INVALID_SOCKET || bind(k, (struct sockaddr *)&a, (int)sizeof a) != 0 ||
        getsockname(k, (struct sockaddr *)&a, &len) != 0 ||
        connect(k, (struct sockaddr *)&a, (int)sizeof a) != 0 || non_blocking(k) != 0) {
        set_err_wsa(err, errlen, "make its wake-up socket");
        if (k != INVALID_SOCKET)
            closesocket(k);
        (void)WSACleanup();
        return LEP_E_IO;
    }
    s->wake_s = (uintptr_t)k;
    return LEP_OK;
}

void lep_priv_sim_wake(lep_sim *s)
{
    static const char one = 1;
    if (sock_of(s->wake_s) != INVALID_SOCKET)
        (void)send(sock_of(s->wake_s), &one, 1, 0);
}

void lep_priv_sim_wake_drain(lep_sim *s)
{
    char junk[64];
    while (recv(sock_of(s->wake_s), junk, (int)sizeof junk, 0) > 0) {
    }
}

void lep_priv_sim_wake_close(lep_sim *s)
{
    if (sock_of(s->wake_s) == INVALID_SOCKET)
        return;
    closesocket(sock_of(s->wake_s));
    s->wake_s = (uintptr_t)INVALID_SOCKET;
    (void)WSACleanup();
}

int lep_priv_sim_open_pty(lep_sim *s, char *err, size_t errlen)
{
    SOCKET ours, theirs;
    int rc;
    if (s->pty[0] == '\0')
        (void)snprintf(s->pty, sizeof s->pty, "%s%ld", LEP_LOOPBACK_PREFIX,
                       (long)InterlockedIncrement(&port_count));
    rc = make_pair(&ours, &theirs, err, errlen);
    if (rc != LEP_OK)
        return rc;
    rc = lep_priv_loopback_add(s->link[0] != '\0' ? s->link : s->pty, theirs, s);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "%s: belongs to another virtual sensor of this program",
                         s->link[0] != '\0' ? s->link : s->pty);
        closesocket(ours);
        closesocket(theirs);
        return rc;
    }
    s->master_s = (uintptr_t)ours;
    return LEP_OK;
}

void lep_priv_sim_close_pty(lep_sim *s)
{
    lep_priv_loopback_remove(s);
    if (sock_of(s->master_s) != INVALID_SOCKET)
        closesocket(sock_of(s->master_s)); /* the host's reads see the hang-up */
    s->master_s = (uintptr_t)INVALID_SOCKET;
}

int lep_priv_sim_wait(lep_sim *s, bool port, bool want_out, int64_t until, unsigned *ready)
{
    WSAPOLLFD p[2];
    int ms = -1, rc;
    p[0].fd = sock_of(s->wake_s);
    p[0].events = POLLRDNORM;
    p[0].revents = 0;
    p[1].fd = sock_of(s->master_s);
    p[1].events = (short)(POLLRDNORM | (want_out ? POLLWRNORM : 0));
    p[1].revents = 0;
    *ready = 0;
    if (until != 0)
        ms = lep_priv_ms_left(until);
    rc = WSAPoll(p, port ? 2u : 1u, ms);
    if (rc < 0)
        return -1;
    if (p[0].revents & POLLRDNORM)
        *ready |= LEP_SIM_READY_WAKE;
    if (port && (p[1].revents & (POLLRDNORM | POLLHUP | POLLERR)))
        *ready |= LEP_SIM_READY_PORT;
    return 0;
}

long lep_priv_sim_read_port(lep_sim *s, uint8_t *buf, size_t cap)
{
    int r = recv(sock_of(s->master_s), (char *)buf, cap > 65536u ? 65536 : (int)cap, 0);
    if (r > 0)
        return r;
    /* 0: the listed end was closed (cannot happen while the list holds it) */
    return r == 0 || WSAGetLastError() != WSAEWOULDBLOCK ? -1 : 0;
}

void lep_priv_sim_flush_out(lep_sim *s)
{
    size_t ready;
    while ((ready = lep_priv_sim_queue_ready(s)) > 0 && sock_of(s->master_s) != INVALID_SOCKET) {
        int64_t t_call = s->trace != NULL ? lep_priv_monotonic_ns() : 0;
        size_t len = ready > 65536u ? 65536u : ready;
        int n = send(sock_of(s->master_s), (const char *)s->out, (int)len, 0);
        if (n > 0) {
            if (s->trace != NULL)
                lep_priv_sim_trace_written(s->trace, (size_t)n, t_call, lep_priv_monotonic_ns());
            lep_priv_sim_queue_written(s, (size_t)n);
            continue;
        }
        break; /* WSAEWOULDBLOCK: nobody reads now; keep it queued */
    }
}

int lep_priv_sim_start_thread(lep_sim *s, void *(*fn)(void *))
{
    return pthread_create(&s->thread, NULL, fn, s); /* no POSIX signals to keep out */
}

void lep_priv_sim_thread_init(void)
{
}

/* ---- the link option: a name in this program's list, not a file ---- */

int lep_priv_sim_link_claim(lep_sim *s, char *err, size_t errlen)
{
    s->lock_fd = -1;
    if (s->link[0] == '\0')
        return LEP_OK;
    if (lep_priv_loopback_listed(s->link)) {
        lep_priv_set_err(err, errlen,
                         "link %s belongs to a running virtual sensor; choose another path",
                         s->link);
        return LEP_E_BUSY;
    }
    return LEP_OK;
}

void lep_priv_sim_remove_link(const lep_sim *s)
{
    lep_priv_loopback_remove(s);
}

void lep_priv_sim_link_release(lep_sim *s)
{
    s->lock_fd = -1;
}
