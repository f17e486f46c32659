/* tonemap: ldr = srgb_encode(curve(exposure x colour)), stored in an UNORM
 * image (the PNG writer stores UNORM8 values as they are). Curves: aces
 * (Narkowicz's fit of the ACES filmic curve, default), reinhard (x / (1 + x))
 * and linear (clamped). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"exposure", VRG_PARAM_FLOAT, 1, 0, 1e6, "multiplies the linear colour before the curve"},
    {"curve", VRG_PARAM_STRING, 0, 0, 0, "aces (Narkowicz's fit, default), reinhard or linear", 0, "aces"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "linear radiance"},
    {.name = "ldr", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R8G8B8A8_UNORM, .help = "sRGB-encoded display values in an UNORM image"},
};

static const char *const curves[] = {"aces", "reinhard", "linear"};

static int check(vrg_pass *pass) { return vrg_param_choice(pass, "curve", curves, 3) < 0 ? -1 : 0; }

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are exposure by name and the curve's index */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "tonemap.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_push_int(pass, "curve", vrg_param_choice(pass, "curve", curves, 3));
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "tonemap",
    .kind = VRG_PLUGIN_PASS,
    .help = "exposure, a filmic curve (aces, reinhard, linear) and sRGB encoding into rgba8",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
    .check = check,
};

VRG_PLUGIN(desc)
