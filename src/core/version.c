/* Runtime version of the loaded library. */
#include "leptrino/leptrino.h"

const char *lep_version(void)
{
    return LEP_VERSION_STRING;
}
