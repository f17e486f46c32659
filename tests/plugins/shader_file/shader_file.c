/* Test plugin whose shader is found on $VOXRG_SHADER_PATH rather than next to
 * the plugin: tests point it at shaders they write (includes, compile errors). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "whatever user.comp writes"},
};

static const vrg_param_desc params[] = {
    {"pixel_loop", VRG_PARAM_BOOL, 0, 0, 1, "dispatch user.comp as a pixel loop (pixel.glsl)"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "user.comp", .pixel_loop = vrg_param_int(pass, "pixel_loop")});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "shader_file",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: runs user.comp from $VOXRG_SHADER_PATH over its output",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
