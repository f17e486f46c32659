#define _POSIX_C_SOURCE 200809L
/* Runtime tests driven through the host API, on lavapipe, with validation and
 * synchronization validation on: any validation message fails the test.
 * Usage: test_runtime CASE (ctest registers one test per case). */
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "voxrg/voxrg.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"

#ifndef TEST_DIR
#define TEST_DIR "."
#endif

static int failures;
static int expect_validation_messages;
static vrg_context *ctx;

#define CHECK(cond, ...)                                                  \
    do {                                                                  \
        if (!(cond)) {                                                    \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                 \
            fputc('\n', stderr);                                          \
            failures++;                                                   \
        }                                                                 \
    } while (0)

static vrg_graph *load_with(const char *name, const char *const *sets, uint32_t nsets, const char *const *reads, uint32_t nreads)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/%s", TEST_DIR, name);
    vrg_graph_desc d = {.path = path, .overrides = sets, .override_count = nsets, .readback = reads, .readback_count = nreads};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        fprintf(stderr, "cannot load %s\n", path);
        failures++;
        return NULL;
    }
    return g;
}

static vrg_graph *load(const char *name) { return load_with(name, NULL, 0, NULL, 0); }

static float px(const vrg_image_data *img, uint32_t x, uint32_t y, int c) { return img->pixels[((size_t)y * img->width + x) * 4 + c]; }

/* The pattern plugin: (x/(W-1), y/(H-1), value, 1). */
static void pattern_at(uint32_t w, uint32_t h, int x, int y, float value, float out[4])
{
    out[0] = (float)x / (float)(w - 1);
    out[1] = (float)y / (float)(h - 1);
    out[2] = value;
    out[3] = 1;
}

/* 3x3 box with clamped coordinates, as the blur plugin computes it. */
static void blur_at(const float *src, uint32_t w, uint32_t h, int x, int y, float out[4])
{
    memset(out, 0, 4 * sizeof(float));
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int sx = x + dx < 0 ? 0 : x + dx >= (int)w ? (int)w - 1 : x + dx;
            int sy = y + dy < 0 ? 0 : y + dy >= (int)h ? (int)h - 1 : y + dy;
            for (int c = 0; c < 4; c++)
                out[c] += src[((size_t)sy * w + sx) * 4 + c] / 9.0f;
        }
}

static float *pattern_image(uint32_t w, uint32_t h, float value)
{
    float *img = malloc((size_t)w * h * 4 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            pattern_at(w, h, (int)x, (int)y, value, img + ((size_t)y * w + x) * 4);
    return img;
}

static float *blur_image(const float *src, uint32_t w, uint32_t h)
{
    float *img = malloc((size_t)w * h * 4 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            blur_at(src, w, h, (int)x, (int)y, img + ((size_t)y * w + x) * 4);
    return img;
}

static double max_diff(const vrg_image_data *img, const float *want, int channels)
{
    double worst = 0;
    for (size_t p = 0; p < (size_t)img->width * img->height; p++)
        for (int c = 0; c < channels; c++)
            worst = fmax(worst, fabs(img->pixels[p * 4 + c] - want[p * 4 + c]));
    return worst;
}

/* pattern → blur → add(blur, pattern): values against a CPU computation. */
static void test_chain(void)
{
    vrg_graph *g = load("chain.ini");
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
    float *pat = pattern_image(img.width, img.height, 0.5f);
    float *blur = blur_image(pat, img.width, img.height);
    for (size_t i = 0; i < (size_t)img.width * img.height * 4; i++)
        blur[i] += pat[i];
    double d = max_diff(&img, blur, 4);
    CHECK(d < 4e-3, "chain output differs from the CPU result by %g", d);
    /* and not trivially: the gradient must be there */
    CHECK(px(&img, img.width - 1, 0, 0) > 1.5f && px(&img, 0, 0, 0) < 0.1f, "no gradient in the output");
    free(pat);
    free(blur);
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* counter: out = prev + 1 while history is valid. */
static void test_history(void)
{
    vrg_graph *g = load("history.ini");
    if (!g)
        return;
    vrg_image_data img;
    for (int frame = 1; frame <= 5; frame++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
        CHECK(px(&img, 0, 0, 0) == (float)frame && px(&img, img.width - 1, img.height - 1, 0) == (float)frame,
              "frame %d: counter is %g", frame, px(&img, 0, 0, 0));
        free(img.pixels);
    }
    vrg_graph_reset_history(g);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_read(g, vrg_graph_output(g), &img);
    CHECK(px(&img, 3, 3, 0) == 1.0f, "after a history reset the counter is %g, not 1", px(&img, 3, 3, 0));
    free(img.pixels);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    uint32_t w, h;
    vrg_graph_size(g, &w, &h);
    CHECK(vrg_graph_resize(g, w / 2, h + 3) == 0, "resize failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_read(g, vrg_graph_output(g), &img);
    CHECK(img.width == w / 2 && img.height == h + 3, "resize gave %ux%u", img.width, img.height);
    CHECK(px(&img, img.width - 1, img.height - 1, 0) == 1.0f, "after resize the counter is %g, not 1", px(&img, 0, 0, 0));
    free(img.pixels);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_read(g, vrg_graph_output(g), &img);
    CHECK(px(&img, 0, 0, 0) == 2.0f, "history not kept after resize: %g", px(&img, 0, 0, 0));
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* A captured frame replayed with direct Vulkan calls (what bench --suite
 * graph times) is valid (validation with synchronization validation is on)
 * and does the frame's work: two counter frames captured (5, 6), replayed
 * four times alternating (7..10), and the runtime's next frame counts 11. */
static void test_capture_replay(void)
{
    vrg_graph *g = load("history.ini");
    if (!g)
        return;
    for (int i = 0; i < 4; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_capture *cap[2] = {vrg_graph_capture_frame(g), vrg_graph_capture_frame(g)};
    CHECK(cap[0] && cap[1], "capture failed");
    uint32_t dispatches = 0, batches = 0;
    if (cap[0])
        vrg_capture_counts(cap[0], &dispatches, &batches);
    CHECK(dispatches == 1 && batches >= 1, "captured %u dispatches, %u barrier batches", dispatches, batches);
    const vrg_device *dev = vrg_context_device(ctx);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = dev->queue_family};
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    vkCreateCommandPool(dev->device, &pi, NULL, &pool);
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    vkAllocateCommandBuffers(dev->device, &ai, &cmd);
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCreateFence(dev->device, &fi, NULL, &fence);
    for (int r = 0; r < 4 && cap[0] && cap[1]; r++) {
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkResetCommandBuffer(cmd, 0);
        vkBeginCommandBuffer(cmd, &bi);
        vrg_capture_record(cap[r % 2], cmd);
        vkEndCommandBuffer(cmd);
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
        vkResetFences(dev->device, 1, &fence);
        CHECK(vkQueueSubmit2(dev->queue, 1, &si, fence) == VK_SUCCESS, "replay submit failed");
        vkWaitForFences(dev->device, 1, &fence, VK_TRUE, UINT64_MAX);
    }
    vkDestroyFence(dev->device, fence, NULL);
    vkDestroyCommandPool(dev->device, pool, NULL);
    vrg_capture_free(cap[0]);
    vrg_capture_free(cap[1]);
    vrg_image_data img;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "frame failed");
    CHECK(px(&img, 3, 5, 0) == 11.0f, "after 6 frames and 4 replays the counter is %g, not 11", px(&img, 3, 5, 0));
    free(img.pixels);
    CHECK(vrg_graph_cpu_ms(g) > 0, "no CPU time for the frame");
    vrg_graph_destroy(g);
}

/* History images are cleared: a counter that reads @prev even when history
 * is invalid restarts at 1 on the first frame, after a reset and a resize. */
static void test_history_cleared(void)
{
    static const char *sets[] = {"counter.always_read=1"};
    vrg_graph *g = load_with("history.ini", sets, 1, NULL, 0);
    if (!g)
        return;
    vrg_image_data img;
    for (int round = 0; round < 3; round++) {
        if (round == 1)
            vrg_graph_reset_history(g);
        if (round == 2)
            CHECK(vrg_graph_resize(g, 5, 3) == 0, "resize failed");
        for (int frame = 1; frame <= 3; frame++) {
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
            CHECK(px(&img, 0, 0, 0) == (float)frame && px(&img, img.width - 1, img.height - 1, 0) == (float)frame,
                  "round %d frame %d: %g (history not cleared?)", round, frame, px(&img, 0, 0, 0));
            free(img.pixels);
        }
    }
    vrg_graph_destroy(g);
}

/* A graph given as text (path: for messages only). */
static vrg_graph *load_text(const char *text, const char *const *reads, uint32_t nreads)
{
    vrg_graph_desc d = {.path = "generated.ini", .text = text, .readback = reads, .readback_count = nreads};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        fprintf(stderr, "cannot load the generated graph\n");
        failures++;
        return NULL;
    }
    return g;
}

static void append(char **text, size_t *len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    *text = realloc(*text, *len + (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(*text + *len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    *len += (size_t)n;
}

/* More history images than one barrier batch holds, all cleared in the same
 * frame (the first, and after a reset): every clear gets its barrier (a
 * missing one is a validation error) and every counter counts from 1. */
static void test_history_many(void)
{
    enum { COUNTERS = 70 };
    char *text = NULL, names[COUNTERS][16];
    const char *reads[COUNTERS];
    size_t len = 0;
    append(&text, &len, "[graph]\nname = history_many\noutput = c0\nwidth = 8\nheight = 8\n");
    for (int i = 0; i < COUNTERS; i++) {
        append(&text, &len, "[pass n%d]\nplugin = counter\nalways_read = 1\nin.prev = c%d@prev\nout.count = c%d\n", i, i, i);
        snprintf(names[i], sizeof names[i], "c%d", i);
        reads[i] = names[i];
    }
    vrg_graph *g = load_text(text, reads, COUNTERS);
    free(text);
    if (!g)
        return;
    for (int round = 0; round < 2; round++) {
        if (round)
            vrg_graph_reset_history(g);
        for (int frame = 1; frame <= 2; frame++) {
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            for (int i = 0; i < COUNTERS; i += COUNTERS - 1) {
                vrg_image_data img;
                CHECK(vrg_graph_read(g, names[i], &img) == 0, "readback of %s failed", names[i]);
                CHECK(px(&img, 7, 7, 0) == (float)frame, "round %d frame %d: %s is %g", round, frame, names[i], px(&img, 7, 7, 0));
                free(img.pixels);
            }
        }
    }
    vrg_graph_destroy(g);
}

/* A pass with more internal images than a barrier batch, all in one
 * vrg_pass_use (a dropped barrier leaves an image in the wrong layout for its
 * clear: a validation error), and more figures than there once was room for,
 * with names longer than 31 characters. */
static void test_many_uses(void)
{
    vrg_graph *g = load_text("[graph]\nname = many_uses\noutput = out\nwidth = 16\nheight = 16\n"
                             "[pass m]\nplugin = many_uses\nimages = 70\nfigures = 20\nout.color = out\n",
                             NULL, 0);
    if (!g)
        return;
    for (int frame = 0; frame < 2; frame++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, "out", &img) == 0, "readback failed");
    CHECK(px(&img, 3, 3, 0) == 70.0f, "output is %g, not 70", px(&img, 3, 3, 0));
    free(img.pixels);
    for (int i = 0; i < 20; i++) {
        char name[96];
        double v = -1;
        snprintf(name, sizeof name, "figure_named_at_length_beyond_thirty_one_characters_%d", i);
        CHECK(vrg_graph_stat(g, "m", name, &v) == 0 && v == i, "figure %d: %s, %g", i, name, v);
    }
    vrg_graph_destroy(g);
}

/* One image (big) placed over more than 64 earlier ones whose lifetimes
 * ended before it starts; only the last few of them are written. Its first
 * use must wait for those writes (the aliasing barrier), or synchronization
 * validation reports a hazard. */
static void test_alias_many(void)
{
    vrg_graph *g = load_text("[graph]\nname = alias_many\noutput = sum\nwidth = 128\nheight = 128\n"
                             "[pass m]\nplugin = many_uses\nimages = 70\nwritten = 6\nscale = 0.0625\nfigures = 0\nout.color = small\n"
                             "[pass gen]\nplugin = pattern\nout.color = big\n"
                             "[pass s]\nplugin = add\nin.a = small\nin.b = big\nout.sum = sum\n",
                             NULL, 0);
    if (!g)
        return;
    int big_block, block;
    uint64_t big_offset, big_size, offset, size;
    CHECK(vrg_graph_placement(g, "big", &big_block, &big_offset, &big_size) == 0, "no placement of big");
    for (int i = 0; i < 70; i++) {
        char name[32];
        snprintf(name, sizeof name, "m.t%d", i);
        CHECK(vrg_graph_placement(g, name, &block, &offset, &size) == 0 && block == big_block && offset >= big_offset &&
                  offset + size <= big_offset + big_size,
              "%s (block %d, %llu + %llu) is not inside big's memory (block %d, %llu + %llu): the test proves nothing", name, block,
              (unsigned long long)offset, (unsigned long long)size, big_block, (unsigned long long)big_offset, (unsigned long long)big_size);
    }
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, "sum", &img) == 0, "readback failed");
    CHECK(px(&img, 0, 0, 0) == 70.0f, "sum is %g, not 70 + 0", px(&img, 0, 0, 0));
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* The dispatch helper's limits fail the frame with a message naming them:
 * more bound slots than bindings (the rest were once left unbound), defines
 * longer than it takes (once cut short). */
static void test_dispatch_limits(void)
{
    static const struct {
        const char *set, *want;
    } cases[] = {
        {"m.long_defines=0", "its slots need more than the 16 bindings of a dispatch"},
        {"m.long_defines=1", "defines of 399 characters (at most"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *log = NULL;
        size_t len = 0;
        FILE *diag = open_memstream(&log, &len);
        const char *sets[] = {cases[i].set};
        vrg_graph_desc d = {.path = "limits.ini", .overrides = sets, .override_count = 1, .diag = diag,
                            .text = "[graph]\noutput = out\nwidth = 8\nheight = 8\n[pass m]\nplugin = many_slots\nout.color = out\n"};
        vrg_graph *g = NULL;
        CHECK(vrg_graph_load(ctx, &d, &g) == 0, "cannot load the graph");
        if (g) {
            CHECK(vrg_graph_frame(g) != 0, "%s: the frame did not fail", cases[i].set);
            vrg_graph_destroy(g);
        }
        fclose(diag);
        CHECK(log && strstr(log, cases[i].want), "%s: no '%s' in: %s", cases[i].set, cases[i].want, log ? log : "");
        free(log);
    }
}

/* accumulate: out = mix(history, color, alpha) once history is valid. The
 * input changes with a --set between graphs, so use two frames of one graph
 * whose color is constant: the result must stay the colour (mix of equals),
 * and the first frame must not read uninitialised history. */
static void test_accumulate(void)
{
    static const char *sets[] = {"acc.alpha=0.25"};
    vrg_graph *g = load_with("accumulate.ini", sets, 1, NULL, 0);
    if (!g)
        return;
    vrg_image_data img;
    for (int i = 0; i < 3; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
    float *pat = pattern_image(img.width, img.height, 0.5f);
    double d = max_diff(&img, pat, 3);
    CHECK(d < 4e-3, "accumulated constant input drifted by %g", d);
    free(pat);
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* pingpong: internal ping-pong images; dst = src + iterations. */
static void test_pingpong(void)
{
    for (int it = 1; it <= 5; it += 2) {
        char set[64];
        snprintf(set, sizeof set, "pp.iterations=%d", it);
        const char *sets[] = {set};
        vrg_graph *g = load_with("pingpong.ini", sets, 1, NULL, 0);
        if (!g)
            return;
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data img;
        CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
        float *pat = pattern_image(img.width, img.height, 0.5f);
        for (size_t i = 0; i < (size_t)img.width * img.height * 4; i++)
            pat[i] += (float)it;
        double d = max_diff(&img, pat, 4);
        CHECK(d < 8e-3, "iterations=%d: output differs from src+%d by %g", it, it, d);
        free(pat);
        free(img.pixels);
        vrg_memory_stats m = vrg_graph_memory(g);
        CHECK(m.transient_count >= 3, "internal images were not made transient resources (%u)", m.transient_count);
        vrg_graph_destroy(g);
    }
}

/* Internal images alias with graph resources, and the result survives it:
 * s1 + blur(s1) with s1 = blur(pattern + 3). */
static void test_pingpong_alias(void)
{
    vrg_graph *g = load("pingpong_alias.ini");
    if (!g)
        return;
    int shared = 0;
    static const char *internal[] = {"pp.ping", "pp.pong"}, *later[] = {"smooth1", "smooth2", "final"};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) {
            int b1, b2;
            uint64_t o1, o2, s1, s2;
            if (vrg_graph_placement(g, internal[i], &b1, &o1, &s1) == 0 && vrg_graph_placement(g, later[j], &b2, &o2, &s2) == 0)
                shared += b1 >= 0 && b1 == b2 && o1 < o2 + s2 && o2 < o1 + s1;
        }
    CHECK(shared >= 1, "no internal ping-pong image shares memory with a graph resource");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
    float *cur = pattern_image(img.width, img.height, 0.5f);
    for (size_t i = 0; i < (size_t)img.width * img.height * 4; i++)
        cur[i] += 3.0f;
    float *s1 = blur_image(cur, img.width, img.height), *s2 = blur_image(s1, img.width, img.height);
    for (size_t i = 0; i < (size_t)img.width * img.height * 4; i++)
        s2[i] += s1[i];
    double d = max_diff(&img, s2, 4);
    CHECK(d < 1.6e-2, "output differs from s1 + blur(s1), s1 = blur(pattern + 3), by %g", d);
    free(cur);
    free(s1);
    free(s2);
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* alias: a chain whose early resources die before later ones are born. */
static void test_alias(void)
{
    vrg_graph *g = load("alias.ini");
    if (!g)
        return;
    vrg_memory_stats m = vrg_graph_memory(g);
    CHECK(m.aliased_bytes < m.naive_bytes, "no memory saved: naive %llu, aliased %llu", (unsigned long long)m.naive_bytes,
          (unsigned long long)m.aliased_bytes);
    CHECK(m.aliased_bytes * 2 <= m.naive_bytes, "a 5-resource chain should at least halve memory: naive %llu, aliased %llu",
          (unsigned long long)m.naive_bytes, (unsigned long long)m.aliased_bytes);
    CHECK(m.alias_shared >= 2, "no two resources share memory (%u)", m.alias_shared);
    /* Two resources whose lifetimes do not overlap sit at the same address. */
    int shared = 0;
    char names[8][32];
    int blocks[8];
    uint64_t offs[8], sizes[8];
    int n = 0;
    static const char *candidates[] = {"gradient", "b1", "b2", "b3", "final"};
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0] && n < 8; i++)
        if (vrg_graph_placement(g, candidates[i], &blocks[n], &offs[n], &sizes[n]) == 0 && blocks[n] >= 0)
            snprintf(names[n], sizeof names[n], "%s", candidates[i]), n++;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            shared += blocks[i] == blocks[j] && offs[i] == offs[j];
    CHECK(n >= 3 && shared >= 1, "no two of %d placed resources share an offset", n);
    CHECK(vrg_graph_pass_culled(g, "unused") == 1, "pass 'unused' was not culled");
    CHECK(vrg_graph_pass_culled(g, "gen") == 0, "pass 'gen' was culled");
    /* Pixels must survive the sharing: 4 blurs of the pattern. */
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
    float *cur = pattern_image(img.width, img.height, 0.5f);
    for (int i = 0; i < 4; i++) {
        float *next = blur_image(cur, img.width, img.height);
        free(cur);
        cur = next;
    }
    double d = max_diff(&img, cur, 4);
    CHECK(d < 6e-3, "aliased chain output differs from the CPU result by %g", d);
    free(cur);
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* fill_buffer's data[i] = i * 7 (1024 words) read into an image through
 * `graph`'s reader, `words` per pixel: channel c of pixel (x, y) must be
 * data[words * ((y*W+x) % (1024 / words)) + c]. */
static void check_buffer_image(const char *graph, uint32_t words)
{
    static const char *sets[] = {"fill.mul=7"};
    vrg_graph *g = load_with(graph, sets, 1, NULL, 0);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "%s: frame failed", graph);
    vrg_image_data img;
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "%s: readback failed", graph);
    int bad = 0;
    for (uint32_t y = 0; y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++)
            for (uint32_t c = 0; c < words; c++)
                bad += px(&img, x, y, (int)c) != (float)((words * ((y * img.width + x) % (1024 / words)) + c) * 7);
    CHECK(bad == 0, "%s: %d channels differ from data[i] = i*7 read %u words per pixel", graph, bad, words);
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* buffers between passes: image(x,y) = data[(y*W+x) % 1024] (a storage buffer). */
static void test_buffer(void) { check_buffer_image("buffer.ini", 1); }

/* A buffer read through a view of its writer's texel format (fill_buffer
 * names rgba32ui): image(x,y).c = data[4 * ((y*W+x) % 256) + c]. */
static void test_buffer_texels(void) { check_buffer_image("buffer_texels.ini", 4); }

/* A scene plugin writes a uniform buffer by transfer; a pass reads it. */
static void test_scene(void)
{
    static const char *sets[] = {"scene.r=1"};
    vrg_graph *g = load_with("scene.ini", sets, 1, NULL, 0);
    if (!g)
        return;
    for (int i = 0; i < 2; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
    CHECK(fabsf(px(&img, 1, 1, 0) - 1.0f) < 1e-3f && fabsf(px(&img, 1, 1, 1) - 0.5f) < 1e-3f && fabsf(px(&img, 1, 1, 2) - 0.75f) < 1e-3f,
          "scene colour is (%g %g %g), want (1 0.5 0.75)", px(&img, 1, 1, 0), px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* Loader errors: each names the plugin path and what was expected. */
static int load_text_errors(const char *text, const char *want1, const char *want2)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    vrg_graph_desc d = {.path = TEST_DIR "/graphs/loader.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(NULL, &d, &g);
    fclose(diag);
    int ok = rc != 0 && strstr(buf, want1) && (!want2 || strstr(buf, want2));
    if (!ok)
        fprintf(stderr, "loader message lacks '%s'/'%s':\n%s\n", want1, want2 ? want2 : "", buf);
    free(buf);
    vrg_graph_destroy(g);
    return ok;
}

static void test_loader(void)
{
    char abi[256];
    snprintf(abi, sizeof abi, "ABI version %u", VRG_ABI_VERSION);
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = bad_abi\n", "bad_abi.so", "has ABI version 999"), "ABI mismatch");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = bad_abi\n", "loader.ini:4:", abi), "ABI mismatch line/expected");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = no_entry\n", "no_entry.so", "vrg_plugin_entry"), "missing entry point");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = not_there\n", "unknown plugin 'not_there'", "searched:"), "missing file");
    /* a file that is not a shared object: dlopen's own error, with the path */
    const char *dir = getenv("VOXRG_PLUGIN_PATH");
    CHECK(dir != NULL, "VOXRG_PLUGIN_PATH is not set for this test");
    if (dir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/garbage.so", dir);
        FILE *f = fopen(path, "w");
        CHECK(f != NULL, "cannot write %s", path);
        if (f) {
            fputs("this is not an ELF file\n", f);
            fclose(f);
            CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = garbage\n", "cannot load plugin 'garbage'", "garbage.so"), "dlopen error");
        }
    }
}

/* counter → accumulate(alpha 0.5): red goes 1, 1.5, 2.25, 3.125, 4.0625
 * (h + (c - h) / 2 with c = frame number), exactly representable in fp16. */
static void test_accumulate_count(void)
{
    vrg_graph *g = load("accumulate_count.ini");
    if (!g)
        return;
    static const float want[] = {1.0f, 1.5f, 2.25f, 3.125f, 4.0625f};
    for (int i = 0; i < 5; i++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data img;
        CHECK(vrg_graph_read(g, vrg_graph_output(g), &img) == 0, "readback failed");
        CHECK(px(&img, 2, 2, 0) == want[i], "frame %d: accumulated %g, want %g", i + 1, px(&img, 2, 2, 0), want[i]);
        free(img.pixels);
    }
    vrg_graph_destroy(g);
}

/* The suite's validation is live: a pass with a deliberate unsynchronised
 * write-after-write must be reported. */
static void test_validation_live(void)
{
    vrg_graph *g = load("hazard.ini");
    if (!g)
        return;
    vrg_graph_frame(g);
    vrg_graph_destroy(g);
    uint32_t v = vrg_context_validation_errors(ctx);
    CHECK(v > 0, "the hazard was not reported: synchronization validation is not running");
    fprintf(stderr, "(%u validation messages expected above)\n", v);
    expect_validation_messages = 1;
}

/* PCG hash, as in tests/plugins/world_probe/world_probe.comp. */
static uint32_t pcg(uint32_t v)
{
    uint32_t s = v * 747796405u + 2891336453u;
    uint32_t w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

static int probe_mismatches(vrg_graph *g, const int lo[3], const int extent[3], int *solid);

/* The boxes of tests/graphs/blocks_probe.ini: later ones win. */
static const struct {
    int lo[3], hi[3];
    const char *block;
} probe_boxes[] = {
    {{-20, 0, -20}, {35, 0, 35}, "white"}, {{-3, 1, -3}, {3, 20, 3}, "stone"}, {{10, 1, -18}, {12, 17, 30}, "red"},
    {{0, 5, 0}, {1, 6, 1}, "air"},         {{30, 30, 30}, {31, 31, 31}, "lamp"},
};

static int expected_block(int x, int y, int z)
{
    int id = VRG_BLOCK_AIR;
    for (size_t i = 0; i < sizeof probe_boxes / sizeof probe_boxes[0]; i++)
        if (x >= probe_boxes[i].lo[0] && x <= probe_boxes[i].hi[0] && y >= probe_boxes[i].lo[1] && y <= probe_boxes[i].hi[1] &&
            z >= probe_boxes[i].lo[2] && z <= probe_boxes[i].hi[2])
            id = vrg_block_by_name(probe_boxes[i].block);
    return id;
}

/* The blocks scene holds exactly its boxes (CPU), the GPU buffer agrees with
 * the CPU store at pseudo-random probes (ids, occupancy and brick bits), and
 * the CPU pick ray finds the right face. */
static void test_blocks_world(void)
{
    vrg_graph *g = load("blocks_probe.ini");
    if (!g)
        return;
    const vrg_world *w = vrg_graph_world(g);
    CHECK(w != NULL, "the blocks scene set no world");
    if (!w) {
        vrg_graph_destroy(g);
        return;
    }
    int wrong = 0, solid = 0;
    for (int y = -2; y < 40; y++)
        for (int z = -40; z < 50; z++)
            for (int x = -40; x < 50; x++) {
                int want = expected_block(x, y, z), got = vrg_world_block(w, x, y, z);
                wrong += want != got;
                solid += got != VRG_BLOCK_AIR;
            }
    CHECK(wrong == 0, "%d voxels differ from the boxes", wrong);
    CHECK(solid == 56 * 56 + 7 * 20 * 7 - 8 + 3 * 17 * 49 + 8, "%d solid voxels", solid);

    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, "probes", &img) == 0, "readback failed");
    int mismatched = 0, probed_solid = 0;
    for (uint32_t i = 0; i < img.width * img.height; i++) {
        int p[3] = {-40 + (int)(pcg(3 * i) % 90), -4 + (int)(pcg(3 * i + 1) % 40), -40 + (int)(pcg(3 * i + 2) % 90)};
        int cx = vrg_floor_div16(p[0]), cy = vrg_floor_div16(p[1]), cz = vrg_floor_div16(p[2]);
        int id = vrg_world_block(w, p[0], p[1], p[2]);
        int brick = 0;
        const vrg_block *chunk = vrg_world_chunk(w, cx, cy, cz);
        if (chunk) {
            int bx = (p[0] & 15) & ~7, by = (p[1] & 15) & ~7, bz = (p[2] & 15) & ~7;
            for (int k = 0; k < 512 && !brick; k++)
                brick = chunk[vrg_chunk_index(bx + (k & 7), by + ((k >> 6) & 7), bz + ((k >> 3) & 7))] != VRG_BLOCK_AIR;
        }
        uint32_t flags = (id != 0) | (brick << 1) | ((chunk != NULL) << 2);
        uint32_t gid = (uint32_t)img.pixels[i * 4], gflags = (uint32_t)img.pixels[i * 4 + 1];
        if (gid != (uint32_t)id || gflags != flags) {
            if (mismatched < 5)
                fprintf(stderr, "probe (%d %d %d): GPU id %u flags %u, CPU id %d flags %u\n", p[0], p[1], p[2], gid, gflags, id, flags);
            mismatched++;
        }
        probed_solid += id != 0;
    }
    CHECK(mismatched == 0, "%d of %u probes differ between GPU and CPU", mismatched, img.width * img.height);
    CHECK(probed_solid > 20, "only %d probes hit a solid block: the probe does not exercise the world", probed_solid);
    free(img.pixels);
    /* a resize re-allocates (and clears) the world buffer: the scene must upload it again */
    CHECK(vrg_graph_resize(g, 48, 40) == 0 && vrg_graph_frame(g) == 0, "resize failed");
    int lo[3] = {-40, -4, -40}, extent[3] = {90, 40, 90}, solid_after;
    int bad = probe_mismatches(g, lo, extent, &solid_after);
    CHECK(bad == 0 && solid_after > 10, "after resize %d probes differ (%d solid)", bad, solid_after);

    vrg_world_hit hit;
    float o[3] = {0.5f, 30.5f, 0.5f}, down[3] = {0, -1, 0};
    CHECK(vrg_world_pick(w, o, down, 100, &hit) == 1, "pick missed the pillar");
    CHECK(hit.block[0] == 0 && hit.block[1] == 20 && hit.block[2] == 0 && hit.normal[1] == 1 && fabsf(hit.distance - 9.5f) < 1e-4f &&
              hit.id == VRG_BLOCK_STONE,
          "pick: block (%d %d %d) normal (%d %d %d) distance %g id %d", hit.block[0], hit.block[1], hit.block[2], hit.normal[0],
          hit.normal[1], hit.normal[2], hit.distance, hit.id);
    float o2[3] = {-30.5f, 10.5f, 0.5f}, east[3] = {1, 0, 0};
    CHECK(vrg_world_pick(w, o2, east, 100, &hit) == 1 && hit.block[0] == -3 && hit.normal[0] == -1, "pick east: block x %d normal x %d",
          hit.block[0], hit.normal[0]);
    CHECK(vrg_world_pick(w, o2, east, 20, &hit) == 0, "pick beyond max_distance hit");
    vrg_graph_destroy(g);
}

/* Pixels of a world_debug distance view (mode 3, pass "view") whose hit or
 * miss differs from the CPU pick ray through the same pixel; counts hits
 * and misses, and the worst relative distance error of the hits. */
static int trace_disagreement(vrg_graph *g, int *hits, int *misses, double *worst, int *pixels)
{
    vrg_image_data img;
    if (vrg_graph_read(g, "view", &img) != 0)
        return -1;
    const vrg_world *w = vrg_graph_world(g);
    const vrg_camera *cam = vrg_graph_camera(g);
    int disagree = 0;
    *hits = *misses = 0;
    *worst = 0;
    for (uint32_t y = 0; y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++) {
            float dir[3];
            vrg_camera_ray(cam, img.width, img.height, (float)x, (float)y, dir);
            vrg_world_hit hit;
            int h = vrg_world_pick(w, cam->position, dir, 512, &hit);
            float gpu = px(&img, x, y, 0);
            if (h != (gpu > 0)) {
                disagree++;
                continue;
            }
            if (h) {
                (*hits)++;
                *worst = fmax(*worst, fabs(gpu - hit.distance) / hit.distance);
            } else
                (*misses)++;
        }
    *pixels = (int)(img.width * img.height);
    free(img.pixels);
    return disagree;
}

/* The GPU's primary rays and two-level DDA against the CPU camera and pick
 * ray, pixel by pixel, on the wall scene (world_debug mode 3: distance). */
static void test_blocks_trace(void)
{
    static const char *sets[] = {"view.mode=3"};
    vrg_graph *g = load_with("blocks_wall.ini", sets, 1, NULL, 0);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    int hits, misses, pixels;
    double worst;
    int disagree = trace_disagreement(g, &hits, &misses, &worst, &pixels);
    /* rays grazing an edge may fall either side in float */
    CHECK(disagree >= 0 && disagree <= pixels / 200, "%d pixels disagree on hit/miss", disagree);
    CHECK(hits > 1000 && misses > 300, "scene not in view: %d hits, %d misses", hits, misses);
    CHECK(worst < 2e-3, "distance differs by %.4f%%", worst * 100);
    vrg_graph_destroy(g);
}

/* Streamed terrain seen toward the horizon: rays leave the box of loaded
 * chunks sideways (the DDA clips to it), and after the camera moves four
 * chunks the box and the GPU copy follow; GPU and CPU rays agree both times. */
static void test_terrain_trace(void)
{
    vrg_graph *g = load("terrain_trace.ini");
    if (!g)
        return;
    for (int move = 0; move < 2; move++) {
        if (move) {
            vrg_camera cam = *vrg_graph_camera(g);
            cam.position[0] += 4 * 16;
            vrg_graph_set_camera(g, &cam);
        }
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        int hits, misses, pixels;
        double worst;
        int disagree = trace_disagreement(g, &hits, &misses, &worst, &pixels);
        CHECK(disagree >= 0 && disagree <= pixels / 200, "camera %d: %d of %d pixels disagree on hit/miss", move, disagree, pixels);
        CHECK(hits > pixels / 4 && misses > pixels / 10, "camera %d: %d hits, %d misses", move, hits, misses);
        CHECK(worst < 2e-3, "camera %d: distance differs by %.4f%%", move, worst * 100);
        /* the box rays clip to (kept between uploads) is that of the
         * non-air blocks of the loaded chunks */
        const vrg_world *w = vrg_graph_world(g);
        int lo[3], hi[3], want_lo[3] = {INT_MAX, INT_MAX, INT_MAX}, want_hi[3] = {INT_MIN, INT_MIN, INT_MIN};
        vrg_world_gpu_box(w, lo, hi);
        for (int cy = -4; cy < 16; cy++)
            for (int cz = -40; cz <= 40; cz++)
                for (int cx = -40; cx <= 40; cx++) {
                    const vrg_block *blocks = vrg_world_chunk(w, cx, cy, cz);
                    for (int i = 0; blocks && i < VRG_CHUNK_VOXELS; i++)
                        if (blocks[i] != VRG_BLOCK_AIR) {
                            const int b[3] = {cx * 16 + i % 16, cy * 16 + i / 256, cz * 16 + i / 16 % 16};
                            for (int a = 0; a < 3; a++)
                                want_lo[a] = b[a] < want_lo[a] ? b[a] : want_lo[a], want_hi[a] = b[a] + 1 > want_hi[a] ? b[a] + 1 : want_hi[a];
                        }
                }
        CHECK(!memcmp(lo, want_lo, sizeof lo) && !memcmp(hi, want_hi, sizeof hi), "camera %d: GPU box %d %d %d..%d %d %d, non-air blocks %d %d %d..%d %d %d",
              move, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], want_lo[0], want_lo[1], want_lo[2], want_hi[0], want_hi[1], want_hi[2]);
    }
    vrg_graph_destroy(g);
}

/* Probes (as in blocks_world) against the CPU store: 0 on agreement. */
static int probe_mismatches(vrg_graph *g, const int lo[3], const int extent[3], int *solid)
{
    const vrg_world *w = vrg_graph_world(g);
    vrg_image_data img;
    if (!w || vrg_graph_read(g, "probes", &img) != 0)
        return -1;
    int bad = 0;
    *solid = 0;
    for (uint32_t i = 0; i < img.width * img.height; i++) {
        int p[3] = {lo[0] + (int)(pcg(3 * i) % (uint32_t)extent[0]), lo[1] + (int)(pcg(3 * i + 1) % (uint32_t)extent[1]),
                    lo[2] + (int)(pcg(3 * i + 2) % (uint32_t)extent[2])};
        int id = vrg_world_block(w, p[0], p[1], p[2]);
        const vrg_block *chunk = vrg_world_chunk(w, vrg_floor_div16(p[0]), vrg_floor_div16(p[1]), vrg_floor_div16(p[2]));
        int differs = (uint32_t)img.pixels[i * 4] != (uint32_t)id || (((uint32_t)img.pixels[i * 4 + 1] >> 2) & 1) != (chunk != NULL) ||
                      ((uint32_t)img.pixels[i * 4 + 1] & 1) != (id != 0);
        if (differs && bad < 3)
            fprintf(stderr, "probe (%d %d %d): GPU id %u flags %u, CPU id %d loaded %d\n", p[0], p[1], p[2], (uint32_t)img.pixels[i * 4],
                    (uint32_t)img.pixels[i * 4 + 1], id, chunk != NULL);
        bad += differs;
        *solid += id != 0;
    }
    free(img.pixels);
    return bad;
}

/* The terrain scene: GPU world equals the CPU store, and the loaded chunk
 * set follows the camera exactly (radius 2, hysteresis 1). */
static void test_terrain_world(void)
{
    vrg_graph *g = load("terrain_probe.ini");
    if (!g)
        return;
    const vrg_world *w = vrg_graph_world(g);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_world_chunk_count(w) == 5 * 5 * 3, "%d chunks loaded at the start, want 75", vrg_world_chunk_count(w));
    int lo[3] = {-40, -2, -40}, extent[3] = {150, 52, 80}, solid; /* the probe pass's parameters */
    int bad = probe_mismatches(g, lo, extent, &solid);
    CHECK(bad == 0, "%d probes differ between GPU and CPU", bad);
    CHECK(solid > 500, "only %d probes in solid terrain", solid);

    /* four chunks east: cx 2..6 wanted, 1 kept by hysteresis, the rest dropped */
    vrg_camera cam = *vrg_graph_camera(g);
    cam.position[0] = 4 * 16 + 8;
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    int wrong = 0;
    for (int cx = -4; cx <= 8; cx++)
        for (int cz = -4; cz <= 4; cz++)
            for (int cy = 0; cy < 3; cy++)
                wrong += vrg_world_has_chunk(w, cx, cy, cz) != (cx >= 1 && cx <= 6 && cz >= -2 && cz <= 2);
    CHECK(wrong == 0 && vrg_world_chunk_count(w) == 6 * 5 * 3, "after moving: %d chunks wrong, %d loaded (want 90)", wrong,
          vrg_world_chunk_count(w));
    /* the GPU copy followed: new chunks are there, dropped ones read as unloaded */
    bad = probe_mismatches(g, lo, extent, &solid);
    CHECK(bad == 0, "after moving, %d probes differ between GPU and CPU", bad);
    vrg_graph_destroy(g);
}

static float srgb_decode(uint8_t v)
{
    float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* Block textures: tiles average to their material's albedo at every level
 * up to one texel per tile; no level mixes tiles; and the GPU samples every
 * uploaded level as generated. */
static void test_atlas(void)
{
    uint8_t *atlas = malloc(vrg_atlas_bytes());
    vrg_atlas_generate(atlas);
    const vrg_material *m = vrg_materials();
    double worst = 0;
    for (int b = 1; b < VRG_BLOCK_COUNT; b++) {
        int tile = m[b].tile_top;
        for (uint32_t k = 0; k <= 4; k++) {
            uint32_t size = VRG_ATLAS_SIZE >> k, ts = VRG_ATLAS_TILE >> k;
            const uint8_t *lv = atlas + vrg_atlas_level_offset(k);
            for (int c = 0; c < 3; c++) {
                double sum = 0;
                for (uint32_t y = 0; y < ts; y++)
                    for (uint32_t x = 0; x < ts; x++)
                        sum += srgb_decode(lv[(((tile / 4) * ts + y) * size + (tile % 4) * ts + x) * 4 + c]);
                worst = fmax(worst, fabs(sum / (ts * ts) - m[b].albedo[c]) / m[b].albedo[c]);
            }
        }
    }
    CHECK(worst < 0.03, "a tile's mean differs from its albedo by %.1f%%", worst * 100);
    /* textures are not flat: level 0 of stone varies */
    const uint8_t *l0 = atlas;
    int lo = 255, hi = 0, stone = m[VRG_BLOCK_STONE].tile_top;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            int v = l0[(((stone / 4) * 16 + y) * VRG_ATLAS_SIZE + (stone % 4) * 16 + x) * 4];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
    CHECK(hi - lo > 20, "stone's texture is flat (%d..%d)", lo, hi);

    vrg_graph *g = load("atlas.ini");
    if (g) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data img;
        CHECK(vrg_graph_read(g, "probe", &img) == 0, "readback failed");
        int bad = 0;
        for (uint32_t k = 0; k < VRG_ATLAS_MIPS; k++)
            for (uint32_t x = 0; x < (uint32_t)(VRG_ATLAS_SIZE >> k); x++)
                for (int c = 0; c < 3; c++) {
                    float want = srgb_decode(atlas[vrg_atlas_level_offset(k) + x * 4 + c]);
                    bad += fabsf(px(&img, x, k, c) - want) > 2e-3f;
                }
        CHECK(bad == 0, "%d sampled texels differ from the generated levels", bad);
        free(img.pixels);
        vrg_graph_destroy(g);
    }
    free(atlas);
}

#define SKIP 77

/* The ray-query backend: BLAS per chunk of exactly the exposed faces (none
 * between two blocks across a chunk border), rebuilt only when chunks
 * change, and ray-query hit distances equal to the CPU pick ray's. */
static int test_rayquery(void)
{
    if (!vrg_context_device(ctx)->features.ray_query) {
        printf("rayquery: skipped: device '%s' has no VK_KHR_ray_query\n", vrg_context_device(ctx)->name);
        return SKIP;
    }
    vrg_graph *g = load("blocks_rayquery.ini");
    if (!g)
        return 0;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    const vrg_world *w = vrg_graph_world(g);
    double built = -1, quads = -1, instances = -1;
    vrg_graph_stat(g, "scene", "blas_built", &built);
    vrg_graph_stat(g, "scene", "blas_quads", &quads);
    vrg_graph_stat(g, "scene", "tlas_instances", &instances);
    long faces = 0;
    int chunks = 0;
    for (int cz = -2; cz <= 2; cz++)
        for (int cy = 0; cy < 2; cy++)
            for (int cx = -2; cx <= 2; cx++) {
                const vrg_block *c = vrg_world_chunk(w, cx, cy, cz);
                int any = 0;
                for (int i = 0; c && i < VRG_CHUNK_VOXELS; i++) {
                    if (c[i] == VRG_BLOCK_AIR)
                        continue;
                    int x = cx * 16 + (i & 15), z = cz * 16 + ((i >> 4) & 15), y = cy * 16 + (i >> 8);
                    static const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
                    for (int f = 0; f < 6; f++)
                        if (vrg_world_block(w, x + d[f][0], y + d[f][1], z + d[f][2]) == VRG_BLOCK_AIR)
                            faces++, any = 1;
                }
                chunks += any;
            }
    CHECK(quads == (double)faces, "BLASes hold %.0f quads, the world has %ld exposed faces", quads, faces);
    CHECK(built == chunks && instances == chunks, "built %.0f BLASes and %.0f instances for %d chunks with faces", built, instances, chunks);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_stat(g, "scene", "blas_built", &built);
    CHECK(built == 0, "an unchanged world rebuilt %.0f BLASes", built);

    vrg_image_data img;
    CHECK(vrg_graph_read(g, "distance", &img) == 0, "readback failed");
    const vrg_camera *cam = vrg_graph_camera(g);
    int disagree = 0, hits = 0;
    double worst = 0;
    for (uint32_t y = 0; y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++) {
            float dir[3];
            vrg_camera_ray(cam, img.width, img.height, (float)x, (float)y, dir);
            vrg_world_hit hit;
            int h = vrg_world_pick(w, cam->position, dir, 512, &hit);
            float t = px(&img, x, y, 0);
            if (h != (t > 0)) {
                disagree++;
                continue;
            }
            if (h) {
                hits++;
                worst = fmax(worst, fabs(t - hit.distance) / hit.distance);
            }
        }
    CHECK(disagree <= (int)(img.width * img.height / 200), "%d pixels disagree on hit/miss", disagree);
    CHECK(hits > 1000, "only %d hits", hits);
    CHECK(worst < 1e-3, "ray-query distance differs by %.4f%%", worst * 100);
    free(img.pixels);
    vrg_graph_destroy(g);
    return 0;
}

/* traversal = rayquery is refused clearly, naming its line, where the device lacks it. */
static void test_traversal_errors(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = v\nwidth = 8\nheight = 8\n[scene]\nplugin = blocks\ntraversal = rtx\nbox = 0 0 0 1 1 1 red\n"
                       "[pass v]\nplugin = world_debug\nin.world = world\nin.frame = frame\nout.color = v\n";
    vrg_graph_desc d = {.path = "traversal.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(NULL, &d, &g);
    fclose(diag);
    CHECK(rc != 0 && strstr(buf, "traversal.ini:7: error[VRG-E047]: traversal = 'rtx': expected dda or rayquery"), "bad traversal message:\n%s", buf);
    free(buf);
    vrg_graph_destroy(g);
}

/* vrg_graph_set_camera refuses a position outside the world, naming the
 * parameter, and keeps the camera it had (check-only: no device needed). */
static void test_camera_range(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = g\nwidth = 8\nheight = 8\n[camera]\nposition = 1 40 2\n"
                       "[pass gen]\nplugin = pattern\nout.color = g\n";
    vrg_graph_desc d = {.path = "camera.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(NULL, &d, &g) == 0, "graph not loaded");
    if (g) {
        vrg_camera far = *vrg_graph_camera(g), nan_cam = far, edge = far;
        far.position[0] = 3e9f;
        nan_cam.position[2] = NAN;
        edge.position[1] = -VRG_WORLD_LIMIT;
        CHECK(vrg_graph_set_camera(g, &far) == -1, "3e9 accepted");
        CHECK(vrg_graph_set_camera(g, &nan_cam) == -1, "NaN accepted");
        CHECK(vrg_graph_camera(g)->position[0] == 1 && vrg_graph_camera(g)->position[2] == 2, "a refused camera was kept");
        CHECK(vrg_graph_set_camera(g, &edge) == 0, "the world's edge refused");
        CHECK(vrg_graph_camera(g)->position[1] == -VRG_WORLD_LIMIT, "the camera at the edge was not kept");
        vrg_graph_destroy(g);
    }
    fclose(diag);
    CHECK(buf && strstr(buf, "vrg_graph_set_camera: camera->position (3e+09, 40, 2) is outside the world"), "message:\n%s", buf ? buf : "");
    free(buf);
}

static const char *gbuffer_reads[] = {"gbuffer.position", "gbuffer.depth", "gbuffer.normal", "gbuffer.ids", "gbuffer.motion"};

/* Normals are unit axis vectors and equal the CPU pick ray's face; ids and
 * depth agree with it too; sky pixels are zero. */
static void test_gbuffer_normals(void)
{
    vrg_graph *g = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data n, depth, ids;
    CHECK(vrg_graph_read(g, "gbuffer.normal", &n) == 0 && vrg_graph_read(g, "gbuffer.depth", &depth) == 0 &&
              vrg_graph_read(g, "gbuffer.ids", &ids) == 0,
          "readback failed");
    const vrg_world *w = vrg_graph_world(g);
    const vrg_camera *cam = vrg_graph_camera(g);
    float fwd[3];
    vrg_camera_forward(cam, fwd);
    int not_axis = 0, wrong = 0, hits = 0, total = (int)(n.width * n.height);
    for (uint32_t y = 0; y < n.height; y++)
        for (uint32_t x = 0; x < n.width; x++) {
            float nx = px(&n, x, y, 0), ny = px(&n, x, y, 1), nz = px(&n, x, y, 2);
            float len = fabsf(nx) + fabsf(ny) + fabsf(nz);
            int axis = (nx != 0) + (ny != 0) + (nz != 0);
            float dir[3];
            vrg_camera_ray(cam, n.width, n.height, (float)x, (float)y, dir);
            vrg_world_hit hit;
            int h = vrg_world_pick(w, cam->position, dir, 1024, &hit);
            if (!h) {
                wrong += len != 0 || px(&ids, x, y, 0) != 0;
                continue;
            }
            hits++;
            not_axis += axis != 1 || len != 1;
            float want_depth = hit.distance * (dir[0] * fwd[0] + dir[1] * fwd[1] + dir[2] * fwd[2]);
            wrong += nx != (float)hit.normal[0] || ny != (float)hit.normal[1] || nz != (float)hit.normal[2] ||
                     px(&ids, x, y, 0) != (float)hit.id || fabsf(px(&depth, x, y, 0) - want_depth) > 1e-3f * want_depth;
        }
    CHECK(not_axis == 0, "%d normals are not unit axis vectors", not_axis);
    CHECK(wrong <= total / 200, "%d of %d pixels disagree with the CPU pick ray (normal, id, depth)", wrong, total);
    CHECK(hits > total / 3, "only %d hits", hits);
    free(n.pixels);
    free(depth.pixels);
    free(ids.pixels);
    vrg_graph_destroy(g);
}

/* Motion vectors: zero for a still camera; for a moving one, each surface
 * pixel minus where the previous camera saw that world point. */
static void test_gbuffer_motion(void)
{
    vrg_graph *g = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    if (!g)
        return;
    vrg_image_data m, pos;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0, "readback failed");
    double worst = 0;
    for (uint32_t i = 0; i < m.width * m.height; i++)
        worst = fmax(worst, fabs(m.pixels[i * 4]) + fabs(m.pixels[i * 4 + 1]));
    CHECK(worst < 0.02, "still camera: motion up to %g px", worst);
    free(m.pixels);

    vrg_camera before = *vrg_graph_camera(g), after = before;
    after.position[0] += 1.0f;
    after.yaw += 2.0f;
    vrg_graph_set_camera(g, &after);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0, "readback failed");
    float vp[16];
    vrg_camera_view_projection(&before, (float)m.width / (float)m.height, vp);
    int bad = 0, checked = 0;
    worst = 0;
    for (uint32_t y = 0; y < m.height; y++)
        for (uint32_t x = 0; x < m.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            float P[4] = {px(&pos, x, y, 0), px(&pos, x, y, 1), px(&pos, x, y, 2), 1}, c[4];
            for (int r = 0; r < 4; r++)
                c[r] = vp[r] * P[0] + vp[4 + r] * P[1] + vp[8 + r] * P[2] + vp[12 + r] * P[3];
            float prev_x = (c[0] / c[3] * 0.5f + 0.5f) * m.width - 0.5f, prev_y = (c[1] / c[3] * 0.5f + 0.5f) * m.height - 0.5f;
            double e = fabs(px(&m, x, y, 0) - ((float)x - prev_x)) + fabs(px(&m, x, y, 1) - ((float)y - prev_y));
            worst = fmax(worst, e);
            bad += e > 0.05;
            checked++;
        }
    CHECK(checked > 1000 && bad == 0, "moving camera: %d of %d motion vectors off (worst %g px)", bad, checked, worst);
    free(m.pixels);
    free(pos.pixels);

    /* a 150-degree turn: points behind the previous camera must not be
     * mirrored onto its screen, their previous pixel is far off screen */
    before.position[0] = before.position[2] = 16.0f; /* above the middle of the floor, looking down */
    before.position[1] = 10.0f;
    before.pitch = -50.0f;
    vrg_graph_set_camera(g, &before);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    after = before;
    after.yaw += 150.0f;
    vrg_graph_set_camera(g, &after);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0, "readback failed");
    vrg_camera_view_projection(&before, (float)m.width / (float)m.height, vp);
    int behind = 0, mirrored = 0;
    for (uint32_t y = 0; y < m.height; y++)
        for (uint32_t x = 0; x < m.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            float P[4] = {px(&pos, x, y, 0), px(&pos, x, y, 1), px(&pos, x, y, 2), 1};
            float w = vp[3] * P[0] + vp[7] * P[1] + vp[11] * P[2] + vp[15];
            if (w > 0)
                continue;
            behind++;
            float prev_x = (float)x - px(&m, x, y, 0), prev_y = (float)y - px(&m, x, y, 1);
            mirrored += prev_x > -1000 && prev_x < (float)m.width + 1000 && prev_y > -1000 && prev_y < (float)m.height + 1000;
        }
    CHECK(behind > 100 && mirrored == 0, "turn: %d of %d points behind the previous camera reproject onto its screen", mirrored, behind);
    free(m.pixels);
    free(pos.pixels);
    vrg_graph_destroy(g);
}

/* DDA and ray-query backends render the same G-buffer: same hit/miss per
 * pixel, depth within a small tolerance, same normals and ids. */
static int test_backends_agree(void)
{
    if (!vrg_context_device(ctx)->features.ray_query) {
        printf("backends_agree: skipped: device '%s' has no VK_KHR_ray_query\n", vrg_context_device(ctx)->name);
        return SKIP;
    }
    vrg_graph *a = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    vrg_graph *b = load_with("gbuffer_blocks_rq.ini", NULL, 0, gbuffer_reads, 5);
    if (!a || !b) {
        vrg_graph_destroy(a);
        vrg_graph_destroy(b);
        return 0;
    }
    CHECK(vrg_graph_frame(a) == 0 && vrg_graph_frame(b) == 0, "frame failed");
    vrg_image_data da, db, na, nb, ia, ib;
    CHECK(vrg_graph_read(a, "gbuffer.depth", &da) == 0 && vrg_graph_read(b, "gbuffer.depth", &db) == 0 && vrg_graph_read(a, "gbuffer.normal", &na) == 0 &&
              vrg_graph_read(b, "gbuffer.normal", &nb) == 0 && vrg_graph_read(a, "gbuffer.ids", &ia) == 0 && vrg_graph_read(b, "gbuffer.ids", &ib) == 0,
          "readback failed");
    int miss_mismatch = 0, other = 0, total = (int)(da.width * da.height);
    double worst = 0;
    for (int i = 0; i < total; i++) {
        int ha = da.pixels[i * 4] > 0, hb = db.pixels[i * 4] > 0;
        if (ha != hb) {
            miss_mismatch++;
            continue;
        }
        if (!ha)
            continue;
        worst = fmax(worst, fabs(da.pixels[i * 4] - db.pixels[i * 4]) / da.pixels[i * 4]);
        other += memcmp(na.pixels + i * 4, nb.pixels + i * 4, 3 * sizeof(float)) != 0 || ia.pixels[i * 4] != ib.pixels[i * 4] ||
                 ia.pixels[i * 4 + 1] != ib.pixels[i * 4 + 1];
    }
    CHECK(miss_mismatch <= total / 500, "%d pixels hit in one backend and miss in the other", miss_mismatch);
    CHECK(worst < 1e-3, "depth differs by %.4f%% between backends", worst * 100);
    CHECK(other <= total / 200, "%d pixels differ in normal or ids between backends", other);
    free(da.pixels), free(db.pixels), free(na.pixels), free(nb.pixels), free(ia.pixels), free(ib.pixels);
    vrg_graph_destroy(a);
    vrg_graph_destroy(b);
    return 0;
}

/* Mean of channel c of img over floor pixels (top faces at y = 1) within
 * r blocks of (x, z) in the plane; -1 when none is visible. */
static float floor_mean(const vrg_image_data *pos, const vrg_image_data *img, int c, float x, float z, float r, float *ratio_rg)
{
    double sum = 0, r_sum = 0, g_sum = 0;
    int n = 0;
    for (uint32_t i = 0; i < pos->width * pos->height; i++) {
        const float *p = pos->pixels + 4 * i;
        if (p[3] == 0 || fabsf(p[1] - 1.0f) > 1e-3f || fabsf(p[0] - x) > r || fabsf(p[2] - z) > r)
            continue;
        sum += img->pixels[4 * i + c];
        r_sum += img->pixels[4 * i];
        g_sum += img->pixels[4 * i + 1];
        n++;
    }
    if (ratio_rg)
        *ratio_rg = g_sum > 0 ? (float)(r_sum / g_sum) : 0;
    return n ? (float)(sum / n) : -1.0f;
}

/* Open flat floor: AO = 1 and sun visibility = 1 everywhere on it. */
static void test_light_floor(void)
{
    static const char *reads[] = {"gbuffer.position", "shadow.visibility", "ao.ao"};
    vrg_graph *g = load_with("light_floor.ini", NULL, 0, reads, 3);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data pos, vis, ao;
    CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "shadow.visibility", &vis) == 0 &&
              vrg_graph_read(g, "ao.ao", &ao) == 0,
          "readback failed");
    int floor = 0, dark = 0, occluded = 0;
    for (uint32_t i = 0; i < pos.width * pos.height; i++) {
        if (pos.pixels[4 * i + 3] == 0)
            continue;
        floor++;
        dark += vis.pixels[4 * i] != 1.0f;
        occluded += ao.pixels[4 * i] != 1.0f;
    }
    CHECK(floor > (int)(pos.width * pos.height) / 2, "only %d floor pixels", floor);
    CHECK(dark == 0 && occluded == 0, "open floor: %d pixels with sun visibility < 1, %d with AO < 1", dark, occluded);
    free(pos.pixels), free(vis.pixels), free(ao.pixels);
    vrg_graph_destroy(g);
}

/* Hard shadow of a wall of height 6: every floor pixel's visibility equals
 * the CPU pick ray toward the sun, and the shadow ends h * cot(elevation)
 * from the wall. */
static void test_light_wall(void)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.normal", "shadow.visibility"};
    vrg_graph *g = load_with("light_wall.ini", NULL, 0, reads, 3);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data pos, nrm, vis;
    CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "gbuffer.normal", &nrm) == 0 &&
              vrg_graph_read(g, "shadow.visibility", &vis) == 0,
          "readback failed");
    vrg_sky_desc sd;
    vrg_sky_default(&sd);
    sd.time_of_day = 13;
    vrg_sky sky;
    vrg_sky_eval(&sd, 0, &sky);
    const vrg_world *w = vrg_graph_world(g);
    int differ = 0, shadowed = 0, lit = 0;
    float edge_z = 1e9f;
    for (uint32_t i = 0; i < pos.width * pos.height; i++) {
        const float *p = pos.pixels + 4 * i, *n = nrm.pixels + 4 * i;
        if (p[3] == 0 || n[1] != 1.0f)
            continue;
        float o[3] = {p[0] + n[0] * 1e-3f, p[1] + n[1] * 1e-3f, p[2] + n[2] * 1e-3f};
        vrg_world_hit hit;
        int blocked = vrg_world_pick(w, o, sky.sun_dir, 256, &hit);
        float v = vis.pixels[4 * i];
        differ += (v == 0.0f) != blocked;
        if (v == 0.0f && p[0] > 12 && p[0] < 35) {
            shadowed++;
            edge_z = fminf(edge_z, p[2]);
        }
        lit += v == 1.0f;
    }
    CHECK(differ <= (int)(pos.width * pos.height) / 200, "%d floor pixels disagree with the CPU shadow ray", differ);
    CHECK(shadowed > 50 && lit > 500, "shadow not in view (%d shadowed, %d lit pixels)", shadowed, lit);
    /* the wall's near face is z = 30, height 6 above the floor top (y = 1 .. 7) */
    float want = 30.0f - 6.0f * sky.sun_dir[2] / sky.sun_dir[1];
    CHECK(fabsf(edge_z - want) < 0.5f, "shadow edge at z = %.2f, want %.2f (h cot e along the sun's azimuth)", edge_z, want);
    free(pos.pixels), free(nrm.pixels), free(vis.pixels);
    vrg_graph_destroy(g);
}

/* A ray pass at half the G-buffer's resolution reads the G-buffer pixel
 * under each of its pixels' centres: with hard shadows (deterministic), half
 * pixel (x, y) equals full pixel (2x + 1, 2y + 1), shadow edge included. */
static void test_light_half_res(void)
{
    static const char *reads[] = {"shadow.visibility", "half"};
    vrg_graph *g = load_with("light_half.ini", NULL, 0, reads, 2);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data full, half;
    CHECK(vrg_graph_read(g, "shadow.visibility", &full) == 0 && vrg_graph_read(g, "half", &half) == 0, "readback failed");
    CHECK(half.width * 2 == full.width && half.height * 2 == full.height, "half is %ux%u, full %ux%u", half.width, half.height, full.width,
          full.height);
    int differ = 0, shadowed = 0, lit = 0;
    for (uint32_t y = 0; y < half.height; y++)
        for (uint32_t x = 0; x < half.width; x++) {
            float v = px(&half, x, y, 0);
            differ += v != px(&full, 2 * x + 1, 2 * y + 1, 0);
            shadowed += v == 0.0f;
            lit += v == 1.0f;
        }
    CHECK(differ == 0, "%d half-resolution pixels differ from the full-resolution pixel under them", differ);
    CHECK(shadowed > 20 && lit > 100, "shadow not in view (%d shadowed, %d lit)", shadowed, lit);
    free(full.pixels), free(half.pixels);
    vrg_graph_destroy(g);
}

/* ---- SVGF ---- */

/* svgf_reproject's test of whether previous pixel t shows the surface at
 * x with normal n in chunk `chunk` (the shader's same_surface, defaults). */
static int svgf_same_surface(const vrg_image_data *ppos, const vrg_image_data *pnrm, const vrg_image_data *pids, int tx, int ty, const float *x,
                             const float *n, float chunk)
{
    if (tx < 0 || ty < 0 || tx >= (int)ppos->width || ty >= (int)ppos->height)
        return 0;
    if (px(ppos, tx, ty, 3) == 0 || px(pids, tx, ty, 1) != chunk)
        return 0;
    float d = px(pnrm, tx, ty, 0) * n[0] + px(pnrm, tx, ty, 1) * n[1] + px(pnrm, tx, ty, 2) * n[2];
    if (d < 0.9f)
        return 0;
    float plane = (px(ppos, tx, ty, 0) - x[0]) * n[0] + (px(ppos, tx, ty, 1) - x[1]) * n[1] + (px(ppos, tx, ty, 2) - x[2]) * n[2];
    return fabsf(plane) <= 0.05f;
}

/* A camera move uncovering the wall behind a pillar: history restarts
 * (length 0) exactly where svgf_reproject's disocclusion tests fail, as
 * recomputed here from both frames' G-buffers; and with the noise-free
 * albedo as the signal, every pixel keeps its own surface's colour: no
 * ghost of the pillar on the wall. */
static void test_svgf_disocclusion(void)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.normal", "gbuffer.ids", "gbuffer.motion", "gbuffer.albedo", "reproject.color",
                                  "reproject.length"};
    vrg_graph *g = load_with("svgf_ghost.ini", NULL, 0, reads, 7);
    if (!g)
        return;
    vrg_image_data ppos, pnrm, pids, pos, nrm, ids, mot, alb, col, len;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.position", &ppos) == 0 && vrg_graph_read(g, "gbuffer.normal", &pnrm) == 0 &&
              vrg_graph_read(g, "gbuffer.ids", &pids) == 0,
          "readback failed");
    vrg_camera cam = *vrg_graph_camera(g);
    cam.position[0] += 3.0f; /* sideways: the wall behind the pillar comes into view */
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "gbuffer.normal", &nrm) == 0 &&
              vrg_graph_read(g, "gbuffer.ids", &ids) == 0 && vrg_graph_read(g, "gbuffer.motion", &mot) == 0 &&
              vrg_graph_read(g, "gbuffer.albedo", &alb) == 0 && vrg_graph_read(g, "reproject.color", &col) == 0 &&
              vrg_graph_read(g, "reproject.length", &len) == 0,
          "readback failed");
    int wrong_reset = 0, ghosts = 0, restarted = 0, kept = 0;
    for (uint32_t y = 0; y < pos.height; y++)
        for (uint32_t xx = 0; xx < pos.width; xx++) {
            if (px(&pos, xx, y, 3) == 0)
                continue;
            float x[3] = {px(&pos, xx, y, 0), px(&pos, xx, y, 1), px(&pos, xx, y, 2)};
            float n[3] = {px(&nrm, xx, y, 0), px(&nrm, xx, y, 1), px(&nrm, xx, y, 2)};
            float chunk = px(&ids, xx, y, 1);
            float qx = (float)xx - px(&mot, xx, y, 0), qy = (float)y - px(&mot, xx, y, 1);
            int q0x = (int)floorf(qx), q0y = (int)floorf(qy);
            float fx = qx - (float)q0x, fy = qy - (float)q0y, wsum = 0;
            for (int i = 0; i < 4; i++) {
                int ox = i & 1, oy = i >> 1;
                float w = (ox ? fx : 1 - fx) * (oy ? fy : 1 - fy);
                if (w > 0 && svgf_same_surface(&ppos, &pnrm, &pids, q0x + ox, q0y + oy, x, n, chunk))
                    wsum += w;
            }
            if (wsum < 1e-4f) {
                int rx = (int)floorf(qx + 0.5f), ry = (int)floorf(qy + 0.5f);
                wsum = 0;
                for (int i = 0; i < 9; i++)
                    wsum += (float)svgf_same_surface(&ppos, &pnrm, &pids, rx + i % 3 - 1, ry + i / 3 - 1, x, n, chunk);
            }
            int want_reset = wsum < 1e-4f, reset = px(&len, xx, y, 0) == 0;
            wrong_reset += want_reset != reset;
            restarted += want_reset;
            kept += !want_reset;
            for (int c = 0; c < 3; c++)
                ghosts += fabsf(px(&col, xx, y, c) - px(&alb, xx, y, c)) > 0.01f;
        }
    CHECK(restarted > 30 && kept > 2000, "the move uncovers too little (%d restarted, %d kept)", restarted, kept);
    printf("svgf_disocclusion: %d restarted, %d kept, %d disagree\n", restarted, kept, wrong_reset);
    CHECK(wrong_reset <= 2, "%d pixels restart where the disocclusion tests say otherwise (%d restarted)", wrong_reset, restarted);
    CHECK(ghosts == 0, "%d colour channels differ from the pixel's own surface: a ghost survived", ghosts);
    vrg_image_data *all[] = {&ppos, &pnrm, &pids, &pos, &nrm, &ids, &mot, &alb, &col, &len};
    for (unsigned i = 0; i < sizeof all / sizeof all[0]; i++)
        free(all[i]->pixels);
    vrg_graph_destroy(g);
}

/* Mean squared error of colour images a and b over all pixels and channels. */
static double mse_rgb(const vrg_image_data *a, const vrg_image_data *b)
{
    double e = 0;
    for (uint32_t i = 0; i < a->width * a->height; i++)
        for (int c = 0; c < 3; c++) {
            double d = (double)a->pixels[4 * i + c] - b->pixels[4 * i + c];
            e += d * d;
        }
    return e / (3.0 * a->width * a->height);
}

/* Still camera, 4 rays per pass: after 16 frames the SVGF output (paper
 * settings) is far closer to the converged reference (1024 samples per
 * pixel, another seed) than the raw frame. Measured on lavapipe: raw MSE
 * 3.83e-3, denoised 1.27e-3 (3.0x); asserted: at least 2x. */
static void test_svgf_mse(void)
{
    static const char *reads[] = {"raw.color", "denoised.color"}, *ref_reads[] = {"converge.color"};
    vrg_graph *g = load_with("svgf_blocks.ini", NULL, 0, reads, 2);
    vrg_graph *r = load_with("svgf_blocks_ref.ini", NULL, 0, ref_reads, 1);
    if (!g || !r)
        return;
    CHECK(vrg_graph_subframes(g) == 1 && vrg_graph_subframes(r) == 128, "subframes %u and %u, want 1 and 128", vrg_graph_subframes(g),
          vrg_graph_subframes(r));
    for (int i = 0; i < 16; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    for (uint32_t i = 0; i < vrg_graph_subframes(r); i++)
        CHECK(vrg_graph_frame(r) == 0, "reference frame failed");
    vrg_image_data raw, den, ref;
    CHECK(vrg_graph_read(g, "raw.color", &raw) == 0 && vrg_graph_read(g, "denoised.color", &den) == 0 &&
              vrg_graph_read(r, "converge.color", &ref) == 0,
          "readback failed");
    CHECK(px(&ref, 10, 60, 3) == 128.0f, "the reference averaged %g frames, want 128", px(&ref, 10, 60, 3));
    double e_raw = mse_rgb(&raw, &ref), e_den = mse_rgb(&den, &ref);
    printf("svgf_mse: raw %.3g, denoised %.3g (%.2fx)\n", e_raw, e_den, e_raw / e_den);
    CHECK(e_den * 2.0 < e_raw, "denoised MSE %.3g is not half the raw %.3g", e_den, e_raw);
    free(raw.pixels), free(den.pixels), free(ref.pixels);
    vrg_graph_destroy(g);
    vrg_graph_destroy(r);
}

/* History is cleared and flagged invalid: after a resize, after
 * vrg_graph_reset_history and in a freshly loaded graph every pixel's
 * history length is 0 again. */
static void test_svgf_history_reset(void)
{
    static const char *reads[] = {"reproject.length"};
    vrg_graph *g = load_with("svgf_blocks.ini", NULL, 0, reads, 1);
    if (!g)
        return;
    vrg_image_data len;
    for (int step = 0; step < 4; step++) {
        if (step == 1)
            CHECK(vrg_graph_resize(g, 120, 80) == 0, "resize failed");
        if (step == 2)
            vrg_graph_reset_history(g);
        if (step == 3) { /* reload */
            vrg_graph_destroy(g);
            g = load_with("svgf_blocks.ini", NULL, 0, reads, 1);
            if (!g)
                return;
        }
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_read(g, "reproject.length", &len) == 0, "readback failed");
        int nonzero = 0;
        for (uint32_t i = 0; i < len.width * len.height; i++)
            nonzero += len.pixels[4 * i] != 0;
        CHECK(nonzero == 0, "step %d: %d pixels kept history", step, nonzero);
        free(len.pixels);
        /* and history builds up again on the next frames */
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_read(g, "reproject.length", &len) == 0, "readback failed");
        int two = 0;
        for (uint32_t i = 0; i < len.width * len.height; i++)
            two += len.pixels[4 * i] == 2;
        CHECK(two > (int)(len.width * len.height) / 4, "step %d: only %d pixels have 2 frames of history", step, two);
        free(len.pixels);
    }
    vrg_graph_destroy(g);
}

static double luminance_of(const vrg_image_data *img, int x, int y)
{
    return 0.2126 * px(img, x, y, 0) + 0.7152 * px(img, x, y, 1) + 0.0722 * px(img, x, y, 2);
}

/* svgf_variance against a CPU computation on the same inputs: spatial mode
 * (7x7 non-sky window, Bessel's correction) and temporal mode both while
 * the history is young (the same-surface window average of the moments)
 * and once it holds 4 frames (m2 - m1^2). */
static void test_svgf_variance(void)
{
    static const char *reads[] = {"reproject.color", "reproject.moments", "reproject.length", "gbuffer.position", "gbuffer.normal",
                                  "variance.color"};
    for (int mode = 0; mode < 2; mode++) {
        const char *sets[] = {mode ? "variance.mode=temporal" : "variance.mode=spatial"};
        vrg_graph *g = load_with("svgf_blocks.ini", sets, 1, reads, 6);
        if (!g)
            return;
        for (int round = 0; round < 2; round++) {
            int frames = round ? 4 : 2; /* 2 frames: length 1 (young); 6 in all: length 5 */
            for (int i = 0; i < frames; i++)
                CHECK(vrg_graph_frame(g) == 0, "frame failed");
            vrg_image_data col, mom, len, pos, nrm, var;
            CHECK(vrg_graph_read(g, "reproject.color", &col) == 0 && vrg_graph_read(g, "reproject.moments", &mom) == 0 &&
                      vrg_graph_read(g, "reproject.length", &len) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0 &&
                      vrg_graph_read(g, "gbuffer.normal", &nrm) == 0 && vrg_graph_read(g, "variance.color", &var) == 0,
                  "readback failed");
            int w = (int)col.width, h = (int)col.height, bad = 0, checked = 0, young = 0;
            double worst = 0;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    double want = 0, float_err = 1e-6; /* what float sums of this size may lose */
                    if (px(&pos, x, y, 3) != 0) {
                        if (mode == 0) {
                            double s1 = 0, s2 = 0, n = 0;
                            for (int dy = -3; dy <= 3; dy++)
                                for (int dx = -3; dx <= 3; dx++) {
                                    int qx = x + dx, qy = y + dy;
                                    if (qx < 0 || qy < 0 || qx >= w || qy >= h || px(&pos, qx, qy, 3) == 0)
                                        continue;
                                    double l = luminance_of(&col, qx, qy);
                                    s1 += l, s2 += l * l, n++;
                                }
                            want = n > 1.5 ? fmax(0.0, (s2 - s1 * s1 / n) / (n - 1)) : 0;
                            float_err += 1e-7 * s2; /* S2 - S1^2/n cancels */
                        } else {
                            double m1, m2;
                            if (px(&len, x, y, 0) + 1 >= 4) {
                                m1 = px(&mom, x, y, 0), m2 = px(&mom, x, y, 1);
                            } else {
                                young++;
                                double a = 0, b = 0, n = 0;
                                for (int dy = -3; dy <= 3; dy++)
                                    for (int dx = -3; dx <= 3; dx++) {
                                        int qx = x + dx, qy = y + dy;
                                        if (qx < 0 || qy < 0 || qx >= w || qy >= h || px(&pos, qx, qy, 3) == 0)
                                            continue;
                                        double d = 0, plane = 0;
                                        for (int c = 0; c < 3; c++) {
                                            d += px(&nrm, qx, qy, c) * px(&nrm, x, y, c);
                                            plane += (px(&pos, qx, qy, c) - px(&pos, x, y, c)) * px(&nrm, x, y, c);
                                        }
                                        if (d < 0.9 || fabs(plane) > 0.1 * (abs(dx) > abs(dy) ? abs(dx) : abs(dy)))
                                            continue;
                                        a += px(&mom, qx, qy, 0), b += px(&mom, qx, qy, 1), n++;
                                    }
                                m1 = a / n, m2 = b / n;
                            }
                            want = fmax(0.0, m2 - m1 * m1);
                            float_err += 1e-4 * m2; /* m2 - m1^2 cancels */
                        }
                    }
                    double got = px(&var, x, y, 3), err = fabs(got - want);
                    /* half-float output; float sums in another order */
                    double tol = 2e-3 * want + float_err;
                    worst = fmax(worst, err);
                    if (err > tol && bad < 3)
                        fprintf(stderr, "  (%d, %d): gpu %.6g cpu %.6g\n", x, y, got, want);
                    bad += err > tol;
                    checked += want > 1e-4;
                }
            CHECK(bad == 0, "mode %s, %d frames: %d pixels differ from the CPU variance (worst %g)", sets[0], round ? 6 : 2, bad, worst);
            CHECK(checked > 1000, "mode %s: only %d pixels with variance", sets[0], checked);
            if (mode == 1)
                CHECK(round ? young == 0 : young > 1000, "temporal, %d frames: %d young pixels", round ? 6 : 2, young);
            vrg_image_data *all[] = {&col, &mom, &len, &pos, &nrm, &var};
            for (int i = 0; i < 6; i++)
                free(all[i]->pixels);
        }
        vrg_graph_destroy(g);
    }
}

/* The hard shadow edge of a wall under noisy AO and indirect light: after
 * filtering it stays within 2 pixels of the edge in the accumulated mean,
 * column by column. */
static void test_svgf_edge(void)
{
    static const char *reads[] = {"atrous.color", "converge.color", "gbuffer.normal"};
    vrg_graph *g = load_with("svgf_edge.ini", NULL, 0, reads, 3);
    if (!g)
        return;
    for (int i = 0; i < 32; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data den, ref, nrm;
    CHECK(vrg_graph_read(g, "atrous.color", &den) == 0 && vrg_graph_read(g, "converge.color", &ref) == 0 &&
              vrg_graph_read(g, "gbuffer.normal", &nrm) == 0,
          "readback failed");
    int w = (int)ref.width, h = (int)ref.height, columns = 0, off = 0, worst = 0;
    for (int x = 0; x < w; x++) {
        /* the floor's run of this column, its darkest and brightest levels in the reference */
        double lo = 1e9, hi = -1e9;
        for (int y = 0; y < h; y++)
            if (px(&nrm, x, y, 1) == 1.0f) {
                lo = fmin(lo, luminance_of(&ref, x, y));
                hi = fmax(hi, luminance_of(&ref, x, y));
            }
        if (hi - lo < 0.5 * hi) /* no shadow in this column */
            continue;
        double t = 0.5 * (lo + hi);
        int edge_ref = -1, edge_den = -1, crossings = 0;
        for (int y = 0; y + 1 < h; y++) {
            if (px(&nrm, x, y, 1) != 1.0f || px(&nrm, x, y + 1, 1) != 1.0f)
                continue;
            if ((luminance_of(&ref, x, y) - t) * (luminance_of(&ref, x, y + 1) - t) < 0) {
                crossings++;
                if (edge_ref < 0)
                    edge_ref = y;
            }
            if (edge_den < 0 && (luminance_of(&den, x, y) - t) * (luminance_of(&den, x, y + 1) - t) < 0)
                edge_den = y;
        }
        if (crossings != 1) /* only clean edges */
            continue;
        columns++;
        int d = edge_den < 0 ? h : abs(edge_den - edge_ref);
        worst = d > worst ? d : worst;
        off += d > 2;
    }
    printf("svgf_edge: %d columns, %d off by more than 2 px, worst %d\n", columns, off, worst);
    CHECK(columns > 20, "only %d columns show a clean shadow edge", columns);
    CHECK(off <= columns / 20, "%d of %d columns have the filtered edge more than 2 px from the reference's (worst %d)", off, columns, worst);
    free(den.pixels), free(ref.pixels), free(nrm.pixels);
    vrg_graph_destroy(g);
}

/* accumulate: the running mean of frames n = 1..N is (N + 1) / 2 with N in
 * alpha; a camera move restarts it at this frame's value; max_frames turns
 * it into a moving average; samples_per_frame reaches hosts as subframes. */
static void test_accumulate_mean(void)
{
    static const char *reads[] = {"mean.color"};
    vrg_graph *g = load_with("progressive.ini", NULL, 0, reads, 1);
    if (!g)
        return;
    CHECK(vrg_graph_subframes(g) == 1, "subframes %u, want 1", vrg_graph_subframes(g));
    vrg_image_data img;
    for (int n = 1; n <= 6; n++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_read(g, "mean.color", &img) == 0, "readback failed");
        CHECK(px(&img, 3, 5, 0) == (n + 1) / 2.0f && px(&img, 3, 5, 3) == (float)n, "frame %d: mean %g over %g frames, want %g over %d", n,
              px(&img, 3, 5, 0), px(&img, 3, 5, 3), (n + 1) / 2.0, n);
        free(img.pixels);
    }
    vrg_camera cam = *vrg_graph_camera(g);
    cam.yaw += 1.0f;
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
    CHECK(px(&img, 3, 5, 0) == 7.0f && px(&img, 3, 5, 3) == 1.0f, "after a camera move: %g over %g frames, want 7 over 1", px(&img, 3, 5, 0),
          px(&img, 3, 5, 3));
    free(img.pixels);
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
    CHECK(px(&img, 3, 5, 0) == 7.5f && px(&img, 3, 5, 3) == 2.0f, "still again: %g over %g frames, want 7.5 over 2", px(&img, 3, 5, 0),
          px(&img, 3, 5, 3));
    free(img.pixels);
    vrg_graph_destroy(g);

    static const char *sets[] = {"mean.max_frames=2", "mean.samples_per_frame=5"};
    g = load_with("progressive.ini", sets, 2, reads, 1);
    if (!g)
        return;
    CHECK(vrg_graph_subframes(g) == 5, "subframes %u, want 5", vrg_graph_subframes(g));
    float want = 1; /* n = 1; then mean += (n - mean) / 2 */
    for (int n = 1; n <= 4; n++) {
        if (n > 1)
            want += ((float)n - want) / 2.0f;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
        CHECK(fabsf(px(&img, 3, 5, 0) - want) < 1e-6f, "max_frames 2, frame %d: %g, want %g", n, px(&img, 3, 5, 0), want);
        free(img.pixels);
    }
    vrg_graph_destroy(g);
}

/* svgf_atrous's options: feedback 0 is the unfiltered input, feedback =
 * iterations is the output; a variance threshold above every pixel's copies
 * the input through; the 3x3 kernel filters too. */
static void test_svgf_atrous_options(void)
{
    static const char *reads[] = {"variance.color", "atrous.color", "atrous.feedback"};
    struct {
        const char *sets[3];
        int expect; /* 0: feedback == input; 1: feedback == output; 2: output == input; 3: output != input */
    } cases[] = {
        {{"atrous.feedback=0", "atrous.iterations=3", "atrous.kernel=5"}, 0},
        {{"atrous.feedback=2", "atrous.iterations=2", "atrous.kernel=5"}, 1},
        {{"atrous.skip_variance=1000000", "atrous.iterations=3", "atrous.kernel=3"}, 2},
        {{"atrous.feedback=1", "atrous.iterations=3", "atrous.kernel=3"}, 3},
    };
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        vrg_graph *g = load_with("svgf_blocks.ini", cases[c].sets, 3, reads, 3);
        if (!g)
            return;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data in, out, fb;
        CHECK(vrg_graph_read(g, "variance.color", &in) == 0 && vrg_graph_read(g, "atrous.color", &out) == 0 &&
                  vrg_graph_read(g, "atrous.feedback", &fb) == 0,
              "readback failed");
        const vrg_image_data *a = cases[c].expect == 1 ? &out : cases[c].expect == 0 ? &in : &out;
        const vrg_image_data *b = cases[c].expect == 0 || cases[c].expect == 1 ? &fb : &in;
        int differ = 0;
        for (uint32_t i = 0; i < 4 * in.width * in.height; i++)
            differ += a->pixels[i] != b->pixels[i];
        if (cases[c].expect == 3)
            CHECK(differ > (int)(in.width * in.height), "case %u (%s): the 3x3 filter changed only %d values", c, cases[c].sets[2], differ);
        else
            CHECK(differ == 0, "case %u (%s, %s): %d values differ", c, cases[c].sets[0], cases[c].sets[1], differ);
        free(in.pixels), free(out.pixels), free(fb.pixels);
        vrg_graph_destroy(g);
    }
    /* feedback from an intermediate iteration (packed texels, the thesis's
     * and the paper's setting) equals the output of a filter that stops there */
    const char *three[] = {"atrous.feedback=1", "atrous.iterations=3", "atrous.kernel=5"};
    const char *one[] = {"atrous.feedback=1", "atrous.iterations=1", "atrous.kernel=5"};
    vrg_graph *g3 = load_with("svgf_blocks.ini", three, 3, reads, 3), *g1 = load_with("svgf_blocks.ini", one, 3, reads, 3);
    if (g3 && g1) {
        vrg_image_data fb3 = {0}, out1 = {0};
        CHECK(vrg_graph_frame(g3) == 0 && vrg_graph_frame(g1) == 0, "frame failed");
        CHECK(vrg_graph_read(g3, "atrous.feedback", &fb3) == 0 && vrg_graph_read(g1, "atrous.color", &out1) == 0, "readback failed");
        int differ = 0, filtered = 0;
        for (uint32_t i = 0; fb3.pixels && out1.pixels && i < 4 * fb3.width * fb3.height; i++)
            /* packHalf2x16 and a rgba16f store may round a half ulp apart */
            differ += fabsf(fb3.pixels[i] - out1.pixels[i]) > fabsf(out1.pixels[i]) * (1.0f / 1024) + 1e-6f;
        vrg_image_data in = {0};
        if (vrg_graph_read(g1, "variance.color", &in) == 0)
            for (uint32_t i = 0; i < 4 * in.width * in.height; i++)
                filtered += in.pixels[i] != out1.pixels[i];
        CHECK(differ == 0, "feedback after iteration 1 of 3 differs from a 1-iteration output in %d values (beyond a half ulp)", differ);
        CHECK(filtered > (int)(in.width * in.height), "one iteration changed only %d values", filtered);
        free(fb3.pixels), free(out1.pixels), free(in.pixels);
    }
    vrg_graph_destroy(g3);
    vrg_graph_destroy(g1);
}

/* An SVGF input at another size than the output is an error naming it,
 * not a silently wrong reprojection. */
static void test_svgf_size_mismatch(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = r.color\nwidth = 16\nheight = 16\n[scene]\nplugin = blocks\nbox = 0 0 0 7 0 7 white\n"
                       "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n"
                       "[pass half]\nplugin = pattern\nout.color = small\n[resource small]\nscale = 0.5\n"
                       "[pass r]\nplugin = svgf_reproject\nin.illumination = small\nin.motion = gbuffer.motion\n"
                       "in.position = gbuffer.position\nin.normal = gbuffer.normal\nin.ids = gbuffer.ids\nin.history = r.color@prev\n"
                       "in.prev_moments = r.moments@prev\nin.prev_length = r.length@prev\nin.prev_position = gbuffer.position@prev\n"
                       "in.prev_normal = gbuffer.normal@prev\nin.prev_ids = gbuffer.ids@prev\n";
    vrg_graph_desc d = {.path = "size.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(ctx, &d, &g);
    int frame_rc = rc == 0 ? vrg_graph_frame(g) : 0;
    fclose(diag);
    CHECK(rc == 0 && frame_rc != 0 && strstr(buf, "input 'illumination' is 8x8, 'color' 16x16"), "size mismatch not reported:\n%s", buf);
    free(buf);
    vrg_graph_destroy(g);
}

/* Writes text to path the way editors save: a new file renamed over the old. */
static void save_file(const char *path, const char *text)
{
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return;
    fputs(text, f);
    fclose(f);
    rename(tmp, path);
}

static const char *user_shader =
    "#version 450\n#include \"tint.glsl\"\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
    "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(TINT, 1.0)); }\n";

/* How a dispatch is sized. A shader's local size is read from the SPIR-V
 * whichever way glslang writes it (an 8x8 shader that does not use
 * gl_WorkGroupSize gets LocalSizeId: it was once read as 1x1 and dispatched
 * 64 times over). A pixel loop covers every pixel with the device's
 * tiles, also where the size is no multiple of them; a pixel loop with
 * another local size is refused with an error naming the shader. */
static void test_dispatch_shape(void)
{
    char dir[] = "/tmp/voxrg-shape-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char user[1100];
    snprintf(user, sizeof user, "%s/user.comp", dir);
    setenv("VOXRG_SHADER_PATH", dir, 1);
    static const char *shaders[] = {
        "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\nlayout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(gl_NumWorkGroups.xy, 0.0, 1.0)); }\n",
        "#version 450\n#include \"pixel.glsl\"\nlayout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;\n"
        "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void shade(ivec2 p) { if (all(lessThan(p, imageSize(dst)))) imageStore(dst, p, vec4(p, 1.0, 0.0)); }\n"
        "void main() { for (uint k = 0u; k < VRG_PIXEL_ROWS; k++) shade(vrg_pixel(k)); }\n",
        "#version 450\n#include \"pixel.glsl\"\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
        "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void shade(ivec2 p) { imageStore(dst, p, vec4(1.0)); }\nvoid main() { shade(vrg_pixel(0u)); }\n",
    };
    for (int c = 0; c < 3; c++) {
        save_file(user, shaders[c]);
        char text[512];
        snprintf(text, sizeof text, "[graph]\noutput = color\nwidth = %d\nheight = %d\n[pass user]\nplugin = shader_file\nout.color = color\npixel_loop = %d\n",
                 c ? 13 : 16, c ? 11 : 16, c > 0);
        char *log = NULL;
        size_t len = 0;
        FILE *diag = open_memstream(&log, &len);
        vrg_graph_desc d = {.path = "shape.ini", .text = text, .diag = diag};
        vrg_graph *g = NULL;
        int rc = vrg_graph_load(ctx, &d, &g);
        CHECK(rc == 0, "case %d: load failed", c);
        int frame_rc = rc == 0 ? vrg_graph_frame(g) : -1;
        fclose(diag);
        vrg_image_data img = {0};
        if (c < 2 && frame_rc == 0 && vrg_graph_read(g, "color", &img) == 0) {
            int bad = 0;
            for (uint32_t y = 0; y < img.height; y++)
                for (uint32_t x = 0; x < img.width; x++) {
                    float want[3] = {c ? (float)x : 2.0f, c ? (float)y : 2.0f, c ? 1.0f : 0.0f};
                    int wrong = 0;
                    for (int k = 0; k < 3; k++)
                        wrong |= px(&img, x, y, k) != want[k];
                    if (wrong && !bad++) /* the first wrong pixel */
                        CHECK(0, "case %d: pixel %u,%u is %g %g %g, want %g %g %g", c, x, y, px(&img, x, y, 0), px(&img, x, y, 1), px(&img, x, y, 2),
                              want[0], want[1], want[2]);
                }
            free(img.pixels);
        } else if (c < 2)
            CHECK(0, "case %d: the frame failed:\n%s", c, log ? log : "");
        else
            CHECK(frame_rc != 0 && log && strstr(log, "pixel_loop dispatch of user.comp: local size 8x8x1"), "case 2: no error:\n%s", log ? log : "");
        free(log);
        vrg_graph_destroy(g);
    }
    unsetenv("VOXRG_SHADER_PATH");
    remove(user), rmdir(dir);
}

/* Hot reload of shaders: a saved shader (or a file it #includes) is in use
 * on the next frame; a broken one is reported with FILE:LINE while the last
 * good pipeline keeps rendering; fixing it brings the new version. */
static void test_hot_reload_shader(void)
{
    char dir[] = "/tmp/voxrg-reload-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char user[1100], tint[1100];
    snprintf(user, sizeof user, "%s/user.comp", dir);
    snprintf(tint, sizeof tint, "%s/tint.glsl", dir);
    save_file(user, user_shader);
    save_file(tint, "#define TINT vec3(0.25, 0.5, 0.75)\n");
    setenv("VOXRG_SHADER_PATH", dir, 1);
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/shader_file.ini", TEST_DIR);
    static const char *reads[] = {"color"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load shader_file.ini");
        fclose(diag);
        free(log);
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    float want[4][3] = {{0.25f, 0.5f, 0.75f}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (int step = 0; step < 4; step++) {
        if (step == 1) /* the included file changes */
            save_file(tint, "#define TINT vec3(1.0, 0.0, 0.0)\n");
        if (step == 2) /* a syntax error in the main file */
            save_file(user, "#version 450\nlayout(local_size_x = 8) in;\nvoid main() { this is not glsl }\n");
        if (step == 3) { /* fixed again, and a new colour */
            save_file(user, user_shader);
            save_file(tint, "#define TINT vec3(0.0, 1.0, 0.0)\n");
        }
        CHECK(vrg_graph_frame(g) == 0, "step %d: the frame failed: a reload must not stop the graph", step);
        CHECK(vrg_graph_read(g, "color", &img) == 0, "readback failed");
        for (int c = 0; c < 3; c++)
            CHECK(fabsf(px(&img, 5, 7, c) - want[step][c]) < 1e-3f, "step %d: channel %d is %g, want %g", step, c, px(&img, 5, 7, c),
                  want[step][c]);
        free(img.pixels);
        const char *err = vrg_graph_reload_error(g);
        if (step == 2) {
            fflush(diag);
            CHECK(err && strstr(err, "user.comp:3: error"), "no FILE:LINE reload error: %s", err ? err : "(none)");
            CHECK(log && strstr(log, "user.comp:3: error"), "the error was not printed: %s", log ? log : "");
        } else
            CHECK(!err, "step %d: unexpected reload error %s", step, err);
        if (step == 1 || step == 3)
            CHECK(vrg_graph_reload_ms(g) >= 0 && vrg_graph_reload_ms(g) < 60000, "step %d: reload time %g ms", step, vrg_graph_reload_ms(g));
    }
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    unsetenv("VOXRG_SHADER_PATH");
    remove(user), remove(tint), rmdir(dir);
}

/* variant 0: as loaded; 1: an unrelated pass added (structural, every
 * history resource keeps its name); 2: the counter's resource renamed */
static const char *reload_graph_text(float step, int variant, int broken)
{
    static char text[1024];
    const char *count = variant == 2 ? "total" : "count";
    snprintf(text, sizeof text,
             "[graph]\noutput = mean.color\nwidth = 8\nheight = 8\n"
             "[pass counter]\nplugin = counter\nin.prev = %s@prev\nout.count = %s\nstep = %g\n"
             "[pass mean]\nplugin = accumulate\nin.src = %s\nin.history = mean.color@prev\n%s%s",
             count, count, step, count, variant == 1 ? "[pass other]\nplugin = counter\nout.count = other\n" : "",
             broken ? "this line is not ini\n" : "");
    return text;
}

/* Hot reload of the graph file: a parameter-only change keeps history (the
 * counter continues) and restarts accumulations; a structural change keeps
 * the history resources whose name, format and size are unchanged and
 * starts the others anew; a broken file leaves the running graph as it was,
 * with the error kept at FILE:LINE. */
static void test_hot_reload_graph(void)
{
    char dir[] = "/tmp/voxrg-graph-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100];
    snprintf(path, sizeof path, "%s/reload.ini", dir);
    save_file(path, reload_graph_text(1, 0, 0));
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    static const char *reads[] = {"mean.color"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load the reload graph");
        fclose(diag);
        free(log);
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    /* each step: the file saved before it, then one frame that notices the
     * save (still the old graph), the reload, and one frame read back */
    struct {
        float step;
        int variant, broken;
        float mean, frames;
    } steps[] = {
        {1, 0, 0, 2, 3},  /* frames 1..3 as loaded: counts 1 2 3 */
        {2, 0, 0, 6, 1},  /* parameters only: 4 (noticing), then 4 + 2 = 6 kept going; the mean restarts */
        {2, 1, 0, 10, 1}, /* a pass added: 8 (noticing), the count kept: 10; the mean restarts */
        {2, 2, 0, 2, 1},  /* the count renamed: its history starts anew: 2 */
        {5, 2, 1, 4, 3},  /* broken: the running graph goes on: 4, 6, mean of 2 4 6 */
    };
    int step_count = (int)(sizeof steps / sizeof steps[0]);
    for (int s = 0; s < step_count; s++) {
        if (s > 0) {
            save_file(path, reload_graph_text(steps[s].step, steps[s].variant, steps[s].broken));
            CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices the save */
            CHECK(vrg_graph_source_changed(g), "step %d: the save was not noticed", s);
            int rc = vrg_graph_reload(&g);
            CHECK((rc == 0) == !steps[s].broken, "step %d: reload returned %d", s, rc);
            if (steps[s].broken) {
                const char *err = vrg_graph_reload_error(g);
                CHECK(err && strstr(err, "reload.ini:14: error"), "no FILE:LINE error for the broken graph: %s", err ? err : "(none)");
            }
        } else
            for (int i = 0; i < 2; i++)
                CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "step %d: frame failed", s);
        CHECK(px(&img, 2, 3, 0) == steps[s].mean && px(&img, 2, 3, 3) == steps[s].frames, "step %d: mean %g over %g frames, want %g over %g",
              s, px(&img, 2, 3, 0), px(&img, 2, 3, 3), steps[s].mean, steps[s].frames);
        free(img.pixels);
    }
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    remove(path), rmdir(dir);
}

static const char *reloadme_source =
    "#include <stdlib.h>\n#include <string.h>\n#include \"voxrg/plugin.h\"\n"
    "static const vrg_slot_desc slots[] = {{.name = \"color\", .dir = VRG_OUT, .kind = VRG_IMAGE,\n"
    "    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};\n"
    "typedef struct { int frames; } state;\n"
    "static int create(vrg_pass *p) { vrg_pass_set_user(p, calloc(1, sizeof(state))); return 0; }\n"
    "static void destroy(vrg_pass *p) { free(vrg_pass_user(p)); }\n"
    "static void execute(vrg_pass *p, VkCommandBuffer cmd) {\n"
    "    state *s = vrg_pass_user(p);\n    s->frames++;\n"
    "    float pc[4] = {VERSION == 1, VERSION == 2, s->frames / 100.0f, 1};\n"
    "    (void)vrg_dispatch(p, cmd, &(vrg_dispatch_desc){.shader = \"reloadme.comp\", .push = pc, .push_size = sizeof pc});\n}\n"
    "static size_t save(vrg_pass *p, void *dst, size_t cap) {\n"
    "#ifdef SAVE_TOO_MUCH\n    (void)p, (void)dst;\n    return cap + 1;\n#endif\n"
    "    if (cap < sizeof(state)) return 0;\n    memcpy(dst, vrg_pass_user(p), sizeof(state));\n    return sizeof(state);\n}\n"
    "static int restore(vrg_pass *p, const void *src, size_t n) {\n"
    "    if (n != sizeof(state)) return -1;\n    memcpy(vrg_pass_user(p), src, n);\n    return 0;\n}\n"
    "#ifndef NAME\n#define NAME \"reloadme\"\n#endif\n"
    "static const vrg_plugin_desc desc = {.abi_version = ABI, .name = NAME, .kind = VRG_PLUGIN_PASS,\n"
    "    .help = \"test: hot reload\", .shader_dir = DIR, .slots = slots, .slot_count = 1, .create = create,\n"
    "    .destroy = destroy, .execute = execute, .save_state = save, .restore_state = restore};\n"
    "VRG_PLUGIN(desc)\n";

/* Builds the test plugin `reloadme` (VERSION paints red or green, ABI its
 * declared ABI version) into dir/reloadme.so with the system compiler. */
static int build_plugin_flags(const char *dir, const char *name, int version, const char *abi, const char *flags)
{
    char src[1100], cmd[4096];
    snprintf(src, sizeof src, "%s/%s.c", dir, name);
    save_file(src, reloadme_source);
    snprintf(cmd, sizeof cmd,
             "cc -std=c11 -shared -fPIC -I'%s/../core/include' %s -DNAME='\"%s\"' -DVERSION=%d -DABI=%s -DDIR='\"%s\"' '%s' -o '%s/%s.so.new' && "
             "mv '%s/%s.so.new' '%s/%s.so'",
             TEST_DIR, flags, name, version, abi, dir, src, dir, name, dir, name, dir, name);
    return system(cmd);
}

static int build_plugin_named(const char *dir, const char *name, int version, const char *abi)
{
    return build_plugin_flags(dir, name, version, abi, "");
}

static int build_reloadme(const char *dir, int version, const char *abi) { return build_plugin_named(dir, "reloadme", version, abi); }

/* How many distinct files named like `name` are mapped into this process:
 * the versions of a plugin still loaded. */
static int mapped_versions(const char *name)
{
    char seen[16][512];
    int n = 0;
    char line[1024];
    FILE *f = fopen("/proc/self/maps", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *path = strchr(line, '/');
        if (!path || !strstr(path, name))
            continue;
        path[strcspn(path, "\n")] = '\0';
        int known = 0;
        for (int i = 0; i < n; i++)
            known |= strcmp(seen[i], path) == 0;
        if (!known && n < 16)
            snprintf(seen[n++], sizeof seen[0], "%s", path);
    }
    if (f)
        fclose(f);
    return n;
}

/* More rebuilt plugins in one reload than there once was room for: every
 * one of them runs its new version afterwards. */
static void test_hot_reload_many_plugins(void)
{
    enum { PLUGINS = 10 };
    char dir[] = "/tmp/voxrg-plugins-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100], name[PLUGINS][32], *text = NULL;
    const char *reads[PLUGINS];
    size_t tlen = 0;
    snprintf(path, sizeof path, "%s/many.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    save_file(shader, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                      "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                      "layout(push_constant) uniform P { vec4 c; } pc;\n"
                      "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n");
    append(&text, &tlen, "[graph]\noutput = c0\nwidth = 8\nheight = 8\n");
    for (int i = 0; i < PLUGINS; i++) {
        snprintf(name[i], sizeof name[i], "reloadme%d", i);
        append(&text, &tlen, "[pass p%d]\nplugin = %s\nout.color = c%d\n", i, name[i], i);
        CHECK(build_plugin_named(dir, name[i], 1, "VRG_ABI_VERSION") == 0, "cannot build %s with cc", name[i]);
    }
    save_file(path, text);
    free(text);
    char cname[PLUGINS][16];
    for (int i = 0; i < PLUGINS; i++) {
        snprintf(cname[i], sizeof cname[i], "c%d", i);
        reads[i] = cname[i];
    }
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    vrg_graph_desc d = {.path = path, .readback = reads, .readback_count = PLUGINS};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < PLUGINS; i++)
            CHECK(build_plugin_named(dir, name[i], 2, "VRG_ABI_VERSION") == 0, "cannot rebuild %s", name[i]);
        CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices every rebuild at once */
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "reload failed: %s",
              vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : "");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < PLUGINS; i++) {
            vrg_image_data img;
            CHECK(vrg_graph_read(g, cname[i], &img) == 0, "readback of %s failed", cname[i]);
            CHECK(px(&img, 1, 1, 0) == 0 && px(&img, 1, 1, 1) == 1, "%s still runs version 1 (%g %g)", name[i], px(&img, 1, 1, 0),
                  px(&img, 1, 1, 1));
            free(img.pixels);
        }
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", path);
    unsetenv("VOXRG_PLUGIN_PATH");
    for (int i = 0; i < PLUGINS; i++) {
        char f[1100];
        snprintf(f, sizeof f, "%s/%s.so", dir, name[i]);
        remove(f);
        snprintf(f, sizeof f, "%s/%s.c", dir, name[i]);
        remove(f);
    }
    remove(shader), remove(path), rmdir(dir);
}

/* More saved files in one poll than there once was room for (the last were
 * dropped): one pass's shader with many includes, all saved again, then the
 * one file that matters, another pass's shader (pattern.comp, taken from
 * $VOXRG_SHADER_OVERRIDE), saved last with a new colour. The includes also
 * outnumber the include table there once was (the last were left out of the
 * source: TINT, in the last include, was undeclared). */
static void test_hot_reload_many_files(void)
{
    enum { INCLUDES = 40 };
    char dir[] = "/tmp/voxrg-includes-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char user[1100], graph[1100], pattern[1100], inc[INCLUDES][1100], *text = NULL;
    size_t tlen = 0;
    snprintf(user, sizeof user, "%s/user.comp", dir);
    snprintf(graph, sizeof graph, "%s/g.ini", dir);
    snprintf(pattern, sizeof pattern, "%s/pattern.comp", dir);
    append(&text, &tlen, "#version 450\n");
    for (int i = 0; i < INCLUDES; i++) {
        snprintf(inc[i], sizeof inc[i], "%s/inc%d.glsl", dir, i);
        append(&text, &tlen, "#include \"inc%d.glsl\"\n", i);
    }
    append(&text, &tlen, "layout(local_size_x = 8, local_size_y = 8) in;\nlayout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                         "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(TINT, 1.0)); }\n");
    static const char pattern_shader[] = "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                                         "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                                         "layout(push_constant) uniform P { float value; } pc;\n"
                                         "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(%d.0, 0.5, 0.0, 1.0)); }\n";
    char pattern_text[sizeof pattern_shader + 16];
    save_file(graph, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass s]\nplugin = shader_file\nout.color = color\n"
                     "[pass p]\nplugin = pattern\nout.color = grad\n");
    for (int i = 0; i < INCLUDES - 1; i++)
        save_file(inc[i], "\n");
    save_file(inc[INCLUDES - 1], "#define TINT vec3(1.0, 0.0, 0.0)\n");
    save_file(user, text);
    snprintf(pattern_text, sizeof pattern_text, pattern_shader, 1);
    save_file(pattern, pattern_text);
    setenv("VOXRG_SHADER_PATH", dir, 1);
    setenv("VOXRG_SHADER_OVERRIDE", dir, 1);
    static const char *reads[] = {"grad"};
    vrg_graph_desc d = {.path = graph, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        vrg_image_data img;
        for (int step = 0; step < 2; step++) {
            if (step == 1) { /* the first pass's files saved again unchanged, the change last */
                save_file(user, text);
                for (int i = 0; i < INCLUDES - 1; i++)
                    save_file(inc[i], "\n");
                save_file(inc[INCLUDES - 1], "#define TINT vec3(1.0, 0.0, 0.0)\n");
                snprintf(pattern_text, sizeof pattern_text, pattern_shader, 2);
                save_file(pattern, pattern_text);
            }
            CHECK(vrg_graph_frame(g) == 0, "step %d: frame failed", step);
            CHECK(vrg_graph_read(g, "color", &img) == 0, "readback failed");
            CHECK(px(&img, 3, 3, 0) == 1.0f && px(&img, 3, 3, 1) == 0.0f, "step %d: colour %g %g", step, px(&img, 3, 3, 0), px(&img, 3, 3, 1));
            free(img.pixels);
            CHECK(vrg_graph_read(g, "grad", &img) == 0, "readback failed");
            CHECK(px(&img, 3, 3, 0) == (float)(step + 1), "step %d: pattern.comp's colour is %g, want %d (its save was not seen)", step,
                  px(&img, 3, 3, 0), step + 1);
            free(img.pixels);
            CHECK(!vrg_graph_reload_error(g), "step %d: reload error %s", step, vrg_graph_reload_error(g));
        }
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", graph);
    free(text);
    unsetenv("VOXRG_SHADER_PATH");
    unsetenv("VOXRG_SHADER_OVERRIDE");
    for (int i = 0; i < INCLUDES; i++)
        remove(inc[i]);
    remove(user), remove(graph), remove(pattern), rmdir(dir);
}

/* A save_state() that claims more bytes than it may write: the new instance
 * starts afresh with a message naming the limit (it was once dropped without
 * a word). */
static void test_hot_reload_state_too_big(void)
{
    char dir[] = "/tmp/voxrg-state-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100], so[1100], src[1100];
    snprintf(path, sizeof path, "%s/state.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    snprintf(so, sizeof so, "%s/bigstate.so", dir);
    snprintf(src, sizeof src, "%s/bigstate.c", dir);
    save_file(path, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass r]\nplugin = bigstate\nout.color = color\n");
    save_file(shader, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                      "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                      "layout(push_constant) uniform P { vec4 c; } pc;\n"
                      "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n");
    CHECK(build_plugin_flags(dir, "bigstate", 1, "VRG_ABI_VERSION", "-DSAVE_TOO_MUCH") == 0, "cannot build the test plugin with cc");
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    vrg_graph_desc d = {.path = path, .diag = diag};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        for (int i = 0; i < 3; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(build_plugin_flags(dir, "bigstate", 2, "VRG_ABI_VERSION", "-DSAVE_TOO_MUCH") == 0, "rebuild failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "reload failed");
        vrg_image_data img;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
        CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.01f) < 1e-3f, "version 2 did not start afresh: %g %g %g", px(&img, 1, 1, 0),
              px(&img, 1, 1, 1), px(&img, 1, 1, 2));
        free(img.pixels);
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", path);
    fclose(diag);
    CHECK(log && strstr(log, "save_state() returned 65537 bytes, more than the 65536 it may write"), "no message: %s", log ? log : "");
    free(log);
    unsetenv("VOXRG_PLUGIN_PATH");
    remove(so), remove(src), remove(shader), remove(path), rmdir(dir);
}

/* Hot reload of a rebuilt plugin: the new build runs from the next graph
 * instance on, with the old instance's state handed over (save_state ->
 * restore_state: its frame count goes on); a rebuild with another ABI
 * version is refused and the running version keeps going. */
static void test_hot_reload_plugin(void)
{
    char dir[] = "/tmp/voxrg-plugin-test-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100];
    snprintf(path, sizeof path, "%s/reload.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    save_file(path, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass r]\nplugin = reloadme\nout.color = color\n");
    save_file(shader, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                      "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                      "layout(push_constant) uniform P { vec4 c; } pc;\n"
                      "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n");
    if (build_reloadme(dir, 1, "VRG_ABI_VERSION") != 0) {
        CHECK(0, "cannot build the test plugin with cc");
        return;
    }
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    vrg_graph_desc d = {.path = path, .diag = diag};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load the plugin reload graph");
        fclose(diag);
        free(log);
        unsetenv("VOXRG_PLUGIN_PATH");
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    for (int i = 0; i < 3; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "color", &img) == 0 && px(&img, 1, 1, 0) == 1 && fabsf(px(&img, 1, 1, 2) - 0.03f) < 1e-3f,
          "version 1 after 3 frames: %g %g %g", px(&img, 1, 1, 0), px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);

    CHECK(build_reloadme(dir, 2, "VRG_ABI_VERSION") == 0, "rebuild failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices the rebuild: frame 4 */
    CHECK(vrg_graph_source_changed(g), "the rebuilt plugin was not noticed");
    CHECK(vrg_graph_reload(&g) == 0, "reload failed:\n%s", vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : "");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 0) == 0 && px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.05f) < 1e-3f,
          "version 2, state carried over (5 frames): %g %g %g", px(&img, 1, 1, 0), px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    /* the old graph is gone, so is version 1: an edit loop does not pile up versions */
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after a reload, want 1", mapped_versions("reloadme.so"));

    CHECK(build_reloadme(dir, 1, "999") == 0, "rebuild failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_reload(&g) != 0, "a plugin with ABI version 999 was accepted");
    const char *err = vrg_graph_reload_error(g);
    CHECK(err && strstr(err, "ABI version 999"), "no ABI error: %s", err ? err : "(none)");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.07f) < 1e-3f, "the running version stopped: %g %g %g", px(&img, 1, 1, 0),
          px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after a refused rebuild, want 1", mapped_versions("reloadme.so"));
    /* more rebuilds: still one version, the state still carried (frames 8..) */
    for (int v = 0; v < 3; v++) {
        CHECK(build_reloadme(dir, 2 - v % 2, "VRG_ABI_VERSION") == 0, "rebuild failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "rebuild %d was not reloaded", v);
    }
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.11f) < 1e-3f, "after three more rebuilds: %g %g %g", px(&img, 1, 1, 0),
          px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after 5 rebuilds, want 1", mapped_versions("reloadme.so"));
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    unsetenv("VOXRG_PLUGIN_PATH");
    char so[1100], src[1100];
    snprintf(so, sizeof so, "%s/reloadme.so", dir);
    snprintf(src, sizeof src, "%s/reloadme.c", dir);
    remove(so), remove(src), remove(shader), remove(path), rmdir(dir);
}

static double resident_mib(void)
{
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2)
            resident = 0;
        fclose(f);
    }
    return (double)resident * (double)sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

/* Soak: the default (thesis) graph at a tiny size for thousands of frames
 * along walk.path, which streams chunks in and out (radius 3): every frame
 * succeeds under validation (a message fails the run), and resident memory
 * after warm-up stays flat (release build). Leaks are LSan's (the sanitizer
 * build, where the quarantine makes resident memory grow by design). */
static void test_soak(void)
{
    char path[1024], camera_path[1024];
    snprintf(path, sizeof path, "%s/../graphs/thesis.ini", TEST_DIR);
    snprintf(camera_path, sizeof camera_path, "%s/../graphs/paths/walk.path", TEST_DIR);
    static const char *sets[] = {"scene.radius=3", "scene.hysteresis=1"};
    vrg_graph_desc d = {.path = path, .width = 32, .height = 18, .overrides = sets, .override_count = 2};
    vrg_graph *g = NULL;
    vrg_camera_path cp = {0};
    if (vrg_graph_load(ctx, &d, &g) != 0 || vrg_camera_path_load(camera_path, &cp, stderr) != 0) {
        CHECK(0, "cannot load the soak graph or path");
        vrg_graph_destroy(g);
        return;
    }
    const int frames = 3000;
    double warm = 0, last = 0, loaded_max = 0;
    int failed = 0;
    vrg_camera cam = *vrg_graph_camera(g);
    for (int k = 0; k < frames && !failed; k++) {
        /* the 20 s path, played at 10x, back and forth */
        float t = (float)(k % 400) * 0.05f;
        vrg_camera_path_eval(&cp, (k / 400) % 2 ? 20.0f - t : t, &cam);
        vrg_graph_set_camera(g, &cam);
        failed = vrg_graph_frame(g) != 0;
        double loaded = 0;
        vrg_graph_stat(g, "scene", "chunks_loaded", &loaded);
        loaded_max = loaded > loaded_max ? loaded : loaded_max;
        if (k == 500)
            warm = resident_mib();
    }
    last = resident_mib();
    CHECK(!failed, "a frame failed during the soak");
    CHECK(loaded_max > 0, "the soak streamed nothing");
    printf("soak: %d frames, resident %.1f MiB after 500, %.1f MiB at the end\n", frames, warm, last);
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VRG_TEST_ASAN 1
#endif
#endif
#ifndef VRG_TEST_ASAN
    /* ASan keeps freed memory in quarantine, so resident memory climbs there
     * by design; leaks are LSan's business in that build */
    CHECK(last - warm < 16.0, "resident memory grew by %.1f MiB over %d frames", last - warm, frames - 500);
#endif
    vrg_camera_path_free(&cp);
    vrg_graph_destroy(g);
}

/* Parameters set while the graph runs: the next frame uses them and
 * accumulations restart; bad names, ranges and kinds are refused. */
static void test_set_param(void)
{
    static const char *reads[] = {"mean.color"};
    vrg_graph *g = load_with("progressive.ini", NULL, 0, reads, 1);
    if (!g)
        return;
    vrg_image_data img;
    for (int i = 0; i < 3; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* counts 1 2 3 */
    CHECK(vrg_graph_set_param(g, "counter.step", 10) == 0, "set counter.step failed");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
    CHECK(px(&img, 0, 0, 0) == 13 && px(&img, 0, 0, 3) == 1, "after step = 10: %g over %g frames, want 13 over 1", px(&img, 0, 0, 0),
          px(&img, 0, 0, 3));
    free(img.pixels);
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
    CHECK(px(&img, 0, 0, 0) == 18 && px(&img, 0, 0, 3) == 2, "next frame: %g over %g, want 18 over 2", px(&img, 0, 0, 0), px(&img, 0, 0, 3));
    free(img.pixels);
    CHECK(vrg_graph_set_param(g, "counter.step", 5000) != 0, "out of range accepted");
    CHECK(vrg_graph_set_param(g, "counter.nope", 1) != 0, "unknown parameter accepted");
    CHECK(vrg_graph_set_param(g, "nobody.step", 1) != 0, "unknown pass accepted");
    CHECK(vrg_graph_set_param(g, "mean.max_frames", 2.5) != 0, "a fraction for an integer accepted");
    vrg_graph_destroy(g);
}

/* With a sun radius > 0 the penumbra widens with the occluder's distance:
 * the 12-high wall's is wider than the 4-high wall's. */
static void test_light_penumbra(void)
{
    static const char *reads[] = {"gbuffer.position", "shadow.visibility"};
    vrg_graph *g = load_with("light_penumbra.ini", NULL, 0, reads, 2);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data pos, vis;
    CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "shadow.visibility", &vis) == 0, "readback failed");
    /* penumbra extent along z, per wall (x 4..20 low, 28..44 high), middles only */
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    int count[2] = {0, 0};
    for (uint32_t i = 0; i < pos.width * pos.height; i++) {
        const float *p = pos.pixels + 4 * i;
        float v = vis.pixels[4 * i];
        if (p[3] == 0 || fabsf(p[1] - 1.0f) > 1e-3f || v <= 0.02f || v >= 0.98f)
            continue;
        int k = p[0] > 8 && p[0] < 16 ? 0 : p[0] > 32 && p[0] < 40 ? 1 : -1;
        if (k < 0 || p[2] > 34)
            continue;
        lo[k] = fminf(lo[k], p[2]);
        hi[k] = fmaxf(hi[k], p[2]);
        count[k]++;
    }
    float w0 = hi[0] - lo[0], w1 = hi[1] - lo[1];
    CHECK(count[0] > 5 && count[1] > 5, "penumbrae not in view (%d, %d pixels)", count[0], count[1]);
    CHECK(w1 > 1.8f * w0, "penumbra of the tall wall %.2f blocks, of the low wall %.2f: not wider with distance", w1, w0);
    free(pos.pixels), free(vis.pixels);
    vrg_graph_destroy(g);
}

/* AO in an inner corner < along one wall < on the open floor; indirect light
 * on the white floor next to the red wall is reddish. */
static void test_light_corner(void)
{
    static const char *reads[] = {"gbuffer.position", "ao.ao", "indirect.irradiance"};
    vrg_graph *g = load_with("light_corner.ini", NULL, 0, reads, 3);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data pos, ao, ind;
    CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "ao.ao", &ao) == 0 &&
              vrg_graph_read(g, "indirect.irradiance", &ind) == 0,
          "readback failed");
    float corner = floor_mean(&pos, &ao, 0, 1.5f, 1.5f, 0.5f, NULL), edge = floor_mean(&pos, &ao, 0, 16.0f, 1.5f, 0.5f, NULL),
          open = floor_mean(&pos, &ao, 0, 16.0f, 16.0f, 0.5f, NULL);
    CHECK(corner >= 0 && edge >= 0 && open >= 0, "sample points not visible (%g %g %g)", corner, edge, open);
    CHECK(corner < edge && edge < open && open > 0.97f, "AO corner %.3f, edge %.3f, open %.3f: want corner < edge < open", corner, edge, open);
    float near_ratio, far_ratio;
    floor_mean(&pos, &ind, 0, 16.0f, 1.5f, 1.0f, &near_ratio);
    floor_mean(&pos, &ind, 0, 16.0f, 20.0f, 1.0f, &far_ratio);
    CHECK(near_ratio > 1.3f * far_ratio && near_ratio > 1.0f, "indirect r/g next to the red wall %.3f, far from it %.3f: not reddish", near_ratio,
          far_ratio);
    free(pos.pixels), free(ao.pixels), free(ind.pixels);
    vrg_graph_destroy(g);
}

/* combine → modulate → tonemap on a lit white floor: the pixel equals
 * exposure * albedo * (sun_radiance * N.L + ambient), sRGB-encoded; with
 * mode = thesis it is exposure * albedo * (2 * ambient + sun * N.L / pi). */
static void test_light_chain(void)
{
    vrg_sky_desc sd;
    vrg_sky_default(&sd);
    sd.time_of_day = 12;
    vrg_sky sky;
    vrg_sky_eval(&sd, 0, &sky);
    const float *albedo = vrg_materials()[VRG_BLOCK_WHITE].albedo;
    for (int thesis = 0; thesis < 2; thesis++) {
        static const char *sets[] = {"combine.mode=thesis"};
        vrg_graph *g = load_with("light_chain.ini", sets, (uint32_t)thesis, NULL, 0);
        if (!g)
            return;
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data img;
        CHECK(vrg_graph_read(g, "ldr", &img) == 0, "readback failed");
        float got[3], want[3];
        for (int c = 0; c < 3; c++) {
            float sun = sky.sun_radiance[c] * sky.sun_dir[1]; /* floor normal is +y */
            float l = thesis ? 2.0f * sky.ambient[c] + sun / 3.14159265f : sun + sky.ambient[c];
            float lin = fminf(0.25f * albedo[c] * l, 1.0f);
            /* the readback decodes nothing for UNORM: compare in the encoded domain */
            want[c] = lin <= 0.0031308f ? lin * 12.92f : 1.055f * powf(lin, 1.0f / 2.4f) - 0.055f;
            got[c] = px(&img, img.width / 2, img.height / 2, c);
        }
        CHECK(fabsf(got[0] - want[0]) < 3.0f / 255 && fabsf(got[1] - want[1]) < 3.0f / 255 && fabsf(got[2] - want[2]) < 3.0f / 255,
              "%s: pixel (%.3f %.3f %.3f), want (%.3f %.3f %.3f)", thesis ? "thesis" : "physical", got[0], got[1], got[2], want[0], want[1], want[2]);
        free(img.pixels);
        vrg_graph_destroy(g);
    }
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*fn)(void);
        int device;
    } cases[] = {
        {"chain", test_chain, 1},     {"history", test_history, 1}, {"accumulate", test_accumulate, 1}, {"pingpong", test_pingpong, 1},
        {"alias", test_alias, 1},     {"buffer", test_buffer, 1},   {"buffer_texels", test_buffer_texels, 1}, {"scene", test_scene, 1},           {"loader", test_loader, 0},
        {"history_cleared", test_history_cleared, 1}, {"pingpong_alias", test_pingpong_alias, 1},
        {"accumulate_count", test_accumulate_count, 1}, {"validation_live", test_validation_live, 1},
        {"blocks_world", test_blocks_world, 1}, {"blocks_trace", test_blocks_trace, 1}, {"terrain_world", test_terrain_world, 1},
        {"terrain_trace", test_terrain_trace, 1},
        {"atlas", test_atlas, 1},         {"traversal_errors", test_traversal_errors, 0}, {"camera_range", test_camera_range, 0},
        {"gbuffer_normals", test_gbuffer_normals, 1}, {"gbuffer_motion", test_gbuffer_motion, 1},
        {"light_floor", test_light_floor, 1},         {"light_wall", test_light_wall, 1},
        {"svgf_disocclusion", test_svgf_disocclusion, 1}, {"svgf_mse", test_svgf_mse, 1},
        {"svgf_history_reset", test_svgf_history_reset, 1}, {"svgf_variance", test_svgf_variance, 1},
        {"svgf_edge", test_svgf_edge, 1}, {"accumulate_mean", test_accumulate_mean, 1},
        {"svgf_atrous_options", test_svgf_atrous_options, 1}, {"svgf_size_mismatch", test_svgf_size_mismatch, 1},
        {"dispatch_shape", test_dispatch_shape, 1}, {"hot_reload_shader", test_hot_reload_shader, 1}, {"hot_reload_graph", test_hot_reload_graph, 1},
        {"hot_reload_plugin", test_hot_reload_plugin, 1}, {"capture_replay", test_capture_replay, 1}, {"soak", test_soak, 1}, {"set_param", test_set_param, 1},
        {"light_half_res", test_light_half_res, 1},
        {"light_penumbra", test_light_penumbra, 1},   {"light_corner", test_light_corner, 1},
        {"light_chain", test_light_chain, 1},
        {"history_many", test_history_many, 1}, {"hot_reload_many_plugins", test_hot_reload_many_plugins, 1},
        {"hot_reload_many_files", test_hot_reload_many_files, 1}, {"many_uses", test_many_uses, 1}, {"dispatch_limits", test_dispatch_limits, 1},
        {"hot_reload_state_too_big", test_hot_reload_state_too_big, 1}, {"alias_many", test_alias_many, 1},
    };
    if (argc != 2) {
        fprintf(stderr, "usage: test_runtime CASE\n");
        return 2;
    }
    if (strcmp(argv[1], "rayquery") == 0 || strcmp(argv[1], "backends_agree") == 0) {
        vrg_context_desc cd = {.validate = 1, .quiet = 1};
        if (vrg_context_create(&cd, &ctx) != 0)
            return 1;
        int rc = strcmp(argv[1], "rayquery") == 0 ? test_rayquery() : test_backends_agree();
        uint32_t v = vrg_context_validation_errors(ctx);
        CHECK(v == 0, "%u validation messages", v);
        vrg_context_destroy(ctx);
        if (rc == SKIP && !failures)
            return SKIP;
        printf("%s: %s\n", argv[1], failures ? "FAILED" : "ok");
        return failures ? 1 : 0;
    }
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (strcmp(cases[i].name, argv[1]) != 0)
            continue;
        if (cases[i].device) {
            vrg_context_desc cd = {.validate = 1, .quiet = 1};
            if (vrg_context_create(&cd, &ctx) != 0)
                return 1;
        }
        cases[i].fn();
        if (ctx) {
            uint32_t v = vrg_context_validation_errors(ctx);
            CHECK(v == 0 || expect_validation_messages, "%u validation messages", v);
            vrg_context_destroy(ctx);
        }
        printf("%s: %s\n", argv[1], failures ? "FAILED" : "ok");
        return failures ? 1 : 0;
    }
    fprintf(stderr, "unknown case '%s'\n", argv[1]);
    return 2;
}
