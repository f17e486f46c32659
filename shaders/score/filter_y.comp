#version 450
// The device scorer's vertical filters and per-pixel errors: FLIP's
// filtered colours in Hunt-adjusted Lab, their HyAB distance and the
// feature difference give FLIP's error; SSIM's moments give the SSIM of the
// window whose corner is this pixel (0 where no window fits).
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 8) in;


// sum over i of k[i + r] · src[y - i], down the column
float conv_y(int k, int r, uint t, uint x)
{
    float s = 0.0;
    int y = int(gl_GlobalInvocationID.y);
    for (int i = -r; i <= r; i++)
        s += kern[k + i + r] * tmp[plane(t, uint(clamp_y(y - i)) * pc.width + x)];
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

// image im's filtered opponent colour at this pixel
vec3 filtered(uint im, uint x)
{
    uint t = T_CSF + 4u * im;
    float a = kern[K_SHARE + 0] * conv_y(K_CSF + 0 * CSF_TAPS, CSF_R, t, x);
    float rg = kern[K_SHARE + 1] * conv_y(K_CSF + 1 * CSF_TAPS, CSF_R, t + 1u, x);
    float by = kern[K_SHARE + 2] * conv_y(K_CSF + 2 * CSF_TAPS, CSF_R, t + 2u, x);
    by += kern[K_SHARE + 3] * conv_y(K_CSF + 3 * CSF_TAPS, CSF_R, t + 3u, x);
    return vec3(a, rg, by);
}

// |edge| and |point| of image im: d along x then g along y, and g along x
// then d along y, for each derivative
vec2 features(uint im, uint x)
{
    uint t = T_FEAT + 3u * im;
    const int d = K_FEAT, d2 = K_FEAT + FEAT_TAPS, g = K_FEAT + 2 * FEAT_TAPS;
    float ex = conv_y(g, FEAT_R, t, x), ey = conv_y(d, FEAT_R, t + 2u, x);
    float px = conv_y(g, FEAT_R, t + 1u, x), py = conv_y(d2, FEAT_R, t + 2u, x);
    return vec2(sqrt(ex * ex + ey * ey), sqrt(px * px + py * py));
}

float flip_error(uint x)
{
    const float qc = 0.7, pc_ = 0.4, pt = 0.95, qf = 0.5;
    float cmax = pow(hyab(hunt_lab(vec3(0.0, 1.0, 0.0)), hunt_lab(vec3(0.0, 0.0, 1.0))), qc);
    float e = pow(hyab(ycxcz_to_hunt_lab(filtered(0u, x)), ycxcz_to_hunt_lab(filtered(1u, x))), qc);
    float color = e < pc_ * cmax ? e * pt / (pc_ * cmax) : pt + (e - pc_ * cmax) / (cmax - pc_ * cmax) * (1.0 - pt);
    vec2 f0 = features(0u, x), f1 = features(1u, x);
    float f = max(abs(f0.x - f1.x), abs(f0.y - f1.y));
    f = pow(f / sqrt(2.0), qf);
    return pow(color, 1.0 - f);
}

float ssim(uint i)
{
    float m[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
    for (int k = 0; k < SSIM_W; k++)
        for (uint c = 0u; c < 5u; c++)
            m[c] += kern[K_SSIM + k] * tmp[plane(T_SSIM + c, i + uint(k) * pc.width)];
    const float c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    float va = m[2] - m[0] * m[0], vb = m[3] - m[1] * m[1], cov = m[4] - m[0] * m[1];
    float ma = m[0] + SSIM_SHIFT, mb = m[1] + SSIM_SHIFT;
    return ((2.0 * ma * mb + c1) * (2.0 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
}

void main()
{
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= pc.width || p.y >= pc.height)
        return;
    uint i = p.y * pc.width + p.x;
    planes[plane(P_FLIP, i)] = flip_error(p.x);
    bool window = p.x + uint(SSIM_W) <= pc.width && p.y + uint(SSIM_W) <= pc.height;
    planes[plane(P_SSIM, i)] = window ? ssim(i) : 0.0;
}
