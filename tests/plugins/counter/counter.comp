#version 450
// count = use_prev ? prev + step : step
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, r32f) uniform readonly image2D prev;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D count;
layout(push_constant) uniform P { float step; int use_prev; } pc;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(count))))
        return;
    float v = pc.step;
    // without history, prev may be a 1x1 stand-in or stale: never read it then
    if (pc.use_prev != 0)
        v += imageLoad(prev, p).r;
    imageStore(count, p, vec4(v, 0.0, 0.0, 1.0));
}
