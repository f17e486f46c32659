#version 450
// voxrg run's display of a graph resource other than the output
// (core/cli/run.c): the resource, converted to rgba32f by a blit, mapped to
// something visible. Modes: 0 colour (linear -> sRGB), 1 normal (n/2 + 1/2),
// 2 depth (near bright, scale = far), 3 motion (hue = direction, brightness
// = pixels * scale), 4 scalar by scale (history length, variance in alpha
// when channel = 3), 5 position (fract, so block edges show).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src;
layout(binding = 1, rgba8) uniform writeonly image2D dst;
layout(push_constant) uniform P {
    int mode, channel;
    float scale;
    int linear_out; // the swapchain encodes to sRGB itself: write linear values
} pc;

vec3 srgb(vec3 c) { return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308))); }

vec3 linear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045))); }

vec3 hue(float h) { return clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0); }

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 v = texelFetch(src, p, 0);
    vec3 c;
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
        c = pc.linear_out != 0 ? v.rgb : srgb(clamp(v.rgb, 0.0, 1.0));
    if (pc.linear_out != 0 && pc.mode != 0)
        c = linear(c); // the mappings above are display values
    imageStore(dst, p, vec4(c, 1.0));
}
