#version 460
// One full-resolution G-buffer pixel per low-resolution pixel (the one
// vrg_pixel_in picks, as the lighting passes do for a G-buffer of another
// size), its motion vector rescaled: gbuffer_downsample.c says why.
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0, rgba32f) uniform readonly image2D in_position;
layout(binding = 1, rgba16f) uniform readonly image2D in_normal;
layout(binding = 2, rg32ui) uniform readonly uimage2D in_ids;
layout(binding = 3, rg16f) uniform readonly image2D in_motion;
layout(binding = 4, rgba32f) uniform writeonly image2D out_position;
layout(binding = 5, rgba16f) uniform writeonly image2D out_normal;
layout(binding = 6, rg32ui) uniform writeonly uimage2D out_ids;
layout(binding = 7, rg16f) uniform writeonly image2D out_motion;
// The optional outputs some pass reads (gbuffer_downsample.c): an unread
// one is a 1x1 stand-in, neither it nor its input touched.
const uint WRITE_IDS = 1u, WRITE_MOTION = 2u;
layout(push_constant) uniform Params {
    int jitter;    // pick this frame's pixel of each footprint (offset)
    int offset[2]; // this frame's pixel within the footprint, from its top left
    uint writes;   // WRITE_* bits
} params;

// With jitter: this frame's pixel of p's footprint, the full-size pixels
// that vrg_pixel_in maps back to p (1 to ceil(full / size) a side, as the
// ratio falls), so that the pixel a texel sampled is one that
// vrg_pixel_in maps back to it (surface_cache's sparse insert looks for it
// there); where rounding puts the pick outside, vrg_pixel_in's own pixel.
ivec2 footprint_pixel(ivec2 p, ivec2 size, ivec2 full)
{
    vec2 ratio = vec2(full) / vec2(size);
    ivec2 lo = ivec2(ceil(vec2(p) * ratio - 0.5)), hi = ivec2(ceil(vec2(p + 1) * ratio - 0.5));
    ivec2 g = min(lo + ivec2(params.offset[0], params.offset[1]) % max(hi - lo, ivec2(1)), full - 1);
    return vrg_pixel_in(g, full, size) == p ? g : vrg_pixel_in(p, size, full);
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_position), full = imageSize(in_position);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 g = params.jitter != 0 ? footprint_pixel(p, size, full) : vrg_pixel_in(p, size, full);
    imageStore(out_position, p, imageLoad(in_position, g));
    imageStore(out_normal, p, imageLoad(in_normal, g));
    if ((params.writes & WRITE_IDS) != 0u)
        imageStore(out_ids, p, imageLoad(in_ids, g));
    // a point that moved m full-resolution pixels moved m * size / full of these
    if ((params.writes & WRITE_MOTION) != 0u)
        imageStore(out_motion, p, vec4(imageLoad(in_motion, g).xy * vec2(size) / vec2(full), 0.0, 0.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
