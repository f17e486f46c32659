#define _POSIX_C_SOURCE 200809L
/* Graph mechanics on the test plugins, whose every output value has a closed
 * form: chains, history, accumulation, ping-pong, aliasing, buffers, scene
 * data, capture, parameters set while running, and live validation.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"

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

/* A resize a pass refuses leaves the graph without frames (no half-made
 * readback to copy into), with a message, until a resize succeeds. */
static void test_resize_refused(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = grey\nwidth = 16\nheight = 16\n[pass limit]\nplugin = resize_limit\nout.color = grey\n";
    vrg_graph_desc d = {.path = "resize.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(ctx, &d, &g) == 0, "load failed");
    if (g) {
        CHECK(vrg_graph_frame(g) == 0, "frame at 16x16 failed");
        CHECK(vrg_graph_resize(g, 64, 64) != 0, "the refused resize succeeded");
        CHECK(vrg_graph_frame(g) != 0, "a frame after the refused resize ran");
        CHECK(vrg_graph_resize(g, 24, 24) == 0, "resize to 24x24 failed");
        CHECK(vrg_graph_frame(g) == 0, "frame at 24x24 failed");
        vrg_image_data img;
        if (vrg_graph_read(g, "grey", &img) == 0) {
            CHECK(img.width == 24 && fabsf(px(&img, 23, 23, 0) - 0.5f) < 1e-3f, "24x24 output wrong: %ux%u, %g", img.width, img.height,
                  px(&img, 23, 23, 0));
            free(img.pixels);
        } else
            CHECK(0, "readback failed");
        vrg_graph_destroy(g);
    }
    fclose(diag);
    CHECK(buf && strstr(buf, "output 64x64 is wider than max_width 32") && strstr(buf, "its last resize failed"), "messages:\n%s", buf ? buf : "");
    free(buf);
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
/* vrg_graph_read_pixels: every written image in schedule order, each
 * @prev copy after its resource, the stored values (halves exactly as the
 * readback decodes them), and a pixel outside the graph refused. */
static void test_read_pixels(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/chain.ini", TEST_DIR);
    vrg_graph_desc d = {.path = path, .keep_images = 1};
    vrg_graph *g = NULL;
    if (!CHECK(vrg_graph_load(ctx, &d, &g) == 0, "chain.ini does not load"))
        return;
    vrg_pixel_value v[8];
    CHECK(vrg_graph_read_pixels(g, 0, 0, v, 8) == -1, "a read before any frame is not refused");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    int n = vrg_graph_read_pixels(g, 7, 5, v, 8);
    const char *want[] = {"gradient", "blurred", "final"}, *pass[] = {"gen", "smooth", "sum"};
    if (CHECK(n == 3, "%d entries, not 3", n))
        for (int i = 0; i < 3; i++)
            CHECK(!strcmp(v[i].resource, want[i]) && !strcmp(v[i].pass, pass[i]) && !v[i].prev && v[i].kept && v[i].channels == 4 &&
                      v[i].x == 7 && v[i].y == 5,
                  "entry %d is %s of %s (prev %d, kept %d, %u channels, at %u,%u)", i, v[i].resource, v[i].pass, v[i].prev, v[i].kept,
                  v[i].channels, v[i].x, v[i].y);
    vrg_image_data img;
    if (n == 3 && CHECK(vrg_graph_read(g, "final", &img) == 0, "readback failed")) {
        for (int c = 0; c < 4; c++)
            CHECK(v[2].value[c] == px(&img, 7, 5, c), "final channel %d: %.9g, the readback %.9g", c, v[2].value[c], px(&img, 7, 5, c));
        free(img.pixels);
        /* the gradient's closed form, within a half's precision */
        CHECK(fabs(v[0].value[0] - 7.0 / 39) < 1e-3 && fabs(v[0].value[1] - 5.0 / 23) < 1e-3 && v[0].value[2] == 0.5 && v[0].value[3] == 1.0 &&
                  v[0].bits[3] == 0x3c00,
              "gradient (%g, %g, %g, %g), alpha bits %#x", v[0].value[0], v[0].value[1], v[0].value[2], v[0].value[3], v[0].bits[3]);
    }
    CHECK(vrg_graph_read_pixels(g, 40, 0, v, 8) == -1, "x = 40 of a 40-wide graph is not refused");
    CHECK(vrg_graph_read_pixels(g, 0, 24, v, 8) == -1, "y = 24 of a 24-high graph is not refused");
    CHECK(vrg_graph_frame(g) == 0, "a frame after the reads failed");
    vrg_graph_destroy(g);

    d.path = path;
    snprintf(path, sizeof path, "%s/graphs/history.ini", TEST_DIR);
    if (!CHECK(vrg_graph_load(ctx, &d, &g) == 0, "history.ini does not load"))
        return;
    for (int f = 0; f < 3; f++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    n = vrg_graph_read_pixels(g, 15, 15, v, 1); /* max 1: the count is still the whole */
    CHECK(n == 2 && !strcmp(v[0].resource, "count") && !v[0].prev && v[0].value[0] == 3.0, "%d entries; count %g", n, v[0].value[0]);
    n = vrg_graph_read_pixels(g, 15, 15, v, 8);
    CHECK(n == 2 && v[1].prev && v[1].kept && v[1].value[0] == 2.0, "@prev: %d entries, prev %d, value %g", n, n > 1 ? v[1].prev : -1,
          n > 1 ? v[1].value[0] : -1);
    vrg_graph_destroy(g);
}

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

/* Persistent buffers start cleared, even on a graph's first frame, when
 * no barrier precedes the clear: a graph fills its persistent buffer with
 * 99 and is destroyed, the next one (whose probe never writes the buffer)
 * must read zeros where the allocator may hand it the same memory. */
static void test_persistent_cleared(void)
{
    static const char *fills[] = {"[graph]\noutput = color\nwidth = 8\nheight = 8\n"
                                  "[pass probe]\nplugin = keep_probe\nout.data = data\nout.color = color\nvalue = 99\n",
                                  "[graph]\noutput = color\nwidth = 8\nheight = 8\n"
                                  "[pass probe]\nplugin = keep_probe\nout.data = data\nout.color = color\nfill = 0\n"};
    static const char *reads[] = {"data"};
    for (int round = 0; round < 4; round++)
        for (int i = 0; i < 2; i++) {
            vrg_graph *g = load_text(fills[i], reads, 1);
            if (!g)
                return;
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            void *data = NULL;
            uint64_t size = 0;
            CHECK(vrg_graph_read_buffer(g, "data", &data, &size) == 0 && size == 16, "readback of data failed");
            const uint32_t *w = data;
            for (int k = 0; w && k < 4; k++)
                CHECK(w[k] == (i == 0 ? 99u : 0u), "round %d, graph %d: word %d is %u on the first frame, want %u", round, i, k, w[k],
                      i == 0 ? 99u : 0u);
            free(data);
            vrg_graph_destroy(g);
        }
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

/* Parameters set while the graph runs: the next frame uses them and
 * accumulations restart; bad names, ranges and kinds are refused, and so
 * are parameters only create() reads (VRG_PARAM_RELOAD). */
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
    /* read only in create(): setting it would change nothing until a reload */
    CHECK(vrg_graph_set_param(g, "mean.samples_per_frame", 2) != 0, "a VRG_PARAM_RELOAD parameter accepted");
    vrg_graph_destroy(g);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"resize_refused", test_resize_refused, 1},
        {"chain", test_chain, 1},
        {"history", test_history, 1},
        {"read_pixels", test_read_pixels, 1},
        {"accumulate", test_accumulate, 1},
        {"pingpong", test_pingpong, 1},
        {"alias", test_alias, 1},
        {"buffer", test_buffer, 1},
        {"buffer_texels", test_buffer_texels, 1},
        {"scene", test_scene, 1},
        {"history_cleared", test_history_cleared, 1},
        {"persistent_cleared", test_persistent_cleared, 1},
        {"pingpong_alias", test_pingpong_alias, 1},
        {"accumulate_count", test_accumulate_count, 1},
        {"validation_live", test_validation_live, 1},
        {"capture_replay", test_capture_replay, 1},
        {"set_param", test_set_param, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
