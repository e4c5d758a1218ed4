/* Virtual sensor, private: the transport's packetising rule (sans-I/O).
 *
 * Between the sensor's output queue and the port, the bytes may be made to
 * arrive as a USB adapter delivers them ("sim-usb-packets",
 * "sim-ftdi-latency"): the rule says, from the times bytes entered the
 * adapter, how many of them the port may have by a given time. No clock, no
 * I/O, no allocation: times are nanoseconds of one monotonic clock, given by
 * the caller, in order.
 *
 *   none   every byte is released when it enters.
 *   usb    a USB full-speed adapter: bytes are released only at 1 ms frame
 *          boundaries (multiples of SIM_USB_FRAME_NS of the clock): at
 *          boundary b, every byte that entered at or before b.
 *   ftdi   an FTDI-style adapter (FTDI AN232B-04, "Small Amounts of Data and
 *          End of Buffer Conditions"): the chip sends a 64-byte bulk packet
 *          (2 status bytes and SIM_FTDI_PAYLOAD bytes of data) once it holds
 *          that much data, or whatever it holds (perhaps nothing: the status
 *          bytes alone) when its latency timer runs out, the timer counting
 *          from the last packet it sent. A packet goes out at a 1 ms frame
 *          boundary: at boundary b, the bytes that entered at or before b
 *          make up as many full packets as they fill; if none is full and
 *          b is latency ms or more after the last packet, all of them go.
 *
 * Bytes are released in the order they entered (a FIFO); the caller writes
 * released bytes to the port and says how many it wrote. */
#ifndef LEPTRINO_HOST_SIM_TRANSPORT_H
#define LEPTRINO_HOST_SIM_TRANSPORT_H

#include <stddef.h>
#include <stdint.h>

#define SIM_USB_FRAME_NS 1000000 /* a USB full-speed frame: 1 ms */
#define SIM_FTDI_PAYLOAD 62u     /* data bytes of a 64-byte bulk packet */
/* Entries (times bytes entered) kept while not released; beyond it, a new
 * entry joins the newest (its bytes then count as entering with them). */
#define SIM_TRANSPORT_ENTRIES 1024u

enum sim_transport_mode { SIM_TRANSPORT_NONE = 0, SIM_TRANSPORT_USB, SIM_TRANSPORT_FTDI };

typedef struct sim_transport_entry {
    int64_t t;    /* when the bytes entered */
    uint64_t end; /* count of bytes entered up to and with these */
} sim_transport_entry;

typedef struct sim_transport {
    int mode;                                     /* enum sim_transport_mode */
    int64_t latency_ns;                           /* ftdi: the latency timer */
    uint64_t entered, released, written;          /* byte counts since init or clear */
    sim_transport_entry e[SIM_TRANSPORT_ENTRIES]; /* not yet released, oldest first */
    size_t head, len;
    int64_t done_to;  /* frame boundaries up to here are done (0: none yet) */
    int64_t last_pkt; /* ftdi: boundary of the last packet (0: none yet) */
} sim_transport;

/* mode: enum sim_transport_mode; ftdi_latency_ms 1..255 with SIM_TRANSPORT_FTDI. */
void lep_priv_sim_transport_init(sim_transport *tr, int mode, int ftdi_latency_ms);
/* n bytes entered the adapter at t (a time earlier than an earlier entry's
 * counts as that entry's). */
void lep_priv_sim_transport_in(sim_transport *tr, int64_t t, size_t n);
/* The frame boundaries up to now happen. */
void lep_priv_sim_transport_advance(sim_transport *tr, int64_t now);
/* Bytes released and not yet written: the port may take this many. */
size_t lep_priv_sim_transport_ready(const sim_transport *tr);
/* n of the ready bytes were written. */
void lep_priv_sim_transport_written(sim_transport *tr, size_t n);
/* When more bytes are released next (a frame boundary), 0 when none waits. */
int64_t lep_priv_sim_transport_next(const sim_transport *tr);
/* The bytes in flight are gone (the queue was emptied): nothing waits. */
void lep_priv_sim_transport_clear(sim_transport *tr);

#endif
