/* Capture of a frame's barriers and dispatches as plain data, so that a
 * benchmark can record the very same commands with direct Vulkan calls and
 * compare the runtime's recording cost with that floor (voxrg bench
 * --suite graph). The runtime appends while g->capture is set: every
 * barrier batch (barrier.c) and every dispatch with its pipeline, pushed
 * descriptors and push constants (dispatch.c). Timestamps, the scene's
 * uploads and readback copies are not captured. The frame itself runs in
 * vrg_graph_capture_frame (graph_frame.c): this file only keeps and
 * replays what it is handed. */
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "capture.h"

typedef struct cap_dispatch {
    VkPipeline pipeline;
    VkPipelineLayout layout;
    uint32_t write_count, push_size, groups[3];
    VkWriteDescriptorSet writes[VRG_MAX_BINDINGS];
    VkDescriptorImageInfo images[VRG_MAX_BINDINGS];
    VkDescriptorBufferInfo buffers[VRG_MAX_BINDINGS];
    VkBufferView texels[VRG_MAX_BINDINGS];
    VkWriteDescriptorSetAccelerationStructureKHR as[VRG_MAX_BINDINGS];
    VkAccelerationStructureKHR as_handles[VRG_MAX_BINDINGS];
    uint8_t push[128];
} cap_dispatch;

typedef struct cap_barrier {
    uint32_t image_count, buffer_count;
    VkImageMemoryBarrier2 *images;
    VkBufferMemoryBarrier2 *buffers;
} cap_barrier;

typedef struct cap_cmd {
    int is_dispatch;
    union {
        cap_dispatch *dispatch;
        cap_barrier barrier;
    };
} cap_cmd;

struct vrg_capture {
    cap_cmd *cmds;
    int count, cap;
    uint32_t dispatches, barriers;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor;
};

static cap_cmd *append(vrg_capture *c)
{
    if (c->count == c->cap) {
        int cap = c->cap ? c->cap * 2 : 64;
        cap_cmd *grown = realloc(c->cmds, sizeof *grown * (size_t)cap);
        if (!grown)
            return NULL;
        c->cmds = grown, c->cap = cap;
    }
    cap_cmd *cmd = &c->cmds[c->count++];
    memset(cmd, 0, sizeof *cmd);
    return cmd;
}

void _vrg_capture_barrier(vrg_capture *c, const VkDependencyInfo *dep)
{
    cap_cmd *cmd = append(c);
    if (!cmd)
        return;
    cap_barrier *b = &cmd->barrier;
    b->image_count = dep->imageMemoryBarrierCount;
    b->buffer_count = dep->bufferMemoryBarrierCount;
    b->images = malloc(sizeof *b->images * (b->image_count + 1));
    b->buffers = malloc(sizeof *b->buffers * (b->buffer_count + 1));
    if (b->image_count)
        memcpy(b->images, dep->pImageMemoryBarriers, sizeof *b->images * b->image_count);
    if (b->buffer_count)
        memcpy(b->buffers, dep->pBufferMemoryBarriers, sizeof *b->buffers * b->buffer_count);
    c->barriers++;
}

void _vrg_capture_dispatch(vrg_capture *c, VkPipeline pipeline, VkPipelineLayout layout, uint32_t write_count, const VkWriteDescriptorSet *writes,
                          const void *push, uint32_t push_size, const uint32_t groups[3])
{
    cap_cmd *cmd = append(c);
    cap_dispatch *d = cmd ? calloc(1, sizeof *d) : NULL;
    if (!d) {
        if (cmd)
            c->count--;
        return;
    }
    cmd->is_dispatch = 1;
    cmd->dispatch = d;
    d->pipeline = pipeline;
    d->layout = layout;
    d->write_count = write_count;
    d->push_size = push_size < sizeof d->push ? push_size : sizeof d->push;
    if (push && d->push_size)
        memcpy(d->push, push, d->push_size);
    memcpy(d->groups, groups, sizeof d->groups);
    /* the writes point into the caller's stack: copy what they point at */
    for (uint32_t i = 0; i < write_count && i < VRG_MAX_BINDINGS; i++) {
        d->writes[i] = writes[i];
        if (writes[i].pImageInfo)
            d->images[i] = *writes[i].pImageInfo, d->writes[i].pImageInfo = &d->images[i];
        if (writes[i].pBufferInfo)
            d->buffers[i] = *writes[i].pBufferInfo, d->writes[i].pBufferInfo = &d->buffers[i];
        if (writes[i].pTexelBufferView)
            d->texels[i] = *writes[i].pTexelBufferView, d->writes[i].pTexelBufferView = &d->texels[i];
        if (writes[i].pNext) { /* the only chained struct: an acceleration structure */
            d->as[i] = *(const VkWriteDescriptorSetAccelerationStructureKHR *)writes[i].pNext;
            d->as_handles[i] = d->as[i].pAccelerationStructures[0];
            d->as[i].pAccelerationStructures = &d->as_handles[i];
            d->as[i].pNext = NULL;
            d->writes[i].pNext = &d->as[i];
        }
    }
    c->dispatches++;
}

vrg_capture *_vrg_capture_new(PFN_vkCmdPushDescriptorSetKHR push_descriptor)
{
    vrg_capture *c = calloc(1, sizeof *c);
    if (c)
        c->push_descriptor = push_descriptor;
    return c;
}

void vrg_capture_record(const vrg_capture *c, VkCommandBuffer cmd)
{
    for (int i = 0; i < c->count; i++) {
        const cap_cmd *k = &c->cmds[i];
        if (!k->is_dispatch) {
            VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                    .bufferMemoryBarrierCount = k->barrier.buffer_count,
                                    .pBufferMemoryBarriers = k->barrier.buffers,
                                    .imageMemoryBarrierCount = k->barrier.image_count,
                                    .pImageMemoryBarriers = k->barrier.images};
            vkCmdPipelineBarrier2(cmd, &dep);
            continue;
        }
        const cap_dispatch *d = k->dispatch;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d->pipeline);
        if (d->write_count)
            c->push_descriptor(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d->layout, 0, d->write_count, d->writes);
        if (d->push_size)
            vkCmdPushConstants(cmd, d->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, d->push_size, d->push);
        vkCmdDispatch(cmd, d->groups[0], d->groups[1], d->groups[2]);
    }
}

void vrg_capture_counts(const vrg_capture *c, uint32_t *dispatches, uint32_t *barrier_batches)
{
    *dispatches = c->dispatches;
    *barrier_batches = c->barriers;
}

void vrg_capture_free(vrg_capture *c)
{
    if (!c)
        return;
    for (int i = 0; i < c->count; i++)
        if (c->cmds[i].is_dispatch)
            free(c->cmds[i].dispatch);
        else
            free(c->cmds[i].barrier.images), free(c->cmds[i].barrier.buffers);
    free(c->cmds);
    free(c);
}
