/* watch.c: files watched for hot reload (inotify). */
#ifndef VRG_WATCH_H
#define VRG_WATCH_H

#include "internal.h"

typedef struct _vrg_watch _vrg_watch;
_vrg_watch *_vrg_watch_create(void);
void _vrg_watch_destroy(_vrg_watch *w);
int _vrg_watch_add(_vrg_watch *w, const char *path);
/* Tracked files whose write completed since the last poll, in *changed
 * (every one; the caller frees it). -1: out of memory. */
int _vrg_watch_poll(_vrg_watch *w, char (**changed)[VRG_PATH_MAX]);
/* Adds a pipeline's files (newline-separated) to the graph's watch, if any. */
void _vrg_graph_watch_pipeline(vrg_graph *g, const char *deps);
#endif
