#define _POSIX_C_SOURCE 200809L
/* The lighting pass: sun and sky on floors and walls, penumbrae, corners, half
 * resolution, and lighting chained after another pass.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"
#include "voxrg/sky.h"

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

/* The haze pass against the formula on the CPU, from the frame's own
 * uniforms: hits keep exp(-density d) of their colour and are all haze at
 * the streamed world's view radius (terrain radius 1: 16 blocks); misses
 * below the horizon are all haze, the sky above is unchanged. The camera
 * looks over the edge of the loaded chunks. */
static void test_haze(void)
{
    static const char *text =
        "[graph]\noutput = hazed\nwidth = 96\nheight = 54\n"
        "[camera]\nposition = 0 45 0\nyaw = -30\npitch = -12\n"
        "[scene]\nplugin = terrain\nradius = 1\nthreads = 2\ntime_of_day = 16\n"
        "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n"
        "[pass haze]\nplugin = haze\nin.color = gbuffer.albedo\nin.position = gbuffer.position\nin.frame = frame\nout.color = hazed\n"
        "density = 0.01\nstart = 0.5\n";
    static const char *reads[] = {"gbuffer.position", "gbuffer.albedo", "frame"};
    vrg_graph *g = load_text(text, reads, 3);
    if (!g)
        return;
    vrg_image_data pos, col, out;
    void *data = NULL;
    uint64_t size = 0;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "gbuffer.albedo", &col) == 0 &&
              vrg_graph_read(g, "hazed", &out) == 0 && vrg_graph_read_buffer(g, "frame", &data, &size) == 0,
          "frame or readback failed");
    if (failures) {
        vrg_graph_destroy(g);
        return;
    }
    vrg_frame_uniforms u;
    memcpy(&u, data, sizeof u);
    CHECK(u.world_grid[3] == 16, "view radius %d, want 16 (radius 1)", u.world_grid[3]);
    vrg_sky sky = {0};
    memcpy(sky.sun_dir, u.sun_dir, sizeof sky.sun_dir);
    sky.sun_elevation = u.sun_dir[3];
    memcpy(sky.sun_radiance, u.sun_radiance, sizeof sky.sun_radiance);
    memcpy(sky.sky_zenith, u.sky_zenith, sizeof sky.sky_zenith);
    memcpy(sky.sky_horizon, u.sky_horizon, sizeof sky.sky_horizon);
    int wrong = 0, edge = 0, below = 0, sky_px = 0;
    for (uint32_t y = 0; y < out.height; y++)
        for (uint32_t x = 0; x < out.width; x++) {
            float ray[3], d[3];
            vrg_camera_ray(vrg_graph_camera(g), out.width, out.height, (float)x, (float)y, ray);
            const float *p = pos.pixels + 4 * (y * out.width + x), *c = col.pixels + 4 * (y * out.width + x);
            float flat[3] = {ray[0], ray[1] > 0 ? ray[1] : 0, ray[2]}, n = sqrtf(flat[0] * flat[0] + flat[1] * flat[1] + flat[2] * flat[2]);
            for (int k = 0; k < 3; k++)
                flat[k] /= n;
            float haze[3], f;
            vrg_sky_radiance(&sky, flat, haze);
            if (p[3] > 0.5f) {
                for (int k = 0; k < 3; k++)
                    d[k] = p[k] - u.camera_pos[k];
                float dist = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), dh = sqrtf(d[0] * d[0] + d[2] * d[2]);
                float t = fminf(fmaxf((dh - 8.0f) / 8.0f, 0.0f), 1.0f);
                f = fmaxf(1.0f - expf(-0.01f * dist), t * t * (3 - 2 * t));
                edge += dh >= 16.0f;
            } else {
                f = ray[1] < 0 ? 1.0f : 0.0f;
                below += ray[1] < -0.02f;
                sky_px += ray[1] > 0.02f;
            }
            for (int k = 0; k < 3; k++) {
                float want = c[k] + (haze[k] - c[k]) * f, got = out.pixels[4 * (y * out.width + x) + k];
                wrong += fabsf(got - want) > 4e-3f + 2e-3f * fabsf(want);
            }
        }
    CHECK(wrong == 0, "%d channels differ from the haze formula", wrong);
    CHECK(edge > 20 && below > 20 && sky_px > 20, "the view does not cover the cases: %d hits beyond the radius, %d misses below, %d sky", edge, below,
          sky_px);
    free(pos.pixels);
    free(col.pixels);
    free(out.pixels);
    free(data);
    vrg_graph_destroy(g);
}

/* ---- stratified sampling ---- */

/* The per-pixel mean of `res` over `frames` frames of `graph` with sets,
 * and (pos not NULL) the G-buffer position; 0 on failure, with nothing
 * left allocated. */
static int mean_over_frames(const char *graph, const char *const *sets, uint32_t nsets, const char *res, int frames, vrg_image_data *mean,
                            vrg_image_data *pos)
{
    const char *reads[] = {res, "gbuffer.position"};
    vrg_graph *g = load_with(graph, sets, nsets, reads, pos ? 2 : 1);
    *mean = (vrg_image_data){0};
    if (!g)
        return 0;
    int ok = 1;
    for (int f = 0; f < frames && ok; f++) {
        vrg_image_data img;
        ok = vrg_graph_frame(g) == 0 && vrg_graph_read(g, res, &img) == 0;
        CHECK(ok, "%s: frame %d failed", graph, f);
        if (!ok)
            break;
        if (!mean->pixels) {
            *mean = img;
            continue;
        }
        for (uint32_t i = 0; i < 4 * img.width * img.height; i++)
            mean->pixels[i] += img.pixels[i];
        free(img.pixels);
    }
    for (uint32_t i = 0; ok && i < 4 * mean->width * mean->height; i++)
        mean->pixels[i] /= (float)frames;
    if (ok && pos) {
        ok = vrg_graph_read(g, "gbuffer.position", pos) == 0;
        CHECK(ok, "%s: cannot read gbuffer.position", graph);
    }
    vrg_graph_destroy(g);
    if (!ok) {
        free(mean->pixels);
        mean->pixels = NULL;
    }
    return ok;
}

/* RMS difference of channel 0 between the means of a and ref over blocks
 * of tile x tile pixels (tile = 1: single pixels), over the blocks whose
 * every pixel is on geometry and whose ref mean lies inside (lo, hi);
 * *count: how many blocks. */
static double tile_rms(const vrg_image_data *a, const vrg_image_data *ref, const vrg_image_data *pos, uint32_t tile, float lo, float hi,
                       int *count)
{
    double sum = 0;
    *count = 0;
    for (uint32_t ty = 0; ty + tile <= pos->height; ty += tile)
        for (uint32_t tx = 0; tx + tile <= pos->width; tx += tile) {
            double ma = 0, mr = 0;
            int on = 1;
            for (uint32_t y = ty; y < ty + tile; y++)
                for (uint32_t x = tx; x < tx + tile; x++) {
                    on &= px(pos, x, y, 3) != 0;
                    ma += px(a, x, y, 0), mr += px(ref, x, y, 0);
                }
            mr /= tile * tile, ma /= tile * tile;
            if (!on || mr <= lo || mr >= hi)
                continue;
            sum += (ma - mr) * (ma - mr);
            (*count)++;
        }
    return *count ? sqrt(sum / *count) : -1;
}

/* stratified = 1 draws one ray per pixel from a sequence that covers the
 * hemisphere (indirect, ao) or the sun's disc (sun_shadow) evenly over
 * each 4x4 tile and over the frames: against 64 rays per pixel over 4
 * frames, a tile's mean of one frame and a pixel's mean of 8 frames are
 * closer than with independent random numbers, and the image is still the
 * same on every run. */
static void test_light_stratified(void)
{
    static const struct {
        const char *graph, *res, *pass;
        float lo, hi; /* tiles whose reference lies in (lo, hi): the indirect light anywhere, the sun's penumbrae, AO near the walls */
    } cases[] = {
        {"light_corner.ini", "indirect.irradiance", "indirect", -1e9f, 1e9f},
        {"light_penumbra.ini", "shadow.visibility", "shadow", 0.02f, 0.98f},
        {"light_corner.ini", "ao.ao", "ao", -1e9f, 0.98f},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char rays[64], white[64], strat[64];
        snprintf(rays, sizeof rays, "%s.rays=1", cases[c].pass);
        snprintf(white, sizeof white, "%s.stratified=0", cases[c].pass);
        snprintf(strat, sizeof strat, "%s.stratified=1", cases[c].pass);
        const char *ref_sets[] = {white}, *white_sets[] = {rays, white}, *strat_sets[] = {rays, strat};
        vrg_image_data ref = {0}, pos = {0}, w1 = {0}, s1 = {0}, w8 = {0}, s8 = {0}, again = {0};
        /* 64 rays a pixel over 4 frames; 1 ray in one frame; 1 ray over 8 frames, twice stratified */
        int ok = mean_over_frames(cases[c].graph, ref_sets, 1, cases[c].res, 4, &ref, &pos) &&
                 mean_over_frames(cases[c].graph, white_sets, 2, cases[c].res, 1, &w1, NULL) &&
                 mean_over_frames(cases[c].graph, strat_sets, 2, cases[c].res, 1, &s1, NULL) &&
                 mean_over_frames(cases[c].graph, white_sets, 2, cases[c].res, 8, &w8, NULL) &&
                 mean_over_frames(cases[c].graph, strat_sets, 2, cases[c].res, 8, &s8, NULL) &&
                 mean_over_frames(cases[c].graph, strat_sets, 2, cases[c].res, 8, &again, NULL);
        if (ok) {
            int n_tiles, n_pixels, n;
            double tile_white = tile_rms(&w1, &ref, &pos, 4, cases[c].lo, cases[c].hi, &n_tiles);
            double tile_strat = tile_rms(&s1, &ref, &pos, 4, cases[c].lo, cases[c].hi, &n);
            double pixel_white = tile_rms(&w8, &ref, &pos, 1, cases[c].lo, cases[c].hi, &n_pixels);
            double pixel_strat = tile_rms(&s8, &ref, &pos, 1, cases[c].lo, cases[c].hi, &n);
            printf("%s: RMS against 256 rays, 4x4 tile of one frame: random %.4f, stratified %.4f (%d tiles); pixel over 8 frames: random %.4f, "
                   "stratified %.4f (%d pixels)\n",
                   cases[c].pass, tile_white, tile_strat, n_tiles, pixel_white, pixel_strat, n_pixels);
            CHECK(n_tiles >= 10 && n_pixels >= 100, "%s: only %d tiles and %d pixels measured", cases[c].pass, n_tiles, n_pixels);
            CHECK(tile_strat < 0.75 * tile_white, "%s: a 4x4 tile's mean is %.4f off stratified, %.4f with random numbers", cases[c].pass, tile_strat,
                  tile_white);
            CHECK(pixel_strat < 0.8 * pixel_white, "%s: a pixel's mean over 8 frames is %.4f off stratified, %.4f with random numbers", cases[c].pass,
                  pixel_strat, pixel_white);
            CHECK(memcmp(s8.pixels, again.pixels, 16u * s8.width * s8.height) == 0, "%s: stratified sampling is not deterministic", cases[c].pass);
        }
        free(ref.pixels), free(pos.pixels), free(w1.pixels), free(s1.pixels), free(w8.pixels), free(s8.pixels), free(again.pixels);
    }
}

/* young_rays: each pixel's indirect light is exactly the 4-ray pass's
 * where it is young (last frame's clamped_reproject length, at the pixel
 * p - motion it came from, below young_history 3, or p - motion off
 * screen) and the 1-ray pass's elsewhere (one random stream per pixel).
 * Frame 0 (no history) is young everywhere, the held camera's frame 5 is
 * old everywhere (anti-lag off: only geometry cuts the history), and
 * after a step sideways the pixels that came from off screen are young,
 * the rest old. */
static void test_light_young(void)
{
    static const char *reads[] = {"indirect.irradiance", "one_ray", "four_rays", "reproject.length", "gbuffer.motion", "gbuffer.position"};
    enum { OUT, ONE, FOUR, LENGTH, MOTION, POS, COUNT };
    vrg_graph *g = load_with("light_young.ini", NULL, 0, reads, COUNT);
    if (!g)
        return;
    vrg_image_data img[COUNT] = {{0}}, prev_length = {0};
    int young_frame0 = -1, old_frame5 = -1, off_moved = 0, old_moved = 0;
    for (int f = 0; f < 8; f++) {
        if (f == 6) {
            vrg_camera cam = *vrg_graph_camera(g);
            cam.position[0] += 3.0f; /* the view slides: its left edge shows ground last frame did not */
            vrg_graph_set_camera(g, &cam);
        }
        if (!CHECK(vrg_graph_frame(g) == 0, "frame %d failed", f))
            break;
        int ok = 1;
        for (int i = 0; i < COUNT; i++) {
            free(img[i].pixels);
            img[i].pixels = NULL;
            ok = ok && vrg_graph_read(g, reads[i], &img[i]) == 0;
        }
        if (!CHECK(ok, "frame %d: readback failed", f))
            break;
        int young = 0, old = 0, off_screen = 0, wrong = 0;
        for (uint32_t y = 0; y < img[OUT].height; y++)
            for (uint32_t x = 0; x < img[OUT].width; x++) {
                if (px(&img[POS], x, y, 3) == 0.0f)
                    continue;
                float qx = floorf((float)x - px(&img[MOTION], x, y, 0) + 0.5f), qy = floorf((float)y - px(&img[MOTION], x, y, 1) + 0.5f);
                int off = qx < 0 || qy < 0 || qx >= (float)img[OUT].width || qy >= (float)img[OUT].height;
                int is_young = f == 0 || off || px(&prev_length, (uint32_t)qx, (uint32_t)qy, 0) < 3.0f;
                young += is_young, old += !is_young, off_screen += off;
                for (int c = 0; c < 3; c++)
                    wrong += px(&img[OUT], x, y, c) != px(&img[is_young ? FOUR : ONE], x, y, c);
            }
        CHECK(wrong == 0, "frame %d: %d channels are not the %s pass's (%d young pixels, %d old)", f, wrong, "1- or 4-ray", young, old);
        if (f == 0)
            young_frame0 = old == 0 ? young : -1;
        if (f == 5)
            old_frame5 = young == 0 ? old : -1;
        if (f == 6)
            off_moved = off_screen, old_moved = old;
        free(prev_length.pixels);
        prev_length = img[LENGTH];
        img[LENGTH].pixels = NULL;
    }
    CHECK(young_frame0 > 1000, "frame 0: %d pixels, want every surface pixel young (-1: some were not)", young_frame0);
    CHECK(old_frame5 > 1000, "frame 5 of a held camera: %d pixels, want every surface pixel old (-1: some were not)", old_frame5);
    CHECK(off_moved > 50 && old_moved > 1000, "after the step: %d pixels came from off screen, %d are old: want both", off_moved, old_moved);
    for (int i = 0; i < COUNT; i++)
        free(img[i].pixels);
    free(prev_length.pixels);
    vrg_graph_destroy(g);
}

/* ao's ray-query variant (the one-file pass's in_tlas, declared where the
 * scene built a TLAS): the corner's AO ordering, and the same AO as the DDA
 * variant's (light_corner.ini connects the tlas, empty on the DDA) but on
 * at most 0.5% of the pixels (a ray grazing an edge may decide either way). */
static int test_ao_rayquery(void)
{
    if (!vrg_context_device(ctx)->features.ray_query) {
        printf("ao_rayquery: skipped: device '%s' has no VK_KHR_ray_query\n", vrg_context_device(ctx)->name);
        return SKIP;
    }
    static const char *reads[] = {"gbuffer.position", "ao.ao"};
    static const char *rq[] = {"scene.traversal=rayquery"};
    vrg_image_data pos, ao[2];
    for (int k = 0; k < 2; k++) {
        vrg_graph *g = load_with("light_corner.ini", k ? rq : NULL, (uint32_t)k, reads, 2);
        if (!g)
            return 0;
        CHECK(vrg_graph_frame(g) == 0, "%s: frame failed", k ? "rayquery" : "dda");
        CHECK((k || vrg_graph_read(g, "gbuffer.position", &pos) == 0) && vrg_graph_read(g, "ao.ao", &ao[k]) == 0, "readback failed");
        vrg_graph_destroy(g);
    }
    float corner = floor_mean(&pos, &ao[1], 0, 1.5f, 1.5f, 0.5f, NULL), edge = floor_mean(&pos, &ao[1], 0, 16.0f, 1.5f, 0.5f, NULL),
          open = floor_mean(&pos, &ao[1], 0, 16.0f, 16.0f, 0.5f, NULL);
    CHECK(corner >= 0 && corner < edge && edge < open && open > 0.97f, "rayquery AO corner %.3f, edge %.3f, open %.3f: want corner < edge < open", corner,
          edge, open);
    uint32_t n = ao[0].width * ao[0].height, differ = 0;
    for (uint32_t i = 0; i < n; i++)
        differ += ao[0].pixels[4 * i] != ao[1].pixels[4 * i];
    CHECK(ao[1].width == ao[0].width && differ <= n / 200, "%u of %u pixels' AO differ between the DDA and ray queries", differ, n);
    free(pos.pixels), free(ao[0].pixels), free(ao[1].pixels);
    return 0;
}

/* shade (combine, modulate, haze and tonemap in one pass) against the chain
 * of the four passes in the same graph, on the same inputs, with the same
 * parameters: every channel within 1 in 255 (the chain rounds its
 * illumination, colour and hazed colour to half floats), for settings of
 * the parameters they share, with the optional inputs unconnected in both,
 * and with a half-size indirect light. The views hold what each step acts
 * on: on a floor of blocks a lamp's emitting faces, sunlit and shadowed
 * floor, floor far enough to be hazed and the sky; on the streamed terrain
 * (radius 1: a view radius of 16 blocks) ground between `start` (0.3) and
 * the default 0.6 of that radius, which only `start` hazes at its edge. */
/* the floor of blocks: a wall, a lamp, the sun at 16:00 */
#define SHADE_BLOCKS                                                                                                             \
    "[camera]\nposition = 6 5 6\nyaw = -135\npitch = -8\n"                                                                      \
    "[scene]\nplugin = blocks\nbox = 0 0 0 47 0 47 white\nbox = 14 1 8 15 6 30 stone\nbox = 9 1 12 10 2 13 lamp\ntime_of_day = 16\n"
typedef struct {
    const char *scene;   /* [camera] and [scene] */
    float camera[3];
    int streamed;        /* the terrain: check the edge haze, not the lamp and shadows */
    const char *shared;  /* haze's and tonemap's parameters, also shade's */
    const char *combine; /* combine's, also shade's */
    int unconnected;     /* no visibility, indirect or emission in either */
    int half_indirect;   /* the indirect light at half size */
} shade_setting;

static void test_shade_chain(void)
{
    static const shade_setting settings[] = {
        {SHADE_BLOCKS, {6, 5, 6}, 0, "density = 0.02\nexposure = 0.45\n", ""},
        {SHADE_BLOCKS, {6, 5, 6}, 0, "density = 0.005\nexposure = 0.8\ncurve = reinhard\n", "direct_scale = 0.7\nindirect_scale = 1.6\n"},
        {SHADE_BLOCKS, {6, 5, 6}, 0, "density = 0.05\nexposure = 0.3\ncurve = linear\n", "direct_scale = 1.3\nindirect_scale = 0.5\n"},
        {"[camera]\nposition = 0 45 0\nyaw = -30\npitch = -40\n[scene]\nplugin = terrain\nradius = 1\nthreads = 2\ntime_of_day = 16\n",
         {0, 45, 0}, 1, "density = 0.002\nstart = 0.3\nexposure = 0.6\n", ""},
        {SHADE_BLOCKS, {6, 5, 6}, 0, "density = 0.02\nexposure = 0.45\n", "indirect_scale = 1.6\n", 1, 0},
        {SHADE_BLOCKS, {6, 5, 6}, 0, "density = 0.02\nexposure = 0.45\n", "", 0, 1},
    };
    for (size_t s = 0; s < sizeof settings / sizeof settings[0]; s++) {
        const shade_setting *st = &settings[s];
        char haze_set[128] = "", tone_set[128] = "";
        for (const char *l = st->shared; *l;) {
            const char *e = strchr(l, '\n');
            char *to = strncmp(l, "density", 7) == 0 || strncmp(l, "start", 5) == 0 ? haze_set : tone_set;
            snprintf(to + strlen(to), sizeof haze_set - strlen(to), "%.*s\n", (int)(e - l), l);
            l = e + 1;
        }
        const char *lights = st->unconnected ? "" : "in.visibility = sun\nin.indirect = indirect\n";
        const char *emits = st->unconnected ? "" : "in.emission = emission\n";
        char *text = NULL;
        size_t len = 0;
        append(&text, &len,
               "[graph]\noutput = ldr\nwidth = 96\nheight = 54\n%s"
               "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nout.emission = emission\n"
               "[pass shadow]\nplugin = sun_shadow\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\nin.normal = gbuffer.normal\n"
               "out.visibility = sun\nrays = 1\nsun_radius = 0\n"
               "[pass indirect]\nplugin = indirect\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\nin.normal = gbuffer.normal\n"
               "out.irradiance = indirect\nrays = 2\n%s"
               "[pass combine]\nplugin = combine\nin.normal = gbuffer.normal\nin.frame = frame\n%s"
               "out.illumination = illumination\n%s"
               "[pass modulate]\nplugin = modulate\nin.illumination = illumination\nin.albedo = gbuffer.albedo\n%sout.color = color\n"
               "[pass haze]\nplugin = haze\nin.color = color\nin.position = gbuffer.position\nin.frame = frame\nout.color = hazed\n%s"
               "[pass tonemap]\nplugin = tonemap\nin.color = hazed\nout.ldr = ldr\n%s"
               "[pass shade]\nplugin = shade\nin.normal = gbuffer.normal\nin.frame = frame\n%s"
               "in.albedo = gbuffer.albedo\n%sin.position = gbuffer.position\nout.ldr = shaded\n%s%s",
               st->scene, st->half_indirect ? "output_scale = 0.5\n" : "", lights, st->combine, emits, haze_set, tone_set, lights, emits,
               st->shared, st->combine);
        static const char *reads[] = {"shaded", "sun", "emission", "gbuffer.position", "indirect"};
        vrg_graph *g = load_text(text, reads, 5);
        free(text);
        if (!g)
            return;
        vrg_image_data chain, shaded, sun, emission, pos, indirect;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "ldr", &chain) == 0 && vrg_graph_read(g, "shaded", &shaded) == 0 &&
                  vrg_graph_read(g, "sun", &sun) == 0 && vrg_graph_read(g, "emission", &emission) == 0 &&
                  vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "indirect", &indirect) == 0,
              "frame or readback failed");
        if (failures) {
            vrg_graph_destroy(g);
            return;
        }
        int wrong = 0, lamp = 0, lit = 0, shadowed = 0, far = 0, edge = 0, sky = 0;
        CHECK(indirect.width == (st->half_indirect ? chain.width / 2 : chain.width), "setting %zu: indirect light %ux%u", s, indirect.width,
              indirect.height);
        double worst = 0;
        for (uint32_t y = 0; y < chain.height; y++)
            for (uint32_t x = 0; x < chain.width; x++) {
                for (int c = 0; c < 3; c++) {
                    double d = fabs((double)px(&chain, x, y, c) - px(&shaded, x, y, c));
                    worst = d > worst ? d : worst;
                    wrong += d > 1.0 / 255 + 1e-6;
                }
                if (px(&pos, x, y, 3) == 0) {
                    sky++;
                    continue;
                }
                float dx = px(&pos, x, y, 0) - st->camera[0], dz = px(&pos, x, y, 2) - st->camera[2];
                lamp += px(&emission, x, y, 0) > 0;
                lit += px(&sun, x, y, 0) > 0.5f;
                shadowed += px(&sun, x, y, 0) < 0.5f;
                far += dx * dx + dz * dz > 30 * 30;
                float d2 = dx * dx + dz * dz;
                edge += d2 > 0.3f * 16 * 0.3f * 16 && d2 < 0.6f * 16 * 0.6f * 16; /* hazed by `start` 0.3, not by the default 0.6 */
            }
        printf("shade_chain %zu: largest difference %.5f (%d channels over 1/255); lamp %d, lit %d, shadowed %d, far %d, edge haze %d, sky %d px\n",
               s, worst, wrong, lamp, lit, shadowed, far, edge, sky);
        CHECK(wrong == 0, "setting %zu: %d channels differ from the chain's by more than 1/255 (largest %.4f)", s, wrong, worst);
        if (st->streamed)
            CHECK(edge >= 100 && sky >= 50, "setting %zu: the view does not show the edge haze: %d px between 0.3 and 0.6 of the view radius, sky %d px",
                  s, edge, sky);
        else
            CHECK(lamp >= 10 && lit >= 100 && shadowed >= 50 && far >= 100 && sky >= 50,
                  "setting %zu: the view does not show every case: lamp %d, lit %d, shadowed %d, far %d, sky %d px", s, lamp, lit, shadowed, far, sky);
        free(chain.pixels), free(shaded.pixels), free(sun.pixels), free(emission.pixels), free(pos.pixels), free(indirect.pixels);
        vrg_graph_destroy(g);
    }
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"haze", test_haze, 1},
        {"light_floor", test_light_floor, 1},
        {"light_wall", test_light_wall, 1},
        {"light_half_res", test_light_half_res, 1},
        {"light_penumbra", test_light_penumbra, 1},
        {"light_corner", test_light_corner, 1},
        {"light_chain", test_light_chain, 1},
        {"shade_chain", test_shade_chain, 1},
        {"light_young", test_light_young, 1},
        {"light_stratified", test_light_stratified, 1},
        {"ao_rayquery", NULL, 1, test_ao_rayquery},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
