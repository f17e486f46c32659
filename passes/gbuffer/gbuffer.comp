#version 460
#define WORLD_BINDING 0
#define FRAME_BINDING 1
#include "world.glsl"
#include "frame.glsl"
#include "trace.glsl"
#include "pixel.glsl"

layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 2) uniform sampler2D atlas;
layout(binding = 3, rgba32f) uniform writeonly image2D out_position;
layout(binding = 4, r32f) uniform writeonly image2D out_depth;
layout(binding = 5, rgba16f) uniform writeonly image2D out_normal;
layout(binding = 6, rgba16f) uniform writeonly image2D out_albedo;
layout(binding = 7, rg32ui) uniform writeonly uimage2D out_ids;
layout(binding = 8, rg16f) uniform writeonly image2D out_motion;
layout(binding = 9, r16f) uniform writeonly image2D out_emission;
// The optional outputs some pass reads (gbuffer.c): an unread one is a 1x1
// stand-in, neither computed nor written (store, below).
const uint WRITE_DEPTH = 1u, WRITE_IDS = 2u, WRITE_MOTION = 4u, WRITE_EMISSION = 8u;
layout(push_constant) uniform Params {
    float max_distance;
    int textured;
    uint writes;  // WRITE_* bits
} params;

// Where a world point (w = 1) or direction (w = 0) was on screen last frame, in pixels.
// Behind the previous camera (clip w <= 0) the projection would mirror it
// onto the screen: report a position far off screen instead, so
// reprojection finds no history there.
vec2 previous_pixel(vec4 p, vec2 size)
{
    vec4 clip = frame.prev_view_proj * p;
    if (clip.w <= 1e-6)
        return vec2(-1e4);  // representable in the rg16f motion image
    return (clip.xy / clip.w * 0.5 + 0.5) * size - 0.5;
}

// The optional outputs, each computed only where its bit is set. t: the
// hit's distance (0 on a miss), moved: the hit point (w = 1) or, on a
// miss, the ray's direction (w = 0), for the motion vector.
void store(ivec2 p, ivec2 size, float t, vec3 d, vec4 moved, uvec2 ids, float emission)
{
    if ((params.writes & WRITE_DEPTH) != 0u)
        imageStore(out_depth, p, vec4(t * dot(d, frame.camera_forward.xyz)));
    if ((params.writes & WRITE_IDS) != 0u)
        imageStore(out_ids, p, uvec4(ids, 0u, 0u));
    if ((params.writes & WRITE_MOTION) != 0u)
        imageStore(out_motion, p, vec4(vec2(p) - previous_pixel(moved, vec2(size)), 0.0, 0.0));
    if ((params.writes & WRITE_EMISSION) != 0u)
        imageStore(out_emission, p, vec4(emission));
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_albedo);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 o = frame.camera_pos.xyz;
    vec3 d = frame_ray_dir(vec2(p), vec2(size));
    Hit h = trace_closest(o, d, params.max_distance);
    if (!h.hit) {
        imageStore(out_position, p, vec4(0.0));
        imageStore(out_normal, p, vec4(0.0));
        imageStore(out_albedo, p, vec4(frame_sky(d), 1.0));
        store(p, size, 0.0, d, vec4(d, 0.0), uvec2(0u), 0.0);
        return;
    }
    vec3 hp = o + d * h.t;
    vec3 n = vec3(h.normal);
    vec4 material = material_albedo_emissive(h.block);
    vec3 albedo = material.rgb;
    if (params.textured != 0) {
        float pixel_angle = 2.0 * length(frame.camera_up.xyz) / float(size.y);
        float lod = world_texture_lod(h.t, pixel_angle, abs(dot(n, d)));
        albedo = textureLod(atlas, world_atlas_uv(h.block, h.normal, world_face_uv(hp, h.normal)), lod).rgb;
    }
    imageStore(out_position, p, vec4(hp, 1.0));
    imageStore(out_normal, p, vec4(n, 0.0));
    imageStore(out_albedo, p, vec4(albedo, 1.0));
    store(p, size, h.t, d, vec4(hp, 1.0), uvec2(h.block, uint(h.chunk) + 1u), material.w);
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
