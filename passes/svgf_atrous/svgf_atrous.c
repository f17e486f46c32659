/* svgf_atrous: the edge-avoiding à-trous wavelet filter of SVGF (Schied et
 * al. 2017), one dispatch per iteration i = 0 .. iterations-1 with taps 2^i
 * pixels apart, through two runtime-owned images (so they alias with every
 * other transient). Input: illumination with its luminance variance in
 * alpha (svgf_variance). A tap q of pixel p weighs
 *   h(q) * w_z * w_n * w_l
 *   h:   B3 spline (5x5: 1/16 1/4 3/8 1/4 1/16) or 3x3 (1/4 1/2 1/4)
 *   w_z = exp(-|N_p . (X_q - X_p)| / (sigma_z * |p - q| * footprint + eps))
 *         the distance of q's point from p's plane against what one pixel
 *         step at p's distance spans (the paper's depth-gradient test, in
 *         world positions: exact planes in a voxel world)
 *   w_n = max(0, N_p . N_q)^sigma_n
 *   w_l = exp(-|l_p - l_q| / (sigma_l * sqrt(g3x3(variance)_p) + eps))
 * A voxel G-buffer's normals are unit axis vectors, so w_n is 1 for taps on
 * faces with p's normal and 0 otherwise, whatever sigma_n > 0; and for those
 * N_p . (X_q - X_p) = d_q - d_p with d = N . X. A first dispatch packs each
 * pixel's colour and variance (as halves), normal axis and d into one
 * rgba32ui texel, and the iterations pass that on, so a tap is one fetch,
 * not three (position, normal, colour): the filter is bound by fetches on a
 * CPU device.
 * The variance is filtered with the squared weights. Pixels whose variance
 * is below skip_variance (the thesis's threshold; 0: never) are copied
 * unfiltered, as are sky pixels. feedback = k writes iteration k's output
 * (0: the unfiltered input) to `feedback`, the history svgf_reproject reads
 * next frame (the paper: 1). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"iterations", VRG_PARAM_INT, 5, 1, 10, "filter iterations (thesis 7, paper 5); step 2^i"},
    {"kernel", VRG_PARAM_INT, 5, 3, 5, "3 (3x3) or 5 (5x5 B3 spline)"},
    {"sigma_z", VRG_PARAM_FLOAT, 1, 0.001, 1000, "position (plane) edge-stopping"},
    {"sigma_n", VRG_PARAM_FLOAT, 128, 0.001, 1024, "normal edge-stopping exponent (voxel normals: any value > 0 separates faces)"},
    {"sigma_l", VRG_PARAM_FLOAT, 4, 0.001, 1000, "luminance edge-stopping, in prefiltered standard deviations"},
    {"skip_variance", VRG_PARAM_FLOAT, 0, 0, 1e6, "copy pixels whose variance is below this (0: filter all)"},
    {"feedback", VRG_PARAM_INT, 1, 0, 10, "iteration whose output becomes next frame's history (0: the input)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "illumination with its luminance variance in alpha (svgf_variance)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (camera)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "filtered illumination (variance in alpha)"},
    {.name = "feedback", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "the iteration `feedback` output: connect svgf_reproject's history to feedback@prev"},
};

static int check(vrg_pass *pass)
{
    int k = vrg_param_int(pass, "kernel"), it = vrg_param_int(pass, "iterations"), fb = vrg_param_int(pass, "feedback");
    if (k != 3 && k != 5)
        return vrg_pass_error(pass, "kernel = %d: expected 3 or 5", k);
    if (fb > it)
        return vrg_pass_error(pass, "feedback = %d: there are only %d iterations", fb, it);
    return 0;
}

static int create(vrg_pass *pass)
{
    /* the packed texels the iterations read and write (svgf_atrous.comp) */
    const char *names[] = {"ping", "pong"};
    for (int i = 0; i < 2; i++)
        if (!vrg_res_connected(vrg_pass_request_image(pass, names[i], VK_FORMAT_R32G32B32A32_UINT, 1.0f, VRG_ACCESS_STORAGE_WRITE)))
            return -1;
    return 0;
}

/* Every dispatch execute() records, which `voxrg check` compiles: the
 * feedback copies, the pack, and the iterations by kernel radius, source
 * and destination (the last one unpacks into color). The iterations run
 * pong -> ping -> pong ... -> color, so iteration i reads pong when i is
 * even and ping when odd: a pair's entry i & 1 is the one for iteration i,
 * and its copy to feedback reads that iteration's destination. Which image
 * an iteration or copy reads (in_src) and writes (out_dst) is what their
 * bindings[] say, the rest of each list is the shader's order; each
 * binding's access is the shader's (readonly, writeonly, a sampler). The
 * pack binds by the shader's names (out_pong is the internal pong). The
 * iterations' push constants: the sigmas and skip_variance by name, and
 * step. */
enum {
    COPY_INPUT,
    COPY_COLOR,
    COPY_PACKED, /* + (i & 1): after iteration i wrote ping, pong */
    PACK = COPY_PACKED + 2,
    ITERATIONS, /* + 4 (radius - 1): the kernel's four below */
    TO_PACKED = 0, /* + (i & 1): pong -> ping, ping -> pong */
    LAST = 2,      /* + (i & 1): pong, ping -> color */
};
#define COPY_FROM(defs, src)                                                                                                                     \
    {.shader = "svgf_atrous.comp", .defines = defs, .pixel_loop = 1, .domain = "feedback", .bindings = {{src}, {"feedback"}}}
#define ITERATION(defs, src, dst)                                                                                                                \
    {.shader = "svgf_atrous.comp", .defines = defs, .pixel_loop = 1, .domain = dst, .bindings = {{src}, {"position"}, {"frame"}, {dst}}}
#define KERNEL(radius)                                                                                                                           \
    ITERATION("KERNEL_RADIUS=" #radius " TO_PACKED", "pong", "ping"), ITERATION("KERNEL_RADIUS=" #radius " TO_PACKED", "ping", "pong"),        \
        ITERATION("KERNEL_RADIUS=" #radius, "pong", "color"), ITERATION("KERNEL_RADIUS=" #radius, "ping", "color")
static const vrg_dispatch_desc dispatches[] = {
    [COPY_INPUT] = COPY_FROM("COPY", "illumination"),
    [COPY_COLOR] = COPY_FROM("COPY", "color"),
    [COPY_PACKED] = COPY_FROM("COPY FROM_PACKED", "ping"),
    [COPY_PACKED + 1] = COPY_FROM("COPY FROM_PACKED", "pong"),
    [PACK] = {.shader = "svgf_atrous.comp", .defines = "PACK", .pixel_loop = 1, .domain = "pong"},
    [ITERATIONS] = KERNEL(1),
    KERNEL(2),
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *same[] = {"illumination", "position", "normal", "ping", "pong"};
    if (vrg_pass_require_same_size(pass, "color", same, 5) != 0)
        return;
    int n = vrg_param_int(pass, "iterations"), fb = vrg_param_int(pass, "feedback");
    int radius = vrg_param_int(pass, "kernel") / 2; /* a define: the taps unroll */
    const vrg_dispatch_desc *kernel = &dispatches[ITERATIONS + 4 * (radius - 1)];
    if (fb == 0 && vrg_dispatch(pass, cmd, &dispatches[COPY_INPUT]) != 0)
        return;
    if (vrg_dispatch(pass, cmd, &dispatches[PACK]) != 0)
        return;
    for (int i = 0; i < n; i++) {
        int last = i == n - 1;
        vrg_push_int(pass, "step", 1 << i);
        if (vrg_dispatch(pass, cmd, &kernel[(last ? LAST : TO_PACKED) + (i & 1)]) != 0)
            return;
        if (i + 1 == fb && vrg_dispatch(pass, cmd, &dispatches[last ? COPY_COLOR : COPY_PACKED + (i & 1)]) != 0)
            return;
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "svgf_atrous",
    .kind = VRG_PLUGIN_PASS,
    .help = "SVGF edge-avoiding a-trous filter: iterations, 3x3 or 5x5, position/normal/luminance edge-stopping, variance skip, feedback",
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
