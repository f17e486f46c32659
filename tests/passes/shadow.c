#define _POSIX_C_SOURCE 200809L
/* sun_shadow's occluder distance and shadow_denoise: the distance on a
 * known scene, the output left out unless read, a contact shadow kept
 * sharp and a far occluder's penumbra smoothed, from 4 rays or from one
 * hard ray.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"

static void sun_at(float hour, float dir[3])
{
    vrg_sky_desc sd;
    vrg_sky_default(&sd);
    sd.time_of_day = hour;
    vrg_sky sky;
    vrg_sky_eval(&sd, 0, &sky);
    memcpy(dir, sky.sun_dir, sizeof sky.sun_dir);
}

static int floor_pixel(const vrg_image_data *pos, const vrg_image_data *nrm, uint32_t i)
{
    return pos->pixels[4 * i + 3] != 0 && nrm->pixels[4 * i + 1] == 1.0f && fabsf(pos->pixels[4 * i + 1] - 1.0f) < 1e-3f;
}

/* Hard shadows of a slab whose bottom is 7 blocks above the floor: each
 * floor pixel's occluder distance is the CPU shadow ray's hit distance, and
 * 7 / sun_dir.y where the ray enters the slab through its bottom (not its
 * sides); -1 where the ray reaches the sky. With a
 * soft sun (16 rays in a 4 degree cone) the mean over the rays that hit
 * stays within 3% of it in the umbra. */
static void occluder_case(const char *const *sets, uint32_t nsets, const char *what)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.normal", "shadow.visibility", "shadow.occluder"};
    const char *soft[8] = {0};
    for (uint32_t i = 0; i < nsets; i++)
        soft[i] = sets[i];
    float sun[3];
    sun_at(13, sun);
    const float want = (8.0f - 1.0f - 1e-3f) / sun[1];
    for (int pass = 0; pass < 2; pass++) {
        soft[nsets] = "shadow.sun_radius=4";
        vrg_graph *g = load_with("shadow_occluder.ini", soft, nsets + (uint32_t)pass, reads, 4);
        if (!g)
            return;
        CHECK(vrg_graph_frame(g) == 0, "%s: frame failed", what);
        vrg_image_data pos, nrm, vis, occ;
        CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "gbuffer.normal", &nrm) == 0 &&
                  vrg_graph_read(g, "shadow.visibility", &vis) == 0 && vrg_graph_read(g, "shadow.occluder", &occ) == 0,
              "%s: readback failed", what);
        const vrg_world *w = vrg_graph_world(g);
        int wrong = 0, umbra = 0, lit = 0, off = 0;
        float worst = 0;
        for (uint32_t i = 0; i < pos.width * pos.height; i++) {
            if (!floor_pixel(&pos, &nrm, i))
                continue;
            const float *p = pos.pixels + 4 * i;
            float o[3] = {p[0], p[1] + 1e-3f, p[2]}, d = occ.pixels[4 * i], v = vis.pixels[4 * i];
            vrg_world_hit hit;
            int blocked = vrg_world_pick(w, o, sun, 256, &hit);
            if (!pass) { /* hard: one ray along sun_dir, the CPU's */
                if (blocked ? fabsf(d - hit.distance) > 0.02f + 2e-3f * hit.distance : d != -1.0f)
                    wrong++;
                umbra += blocked, lit += !blocked;
            } else if (v == 0.0f || v == 1.0f) {
                wrong += v == 1.0f && d != -1.0f; /* no ray hit */
                lit += v == 1.0f;
            }
            /* where the ray along sun_dir meets the slab's bottom plane: with
             * a margin for the cone, inside its footprint (x 12..37, z
             * 16..31) every ray enters through the bottom face, at 7 / d.y */
            float qx = o[0] + sun[0] * want, qz = o[2] + sun[2] * want, m = pass ? 1.0f : 0.05f;
            if (v == 0.0f && qx > 12 + m && qx < 37 - m && qz > 16 + m && qz < 31 - m) {
                umbra += pass;
                float e = fabsf(d - want) / want;
                worst = fmaxf(worst, e);
                off += e > (pass ? 0.03f : 3e-3f);
            }
        }
        CHECK(umbra > 100 && lit > 500, "%s: shadow not in view (%d shadowed, %d lit floor pixels)", what, umbra, lit);
        CHECK(wrong <= (int)(pos.width * pos.height) / 500, "%s, sun_radius %d: %d floor pixels whose occluder distance disagrees with the CPU ray", what,
              pass ? 4 : 0, wrong);
        CHECK(off == 0, "%s, sun_radius %d: %d umbra pixels off 7 / sun_dir.y = %.3f by more than %s (worst %.2f%%)", what, pass ? 4 : 0, off, want,
              pass ? "3%" : "0.3%", 100 * worst);
        free(pos.pixels), free(nrm.pixels), free(vis.pixels), free(occ.pixels);
        vrg_graph_destroy(g);
    }
}

static void test_shadow_occluder(void) { occluder_case(NULL, 0, "dda"); }

/* The ray-query backend's any-hit is not the closest hit: the pass asks
 * for the closest when it writes the distance. */
static int test_shadow_occluder_rayquery(void)
{
    if (!vrg_context_device(ctx)->features.ray_query) {
        printf("shadow_occluder_rayquery: skipped: device '%s' has no VK_KHR_ray_query\n", vrg_context_device(ctx)->name);
        return SKIP;
    }
    static const char *sets[] = {"scene.traversal=rayquery"};
    occluder_case(sets, 1, "rayquery");
    return 0;
}

/* The occluder output is an optional one: a 1x1 stand-in unless a pass
 * reads it (shadow_denoise.ini) or it is read back. The graph's report
 * (voxrg check's listing) shows each resource's size. */
static int occluder_full_size(const vrg_graph *g)
{
    char *text = NULL, line[256] = "";
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return -1;
    vrg_graph_report(g, f);
    fclose(f);
    const char *at = strstr(text, "  shadow.occluder ");
    if (at)
        snprintf(line, sizeof line, "%.*s", (int)strcspn(at, "\n"), at);
    free(text);
    if (strstr(line, " 160x100 "))
        return 1;
    return strstr(line, " 1x1 ") && strstr(line, "(unread optional output)") ? 0 : -1;
}

static void test_shadow_occluder_unread(void)
{
    static const char *unread[] = {"shadow.visibility"}, *read[] = {"shadow.visibility", "shadow.occluder"},
                      *denoised[] = {"denoise.visibility"};
    const struct {
        const char *graph, *const *reads;
        uint32_t nreads;
        int want;
    } cases[] = {{"shadow_occluder.ini", unread, 1, 0}, {"shadow_occluder.ini", read, 2, 1}, {"shadow_denoise.ini", denoised, 1, 1}};
    for (int c = 0; c < 3; c++) {
        vrg_graph *g = load_with(cases[c].graph, NULL, 0, cases[c].reads, cases[c].nreads);
        if (!g)
            return;
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(occluder_full_size(g) == cases[c].want, "%s, reading back %s: shadow.occluder %s", cases[c].graph, cases[c].reads[cases[c].nreads - 1],
              cases[c].want ? "is not a 160x100 image" : "is not the 1x1 stand-in of an unread optional output");
        vrg_graph_destroy(g);
    }
}

/* Per image column (the walls run along x, so shadow edges are rows), the
 * pixels of the given floor strip with 0.1 < v < 0.9: the edge's width in
 * pixels, averaged over the columns where the reference has an edge (a
 * shadow in the strip and light beside it). */
static float edge_width(const vrg_image_data *pos, const vrg_image_data *nrm, const vrg_image_data *ref, const vrg_image_data *v, float x0, float x1,
                        float z0, float z1)
{
    int soft = 0, columns = 0;
    for (uint32_t x = 0; x < pos->width; x++) {
        int n = 0, dark = 0, light = 0;
        for (uint32_t y = 0; y < pos->height; y++) {
            uint32_t i = y * pos->width + x;
            const float *p = pos->pixels + 4 * i;
            if (!floor_pixel(pos, nrm, i) || p[0] < x0 || p[0] > x1 || p[2] < z0 || p[2] > z1)
                continue;
            float s = v->pixels[4 * i], r = ref->pixels[4 * i];
            n += s > 0.1f && s < 0.9f;
            dark += r <= 0.1f, light += r >= 0.9f;
        }
        if (dark && light) {
            soft += n;
            columns++;
        }
    }
    return columns >= 10 ? (float)soft / (float)columns : -1.0f;
}

/* Mean squared difference from the 64-ray visibility over the floor pixels
 * of a strip inside the reference's penumbra (0.05 < ref < 0.95). */
static double penumbra_mse(const vrg_image_data *pos, const vrg_image_data *nrm, const vrg_image_data *ref, const vrg_image_data *v, float x0, float x1,
                           int *count)
{
    double sum = 0;
    *count = 0;
    for (uint32_t i = 0; i < pos->width * pos->height; i++) {
        const float *p = pos->pixels + 4 * i;
        float r = ref->pixels[4 * i];
        if (!floor_pixel(pos, nrm, i) || p[0] < x0 || p[0] > x1 || r <= 0.05f || r >= 0.95f)
            continue;
        double d = v->pixels[4 * i] - r;
        sum += d * d;
        (*count)++;
    }
    return *count ? sum / *count : 0;
}

/* shadow_denoise.ini's shadow pass with `sets`, through the filter: the
 * contact shadow of the 3-high wall keeps an edge at most 2 pixels wide (a
 * filter of fixed radius widens it), while in the penumbra of the slab 12
 * blocks up the squared error against 64 rays falls at least 3-fold. */
static void denoise_case(const char *const *sets, uint32_t nsets, const char *what)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.normal", "shadow.visibility", "ref.visibility", "denoise.visibility"};
    vrg_graph *g = load_with("shadow_denoise.ini", sets, nsets, reads, 5);
    if (!g)
        return;
    vrg_image_data pos = {0}, nrm = {0}, raw = {0}, ref = {0}, den = {0};
    if (!CHECK(vrg_graph_frame(g) == 0, "%s: frame failed", what) ||
        !CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, "gbuffer.normal", &nrm) == 0 &&
                   vrg_graph_read(g, "shadow.visibility", &raw) == 0 && vrg_graph_read(g, "ref.visibility", &ref) == 0 &&
                   vrg_graph_read(g, "denoise.visibility", &den) == 0,
               "%s: readback failed", what)) {
        free(pos.pixels), free(nrm.pixels), free(raw.pixels), free(ref.pixels), free(den.pixels);
        vrg_graph_destroy(g);
        return;
    }
    /* the contact shadow: the wall's middle, in front of it (z < 30) */
    float ref_w = edge_width(&pos, &nrm, &ref, &ref, 8, 16, 24, 30), den_w = edge_width(&pos, &nrm, &ref, &den, 8, 16, 24, 30);
    CHECK(ref_w >= 0 && den_w >= 0, "%s: contact shadow edge not in view (widths %.2f, %.2f)", what, ref_w, den_w);
    CHECK(den_w <= 2.0f, "%s: contact shadow edge %.2f pixels wide after denoising (64 rays: %.2f), want <= 2", what, den_w, ref_w);
    int n_raw, n_den;
    double e_raw = penumbra_mse(&pos, &nrm, &ref, &raw, 31, 41, &n_raw), e_den = penumbra_mse(&pos, &nrm, &ref, &den, 31, 41, &n_den);
    CHECK(n_raw > 100, "%s: far penumbra not in view (%d pixels)", what, n_raw);
    CHECK(e_den * 3 <= e_raw, "%s: far penumbra: squared error %.5f after denoising, %.5f before: want a 3-fold drop", what, e_den, e_raw);
    printf("%s: contact edge %.2f px (64 rays %.2f); far penumbra (%d px) mse %.5f -> %.5f\n", what, den_w, ref_w, n_raw, e_raw, e_den);
    free(pos.pixels), free(nrm.pixels), free(raw.pixels), free(ref.pixels), free(den.pixels);
    vrg_graph_destroy(g);
}

/* 4 rays toward the 6-degree disc: the filter removes their noise */
static void test_shadow_denoise(void) { denoise_case(NULL, 0, "4 rays"); }

/* One ray to the sun's centre (a hard shadow, no noise) and the filter
 * told the disc's radius: it spreads the hard edge over the penumbra's
 * width from the ray's blocker distance (PCSS's idea with an exact
 * blocker), which is how the 1-ray graphs shade a soft sun. */
static void test_shadow_denoise_hard(void)
{
    static const char *hard[] = {"shadow.sun_radius=0"};
    denoise_case(hard, 1, "hard ray");
}

/* shadow_grazing.ini: the ground seen 10 degrees down, a slab's penumbra
 * on it, one hard ray spread by the filter with each kernel. A disc in
 * pixels is as wide in pixels across the view as along it, where the
 * ground's blocks are foreshortened, so it spreads the shadow's edges that
 * face the camera over several penumbra widths; the disc on the face,
 * projected, does not: its squared error against 64 rays, over the floor
 * pixels in the slab's shadow and penumbra (x 28..47, z 12..47), must be at
 * most 0.7 times the screen kernel's and below the unfiltered hard ray's. */
static double grazing_mse(const char *kernel, double *hard, int *count)
{
    static const char *reads[] = {"gbuffer.position", "gbuffer.normal", "shadow.visibility", "ref.visibility", "denoise.visibility"};
    char set[64];
    snprintf(set, sizeof set, "denoise.kernel=%s", kernel);
    const char *sets[] = {set};
    vrg_graph *g = load_with("shadow_grazing.ini", sets, 1, reads, 5);
    if (!g)
        return -1;
    enum { POS, NRM, RAW, REF, DEN, N };
    vrg_image_data img[N];
    double sum = 0, sum_hard = 0;
    *count = 0;
    if (CHECK(vrg_graph_frame(g) == 0, "kernel %s: frame failed", kernel) && read_images(g, reads, img, N) == 0) {
        for (uint32_t i = 0; i < img[POS].width * img[POS].height; i++) {
            const float *p = img[POS].pixels + 4 * i;
            if (!floor_pixel(&img[POS], &img[NRM], i) || p[0] < 28 || p[2] < 12)
                continue;
            double d = img[DEN].pixels[4 * i] - img[REF].pixels[4 * i], h = img[RAW].pixels[4 * i] - img[REF].pixels[4 * i];
            sum += d * d, sum_hard += h * h;
            (*count)++;
        }
        for (int k = 0; k < N; k++)
            free(img[k].pixels);
    }
    vrg_graph_destroy(g);
    *hard = *count ? sum_hard / *count : 0;
    return *count ? sum / *count : -1;
}

static void test_shadow_denoise_surface(void)
{
    int n_screen, n_surface;
    double hard, hard2, screen = grazing_mse("screen", &hard, &n_screen), surface = grazing_mse("surface", &hard2, &n_surface);
    if (!CHECK(n_screen > 1000 && n_surface == n_screen, "the slab's shadow is not in view (%d, %d floor pixels)", n_screen, n_surface))
        return;
    CHECK(surface <= 0.7 * screen, "grazing ground: squared error %.5f with the surface kernel, %.5f with the screen kernel: want at most 0.7 times", surface,
          screen);
    CHECK(hard == hard2, "grazing ground: the unfiltered hard ray differs between the two runs (%.6f, %.6f)", hard, hard2);
    CHECK(surface < hard, "grazing ground: squared error %.5f with the surface kernel, %.5f unfiltered", surface, hard);
    printf("grazing ground (%d px): mse hard %.5f, screen kernel %.5f, surface kernel %.5f\n", n_screen, hard, screen, surface);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"shadow_occluder", test_shadow_occluder, 1},
        {"shadow_occluder_rayquery", NULL, 1, test_shadow_occluder_rayquery},
        {"shadow_occluder_unread", test_shadow_occluder_unread, 1},
        {"shadow_denoise", test_shadow_denoise, 1},
        {"shadow_denoise_hard", test_shadow_denoise_hard, 1},
        {"shadow_denoise_surface", test_shadow_denoise_surface, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
