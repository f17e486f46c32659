/* Synchronisation: the exact barrier between the state a resource is in
 * and the use about to happen (what each access means to Vulkan: access.c).
 * Used by the recorder before every pass, by the dispatch helper between a
 * pass's own dispatches, and by `check` (on a simulated frame) to print them. */
#include <string.h>
#include "internal.h"
#include "capture.h"

/* Write-after-write and write-after-read need an execution dependency on
 * every earlier access (and the last write made available); read-after-write
 * needs the write made visible to the reading stage; a layout change counts
 * as a write. Reads already made visible need nothing. */
int _vrg_sync_use(_vrg_sync *s, _vrg_access_info need, int discard, _vrg_barrier_rec *b)
{
    int is_image = need.layout != VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout old = discard ? VK_IMAGE_LAYOUT_UNDEFINED : s->layout;
    int layout_change = is_image && (discard || s->layout != need.layout);
    memset(b, 0, sizeof *b);
    b->old_layout = old;
    b->new_layout = is_image ? need.layout : VK_IMAGE_LAYOUT_UNDEFINED;
    b->dst_stage = need.stage;
    b->dst_access = need.access;
    int needed = 0;
    if (need.writes || layout_change) {
        b->src_stage = s->write_stages | s->read_stages;
        b->src_access = s->write_access;
        needed = layout_change || b->src_stage != 0;
        if (need.writes) {
            s->write_stages = need.stage;
            s->write_access = need.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                             VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
            s->read_stages = 0;
            s->visible_stages = 0;
            s->visible_access = 0;
        } else {
            /* A transition that only prepares a read: the read stage now
             * orders everything after it. */
            s->read_stages = need.stage;
            s->visible_stages = need.stage;
            s->visible_access = need.access;
        }
    } else {
        int visible = (need.stage & ~s->visible_stages) == 0 && (need.access & ~s->visible_access) == 0;
        if (s->write_stages && !visible) {
            b->src_stage = s->write_stages;
            b->src_access = s->write_access;
            needed = 1;
            s->visible_stages |= need.stage;
            s->visible_access |= need.access;
        }
        s->read_stages |= need.stage;
    }
    if (is_image)
        s->layout = need.layout;
    return needed;
}

/* One use of one resource copy: merges in the accesses of resources that
 * shared its memory before (aliasing) when its contents start anew. */
static int barrier_for(vrg_graph *g, int ri, int copy, vrg_access access, _vrg_barrier_rec *out)
{
    _vrg_resource *r = &g->res[ri];
    int transient = !r->history && !r->persistent;
    int discard = transient && !r->touched[copy];
    _vrg_sync before = r->sync[copy];
    r->touched[copy] = 1;
    int needed = _vrg_sync_use(&r->sync[copy], _vrg_access_info_of(access, r->kind), discard, out);
    out->res = ri;
    out->copy = copy;
    if (discard) {
        for (int i = 0; i < r->overlap_count; i++) {
            const _vrg_sync *o = &g->res[g->overlaps[r->overlap_first + i]].sync[0];
            out->src_stage |= o->write_stages | o->read_stages;
            out->src_access |= o->write_access;
            out->aliasing |= (o->write_stages | o->read_stages) != 0;
        }
        /* its own accesses last frame: reuse of the same memory */
        out->src_stage |= before.write_stages | before.read_stages;
        out->src_access |= before.write_access;
        needed |= out->src_stage != 0;
    }
    return needed;
}

int _vrg_pass_barriers(vrg_graph *g, vrg_pass *p, _vrg_barrier_rec *out, int max)
{
    int n = 0;
    for (int s = 0; s < (int)p->plugin->desc->slot_count && n < max; s++) {
        const _vrg_binding_ref *b = &p->slots[s];
        if (b->res < 0 || (g->res[b->res].kind == VRG_ACCEL && !g->res[b->res].size)) /* an empty TLAS: nothing to order */
            continue;
        int copy = _vrg_copy_of(g, b->res, b->prev);
        if (barrier_for(g, b->res, copy, vrg_slot(p, s)->access, &out[n]))
            n++;
    }
    return n;
}

int _vrg_resource_barrier(vrg_graph *g, int res, int copy, vrg_access access, _vrg_barrier_rec *out)
{
    return barrier_for(g, res, copy, access, out);
}

/* One vkCmdPipelineBarrier2 per batch of this many of each kind: a frame's
 * history clear can bring every kept resource's two copies at once, more
 * than a stack array should hold. Barriers of one call are for distinct
 * resource copies, so splitting them changes no ordering. */
enum { BARRIER_BATCH = 64 };

static void flush_batch(vrg_graph *g, VkCommandBuffer cmd, const VkImageMemoryBarrier2 *img, uint32_t ni,
                        const VkBufferMemoryBarrier2 *buf, uint32_t nb)
{
    if (!ni && !nb)
        return;
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .bufferMemoryBarrierCount = nb,
        .pBufferMemoryBarriers = buf,
        .imageMemoryBarrierCount = ni,
        .pImageMemoryBarriers = img,
    };
    if (g->capture)
        _vrg_capture_barrier(g->capture, &dep);
    vkCmdPipelineBarrier2(cmd, &dep);
}

void _vrg_emit_barriers(vrg_graph *g, VkCommandBuffer cmd, const _vrg_barrier_rec *b, int n)
{
    VkImageMemoryBarrier2 img[BARRIER_BATCH];
    VkBufferMemoryBarrier2 buf[BARRIER_BATCH];
    uint32_t ni = 0, nb = 0;
    for (int i = 0; i < n; i++) {
        const _vrg_resource *r = &g->res[b[i].res];
        VkPipelineStageFlags2 src = b[i].src_stage ? b[i].src_stage : VK_PIPELINE_STAGE_2_NONE;
        if (r->kind == VRG_IMAGE)
            img[ni++] = (VkImageMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
                .srcStageMask = src,
                .srcAccessMask = b[i].src_access,
                .dstStageMask = b[i].dst_stage,
                .dstAccessMask = b[i].dst_access,
                .oldLayout = b[i].old_layout,
                .newLayout = b[i].new_layout,
                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .image = r->image[b[i].copy],
                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1},
            };
        else if ((r->kind == VRG_BUFFER || r->kind == VRG_ACCEL) && r->buffer[b[i].copy])
            buf[nb++] = (VkBufferMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                .srcStageMask = src,
                .srcAccessMask = b[i].src_access,
                .dstStageMask = b[i].dst_stage,
                .dstAccessMask = b[i].dst_access,
                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .buffer = r->buffer[b[i].copy],
                .size = VK_WHOLE_SIZE,
            };
        if (ni == BARRIER_BATCH || nb == BARRIER_BATCH) {
            flush_batch(g, cmd, img, ni, buf, nb);
            ni = nb = 0;
        }
    }
    flush_batch(g, cmd, img, ni, buf, nb);
}
