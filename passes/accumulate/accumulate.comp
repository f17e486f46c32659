#version 460
// Progressive mean of frames for a still camera: accumulate.c.
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_src;
layout(binding = 1) uniform sampler2D in_history;
layout(binding = 2, rgba32f) uniform writeonly image2D out_color;
layout(push_constant) uniform Params {
    int reset, max_frames;
} params;

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_src, vrg_pixel_in(p, size, textureSize(in_src, 0)), 0).rgb;
    if (params.reset != 0) {
        imageStore(out_color, p, vec4(c, 1.0));
        return;
    }
    vec4 h = texelFetch(in_history, p, 0);
    float n = h.a + 1.0;
    if (params.max_frames > 0)
        n = min(n, float(params.max_frames));
    imageStore(out_color, p, vec4(h.rgb + (c - h.rgb) / n, n));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
