/* A debug view of the voxel world: one primary ray per pixel through the
 * two-level DDA, shown as shaded albedo (with a hard sun shadow), normals,
 * block ids or distance. Enough to see a scene before the real passes. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"mode", VRG_PARAM_INT, 0, 0, 3, "0 shaded, 1 normals, 2 block ids, 3 distance"},
    {"shadows", VRG_PARAM_BOOL, 1, 0, 1, "trace a hard shadow ray toward the sun in mode 0"},
    {"exposure", VRG_PARAM_FLOAT, 0.35, 0, 100, "scale of the shaded radiance"},
    {"max_distance", VRG_PARAM_FLOAT, 512, 1, 4096, "ray length in blocks"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the scene's world (world.glsl reads 16-byte texels)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms"},
    {.name = "atlas", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "block textures; without them blocks show their mean albedo"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "the view"},
};

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are the parameters by name, and textured */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "world_debug.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_push_int(pass, "textured", vrg_res_connected(vrg_pass_res(pass, "atlas")));
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "world_debug",
    .kind = VRG_PLUGIN_PASS,
    .help = "debug view of the voxel world: primary rays, shaded (textured) albedo / normals / block ids / distance",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
