/* haze: distance haze toward the sky's colour along each pixel's ray, so
 * that the edge of a streamed world and the void below the horizon beyond
 * it do not show. Runs on the final linear colour (after denoising: the
 * haze is smooth and needs no filtering). haze.comp has the formula. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {.name = "density", .type = VRG_PARAM_FLOAT, .default_value = 0.0015, .min = 0, .max = 1,
     .help = "aerial haze per block: a hit at distance d keeps exp(-density * d) of its colour"},
    {.name = "start", .type = VRG_PARAM_FLOAT, .default_value = 0.6, .min = 0, .max = 0.99,
     .help = "streamed worlds: fraction of the view radius where the edge haze begins (full haze at the radius)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "linear radiance (modulate)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position (w = 1 on a hit)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM,
     .help = "the scene's per-frame uniforms (camera, sky, view radius)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "linear radiance with haze"},
};

typedef struct haze_push {
    float density, start;
} haze_push;

/* every dispatch execute() records: checked by `voxrg check` */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "haze.comp", .push_size = sizeof(haze_push), .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    haze_push pc = {(float)vrg_param(pass, "density"), (float)vrg_param(pass, "start")};
    vrg_dispatch_desc d = dispatches[0];
    d.push = &pc;
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "haze",
    .kind = VRG_PLUGIN_PASS,
    .help = "distance haze toward the sky colour: hides a streamed world's edge and the void below the horizon",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
