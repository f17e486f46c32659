/* The metrics of `voxrg compare` (names, labels, which way is better) and
 * the best candidate by one of them: shared by the measuring (compare.c)
 * and the report (report.c). */
#include <math.h>
#include "compare_result.h"

const char *const vrg_cmp_metric_names[VRG_CMP_METRICS] = {"psnr", "ssim", "flip", "temporal"};
const char *const vrg_cmp_metric_labels[VRG_CMP_METRICS] = {"PSNR (dB)", "SSIM", "FLIP", "temporal error"};
const int vrg_cmp_metric_higher_better[VRG_CMP_METRICS] = {1, 1, 0, 0};

int vrg_cmp_best(const vrg_cmp_result *r, int m)
{
    int best = -1;
    for (int i = 0; i < r->count; i++) {
        double v = m < 0 ? -r->cand[i].gpu_mean_ms : vrg_cmp_metric_higher_better[m] ? r->cand[i].summary[m] : -r->cand[i].summary[m];
        double b = best < 0 ? 0
                   : m < 0  ? -r->cand[best].gpu_mean_ms
                   : vrg_cmp_metric_higher_better[m] ? r->cand[best].summary[m]
                                                      : -r->cand[best].summary[m];
        if (!isnan(v) && (best < 0 || v > b))
            best = i;
    }
    return best;
}
