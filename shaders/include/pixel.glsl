// Which pixels an invocation shades, for a pass dispatched over an image
// with vrg_dispatch_desc.pixel_loop = 1 and
//   layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
//   void shade(ivec2 p) { ... }
//   void main() { for (uint k = 0u; k < VRG_PIXEL_ROWS; k++) shade(vrg_pixel(k)); }
// The runtime defines VRG_GROUP_X/Y, VRG_TILE_W/H and VRG_PIXEL_ROWS per
// device (core/runtime/src/context.c): on a CPU device a group is one SIMD row of
// invocations (8x1) shading a 4x2 tile of pixels, VRG_PIXEL_ROWS tiles per
// invocation; on a GPU 8x8 groups, 8x8 tiles, one pixel per invocation.
//
// Why a loop: lavapipe runs every SIMD row of invocations as a coroutine with
// its own allocation and set-up, which cost more than a simple pass's work;
// shading several pixels per invocation made such passes much faster
// (docs/benchmarks.md).
// Why tiles: the lanes of a SIMD row run in lockstep, and a ray loop runs
// until its slowest lane is done; the rays of a 4x2 tile are more alike than
// those of 8 pixels in a row, so fewer lanes idle (docs/benchmarks.md).
// Why these rows: the dispatch covers Q rows of tiles and invocation row q
// shades tile rows q, q + Q, q + 2Q, ... lavapipe gives each of its threads
// one contiguous block of a dispatch's workgroups, so with plain rows one
// thread would get the cheap sky at the top of the screen and the other the
// terrain; this way every block of the dispatch samples the whole height.
// The loop may run past the image: shade() checks the bounds. The runtime
// refuses a pixel loop whose local size is not VRG_GROUP_X x VRG_GROUP_Y.
#ifndef VOXRG_PIXEL_GLSL
#define VOXRG_PIXEL_GLSL
#include "ifloor.glsl"
ivec2 vrg_pixel(uint k)
{
    uint i = gl_LocalInvocationIndex;
    uint tile_row = gl_WorkGroupID.y + k * gl_NumWorkGroups.y;
    return ivec2(gl_WorkGroupID.x * VRG_TILE_W + i % VRG_TILE_W, tile_row * VRG_TILE_H + i / VRG_TILE_W);
}

// The pixel under pixel p's centre in an input of size src, for an output of
// size dst: p itself when the sizes match, else the nearest (a pass may run
// at a lower or higher resolution than its inputs: [resource] scale). Float
// maths and ifloor: integer division and int(float) are scalar per lane on
// a CPU device.
ivec2 vrg_pixel_in(ivec2 p, ivec2 dst, ivec2 src)
{
    return clamp(ifloor((vec2(p) + 0.5) * vec2(src) / vec2(dst)), ivec2(0), src - 1);
}

// Where the src pixel vrg_pixel_in picks for dst pixel q has its centre,
// in dst pixels past q's own centre (exact when src / dst is a whole
// number; a quarter pixel at half size): an upsampler that reads back
// values computed at vrg_pixel_in's pixels places them there.
vec2 vrg_pixel_in_offset(ivec2 dst, ivec2 src)
{
    vec2 ratio = vec2(src) / vec2(dst);
    return (floor(0.5 * ratio) + 0.5) / ratio - 0.5;
}
#endif
