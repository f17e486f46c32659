/* The device scorer (voxrg/device_score.h) against the CPU metrics
 * (voxrg/metrics.h), the reference, on the same bytes: synthetic images at
 * three sizes and frames rendered by a shipped graph, scored from the graph's
 * output image without reading it back; the same frame scored again gives
 * the same bits. The tolerances are docs/compare.md's ("Scoring on the
 * device"). */
#include <stdint.h>
#include "harness.h"
#include "voxrg/device_score.h"
#include "voxrg/metrics.h"
#include "voxrg/png.h"

/* PSNR and temporal error: integer sums on the device, so only the CPU's
 * float 8-bit values differ (2^-24 relative); SSIM: float per window and in
 * the partial sums; FLIP: the bound the issue sets for the mean. */
#define TOL_PSNR_DB 1e-5
#define TOL_TEMPORAL 1e-7
#define TOL_SSIM 2e-5
#define TOL_FLIP 1e-5
/* one pixel of FLIP's map (the mean is the figure held to 1e-5) */
#define TOL_FLIP_PIXEL 1e-4

static void to_float(const uint8_t *rgb, size_t n, float *out)
{
    for (size_t i = 0; i < n * 3; i++)
        out[i] = rgb[i] / 255.0f;
}

static uint32_t hash(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    return x ^ (x >> 16);
}

/* A reference with smooth gradients, hard edges and fine texture, moving
 * with frame f; the candidate is it plus noise of a denoiser's size, and a
 * block of large errors. */
static void synthetic(uint32_t w, uint32_t h, uint32_t f, uint8_t *ref, uint8_t *test)
{
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            for (uint32_t c = 0; c < 3; c++) {
                size_t i = ((size_t)y * w + x) * 3 + c;
                double v = 0.5 + 0.4 * sin(0.07 * (x + 3 * f) + 0.11 * y + c);
                if (((x + f) / 9 + y / 7) % 2 && c != 1)
                    v *= 0.3;
                v += 0.05 * ((hash((uint32_t)(x * 7919 + y * 104729 + c)) & 255) / 255.0 - 0.5);
                int r = (int)lrint(255 * fmin(fmax(v, 0), 1));
                int n = (int)(hash((uint32_t)(i * 31 + f * 1000003)) % 13) - 6;
                if (x > w / 2 && x < w / 2 + 8 && y > h / 3 && y < h / 3 + 6)
                    n += 90;
                ref[i] = (uint8_t)r;
                test[i] = (uint8_t)(r + n < 0 ? 0 : r + n > 255 ? 255 : r + n);
            }
}

typedef struct cpu_frame {
    float *cur, *prev, *refc, *refp, *map;
} cpu_frame;

/* The device's scores of frame k against the CPU's on the same bytes; the
 * map's largest per-pixel difference goes to *worst_pixel. */
static void agree(const char *what, uint32_t k, uint32_t w, uint32_t h, cpu_frame *c, const vrg_device_scores *d, const float *map,
                  double *worst_pixel)
{
    double psnr = vrg_metric_psnr(c->cur, c->refc, w, h), ssim = vrg_metric_ssim(c->cur, c->refc, w, h);
    double flip = vrg_metric_flip(c->cur, c->refc, w, h, c->map);
    CHECK(fabs(d->psnr - psnr) <= TOL_PSNR_DB, "%s frame %u: PSNR %.9f on the device, %.9f on the CPU", what, k, d->psnr, psnr);
    CHECK(fabs(d->ssim - ssim) <= TOL_SSIM, "%s frame %u: SSIM %.9f on the device, %.9f on the CPU", what, k, d->ssim, ssim);
    CHECK(fabs(d->flip - flip) <= TOL_FLIP, "%s frame %u: FLIP %.9f on the device, %.9f on the CPU", what, k, d->flip, flip);
    if (k == 0)
        CHECK(isnan(d->temporal), "%s: the first frame has a temporal error %g", what, d->temporal);
    else {
        double t = vrg_metric_temporal(c->cur, c->prev, c->refc, c->refp, w, h);
        CHECK(fabs(d->temporal - t) <= TOL_TEMPORAL, "%s frame %u: temporal %.9f on the device, %.9f on the CPU", what, k, d->temporal, t);
    }
    for (size_t i = 0; map && i < (size_t)w * h; i++)
        *worst_pixel = fmax(*worst_pixel, fabs(map[i] - c->map[i]));
    printf("%s frame %u: PSNR %+.2e dB, SSIM %+.2e, FLIP %+.2e, temporal %+.2e (device - CPU)\n", what, k, d->psnr - psnr, d->ssim - ssim,
           d->flip - flip, k ? d->temporal - vrg_metric_temporal(c->cur, c->prev, c->refc, c->refp, w, h) : 0.0);
}

static cpu_frame cpu_frame_new(size_t n)
{
    cpu_frame c = {malloc(sizeof(float) * n * 3), malloc(sizeof(float) * n * 3), malloc(sizeof(float) * n * 3), malloc(sizeof(float) * n * 3),
                   malloc(sizeof(float) * n)};
    return c;
}

static void cpu_frame_next(cpu_frame *c)
{
    float *t = c->prev;
    c->prev = c->cur, c->cur = t;
    t = c->refp;
    c->refp = c->refc, c->refc = t;
}

static void cpu_frame_free(cpu_frame *c)
{
    free(c->cur), free(c->prev), free(c->refc), free(c->refp), free(c->map);
}

static void synthetic_size(uint32_t w, uint32_t h)
{
    size_t n = (size_t)w * h;
    uint8_t *ref = malloc(n * 3), *test = malloc(n * 3);
    float *map = malloc(sizeof(float) * n);
    cpu_frame c = cpu_frame_new(n);
    vrg_device_scorer *s = NULL;
    if (!CHECK(vrg_device_scorer_create(ctx, w, h, &s) == 0, "scorer for %ux%u", w, h))
        return;
    char what[32];
    snprintf(what, sizeof what, "synthetic %ux%u", w, h);
    double worst = 0;
    vrg_device_scores first = {0};
    for (uint32_t k = 0; k < 3; k++) {
        synthetic(w, h, k, ref, test);
        if (k == 2) /* identical frames: PSNR capped, FLIP 0, SSIM 1 */
            memcpy(test, ref, n * 3);
        vrg_device_scores d;
        CHECK(vrg_device_score_submit(s, NULL, test, ref, 1) == 0, "submit");
        CHECK(vrg_device_score_collect(s, map, &d) == 0, "collect");
        to_float(test, n, c.cur);
        to_float(ref, n, c.refc);
        agree(what, k, w, h, &c, &d, map, &worst);
        cpu_frame_next(&c);
        if (k == 0)
            first = d;
    }
    CHECK(worst <= TOL_FLIP_PIXEL, "%s: FLIP's maps differ by %g in a pixel", what, worst);
    /* the sums run in a fixed order: frame 0 again gives the same bits */
    vrg_device_scores again;
    synthetic(w, h, 0, ref, test);
    vrg_device_scorer_restart(s);
    CHECK(vrg_device_score_submit(s, NULL, test, ref, 0) == 0 && vrg_device_score_collect(s, NULL, &again) == 0, "scoring again");
    CHECK(again.psnr == first.psnr && again.ssim == first.ssim && again.flip == first.flip && isnan(again.temporal),
          "%s: frame 0 scored again gives PSNR %.17g SSIM %.17g FLIP %.17g, first %.17g %.17g %.17g", what, again.psnr, again.ssim, again.flip,
          first.psnr, first.ssim, first.flip);
    printf("%s: FLIP map, largest difference in a pixel %.2e\n", what, worst);
    vrg_device_scorer_destroy(s);
    cpu_frame_free(&c);
    free(ref), free(test), free(map);
}

static void test_synthetic(void)
{
    synthetic_size(64, 36);
    synthetic_size(320, 180);
    /* sizes the stages' strips (128 pixels) and steps (4) do not divide */
    synthetic_size(131, 37);
}

static vrg_graph *load_raw(const char *const sets[3], uint32_t w, uint32_t h)
{
    vrg_graph_desc d = {.path = TEST_DIR "/../graphs/raw.ini", .overrides = sets, .override_count = 3, .width = w, .height = h};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(ctx, &d, &g) == 0, "loading %s", d.path);
    return g;
}

/* raw.ini (one ray per effect) scored against raw.ini with 16 rays, both
 * rendered here along a short camera move; the candidate straight from its
 * output image, the CPU from the bytes read back. */
static void test_rendered(void)
{
    const uint32_t w = 96, h = 54, frames = 3;
    const char *const cand_sets[] = {"shadow.rays=1", "ao.rays=1", "indirect.rays=1"};
    const char *const ref_sets[] = {"shadow.rays=16", "ao.rays=16", "indirect.rays=16"};
    vrg_graph *cand = load_raw(cand_sets, w, h), *ref = load_raw(ref_sets, w, h);
    vrg_device_scorer *s = NULL;
    if (!cand || !ref || !CHECK(vrg_device_scorer_create(ctx, w, h, &s) == 0, "scorer"))
        goto out;
    size_t n = (size_t)w * h;
    cpu_frame c = cpu_frame_new(n);
    float *map = malloc(sizeof(float) * n);
    double worst = 0;
    for (uint32_t k = 0; k < frames; k++) {
        vrg_camera cam = *vrg_graph_camera(cand);
        cam.position[0] += 2.0f * k;
        cam.yaw += 1.5f * k;
        vrg_graph_set_camera(cand, &cam);
        vrg_graph_set_camera(ref, &cam);
        vrg_image_data ci, ri;
        if (!CHECK(vrg_graph_frame(cand) == 0 && vrg_graph_frame(ref) == 0, "frame %u", k) ||
            !CHECK(vrg_graph_read(ref, vrg_graph_output(ref), &ri) == 0, "reference readback"))
            break;
        uint8_t *ref_rgb = vrg_image_rgb8(&ri);
        vrg_device_scores d;
        CHECK(vrg_device_score_submit(s, cand, NULL, ref_rgb, 1) == 0, "submit of the graph's output");
        CHECK(vrg_device_score_collect(s, map, &d) == 0, "collect");
        if (!CHECK(vrg_graph_read(cand, vrg_graph_output(cand), &ci) == 0, "candidate readback"))
            break;
        uint8_t *cand_rgb = vrg_image_rgb8(&ci);
        to_float(cand_rgb, n, c.cur);
        to_float(ref_rgb, n, c.refc);
        agree("raw.ini 1 ray vs 16", k, w, h, &c, &d, map, &worst);
        cpu_frame_next(&c);
        free(ci.pixels), free(ri.pixels), free(cand_rgb), free(ref_rgb);
    }
    CHECK(worst <= TOL_FLIP_PIXEL, "rendered: FLIP's maps differ by %g in a pixel", worst);
    cpu_frame_free(&c);
    free(map);
out:
    vrg_device_scorer_destroy(s);
    vrg_graph_destroy(cand);
    vrg_graph_destroy(ref);
}

/* An output that is not the 8-bit image compare writes, or of another size,
 * is refused, naming the output and its format. */
static void test_refused(void)
{
    vrg_graph *g = load("chain.ini"); /* 40x24 rgba16f */
    vrg_device_scorer *s = NULL, *small = NULL;
    if (!g || !CHECK(vrg_graph_frame(g) == 0, "frame") || !CHECK(vrg_device_scorer_create(ctx, 40, 24, &s) == 0, "scorer"))
        goto out;
    uint8_t *ref = calloc(40 * 24, 3);
    CHECK(vrg_device_score_submit(s, g, NULL, ref, 0) == -1, "an rgba16f output was scored");
    CHECK(vrg_device_score_submit(s, NULL, NULL, ref, 0) == -1, "no candidate was scored");
    CHECK(vrg_device_score_submit(s, g, NULL, NULL, 0) == -1, "no reference was scored");
    vrg_device_scores d;
    CHECK(vrg_device_score_collect(s, NULL, &d) == -1, "a collect without a submit");
    free(ref);
    CHECK(vrg_device_scorer_create(ctx, 0, 24, &small) == -1, "an empty scorer");
out:
    vrg_device_scorer_destroy(s);
    vrg_graph_destroy(g);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"synthetic", test_synthetic, 1},
        {"rendered", test_rendered, 1},
        {"refused", test_refused, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
