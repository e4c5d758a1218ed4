/* Scripted in-memory sensor for client tests: a lep_io whose clock is virtual
 * (a read that finds nothing advances it by its timeout, 1000 ms when it is
 * negative; a read that makes up stream data or noise advances it by 1 ms),
 * answered by a real
 * lep_device unless the test forces NAKs, silence or a reply of its own. */
#ifndef LEP_TEST_SCRIPT_IO_H
#define LEP_TEST_SCRIPT_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/leptrino.h"

#define SCRIPT_IN_CAP 16384u
#define SCRIPT_OUT_CAP 4096u
#define SCRIPT_MAX_READS 1000000u

typedef struct script_io {
    uint32_t now;              /* virtual clock, ms */
    uint8_t in[SCRIPT_IN_CAP]; /* bytes waiting for the host */
    size_t in_len;
    size_t in_pos;
    uint8_t out[SCRIPT_OUT_CAP]; /* everything the host wrote */
    size_t out_len;
    unsigned writes;     /* write calls */
    unsigned commands;   /* commands the device answered */
    size_t max_chunk;    /* read returns at most this many bytes (0: no limit) */
    int naks_left;       /* answer the next N commands with DLE NAK */
    bool silent;         /* ignore commands: no answer, no effect */
    unsigned inflight;   /* data frames sent before each answer while streaming */
    bool endless_stream; /* while streaming, an empty line grows a data frame per ms */
    int read_error;      /* non-zero: read returns it */
    int write_error;     /* non-zero: write returns it */
    uint8_t forced[128]; /* raw bytes sent instead of the device's next answer */
    size_t forced_len;
    uint16_t seq;           /* sequence number put into generated data frames */
    unsigned reads;         /* read calls (past SCRIPT_MAX_READS read fails: a runaway loop) */
    int last_timeout;       /* timeout_ms of the last read call */
    unsigned stall_reads;   /* the next N reads of an empty line find nothing, even streaming */
    bool noise;             /* an empty line grows 64 bytes of noise (no frame) per ms */
    int overclaim;          /* read reports this many bytes more than it copied */
    size_t total_read;      /* bytes handed to the host by all reads */
    unsigned lose_answers;  /* the next N commands are executed but their answers are lost */
    unsigned lose_commands; /* the next N commands never reach the device */
    uint32_t tick;          /* the clock advances this many ms at every now_ms call */
    lep_device dev;
} script_io;

/* Reset s with a PFS055YA501U6-like device, filter 0, endless streaming on. */
void script_io_init(script_io *s);
lep_io script_io_table(script_io *s);
/* script_io_init(s), then a client c on s's table (the test fails if
 * lep_client_init refuses it). */
void script_io_client(script_io *s, lep_client *c);
/* Queue raw bytes for the host. */
void script_push(script_io *s, const uint8_t *data, size_t len);
/* Queue the frame of a response message. */
void script_push_msg(script_io *s, const uint8_t *msg, size_t len);
/* Queue one continuous data frame with the next sequence number. */
void script_push_data(script_io *s);
/* Stop the endless stream, queue n data frames and copy every byte queued
 * for the host into wire (the test fails if they exceed cap); returns their
 * count. The bytes stay queued: step them in by hand, do not read them. */
size_t script_take_data(script_io *s, unsigned n, uint8_t *wire, size_t cap);
/* Bytes queued but not read yet. */
size_t script_pending(const script_io *s);

#endif
