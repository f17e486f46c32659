/* Memory placement of transient resources (aliasing): first fit by
 * decreasing size into one heap block per memory-type set, two resources
 * sharing memory only when their lifetimes (compile.c) do not overlap.
 * Allocate runs it once the memory requirements are known; like compile,
 * it touches no Vulkan object, so `check` without a device plans from
 * estimated sizes with exactly this code. */
#include <stdlib.h>
#include "internal.h"

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
        if (_vrg_resource_kept(r)) {
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
