/* Test plugin whose storage-buffer input names a texel format, which only
 * TEXEL_READ inputs (and outputs) may: the loader must refuse it, naming the
 * slot and its path. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_UINT},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)pass;
    (void)cmd;
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "bad_texel_format",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a texel format on a storage-buffer input",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
