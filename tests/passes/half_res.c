#define _POSIX_C_SOURCE 200809L /* open_memstream */
/* Half-resolution lighting: gbuffer_downsample against the full G-buffer,
 * bilateral_upsample against each pixel's known answer (the half G-buffer's
 * own normals and positions upsampled), and a [pass]'s output_scale. */
#include "harness.h"

static const char *const reads[] = {"gbuffer.position", "gbuffer.normal", "gbuffer.ids", "gbuffer.motion", "half.position", "half.normal",
                                    "half.ids",         "half.motion",    "up_normal",   "up_position",    "up_bilinear",  "vis_half",
                                    "vis_quarter",      "atrous.color",   "up_ring_normal", "up_ring_position", "up_facing_normal", "up_facing_position",
                                    "up_facing2_normal", "up_facing2_position"};
enum {
    FULL_POS,
    FULL_N,
    FULL_IDS,
    FULL_MOTION,
    HALF_POS,
    HALF_N,
    HALF_IDS,
    HALF_MOTION,
    UP_N,
    UP_POS,
    UP_BILINEAR,
    VIS_HALF,
    VIS_QUARTER,
    ATROUS,
    UP_RING_N,
    UP_RING_POS,
    UP_FACING_N,
    UP_FACING_POS,
    UP_FACING2_N,
    UP_FACING2_POS,
    COUNT
};

/* Two frames, the camera stepped sideways in between (motion vectors). */
static vrg_graph *render_two(vrg_image_data img[COUNT])
{
    vrg_graph *g = load_with("half_res.ini", NULL, 0, reads, COUNT);
    if (!g)
        return NULL;
    vrg_camera cam = *vrg_graph_camera(g);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    cam.position[0] += 0.7f;
    cam.position[2] += 0.3f;
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    if (read_images(g, reads, img, COUNT) != 0) {
        vrg_graph_destroy(g);
        return NULL;
    }
    return g;
}

static void release(vrg_graph *g, vrg_image_data img[COUNT])
{
    for (int i = 0; i < COUNT; i++)
        free(img[i].pixels);
    vrg_graph_destroy(g);
}

/* Each half pixel is the full pixel vrg_pixel_in maps it to, (2x+1, 2y+1),
 * motion halved; output_scale halves an output, a [resource] scale wins. */
static void test_gbuffer_downsample(void)
{
    vrg_image_data img[COUNT];
    vrg_graph *g = render_two(img);
    if (!g)
        return;
    const vrg_image_data *full = &img[FULL_POS];
    for (int i = HALF_POS; i <= HALF_MOTION; i++)
        CHECK(img[i].width * 2 == full->width && img[i].height * 2 == full->height, "%s is %ux%u, the G-buffer %ux%u", reads[i], img[i].width,
              img[i].height, full->width, full->height);
    CHECK(img[VIS_HALF].width * 2 == full->width && img[VIS_HALF].height * 2 == full->height, "output_scale 0.5: vis_half is %ux%u",
          img[VIS_HALF].width, img[VIS_HALF].height);
    CHECK(img[VIS_QUARTER].width * 4 == full->width && img[VIS_QUARTER].height * 4 == full->height,
          "[resource] scale 0.25 over output_scale 0.5: vis_quarter is %ux%u", img[VIS_QUARTER].width, img[VIS_QUARTER].height);
    CHECK(img[ATROUS].width * 2 == full->width && img[ATROUS].height * 2 == full->height, "output_scale 0.5: atrous.color is %ux%u",
          img[ATROUS].width, img[ATROUS].height);
    /* its scratch images (vrg_pass_request_image) follow output_scale: what check prints */
    char *report = NULL;
    size_t report_len = 0;
    FILE *f = open_memstream(&report, &report_len);
    if (f) {
        vrg_graph_report(g, f);
        fclose(f);
    }
    for (int i = 0; i < 2; i++) {
        const char *line = report ? strstr(report, i ? "atrous.pong " : "atrous.ping ") : NULL;
        CHECK(line && strstr(line, "48x32") && strstr(line, "48x32") < strchr(line, '\n'), "sparse_atrous's %s is not 48x32 in the report: %.80s",
              i ? "pong" : "ping", line ? line : "(missing)");
    }
    free(report);
    int differ = 0, moving = 0, hits = 0;
    for (uint32_t y = 0; y < img[HALF_POS].height; y++)
        for (uint32_t x = 0; x < img[HALF_POS].width; x++) {
            for (int i = 0; i < 3; i++)
                for (int c = 0; c < 4; c++)
                    differ += px(&img[HALF_POS + i], x, y, c) != px(&img[FULL_POS + i], 2 * x + 1, 2 * y + 1, c);
            for (int c = 0; c < 2; c++) {
                float want = 0.5f * px(&img[FULL_MOTION], 2 * x + 1, 2 * y + 1, c), got = px(&img[HALF_MOTION], x, y, c);
                differ += fabsf(got - want) > 1e-3f * (1.0f + fabsf(want));
                moving += fabsf(want) > 0.2f;
            }
            hits += px(&img[HALF_POS], x, y, 3) != 0.0f;
        }
    CHECK(differ == 0, "%d half G-buffer channels differ from the full-resolution pixel under them (motion: halved)", differ);
    CHECK(moving > 100 && hits > 500, "the view does not test it: %d moving channels, %d hits", moving, hits);
    release(g, img);
}

/* Whether the half texel q lies on full pixel (x, y)'s surface: the
 * shader's test (bilateral_upsample.c), plane_tolerance 0.1. */
static int on_surface(const vrg_image_data img[COUNT], uint32_t x, uint32_t y, int qx, int qy, float *dist)
{
    float d[3], along = 0, len = 0, ndot = 0;
    if (px(&img[HALF_POS], (uint32_t)qx, (uint32_t)qy, 3) == 0.0f)
        return 0;
    for (int c = 0; c < 3; c++) {
        d[c] = px(&img[HALF_POS], (uint32_t)qx, (uint32_t)qy, c) - px(&img[FULL_POS], x, y, c);
        along += d[c] * px(&img[FULL_N], x, y, c);
        len += d[c] * d[c];
        ndot += px(&img[HALF_N], (uint32_t)qx, (uint32_t)qy, c) * px(&img[FULL_N], x, y, c);
    }
    *dist = sqrtf(len);
    return ndot >= 0.9f && fabsf(along) <= 0.1f * *dist + 1e-3f;
}

static float dist3(const vrg_image_data *a, uint32_t ax, uint32_t ay, const vrg_image_data *b, uint32_t bx, uint32_t by)
{
    float d = 0;
    for (int c = 0; c < 3; c++)
        d += (px(a, ax, ay, c) - px(b, bx, by, c)) * (px(a, ax, ay, c) - px(b, bx, by, c));
    return sqrtf(d);
}

/* Full pixel x lies between half texels b = floor((x - 1) / 2) and b + 1
 * (half texel q holds full pixel 2q+1), at fraction f past b. */
static int texel_below(uint32_t x, float *f)
{
    int b = (int)floorf(((float)x - 1.0f) / 2.0f);
    *f = ((float)x - 1.0f) / 2.0f - (float)b;
    return b;
}

/* Texel q clamped into the half image, as the shader's texelFetch of clamp(). */
static int clamp_texel(int q, uint32_t size) { return q < 0 ? 0 : q >= (int)size ? (int)size - 1 : q; }

/* Upsampling the half G-buffer's own normals and positions, where each
 * pixel's answer is known. Half texel q holds full pixel 2q+1 (checked by
 * gbuffer_downsample), so full pixel x lies between texels (x - 1) / 2
 * rounded down and the next. A pixel with a texel of its surface among
 * those 2x2 gets exactly its normal and a position on its plane, and where
 * all four are on it, its own position (bilinear on a plane, samples in
 * the right place); one without (weight-0 texels do not count) gets the
 * nearest hit texel's values (of the 2x2, else of the 4x4 around them),
 * else 1 (a thin pole no texel hit); plain bilinear leaves pixels off
 * their plane at the wall's steps and silhouettes. Sky pixels get 1. */
static void test_upsample_edges(void)
{
    vrg_image_data img[COUNT];
    vrg_graph *g = render_two(img);
    if (!g)
        return;
    const vrg_image_data *pos = &img[FULL_POS], *n = &img[FULL_N], *low = &img[HALF_POS];
    int hits = 0, wrong = 0, nearest_wrong = 0, fallbacks = 0, rings = 0, ones = 0, off_plane_bilinear = 0, sky_wrong = 0, sky = 0, interior = 0;
    double shift_sum = 0, shift_max = 0;
    for (uint32_t y = 0; y < pos->height; y++)
        for (uint32_t x = 0; x < pos->width; x++) {
            if (px(pos, x, y, 3) == 0.0f) {
                sky++;
                for (int c = 0; c < 4; c++)
                    sky_wrong += px(&img[UP_N], x, y, c) != 1.0f;
                continue;
            }
            hits++;
            /* bilinear weights: an odd pixel sits on a texel's sample (weight 1 there) */
            float fx, fy;
            int bx = texel_below(x, &fx), by = texel_below(y, &fy);
            int qualified = 0, weighted = 0, nx = -1, ny = -1, ring = 0;
            float nearest = 1e30f;
            for (int j = 0; j < 20; j++) {
                int inner = j < 4, ox = inner ? (j & 1) : (j - 4) % 4 - 1, oy = inner ? (j >> 1) : (j - 4) / 4 - 1;
                if (j == 4 && nx >= 0)
                    break; /* a hit among the 2x2 */
                if (!inner && ox >= 0 && ox <= 1 && oy >= 0 && oy <= 1)
                    continue;
                int qx = clamp_texel(bx + ox, low->width), qy = clamp_texel(by + oy, low->height);
                float dist = 1e30f;
                int hit = px(low, (uint32_t)qx, (uint32_t)qy, 3) != 0.0f;
                if (inner) {
                    int w = (ox ? fx : 1.0f - fx) * (oy ? fy : 1.0f - fy) > 0.0f, on = on_surface(img, x, y, qx, qy, &dist);
                    qualified += w && on; /* a texel of weight 0 counts only as the nearest */
                    weighted += w;
                }
                else if (hit)
                    dist = dist3(low, (uint32_t)qx, (uint32_t)qy, pos, x, y);
                if (hit && dist < nearest)
                    nearest = dist, nx = qx, ny = qy, ring = !inner;
            }
            float d = 0, db = 0, dn = 0;
            for (int c = 0; c < 3; c++) {
                float nc = px(n, x, y, c);
                d += nc * (px(&img[UP_POS], x, y, c) - px(pos, x, y, c));
                db += nc * (px(&img[UP_BILINEAR], x, y, c) - px(pos, x, y, c));
                dn += fabsf(px(&img[UP_N], x, y, c) - (qualified ? nc : nx >= 0 ? px(&img[HALF_N], (uint32_t)nx, (uint32_t)ny, c) : 1.0f));
            }
            off_plane_bilinear += fabsf(db) > 0.05f;
            if (qualified == weighted && bx >= 0 && by >= 0 && bx + 1 < (int)low->width && by + 1 < (int)low->height) {
                /* all four on its plane: its own position, to a fraction of the texel spacing */
                float step = dist3(low, (uint32_t)bx, (uint32_t)by, low, (uint32_t)bx + 1, (uint32_t)by);
                double r = dist3(&img[UP_POS], x, y, pos, x, y) / (step > 1e-6f ? step : 1e-6f);
                shift_sum += r, interior++;
                shift_max = r > shift_max ? r : shift_max;
            }
            if (qualified)
                wrong += dn > 1e-3f || fabsf(d) > 0.05f; /* f16 positions: 0.016 at 32..64 */
            else {
                fallbacks++, rings += ring, ones += nx < 0;
                /* the nearest hit texel's values, else (none in the 4x4) 1 */
                int far = 0;
                for (int c = 0; c < 3; c++)
                    far |= nx < 0 && px(&img[UP_POS], x, y, c) != 1.0f;
                nearest_wrong += dn > 1e-3f || far || (nx >= 0 && dist3(&img[UP_POS], x, y, low, (uint32_t)nx, (uint32_t)ny) > 0.05f);
            }
        }
    CHECK(sky > 100 && hits > 2000, "the view does not test it: %d sky, %d hits", sky, hits);
    CHECK(sky_wrong == 0, "%d sky channels are not 1", sky_wrong);
    CHECK(wrong == 0, "%d of %d pixels with a texel of their surface got another surface's normal or left their plane", wrong, hits);
    CHECK(nearest_wrong == 0, "%d of %d pixels without one did not get the nearest hit texel's value (or 1)", nearest_wrong, fallbacks);
    /* the poles beyond the wall, about a pixel wide: pixels on them whose
     * 2x2 texels all missed, with a hit in the ring of the 4x4 or none */
    CHECK(rings > 10 && ones > 10, "the view does not test the fallback: %d pixels took a texel of the 4x4's ring, %d took 1", rings, ones);
    CHECK(interior > 1000 && shift_sum / interior < 0.03 && shift_max < 0.1,
          "%d pixels inside their surface lie %.3f texel steps from their own position on average (at most %.3f): the texels are misplaced",
          interior, interior ? shift_sum / interior : 0.0, shift_max);
    CHECK(off_plane_bilinear > 100, "bilinear leaves only %d pixels off their plane: the view has no edges", off_plane_bilinear);
    release(g, img);
}

/* A fallback's outputs at pixel (x, y) (normal and position upsampled:
 * got_n, got_pos) against those without the fallback (was_n, was_pos):
 * same_channels counts the channels that differ (where the fallback must
 * not act). */
static int same_channels(const vrg_image_data img[COUNT], int got_n, int got_pos, int was_n, int was_pos, uint32_t x, uint32_t y)
{
    int differ = 0;
    for (int c = 0; c < 4; c++)
        differ += px(&img[got_n], x, y, c) != px(&img[was_n], x, y, c) || px(&img[got_pos], x, y, c) != px(&img[was_pos], x, y, c);
    return differ;
}

/* Where it acts: its own normal exactly (voxel normals are axis-aligned)
 * and the blend want / wsum of the texels' positions, else *wrong; *fixed
 * (unless NULL) where the output without it (was_n) had another normal. */
static void check_blend(const vrg_image_data img[COUNT], int got_n, int got_pos, int was_n, uint32_t x, uint32_t y, const double want[3],
                        double wsum, int *wrong, int *fixed)
{
    float dn = 0, dp = 0, dold = 0;
    for (int c = 0; c < 3; c++) {
        dn += fabsf(px(&img[got_n], x, y, c) - px(&img[FULL_N], x, y, c));
        dp += fabsf(px(&img[got_pos], x, y, c) - (float)(want[c] / wsum));
        dold += fabsf(px(&img[was_n], x, y, c) - px(&img[FULL_N], x, y, c));
    }
    /* f16 output: positions to 0.016 at 32..64 blocks */
    *wrong += dn > 1e-3f || dp > 0.06f;
    if (fixed)
        *fixed += dold > 0.1f;
}

/* Texel j (0 to 15, row by row) of the 4x4 around full pixel (x, y): its
 * place clamped into the half image, whether it is one of the 2x2 and, if
 * so, whether its bilinear weight is above 0, and the weight 1 / (1 + t^2)
 * that surface_ring and orientation_fallback give it, t its offset in
 * texels from the pixel's centre. */
typedef struct {
    int qx, qy, inner, weighted;
    double ring_weight;
} footprint_texel;

static footprint_texel footprint_at(uint32_t x, uint32_t y, int j, const vrg_image_data *low)
{
    float fx, fy;
    int bx = texel_below(x, &fx), by = texel_below(y, &fy), ox = j % 4 - 1, oy = j / 4 - 1;
    footprint_texel t = {clamp_texel(bx + ox, low->width), clamp_texel(by + oy, low->height), ox >= 0 && ox <= 1 && oy >= 0 && oy <= 1, 0, 0};
    t.weighted = t.inner && (ox ? fx : 1.0f - fx) * (oy ? fy : 1.0f - fy) > 0.0f;
    double tx = ox - fx, ty = oy - fy;
    t.ring_weight = 1.0 / (1.0 + tx * tx + ty * ty);
    return t;
}

/* Adds texel t's values, weighted by its ring weight, to want and wsum. */
static void add_ring_texel(const vrg_image_data *low, footprint_texel t, double want[3], double *wsum)
{
    for (int c = 0; c < 3; c++)
        want[c] += t.ring_weight * px(low, (uint32_t)t.qx, (uint32_t)t.qy, c);
    *wsum += t.ring_weight;
}

/* surface_ring = 1: a pixel none of whose 2x2 texels (of weight > 0) is
 * on its surface takes the ring's texels that are, weighted 1 / (1 + t^2)
 * by their offset t in texels from the pixel's centre: its own normal
 * exactly (voxel normals are axis-aligned) and that blend of their
 * positions. Elsewhere it is the output without surface_ring. The view
 * must hold pixels where this differs: where the nearest hit of the 2x2
 * (the output without it) has another normal. */
static void test_upsample_ring(void)
{
    vrg_image_data img[COUNT];
    vrg_graph *g = render_two(img);
    if (!g)
        return;
    const vrg_image_data *pos = &img[FULL_POS], *low = &img[HALF_POS];
    int ring_pixels = 0, fixed = 0, wrong = 0, same_wrong = 0;
    for (uint32_t y = 0; y < pos->height; y++)
        for (uint32_t x = 0; x < pos->width; x++) {
            if (px(pos, x, y, 3) == 0.0f)
                continue;
            int qualified = 0;
            double want[3] = {0, 0, 0}, wsum = 0;
            for (int j = 0; j < 16; j++) {
                footprint_texel t = footprint_at(x, y, j, low);
                float dist;
                if (!on_surface(img, x, y, t.qx, t.qy, &dist))
                    continue;
                if (t.inner)
                    qualified += t.weighted;
                else
                    add_ring_texel(low, t, want, &wsum);
            }
            if (qualified || wsum == 0.0) {
                /* the 2x2 decides, or nothing on the surface in the 4x4: as without surface_ring */
                same_wrong += same_channels(img, UP_RING_N, UP_RING_POS, UP_N, UP_POS, x, y);
                continue;
            }
            ring_pixels++;
            check_blend(img, UP_RING_N, UP_RING_POS, UP_N, x, y, want, wsum, &wrong, &fixed);
        }
    CHECK(same_wrong == 0, "%d channels differ from the output without surface_ring where the 2x2 decides", same_wrong);
    CHECK(wrong == 0, "%d of %d pixels with their surface only in the ring did not get the ring's texels on it", wrong, ring_pixels);
    CHECK(fixed > 20, "the view does not test it: %d pixels (of %d) whose nearest texel has another normal", fixed, ring_pixels);
    release(g, img);
}

/* orientation_fallback = 1: a pixel with no texel on its surface among
 * the 2x2 (of weight > 0) or, with surface_ring, the ring takes the texels
 * of those (the 2x2's; with surface_ring the ring's too) whose normal is
 * its own but which lie on other planes, weighted 1 / (1 + t^2) as the
 * ring's: its own normal exactly and that blend of their positions.
 * Elsewhere it is the output without the fallback (got_* against was_*).
 * Counts the pixels where it acts, those of them where that changes the
 * output, and the failures. */
static void check_facing(const vrg_image_data img[COUNT], int with_ring, int got_n, int got_pos, int was_n, int was_pos, int *pixels,
                         int *changed, int *wrong, int *same_wrong)
{
    const vrg_image_data *pos = &img[FULL_POS], *n = &img[FULL_N], *low = &img[HALF_POS];
    for (uint32_t y = 0; y < pos->height; y++)
        for (uint32_t x = 0; x < pos->width; x++) {
            if (px(pos, x, y, 3) == 0.0f)
                continue;
            int qualified = 0, ring = 0;
            double want[3] = {0, 0, 0}, wsum = 0;
            for (int j = 0; j < 16; j++) {
                footprint_texel t = footprint_at(x, y, j, low);
                if (!t.inner && !with_ring)
                    continue;
                float dist;
                if (on_surface(img, x, y, t.qx, t.qy, &dist)) {
                    qualified += t.weighted;
                    ring += !t.inner;
                    continue;
                }
                float ndot = 0;
                for (int c = 0; c < 3; c++)
                    ndot += px(&img[HALF_N], (uint32_t)t.qx, (uint32_t)t.qy, c) * px(n, x, y, c);
                if (px(low, (uint32_t)t.qx, (uint32_t)t.qy, 3) == 0.0f || ndot < 0.9f)
                    continue;
                add_ring_texel(low, t, want, &wsum);
            }
            if (qualified || ring || wsum == 0.0) {
                /* a texel on the surface decides, or none faces its way: as without the fallback */
                *same_wrong += same_channels(img, got_n, got_pos, was_n, was_pos, x, y);
                continue;
            }
            (*pixels)++;
            *changed += same_channels(img, got_n, got_pos, was_n, was_pos, x, y) > 0;
            check_blend(img, got_n, got_pos, was_n, x, y, want, wsum, wrong, NULL);
        }
}

/* The view must hold pixels where the fallback changes the output. */
static void test_upsample_facing(void)
{
    vrg_image_data img[COUNT];
    vrg_graph *g = render_two(img);
    if (!g)
        return;
    for (int with_ring = 1; with_ring >= 0; with_ring--) {
        int pixels = 0, changed = 0, wrong = 0, same_wrong = 0;
        check_facing(img, with_ring, with_ring ? UP_FACING_N : UP_FACING2_N, with_ring ? UP_FACING_POS : UP_FACING2_POS,
                     with_ring ? UP_RING_N : UP_N, with_ring ? UP_RING_POS : UP_POS, &pixels, &changed, &wrong, &same_wrong);
        const char *which = with_ring ? "with surface_ring" : "without surface_ring";
        CHECK(same_wrong == 0, "%s: %d channels differ from the output without orientation_fallback where a texel on the surface or none facing decides",
              which, same_wrong);
        CHECK(wrong == 0, "%s: %d of %d pixels with only texels facing their way on other planes did not get those texels' blend", which, wrong,
              pixels);
        CHECK(changed >= 5, "%s: the view does not test it: %d pixels (of %d) where it changes the output", which, changed, pixels);
    }
    release(g, img);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"gbuffer_downsample", test_gbuffer_downsample, 1},
        {"upsample_edges", test_upsample_edges, 1},
        {"upsample_ring", test_upsample_ring, 1},
        {"upsample_facing", test_upsample_facing, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
