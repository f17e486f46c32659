/* Output files written whole or not at all (voxrg/output.h).
 *
 * The data goes to a temporary file in the target's folder, so that the
 * final rename stays within one file system. Where the file system allows,
 * the temporary file has no name (O_TMPFILE) until it is linked in: a
 * process killed before that leaves nothing behind. Elsewhere it is a
 * uniquely named hidden file. Before the rename the data is flushed and
 * synced, so that a crash after it cannot leave an empty or short file under
 * the target's name; the folder is synced after it, so that the rename
 * itself survives a crash.
 *
 * The file put in place has the mode of the one it replaces (a new one
 * the umask's).
 *
 * A target that is not a regular file (a device such as /dev/stdout, a
 * pipe) cannot be replaced and is not: it is written directly. A symbolic
 * link to a file is followed, so that the file it names is replaced and
 * the link stays. */
#define _GNU_SOURCE /* O_TMPFILE, AT_EMPTY_PATH */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "voxrg/output.h"

#define PATH_CAP 4096 /* as PATH_MAX, which <limits.h> defines only for some feature macros */

struct vrg_output {
    FILE *f;
    int fd;     /* the file's own descriptor: the link is made through it after fclose */
    int dir_fd;
    int named;  /* 1: the temporary file has the name tmp; 0: unnamed until committed */
    int direct; /* 1: the target itself is written (not a regular file) */
    int err;    /* the reason of a failed write seen before the commit */
    char *path; /* the target, as given (for messages) */
    char *real; /* where a symbolic link at path leads; NULL if path is none */
    const char *base; /* the target's name within its folder (points into path) */
    char tmp[PATH_CAP];
};

static int fail(const char *path, const char *what, int err)
{
    fprintf(stderr, "error: cannot %s %s: %s\n", what, path, strerror(err ? err : EIO));
    return -1;
}

/* A name no other writer (another thread or process, on this machine or
 * another one sharing the folder over NFS, where process ids repeat, or an
 * earlier commit of this one) is using: hidden, with the target's name for
 * whoever finds it, then the host, process, a counter and random bits. */
static void temp_name(char *buf, size_t cap, const char *base)
{
    static unsigned counter;
    unsigned n = __atomic_fetch_add(&counter, 1, __ATOMIC_RELAXED), random = 0;
    char host[64] = "";
    if (gethostname(host, sizeof host) != 0 || strchr(host, '/'))
        host[0] = '\0';
    host[sizeof host - 1] = '\0';
    if (getrandom(&random, sizeof random, GRND_NONBLOCK) != (ssize_t)sizeof random)
        random ^= (unsigned)(uintptr_t)&random ^ (unsigned)time(NULL);
    /* the target's name cut to 150 bytes: with the suffix it stays within
     * NAME_MAX (255) however long a valid target name is */
    snprintf(buf, cap, ".%.150s.%.40s.%ld.%u.%08x.tmp", base, host, (long)getpid(), n, random);
}

/* The folder part of path ("." for a bare name) opened as a directory. */
static int open_dir(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (slash == path)
        return open("/", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    char dir[PATH_CAP];
    if ((size_t)(slash - path) >= sizeof dir) {
        errno = ENAMETOOLONG;
        return -1;
    }
    memcpy(dir, path, (size_t)(slash - path));
    dir[slash - path] = '\0';
    return open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
}

/* An unnamed file can be linked in only through /proc/self/fd (or with
 * CAP_DAC_READ_SEARCH): without /proc it would be a file that cannot be committed. */
static int open_unnamed(int dir_fd)
{
    if (access("/proc/self/fd", X_OK) != 0) {
        errno = EOPNOTSUPP;
        return -1;
    }
    return openat(dir_fd, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
}

static void output_free(vrg_output *out)
{
    if (out->f)
        fclose(out->f);
    if (out->fd >= 0)
        close(out->fd);
    if (out->dir_fd >= 0)
        close(out->dir_fd);
    free(out->path);
    free(out->real);
    free(out);
}

static vrg_output *open_direct(vrg_output *out, int *err)
{
    out->direct = 1;
    int fd = open(out->path, O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0 || !(out->f = fdopen(fd, "wb"))) {
        *err = errno;
        if (fd >= 0)
            close(fd);
        output_free(out);
        return NULL;
    }
    return out;
}

/* vrg_output_open without the message: NULL and *err. */
static vrg_output *output_open(const char *path, int *err)
{
    vrg_output *out = calloc(1, sizeof *out);
    char *copy = strdup(path);
    if (!out || !copy) {
        free(out), free(copy);
        *err = ENOMEM;
        return NULL;
    }
    out->path = copy;
    out->fd = out->dir_fd = -1;
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
        return open_direct(out, err);
    char *real = lstat(path, &st) == 0 && S_ISLNK(st.st_mode) ? realpath(path, NULL) : NULL;
    if (real) { /* the name replaced is the link's file's; messages keep the name given */
        out->real = real;
        copy = real;
    }
    const char *slash = strrchr(copy, '/');
    out->base = slash ? slash + 1 : copy;
    if (!*out->base) {
        *err = EISDIR;
        output_free(out);
        return NULL;
    }
    int fd = -1;
    if ((out->dir_fd = open_dir(copy)) >= 0 && (fd = open_unnamed(out->dir_fd)) < 0 &&
        (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) { /* no O_TMPFILE here: a named file */
        out->named = 1;
        temp_name(out->tmp, sizeof out->tmp, out->base);
        fd = openat(out->dir_fd, out->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    }
    /* a file replaced keeps its permissions (a 0600 file stays private);
     * a new one gets the umask's */
    int mode_failed = fd >= 0 && stat(copy, &st) == 0 && S_ISREG(st.st_mode) && fchmod(fd, st.st_mode & 07777) != 0;
    if (fd < 0 || mode_failed || (out->fd = dup(fd)) < 0 || !(out->f = fdopen(fd, "wb"))) {
        *err = errno;
        if (fd >= 0 && !out->f)
            close(fd);
        if (fd >= 0 && out->named)
            unlinkat(out->dir_fd, out->tmp, 0);
        output_free(out);
        return NULL;
    }
    return out;
}

vrg_output *vrg_output_open(const char *path)
{
    int err = 0;
    vrg_output *out = output_open(path, &err);
    if (!out)
        fail(path, "write", err);
    return out;
}

FILE *vrg_output_stream(vrg_output *out) { return out->f; }

/* Links the unnamed file in as name: through /proc (any user), else by
 * descriptor (needs CAP_DAC_READ_SEARCH). */
static int link_unnamed(const vrg_output *out, const char *name)
{
    char proc[64];
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", out->fd);
    if (linkat(AT_FDCWD, proc, out->dir_fd, name, AT_SYMLINK_FOLLOW) == 0)
        return 0;
    int err = errno;
    if (err == EEXIST)
        return -1;
    if (linkat(out->fd, "", out->dir_fd, name, AT_EMPTY_PATH) == 0)
        return 0;
    errno = err; /* the first attempt's reason (ENOSPC, EDQUOT...), not the fallback's */
    return -1;
}

/* The written file under the target's name. An unnamed file goes straight
 * to a new target (nothing to replace, so nothing can be left behind);
 * over an existing one it takes a hidden name first, since a link cannot
 * replace a file and a rename can. */
static int put_in_place(vrg_output *out)
{
    if (!out->named) {
        if (link_unnamed(out, out->base) == 0)
            return 0;
        if (errno != EEXIST)
            return -1;
        temp_name(out->tmp, sizeof out->tmp, out->base);
        if (link_unnamed(out, out->tmp) != 0)
            return -1;
        out->named = 1;
    }
    return renameat(out->dir_fd, out->tmp, out->dir_fd, out->base);
}

int vrg_output_commit(vrg_output *out)
{
    FILE *f = out->f;
    out->f = NULL;
    errno = 0;
    int rc = fflush(f) != 0 || ferror(f) ? -1 : 0;
    int err = out->err ? out->err : errno;
    if (out->direct) {
        if (fclose(f) != 0 && rc == 0)
            rc = -1, err = errno;
        if (rc != 0)
            fail(out->path, "write", err);
        output_free(out);
        return rc;
    }
    if (rc == 0 && fsync(out->fd) != 0)
        rc = -1, err = errno;
    if (fclose(f) != 0 && rc == 0)
        rc = -1, err = errno;
    if (rc == 0 && put_in_place(out) != 0)
        rc = -1, err = errno;
    if (rc != 0) {
        if (out->named)
            unlinkat(out->dir_fd, out->tmp, 0);
        fail(out->path, "write", err);
    } else if (fsync(out->dir_fd) != 0) {
        rc = fail(out->path, "sync the folder of", errno);
    }
    output_free(out);
    return rc;
}

void vrg_output_abort(vrg_output *out)
{
    if (!out)
        return;
    if (out->named)
        unlinkat(out->dir_fd, out->tmp, 0);
    output_free(out);
}

int vrg_output_write(const char *path, const void *data, size_t size)
{
    vrg_output *out = vrg_output_open(path);
    if (!out)
        return -1;
    if (fwrite(data, 1, size, out->f) != size)
        out->err = errno; /* the stream keeps the error, commit reports it */
    return vrg_output_commit(out);
}

int vrg_output_dir_check(const char *dir)
{
    char probe[PATH_CAP];
    int err = ENAMETOOLONG;
    vrg_output *out = NULL;
    if (snprintf(probe, sizeof probe, "%s/.voxrg-probe", dir) < (int)sizeof probe)
        out = output_open(probe, &err);
    if (!out)
        return fail(dir, "write in", err);
    vrg_output_abort(out);
    return 0;
}
