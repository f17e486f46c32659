#version 450
// image(x, y) = float(data[(y*W + x) % 1024])
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std430) readonly buffer Data { uint data[]; };
layout(set = 0, binding = 1, r32f) uniform writeonly image2D image;

void main()
{
    ivec2 size = imageSize(image);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    uint i = (uint(p.y) * uint(size.x) + uint(p.x)) % 1024u;
    imageStore(image, p, vec4(float(data[i]), 0.0, 0.0, 1.0));
}
