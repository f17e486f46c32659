#define _GNU_SOURCE
/* Where this voxrg lives. An installed libvoxrg finds everything relative
 * to its own file (dladdr), so a prefix can be moved or copied:
 * PREFIX/lib/libvoxrg.so -> PREFIX/lib/voxrg/plugins (shipped plugins) and
 * PREFIX/share/voxrg (shared shaders, graphs, camera paths). In the build
 * tree the data folder is the source tree: tests and the CLI run from the
 * build and see edits to shaders/ and graphs/ at once. The source tree is
 * used only while the library (or a test linking it statically) lies in the
 * build folder, so an installed copy never reads the checkout. */
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "internal.h"
#include "voxrg/version.h"

const char *vrg_version(void) { return VRG_VERSION_STRING; }

static char lib_dir[VRG_PATH_MAX];
static char data_dir[VRG_PATH_MAX];
static int build_tree;
static pthread_once_t dirs_once = PTHREAD_ONCE_INIT;

static int inside(const char *path, const char *dir)
{
    size_t n = strlen(dir);
    return n && strncmp(path, dir, n) == 0 && (path[n] == '/' || path[n] == '\0');
}

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static void dirs_find(void)
{
    Dl_info info;
    char real[PATH_MAX];
    if (!dladdr((void *)vrg_version, &info) || !info.dli_fname || !realpath(info.dli_fname, real))
        return; /* both stay empty: nothing is searched relative to them */
    char *slash = strrchr(real, '/');
    if (slash)
        *slash = '\0';
    snprintf(lib_dir, sizeof lib_dir, "%s", real);
    snprintf(data_dir, sizeof data_dir, "%s/../share/voxrg", real);
    /* an installed layout wins even inside the build folder (a prefix
     * staged there, as the install test does) */
    if (is_dir(data_dir))
        return;
#if defined(VRG_BUILD_DIR) && defined(VRG_SOURCE_DIR)
    char build[PATH_MAX];
    if (realpath(VRG_BUILD_DIR, build) && inside(real, build)) {
        build_tree = 1;
        snprintf(data_dir, sizeof data_dir, "%s", VRG_SOURCE_DIR);
    }
#endif
    (void)inside;
}

int _vrg_build_tree(void)
{
    pthread_once(&dirs_once, dirs_find);
    return build_tree;
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
