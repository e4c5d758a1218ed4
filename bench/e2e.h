/* leptrino-bench end to end: the client over a pty against leptrino-sim
 * running as another process, plus the Python per-sample costs. */
#ifndef LEPTRINO_BENCH_E2E_H
#define LEPTRINO_BENCH_E2E_H

typedef struct e2e_options {
    const char *self;   /* this program (re-run under strace for syscall counts) */
    const char *sim;    /* leptrino-sim */
    const char *python; /* interpreter for the Python bench */
    const char *source; /* source tree (bindings/python/bench_record.py) */
    int smoke;          /* short runs */
} e2e_options;

void e2e_defaults(e2e_options *o, const char *self);
/* Writes the "end_to_end" and "python" members of the open JSON object. */
void e2e_report(const e2e_options *o);
/* `--e2e-child MODE PORT SECONDS`: stream from PORT, for strace. */
int e2e_child_main(int argc, char **argv);

#endif
