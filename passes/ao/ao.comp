#version 460
// Ambient occlusion (see ao.c): the fraction of `rays` cosine-weighted
// hemisphere rays that travel `radius` blocks without a hit.
#define WORLD_BINDING 0
#define FRAME_BINDING 1
#include "world.glsl"
#include "frame.glsl"
#include "trace.glsl"
#include "pixel.glsl"
#include "random.glsl"

layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 2, rgba32f) uniform readonly image2D in_position;
layout(binding = 3, rgba16f) uniform readonly image2D in_normal;
layout(binding = 4, r16f) uniform writeonly image2D out_ao;
layout(push_constant) uniform Params {
    int rays;
    float radius;
    int stratified; // rays from stratified points (rng_pair)
} params;

const uint SALT = 0x414f0002u;  // this pass's random stream

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_ao);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 g = vrg_pixel_in(p, size, imageSize(in_position));  // the G-buffer may differ in size
    vec4 pos = imageLoad(in_position, g);
    if (pos.w == 0.0) {
        imageStore(out_ao, p, vec4(1.0));
        return;
    }
    vec3 n = imageLoad(in_normal, g).xyz;
    vec3 o = pos.xyz + n * 1e-3;
    Rng r = rng_init(uvec2(p), frame.frame_info.x, frame.frame_info.w, SALT);
    int open = 0;
    for (int i = 0; i < params.rays; i++) {
        vec2 u = rng_pair(r, params.stratified != 0, uint(i), uint(params.rays));
        if (!trace_any(o, sample_cosine(n, u.x, u.y), params.radius))
            open++;
    }
    imageStore(out_ao, p, vec4(float(open) / float(params.rays)));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
