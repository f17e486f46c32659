/* Test plugin "ema": exponential moving average through history,
 * color = history valid ? mix(history, src, alpha) : src.
 * The input is "src", not "color": slots are looked up by name alone
 * (vrg_pass_res, bindings, in.X/out.X keys), so one plugin cannot have both
 * an in.color and an out.color. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"alpha", VRG_PARAM_FLOAT, 0.2, 0.0, 1.0, "weight of the new frame"},
};

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this frame"},
    {.name = "history", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .flags = VRG_SLOT_OPTIONAL, .help = "connect as RESULT@prev"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "the running average"},
};

typedef struct ema_push {
    float alpha;
    int32_t use_history;
} ema_push;

/* listed: `voxrg check` compiles it (graphs/runtime-demo.ini uses this plugin) */
static const vrg_dispatch_desc dispatches[] = {{.shader = "ema.comp", .push_size = sizeof(ema_push)}};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    /* the unconnected history is bound to a stand-in; use_history keeps the shader off it */
    int connected = vrg_res_connected(vrg_pass_res(pass, "history"));
    ema_push pc = {(float)vrg_param(pass, "alpha"), connected && vrg_res_history_valid(pass, vrg_pass_res(pass, "history"))};
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "ema.comp", .push = &pc, .push_size = sizeof pc});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "ema",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: temporal accumulation, mix(history, src, alpha)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
