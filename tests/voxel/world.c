#define _POSIX_C_SOURCE 200809L
/* The voxel world on the GPU: chunk layout and traversal against the CPU
 * world, streamed terrain, the block atlas, and the ray-query backend.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"

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

/* The edit box the frame uniforms carry (vrg_world_uploaded_edits): the
 * blocks vrg_world_set_block changed, in the frame whose upload brings
 * them to the GPU; empty on the next frame, for a block set to what it
 * was, and for chunks streamed in. */
static void test_edit_box(void)
{
    vrg_graph *g = load("blocks_probe.ini");
    vrg_world *w = g ? vrg_graph_world(g) : NULL;
    CHECK(!g || w != NULL, "the blocks scene set no world");
    if (!w) {
        vrg_graph_destroy(g);
        return;
    }
    int lo[3], hi[3];
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_world_uploaded_edits(w, lo, hi);
    CHECK(lo[0] >= hi[0], "the first frame (chunks streamed in, no edit) has an edit box %d..%d", lo[0], hi[0]);
    /* two blocks in two chunks changed (stone for air, air for anything
     * else), and one set to what it is */
    vrg_block b1 = vrg_world_block(w, 3, 5, -7) == VRG_BLOCK_AIR ? VRG_BLOCK_STONE : VRG_BLOCK_AIR,
              b2 = vrg_world_block(w, 20, 2, 9) == VRG_BLOCK_AIR ? VRG_BLOCK_STONE : VRG_BLOCK_AIR;
    CHECK(vrg_world_set_block(w, 3, 5, -7, b1) == 0 && vrg_world_set_block(w, 20, 2, 9, b2) == 0 &&
              vrg_world_set_block(w, 30, 30, 30, vrg_world_block(w, 30, 30, 30)) == 0,
          "set_block failed");
    vrg_world_uploaded_edits(w, lo, hi);
    CHECK(lo[0] >= hi[0], "edits not yet uploaded are in the box %d..%d", lo[0], hi[0]);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_world_uploaded_edits(w, lo, hi);
    CHECK(lo[0] == 3 && lo[1] == 2 && lo[2] == -7 && hi[0] == 21 && hi[1] == 6 && hi[2] == 10, "edit box %d %d %d..%d %d %d, want 3 2 -7..21 6 10",
          lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_world_uploaded_edits(w, lo, hi);
    CHECK(lo[0] >= hi[0], "the frame after the edits still has an edit box %d..%d", lo[0], hi[0]);
    /* an edited chunk replaced (streamed in again) or dropped before its
     * upload takes its edit box with it */
    const vrg_block *chunk = vrg_world_chunk(w, 0, 0, -1);
    static vrg_block copy[VRG_CHUNK_VOXELS];
    if (chunk)
        memcpy(copy, chunk, sizeof copy);
    CHECK(chunk && vrg_world_set_block(w, 3, 5, -7, b1 == VRG_BLOCK_AIR ? VRG_BLOCK_STONE : VRG_BLOCK_AIR) == 0 &&
              vrg_world_set_block(w, 20, 2, 9, b2 == VRG_BLOCK_AIR ? VRG_BLOCK_STONE : VRG_BLOCK_AIR) == 0,
          "set_block failed");
    vrg_world_put_chunk(w, 0, 0, -1, copy);
    vrg_world_drop_chunk(w, 1, 0, 0);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_world_uploaded_edits(w, lo, hi);
    CHECK(lo[0] >= hi[0], "edits of a chunk replaced or dropped before its upload are in the box %d %d %d..%d %d %d", lo[0], lo[1], lo[2], hi[0],
          hi[1], hi[2]);
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

/* A small terrain graph with a hard ray-query shadow (no random numbers, so
 * frame counters do not matter): seed and exposure vary between saves;
 * broken makes modulate read a pass (tests/plugins/resize_limit) whose
 * resize() refuses the graph's width: the load fails after every pass's
 * create() ran and the resources were allocated. */
static const char *keep_world_text(int seed, float exposure, int journal, int broken)
{
    static char text[1400];
    snprintf(text, sizeof text,
             "[graph]\noutput = ldr\nwidth = 64\nheight = 36\n"
             "[camera]\nposition = -20 45 20\nyaw = -40\npitch = -30\n"
             "[scene]\nplugin = terrain\nseed = %d\nradius = 1\ntraversal = rayquery\nthreads = 2\n%s"
             "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\nin.tlas = tlas\n"
             "[pass shadow]\nplugin = sun_shadow\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\n"
             "in.normal = gbuffer.normal\nin.tlas = tlas\nout.visibility = sun\nrays = 1\nsun_radius = 0\n"
             "[pass combine]\nplugin = combine\nin.normal = gbuffer.normal\nin.frame = frame\nin.visibility = sun\nout.illumination = light\n"
             "[pass modulate]\nplugin = modulate\nin.illumination = light\nin.albedo = %s\nout.color = color\n"
             "[pass tonemap]\nplugin = tonemap\nin.color = color\nout.ldr = ldr\nexposure = %g\n%s",
             seed, journal ? "" : "edits = none\n", broken ? "limit.color" : "gbuffer.albedo", exposure,
             broken ? "[pass limit]\nplugin = resize_limit\nmax_width = 8\n" : "");
    return text;
}

/* One frame of path's graph, freshly loaded: what a reload must match. */
static int fresh_image(const char *path, vrg_image_data *img)
{
    static const char *reads[] = {"ldr"};
    vrg_graph_desc d = {.path = path, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0)
        return -1;
    int rc = vrg_graph_frame(g) == 0 && vrg_graph_read(g, "ldr", img) == 0 ? 0 : -1;
    vrg_graph_destroy(g);
    return rc;
}

static int same_pixels(const vrg_image_data *a, const vrg_image_data *b)
{
    return a->width == b->width && a->height == b->height && memcmp(a->pixels, b->pixels, (size_t)a->width * a->height * 4 * sizeof(float)) == 0;
}

static double scene_stat(vrg_graph *g, const char *name)
{
    double v = -1;
    return vrg_graph_stat(g, "scene", name, &v) == 0 ? v : -1;
}

/* A graph reload whose world parameters (and edit journal) are unchanged
 * shares the generated world with the new graph (terrain's world_kept)
 * instead of generating it again, and what the GPU holds of it: its first
 * frame uploads no chunk (gpu_world_kept) and builds no BLAS. Each renders
 * what a freshly loaded graph renders. A changed seed generates a new
 * world, uploaded and built whole. A reload that fails after the scene's
 * create() leaves the old graph rendering as before, and the next reload
 * keeps the world still; a resize before the first frame of a reload that
 * kept the world buffer makes a new one, which is uploaded whole. */
static void test_terrain_reload_keeps_world(void)
{
    char dir[] = "/tmp/voxrg-keep-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100];
    snprintf(path, sizeof path, "%s/keep.ini", dir);
    save_file(path, keep_world_text(7, 0.5f, 1, 0));
    static const char *reads[] = {"ldr"};
    vrg_graph_desc d = {.path = path, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load %s", path);
        return;
    }
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    const vrg_world *before = vrg_graph_world(g);
    struct {
        int seed;
        float exposure;
        int journal, kept, broken, resize;
    } steps[] = {{7, 0.8f, 1, 1, 0, 0}, {7, 0.6f, 1, 1, 1, 0}, {7, 0.5f, 1, 1, 0, 0}, {9, 0.8f, 1, 0, 0, 0},
                 {9, 0.3f, 1, 1, 0, 1}, {9, 0.3f, 0, 0, 0, 0}}; /* the last: its chunks held the journal's edits */
    float exposure = 0.5f;
    for (int s = 0; s < (int)(sizeof steps / sizeof steps[0]); s++) {
        save_file(path, keep_world_text(steps[s].seed, steps[s].exposure, steps[s].journal, steps[s].broken));
        CHECK((vrg_graph_reload(&g) == 0) == !steps[s].broken, "step %d: reload %s", s, steps[s].broken ? "succeeded" : "failed");
        CHECK((vrg_graph_world(g) == before) == steps[s].kept, "step %d: the world %s", s, steps[s].kept ? "was generated again" : "was kept");
        before = vrg_graph_world(g);
        if (steps[s].broken) /* the old graph runs on: what a fresh graph of its file renders */
            save_file(path, keep_world_text(steps[s].seed, exposure, steps[s].journal, 0));
        else
            exposure = steps[s].exposure;
        if (steps[s].resize)
            CHECK(vrg_graph_resize(g, 64, 36) == 0, "step %d: resize failed", s);
        vrg_image_data img, want;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "ldr", &img) == 0, "step %d: frame failed", s);
        double kept = scene_stat(g, "world_kept"), gpu_kept = scene_stat(g, "gpu_world_kept");
        double uploaded = scene_stat(g, "chunks_uploaded"), built = scene_stat(g, "blas_built");
        CHECK(kept == steps[s].kept, "step %d: world_kept %g", s, kept);
        /* the old graph after a failed reload: its next frame, nothing new */
        int whole_gpu = steps[s].kept && !steps[s].resize && !steps[s].broken;
        CHECK(gpu_kept == whole_gpu, "step %d: gpu_world_kept %g", s, gpu_kept);
        CHECK(steps[s].kept && !steps[s].resize ? uploaded == 0 : uploaded > 0, "step %d: %g chunks uploaded", s, uploaded);
        CHECK(steps[s].kept ? built == 0 : built > 0, "step %d: %g BLASes built", s, built);
        CHECK(fresh_image(path, &want) == 0, "step %d: the fresh graph failed", s);
        CHECK(same_pixels(&img, &want), "step %d: the reloaded graph's image differs from a fresh graph's", s);
        free(img.pixels);
        free(want.pixels);
    }
    vrg_graph_destroy(g);
    unlink(path);
    strcat(path, ".edits"); /* the terrain's journal beside the graph */
    unlink(path);
    rmdir(dir);
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
                        sum += srgb_decode(lv[(((tile / VRG_ATLAS_COLUMNS) * ts + y) * size + (tile % VRG_ATLAS_COLUMNS) * ts + x) * 4 + c]);
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
            int v = l0[(((stone / VRG_ATLAS_COLUMNS) * 16 + y) * VRG_ATLAS_SIZE + (stone % VRG_ATLAS_COLUMNS) * 16 + x) * 4];
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

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"terrain_reload_keeps_world", test_terrain_reload_keeps_world, 1, NULL},
        {"blocks_world", test_blocks_world, 1},
        {"edit_box", test_edit_box, 1},
        {"blocks_trace", test_blocks_trace, 1},
        {"terrain_world", test_terrain_world, 1},
        {"terrain_trace", test_terrain_trace, 1},
        {"atlas", test_atlas, 1},
        {"rayquery", NULL, 1, test_rayquery},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
