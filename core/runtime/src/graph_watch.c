/* Hot reload of a live graph: which files it is built from, and between
 * frames the saves among them. A saved shader recompiles the pipelines
 * that read it before the next frame records; a saved graph file or a
 * rebuilt plugin is noted for the host, whose vrg_graph_reload (reload.c)
 * builds the new graph. */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "internal.h"
#include "watch.h"

static void watch_path(void *user, const char *path) { _vrg_watch_add(user, path); }

int vrg_graph_watch(vrg_graph *g, int on)
{
    if (!on) {
        _vrg_watch_destroy(g->watch);
        g->watch = NULL;
        return 0;
    }
    if (g->watch)
        return 0;
    g->watch = _vrg_watch_create();
    if (!g->watch) {
        _vrg_error(&g->diag, VRG_E_WATCH_FAILED, "hot reload: cannot watch files (inotify: %s)", strerror(errno));
        return -1;
    }
    g->reload_ms = -1;
    if (g->loaded_from_file)
        _vrg_watch_add(g->watch, g->path);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_watch_add(g->watch, g->passes[i].plugin->source);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_pipelines_deps(&g->passes[i], watch_path, g->watch);
    return 0;
}

void vrg_graph_sources(const vrg_graph *g, void (*fn)(void *user, const char *path), void *user)
{
    if (g->loaded_from_file)
        fn(user, g->path);
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].plugin)
            fn(user, g->passes[i].plugin->source);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_pipelines_deps((vrg_pass *)&g->passes[i], fn, user);
    for (int i = 0; i < g->pass_count; i++)
        for (int k = 0; k < g->passes[i].input_count; k++)
            fn(user, g->passes[i].inputs[k]);
}

/* The graph file or a plugin was saved: the host is to reload. The newest
 * of their mtimes starts the save-to-frame time of that reload (a plugin
 * rebuilt long after the graph was saved is timed from its own build). */
static void note_source_saved(vrg_graph *g, const char *path)
{
    struct stat st;
    g->source_changed = 1;
    if (stat(path, &st) == 0) {
        double t = (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
        g->source_saved_at = t > g->source_saved_at ? t : g->source_saved_at;
    }
}

typedef struct shader_dep_hit {
    const char *path;
    int found;
} shader_dep_hit;

static void is_changed_dep(void *user, const char *path)
{
    shader_dep_hit *h = user;
    h->found |= strcmp(h->path, path) == 0;
}

/* Saved shaders: recompile the pipelines that read them before this frame
 * records. Failures keep the old pipeline; their messages (FILE:LINE) go to
 * the diagnostics as usual and are kept for vrg_graph_reload_error. */
static void apply_reloads(vrg_graph *g)
{
    char (*changed)[VRG_PATH_MAX], self[VRG_PATH_MAX];
    int n = _vrg_watch_poll(g->watch, &changed);
    if (n < 0)
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "hot reload: out of memory listing the changed files");
    if (n <= 0)
        return;
    /* the graph file itself: the host reloads it (vrg_graph_reload) */
    if (g->loaded_from_file && realpath(g->path, self))
        for (int i = 0; i < n; i++)
            if (strcmp(changed[i], self) == 0)
                note_source_saved(g, changed[i]);
    /* a rebuilt plugin: also the host's to reload (a new graph instance).
     * A shader-only pass's interface is read from its file and every file
     * it includes (a push block or binding may be declared in an include):
     * a change to any of them re-reads it, as a rebuilt plugin */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < g->pass_count; k++) {
            shader_dep_hit hit = {.path = changed[i]};
            if (g->passes[k].plugin->shader_pass)
                _vrg_pipelines_deps(&g->passes[k], is_changed_dep, &hit);
            if (strcmp(changed[i], g->passes[k].plugin->source) != 0 && !hit.found)
                continue;
            g->passes[k].plugin_rebuilt = 1;
            g->plugins_rebuilt = 1;
            note_source_saved(g, changed[i]);
        }
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    FILE *real = g->diag.out;
    if (mem)
        g->diag.out = mem;
    int failed = 0, swapped = 0;
    for (int i = 0; i < g->pass_count; i++) {
        /* a shader-only pass's files (its own and its includes) are its interface too: the host's
         * reload (a new version of the plugin) re-reads and re-checks it */
        if (g->passes[i].plugin_rebuilt && g->passes[i].plugin->shader_pass)
            continue;
        int r = _vrg_pipelines_reload(&g->passes[i], changed, n);
        failed |= r < 0;
        swapped += r > 0 ? r : 0;
    }
    if (mem) {
        g->diag.out = real;
        fclose(mem);
        fputs(text ? text : "", real ? real : stderr);
        snprintf(g->reload_error, sizeof g->reload_error, "%s", failed && text ? text : "");
        free(text);
    }
    if (swapped) { /* the newest save among the files: the start of the save-to-frame time */
        double newest = 0;
        for (int i = 0; i < n; i++) {
            struct stat st;
            if (stat(changed[i], &st) == 0) {
                double t = (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
                newest = t > newest ? t : newest;
            }
        }
        g->pending_since = newest;
    }
    free(changed);
}

int vrg_graph_poll_changes(vrg_graph *g)
{
    if (g->watch)
        apply_reloads(g);
    return g->source_changed;
}

const char *vrg_graph_reload_error(const vrg_graph *g) { return g->reload_error[0] ? g->reload_error : NULL; }

double vrg_graph_reload_ms(const vrg_graph *g) { return g->watch ? g->reload_ms : -1; }
