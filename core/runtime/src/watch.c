/* Files watched for hot reload (inotify). Directories are watched rather
 * than files: editors save by writing a new file and renaming it over the
 * old one, which a watch on the old file's inode would miss. Only completed
 * writes count: IN_CLOSE_WRITE (written in place and closed) and
 * IN_MOVED_TO (renamed into place); a file being written is never reported
 * half done. A graph's watch (graph_watch.c) also takes the files of each
 * pipeline the dispatch helper compiles, as it compiles them. */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <unistd.h>
#include "internal.h"
#include "watch.h"

typedef struct watched_file {
    int wd;                 /* its directory's watch */
    char path[VRG_PATH_MAX];    /* as given (normalised) */
    char name[NAME_MAX + 1];
} watched_file;

struct _vrg_watch {
    int fd;
    watched_file *files;
    int count, cap;
};

_vrg_watch *_vrg_watch_create(void)
{
    _vrg_watch *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (w->fd < 0) {
        free(w);
        return NULL;
    }
    return w;
}

void _vrg_watch_destroy(_vrg_watch *w)
{
    if (!w)
        return;
    close(w->fd); /* drops every watch */
    free(w->files);
    free(w);
}

int _vrg_watch_add(_vrg_watch *w, const char *path)
{
    char full[VRG_PATH_MAX];
    if (!w || !realpath(path, full))
        return -1;
    for (int i = 0; i < w->count; i++)
        if (strcmp(w->files[i].path, full) == 0)
            return 0;
    char dir[VRG_PATH_MAX];
    snprintf(dir, sizeof dir, "%s", full);
    char *slash = strrchr(dir, '/');
    if (!slash)
        return -1;
    *slash = '\0';
    /* the same directory returns the same watch descriptor */
    int wd = inotify_add_watch(w->fd, dir[0] ? dir : "/", IN_CLOSE_WRITE | IN_MOVED_TO);
    if (wd < 0)
        return -1;
    if (w->count == w->cap) {
        int cap = w->cap ? 2 * w->cap : 16;
        watched_file *f = realloc(w->files, (size_t)cap * sizeof *f);
        if (!f)
            return -1;
        w->files = f;
        w->cap = cap;
    }
    watched_file *f = &w->files[w->count++];
    f->wd = wd;
    snprintf(f->path, sizeof f->path, "%s", full);
    snprintf(f->name, sizeof f->name, "%s", slash + 1);
    return 0;
}

/* Adds path to *list unless it is there; the list grows as needed. */
static int add_changed(char (**list)[VRG_PATH_MAX], int n, int *cap, const char *path)
{
    for (int k = 0; k < n; k++)
        if (strcmp((*list)[k], path) == 0)
            return n;
    if (n == *cap) {
        int grown_cap = *cap ? 2 * *cap : 16;
        char (*grown)[VRG_PATH_MAX] = realloc(*list, (size_t)grown_cap * sizeof *grown);
        if (!grown)
            return -1;
        *list = grown;
        *cap = grown_cap;
    }
    snprintf((*list)[n], VRG_PATH_MAX, "%s", path);
    return n + 1;
}

int _vrg_watch_poll(_vrg_watch *w, char (**changed)[VRG_PATH_MAX])
{
    int n = 0, cap = 0;
    *changed = NULL;
    if (!w)
        return 0;
    char buf[16384] __attribute__((aligned(__alignof__(struct inotify_event))));
    for (;;) {
        ssize_t len = read(w->fd, buf, sizeof buf);
        if (len <= 0)
            break; /* EAGAIN: nothing more */
        for (char *p = buf; p < buf + len;) {
            const struct inotify_event *ev = (const struct inotify_event *)p;
            p += sizeof *ev + ev->len;
            if (!ev->len)
                continue;
            for (int i = 0; i < w->count; i++) {
                if (w->files[i].wd != ev->wd || strcmp(w->files[i].name, ev->name) != 0)
                    continue;
                int grown = add_changed(changed, n, &cap, w->files[i].path);
                if (grown < 0) {
                    free(*changed);
                    *changed = NULL;
                    return -1;
                }
                n = grown;
            }
        }
    }
    return n;
}

void _vrg_graph_watch_pipeline(vrg_graph *g, const char *deps)
{
    if (!g->watch)
        return;
    for (const char *d = deps; d && *d;) {
        const char *end = strchr(d, '\n');
        char path[VRG_PATH_MAX];
        snprintf(path, sizeof path, "%.*s", (int)(end ? end - d : (long)strlen(d)), d);
        _vrg_watch_add(g->watch, path);
        d = end ? end + 1 : d + strlen(d);
    }
}
