#version 460
// distance haze toward the sky colour: hides a streamed world's edge and the void below the horizon
// Haze along each pixel's ray toward the sky's colour at the horizon, so
// that the edge of a streamed world and the void below the horizon beyond
// it do not show. Runs on the final linear colour (after denoising: the
// haze is smooth and needs no filtering); docs/lighting.md has the formula.
#define FRAME_BINDING 2
#include "frame.glsl"
#include "pixel.glsl"
#include "haze.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_color;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 3, rgba16f) uniform writeonly image2D out_color;
layout(push_constant) uniform Params {
    float density; // @param default=0.0015 min=0 max=1 help="aerial haze per block: a hit at distance d keeps exp(-density * d) of its colour"
    float start;   // @param default=0.6 min=0 max=0.99 help="streamed worlds: fraction of the view radius where the edge haze begins (full haze at the radius)"
} params;

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_color, vrg_pixel_in(p, size, textureSize(in_color, 0)), 0).rgb;
    vec4 pos = texelFetch(in_position, vrg_pixel_in(p, size, textureSize(in_position, 0)), 0);
    imageStore(out_color, p, vec4(haze_blend(c, pos, p, size, params.density, params.start), 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
