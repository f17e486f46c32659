/* Test plugin: src plus a closed-form term, with one poisoned value, for
 * the float dumps, `inspect` and --check-finite:
 *   color(x, y) = src(x, y) + (0, 0, 0.25, 0), except channel `channel` of
 *                 pixel (x, y) = (`x`, `y`), which is NaN (`value` 0) or
 *                 +Inf (1), or left alone with x = -1;
 *   depth(x, y) = x + y / 1024 (r32f), ids(x, y) = (x, y * 65536 + 7) (rg32ui:
 *                 integers no float holds exactly past 2^24). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"x", VRG_PARAM_INT, 5, -1, 16383, "column of the poisoned pixel; -1: none"},
    {"y", VRG_PARAM_INT, 3, 0, 16383, "row of the poisoned pixel"},
    {"channel", VRG_PARAM_INT, 2, 0, 3, "its poisoned channel"},
    {"value", VRG_PARAM_INT, 0, 0, 1, "0: NaN, 1: +Inf"},
};

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "any rgba16f image"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .scale = 1.0f, .help = "src + (0, 0, 0.25, 0), one value NaN or Inf"},
    {.name = "depth", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32_SFLOAT,
     .scale = 1.0f, .help = "x + y / 1024"},
    {.name = "ids", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_UINT,
     .scale = 1.0f, .help = "(x, y * 65536 + 7)"},
};

static const vrg_dispatch_desc dispatches[] = {{.shader = "nan_pixel.comp", .push_size = 4 * sizeof(int32_t)}};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    int32_t pc[4] = {vrg_param_int(pass, "x"), vrg_param_int(pass, "y"), vrg_param_int(pass, "channel"), vrg_param_int(pass, "value")};
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "nan_pixel.comp", .push = pc, .push_size = sizeof pc});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "nan_pixel",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: src + 0.25 blue with one NaN or Inf; a float and a uint image",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
