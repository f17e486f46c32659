/* Test plugin for buffer resources: data[i] = i * mul for the 1024 uints of
 * a 4096-byte storage buffer. There is no image to size the dispatch, so the
 * group count is given: 1024 / 64 invocations per group. Its texel format
 * is rgba32ui: TEXEL_READ readers (texel_quads) see 256 texels of 4 uints. */
#include "voxrg/plugin.h"

#define FILL_COUNT 1024u
#define FILL_GROUP 64u /* local_size_x in fill_buffer.comp */

static const vrg_param_desc params[] = {
    {"mul", VRG_PARAM_INT, 3, 0, 1000, "data[i] = i * mul"},
};

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R32G32B32A32_UINT, .size = FILL_COUNT * 4, .help = "1024 uints, data[i] = i * mul"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    uint32_t mul = (uint32_t)vrg_param_int(pass, "mul");
    vrg_dispatch_desc d = {
        .shader = "fill_buffer.comp",
        .push = &mul,
        .push_size = sizeof mul,
        .groups_x = FILL_COUNT / FILL_GROUP,
    };
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "fill_buffer",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: buffer of 1024 uints, data[i] = i * mul",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
