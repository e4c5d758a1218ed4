/* leptrino-sim: a virtual Leptrino sensor on a pseudo-terminal.
 *
 * Prints the port path as the first line of stdout, then serves until
 * SIGINT/SIGTERM/SIGHUP (clean exit 0, link removed). SIGUSR1 power-cycles
 * the virtual sensor (a pending filter setting takes effect). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <pthread.h>

#include "leptrino/leptrino.h"
#include "leptrino/sim.h"

#define EXIT_USAGE 2

static const char usage[] =
    "usage: leptrino-sim [options]\n"
    "A virtual Leptrino force/torque sensor on a pseudo-terminal. Prints the port\n"
    "path as the first line of stdout, then serves until SIGINT/SIGTERM/SIGHUP.\n"
    "SIGUSR1 power-cycles the sensor (a filter setting takes effect then).\n"
    "\n"
    "identity:\n"
    "  --model NAME          CFS018CA201U, CFS034CA301U, PFS055YA501U6 (default), PFS080YS102U6\n"
    "  --serial DIGITS       1..8 digits (default 00000001)\n"
    "  --firmware VER        1..4 characters (default 1.13)\n"
    "  --output-rate-field   answer product info in the 38-byte form with the output rate\n"
    "  --filter CODE         filter code in effect at power-on, 0..3 (default 0)\n"
    "signal:\n"
    "  --rate HZ             continuous output rate, 1..10000 (default 1200)\n"
    "  --seed N              waveform and fault randomness (default 1)\n"
    "  --amplitude F         sine amplitude, fraction of rated (default 0.2)\n"
    "  --noise F             noise amplitude, fraction of rated (default 0.005)\n"
    "  --constant            constant load (amplitude as the level), no noise\n"
    "  --replay FILE         replay raw counts fx,fy,fz,mx,my,mz[,status] per line, looping\n"
    "  --overload-every S    an overload episode every S seconds of a stream\n"
    "  --overload-duration S length of an episode (default 0.1)\n"
    "faults:\n"
    "  --nak P               probability of NAKing a valid command\n"
    "  --corrupt P           probability of flipping a bit of an outgoing message\n"
    "  --garbage P           probability of garbage bytes before an outgoing message\n"
    "  --drop P              probability of dropping a data message\n"
    "  --stall MS            stall (send nothing, answer nothing) for MS milliseconds ...\n"
    "  --stall-after S       ... S seconds after start (default 0)\n"
    "  --hangup-after S      hang up (close the port) S seconds after start\n"
    "  --reopen-after MS     after a hang-up, reopen after MS ms at the --link path\n"
    "  --start-streaming     power up already streaming (a stream left by an earlier program)\n"
    "other:\n"
    "  --link PATH           also make a symlink to the port at PATH; the first line shows it\n"
    "  --exit-after S        exit by itself after S seconds (0: never)\n"
    "  --stats               print the simulator's counters on stderr at exit\n"
    "  --list-models         print the model presets with their rated values, then exit\n"
    "  --help, --version\n";

static int bad(const char *msg, const char *opt, const char *val)
{
    if (val != NULL)
        fprintf(stderr, "leptrino-sim: %s %s: %s (see --help)\n", opt, val, msg);
    else
        fprintf(stderr, "leptrino-sim: %s: %s (see --help)\n", opt, msg);
    return EXIT_USAGE;
}

static int parse_double(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || errno != 0 || !(v >= lo && v <= hi))
        return -1;
    *out = v;
    return 0;
}

static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno != 0 || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

static int list_models(void)
{
    const char *const *m;
    printf("%-14s %8s %8s %8s %8s %8s %8s\n", "model", "Fx[N]", "Fy[N]", "Fz[N]", "Mx[Nm]",
           "My[Nm]", "Mz[Nm]");
    for (m = lep_sim_models(); *m != NULL; m++) {
        lep_rated r;
        if (lep_sim_model_rated(*m, &r) != LEP_OK)
            continue;
        printf("%-14s %8g %8g %8g %8g %8g %8g\n", *m, (double)r.axis[0], (double)r.axis[1],
               (double)r.axis[2], (double)r.axis[3], (double)r.axis[4], (double)r.axis[5]);
    }
    return 0;
}

struct cli {
    lep_sim_options o;
    double exit_after;
    int stats;
};

/* True when name is opt; its value is then in *val (from "=VALUE" or the
 * next argument), or *missing is set when there is none. */
static int takes(const char *name, const char *opt, const char **val, int argc, char **argv,
                 int *i, int *missing)
{
    if (strcmp(name, opt) != 0)
        return 0;
    if (*val != NULL)
        return 1;
    if (*i + 1 < argc) {
        *val = argv[++*i];
        return 1;
    }
    *missing = 1;
    return 0;
}

/* Parse argv into c. Returns -1 to go on, else an exit code. */
static int parse(int argc, char **argv, struct cli *c)
{
    int i;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL;
        char name[40];
        const char *eq;
        double d;
        long l;
        if (strncmp(a, "--", 2) != 0)
            return bad("unexpected argument", a, NULL);
        eq = strchr(a, '=');
        if (eq != NULL) {
            size_t n = (size_t)(eq - a);
            if (n >= sizeof name)
                return bad("unknown option", a, NULL);
            memcpy(name, a, n);
            name[n] = '\0';
            val = eq + 1;
        } else {
            if (strlen(a) >= sizeof name)
                return bad("unknown option", a, NULL);
            strcpy(name, a);
        }
#define FLAG(opt) (strcmp(name, opt) == 0 && val == NULL)
#define TAKES(opt) takes(name, opt, &val, argc, argv, &i, &missing)
        {
            int missing = 0;
            if (FLAG("--help")) {
                fputs(usage, stdout);
                return 0;
            } else if (FLAG("--version")) {
                printf("leptrino-sim %s\n", lep_version());
                return 0;
            } else if (FLAG("--list-models")) {
                return list_models();
            } else if (FLAG("--output-rate-field")) {
                c->o.output_rate_field = true;
            } else if (FLAG("--constant")) {
                c->o.constant = true;
            } else if (FLAG("--start-streaming")) {
                c->o.start_streaming = true;
            } else if (FLAG("--stats")) {
                c->stats = 1;
            } else if (TAKES("--model")) {
                lep_rated r;
                if (lep_sim_model_rated(val, &r) != LEP_OK)
                    return bad("unknown model (see --list-models)", name, val);
                c->o.model = val;
            } else if (TAKES("--serial")) {
                c->o.serial = val;
            } else if (TAKES("--firmware")) {
                c->o.firmware = val;
            } else if (TAKES("--filter")) {
                if (parse_long(val, 0, 3, &l) != 0)
                    return bad("expected a filter code 0..3", name, val);
                c->o.filter = (uint8_t)l;
            } else if (TAKES("--rate")) {
                if (parse_double(val, 1.0, 10000.0, &d) != 0)
                    return bad("expected a rate in Hz, 1..10000", name, val);
                c->o.rate_hz = d;
            } else if (TAKES("--seed")) {
                char *end;
                errno = 0;
                c->o.seed = strtoull(val, &end, 0);
                if (end == val || *end != '\0' || errno != 0 || val[0] == '-')
                    return bad("expected a non-negative integer", name, val);
            } else if (TAKES("--amplitude")) {
                if (parse_double(val, 0.0, 4.0, &d) != 0)
                    return bad("expected a fraction of rated, 0..4", name, val);
                c->o.amplitude = d;
            } else if (TAKES("--noise")) {
                if (parse_double(val, 0.0, 1.0, &d) != 0)
                    return bad("expected a fraction of rated, 0..1", name, val);
                c->o.noise = d;
            } else if (TAKES("--replay")) {
                c->o.replay_csv = val;
            } else if (TAKES("--overload-every")) {
                if (parse_double(val, 0.0, 1e6, &d) != 0)
                    return bad("expected seconds >= 0", name, val);
                c->o.overload_every_s = d;
            } else if (TAKES("--overload-duration")) {
                if (parse_double(val, 1e-6, 1e6, &d) != 0)
                    return bad("expected seconds > 0", name, val);
                c->o.overload_duration_s = d;
            } else if (TAKES("--nak") || TAKES("--corrupt") || TAKES("--garbage") ||
                       TAKES("--drop")) {
                if (parse_double(val, 0.0, 1.0, &d) != 0)
                    return bad("expected a probability 0..1", name, val);
                if (strcmp(name, "--nak") == 0)
                    c->o.p_nak = d;
                else if (strcmp(name, "--corrupt") == 0)
                    c->o.p_corrupt = d;
                else if (strcmp(name, "--garbage") == 0)
                    c->o.p_garbage = d;
                else
                    c->o.p_drop = d;
            } else if (TAKES("--stall")) {
                if (parse_long(val, 0, INT_MAX, &l) != 0)
                    return bad("expected milliseconds >= 0", name, val);
                c->o.stall_ms = (int)l;
            } else if (TAKES("--stall-after")) {
                if (parse_double(val, 0.0, 1e6, &d) != 0)
                    return bad("expected seconds >= 0", name, val);
                c->o.stall_after_s = d;
            } else if (TAKES("--hangup-after")) {
                if (parse_double(val, 0.0, 1e6, &d) != 0)
                    return bad("expected seconds >= 0", name, val);
                c->o.hangup_after_s = d;
            } else if (TAKES("--reopen-after")) {
                if (parse_long(val, 0, INT_MAX, &l) != 0)
                    return bad("expected milliseconds >= 0", name, val);
                c->o.reopen_after_ms = (int)l;
            } else if (TAKES("--link")) {
                if (val[0] == '\0')
                    return bad("expected a path", name, NULL);
                c->o.link = val;
            } else if (TAKES("--exit-after")) {
                if (parse_double(val, 0.0, 1e9, &d) != 0)
                    return bad("expected seconds >= 0", name, val);
                c->exit_after = d;
            } else if (missing) {
                return bad("needs a value", name, NULL);
            } else if (val != NULL && (strcmp(name, "--help") == 0 || strcmp(name, "--version") == 0 ||
                                       strcmp(name, "--constant") == 0 ||
                                       strcmp(name, "--stats") == 0 ||
                                       strcmp(name, "--list-models") == 0 ||
                                       strcmp(name, "--output-rate-field") == 0 ||
                                       strcmp(name, "--start-streaming") == 0)) {
                return bad("takes no value", name, NULL);
            } else {
                return bad("unknown option", name, NULL);
            }
        }
#undef FLAG
#undef TAKES
    }
    if (c->o.reopen_after_ms >= 0 && c->o.link == NULL)
        return bad("needs --link PATH (the path that survives the reopen)", "--reopen-after", NULL);
    if (c->o.stall_after_s > 0 && c->o.stall_ms == 0)
        return bad("needs --stall MS", "--stall-after", NULL);
    return -1;
}

static void print_stats(lep_sim *s)
{
    lep_sim_stats st;
    lep_sim_get_stats(s, &st);
    fprintf(stderr,
            "leptrino-sim: %llu samples sent, %llu dropped, %llu skipped, %llu blocked; "
            "%llu commands, %llu NAKs (%llu faked), %llu corrupted, %llu garbage bytes, "
            "%llu hang-ups, %llu reopens, %llu power cycles\n",
            (unsigned long long)st.samples_sent, (unsigned long long)st.samples_dropped,
            (unsigned long long)st.samples_skipped, (unsigned long long)st.samples_blocked,
            (unsigned long long)st.commands, (unsigned long long)st.naks,
            (unsigned long long)st.faked_naks, (unsigned long long)st.bytes_corrupted,
            (unsigned long long)st.garbage_bytes, (unsigned long long)st.hangups,
            (unsigned long long)st.reopens, (unsigned long long)st.power_cycles);
}

int main(int argc, char **argv)
{
    struct cli c;
    lep_sim *sim = NULL;
    char err[256];
    sigset_t set;
    int rc;

    memset(&c, 0, sizeof c);
    lep_sim_options_init(&c.o);
    rc = parse(argc, argv, &c);
    if (rc >= 0)
        return rc;

    /* Signals are taken synchronously with sigwait (the sim thread blocks all). */
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    sigaddset(&set, SIGUSR1);
    sigaddset(&set, SIGALRM);
    pthread_sigmask(SIG_BLOCK, &set, NULL);
    signal(SIGPIPE, SIG_IGN);

    rc = lep_sim_start(&c.o, &sim, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino-sim: %s\n", err[0] ? err : lep_strerror(rc));
        return rc == LEP_E_ARG ? EXIT_USAGE : 1;
    }
    printf("%s\n", lep_sim_port(sim));
    fflush(stdout);
    if (strcmp(lep_sim_port(sim), lep_sim_pty_path(sim)) != 0)
        fprintf(stderr, "leptrino-sim: %s -> %s\n", lep_sim_port(sim), lep_sim_pty_path(sim));

    if (c.exit_after > 0) {
        struct itimerval it;
        memset(&it, 0, sizeof it);
        it.it_value.tv_sec = (time_t)c.exit_after;
        it.it_value.tv_usec = (suseconds_t)((c.exit_after - (double)it.it_value.tv_sec) * 1e6);
        if (it.it_value.tv_sec == 0 && it.it_value.tv_usec == 0)
            it.it_value.tv_usec = 1;
        if (setitimer(ITIMER_REAL, &it, NULL) != 0)
            fprintf(stderr, "leptrino-sim: --exit-after: cannot arm a timer\n");
    }

    for (;;) {
        int sig = 0;
        if (sigwait(&set, &sig) != 0)
            continue;
        if (sig == SIGUSR1) {
            lep_sim_power_cycle(sim);
            continue;
        }
        break; /* SIGINT, SIGTERM, SIGHUP, SIGALRM (--exit-after) */
    }
    if (c.stats)
        print_stats(sim);
    lep_sim_stop(sim);
    return 0;
}
