/* ROS 2 WrenchStamped messages in CDR from a session's batch arrays
 * (leptrino/ros_cdr.h has the byte layout). */
#include "leptrino/ros_cdr.h"

#include <math.h>
#include <float.h>
#include <string.h>

#include "leptrino/error.h"
#include "struct_api.h"

#define NS_PER_S 1000000000LL
/* The stamp's seconds are an int32 (builtin_interfaces/Time). */
#define MAX_NS ((int64_t)INT32_MAX * NS_PER_S + (NS_PER_S - 1))

static uint8_t *put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xffu);
    p[1] = (uint8_t)((v >> 8) & 0xffu);
    p[2] = (uint8_t)((v >> 16) & 0xffu);
    p[3] = (uint8_t)(v >> 24);
    return p + 4;
}

static uint8_t *put_f64(uint8_t *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    put_u32(p, (uint32_t)(v & 0xffffffffu));
    put_u32(p + 4, (uint32_t)(v >> 32));
    return p + 8;
}

/* Bytes after the encapsulation header up to the doubles. */
static size_t head_len(size_t frame_id_len)
{
    size_t n = 8 + 4 + frame_id_len + 1;
    return n + (8 - n % 8) % 8;
}

size_t lep_ros_wrench_size(size_t frame_id_len)
{
    if (frame_id_len > LEP_ROS_FRAME_ID_MAX)
        return 0;
    return 4 + head_len(frame_id_len) + 6 * 8;
}

/* The stamp of t_utc in ns, or -1 when it is not one. The whole seconds
 * first, then the fraction (exact in a double) rounded to the nanosecond:
 * t_utc * 1e9 as one double would round to 256 ns today. */
static int64_t stamp_of(double t_utc)
{
    double sec, ns;
    if (!isfinite(t_utc) || t_utc < 0.0 || t_utc >= (double)INT32_MAX + 1.0)
        return -1;
    sec = floor(t_utc);
    ns = nearbyint((t_utc - sec) * 1e9);
    if ((int64_t)sec * NS_PER_S + (int64_t)ns > MAX_NS)
        return -1;
    return (int64_t)sec * NS_PER_S + (int64_t)ns;
}

static void write_one(uint8_t *p, const uint8_t *head, size_t hlen, const double v[LEP_AXES])
{
    size_t k;
    memcpy(p, head, hlen);
    p += hlen;
    for (k = 0; k < LEP_AXES; k++)
        p = put_f64(p, v[k]);
}

int lep_ros_wrench_cdr_batch(const lep_session_batch *b, size_t from, size_t n,
                             const lep_rated *rated, const char *frame_id, int64_t *last_ns,
                             uint8_t *wrench, uint8_t *wrench_raw, size_t cap, int64_t *stamp_ns)
{
    uint8_t head[4 + 8 + 4 + LEP_ROS_FRAME_ID_MAX + 1 + 7];
    size_t flen, hlen, size, i;
    int64_t last;

    if (b == NULL || frame_id == NULL || last_ns == NULL || from > b->n || n > b->n - from ||
        (n > 0 && b->t_utc == NULL) || (wrench != NULL && b->si == NULL) ||
        (wrench_raw != NULL && (b->raw == NULL || rated == NULL)))
        return LEP_E_ARG;
    flen = strlen(frame_id);
    size = lep_ros_wrench_size(flen);
    if (size == 0)
        return LEP_E_ARG;
    if ((wrench != NULL || wrench_raw != NULL) && n > cap / size)
        return LEP_E_BUFFER;
    for (i = 0; i < n; i++)
        if (stamp_of(b->t_utc[from + i]) < 0)
            return LEP_E_VALUE;

    /* Encapsulation header, a stamp placeholder, frame_id and its padding:
     * the same for every message but the stamp. */
    hlen = 4 + head_len(flen);
    memset(head, 0, sizeof head);
    head[1] = 0x01;
    put_u32(head + 12, (uint32_t)(flen + 1));
    memcpy(head + 16, frame_id, flen);

    last = *last_ns;
    for (i = 0; i < n; i++) {
        const size_t j = from + i;
        int64_t ns = stamp_of(b->t_utc[j]);
        if (ns < last)
            ns = last;
        last = ns;
        put_u32(head + 4, (uint32_t)(ns / NS_PER_S));
        put_u32(head + 8, (uint32_t)(ns % NS_PER_S));
        if (stamp_ns != NULL)
            stamp_ns[i] = ns;
        if (wrench != NULL)
            write_one(wrench + i * size, head, hlen, b->si + j * LEP_AXES);
        if (wrench_raw != NULL) {
            lep_sample s;
            double si[LEP_AXES];
            memset(&s, 0, sizeof s);
            memcpy(s.raw, b->raw + j * LEP_AXES, sizeof s.raw);
            lep_sample_to_si(&s, rated, si);
            write_one(wrench_raw + i * size, head, hlen, si);
        }
    }
    *last_ns = last;
    return LEP_OK;
}

int lep_ros_wrench_cdr(size_t n, const double *t_utc, const double *si, const int16_t *raw,
                       const double rated[6], const char *frame_id, int64_t *last_ns,
                       uint8_t *wrench, uint8_t *wrench_raw, size_t cap, int64_t *stamp_ns)
{
    lep_session_batch b;
    lep_rated r;
    int k;
    if (rated != NULL) {
        for (k = 0; k < LEP_AXES; k++) {
            if (!(rated[k] > 0.0 && rated[k] <= FLT_MAX)) /* also NaN */
                return LEP_E_VALUE;
            r.axis[k] = (float)rated[k];
        }
    }
    /* The batch is only read (its members are not const for the session's sake). */
    memset(&b, 0, sizeof b);
    b.cap = b.n = n;
    b.t_utc = (double *)t_utc;
    b.si = (double *)si;
    b.raw = (int16_t *)raw;
    return lep_ros_wrench_cdr_batch(&b, 0, n, rated != NULL ? &r : NULL, frame_id, last_ns, wrench,
                                    wrench_raw, cap, stamp_ns);
}
