/* Private (not installed): a recorder of what a session's timeline is fed
 * (session_timeline.h, timeline_tap), for leptrino-stamp-error
 * --record-reads, which records read traces that test_timeline replays. */
#ifndef LEPTRINO_HOST_SESSION_TAP_H
#define LEPTRINO_HOST_SESSION_TAP_H

#include "leptrino/session.h"
#include "session_timeline.h"

/* From now on, tap (NULL: none) is given every feed of s's timeline, on the
 * thread that feeds it; tap must outlive s or be taken off. Set it before
 * lep_session_start to record a stream from its start. */
void lep_priv_session_tap_timeline(lep_session *s, const timeline_tap *tap);

#endif
