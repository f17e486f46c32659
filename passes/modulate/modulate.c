/* modulate: colour = albedo x (illumination + emission): the reflected
 * light and, where the G-buffer's emission is connected, the light emitted
 * by the surface (radiance albedo x e, docs/world.md). Added here, after any
 * denoiser, not in combine: it is exact, and a denoiser would blur it and
 * keep it in its history. Sky pixels keep the sky radiance the G-buffer
 * stores in albedo (combine writes illumination 1 there, emission is 0). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "albedo-demodulated illumination (combine, or a denoised copy)"},
    {.name = "albedo", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer albedo (sky radiance on a miss)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "linear radiance: albedo x (illumination + emission)"},
    {.name = "emission", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "G-buffer emission: the emissive scale of the surface; unconnected: nothing emits"},
};

/* every dispatch execute() records: checked by `voxrg check` */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "modulate.comp", .pixel_loop = 1},
    {.shader = "modulate.comp", .defines = "EMISSION=1", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_dispatch_desc d = dispatches[vrg_res_connected(vrg_pass_res(pass, "emission")) ? 1 : 0];
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "modulate",
    .kind = VRG_PLUGIN_PASS,
    .help = "colour = albedo x (illumination + emission) (sky passes through)",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
