/* Virtual sensor: the link path (a symlink to the pty). Who owns it, what may
 * be replaced, pointing it at a new pty atomically, removing it.
 *
 * Ownership: a running virtual sensor holds an exclusive flock on
 * "<link>.lock" (a small file it marks as its own) for as long as it runs;
 * the kernel drops the lock when the process dies, however it dies. A
 * sensor that cannot take the lock refuses the path. Holding the lock, it
 * replaces only nothing, or a symlink to a pseudo-terminal (a link left by
 * a sensor that is gone); anything else at the path is refused and kept. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "sim_priv.h"

/* First line of a lock file: how a sensor knows the file is its kind's. */
static const char lock_mark[] = "leptrino-sim link lock\n";

/* Paths of pseudo-terminal slaves: /dev/pts/N (Linux, the BSDs), /dev/ttysNNN (macOS). */
static bool pty_name(const char *p)
{
    return strncmp(p, "/dev/pts/", 9) == 0 ||
           (strncmp(p, "/dev/ttys", 9) == 0 && p[9] >= '0' && p[9] <= '9');
}

static const char *kind_of(mode_t m)
{
    if (S_ISREG(m))
        return "a regular file";
    if (S_ISDIR(m))
        return "a directory";
    if (S_ISCHR(m) || S_ISBLK(m))
        return "a device node";
    if (S_ISFIFO(m))
        return "a FIFO";
    if (S_ISSOCK(m))
        return "a socket";
    return "something";
}

/* May the link path be (re)placed? Nothing there, or a symlink to a
 * pseudo-terminal (existing or gone). LEP_E_BUSY with a message otherwise. */
static int replaceable(const char *link, char *err, size_t errlen)
{
    struct stat st;
    char target[PATH_MAX];
    ssize_t n;
    if (lstat(link, &st) != 0) {
        if (errno == ENOENT)
            return LEP_OK;
        lep_priv_set_err(err, errlen, "link %s: %s", link, strerror(errno));
        return LEP_E_IO;
    }
    if (!S_ISLNK(st.st_mode)) {
        lep_priv_set_err(err, errlen,
                         "link %s: the path holds %s; only a stale link to a pseudo-terminal "
                         "is replaced (nothing was changed)",
                         link, kind_of(st.st_mode));
        return LEP_E_BUSY;
    }
    n = readlink(link, target, sizeof target - 1);
    if (n < 0) {
        lep_priv_set_err(err, errlen, "link %s: %s", link, strerror(errno));
        return LEP_E_IO;
    }
    target[n] = '\0';
    if (pty_name(target)) {
        if (stat(link, &st) != 0 || S_ISCHR(st.st_mode))
            return LEP_OK; /* gone, or still a terminal: a stale sensor link */
    }
    lep_priv_set_err(err, errlen,
                     "link %s: a symbolic link to %s, not to a pseudo-terminal; only a stale "
                     "link to a pseudo-terminal is replaced (nothing was changed)",
                     link, target);
    return LEP_E_BUSY;
}

/* The pid written in a lock file, or 0. */
static long lock_pid(int fd)
{
    char buf[128];
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    const char *p;
    if (n <= 0)
        return 0;
    buf[n] = '\0';
    p = strstr(buf, "pid ");
    return p != NULL ? strtol(p + 4, NULL, 10) : 0;
}

/* Open the lock file: create it with our mark, or open one that carries it. */
static int open_lock(const char *path, char *err, size_t errlen)
{
    struct stat st;
    char buf[sizeof lock_mark];
    int fd = open(path, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) {
        if (write(fd, lock_mark, sizeof lock_mark - 1) != (ssize_t)(sizeof lock_mark - 1)) {
            lep_priv_set_err(err, errlen, "%s: cannot write: %s", path, strerror(errno));
            (void)unlink(path);
            close(fd);
            return -1;
        }
        return fd;
    }
    if (errno != EEXIST) {
        lep_priv_set_err(err, errlen,
                         "%s: cannot create the link's lock file: %s (nothing was changed)", path,
                         strerror(errno));
        return -1;
    }
    fd = open(path, O_RDWR | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > 256 ||
        pread(fd, buf, sizeof lock_mark - 1, 0) != (ssize_t)(sizeof lock_mark - 1) ||
        memcmp(buf, lock_mark, sizeof lock_mark - 1) != 0) {
        lep_priv_set_err(err, errlen,
                         "%s exists and is not a leptrino-sim lock file (nothing was changed)",
                         path);
        if (fd >= 0)
            close(fd);
        return -1;
    }
    return fd;
}

int lep_priv_sim_link_claim(lep_sim *s, char *err, size_t errlen)
{
    int tries;
    s->lock_fd = -1;
    if (s->link[0] == '\0')
        return LEP_OK;
    if (snprintf(s->lock_path, sizeof s->lock_path, "%s.lock", s->link) >=
        (int)sizeof s->lock_path) {
        lep_priv_set_err(err, errlen, "link %s: path too long", s->link);
        return LEP_E_ARG;
    }
    for (tries = 0; tries < 8; tries++) {
        struct stat a, b;
        char line[48];
        int n, fd = open_lock(s->lock_path, err, errlen);
        if (fd < 0)
            return LEP_E_BUSY;
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            long pid = lock_pid(fd);
            if (pid > 0)
                lep_priv_set_err(err, errlen,
                                 "link %s belongs to a running virtual sensor (pid %ld); "
                                 "choose another path",
                                 s->link, pid);
            else
                lep_priv_set_err(err, errlen,
                                 "link %s belongs to a running virtual sensor; choose another path",
                                 s->link);
            close(fd);
            return LEP_E_BUSY;
        }
        /* The file we locked must still be the one at the path: an owner
         * that stopped meanwhile removed it, and a newcomer made another. */
        if (fstat(fd, &a) != 0 || stat(s->lock_path, &b) != 0 || a.st_dev != b.st_dev ||
            a.st_ino != b.st_ino) {
            close(fd);
            continue;
        }
        n = snprintf(line, sizeof line, "pid %ld\n", (long)getpid());
        if (ftruncate(fd, (off_t)(sizeof lock_mark - 1)) != 0 ||
            pwrite(fd, line, (size_t)n, (off_t)(sizeof lock_mark - 1)) != n) {
            /* the pid is for messages only: go on without it */
        }
        s->lock_fd = fd;
        return replaceable(s->link, err, errlen);
    }
    lep_priv_set_err(err, errlen, "link %s: its lock file keeps changing", s->link);
    return LEP_E_BUSY;
}

void lep_priv_sim_link_release(lep_sim *s)
{
    struct stat a, b;
    if (s->lock_fd < 0)
        return;
    /* Still ours at the path (we hold the lock): remove it, then unlock. */
    if (fstat(s->lock_fd, &a) == 0 && stat(s->lock_path, &b) == 0 && a.st_dev == b.st_dev &&
        a.st_ino == b.st_ino)
        (void)unlink(s->lock_path);
    close(s->lock_fd);
    s->lock_fd = -1;
}

/* Point link at target atomically (a new symlink renamed over the old), if
 * what is at the path may be replaced. */
int lep_priv_sim_relink(const lep_sim *s, char *err, size_t errlen)
{
    char tmp[PATH_MAX + 32];
    struct stat st;
    int rc = replaceable(s->link, err, errlen);
    if (rc != LEP_OK)
        return rc;
    if (snprintf(tmp, sizeof tmp, "%s.%ld.tmp", s->link, (long)getpid()) >= (int)sizeof tmp) {
        lep_priv_set_err(err, errlen, "link %s: path too long", s->link);
        return LEP_E_ARG;
    }
    /* A temporary link left by a sensor of this pid that died: ours to remove. */
    if (lstat(tmp, &st) == 0 && S_ISLNK(st.st_mode))
        (void)unlink(tmp);
    if (symlink(s->pty, tmp) != 0) {
        lep_priv_set_err(err, errlen, "link %s: cannot make %s: %s", s->link, tmp, strerror(errno));
        return LEP_E_IO;
    }
    if (rename(tmp, s->link) != 0) {
        lep_priv_set_err(err, errlen, "link %s: cannot make the link: %s", s->link,
                         strerror(errno));
        (void)unlink(tmp);
        return LEP_E_IO;
    }
    return LEP_OK;
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
