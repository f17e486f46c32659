#version 450
// Keeps the GPU busy for pc.stop iterations of one invocation, so that the
// host records the next frame before this frame's ring copy runs. The texel
// is volatile: the loop cannot be folded.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, r32f) uniform volatile coherent image2D color;
layout(push_constant) uniform P { float stop; } pc;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(color))))
        return;
    imageStore(color, p, vec4(0.0));
    if (p != ivec2(0))
        return;
    while (imageLoad(color, p).x < pc.stop)
        imageStore(color, p, imageLoad(color, p) + vec4(1.0));
}
