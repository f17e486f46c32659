// Workgroups mapped to scattered screen tiles. lavapipe hands each CPU
// thread one contiguous block of a dispatch, so neighbouring (similarly
// expensive) tiles would land on one thread; a multiplicative permutation of
// the workgroup index spreads them out. The permutation is a bijection: the
// multiplier is a prime that does not divide the workgroup count.
#ifndef VOXRG_TILES_GLSL
#define VOXRG_TILES_GLSL

ivec2 tile_pixel()
{
    uint gx = gl_NumWorkGroups.x, total = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    uint g = gl_WorkGroupID.y * gx + gl_WorkGroupID.x;
    uint prime = 40503u;
    if (total % prime == 0u)
        prime = 65521u;
    // g * prime mod total without 64-bit integers (exact while total < 2^23)
    uint hi = (g * (prime >> 8u)) % total;
    uint r = (hi * 256u + g * (prime & 255u)) % total;
    return ivec2(r % gx, r / gx) * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy);
}
#endif
