/* Read a Leptrino sensor through a session: identify it, stream 1 s and
 * report the count and rate, tare it, and show the error for a missing port.
 * usage: example_stream PORT      (a real sensor, e.g. /dev/ttyACM0)
 *        example_stream --sim     (the built-in virtual sensor, a constant load) */
#include <leptrino/leptrino.h>
#include <leptrino/session.h>
#include <stdio.h>
#include <string.h>

#define CAP 256

/* Read for `seconds`, returning the samples read and the mean Fz. */
static int stream_for(lep_session *s, double seconds, size_t *count, double *mean_fz)
{
    static double t[CAP], si[CAP * 6];
    double t0 = -1.0, sum = 0.0;
    size_t n, i;
    int rc;
    *count = 0;
    for (;;) {
        rc = lep_session_read(s, 500, CAP, &n, t, NULL, si, NULL, NULL, NULL, NULL, NULL);
        if (rc != LEP_OK)
            return rc;
        for (i = 0; i < n; i++) {
            if (t0 < 0.0)
                t0 = t[i];
            if (t[i] - t0 >= seconds) {
                *mean_fz = *count > 0 ? sum / (double)*count : 0.0;
                return LEP_OK;
            }
            sum += si[i * 6 + LEP_FZ];
            (*count)++;
        }
    }
}

int main(int argc, char **argv)
{
    char err[256], model[64], serial[32], firmware[16];
    double rated[6], ev[LEP_EVF_COUNT], fz = 0.0, health[LEP_H_COUNT];
    lep_options *o;
    lep_session *s = NULL;
    size_t count;
    int rc, missing;

    if (argc != 2) {
        fprintf(stderr, "usage: example_stream PORT|--sim\n");
        return 2;
    }
    o = lep_options_new();
    if (o == NULL)
        return 1;
    if (strcmp(argv[1], "--sim") == 0) {
        lep_options_set_int(o, "sim", 1, NULL, 0);
        lep_options_set_int(o, "sim-constant", 1, NULL, 0); /* a still load: the tare shows */
    } else if (lep_options_set(o, "port", argv[1], err, sizeof err) != LEP_OK) {
        fprintf(stderr, "example_stream: %s\n", err);
        return 2;
    }
    rc = lep_session_open(o, &s, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "example_stream: %s\n", err);
        lep_options_free(o);
        return 1;
    }
    lep_session_info(s, LEP_INFO_MODEL, model, sizeof model, NULL);
    lep_session_info(s, LEP_INFO_SERIAL, serial, sizeof serial, NULL);
    lep_session_info(s, LEP_INFO_FIRMWARE, firmware, sizeof firmware, NULL);
    lep_session_rated(s, rated);
    printf("%s serial %s firmware %s, rated Fz %g N Mz %g N m\n", model, serial, firmware,
           rated[LEP_FZ], rated[LEP_MZ]);

    if ((rc = lep_session_start(s)) != LEP_OK || (rc = stream_for(s, 1.0, &count, &fz)) != LEP_OK)
        goto out;
    lep_session_health(s, health, LEP_H_COUNT);
    printf("1 s: %zu samples, %.1f Hz, mean Fz %.3f N\n", count, health[LEP_H_MEASURED_HZ], fz);

    /* Tare over 100 samples; the event says when the new offsets hold. */
    if ((rc = lep_session_tare(s, 100, 0.0)) != LEP_OK)
        goto out;
    for (;;) {
        if ((rc = stream_for(s, 0.05, &count, &fz)) != LEP_OK)
            goto out;
        if (lep_session_next_event(s, ev, LEP_EVF_COUNT) == 1 && ev[LEP_EVF_TYPE] == LEP_EV_TARE)
            break;
    }
    if ((rc = stream_for(s, 0.2, &count, &fz)) != LEP_OK)
        goto out;
    printf("after the tare: mean Fz %.3f N\n", fz);
out:
    if (rc != LEP_OK)
        fprintf(stderr, "example_stream: %s\n", lep_strerror(rc));
    lep_session_close(s);

    /* A port that is not there: the code, and a message naming the port. */
    lep_options_set(o, "sim", "0", NULL, 0);
    lep_options_set(o, "port", "/dev/leptrino-missing", NULL, 0);
    missing = lep_session_open(o, &s, err, sizeof err);
    if (missing != LEP_OK)
        printf("missing port: %s (%s)\n", err, lep_strerror(missing));
    else
        lep_session_close(s);
    lep_options_free(o);
    return rc == LEP_OK ? 0 : 1;
}
