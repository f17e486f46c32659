#version 450
// The device scorer's horizontal filters: FLIP's contrast sensitivity terms
// and feature responses (edge pixels repeat beyond the borders), SSIM's five
// moments over the 11 pixels from x on (valid mode), stored by column for
// filter_y.comp (a column's values consecutive). An invocation walks along
// STRIP pixels of one row with a window of each input in registers: each
// pixel shifts the windows and reads one value per input, and the loop's
// body is small. On a CPU device (lavapipe) each read or write is a
// per-lane bounds-checked access, the bulk of the stage's instructions.
#extension GL_EXT_control_flow_attributes : require
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 1) in;
#define WIN (2 * CSF_R + 1)

// the CPU's convolution at the window's centre, sum over i of
// k[i + r] · src[x - i], the kernel being symmetric (anti: antisymmetric),
// so that the taps at ±i share a weight
float conv(float v[WIN], int k, int r, bool anti)
{
    float a = kern[k + r] * v[CSF_R], b = 0.0;
    [[unroll]] for (int i = 1; i <= r; i++) {
        float p = (anti ? v[CSF_R - i] - v[CSF_R + i] : v[CSF_R - i] + v[CSF_R + i]) * kern[k + r + i];
        if ((i & 1) == 1)
            b += p;
        else
            a += p;
    }
    return a + b;
}

void main()
{
    uint y = gl_GlobalInvocationID.x;
    int x0 = int(gl_WorkGroupID.y) * STRIP, x1 = min(x0 + STRIP, int(pc.width));
    if (y >= pc.height)
        return;
    uint row = y * pc.width;
    // w: pixels x - CSF_R .. x + CSF_R of the opponent channels, and of the
    // achromatic one as FLIP's features see it, (Y + 16) / 116; a, b: SSIM's
    // lumas from x on
    float w[2][4][WIN], a[SSIM_W], b[SSIM_W];
    for (int x = x0 - 2 * CSF_R; x < x1; x++) {
        [[unroll]] for (int im = 0; im < 2; im++) {
            [[unroll]] for (int c = 0; c < 4; c++)
                [[unroll]] for (int t = 0; t < WIN - 1; t++)
                    w[im][c][t] = w[im][c][t + 1];
            uint e = row + uint(clamp_x(x + CSF_R)), opp = P_OPP + 3u * uint(im);
            w[im][0][WIN - 1] = planes[plane(opp, e)];
            w[im][1][WIN - 1] = planes[plane(opp + 1u, e)];
            w[im][2][WIN - 1] = planes[plane(opp + 2u, e)];
            w[im][3][WIN - 1] = (w[im][0][WIN - 1] + 16.0) / 116.0;
        }
        [[unroll]] for (int t = 0; t < SSIM_W - 1; t++)
            a[t] = a[t + 1], b[t] = b[t + 1];
        uint e = row + uint(clamp_x(x + SSIM_W - 1));
        a[SSIM_W - 1] = planes[plane(P_LUMA_TEST, e)];
        b[SSIM_W - 1] = planes[plane(P_LUMA_REF, e)];
        if (x < x0)
            continue;
        uint o = uint(x) * pc.height + y;
        [[unroll]] for (int im = 0; im < 2; im++) {
            uint t = T_CSF + 4u * uint(im), f = T_FEAT + 3u * uint(im);
            tmp[plane(t, o)] = conv(w[im][0], K_CSF, CSF_R, false);
            tmp[plane(t + 1u, o)] = conv(w[im][1], K_CSF + CSF_TAPS, CSF_R, false);
            tmp[plane(t + 2u, o)] = conv(w[im][2], K_CSF + 2 * CSF_TAPS, CSF_R, false);
            tmp[plane(t + 3u, o)] = conv(w[im][2], K_CSF + 3 * CSF_TAPS, CSF_R, false);
            tmp[plane(f, o)] = conv(w[im][3], K_FEAT, FEAT_R, true);
            tmp[plane(f + 1u, o)] = conv(w[im][3], K_FEAT + FEAT_TAPS, FEAT_R, false);
            tmp[plane(f + 2u, o)] = conv(w[im][3], K_FEAT + 2 * FEAT_TAPS, FEAT_R, false);
        }
        if (x + SSIM_W <= int(pc.width)) {
            float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
            [[unroll]] for (int k = 0; k < SSIM_W; k++) {
                float wk = kern[K_SSIM + k];
                m[0] += wk * a[k];
                m[1] += wk * b[k];
                m[2] += wk * (a[k] * a[k]);
                m[3] += wk * (b[k] * b[k]);
                m[4] += wk * (a[k] * b[k]);
            }
            [[unroll]] for (int c = 0; c < 5; c++)
                tmp[plane(T_SSIM + uint(c), o)] = m[c];
        }
    }
}
