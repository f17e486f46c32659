/* Phase 3, compile: cull, order, lifetimes, and memory placement (aliasing).
 * Nothing here touches Vulkan objects, so `check` without a device and the
 * fuzzer run exactly this code. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

/* ---- formats ---- */

static const struct {
    const char *name;
    VkFormat format;
    uint32_t bytes, channels;
} formats[] = {
    {"r8", VK_FORMAT_R8_UNORM, 1, 1},
    {"rg8", VK_FORMAT_R8G8_UNORM, 2, 2},
    {"rgba8", VK_FORMAT_R8G8B8A8_UNORM, 4, 4},
    {"rgba8_srgb", VK_FORMAT_R8G8B8A8_SRGB, 4, 4},
    {"r16f", VK_FORMAT_R16_SFLOAT, 2, 1},
    {"rg16f", VK_FORMAT_R16G16_SFLOAT, 4, 2},
    {"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT, 8, 4},
    {"r32f", VK_FORMAT_R32_SFLOAT, 4, 1},
    {"rg32f", VK_FORMAT_R32G32_SFLOAT, 8, 2},
    {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT, 16, 4},
    {"r32ui", VK_FORMAT_R32_UINT, 4, 1},
    {"rg32ui", VK_FORMAT_R32G32_UINT, 8, 2},
    {"rgba32ui", VK_FORMAT_R32G32B32A32_UINT, 16, 4},
    {"r11g11b10f", VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4, 3},
};

VkFormat _vrg_format_parse(const char *s)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (strcmp(formats[i].name, s) == 0)
            return formats[i].format;
    return VK_FORMAT_UNDEFINED;
}

const char *_vrg_format_list(void)
{
    static char list[512];
    if (!list[0]) {
        strcat(list, "one of");
        for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++) {
            strcat(list, i ? ", " : " ");
            strcat(list, formats[i].name);
        }
    }
    return list;
}

const char *_vrg_format_name(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].name;
    return "unknown-format";
}

uint64_t _vrg_format_bytes(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].bytes;
    return 16;
}

uint32_t _vrg_format_channels(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].channels;
    return 4;
}

void _vrg_resource_extent(const vrg_graph *g, const _vrg_resource *r, uint32_t *w, uint32_t *h)
{
    if (r->abs_width) {
        *w = r->abs_width;
        *h = r->abs_height;
        return;
    }
    float s = r->scale > 0 ? r->scale : 1.0f;
    *w = (uint32_t)fmaxf(1.0f, floorf((float)g->width * s + 0.5f));
    *h = (uint32_t)fmaxf(1.0f, floorf((float)g->height * s + 0.5f));
}

/* A kept resource survives the frame: never aliased, never culled away. */
static int kept(const _vrg_resource *r) { return r->history || r->persistent; }

/* ---- cull ---- */

static void mark_alive(vrg_graph *g, int pi, int *alive)
{
    if (pi < 0 || alive[pi])
        return;
    alive[pi] = 1;
    vrg_pass *p = &g->passes[pi];
    for (int s = 0; p->plugin && s < (int)p->plugin->desc->slot_count; s++)
        if (vrg_slot(p, s)->dir == VRG_IN && p->slots[s].res >= 0)
            mark_alive(g, g->res[p->slots[s].res].writer, alive);
}

static void cull(vrg_graph *g)
{
    int alive[VRG_MAX_PASSES] = {0};
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->is_output || r->readback || r->history)
            mark_alive(g, r->writer, alive);
    }
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].is_scene)
            mark_alive(g, i, alive);
    for (int i = 0; i < g->pass_count; i++)
        g->passes[i].culled = !alive[i];
}

/* ---- order: Kahn's algorithm, ties broken by file order, scene first ---- */

static int schedule(vrg_graph *g)
{
    int indeg[VRG_MAX_PASSES] = {0}, done[VRG_MAX_PASSES] = {0};
    for (int i = 0; i < g->pass_count; i++) {
        vrg_pass *p = &g->passes[i];
        p->order = -1;
        if (p->culled)
            continue;
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
            _vrg_binding_ref *b = &p->slots[s];
            if (vrg_slot(p, s)->dir == VRG_IN && b->res >= 0 && !b->prev && g->res[b->res].writer >= 0)
                indeg[i]++;
        }
    }
    g->schedule_count = 0;
    for (;;) {
        int pick = -1;
        for (int i = 0; i < g->pass_count; i++) {
            if (g->passes[i].culled || done[i] || indeg[i] > 0)
                continue;
            if (pick < 0 || (g->passes[i].is_scene && !g->passes[pick].is_scene))
                pick = i;
        }
        if (pick < 0)
            break;
        done[pick] = 1;
        g->passes[pick].order = g->schedule_count;
        g->schedule[g->schedule_count++] = pick;
        /* release readers of everything pick writes */
        for (int i = 0; i < g->pass_count; i++) {
            vrg_pass *p = &g->passes[i];
            if (p->culled || done[i])
                continue;
            for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
                _vrg_binding_ref *b = &p->slots[s];
                if (vrg_slot(p, s)->dir == VRG_IN && b->res >= 0 && !b->prev && g->res[b->res].writer == pick)
                    indeg[i]--;
            }
        }
    }
    for (int i = 0; i < g->pass_count; i++)
        if (!g->passes[i].culled && !done[i]) {
            _vrg_error_at(&g->diag, g->passes[i].line, VRG_E_CYCLE, NULL, "pass '%s' cannot be scheduled (cycle)", g->passes[i].name);
            return -1;
        }
    return 0;
}

/* ---- lifetimes, in schedule order ---- */

static void use_at(_vrg_resource *r, int order)
{
    if (r->first_use < 0 || order < r->first_use)
        r->first_use = order;
    if (order > r->last_use)
        r->last_use = order;
}

static void lifetimes(vrg_graph *g)
{
    for (int i = 0; i < g->res_count; i++)
        g->res[i].first_use = g->res[i].last_use = -1;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++)
            if (p->slots[s].res >= 0)
                use_at(&g->res[p->slots[s].res], k);
    }
    for (int i = 0; i < g->res_count; i++)
        if (g->res[i].internal_owner >= 0 && g->passes[g->res[i].internal_owner].order >= 0)
            use_at(&g->res[i], g->passes[g->res[i].internal_owner].order);
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->first_use < 0)
            continue;
        /* read back after the last pass; kept resources live all frame; a
         * viewer's graph keeps every image to the end */
        if (r->is_output || r->readback || (g->desc.keep_images && r->kind == VRG_IMAGE))
            r->last_use = g->schedule_count;
        if (kept(r)) {
            r->first_use = 0;
            r->last_use = g->schedule_count;
        }
    }
}

int _vrg_compile(vrg_graph *g)
{
    cull(g);
    if (schedule(g) != 0)
        return -1;
    lifetimes(g);
    return 0;
}

/* ---- aliasing: first-fit placement by decreasing size ---- */

static int lifetimes_overlap(const _vrg_resource *a, const _vrg_resource *b)
{
    return a->first_use <= b->last_use && b->first_use <= a->last_use;
}

static int memory_overlap(const _vrg_resource *a, const _vrg_resource *b)
{
    return a->block == b->block && a->offset < b->offset + b->req.size && b->offset < a->offset + a->req.size;
}

/* Sorted as (size, index) pairs: the comparator needs nothing but its arguments. */
typedef struct sized_res {
    VkDeviceSize size;
    int index;
} sized_res;

static int by_size_desc(const void *x, const void *y)
{
    const sized_res *a = x, *b = y;
    if (a->size != b->size)
        return a->size < b->size ? 1 : -1;
    return a->index - b->index;
}

/* One heap block per memory-type set. A new block is made only for a
 * resource whose type bits meet no block's, and blocks only ever narrow
 * their bits, so blocks hold disjoint non-empty sets of memory types: there
 * are never more than VK_MAX_MEMORY_TYPES. Vulkan guarantees a resource at
 * least one allowed type; one without any is reported, not guessed at. */
static int block_for(vrg_graph *g, const _vrg_resource *r)
{
    if (!r->req.memoryTypeBits) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "resource '%s': the device allows no memory type for it", r->name);
        return -1;
    }
    int b;
    for (b = 0; b < g->block_count; b++)
        if (g->blocks[b].type_bits & r->req.memoryTypeBits)
            break;
    if (b == g->block_count)
        g->blocks[g->block_count++] = (_vrg_heap_block){.type_bits = r->req.memoryTypeBits};
    g->blocks[b].type_bits &= r->req.memoryTypeBits;
    return b;
}

/* Lowest offset in block b that clashes with no placed resource alive at the same time. */
static VkDeviceSize lowest_free_offset(const vrg_graph *g, const _vrg_resource *r, int b, const sized_res *placed, int placed_count)
{
    VkDeviceSize align = r->req.alignment ? r->req.alignment : 1;
    VkDeviceSize offset = 0;
    for (int moved = 1; moved;) {
        moved = 0;
        offset = (offset + align - 1) / align * align;
        for (int j = 0; j < placed_count; j++) {
            const _vrg_resource *o = &g->res[placed[j].index];
            if (o->block != b || !lifetimes_overlap(r, o))
                continue;
            if (offset < o->offset + o->req.size && o->offset < offset + r->req.size) {
                offset = o->offset + o->req.size;
                moved = 1;
                break;
            }
        }
    }
    return offset;
}

/* Who shares memory with whom (the aliasing barriers need it): one list for
 * the graph, each resource a run of it, as long as it needs. */
static int list_overlaps(vrg_graph *g, const sized_res *placed, int placed_count)
{
    g->overlap_used = 0;
    for (int k = 0; k < placed_count; k++) {
        _vrg_resource *r = &g->res[placed[k].index];
        r->overlap_first = g->overlap_used;
        for (int j = 0; j < placed_count; j++) {
            if (j == k || !memory_overlap(r, &g->res[placed[j].index]))
                continue;
            if (g->overlap_used == g->overlap_cap) {
                int cap = g->overlap_cap ? 2 * g->overlap_cap : 256;
                int *grown = realloc(g->overlaps, (size_t)cap * sizeof *grown);
                if (!grown) {
                    _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "out of memory planning aliased memory");
                    return -1;
                }
                g->overlaps = grown;
                g->overlap_cap = cap;
            }
            g->overlaps[g->overlap_used++] = placed[j].index;
            r->overlap_count++;
        }
    }
    return 0;
}

int _vrg_plan_aliasing(vrg_graph *g)
{
    sized_res order[VRG_MAX_RESOURCES];
    int n = 0;
    g->block_count = 0;
    g->overlap_used = 0;
    g->naive_bytes = g->aliased_bytes = g->history_bytes = 0;
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        r->block = -1;
        r->offset = 0;
        r->overlap_first = r->overlap_count = 0;
        if (r->first_use < 0)
            continue;
        if (kept(r)) {
            g->history_bytes += r->req.size * (r->history ? 2 : 1);
            continue;
        }
        g->naive_bytes += r->req.size;
        order[n++] = (sized_res){r->req.size, i};
    }
    qsort(order, (size_t)n, sizeof order[0], by_size_desc);
    for (int k = 0; k < n; k++) {
        _vrg_resource *r = &g->res[order[k].index];
        int b = block_for(g, r);
        if (b < 0)
            return -1;
        r->block = b;
        r->offset = lowest_free_offset(g, r, b, order, k);
        if (r->offset + r->req.size > g->blocks[b].size)
            g->blocks[b].size = r->offset + r->req.size;
    }
    if (list_overlaps(g, order, n) != 0)
        return -1;
    for (int b = 0; b < g->block_count; b++)
        g->aliased_bytes += g->blocks[b].size;
    return 0;
}
