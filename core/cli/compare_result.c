/* The metrics of `voxrg compare` (names, labels, which way is better), the
 * best candidate by one of them, and the verdict over the cases: shared by
 * the measuring (compare.c) and the report (report.c). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

int vrg_cmp_name_ok(const char *name, size_t len)
{
    if (len < 1 || len > 63 || name[0] == '.' || name[len - 1] == '.')
        return 0;
    for (size_t i = 0; i < len; i++)
        if (!isalnum((unsigned char)name[i]) && !strchr("_-.", name[i]))
            return 0;
    return 1;
}

/* how much better candidate i is than the baseline on a case by metric m:
 * the difference, signed so that positive is better; NAN when unknown */
static double gain(const vrg_cmp_result *c, int i, int base, int m)
{
    double d = c->cand[i].summary[m] - c->cand[base].summary[m];
    return vrg_cmp_metric_higher_better[m] ? d : -d;
}

static void sentence(const vrg_cmp_run *run, int i, vrg_cmp_verdict *v)
{
    const char *me = run->cases[0].cand[i].name, *base = run->cases[0].cand[run->baseline].name;
    if (i == run->baseline) {
        snprintf(v->sentence, sizeof v->sentence, "%s: the baseline", me);
        return;
    }
    int n = run->case_count, p = VRG_CMP_PSNR, fl = VRG_CMP_FLIP;
    int len = snprintf(v->sentence, sizeof v->sentence,
                       "%s: beats %s on %d of %d case%s in PSNR and %d in FLIP (worse on %d and %d, equal on %d and %d); "
                       "mean difference %+.2f dB PSNR, %+.4f FLIP",
                       me, base, v->wins[p], n, n == 1 ? "" : "s", v->wins[fl], v->losses[p], v->losses[fl], v->ties[p], v->ties[fl],
                       v->mean_diff[p], v->mean_diff[fl]);
    if (v->worst[p] >= 0 && len > 0 && (size_t)len < sizeof v->sentence) {
        const char *name = run->cases[v->worst[p]].case_name;
        snprintf(v->sentence + len, sizeof v->sentence - (size_t)len, "; worst: %s, %+.2f dB", *name ? name : "the run", v->worst_diff[p]);
    }
}

int vrg_cmp_judge(vrg_cmp_run *run)
{
    int count = run->case_count ? run->cases[0].count : 0;
    free(run->verdict);
    run->verdict = calloc((size_t)(count ? count : 1), sizeof *run->verdict);
    if (!run->verdict)
        return -1;
    for (int i = 0; i < count; i++) {
        vrg_cmp_verdict *v = &run->verdict[i];
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            double sum = 0, worst = INFINITY;
            int known = 0;
            v->worst[m] = -1;
            for (int k = 0; k < run->case_count; k++) {
                double g = gain(&run->cases[k], i, run->baseline, m);
                if (isnan(g))
                    continue;
                known++;
                sum += run->cases[k].cand[i].summary[m] - run->cases[k].cand[run->baseline].summary[m];
                v->wins[m] += g > 0, v->losses[m] += g < 0, v->ties[m] += g == 0;
                if (g < worst)
                    worst = g, v->worst[m] = k;
            }
            v->mean_diff[m] = known ? sum / known : NAN;
            v->worst_diff[m] = v->worst[m] >= 0 ? (vrg_cmp_metric_higher_better[m] ? worst : -worst) : NAN;
        }
        sentence(run, i, v);
    }
    return 0;
}
