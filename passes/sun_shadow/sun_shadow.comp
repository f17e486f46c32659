#version 460
// Sun visibility (see sun_shadow.c): the fraction of `rays` rays toward
// points of the sun's disc that reach max_distance without a hit; with
// OCCLUDER defined (the output is read) also the mean distance to the
// blocker over the rays that hit, -1 where none did.
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
layout(binding = 4, r16f) uniform writeonly image2D out_visibility;
layout(binding = 5, r16f) uniform writeonly image2D out_occluder;
layout(push_constant) uniform Params {
    int rays;
    float sun_radians;  // the parameter sun_radius in radians; 0: exactly sun_dir, and rays == 1
    float max_distance;
    int stratified; // rays from stratified points (rng_pair)
} params;

const uint SALT = 0x53554e01u;  // this pass's random stream

void store_occluder(ivec2 p, int hits, float dist)
{
#ifdef OCCLUDER
    imageStore(out_occluder, p, vec4(hits > 0 ? dist / float(hits) : -1.0));
#endif
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_visibility);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 g = vrg_pixel_in(p, size, imageSize(in_position));  // the G-buffer may differ in size
    vec4 pos = imageLoad(in_position, g);
    if (pos.w == 0.0) {
        imageStore(out_visibility, p, vec4(1.0));
        store_occluder(p, 0, 0.0);
        return;
    }
    vec3 n = imageLoad(in_normal, g).xyz;
    vec3 l = frame.sun_dir.xyz;
    if (l.y <= 0.0 || dot(n, l) <= 0.0) {
        imageStore(out_visibility, p, vec4(0.0));
        store_occluder(p, 0, 0.0);
        return;
    }
    vec3 o = pos.xyz + n * 1e-3;
    Rng r = rng_init(uvec2(p), frame.frame_info.x, frame.frame_info.w, SALT);
    int seen = 0, hits = 0;
    float dist = 0.0;
    for (int i = 0; i < params.rays; i++) {
        vec3 d = l;
        if (params.sun_radians > 0.0) {
            vec2 u = rng_pair(r, params.stratified != 0, uint(i), uint(params.rays));
            d = sample_cone(l, params.sun_radians, u.x, u.y);
        }
        if (dot(n, d) <= 0.0)
            continue;
#ifdef OCCLUDER
        // the DDA's any-hit is the closest hit, a ray query's is not
        Hit h = trace_closest(o, d, params.max_distance);
        if (h.hit) {
            hits++;
            dist += h.t;
        } else {
            seen++;
        }
#else
        if (!trace_any(o, d, params.max_distance))
            seen++;
#endif
    }
    imageStore(out_visibility, p, vec4(float(seen) / float(params.rays)));
    store_occluder(p, hits, dist);
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
