#version 460
// debug mosaic of the G-buffer: normals, depth, albedo, motion
// The G-buffer as a 2x2 mosaic at full size, each quadrant showing its
// source at half resolution (nearest, every other pixel):
//   top-left     normal * 0.5 + 0.5 (sky black)
//   top-right    linear depth as 1 - depth / far (sky black)
//   bottom-left  albedo, sRGB-encoded and clamped (sky: sky radiance)
//   bottom-right motion: hue = direction, brightness = |motion| * motion_scale
//                (still pixels black)
// Written as display values into an UNORM image.
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_position;
layout(binding = 1) uniform sampler2D in_depth;
layout(binding = 2) uniform sampler2D in_normal;
layout(binding = 3) uniform sampler2D in_albedo;
layout(binding = 4) uniform sampler2D in_motion;
layout(binding = 5, rgba8) uniform writeonly image2D out_view;
layout(push_constant) uniform Params {
    float far;          // @param default=256 min=0.001 max=1e6 help="depth shown black (blocks)"
    float motion_scale; // @param default=0.25 min=0 max=1e6 help="brightness per pixel of motion"
} params;

vec3 srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec3 hue(float h) // h in [0, 1): fully saturated colour wheel
{
    return clamp(abs(fract(h + vec3(0.0, 2.0, 1.0) / 3.0) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
}

// Source texel for a quadrant-local pixel q: every other texel, clamped.
ivec2 source(sampler2D s, ivec2 q)
{
    return min(q * 2, textureSize(s, 0) - 1);
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_view);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 half_size = (size + 1) / 2;
    ivec2 quad = ivec2(greaterThanEqual(p, half_size));
    ivec2 q = p - quad * half_size;
    bool sky = texelFetch(in_position, source(in_position, q), 0).w == 0.0;
    vec3 c = vec3(0.0);
    if (quad == ivec2(0, 0)) {
        if (!sky)
            c = texelFetch(in_normal, source(in_normal, q), 0).xyz * 0.5 + 0.5;
    } else if (quad == ivec2(1, 0)) {
        if (!sky)
            c = vec3(clamp(1.0 - texelFetch(in_depth, source(in_depth, q), 0).r / params.far, 0.0, 1.0));
    } else if (quad == ivec2(0, 1)) {
        c = srgb_encode(texelFetch(in_albedo, source(in_albedo, q), 0).rgb);
    } else {
        vec2 m = texelFetch(in_motion, source(in_motion, q), 0).xy;
        float len = length(m);
        if (len > 0.0 && !isnan(len))
            c = hue(atan(-m.y, m.x) / 6.28318530718 + 0.5) * min(len * params.motion_scale, 1.0);
    }
    imageStore(out_view, p, vec4(c, 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
