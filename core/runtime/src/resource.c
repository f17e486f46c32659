/* The graph's table of resources: finding one by name, adding one (the
 * validator for what a graph file names, the pass API for what create()
 * asks for), and which of a history resource's two copies a frame uses. */
#include <string.h>
#include "internal.h"

int _vrg_graph_find_resource(const vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0)
            return i;
    return -1;
}

int _vrg_graph_add_resource(vrg_graph *g, const char *name)
{
    int i = _vrg_graph_find_resource(g, name);
    if (i >= 0)
        return i;
    if (g->res_count >= VRG_MAX_RESOURCES)
        return -1;
    _vrg_resource *r = &g->res[g->res_count];
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    r->writer = -1;
    r->writer_slot = -1;
    r->internal_owner = -1;
    r->block = -1;
    r->first_use = r->last_use = -1;
    return g->res_count++;
}

/* The frame index's parity picks the copy: this frame's writes go to one,
 * @prev reads the other, and they swap every frame. */
int _vrg_copy_of(const vrg_graph *g, int res, int prev)
{
    if (!g->res[res].history)
        return 0;
    int current = (int)(g->frame.frame_index & 1);
    return prev ? current ^ 1 : current;
}
