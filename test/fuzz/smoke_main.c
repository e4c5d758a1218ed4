/* Without libFuzzer: run the fuzz entry over the inputs of earlier finds
 * (FUZZ_REGRESSIONS: test/fuzz/regressions/<target>), then over a fixed
 * pseudo-random corpus of mutated valid frames, so every ctest run (and the
 * sanitizer run) exercises it. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <string.h>

#include "leptrino/leptrino.h"

#ifndef FUZZ_SMOKE_ITERATIONS
#define FUZZ_SMOKE_ITERATIONS 20000u
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint64_t state = 0x9E3779B97F4A7C15u;

static uint32_t next(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (uint32_t)(state >> 32);
}

#ifdef FUZZ_REGRESSIONS
/* Replay every file of the regression directory (none is fine). */
static unsigned replay(const char *dir)
{
    static uint8_t data[1u << 16];
    char path[4096];
    unsigned count = 0;
    struct dirent *e;
    DIR *d = opendir(dir);
    if (d == NULL) {
        return 0;
    }
    while ((e = readdir(d)) != NULL) {
        FILE *f;
        size_t n;
        if (e->d_name[0] == '.') {
            continue;
        }
        snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
        f = fopen(path, "rb");
        if (f == NULL) {
            continue;
        }
        n = fread(data, 1, sizeof(data), f);
        fclose(f);
        LLVMFuzzerTestOneInput(data, n);
        count++;
    }
    closedir(d);
    return count;
}
#endif

int main(void)
{
    static uint8_t buf[4096];
    unsigned iter;
    unsigned long bytes = 0;
#ifdef FUZZ_REGRESSIONS
    printf("fuzz smoke: %u regression inputs replayed\n", replay(FUZZ_REGRESSIONS));
#endif
    for (iter = 0; iter < (unsigned)FUZZ_SMOKE_ITERATIONS; iter++) {
        size_t len = 0;
        size_t target = next() % sizeof(buf);
        /* Mostly valid frames with a few flipped, dropped or inserted bytes. */
        while (len + LEP_MAX_FRAME < target) {
            uint8_t msg[LEP_MAX_MESSAGE];
            size_t n = 1 + next() % (iter % 7u == 0u ? LEP_MAX_MESSAGE : 24u);
            size_t i;
            size_t flen;
            for (i = 0; i < n; i++) {
                msg[i] = (uint8_t)(next() % 5u == 0u ? 0x10u : next());
            }
            if (n >= 4) {
                msg[0] = (uint8_t)n;
                msg[1] = 0xFF;
            }
            if (lep_frame_encode(msg, n, buf + len, sizeof(buf) - len, &flen) == LEP_OK) {
                len += flen;
            }
        }
        if (len > 0) {
            unsigned k;
            for (k = 0; k < iter % 5u; k++) {
                buf[next() % len] ^= (uint8_t)(1u << (next() % 8u));
            }
        }
        LLVMFuzzerTestOneInput(buf, len);
        bytes += (unsigned long)len;
    }
    printf("fuzz smoke: %u inputs, %lu bytes, invariants held\n", (unsigned)FUZZ_SMOKE_ITERATIONS,
           bytes);
    return 0;
}
