/* Plugins are found by name on a search path and loaded once per process:
 *   $VOXRG_PLUGIN_PATH (':'-separated), the graph file's folder and its
 *   plugins/ subfolder, <exe>/plugins (build tree), <exe>/../lib/voxrg/plugins
 *   (install tree). The first NAME.so found wins. */
#define _GNU_SOURCE
#include <dirent.h>
#include <dlfcn.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "internal.h"

/* Slots stay put (graphs hold pointers to them); an unloaded version's slot
 * is emptied (name "") and reused. */
static vrg_plugin loaded[VRG_MAX_PLUGINS];
static int loaded_count;
static unsigned last_generation;

/* The current version of NAME (matched on `source` instead when by_source). */
static vrg_plugin *newest(const char *key, int by_source)
{
    vrg_plugin *best = NULL;
    for (int i = 0; i < loaded_count; i++)
        if (loaded[i].name[0] && strcmp(by_source ? loaded[i].source : loaded[i].name, key) == 0 &&
            (!best || loaded[i].generation > best->generation))
            best = &loaded[i];
    return best;
}

static vrg_plugin *free_slot(void)
{
    for (int i = 0; i < loaded_count; i++)
        if (!loaded[i].name[0])
            return &loaded[i];
    return loaded_count < VRG_MAX_PLUGINS ? &loaded[loaded_count++] : NULL;
}

static const vrg_plugin *keep(const vrg_plugin *p)
{
    vrg_plugin *slot = free_slot();
    if (slot) {
        *slot = *p;
        slot->generation = ++last_generation;
        slot->users = 0;
    }
    return slot;
}

void vrg_plugin_acquire(const vrg_plugin *p) { ((vrg_plugin *)p)->users++; }

void vrg_plugin_release(const vrg_plugin *cp)
{
    vrg_plugin *p = (vrg_plugin *)cp;
    if (--p->users > 0 || newest(p->name, 0) == p)
        return; /* in use, or the current version (kept loaded: a cache) */
    dlclose(p->handle);
    memset(p, 0, sizeof *p);
}

static int add_dir(char dirs[][VRG_PATH_MAX], int n, int max, const char *dir)
{
    for (int i = 0; i < n; i++)
        if (strcmp(dirs[i], dir) == 0)
            return n;
    if (n < max)
        snprintf(dirs[n++], VRG_PATH_MAX, "%s", dir);
    return n;
}

enum { SEARCH_DIRS = 32, FIXED_DIRS = 5 }; /* fixed: the graph's two, the executable's two, the build's */

/* The folders searched for plugins, in order. *env_overflow is set when
 * $VOXRG_PLUGIN_PATH names more folders than fit beside the fixed ones. */
static int search_dirs(const char *graph_path, char dirs[][VRG_PATH_MAX], int max, int *env_overflow)
{
    int n = 0;
    char dir[VRG_PATH_MAX + 16];
    const char *env = getenv("VOXRG_PLUGIN_PATH");
    *env_overflow = 0;
    if (env) {
        const char *p = env;
        while (*p) {
            if (n == max - FIXED_DIRS) {
                *env_overflow = 1;
                break;
            }
            const char *c = strchr(p, ':');
            size_t len = c ? (size_t)(c - p) : strlen(p);
            if (len && len < VRG_PATH_MAX) {
                snprintf(dir, sizeof dir, "%.*s", (int)len, p);
                n = add_dir(dirs, n, max, dir);
            }
            p = c ? c + 1 : p + len;
        }
    }
    if (graph_path) {
        const char *slash = strrchr(graph_path, '/');
        int len = slash ? (int)(slash - graph_path) : 1;
        snprintf(dir, sizeof dir, "%.*s", len, slash ? graph_path : ".");
        n = add_dir(dirs, n, max, dir);
        snprintf(dir, sizeof dir, "%.*s/plugins", len, slash ? graph_path : ".");
        n = add_dir(dirs, n, max, dir);
    }
    char exe[VRG_PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash)
            *slash = '\0';
        snprintf(dir, sizeof dir, "%s/plugins", exe);
        n = add_dir(dirs, n, max, dir);
        snprintf(dir, sizeof dir, "%s/../lib/voxrg/plugins", exe);
        n = add_dir(dirs, n, max, dir);
    }
#ifdef VRG_BUILD_PLUGIN_DIR
    /* tests and fuzzers run from other folders of the build */
    n = add_dir(dirs, n, max, VRG_BUILD_PLUGIN_DIR);
#endif
    return n;
}

static int check_desc(const vrg_plugin *p, vrg_diag *d, int line)
{
    const vrg_plugin_desc *desc = p->desc;
    const char *why = NULL;
    if (!desc->name || strcmp(desc->name, p->name) != 0)
        why = "its descriptor's name differs from its file name";
    else if (desc->kind != VRG_PLUGIN_PASS && desc->kind != VRG_PLUGIN_SCENE)
        why = "kind is neither VRG_PLUGIN_PASS nor VRG_PLUGIN_SCENE";
    else if (!desc->execute)
        why = "execute callback is NULL";
    else if (desc->slot_count > VRG_MAX_SLOTS || (desc->slot_count && !desc->slots))
        why = "slot table is too large or missing";
    else if (desc->param_count > VRG_MAX_PARAMS || (desc->param_count && !desc->params))
        why = "parameter table is too large or missing";
    if (why) {
        vrg_error_at(d, line, NULL, "plugin '%s' (%s): %s", p->name, p->path, why);
        return -1;
    }
    for (uint32_t i = 0; i < desc->param_count; i++)
        if ((desc->params[i].flags & VRG_PARAM_REPEATABLE) && desc->params[i].type != VRG_PARAM_STRING) {
            vrg_error_at(d, line, NULL, "plugin '%s' (%s): parameter '%s' is repeatable but not a string", p->name, p->path, desc->params[i].name);
            return -1;
        }
    for (uint32_t i = 0; i < desc->slot_count; i++) {
        const vrg_slot_desc *s = &desc->slots[i];
        if (!s->name || (s->dir != VRG_IN && s->dir != VRG_OUT) || s->kind < VRG_IMAGE || s->kind > VRG_ACCEL ||
            s->access < VRG_ACCESS_SAMPLED || s->access > VRG_ACCESS_TEXEL_READ) {
            vrg_error_at(d, line, NULL, "plugin '%s' (%s): slot %u is malformed (name, dir, kind, access)", p->name, p->path, i);
            return -1;
        }
        int as_access = s->access == VRG_ACCESS_AS_BUILD || s->access == VRG_ACCESS_RAY_QUERY;
        if ((s->access == VRG_ACCESS_SAMPLED && s->kind != VRG_IMAGE) || ((s->access == VRG_ACCESS_UNIFORM || s->access == VRG_ACCESS_TEXEL_READ) && s->kind != VRG_BUFFER) ||
            as_access != (s->kind == VRG_ACCEL)) {
            vrg_error_at(d, line, NULL, "plugin '%s' (%s): slot '%s': %s access does not fit a%s", p->name, p->path, s->name,
                         vrg_access_name(s->access), s->kind == VRG_IMAGE ? "n image" : s->kind == VRG_BUFFER ? " buffer" : "n acceleration structure");
            return -1;
        }
        /* a buffer's format is the texel format of its TEXEL_READ views */
        int texel_format = s->format == VK_FORMAT_R32_UINT || s->format == VK_FORMAT_R32G32_UINT || s->format == VK_FORMAT_R32G32B32A32_UINT;
        if (s->kind == VRG_BUFFER && s->format && !texel_format) {
            vrg_error_at(d, line, NULL, "plugin '%s' (%s): slot '%s': a buffer's format is the texel format of its TEXEL_READ views: r32ui, rg32ui or rgba32ui, not %s",
                         p->name, p->path, s->name, vrg_format_name(s->format));
            return -1;
        }
        if (s->kind == VRG_BUFFER && s->format && s->dir == VRG_IN && s->access != VRG_ACCESS_TEXEL_READ) {
            vrg_error_at(d, line, NULL, "plugin '%s' (%s): slot '%s': a %s input names a texel format; only texel-read inputs (VRG_ACCESS_TEXEL_READ) and outputs do",
                         p->name, p->path, s->name, vrg_access_name(s->access));
            return -1;
        }
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(desc->slots[j].name, s->name) == 0 && desc->slots[j].dir == s->dir) {
                vrg_error_at(d, line, NULL, "plugin '%s' (%s): two %s slots named '%s'", p->name, p->path, s->dir == VRG_IN ? "input" : "output",
                             s->name);
                return -1;
            }
    }
    return 0;
}

const vrg_plugin *vrg_plugin_load(const char *name, const char *graph_path, vrg_diag *d, int line)
{
    /* the newest version: a reloaded plugin supersedes its earlier ones */
    const vrg_plugin *current = name[0] ? newest(name, 0) : NULL;
    if (current)
        return current;
    if (!name[0] || strchr(name, '/') || strlen(name) >= VRG_NAME_MAX) {
        vrg_error_at(d, line, "a plugin is named by its file name without .so", "unknown plugin '%s'", name);
        return NULL;
    }
    if (loaded_count >= VRG_MAX_PLUGINS && !free_slot()) {
        vrg_error_at(d, line, NULL, "too many plugins (at most %d)", VRG_MAX_PLUGINS);
        return NULL;
    }
    char dirs[SEARCH_DIRS][VRG_PATH_MAX];
    int overflow;
    int nd = search_dirs(graph_path, dirs, SEARCH_DIRS, &overflow);
    if (overflow) {
        vrg_error_at(d, line, NULL, "$VOXRG_PLUGIN_PATH names more than %d folders", SEARCH_DIRS - FIXED_DIRS);
        return NULL;
    }
    vrg_plugin p = {0};
    snprintf(p.name, sizeof p.name, "%s", name);
    for (int i = 0; i < nd && !p.path[0]; i++) {
        char path[VRG_PATH_MAX + VRG_NAME_MAX + 8];
        snprintf(path, sizeof path, "%s/%s.so", dirs[i], name);
        if (access(path, F_OK) == 0) {
            char *real = realpath(path, NULL);
            snprintf(p.path, sizeof p.path, "%s", real ? real : path);
            snprintf(p.source, sizeof p.source, "%s", p.path);
            free(real);
        }
    }
    if (!p.path[0]) {
        char hint[2048] = "searched:";
        for (int i = 0; i < nd; i++) {
            strncat(hint, " ", sizeof hint - strlen(hint) - 1);
            strncat(hint, dirs[i], sizeof hint - strlen(hint) - 1);
        }
        strncat(hint, " (set VOXRG_PLUGIN_PATH; `voxrg plugins` lists what exists)", sizeof hint - strlen(hint) - 1);
        vrg_error_at(d, line, hint, "unknown plugin '%s'", name);
        return NULL;
    }
    p.handle = dlopen(p.path, RTLD_NOW | RTLD_LOCAL);
    if (!p.handle) {
        vrg_error_at(d, line, "is it a shared object built for this machine?", "cannot load plugin '%s' from %s: %s", name, p.path, dlerror());
        return NULL;
    }
    vrg_plugin_entry_fn entry = (vrg_plugin_entry_fn)dlsym(p.handle, VRG_PLUGIN_ENTRY_SYMBOL);
    if (!entry) {
        vrg_error_at(d, line, "a plugin's source ends with VRG_PLUGIN(desc)", "plugin '%s' (%s) does not export %s", name, p.path, VRG_PLUGIN_ENTRY_SYMBOL);
        dlclose(p.handle);
        return NULL;
    }
    p.desc = entry(VRG_ABI_VERSION);
    if (!p.desc) {
        vrg_error_at(d, line, NULL, "plugin '%s' (%s): %s returned NULL", name, p.path, VRG_PLUGIN_ENTRY_SYMBOL);
        dlclose(p.handle);
        return NULL;
    }
    if (p.desc->abi_version != VRG_ABI_VERSION) {
        vrg_error_at(d, line, "rebuild the plugin against this voxrg's headers",
                     "plugin '%s' (%s) has ABI version %u, this voxrg expects ABI version %u", name, p.path, p.desc->abi_version,
                     VRG_ABI_VERSION);
        dlclose(p.handle);
        return NULL;
    }
    if (check_desc(&p, d, line) != 0) {
        dlclose(p.handle);
        return NULL;
    }
    return keep(&p);
}

/* Hot reload of a rebuilt plugin: the file at `path` (the one a loaded
 * plugin came from) is copied to a private file and loaded from there, so
 * the build may overwrite it again and dlopen does not hand back the old
 * image; its ABI and descriptor are checked like any plugin's. On success
 * it becomes the newest version of its name (graphs loaded from now on use
 * it); the old version stays loaded while graphs still run it, and is
 * unloaded with its last user. */
int vrg_plugin_reload(const char *path, vrg_diag *d)
{
    vrg_plugin *old = newest(path, 1);
    if (!old) {
        vrg_error(d, "plugin %s: not a loaded plugin", path);
        return -1;
    }
    if (loaded_count >= VRG_MAX_PLUGINS && !free_slot()) {
        vrg_error(d, "plugin %s: too many plugin versions loaded (at most %d)", path, VRG_MAX_PLUGINS);
        return -1;
    }
    char dir[] = "/tmp/voxrg-plugin-XXXXXX";
    if (!mkdtemp(dir)) {
        vrg_error(d, "plugin %s: cannot make a private copy", path);
        return -1;
    }
    vrg_plugin p = {0};
    snprintf(p.name, sizeof p.name, "%s", old->name);
    snprintf(p.source, sizeof p.source, "%s", path);
    snprintf(p.path, sizeof p.path, "%s/%s.so", dir, p.name);
    FILE *in = fopen(path, "rb"), *out = fopen(p.path, "wb");
    int copied = in && out;
    char buf[65536];
    size_t n;
    while (copied && (n = fread(buf, 1, sizeof buf, in)) > 0)
        copied = fwrite(buf, 1, n, out) == n;
    if (in)
        fclose(in);
    if (out && fclose(out) != 0)
        copied = 0;
    int rc = -1;
    if (!copied)
        vrg_error(d, "plugin %s: cannot copy it to %s", path, p.path);
    else if (!(p.handle = dlopen(p.path, RTLD_NOW | RTLD_LOCAL)))
        vrg_error(d, "plugin %s: cannot load the rebuilt file: %s", path, dlerror());
    else {
        vrg_plugin_entry_fn entry = (vrg_plugin_entry_fn)dlsym(p.handle, VRG_PLUGIN_ENTRY_SYMBOL);
        p.desc = entry ? entry(VRG_ABI_VERSION) : NULL;
        if (!p.desc)
            vrg_error(d, "plugin %s: the rebuilt file has no %s or it returned NULL", path, VRG_PLUGIN_ENTRY_SYMBOL);
        else if (p.desc->abi_version != VRG_ABI_VERSION)
            vrg_error(d, "plugin %s: the rebuilt file has ABI version %u, this voxrg expects ABI version %u", path, p.desc->abi_version,
                      VRG_ABI_VERSION);
        else if (check_desc(&p, d, 0) == 0)
            rc = 0;
    }
    /* the loaded image stays mapped: the private file can go, and messages
     * name the file the user builds */
    unlink(p.path);
    rmdir(dir);
    snprintf(p.path, sizeof p.path, "%s", path);
    if (rc != 0) {
        if (p.handle)
            dlclose(p.handle);
        return -1;
    }
    keep(&p);
    if (old->users == 0) { /* superseded with no pass running it: unload now */
        old->users = 1;
        vrg_plugin_release(old);
    }
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp((*(const vrg_plugin *const *)a)->name, (*(const vrg_plugin *const *)b)->name);
}

int vrg_plugin_list(const vrg_plugin **out, int max)
{
    char dirs[SEARCH_DIRS][VRG_PATH_MAX];
    int overflow;
    int nd = search_dirs(NULL, dirs, SEARCH_DIRS, &overflow);
    vrg_diag quiet = {.out = stderr, .file = "plugins"};
    if (overflow)
        vrg_error(&quiet, "$VOXRG_PLUGIN_PATH names more than %d folders: those after it are not searched", SEARCH_DIRS - FIXED_DIRS);
    for (int i = 0; i < nd; i++) {
        DIR *dir = opendir(dirs[i]);
        if (!dir)
            continue;
        struct dirent *e;
        while ((e = readdir(dir))) {
            size_t len = strlen(e->d_name);
            if (len < 4 || strcmp(e->d_name + len - 3, ".so") != 0 || len - 3 >= VRG_NAME_MAX)
                continue;
            char name[VRG_NAME_MAX];
            snprintf(name, sizeof name, "%.*s", (int)(len - 3), e->d_name);
            int known = 0;
            for (int k = 0; k < loaded_count; k++)
                known |= strcmp(loaded[k].name, name) == 0;
            if (!known) {
                /* A broken plugin on the path is reported, not fatal, here. */
                FILE *devnull = fopen("/dev/null", "w");
                quiet.out = devnull ? devnull : stderr;
                vrg_plugin_load(name, NULL, &quiet, 0);
                if (devnull)
                    fclose(devnull);
            }
        }
        closedir(dir);
    }
    int n = 0;
    for (int i = 0; i < loaded_count && n < max; i++)
        if (loaded[i].name[0] && newest(loaded[i].name, 0) == &loaded[i]) /* current versions only */
            out[n++] = &loaded[i];
    qsort(out, (size_t)n, sizeof *out, by_name);
    return n;
}

int vrg_list_plugins(const vrg_plugin_desc **descs, const char **paths, int max)
{
    const vrg_plugin *list[VRG_MAX_PLUGINS];
    int n = vrg_plugin_list(list, max < VRG_MAX_PLUGINS ? max : VRG_MAX_PLUGINS);
    for (int i = 0; i < n; i++) {
        descs[i] = list[i]->desc;
        paths[i] = list[i]->path;
    }
    return n;
}
