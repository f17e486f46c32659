#version 450
// dst(x,y) = average of the 3x3 neighbourhood of src, coordinates clamped
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D dst;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst))))
        return;
    // texelFetch, not texture(): the sampler's filter and address mode play no part
    ivec2 last = textureSize(src, 0) - 1;
    vec4 sum = vec4(0.0);
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            sum += texelFetch(src, clamp(p + ivec2(dx, dy), ivec2(0), last), 0);
    imageStore(dst, p, sum / 9.0);
}
