#version 460
// ambient occlusion: fraction of cosine-weighted hemisphere rays that travel `radius` blocks unoccluded
// `rays` cosine-weighted rays per pixel in the hemisphere around the face
// normal, each of length `radius` blocks, traced through the world (DDA,
// or ray queries when the scene built a TLAS).
//   ao = (rays that travel `radius` without a hit) / rays, in [0, 1]
// With cosine-weighted directions (pdf cos/pi) this estimates the
// cosine-weighted ambient visibility (1/pi) * integral of V(w) cos(w) dw over
// the hemisphere: 1 on an open floor. Sky pixels (position.w == 0): 1, no
// rays. Rays start at position + normal * 1e-3. stratified = 1 draws the
// directions from random.glsl's stratified points (docs/lighting.md,
// "Sampling").
// The world and the TLAS are declared here, named as slots, for
// world.glsl and trace.glsl (WORLD_TEXELS, TRACE_TLAS). in_tlas is
// declared, and trace.glsl's ray-query backend traces it, in the variant
// compiled where the scene built a TLAS (HAS_TLAS); elsewhere the DDA
// traces the world.
#ifdef HAS_TLAS
#extension GL_EXT_ray_query : require
#define TRACE_RAYQUERY
#define TRACE_TLAS in_tlas
#endif
layout(binding = 0) uniform usamplerBuffer in_world;
#define WORLD_TEXELS in_world
#define FRAME_BINDING 1
#include "world.glsl"
#include "frame.glsl"
#ifdef HAS_TLAS
layout(binding = 5) uniform accelerationStructureEXT in_tlas; // @optional help="the scene's TLAS: trace with ray queries (traversal = rayquery)"
#endif
#include "trace.glsl"
#include "pixel.glsl"
#include "random.glsl"

layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 2, rgba32f) uniform readonly image2D in_position;
layout(binding = 3, rgba16f) uniform readonly image2D in_normal;
layout(binding = 4, r16f) uniform writeonly image2D out_ao;
layout(push_constant) uniform Params {
    int rays;        // @param default=4 min=1 max=64 help="AO rays per pixel"
    float radius;    // @param default=4 min=0.01 max=1024 help="AO ray length, blocks"
    bool stratified; // @param default=0 help="directions from a sequence that covers the hemisphere evenly over each 4x4 tile of pixels and over the frames (0: independent random numbers)"
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
        vec2 u = rng_pair(r, params.stratified, uint(i), uint(params.rays));
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
