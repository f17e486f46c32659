#version 450
// The device scorer's vertical filters and per-pixel errors: FLIP's
// filtered colours in Hunt-adjusted Lab, their HyAB distance and the
// feature difference give FLIP's error; SSIM's moments give the SSIM of the
// window whose corner is the pixel (0 where no window fits). An invocation
// does SEG pixels of a column from one window of each input, read once.
// The loops over the SEG pixels and the taps are unrolled, so that the
// window is indexed by constants and stays in registers (on lavapipe the
// first compile takes longer; Mesa's shader cache keeps the result).
#extension GL_EXT_control_flow_attributes : require
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#define WIN (SEG + 2 * CSF_R)

// the window: plane t of column x from y0 - CSF_R on, edge pixels repeated
void window(uint t, uint x, int y0, out float v[WIN])
{
    for (int i = 0; i < WIN; i++)
        v[i] = tmp[plane(t, uint(clamp_y(y0 - CSF_R + i)) * pc.width + x)];
}

// the CPU's convolution at y0 + j: sum over i of k[i + r] · src[y0 + j - i]
float conv(float v[WIN], int k, int r, int j)
{
    float s = 0.0;
    [[unroll]] for (int i = -r; i <= r; i++)
        s += kern[k + i + r] * v[j - i + CSF_R];
    return s;
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

// SSIM of the window whose corner is pixel (x, y0 + j), from its column
// of horizontal moments
float ssim(float m[5])
{
    const float c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    float va = m[2] - m[0] * m[0], vb = m[3] - m[1] * m[1], cov = m[4] - m[0] * m[1];
    float ma = m[0] + SSIM_SHIFT, mb = m[1] + SSIM_SHIFT;
    return ((2.0 * ma * mb + c1) * (2.0 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
}

void main()
{
    uvec2 g = gl_GlobalInvocationID.xy;
    int y0 = int(g.y) * SEG;
    if (g.x >= pc.width || y0 >= int(pc.height))
        return;
    uint x = g.x;
    int n = min(SEG, int(pc.height) - y0);
    float v[WIN];
    vec3 colour[2][SEG];
    vec2 features[2][SEG];
    for (uint im = 0u; im < 2u; im++) {
        uint t = T_CSF + 4u * im, f = T_FEAT + 3u * im;
        const int d = K_FEAT, d2 = K_FEAT + FEAT_TAPS, gk = K_FEAT + 2 * FEAT_TAPS;
        window(t, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            colour[im][j].x = kern[K_SHARE + 0] * conv(v, K_CSF, CSF_R, j);
        window(t + 1u, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            colour[im][j].y = kern[K_SHARE + 1] * conv(v, K_CSF + CSF_TAPS, CSF_R, j);
        window(t + 2u, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            colour[im][j].z = kern[K_SHARE + 2] * conv(v, K_CSF + 2 * CSF_TAPS, CSF_R, j);
        window(t + 3u, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            colour[im][j].z += kern[K_SHARE + 3] * conv(v, K_CSF + 3 * CSF_TAPS, CSF_R, j);
        // edges: d along x then g along y, and g along x then d along y;
        // points alike with the second derivative
        window(f, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            features[im][j].x = conv(v, gk, FEAT_R, j);
        window(f + 1u, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++)
            features[im][j].y = conv(v, gk, FEAT_R, j);
        window(f + 2u, x, y0, v);
        [[unroll]] for (int j = 0; j < SEG; j++) {
            float ey = conv(v, d, FEAT_R, j), py = conv(v, d2, FEAT_R, j);
            vec2 xs = features[im][j];
            features[im][j] = vec2(sqrt(xs.x * xs.x + ey * ey), sqrt(xs.y * xs.y + py * py));
        }
    }
    [[unroll]] for (int j = 0; j < SEG; j++)
        if (j < n)
            planes[plane(P_FLIP, uint(y0 + j) * pc.width + x)] = flip_error(colour[0][j], colour[1][j], features[0][j], features[1][j]);
    float col[5][SEG + SSIM_W - 1];
    for (uint c = 0u; c < 5u; c++)
        for (int i = 0; i < SEG + SSIM_W - 1; i++)
            col[c][i] = tmp[plane(T_SSIM + c, uint(min(y0 + i, int(pc.height) - 1)) * pc.width + x)];
    bool fits = x + uint(SSIM_W) <= pc.width;
    [[unroll]] for (int j = 0; j < SEG && j < n; j++) {
        float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
        for (int k = 0; k < SSIM_W; k++)
            for (uint c = 0u; c < 5u; c++)
                m[c] += kern[K_SSIM + k] * col[c][j + k];
        bool window = fits && y0 + j + SSIM_W <= int(pc.height);
        planes[plane(P_SSIM, uint(y0 + j) * pc.width + x)] = window ? ssim(m) : 0.0;
    }
}
