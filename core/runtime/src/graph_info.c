/* What a host asks of a loaded graph: its passes, timings, statistics,
 * memory and placement, and whether two graphs see the same world. */
#include <math.h>
#include <string.h>
#include "internal.h"

uint32_t vrg_graph_pass_count(const vrg_graph *g) { return (uint32_t)g->pass_count; }

double vrg_graph_cpu_ms(const vrg_graph *g) { return g->cpu_ms; }

double vrg_graph_pass_cpu_ms(const vrg_graph *g, uint32_t i) { return i < (uint32_t)g->pass_count ? g->pass_cpu_ms[i] : -1; }

const char *vrg_graph_pass_name(const vrg_graph *g, uint32_t i) { return i < (uint32_t)g->pass_count ? g->passes[i].name : NULL; }

const vrg_plugin_desc *vrg_graph_pass_plugin(const vrg_graph *g, uint32_t i) { return i < (uint32_t)g->pass_count ? g->passes[i].plugin->desc : NULL; }

double vrg_graph_pass_ms(const vrg_graph *g, uint32_t i) { return i < (uint32_t)g->pass_count ? g->pass_ms[i] : -1; }

const char *vrg_graph_output(const vrg_graph *g) { return g->output_name; }

uint32_t vrg_graph_subframes(const vrg_graph *g) { return g->subframes > 1 ? g->subframes : 1; }

void vrg_graph_size(const vrg_graph *g, uint32_t *w, uint32_t *h)
{
    *w = g->width;
    *h = g->height;
}

int vrg_graph_resource_kind(const vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0)
            return (int)g->res[i].kind;
    return -1;
}

static const vrg_pass *scene_of(const vrg_graph *g)
{
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].is_scene)
            return &g->passes[i];
    return NULL;
}

/* Two graphs compared frame by frame must see the same world from the same
 * random sequences: the scene (plugin, every parameter), [graph] seed and
 * fps (camera paths are sampled per frame), and size. */
int vrg_graph_same_world(const vrg_graph *a, const vrg_graph *b, char *why, size_t cap)
{
    const vrg_pass *sa = scene_of(a), *sb = scene_of(b);
    if (a->width != b->width || a->height != b->height)
        snprintf(why, cap, "sizes differ: %s is %ux%u, %s %ux%u", a->path, a->width, a->height, b->path, b->width, b->height);
    else if (a->seed != b->seed)
        snprintf(why, cap, "[graph] seeds differ: %s has %u, %s %u", a->path, a->seed, b->path, b->seed);
    else if (a->fps != b->fps)
        snprintf(why, cap, "[graph] fps differ: %s has %g, %s %g", a->path, a->fps, b->path, b->fps);
    else if (!sa != !sb)
        snprintf(why, cap, "%s has a [scene], %s none", sa ? a->path : b->path, sa ? b->path : a->path);
    else if (sa && strcmp(sa->plugin->name, sb->plugin->name) != 0)
        snprintf(why, cap, "scenes differ: %s:%d uses '%s', %s:%d '%s'", a->path, sa->line, sa->plugin->name, b->path, sb->line, sb->plugin->name);
    else if (sa) {
        const vrg_plugin_desc *pd = sa->plugin->desc;
        for (uint32_t k = 0; k < pd->param_count; k++)
            if (sa->params[k] != sb->params[k] && !(isnan(sa->params[k]) && isnan(sb->params[k]))) {
                snprintf(why, cap, "scenes differ: %s:%d has %s = %g, %s:%d %g", a->path, sa->line, pd->params[k].name, sa->params[k], b->path,
                         sb->line, sb->params[k]);
                return -1;
            }
        int same = sa->string_count == sb->string_count;
        for (int k = 0; same && k < sa->string_count; k++)
            same = sa->strings[k].param == sb->strings[k].param && strcmp(sa->strings[k].value, sb->strings[k].value) == 0;
        if (same)
            return 0;
        snprintf(why, cap, "scenes differ: %s:%d and %s:%d set different text parameters (e.g. box)", a->path, sa->line, b->path, sb->line);
    } else
        return 0;
    return -1;
}

vrg_memory_stats vrg_graph_memory(const vrg_graph *g)
{
    vrg_memory_stats s = {.naive_bytes = g->naive_bytes, .aliased_bytes = g->aliased_bytes, .history_bytes = g->history_bytes};
    for (int i = 0; i < g->res_count; i++) {
        const _vrg_resource *r = &g->res[i];
        if (r->block < 0 || r->first_use < 0)
            continue;
        s.transient_count++;
        if (r->overlap_count)
            s.alias_shared++;
    }
    return s;
}

int vrg_graph_placement(const vrg_graph *g, const char *name, int *block, uint64_t *offset, uint64_t *size)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0) {
            *block = g->res[i].block;
            *offset = g->res[i].offset;
            *size = g->res[i].req.size;
            return 0;
        }
    return -1;
}

int vrg_graph_pass_culled(const vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->pass_count; i++)
        if (strcmp(g->passes[i].name, name) == 0)
            return g->passes[i].culled;
    return -1;
}

int vrg_graph_stat(const vrg_graph *g, const char *pass, const char *name, double *value)
{
    for (int i = 0; i < g->pass_count; i++)
        if (strcmp(g->passes[i].name, pass) == 0)
            for (int k = 0; k < g->passes[i].stat_count; k++)
                if (strcmp(g->passes[i].stats[k].name, name) == 0) {
                    *value = g->passes[i].stats[k].value;
                    return 0;
                }
    return -1;
}

const char *vrg_graph_stat_at(const vrg_graph *g, uint32_t pass, uint32_t i, double *value)
{
    if (pass >= (uint32_t)g->pass_count || i >= (uint32_t)g->passes[pass].stat_count)
        return NULL;
    *value = g->passes[pass].stats[i].value;
    return g->passes[pass].stats[i].name;
}
