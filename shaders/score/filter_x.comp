#version 450
// The device scorer's first stage, along rows: from the 8-bit pixels,
// FLIP's opponent (YCxCz) channels and SSIM's luma of both images; their
// horizontal filters, FLIP's contrast sensitivity terms and feature
// responses (edge pixels repeat beyond the borders) and SSIM's five moments
// over the 11 pixels from x on (valid mode), stored by column for
// filter_y.comp (a column's values consecutive); and the exact integer
// sums of the squared and temporal errors of the 8-bit values.
// An invocation walks along STRIP pixels of one row, STEP pixels a step,
// with a window of each channel in registers: a step shifts the windows
// once and reads STEP pixels of each image, and the loop's body stays
// small. On a CPU device (lavapipe) the reads, the writes and the windows'
// shifts (spilled registers) are most of the work, not the sums
// (docs/benchmarks.md).
#extension GL_EXT_control_flow_attributes : require
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 1) in;
#define WIN (2 * CSF_R + 1)
#define STEP 4
#define WK (WIN + STEP - 1)
// SSIM's window (x .. x + 10) is the right half of the filters' window
#if CSF_R < SSIM_W - 1
#error "FLIP's filter radius is shorter than SSIM's window"
#endif

vec3 unit(uvec3 b) { return vec3(b) / 255.0; }

float srgb_decode(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

vec3 ycxcz(vec3 rgb)
{
    vec3 lin = vec3(srgb_decode(rgb.r), srgb_decode(rgb.g), srgb_decode(rgb.b));
    vec3 wp = white();
    vec3 v = rgb_to_xyz(lin) / wp;
    return vec3(116.0 * v.y - 16.0, 500.0 * (v.x - v.y), 200.0 * (v.y - v.z));
}

float luma(vec3 c) { return 0.2989 * c.r + 0.5870 * c.g + 0.1140 * c.b; }

// the CPU's convolution at the window's centre, sum over i of
// k[i + r] · src[x - i], the kernel being symmetric (anti: antisymmetric),
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

void main()
{
    uint y = gl_GlobalInvocationID.x, strip = gl_WorkGroupID.y;
    int x0 = int(strip) * STRIP, x1 = min(x0 + STRIP, int(pc.width));
    if (y >= pc.height)
        return;
    uint row = y * pc.width;
    // w: pixels x - CSF_R .. x + STEP - 1 + CSF_R of the opponent channels
    // of the candidate (0) and the reference (1), and of the achromatic one
    // as FLIP's features see it, (Y + 16) / 116; l: SSIM's lumas
    float w[2][4][WK], l[2][WK];
    uint sq = 0u, temporal = 0u;
    // a step reads pixels x + CSF_R .. x + CSF_R + STEP - 1; the steps
    // before x0 only fill the windows
    for (int x = x0 - STEP * ((2 * CSF_R + STEP - 1) / STEP); x < x1; x += STEP) {
        [[unroll]] for (int t = 0; t < WK - STEP; t++)
            [[unroll]] for (int im = 0; im < 2; im++) {
                [[unroll]] for (int c = 0; c < 4; c++)
                    w[im][c][t] = w[im][c][t + STEP];
                l[im][t] = l[im][t + STEP];
            }
        [[unroll]] for (int j = 0; j < STEP; j++) {
            int e = x + CSF_R + j;
            uint i = row + uint(clamp_x(e));
            uvec3 px[2] = uvec3[2](bytes(pc.cand.u[i]), bytes(pc.ref_px.u[i]));
            [[unroll]] for (int im = 0; im < 2; im++) {
                vec3 rgb = unit(px[im]), o = ycxcz(rgb);
                w[im][0][WK - STEP + j] = o.x;
                w[im][1][WK - STEP + j] = o.y;
                w[im][2][WK - STEP + j] = o.z;
                w[im][3][WK - STEP + j] = (o.x + 16.0) / 116.0;
                l[im][WK - STEP + j] = luma(rgb) - SSIM_SHIFT;
            }
            // each pixel's errors once, by the strip it is in
            if (e >= x0 && e < x1) {
                ivec3 d = ivec3(px[0]) - ivec3(px[1]);
                sq += uint(d.r * d.r + d.g * d.g + d.b * d.b);
                ivec3 dt = abs((ivec3(px[0]) - ivec3(bytes(pc.cand_prev.u[i]))) - (ivec3(px[1]) - ivec3(bytes(pc.ref_prev.u[i]))));
                temporal += uint(dt.r + dt.g + dt.b);
            }
        }
        if (x < x0)
            continue;
        [[unroll]] for (int j = 0; j < STEP; j++) {
            int xj = x + j, c = CSF_R + j;
            if (xj >= x1)
                break;
            uint o = uint(xj) * pc.height + y;
            // tmp's planes: the reference's (image 1 here) first
            [[unroll]] for (int im = 0; im < 2; im++) {
                uint t = T_CSF + 4u * uint(1 - im), f = T_FEAT + 3u * uint(1 - im);
                pc.tmp.f[plane(t, o)] = conv(w[im][0], c, K_CSF, CSF_R, false);
                pc.tmp.f[plane(t + 1u, o)] = conv(w[im][1], c, K_CSF + CSF_TAPS, CSF_R, false);
                pc.tmp.f[plane(t + 2u, o)] = conv(w[im][2], c, K_CSF + 2 * CSF_TAPS, CSF_R, false);
                pc.tmp.f[plane(t + 3u, o)] = conv(w[im][2], c, K_CSF + 3 * CSF_TAPS, CSF_R, false);
                pc.tmp.f[plane(f, o)] = conv(w[im][3], c, K_FEAT, FEAT_R, true);
                pc.tmp.f[plane(f + 1u, o)] = conv(w[im][3], c, K_FEAT + FEAT_TAPS, FEAT_R, false);
                pc.tmp.f[plane(f + 2u, o)] = conv(w[im][3], c, K_FEAT + 2 * FEAT_TAPS, FEAT_R, false);
            }
            if (xj + SSIM_W <= int(pc.width)) {
                float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
                [[unroll]] for (int k = 0; k < SSIM_W; k++) {
                    float wk = kern[K_SSIM + k], a = l[0][c + k], b = l[1][c + k];
                    m[0] += wk * a;
                    m[1] += wk * b;
                    m[2] += wk * (a * a);
                    m[3] += wk * (b * b);
                    m[4] += wk * (a * b);
                }
                [[unroll]] for (int q = 0; q < 5; q++)
                    pc.tmp.f[plane(T_SSIM + uint(q), o)] = m[q];
            }
        }
    }
    pc.partials.u[2u * (strip * pc.height + y)] = sq;
    pc.partials.u[2u * (strip * pc.height + y) + 1u] = temporal;
}
