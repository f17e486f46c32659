#version 450
// color(x, y) = constants.color for every pixel
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform Constants { vec4 color; } constants;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D color;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(color))))
        return;
    imageStore(color, p, constants.color);
}
