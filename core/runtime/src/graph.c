/* The graph's life: load (parse → validate → compile → create → allocate),
 * frames, resize, readback, destroy. Each phase is its own file. */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <sys/stat.h>
#include <time.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

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
 * while a frame is late, record.c), then the frame's timestamps. */
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
    g->timestamp_offset = size;
    size += 2 * sizeof(uint64_t) * VRG_MAX_PASSES;
    g->readback_slot_bytes = align256(size);
    for (uint32_t i = 0; i < g->frames_in_flight; i++)
        g->slots[i].readback_base = i * g->readback_slot_bytes;
    size = g->frames_in_flight * g->readback_slot_bytes;
    VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
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
    if (rc == 0)
        rc = _vrg_compile(g);
    if (rc == 0 && ctx) {
        rc = create_passes(g);
        if (rc == 0)
            rc = _vrg_compile(g); /* internal resources now exist: lifetimes again */
    }
    if (rc == 0)
        rc = _vrg_allocate(g);
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
        _vrg_free_resources(g);
        free_frame_objects(g);
    }
    for (int i = 0; i < g->pass_count; i++) {
        _vrg_pass_free_params(&g->passes[i]);
        _vrg_pass_free_shared(&g->passes[i]);
        _vrg_pass_clear_stats(&g->passes[i], 1);
        if (g->passes[i].plugin)
            _vrg_plugin_release(g->passes[i].plugin); /* last: nothing of the plugin's is used after */
    }
    free(g->overlaps);
    free(g);
}

/* ---- hot reload ---- */

static void watch_path(void *user, const char *path) { _vrg_watch_add(user, path); }

void _vrg_graph_watch_pipeline(vrg_graph *g, const char *deps)
{
    if (!g->watch)
        return;
    for (const char *d = deps; d && *d;) {
        const char *end = strchr(d, '\n');
        char path[VRG_PATH_MAX];
        snprintf(path, sizeof path, "%.*s", (int)(end ? end - d : (long)strlen(d)), d);
        _vrg_watch_add(g->watch, path);
        d = end ? end + 1 : d + strlen(d);
    }
}

int vrg_graph_watch(vrg_graph *g, int on)
{
    if (!on) {
        _vrg_watch_destroy(g->watch);
        g->watch = NULL;
        return 0;
    }
    if (g->watch)
        return 0;
    g->watch = _vrg_watch_create();
    if (!g->watch) {
        _vrg_error(&g->diag, VRG_E_WATCH_FAILED, "hot reload: cannot watch files (inotify: %s)", strerror(errno));
        return -1;
    }
    g->reload_ms = -1;
    if (g->loaded_from_file)
        _vrg_watch_add(g->watch, g->path);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_watch_add(g->watch, g->passes[i].plugin->source);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_pipelines_deps(&g->passes[i], watch_path, g->watch);
    return 0;
}

/* ---- the files a graph is built from ---- */

void vrg_graph_sources(const vrg_graph *g, void (*fn)(void *user, const char *path), void *user)
{
    if (g->loaded_from_file)
        fn(user, g->path);
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].plugin)
            fn(user, g->passes[i].plugin->source);
    for (int i = 0; i < g->pass_count; i++)
        _vrg_pipelines_deps((vrg_pass *)&g->passes[i], fn, user);
}

/* The graph file or a plugin was saved: the host is to reload. The newest
 * of their mtimes starts the save-to-frame time of that reload (a plugin
 * rebuilt long after the graph was saved is timed from its own build). */
static void note_source_saved(vrg_graph *g, const char *path)
{
    struct stat st;
    g->source_changed = 1;
    if (stat(path, &st) == 0) {
        double t = (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
        g->source_saved_at = t > g->source_saved_at ? t : g->source_saved_at;
    }
}

/* Saved shaders: recompile the pipelines that read them before this frame
 * records. Failures keep the old pipeline; their messages (FILE:LINE) go to
 * the diagnostics as usual and are kept for vrg_graph_reload_error. */
static void apply_reloads(vrg_graph *g)
{
    char (*changed)[VRG_PATH_MAX], self[VRG_PATH_MAX];
    int n = _vrg_watch_poll(g->watch, &changed);
    if (n < 0)
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "hot reload: out of memory listing the changed files");
    if (n <= 0)
        return;
    /* the graph file itself: the host reloads it (vrg_graph_reload) */
    if (g->loaded_from_file && realpath(g->path, self))
        for (int i = 0; i < n; i++)
            if (strcmp(changed[i], self) == 0)
                note_source_saved(g, changed[i]);
    /* a rebuilt plugin: also the host's to reload (a new graph instance) */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < g->pass_count; k++) {
            if (strcmp(changed[i], g->passes[k].plugin->source) != 0)
                continue;
            g->passes[k].plugin_rebuilt = 1;
            g->plugins_rebuilt = 1;
            note_source_saved(g, changed[i]);
        }
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    FILE *real = g->diag.out;
    if (mem)
        g->diag.out = mem;
    int failed = 0, swapped = 0;
    for (int i = 0; i < g->pass_count; i++) {
        int r = _vrg_pipelines_reload(&g->passes[i], changed, n);
        failed |= r < 0;
        swapped += r > 0 ? r : 0;
    }
    if (mem) {
        g->diag.out = real;
        fclose(mem);
        fputs(text ? text : "", real ? real : stderr);
        snprintf(g->reload_error, sizeof g->reload_error, "%s", failed && text ? text : "");
        free(text);
    }
    if (swapped) { /* the newest save among the files: the start of the save-to-frame time */
        double newest = 0;
        for (int i = 0; i < n; i++) {
            struct stat st;
            if (stat(changed[i], &st) == 0) {
                double t = (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
                newest = t > newest ? t : newest;
            }
        }
        g->pending_since = newest;
    }
    free(changed);
}

int vrg_graph_poll_changes(vrg_graph *g)
{
    if (g->watch)
        apply_reloads(g);
    return g->source_changed;
}

int vrg_graph_frame(vrg_graph *g)
{
    if (!g->ctx || !g->allocated) {
        _vrg_error(&g->diag, VRG_E_NO_DEVICE, "graph '%s' has no device resources (loaded without a context, or its last resize failed)", g->name);
        return -1;
    }
    if (g->ctx->gpu_busy) { /* the command buffer may still be executing */
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "graph '%s': the GPU is still busy with a frame that timed out or was interrupted", g->name);
        return -1;
    }
    (void)vrg_graph_poll_changes(g); /* saved shaders swap in before recording */
    int rc = _vrg_record_frame(g);
    /* this frame used the change: the save-to-frame time ends when it has
     * ended on the GPU (the wait drains the frames in flight, once) */
    if (rc == 0 && g->pending_since > 0)
        rc = vrg_graph_wait(g);
    if (g->pending_since > 0) {
        struct timespec now;
        clock_gettime(CLOCK_REALTIME, &now);
        g->reload_ms = ((double)now.tv_sec + 1e-9 * (double)now.tv_nsec - g->pending_since) * 1e3;
        g->pending_since = 0;
    }
    return rc;
}

/* "pass.param": the pass and the parameter's index, or -1 after an error */
static int find_param(vrg_graph *g, const char *pass_param, vrg_pass **out)
{
    const char *dot = strchr(pass_param, '.');
    vrg_pass *p = NULL;
    for (int i = 0; dot && i < g->pass_count && !p; i++)
        if (strlen(g->passes[i].name) == (size_t)(dot - pass_param) && strncmp(g->passes[i].name, pass_param, (size_t)(dot - pass_param)) == 0)
            p = &g->passes[i];
    if (!p) {
        _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "%s: no pass of that name (PASS.PARAM)", pass_param);
        return -1;
    }
    *out = p;
    const vrg_plugin_desc *d = p->plugin->desc;
    for (uint32_t i = 0; i < d->param_count; i++)
        if (strcmp(d->params[i].name, dot + 1) == 0)
            return (int)i;
    _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "%s: pass '%s' (plugin %s) has no parameter '%s'", pass_param, p->name, p->plugin->name, dot + 1);
    return -1;
}

int vrg_graph_get_param(vrg_graph *g, const char *pass_param, double *value)
{
    vrg_pass *p;
    int i = find_param(g, pass_param, &p);
    if (i < 0)
        return -1;
    *value = p->params[i];
    return 0;
}

int vrg_graph_set_param(vrg_graph *g, const char *pass_param, double value)
{
    vrg_pass *p;
    int i = find_param(g, pass_param, &p);
    if (i >= 0) {
        const vrg_param_desc *pd = &p->plugin->desc->params[i];
        if (pd->type == VRG_PARAM_STRING || (pd->flags & VRG_PARAM_RELOAD)) {
            _vrg_error(&g->diag, VRG_E_PARAM_NOT_SETTABLE, "set %s: %s; edit the graph file (it reloads)", pass_param,
                       pd->type == VRG_PARAM_STRING ? "a string parameter" : "read only when the pass is created");
            return -1;
        }
        if (value != value || (pd->type != VRG_PARAM_FLOAT && value != floor(value)) || ((pd->min != 0 || pd->max != 0) && (value < pd->min || value > pd->max))) {
            _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "set %s = %g: %s takes %s in [%g, %g]", pass_param, value, pd->name, pd->type == VRG_PARAM_FLOAT ? "a number" : "an integer",
                      pd->min, pd->max);
            return -1;
        }
        if (p->params[i] != value) {
            p->params[i] = value;
            g->params_changed = 1; /* accumulations restart; history stays */
        }
        return 0;
    }
    return -1;
}

const char *vrg_graph_reload_error(const vrg_graph *g) { return g->reload_error[0] ? g->reload_error : NULL; }
double vrg_graph_reload_ms(const vrg_graph *g) { return g->watch ? g->reload_ms : -1; }

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

void vrg_graph_reset_history(vrg_graph *g) { g->history_reset = 1; }

void vrg_graph_set_frame_index(vrg_graph *g, uint64_t index)
{
    g->frame.frame_index = index;
    g->history_reset = 1; /* the @prev copy is picked by the index's parity */
}

static int find_readable(vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0) {
            if (!(g->res[i].is_output || g->res[i].readback || i == g->shown) || g->res[i].first_use < 0) {
                _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "resource '%s' is not read back (ask for it in vrg_graph_desc.readback)", name);
                return -1;
            }
            if (g->last_slot < 0) {
                _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "resource '%s': no frame rendered yet", name);
                return -1;
            }
            /* what is read is the last submitted frame's: it must end first */
            return _vrg_wait_frames(g) == 0 ? i : -1;
        }
    _vrg_error(&g->diag, VRG_E_UNKNOWN_RESOURCE, "the graph has no resource '%s'", name);
    return -1;
}

/* The last submitted frame's part of the readback buffer. */
static const uint8_t *last_readback(const vrg_graph *g) { return (const uint8_t *)g->readback_map + g->slots[g->last_slot].readback_base; }

int vrg_graph_wait(vrg_graph *g)
{
    if (g->ctx && g->ctx->gpu_busy) {
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "graph '%s': the GPU is still busy with a frame that timed out or was interrupted", g->name);
        return -1;
    }
    return g->ctx ? _vrg_wait_frames(g) : 0;
}

int64_t vrg_graph_timed_frame(const vrg_graph *g) { return g->timed_frame; }
uint32_t vrg_graph_frames_in_flight(const vrg_graph *g) { return g->frames_in_flight; }

static float half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h >> 15) << 31, exp = (h >> 10) & 0x1f, mant = h & 0x3ff, bits;
    if (exp == 0) {
        if (mant == 0)
            bits = sign;
        else { /* subnormal */
            exp = 127 - 14;
            while (!(mant & 0x400)) {
                mant <<= 1;
                exp--;
            }
            bits = sign | (exp << 23) | ((mant & 0x3ff) << 13);
        }
    } else if (exp == 31)
        bits = sign | 0x7f800000u | (mant << 13);
    else
        bits = sign | ((exp + 127 - 15) << 23) | (mant << 13);
    float f;
    memcpy(&f, &bits, 4);
    return f;
}

static float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f); }

static int showable(const vrg_graph *g, int i)
{
    const _vrg_resource *r = &g->res[i];
    return r->kind == VRG_IMAGE && r->first_use >= 0 && r->writer >= 0 && r->internal_owner < 0 && !r->dummy;
}

uint32_t vrg_graph_image_count(const vrg_graph *g)
{
    uint32_t n = 0;
    for (int i = 0; g->desc.keep_images && i < g->res_count; i++)
        n += showable(g, i);
    return n;
}

const char *vrg_graph_image_name(const vrg_graph *g, uint32_t k)
{
    for (int i = 0; g->desc.keep_images && i < g->res_count; i++)
        if (showable(g, i) && k-- == 0)
            return g->res[i].name;
    return NULL;
}

int vrg_graph_show(vrg_graph *g, const char *name)
{
    g->shown = -1;
    if (!name)
        return 0;
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0 && g->desc.keep_images && showable(g, i)) {
            g->shown = i;
            return 0;
        }
    _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "show %s: not an image this graph keeps for viewing (load it with keep_images)", name);
    return -1;
}

VkImageView vrg_graph_image_view(vrg_graph *g, const char *name)
{
    int i = find_readable(g, name);
    return i < 0 || g->res[i].kind != VRG_IMAGE ? VK_NULL_HANDLE : g->res[i].view[_vrg_copy_of(g, i, g->res[i].history)];
}

int vrg_graph_image(vrg_graph *g, const char *name, VkImage *image, VkExtent2D *extent, VkFormat *format)
{
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_IMAGE) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is not an image", name);
        return -1;
    }
    /* the frame counter moved on: last frame's copy is now the "previous" one */
    *image = r->image[_vrg_copy_of(g, i, r->history)];
    *extent = (VkExtent2D){r->width, r->height};
    *format = r->format;
    return 0;
}

int vrg_graph_read(vrg_graph *g, const char *name, vrg_image_data *out)
{
    memset(out, 0, sizeof *out);
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_IMAGE) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is a buffer: use vrg_graph_read_buffer", name);
        return -1;
    }
    const uint8_t *src = last_readback(g) + g->readback_offset[i];
    uint32_t ch = _vrg_format_channels(r->format);
    size_t n = (size_t)r->width * r->height;
    out->width = r->width;
    out->height = r->height;
    out->channels = ch;
    out->format = r->format;
    out->pixels = calloc(n * 4, sizeof(float));
    for (size_t p = 0; p < n; p++) {
        float v[4] = {0, 0, 0, 1};
        for (uint32_t c = 0; c < ch; c++) {
            switch (r->format) {
            case VK_FORMAT_R8_UNORM:
            case VK_FORMAT_R8G8_UNORM:
            case VK_FORMAT_R8G8B8A8_UNORM: v[c] = src[p * ch + c] / 255.0f; break;
            case VK_FORMAT_R8G8B8A8_SRGB: v[c] = c < 3 ? srgb_to_linear(src[p * 4 + c] / 255.0f) : src[p * 4 + c] / 255.0f; break;
            case VK_FORMAT_R16_SFLOAT:
            case VK_FORMAT_R16G16_SFLOAT:
            case VK_FORMAT_R16G16B16A16_SFLOAT: {
                uint16_t h;
                memcpy(&h, src + (p * ch + c) * 2, 2);
                v[c] = half_to_float(h);
                break;
            }
            case VK_FORMAT_R32_UINT:
            case VK_FORMAT_R32G32_UINT:
            case VK_FORMAT_R32G32B32A32_UINT: {
                uint32_t u;
                memcpy(&u, src + (p * ch + c) * 4, 4);
                v[c] = (float)u;
                break;
            }
            case VK_FORMAT_B10G11R11_UFLOAT_PACK32: {
                uint32_t u;
                memcpy(&u, src + p * 4, 4);
                /* 11/11/10-bit floats share half's exponent: widen them to halves */
                uint32_t bits[3] = {(u & 0x7ff) << 4, ((u >> 11) & 0x7ff) << 4, ((u >> 22) & 0x3ff) << 5};
                v[c] = half_to_float((uint16_t)bits[c]);
                break;
            }
            default: memcpy(&v[c], src + (p * ch + c) * 4, 4); break;
            }
        }
        memcpy(out->pixels + p * 4, v, sizeof v);
    }
    return 0;
}

int vrg_graph_resource_kind(const vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0)
            return (int)g->res[i].kind;
    return -1;
}

int vrg_graph_read_buffer(vrg_graph *g, const char *name, void **data, uint64_t *size)
{
    *data = NULL;
    *size = 0;
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_BUFFER) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is an image: use vrg_graph_read", name);
        return -1;
    }
    *data = malloc(r->size);
    memcpy(*data, last_readback(g) + g->readback_offset[i], r->size);
    *size = r->size;
    return 0;
}

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

int vrg_graph_set_camera(vrg_graph *g, const vrg_camera *c)
{
    if (!vrg_camera_position_in_world(c->position)) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "vrg_graph_set_camera: camera->position (%g, %g, %g) is outside the world: each coordinate lies in [%g, %g] (VRG_WORLD_LIMIT)",
                  c->position[0], c->position[1], c->position[2], -VRG_WORLD_LIMIT, VRG_WORLD_LIMIT);
        return -1;
    }
    g->camera = *c;
    return 0;
}
const vrg_camera *vrg_graph_camera(const vrg_graph *g) { return &g->camera; }
double vrg_graph_frame_seconds(const vrg_graph *g) { return 1.0 / g->fps; }

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
