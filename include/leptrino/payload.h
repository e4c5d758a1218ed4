/* Payload: the gravity wrench of a tool mounted on the sensor, and its
 * identification from a few static poses.
 *
 * The model (docs/session.md). With g the gravity vector in the sensor frame
 * (m/s^2; (0, 0, -9.80665) when the sensor's z axis points up), a payload of
 * mass m (kg) whose centre of mass is c (m, sensor frame), and the sensor's
 * biases F_b, M_b, the sensor reads
 *
 *     F = m g + F_b        M = c x (m g) + M_b
 *
 * Identification is the linear least-squares problem of that model in the
 * parameters (m, F_b, m c, M_b), as in D. Kubus, T. Kroeger, F. M. Wahl,
 * "On-line estimation of inertial parameters using a recursive total
 * least-squares approach", IEEE/RSJ IROS 2008 (there with accelerations; a
 * static pose keeps gravity alone). It separates exactly into two problems:
 * forces give m and F_b, moments give m c and M_b.
 *
 * Every function here is re-entrant (no state), never blocks, and never
 * allocates except lep_payload_pose_read (freed before it returns). */
#ifndef LEPTRINO_PAYLOAD_H
#define LEPTRINO_PAYLOAD_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

enum lep_payload_constants {
    /* Fewest poses an identification takes. */
    LEP_PAYLOAD_MIN_POSES = 3
};

/* Standard gravity, 9.80665 m/s^2 (the default gravity vector is (0, 0, -this)). */
LEP_API double lep_standard_gravity(void);

/* Smallest spread of the gravity vectors an identification accepts
 * (LEP_FIT_SPREAD): 0.02, an RMS tilt of about 1.1 degrees in the direction
 * the poses cover least. */
LEP_API double lep_payload_min_spread(void);

/* A payload is 4 doubles: mass kg (>= 0), then the centre of mass x, y, z
 * in metres, sensor frame (the option "payload" takes the same four). */

/* The gravity wrench of payload[4] at gravity[3] (sensor frame): wrench[6] =
 * (m g, c x m g), N and N m. LEP_E_ARG for NULL, non-finite values or a
 * negative mass (wrench then untouched). */
LEP_API int lep_payload_wrench(const double payload[4], const double gravity[3], double wrench[6]);

/* What an identification found, as indices into the array
 * lep_payload_identify fills. */
enum lep_fit_field {
    LEP_FIT_PAYLOAD = 0,        /* 4 fields: mass kg, centre of mass x y z m */
    LEP_FIT_FORCE_BIAS_N = 4,   /* 3 fields: F_b */
    LEP_FIT_TORQUE_BIAS_NM = 7, /* 3 fields: M_b */
    LEP_FIT_RESIDUAL = 10,      /* 6 fields: per axis, RMS over the poses of measured - model
                                   (N, N m): the noise of the means plus what the model misses */
    LEP_FIT_SPREAD = 16,        /* how well the gravity vectors cover the directions the centre
                                   of mass needs: sqrt(l_min / (n mean|g|^2)), l_min the smallest
                                   eigenvalue of sum(|d|^2 I - d d^T), d = g - mean g. 0 when
                                   the vectors lie on one line; 1/sqrt(2)..1 for poses spread
                                   evenly over the sphere */
    LEP_FIT_POSES = 17,         /* poses used */
    LEP_FIT_COUNT = 18
};

/* Identify a payload and the sensor's biases from n static poses: gravity
 * [n*3] (row i: g at pose i, m/s^2, sensor frame) and wrench [n*6] (row i:
 * the mean wrench measured there, N and N m, not tared). On success fills
 * the first min(nfit, LEP_FIT_COUNT) fields of fit and returns LEP_OK.
 * Refused, with one line in err (when not NULL) and fit untouched:
 *   LEP_E_ARG    NULL pointer, or a value that is NaN or infinite (the line
 *                names the pose and the value);
 *   LEP_E_VALUE  the poses do not determine the payload: fewer than
 *                LEP_PAYLOAD_MIN_POSES, gravity vectors that spread less than
 *                lep_payload_min_spread() (too few distinct directions: all
 *                on one line, or nearly the same), or a mass found not
 *                positive (no payload, or gravity given with the wrong sign
 *                or frame).
 * Never answers from a degenerate set: the conditioning is checked, not just n. */
LEP_API int lep_payload_identify(const double *gravity, const double *wrench, size_t n, double *fit,
                                 size_t nfit, char *err, size_t errlen);

/* The mean wrench of one pose, from a CSV recording made by the leptrino tool
 * (`leptrino stream`, leptrino/output.h): in the sensor frame, N and N m, as
 * the sensor measured it (any tare in the recording's metadata added back, any
 * rotation and moment point of the output undone). Uses the SI columns when
 * present, else the raw counts with the rated values of the metadata. *samples
 * (may be NULL) gets how many rows were averaged. Errors (one line in err
 * naming the file, and the line where it applies): LEP_E_ARG NULL; LEP_E_NOT_FOUND,
 * LEP_E_IO; LEP_E_VALUE for what it cannot average faithfully: not a leptrino
 * CSV recording (no metadata line, JSON lines), several sensors, a tare or
 * payload that changed during the recording, no force/torque columns, an
 * overloaded sample, no rows, a malformed line. Blocks on file I/O only. */
LEP_API int lep_payload_pose_read(const char *path, double mean[6], uint64_t *samples, char *err,
                                  size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
