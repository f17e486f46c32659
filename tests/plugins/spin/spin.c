/* Test plugin: a shader that runs until a parameter-controlled condition
 * holds. Each invocation counts up from 0 in its output texel until the
 * count equals `stop`: a stop the count reaches ends it, the default -1
 * never does (for GPU timeouts and interrupts). The output is src + count. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"stop", VRG_PARAM_FLOAT, -1.0, -1.0, 1e6, "the count that ends the loop; -1: never"},
};

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "added to the count"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R32G32B32A32_SFLOAT, .scale = 1.0f, .help = "src + stop (when it ends)"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    float stop = (float)vrg_param(pass, "stop");
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "spin.comp", .push = &stop, .push_size = sizeof stop});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "spin",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: loops until a count reaches stop (-1: forever)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
