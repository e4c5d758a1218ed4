/* leptrino-soak: the client against the virtual sensor over a pty, with every
 * fault on, for a given time. Issues commands and streams; checks every
 * delivered sample against what the sensor sent for its sequence number
 * (lep_sim_stream_sample) and every answer against the sensor's identity;
 * prints one JSON object. Exit 0 when no sample was wrong, duplicated or out
 * of order (and no answer wrong), 1 otherwise, 2 for bad arguments. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/process.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "soak.h"

#define EXIT_USAGE 2

/* The sensor's faults unless the command line says otherwise. */
static const char *const fault_defaults[][2] = {
    { "corrupt", "0.01" }, { "nak", "0.05" },          { "garbage", "0.02" },
    { "drop", "0.005" },   { "start-streaming", "1" }, { "reopen-after", "300" },
};

static const char usage[] =
    "usage: leptrino-soak [--duration S] [--stall-every S] [--hangup-every S] [--NAME VALUE]...\n"
    "Runs the client against a virtual sensor over a pseudo-terminal with every fault\n"
    "on (corruption, NAKs, garbage, drops, stalls, hang-ups with the port coming back,\n"
    "a stream left running at start), issuing commands and streaming, and checks every\n"
    "delivered sample against what the sensor sent for its sequence number. Prints\n"
    "one JSON object on stdout. Exit 1 on any wrong, duplicated or out-of-order sample.\n"
    "\n"
    "  --duration S      how long to run (default 60)\n"
    "  --stall-every S   a stall of 50..600 ms every S seconds on average (default 3; 0: none)\n"
    "  --hangup-every S  a hang-up every S seconds on average (default 15; 0: none)\n"
    "  --NAME VALUE      any virtual sensor option (leptrino-sim --help); the soak's\n"
    "                    defaults: --corrupt 0.01 --nak 0.05 --garbage 0.02 --drop 0.005\n"
    "                    --start-streaming --reopen-after 300 --seed 1\n"
    "  --check-filter C  check samples against filter code C instead of the sensor's (a\n"
    "                    test of the check itself: a wrong code must fail the run)\n"
    "  --bit-errors N    instead: flip two random bits in N random valid frames of each\n"
    "                    kind and count those the BCC and the message checks accept\n"
    "  --help, --version\n";

typedef struct soak {
    lep_sim_options opt;
    double duration_s, stall_every_s, hangup_every_s;
    uint64_t bit_errors; /* --bit-errors N: that measurement instead */
    int check_filter;    /* --check-filter CODE: check against this code (a test of the check) */
    lep_sim *sim;
    lep_serial *port;
    lep_client client;
    lep_product_info want_info;
    lep_rated want_rated;
    uint64_t rng;
    double t_end, next_stall, next_hangup;
    /* results */
    uint64_t delivered, duplicated, out_of_order, wrong, answers_wrong;
    uint64_t commands, failed, reconnects, streams, stalls, hangups, timeouts;
    /* client counters, summed over connections */
    uint64_t resent_nak, resent_timeout, resent_confirmed, recoveries;
    double max_gap_s;
} soak;

static uint64_t next_random(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* Uniform in [lo, hi). */
static double uniform(soak *k, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(next_random(&k->rng) >> 11) / 9007199254740992.0);
}

/* The next time of a fault that comes every `every` seconds on average. */
static double next_time(soak *k, double every)
{
    return every > 0 ? lep_monotonic_seconds() + uniform(k, 0.5 * every, 1.5 * every) : 1e300;
}

static void sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    nanosleep(&ts, NULL);
}

/* Faults the soak drives itself, at random times: stalls and hang-ups. */
static void inject(soak *k)
{
    double now = lep_monotonic_seconds();
    if (now >= k->next_stall) {
        lep_sim_stall(k->sim, (int)uniform(k, 50, 600));
        k->stalls++;
        k->next_stall = next_time(k, k->stall_every_s);
    }
    if (now >= k->next_hangup) {
        lep_sim_hangup(k->sim);
        k->hangups++;
        k->next_hangup = next_time(k, k->hangup_every_s);
    }
}

static void close_port(soak *k)
{
    if (k->port != NULL) {
        lep_client_stats cs;
        lep_client_get_stats(&k->client, &cs);
        k->resent_nak += cs.retries;
        k->resent_timeout += cs.resent_after_timeout;
        k->resent_confirmed += cs.resent_confirmed;
        k->recoveries += cs.recoveries;
        lep_serial_close(k->port);
        k->port = NULL;
    }
}

/* (Re)open the port at the link (it comes back after a hang-up) and recover.
 * Returns 0, or -1 when the time is up. */
static int connect_port(soak *k)
{
    char err[256];
    for (;;) {
        int rc;
        if (lep_monotonic_seconds() > k->t_end)
            return -1;
        close_port(k);
        if (lep_serial_open(lep_sim_port(k->sim), &k->port, err, sizeof err) != LEP_OK) {
            k->port = NULL;
            sleep_ms(20); /* hung up: the link is back after reopen-after ms */
            continue;
        }
        lep_serial_client_init(&k->client, k->port);
        lep_client_set_timeout(&k->client, 200);
        lep_client_set_retries(&k->client, 8);
        k->commands++;
        rc = lep_client_sync(&k->client, 30, NULL);
        if (rc == LEP_OK)
            return 0;
        if (rc != LEP_E_DISCONNECTED)
            k->failed++;
        inject(k);
    }
}

/* Account a transaction's result: 0 ok, 1 failed (recover with a sync),
 * 2 disconnected (reconnect). */
static int outcome(soak *k, int rc)
{
    k->commands++;
    if (rc == LEP_OK)
        return 0;
    if (rc == LEP_E_DISCONNECTED)
        return 2;
    k->failed++;
    if (rc == LEP_E_TIMEOUT)
        k->timeouts++;
    return 1;
}

static int queries(soak *k)
{
    lep_product_info info;
    lep_rated rated;
    uint8_t code = 0xFF;
    lep_sample smp;
    int r;
    if ((r = outcome(k, lep_client_product_info(&k->client, &info))) != 0)
        return r;
    if (strcmp(info.model, k->want_info.model) != 0 ||
        strcmp(info.serial, k->want_info.serial) != 0 ||
        strcmp(info.firmware, k->want_info.firmware) != 0)
        k->answers_wrong++;
    inject(k);
    if ((r = outcome(k, lep_client_rated(&k->client, &rated))) != 0)
        return r;
    if (memcmp(&rated, &k->want_rated, sizeof rated) != 0)
        k->answers_wrong++;
    if ((r = outcome(k, lep_client_filter_get(&k->client, &code))) != 0)
        return r;
    if (code != k->opt.filter)
        k->answers_wrong++;
    if ((r = outcome(k, lep_client_sample(&k->client, &smp))) != 0)
        return r;
    if (smp.reserved != 0)
        k->answers_wrong++;
    return 0;
}

/* One stream: start, check every sample for a while, stop. */
static int stream(soak *k)
{
    double until = lep_monotonic_seconds() + uniform(k, 0.2, 1.5), last;
    uint64_t kk = 0;
    bool first = true;
    int r;
    if ((r = outcome(k, lep_client_start(&k->client))) != 0)
        return r;
    k->streams++;
    last = lep_monotonic_seconds();
    while (lep_monotonic_seconds() < until && lep_monotonic_seconds() < k->t_end) {
        lep_sample got, want;
        int rc = lep_client_next_sample(&k->client, &got, 1000);
        double now = lep_monotonic_seconds();
        inject(k);
        if (rc == LEP_E_TIMEOUT) {
            k->timeouts++;
            continue;
        }
        if (rc == LEP_E_DISCONNECTED)
            return 2;
        if (rc != LEP_OK) {
            k->failed++;
            return 1;
        }
        if (now - last > k->max_gap_s)
            k->max_gap_s = now - last;
        last = now;
        k->delivered++;
        /* k = the index in the stream: unwrap the 16-bit sequence number */
        if (first) {
            kk = got.reserved;
            first = false;
        } else {
            uint16_t d = (uint16_t)(got.reserved - (uint16_t)kk);
            if (d == 0) {
                k->duplicated++;
                continue;
            }
            if (d >= 0x8000u) {
                k->out_of_order++;
                continue;
            }
            kk += d;
        }
        if (lep_sim_sample_at(k->sim, kk,
                              k->check_filter >= 0 ? (uint8_t)k->check_filter : k->opt.filter,
                              &want) != LEP_OK ||
            memcmp(&want, &got, sizeof want) != 0)
            k->wrong++;
    }
    return outcome(k, lep_client_stop(&k->client));
}

static void run(soak *k)
{
    bool connected = false;
    k->t_end = lep_monotonic_seconds() + k->duration_s;
    k->next_stall = next_time(k, k->stall_every_s);
    k->next_hangup = next_time(k, k->hangup_every_s);
    while (lep_monotonic_seconds() < k->t_end) {
        int r;
        if (!connected) {
            if (connect_port(k) != 0)
                break;
            connected = true;
        }
        r = queries(k);
        if (r == 0)
            r = queries(k);
        if (r == 0)
            r = stream(k);
        if (r == 2) {
            k->reconnects++;
            connected = false;
        } else if (r == 1) {
            /* recover as a program would: stop, drain, identify */
            int s = outcome(k, lep_client_sync(&k->client, 30, NULL));
            if (s == 2) {
                k->reconnects++;
                connected = false;
            }
        }
        inject(k);
    }
    if (connected) /* leave the sensor idle */
        (void)lep_client_stop(&k->client);
    close_port(k);
}

static void report(const soak *k, const lep_sim_counters *st, double elapsed, double cpu)
{
    uint64_t generated =
        st->samples_sent + st->samples_dropped + st->samples_skipped + st->samples_blocked;
    uint64_t unique = k->delivered - k->duplicated - k->out_of_order;
    printf("{\"duration_s\":%.3f,\"seed\":%llu,\"generated\":%llu,\"sent\":%llu,"
           "\"delivered\":%llu,\"lost\":{\"dropped\":%llu,\"stalled\":%llu,\"blocked\":%llu,"
           "\"line\":%llu},\"duplicated\":%llu,\"out_of_order\":%llu,\"delivered_wrong\":%llu,"
           "\"answers_wrong\":%llu,\"commands\":%llu,\"resent\":%llu,"
           "\"resent_by_cause\":{\"nak\":%llu,\"timeout\":%llu},\"resent_confirmed\":%llu,"
           "\"start_recoveries\":%llu,\"failed\":%llu,"
           "\"timeouts\":%llu,\"reconnects\":%llu,\"max_gap_ms\":%.1f,\"streams\":%llu,"
           "\"faults\":{\"corrupted\":%llu,\"naks\":%llu,\"garbage_bytes\":%llu,"
           "\"stalls\":%llu,\"hangups\":%llu,\"reopens\":%llu},\"cpu_s\":%.3f}\n",
           elapsed, (unsigned long long)k->opt.seed, (unsigned long long)generated,
           (unsigned long long)st->samples_sent, (unsigned long long)k->delivered,
           (unsigned long long)st->samples_dropped, (unsigned long long)st->samples_skipped,
           (unsigned long long)st->samples_blocked,
           (unsigned long long)(st->samples_sent > unique ? st->samples_sent - unique : 0u),
           (unsigned long long)k->duplicated, (unsigned long long)k->out_of_order,
           (unsigned long long)k->wrong, (unsigned long long)k->answers_wrong,
           (unsigned long long)k->commands, (unsigned long long)(k->resent_nak + k->resent_timeout),
           (unsigned long long)k->resent_nak, (unsigned long long)k->resent_timeout,
           (unsigned long long)k->resent_confirmed, (unsigned long long)k->recoveries,
           (unsigned long long)k->failed, (unsigned long long)k->timeouts,
           (unsigned long long)k->reconnects, k->max_gap_s * 1000.0, (unsigned long long)k->streams,
           (unsigned long long)st->bytes_corrupted, (unsigned long long)st->faked_naks,
           (unsigned long long)st->garbage_bytes, (unsigned long long)st->stalls,
           (unsigned long long)st->hangups, (unsigned long long)st->reopens, cpu);
}

static int bad(const char *opt, const char *msg)
{
    fprintf(stderr, "leptrino-soak: %s: %s (see --help)\n", opt, msg);
    return EXIT_USAGE;
}

static int seconds_arg(const char *name, const char *val, double *out)
{
    char *end;
    double v;
    if (val == NULL)
        return bad(name, "needs a value");
    errno = 0;
    v = strtod(val, &end);
    if (end == val || *end != '\0' || errno != 0 || !(v >= 0.0 && v <= 1e6))
        return bad(name, "expected seconds, 0..1000000");
    *out = v;
    return -1;
}

/* Returns -1 to go on, else an exit code. */
static int parse(int argc, char **argv, soak *k)
{
    size_t i;
    int a;
    char err[256];
    lep_sim_options_init(&k->opt);
    for (i = 0; i < sizeof fault_defaults / sizeof fault_defaults[0]; i++)
        (void)lep_sim_option_set(&k->opt, fault_defaults[i][0], fault_defaults[i][1], NULL, 0);
    k->duration_s = 60;
    k->check_filter = -1;
    k->stall_every_s = 3;
    k->hangup_every_s = 15;
    a = 1;
    while (a < argc) {
        const char *name = argv[a], *val = a + 1 < argc ? argv[a + 1] : NULL;
        int used = 2; /* the option and its value */
        const lep_sim_option_info *in;
        int rc = -1;
        if (strcmp(name, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        }
        if (strcmp(name, "--version") == 0) {
            printf("leptrino-soak %s\n", lep_version());
            return 0;
        }
        if (strcmp(name, "--duration") == 0)
            rc = seconds_arg(name, val, &k->duration_s);
        else if (strcmp(name, "--stall-every") == 0)
            rc = seconds_arg(name, val, &k->stall_every_s);
        else if (strcmp(name, "--hangup-every") == 0)
            rc = seconds_arg(name, val, &k->hangup_every_s);
        else if (strcmp(name, "--check-filter") == 0) {
            if (val == NULL || strlen(val) != 1 || val[0] < '0' || val[0] > '3')
                return bad(name, "expected a filter code 0..3");
            k->check_filter = val[0] - '0';
        } else if (strcmp(name, "--bit-errors") == 0) {
            char *end;
            errno = 0;
            k->bit_errors = val != NULL ? strtoull(val, &end, 10) : 0;
            if (val == NULL || end == val || *end != '\0' || errno != 0 || val[0] == '-' ||
                k->bit_errors == 0)
                return bad(name, "expected a count of frames > 0");
        } else if (strncmp(name, "--", 2) == 0 && (in = lep_sim_option_find(name + 2)) != NULL &&
                   strcmp(in->name, name + 2) == 0) {
            if (in->type == LEP_SIM_OPT_FLAG) {
                val = NULL;
                used = 1;
            }
            if (lep_sim_option_set(&k->opt, in->name, val, err, sizeof err) != LEP_OK) {
                fprintf(stderr, "leptrino-soak: --%s (see --help)\n", err);
                return EXIT_USAGE;
            }
        } else {
            return bad(name, "unknown option");
        }
        if (rc >= 0)
            return rc;
        a += used;
    }
    if (k->duration_s <= 0)
        return bad("--duration", "expected more than 0 s");
    return -1;
}

int main(int argc, char **argv)
{
    soak k;
    char err[256];
    lep_sim_counters st;
    double t0, cpu0;
    int rc;
    memset(&k, 0, sizeof k);
    rc = parse(argc, argv, &k);
    if (rc >= 0)
        return rc;
    if (k.bit_errors > 0)
        return soak_bit_errors(k.bit_errors, k.opt.seed);
    signal(SIGPIPE, SIG_IGN);
    if (k.opt.link[0] == '\0') {
        /* the port comes back under the same name after a hang-up */
        const char *dir = getenv("TMPDIR");
        snprintf(k.opt.link, sizeof k.opt.link, "%s/leptrino-soak-%ld",
                 dir != NULL && dir[0] != '\0' && strlen(dir) < 256 ? dir : "/tmp", (long)getpid());
    }
    k.rng = k.opt.seed ^ 0x50A4u;
    rc = lep_sim_start_so(&k.opt, &k.sim, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino-soak: cannot start the virtual sensor: %s\n", err);
        return rc == LEP_E_ARG ? EXIT_USAGE : 1;
    }
    memset(&k.want_info, 0, sizeof k.want_info);
    snprintf(k.want_info.model, sizeof k.want_info.model, "%.*s",
             (int)(sizeof k.want_info.model - 1), k.opt.model);
    snprintf(k.want_info.serial, sizeof k.want_info.serial, "%.*s",
             (int)(sizeof k.want_info.serial - 1), k.opt.serial);
    snprintf(k.want_info.firmware, sizeof k.want_info.firmware, "%.*s",
             (int)(sizeof k.want_info.firmware - 1), k.opt.firmware);
    (void)lep_sim_model_rated_f(k.opt.model, &k.want_rated);
    t0 = lep_monotonic_seconds();
    cpu0 = lep_cpu_seconds();
    run(&k);
    lep_sim_get_stats(k.sim, &st);
    report(&k, &st, lep_monotonic_seconds() - t0, lep_cpu_seconds() - cpu0);
    lep_sim_stop(k.sim);
    return k.wrong + k.duplicated + k.out_of_order + k.answers_wrong > 0 ? 1 : 0;
}
