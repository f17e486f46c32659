#version 450
// Counts in the output texel until the count equals pc.stop. The texel is
// volatile, so every iteration stores and loads it again: the compiler can
// neither fold the loop nor prove that it ends.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba32f) uniform volatile coherent image2D color;
layout(push_constant) uniform P { float stop; } pc;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(color))))
        return;
    imageStore(color, p, vec4(0.0));
    while (imageLoad(color, p).x != pc.stop)
        imageStore(color, p, imageLoad(color, p) + vec4(1.0));
    imageStore(color, p, texelFetch(src, p, 0) + imageLoad(color, p));
}
