/* The options about the load on the sensor, shared by the commands that take
 * them (`stream`, `watch`): --payload, --gravity and --limit into a
 * lep_session_options, and their help. The session does the compensation and
 * the limits; the limits' text syntax and the merge of a repeated --limit are
 * the library's (lep_limits_add). */
#include <string.h>

#include "cli.h"

bool cli_load_option(cli_args *a, lep_session_options *so, bool limits)
{
    const char *v;
    if (cli_args_is(a, NULL, "--payload")) {
        double p[4];
        if (cli_args_doubles(a, p, 4)) {
            if (p[0] < 0.0)
                cli_args_error(a, "option --payload: the mass %g kg is negative", p[0]);
            so->payload.mass_kg = p[0];
            memcpy(so->payload.com_m, p + 1, sizeof so->payload.com_m);
        }
    } else if (cli_args_is(a, NULL, "--gravity")) {
        (void)cli_args_doubles(a, so->gravity, 3);
    } else if (limits && cli_args_is(a, NULL, "--limit")) {
        v = cli_args_value(a);
        /* a repeated --limit adds its axes: the library's merge rule */
        if (v != NULL && lep_limits_add(v, so->limit) != LEP_OK)
            cli_args_error(a,
                           "option --limit: '%s' is not AXIS=VALUE,... with AXIS one of "
                           "fx, fy, fz, mx, my, mz and VALUE > 0 (N, N m), each axis limited "
                           "once over every --limit",
                           v);
    } else {
        return false;
    }
    return true;
}

void cli_load_help(FILE *f, bool limits)
{
    fputs("      --payload M,CX,CY,CZ a tool on the sensor: mass kg, centre of mass m\n"
          "                           (sensor frame; from `leptrino payload`): its\n"
          "                           gravity wrench is removed from the SI values (raw\n"
          "                           and zeroed counts stay as measured); a tare then\n"
          "                           removes the bias only\n"
          "      --gravity GX,GY,GZ   gravity in the sensor frame, m/s^2 (default\n"
          "                           0,0,-9.80665: the z axis up)\n",
          f);
    if (limits)
        fputs("      --limit AXIS=V,...   limits on the SI values (after compensation, in the\n"
              "                           output frame), N and N m, e.g. fz=50,mz=2: samples\n"
              "                           beyond are flagged 16, '# limit exceeded' and\n"
              "                           '# limit cleared' lines mark each episode\n"
              "                           (repeatable: the axes add up; an axis limited\n"
              "                           twice is refused)\n",
              f);
}
