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
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <pthread.h>

#include "leptrino/leptrino.h"
#include "leptrino/process.h"
#include "leptrino/sim.h"
#include "struct_api.h"

#define EXIT_USAGE 2

static const char usage_head[] =
    "usage: leptrino-sim [options]\n"
    "A virtual Leptrino force/torque sensor on a pseudo-terminal. Prints the port\n"
    "path as the first line of stdout, then serves until SIGINT/SIGTERM/SIGHUP.\n"
    "SIGUSR1 power-cycles the sensor (a filter setting takes effect then).\n"
    "\n"
    "virtual sensor (--NAME VALUE or --NAME=VALUE):\n";

static const char usage_tail[] =
    "program:\n"
    "  --exit-after S          exit by itself after S seconds (0: never)\n"
    "  --stats                 print the simulator's counters on stderr at exit\n"
    "  --trace-writes FILE     record when each data message was written (FILE must not exist;\n"
    "                          binary records, see docs/simulator.md; for benchmarks)\n"
    "  --list-models           print the model presets with their rated values, then exit\n"
    "  --help, --version\n";

/* One help line per row of the library's option table. */
static void print_usage(void)
{
    size_t i;
    fputs(usage_head, stdout);
    for (i = 0; i < lep_sim_option_count(); i++) {
        const lep_sim_option_info *in = lep_sim_option_at(i);
        char left[64];
        snprintf(left, sizeof left, "--%s%s%s", in->name, in->arg ? " " : "",
                 in->arg ? in->arg : "");
        printf("  %-22s %s", left, in->help);
        if (in->type == LEP_SIM_OPT_DOUBLE || in->type == LEP_SIM_OPT_INT ||
            (in->type == LEP_SIM_OPT_UINT && in->max < 1e18))
            printf(", %s%.15g..%.15g", in->min_exclusive ? ">" : "", in->min, in->max);
        if (in->default_text != NULL && in->type != LEP_SIM_OPT_CHOICE)
            printf(" (default %s)", in->default_text);
        else if (in->default_text != NULL)
            printf("\n  %-22s (default %s)", "", in->default_text);
        putchar('\n');
    }
    fputs(usage_tail, stdout);
}

static int bad(const char *msg, const char *opt, const char *val)
{
    if (val != NULL)
        fprintf(stderr, "leptrino-sim: %s %s: %s (see --help)\n", opt, val, msg);
    else
        fprintf(stderr, "leptrino-sim: %s: %s (see --help)\n", opt, msg);
    return EXIT_USAGE;
}

static int list_models(void)
{
    const char *const *m;
    printf("%-14s %8s %8s %8s %8s %8s %8s\n", "model", "Fx[N]", "Fy[N]", "Fz[N]", "Mx[Nm]",
           "My[Nm]", "Mz[Nm]");
    for (m = lep_sim_models(); *m != NULL; m++) {
        lep_rated r;
        if (lep_sim_model_rated_f(*m, &r) != LEP_OK)
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
    const char *trace_writes; /* --trace-writes FILE, or NULL */
};

/* Parse argv into c. Returns -1 to go on, else an exit code. */
static int parse(int argc, char **argv, struct cli *c)
{
    int i;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL, *eq;
        const lep_sim_option_info *in;
        char name[40], err[256];
        if (strncmp(a, "--", 2) != 0)
            return bad("unexpected argument", a, NULL);
        eq = strchr(a, '=');
        {
            size_t n = eq != NULL ? (size_t)(eq - a) : strlen(a);
            if (n >= sizeof name)
                return bad("unknown option", a, NULL);
            memcpy(name, a, n);
            name[n] = '\0';
        }
        if (eq != NULL)
            val = eq + 1;
        if (strcmp(name, "--help") == 0 || strcmp(name, "--version") == 0 ||
            strcmp(name, "--list-models") == 0 || strcmp(name, "--stats") == 0) {
            if (val != NULL)
                return bad("takes no value", name, NULL);
            if (strcmp(name, "--help") == 0) {
                print_usage();
                return 0;
            }
            if (strcmp(name, "--version") == 0) {
                printf("leptrino-sim %s\n", lep_version());
                return 0;
            }
            if (strcmp(name, "--list-models") == 0)
                return list_models();
            c->stats = 1;
            continue;
        }
        if (strcmp(name, "--trace-writes") == 0) {
            if (val == NULL && i + 1 < argc)
                val = argv[++i];
            if (val == NULL || val[0] == '\0')
                return bad("needs a file name", name, NULL);
            c->trace_writes = val;
            continue;
        }
        if (strcmp(name, "--exit-after") == 0) {
            char *end;
            if (val == NULL && i + 1 < argc)
                val = argv[++i];
            if (val == NULL)
                return bad("needs a value", name, NULL);
            errno = 0;
            c->exit_after = strtod(val, &end);
            if (end == val || *end != '\0' || errno != 0 ||
                !(c->exit_after >= 0.0 && c->exit_after <= 1e9))
                return bad("expected seconds, 0..1e9", name, val);
            continue;
        }
        /* The virtual sensor's own options: the library's table. Only the
         * dash-separated names here (no underscore or field aliases). */
        in = lep_sim_option_find(name + 2);
        if (in == NULL || strcmp(in->name, name + 2) != 0)
            return bad("unknown option", name, NULL);
        if (in->type == LEP_SIM_OPT_FLAG) {
            if (val != NULL)
                return bad("takes no value", name, NULL);
        } else if (val == NULL) {
            if (i + 1 >= argc)
                return bad("needs a value", name, NULL);
            val = argv[++i];
        }
        if (lep_sim_option_set(&c->o, in->name, val, err, sizeof err) != LEP_OK) {
            fprintf(stderr, "leptrino-sim: --%s (see --help)\n", err);
            return EXIT_USAGE;
        }
    }
    {
        char err[256];
        if (lep_sim_options_check(&c->o, err, sizeof err) != LEP_OK) {
            fprintf(stderr, "leptrino-sim: --%s (see --help)\n", err);
            return EXIT_USAGE;
        }
    }
    return -1;
}

static void print_stats(lep_sim *s)
{
    lep_sim_counters st;
    double cpu = lep_cpu_seconds();
    lep_sim_get_stats(s, &st);
    fprintf(stderr,
            "leptrino-sim: %llu samples sent, %llu dropped, %llu skipped, %llu blocked; "
            "%llu commands, %llu NAKs (%llu faked), %llu corrupted, %llu garbage bytes, "
            "%llu hang-ups, %llu reopens, %llu power cycles; "
            "CPU %.3f s (%.2f us per sample sent)\n",
            (unsigned long long)st.samples_sent, (unsigned long long)st.samples_dropped,
            (unsigned long long)st.samples_skipped, (unsigned long long)st.samples_blocked,
            (unsigned long long)st.commands, (unsigned long long)st.naks,
            (unsigned long long)st.faked_naks, (unsigned long long)st.bytes_corrupted,
            (unsigned long long)st.garbage_bytes, (unsigned long long)st.hangups,
            (unsigned long long)st.reopens, (unsigned long long)st.power_cycles, cpu,
            st.samples_sent > 0 ? cpu * 1e6 / (double)st.samples_sent : 0.0);
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

    err[0] = '\0';
    rc = lep_sim_start_so(&c.o, &sim, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino-sim: %s\n", err[0] ? err : lep_strerror(rc));
        return rc == LEP_E_ARG ? EXIT_USAGE : 1;
    }
    if (err[0] != '\0') /* started, with a warning (a replay file cut short) */
        fprintf(stderr, "leptrino-sim: warning: %s\n", err);
    if (c.trace_writes != NULL &&
        lep_sim_trace_writes(sim, c.trace_writes, err, sizeof err) != LEP_OK) {
        fprintf(stderr, "leptrino-sim: --trace-writes: %s\n", err);
        lep_sim_stop(sim);
        return 1;
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
