/* Test scene plugin: writes (r, g, b, 1) into the first 16 bytes of a
 * persistent 256-byte buffer with a transfer, every frame. A scene runs
 * before every pass and is never culled, so scene_color can read it. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"r", VRG_PARAM_FLOAT, 0.25, 0.0, 1.0, "constants[0]"},
    {"g", VRG_PARAM_FLOAT, 0.5, 0.0, 1.0, "constants[1]"},
    {"b", VRG_PARAM_FLOAT, 0.75, 0.0, 1.0, "constants[2]"},
};

static const vrg_slot_desc slots[] = {
    {.name = "constants", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 256,
     .flags = VRG_SLOT_PERSISTENT, .help = "vec4(r, g, b, 1) at offset 0"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    float v[4] = {(float)vrg_param(pass, "r"), (float)vrg_param(pass, "g"), (float)vrg_param(pass, "b"), 1.0f};
    VkBuffer buf = vrg_res_buffer(pass, vrg_pass_res(pass, "constants"));
    /* the runtime has the slot in TRANSFER_DST already: no barrier of our own */
    vkCmdUpdateBuffer(cmd, buf, 0, sizeof v, v);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "test_scene",
    .kind = VRG_PLUGIN_SCENE,
    .help = "test: scene constants (r, g, b, 1)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
