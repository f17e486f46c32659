/* Image metrics (voxrg/metrics.h): PSNR, SSIM, LDR-FLIP, temporal error.
 * Written from the papers: Wang, Bovik, Sheikh, Simoncelli, "Image Quality
 * Assessment: From Error Visibility to Structural Similarity" (2004), and
 * Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild, "FLIP: A
 * Difference Evaluator for Alternating Images" (HPG 2020). Filters are
 * separable (the FLIP paper's 2D kernels are products or sums of products);
 * FLIP's filters repeat the edge pixel beyond the borders (clamp to edge), as
 * the official implementation (NVlabs FLIP) pads, so scores compare with it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/metrics.h"
#include "metrics_kernels.h"

#define PI 3.14159265358979323846

double vrg_metric_psnr(const float *test, const float *ref, uint32_t w, uint32_t h)
{
    size_t n = (size_t)w * h * 3;
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)test[i] - ref[i];
        sum += d * d;
    }
    double mse = n ? sum / (double)n : 0;
    double db = mse > 0 ? 10.0 * log10(1.0 / mse) : VRG_PSNR_MAX_DB;
    return db < VRG_PSNR_MAX_DB ? db : VRG_PSNR_MAX_DB;
}

double vrg_metric_temporal(const float *test, const float *test_prev, const float *ref, const float *ref_prev, uint32_t w, uint32_t h)
{
    size_t n = (size_t)w * h * 3;
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += fabs(((double)test[i] - test_prev[i]) - ((double)ref[i] - ref_prev[i]));
    return n ? sum / (double)n : 0;
}

/* ---- SSIM ---- */

enum { SSIM_WINDOW = VRG_SSIM_WINDOW };

/* Valid-mode separable filtering of `src` (w x h) with the 11-tap kernel:
 * out is (w-10) x (h-10). `tmp` holds (w-10) x h. */
static void filter_valid(const double *src, uint32_t w, uint32_t h, const double *k, double *tmp, double *out)
{
    uint32_t ow = w - (SSIM_WINDOW - 1), oh = h - (SSIM_WINDOW - 1);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < SSIM_WINDOW; i++)
                s += k[i] * src[(size_t)y * w + x + i];
            tmp[(size_t)y * ow + x] = s;
        }
    for (uint32_t y = 0; y < oh; y++)
        for (uint32_t x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < SSIM_WINDOW; i++)
                s += k[i] * tmp[(size_t)(y + i) * ow + x];
            out[(size_t)y * ow + x] = s;
        }
}

void _vrg_ssim_kernel(double k[VRG_SSIM_WINDOW])
{
    double ksum = 0;
    for (int i = 0; i < SSIM_WINDOW; i++) {
        double x = i - SSIM_WINDOW / 2;
        k[i] = exp(-x * x / (2 * 1.5 * 1.5));
        ksum += k[i];
    }
    for (int i = 0; i < SSIM_WINDOW; i++)
        k[i] /= ksum;
}

double vrg_metric_ssim(const float *test, const float *ref, uint32_t w, uint32_t h)
{
    if (w < SSIM_WINDOW || h < SSIM_WINDOW)
        return -1;
    double k[SSIM_WINDOW];
    _vrg_ssim_kernel(k);
    size_t n = (size_t)w * h, on = (size_t)(w - SSIM_WINDOW + 1) * (h - SSIM_WINDOW + 1);
    /* a, b, a², b², ab, then the five filtered, then scratch */
    double *buf = malloc(sizeof(double) * (5 * n + 5 * on + (size_t)(w - SSIM_WINDOW + 1) * h));
    if (!buf)
        return -1;
    double *in[5] = {buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n};
    double *mean[5], *tmp = buf + 5 * n + 5 * on;
    for (int c = 0; c < 5; c++)
        mean[c] = buf + 5 * n + (size_t)c * on;
    for (size_t i = 0; i < n; i++) {
        double a = 0.2989 * test[3 * i] + 0.5870 * test[3 * i + 1] + 0.1140 * test[3 * i + 2];
        double b = 0.2989 * ref[3 * i] + 0.5870 * ref[3 * i + 1] + 0.1140 * ref[3 * i + 2];
        in[0][i] = a, in[1][i] = b, in[2][i] = a * a, in[3][i] = b * b, in[4][i] = a * b;
    }
    for (int c = 0; c < 5; c++)
        filter_valid(in[c], w, h, k, tmp, mean[c]);
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double sum = 0;
    for (size_t i = 0; i < on; i++) {
        double ma = mean[0][i], mb = mean[1][i];
        double va = mean[2][i] - ma * ma, vb = mean[3][i] - mb * mb, cov = mean[4][i] - ma * mb;
        sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
    }
    free(buf);
    return sum / (double)on;
}

/* ---- FLIP ---- */

/* The paper's viewing conditions: 0.7 m from a 0.7 m wide 3840-pixel display. */
double vrg_flip_pixels_per_degree(void) { return 0.7 * (3840.0 / 0.7) * (PI / 180.0); }

/* linear sRGB (D65) <-> CIE XYZ */
static const double rgb_to_xyz[3][3] = {
    {0.4124564, 0.3575761, 0.1804375},
    {0.2126729, 0.7151522, 0.0721750},
    {0.0193339, 0.1191920, 0.9503041},
};
static const double xyz_to_rgb[3][3] = {
    {3.2404542, -1.5371385, -0.4985314},
    {-0.9692660, 1.8760108, 0.0415560},
    {0.0556434, -0.2040259, 1.0572252},
};

static void mul3(const double m[3][3], const double v[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
}

/* the white point: XYZ of linear RGB (1, 1, 1) */
static void white(double wp[3])
{
    const double one[3] = {1, 1, 1};
    mul3(rgb_to_xyz, one, wp);
}

static double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

/* display sRGB -> YCxCz (the opponent space FLIP filters in) */
static void srgb_to_ycxcz(const float *rgb, double out[3])
{
    double lin[3] = {srgb_decode(rgb[0]), srgb_decode(rgb[1]), srgb_decode(rgb[2])}, xyz[3], wp[3];
    mul3(rgb_to_xyz, lin, xyz);
    white(wp);
    double x = xyz[0] / wp[0], y = xyz[1] / wp[1], z = xyz[2] / wp[2];
    out[0] = 116 * y - 16;
    out[1] = 500 * (x - y);
    out[2] = 200 * (y - z);
}

/* YCxCz -> linear RGB clamped to [0, 1] -> CIELAB with Hunt's adjustment
 * (a and b scaled by 0.01 L) */
static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

static void linear_to_hunt_lab(const double lin[3], double out[3])
{
    double xyz[3], wp[3];
    mul3(rgb_to_xyz, lin, xyz);
    white(wp);
    double fx = lab_f(xyz[0] / wp[0]), fy = lab_f(xyz[1] / wp[1]), fz = lab_f(xyz[2] / wp[2]);
    double l = 116 * fy - 16;
    out[0] = l;
    out[1] = 0.01 * l * 500 * (fx - fy);
    out[2] = 0.01 * l * 200 * (fy - fz);
}

static void ycxcz_to_hunt_lab(const double c[3], double out[3])
{
    double wp[3], xyz[3], lin[3];
    white(wp);
    double y = (c[0] + 16) / 116;
    xyz[0] = (y + c[1] / 500) * wp[0];
    xyz[1] = y * wp[1];
    xyz[2] = (y - c[2] / 200) * wp[2];
    mul3(xyz_to_rgb, xyz, lin);
    for (int i = 0; i < 3; i++)
        lin[i] = lin[i] < 0 ? 0 : lin[i] > 1 ? 1 : lin[i];
    linear_to_hunt_lab(lin, out);
}

static double hyab(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + sqrt((a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static int clamp_to_edge(int i, int n) { return i < 0 ? 0 : i >= n ? n - 1 : i; }

/* out = src convolved with kx along x then ky along y (radius r); beyond the
 * borders the edge pixel repeats */
static void convolve_sep(const double *src, int w, int h, const double *kx, const double *ky, int r, double *tmp, double *out)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -r; i <= r; i++)
                s += kx[i + r] * src[(size_t)y * w + clamp_to_edge(x - i, w)];
            tmp[(size_t)y * w + x] = s;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -r; i <= r; i++)
                s += ky[i + r] * tmp[(size_t)clamp_to_edge(y - i, h) * w + x];
            out[(size_t)y * w + x] = s;
        }
}

/* The contrast sensitivity filters of the achromatic, red-green and
 * blue-yellow channels: a1 sqrt(pi/b1) exp(-pi² d²/b1) + a2 sqrt(pi/b2)
 * exp(-pi² d²/b2), d in degrees, normalised to sum 1 over the square of
 * radius r = ceil(3 sqrt(max b / (2 pi²)) ppd). */
static const double csf[3][4] = {
    {1.0, 0.0047, 0.0, 1e-5},   /* A */
    {1.0, 0.0053, 0.0, 1e-5},   /* RG */
    {34.1, 0.04, 13.5, 0.025},  /* BY */
};

int _vrg_flip_csf_radius(double ppd)
{
    double bmax = 0;
    for (int c = 0; c < 3; c++)
        bmax = fmax(bmax, fmax(csf[c][1], csf[c][3]));
    return (int)ceil(3 * sqrt(bmax / (2 * PI * PI)) * ppd);
}

double _vrg_flip_csf_kernel(int channel, int term, double ppd, int r, double *k)
{
    double weight = 0, total = 0;
    for (int t = 0; t < 2; t++) { /* the 2D term is a·sqrt(pi/b)·k(x)·k(y), k(x) = exp(-pi² (x/ppd)² / b) */
        double a = csf[channel][2 * t], b = csf[channel][2 * t + 1], s = 0;
        for (int i = -r; i <= r; i++)
            s += exp(-PI * PI * (i / ppd) * (i / ppd) / b);
        total += a * sqrt(PI / b) * s * s;
        if (t == term)
            weight = a * sqrt(PI / b) * s * s;
    }
    if (weight == 0)
        return 0;
    double b = csf[channel][2 * term + 1], s = 0;
    for (int i = -r; i <= r; i++)
        s += k[i + r] = exp(-PI * PI * (i / ppd) * (i / ppd) / b);
    for (int i = 0; i <= 2 * r; i++)
        k[i] /= s;
    return weight / total;
}

static void csf_filter(const double *src, int w, int h, int channel, double ppd, double *tmp, double *acc, double *out)
{
    int r = _vrg_flip_csf_radius(ppd);
    double *k = malloc(sizeof(double) * (size_t)(2 * r + 1));
    memset(out, 0, sizeof(double) * (size_t)w * h);
    for (int t = 0; t < 2; t++) {
        double share = _vrg_flip_csf_kernel(channel, t, ppd, r, k);
        if (share == 0)
            continue;
        convolve_sep(src, w, h, k, k, r, tmp, acc);
        for (size_t i = 0; i < (size_t)w * h; i++)
            out[i] += share * acc[i];
    }
    free(k);
}

/* Edge (first derivative) or point (second derivative) detection on the
 * normalised achromatic channel: Gaussian derivative kernels with
 * sigma = 0.5 · 0.082° · ppd, their positive and negative weights each
 * normalised to sum ±1. Writes the magnitude of the (x, y) responses. */
int _vrg_flip_feature_radius(double ppd)
{
    double sd = 0.5 * 0.082 * ppd;
    return (int)ceil(3 * sd);
}

void _vrg_flip_feature_kernels(double ppd, int second, int r, double *d, double *g)
{
    double sd = 0.5 * 0.082 * ppd;
    double pos = 0, neg = 0, gsum = 0;
    for (int i = -r; i <= r; i++) {
        double e = exp(-(double)i * i / (2 * sd * sd));
        d[i + r] = second ? ((double)i * i / (sd * sd) - 1) * e : -i * e;
        g[i + r] = e;
        gsum += e;
        if (d[i + r] > 0)
            pos += d[i + r];
        else
            neg -= d[i + r];
    }
    /* the 2D kernel d(x) g(y): its positive part sums to pos·gsum */
    for (int i = 0; i <= 2 * r; i++) {
        d[i] /= d[i] > 0 ? pos : neg;
        g[i] /= gsum;
    }
}

static void features(const double *src, int w, int h, int second, double ppd, double *tmp, double *gx, double *gy, double *mag)
{
    int r = _vrg_flip_feature_radius(ppd);
    double *d = malloc(sizeof(double) * (size_t)(2 * r + 1) * 2), *g = d + 2 * r + 1;
    _vrg_flip_feature_kernels(ppd, second, r, d, g);
    convolve_sep(src, w, h, d, g, r, tmp, gx);
    convolve_sep(src, w, h, g, d, r, tmp, gy);
    for (size_t i = 0; i < (size_t)w * h; i++)
        mag[i] = sqrt(gx[i] * gx[i] + gy[i] * gy[i]);
    free(d);
}

double vrg_metric_flip(const float *test, const float *ref, uint32_t width, uint32_t height, float *map)
{
    int w = (int)width, h = (int)height;
    size_t n = (size_t)w * h;
    if (!n)
        return 0;
    double ppd = vrg_flip_pixels_per_degree();
    /* per image: 3 opponent planes, 3 filtered planes; scratch: 4 planes */
    double *buf = malloc(sizeof(double) * n * 16);
    if (!buf)
        return -1;
    double *opp[2][3], *filt[2][3], *tmp = buf + 12 * n, *acc = tmp + n, *gx = acc + n, *gy = gx + n;
    for (int im = 0; im < 2; im++)
        for (int c = 0; c < 3; c++) {
            opp[im][c] = buf + (size_t)(im * 6 + c) * n;
            filt[im][c] = buf + (size_t)(im * 6 + 3 + c) * n;
        }
    for (int im = 0; im < 2; im++) {
        const float *src = im ? test : ref;
        for (size_t i = 0; i < n; i++) {
            double o[3];
            srgb_to_ycxcz(src + 3 * i, o);
            for (int c = 0; c < 3; c++)
                opp[im][c][i] = o[c];
        }
        for (int c = 0; c < 3; c++)
            csf_filter(opp[im][c], w, h, c, ppd, tmp, acc, filt[im][c]);
    }
    /* colour: HyAB distance of the filtered images in Hunt-adjusted Lab,
     * raised to qc = 0.7, redistributed against the green-blue distance */
    const double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;
    double green[3], blue[3];
    linear_to_hunt_lab((const double[3]){0, 1, 0}, green);
    linear_to_hunt_lab((const double[3]){0, 0, 1}, blue);
    double cmax = pow(hyab(green, blue), qc);
    double *color = filt[0][0]; /* reuse: the filtered planes are read before written */
    for (size_t i = 0; i < n; i++) {
        double a[3] = {filt[0][0][i], filt[0][1][i], filt[0][2][i]}, b[3] = {filt[1][0][i], filt[1][1][i], filt[1][2][i]}, la[3], lb[3];
        ycxcz_to_hunt_lab(a, la);
        ycxcz_to_hunt_lab(b, lb);
        double e = pow(hyab(la, lb), qc);
        color[i] = e < pc * cmax ? e * pt / (pc * cmax) : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
    }
    /* features: edges and points of the achromatic channel, (Y + 16) / 116 */
    double *y[2] = {filt[0][1], filt[0][2]}, *edge[2] = {filt[1][0], filt[1][1]}, *point[2] = {filt[1][2], opp[1][1]};
    for (int im = 0; im < 2; im++) {
        for (size_t i = 0; i < n; i++)
            y[im][i] = (opp[im][0][i] + 16) / 116;
        features(y[im], w, h, 0, ppd, tmp, gx, gy, edge[im]);
        features(y[im], w, h, 1, ppd, tmp, gx, gy, point[im]);
    }
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        double f = fmax(fabs(edge[0][i] - edge[1][i]), fabs(point[0][i] - point[1][i]));
        f = pow(f / sqrt(2.0), qf);
        double e = pow(color[i], 1 - f);
        sum += e;
        if (map)
            map[i] = (float)e;
    }
    free(buf);
    return sum / (double)n;
}

/* ---- error colours ---- */

void vrg_error_color(float e, uint8_t rgb[3])
{
    /* control points of a magma-like ramp: black, purple, red, orange, pale yellow */
    static const float stops[5][3] = {{0, 0, 4}, {81, 18, 124}, {183, 55, 121}, {252, 137, 97}, {252, 253, 191}};
    e = e < 0 ? 0 : e > 1 ? 1 : e;
    float t = e * 4;
    int i = t >= 4 ? 3 : (int)t;
    float f = t - (float)i;
    for (int c = 0; c < 3; c++)
        rgb[c] = (uint8_t)lrintf(stops[i][c] + (stops[i + 1][c] - stops[i][c]) * f);
}
