/* Image metrics for comparing renderings with a reference.
 * Images are display-encoded sRGB values in [0, 1], three floats per pixel,
 * row by row. See docs/compare.md for the definitions and constants. */
#ifndef VOXRG_METRICS_H
#define VOXRG_METRICS_H
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_tools (built with
 * -fvisibility=hidden); its internals stay hidden. */
#pragma GCC visibility push(default)

/* PSNR over the three channels, peak 1. Identical images have no finite
 * PSNR: the value is capped at VRG_PSNR_MAX_DB. */
#define VRG_PSNR_MAX_DB 100.0
double vrg_metric_psnr(const float *test, const float *ref, uint32_t width, uint32_t height);

/* SSIM (Wang et al. 2004) of the luma 0.2989 R + 0.5870 G + 0.1140 B: 11x11
 * Gaussian window (sigma 1.5), K1 0.01, K2 0.03, L 1, averaged over the
 * windows that fit in the image. -1 if the image is under 11x11. */
#define VRG_SSIM_WINDOW 11
double vrg_metric_ssim(const float *test, const float *ref, uint32_t width, uint32_t height);

/* LDR-FLIP (Andersson et al. 2020), mean of the per-pixel error in [0, 1],
 * for a 0.7 m wide 3840-pixel monitor seen from 0.7 m (67 pixels per
 * degree, the paper's default). `map` (width*height floats) receives the
 * error map when not NULL. */
double vrg_metric_flip(const float *test, const float *ref, uint32_t width, uint32_t height, float *map);
double vrg_flip_pixels_per_degree(void);

/* Temporal error: mean over pixels and channels of
 * |(test - test_prev) - (ref - ref_prev)|: change the reference also
 * shows (moving light, camera) is not counted, flicker is. */
double vrg_metric_temporal(const float *test, const float *test_prev, const float *ref, const float *ref_prev, uint32_t width,
                           uint32_t height);

/* A colour for an error in [0, 1] (a magma-like ramp, as FLIP's maps use). */
void vrg_error_color(float e, uint8_t rgb[3]);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
