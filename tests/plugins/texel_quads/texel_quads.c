/* Test plugin reading a buffer through a TEXEL_READ view of 16-byte texels:
 * image(x, y) = vec4(texel[(y*W + x) % 256]). The buffer's writer must name
 * the same texel format (fill_buffer does); one that names none (r32ui)
 * fails validation (tests/bad/texel_format_mismatch.ini). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .size = 4096, .help = "at least 256 texels of 4 uints"},
    {.name = "image", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R32G32B32A32_SFLOAT, .scale = 1.0f, .help = "vec4(texel[(y*W + x) % 256])"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "texel_quads.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "texel_quads",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: rgba32f image of a buffer read as rgba32ui texels",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
