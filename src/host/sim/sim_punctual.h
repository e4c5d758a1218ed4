/* Virtual sensor, private: keeping the sensor's deadlines as its crystal does.
 *
 * A real sensor sends each sample on its crystal's tick. A thread that sleeps
 * until a deadline wakes after it, by the kernel's timer and scheduling
 * latency (tens of microseconds on a virtual machine, even with a timer slack
 * of 1 ns), and a sensor written that way is late by as much on every sample:
 * a bias in every arrival that no reader can see or remove. So the serving
 * thread sleeps until a margin before each deadline and watches the clock for
 * the rest (a spin of about the margin less its wake-up lateness).
 *
 * The margin follows the thread's own wake-up lateness: a running estimate of
 * its 80th percentile (a stochastic quantile rule: up by SIM_PUNCTUAL_UP_NS
 * after a wake-up later than the margin, down by SIM_PUNCTUAL_DOWN_NS after
 * one within it), kept within [0, SIM_PUNCTUAL_MAX_NS]. It starts at the
 * maximum, so the first samples are punctual too. About one wake-up in five
 * is still late, by what its lateness exceeds the margin (a host's stamps
 * rest on the earliest arrivals, which are punctual); a wake-up later than
 * the maximum (a loaded machine) is late by the rest.
 *
 * Times are nanoseconds of the monotonic clock. The rule (init, wake, learn)
 * has no clock and no I/O; lep_priv_sim_punctual_sleep is the only call that
 * sleeps. Not thread-safe: one sim_punctual per serving thread. */
#ifndef LEPTRINO_HOST_SIM_PUNCTUAL_H
#define LEPTRINO_HOST_SIM_PUNCTUAL_H

#include <stdint.h>

#define SIM_PUNCTUAL_MAX_NS 250000 /* the margin's ceiling: 250 us */
#define SIM_PUNCTUAL_UP_NS 4000    /* 80th percentile: 4 up for 1 down */
#define SIM_PUNCTUAL_DOWN_NS 1000

typedef struct sim_punctual {
    int64_t margin_ns; /* sleep until this long before a deadline */
} sim_punctual;

void lep_priv_sim_punctual_init(sim_punctual *p);
/* When a sleep towards deadline should end: the margin before it. */
int64_t lep_priv_sim_punctual_wake(const sim_punctual *p, int64_t deadline);
/* A sleep until a wake time (from lep_priv_sim_punctual_wake) ended late_ns
 * after it (negative: before it, as after a signal); the margin follows. */
void lep_priv_sim_punctual_learn(sim_punctual *p, int64_t late_ns);
/* Blocks until deadline (returns at once if it has passed): sleeps until the
 * margin before it, learns that wake-up's lateness, then watches the clock
 * until the deadline. Returns no earlier than the deadline. */
void lep_priv_sim_punctual_sleep(sim_punctual *p, int64_t deadline);

#endif
