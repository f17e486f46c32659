#version 460
// One à-trous iteration of SVGF (or, with COPY, a copy): svgf_atrous.c has
// the weights.
#include "pixel.glsl"
#include "color.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;

#if defined(SURFACE)
layout(binding = 0) uniform sampler2D in_position;
layout(binding = 1) uniform sampler2D in_normal;
layout(binding = 2, rg32f) uniform writeonly image2D out_surface;

// (normal axis 0..5 = +x -x +y -y +z -z, or -1 on sky; N . X)
void shade(ivec2 p)
{
    if (any(greaterThanEqual(p, imageSize(out_surface))))
        return;
    vec4 x = texelFetch(in_position, p, 0);
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    vec3 a = abs(n);
    float axis = a.x > 0.5 ? (n.x > 0.0 ? 0.0 : 1.0) : a.y > 0.5 ? (n.y > 0.0 ? 2.0 : 3.0) : (n.z > 0.0 ? 4.0 : 5.0);
    imageStore(out_surface, p, vec4(x.w == 0.0 ? -1.0 : axis, dot(n, x.xyz), 0.0, 0.0));
}
#elif defined(COPY)
layout(binding = 0) uniform sampler2D in_src;
layout(binding = 1, rgba16f) uniform writeonly image2D out_dst;

void shade(ivec2 p)
{
    if (all(lessThan(p, imageSize(out_dst))))
        imageStore(out_dst, p, texelFetch(in_src, p, 0));
}
#else
#define FRAME_BINDING 3
#include "frame.glsl"
layout(binding = 0) uniform sampler2D in_src;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 2) uniform sampler2D in_surface;  // (normal axis, N . X): the SURFACE dispatch
layout(binding = 4, rgba16f) uniform writeonly image2D out_dst;
layout(push_constant) uniform Params {
    float sigma_z, sigma_n, sigma_l, skip_variance;
    int step, kernel;
} params;

// 3x3 Gaussian (1/4 1/2 1/4) of the variance around p: steadier than the
// pixel's own for the luminance test
float variance_3x3(ivec2 p, ivec2 size)
{
    float s = 0.0, w = 0.0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
            float k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
            s += k * texelFetch(in_src, q, 0).a;
            w += k;
        }
    return s / w;
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_dst);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 c = texelFetch(in_src, p, 0);
    vec2 sp = texelFetch(in_surface, p, 0).xy;
    if (sp.x < 0.0 || c.a < params.skip_variance) { // sky, or quiet enough already
        imageStore(out_dst, p, c);
        return;
    }
    vec3 x = texelFetch(in_position, p, 0).xyz;
    float lp = luminance(c.rgb);
    float sigma_l = params.sigma_l * sqrt(max(variance_3x3(p, size), 0.0)) + 1e-6;
    // world size of one pixel step at p's distance (vertical fov in camera_pos.w)
    float footprint = distance(x, frame.camera_pos.xyz) * 2.0 * tan(0.5 * frame.camera_pos.w) / float(size.y);
    const float B3[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    const float G3[2] = float[2](1.0 / 2.0, 1.0 / 4.0);
    int r = params.kernel == 5 ? 2 : 1;
    vec3 sum = vec3(0.0);
    float var = 0.0, wsum = 0.0;
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            ivec2 q = p + ivec2(dx, dy) * params.step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            vec2 sq = texelFetch(in_surface, q, 0).xy;
            if (sq.x != sp.x) // sky, or another normal: w_n = 0
                continue;
            float h = r == 2 ? B3[abs(dx)] * B3[abs(dy)] : G3[abs(dx)] * G3[abs(dy)];
            vec4 cq = texelFetch(in_src, q, 0);
            float dist = length(vec2(dx, dy)) * float(params.step);
            float wz = exp(-abs(sq.y - sp.y) / (params.sigma_z * dist * footprint + 1e-6));
            float wl = exp(-abs(lp - luminance(cq.rgb)) / sigma_l);
            float w = h * wz * wl;
            sum += w * cq.rgb;
            var += w * w * cq.a;
            wsum += w;
        }
    // the centre tap has w = h > 0, so wsum > 0
    imageStore(out_dst, p, vec4(sum / wsum, var / (wsum * wsum)));
}
#endif

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
