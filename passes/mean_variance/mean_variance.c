/* mean_variance: the luminance variance of the accumulated mean, the noise
 * the spatial filter has left to remove, stored with the colour (rgb,
 * variance in alpha; the interface of svgf_variance, so the two swap).
 *   var = (m2 - m1^2) / N
 * with m1, m2 the accumulated luminance moments and N the effective sample
 * count of the accumulation (clamped_reproject writes it in its colour's
 * alpha). svgf_variance's temporal mode gives m2 - m1^2 alone, the variance
 * of one sample: with N samples averaged that overstates the noise N
 * times, and a filter steered by it blurs across real edges. While the
 * history is young (length + 1 < min_history) the moments are averaged
 * over the size x size window's pixels of the same surface (normal dot >=
 * 0.9, within 0.1 blocks per pixel of offset from this pixel's plane): a
 * spatial estimate, still divided by N. Sky pixels get variance 0.
 * Debug output (optional, computed only when something reads it: the
 * VARIANCE variant): `variance`, r the variance (as in color's alpha), g 1
 * where it came from the pixel's own moments, 0 where from the window
 * (and on sky). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"size", VRG_PARAM_INT, 5, 3, 15, "window width (odd) of the spatial estimate for young history"},
    {"min_history", VRG_PARAM_INT, 4, 1, 100, "frames of history before the pixel's own moments are trusted"},
};

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "accumulated illumination, effective sample count in alpha (clamped_reproject color)"},
    {.name = "moments", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "accumulated luminance moments"},
    {.name = "length", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "history length"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "illumination with the variance of its mean luminance in alpha"},
    {.name = "variance", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "r: the variance (color's alpha); g: 1 where from the pixel's own moments, 0 from the window (written only when read)"},
};

static int check(vrg_pass *pass)
{
    if (vrg_param_int(pass, "size") % 2 == 0)
        return vrg_pass_error(pass, "size = %d: the window needs a centre, give an odd size", vrg_param_int(pass, "size"));
    return 0;
}

/* the dispatches execute() records: checked by `voxrg check`; their push
 * constants are min_history by name and the window's radius. The second,
 * with the variance output, instead of the first when that is read. Both
 * bind by the shader's binding names (the first leaves variance out). */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "mean_variance.comp", .pixel_loop = 1},
    {.shader = "mean_variance.comp", .defines = "VARIANCE", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *same[] = {"illumination", "moments", "length", "position", "normal"};
    if (vrg_pass_require_same_size(pass, "color", same, sizeof same / sizeof same[0]) != 0)
        return;
    vrg_push_int(pass, "radius", vrg_param_int(pass, "size") / 2);
    /* the unread debug output is a 1x1 stand-in: left out */
    (void)vrg_dispatch(pass, cmd, &dispatches[vrg_res_connected(vrg_pass_res(pass, "variance")) ? 1 : 0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "mean_variance",
    .kind = VRG_PLUGIN_PASS,
    .help = "variance of the accumulated mean: moments' variance / effective sample count, spatial while history is young",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
