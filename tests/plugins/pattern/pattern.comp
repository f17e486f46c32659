#version 450
// pixel (x, y) of a WxH image = (x/(W-1), y/(H-1), value, 1)
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D dst;
layout(push_constant) uniform P { float value; } pc;

void main()
{
    ivec2 size = imageSize(dst);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    // a 1-pixel-wide image would divide 0 by 0; its only column gets 0 instead
    vec2 last = max(vec2(size - 1), vec2(1.0));
    imageStore(dst, p, vec4(vec2(p) / last, pc.value, 1.0));
}
