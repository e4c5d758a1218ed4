/* Private (Windows only): in-process loopback ports, the virtual sensor's
 * stand-in for a pseudo-terminal (serial_loopback_win32.c).
 *
 * The virtual sensor (sim_link_win32.c) makes a connected pair of TCP
 * sockets on 127.0.0.1 and lists the host's end under a name ("sim:1", or
 * the sensor's link option). lep_serial_open (serial_win32.c) opens a listed
 * name instead of a COM port and reads and writes it with a COM port's
 * contract. The list owns the listed socket: it outlives a host that closes
 * the port (as the POSIX sensor holds its pty's slave side), and is closed
 * when the sensor has unlisted it and no host has it open. */
#ifndef LEPTRINO_SERIAL_LOOPBACK_H
#define LEPTRINO_SERIAL_LOOPBACK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <winsock2.h>

/* Names the virtual sensor makes up for itself: "sim:" and a number. */
#define LEP_LOOPBACK_PREFIX "sim:"

/* The sensor's side. List host_end (a non-blocking connected socket) under
 * name for owner: LEP_OK (the list owns host_end from then on), or
 * LEP_E_BUSY when another sensor lists that name (host_end stays the
 * caller's). Takes a Winsock reference for as long as the socket lives. */
int lep_priv_loopback_add(const char *name, SOCKET host_end, const void *owner);
/* True when some sensor lists name. */
bool lep_priv_loopback_listed(const char *name);
/* Unlist owner's name (nothing when owner lists none): later opens fail; the
 * socket is closed now, or when the host that has it open closes it. */
void lep_priv_loopback_remove(const void *owner);

/* The host's side. */
typedef struct lep_loopback_port lep_loopback_port;
/* Open the port listed under name: LEP_OK with *out set; LEP_OK with *out
 * NULL when no sensor lists name and it is not a "sim:" name (a COM port
 * then); LEP_E_NOT_FOUND for a "sim:" name nobody lists (the sensor hung up
 * or stopped), LEP_E_BUSY when another host has it open; with a message. */
int lep_priv_loopback_open(const char *name, lep_loopback_port **out, char *err, size_t errlen);
void lep_priv_loopback_close(lep_loopback_port *p);
/* lep_io's read and write (user: the port): a COM port's contract (wait at
 * most timeout_ms, < 0 without end, 0 not at all; return what is there at
 * once); LEP_E_DISCONNECTED once the sensor has hung up. */
int lep_priv_loopback_read(void *user, uint8_t *buf, size_t cap, int timeout_ms);
int lep_priv_loopback_write(void *user, const uint8_t *data, size_t len);

#endif
