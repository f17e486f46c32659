/* Test plugin whose input demands a size (scale 1 of the graph), so the
 * validator's size-mismatch check has something to catch. dst = src. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .scale = 1.0f,
     .help = "must be the graph's size"},
    {.name = "dst", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "copy of src"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "fixed_size.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "fixed_size",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: copy whose input must be full size",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
