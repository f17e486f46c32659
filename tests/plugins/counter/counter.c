/* Test plugin for history (@prev): count = prev + step when last frame's
 * value exists, else step. After N frames from a fresh start the value is
 * N * step; a resize, reload or reset_history restarts it at step. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"step", VRG_PARAM_FLOAT, 1.0, -1000.0, 1000.0, "added every frame"},
    {"always_read", VRG_PARAM_BOOL, 0, 0, 1, "read prev even when history is invalid (tests that it was cleared to 0)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "prev", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ,
     .format = VK_FORMAT_R32_SFLOAT, .flags = VRG_SLOT_OPTIONAL, .help = "connect as count@prev"},
    {.name = "count", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R32_SFLOAT, .scale = 1.0f, .help = "frames counted, times step"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    /* An unconnected optional slot is still bound (to a 1x1 stand-in), so
     * the shader is told through use_prev whether to read it at all. */
    int connected = vrg_res_connected(vrg_pass_res(pass, "prev"));
    struct {
        float step;
        int32_t use_prev;
    } pc = {(float)vrg_param(pass, "step"), connected && (vrg_res_history_valid(pass, vrg_pass_res(pass, "prev")) || vrg_param_int(pass, "always_read"))};
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "counter.comp", .push = &pc, .push_size = sizeof pc});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "counter",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: counts frames through its own history",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
