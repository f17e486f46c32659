#version 450
// The device scorer's second stage, down columns: FLIP's vertical filters,
// the filtered colours in Hunt-adjusted Lab, their HyAB distance and the
// feature difference give FLIP's error per pixel (its map); SSIM's
// vertical moments give the SSIM of the window whose corner is the pixel
// (where one fits). Each invocation adds its strip's FLIP and SSIM values
// in row order: the same sums on every run. The horizontal stage's planes
// are stored by column (filter_x.comp), so that a column's values are
// consecutive. An invocation walks down STRIP rows of one column, STEP rows
// a step, with a window of each plane in registers: a step shifts the
// windows once and reads STEP values of each plane, and the loop's body
// stays small (docs/benchmarks.md).
#extension GL_EXT_control_flow_attributes : require
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 1) in;
#define WIN (2 * CSF_R + 1)
#define STEP 4
#define WK (WIN + STEP - 1)
#define SK (SSIM_W + STEP - 1)
#define COLUMN_PLANES 14 // T_CSF and T_FEAT of both images

// the CPU's convolution at the window's centre, sum over i of
// k[i + r] · src[y - i], the kernel being symmetric (anti: antisymmetric),
// so that the taps at ±i share a weight
float conv(float v[WK], int c, int k, int r, bool anti)
{
    float a = kern[k + r] * v[c], b = 0.0;
    [[unroll]] for (int i = 1; i <= r; i++) {
        float p = (anti ? v[c - i] - v[c + i] : v[c - i] + v[c + i]) * kern[k + r + i];
        if ((i & 1) == 1)
            b += p;
        else
            a += p;
    }
    return a + b;
}

float lab_f(float t)
{
    const float d = 6.0 / 29.0;
    return t > d * d * d ? pow(t, 1.0 / 3.0) : t / (3.0 * d * d) + 4.0 / 29.0;
}

vec3 hunt_lab(vec3 lin)
{
    vec3 wp = white();
    vec3 v = rgb_to_xyz(lin) / wp;
    vec3 f = vec3(lab_f(v.x), lab_f(v.y), lab_f(v.z));
    float l = 116.0 * f.y - 16.0;
    return vec3(l, 0.01 * l * 500.0 * (f.x - f.y), 0.01 * l * 200.0 * (f.y - f.z));
}

vec3 ycxcz_to_hunt_lab(vec3 c)
{
    vec3 wp = white();
    float y = (c.x + 16.0) / 116.0;
    vec3 xyz = vec3((y + c.y / 500.0) * wp.x, y * wp.y, (y - c.z / 200.0) * wp.z);
    return hunt_lab(clamp(xyz_to_rgb(xyz), 0.0, 1.0));
}

float hyab(vec3 a, vec3 b) { return abs(a.x - b.x) + length(a.yz - b.yz); }

float flip_error(vec3 ref, vec3 test, vec2 ref_features, vec2 test_features)
{
    const float qc = 0.7, pc_ = 0.4, pt = 0.95, qf = 0.5;
    float cmax = pow(hyab(hunt_lab(vec3(0.0, 1.0, 0.0)), hunt_lab(vec3(0.0, 0.0, 1.0))), qc);
    float e = pow(hyab(ycxcz_to_hunt_lab(ref), ycxcz_to_hunt_lab(test)), qc);
    float color = e < pc_ * cmax ? e * pt / (pc_ * cmax) : pt + (e - pc_ * cmax) / (cmax - pc_ * cmax) * (1.0 - pt);
    float f = max(abs(ref_features.x - test_features.x), abs(ref_features.y - test_features.y));
    f = pow(f / sqrt(2.0), qf);
    return pow(color, 1.0 - f);
}

// SSIM of the window whose corner is the pixel, from its column of
// horizontal moments
float ssim(float m[5])
{
    const float c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    float va = m[2] - m[0] * m[0], vb = m[3] - m[1] * m[1], cov = m[4] - m[0] * m[1];
    float ma = m[0] + SSIM_SHIFT, mb = m[1] + SSIM_SHIFT;
    return ((2.0 * ma * mb + c1) * (2.0 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
}

void main()
{
    uint x = gl_GlobalInvocationID.x, strip = gl_WorkGroupID.y;
    int y0 = int(strip) * STRIP, y1 = min(y0 + STRIP, int(pc.height));
    if (x >= pc.width)
        return;
    uint col = x * pc.height;
    bool fits = x + uint(SSIM_W) <= pc.width;
    // w: rows y - CSF_R .. y + STEP - 1 + CSF_R of each plane; s: rows
    // y .. y + STEP - 1 + SSIM_W - 1 of SSIM's moments
    float w[COLUMN_PLANES][WK], s[5][SK];
    float flip_sum = 0.0, ssim_sum = 0.0;
    // the steps before y0 only fill the windows
    for (int y = y0 - STEP * ((2 * CSF_R + STEP - 1) / STEP); y < y1; y += STEP) {
        [[unroll]] for (int p = 0; p < COLUMN_PLANES; p++) {
            [[unroll]] for (int t = 0; t < WK - STEP; t++)
                w[p][t] = w[p][t + STEP];
            [[unroll]] for (int j = 0; j < STEP; j++)
                w[p][WK - STEP + j] = pc.tmp.f[plane(uint(p), col + uint(clamp_y(y + CSF_R + j)))];
        }
        [[unroll]] for (int c = 0; c < 5; c++) {
            [[unroll]] for (int t = 0; t < SK - STEP; t++)
                s[c][t] = s[c][t + STEP];
            [[unroll]] for (int j = 0; j < STEP; j++)
                s[c][SK - STEP + j] = pc.tmp.f[plane(T_SSIM + uint(c), col + uint(clamp_y(y + SSIM_W - 1 + j)))];
        }
        if (y < y0)
            continue;
        [[unroll]] for (int j = 0; j < STEP; j++) {
            int yj = y + j, c = CSF_R + j;
            if (yj >= y1)
                break;
            vec3 colour[2];
            vec2 features[2];
            const int d = K_FEAT, d2 = K_FEAT + FEAT_TAPS, gk = K_FEAT + 2 * FEAT_TAPS;
            [[unroll]] for (int im = 0; im < 2; im++) {
                int t = int(T_CSF) + 4 * im, f = int(T_FEAT) + 3 * im;
                colour[im].x = kern[K_SHARE + 0] * conv(w[t], c, K_CSF, CSF_R, false);
                colour[im].y = kern[K_SHARE + 1] * conv(w[t + 1], c, K_CSF + CSF_TAPS, CSF_R, false);
                colour[im].z = kern[K_SHARE + 2] * conv(w[t + 2], c, K_CSF + 2 * CSF_TAPS, CSF_R, false);
                colour[im].z += kern[K_SHARE + 3] * conv(w[t + 3], c, K_CSF + 3 * CSF_TAPS, CSF_R, false);
                // edges: d along x then g along y, and g along x then d along y;
                // points alike with the second derivative
                float ex = conv(w[f], c, gk, FEAT_R, false), px = conv(w[f + 1], c, gk, FEAT_R, false);
                float ey = conv(w[f + 2], c, d, FEAT_R, true), py = conv(w[f + 2], c, d2, FEAT_R, false);
                features[im] = vec2(sqrt(ex * ex + ey * ey), sqrt(px * px + py * py));
            }
            float e = flip_error(colour[0], colour[1], features[0], features[1]);
            if (pc.want_map != 0u)
                pc.flip_map.f[uint(yj) * pc.width + x] = e;
            flip_sum += e;
            float m[5];
            [[unroll]] for (int q = 0; q < 5; q++) {
                m[q] = 0.0;
                [[unroll]] for (int k = 0; k < SSIM_W; k++)
                    m[q] += kern[K_SSIM + k] * s[q][j + k];
            }
            if (fits && yj + SSIM_W <= int(pc.height))
                ssim_sum += ssim(m);
        }
    }
    uint p = P_COLUMNS + 2u * (strip * pc.width + x);
    pc.partials.u[p] = floatBitsToUint(flip_sum);
    pc.partials.u[p + 1u] = floatBitsToUint(ssim_sum);
}
