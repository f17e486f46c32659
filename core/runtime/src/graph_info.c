/* What a host asks of a loaded graph: its passes, timings, statistics,
 * memory and placement, and whether two graphs see the same world. */
#define _POSIX_C_SOURCE 200809L /* fileno */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
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

int vrg_graph_resource_info(const vrg_graph *g, const char *name, vrg_resource_info *out)
{
    memset(out, 0, sizeof *out);
    int i = _vrg_graph_find_resource(g, name);
    if (i < 0)
        return -1;
    const _vrg_resource *r = &g->res[i];
    out->kind = r->kind;
    out->format = r->format;
    out->width = r->width;
    out->height = r->height;
    out->size = r->size;
    out->writer = r->writer >= 0 ? g->passes[r->writer].name : NULL;
    out->history = r->history;
    return 0;
}

static const vrg_pass *scene_of(const vrg_graph *g)
{
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].is_scene)
            return &g->passes[i];
    return NULL;
}

/* A file's size for messages: "absent", "N bytes", or why it cannot be read. */
static void describe(FILE *f, int err, char *buf, size_t cap)
{
    if (!f && err == ENOENT)
        snprintf(buf, cap, "absent");
    else if (!f)
        snprintf(buf, cap, "unreadable: %s", vrg_open_strerror(err));
    else {
        struct stat st;
        snprintf(buf, cap, "%lld bytes", fstat(fileno(f), &st) == 0 ? (long long)st.st_size : -1ll);
    }
}

/* 1 when both files hold the same bytes or neither exists; else 0 with
 * each one's state in ha / hb. */
static int same_content(const char *a, const char *b, char *ha, char *hb, size_t cap)
{
    FILE *fa = vrg_fopen_regular(a, "rb");
    int ea = fa ? 0 : errno;
    FILE *fb = vrg_fopen_regular(b, "rb");
    int eb = fb ? 0 : errno, same = !fa && !fb && ea == ENOENT && eb == ENOENT;
    if (fa && fb) {
        char x[8192], y[8192];
        size_t nx, ny;
        do {
            nx = fread(x, 1, sizeof x, fa), ny = fread(y, 1, sizeof y, fb);
            same = nx == ny && memcmp(x, y, nx) == 0;
        } while (same && nx == sizeof x);
        same = same && !ferror(fa) && !ferror(fb);
    }
    describe(fa, ea, ha, cap);
    describe(fb, eb, hb, cap);
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

/* The scenes' data files (vrg_pass_input_file), pair by pair, by content:
 * the same model in two folders is the same world; a journal beside one
 * graph and not the other is not. */
static int same_scene_inputs(const vrg_graph *a, const vrg_pass *sa, const vrg_graph *b, const vrg_pass *sb, char *why, size_t cap)
{
    if (sa->input_count != sb->input_count) {
        snprintf(why, cap, "scenes differ: %s:%d reads %d data files, %s:%d %d", a->path, sa->line, sa->input_count, b->path, sb->line,
                 sb->input_count);
        return 0;
    }
    for (int k = 0; k < sa->input_count; k++) {
        char ha[128], hb[128];
        if (!same_content(sa->inputs[k], sb->inputs[k], ha, hb, sizeof ha)) {
            snprintf(why, cap, "scenes differ: %s:%d reads %s (%s), %s:%d reads %s (%s%s)", a->path, sa->line, sa->inputs[k], ha, b->path,
                     sb->line, sb->inputs[k], hb, strcmp(ha, hb) ? "" : ", other content");
            return 0;
        }
    }
    return 1;
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
        if (!same)
            snprintf(why, cap, "scenes differ: %s:%d and %s:%d set different text parameters (e.g. box)", a->path, sa->line, b->path, sb->line);
        else if (same_scene_inputs(a, sa, b, sb, why, cap))
            return 0;
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
