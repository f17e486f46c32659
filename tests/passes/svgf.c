#define _POSIX_C_SOURCE 200809L
/* SVGF (temporal accumulation, variance, a-trous) and progressive
 * accumulation: disocclusion, error against a converged reference, history
 * resets, variance, edges, options and sizes.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"
#include "voxrg/edits.h"
#include <stdlib.h>
#include <unistd.h>

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

/* The pillar of svgf_ghost.ini (x 22..24, y 1..10, z 11..12) removed
 * through an edit journal, as `voxrg run` removes blocks: 0, or -1. */
static int remove_pillar(vrg_graph *g, vrg_edits *e)
{
    char err[512];
    for (int y = 1; y <= 10; y++)
        for (int z = 11; z <= 12; z++)
            for (int x = 22; x <= 24; x++)
                if (vrg_edits_set(e, vrg_graph_world(g), x, y, z, VRG_BLOCK_AIR, err, sizeof err) != 0) {
                    fprintf(stderr, "%s\n", err);
                    return -1;
                }
    return 0;
}

/* A still camera, history built on the pillar, then the pillar removed by
 * edits: from the first frame after the edit the reprojected colour is the
 * fresh render of the edited world (a new graph, the same edits, no
 * history), so no ghost of the removed blocks survives in the history. */
static void test_svgf_edit_removal(void)
{
    static const char *reads[] = {"reproject.color"};
    char dir[] = "/tmp/vrg_edit_ghost_XXXXXX", path[64], err[512] = "the graph did not load";
    vrg_graph *g = load_with("svgf_ghost.ini", NULL, 0, reads, 1), *fresh = load_with("svgf_ghost.ini", NULL, 0, reads, 1);
    CHECK(mkdtemp(dir) != NULL, "mkdtemp failed");
    snprintf(path, sizeof path, "%s/ghost.edits", dir);
    vrg_edits *e = g ? vrg_edits_open(path, "svgf_ghost", vrg_graph_world(g), err, sizeof err) : NULL;
    CHECK(e != NULL, "%s", err);
    if (!g || !fresh || !e)
        return;
    vrg_image_data before, after[2], want;
    for (int i = 0; i < 4; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "reproject.color", &before) == 0, "readback failed");
    CHECK(remove_pillar(g, e) == 0 && remove_pillar(fresh, e) == 0, "the edits failed");
    for (int i = 0; i < 2; i++)
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "reproject.color", &after[i]) == 0, "frame after the edit failed");
    CHECK(vrg_graph_frame(fresh) == 0 && vrg_graph_read(fresh, "reproject.color", &want) == 0, "fresh frame failed");
    int uncovered = 0, ghosts[2] = {0, 0};
    for (uint32_t p = 0; p < want.width * want.height; p++)
        for (int c = 0; c < 3; c++) {
            uncovered += c == 0 && fabsf(before.pixels[4 * p] - want.pixels[4 * p]) > 0.05f;
            for (int k = 0; k < 2; k++)
                ghosts[k] += fabsf(after[k].pixels[4 * p + c] - want.pixels[4 * p + c]) > 0.01f;
        }
    printf("svgf_edit_removal: %d pixels uncovered, %d and %d channels off the fresh render\n", uncovered, ghosts[0], ghosts[1]);
    CHECK(uncovered > 100, "removing the pillar changed only %d pixels: the test would not see a ghost", uncovered);
    CHECK(ghosts[0] == 0 && ghosts[1] == 0, "%d, %d colour channels differ from the fresh render: a ghost of the removed pillar", ghosts[0],
          ghosts[1]);
    free(before.pixels), free(after[0].pixels), free(after[1].pixels), free(want.pixels);
    vrg_edits_close(e);
    unlink(path);
    rmdir(dir);
    vrg_graph_destroy(g);
    vrg_graph_destroy(fresh);
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

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"svgf_disocclusion", test_svgf_disocclusion, 1},
        {"svgf_edit_removal", test_svgf_edit_removal, 1},
        {"svgf_mse", test_svgf_mse, 1},
        {"svgf_history_reset", test_svgf_history_reset, 1},
        {"svgf_variance", test_svgf_variance, 1},
        {"svgf_edge", test_svgf_edge, 1},
        {"accumulate_mean", test_accumulate_mean, 1},
        {"svgf_atrous_options", test_svgf_atrous_options, 1},
        {"svgf_size_mismatch", test_svgf_size_mismatch, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
