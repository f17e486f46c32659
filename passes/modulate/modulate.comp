#version 460
// colour = albedo x (illumination + emission) (sky passes through)
// The reflected light and, where the G-buffer's emission is connected, the
// light emitted by the surface (radiance albedo x e, docs/world.md). Added
// here, after any denoiser, not in combine: it is exact, and a denoiser
// would blur it and keep it in its history. Sky pixels keep the sky
// radiance the G-buffer stores in albedo (combine writes illumination 1
// there, emission is 0).
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_albedo;
layout(binding = 2, rgba16f) uniform writeonly image2D out_color;
layout(binding = 3) uniform sampler2D in_emission; // @optional help="G-buffer emission: the emissive scale of the surface; unconnected: nothing emits"

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    // inputs may differ in size: nearest texel under the pixel
    vec3 l = texelFetch(in_illumination, vrg_pixel_in(p, size, textureSize(in_illumination, 0)), 0).rgb;
    vec3 a = texelFetch(in_albedo, vrg_pixel_in(p, size, textureSize(in_albedo, 0)), 0).rgb;
#ifdef HAS_EMISSION
    l += texelFetch(in_emission, vrg_pixel_in(p, size, textureSize(in_emission, 0)), 0).r;  // emits albedo x e
#endif
    imageStore(out_color, p, vec4(a * l, 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
