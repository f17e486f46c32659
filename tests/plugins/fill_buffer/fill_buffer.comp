#version 450
// data[i] = i * mul
layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) writeonly buffer Data { uint data[]; };
layout(push_constant) uniform P { uint mul; } pc;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < uint(data.length()))
        data[i] = i * pc.mul;
}
