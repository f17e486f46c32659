/* Graph hot reload: the saved graph file is loaded as a new graph beside the
 * running one; on any error the running graph stays. When the new graph has
 * the same structure (passes, plugins, connections, resources: a change of
 * parameter values only), its history resources are copied over from the
 * old graph and history stays valid, so temporal passes carry on; passes
 * see frame->params_changed once (after any reload). After a structural change the history
 * resources whose name, format and size are unchanged are copied over too;
 * the rest start cleared, frame->history_valid is 0 if any did, and
 * vrg_res_history_valid tells a pass which of its inputs still hold the
 * past. The frame counter and the camera carry over either way. */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "internal.h"
#include "phases.h"
#include "plugin_loader.h"

static int same_resource(const _vrg_resource *a, const _vrg_resource *b)
{
    return strcmp(a->name, b->name) == 0 && a->kind == b->kind && a->format == b->format && a->width == b->width &&
           a->height == b->height && a->size == b->size && a->mips == b->mips && a->history == b->history &&
           a->persistent == b->persistent && (a->first_use < 0) == (b->first_use < 0);
}

/* Same passes, plugins, connections and resources: only parameter values differ. */
static int same_structure(const vrg_graph *a, const vrg_graph *b)
{
    if (a->pass_count != b->pass_count || a->res_count != b->res_count)
        return 0;
    for (int i = 0; i < a->res_count; i++)
        if (!same_resource(&a->res[i], &b->res[i]))
            return 0;
    for (int i = 0; i < a->pass_count; i++) {
        const vrg_pass *p = &a->passes[i], *q = &b->passes[i];
        if (strcmp(p->name, q->name) != 0 || strcmp(p->plugin->name, q->plugin->name) != 0 ||
            p->plugin->desc->slot_count != q->plugin->desc->slot_count || p->culled != q->culled)
            return 0;
        for (uint32_t s = 0; s < p->plugin->desc->slot_count; s++)
            if (p->slots[s].res != q->slots[s].res || p->slots[s].prev != q->slots[s].prev || p->slots[s].dummy != q->slots[s].dummy)
                return 0;
    }
    return 1;
}

/* The old graph's resource that new resource i continues: same name,
 * kind, format, size and history, or -1. */
static int matching(const vrg_graph *old, const vrg_graph *g, int i)
{
    const _vrg_resource *to = &g->res[i];
    for (int j = 0; j < old->res_count; j++) {
        const _vrg_resource *from = &old->res[j];
        if (strcmp(from->name, to->name) == 0)
            return from->kind == to->kind && from->format == to->format && from->width == to->width && from->height == to->height &&
                           from->size == to->size && from->mips == to->mips && from->history == to->history && from->first_use >= 0
                       ? j
                       : -1;
    }
    return -1;
}

/* Both copies of every history resource the old graph has a match for,
 * old graph to new, on the new graph's command buffer; the trackers of both
 * graphs learn the transfer. The copied ones are marked history_kept. */
static int copy_history(vrg_graph *old, vrg_graph *g)
{
    VkDevice dev = g->ctx->dev.device;
    /* the new graph has run no frame: its first slot is free */
    VkCommandBuffer cmd = g->slots[0].cmd;
    VkFence fence = g->slots[0].fence;
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &bi);
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *to = &g->res[i];
        int j = to->history && to->first_use >= 0 && to->kind != VRG_ACCEL ? matching(old, g, i) : -1;
        if (j < 0)
            continue;
        _vrg_resource *from = &old->res[j];
        to->history_kept = 1;
        for (int c = 0; c < 2; c++) {
            _vrg_barrier_rec src, dst;
            if (_vrg_sync_use(&from->sync[c], _vrg_access_info_of(VRG_ACCESS_TRANSFER_SRC, from->kind), 0, &src)) {
                src.res = j, src.copy = c;
                _vrg_emit_barriers(old, cmd, &src, 1);
            }
            if (_vrg_sync_use(&to->sync[c], _vrg_access_info_of(VRG_ACCESS_TRANSFER_DST, to->kind), 1, &dst)) {
                dst.res = i, dst.copy = c;
                _vrg_emit_barriers(g, cmd, &dst, 1);
            }
            if (to->kind == VRG_IMAGE) {
                VkImageCopy region = {
                    .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                    .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                    .extent = {to->width, to->height, 1},
                };
                vkCmdCopyImage(cmd, from->image[c], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to->image[c], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
            } else {
                VkBufferCopy region = {.size = to->size};
                vkCmdCopyBuffer(cmd, from->buffer[c], to->buffer[c], 1, &region);
            }
        }
    }
    vkEndCommandBuffer(cmd);
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
    vkResetFences(dev, 1, &fence);
    double waited;
    if (vkQueueSubmit2(g->ctx->dev.queue, 1, &si, fence) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "reload: submitting the copy of history failed");
        return -1;
    }
    _vrg_wait_result w = _vrg_wait_fence(g->ctx, fence, &waited);
    if (w != VRG_WAIT_DONE) {
        _vrg_error(&g->diag, w == VRG_WAIT_FAILED ? VRG_E_DEVICE_LOST : VRG_E_GPU_TIMEOUT, "reload: the copy of history %s after %.1f s",
                   w == VRG_WAIT_FAILED ? "failed" : w == VRG_WAIT_INTERRUPTED ? "was interrupted" : "timed out", waited);
        return -1;
    }
    return 0;
}

/* Same kind, format, size and mips, both persistent (one copy, never
 * history) with memory of their own (an aliased block is shared). */
static int can_keep(const _vrg_resource *to, const _vrg_resource *from)
{
    return to->kind == from->kind && to->format == from->format && to->width == from->width && to->height == from->height &&
           to->size == from->size && to->mips == from->mips && to->first_use >= 0 && from->first_use >= 0 && to->persistent &&
           from->persistent && !to->history && !from->history && to->block < 0 && from->block < 0;
}

/* The Vulkan objects and sync state of a and b change places. */
static void swap_objects(_vrg_resource *a, _vrg_resource *b)
{
    _vrg_resource t = *a;
    memcpy(a->image, b->image, sizeof a->image);
    memcpy(a->view, b->view, sizeof a->view);
    memcpy(a->buffer, b->buffer, sizeof a->buffer);
    memcpy(a->texel_view, b->texel_view, sizeof a->texel_view);
    memcpy(a->own_memory, b->own_memory, sizeof a->own_memory);
    memcpy(a->sync, b->sync, sizeof a->sync);
    memcpy(b->image, t.image, sizeof t.image);
    memcpy(b->view, t.view, sizeof t.view);
    memcpy(b->buffer, t.buffer, sizeof t.buffer);
    memcpy(b->texel_view, t.texel_view, sizeof t.texel_view);
    memcpy(b->own_memory, t.own_memory, sizeof t.own_memory);
    memcpy(b->sync, t.sync, sizeof t.sync);
}

/* The resources new passes asked to keep (vrg_pass_keep_resource) take
 * over the Vulkan objects of their previous instances' (and the old graph
 * frees the new, unused ones with itself); the sync state goes with them,
 * so the new graph's first barrier waits for the old graph's last use.
 * Called once the reload cannot fail and the old graph's frames have
 * ended: the old graph never runs again, and no frame of it still reads
 * what the new one writes. */
static void keep_resources(vrg_graph *old, vrg_graph *g)
{
    for (int i = 0; i < g->pass_count; i++) {
        vrg_pass *q = &g->passes[i], *p = vrg_pass_previous_instance(q);
        for (uint32_t s = 0; p && s < q->plugin->desc->slot_count; s++) {
            int ri = q->slots[s].res, rj = p->slots[s].res;
            if (!(q->keep_slots >> s & 1) || ri < 0 || rj < 0 || q->slots[s].dummy || p->slots[s].dummy || !can_keep(&g->res[ri], &old->res[rj]))
                continue;
            swap_objects(&g->res[ri], &old->res[rj]);
            g->res[ri].carried = 1;
        }
    }
}

/* A pass whose plugin was rebuilt hands its state from the old instance to
 * the new one, where both versions offer it. */
static void carry_state(vrg_graph *old, vrg_graph *g)
{
    static unsigned char state[1 << 16];
    for (int i = 0; i < g->pass_count; i++) {
        vrg_pass *q = &g->passes[i];
        for (int k = 0; k < old->pass_count; k++) {
            vrg_pass *p = &old->passes[k];
            if (strcmp(p->name, q->name) != 0 || strcmp(p->plugin->name, q->plugin->name) != 0 || !p->created || !q->created)
                continue;
            if (p->plugin->desc->save_state && q->plugin->desc->restore_state) {
                _vrg_running before = _vrg_running_enter("save_state", p->name, p->plugin);
                size_t n = p->plugin->desc->save_state(p, state, sizeof state);
                _vrg_running_enter("restore_state", q->name, q->plugin);
                int rc = n <= sizeof state ? q->plugin->desc->restore_state(q, state, n) : 0;
                _vrg_running_leave(before);
                if (n > sizeof state)
                    _vrg_pass_fail(q, VRG_E_CALLBACK_FAILED, "save_state() returned %zu bytes, more than the %zu it may write: the pass starts afresh", n, sizeof state);
                else if (rc != 0)
                    _vrg_pass_fail(q, VRG_E_CALLBACK_FAILED, "restore_state() failed: the pass starts afresh");
            }
        }
    }
}

/* Every rebuilt plugin file (passes marked by apply_reloads), once each.
 * Returns -1 with reload_error set at the first that fails. */
static int reload_plugins(vrg_graph *old)
{
    int rc = 0;
    for (int i = 0; i < old->pass_count && rc == 0 && old->plugins_rebuilt; i++) {
        const vrg_pass *p = &old->passes[i];
        int done = 0;
        for (int j = 0; j < i; j++)
            done |= old->passes[j].plugin_rebuilt && strcmp(old->passes[j].plugin->source, p->plugin->source) == 0;
        if (!p->plugin_rebuilt || done)
            continue;
        char *text = NULL;
        size_t len = 0;
        FILE *mem = open_memstream(&text, &len);
        _vrg_diag pd = {.out = mem ? mem : old->desc.diag, .file = old->path};
        rc = _vrg_plugin_reload(p->plugin->source, &pd);
        if (mem) {
            fclose(mem);
            fputs(text ? text : "", old->desc.diag ? old->desc.diag : stderr);
        }
        if (rc != 0)
            snprintf(old->reload_error, sizeof old->reload_error, "%s", text ? text : "plugin reload failed");
        free(text);
    }
    for (int i = 0; i < old->pass_count; i++)
        old->passes[i].plugin_rebuilt = 0;
    old->plugins_rebuilt = 0;
    return rc;
}

int vrg_graph_reload(vrg_graph **pg)
{
    vrg_graph *old = *pg;
    if (!old->ctx || !old->loaded_from_file) {
        _vrg_error(&old->diag, VRG_E_NO_DEVICE, "reload: the graph was not loaded from a file with a device");
        return -1;
    }
    if (old->ctx->gpu_busy) {
        _vrg_error(&old->diag, VRG_E_GPU_BUSY, "reload: the GPU is still busy with a frame that timed out or was interrupted");
        return -1;
    }
    double saved_at = old->source_saved_at; /* this reload takes these saves, done or refused */
    old->source_saved_at = 0;
    /* rebuilt plugins first: the new graph picks up their newest versions */
    if (reload_plugins(old) != 0) {
        old->source_changed = 0;
        return -1;
    }
    vrg_graph_desc d = old->desc;
    d.text = NULL;
    d.path = old->path;
    d.width = old->width, d.height = old->height; /* a resized graph keeps its size */
    /* the messages of a failed load are kept for the host (overlay) too */
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    FILE *real = old->desc.diag ? old->desc.diag : stderr;
    d.diag = mem ? mem : real;
    vrg_graph *g = NULL;
    int rc = _vrg_graph_load_replacing(old->ctx, &d, old, &g);
    if (mem) {
        fclose(mem);
        fputs(text ? text : "", real);
    }
    if (rc != 0) {
        snprintf(old->reload_error, sizeof old->reload_error, "%s", text ? text : "reload failed");
        old->source_changed = 0;
        free(text);
        return -1;
    }
    free(text);
    g->desc.diag = old->desc.diag;
    g->diag.out = old->desc.diag;
    /* the old graph's frames in flight end before its passes hand their
     * state over (save_state may read what they write) and before its
     * resources are copied and freed (a GPU timeout here is reported like
     * a frame's) */
    if (_vrg_wait_frames(old) != 0) {
        vrg_graph_destroy(g);
        return -1;
    }
    carry_state(old, g);
    /* pipelines depend on the shader, its defines and descriptor types only:
     * a pass running the same plugin keeps its compiled ones (no new JIT) */
    for (int i = 0; i < g->pass_count; i++)
        for (int k = 0; k < old->pass_count; k++)
            if (strcmp(old->passes[k].name, g->passes[i].name) == 0 && old->passes[k].plugin == g->passes[i].plugin &&
                !g->passes[i].pipelines) {
                g->passes[i].pipelines = old->passes[k].pipelines;
                old->passes[k].pipelines = NULL;
            }
    g->frame.frame_index = old->frame.frame_index; /* random sequences and history copies continue */
    g->camera = old->camera;
    g->last_camera = old->last_camera;
    if (copy_history(old, g) != 0) {
        vrg_graph_destroy(g);
        return -1;
    }
    keep_resources(old, g); /* nothing fails from here on */
    g->predecessor = NULL; /* the reload is done: old goes below */
    if (same_structure(old, g)) /* every history resource carried over */
        g->history_reset = 0;
    else
        g->history_carried = 1; /* a reset, but the matching ones survive it */
    g->params_changed = 1;      /* the graph changed under accumulations either way */
    struct stat st;
    if (saved_at > 0) /* the files whose saves the watch saw: the graph, rebuilt plugins */
        g->pending_since = saved_at;
    else if (stat(old->path, &st) == 0) /* a reload the host asked for unprompted */
        g->pending_since = (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
    if (old->watch)
        vrg_graph_watch(g, 1);
    vrg_graph_destroy(old);
    *pg = g;
    return 0;
}

int vrg_graph_source_changed(const vrg_graph *g) { return g->source_changed; }
