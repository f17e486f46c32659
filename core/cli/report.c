/* The HTML report of voxrg compare: one self-contained file (images as
 * data: URIs, plots as inline SVG, no scripts). In order: the settings, the
 * summary table (best per column marked), per-frame plots of each metric,
 * GPU time as stacked bars per candidate, and for the shown frames the
 * reference and each candidate side by side with FLIP maps and zoomed
 * crops where the error is largest. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "report.h"
#include "voxrg/metrics.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "voxrg/voxrg.h"

/* candidates' colours (plots, legends); passes' colours (bars) */
static const char *const series[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf"};
static const char *const pass_colors[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1",
                                          "#ff9da7", "#9c755f", "#bab0ac", "#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                                          "#66a61e", "#e6ab02", "#a6761d", "#666666", "#a6cee3", "#fb9a99"};

static const char *cand_color(int i) { return series[i % (int)(sizeof series / sizeof series[0])]; }

/* 1 when candidate i's pass p is the first of its name in the result */
static int first_of_name(const vrg_cmp_result *r, int i, int p)
{
    const char *name = r->cand[i].passes[p].name;
    for (int j = 0; j <= i; j++)
        for (int q = 0; q < (j == i ? p : r->cand[j].pass_count); q++)
            if (!strcmp(r->cand[j].passes[q].name, name))
                return 0;
    return 1;
}

/* a pass's colour: by the order its name first appears, so neighbours differ */
static const char *pass_color(const vrg_cmp_result *r, const char *name)
{
    int k = 0;
    for (int i = 0; i < r->count; i++)
        for (int p = 0; p < r->cand[i].pass_count; p++)
            if (first_of_name(r, i, p)) {
                if (!strcmp(r->cand[i].passes[p].name, name))
                    return pass_colors[k % (int)(sizeof pass_colors / sizeof pass_colors[0])];
                k++;
            }
    return pass_colors[0];
}

static void esc(FILE *f, const char *s)
{
    for (; *s; s++)
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
}

static void base64(FILE *f, const unsigned char *d, size_t n)
{
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) | (i + 2 < n ? d[i + 2] : 0);
        fputc(t[v >> 18 & 63], f);
        fputc(t[v >> 12 & 63], f);
        fputc(i + 1 < n ? t[v >> 6 & 63] : '=', f);
        fputc(i + 2 < n ? t[v & 63] : '=', f);
    }
}

/* <img> of 8-bit RGB, shown `scale` times its size */
static int image(FILE *f, const uint8_t *rgb, uint32_t w, uint32_t h, int scale, const char *alt)
{
    void *png;
    size_t size;
    if (vrg_png_encode_rgb8(rgb, w, h, &png, &size) != 0)
        return -1;
    /* tabindex: a click focuses the image, which the style zooms (no script) */
    fprintf(f, "<img tabindex=\"0\" width=\"%u\" height=\"%u\" alt=\"", w * (uint32_t)scale, h * (uint32_t)scale);
    esc(f, alt);
    fputs("\" src=\"data:image/png;base64,", f);
    base64(f, png, size);
    fputs("\">", f);
    free(png);
    return 0;
}

/* <figure> of an image made for it (freed here; NULL: it could not be
 * made) with the caption LABEL NAME */
static int figure(FILE *f, uint8_t *rgb, uint32_t w, uint32_t h, int scale, const char *alt, const char *label, const char *name)
{
    fputs("<figure>", f);
    int rc = rgb ? image(f, rgb, w, h, scale, alt) : -1;
    fputs("<figcaption>", f);
    esc(f, label);
    esc(f, name);
    fputs("</figcaption></figure>", f);
    free(rgb);
    return rc;
}

/* FLIP map, 0 to `range` over the error colours (above it: the top colour) */
static uint8_t *heat_map(const float *map, size_t n, double range)
{
    uint8_t *rgb = malloc(n * 3);
    for (size_t i = 0; rgb && i < n; i++)
        vrg_error_color((float)fmin(map[i] / range, 1.0), rgb + 3 * i);
    return rgb;
}

/* signed: blue where below the reference, red where above, white equal,
 * full at +-range */
static void signed_color(double d, double range, uint8_t rgb[3])
{
    double t = fmin(fabs(d) / range, 1.0);
    uint8_t fade = (uint8_t)lround(255 * (1 - t));
    rgb[0] = d > 0 ? 255 : fade, rgb[1] = fade, rgb[2] = d < 0 ? 255 : fade;
}

static double luma(const uint8_t *p) { return (0.2989 * p[0] + 0.5870 * p[1] + 0.1140 * p[2]) / 255.0; }

/* 1, 2 or 5 times a power of ten, at least v: a scale's end that reads well */
static double nice_ceil(double v)
{
    double p = pow(10, floor(log10(v)));
    return v <= p ? p : v <= 2 * p ? 2 * p : v <= 5 * p ? 5 * p : 10 * p;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* The scale of shown frame s's maps: the 99th percentile of the FLIP
 * errors (signed = 0) or of |luma difference| (signed = 1) over the
 * candidates, so that denoiser-level errors are seen, not only outliers;
 * at least 0.001, at most 1. */
static double map_range(const vrg_cmp_result *r, int s, int is_signed)
{
    size_t n = (size_t)r->width * r->height, total = 0;
    float *v = malloc(sizeof *v * n * (size_t)(r->count ? r->count : 1));
    for (int i = 0; v && i < r->count; i++)
        for (size_t p = 0; p < n; p++)
            if (!is_signed && r->cand[i].flip_map[s])
                v[total++] = r->cand[i].flip_map[s][p];
            else if (is_signed && r->cand[i].shown[s])
                v[total++] = (float)fabs(luma(r->cand[i].shown[s] + 3 * p) - luma(r->reference_shown[s] + 3 * p));
    double q = 1;
    if (v && total) {
        qsort(v, total, sizeof *v, cmp_float);
        q = v[(size_t)(0.99 * (double)(total - 1))];
    }
    free(v);
    return nice_ceil(fmin(fmax(q, 0.001), 1.0));
}

static uint8_t *signed_map(const uint8_t *cand, const uint8_t *ref, size_t n, double range)
{
    uint8_t *rgb = malloc(n * 3);
    for (size_t i = 0; rgb && i < n; i++)
        signed_color(luma(cand + 3 * i) - luma(ref + 3 * i), range, rgb + 3 * i);
    return rgb;
}

static uint8_t *crop(const uint8_t *rgb, uint32_t w, uint32_t x0, uint32_t y0, uint32_t cw, uint32_t ch)
{
    uint8_t *out = malloc((size_t)cw * ch * 3);
    for (uint32_t y = 0; out && y < ch; y++)
        memcpy(out + (size_t)y * cw * 3, rgb + ((size_t)(y0 + y) * w + x0) * 3, (size_t)cw * 3);
    return out;
}

/* The crop window (side `side`) with the largest FLIP summed over the candidates. */
static void worst_window(const vrg_cmp_result *r, int s, uint32_t side, uint32_t *bx, uint32_t *by)
{
    uint32_t w = r->width, h = r->height;
    double *sum = calloc((size_t)(w + 1) * (h + 1), sizeof *sum); /* summed-area table */
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            double v = 0;
            for (int i = 0; i < r->count; i++)
                v += r->cand[i].flip_map[s] ? r->cand[i].flip_map[s][(size_t)y * w + x] : 0;
            sum[(size_t)(y + 1) * (w + 1) + x + 1] = v + sum[(size_t)y * (w + 1) + x + 1] + sum[(size_t)(y + 1) * (w + 1) + x] - sum[(size_t)y * (w + 1) + x];
        }
    double best = -1;
    *bx = *by = 0;
    for (uint32_t y = 0; y + side <= h; y += 2)
        for (uint32_t x = 0; x + side <= w; x += 2) {
            double v = sum[(size_t)(y + side) * (w + 1) + x + side] - sum[(size_t)y * (w + 1) + x + side] - sum[(size_t)(y + side) * (w + 1) + x] +
                       sum[(size_t)y * (w + 1) + x];
            if (v > best)
                best = v, *bx = x, *by = y;
        }
    free(sum);
}

/* ---- plots ---- */

enum { PLOT_W = 560, PLOT_H = 200, PAD_L = 56, PAD_R = 12, PAD_T = 10, PAD_B = 26 };

static void plot(FILE *f, const vrg_cmp_result *r, int m)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < r->count; i++)
        for (uint32_t k = 0; k < r->frames; k++) {
            double v = r->cand[i].per_frame[m][k];
            if (!isnan(v))
                lo = fmin(lo, v), hi = fmax(hi, v);
        }
    if (!(hi >= lo))
        lo = 0, hi = 1;
    if (hi - lo < 1e-9)
        lo -= 0.5, hi += 0.5;
    double pad = (hi - lo) * 0.06;
    lo -= pad, hi += pad;
    double xs = (double)(PLOT_W - PAD_L - PAD_R) / (r->frames > 1 ? r->frames - 1 : 1), ys = (PLOT_H - PAD_T - PAD_B) / (hi - lo);
#define PX(k) (PAD_L + (k) * xs)
#define PY(v) (PLOT_H - PAD_B - ((v) - lo) * ys)
    fprintf(f, "<figure class=\"plot\"><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" role=\"img\">",
            PLOT_W, PLOT_H, PLOT_W, PLOT_H);
    if (r->warmup)
        fprintf(f, "<rect class=\"warmup\" x=\"%.1f\" y=\"%d\" width=\"%.1f\" height=\"%d\"><title>warm-up frames, not in the summary</title></rect>",
                PX(0.0), PAD_T, fmax(PX(r->warmup - 0.5) - PX(0.0), 1), PLOT_H - PAD_T - PAD_B);
    fprintf(f, "<line class=\"axis\" x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\"/>", PAD_L, PLOT_H - PAD_B, PLOT_W - PAD_R, PLOT_H - PAD_B);
    fprintf(f, "<line class=\"axis\" x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\"/>", PAD_L, PAD_T, PAD_L, PLOT_H - PAD_B);
    for (int t = 0; t <= 4; t++) {
        double v = lo + (hi - lo) * t / 4;
        fprintf(f, "<line class=\"grid\" x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\"/><text class=\"tick\" x=\"%d\" y=\"%.1f\">%.4g</text>", PAD_L,
                PY(v), PLOT_W - PAD_R, PY(v), PAD_L - 4, PY(v) + 4, v);
    }
    uint32_t step = r->frames > 10 ? (r->frames + 9) / 10 : 1;
    for (uint32_t k = 0; k < r->frames; k += step)
        fprintf(f, "<text class=\"xtick\" x=\"%.1f\" y=\"%d\">%u</text>", PX((double)k), PLOT_H - PAD_B + 16, k);
    /* the first candidates drawn widest, each later one narrower on top and
     * dashed by its round of the colours: a line under an equal one shows */
    static const char *const dashes[] = {"none", "6 3", "2 2", "8 3 2 3"};
    for (int i = 0; i < r->count; i++) {
        double width = r->count > 1 ? 4.5 - 3.0 * i / (r->count - 1) : 2;
        int round = i / (int)(sizeof series / sizeof series[0]);
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%.2f\" stroke-dasharray=\"%s\" stroke-opacity=\"0.9\" points=\"",
                cand_color(i), width, dashes[round % 4]);
        for (uint32_t k = 0; k < r->frames; k++)
            if (!isnan(r->cand[i].per_frame[m][k]))
                fprintf(f, "%.1f,%.1f ", PX((double)k), PY(r->cand[i].per_frame[m][k]));
        fputs("\"><title>", f);
        esc(f, r->cand[i].name);
        fputs("</title></polyline>", f);
    }
#undef PX
#undef PY
    fprintf(f, "</svg><figcaption>%s per frame (%s is better)</figcaption></figure>\n", vrg_cmp_metric_labels[m],
            vrg_cmp_metric_higher_better[m] ? "higher" : "lower");
}

static void bars(FILE *f, const vrg_cmp_result *r)
{
    double most = 0;
    for (int i = 0; i < r->count; i++) {
        double t = 0;
        for (int p = 0; p < r->cand[i].pass_count; p++)
            t += r->cand[i].passes[p].mean_ms;
        most = fmax(most, t);
    }
    enum { LABEL = 150, BAR = 480, ROW = 26 };
    int h = ROW * r->count + 8;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" role=\"img\">", LABEL + BAR + 90, h,
            LABEL + BAR + 90, h);
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        double x = LABEL, y = 4 + ROW * i, t = 0;
        fprintf(f, "<text class=\"label\" x=\"%d\" y=\"%.1f\">", LABEL - 6, y + 16);
        esc(f, c->name);
        fputs("</text>", f);
        for (int p = 0; p < c->pass_count; p++) {
            double wd = most > 0 ? c->passes[p].mean_ms / most * BAR : 0;
            fprintf(f, "<rect class=\"pass\" x=\"%.2f\" y=\"%.1f\" width=\"%.2f\" height=\"20\" fill=\"%s\"><title>", x, y, wd,
                    pass_color(r, c->passes[p].name));
            esc(f, c->passes[p].name);
            fprintf(f, ": %.3f ms (p95 %.3f)</title></rect>", c->passes[p].mean_ms, c->passes[p].p95_ms);
            x += wd;
            t += c->passes[p].mean_ms;
        }
        fprintf(f, "<text class=\"total\" x=\"%.1f\" y=\"%.1f\">%.2f ms</text>", x + 6, y + 16, t);
    }
    fputs("</svg>\n<p class=\"legend\">", f);
    /* each pass name once */
    for (int i = 0; i < r->count; i++)
        for (int p = 0; p < r->cand[i].pass_count; p++) {
            if (!first_of_name(r, i, p))
                continue;
            fprintf(f, "<span><i style=\"background:%s\"></i>", pass_color(r, r->cand[i].passes[p].name));
            esc(f, r->cand[i].passes[p].name);
            fputs("</span> ", f);
        }
    fputs("</p>\n", f);
    /* the same as a table, with the p95s: a row per pass, a column per candidate */
    fputs("<table class=\"passes\"><thead><tr><th>pass: mean / p95 ms</th>", f);
    for (int i = 0; i < r->count; i++) {
        fputs("<th>", f);
        esc(f, r->cand[i].name);
        fputs("</th>", f);
    }
    fputs("</tr></thead><tbody>\n", f);
    for (int i = 0; i < r->count; i++)
        for (int p = 0; p < r->cand[i].pass_count; p++) {
            const char *name = r->cand[i].passes[p].name;
            if (!first_of_name(r, i, p))
                continue;
            fputs("<tr><td>", f);
            esc(f, name);
            fputs("</td>", f);
            for (int j = 0; j < r->count; j++) {
                const vrg_cmp_pass *hit = NULL;
                for (int q = 0; q < r->cand[j].pass_count && !hit; q++)
                    hit = !strcmp(r->cand[j].passes[q].name, name) ? &r->cand[j].passes[q] : NULL;
                if (hit)
                    fprintf(f, "<td class=\"num\">%.3f / %.3f</td>", hit->mean_ms, hit->p95_ms);
                else
                    fputs("<td class=\"num\">-</td>", f);
            }
            fputs("</tr>\n", f);
        }
    fputs("<tr><td>whole frame</td>", f);
    for (int j = 0; j < r->count; j++)
        fprintf(f, "<td class=\"num\">%.3f / %.3f</td>", r->cand[j].gpu_mean_ms, r->cand[j].gpu_p95_ms);
    fputs("</tr></tbody></table>\n", f);
}

/* ---- the page ---- */

static const char *style =
    "body{font:14px/1.4 system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}"
    "h1{font-size:22px}h2{font-size:18px;margin-top:28px;border-bottom:1px solid #ccc}"
    "table{border-collapse:collapse}th,td{padding:4px 10px;border-bottom:1px solid #e3e3e3;text-align:left}"
    "td.num{text-align:right;font-variant-numeric:tabular-nums}td.best{font-weight:bold;background:#e6f4e6}"
    ".plots{display:flex;flex-wrap:wrap;gap:12px}figure{margin:0 12px 12px 0}figcaption{font-size:12px;color:#555}"
    ".axis{stroke:#444}.grid{stroke:#eee}.tick{font-size:10px;text-anchor:end}.xtick{font-size:10px;text-anchor:middle}"
    ".warmup{fill:#f0f0f0}.label{font-size:12px;text-anchor:end}.total{font-size:12px}"
    ".legend span{margin-right:14px;white-space:nowrap}.legend i{display:inline-block;width:12px;height:12px;margin-right:4px;vertical-align:-1px}"
    "table.matrix td small{color:#555}ul.verdict li{margin:4px 0}"
    ".frames{display:flex;flex-wrap:wrap;gap:8px;align-items:flex-start}.frames img{display:block;max-width:100%;image-rendering:pixelated}"
    ".frames img{cursor:zoom-in}.frames img:focus{transform:scale(3);transform-origin:0 0;position:relative;z-index:2;cursor:zoom-out;"
    "outline:2px solid #444;max-width:none}";

static void settings(FILE *f, const vrg_cmp_result *r)
{
    fputs("<table class=\"settings\"><tbody><tr><th>reference</th><td>", f);
    esc(f, r->reference);
    if (r->reference_overrides[0]) {
        fputs(" with ", f);
        esc(f, r->reference_overrides);
    }
    fprintf(f, " (%u of %u frames from the cache)</td></tr><tr><th>camera</th><td>", r->reference_cached, r->frames);
    esc(f, r->camera ? r->camera : "the first graph's [camera], held still");
    fprintf(f, "</td></tr><tr><th>frames</th><td>%u at %ux%u from the path's frame %u; ", r->frames, r->width, r->height, r->start);
    if (r->warmup)
        fprintf(f, "frames 0 to %u are warm-up, left out of the summary</td></tr>", r->warmup - 1);
    else
        fputs("no warm-up</td></tr>", f);
    fputs("<tr><th>device</th><td>", f);
    esc(f, r->device);
    fputs("</td></tr></tbody></table>\n", f);
}

static void summary(FILE *f, const vrg_cmp_result *r)
{
    fputs("<table class=\"summary\"><thead><tr><th>candidate</th><th>graph</th>", f);
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        fprintf(f, "<th>%s %s</th>", vrg_cmp_metric_labels[m], vrg_cmp_metric_higher_better[m] ? "&#8593;" : "&#8595;");
    fputs("<th>GPU ms &#8595;</th><th>GPU ms p95</th></tr></thead><tbody>\n", f);
    int best[VRG_CMP_METRICS + 1];
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        best[m] = vrg_cmp_best(r, m);
    best[VRG_CMP_METRICS] = vrg_cmp_best(r, -1);
    static const char *fmt[VRG_CMP_METRICS] = {"%.2f", "%.4f", "%.4f", "%.5f"};
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        fprintf(f, "<tr data-candidate=\"");
        esc(f, c->name);
        fprintf(f, "\"><td><i style=\"display:inline-block;width:10px;height:10px;background:%s\"></i> ", cand_color(i));
        esc(f, c->name);
        fputs("</td><td>", f);
        esc(f, c->graph);
        if (c->base >= 0) {
            fputs(" (variant of ", f);
            esc(f, r->cand[c->base].name);
            fputs(")", f);
        }
        if (c->overrides[0]) {
            fputs(" with ", f);
            esc(f, c->overrides);
        }
        fputs("</td>", f);
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            fprintf(f, "<td class=\"num%s\" data-metric=\"%s\" data-value=\"%.9g\">", best[m] == i ? " best" : "", vrg_cmp_metric_names[m],
                    c->summary[m]);
            fprintf(f, fmt[m], c->summary[m]);
            fprintf(f, "%s</td>", best[m] == i ? " &#9733;" : "");
        }
        fprintf(f, "<td class=\"num%s\" data-metric=\"gpu_ms_mean\" data-value=\"%.9g\">%.2f%s</td>", best[VRG_CMP_METRICS] == i ? " best" : "",
                c->gpu_mean_ms, c->gpu_mean_ms, best[VRG_CMP_METRICS] == i ? " &#9733;" : "");
        fprintf(f, "<td class=\"num\" data-metric=\"gpu_ms_p95\" data-value=\"%.9g\">%.2f</td></tr>\n", c->gpu_p95_ms, c->gpu_p95_ms);
    }
    fprintf(f, "</tbody></table>\n<p>Means over frames %u to %u (temporal error from frame 1 on); &#9733; marks the best in each column. PSNR "
               "of identical images is reported as %g dB, the cap.</p>\n",
            r->warmup, r->frames - 1, VRG_PSNR_MAX_DB);
}

static int frames(FILE *f, const vrg_cmp_result *r)
{
    uint32_t w = r->width, h = r->height, side = w < h ? w / 4 : h / 4;
    side = side > 64 ? 64 : side < 8 ? (w < 8 || h < 8 ? (w < h ? w : h) : 8) : side;
    int scale = side ? (int)(192 / side) : 1;
    scale = scale < 1 ? 1 : scale > 8 ? 8 : scale;
    int fscale = w < 320 ? (int)(320 / w) : 1; /* small frames shown larger, pixels kept sharp */
    int rc = 0;
    for (int s = 0; s < r->shown_count && rc == 0; s++) {
        uint32_t x0, y0;
        worst_window(r, s, side, &x0, &y0);
        fprintf(f, "<h3>frame %d</h3>\n<div class=\"frames\">", r->shown[s]);
        fputs("<figure>", f);
        rc |= image(f, r->reference_shown[s], w, h, fscale, "reference");
        fputs("<figcaption>reference</figcaption></figure>", f);
        for (int i = 0; i < r->count && rc == 0; i++) {
            fputs("<figure>", f);
            rc |= image(f, r->cand[i].shown[s], w, h, fscale, r->cand[i].name);
            fputs("<figcaption>", f);
            esc(f, r->cand[i].name);
            fprintf(f, ": PSNR %.2f dB, FLIP %.4f</figcaption></figure>", r->cand[i].per_frame[VRG_CMP_PSNR][r->shown[s]],
                    r->cand[i].per_frame[VRG_CMP_FLIP][r->shown[s]]);
        }
        fputs("</div>\n<div class=\"frames\">", f);
        /* the colour bar under the reference's column, the maps under the candidates' */
        double range = map_range(r, s, 0), srange = map_range(r, s, 1);
        uint8_t ramp[256 * 12 * 3];
        for (int x = 0; x < 256; x++)
            for (int y = 0; y < 12; y++)
                vrg_error_color(x / 255.0f, ramp + 3 * (y * 256 + x));
        fputs("<figure>", f);
        rc |= image(f, ramp, 256, 12, 1, "FLIP colour bar");
        fprintf(f, "<figcaption>FLIP error: 0 (left) to %g and above (right); the 99th percentile of the maps</figcaption></figure>", range);
        for (int i = 0; i < r->count && rc == 0; i++)
            rc |= figure(f, heat_map(r->cand[i].flip_map[s], (size_t)w * h, range), w, h, fscale, "FLIP map", "FLIP map: ", r->cand[i].name);
        fputs("</div>\n<div class=\"frames\">", f);
        for (int x = 0; x < 256; x++)
            for (int y = 0; y < 12; y++)
                signed_color((x - 127.5) / 127.5 * srange, srange, ramp + 3 * (y * 256 + x));
        fputs("<figure>", f);
        rc |= image(f, ramp, 256, 12, 1, "signed difference colour bar");
        fprintf(f, "<figcaption>candidate &#8722; reference, luma: &#8722;%g (blue) to +%g (red)</figcaption></figure>", srange, srange);
        for (int i = 0; i < r->count && rc == 0; i++)
            rc |= figure(f, signed_map(r->cand[i].shown[s], r->reference_shown[s], (size_t)w * h, srange), w, h, fscale, "signed difference",
                         "difference: ", r->cand[i].name);
        fprintf(f, "</div>\n<p>Zoomed: the %ux%u window at (%u, %u) with the largest FLIP error summed over the candidates; click any image to zoom it 3x, click elsewhere to zoom out.</p>\n"
                   "<div class=\"frames crop\">",
                side, side, x0, y0);
        for (int i = -1; i < r->count && rc == 0; i++)
            rc |= figure(f, crop(i < 0 ? r->reference_shown[s] : r->cand[i].shown[s], w, x0, y0, side, side), side, side, scale,
                         i < 0 ? "reference, zoomed" : r->cand[i].name, "", i < 0 ? "reference" : r->cand[i].name);
        fputs("</div>\n", f);
    }
    return rc;
}

int vrg_cmp_report_case(FILE *f, const vrg_cmp_result *r)
{
    if (r->case_name[0]) {
        fputs("<h2 class=\"case\" id=\"case-", f);
        esc(f, r->case_name);
        fputs("\">case ", f);
        esc(f, r->case_name);
        if (r->scene[0]) {
            fputs(" <small>(", f);
            esc(f, r->scene);
            fputs(")</small>", f);
        }
        fputs("</h2>\n", f);
    }
    settings(f, r);
    fputs("<h2>Summary</h2>\n", f);
    summary(f, r);
    fputs("<h2>Per frame</h2>\n<p class=\"legend\">", f);
    for (int i = 0; i < r->count; i++) {
        fprintf(f, "<span><i style=\"background:%s\"></i>", cand_color(i));
        esc(f, r->cand[i].name);
        fputs("</span> ", f);
    }
    fputs("(grey: warm-up)</p>\n<div class=\"plots\">\n", f);
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        plot(f, r, m);
    fputs("</div>\n<h2>GPU time per frame</h2>\n<p>Mean per-pass GPU ms from warm-up on, stacked (hover for each pass's mean and p95).</p>\n", f);
    bars(f, r);
    fputs("<h2>Frames</h2>\n", f);
    int rc = frames(f, r);
    if (rc != 0)
        fprintf(stderr, "error: the report of case '%s': a frame could not be encoded\n", r->case_name);
    return rc;
}

/* a cell's background: green where better than the baseline, red where
 * worse, the stronger the larger the difference against the largest in
 * the table */
static void cell_color(FILE *f, double gain, double largest)
{
    if (isnan(gain) || gain == 0 || largest <= 0) {
        fputs("#fff", f);
        return;
    }
    double t = fabs(gain) / largest;
    int fade = (int)(255 - 120 * (t > 1 ? 1 : t));
    fprintf(f, gain > 0 ? "rgb(%d,255,%d)" : "rgb(255,%d,%d)", fade, fade);
}

/* metric m over the cases (rows) and candidates (columns), each cell its
 * summary and its difference to the baseline's; then the verdict's rows */
static void matrix(FILE *f, const vrg_cmp_run *run, int m)
{
    static const char *fmt[VRG_CMP_METRICS] = {"%.2f", "%.4f", "%.4f", "%.5f"}, *dfmt[VRG_CMP_METRICS] = {"%+.2f", "%+.4f", "%+.4f", "%+.5f"};
    const vrg_cmp_result *r0 = &run->cases[0];
    double largest = 0;
    for (int c = 0; c < run->case_count; c++)
        for (int i = 0; i < r0->count; i++) {
            double d = fabs(run->cases[c].cand[i].summary[m] - run->cases[c].cand[run->baseline].summary[m]);
            largest = d > largest ? d : largest;
        }
    fprintf(f, "<h3>%s %s</h3>\n<table class=\"matrix\"><thead><tr><th>case</th>", vrg_cmp_metric_labels[m],
            vrg_cmp_metric_higher_better[m] ? "&#8593;" : "&#8595;");
    for (int i = 0; i < r0->count; i++) {
        fputs("<th>", f);
        esc(f, r0->cand[i].name);
        fputs(i == run->baseline ? " (baseline)</th>" : "</th>", f);
    }
    fputs("</tr></thead><tbody>\n", f);
    for (int c = 0; c < run->case_count; c++) {
        const vrg_cmp_result *r = &run->cases[c];
        fputs("<tr><td>", f);
        esc(f, r->case_name[0] ? r->case_name : "the run");
        fputs("</td>", f);
        for (int i = 0; i < r->count; i++) {
            double v = r->cand[i].summary[m], d = v - r->cand[run->baseline].summary[m];
            fprintf(f, "<td class=\"num\" data-cell=\"%s\" data-case=\"", vrg_cmp_metric_names[m]);
            esc(f, r->case_name);
            fputs("\" data-candidate-name=\"", f);
            esc(f, r->cand[i].name);
            fprintf(f, "\" data-value=\"%.9g\" data-difference=\"%.9g\" style=\"background:", v, d);
            cell_color(f, vrg_cmp_metric_higher_better[m] ? d : -d, largest);
            fputs("\">", f);
            fprintf(f, fmt[m], v);
            if (i != run->baseline) {
                fputs(" <small>(", f);
                fprintf(f, dfmt[m], d);
                fputs(")</small>", f);
            }
            fputs("</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("<tr><th>mean difference</th>", f);
    for (int i = 0; i < r0->count; i++) {
        fputs("<td class=\"num\">", f);
        fprintf(f, dfmt[m], run->verdict[i].mean_diff[m]);
        fputs("</td>", f);
    }
    fputs("</tr>\n<tr><th>better / worse / equal</th>", f);
    for (int i = 0; i < r0->count; i++)
        fprintf(f, "<td class=\"num\">%d / %d / %d</td>", run->verdict[i].wins[m], run->verdict[i].losses[m], run->verdict[i].ties[m]);
    fputs("</tr>\n<tr><th>worst case</th>", f);
    for (int i = 0; i < r0->count; i++) {
        const vrg_cmp_verdict *v = &run->verdict[i];
        fputs("<td class=\"num\">", f);
        if (i != run->baseline && v->worst[m] >= 0) {
            esc(f, run->cases[v->worst[m]].case_name[0] ? run->cases[v->worst[m]].case_name : "the run");
            fputc(' ', f);
            fprintf(f, dfmt[m], v->worst_diff[m]);
        }
        fputs("</td>", f);
    }
    fputs("</tr>\n</tbody></table>\n", f);
}

static void verdict(FILE *f, const vrg_cmp_run *run)
{
    fputs("<h2>Verdict</h2>\n<ul class=\"verdict\">", f);
    for (int i = 0; i < run->cases[0].count; i++) {
        fputs("<li>", f);
        esc(f, run->verdict[i].sentence);
        fputs("</li>", f);
    }
    fputs("</ul>\n<p>Each cell: the candidate's summary on the case and, in brackets, its difference to the baseline's; green where "
          "better, red where worse.</p>\n",
          f);
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        if (m != VRG_CMP_SSIM)
            matrix(f, run, m);
}

int vrg_cmp_write_report(const char *path, const vrg_cmp_run *run, FILE *sections)
{
    vrg_output *out = vrg_output_open(path);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    const vrg_cmp_result *r0 = &run->cases[0];
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>voxrg compare: ");
    for (int i = 0; i < r0->count; i++) {
        fputs(i ? ", " : "", f);
        esc(f, r0->cand[i].name);
    }
    fprintf(f, "</title>\n<style>%s</style>\n</head>\n<body>\n<h1>voxrg compare</h1>\n", style);
    if (run->cases_file) {
        fputs("<p>Cases from ", f);
        esc(f, run->cases_file);
        fprintf(f, ": %d.</p>\n", run->case_count);
    }
    verdict(f, run);
    char buf[65536];
    size_t n;
    int rc = fflush(sections) != 0 || fseek(sections, 0, SEEK_SET) != 0;
    while (!rc && (n = fread(buf, 1, sizeof buf, sections)) > 0)
        rc = fwrite(buf, 1, n, f) != n;
    rc |= ferror(sections);
    fputs("</body>\n</html>\n", f);
    if (rc != 0) {
        fprintf(stderr, "error: cannot write %s: the cases' part could not be read back\n", path);
        vrg_output_abort(out);
        return -1;
    }
    return vrg_output_commit(out);
}
