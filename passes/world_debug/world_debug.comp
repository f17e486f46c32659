#version 450
#define WORLD_BINDING 0
#define FRAME_BINDING 1
#include "world.glsl"
#include "frame.glsl"
#include "trace.glsl"
#include "pixel.glsl"

layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 2) uniform sampler2D atlas;
layout(binding = 3, rgba16f) uniform writeonly image2D color;
layout(push_constant) uniform Params {
    int mode;
    int shadows;
    float exposure;
    float max_distance;
    int textured;
} params;

// A stable, distinct colour per block id.
vec3 id_color(uint id)
{
    uint h = id * 2654435761u;
    return vec3((h >> 8) & 255u, (h >> 16) & 255u, (h >> 24) & 255u) / 255.0;
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 o = frame.camera_pos.xyz;
    vec3 d = frame_ray_dir(vec2(p), vec2(size));
    Hit h = trace_closest(o, d, params.max_distance);
    vec3 c;
    if (!h.hit) {
        c = params.mode == 0 ? frame_sky(d) * params.exposure : vec3(0.0);
    } else if (params.mode == 1) {
        c = vec3(h.normal);
    } else if (params.mode == 2) {
        c = id_color(h.block);
    } else if (params.mode == 3) {
        c = vec3(h.t);
    } else {
        vec3 n = vec3(h.normal);
        vec3 l = frame.sun_dir.xyz;
        float ndl = max(dot(n, l), 0.0);
        float visible = 1.0;
        if (params.shadows != 0 && ndl > 0.0) {
            vec3 pos = o + d * h.t + n * 1e-3;
            visible = trace_any(pos, l, params.max_distance) ? 0.0 : 1.0;
        }
        vec3 albedo = material_albedo(h.block);
        if (params.textured != 0) {
            vec3 hp = o + d * h.t;
            float pixel_angle = 2.0 * length(frame.camera_up.xyz) / float(size.y);
            float lod = world_texture_lod(h.t, pixel_angle, abs(dot(n, d)));
            albedo = textureLod(atlas, world_atlas_uv(h.block, h.normal, world_face_uv(hp, h.normal)), lod).rgb;
        }
        c = albedo * (frame.sun_radiance.rgb * ndl * visible + frame.ambient.rgb) * params.exposure;
    }
    imageStore(color, p, vec4(c, 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
