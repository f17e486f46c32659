#version 460
// exposure, a filmic curve (aces, reinhard, linear) and sRGB encoding into rgba8
// ldr = srgb_encode(curve(exposure x colour)), stored in an UNORM image (the
// PNG writer stores UNORM8 values as they are). Curves: aces (Narkowicz's
// fit of the ACES filmic curve, default), reinhard (x / (1 + x)) and linear
// (clamped).
#include "pixel.glsl"
#include "tonemap.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_color;
layout(binding = 1, rgba8) uniform writeonly image2D out_ldr;
layout(push_constant) uniform Params {
    float exposure; // @param default=1 min=0 max=1e6 help="multiplies the linear colour before the curve"
    int curve;      // @param choices=aces,reinhard,linear default=aces help="aces (Narkowicz's fit, default), reinhard or linear"
} params;

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_ldr);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_color, vrg_pixel_in(p, size, textureSize(in_color, 0)), 0).rgb;
    imageStore(out_ldr, p, vec4(tonemap_encode(c, params.exposure, params.curve), 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
