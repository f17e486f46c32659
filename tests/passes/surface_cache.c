#define _POSIX_C_SOURCE 200809L /* open_memstream */
/* surface_cache against known answers on a still floor
 * (tests/graphs/surface_cache.ini): the history's weights, the bilinear
 * gather's placement, cells small enough to be one pixel's own, the table
 * emptied by new parameters, and a table too small reported.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"

static const char *const reads[] = {"cache.color", "ticks.color", "light", "tick.count", "gbuffer.position", "fell.color"};
enum { CACHE, TICKS, LIGHT, TICK, POS, FELL, COUNT };

static int read_all(vrg_graph *g, vrg_image_data img[COUNT]) { return read_images(g, reads, img, COUNT); }

static void free_all(vrg_image_data img[COUNT])
{
    for (int i = 0; i < COUNT; i++)
        free(img[i].pixels);
}

/* What a cell holds after `frames` frames of the counter (frame k gives
 * k * step to every sample): the resolve's recursion with n samples per
 * frame, n = min(n, (max_frames - 1) * count) + count, weight count / n. */
static double expected_mean(int frames, double max_frames, double step)
{
    double mean = 0, n = 0;
    for (int k = 1; k <= frames; k++) {
        n = fmin(n, max_frames - 1) + 1; /* in units of one frame's count */
        mean += (k * step - mean) / n;
    }
    return mean;
}

/* The history: every floor pixel shows the recursion's value (max_frames 4:
 * the plain mean for 4 frames, then an exponential average), within the
 * fixed point's 1/1024 and half floats; one channel cached, the others
 * passed through. */
static void test_cache_history(void)
{
    vrg_graph *g = load_with("surface_cache.ini", NULL, 0, reads, COUNT);
    if (!g)
        return;
    for (int frames = 1; frames <= 9; frames++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        if (frames != 3 && frames != 9)
            continue;
        vrg_image_data img[COUNT];
        if (read_all(g, img) != 0)
            break;
        double want = expected_mean(frames, 4, 0.0625), worst = 0;
        int floor = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++) {
                if (px(&img[POS], x, y, 3) == 0)
                    continue;
                floor++;
                CHECK(fabsf(px(&img[TICK], x, y, 0) - (float)(frames * 0.0625)) < 1e-6f, "the counter shows %g after %d frames",
                      px(&img[TICK], x, y, 0), frames);
                worst = fmax(worst, fabs(px(&img[TICKS], x, y, 0) - want));
                /* channels = 1: the rest is the counter's own (r32f reads as (r, 0, 0, 1)) */
                CHECK(px(&img[TICKS], x, y, 1) == 0 && px(&img[TICKS], x, y, 3) == 1, "(%u, %u): channels past the first are (%g, %g), not the signal's",
                      x, y, px(&img[TICKS], x, y, 1), px(&img[TICKS], x, y, 3));
            }
        CHECK(floor > 1000, "only %d floor pixels", floor);
        CHECK(worst < 2e-3, "after %d frames a cell holds up to %g away from %g", frames, worst, want);
        free_all(img);
    }
    vrg_graph_destroy(g);
}

/* sun_span: under a moving sun a cell's history is worth at most sun_span
 * / (the degrees the sun moved since the last frame) frames (here 2.5, not
 * rounded), so the counter's cells follow the recursion with max_frames
 * 2.5, not the
 * 1000 the pass is given; a still sun leaves max_frames in force. */
static void test_cache_sun_span(void)
{
    const double day = 20; /* seconds: about 0.3 degrees a frame at 60 fps */
    vrg_graph *g = load("surface_cache.ini");
    double frame_s = g ? vrg_graph_frame_seconds(g) : 1.0 / 60;
    vrg_graph_destroy(g);
    double moved = sun_moved_degrees(10, day, frame_s, 8);
    CHECK(moved > 0.05, "the sun moves only %g degrees a frame: the case shows nothing", moved);
    for (int moving = 0; moving <= 1; moving++) {
        char daylen[64], span[64];
        snprintf(daylen, sizeof daylen, "scene.day_length=%.17g", moving ? day : 0.0);
        snprintf(span, sizeof span, "ticks.sun_span=%.17g", 2.5 * moved);
        const char *sets[] = {"ticks.max_frames=1000", daylen, span};
        if (!(g = load_with("surface_cache.ini", sets, 3, reads, COUNT)))
            return;
        for (int i = 0; i < 9; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data img[COUNT];
        if (read_all(g, img) != 0) {
            vrg_graph_destroy(g);
            return;
        }
        double want = expected_mean(9, moving ? 2.5 : 1000, 0.0625), worst = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                if (px(&img[POS], x, y, 3) != 0)
                    worst = fmax(worst, fabs(px(&img[TICKS], x, y, 0) - want));
        printf("cache_sun_span: %s sun (%.4f degrees a frame, sun_span %.4f): cells within %g of %g\n", moving ? "moving" : "still", moved,
               2.5 * moved, worst, want);
        CHECK(worst < 2e-3, "%s sun: a cell holds up to %g away from %g (the recursion with max_frames %g)", moving ? "moving" : "still", worst,
              want, moving ? 2.5 : 1000.0);
        free_all(img);
        vrg_graph_destroy(g);
    }
}

/* the floor covers the (2r+1)^2 pixels around (x, y): cells there are whole */
static int floor_around(const vrg_image_data *pos, uint32_t x, uint32_t y, uint32_t r)
{
    for (uint32_t v = y - r; v <= y + r; v++)
        for (uint32_t u = x - r; u <= x + r; u++)
            if (px(pos, u, v, 3) == 0)
                return 0;
    return 1;
}

/* Eviction: cells not given samples for evict_frames frames are freed (each
 * frame looks at a quarter of the table), and their slots serve again.
 * The floor is seen, then only the sky for 20 frames, then the floor
 * again: its cells start over, so the cached counter is that frame's value
 * alone; kept cells would blend it with the value of 20 frames before. */
static void test_cache_evict(void)
{
    static const char *sets[] = {"ticks.evict_frames=2"};
    vrg_graph *g = load_with("surface_cache.ini", sets, 1, reads, COUNT);
    if (!g)
        return;
    vrg_camera floor_view = *vrg_graph_camera(g), sky_view = floor_view;
    sky_view.pitch = 60;
    int frames = 0;
    for (; frames < 3; frames++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_set_camera(g, &sky_view);
    for (; frames < 23; frames++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_graph_set_camera(g, &floor_view);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    frames++;
    vrg_image_data img[COUNT];
    if (read_all(g, img) == 0) {
        double want = frames * 0.0625, worst = 0;
        int floor = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                if (px(&img[POS], x, y, 3) != 0) {
                    floor++;
                    worst = fmax(worst, fabs(px(&img[TICKS], x, y, 0) - want));
                }
        CHECK(floor > 1000, "only %d floor pixels", floor);
        CHECK(worst < 2e-3, "back on the floor after 20 frames of sky, a cell holds up to %g away from this frame's %g: not freed", worst, want);
        free_all(img);
    }
    vrg_graph_destroy(g);
}

/* surface_cache.ini with sets after `frames` frames, every image read back */
static int render_with(const char *const *sets, uint32_t nsets, int frames, vrg_image_data img[COUNT])
{
    vrg_graph *g = load_with("surface_cache.ini", sets, nsets, reads, COUNT);
    if (!g)
        return -1;
    int rc = 0;
    for (int i = 0; i < frames && rc == 0; i++)
        CHECK((rc = vrg_graph_frame(g)) == 0, "frame failed");
    if (rc == 0)
        rc = read_all(g, img);
    vrg_graph_destroy(g);
    return rc;
}

/* The ticks pass's image after 4 frames looking at the floor and 12
 * turned away from part of it (whose cells expire after 2 frames and are
 * freed), with a table of `cells` slots (and `extra` set, if given);
 * *freed_before_live: slots freed with a live cell's slot right after them,
 * at the end; *stale (if given): slots still holding a cell that had no
 * samples in the last 7 frames (expired, and its share of the table
 * looked at since: every evict pass should have freed it). */
static int turn_away(const char *cells, const char *extra, vrg_image_data *ticks, int *freed_before_live, int *stale)
{
    static const char *const with_table[] = {"ticks.color", "ticks.table"};
    const char *sets[] = {"ticks.evict_frames=2", "ticks.max_frames=1000", cells, extra};
    vrg_graph *g = load_with("surface_cache.ini", sets, extra ? 4 : 3, with_table, 2);
    if (!g)
        return -1;
    vrg_camera view = *vrg_graph_camera(g);
    int rc = 0;
    for (int frame = 0; frame < 16 && rc == 0; frame++) {
        if (frame == 4) {
            view.yaw += 30;
            vrg_graph_set_camera(g, &view);
        }
        CHECK((rc = vrg_graph_frame(g)) == 0, "frame failed");
        double uncached = 0;
        CHECK(vrg_graph_stat(g, "ticks", "uncached", &uncached) == 0 && uncached == 0, "%s: %g samples uncached", cells, uncached);
    }
    uint32_t *words = NULL;
    uint64_t size = 0;
    if (rc == 0)
        rc = vrg_graph_read(g, "ticks.color", ticks);
    if (rc == 0)
        rc = vrg_graph_read_buffer(g, "ticks.table", (void **)&words, &size);
    if (rc == 0) {
        /* 16 header words, then 8-word entries (1 channel), check word first */
        uint64_t slots = (size / 4 - 16) / 9;
        *freed_before_live = 0;
        for (uint64_t i = 0; i + 1 < slots; i++)
            *freed_before_live += words[16 + 8 * i] == 1 && words[16 + 8 * (i + 1)] >= 2;
        /* word 1 of an entry: the last frame with samples (the last frame is 15) */
        if (stale) {
            *stale = 0;
            for (uint64_t i = 0; i < slots; i++)
                *stale += words[16 + 8 * i] >= 2 && words[16 + 8 * i + 1] + 7 < 15;
        }
    }
    free(words);
    vrg_graph_destroy(g);
    return rc;
}

/* Freed slots inside probe runs: a cell found past a freed slot keeps its
 * history, and a new cell may take the freed slot. With the table about
 * half full the image after turning away from part of the floor is the
 * same as with a table 64 times larger, where runs are short; the small
 * table did have freed slots right before live ones. */
static void test_cache_freed_runs(void)
{
    vrg_image_data small = {0}, large = {0};
    int freed_small = 0, freed_large = 0;
    if (turn_away("ticks.cells=1024", NULL, &small, &freed_small, NULL) == 0 && turn_away("ticks.cells=65536", NULL, &large, &freed_large, NULL) == 0) {
        size_t n = (size_t)small.width * small.height * 4, differ = 0;
        for (size_t i = 0; i < n; i++)
            differ += small.pixels[i] != large.pixels[i];
        printf("freed slots right before live ones: %d (1024 slots), %d (65536); values that differ: %zu\n", freed_small, freed_large,
               differ);
        CHECK(freed_small >= 10, "only %d freed slots before live ones: the case is not exercised", freed_small);
        CHECK(differ == 0, "%zu values differ between the tables: a lookup stopped at a freed slot, or reused a live one", differ);
    }
    free(small.pixels);
    free(large.pixels);
}

/* Evict and resolve split among invocations as on a GPU (one slot each)
 * or as on a CPU (16 slots each; 256 groups striding through the listed
 * cells) give the same image: with a small table turned half away from
 * (so cells expire and freed slots sit inside probe runs), and on the
 * chain of three coarse levels (four cells listed per pixel). The images
 * cannot show when a slot is freed: the count of expired cells still in
 * the table shows that each split's evict reached every slot of its
 * shares. (Resolve strides through the list, so its group count decides
 * only how long it takes.) */
static void test_cache_slot_invocations(void)
{
    vrg_image_data ticks[2] = {{0}}, chain[2] = {{0}};
    int freed[2] = {0, 0}, stale[2] = {0, 0}, ok = 1;
    static const char *const chain_reads[] = {"chain.color"};
    for (int per_slot = 0; per_slot <= 1 && ok; per_slot++) {
        char set[64];
        snprintf(set, sizeof set, "ticks.slot_invocations=%d", per_slot);
        CHECK(ok = turn_away("ticks.cells=1024", set, &ticks[per_slot], &freed[per_slot], &stale[per_slot]) == 0, "turning away failed");
        snprintf(set, sizeof set, "chain.slot_invocations=%d", per_slot);
        const char *sets[] = {set};
        vrg_graph *g = ok ? load_with("surface_cache.ini", sets, 1, chain_reads, 1) : NULL;
        ok = g != NULL;
        for (int f = 0; f < 5 && ok; f++)
            CHECK(ok = vrg_graph_frame(g) == 0, "frame failed");
        if (ok)
            CHECK(ok = vrg_graph_read(g, "chain.color", &chain[per_slot]) == 0, "readback of chain.color failed");
        /* the split the parameter asked for is the one recorded */
        double run = 0, groups = 0;
        if (ok) {
            CHECK(vrg_graph_stat(g, "chain", "evict_slots_per_invocation", &run) == 0 && run == (per_slot ? 1 : 16),
                  "slot_invocations = %d: evict ran %g slots per invocation", per_slot, run);
            /* a GPU's: a group of 64 per cell the frame can list, 64x48 pixels x 4 levels */
            CHECK(vrg_graph_stat(g, "chain", "resolve_groups", &groups) == 0 && groups == (per_slot ? 64 * 48 * 4 / 64 : 256),
                  "slot_invocations = %d: resolve ran %g groups", per_slot, groups);
        }
        if (g)
            vrg_graph_destroy(g);
    }
    if (ok) {
        size_t differ = 0, n = (size_t)ticks[0].width * ticks[0].height * 4, m = (size_t)chain[0].width * chain[0].height * 4;
        for (size_t i = 0; i < n; i++)
            differ += ticks[0].pixels[i] != ticks[1].pixels[i];
        size_t chain_differ = 0;
        for (size_t i = 0; i < m; i++)
            chain_differ += chain[0].pixels[i] != chain[1].pixels[i];
        printf("freed slots right before live ones: %d (CPU split), %d (GPU split); expired cells not freed: %d, %d; values that differ: "
               "%zu turned away, %zu on the chain\n",
               freed[0], freed[1], stale[0], stale[1], differ, chain_differ);
        CHECK(freed[0] >= 10 && freed[1] >= 10, "only %d / %d freed slots before live ones: eviction is not exercised", freed[0], freed[1]);
        CHECK(stale[0] == 0 && stale[1] == 0, "%d / %d expired cells not freed: the evict pass does not reach every slot", stale[0], stale[1]);
        CHECK(differ == 0, "%zu values differ after turning away: one split evicts or resolves what the other does not", differ);
        CHECK(chain_differ == 0, "%zu values differ on the chain: one split resolves cells the other does not", chain_differ);
    }
    for (int i = 0; i < 2; i++) {
        free(ticks[i].pixels);
        free(chain[i].pixels);
    }
}

/* The gather: red is linear in world x along each screen row, so the
 * bilinear blend of cells around a point gives the point's own red, up to
 * the offset of the centroid of the pixels a cell holds from its centre
 * (pixels near the floor's edge, whose cells are partly off the floor, are
 * left out);
 * gathering from cells half a cell off would make it a consistent error of
 * half a cell. Blurring still happened:
 * green (not linear in world z) differs. */
static void test_cache_gather(void)
{
    vrg_image_data img[COUNT];
    if (render_with(NULL, 0, 3, img) != 0)
        return;
    uint32_t w = img[POS].width, h = img[POS].height;
    double pixel_red = 1.0 / (w - 1), signed_sum = 0, worst = 0, green_diff = 0;
    int n = 0;
    for (uint32_t y = 8; y + 8 < h; y++)
        for (uint32_t x = 8; x + 8 < w; x++) {
            if (!floor_around(&img[POS], x, y, 8))
                continue;
            double e = px(&img[CACHE], x, y, 0) - px(&img[LIGHT], x, y, 0);
            signed_sum += e;
            worst = fmax(worst, fabs(e));
            green_diff += fabs(px(&img[CACHE], x, y, 1) - px(&img[LIGHT], x, y, 1));
            CHECK(fabsf(px(&img[CACHE], x, y, 2) - 1.0f) < 2e-3f, "(%u, %u): blue %g, the signal's is 1", x, y, px(&img[CACHE], x, y, 2));
            n++;
        }
    CHECK(n > 500, "only %d interior floor pixels", n);
    double mean = signed_sum / (n > 0 ? n : 1);
    printf("gather: red error mean %.5f, worst %.5f (one pixel of red: %.5f); green mean difference %.5f\n", mean, worst, pixel_red,
           green_diff / (n > 0 ? n : 1));
    CHECK(fabs(mean) < 0.15 * pixel_red, "the cached red is off by %g on average (one pixel: %g): cells are gathered off their place", mean,
          pixel_red);
    CHECK(worst < 1.5 * pixel_red, "the cached red is up to %g off (one pixel: %g)", worst, pixel_red);
    CHECK(green_diff / (n > 0 ? n : 1) > 1e-3, "green is unchanged: nothing was averaged");
    free_all(img);
}

/* mean |cached - signal| of green over the floor after 3 frames, with sets */
static double green_blur(const char *const *sets, uint32_t nsets)
{
    double diff = -1;
    vrg_image_data img[COUNT];
    if (render_with(sets, nsets, 3, img) == 0) {
        double sum = 0;
        int n = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                if (px(&img[POS], x, y, 3) != 0) {
                    sum += fabs(px(&img[CACHE], x, y, 1) - px(&img[LIGHT], x, y, 1));
                    n++;
                }
        diff = sum / (n > 0 ? n : 1);
        free_all(img);
    }
    return diff;
}

/* Whether pixel (x, y) shows the floor's top face (y = 1) */
static int on_top(const vrg_image_data *pos, uint32_t x, uint32_t y)
{
    return px(pos, x, y, 3) != 0 && fabsf(px(pos, x, y, 1) - 1.0f) < 1e-3f;
}

/* The cache pass's image after 3 frames with sets, seen from nearly
 * straight above the floor's middle (pitch -89, the camera's limit), high
 * enough that the whole floor is in view: every top-face point at about
 * one depth (25.8 to 26.2), so at one level, and no pixel's coarse cells
 * are another pixel's fine ones; the floor's 32 blocks are whole cells of
 * 4, 8 and 16 blocks, so no cell is cut by the image's edges. *pos: the
 * G-buffer position (may be NULL). Returns the mean |cached - signal| of
 * green over the top face (-1 on failure). */
static double cache_from_above(const char *const *sets, uint32_t nsets, vrg_image_data *cache, vrg_image_data *pos)
{
    static const char *const above_reads[] = {"cache.color", "light", "gbuffer.position"};
    vrg_graph *g = load_with("surface_cache.ini", sets, nsets, above_reads, 3);
    if (!g)
        return -1;
    vrg_camera above = *vrg_graph_camera(g);
    above.position[0] = 16, above.position[1] = 27, above.position[2] = 16;
    above.pitch = -89;
    int rc = vrg_graph_set_camera(g, &above);
    CHECK(rc == 0, "the camera above the floor was refused");
    for (int i = 0; i < 3 && rc == 0; i++)
        CHECK((rc = vrg_graph_frame(g)) == 0, "frame failed");
    vrg_image_data light = {0}, position = {0};
    if (rc == 0)
        CHECK((rc = vrg_graph_read(g, "cache.color", cache)) == 0, "readback of cache.color failed");
    if (rc == 0)
        CHECK((rc = vrg_graph_read(g, "light", &light)) == 0, "readback of light failed");
    if (rc == 0)
        CHECK((rc = vrg_graph_read(g, "gbuffer.position", &position)) == 0, "readback of gbuffer.position failed");
    double blur = -1;
    if (rc == 0) {
        blur = 0;
        int n = 0;
        for (uint32_t y = 0; y < cache->height; y++)
            for (uint32_t x = 0; x < cache->width; x++)
                if (on_top(&position, x, y)) {
                    blur += fabs(px(cache, x, y, 1) - px(&light, x, y, 1));
                    n++;
                }
        CHECK(n > 500, "only %d pixels of the floor's top in view from above", n);
        blur /= n > 0 ? n : 1;
    }
    free(light.pixels);
    if (pos)
        *pos = position;
    else
        free(position.pixels);
    vrg_graph_destroy(g);
    return blur;
}

/* Coarse cells: a cell younger than young_samples leans on the cells
 * twice as wide, and so on up to 2^coarse_levels times wider (the chain:
 * test_cache_chain). Always young (young_samples 1e6) the image is the
 * widest cells' (green, not linear on the floor, is blurred more than by
 * the fine cells alone). Never young (0.001) it is the fine cells' image, to
 * a half float's rounding, seen from nearly above: where the floor's depth
 * changes, a pixel's fine cells are also nearer pixels' coarse cells, by
 * design (they carry a surface's history across its change of level), and
 * hold their samples too. With the fallback input connected and no coarse
 * levels, young cells lean on it instead. */
static void test_cache_coarse(void)
{
    vrg_image_data fine_img = {0}, never_img = {0};
    static const char *always[] = {"cache.coarse_levels=2", "cache.young_samples=1000000"};
    static const char *never[] = {"cache.coarse_levels=2", "cache.young_samples=0.001"};
    double fine = green_blur(NULL, 0), coarse = green_blur(always, 2);
    printf("green blur: fine cells %.5f, coarse %.5f\n", fine, coarse);
    CHECK(fine > 0 && coarse > 2 * fine, "coarse cells blur green by %g, the fine ones by %g: not the coarse cells'", coarse, fine);
    double above_fine = cache_from_above(NULL, 0, &fine_img, NULL), above_never = cache_from_above(never, 2, &never_img, NULL);
    printf("green blur from above: fine cells %.5f, never young %.5f\n", above_fine, above_never);
    CHECK(above_fine > 1e-3, "from above the fine cells averaged nothing (green blur %g): is the floor in view?", above_fine);
    /* with a fallback and no coarse levels young cells lean on the fallback: `fell` is always young */
    vrg_graph *g = load_with("surface_cache.ini", NULL, 0, reads, COUNT);
    vrg_image_data img[COUNT];
    if (g && vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0 && read_all(g, img) == 0) {
        double worst = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                if (px(&img[POS], x, y, 3) != 0)
                    worst = fmax(worst, fabs(px(&img[FELL], x, y, 0) - px(&img[TICK], x, y, 0)) + fabs(px(&img[FELL], x, y, 1)));
        CHECK(worst < 1e-3, "always young with a fallback: up to %g away from the fallback", worst);
        free_all(img);
    }
    if (g)
        vrg_graph_destroy(g);
    if (fine_img.pixels && never_img.pixels) {
        size_t n = (size_t)fine_img.width * fine_img.height * 4;
        double worst = 0;
        for (size_t i = 0; i < n; i++)
            worst = fmax(worst, fabs(fine_img.pixels[i] - never_img.pixels[i]));
        CHECK(worst < 1e-3, "with no young cells the image is not the fine cells' alone: up to %g apart", worst);
    }
    free(fine_img.pixels);
    free(never_img.pixels);
}

/* The chain: with coarse_levels = k a young cell leans on the cells twice
 * as wide, young ones of those on the next level up, up to 2^k times wider,
 * whose young cells lean on the fallback. The chain pass caches the counter
 * (the same mean at every level) with the pattern as its fallback; cells
 * at least a pixel wide, young below 16 samples, 3 frames: a fine cell
 * (under 2 pixels wide: at most 12 samples) is young, a cell 8 times wider
 * is not, so on the floor the image is the counter's mean. Had the fallback
 * stood in for the coarse levels, as it did before the chain, the pattern
 * would show. Young everywhere (young_samples 1e6) the image is the
 * fallback's. */
static void test_cache_chain(void)
{
    static const char *const chain_reads[] = {"chain.color", "light", "gbuffer.position"};
    static const char *const always_young[] = {"chain.young_samples=1000000"};
    for (int young = 0; young <= 1; young++) {
        vrg_graph *g = load_with("surface_cache.ini", always_young, young ? 1 : 0, chain_reads, 3);
        if (!g)
            return;
        vrg_image_data img[3] = {{0}};
        int ok = 1;
        for (int f = 0; f < 3 && ok; f++)
            CHECK(ok = vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < 3 && ok; i++)
            CHECK(ok = vrg_graph_read(g, chain_reads[i], &img[i]) == 0, "readback of %s failed", chain_reads[i]);
        if (ok) {
            double mean = expected_mean(3, 32, 0.0625), worst = 0, pattern_off = 0;
            int n = 0;
            for (uint32_t y = 4; y + 4 < img[2].height; y++)
                for (uint32_t x = 4; x + 4 < img[2].width; x++) {
                    if (!floor_around(&img[2], x, y, 4))
                        continue;
                    double want = young ? px(&img[1], x, y, 0) : mean;
                    worst = fmax(worst, fabs(px(&img[0], x, y, 0) - want));
                    pattern_off = fmax(pattern_off, fabs(px(&img[1], x, y, 0) - mean));
                    n++;
                }
            printf("chain, %s: %d floor pixels, up to %.5f from the %s (the pattern is up to %.3f from the mean)\n",
                   young ? "always young" : "young fine cells", n, worst, young ? "fallback" : "counter's mean", pattern_off);
            CHECK(n > 500, "only %d interior floor pixels", n);
            CHECK(pattern_off > 0.1, "the pattern is within %g of the counter's mean: the test tells nothing", pattern_off);
            CHECK(worst < 2e-3, "%s: up to %g away from the %s", young ? "always young" : "fine cells young, coarse ones not", worst,
                  young ? "fallback" : "coarse cells' mean");
        }
        for (int i = 0; i < 3; i++)
            free(img[i].pixels);
        vrg_graph_destroy(g);
    }
}

/* The largest difference of green between two images over the floor's top */
static double worst_on_top(const vrg_image_data *a, const vrg_image_data *b, const vrg_image_data *pos)
{
    double worst = 0;
    for (uint32_t y = 0; y < a->height; y++)
        for (uint32_t x = 0; x < a->width; x++)
            if (on_top(pos, x, y))
                worst = fmax(worst, fabs(px(a, x, y, 1) - px(b, x, y, 1)));
    return worst;
}

/* The chain's middle level, from above the whole floor (one level, whole
 * cells): after 3 frames a cell of the cache pass holds about 84 samples,
 * a cell twice as wide about 330, 4 times as wide about 1300 (28, 111 and
 * 445 pixels a frame). With young_samples 200 the fine cells are young
 * (one coarse level changes the image) and the cells twice as wide are
 * not, so the chain stops there: two coarse levels give the image of one,
 * exactly. With 800 the cells twice as wide are young too and lean on the
 * level above: two levels differ from one. A chain that read only its
 * widest level fails the first case; one that stopped at the first coarse
 * level fails the second. */
static void test_cache_chain_levels(void)
{
    static const char *sets[5][2] = {{"cache.coarse_levels=0", "cache.young_samples=200"},
                                     {"cache.coarse_levels=1", "cache.young_samples=200"},
                                     {"cache.coarse_levels=2", "cache.young_samples=200"},
                                     {"cache.coarse_levels=1", "cache.young_samples=800"},
                                     {"cache.coarse_levels=2", "cache.young_samples=800"}};
    vrg_image_data img[5] = {{0}}, pos = {0};
    int ok = 1;
    for (int i = 0; i < 5 && ok; i++)
        ok = cache_from_above(sets[i], 2, &img[i], i == 0 ? &pos : NULL) > 0;
    if (ok) {
        double young_fine = worst_on_top(&img[0], &img[1], &pos), same = worst_on_top(&img[1], &img[2], &pos),
               differ = worst_on_top(&img[3], &img[4], &pos);
        printf("chain levels, young below 200: no or one coarse level up to %.6f apart, one or two %.6f; below 800: one or two %.6f\n",
               young_fine, same, differ);
        CHECK(young_fine > 1e-3, "young below 200, one coarse level gives the fine cells' image (up to %g apart): they were not young",
              young_fine);
        CHECK(same == 0, "young below 200 (the first coarse level not young) two coarse levels differ from one by up to %g", same);
        CHECK(differ > 1e-3, "young below 800 (the first coarse level young) two coarse levels give one's image (up to %g apart)", differ);
    }
    for (int i = 0; i < 5; i++)
        free(img[i].pixels);
    free(pos.pixels);
}

/* Cells a quarter of a pixel wide hold one pixel's sample each, so the
 * cache gives back the signal itself: two pixels in one cell, or a lookup
 * finding another cell's entry, would show. */
static void test_cache_own_cells(void)
{
    static const char *sets[] = {"cache.cell_pixels=0.25"};
    vrg_image_data img[COUNT];
    if (render_with(sets, 1, 2, img) != 0)
        return;
    double worst = 0;
    for (uint32_t y = 0; y < img[POS].height; y++)
        for (uint32_t x = 0; x < img[POS].width; x++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(px(&img[CACHE], x, y, c) - px(&img[LIGHT], x, y, c)));
    CHECK(worst < 2e-3, "one pixel per cell: the cache differs from the signal by up to %g", worst);
    free_all(img);
}

/* The share of floor pixels whose cached value (cache_sparse.ini: the
 * half-size position, sampled at gbuffer_downsample's pixels) is their own
 * position after `frames` frames with sets, at width x height (0: the
 * graph's 64x48); -1 on failure. */
static double sparse_own_share(const char *const *sets, uint32_t nsets, int frames, uint32_t width, uint32_t height)
{
    /* wrong.color read too: the graph's other cache runs (test_cache_sparse) */
    static const char *const sparse_reads[] = {"sparse.color", "gbuffer.position", "wrong.color"};
    vrg_graph *g = load_with("cache_sparse.ini", sets, nsets, sparse_reads, 3);
    if (!g)
        return -1;
    if (width && vrg_graph_resize(g, width, height) != 0) {
        CHECK(0, "resize to %ux%u failed", width, height);
        vrg_graph_destroy(g);
        return -1;
    }
    for (int i = 0; i < frames; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data cached, pos;
    if (vrg_graph_read(g, "sparse.color", &cached) != 0 || vrg_graph_read(g, "gbuffer.position", &pos) != 0) {
        CHECK(0, "readback failed");
        vrg_graph_destroy(g);
        return -1;
    }
    int floor = 0, own = 0;
    for (uint32_t y = 0; y < pos.height; y++)
        for (uint32_t x = 0; x < pos.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            floor++;
            /* a half float holds a position of up to 32 blocks to 1/64; the
             * next pixel's point is a tenth of a block away or more */
            int same = 1;
            for (int c = 0; c < 3; c++)
                same &= fabs(px(&cached, x, y, c) - px(&pos, x, y, c)) < 0.02;
            own += same;
        }
    free(cached.pixels);
    free(pos.pixels);
    vrg_graph_destroy(g);
    CHECK(floor > 1000, "only %d floor pixels", floor);
    return floor > 0 ? (double)own / floor : -1;
}

/* A signal smaller than the G-buffer (signal_position connected): each
 * half-size texel's sample goes to the cell of the one pixel it was taken
 * at, not to its neighbours' (a cache that gave the whole footprint's cells
 * each sample would, after 4 frames of jitter, leave none showing its own
 * position: their cells would hold the mean of four). With
 * gbuffer_downsample's jitter every pixel is sampled once in 4 frames, so
 * after 4 frames every floor pixel's own cell shows its own position, at
 * an odd size too (65x49: half-size texels of 1 or 2 pixels a side, whose
 * picks must be the pixels the cache maps back to them); without jitter
 * only the pixel each texel always takes does (the others' cells never get
 * a sample: they show the texel's, another pixel's position). */
static void test_cache_sparse(void)
{
    static const char *const fixed[] = {"half.jitter=0"};
    double jittered = sparse_own_share(NULL, 0, 4, 0, 0), one = sparse_own_share(NULL, 0, 1, 0, 0), still = sparse_own_share(fixed, 1, 4, 0, 0);
    double odd = sparse_own_share(NULL, 0, 4, 65, 49);
    printf("floor pixels showing their own position: jitter, 4 frames %.3f, 1 frame %.3f; no jitter, 4 frames %.3f; 65x49, 4 frames %.3f\n",
           jittered, one, still, odd);
    CHECK(jittered > 0.99, "with jitter, after 4 frames only %.3f of the floor's pixels show their own position", jittered);
    CHECK(odd > 0.99, "at 65x49, with jitter, after 4 frames only %.3f of the floor's pixels show their own position", odd);
    /* the counts the host reads back: every hit texel matched one pixel;
     * a signal_position that is no copy of position (pass `wrong`)
     * matches none, and the pass warns, once */
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/cache_sparse.ini", TEST_DIR);
    static const char *const both[] = {"sparse.color", "wrong.color"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = both, .readback_count = 2};
    vrg_graph *g = NULL;
    double texels = -1, matched = -1, wrong_texels = -1, wrong_matched = -1;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        for (int i = 0; i < 6; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_stat(g, "sparse", "sparse_texels", &texels) == 0 && vrg_graph_stat(g, "sparse", "sparse_matched", &matched) == 0 &&
                  vrg_graph_stat(g, "wrong", "sparse_texels", &wrong_texels) == 0 && vrg_graph_stat(g, "wrong", "sparse_matched", &wrong_matched) == 0,
              "no sparse stats");
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", path);
    fclose(diag);
    printf("hit texels %g, matched %g; with a wrong signal_position %g and %g\n", texels, matched, wrong_texels, wrong_matched);
    CHECK(texels > 300 && matched == texels, "%g hit texels, %g matched a pixel: each should match one", texels, matched);
    CHECK(wrong_texels > 300 && wrong_matched == 0, "a signal_position that is no copy of position: %g of %g texels matched", wrong_matched, wrong_texels);
    const char *warned = log ? strstr(log, "nothing reaches the cache") : NULL;
    CHECK(warned && strstr(log, "cache_sparse.ini:") && !strstr(warned + 1, "nothing reaches the cache"), "no single warning naming the line: %s",
          log ? log : "");
    free(log);
    CHECK(one > 0.2 && one < 0.3, "after 1 frame %.3f of the floor's pixels show their own position, not a quarter", one);
    CHECK(still > 0.2 && still < 0.3, "without jitter %.3f of the floor's pixels show their own position, not a quarter", still);
}

/* Of the horizontally neighbouring interior floor pixels, the fraction
 * whose cached red is the same, after 3 frames with sets; -1 on failure.
 * *error: the mean |cached - signal| of red, in pixels of red. */
static double same_red(const char *const *sets, uint32_t nsets, double *error)
{
    vrg_image_data img[COUNT];
    if (render_with(sets, nsets, 3, img) != 0)
        return -1;
    int pairs = 0, same = 0;
    double sum = 0;
    for (uint32_t y = 8; y + 8 < img[POS].height; y++)
        for (uint32_t x = 8; x + 9 < img[POS].width; x++)
            if (floor_around(&img[POS], x, y, 8) && floor_around(&img[POS], x + 1, y, 8)) {
                pairs++;
                same += px(&img[CACHE], x, y, 0) == px(&img[CACHE], x + 1, y, 0);
                sum += fabs(px(&img[CACHE], x, y, 0) - px(&img[LIGHT], x, y, 0));
            }
    *error = pairs > 0 ? sum / pairs * (img[POS].width - 1) : 0;
    free_all(img);
    CHECK(pairs > 400, "only %d pairs of interior floor pixels", pairs);
    return pairs > 0 ? (double)same / pairs : -1;
}

/* bilinear = 0: each pixel reads its point's own cell, so all the pixels
 * of a cell (4 to 8 pixels wide here) show its one mean, where the
 * bilinear blend gives nearly every pixel a value of its own (red is
 * linear in world x along a row). The mean is the cell's own: a pixel's
 * red is off by a quarter of the cell's width on average (1 to 2 pixels
 * of red); a neighbouring cell's would be a whole width off. */
static void test_cache_nearest(void)
{
    static const char *nearest[] = {"cache.bilinear=0"};
    double blended_error = 0, own_error = 0;
    double blended = same_red(NULL, 0, &blended_error), own = same_red(nearest, 1, &own_error);
    printf("neighbours with the same red: bilinear %.3f, own cell %.3f; mean red error %.2f and %.2f pixels of red\n", blended, own,
           blended_error, own_error);
    CHECK(own > 0.6, "own cell: only %.3f of neighbouring pixels show the same red", own);
    CHECK(own_error < 2.5, "own cell: red is %.2f pixels of red off on average: not the pixel's own cell", own_error);
    CHECK(blended >= 0 && blended < 0.2, "bilinear: %.3f of neighbouring pixels show the same red", blended);
}

/* min_cell: cells a quarter of a pixel wide (here a quarter of a block,
 * each pixel nearly its own cell) become 8 blocks wide (about 11 pixels)
 * with min_cell 8, so that with bilinear = 0 most neighbouring pixels show
 * their shared cell's one mean, where without it few do. */
static void test_cache_min_cell(void)
{
    static const char *small[] = {"cache.cell_pixels=0.25", "cache.bilinear=0"};
    static const char *floored[] = {"cache.cell_pixels=0.25", "cache.bilinear=0", "cache.min_cell=8"};
    double small_error = 0, floored_error = 0;
    double free_cells = same_red(small, 2, &small_error), wide = same_red(floored, 3, &floored_error);
    printf("neighbours with the same red: cells a quarter of a pixel %.3f, min_cell 8 %.3f\n", free_cells, wide);
    CHECK(free_cells >= 0 && free_cells < 0.3, "quarter-pixel cells: %.3f of neighbouring pixels show the same red", free_cells);
    CHECK(wide > 0.75, "min_cell 8: only %.3f of neighbouring pixels show the same red", wide);
}

/* New parameter values empty the table: after the light goes from 1 to 0
 * the cache shows 0 at once, not an average with the frames before. */
static void test_cache_reset(void)
{
    vrg_graph *g = load_with("surface_cache.ini", NULL, 0, reads, COUNT);
    if (!g)
        return;
    for (int i = 0; i < 4; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_set_param(g, "light.value", 0.0) == 0, "light.value not set");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img[COUNT];
    if (read_all(g, img) == 0) {
        double worst = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                if (px(&img[POS], x, y, 3) != 0)
                    worst = fmax(worst, px(&img[CACHE], x, y, 2));
        CHECK(worst < 1e-3, "blue is up to %g one frame after it became 0: the old parameters' history survived", worst);
        free_all(img);
    }
    vrg_graph_destroy(g);
}

/* A table too small for the samples: the pixels left out show their own
 * sample, the count is the stat `uncached` and one warning names `cells`. */
static void test_cache_full(void)
{
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/surface_cache.ini", TEST_DIR);
    static const char *sets[] = {"cache.cell_pixels=0.25", "cache.cells=1024"};
    vrg_graph_desc d = {.path = path, .overrides = sets, .override_count = 2, .diag = diag, .readback = reads, .readback_count = COUNT};
    vrg_graph *g = NULL;
    if (!diag || vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load surface_cache.ini");
        if (diag)
            fclose(diag);
        free(log);
        return;
    }
    double uncached = 0;
    for (int i = 0; i < 4; i++) {
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_stat(g, "cache", "uncached", &uncached) == 0, "no stat 'uncached'");
    }
    /* 1024 slots, over 1500 floor pixels each wanting its own */
    CHECK(uncached >= 400, "uncached = %g with 1024 slots for every floor pixel", uncached);
    vrg_image_data img[COUNT];
    if (read_all(g, img) == 0) {
        double worst = 0;
        for (uint32_t y = 0; y < img[POS].height; y++)
            for (uint32_t x = 0; x < img[POS].width; x++)
                worst = fmax(worst, fabs(px(&img[CACHE], x, y, 0) - px(&img[LIGHT], x, y, 0)));
        CHECK(worst < 2e-3, "with the table full the image differs from the signal by up to %g", worst);
        free_all(img);
    }
    vrg_graph_destroy(g);
    fclose(diag);
    CHECK(log && strstr(log, "no free cell in 64 probes") && strstr(log, "cells = 1024") && strstr(log, "raise cells"),
          "no warning naming cells and the probe limit: %s", log ? log : "");
    const char *second = log ? strstr(log, "no free cell") : NULL;
    CHECK(!second || !strstr(second + 1, "no free cell"), "the warning repeats every frame: %s", log);
    free(log);
}

/* A table larger than the device binds as one storage buffer is refused
 * when the graph loads, naming cells (lavapipe binds 128 MiB). */
static int test_cache_too_large(void)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(vrg_context_device(ctx)->physical_device, &props);
    /* `cache` caches 4 channels: an entry of 16 words, 1 of the list */
    uint64_t bytes = 4u * (16u + (uint64_t)(1u << 26) * 17u);
    if (bytes <= props.limits.maxStorageBufferRange) {
        printf("skipped: this device binds %u bytes\n", props.limits.maxStorageBufferRange);
        return SKIP;
    }
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/surface_cache.ini", TEST_DIR);
    static const char *sets[] = {"cache.cells=67108864"};
    vrg_graph_desc d = {.path = path, .overrides = sets, .override_count = 1, .diag = diag};
    vrg_graph *g = NULL;
    CHECK(diag && vrg_graph_load(ctx, &d, &g) != 0, "a table of %llu bytes was accepted", (unsigned long long)bytes);
    if (g)
        vrg_graph_destroy(g);
    if (diag)
        fclose(diag);
    CHECK(log && strstr(log, "surface_cache.ini:") && strstr(log, "cells = 67108864 needs a table of") && strstr(log, "lower cells"),
          "no error naming cells: %s", log ? log : "");
    free(log);
    return 0;
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"cache_history", test_cache_history, 1, NULL}, {"cache_sun_span", test_cache_sun_span, 1, NULL}, {"cache_evict", test_cache_evict, 1, NULL}, {"cache_gather", test_cache_gather, 1, NULL},
        {"cache_sparse", test_cache_sparse, 1, NULL},
        {"cache_own_cells", test_cache_own_cells, 1, NULL}, {"cache_coarse", test_cache_coarse, 1, NULL}, {"cache_chain", test_cache_chain, 1, NULL}, {"cache_chain_levels", test_cache_chain_levels, 1, NULL}, {"cache_reset", test_cache_reset, 1, NULL},
        {"cache_nearest", test_cache_nearest, 1, NULL}, {"cache_min_cell", test_cache_min_cell, 1, NULL}, {"cache_freed_runs", test_cache_freed_runs, 1, NULL}, {"cache_full", test_cache_full, 1, NULL}, {"cache_slot_invocations", test_cache_slot_invocations, 1, NULL}, {"cache_too_large", NULL, 1, test_cache_too_large},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
