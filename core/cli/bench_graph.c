/* voxrg bench --suite graph: what the runtime costs on the CPU per frame of
 * the thesis graph, against a baseline that records the same barriers and
 * dispatches directly with Vulkan; and how long the graph takes to compile.
 *
 * Runtime: vrg_graph_cpu_ms, from the start of recording to the return of
 * vkQueueSubmit2: the barrier tracking, each pass's execute (pipeline and
 * resource lookups, descriptors, push constants), the scene's per-frame
 * uniform upload, timestamps and the output's readback copy. Baseline: two
 * consecutive frames are captured (vrg_graph_capture_frame); then, in the
 * same run, a fresh command buffer is recorded from a capture (its barrier
 * batches, pipeline binds, push descriptors, push constants and dispatches:
 * a loop of vkCmd calls over plain arrays) and submitted, alternating the
 * two captures so each finds the resources as its frame did. Both are timed
 * from the command buffer's reset to the return of vkQueueSubmit2, neither waits
 * for the GPU inside the timing. The camera is still: no terrain streams. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "util.h"

static int baseline(vrg_context *ctx, vrg_capture *const cap[2], int runs, double *ms)
{
    const vrg_device *dev = vrg_context_device(ctx);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, .queueFamilyIndex = dev->queue_family};
    VkCommandPool pool;
    if (vkCreateCommandPool(dev->device, &pi, NULL, &pool) != VK_SUCCESS)
        return -1;
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer cmd;
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vkAllocateCommandBuffers(dev->device, &ai, &cmd);
    vkCreateFence(dev->device, &fi, NULL, &fence);
    int rc = 0;
    for (int r = -2; r < runs && rc == 0; r++) { /* two warm-up replays */
        double t0 = vrg_cli_now_ms();
        vkResetCommandBuffer(cmd, 0); /* the runtime's timing includes its reset too */
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        vkBeginCommandBuffer(cmd, &bi);
        vrg_capture_record(cap[(r + 2) % 2], cmd); /* first the earlier frame: the graph last ran the later one's parity */
        vkEndCommandBuffer(cmd);
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
        vkResetFences(dev->device, 1, &fence);
        rc = vkQueueSubmit2(dev->queue, 1, &si, fence) == VK_SUCCESS ? 0 : -1;
        if (r >= 0)
            ms[r] = vrg_cli_now_ms() - t0;
        if (rc == 0 && vkWaitForFences(dev->device, 1, &fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS)
            rc = -1;
    }
    vkDestroyFence(dev->device, fence, NULL);
    vkDestroyCommandPool(dev->device, pool, NULL);
    return rc;
}

int vrg_bench_graph(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    int runs = o->smoke ? 2 : (o->runs < 20 ? 20 : o->runs), n = *count, rc = 0;
    if (vrg_bench_room(n, 8))
        return -1;
    char path[1100];
    snprintf(path, sizeof path, "%s/graphs/thesis.ini", vrg_data_dir());
    /* compile: parse, validate, schedule, lifetimes and the aliasing plan (no device) */
    double compile[64];
    int compiles = o->smoke ? 1 : (o->runs < 64 ? o->runs : 64);
    for (int r = -1; r < compiles && rc == 0; r++) {
        vrg_graph_desc d = {.path = path, .width = o->width, .height = o->height};
        vrg_graph *g = NULL;
        double t0 = vrg_cli_now_ms();
        rc = vrg_graph_load(NULL, &d, &g);
        if (r >= 0)
            compile[r] = vrg_cli_now_ms() - t0;
        vrg_graph_destroy(g);
    }
    vrg_graph *g = rc == 0 ? vrg_bench_load_shipped(ctx, "thesis.ini", o->width, o->height, o->smoke) : NULL;
    if (!g)
        return -1;
    double *runtime = calloc((size_t)runs, sizeof *runtime), *base = calloc((size_t)runs, sizeof *base);
    double *scene = calloc((size_t)runs, sizeof *scene), *rest = calloc((size_t)runs, sizeof *rest);
    vrg_capture *cap[2] = {NULL, NULL};
    for (int w = 0; w < 3 && rc == 0; w++) /* the JIT, the world's upload */
        rc = vrg_graph_frame(g);
    if (rc == 0 && (!(cap[0] = vrg_graph_capture_frame(g)) || !(cap[1] = vrg_graph_capture_frame(g))))
        rc = -1;
    int scene_pass = -1;
    for (uint32_t i = 0; i < vrg_graph_pass_count(g); i++)
        if (!strcmp(vrg_graph_pass_name(g, i), "scene"))
            scene_pass = (int)i;
    /* an even number of runtime frames: the last has cap[1]'s parity */
    for (int r = 0; r < runs + runs % 2 && rc == 0; r++) {
        rc = vrg_graph_frame(g);
        if (r >= runs)
            continue;
        runtime[r] = vrg_graph_cpu_ms(g);
        scene[r] = scene_pass >= 0 ? vrg_graph_pass_cpu_ms(g, (uint32_t)scene_pass) : 0;
        rest[r] = runtime[r] - scene[r];
    }
    if (rc == 0)
        rc = baseline(ctx, cap, runs, base);
    if (rc == 0) {
        uint32_t dispatches, batches;
        vrg_capture_counts(cap[0], &dispatches, &batches);
        char name[160];
        out[n++] = vrg_bench_summarise("graph: compile thesis.ini (parse, validate, schedule, aliasing plan; no device)", "ms", compile, compiles);
        snprintf(name, sizeof name, "graph: thesis.ini runtime CPU per frame, record + submit (%u dispatches, %u barrier batches, %ux%u)",
                 dispatches, batches, o->width, o->height);
        double med_runtime, med_base;
        vrg_bench_figure fr = vrg_bench_summarise(name, "ms", runtime, runs);
        out[n++] = fr;
        med_runtime = fr.median;
        vrg_bench_figure fb = vrg_bench_summarise("graph: baseline CPU per frame, the same barriers and dispatches recorded directly", "ms", base, runs);
        out[n++] = fb;
        med_base = fb.median;
        vrg_bench_figure fs = vrg_bench_summarise("graph: of the runtime's, the scene plugin's execute (terrain streaming check, uniforms)", "ms", scene, runs);
        out[n++] = fs;
        vrg_bench_figure fo = vrg_bench_summarise("graph: runtime CPU per frame without the scene plugin's execute", "ms", rest, runs);
        out[n++] = fo;
        double ratio = med_base > 0 ? med_runtime / med_base : 0, over = (med_runtime - med_base) * 1000.0;
        double over_rest = (fo.median - med_base) * 1000.0;
        out[n++] = vrg_bench_summarise("graph: runtime / baseline (medians)", "x", &ratio, 1);
        out[n++] = vrg_bench_summarise("graph: runtime overhead over the baseline (medians)", "us", &over, 1);
        out[n++] = vrg_bench_summarise("graph: runtime overhead over the baseline, scene plugin's execute not counted", "us", &over_rest, 1);
    }
    vrg_capture_free(cap[0]);
    vrg_capture_free(cap[1]);
    free(runtime), free(base), free(scene), free(rest);
    vrg_graph_destroy(g);
    *count = n;
    return rc;
}
