/* gbuffer_view: the G-buffer as a 2x2 mosaic at full size, each quadrant
 * showing its source at half resolution (nearest, every other pixel):
 *   top-left     normal * 0.5 + 0.5 (sky black)
 *   top-right    linear depth as 1 - depth / far (sky black)
 *   bottom-left  albedo, sRGB-encoded and clamped (sky: sky radiance)
 *   bottom-right motion: hue = direction, brightness = |motion| * motion_scale
 *                (still pixels black)
 * Written as display values into an UNORM image. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"far", VRG_PARAM_FLOAT, 256, 0.001, 1e6, "depth shown black (blocks)"},
    {"motion_scale", VRG_PARAM_FLOAT, 0.25, 0, 1e6, "brightness per pixel of motion"},
};

static const vrg_slot_desc slots[] = {
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "depth", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer linear depth"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "albedo", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer albedo"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer motion (pixels)"},
    {.name = "view", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R8G8B8A8_UNORM, .help = "mosaic: normal | depth / albedo | motion, display values"},
};

typedef struct gbuffer_view_push {
    float far_depth, motion_scale;
} gbuffer_view_push;

/* every dispatch execute() records: checked by `voxrg check` */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "gbuffer_view.comp", .push_size = sizeof(gbuffer_view_push), .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    gbuffer_view_push pc = {(float)vrg_param(pass, "far"), (float)vrg_param(pass, "motion_scale")};
    vrg_dispatch_desc d = dispatches[0];
    d.push = &pc;
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "gbuffer_view",
    .kind = VRG_PLUGIN_PASS,
    .help = "debug mosaic of the G-buffer: normals, depth, albedo, motion",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
