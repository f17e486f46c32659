#version 450
// color = src + (0, 0, 0.25, 0) but one value NaN or +Inf; depth = x + y/1024;
// ids = (x, y * 65536 + 7)
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D color;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D depth;
layout(set = 0, binding = 3, rg32ui) uniform writeonly uimage2D ids;
layout(push_constant) uniform P { ivec2 poisoned; int channel; int inf; } pc;

void main()
{
    ivec2 size = imageSize(color);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 c = imageLoad(src, p) + vec4(0.0, 0.0, 0.25, 0.0);
    if (p == pc.poisoned)
        // from bits: a compiler may fold 0.0 / 0.0 or 1.0 / 0.0 into anything
        c[pc.channel] = uintBitsToFloat(pc.inf != 0 ? 0x7f800000u : 0x7fc00000u);
    imageStore(color, p, c);
    imageStore(depth, p, vec4(float(p.x) + float(p.y) / 1024.0));
    imageStore(ids, p, uvec4(uint(p.x), uint(p.y) * 65536u + 7u, 0u, 0u));
}
