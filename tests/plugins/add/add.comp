#version 450
// sum = a + (use_b ? b : 0); inputs read at the same pixel, clamped to their size
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D a;
layout(set = 0, binding = 1) uniform sampler2D b;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D sum;
layout(push_constant) uniform P { int use_b; } pc;

vec4 fetch(sampler2D s, ivec2 p)
{
    return texelFetch(s, clamp(p, ivec2(0), textureSize(s, 0) - 1), 0);
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(sum))))
        return;
    vec4 v = fetch(a, p);
    if (pc.use_b != 0)
        v += fetch(b, p);
    imageStore(sum, p, v);
}
