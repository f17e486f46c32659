#ifndef VOXRG_CLI_COMPARE_RESULT_H
#define VOXRG_CLI_COMPARE_RESULT_H
/* What `voxrg compare` measured: per case, each candidate's metrics per
 * frame and their summaries, pass timings and the frames shown; and over
 * the cases, each candidate against the baseline (the verdict). The
 * measuring (compare.c) fills it in, the report (report.c) and the files
 * read it. */
#include <stddef.h>
#include <stdint.h>

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

/* One case: its settings and every candidate's results on it. */
typedef struct vrg_cmp_result {
    char case_name[64];             /* "" for a run without --cases */
    char scene[1024];               /* the case's scene.PARAM=VALUE overrides, comma-separated */
    const char *reference;          /* graph file */
    char reference_overrides[1024];
    const char *camera;             /* path file, or NULL: the first graph's [camera] */
    const char *device;
    uint32_t width, height, frames, warmup;
    uint32_t start;                 /* the camera path's first frame (frame numbers count from it) */
    uint32_t reference_cached;      /* reference frames taken from the cache */
    int shown[VRG_CMP_MAX_SHOWN], shown_count;
    uint8_t *reference_shown[VRG_CMP_MAX_SHOWN];
    vrg_cmp_candidate *cand;        /* [count], the same candidates in every case */
    int count;
} vrg_cmp_result;

/* One candidate over the cases, against the baseline candidate: per
 * metric the mean of its summary's difference to the baseline's, the
 * cases it is better, worse and equal on, and its worst case. */
typedef struct vrg_cmp_verdict {
    double mean_diff[VRG_CMP_METRICS];
    int wins[VRG_CMP_METRICS], losses[VRG_CMP_METRICS], ties[VRG_CMP_METRICS];
    int worst[VRG_CMP_METRICS];      /* the case with the worst difference; -1 when none is worse */
    double worst_diff[VRG_CMP_METRICS];
    char sentence[512];
} vrg_cmp_verdict;

/* The whole run: the cases, then the verdict of each candidate. */
typedef struct vrg_cmp_run {
    const char *cases_file;         /* NULL without --cases */
    int score_device;               /* --score device: of the candidates' frames only the shown are written */
    vrg_cmp_result *cases;          /* [case_count] */
    int case_count;
    int baseline;                   /* the candidate the others are measured against */
    vrg_cmp_verdict *verdict;       /* [candidate count] */
} vrg_cmp_run;

/* The candidate with the best summary of metric m (or GPU ms, m = -1). */
int vrg_cmp_best(const vrg_cmp_result *r, int m);

/* A candidate's or case's name, part of file names and a CSV field: 1 to
 * 63 of A-Z a-z 0-9 _ - and dots, not first or last. */
int vrg_cmp_name_ok(const char *name, size_t len);

/* Fills run->verdict (allocated here) from the cases' summaries. 0 or -1. */
int vrg_cmp_judge(vrg_cmp_run *run);
#endif
