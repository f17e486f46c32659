/* Test plugin: a gradient with a closed form, so every later test can
 * predict its input exactly: pixel (x, y) = (x/(W-1), y/(H-1), value, 1). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"value", VRG_PARAM_FLOAT, 0.5, 0.0, 1.0, "blue channel of every pixel"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "(x/(W-1), y/(H-1), value, 1)"},
};

/* listed: `voxrg check` compiles it (graphs/runtime-demo.ini uses this plugin) */
static const vrg_dispatch_desc dispatches[] = {{.shader = "pattern.comp", .push_size = sizeof(float)}};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    float value = (float)vrg_param(pass, "value");
    /* vrg_dispatch reports its own errors; nothing more to do here on failure */
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "pattern.comp", .push = &value, .push_size = sizeof value});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "pattern",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: UV gradient, blue = value",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
