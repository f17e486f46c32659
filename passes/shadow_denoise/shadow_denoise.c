/* shadow_denoise: a spatial filter of the sun visibility whose radius
 * follows the penumbra's width, as NVIDIA's SIGMA estimates it: a blocker at
 * distance d casts, from a sun of angular radius a, a penumbra about
 * 2 d tan(a) wide, which spans 2 d tan(a) / s pixels where one pixel
 * covers s = z * 2 tan(fov / 2) / height blocks at view depth z. So contact
 * shadows (small d) are left sharp and shadows of far occluders (leaves
 * high above the ground) are smoothed.
 *
 * Two kinds of dispatch (shadow_denoise.comp):
 *   PACK   per pixel: the mean occluder distance over the same plane's
 *          pixels in a 5x5 window (every other pixel; pixels whose rays all
 *          missed have no distance, so a lit pixel at a penumbra's edge
 *          takes its neighbours'), the radius
 *          r = radius_scale * penumbra width / 2 / s, capped at max_radius
 *          (0 where no pixel in the window saw a blocker), packed with the
 *          visibility, the pixel's plane (N.X) and its normal axis into one
 *          texel, so that a tap is one fetch.
 *   BLUR   `iterations` times, the radius halving each time: `taps` taps on
 *          a golden-angle spiral filling the disc of radius r, turned by a
 *          per-pixel, per-frame angle; a tap weighs
 *            exp(-2 |q - p|^2 / r^2) * [same normal axis]
 *              * [|N.X_q - N.X_p| <= sigma_z * |q - p| * s]
 *          (the plane test of svgf_atrous: a tap on another plane, a step or
 *          a wall, does not count). Pixels with r < 0.5 are copied.
 * kernel = surface takes the penumbra's disc on the face instead: r in
 * blocks (radius_scale * d tan(a)), its taps through the screen images of
 * r along the face's two axes (an ellipse, each of those two at most
 * max_radius pixels, after an iteration's halving), the plane test against rho * r for a tap at rho of
 * the radius; the ground seen at a grazing angle is then filtered over the
 * penumbra's blocks, not a disc of pixels that spans many more of them.
 * Sky pixels pass through. sun_radius is the disc sun_shadow sampled, or,
 * given a hard shadow (sun_shadow's sun_radius 0: one exact ray, its
 * blocker's distance), the disc to spread its edge for: the penumbra's
 * width from that distance, as PCSS estimates it. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"sun_radius", VRG_PARAM_FLOAT, 0.27, 0, 45, "angular radius of the sun's disc, degrees: sun_shadow's sun_radius, or the light's when sun_shadow traces a hard shadow"},
    {"radius_scale", VRG_PARAM_FLOAT, 1, 0, 16, "filter radius in penumbra half-widths (0: no filtering)"},
    {"max_radius", VRG_PARAM_FLOAT, 16, 1, 64, "largest filter radius, pixels"},
    {"taps", VRG_PARAM_INT, 12, 4, 32, "taps per iteration"},
    {"iterations", VRG_PARAM_INT, 2, 1, 4, "filter passes, each with half the previous radius"},
    {"sigma_z", VRG_PARAM_FLOAT, 1, 0.001, 1000, "plane edge-stopping: most distance from p's plane per pixel of offset, in pixel footprints (kernel surface: per block of the tap's distance on the face)"},
    {.name = "kernel", .type = VRG_PARAM_STRING, .default_string = "screen",
     .help = "screen (a disc in pixels, as wide as the penumbra where the face looks at the camera) or surface (the penumbra's disc on the face, projected: foreshortened where the face is seen at a grazing angle)"},
};

/* the names kernel takes: the runtime checks the graph's value and pushes
 * its index as the shader's `kernel` */
static const char *const param_choices[] = {NULL, NULL, NULL, NULL, NULL, NULL, "screen,surface"};
_Static_assert(sizeof param_choices / sizeof param_choices[0] == sizeof params / sizeof params[0], "a choice list (or NULL) per parameter");

static const vrg_slot_desc slots[] = {
    {.name = "visibility", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "sun visibility in red (sun_shadow's, or its temporal accumulation)"},
    {.name = "occluder", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "sun_shadow's occluder: mean blocker distance, -1 none"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (camera)"},
    {.name = "visibility", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .help = "filtered sun visibility"},
    {.name = "radius", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL, .help = "the first iteration's filter radius, pixels (kernel surface: the longer of the disc's two projected radii; written only when read)"},
};

static int create(vrg_pass *pass)
{
    /* packed texels (visibility, radius, plane, normal axis) the iterations pass on */
    const char *names[] = {"ping", "pong"};
    for (int i = 0; i < 2; i++)
        if (!vrg_res_connected(vrg_pass_request_image(pass, names[i], VK_FORMAT_R32G32B32A32_UINT, 1.0f, VRG_ACCESS_STORAGE_WRITE)))
            return -1;
    return 0;
}

/* Every dispatch execute() records, which `voxrg check` compiles: the
 * pack with and without the radius output, and the blurs. These run pong
 * -> ping -> pong ... -> out.visibility, so iteration i reads pong when i
 * is even and ping when odd: a pair's entry i & 1 is the one for iteration
 * i. Which image a blur reads (in_src) and writes (out_dst) is what its
 * bindings[] say, frame between them in the shader's order; each binding's
 * access is the shader's (readonly, writeonly). The packs bind by the
 * shader's names (out_pong is the internal pong). Push constants: the
 * parameters by name, the sun's radius in radians and the iteration. */
enum {
    PACK,
    PACK_RADIUS, /* radius is read: write it */
    BLUR_PACKED, /* + (i & 1): pong -> ping, ping -> pong */
    BLUR_LAST = BLUR_PACKED + 2, /* + (i & 1): pong, ping -> out.visibility */
};
#define BLUR(defs, src, dst)                                                                                                                     \
    {.shader = "shadow_denoise.comp", .defines = defs, .pixel_loop = 1, .domain = dst, .bindings = {{src}, {"frame"}, {dst}}}
static const vrg_dispatch_desc dispatches[] = {
    [PACK] = {.shader = "shadow_denoise.comp", .defines = "PACK", .pixel_loop = 1, .domain = "pong"},
    [PACK_RADIUS] = {.shader = "shadow_denoise.comp", .defines = "PACK RADIUS_OUT", .pixel_loop = 1, .domain = "pong"},
    [BLUR_PACKED] = BLUR("BLUR TO_PACKED", "pong", "ping"),
    [BLUR_PACKED + 1] = BLUR("BLUR TO_PACKED", "ping", "pong"),
    [BLUR_LAST] = BLUR("BLUR", "pong", "out.visibility"),
    [BLUR_LAST + 1] = BLUR("BLUR", "ping", "out.visibility"),
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *same[] = {"in.visibility", "occluder", "position", "normal", "ping", "pong"};
    if (vrg_pass_require_same_size(pass, "out.visibility", same, 6) != 0)
        return;
    float sun_radians = (float)(vrg_param(pass, "sun_radius") * 3.14159265358979323846 / 180.0);
    /* an unread radius is a 1x1 stand-in: the shader leaves it alone */
    vrg_push_float(pass, "sun_radians", sun_radians);
    vrg_push_int(pass, "iteration", 0);
    if (vrg_dispatch(pass, cmd, &dispatches[vrg_res_connected(vrg_pass_res(pass, "radius")) ? PACK_RADIUS : PACK]) != 0)
        return;
    int n = vrg_param_int(pass, "iterations");
    for (int i = 0; i < n; i++) {
        vrg_push_float(pass, "sun_radians", sun_radians);
        vrg_push_int(pass, "iteration", i);
        if (vrg_dispatch(pass, cmd, &dispatches[(i == n - 1 ? BLUR_LAST : BLUR_PACKED) + (i & 1)]) != 0)
            return;
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "shadow_denoise",
    .kind = VRG_PLUGIN_PASS,
    .help = "sun visibility filter whose radius follows the penumbra width (occluder distance, sun radius, view depth), plane edge-stopping",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .param_choices = param_choices,
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
