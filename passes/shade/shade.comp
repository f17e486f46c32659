#version 460
// combine (physical), modulate, haze and tonemap in one pass: the final colour from sun, indirect light and G-buffer
// The same image as the chain combine (mode physical, no AO) → modulate →
// haze → tonemap, up to the rounding of the chain's half-float images (at
// most 1 in 255: test shade_chain), in one pass. On a CPU device every
// full-size pass costs about as much again for its own set-up and images
// as for its arithmetic, and these four are a fifth of interactive.ini's
// frame on lavapipe: one pass takes under half of that (README.md).
// For AO or the thesis formula, use the chain.
#define FRAME_BINDING 1
#include "frame.glsl"
#include "pixel.glsl"
#include "haze.glsl"
#include "tonemap.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_normal;
layout(binding = 2) uniform sampler2D in_visibility; // @optional help="sun visibility in [0, 1] (sun_shadow, shadow_denoise); unconnected: 1, no shadows"
layout(binding = 3) uniform sampler2D in_indirect;   // @optional help="one-bounce irradiance / pi (indirect); unconnected: the sky's ambient stands in"
layout(binding = 4) uniform sampler2D in_albedo;
layout(binding = 5) uniform sampler2D in_emission;   // @optional help="G-buffer emission: the emissive scale of the surface; unconnected: nothing emits"
layout(binding = 6) uniform sampler2D in_position;
layout(binding = 7, rgba8) uniform writeonly image2D out_ldr;
layout(push_constant) uniform Params {
    float direct_scale;   // @param default=1 min=0 max=1000 help="multiplies the sun term (combine's)"
    float indirect_scale; // @param default=1 min=0 max=1000 help="multiplies the indirect term or its ambient stand-in (combine's)"
    float density;        // @param default=0.0015 min=0 max=1 help="aerial haze per block: a hit at distance d keeps exp(-density * d) of its colour (haze's)"
    float start;          // @param default=0.6 min=0 max=0.99 help="streamed worlds: fraction of the view radius where the edge haze begins (haze's)"
    float exposure;       // @param default=1 min=0 max=1e6 help="multiplies the linear colour before the curve (tonemap's)"
    int curve;            // @param choices=aces,reinhard,linear default=aces help="aces (Narkowicz's fit, default), reinhard or linear (tonemap's)"
} params;

// Texel of an input under output pixel p (inputs may differ in size).
vec4 fetch(sampler2D s, ivec2 p, ivec2 size) { return texelFetch(s, vrg_pixel_in(p, size, textureSize(s, 0)), 0); }

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_ldr);
    if (any(greaterThanEqual(p, size)))
        return;
    // combine's illumination: 1 on the sky, so that the albedo (the sky's radiance) passes
    vec3 n = fetch(in_normal, p, size).xyz, l = vec3(1.0);
    if (dot(n, n) >= 0.25) {
        n = normalize(n);
#ifdef HAS_VISIBILITY
        float v = clamp(fetch(in_visibility, p, size).r, 0.0, 1.0);
#else
        float v = 1.0;
#endif
#ifdef HAS_INDIRECT
        vec3 indirect = max(fetch(in_indirect, p, size).rgb, vec3(0.0));
#else
        vec3 indirect = frame.ambient.rgb;
#endif
        vec3 sun = frame.sun_radiance.rgb * max(dot(n, frame.sun_dir.xyz), 0.0) * v;
        l = params.direct_scale * sun + params.indirect_scale * indirect;
    }
    // modulate's colour
#ifdef HAS_EMISSION
    l += fetch(in_emission, p, size).r; // emits albedo x e
#endif
    vec3 c = fetch(in_albedo, p, size).rgb * l;
    c = haze_blend(c, fetch(in_position, p, size), p, size, params.density, params.start);
    imageStore(out_ldr, p, vec4(tonemap_encode(c, params.exposure, params.curve), 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
