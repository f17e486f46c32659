/* Sun visibility: `rays` shadow rays per pixel toward points spread
 * uniformly over the sun's disc (a cone of half-angle sun_radius around
 * frame.sun_dir), traced through the world (DDA, or ray queries when the
 * scene built a TLAS). visibility = unoccluded rays / rays traced, in [0, 1].
 *   sky pixel (position.w == 0)            1, no rays
 *   sun at or below the horizon (y <= 0)   0, no rays
 *   face turned away (N.L <= 0)            0, no rays
 *   sun_radius == 0 (hard shadows)         one ray exactly along sun_dir,
 *                                          whatever `rays` says (they would
 *                                          all be the same ray)
 * A disc sample below the face's horizon (N.D <= 0) counts as occluded
 * without tracing. Rays start at position + normal * 1e-3. The disc points
 * come from the pixel's random stream, or with stratified = 1 from a
 * sequence that covers the disc evenly over 4x4 tiles and frames
 * (random.glsl's rng_pair; docs/lighting.md, "Sampling").
 * occluder (optional, computed only when something reads it): the mean
 * distance, blocks, from the ray origin to the first block hit, over the
 * traced rays that hit; -1 where none did (lit, sky, no rays traced). A
 * denoiser derives the penumbra's width from it (passes/shadow_denoise). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"rays", VRG_PARAM_INT, 4, 1, 64, "shadow rays per pixel (one when sun_radius is 0)"},
    {"sun_radius", VRG_PARAM_FLOAT, 0.27, 0, 45, "angular radius of the sun's disc, degrees (0.27: the real sun; 0: hard shadows)"},
    {"max_distance", VRG_PARAM_FLOAT, 256, 1, 16384, "shadow ray length, blocks"},
    {"stratified", VRG_PARAM_BOOL, 0, 0, 1,
     "points on the disc from a sequence that covers it evenly over each 4x4 tile of pixels and over the frames (0: independent random numbers)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the scene's world (world.glsl reads 16-byte texels)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "gbuffer position: world hit point, w = 1 on a hit, 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "gbuffer normal: the face normal"},
    {.name = "visibility", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .help = "fraction of the sun's disc seen, [0,1]; 1 on sky"},
    {.name = "occluder", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL, .help = "mean distance to the blocker over the rays that hit, blocks; -1 where none hit (written only when read)"},
    /* the acceleration structure stays last: an absent one is not bound */
    {.name = "tlas", .dir = VRG_IN, .kind = VRG_ACCEL, .access = VRG_ACCESS_RAY_QUERY, .flags = VRG_SLOT_OPTIONAL,
     .help = "the scene's TLAS: trace with ray queries (traversal = rayquery)"},
};

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are the parameters by name, the sun's radius in radians and
 * one ray for a point sun */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "sun_shadow.comp", .pixel_loop = 1},
    {.shader = "sun_shadow.comp", .defines = "OCCLUDER=1", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    float radians = (float)(vrg_param(pass, "sun_radius") * 3.14159265358979323846 / 180.0);
    vrg_push_float(pass, "sun_radians", radians);
    if (radians <= 0.0f)
        vrg_push_int(pass, "rays", 1);
    /* the unconnected output is a 1x1 stand-in: the shader neither writes
     * it nor finds the closest hit the distance needs */
    (void)vrg_dispatch(pass, cmd, &dispatches[vrg_res_connected(vrg_pass_res(pass, "occluder")) ? 1 : 0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "sun_shadow",
    .kind = VRG_PLUGIN_PASS,
    .help = "sun visibility: shadow rays toward the sun's disc (soft), or exactly toward the sun (sun_radius = 0)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
