/* The graph's life: load runs the phases in order (parse → validate →
 * compile → create → allocate), then makes the device objects of each
 * frame slot and the readback buffer; resize and destroy undo and redo
 * what they need. Each phase is its own file; the graph's other faces
 * (frames, hot reload, readback, parameters, queries) are graph_*.c. */
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "phases.h"
#include "parse.h"
#include "plugin_loader.h"
#include "watch.h"

static int create_passes(vrg_graph *g)
{
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        _vrg_running before = _vrg_running_enter("create", p->name, p->plugin);
        int rc = p->plugin->desc->create ? p->plugin->desc->create(p) : 0;
        _vrg_running_leave(before);
        if (rc != 0) {
            if (!p->failed)
                _vrg_pass_fail(p, VRG_E_CALLBACK_FAILED, "create() failed");
            return -1;
        }
        if (p->failed)
            return -1;
        p->created = 1;
    }
    return 0;
}

static int resize_passes(vrg_graph *g)
{
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        _vrg_running before = _vrg_running_enter("resize", p->name, p->plugin);
        int rc = p->plugin->desc->resize ? p->plugin->desc->resize(p) : 0;
        _vrg_running_leave(before);
        if (rc != 0) {
            if (!p->failed)
                _vrg_pass_fail(p, VRG_E_CALLBACK_FAILED, "resize() failed");
            return -1;
        }
    }
    return 0;
}

static int frame_objects(vrg_graph *g)
{
    vrg_context *ctx = g->ctx;
    VkDevice dev = ctx->dev.device;
    for (uint32_t i = 0; i < g->frames_in_flight; i++) {
        struct _vrg_frame_slot *s = &g->slots[i];
        VkCommandBufferAllocateInfo ai = {
            .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = ctx->cmd_pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
        VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        if (vkAllocateCommandBuffers(dev, &ai, &s->cmd) != VK_SUCCESS || vkCreateFence(dev, &fi, NULL, &s->fence) != VK_SUCCESS) {
            _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "cannot create the command buffer and fence of frame slot %u", i);
            return -1;
        }
        if (ctx->dev.features.timestamps && g->schedule_count) {
            VkQueryPoolCreateInfo qi = {
                .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = (uint32_t)(2 * g->schedule_count)};
            if (vkCreateQueryPool(dev, &qi, NULL, &s->queries) != VK_SUCCESS)
                s->queries = VK_NULL_HANDLE; /* timings become -1; rendering goes on */
            _vrg_name_object(ctx, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)s->queries, "%s/pass timestamps[%u]", g->name, i);
        }
        _vrg_name_object(ctx, VK_OBJECT_TYPE_COMMAND_BUFFER, (uint64_t)s->cmd, "%s/frame[%u]", g->name, i);
    }
    return 0;
}

static void free_frame_objects(vrg_graph *g)
{
    VkDevice dev = g->ctx->dev.device;
    for (uint32_t i = 0; i < g->frames_in_flight; i++) {
        struct _vrg_frame_slot *s = &g->slots[i];
        if (s->cmd)
            vkFreeCommandBuffers(dev, g->ctx->cmd_pool, 1, &s->cmd);
        vkDestroyFence(dev, s->fence, NULL);
        vkDestroyQueryPool(dev, s->queries, NULL);
    }
}

static VkDeviceSize align256(VkDeviceSize v) { return (v + 255) / 256 * 256; }

/* A part per frame slot: the read-back resources, then a word per scheduled
 * pass the GPU sets when the pass is done (the host reads which one runs
 * while a frame is late, record.c), then the frame's timestamps. After the
 * slots, the texels vrg_graph_read_pixels copies. */
static int readback_buffer(vrg_graph *g)
{
    VkDevice dev = g->ctx->dev.device;
    VkDeviceSize size = 0;
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->first_use < 0 || !(r->is_output || r->readback))
            continue;
        g->readback_offset[i] = size;
        VkDeviceSize bytes = r->kind == VRG_IMAGE ? (VkDeviceSize)r->width * r->height * _vrg_format_bytes(r->format) : r->size;
        size += (bytes + 15) / 16 * 16;
    }
    g->progress_offset = size;
    size += 4 * VRG_MAX_PASSES;
    if (g->check_finite) {
        VkDeviceSize align = g->ctx->props.limits.minStorageBufferOffsetAlignment;
        g->finite_stride = align > 4 ? align : 4; /* a word per check, each bound alone */
        g->finite_offset = align256(size);
        int checks = _vrg_finite_plan(g);
        if (checks < 0)
            return -1;
        size = g->finite_offset + (VkDeviceSize)checks * g->finite_stride;
    }
    g->timestamp_offset = size;
    size += 2 * sizeof(uint64_t) * VRG_MAX_PASSES;
    g->readback_slot_bytes = align256(size);
    for (uint32_t i = 0; i < g->frames_in_flight; i++)
        g->slots[i].readback_base = i * g->readback_slot_bytes;
    size = g->frames_in_flight * g->readback_slot_bytes;
    /* one texel of each image's two copies for vrg_graph_read_pixels */
    g->pixel_offset = size;
    size += 2 * VRG_MAX_RESOURCES * VRG_PIXEL_BYTES;
    VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT | (g->check_finite ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : 0)};
    VkMemoryRequirements req = {0};
    int type = -1;
    if (vkCreateBuffer(dev, &ci, NULL, &g->readback_buffer) == VK_SUCCESS) {
        vkGetBufferMemoryRequirements(dev, g->readback_buffer, &req);
        type = _vrg_find_memory_type(g->ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    }
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(dev, &ai, NULL, &g->readback_memory) != VK_SUCCESS ||
        vkBindBufferMemory(dev, g->readback_buffer, g->readback_memory, 0) != VK_SUCCESS ||
        vkMapMemory(dev, g->readback_memory, 0, VK_WHOLE_SIZE, 0, &g->readback_map) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "cannot allocate %llu bytes of host-visible memory for readback", (unsigned long long)size);
        return -1;
    }
    g->readback_size = size;
    _vrg_name_object(g->ctx, VK_OBJECT_TYPE_BUFFER, (uint64_t)g->readback_buffer, "%s/readback", g->name);
    return 0;
}

static void free_readback(vrg_graph *g)
{
    if (!g->ctx)
        return;
    VkDevice dev = g->ctx->dev.device;
    if (g->readback_map)
        vkUnmapMemory(dev, g->readback_memory);
    vkDestroyBuffer(dev, g->readback_buffer, NULL);
    vkFreeMemory(dev, g->readback_memory, NULL);
    g->readback_buffer = VK_NULL_HANDLE;
    g->readback_memory = VK_NULL_HANDLE;
    g->readback_map = NULL;
    g->last_slot = -1; /* nothing to read until the next frame */
}

int vrg_graph_load(vrg_context *ctx, const vrg_graph_desc *desc, vrg_graph **out) { return _vrg_graph_load_replacing(ctx, desc, NULL, out); }

int _vrg_graph_load_replacing(vrg_context *ctx, const vrg_graph_desc *desc, vrg_graph *predecessor, vrg_graph **out)
{
    *out = NULL;
    vrg_graph *g = calloc(1, sizeof *g);
    _vrg_ast *ast = calloc(1, sizeof *ast);
    g->ctx = ctx;
    g->predecessor = predecessor;
    snprintf(g->path, sizeof g->path, "%s", desc->path ? desc->path : "<graph>");
    g->desc = *desc;
    g->shown = -1;
    g->loaded_from_file = desc->path && !desc->text;
    g->diag = (_vrg_diag){.out = desc->diag, .file = g->path, .collect = 1};
    for (int i = 0; i < VRG_MAX_PASSES; i++)
        g->pass_ms[i] = -1;
    g->timed_frame = -1;
    g->last_slot = -1;
    g->frames_in_flight = VRG_FRAMES_IN_FLIGHT_DEFAULT;
    g->output = -1;
    vrg_camera_default(&g->camera);
    snprintf(g->name, sizeof g->name, "graph");
    int rc;
    if (desc->path && strlen(desc->path) >= sizeof g->path) {
        _vrg_error(&g->diag, VRG_E_GRAPH_PATH_TOO_LONG, "graph path is longer than %zu characters", sizeof g->path - 1);
        rc = -1;
        ast->fatal = 1;
    } else
        rc = _vrg_parse(g->path, desc->text, ast, &g->diag);
    /* Keep going after syntax errors so one run shows every problem. */
    if (!ast->fatal && (rc == 0 || ast->section_count > 0))
        rc = _vrg_validate(g, ast, desc) | rc;
    free(ast);
    /* the inputs of a pass that wrote NaN are read when its frame ended:
     * every image kept to the end, no later frame begun */
    g->check_finite = desc->check_finite ? 2 : ctx && ctx->validate ? 1 : 0;
    if (desc->check_finite) {
        g->desc.keep_images = 1;
        g->frames_in_flight = 1;
    }
    if (rc == 0)
        rc = _vrg_compile(g);
    if (rc == 0 && ctx) {
        rc = create_passes(g);
        if (rc == 0)
            rc = _vrg_compile(g); /* internal resources now exist: lifetimes again */
    }
    if (rc == 0)
        rc = _vrg_allocate(g);
    if (rc == 0 && ctx && g->check_finite)
        rc = _vrg_finite_create(g);
    if (rc == 0 && ctx) {
        rc = frame_objects(g);
        if (rc == 0)
            rc = readback_buffer(g);
        if (rc == 0)
            rc = resize_passes(g);
    }
    _vrg_diag_flush(&g->diag);
    if (rc != 0) {
        vrg_graph_destroy(g);
        return -1;
    }
    *out = g;
    return 0;
}

void vrg_graph_destroy(vrg_graph *g)
{
    if (!g)
        return;
    /* the GPU may still be running this graph's work and never stop:
     * nothing it uses can be freed (vrg_context_gpu_busy) */
    if (g->ctx && g->ctx->gpu_busy)
        return;
    /* this graph's frames in flight first, with the GPU timeout: a stuck
     * frame is reported and its objects left, as above, instead of waiting
     * for it forever */
    if (g->ctx && _vrg_wait_frames(g) != 0)
        return;
    _vrg_watch_destroy(g->watch);
    if (g->ctx) {
        VkDevice dev = g->ctx->dev.device;
        vkDeviceWaitIdle(dev); /* what hosts recorded with the graph's images (a window's blit) */
        for (int i = 0; i < g->pass_count; i++) {
            vrg_pass *p = &g->passes[i];
            if (p->created && p->plugin->desc->destroy) {
                _vrg_running before = _vrg_running_enter("destroy", p->name, p->plugin);
                p->plugin->desc->destroy(p);
                _vrg_running_leave(before);
            }
            _vrg_pipelines_destroy(p);
            _vrg_pass_free_host_buffers(p);
        }
        _vrg_free_retired(g, 1); /* also what destroy callbacks freed just now */
        free_readback(g);
        _vrg_finite_destroy(g);
        _vrg_free_resources(g);
        free_frame_objects(g);
    }
    for (int i = 0; i < g->pass_count; i++) {
        _vrg_pass_free_params(&g->passes[i]);
        _vrg_name_plans_free(&g->passes[i]);
        _vrg_pass_free_shared(&g->passes[i]);
        _vrg_pass_clear_stats(&g->passes[i], 1);
        if (g->passes[i].plugin)
            _vrg_plugin_release(g->passes[i].plugin); /* last: nothing of the plugin's is used after */
    }
    free(g->overlaps);
    free(g);
}

int vrg_graph_resize(vrg_graph *g, uint32_t width, uint32_t height)
{
    if (!width || !height || width > 16384 || height > 16384) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "resize to %ux%u: sizes are 1..16384", width, height);
        return -1;
    }
    if (g->ctx && g->ctx->gpu_busy) {
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "resize: the GPU is still busy with a frame that timed out or was interrupted");
        return -1;
    }
    /* the frames in flight use the resources: they end first (or time out) */
    if (g->ctx && _vrg_wait_frames(g) != 0)
        return -1;
    free_readback(g);
    _vrg_free_resources(g);
    g->width = width;
    g->height = height;
    if (_vrg_allocate(g) != 0)
        return -1;
    if (g->ctx && (readback_buffer(g) != 0 || resize_passes(g) != 0)) {
        g->allocated = 0; /* half resized (no readback buffer, or a pass refused): no frame until a resize succeeds */
        return -1;
    }
    return 0;
}
