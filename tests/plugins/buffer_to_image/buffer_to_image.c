/* Test plugin reading a storage buffer into an image, so buffer contents can
 * be checked through an ordinary image readback too:
 * image(x, y) = float(data[(y*W + x) % 1024]). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_READ, .size = 4096,
     .help = "at least 1024 uints"},
    {.name = "image", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R32_SFLOAT, .scale = 1.0f, .help = "float(data[(y*W + x) % 1024])"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "buffer_to_image.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "buffer_to_image",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: r32f image of a uint buffer",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
