/* Ambient occlusion: `rays` cosine-weighted rays per pixel in the hemisphere
 * around the face normal, each of length `radius` blocks, traced through the
 * world (DDA, or ray queries when the scene built a TLAS).
 *   ao = (rays that travel `radius` without a hit) / rays, in [0, 1]
 * With cosine-weighted directions (pdf cos/pi) this estimates the
 * cosine-weighted ambient visibility (1/pi) * integral of V(w) cos(w) dw over
 * the hemisphere: 1 on an open floor. Sky pixels (position.w == 0): 1, no
 * rays. Rays start at position + normal * 1e-3. stratified = 1 draws the
 * directions from random.glsl's stratified points (docs/lighting.md,
 * "Sampling"). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"rays", VRG_PARAM_INT, 4, 1, 64, "AO rays per pixel"},
    {"radius", VRG_PARAM_FLOAT, 4, 0.01, 1024, "AO ray length, blocks"},
    {"stratified", VRG_PARAM_BOOL, 0, 0, 1,
     "directions from a sequence that covers the hemisphere evenly over each 4x4 tile of pixels and over the frames (0: independent random numbers)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the scene's world (world.glsl reads 16-byte texels)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "gbuffer position: world hit point, w = 1 on a hit, 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "gbuffer normal: the face normal"},
    {.name = "ao", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .help = "ambient visibility, [0,1]; 1 on sky"},
    {.name = "tlas", .dir = VRG_IN, .kind = VRG_ACCEL, .access = VRG_ACCESS_RAY_QUERY, .flags = VRG_SLOT_OPTIONAL,
     .help = "the scene's TLAS: trace with ray queries (traversal = rayquery)"},
};

/* its one dispatch, checked by `voxrg check` and, with no execute, recorded
 * by the runtime; its push constants are the parameters, by name */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "ao.comp", .pixel_loop = 1},
};

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "ao",
    .kind = VRG_PLUGIN_PASS,
    .help = "ambient occlusion: fraction of cosine-weighted hemisphere rays that travel `radius` blocks unoccluded",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
