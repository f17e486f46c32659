/* The image metrics of voxrg compare against values computed by hand on
 * tiny synthetic images. Reference values (docs/compare.md):
 * - PSNR of a constant offset d: 10 log10(1 / d²): 20 dB for 0.1, 40 dB for 0.01.
 * - SSIM of two constant images: the variance and covariance terms are 1,
 *   so SSIM = (2 m1 m2 + C1) / (m1² + m2² + C1) with m the luma.
 * - FLIP of two constant grey images: no edges or points, and the CSF
 *   filters leave a constant image as it is, so the error is the colour
 *   term alone: HyAB distance of the Hunt-adjusted Lab greys, ^0.7,
 *   redistributed against cmax = HyAB(green, blue)^0.7 = 41.2755. Black
 *   against white: 100^0.7 = 25.119 > 0.4 cmax, so 0.95 + (25.119 - 16.510)
 *   / (41.275 - 16.510) · 0.05 = 0.96738; grey 0.5 against 0.6: 0.28502.
 * - FLIP of a small non-constant pair (flip_pair) is pinned to the value of
 *   an independent plain-Python FLIP (flip_reference.py: 2D kernels, edge
 *   pixels repeated beyond the borders as the official code pads), which
 *   the test also runs when python3 is there, so either side drifting
 *   fails. The image is smaller than the filters, so every pixel's score
 *   depends on the padding. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/metrics.h"
#include "check.h"

static int failures;

enum { W = 48, H = 32, N = W * H * 3 };

static void fill(float *img, float v)
{
    for (int i = 0; i < N; i++)
        img[i] = v;
}

/* a test pattern with edges, gradients and colour */
static void pattern(float *img)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = img + 3 * (y * W + x);
            p[0] = (x / 8 + y / 8) % 2 ? 0.8f : 0.2f;
            p[1] = (float)x / (W - 1);
            p[2] = (float)y / (H - 1) * 0.5f + 0.25f;
        }
}

/* pattern plus uniform noise of the given amplitude, clamped, fixed seed */
static void noisy(const float *src, float *dst, float amplitude)
{
    uint32_t s = 12345;
    for (int i = 0; i < N; i++) {
        s = s * 1664525u + 1013904223u;
        float u = (float)(s >> 8) / 16777216.0f * 2 - 1;
        float v = src[i] + amplitude * u;
        dst[i] = v < 0 ? 0 : v > 1 ? 1 : v;
    }
}

static void test_psnr(void)
{
    static float a[N], b[N];
    fill(a, 0.5f);
    fill(b, 0.6f);
    CHECK(fabs(vrg_metric_psnr(b, a, W, H) - 20.0) < 1e-4, "offset 0.1: %g dB, want 20", vrg_metric_psnr(b, a, W, H));
    fill(b, 0.51f);
    CHECK(fabs(vrg_metric_psnr(b, a, W, H) - 40.0) < 1e-3, "offset 0.01: %g dB, want 40", vrg_metric_psnr(b, a, W, H));
    pattern(a);
    CHECK(vrg_metric_psnr(a, a, W, H) == VRG_PSNR_MAX_DB, "identical: %g dB, want the cap", vrg_metric_psnr(a, a, W, H));
}

static void test_ssim(void)
{
    static float a[N], b[N];
    pattern(a);
    CHECK(fabs(vrg_metric_ssim(a, a, W, H) - 1.0) < 1e-12, "SSIM with itself: %.15g", vrg_metric_ssim(a, a, W, H));
    double last = 1.0;
    float amps[] = {0.01f, 0.05f, 0.1f, 0.2f, 0.4f};
    for (int i = 0; i < 5; i++) {
        noisy(a, b, amps[i]);
        double s = vrg_metric_ssim(b, a, W, H);
        CHECK(s < last && s > -1, "noise %g: SSIM %g, not below %g", amps[i], s, last);
        last = s;
    }
    fill(a, 0.5f);
    fill(b, 0.6f);
    double m1 = 0.5 * (0.2989 + 0.5870 + 0.1140), m2 = (double)0.6f * (0.2989 + 0.5870 + 0.1140), c1 = 1e-4; /* 0.6f: the image holds floats */
    double want = (2 * m1 * m2 + c1) / (m1 * m1 + m2 * m2 + c1);
    CHECK(fabs(vrg_metric_ssim(b, a, W, H) - want) < 1e-9, "constant 0.5 vs 0.6: %.9g, want %.9g", vrg_metric_ssim(b, a, W, H), want);
    CHECK(vrg_metric_ssim(a, b, 10, 10) == -1, "an image under 11x11 has no SSIM");
}

static void test_flip(void)
{
    static float a[N], b[N];
    static float map[W * H];
    pattern(a);
    CHECK(vrg_metric_flip(a, a, W, H, map) == 0.0, "identical: FLIP %g", vrg_metric_flip(a, a, W, H, NULL));
    for (int i = 0; i < W * H; i++)
        if (map[i] != 0) {
            CHECK(0, "identical: map[%d] = %g", i, map[i]);
            break;
        }
    /* zero only for identical images: one channel of one pixel off by 1/255 */
    memcpy(b, a, sizeof b);
    b[3 * (5 * W + 7) + 1] += 1.0f / 255;
    double tiny = vrg_metric_flip(b, a, W, H, map);
    CHECK(tiny > 0 && map[5 * W + 7] > 0, "a 1/255 change: FLIP %g, at the pixel %g", tiny, map[5 * W + 7]);
    double last = tiny;
    float amps[] = {0.02f, 0.05f, 0.1f, 0.2f, 0.4f};
    for (int i = 0; i < 5; i++) {
        noisy(a, b, amps[i]);
        double f = vrg_metric_flip(b, a, W, H, NULL);
        CHECK(f > last && f <= 1, "noise %g: FLIP %g, not above %g", amps[i], f, last);
        last = f;
    }
    fill(a, 0.0f);
    fill(b, 1.0f);
    CHECK(fabs(vrg_metric_flip(b, a, W, H, NULL) - 0.96738) < 2e-5, "black vs white: %.6f, want 0.96738", vrg_metric_flip(b, a, W, H, NULL));
    fill(a, 0.5f);
    fill(b, 0.6f);
    CHECK(fabs(vrg_metric_flip(b, a, W, H, NULL) - 0.28502) < 2e-5, "grey 0.5 vs 0.6: %.6f, want 0.28502", vrg_metric_flip(b, a, W, H, NULL));
    /* the feature term: a step edge moved by two pixels is an error at the
     * edge only, and more than the colour difference of its pixels alone */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                a[3 * (y * W + x) + c] = x < 24 ? 0.2f : 0.8f;
                b[3 * (y * W + x) + c] = x < 26 ? 0.2f : 0.8f;
            }
    vrg_metric_flip(b, a, W, H, map);
    CHECK(map[16 * W + 24] > 0.5f && map[16 * W + 4] < 1e-6f && map[16 * W + 44] < 1e-6f, "moved edge: at it %g, far left %g, far right %g",
          map[16 * W + 24], map[16 * W + 4], map[16 * W + 44]);
}

/* flip_reference.py's image_pair(), in 1/255 steps: a colour gradient with
 * one bright pixel; the test has it moved by one and three border pixels
 * changed, one in a corner */
enum { PAIR_W = 8, PAIR_H = 6 };

static void flip_pair(float *ref, float *test)
{
    for (int y = 0; y < PAIR_H; y++)
        for (int x = 0; x < PAIR_W; x++) {
            int v[3] = {30 + 28 * x, 50 + 35 * y, 200 - 20 * x - 10 * y};
            if (x == 3 && y == 2)
                v[0] = v[1] = v[2] = 240;
            for (int c = 0; c < 3; c++)
                ref[3 * (y * PAIR_W + x) + c] = (float)v[c] / 255.0f;
        }
    memcpy(test, ref, sizeof(float) * PAIR_W * PAIR_H * 3);
    memcpy(test + 3 * (2 * PAIR_W + 3), ref + 3 * (2 * PAIR_W + 4), sizeof(float) * 3);
    memcpy(test + 3 * (2 * PAIR_W + 4), ref + 3 * (2 * PAIR_W + 3), sizeof(float) * 3);
    const float red[3] = {1, 0, 0}, black[3] = {0, 0, 0};
    memcpy(test, red, sizeof red);
    test[3 * (3 * PAIR_W + 7) + 1] += 40.0f / 255.0f;
    memcpy(test + 3 * (5 * PAIR_W + 2), black, sizeof black);
}

/* argv: the Python reference's value, when python3 ran it */
static void test_flip_pinned(int argc, char **argv)
{
    const double pinned = 0.282053842617, tolerance = 1e-6;
    static float ref[PAIR_W * PAIR_H * 3], test[PAIR_W * PAIR_H * 3];
    flip_pair(ref, test);
    double c = vrg_metric_flip(test, ref, PAIR_W, PAIR_H, NULL);
    CHECK(fabs(c - pinned) < tolerance, "C FLIP of the pair %.12f, pinned %.12f", c, pinned);
    if (argc < 1)
        return;
    char *end;
    double py = strtod(argv[0], &end);
    CHECK(end != argv[0] && *end == 0, "the Python reference's output '%s' is not a number", argv[0]);
    CHECK(fabs(py - pinned) < tolerance, "Python FLIP of the pair %.12f, pinned %.12f", py, pinned);
    CHECK(fabs(py - c) < tolerance, "Python FLIP %.12f, C %.12f", py, c);
}

static void test_temporal(void)
{
    static float r0[N], r1[N], t0[N], t1[N];
    pattern(r0);
    memcpy(t0, r0, sizeof t0);
    CHECK(vrg_metric_temporal(t0, t0, r0, r0, W, H) == 0, "a still, identical sequence");
    /* the light changes: both brighten by 0.1, which is no flicker */
    for (int i = 0; i < N; i++)
        r1[i] = r0[i] * 0.5f + 0.1f, t0[i] = r0[i] * 0.5f, t1[i] = t0[i] + 0.1f, r0[i] = t0[i];
    CHECK(fabs(vrg_metric_temporal(t1, t0, r1, r0, W, H)) < 1e-6, "equal change counted: %g", vrg_metric_temporal(t1, t0, r1, r0, W, H));
    /* flicker: the test alternates by 0.05 while the reference holds */
    for (int i = 0; i < N; i++)
        t1[i] = t0[i] + (i % 2 ? 0.05f : -0.05f);
    CHECK(fabs(vrg_metric_temporal(t1, t0, r0, r0, W, H) - 0.05) < 1e-6, "flicker 0.05: %g", vrg_metric_temporal(t1, t0, r0, r0, W, H));
}

static void test_colors(void)
{
    uint8_t lo[3], hi[3], mid[3];
    vrg_error_color(0, lo);
    vrg_error_color(1, hi);
    vrg_error_color(0.5f, mid);
    CHECK(lo[0] + lo[1] + lo[2] < 10 && hi[0] + hi[1] + hi[2] > 600 && mid[0] > mid[1], "ramp %d,%d,%d %d,%d,%d %d,%d,%d", lo[0], lo[1], lo[2],
          mid[0], mid[1], mid[2], hi[0], hi[1], hi[2]);
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*fn)(void);
    } cases[] = {{"psnr", test_psnr}, {"ssim", test_ssim}, {"flip", test_flip}, {"temporal", test_temporal}, {"colors", test_colors}};
    int ran = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (argc < 2 || strcmp(argv[1], cases[i].name) == 0)
            cases[i].fn(), ran++;
    if (argc < 2 || strcmp(argv[1], "flip_pinned") == 0)
        test_flip_pinned(argc > 2 ? argc - 2 : 0, argv + 2), ran++;
    /* a misspelt case in CMakeLists.txt would otherwise pass by running nothing */
    CHECK(ran > 0, "no test case named '%s'", argv[1]);
    printf("metrics: %s\n", failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
