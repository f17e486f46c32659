/* What a pass hands to its host beside its images: objects shared by name
 * (the voxel layer's world, for CPU block queries) and debug names of the
 * Vulkan objects it makes itself. The runtime only keeps the pointers: it
 * knows nothing of what they point to, which is what keeps layers above it
 * (voxel, tools) out of the runtime. */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include <stdlib.h>
#include <string.h>
#include "internal.h"

struct _vrg_shared {
    char *name;
    void *object;
    struct _vrg_shared *next;
};

int vrg_pass_share(vrg_pass *p, const char *name, void *object)
{
    if (!name || !*name)
        return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_share: the name is empty");
    struct _vrg_shared **at = &p->shared;
    while (*at && strcmp((*at)->name, name) != 0)
        at = &(*at)->next;
    if (*at && !object) {
        struct _vrg_shared *gone = *at;
        *at = gone->next;
        free(gone->name);
        free(gone);
        return 0;
    }
    if (!*at) {
        if (!object)
            return 0;
        struct _vrg_shared *s = calloc(1, sizeof *s);
        if (!s || !(s->name = strdup(name))) {
            free(s);
            return _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "vrg_pass_share '%s': out of memory", name);
        }
        *at = s;
    }
    (*at)->object = object;
    return 0;
}

void *vrg_graph_shared(const vrg_graph *g, const char *name)
{
    /* graph order: a scene (always first) before the passes */
    for (int i = 0; i < g->pass_count; i++)
        for (const struct _vrg_shared *s = g->passes[i].shared; s; s = s->next)
            if (strcmp(s->name, name) == 0)
                return s->object;
    return NULL;
}

void _vrg_pass_free_shared(vrg_pass *p)
{
    while (p->shared) {
        struct _vrg_shared *s = p->shared;
        p->shared = s->next;
        free(s->name);
        free(s);
    }
}

void vrg_pass_name_object(vrg_pass *p, VkObjectType type, uint64_t handle, const char *name)
{
    if (p->graph->ctx)
        _vrg_name_object(p->graph->ctx, type, handle, "%s/%s.%s", p->graph->name, p->name, name);
}
