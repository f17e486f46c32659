#version 460
// listed_probe's two steps (STEP=0, STEP=1), recorded by the runtime in order
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform image2D out_color;
layout(push_constant) uniform Params {
    int level; // the index of the parameter's value among its choices
} params;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_color))))
        return;
#if STEP == 0
    imageStore(out_color, p, vec4(0.5, 0.0, 0.0, 1.0));
#else
    imageStore(out_color, p, imageLoad(out_color, p) + vec4(0.0, 0.25 * float(params.level), 0.25, 0.0));
#endif
}
