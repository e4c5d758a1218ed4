/* Sizes the session's units agree on: a read's buffer, the samples it can
 * complete, the rows and events kept. */
#ifndef LEPTRINO_HOST_SESSION_SIZES_H
#define LEPTRINO_HOST_SESSION_SIZES_H

/* Bytes taken from the port per read: 16 KiB is 0.55 s of a 1.2 kHz stream,
 * so a latency budget of up to half a second needs one read per wake-up. */
#define SESSION_RBUF 16384u
/* Smallest wire size of a data frame (DLE STX, 20 bytes, DLE ETX, BCC). */
#define SESSION_MIN_FRAME 25u
/* Samples one read can complete: every byte in whole frames, plus the frame
 * begun by the previous read. */
#define SESSION_PENDING (SESSION_RBUF / SESSION_MIN_FRAME + 2u)
/* Rows kept for reads: those held back while a hole is suspected (one read's
 * worth at most) and the next read's. */
#define SESSION_ROWS (2u * SESSION_PENDING)
/* Events kept until lep_session_next_event takes them; beyond, the oldest go
 * (counted in lep_session_health_info.events_dropped). */
#define SESSION_EVENTS 1024u

#endif
