/* Read a Leptrino sensor: identify it, then print 10 streamed samples in N and N m.
 * usage: example_stream PORT      (a real sensor, e.g. /dev/ttyACM0)
 *        example_stream --sim     (the built-in virtual sensor) */
#include <leptrino/leptrino.h>
#include <leptrino/serial.h>
#include <leptrino/sim.h>
#include <stdio.h>
#include <string.h>

static int fail(const char *what, int rc)
{
    fprintf(stderr, "example_stream: %s: %s\n", what, lep_strerror(rc));
    return 1;
}

int main(int argc, char **argv)
{
    char err[256];
    lep_sim *sim = NULL;
    lep_serial *port = NULL;
    lep_client client;
    lep_product_info info;
    lep_rated rated;
    const char *path;
    int rc;
    int i;

    if (argc != 2) {
        fprintf(stderr, "usage: example_stream PORT|--sim\n");
        return 2;
    }
    path = argv[1];
    if (strcmp(path, "--sim") == 0) {
        lep_sim_options opt;
        lep_sim_options_init(&opt);
        if ((rc = lep_sim_start_so(&opt, &sim, err, sizeof(err))) != LEP_OK) {
            fprintf(stderr, "example_stream: %s\n", err);
            return 1;
        }
        path = lep_sim_port(sim);
    }
    if ((rc = lep_serial_open(path, &port, err, sizeof(err))) != LEP_OK) {
        fprintf(stderr, "example_stream: %s\n", err);
        lep_sim_stop(sim);
        return 1;
    }
    lep_serial_client_init(&client, port);

    /* Stop a stream an earlier program may have left running, then identify. */
    if ((rc = lep_client_sync(&client, 50, &info)) != LEP_OK ||
        (rc = lep_client_rated(&client, &rated)) != LEP_OK) {
        return fail("sensor not answering", rc);
    }
    printf("%s serial %s firmware %s\n", info.model, info.serial, info.firmware);

    if ((rc = lep_client_start(&client)) != LEP_OK) {
        return fail("start", rc);
    }
    for (i = 0; i < 10; i++) {
        lep_sample s;
        double si[LEP_AXES];
        if ((rc = lep_client_next_sample(&client, &s, 100)) != LEP_OK) {
            break;
        }
        lep_sample_to_si(&s, &rated, si);
        printf("Fx %8.3f Fy %8.3f Fz %8.3f N   Mx %7.4f My %7.4f Mz %7.4f N m  status 0x%02x\n",
               si[LEP_FX], si[LEP_FY], si[LEP_FZ], si[LEP_MX], si[LEP_MY], si[LEP_MZ], s.status);
    }
    (void)lep_client_stop(&client);
    lep_serial_close(port);
    lep_sim_stop(sim);
    return rc == LEP_OK ? 0 : fail("stream", rc);
}
