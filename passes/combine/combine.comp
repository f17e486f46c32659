#version 460
// combine.c has the formulas; docs/lighting.md derives them.
#define FRAME_BINDING 1
#include "frame.glsl"
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_normal;
layout(binding = 2) uniform sampler2D in_visibility;
layout(binding = 3) uniform sampler2D in_ao;
layout(binding = 4) uniform sampler2D in_indirect;
layout(binding = 5, rgba16f) uniform writeonly image2D out_illumination;
layout(push_constant) uniform Params {
    float direct_scale, indirect_scale, ao_scale;
    int mode; // 0 physical, 1 thesis
    int has_visibility, has_ao, has_indirect;
} params;

const float PI = 3.14159265358979;

// Texel of an input under output pixel p (inputs may differ in size).
vec4 fetch(sampler2D s, ivec2 p, ivec2 size) { return texelFetch(s, vrg_pixel_in(p, size, textureSize(s, 0)), 0); }

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_illumination);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 n = fetch(in_normal, p, size).xyz;
    if (dot(n, n) < 0.25) { // sky: modulate passes albedo (the sky radiance) through
        imageStore(out_illumination, p, vec4(1.0));
        return;
    }
    n = normalize(n);
    float v = params.has_visibility != 0 ? clamp(fetch(in_visibility, p, size).r, 0.0, 1.0) : 1.0;
    float ao = params.has_ao != 0 ? clamp(fetch(in_ao, p, size).r, 0.0, 1.0) : 1.0;
    ao = 1.0 - params.ao_scale * (1.0 - ao);
    // reflected radiance of a white Lambertian surface lit by the sun (camera.h's units)
    vec3 sun = frame.sun_radiance.rgb * max(dot(n, frame.sun_dir.xyz), 0.0) * v;
    // cosine-weighted mean incoming radiance = irradiance / pi = what a white surface reflects
    vec3 indirect = params.has_indirect != 0 ? max(fetch(in_indirect, p, size).rgb, vec3(0.0))
                                             : frame.ambient.rgb * ao;
    vec3 l;
    if (params.mode == 0)
        l = params.direct_scale * sun + params.indirect_scale * indirect;
    else
        l = params.direct_scale * sun * ao / PI + 2.0 * params.indirect_scale * indirect;
    imageStore(out_illumination, p, vec4(l, 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
