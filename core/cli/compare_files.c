/* What a `voxrg compare` run writes and prints (compare_files.h):
 * metrics.csv and metrics.json, the summaries and the verdict on stdout,
 * and a run's memory; for the run (compare.c) and the merge of its
 * shards (compare_shard.c) alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "compare_files.h"
#include "util.h"
#include "voxrg/metrics.h"
#include "voxrg/output.h"

/* a number for JSON and CSV: NAN (no value) as null / empty */
static void num(FILE *f, double v, int json)
{
    if (isnan(v))
        fputs(json ? "null" : "", f);
    else
        fprintf(f, "%.9g", v);
}

/* a CSV field, quoted when it holds a separator, a quote or a line break
 * (RFC 4180): graph names come from file names, which may */
static void csv_field(FILE *f, const char *s)
{
    if (!s[strcspn(s, ",\"\r\n")]) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static int write_csv(const char *dir, const vrg_cmp_run *run)
{
    char final[VRG_CLI_PATH];
    snprintf(final, sizeof final, "%s/metrics.csv", dir);
    vrg_output *out = vrg_output_open(final);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    fprintf(f, "%scandidate,frame,warmup,psnr,ssim,flip,temporal\n", run->cases_file ? "case," : "");
    for (int c = 0; c < run->case_count; c++) {
        const vrg_cmp_result *r = &run->cases[c];
        for (int i = 0; i < r->count; i++)
            for (uint32_t k = 0; k < r->frames; k++) {
                if (run->cases_file)
                    fprintf(f, "%s,", r->case_name); /* a case name needs no quotes */
                csv_field(f, r->cand[i].name);
                fprintf(f, ",%u,%d", k, k < r->warmup);
                for (int m = 0; m < VRG_CMP_METRICS; m++) {
                    fputc(',', f);
                    num(f, r->cand[i].per_frame[m][k], 0);
                }
                fputc('\n', f);
            }
    }
    return vrg_output_commit(out);
}

/* one case's settings and candidates, as members of an object (indented by `in`) */
static void json_case(FILE *f, const vrg_cmp_result *r, const char *in)
{
    char e1[2100], e2[2100], e3[2100];
    fprintf(f, "%s\"reference\": {\"graph\": \"%s\", \"overrides\": \"%s\", \"frames_from_cache\": %u},\n", in,
            vrg_cli_json_str(r->reference, e1, sizeof e1), vrg_cli_json_str(r->reference_overrides, e2, sizeof e2), r->reference_cached);
    fprintf(f, "%s\"camera\": %s%s%s,\n", in, r->camera ? "\"" : "", r->camera ? vrg_cli_json_str(r->camera, e1, sizeof e1) : "null",
            r->camera ? "\"" : "");
    fprintf(f, "%s\"device\": \"%s\",\n%s\"width\": %u,\n%s\"height\": %u,\n%s\"start\": %u,\n%s\"frames\": %u,\n%s\"warmup\": %u,\n", in,
            vrg_cli_json_str(r->device, e1, sizeof e1), in, r->width, in, r->height, in, r->start, in, r->frames, in, r->warmup);
    fprintf(f, "%s\"psnr_cap_db\": %g,\n%s\"candidates\": [", in, VRG_PSNR_MAX_DB, in);
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        fprintf(f, "%s\n%s  {\"name\": \"%s\", \"graph\": \"%s\", \"overrides\": \"%s\", ", i ? "," : "", in,
                vrg_cli_json_str(c->name, e1, sizeof e1), vrg_cli_json_str(c->graph, e2, sizeof e2),
                vrg_cli_json_str(c->overrides, e3, sizeof e3));
        /* the listed graph a variant changes, by its candidate name: two listings may share a path */
        if (c->base >= 0)
            fprintf(f, "\"variant_of\": \"%s\",\n%s    \"summary\": {", vrg_cli_json_str(r->cand[c->base].name, e1, sizeof e1), in);
        else
            fprintf(f, "\"variant_of\": null,\n%s    \"summary\": {", in);
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            fprintf(f, "\"%s\": ", vrg_cmp_metric_names[m]);
            num(f, c->summary[m], 1);
            fputs(", ", f);
        }
        fprintf(f, "\"gpu_ms_mean\": %.9g, \"gpu_ms_p95\": %.9g},\n%s    \"passes\": [", c->gpu_mean_ms, c->gpu_p95_ms, in);
        for (int p = 0; p < c->pass_count; p++)
            fprintf(f, "%s{\"name\": \"%s\", \"mean_ms\": %.9g, \"p95_ms\": %.9g}", p ? ", " : "",
                    vrg_cli_json_str(c->passes[p].name, e1, sizeof e1), c->passes[p].mean_ms, c->passes[p].p95_ms);
        fprintf(f, "],\n%s    \"frames\": [", in);
        for (uint32_t k = 0; k < r->frames; k++) {
            fprintf(f, "%s\n%s      {\"frame\": %u", k ? "," : "", in, k);
            for (int m = 0; m < VRG_CMP_METRICS; m++) {
                fprintf(f, ", \"%s\": ", vrg_cmp_metric_names[m]);
                num(f, c->per_frame[m][k], 1);
            }
            fputc('}', f);
        }
        fprintf(f, "\n%s    ]}", in);
    }
    fprintf(f, "\n%s]", in);
}

/* per metric: {"psnr": V, ...} of one of the verdict's arrays */
static void json_metrics(FILE *f, const char *key, const double *v, const int *iv)
{
    fprintf(f, "\"%s\": {", key);
    for (int m = 0; m < VRG_CMP_METRICS; m++) {
        fprintf(f, "%s\"%s\": ", m ? ", " : "", vrg_cmp_metric_names[m]);
        if (v)
            num(f, v[m], 1);
        else
            fprintf(f, "%d", iv[m]);
    }
    fputc('}', f);
}

static void json_verdict(FILE *f, const vrg_cmp_run *run)
{
    char e1[2100];
    const vrg_cmp_result *r0 = &run->cases[0];
    fprintf(f, "  \"baseline\": \"%s\",\n  \"verdict\": [", vrg_cli_json_str(r0->cand[run->baseline].name, e1, sizeof e1));
    for (int i = 0; i < r0->count; i++) {
        const vrg_cmp_verdict *v = &run->verdict[i];
        fprintf(f, "%s\n    {\"candidate\": \"%s\", ", i ? "," : "", vrg_cli_json_str(r0->cand[i].name, e1, sizeof e1));
        json_metrics(f, "mean_difference", v->mean_diff, NULL);
        fputs(", ", f);
        json_metrics(f, "wins", NULL, v->wins);
        fputs(", ", f);
        json_metrics(f, "losses", NULL, v->losses);
        fputs(", ", f);
        json_metrics(f, "ties", NULL, v->ties);
        fputs(",\n     \"worst\": {", f);
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            fprintf(f, "%s\"%s\": ", m ? ", " : "", vrg_cmp_metric_names[m]);
            if (v->worst[m] < 0)
                fputs("null", f);
            else {
                fprintf(f, "{\"case\": \"%s\", \"difference\": ", run->cases[v->worst[m]].case_name);
                num(f, v->worst_diff[m], 1);
                fputc('}', f);
            }
        }
        fprintf(f, "},\n     \"sentence\": \"%s\"}", vrg_cli_json_str(v->sentence, e1, sizeof e1));
    }
    fputs("\n  ]\n", f);
}

static int write_json(const char *dir, const vrg_cmp_run *run)
{
    char final[VRG_CLI_PATH], e1[2100], e2[2100];
    snprintf(final, sizeof final, "%s/metrics.json", dir);
    vrg_output *out = vrg_output_open(final);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    fputs("{\n", f);
    if (!run->cases_file)
        json_case(f, &run->cases[0], "  ");
    else {
        fprintf(f, "  \"cases_file\": \"%s\",\n  \"cases\": [", vrg_cli_json_str(run->cases_file, e1, sizeof e1));
        for (int c = 0; c < run->case_count; c++) {
            const vrg_cmp_result *r = &run->cases[c];
            fprintf(f, "%s\n    {\"name\": \"%s\",\n     \"scene\": \"%s\",\n", c ? "," : "", r->case_name,
                    vrg_cli_json_str(r->scene, e2, sizeof e2));
            json_case(f, r, "     ");
            fputs("}", f);
        }
        fputs("\n  ]", f);
    }
    fputs(",\n", f);
    json_verdict(f, run);
    fputs("}\n", f);
    return vrg_output_commit(out);
}

int vrg_cmp_write_metrics(const char *dir, const vrg_cmp_run *run) { return write_csv(dir, run) || write_json(dir, run) ? -1 : 0; }

static void print_summary(const vrg_cmp_result *r)
{
    printf("\n%s%s%u frames at %ux%u, summary from frame %u on; reference %s%s%s\n", r->case_name[0] ? r->case_name : "",
           r->case_name[0] ? ": " : "", r->frames, r->width, r->height, r->warmup, r->reference, r->reference_overrides[0] ? " with " : "",
           r->reference_overrides);
    printf("%-20s %11s %8s %8s %10s %10s %10s\n", "candidate", "PSNR dB", "SSIM", "FLIP", "temporal", "GPU ms", "p95 ms");
    int best[VRG_CMP_METRICS + 1];
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        best[m] = vrg_cmp_best(r, m);
    best[VRG_CMP_METRICS] = vrg_cmp_best(r, -1);
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        printf("%-20.20s %10.2f%s %7.4f%s %7.4f%s %9.5f%s %9.2f%s %10.2f\n", c->name, c->summary[0], best[0] == i ? "*" : " ", c->summary[1],
               best[1] == i ? "*" : " ", c->summary[2], best[2] == i ? "*" : " ", c->summary[3], best[3] == i ? "*" : " ", c->gpu_mean_ms,
               best[4] == i ? "*" : " ", c->gpu_p95_ms);
    }
    printf("* best in the column\n");
}

void vrg_cmp_print(const vrg_cmp_run *run)
{
    for (int c = 0; c < run->case_count; c++)
        print_summary(&run->cases[c]);
    printf("\n");
    for (int i = 0; i < run->cases[0].count; i++)
        printf("%s\n", run->verdict[i].sentence);
}

void vrg_cmp_free_shown(vrg_cmp_result *r)
{
    for (int i = 0; r->cand && i < r->count; i++)
        for (int s = 0; s < VRG_CMP_MAX_SHOWN; s++) {
            free(r->cand[i].shown[s]), free(r->cand[i].flip_map[s]);
            r->cand[i].shown[s] = NULL, r->cand[i].flip_map[s] = NULL;
        }
    for (int s = 0; s < VRG_CMP_MAX_SHOWN; s++)
        free(r->reference_shown[s]), r->reference_shown[s] = NULL;
}

void vrg_cmp_run_free(vrg_cmp_run *run)
{
    for (int c = 0; c < run->case_count; c++) {
        vrg_cmp_result *r = &run->cases[c];
        vrg_cmp_free_shown(r);
        for (int i = 0; r->cand && i < r->count; i++)
            for (int m = 0; m < VRG_CMP_METRICS; m++)
                free(r->cand[i].per_frame[m]);
        free(r->cand);
    }
    free(run->cases);
    free(run->verdict);
}
