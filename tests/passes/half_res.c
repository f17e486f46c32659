/* Half-resolution lighting: gbuffer_downsample against the full G-buffer,
 * bilateral_upsample against each pixel's known answer (the half G-buffer's
 * own normals and positions upsampled), and a [pass]'s output_scale. */
#include "harness.h"

static const char *const reads[] = {"gbuffer.position", "gbuffer.normal", "gbuffer.ids", "gbuffer.motion", "half.position", "half.normal",
                                    "half.ids",         "half.motion",    "up_normal",   "up_position",    "up_bilinear",  "vis_half",
                                    "vis_quarter"};
enum { FULL_POS, FULL_N, FULL_IDS, FULL_MOTION, HALF_POS, HALF_N, HALF_IDS, HALF_MOTION, UP_N, UP_POS, UP_BILINEAR, VIS_HALF, VIS_QUARTER, COUNT };

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
    for (int i = 0; i < COUNT; i++)
        if (vrg_graph_read(g, reads[i], &img[i]) != 0) {
            CHECK(0, "readback of %s failed", reads[i]);
            for (int k = 0; k < i; k++)
                free(img[k].pixels);
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

/* Upsampling the half G-buffer's own normals and positions, where each
 * pixel's answer is known: a pixel with a texel of its surface among its
 * 2x2 gets exactly its normal and a position on its plane; one without gets
 * the nearest texel's; plain bilinear leaves pixels off their plane at the
 * wall's steps and silhouettes. Sky pixels get 1. */
static void test_upsample_edges(void)
{
    vrg_image_data img[COUNT];
    vrg_graph *g = render_two(img);
    if (!g)
        return;
    const vrg_image_data *pos = &img[FULL_POS], *n = &img[FULL_N], *low = &img[HALF_POS];
    int hits = 0, wrong = 0, nearest_wrong = 0, fallbacks = 0, off_plane_bilinear = 0, sky_wrong = 0, sky = 0;
    for (uint32_t y = 0; y < pos->height; y++)
        for (uint32_t x = 0; x < pos->width; x++) {
            if (px(pos, x, y, 3) == 0.0f) {
                sky++;
                for (int c = 0; c < 4; c++)
                    sky_wrong += px(&img[UP_N], x, y, c) != 1.0f;
                continue;
            }
            hits++;
            int bx = (int)floorf((x + 0.5f) * low->width / pos->width - 0.5f), by = (int)floorf((y + 0.5f) * low->height / pos->height - 0.5f);
            int qualified = 0, nx = -1, ny = -1;
            float nearest = 1e30f;
            for (int j = 0; j < 4; j++) {
                int qx = bx + (j & 1), qy = by + (j >> 1), hit;
                qx = qx < 0 ? 0 : qx >= (int)low->width ? (int)low->width - 1 : qx;
                qy = qy < 0 ? 0 : qy >= (int)low->height ? (int)low->height - 1 : qy;
                float dist = 1e30f;
                hit = px(low, (uint32_t)qx, (uint32_t)qy, 3) != 0.0f;
                qualified += on_surface(img, x, y, qx, qy, &dist);
                if (hit && dist < nearest)
                    nearest = dist, nx = qx, ny = qy;
            }
            float d = 0, db = 0, dn = 0;
            for (int c = 0; c < 3; c++) {
                float nc = px(n, x, y, c);
                d += nc * (px(&img[UP_POS], x, y, c) - px(pos, x, y, c));
                db += nc * (px(&img[UP_BILINEAR], x, y, c) - px(pos, x, y, c));
                dn += fabsf(px(&img[UP_N], x, y, c) - (qualified ? nc : px(&img[HALF_N], (uint32_t)nx, (uint32_t)ny, c)));
            }
            off_plane_bilinear += fabsf(db) > 0.05f;
            if (qualified)
                wrong += dn > 1e-3f || fabsf(d) > 0.05f; /* f16 positions: 0.016 at 32..64 */
            else
                fallbacks++, nearest_wrong += nx < 0 || dn > 1e-3f;
        }
    CHECK(sky > 100 && hits > 2000, "the view does not test it: %d sky, %d hits", sky, hits);
    CHECK(sky_wrong == 0, "%d sky channels are not 1", sky_wrong);
    CHECK(wrong == 0, "%d of %d pixels with a texel of their surface got another surface's normal or left their plane", wrong, hits);
    CHECK(nearest_wrong == 0, "%d of %d pixels without one did not get the nearest texel's value", nearest_wrong, fallbacks);
    CHECK(off_plane_bilinear > 100, "bilinear leaves only %d pixels off their plane: the view has no edges", off_plane_bilinear);
    release(g, img);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"gbuffer_downsample", test_gbuffer_downsample, 1},
        {"upsample_edges", test_upsample_edges, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
