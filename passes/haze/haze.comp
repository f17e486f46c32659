#version 460
// distance haze toward the sky colour: hides a streamed world's edge and the void below the horizon
// Haze along each pixel's ray toward the sky's colour at the horizon, so
// that the edge of a streamed world and the void below the horizon beyond
// it do not show. Runs on the final linear colour (after denoising: the
// haze is smooth and needs no filtering); docs/lighting.md has the formula.
#define FRAME_BINDING 2
#include "frame.glsl"
#include "pixel.glsl"

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
    vec3 dir = frame_ray_dir(vec2(p), vec2(size));
    // the sky at the horizon in the ray's direction (its glow included)
    vec3 flat_dir = vec3(dir.x, max(dir.y, 0.0), dir.z);
    vec3 haze = frame_sky(length(flat_dir) > 1e-6 ? normalize(flat_dir) : vec3(0.0, 1.0, 0.0));
    float f;
    if (pos.w > 0.5) {
        vec3 to = pos.xyz - frame.camera_pos.xyz;
        f = 1.0 - exp(-params.density * length(to));
        float radius = float(frame.world_grid.w);
        if (radius > 0.0) // a streamed world: gone by its view radius
            f = max(f, smoothstep(params.start * radius, radius, length(to.xz)));
    } else
        f = dir.y < 0.0 ? 1.0 : 0.0; // below the horizon a miss is beyond the world
    imageStore(out_color, p, vec4(mix(c, haze, f), 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
