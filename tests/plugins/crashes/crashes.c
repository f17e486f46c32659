/* Test plugin with a bug: from frame `at_frame` on, execute writes to an
 * unmapped address. The runtime must say which pass and plugin died, in which
 * callback, before the process ends of the signal. */
#include <stdint.h>
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"at_frame", VRG_PARAM_INT, 1, 0, 1000, "the first frame whose execute crashes"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_TRANSFER_DST, .format = VK_FORMAT_R8G8B8A8_UNORM},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)cmd;
    if (vrg_pass_frame(pass)->frame_index >= (uint64_t)vrg_param_int(pass, "at_frame")) {
        /* a volatile store to an unmapped address: no compiler may drop it */
        volatile uintptr_t nowhere = 16;
        *(volatile int *)nowhere = 1;
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "crashes",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: crashes in execute from frame at_frame on",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
