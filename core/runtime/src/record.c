/* Phase 5, record: one command buffer per frame. Before each pass the
 * barriers its slots need, then the plugin's execute, bracketed by GPU
 * timestamps; history images are cleared when history is reset; the output
 * and dumped resources are copied to a host buffer at the end.
 *
 * Frames in flight: a frame records into the next of frames_in_flight
 * slots (command buffer, fence, query pool, part of the readback buffer)
 * after waiting only for the frame that used that slot before. Frames run
 * in submission order on one queue, so the barriers the trackers derive
 * order a frame after the previous one as they did when the CPU waited. */
#define _POSIX_C_SOURCE 200809L
#include <string.h>
#include <time.h>
#include "internal.h"
#include "shader_pass.h"
#include "phases.h"

/* @prev copies on every history reset (but those a reload carried over);
 * persistent resources only when new (but those a reload kept). Returns
 * how many history resources were cleared: history is valid this frame
 * when none was. */
static int clear_kept(vrg_graph *g, VkCommandBuffer cmd)
{
    _vrg_barrier_rec b[2 * VRG_MAX_RESOURCES] = {0}; /* both copies of every resource */
    struct {
        int res, copy;
    } clear[2 * VRG_MAX_RESOURCES];
    int n = 0, nclear = 0, cleared = 0;
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        r->history_cleared = r->history && g->history_reset && !r->history_kept;
        r->history_kept = 0;
        r->fresh = g->fresh && !r->carried;
        r->carried = 0;
        cleared += r->history_cleared && r->first_use >= 0;
        if (r->first_use < 0 || r->kind == VRG_ACCEL || !(r->history_cleared || (r->persistent && r->fresh)))
            continue;
        for (int c = 0; c < (r->history ? 2 : 1); c++) {
            /* old contents are garbage: start from UNDEFINED */
            r->sync[c].layout = VK_IMAGE_LAYOUT_UNDEFINED;
            if (_vrg_sync_use(&r->sync[c], _vrg_access_info_of(VRG_ACCESS_TRANSFER_DST, r->kind), 1, &b[n]))
                b[n].res = i, b[n].copy = c, n++;
            /* cleared whether or not a barrier was needed first: a new
             * buffer has no earlier access to wait for, and its memory may
             * hold what a destroyed graph left there */
            clear[nclear].res = i, clear[nclear].copy = c, nclear++;
        }
    }
    _vrg_emit_barriers(g, cmd, b, n);
    for (int k = 0; k < nclear; k++) {
        _vrg_resource *r = &g->res[clear[k].res];
        if (r->kind == VRG_IMAGE) {
            VkClearColorValue zero = {{0}};
            VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
            vkCmdClearColorImage(cmd, r->image[clear[k].copy], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        } else
            vkCmdFillBuffer(cmd, r->buffer[clear[k].copy], 0, VK_WHOLE_SIZE, 0);
    }
    return cleared;
}

static void copy_readbacks(vrg_graph *g, VkCommandBuffer cmd, const struct _vrg_frame_slot *s)
{
    _vrg_barrier_rec b[VRG_MAX_RESOURCES + 1] = {0}; /* every read-back resource, and the shown one */
    int n = 0, want[VRG_MAX_RESOURCES], nw = 0;
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->first_use < 0 || !(r->is_output || r->readback))
            continue;
        want[nw++] = i;
        if (_vrg_resource_barrier(g, i, _vrg_copy_of(g, i, 0), VRG_ACCESS_TRANSFER_SRC, &b[n]))
            n++;
    }
    /* the viewer's choice: left in TRANSFER_SRC like the output, not copied */
    if (g->shown >= 0 && _vrg_resource_barrier(g, g->shown, _vrg_copy_of(g, g->shown, 0), VRG_ACCESS_TRANSFER_SRC, &b[n]))
        n++;
    _vrg_emit_barriers(g, cmd, b, n);
    for (int k = 0; k < nw; k++) {
        _vrg_resource *r = &g->res[want[k]];
        int c = _vrg_copy_of(g, want[k], 0);
        if (r->kind == VRG_IMAGE) {
            VkBufferImageCopy region = {
                .bufferOffset = s->readback_base + g->readback_offset[want[k]],
                .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                .imageExtent = {r->width, r->height, 1},
            };
            vkCmdCopyImageToBuffer(cmd, r->image[c], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, g->readback_buffer, 1, &region);
        } else {
            VkBufferCopy region = {.srcOffset = 0, .dstOffset = s->readback_base + g->readback_offset[want[k]], .size = r->size};
            vkCmdCopyBuffer(cmd, r->buffer[c], g->readback_buffer, 1, &region);
        }
    }
    /* the timestamps go to the same memory: vkGetQueryPoolResults would
     * wait for the whole device (lavapipe), i.e. for later frames too */
    if (s->queries) {
        VkMemoryBarrier2 after = {
            .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
            .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
            .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
        };
        VkDependencyInfo wait = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &after};
        vkCmdPipelineBarrier2(cmd, &wait);
        vkCmdCopyQueryPoolResults(cmd, s->queries, 0, (uint32_t)(2 * g->schedule_count), g->readback_buffer, s->readback_base + g->timestamp_offset,
                                  sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    }
    VkBufferMemoryBarrier2 host = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
        .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = g->readback_buffer,
        .offset = s->readback_base,
        .size = g->readback_slot_bytes,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &host};
    vkCmdPipelineBarrier2(cmd, &dep);
}

static void read_timestamps(vrg_graph *g, const struct _vrg_frame_slot *s)
{
    for (int i = 0; i < g->pass_count; i++)
        g->pass_ms[i] = -1;
    g->timed_frame = (int64_t)s->frame_index;
    if (!s->queries)
        return;
    const uint64_t *ts = (const uint64_t *)((const uint8_t *)g->readback_map + s->readback_base + g->timestamp_offset);
    double ns = g->ctx->dev.features.timestamp_period_ns;
    for (int k = 0; k < s->schedule_count; k++)
        g->pass_ms[g->schedule[k]] = (double)(ts[2 * k + 1] - ts[2 * k]) * ns * 1e-6;
}

/* After scheduled pass k: its progress word is set once everything before
 * has run. Not timestamps: lavapipe's vkGetQueryPoolResults waits for the
 * device to idle, so a late frame's queries cannot be read. */
static void mark_done(vrg_graph *g, VkCommandBuffer cmd, const struct _vrg_frame_slot *s, int k)
{
    VkMemoryBarrier2 after = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &after};
    vkCmdPipelineBarrier2(cmd, &dep);
    vkCmdFillBuffer(cmd, g->readback_buffer, s->readback_base + g->progress_offset + 4 * (VkDeviceSize)k, 4, 1);
}

/* The scheduled pass still running on the GPU: the first whose progress
 * word is unset; -1 if every pass ended (the frame's copies are what runs). */
static int running_pass(const vrg_graph *g, const struct _vrg_frame_slot *s)
{
    const volatile uint32_t *done = (const volatile uint32_t *)((const uint8_t *)g->readback_map + s->readback_base + g->progress_offset);
    for (int k = 0; k < s->schedule_count; k++)
        if (!done[k])
            return g->schedule[k];
    return -1;
}

static void report_stuck(vrg_graph *g, const struct _vrg_frame_slot *s, _vrg_wait_result wr, double waited_s)
{
    unsigned long long frame = (unsigned long long)s->frame_index;
    if (wr == VRG_WAIT_FAILED) {
        _vrg_error(&g->diag, VRG_E_DEVICE_LOST, "frame %llu: waiting for the GPU failed (device lost?)", frame);
        return;
    }
    int k = running_pass(g, s);
    char what[VRG_NAME_MAX * 2 + 32];
    if (k >= 0)
        snprintf(what, sizeof what, "pass '%s' (plugin %s)", g->passes[k].name, g->passes[k].plugin->name);
    else
        snprintf(what, sizeof what, "%s", "the frame's final copies");
    if (wr == VRG_WAIT_TIMEOUT)
        _vrg_error(&g->diag, VRG_E_GPU_TIMEOUT, "frame %llu: %s has run for more than %g s on the GPU (the limit: vrg_context_desc.gpu_timeout_s or $VOXRG_GPU_TIMEOUT)", frame, what,
                  g->ctx->gpu_timeout_s);
    else
        _vrg_error(&g->diag, VRG_E_GPU_TIMEOUT, "frame %llu: interrupted after %.1f s on the GPU, %s still running", frame, waited_s, what);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* Waits for the slot's frame; its timestamps become the latest timings. */
static int wait_slot(vrg_graph *g, struct _vrg_frame_slot *s)
{
    if (!s->pending)
        return 0;
    double waited;
    _vrg_wait_result wr = _vrg_wait_fence(g->ctx, s->fence, &waited);
    if (wr != VRG_WAIT_DONE) {
        report_stuck(g, s, wr, waited);
        return -1;
    }
    s->pending = 0;
    if (s->serial > g->finished) {
        g->finished = s->serial;
        read_timestamps(g, s);
    }
    /* a NaN fails the frame's host call (vrg_graph_frame or vrg_graph_wait),
     * not the wait itself: readbacks and destroy go on */
    if (g->check_finite && _vrg_finite_collect(g, s->readback_base, s->frame_index) != 0)
        g->finite_failed = 1;
    return 0;
}

int _vrg_wait_frames(vrg_graph *g)
{
    if (g->ctx && g->ctx->gpu_busy && g->submitted > g->finished) {
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "graph '%s': the GPU is still busy with a frame that timed out or was interrupted", g->name);
        return -1;
    }
    /* oldest first: the timings end as the newest frame's */
    for (uint64_t serial = g->finished + 1; serial <= g->submitted; serial++)
        for (uint32_t i = 0; i < g->frames_in_flight; i++)
            if (g->slots[i].pending && g->slots[i].serial == serial && wait_slot(g, &g->slots[i]) != 0)
                return -1;
    _vrg_free_retired(g, 0);
    return 0;
}

int _vrg_record_frame(vrg_graph *g)
{
    uint32_t slot = (uint32_t)(g->submitted % g->frames_in_flight);
    struct _vrg_frame_slot *s = &g->slots[slot];
    /* the only wait: for the frame that used this slot (frames_in_flight ago) */
    if (wait_slot(g, s) != 0 || _vrg_finite_failed(g))
        return -1;
    _vrg_free_retired(g, 0);
    double start = now_ms(); /* the runtime's CPU time: up to the submit, not the GPU's */
    VkDevice dev = g->ctx->dev.device;
    VkCommandBuffer cmd = s->cmd;
    vkResetCommandBuffer(cmd, 0);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &bi);
    if (s->queries)
        vkCmdResetQueryPool(cmd, s->queries, 0, (uint32_t)(2 * g->schedule_count));
    g->frame.frame_slot = slot;
    g->frame.frames_in_flight = g->frames_in_flight;
    g->frame.width = g->width;
    g->frame.height = g->height;
    g->frame.seed = g->seed;
    g->frame.time_s = (double)g->frame.frame_index / g->fps;
    g->frame.camera = g->camera;
    /* after a reset history is invalid, unless a reload carried every
     * history resource over (vrg_res_history_valid tells them apart) */
    int lost = clear_kept(g, cmd);
    if (g->check_finite)
        _vrg_finite_begin(g, cmd, s->readback_base);
    g->frame.history_valid = !g->history_reset || (g->history_carried && !lost);
    /* carried resources continue last frame, so motion is from its camera */
    g->frame.prev_camera = g->frame.history_valid || g->history_carried ? g->last_camera : g->camera;
    g->history_carried = 0;
    g->last_camera = g->camera;
    for (int i = 0; i < g->res_count; i++)
        g->res[i].touched[0] = g->res[i].touched[1] = 0;
    g->frame.resources_new = g->fresh;
    g->frame.params_changed = g->params_changed;
    g->params_changed = 0;
    g->history_reset = 0;
    g->fresh = 0;
    int failed = 0;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        if (s->queries)
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, s->queries, (uint32_t)(2 * k));
        _vrg_barrier_rec b[VRG_MAX_SLOTS];
        int n = _vrg_pass_barriers(g, p, b, VRG_MAX_SLOTS);
        _vrg_emit_barriers(g, cmd, b, n);
        p->failed = 0;
        _vrg_pass_clear_stats(p, 0); /* figures are this frame's */
        p->cmd = cmd;
        double t0 = now_ms();
        _vrg_running before = _vrg_running_enter("execute", p->name, p->plugin);
        if (p->plugin->shader_pass) /* a shader-only pass: one dispatch, of the variant its connections and choices pick */
            _vrg_shader_pass_execute(p, cmd);
        else if (p->plugin->desc->execute)
            p->plugin->desc->execute(p, cmd);
        else /* a pass whose execute would only record its list */
            _vrg_dispatch_listed(p, cmd);
        _vrg_running_leave(before);
        /* a value pushed by name that no dispatch read: the pass's mistake */
        if (p->push_count && !p->failed)
            _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "'%s' was set with %s after the pass's last dispatch: no dispatch read it", p->push_values[0].name,
                           p->push_values[0].setter);
        p->push_count = 0;
        g->pass_cpu_ms[g->schedule[k]] = now_ms() - t0;
        p->cmd = VK_NULL_HANDLE;
        failed |= p->failed;
        if (s->queries)
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, s->queries, (uint32_t)(2 * k + 1));
        if (g->check_finite) /* after the pass's end timestamp: not in its time */
            _vrg_finite_after_pass(g, cmd, s->readback_base, k);
        mark_done(g, cmd, s, k);
    }
    if (g->check_finite)
        _vrg_finite_end(g, cmd, s->readback_base);
    copy_readbacks(g, cmd, s);
    vkEndCommandBuffer(cmd);
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
    vkResetFences(dev, 1, &s->fence);
    /* the host's writes are visible to the submission (coherent memory) */
    memset((uint8_t *)g->readback_map + s->readback_base + g->progress_offset, 0, 4 * (size_t)g->schedule_count);
    VkResult res = vkQueueSubmit2(g->ctx->dev.queue, 1, &si, s->fence);
    g->cpu_ms = now_ms() - start;
    if (res != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "frame %llu: queue submission failed (%d)", (unsigned long long)g->frame.frame_index, res);
        return -1;
    }
    s->pending = 1;
    s->frame_index = g->frame.frame_index;
    s->serial = ++g->submitted;
    s->schedule_count = g->schedule_count;
    g->last_slot = (int)slot;
    g->frame.frame_index++;
    return failed ? -1 : 0;
}
