#version 450
// color = use_history ? mix(history, src, alpha) : src
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D history;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D color;
layout(push_constant) uniform P { float alpha; int use_history; } pc;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(color))))
        return;
    vec4 c = texelFetch(src, clamp(p, ivec2(0), textureSize(src, 0) - 1), 0);
    if (pc.use_history != 0)
        c = mix(imageLoad(history, p), c, pc.alpha);
    imageStore(color, p, c);
}
