// The pixel an invocation shades, for a pass dispatched over an image with
//   layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
// (the runtime defines VRG_GROUP_X/Y per device: one SIMD row on a CPU
// device, 8x8 on a GPU; core/src/shader.c).
//
// Rows of workgroups are interleaved: dispatch row r shades screen row
// k + j*S, where row r is the j-th member of stride class k. lavapipe gives
// each of its threads one contiguous block of a dispatch's workgroups, so
// without this one thread gets the cheap sky at the top of the screen and
// the other the terrain below it; with it, every contiguous block of the
// dispatch covers the whole screen height. A bijection for any row count.
#ifndef VOXRG_PIXEL_GLSL
#define VOXRG_PIXEL_GLSL
const uint PIXEL_ROW_STRIDE = 16u;

// a / n and a % n through a float division fixed up by one step: exact for
// the sizes here, and a CPU device has no SIMD integer division (eight
// scalar divides per row of invocations cost a ray pass 20-30%).
uint pixel_div(uint a, uint n, out uint rem)
{
    // the bit trick of world_floor1: int(floor()) is scalar per lane on a CPU
    int q = floatBitsToInt(floor(float(a) / float(n)) + 12582912.0) - 0x4B400000;
    int r = int(a) - q * int(n);
    q += r >= int(n) ? 1 : (r < 0 ? -1 : 0);
    rem = uint(int(a) - q * int(n));
    return uint(q);
}

uint pixel_group_row(uint r, uint rows)
{
    uint S = PIXEL_ROW_STRIDE, B = rows / S, q = rows % S;  // S is a power of two
    uint k, j;
    if (r < q * (B + 1u)) {  // the first q classes hold B + 1 rows
        k = pixel_div(r, B + 1u, j);
    } else {                 // the rest hold B (B > 0 here)
        k = q + pixel_div(r - q * (B + 1u), max(B, 1u), j);
    }
    return j * S + k;
}

ivec2 vrg_pixel()
{
    uint row = pixel_group_row(gl_WorkGroupID.y, gl_NumWorkGroups.y);
    return ivec2(gl_GlobalInvocationID.x, row * gl_WorkGroupSize.y + gl_LocalInvocationID.y);
}
#endif
