/* Benchmark (not a test): stream from an in-process virtual sensor through a
 * real pty and print the measured rate, its deviation and per-read figures.
 *
 *   bench_stream [seconds=10] [rate_hz=1200] */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>

#include "leptrino/leptrino.h"
#include "leptrino/process.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"

/* Counts what the client asks of the port. */
struct counting {
    lep_io inner;
    unsigned long reads, empty_reads, bytes, writes;
};

static int c_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    struct counting *k = user;
    int n = k->inner.read(k->inner.user, buf, cap, timeout_ms);
    k->reads++;
    if (n > 0)
        k->bytes += (unsigned long)n;
    else if (n == 0)
        k->empty_reads++;
    return n;
}

static int c_write(void *user, const uint8_t *data, size_t len)
{
    struct counting *k = user;
    k->writes++;
    return k->inner.write(k->inner.user, data, len);
}

static uint32_t c_now(void *user)
{
    struct counting *k = user;
    return k->inner.now_ms(k->inner.user);
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? atof(argv[1]) : 10.0;
    double rate = argc > 2 ? atof(argv[2]) : 1200.0;
    lep_sim_options o;
    lep_sim *sim = NULL;
    lep_serial *port = NULL;
    lep_client client;
    lep_client_rx rx;
    struct counting k = { { 0 }, 0, 0, 0, 0 };
    lep_io io;
    lep_sample smp;
    lep_sim_counters st;
    char err[256];
    unsigned long n = 0, gaps = 0;
    uint16_t expect = 0;
    double t_first = 0, t_last = 0, t_end, max_gap = 0, cpu0, cpu1;
    int rc;

    lep_sim_options_init(&o);
    o.rate_hz = rate;
    if (lep_sim_start_so(&o, &sim, err, sizeof err) != LEP_OK ||
        lep_serial_open(lep_sim_port(sim), &port, err, sizeof err) != LEP_OK) {
        fprintf(stderr, "bench_stream: %s\n", err);
        return 1;
    }
    lep_serial_get_io(port, &k.inner);
    io.read = c_read;
    io.write = c_write;
    io.now_ms = c_now;
    io.user = &k;
    lep_client_init(&client, &io);
    lep_client_set_rx(&client, &rx);
    if ((rc = lep_client_start(&client)) != LEP_OK) {
        fprintf(stderr, "bench_stream: start: %s\n", lep_strerror(rc));
        return 1;
    }
    k.reads = k.empty_reads = k.bytes = 0;
    cpu0 = lep_cpu_seconds();
    t_end = lep_monotonic_seconds() + seconds;
    for (;;) {
        double t;
        rc = lep_client_next_sample(&client, &smp, 1000);
        t = lep_monotonic_seconds();
        if (rc != LEP_OK) {
            fprintf(stderr, "bench_stream: %s\n", lep_strerror(rc));
            return 1;
        }
        if (n == 0)
            t_first = t;
        else if (t - t_last > max_gap)
            max_gap = t - t_last;
        gaps += (uint16_t)(smp.reserved - expect);
        expect = (uint16_t)(smp.reserved + 1u);
        t_last = t;
        n++;
        if (t >= t_end)
            break;
    }
    cpu1 = lep_cpu_seconds();
    lep_client_stop(&client);
    lep_sim_get_stats(sim, &st);
    {
        double span = t_last - t_first;
        double measured = (double)(n - 1) / span;
        printf("stream over %.3f s at a nominal %.1f Hz\n", span, rate);
        printf("  samples received   %lu (sequence gaps: %lu)\n", n, gaps);
        printf("  measured rate      %.3f Hz, deviation %+.4f %%\n", measured,
               (measured - rate) / rate * 100.0);
        printf("  longest gap        %.3f ms (period %.3f ms)\n", max_gap * 1e3, 1e3 / rate);
        printf("  reads              %lu (%lu returned nothing), %.2f per sample\n", k.reads,
               k.empty_reads, (double)k.reads / (double)n);
        printf("  bytes per read     %.1f (%.2f samples)\n", (double)k.bytes / (double)k.reads,
               (double)k.bytes / (double)k.reads / 25.0); /* 20-byte message + 5 */
        printf("  syscalls per read  2 (one poll, one read); per sample %.2f\n",
               2.0 * (double)k.reads / (double)n);
        printf("  process CPU        %.2f %% of one core (client + sim thread)\n",
               (cpu1 - cpu0) / span * 100.0);
        printf("  sim: sent %llu, skipped %llu, blocked %llu\n",
               (unsigned long long)st.samples_sent, (unsigned long long)st.samples_skipped,
               (unsigned long long)st.samples_blocked);
    }
    lep_serial_close(port);
    lep_sim_stop(sim);
    return 0;
}
