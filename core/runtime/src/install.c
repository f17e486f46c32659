#define _GNU_SOURCE
/* Where this voxrg lives. An installed libvoxrg finds everything relative
 * to its own file (dladdr), so a prefix can be moved or copied:
 * PREFIX/lib/libvoxrg.so -> PREFIX/lib/voxrg/plugins (shipped plugins) and
 * PREFIX/share/voxrg (shared shaders, graphs, camera paths). In voxrg's
 * build the data folder is the source tree: tests and the CLI run from the
 * build and see edits to shaders/ and graphs/ at once. The build says so in
 * a file beside the library (and beside each test program that links it
 * statically), voxrg-build-tree, of two lines: `data=SOURCE_TREE` and
 * `plugins=BUILD/plugins`. No build or source path is compiled in: an
 * installed copy has no such file beside it and never reads the checkout. */
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "internal.h"
#include "voxrg/version.h"

const char *vrg_version(void) { return VRG_VERSION_STRING; }

static char lib_dir[VRG_PATH_MAX];
static char data_dir[VRG_PATH_MAX];
static char build_plugin_dir[VRG_PATH_MAX];
static pthread_once_t dirs_once = PTHREAD_ONCE_INIT;

#define BUILD_TREE_FILE "voxrg-build-tree"

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* value of `key=value` in line (its newline cut), or NULL */
static const char *value_of(char *line, const char *key)
{
    size_t n = strlen(key);
    if (strncmp(line, key, n) != 0 || line[n] != '=')
        return NULL;
    line[strcspn(line, "\n")] = '\0';
    return line + n + 1;
}

/* The build's data and plugin folders from dir/voxrg-build-tree, where the
 * build wrote it; nothing when there is no such file. */
static void build_tree_read(const char *dir)
{
    char path[VRG_PATH_MAX + sizeof BUILD_TREE_FILE + 1];
    snprintf(path, sizeof path, "%s/" BUILD_TREE_FILE, dir);
    FILE *f = vrg_fopen_regular(path, "r");
    if (!f) { /* none (an installed voxrg has none) goes unsaid; something else in its place is said */
        if (errno == EINVAL || errno == EISDIR)
            fprintf(stderr, "voxrg: %s is not a regular file: ignored\n", path);
        return;
    }
    char line[VRG_PATH_MAX + 16], data[VRG_PATH_MAX] = "", plugins[VRG_PATH_MAX] = "";
    const char *v;
    while (fgets(line, sizeof line, f))
        if ((v = value_of(line, "data")))
            snprintf(data, sizeof data, "%s", v);
        else if ((v = value_of(line, "plugins")))
            snprintf(plugins, sizeof plugins, "%s", v);
    fclose(f);
    if (!data[0] || !plugins[0]) {
        fprintf(stderr, "voxrg: %s names no data= or plugins= folder: ignored\n", path);
        return;
    }
    snprintf(data_dir, sizeof data_dir, "%s", data);
    snprintf(build_plugin_dir, sizeof build_plugin_dir, "%s", plugins);
}

static void dirs_find(void)
{
    Dl_info info;
    char real[PATH_MAX];
    if (!dladdr((void *)vrg_version, &info) || !info.dli_fname || !realpath(info.dli_fname, real))
        return; /* all stay empty: nothing is searched relative to them */
    char *slash = strrchr(real, '/');
    if (slash)
        *slash = '\0';
    snprintf(lib_dir, sizeof lib_dir, "%s", real);
    snprintf(data_dir, sizeof data_dir, "%s/../share/voxrg", real);
    /* an installed layout wins even inside the build folder (a prefix
     * staged there, as the install test does) */
    if (!is_dir(data_dir))
        build_tree_read(real);
}

const char *_vrg_build_plugin_dir(void)
{
    pthread_once(&dirs_once, dirs_find);
    return build_plugin_dir;
}

const char *_vrg_lib_dir(void)
{
    pthread_once(&dirs_once, dirs_find);
    return lib_dir;
}

const char *vrg_data_dir(void)
{
    pthread_once(&dirs_once, dirs_find);
    return data_dir;
}
