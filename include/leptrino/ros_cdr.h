/* ROS 2 messages of a session's samples, serialized (OS layer).
 *
 * lep_ros_wrench_cdr turns samples, as lep_session_read fills them, into
 * geometry_msgs/msg/WrenchStamped messages in CDR, the bytes every ROS 2
 * transport carries (rmw_zenoh's payload, a DDS serialized sample, an MCAP
 * "cdr" message, a Foxglove "cdr" message): one call per batch, so that a
 * binding publishing at the sensor's rate makes no object per sample.
 *
 * One message, little-endian XCDR1, offsets from the payload's start:
 *   0  encapsulation header 00 01 00 00 (CDR_LE, options 0)
 *   4  header.stamp.sec      int32
 *   8  header.stamp.nanosec  uint32
 *  12  header.frame_id       uint32 length counting the NUL, the bytes, NUL
 *      padding to a multiple of 8 counted from offset 4
 *      wrench.force.x/y/z, wrench.torque.x/y/z: 6 float64
 * Every message of a frame_id has the same size: lep_ros_wrench_size().
 *
 * Pure computation on caller-owned memory: no allocation, no I/O, no global
 * state; re-entrant (one thread per *last_ns). Errors are LEP_E_* codes. */
#ifndef LEPTRINO_ROS_CDR_H
#define LEPTRINO_ROS_CDR_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest frame_id accepted, in bytes (without the NUL). */
enum lep_ros_constants { LEP_ROS_FRAME_ID_MAX = 255 };

/* Bytes of one WrenchStamped message whose frame_id is frame_id_len bytes
 * long (0 when frame_id_len > LEP_ROS_FRAME_ID_MAX). */
LEP_API size_t lep_ros_wrench_size(size_t frame_id_len);

/* Serialize n samples, message after message, into wrench (the session's
 * output si[n*6]: N, N m) and wrench_raw (the raw counts raw[n*6] in N and
 * N m through rated[6]), each of cap bytes and each may be NULL to skip it.
 * Each message's stamp is t_utc[i] rounded to the nanosecond, held at
 * *last_ns when it would go back (the session's double can step back by a
 * rounding step); *last_ns is then the last stamp written. stamp_ns (NULL to
 * skip) receives the n stamps (ns since the epoch), the same for both
 * topics. frame_id: a NUL-terminated UTF-8 string of at most
 * LEP_ROS_FRAME_ID_MAX bytes.
 *
 * All or nothing: on an error nothing is written and *last_ns is unchanged.
 * LEP_E_ARG: t_utc, frame_id or last_ns NULL; wrench given and si NULL;
 * wrench_raw given and raw or rated NULL; frame_id too long. LEP_E_BUFFER:
 * cap < n * lep_ros_wrench_size(). LEP_E_VALUE: a t_utc that is not finite
 * or whose seconds do not fit builtin_interfaces/Time (int32, from 1970), or
 * a rated value that is not a finite float > 0. n = 0 writes nothing, LEP_OK. */
LEP_API int lep_ros_wrench_cdr(size_t n, const double *t_utc, const double *si, const int16_t *raw,
                               const double rated[6], const char *frame_id, int64_t *last_ns,
                               uint8_t *wrench, uint8_t *wrench_raw, size_t cap, int64_t *stamp_ns);

#ifdef __cplusplus
}
#endif

#endif
