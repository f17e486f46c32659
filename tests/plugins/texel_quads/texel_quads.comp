#version 450
// image(x, y) = vec4(texel[(y*W + x) % 256]), texels of 4 uints
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform usamplerBuffer data;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D image;

void main()
{
    ivec2 size = imageSize(image);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    int i = (p.y * size.x + p.x) % 256;
    imageStore(image, p, vec4(texelFetch(data, i)));
}
