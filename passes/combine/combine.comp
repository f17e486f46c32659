#version 460
// illumination L (radiance / albedo) from sun visibility, AO and indirect; mode physical or thesis
// The albedo-demodulated illumination L that the denoiser filters and
// modulate multiplies by albedo (final radiance = albedo x L), from sun
// visibility, ambient occlusion and one-bounce indirect light. Two formulas
// (docs/lighting.md derives them):
//   physical (default, Lambertian, in the units of voxrg/camera.h):
//     L = direct_scale * sun_radiance * max(N.L, 0) * V
//       + indirect_scale * indirect                      (indirect connected)
//       | ambient * AO                                   (else: sky stand-in)
//   thesis: colour = (2 L_I + L_D / pi) * A with AO multiplied into direct:
//     L = 2 * indirect_scale * (indirect | ambient * AO)
//       + direct_scale * sun_radiance * max(N.L, 0) * V * AO / pi
// AO strength: AO' = 1 - ao_scale * (1 - AO). Sky pixels (normal 0): L = 1,
// so modulate passes the sky radiance the G-buffer keeps in albedo.
// Each optional input is read in the variant compiled where it is
// connected (HAS_VISIBILITY, HAS_AO, HAS_INDIRECT).
#define FRAME_BINDING 1
#include "frame.glsl"
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_normal;
layout(binding = 2) uniform sampler2D in_visibility; // @optional help="sun visibility in [0, 1] (sun_shadow); unconnected: 1, no shadows"
layout(binding = 3) uniform sampler2D in_ao;         // @optional help="ambient visibility in [0, 1] (ao); unconnected: 1"
layout(binding = 4) uniform sampler2D in_indirect;   // @optional help="one-bounce irradiance / pi (indirect); unconnected: ambient * AO stands in"
layout(binding = 5, rgba16f) uniform writeonly image2D out_illumination;
layout(push_constant) uniform Params {
    float direct_scale;   // @param default=1 min=0 max=1000 help="multiplies the sun term"
    float indirect_scale; // @param default=1 min=0 max=1000 help="multiplies the indirect term (or its ambient stand-in)"
    float ao_scale;       // @param default=1 min=0 max=1 help="AO strength: AO' = 1 - ao_scale (1 - AO); 0 ignores AO"
    int mode;             // @param choices=physical,thesis default=physical help="physical (Lambertian, default) or thesis ((2 L_I + L_D/pi) A, AO on direct)"
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
#ifdef HAS_VISIBILITY
    float v = clamp(fetch(in_visibility, p, size).r, 0.0, 1.0);
#else
    float v = 1.0;
#endif
#ifdef HAS_AO
    float ao = clamp(fetch(in_ao, p, size).r, 0.0, 1.0);
#else
    float ao = 1.0;
#endif
    ao = 1.0 - params.ao_scale * (1.0 - ao);
    // reflected radiance of a white Lambertian surface lit by the sun (camera.h's units)
    vec3 sun = frame.sun_radiance.rgb * max(dot(n, frame.sun_dir.xyz), 0.0) * v;
    // cosine-weighted mean incoming radiance = irradiance / pi = what a white surface reflects
#ifdef HAS_INDIRECT
    vec3 indirect = max(fetch(in_indirect, p, size).rgb, vec3(0.0));
#else
    vec3 indirect = frame.ambient.rgb * ao;
#endif
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
