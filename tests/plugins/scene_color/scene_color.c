/* Test plugin reading a uniform buffer: every pixel of color is the vec4 at
 * offset 0 of constants (test_scene puts (r, g, b, 1) there). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "constants", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .size = 16,
     .help = "a vec4 at offset 0"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "the vec4, everywhere"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "scene_color.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "scene_color",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: fills an image with a uniform-buffer colour",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
