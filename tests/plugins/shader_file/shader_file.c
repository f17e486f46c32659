/* Test plugin whose shader is found on $VOXRG_SHADER_PATH rather than next to
 * the plugin: tests point it at shaders they write (includes, compile errors). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "whatever user.comp writes"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "user.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "shader_file",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: runs user.comp from $VOXRG_SHADER_PATH over its output",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
