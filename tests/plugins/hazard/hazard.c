/* Test plugin that breaks the rules on purpose: it fills its output buffer
 * twice with no barrier between the writes. Synchronization validation must
 * report the write-after-write hazard; the test that uses it proves the
 * suite's validation is live and would catch a missing runtime barrier. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 4096,
     .help = "filled twice, unsynchronised"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    VkBuffer b = vrg_res_buffer(pass, vrg_pass_res(pass, "data"));
    vkCmdFillBuffer(cmd, b, 0, VK_WHOLE_SIZE, 1);
    vkCmdFillBuffer(cmd, b, 0, VK_WHOLE_SIZE, 2); /* no barrier: a WAW hazard */
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "hazard",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a deliberate write-after-write hazard for validation to catch",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
