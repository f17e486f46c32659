#define _POSIX_C_SOURCE 200809L /* open_memstream */
/* The temporal passes' debug outputs (optional: written only when read):
 * history length and disocclusion under a still camera and a fast turn,
 * the reprojection target against the motion vectors, the clamp amount,
 * the surface cache's occupancy, the variance; each a 1x1 stand-in unless
 * read, and reading them changes none of the pass's other outputs; and
 * the tiles pass that shows them side by side (graphs/debug-*.ini).
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/camera.h"

static void free_images(vrg_image_data *img, int n)
{
    for (int i = 0; i < n; i++)
        free(img[i].pixels);
}

/* What voxrg check's listing says of resource `name`: 0 the 1x1 stand-in
 * of an unread optional output, 1 an image whose line holds `size`, -1
 * neither. */
static int listed_full_size(const vrg_graph *g, const char *name, const char *size)
{
    char *text = NULL, line[256] = "", key[128];
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return -1;
    vrg_graph_report(g, f);
    fclose(f);
    snprintf(key, sizeof key, "  %s ", name);
    const char *at = strstr(text, key);
    if (at)
        snprintf(line, sizeof line, "%.*s", (int)strcspn(at, "\n"), at);
    free(text);
    if (strstr(line, " 1x1 ") && strstr(line, "(unread optional output)"))
        return 0;
    return line[0] && strstr(line, size) ? 1 : -1;
}

/* svgf_reproject under a still camera, then a fast turn
 * (svgf_ghost.ini: the albedo as the signal). Still: every surface pixel's
 * history length grows by one a frame (0 on the first, where the mask is
 * set everywhere: there is no history yet), the mask is 0 after it, and the
 * history is read at the pixel's own centre with all four taps. After a
 * 25 degree turn: the mask is set exactly where the history restarted
 * (length 0), the history of the others is one frame longer than it was,
 * and it was read at p + 0.5 - motion. */
static void test_debug_svgf_history(void)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.motion", "reproject.length", "reproject.disocclusion", "reproject.reprojection"};
    enum { POS, MOT, LEN, MASK, TARGET, N };
    vrg_graph *g = load_with("svgf_ghost.ini", NULL, 0, reads, N);
    if (!g)
        return;
    CHECK(listed_full_size(g, "reproject.disocclusion", " 96x64 ") == 1 && listed_full_size(g, "reproject.reprojection", " 96x64 ") == 1,
          "the debug outputs read back are not full-size images");
    vrg_image_data img[N];
    for (int frame = 0; frame < 4; frame++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        if (read_images(g, reads, img, N) != 0)
            break;
        int surface = 0, wrong_len = 0, wrong_mask = 0, wrong_target = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++) {
                if (px(&img[POS], x, y, 3) == 0) {
                    wrong_mask += px(&img[MASK], x, y, 0) != 0;
                    continue;
                }
                surface++;
                wrong_len += px(&img[LEN], x, y, 0) != (float)frame;
                wrong_mask += px(&img[MASK], x, y, 0) != (frame == 0 ? 1.0f : 0.0f);
                /* a still camera's motion is 0 within float rounding */
                if (frame > 0)
                    wrong_target += fabsf(px(&img[TARGET], x, y, 0) - ((float)x + 0.5f)) > 1e-3f ||
                                    fabsf(px(&img[TARGET], x, y, 1) - ((float)y + 0.5f)) > 1e-3f || px(&img[TARGET], x, y, 2) < 0.999f ||
                                    px(&img[TARGET], x, y, 3) != 1.0f;
            }
        CHECK(surface > 3000, "only %d surface pixels", surface);
        CHECK(wrong_len == 0, "frame %d, still camera: %d surface pixels have a history length other than %d", frame, wrong_len, frame);
        CHECK(wrong_mask == 0, "frame %d, still camera: %d pixels with the disocclusion mask wrong (want %d on surfaces)", frame, wrong_mask,
              frame == 0);
        CHECK(wrong_target == 0, "frame %d, still camera: %d surface pixels not read at their own centre with all 4 taps", frame, wrong_target);
        free_images(img, N);
    }
    vrg_image_data before;
    if (vrg_graph_read(g, "reproject.length", &before) != 0) {
        CHECK(0, "readback failed");
        return;
    }
    vrg_camera cam = *vrg_graph_camera(g);
    cam.yaw += 25.0f; /* a fast turn: a quarter of the view is new */
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    if (read_images(g, reads, img, N) == 0) {
        int restarted = 0, kept = 0, wrong_mask = 0, wrong_len = 0, wrong_target = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++) {
                if (px(&img[POS], x, y, 3) == 0)
                    continue;
                float len = px(&img[LEN], x, y, 0), mask = px(&img[MASK], x, y, 0);
                float tx = (float)x + 0.5f - px(&img[MOT], x, y, 0), ty = (float)y + 0.5f - px(&img[MOT], x, y, 1);
                wrong_mask += mask != (len == 0 ? 1.0f : 0.0f);
                restarted += len == 0, kept += len > 0;
                /* kept history: one frame more than the (uniform) history it was read from */
                wrong_len += len > 0 && len != 4.0f;
                if (fabsf(px(&img[TARGET], x, y, 0) - tx) > 1e-3f || fabsf(px(&img[TARGET], x, y, 1) - ty) > 1e-3f)
                    wrong_target++;
                /* w: 0 where nothing passed, 1 or 2 where taps did */
                wrong_target += (px(&img[TARGET], x, y, 3) == 0) != (len == 0);
            }
        printf("debug_svgf_history: after the turn %d restarted, %d kept\n", restarted, kept);
        CHECK(restarted > 300 && kept > 1000, "the turn uncovers too little or too much (%d restarted, %d kept)", restarted, kept);
        CHECK(wrong_mask == 0, "after the turn %d surface pixels whose disocclusion mask disagrees with the restarted history", wrong_mask);
        CHECK(wrong_len == 0, "after the turn %d kept pixels whose history is not 4 frames", wrong_len);
        CHECK(wrong_target == 0, "after the turn %d surface pixels whose reprojection target is not p + 0.5 - motion", wrong_target);
        free_images(img, N);
    }
    free(before.pixels);
    vrg_graph_destroy(g);
}

/* clamped_reproject (denoise_light.ini: a noise-free light whose blue
 * drops from 1 to 0 after 10 still frames). With clamp_k = 0 and no
 * anti-lag the clamp amount is 0 everywhere and the history length grows
 * by one a frame, the mask set on the first frame only; with clamp_k =
 * 1.5 the still history sits inside the box (amount 0) until the light
 * changes, when the clamp moves it on every surface pixel. */
static void clamped_case(const char *clamp_k, int want_moved)
{
    static const char *reads[] = {"gbuffer.position", "reproject.length", "reproject.disocclusion", "reproject.clamp", "reproject.reprojection"};
    enum { POS, LEN, MASK, CLAMP, TARGET, N };
    const char *sets[] = {clamp_k, "reproject.antilag=0"};
    vrg_graph *g = load_with("denoise_light.ini", sets, 2, reads, N);
    if (!g)
        return;
    vrg_image_data img[N];
    for (int frame = 0; frame < 11; frame++) {
        if (frame == 10)
            CHECK(vrg_graph_set_param(g, "light.value", 0.0) == 0, "light.value not set");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        if (frame != 0 && frame != 1 && frame != 9 && frame != 10)
            continue;
        if (read_images(g, reads, img, N) != 0)
            break;
        int surface = 0, wrong_len = 0, wrong_mask = 0, moved = 0, antilag = 0, wrong_target = 0;
        float most = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++) {
                if (px(&img[POS], x, y, 3) == 0)
                    continue;
                surface++;
                wrong_len += px(&img[LEN], x, y, 0) != (float)frame;
                wrong_mask += px(&img[MASK], x, y, 0) != (frame == 0 ? 1.0f : 0.0f);
                float amount = px(&img[CLAMP], x, y, 0);
                moved += amount > 0.2f;
                most = fmaxf(most, amount);
                antilag += px(&img[CLAMP], x, y, 1) != 0;
                if (frame > 0)
                    wrong_target += fabsf(px(&img[TARGET], x, y, 0) - ((float)x + 0.5f)) > 1e-3f ||
                                    fabsf(px(&img[TARGET], x, y, 1) - ((float)y + 0.5f)) > 1e-3f || px(&img[TARGET], x, y, 3) != 1.0f;
            }
        CHECK(surface > 1500, "only %d surface pixels", surface);
        CHECK(wrong_len == 0 && wrong_mask == 0, "%s, frame %d: %d pixels' history length is not %d, %d pixels' disocclusion mask is not %d", clamp_k,
              frame, wrong_len, frame, wrong_mask, frame == 0);
        CHECK(wrong_target == 0, "%s, frame %d: %d surface pixels not read at their own centre", clamp_k, frame, wrong_target);
        CHECK(antilag == 0, "%s, frame %d: anti-lag is off, yet %d pixels report its share", clamp_k, frame, antilag);
        if (!want_moved || frame < 10)
            CHECK(most == 0, "%s, frame %d: the clamp amount reaches %g where nothing is clamped", clamp_k, frame, most);
        else
            CHECK(moved == surface, "%s, after the light changed: the clamp moved the history by over 0.2 on only %d of %d surface pixels", clamp_k,
                  moved, surface);
        free_images(img, N);
    }
    vrg_graph_destroy(g);
}

static void test_debug_clamped(void)
{
    clamped_case("reproject.clamp_k=0", 0);
    clamped_case("reproject.clamp_k=1.5", 1);
}

/* surface_cache's occupancy on the still floor of surface_cache.ini
 * (cell_pixels 4): after one frame every floor pixel's cells hold samples
 * and they are found (all four but near the floor's far edge); three frames later they hold three times as many (the
 * same pixels give the same cells their samples each frame; max_frames is
 * 32); the colour is theirs alone; they were given samples this frame (age
 * 0). Sky pixels: 0. */
static void test_debug_cache(void)
{
    static const char *reads[] = {"gbuffer.position", "cache.occupancy"};
    vrg_graph *g = load_with("surface_cache.ini", NULL, 0, reads, 2);
    if (!g)
        return;
    vrg_image_data first[2], img[2];
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    if (read_images(g, reads, first, 2) != 0)
        return;
    for (int i = 0; i < 3; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    if (read_images(g, reads, img, 2) == 0) {
        int floor = 0, empty = 0, wrong = 0, sky = 0, whole = 0;
        for (uint32_t y = 0; y < img[0].height; y++)
            for (uint32_t x = 0; x < img[0].width; x++) {
                const float *o = img[1].pixels + 4 * (y * img[1].width + x);
                if (px(&img[0], x, y, 3) == 0) {
                    sky += o[0] != 0 || o[1] != 0 || o[2] != 0 || o[3] != 0;
                    continue;
                }
                floor++;
                float n1 = px(&first[1], x, y, 0);
                empty += n1 <= 0 || o[0] <= 0;
                /* cells at the floor's far edge may have neighbours no pixel gives samples */
                wrong += fabsf(o[0] - 4 * n1) > 1e-3f * o[0] || o[1] <= 0 || o[1] > 1 || o[2] != 1 || o[3] != 0;
                whole += o[1] == 1;
            }
        printf("debug_cache: %d floor pixels, samples per point after 4 frames e.g. %g\n", floor,
               px(&img[1], img[1].width / 2, img[1].height - 1, 0));
        CHECK(floor > 1000, "only %d floor pixels", floor);
        CHECK(empty == 0, "%d floor pixels whose cells hold no samples", empty);
        CHECK(wrong == 0, "%d floor pixels whose occupancy after 4 frames is not (4 x the first frame's samples, (0, 1], 1, 0)", wrong);
        CHECK(whole > floor * 3 / 4, "only %d of %d floor pixels find all their 2x2 cells", whole, floor);
        CHECK(sky == 0, "%d sky pixels with an occupancy", sky);
        free_images(img, 2);
    }
    free_images(first, 2);
    vrg_graph_destroy(g);
}

/* The variance output is the variance the pass stores in its colour's
 * alpha, exactly, and says where it came from: svgf_variance temporal (the
 * pixel's own moments once length + 1 >= min_history = 4) and spatial (a
 * window: never), mean_variance likewise. */
static void variance_case(const char *graph, const char *set, int mode_temporal)
{
    static const char *reads[] = {"gbuffer.position", "reproject.length", "variance.color", "variance.variance"};
    enum { POS, LEN, COL, VAR, N };
    vrg_graph *g = load_with(graph, set ? &set : NULL, set ? 1 : 0, reads, N);
    if (!g)
        return;
    for (int frame = 0; frame < 5; frame++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        if (frame != 1 && frame != 4)
            continue;
        vrg_image_data img[N];
        if (read_images(g, reads, img, N) != 0)
            break;
        int differ = 0, wrong_source = 0, own = 0, positive = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++) {
                float v = px(&img[VAR], x, y, 0), from_own = px(&img[VAR], x, y, 1);
                differ += v != px(&img[COL], x, y, 3);
                positive += v > 0;
                int want_own = px(&img[POS], x, y, 3) != 0 && mode_temporal && px(&img[LEN], x, y, 0) + 1 >= 4;
                wrong_source += from_own != (float)want_own;
                own += want_own;
            }
        CHECK(differ == 0, "%s %s, frame %d: %d pixels whose variance output differs from the colour's alpha", graph, set ? set : "", frame, differ);
        CHECK(positive > 1000, "%s %s, frame %d: only %d pixels with a variance above 0", graph, set ? set : "", frame, positive);
        CHECK(wrong_source == 0, "%s %s, frame %d: %d pixels wrong about where their variance came from", graph, set ? set : "", frame,
              wrong_source);
        CHECK((own > 0) == (mode_temporal && frame == 4), "%s %s, frame %d: %d pixels from their own moments", graph, set ? set : "", frame, own);
        free_images(img, N);
    }
    vrg_graph_destroy(g);
}

static void test_debug_variance(void)
{
    variance_case("svgf_blocks.ini", NULL, 1);
    variance_case("svgf_blocks.ini", "variance.mode=spatial", 0);
    variance_case("denoise_blocks.ini", NULL, 1);
}

/* Reading the debug outputs changes nothing else: each pass's other
 * outputs are the same bytes over frames of a moving camera with and
 * without them read, and unread they are 1x1 stand-ins. */
static void same_case(const char *graph, const char *const *debug, int ndebug, const char *const *outputs, int noutputs)
{
    const char *reads[16];
    for (int i = 0; i < noutputs; i++)
        reads[i] = outputs[i];
    for (int i = 0; i < ndebug; i++)
        reads[noutputs + i] = debug[i];
    vrg_graph *plain = load_with(graph, NULL, 0, outputs, (uint32_t)noutputs);
    vrg_graph *g = load_with(graph, NULL, 0, reads, (uint32_t)(noutputs + ndebug));
    if (!plain || !g)
        return;
    for (int i = 0; i < ndebug; i++) {
        CHECK(listed_full_size(plain, debug[i], " ") == 0, "%s: %s, not read, is not a 1x1 stand-in", graph, debug[i]);
        CHECK(listed_full_size(g, debug[i], " ") == 1, "%s: %s, read back, is a stand-in", graph, debug[i]);
    }
    for (int frame = 0; frame < 4; frame++) {
        vrg_camera cam = *vrg_graph_camera(plain);
        cam.position[0] += 0.5f, cam.yaw += 3.0f;
        vrg_graph_set_camera(plain, &cam);
        vrg_graph_set_camera(g, &cam);
        CHECK(vrg_graph_frame(plain) == 0 && vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < noutputs; i++) {
            vrg_image_data a, b;
            if (vrg_graph_read(plain, outputs[i], &a) != 0 || vrg_graph_read(g, outputs[i], &b) != 0) {
                CHECK(0, "readback of %s failed", outputs[i]);
                return;
            }
            CHECK(memcmp(a.pixels, b.pixels, 4 * sizeof(float) * a.width * a.height) == 0, "%s, frame %d: %s differs when the debug outputs are read",
                  graph, frame, outputs[i]);
            free(a.pixels), free(b.pixels);
        }
    }
    vrg_graph_destroy(plain);
    vrg_graph_destroy(g);
}

static void test_debug_unchanged(void)
{
    static const char *svgf_debug[] = {"reproject.disocclusion", "reproject.reprojection", "variance.variance"};
    static const char *svgf_out[] = {"reproject.color", "reproject.moments", "reproject.length", "variance.color"};
    same_case("svgf_blocks.ini", svgf_debug, 3, svgf_out, 4);
    static const char *clamped_debug[] = {"reproject.disocclusion", "reproject.reprojection", "reproject.clamp", "variance.variance"};
    static const char *clamped_out[] = {"reproject.color", "reproject.fast", "reproject.moments", "reproject.length", "variance.color"};
    same_case("denoise_blocks.ini", clamped_debug, 4, clamped_out, 5);
    static const char *cache_debug[] = {"cache.occupancy", "chain.occupancy"};
    static const char *cache_out[] = {"cache.color", "chain.color"};
    same_case("surface_cache.ini", cache_debug, 2, cache_out, 2);
}

/* tiles: four inputs in a 2x2 grid of 30x20 tiles, each a 60x40 gradient
 * (pattern: (x/59, y/39, value)) read at its nearest texel: tile 0 as
 * it is, tile 1 its green remapped from [0.5, 1] as grey, tile 2
 * unconnected (black), tile 3 its red through the false-colour ramp; and
 * an integer input (the G-buffer's ids) refused with an error. */
static void heat_ramp(float v, float out[3])
{
    static const float stops[7][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {1, 1, 1}};
    float s = v * 6;
    int k = s >= 5 ? 5 : (int)s;
    for (int c = 0; c < 3; c++)
        out[c] = stops[k][c] + (stops[k + 1][c] - stops[k][c]) * (s - (float)k);
}

static void test_tiles_layout(void)
{
    static const char *text = "[graph]\nname = tiles_layout\noutput = view\nwidth = 60\nheight = 40\n"
                              "[pass a]\nplugin = pattern\nout.color = a\nvalue = 0.25\n"
                              "[pass tiles]\nplugin = tiles\nin.t0 = a\nin.t1 = a\nin.t3 = a\nout.view = view\n"
                              "t1_channel = g\nt1_min = 0.5\nt3_channel = r\nt3_heat = 1\n";
    vrg_graph *g = load_text(text, NULL, 0);
    if (!g)
        return;
    vrg_image_data view;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "view", &view) == 0, "frame or readback failed");
    if (!view.pixels)
        return;
    int wrong = 0;
    for (uint32_t y = 0; y < 40; y++)
        for (uint32_t x = 0; x < 60; x++) {
            uint32_t tile = (y / 20) * 2 + x / 30, qx = x % 30, qy = y % 20;
            float src[3] = {(float)(2 * qx + 1) / 59.0f, (float)(2 * qy + 1) / 39.0f, 0.25f}, want[3] = {0, 0, 0};
            if (tile == 0)
                memcpy(want, src, sizeof want);
            else if (tile == 1)
                want[0] = want[1] = want[2] = fmaxf(0.0f, (src[1] - 0.5f) / 0.5f);
            else if (tile == 3)
                heat_ramp(src[0], want);
            for (int c = 0; c < 3; c++)
                if (fabsf(px(&view, x, y, c) - want[c]) > 2.0f / 255.0f) {
                    if (wrong < 4)
                        fprintf(stderr, "  (%u, %u) tile %u channel %d: %g, want %g\n", x, y, tile, c, px(&view, x, y, c), want[c]);
                    wrong++;
                }
        }
    CHECK(wrong == 0, "%d channels of the tiles differ from the remapped inputs", wrong);
    free(view.pixels);
    vrg_graph_destroy(g);

    static const char *ids = "[graph]\nname = tiles_ids\noutput = view\nwidth = 32\nheight = 24\n"
                             "[scene]\nplugin = blocks\nbox = 0 0 0 15 0 15 white\n"
                             "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n"
                             "[pass tiles]\nplugin = tiles\nin.t0 = gbuffer.ids\nout.view = view\n";
    /* refused on load, at the in.t0 line (16), before any frame */
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    vrg_graph_desc d = {.path = "tiles_ids.ini", .text = ids, .diag = diag};
    g = NULL;
    int rc = vrg_graph_load(ctx, &d, &g);
    fclose(diag);
    CHECK(rc != 0 && buf && strstr(buf, "tiles_ids.ini:16: error") && strstr(buf, "in.t0: an integer image cannot be shown"),
          "an integer image in a tile was not refused at in.t0's line:\n%s", buf ? buf : "");
    free(buf);
    vrg_graph_destroy(g);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"debug_svgf_history", test_debug_svgf_history, 1},
        {"debug_clamped", test_debug_clamped, 1},
        {"debug_cache", test_debug_cache, 1},
        {"debug_variance", test_debug_variance, 1},
        {"debug_unchanged", test_debug_unchanged, 1},
        {"tiles_layout", test_tiles_layout, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
