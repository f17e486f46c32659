#version 450
// dst = src + add, every channel
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D dst;
layout(push_constant) uniform P { float add; } pc;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst))))
        return;
    // clamp: src may be smaller than dst (its size is not fixed by the slot)
    imageStore(dst, p, imageLoad(src, min(p, imageSize(src) - 1)) + vec4(pc.add));
}
