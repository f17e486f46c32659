#version 460
// One-bounce indirect light (formulas in indirect.c): the mean, over `rays`
// cosine-weighted directions, of the radiance arriving along each.
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
layout(binding = 4) uniform sampler2D atlas;
layout(binding = 5, rgba16f) uniform writeonly image2D out_irradiance;
layout(binding = 6) uniform sampler2D in_history_length;
layout(binding = 7) uniform sampler2D in_motion;
// then the TLAS when the scene built one (trace.glsl: VRG_ACCEL_BINDING)
layout(push_constant) uniform Params {
    int rays;
    float max_distance;
    int shadow;
    int textured;
    int stratified; // rays from stratified points (rng_pair)
    int young_rays;
    float young_history;
} params;

// young_rays where last frame's history at the pixel this one came from
// was short or off screen (indirect.c), else rays
int rays_at(ivec2 p, ivec2 size)
{
    if (params.young_rays <= 0)
        return params.rays;
    // bounds in floats: a motion of inf (half overflow) must not become an int
    vec2 q = floor(vec2(p) - texelFetch(in_motion, p, 0).xy + 0.5);
    if (!(all(greaterThanEqual(q, vec2(0.0))) && all(lessThan(q, vec2(size)))))
        return params.young_rays;
    return texelFetch(in_history_length, ivec2(q), 0).r < params.young_history ? params.young_rays : params.rays;
}

const uint SALT = 0x494e0003u;  // this pass's random stream

// Radiance leaving the face n2 of block b at x2 toward the first surface:
// what it reflects and what it emits (albedo x its emissive scale).
vec3 bounce(vec3 x2, ivec3 n2, uint b)
{
    vec4 material = material_albedo_emissive(b);
    vec3 albedo = params.textured != 0 ? textureLod(atlas, world_atlas_uv(b, n2, vec2(0.5)), 4.0).rgb : material.rgb;
    vec3 l = frame.sun_dir.xyz;
    float ndl = max(dot(vec3(n2), l), 0.0);
    float v = 1.0;
    if (ndl <= 0.0 || l.y <= 0.0)
        v = 0.0;
    else if (params.shadow != 0 && trace_any(x2 + vec3(n2) * 1e-3, l, params.max_distance))
        v = 0.0;
    return albedo * (frame.sun_radiance.rgb * ndl * v + frame.ambient.rgb + material.w);
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_irradiance);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 g = vrg_pixel_in(p, size, imageSize(in_position));  // the G-buffer may differ in size
    vec4 pos = imageLoad(in_position, g);
    if (pos.w == 0.0) {
        imageStore(out_irradiance, p, vec4(0.0));
        return;
    }
    vec3 n = imageLoad(in_normal, g).xyz;
    vec3 o = pos.xyz + n * 1e-3;
    Rng r = rng_init(uvec2(p), frame.frame_info.x, frame.frame_info.w, SALT);
    vec3 sum = vec3(0.0);
    int rays = rays_at(p, size);
    for (int i = 0; i < rays; i++) {
        vec2 u = rng_pair(r, params.stratified != 0, uint(i), uint(rays));
        vec3 d = sample_cosine(n, u.x, u.y);
        Hit h = trace_closest(o, d, params.max_distance);
        sum += h.hit ? bounce(o + d * h.t, h.normal, h.block) : frame_sky(d);
    }
    imageStore(out_irradiance, p, vec4(sum / float(rays), 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
