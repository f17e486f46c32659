/* Test plugin: reads one image sampled and another as a storage image, so a
 * graph binding the same resource to both must be refused (one descriptor
 * cannot see two layouts). dst = src + aux. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "sampled term"},
    {.name = "aux", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "storage-read term"},
    {.name = "dst", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "src + aux"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "mixed_reads.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "mixed_reads",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: dst = src (sampled) + aux (storage read)",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
