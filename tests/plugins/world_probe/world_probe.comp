#version 450
#define WORLD_BINDING 0
#include "world.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, rg32ui) uniform writeonly uimage2D probes;
layout(push_constant) uniform Params { ivec4 lo; ivec4 extent; } params; // ivec4: std430 aligns ivec3 to 16 bytes

// PCG hash (the same in tests/voxel/world.c).
uint pcg(uint v)
{
    uint s = v * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

void main()
{
    ivec2 size = imageSize(probes);
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, size)))
        return;
    uint i = uint(px.y * size.x + px.x);
    ivec3 p = params.lo.xyz + ivec3(uvec3(pcg(3u * i), pcg(3u * i + 1u), pcg(3u * i + 2u)) % uvec3(params.extent.xyz));
    int base = world_chunk(p >> 4);
    uint flags = 0u;
    uint id = 0u;
    if (base >= 0) {
        ivec3 l = p & 15;
        id = world_block_local(base, l);
        flags = (world_voxel_solid(base, l) ? 1u : 0u) | (world_brick_solid(base, l >> 3) ? 2u : 0u) | 4u;
    }
    imageStore(probes, px, uvec4(id, flags, 0u, 0u));
}
