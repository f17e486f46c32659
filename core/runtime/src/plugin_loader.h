/* plugin_loader.c: finding, checking and loading plugins, and their
 * versions under hot reload (the plugin itself: _vrg_plugin, internal.h). */
#ifndef VRG_PLUGIN_LOADER_H
#define VRG_PLUGIN_LOADER_H

#include "internal.h"

/* Finds NAME on the search path (plugin_loader.c's header comment) and loads
 * a private copy of it; NULL after reporting at `line`. A file already loaded
 * is not loaded again. `graph_path` is the graph file (for its plugin_path,
 * ':'-separated folders relative to it, NULL if none). */
const _vrg_plugin *_vrg_plugin_load(const char *name, const char *graph_path, const char *plugin_path, _vrg_diag *d, int line);
/* Every folder of a graph's plugin_path exists; errors at `line`. The
 * same resolution as the search path's (relative to the graph file). */
int _vrg_plugin_path_check(const char *graph_path, const char *plugin_path, _vrg_diag *d, int line);
/* The checks a plugin's descriptor must pass (also run by the fuzzer). */
int _vrg_plugin_check_desc(const vrg_plugin_desc *desc, const char *name, const char *path, _vrg_diag *d, int line);
/* A pass runs the plugin / no longer does. A superseded version (a hot
 * reload loaded a newer one) is unloaded when its last user goes. */
void _vrg_plugin_acquire(const _vrg_plugin *p);
void _vrg_plugin_release(const _vrg_plugin *p);
/* A rebuilt plugin file becomes the newest version of its plugin (hot reload). */
int _vrg_plugin_reload(const char *source_path, _vrg_diag *d);
/* Every plugin on the search path (for `voxrg plugins`), the current
 * version of each file; returns how many there are (more than max: only max
 * filled). Files that fail to load are reported to `problems` (NULL: not)
 * and counted in *failed. */
int _vrg_plugin_list(const _vrg_plugin **out, int max, FILE *problems, int *failed);
#endif
