/* `leptrino payload`: identify a tool's mass and centre of mass from poses
 * recorded with `leptrino stream`. The reading of a pose and the
 * identification are the library's (leptrino/payload.h); this parses the
 * arguments and prints. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <leptrino/payload.h>
#include "struct_api.h"

#include "cli.h"

#define MAX_POSES 64

static void help(void)
{
    fputs("Usage: leptrino payload POSE.csv@GX,GY,GZ POSE.csv@GX,GY,GZ ... [options]\n"
          "\n"
          "Identify the mass and centre of mass of a tool mounted on the sensor, and\n"
          "the sensor's force and torque biases, from 3 or more static poses. Each\n"
          "POSE.csv is a recording made with `leptrino stream` (CSV) while the robot\n"
          "held still; GX,GY,GZ is gravity in the sensor frame at that pose, m/s^2\n"
          "((0,0,-9.80665) when the sensor's z axis points up). Any tare in a\n"
          "recording is added back and any --rotate/--shift undone: the result is in\n"
          "the sensor frame. The model: F = m g + F_b, M = c x (m g) + M_b, solved\n"
          "by linear least squares (Kubus, Kroeger and Wahl, 2008).\n"
          "\n"
          "The gravity vectors must span more than one line: tilt the tool about two\n"
          "different axes between poses (turning it about the vertical changes\n"
          "nothing). A set that does not determine the payload is refused (exit 1),\n"
          "never answered.\n"
          "\n"
          "Prints the payload, the biases, the residual (per axis, RMS over the\n"
          "poses of measured - model) and the argument for --payload / --sim-payload.\n"
          "\n"
          "Options:\n"
          "  --json                   one JSON object instead of the text\n"
          "  -h, --help               show this help\n"
          "\n"
          "Example:\n"
          "  leptrino stream /dev/ttyACM0 --duration 2 -o up.csv     (robot holds still)\n"
          "  ...\n"
          "  leptrino payload up.csv@0,0,-9.80665 tilt-x.csv@0,6.93,-6.93 \\\n"
          "                   tilt-y.csv@-6.93,0,-6.93\n"
          "\n",
          stdout);
    cli_print_help_end(stdout, 0);
}

/* "PATH@GX,GY,GZ" into path (in place) and g; false when malformed. */
static bool parse_pose(char *arg, double g[3])
{
    char *at = strrchr(arg, '@');
    const char *p;
    int k;
    if (at == NULL || at == arg)
        return false;
    p = at + 1;
    for (k = 0; k < 3; k++) {
        char *end;
        errno = 0;
        g[k] = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(g[k]) || (k < 2 ? *end != ',' : *end != '\0'))
            return false;
        p = end + 1;
    }
    *at = '\0'; /* arg is the path now */
    return true;
}

static void vec(const char *sep, const double *v, int n)
{
    int k;
    for (k = 0; k < n; k++)
        printf("%s%.9g", k > 0 ? sep : "", v[k]);
}

static void print_text(const lep_payload_fit *f, const uint64_t *samples, size_t n)
{
    size_t i;
    printf("%-14s%zu (", "poses:", n);
    for (i = 0; i < n; i++)
        printf("%s%llu", i > 0 ? ", " : "", (unsigned long long)samples[i]);
    printf(" samples)\n");
    printf("%-14s%.6g kg\n", "mass:", f->payload.mass_kg);
    printf("%-14s", "com:");
    vec(" ", f->payload.com_m, 3);
    printf(" m (x y z, sensor frame)\n");
    printf("%-14s", "force bias:");
    vec(" ", f->force_bias_N, 3);
    printf(" N\n%-14s", "torque bias:");
    vec(" ", f->torque_bias_Nm, 3);
    printf(" N m\n");
    printf("%-14sfx %.3g fy %.3g fz %.3g N, mx %.3g my %.3g mz %.3g N m (RMS over the poses)\n",
           "residual:", f->residual[0], f->residual[1], f->residual[2], f->residual[3],
           f->residual[4], f->residual[5]);
    printf("%-14s%.3g (at least %g)\n", "spread:", f->spread, LEP_PAYLOAD_MIN_SPREAD);
    printf("%-14s--payload %.9g,%.9g,%.9g,%.9g\n", "use:", f->payload.mass_kg, f->payload.com_m[0],
           f->payload.com_m[1], f->payload.com_m[2]);
}

static void print_json(const lep_payload_fit *f, const uint64_t *samples, size_t n)
{
    size_t i;
    printf("{\"mass_kg\":%.17g,\"com_m\":[", f->payload.mass_kg);
    vec(",", f->payload.com_m, 3);
    printf("],\"force_bias_N\":[");
    vec(",", f->force_bias_N, 3);
    printf("],\"torque_bias_Nm\":[");
    vec(",", f->torque_bias_Nm, 3);
    printf("],\"residual\":[");
    vec(",", f->residual, LEP_AXES);
    printf("],\"spread\":%.9g,\"poses\":%zu,\"samples\":[", f->spread, n);
    for (i = 0; i < n; i++)
        printf("%s%llu", i > 0 ? "," : "", (unsigned long long)samples[i]);
    printf("],\"payload_argument\":\"%.9g,%.9g,%.9g,%.9g\"}\n", f->payload.mass_kg,
           f->payload.com_m[0], f->payload.com_m[1], f->payload.com_m[2]);
}

int cli_cmd_payload(int argc, char **argv)
{
    cli_args a;
    static double g[MAX_POSES * 3], w[MAX_POSES * LEP_AXES];
    static uint64_t samples[MAX_POSES];
    char *path[MAX_POSES];
    size_t n = 0, i;
    bool json = false;
    char err[512];
    lep_payload_fit fit;
    int rc;

    cli_args_init(&a, argc, argv, "payload");
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return CLI_OK;
        } else if (cli_args_is(&a, NULL, "--json")) {
            json = cli_args_flag(&a);
        } else if (a.positional) {
            if (n == MAX_POSES) {
                cli_args_error(&a, "more than %d poses", MAX_POSES);
                break;
            }
            path[n] = a.argv[a.next - 1];
            if (!parse_pose(path[n], &g[n * 3])) {
                cli_args_error(&a, "'%s' is not POSE.csv@GX,GY,GZ (gravity in m/s^2)", a.cur);
                break;
            }
            n++;
        } else {
            cli_args_unknown(&a);
        }
    }
    if (a.failed)
        return CLI_USAGE;
    if (n < LEP_PAYLOAD_MIN_POSES) {
        cli_args_error(&a, "%zu pose%s given: at least %u are needed", n, n == 1 ? "" : "s",
                       LEP_PAYLOAD_MIN_POSES);
        return CLI_USAGE;
    }
    for (i = 0; i < n; i++) {
        rc = lep_payload_pose_read(path[i], &w[i * LEP_AXES], &samples[i], err, sizeof err);
        if (rc != LEP_OK) {
            fprintf(stderr, "leptrino: payload: %s\n", err);
            return CLI_FAIL;
        }
    }
    rc = lep_payload_identify_fit(g, w, n, &fit, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino: payload: %s\n", err);
        return CLI_FAIL;
    }
    if (json)
        print_json(&fit, samples, n);
    else
        print_text(&fit, samples, n);
    return CLI_OK;
}
