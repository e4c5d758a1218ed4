/* Virtual sensor: the link path (a symlink to the pty) made and removed. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "sim_priv.h"

/* Point link at target atomically (a new symlink renamed over the old). */
int lep_priv_sim_relink(const char *link, const char *target)
{
    char tmp[PATH_MAX + 32];
    int n = snprintf(tmp, sizeof tmp, "%s.%ld.tmp", link, (long)getpid());
    if (n < 0 || (size_t)n >= sizeof tmp)
        return -1;
    (void)unlink(tmp);
    if (symlink(target, tmp) != 0)
        return -1;
    if (rename(tmp, link) != 0) {
        (void)unlink(tmp);
        return -1;
    }
    return 0;
}

/* Remove the link only while it still points at our pty. */
void lep_priv_sim_remove_link(const lep_sim *s)
{
    char target[PATH_MAX];
    ssize_t n;
    if (s->link == NULL || s->link[0] == '\0')
        return;
    n = readlink(s->link, target, sizeof target - 1);
    if (n < 0)
        return;
    target[n] = '\0';
    if (strcmp(target, s->pty) == 0)
        (void)unlink(s->link);
}
