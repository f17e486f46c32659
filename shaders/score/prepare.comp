#version 450
// The device scorer's first stage, per pixel: FLIP's opponent channels and
// SSIM's luma of both images, and the exact integer squared and temporal
// errors of the 8-bit values.
#include "score.glsl"
layout(local_size_x = 8, local_size_y = 8) in;


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

void main()
{
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= pc.width || p.y >= pc.height)
        return;
    uint i = p.y * pc.width + p.x;
    uvec3 t = bytes(cand[i]), r = bytes(ref_px[i]);
    vec3 tf = unit(t), rf = unit(r);
    vec3 o = ycxcz(rf);
    planes[plane(P_OPP + 0u, i)] = o.x;
    planes[plane(P_OPP + 1u, i)] = o.y;
    planes[plane(P_OPP + 2u, i)] = o.z;
    o = ycxcz(tf);
    planes[plane(P_OPP + 3u, i)] = o.x;
    planes[plane(P_OPP + 4u, i)] = o.y;
    planes[plane(P_OPP + 5u, i)] = o.z;
    planes[plane(P_LUMA_TEST, i)] = luma(tf) - SSIM_SHIFT;
    planes[plane(P_LUMA_REF, i)] = luma(rf) - SSIM_SHIFT;
    ivec3 d = ivec3(t) - ivec3(r);
    ints[2u * i] = uint(d.r * d.r + d.g * d.g + d.b * d.b);
    ivec3 dt = (ivec3(t) - ivec3(bytes(cand_prev[i]))) - (ivec3(r) - ivec3(bytes(ref_prev[i])));
    dt = abs(dt);
    ints[2u * i + 1u] = uint(dt.r + dt.g + dt.b);
}
