#version 450
// The device scorer's horizontal filters: FLIP's contrast sensitivity terms
// and feature responses (edge pixels repeat beyond the borders), SSIM's five
// moments over the 11 pixels from x on (valid mode). An invocation filters
// SEG pixels of a row from one window of its inputs, read once (the reads,
// not the sums, are what costs on a CPU device). The sums run over the taps
// in the CPU's order.
// The loops over the SEG pixels and the taps are unrolled, so that the
// window is indexed by constants and stays in registers (on lavapipe the
// first compile takes longer; Mesa's shader cache keeps the result).
#extension GL_EXT_control_flow_attributes : require
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#define WIN (SEG + 2 * CSF_R)

// the window: plane p from x0 - CSF_R on, edge pixels repeated
void window(uint p, uint row, int x0, out float v[WIN])
{
    for (int t = 0; t < WIN; t++)
        v[t] = planes[plane(p, row + uint(clamp_x(x0 - CSF_R + t)))];
}

// the CPU's convolution at x0 + j: sum over i of k[i + r] · src[x0 + j - i]
float conv(float v[WIN], int k, int r, int j)
{
    float s = 0.0;
    [[unroll]] for (int i = -r; i <= r; i++)
        s += kern[k + i + r] * v[j - i + CSF_R];
    return s;
}

void main()
{
    uvec2 g = gl_GlobalInvocationID.xy;
    int x0 = int(g.x) * SEG;
    if (x0 >= int(pc.width) || g.y >= pc.height)
        return;
    uint row = g.y * pc.width;
    int n = min(SEG, int(pc.width) - x0);
    float v[WIN];
    for (uint im = 0u; im < 2u; im++) {
        uint opp = P_OPP + 3u * im, t = T_CSF + 4u * im, f = T_FEAT + 3u * im;
        window(opp, row, x0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            if (j < n)
                tmp[plane(t, row + uint(x0 + j))] = conv(v, K_CSF, CSF_R, j);
        // FLIP's features see the achromatic channel as (Y + 16) / 116
        for (int e = 0; e < WIN; e++)
            v[e] = (v[e] + 16.0) / 116.0;
        [[unroll]] for (int j = 0; j < SEG; j++)
            for (int k = 0; k < 3 && j < n; k++)
                tmp[plane(f + uint(k), row + uint(x0 + j))] = conv(v, K_FEAT + k * FEAT_TAPS, FEAT_R, j);
        window(opp + 1u, row, x0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            if (j < n)
                tmp[plane(t + 1u, row + uint(x0 + j))] = conv(v, K_CSF + CSF_TAPS, CSF_R, j);
        window(opp + 2u, row, x0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            if (j < n) {
                tmp[plane(t + 2u, row + uint(x0 + j))] = conv(v, K_CSF + 2 * CSF_TAPS, CSF_R, j);
                tmp[plane(t + 3u, row + uint(x0 + j))] = conv(v, K_CSF + 3 * CSF_TAPS, CSF_R, j);
            }
    }
    // SSIM: windows from x on, those that fit
    float a[SEG + SSIM_W], b[SEG + SSIM_W];
    for (int t = 0; t < SEG + SSIM_W - 1; t++) {
        uint x = uint(min(x0 + t, int(pc.width) - 1));
        a[t] = planes[plane(P_LUMA_TEST, row + x)];
        b[t] = planes[plane(P_LUMA_REF, row + x)];
    }
    for (int j = 0; j < n && x0 + j + SSIM_W <= int(pc.width); j++) {
        float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
        for (int k = 0; k < SSIM_W; k++) {
            float w = kern[K_SSIM + k];
            m[0] += w * a[j + k];
            m[1] += w * b[j + k];
            m[2] += w * (a[j + k] * a[j + k]);
            m[3] += w * (b[j + k] * b[j + k]);
            m[4] += w * (a[j + k] * b[j + k]);
        }
        for (uint c = 0u; c < 5u; c++)
            tmp[plane(T_SSIM + c, row + uint(x0 + j))] = m[c];
    }
}
