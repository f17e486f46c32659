/* Test plugin: samples a mip-mapped atlas at explicit levels, so a test can
 * compare what the GPU sees with the generated texels. Pixel (x, level)
 * samples texel x of row 0 of that level (at its centre, textureLod). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "atlas", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED},
    {.name = "probe", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .width = 256, .height = 9}, /* VRG_ATLAS_SIZE x VRG_ATLAS_MIPS (voxrg/world.h) */
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "atlas_probe.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "atlas_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: atlas texels at every mip level",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
