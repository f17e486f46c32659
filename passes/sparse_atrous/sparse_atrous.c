/* sparse_atrous: a cheaper edge-avoiding à-trous filter for accumulated
 * illumination. Iteration i = 0 .. iterations-1 takes the 3x3 taps 2^i
 * pixels apart (weights 1/4 1/2 1/4 per axis): 9 fetches a pixel instead
 * of svgf_atrous's 25, and with the default 4 iterations 36 instead of the
 * thesis's 175 (7 iterations of 5x5). A tap q of pixel p weighs
 *   h(q) * w_z * w_l, with taps on another face (normal axis) or the sky 0
 *   w_z = exp(-|N_p . (X_q - X_p)| / (sigma_z * |p - q| * footprint + eps))
 *   w_l = exp(-|l_p - l_q| / (sigma_l * sqrt(var_p) + eps))
 * var_p the variance of p's mean luminance (mean_variance): it shrinks as
 * history grows, so the filter weakens where the accumulation has already
 * removed the noise and stays strong where history is short. var_p is the
 * pixel's own (svgf_atrous prefilters it over 3x3: 9 more fetches a tap
 * pixel); the variance of the mean is already an average over its samples.
 * History length decides how far a pixel is filtered too: a pixel whose
 * history holds long_history frames or more (in.length; unconnected: no
 * pixel counts as long) takes only the first long_iterations iterations and
 * is copied through the rest; one whose variance is below skip_variance is
 * copied (0: never). The variance is filtered with the squared weights.
 * A first dispatch packs colour and variance (halves), N . X, the normal
 * axis and the history length into one rgba32ui texel: a tap is one fetch.
 * feedback = k writes iteration k's output (0: the input) to `feedback`,
 * the history the temporal pass reads next frame. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"iterations", VRG_PARAM_INT, 4, 1, 10, "filter iterations; step 2^i"},
    {"sigma_z", VRG_PARAM_FLOAT, 1, 0.001, 1000, "position (plane) edge-stopping"},
    {"sigma_l", VRG_PARAM_FLOAT, 4, 0.001, 1000, "luminance edge-stopping, in standard deviations of the mean"},
    {"skip_variance", VRG_PARAM_FLOAT, 0, 0, 1e6, "copy pixels whose variance is below this (0: filter all)"},
    {"long_history", VRG_PARAM_INT, 0, 0, 255, "history length (frames) from which a pixel takes only long_iterations (0: off)"},
    {"long_iterations", VRG_PARAM_INT, 2, 0, 10, "iterations a pixel with a long history takes"},
    {"feedback", VRG_PARAM_INT, 1, 0, 10, "iteration whose output becomes next frame's history (0: the input)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "illumination with its luminance variance in alpha (mean_variance)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "length", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "history length (clamped_reproject); needed by long_history"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (camera)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "filtered illumination (variance in alpha)"},
    {.name = "feedback", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "the iteration `feedback` output: connect the temporal pass's history to feedback@prev"},
};

static int check(vrg_pass *pass)
{
    int it = vrg_param_int(pass, "iterations"), fb = vrg_param_int(pass, "feedback");
    if (fb > it)
        return vrg_pass_error(pass, "feedback = %d: there are only %d iterations", fb, it);
    if (vrg_param_int(pass, "long_history") > 0 && !vrg_res_connected(vrg_pass_res(pass, "length")))
        return vrg_pass_error(pass, "long_history = %d reads the history length: connect in.length", vrg_param_int(pass, "long_history"));
    return 0;
}

static int create(vrg_pass *pass)
{
    /* the packed texels the iterations read and write (sparse_atrous.comp) */
    const char *names[] = {"ping", "pong"};
    for (int i = 0; i < 2; i++)
        if (!vrg_res_connected(vrg_pass_request_image(pass, names[i], VK_FORMAT_R32G32B32A32_UINT, 1.0f, VRG_ACCESS_STORAGE_WRITE)))
            return -1;
    return 0;
}

/* Every dispatch execute() records, which `voxrg check` compiles. The
 * iterations run pong -> ping -> pong ... -> color, so iteration i reads
 * pong when i is even and ping when odd: a pair's entry i & 1 is the one
 * for iteration i, and its copy to feedback reads that iteration's
 * destination. Which image an iteration or copy reads (in_src) and writes
 * (out_dst) is what their bindings[] say, the rest of each list is the
 * shader's order; each binding's access is the shader's (readonly,
 * writeonly, a sampler). The packs bind by the shader's names
 * (out_pong is the internal pong). The iterations' push constants:
 * sigma_z, sigma_l and skip_variance by name, step and long_history
 * (which turns on per iteration). */
enum {
    COPY_INPUT,
    COPY_COLOR,
    COPY_PACKED, /* + (i & 1): after iteration i wrote ping, pong */
    PACK = COPY_PACKED + 2,
    PACK_LENGTH,
    FILTER_PACKED, /* + (i & 1): pong -> ping, ping -> pong */
    FILTER_LAST = FILTER_PACKED + 2, /* + (i & 1): pong, ping -> color */
};
#define COPY_FROM(defs, src)                                                                                                                     \
    {.shader = "sparse_atrous.comp", .defines = defs, .pixel_loop = 1, .domain = "feedback", .bindings = {{src}, {"feedback"}}}
#define ITERATION(defs, src, dst)                                                                                                                \
    {.shader = "sparse_atrous.comp", .defines = defs, .pixel_loop = 1, .domain = dst, .bindings = {{src}, {"position"}, {"frame"}, {dst}}}
static const vrg_dispatch_desc dispatches[] = {
    [COPY_INPUT] = COPY_FROM("COPY", "illumination"),
    [COPY_COLOR] = COPY_FROM("COPY", "color"),
    [COPY_PACKED] = COPY_FROM("COPY FROM_PACKED", "ping"),
    [COPY_PACKED + 1] = COPY_FROM("COPY FROM_PACKED", "pong"),
    [PACK] = {.shader = "sparse_atrous.comp", .defines = "PACK", .pixel_loop = 1, .domain = "pong"},
    [PACK_LENGTH] = {.shader = "sparse_atrous.comp", .defines = "PACK WITH_LENGTH", .pixel_loop = 1, .domain = "pong"},
    [FILTER_PACKED] = ITERATION("FILTER TO_PACKED", "pong", "ping"),
    [FILTER_PACKED + 1] = ITERATION("FILTER TO_PACKED", "ping", "pong"),
    [FILTER_LAST] = ITERATION("FILTER", "pong", "color"),
    [FILTER_LAST + 1] = ITERATION("FILTER", "ping", "color"),
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *same[] = {"illumination", "position", "normal", "ping", "pong"};
    if (vrg_pass_require_same_size(pass, "color", same, 5) != 0)
        return;
    int n = vrg_param_int(pass, "iterations"), fb = vrg_param_int(pass, "feedback");
    int long_history = vrg_param_int(pass, "long_history");
    if (fb == 0 && vrg_dispatch(pass, cmd, &dispatches[COPY_INPUT]) != 0)
        return;
    if (vrg_dispatch(pass, cmd, &dispatches[vrg_res_connected(vrg_pass_res(pass, "length")) ? PACK_LENGTH : PACK]) != 0)
        return;
    for (int i = 0; i < n; i++) {
        int last = i == n - 1;
        vrg_push_int(pass, "step", 1 << i);
        /* from this iteration on, long-history pixels are copied through */
        vrg_push_int(pass, "long_history", long_history > 0 && i >= vrg_param_int(pass, "long_iterations") ? long_history : 0);
        if (vrg_dispatch(pass, cmd, &dispatches[(last ? FILTER_LAST : FILTER_PACKED) + (i & 1)]) != 0)
            return;
        if (i + 1 == fb && vrg_dispatch(pass, cmd, &dispatches[last ? COPY_COLOR : COPY_PACKED + (i & 1)]) != 0)
            return;
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "sparse_atrous",
    .kind = VRG_PLUGIN_PASS,
    .help = "cheaper a-trous: 3x3 taps with step doubling, steered by the variance of the mean and the history length",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
