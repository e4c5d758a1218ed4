/* lep_cli_sim: a virtual sensor in its own process for the CLI tests, so
 * that the sensor outlives a `leptrino` run and can be inspected after it.
 *
 * Usage: lep_cli_sim [--rate HZ] [--constant] [--start-streaming]
 * Prints the port on the first line, then reads commands on stdin, one per
 * line, answering each with one line:
 *   stats  -> "streaming=0|1 samples=N filter=C pending=C commands=N hangups=N"
 *   power  -> power cycle (a pending filter applies), "ok"
 *   hangup -> hang up now, "ok"
 *   quit (or end of input) -> stop and exit 0 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <leptrino/leptrino.h>
#include <leptrino/sim.h>
#include "struct_api.h"

int main(int argc, char **argv)
{
    lep_sim_options o;
    lep_sim *sim = NULL;
    char err[256], line[128];
    int i;

    lep_sim_options_init(&o);
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--rate") == 0 && i + 1 < argc) {
            o.rate_hz = strtod(argv[++i], NULL);
        } else if (strcmp(argv[i], "--constant") == 0) {
            o.constant = true;
        } else if (strcmp(argv[i], "--start-streaming") == 0) {
            o.start_streaming = true;
        } else {
            fprintf(stderr, "lep_cli_sim: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (lep_sim_start_so(&o, &sim, err, sizeof err) != LEP_OK) {
        fprintf(stderr, "lep_cli_sim: %s\n", err);
        return 1;
    }
    printf("%s\n", lep_sim_port(sim));
    fflush(stdout);
    while (fgets(line, sizeof line, stdin) != NULL) {
        line[strcspn(line, "\r\n")] = '\0';
        if (strcmp(line, "stats") == 0) {
            lep_sim_counters st;
            lep_sim_get_stats(sim, &st);
            printf("streaming=%d samples=%llu filter=%u pending=%u commands=%llu hangups=%llu\n",
                   st.streaming ? 1 : 0, (unsigned long long)st.samples_sent, (unsigned)st.filter,
                   (unsigned)st.filter_pending, (unsigned long long)st.commands,
                   (unsigned long long)st.hangups);
        } else if (strcmp(line, "power") == 0) {
            lep_sim_power_cycle(sim);
            printf("ok\n");
        } else if (strcmp(line, "hangup") == 0) {
            lep_sim_hangup(sim);
            printf("ok\n");
        } else if (strcmp(line, "quit") == 0) {
            break;
        } else {
            printf("unknown command\n");
        }
        fflush(stdout);
    }
    lep_sim_stop(sim);
    return 0;
}
