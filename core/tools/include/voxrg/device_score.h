/* Scoring on the device: the metrics of voxrg/metrics.h (PSNR, SSIM,
 * LDR-FLIP, temporal error) computed by compute shaders on the device that
 * rendered the frame, so that only the per-frame sums (and FLIP's error
 * map, when asked for) come back to the host. The functions of metrics.h
 * are the reference; docs/compare.md says how closely these agree. */
#ifndef VOXRG_DEVICE_SCORE_H
#define VOXRG_DEVICE_SCORE_H
#include <stdint.h>
#include "voxrg/voxrg.h"

#ifdef __cplusplus
extern "C" {
#endif
#pragma GCC visibility push(default)

typedef struct vrg_device_scorer vrg_device_scorer;

typedef struct vrg_device_scores {
    double psnr, ssim, flip;
    double temporal; /* NAN on the first frame of a sequence */
} vrg_device_scores;

/* Pipelines and buffers for width x height frames on ctx's device. Returns
 * 0, or -1 after printing why (a shader that does not compile names its
 * file and line). */
int vrg_device_scorer_create(vrg_context *ctx, uint32_t width, uint32_t height, vrg_device_scorer **out);
/* Waits for a frame still being scored. NULL is fine. */
void vrg_device_scorer_destroy(vrg_device_scorer *s);
/* The next frame starts a sequence: it has no previous frame (temporal
 * error NAN). */
void vrg_device_scorer_restart(vrg_device_scorer *s);

/* Submits the scoring of one frame against the reference `ref` (RGB8,
 * width * height * 3 bytes, copied before it returns): the candidate is the
 * output of g's last frame when g is not NULL (an R8G8B8A8_UNORM image: the
 * bytes compare writes to PNG, never read back here), else the RGB8 bytes
 * `test`. The previous frame submitted since the last restart is the
 * temporal error's previous frame, for the candidate and the reference
 * alike. Returns at once when the device works on its own (a host may
 * render the next frame meanwhile: the work is ordered before it on the
 * queue); one frame at a time: vrg_device_score_collect comes before the
 * next submit. want_map: keep FLIP's error map for the collect. Returns 0,
 * or -1 after printing why (the output's format or size not scorable). */
int vrg_device_score_submit(vrg_device_scorer *s, vrg_graph *g, const uint8_t *test, const uint8_t *ref, int want_map);
/* Waits for the frame submitted and returns its scores; with want_map at
 * the submit and map not NULL, FLIP's per-pixel error (width * height
 * floats). Returns 0, or -1 after printing why. */
int vrg_device_score_collect(vrg_device_scorer *s, float *map, vrg_device_scores *out);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
