/* modulate: colour = albedo x illumination. Sky pixels keep the sky radiance
 * the G-buffer stores in albedo (combine writes illumination 1 there). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "albedo-demodulated illumination (combine, or a denoised copy)"},
    {.name = "albedo", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer albedo (sky radiance on a miss)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "linear radiance: albedo x illumination"},
};

/* every dispatch execute() records: checked by `voxrg check` */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "modulate.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_dispatch_desc d = dispatches[0];
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "modulate",
    .kind = VRG_PLUGIN_PASS,
    .help = "colour = albedo x illumination (sky passes through)",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
