#version 450
// The device scorer's horizontal filters, per pixel: FLIP's contrast
// sensitivity terms and feature responses (edge pixels repeat beyond the
// borders), SSIM's five moments over the 11 pixels from x on (valid mode).
// The sums run over the taps in the CPU's order.
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

// kernel at kernel offset k, radius r, of plane p along the row: the CPU's
// convolution, sum over i of k[i + r] · src[x - i]
float conv_x(int k, int r, uint p, int x, uint row)
{
    float s = 0.0;
    for (int i = -r; i <= r; i++)
        s += kern[k + i + r] * planes[plane(p, row + uint(clamp_x(x - i)))];
    return s;
}

// the same on the achromatic channel normalised as FLIP's features see it
float conv_x_y(int k, uint p, int x, uint row)
{
    float s = 0.0;
    for (int i = -FEAT_R; i <= FEAT_R; i++)
        s += kern[k + i + FEAT_R] * ((planes[plane(p, row + uint(clamp_x(x - i)))] + 16.0) / 116.0);
    return s;
}

void main()
{
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= pc.width || p.y >= pc.height)
        return;
    uint row = p.y * pc.width, i = row + p.x;
    int x = int(p.x);
    for (uint im = 0u; im < 2u; im++) {
        uint opp = P_OPP + 3u * im;
        tmp[plane(T_CSF + 4u * im + 0u, i)] = conv_x(K_CSF + 0 * CSF_TAPS, CSF_R, opp, x, row);
        tmp[plane(T_CSF + 4u * im + 1u, i)] = conv_x(K_CSF + 1 * CSF_TAPS, CSF_R, opp + 1u, x, row);
        tmp[plane(T_CSF + 4u * im + 2u, i)] = conv_x(K_CSF + 2 * CSF_TAPS, CSF_R, opp + 2u, x, row);
        tmp[plane(T_CSF + 4u * im + 3u, i)] = conv_x(K_CSF + 3 * CSF_TAPS, CSF_R, opp + 2u, x, row);
        for (uint f = 0u; f < 3u; f++)
            tmp[plane(T_FEAT + 3u * im + f, i)] = conv_x_y(K_FEAT + int(f) * FEAT_TAPS, opp, x, row);
    }
    if (p.x + uint(SSIM_W) > pc.width)
        return;
    float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
    for (int k = 0; k < SSIM_W; k++) {
        float a = planes[plane(P_LUMA_TEST, i + uint(k))], b = planes[plane(P_LUMA_REF, i + uint(k))], w = kern[K_SSIM + k];
        m[0] += w * a;
        m[1] += w * b;
        m[2] += w * (a * a);
        m[3] += w * (b * b);
        m[4] += w * (a * b);
    }
    for (uint c = 0u; c < 5u; c++)
        tmp[plane(T_SSIM + c, i)] = m[c];
}
