#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D atlas;
layout(binding = 1, rgba32f) uniform writeonly image2D probe;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(probe))))
        return;
    int level = p.y;
    ivec2 size = textureSize(atlas, level);
    if (p.x >= size.x) {
        imageStore(probe, p, vec4(-1.0));
        return;
    }
    vec2 uv = (vec2(p.x, 0) + 0.5) / vec2(size);
    imageStore(probe, p, textureLod(atlas, uv, float(level)));
}
