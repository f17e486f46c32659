#ifndef VOXRG_CLI_COMPARE_RESULT_H
#define VOXRG_CLI_COMPARE_RESULT_H
/* What `voxrg compare` measured: each candidate's metrics per frame and
 * their summaries, pass timings and the frames shown; the measuring
 * (compare.c) fills it in, the report (report.c) and the files read it. */
#include <stdint.h>

#define VRG_CMP_MAX_CANDIDATES 16
#define VRG_CMP_MAX_SHOWN 3
#define VRG_CMP_MAX_PASSES 64

/* the metrics, in the order of every table, file and plot */
enum { VRG_CMP_PSNR, VRG_CMP_SSIM, VRG_CMP_FLIP, VRG_CMP_TEMPORAL, VRG_CMP_METRICS };
extern const char *const vrg_cmp_metric_names[VRG_CMP_METRICS];  /* psnr ssim flip temporal */
extern const char *const vrg_cmp_metric_labels[VRG_CMP_METRICS]; /* PSNR (dB) ... */
extern const int vrg_cmp_metric_higher_better[VRG_CMP_METRICS];

typedef struct vrg_cmp_pass {
    char name[64];
    double mean_ms, p95_ms;
} vrg_cmp_pass;

typedef struct vrg_cmp_candidate {
    char name[64];
    char graph[1024];
    char overrides[1024];         /* "pass.param=value,..." as given, "" for none */
    int base;                     /* a variant: the index of the listed graph it changes; -1 for a listed graph */
    double *per_frame[VRG_CMP_METRICS]; /* [frames]; temporal of frame 0 is NAN */
    double summary[VRG_CMP_METRICS];    /* means over the frames from warmup on */
    vrg_cmp_pass passes[VRG_CMP_MAX_PASSES];
    int pass_count;
    double gpu_mean_ms, gpu_p95_ms; /* the whole frame, from warmup on */
    uint8_t *shown[VRG_CMP_MAX_SHOWN];   /* 8-bit RGB of the shown frames */
    float *flip_map[VRG_CMP_MAX_SHOWN];
} vrg_cmp_candidate;

typedef struct vrg_cmp_result {
    const char *reference;          /* graph file */
    char reference_overrides[1024];
    const char *camera;             /* path file, or NULL: the first graph's [camera] */
    const char *device;
    uint32_t width, height, frames, warmup;
    uint32_t start;                 /* the camera path's first frame (frame numbers count from it) */
    uint32_t reference_cached;      /* reference frames taken from the cache */
    int shown[VRG_CMP_MAX_SHOWN], shown_count;
    uint8_t *reference_shown[VRG_CMP_MAX_SHOWN];
    vrg_cmp_candidate cand[VRG_CMP_MAX_CANDIDATES];
    int count;
} vrg_cmp_result;

/* The candidate with the best summary of metric m (or GPU ms, m = -1). */
int vrg_cmp_best(const vrg_cmp_result *r, int m);
#endif
