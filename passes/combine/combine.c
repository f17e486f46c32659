/* combine: the albedo-demodulated illumination L that the denoiser filters
 * and modulate multiplies by albedo (final radiance = albedo x L), from sun
 * visibility, ambient occlusion and one-bounce indirect light. Two formulas
 * (docs/lighting.md):
 *   physical (default, Lambertian, in the units of voxrg/camera.h):
 *     L = direct_scale * sun_radiance * max(N.L, 0) * V
 *       + indirect_scale * indirect                      (indirect connected)
 *       | ambient * AO                                   (else: sky stand-in)
 *   thesis: colour = (2 L_I + L_D / pi) * A with AO multiplied into direct:
 *     L = 2 * indirect_scale * (indirect | ambient * AO)
 *       + direct_scale * sun_radiance * max(N.L, 0) * V * AO / pi
 * AO strength: AO' = 1 - ao_scale * (1 - AO). Sky pixels (normal 0): L = 1,
 * so modulate passes the sky radiance the G-buffer keeps in albedo. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"mode", VRG_PARAM_STRING, 0, 0, 0, "physical (Lambertian, default) or thesis ((2 L_I + L_D/pi) A, AO on direct)", 0, "physical"},
    {"direct_scale", VRG_PARAM_FLOAT, 1, 0, 1000, "multiplies the sun term"},
    {"indirect_scale", VRG_PARAM_FLOAT, 1, 0, 1000, "multiplies the indirect term (or its ambient stand-in)"},
    {"ao_scale", VRG_PARAM_FLOAT, 1, 0, 1, "AO strength: AO' = 1 - ao_scale (1 - AO); 0 ignores AO"},
};

static const vrg_slot_desc slots[] = {
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal; 0 on sky"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (sun, ambient)"},
    {.name = "visibility", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "sun visibility in [0, 1] (sun_shadow); unconnected: 1, no shadows"},
    {.name = "ao", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "ambient visibility in [0, 1] (ao); unconnected: 1"},
    {.name = "indirect", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "one-bounce irradiance / pi (indirect); unconnected: ambient * AO stands in"},
    {.name = "illumination", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "albedo-demodulated illumination L (radiance = albedo x L); 1 on sky"},
};

static const char *const modes[] = {"physical", "thesis"};

static int check(vrg_pass *pass) { return vrg_param_choice(pass, "mode", modes, 2) < 0 ? -1 : 0; }

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are the scales by name, the mode's index and which optional
 * inputs are connected */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "combine.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_push_int(pass, "mode", vrg_param_choice(pass, "mode", modes, 2));
    vrg_push_int(pass, "has_visibility", vrg_res_connected(vrg_pass_res(pass, "visibility")));
    vrg_push_int(pass, "has_ao", vrg_res_connected(vrg_pass_res(pass, "ao")));
    vrg_push_int(pass, "has_indirect", vrg_res_connected(vrg_pass_res(pass, "indirect")));
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "combine",
    .kind = VRG_PLUGIN_PASS,
    .help = "illumination L (radiance / albedo) from sun visibility, AO and indirect; mode physical or thesis",
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
