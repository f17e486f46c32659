/* bilateral_upsample: demodulated illumination computed on a low-resolution
 * G-buffer (gbuffer_downsample) brought back to the full G-buffer. Each
 * full-resolution pixel blends the 2x2 low-resolution texels around it with
 * bilinear weights, keeping only texels on its own surface: the same normal
 * and within `plane_tolerance` of its plane per block of distance between
 * the two points (voxel faces are planes, so this test is exact where
 * bilinear filtering would bleed light across a silhouette or a step).
 * Texel q is placed where its sample lies: gbuffer_downsample copies the
 * full-resolution pixel vrg_pixel_in() picks, a quarter texel past q's
 * centre at half size. Where none of the four qualifies (a thin feature no
 * low-resolution pixel hit) it takes the nearest of them in space that is
 * a hit, else the nearest hit of the 4x4 around them, else 1. With
 * surface_ring it first blends the texels of the 4x4's ring that are on
 * the pixel's surface, weighted 1 / (1 + t^2) by their offset t in texels
 * from the pixel: the same face a texel or two further off says more of
 * the pixel's light than the nearest texel of another face (in foliage
 * and at steps, where this happens most). With orientation_fallback a
 * pixel none of whose texels read is on its surface then blends, alike,
 * those that face its way on other planes: a 1-px face of a step seen
 * from afar gets the light of the step faces beside it, which face the
 * same sky and ground, not that of the floor in front. Both off by
 * default so that a graph keeps its images; the sweeps that turned them
 * on in interactive.ini's chain (tests/graphs/interactive-chain.ini) are
 * in docs/denoisers.md. Sky pixels get 1, the illumination combine writes
 * for sky (modulate passes the sky through).
 * mode = bilinear or nearest turn the surface test off, for comparison. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {.name = "mode", .type = VRG_PARAM_STRING, .default_string = "bilateral",
     .help = "bilateral (only texels on the pixel's surface), bilinear or nearest"},
    {.name = "plane_tolerance", .type = VRG_PARAM_FLOAT, .default_value = 0.1, .min = 0, .max = 1,
     .help = "a texel is on the pixel's plane when its offset from it is at most this per block of distance"},
    {.name = "surface_ring", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,
     .help = "1: where none of the 2x2 is on the pixel's surface, blend the texels of the 4x4's ring that are, before the nearest hit"},
    {.name = "orientation_fallback", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,
     .help = "1: where no texel read is on the pixel's surface, blend those facing its way on other planes, before the nearest hit"},
};

/* the names mode takes: the runtime checks the graph's value and pushes
 * its index as the shader's `mode` */
static const char *const param_choices[] = {"bilateral,bilinear,nearest", NULL, NULL, NULL};
_Static_assert(sizeof param_choices / sizeof param_choices[0] == sizeof params / sizeof params[0], "a choice list (or NULL) per parameter");

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "low-resolution illumination (any filter's output), the size of low_position"},
    {.name = "low_position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "the low-resolution G-buffer position it was computed on"},
    {.name = "low_normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "the low-resolution G-buffer normal"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "full-resolution G-buffer position"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "full-resolution G-buffer normal"},
    {.name = "illumination", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "illumination at the size of position (the graph's unless its [resource] section says otherwise)"},
};

/* the one dispatch execute() records (every slot, in order): checked by
 * `voxrg check`; its push constants are the parameters by name (mode as
 * its index in param_choices) */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "bilateral_upsample.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *low[] = {"low_position", "low_normal"}, *full[] = {"in.normal", "out.illumination"};
    if (vrg_pass_require_same_size(pass, "in.illumination", low, 2) != 0 || vrg_pass_require_same_size(pass, "in.position", full, 2) != 0)
        return;
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "bilateral_upsample",
    .kind = VRG_PLUGIN_PASS,
    .help = "low-resolution illumination to the full G-buffer: bilinear over the texels on each pixel's surface",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
    .param_choices = param_choices,
};

VRG_PLUGIN(desc)
