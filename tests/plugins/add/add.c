/* Test plugin with an optional input: sum = a + (b connected ? b : 0).
 * Exercises a pass with two readers of one resource in chain.ini. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "a", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "first term"},
    {.name = "b", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "second term; 0 when unconnected"},
    {.name = "sum", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "a + b"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    /* b is bound to a stand-in when unconnected; the flag keeps it out of the sum */
    int32_t use_b = vrg_res_connected(vrg_pass_res(pass, "b"));
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "add.comp", .push = &use_b, .push_size = sizeof use_b});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "add",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: sum = a + b",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
