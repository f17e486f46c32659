/* svgf_variance: the per-pixel luminance variance that steers the à-trous
 * filter, stored with the colour (rgb, variance in alpha).
 *   mode = spatial (the thesis): the sample variance of luminance over a
 *     size x size window (default 7), with Bessel's correction
 *     (sum (l - mean)^2 / (n - 1)), n the window's non-sky pixels; computed
 *     separably: a horizontal pass sums l, l^2 and n into an internal image,
 *     a vertical pass finishes.
 *   mode = temporal (the SVGF paper): m2 - m1^2 from the accumulated
 *     moments once the history holds min_history frames (length + 1 >=
 *     min_history, default 4); younger pixels use the moments averaged over
 *     the size x size window's pixels of the same surface (normal dot >=
 *     0.9 and within 0.1 blocks per pixel of offset from this pixel's
 *     plane), an edge-aware spatial estimate.
 * Sky pixels get variance 0.
 * Debug output (optional, computed only when something reads it: the
 * VARIANCE variants): `variance`, r the variance (as in color's alpha), g 1
 * where it came from the pixel's own accumulated moments (temporal mode,
 * history old enough), 0 where from a spatial window (and on sky). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"mode", VRG_PARAM_STRING, 0, 0, 0, "spatial (thesis: windowed variance) or temporal (SVGF paper: from moments)", 0, "spatial"},
    {"size", VRG_PARAM_INT, 7, 3, 15, "window width (odd)"},
    {"min_history", VRG_PARAM_INT, 4, 1, 100, "temporal: frames of history before the moments are trusted"},
};
/* the names mode takes (the runtime checks the graph's value;
 * vrg_param_choice(pass, "mode", NULL, 0) is its index) */
static const char *const param_choices[] = {"spatial,temporal", NULL, NULL};
_Static_assert(sizeof param_choices / sizeof param_choices[0] == sizeof params / sizeof params[0], "a choice list (or NULL) per parameter");

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "accumulated illumination (svgf_reproject color)"},
    {.name = "moments", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "temporal: accumulated luminance moments (svgf_reproject)"},
    {.name = "length", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "temporal: history length (svgf_reproject)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "illumination with its luminance variance in alpha"},
    {.name = "variance", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "r: the variance (color's alpha); g: 1 where from the pixel's own moments, 0 from a spatial window (written only when read)"},
};


static int check(vrg_pass *pass)
{
    int mode = vrg_param_choice(pass, "mode", NULL, 0);
    if (vrg_param_int(pass, "size") % 2 == 0)
        return vrg_pass_error(pass, "size = %d: the window needs a centre, give an odd size", vrg_param_int(pass, "size"));
    if (mode == 1 && (!vrg_res_connected(vrg_pass_res(pass, "moments")) || !vrg_res_connected(vrg_pass_res(pass, "length"))))
        return vrg_pass_error(pass, "mode = temporal reads the moments and the history length: connect in.moments and in.length");
    return 0;
}

static int create(vrg_pass *pass)
{
    /* spatial mode's row sums: l, l^2, non-sky count */
    return vrg_res_connected(vrg_pass_request_image(pass, "rows", VK_FORMAT_R32G32B32A32_SFLOAT, 1.0f, VRG_ACCESS_STORAGE_WRITE)) ? 0 : -1;
}

/* every dispatch execute() records, which `voxrg check` compiles: temporal
 * mode's one, spatial mode's rows and columns, and the two that write
 * color, again with the variance output (when it is read). Their push
 * constants: min_history by name and the window's radius. Each binds by
 * the shader's binding names: out_rows and in_rows are the internal rows,
 * written, then read (their access is the shader's writeonly, readonly). */
enum { TEMPORAL, ROWS, COLUMNS, TEMPORAL_VARIANCE, COLUMNS_VARIANCE };
static const vrg_dispatch_desc dispatches[] = {
    [TEMPORAL] = {.shader = "svgf_variance.comp", .defines = "TEMPORAL", .pixel_loop = 1},
    [ROWS] = {.shader = "svgf_variance.comp", .defines = "ROWS", .pixel_loop = 1, .domain = "rows"},
    [COLUMNS] = {.shader = "svgf_variance.comp", .defines = "COLUMNS", .pixel_loop = 1},
    [TEMPORAL_VARIANCE] = {.shader = "svgf_variance.comp", .defines = "TEMPORAL VARIANCE", .pixel_loop = 1},
    [COLUMNS_VARIANCE] = {.shader = "svgf_variance.comp", .defines = "COLUMNS VARIANCE", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *scratch[] = {"rows"};
    if (vrg_pass_require_same_size(pass, "color", scratch, 1) != 0)
        return;
    int mode = vrg_param_choice(pass, "mode", NULL, 0);
    int radius = vrg_param_int(pass, "size") / 2;
    /* the unread debug output is a 1x1 stand-in: left out */
    int debug = vrg_res_connected(vrg_pass_res(pass, "variance"));
    vrg_push_int(pass, "radius", radius);
    if (mode == 1) {
        (void)vrg_dispatch(pass, cmd, &dispatches[debug ? TEMPORAL_VARIANCE : TEMPORAL]);
    } else if (vrg_dispatch(pass, cmd, &dispatches[ROWS]) == 0) {
        vrg_push_int(pass, "radius", radius);
        (void)vrg_dispatch(pass, cmd, &dispatches[debug ? COLUMNS_VARIANCE : COLUMNS]);
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "svgf_variance",
    .kind = VRG_PLUGIN_PASS,
    .help = "luminance variance for the a-trous filter: spatial (thesis, 7x7 with Bessel) or temporal (SVGF moments)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
    .param_choices = param_choices,
};

VRG_PLUGIN(desc)
