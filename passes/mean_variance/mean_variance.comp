#version 460
// Variance of the accumulated mean: mean_variance.c has the definition.
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_moments;
layout(binding = 2) uniform sampler2D in_length;
layout(binding = 3) uniform sampler2D in_position;
layout(binding = 4) uniform sampler2D in_normal;
layout(binding = 5, rgba16f) uniform writeonly image2D out_color;
#ifdef VARIANCE
layout(binding = 6, rg16f) uniform writeonly image2D out_variance;
#endif
layout(push_constant) uniform Params {
    int radius, min_history;
} params;

// the moments averaged over the window's pixels on p's surface
vec2 spatial_moments(ivec2 p, ivec2 size, vec3 x)
{
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    vec3 s = vec3(0.0);
    for (int dy = -params.radius; dy <= params.radius; dy++)
        for (int dx = -params.radius; dx <= params.radius; dx++) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            vec4 xq = texelFetch(in_position, q, 0);
            if (xq.w == 0.0 || dot(texelFetch(in_normal, q, 0).xyz, n) < 0.9 ||
                abs(dot(xq.xyz - x, n)) > 0.1 * float(max(abs(dx), abs(dy))))
                continue;
            s += vec3(texelFetch(in_moments, q, 0).xy, 1.0);
        }
    return s.xy / s.z; // the centre always counts
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 c = texelFetch(in_illumination, p, 0);
    vec4 x = texelFetch(in_position, p, 0);
    float var = 0.0;
#ifdef VARIANCE
    float own = 0.0; // 1: from the pixel's own moments
#endif
    if (x.w != 0.0) {
        bool young = texelFetch(in_length, p, 0).r + 1.0 < float(params.min_history);
        vec2 m = young ? spatial_moments(p, size, x.xyz) : texelFetch(in_moments, p, 0).xy;
        var = max(0.0, m.y - m.x * m.x) / max(c.a, 1.0);
#ifdef VARIANCE
        own = young ? 0.0 : 1.0;
#endif
    }
    imageStore(out_color, p, vec4(c.rgb, var));
#ifdef VARIANCE
    imageStore(out_variance, p, vec4(var, own, 0.0, 0.0));
#endif
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
