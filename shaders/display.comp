#version 450
// voxrg run's display stage (core/cli/run.c): what the window shows, at the
// window's size. A is the graph's output or another of its resources, B (with
// --ab) the other graph's output from column `split` on; both were converted
// to rgba32f by a blit at their render size and are upscaled here (nearest or
// bilinear), then the overlay layer (RGBA8, window-sized, drawn on the CPU) is
// blended over them, so its text stays sharp at any render scale.
// A's modes: 0 colour (linear -> sRGB), 1 normal (n/2 + 1/2), 2 depth (near
// bright, scale = far), 3 motion (hue = direction, brightness = pixels *
// scale), 4 scalar by scale (history length, variance in alpha when channel =
// 3), 5 position (fract, so block edges show), 6 the output as it is (already
// what the swapchain takes).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src_a;
layout(binding = 1) uniform sampler2D src_b;
layout(binding = 2, rgba16f) uniform writeonly image2D dst;
layout(binding = 3, std430) readonly buffer Overlay { uint overlay[]; };
layout(push_constant) uniform P {
    int mode, channel;
    float scale;
    int linear_out; // the swapchain encodes to sRGB itself: write linear values
    int bilinear;
    int split;      // first column showing B (the width: no B)
    int overlay_on;
} pc;

vec3 srgb(vec3 c) { return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308))); }

vec3 linear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045))); }

vec3 hue(float h) { return clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0); }

// The source texel under window pixel p: the pixel centres map onto each
// other, so at equal sizes every texel is read as it is.
vec4 upscaled(sampler2D s, ivec2 p, ivec2 size)
{
    ivec2 src = textureSize(s, 0);
    vec2 at = (vec2(p) + 0.5) * vec2(src) / vec2(size) - 0.5;
    ivec2 hi = src - 1;
    if (pc.bilinear == 0)
        return texelFetch(s, clamp(ivec2(floor(at + 0.5)), ivec2(0), hi), 0);
    ivec2 i = ivec2(floor(at));
    vec2 f = at - vec2(i);
    vec4 a = texelFetch(s, clamp(i, ivec2(0), hi), 0), b = texelFetch(s, clamp(i + ivec2(1, 0), ivec2(0), hi), 0);
    vec4 c = texelFetch(s, clamp(i + ivec2(0, 1), ivec2(0), hi), 0), d = texelFetch(s, clamp(i + ivec2(1, 1), ivec2(0), hi), 0);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

vec3 visualised(vec4 v)
{
    vec3 c;
    if (pc.mode == 6)
        return v.rgb;
    if (pc.mode == 1)
        c = v.xyz * 0.5 + 0.5;
    else if (pc.mode == 2)
        c = vec3(v.x > 0.0 ? clamp(1.0 - v.x / pc.scale, 0.0, 1.0) : 0.0);
    else if (pc.mode == 3)
        c = hue(atan(v.y, v.x) / 6.2831853 + 0.5) * clamp(length(v.xy) * pc.scale, 0.0, 1.0);
    else if (pc.mode == 4)
        c = vec3(clamp(v[pc.channel] * pc.scale, 0.0, 1.0));
    else if (pc.mode == 5)
        c = v.w == 0.0 ? vec3(0.0) : fract(v.xyz);
    else
        return pc.linear_out != 0 ? v.rgb : srgb(clamp(v.rgb, 0.0, 1.0));
    return pc.linear_out != 0 ? linear(c) : c; // the mappings above are display values
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = p.x < pc.split ? visualised(upscaled(src_a, p, size)) : upscaled(src_b, p, size).rgb;
    if (pc.overlay_on != 0) {
        vec4 o = unpackUnorm4x8(overlay[p.y * size.x + p.x]);
        c = mix(c, pc.linear_out != 0 ? linear(o.rgb) : o.rgb, o.a);
    }
    imageStore(dst, p, vec4(c, 1.0));
}
