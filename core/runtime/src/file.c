/* Files a user names, opened without blocking (voxrg/plugin.h).
 *
 * open(2) of a FIFO waits for a writer, of a device may wait for ever, and
 * reading either never ends: a graph, a shader, a model, a journal or an
 * image named by a user could hang whoever opens it. With O_NONBLOCK the
 * open returns at once whatever the path is; fstat then tells a regular
 * file from the rest, checked on the descriptor itself, so that nothing can
 * be swapped in between the check and the use. */
#define _POSIX_C_SOURCE 200809L /* fdopen, O_CLOEXEC */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "voxrg/plugin.h"

int vrg_open_regular(const char *path, int flags)
{
    int fd = open(path, (flags & ~O_CREAT) | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return -1;
    struct stat st;
    int err = fstat(fd, &st) != 0 ? errno : S_ISDIR(st.st_mode) ? EISDIR : S_ISREG(st.st_mode) ? 0 : EINVAL;
    /* a regular file ignores O_NONBLOCK; cleared all the same, so that the
     * descriptor behaves as a plain open's */
    if (!err && fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0)
        err = errno;
    if (err) {
        close(fd);
        errno = err;
        return -1;
    }
    return fd;
}

FILE *vrg_fopen_regular(const char *path, const char *mode)
{
    int flags = mode[0] == 'a' ? O_WRONLY | O_APPEND : mode[0] == 'r' ? O_RDONLY : -1;
    if (flags < 0 || strchr(mode, 'w')) {
        errno = EINVAL;
        return NULL;
    }
    if (strchr(mode, '+'))
        flags = (flags & ~O_ACCMODE) | O_RDWR;
    int fd = vrg_open_regular(path, flags);
    FILE *f = fd >= 0 ? fdopen(fd, mode) : NULL;
    if (!f && fd >= 0) {
        int err = errno;
        close(fd);
        errno = err;
    }
    return f;
}

const char *vrg_open_strerror(int err) { return err == EINVAL ? "not a regular file" : strerror(err); }
