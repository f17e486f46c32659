/* clamped_reproject: temporal accumulation that neither lags nor ghosts.
 * The history is reprojected and tested exactly as svgf_reproject does
 * (motion vectors; object id, normal and plane tests; bilinear taps, else
 * the 3x3 around the nearest pixel, else a restart), except that where all
 * four bilinear taps pass, the colour is resampled with a 4x4 Catmull-Rom
 * clamped to those taps' range (cubic = 1): bilinear resampling every frame
 * blurs the history more with every frame it is kept. Then:
 *   - neighbourhood clamp: in YCoCg, the reprojected slow history is
 *     clamped to mean +- clamp_k * sigma of this frame's 3x3 neighbourhood
 *     (non-sky pixels), so colour from another surface or from before a
 *     lighting change cannot survive (clamp_k = 0: no clamp);
 *   - fast history: a second accumulation with weight max(fast_alpha,
 *     1 / (length + 1)) (read back from this pass's own `fast`), which
 *     follows a change within a few frames;
 *   - anti-lag: where the slow history and the fast one disagree by more
 *     than antilag_threshold times what the fast history's noise explains
 *     (the 3x3 luminance sigma * sqrt(fast_alpha / (2 - fast_alpha))), with
 *     e the excess and r = 1 - 1 / (1 + antilag * e), the slow history
 *     moves to the fast one by r and the history length is divided by
 *     1 + antilag * e, so the lighting of now replaces that of frames ago
 *     instead of leaking in at alpha (antilag = 0: off);
 *   - history length out, for the variance and the spatial filter, and in
 *     `fast`'s alpha, where this pass reads it back next frame (a
 *     separate prev_length input would make 17 bindings, over a
 *     dispatch's 16).
 *   - sun span: under a moving key light (the sun through the day) the
 *     history length is cut to sun_span / the degrees the light moved since
 *     the last frame, so the history averages light from at most sun_span
 *     degrees of its path: the neighbourhood clamp and anti-lag see a
 *     change only once it exceeds this frame's noise, and lighting that
 *     drifts by less than that a frame (indirect light under a moving sun)
 *     otherwise lags by the whole history (sun_span = 0: no limit; a still
 *     light is never cut);
 * footprints > 0 adds a reprojection test: the previous point lies within
 * that many pixel steps of this one (a step at the point's distance,
 * stretched by 1 / |N.V|): far away one pixel spans blocks, and coplanar
 * faces in one chunk pass the plane test blocks apart.
 * Weights: a = max(alpha, 1 / (length + 1)) for colour and moments alike,
 * so the moments are averaged over the same samples as the colour and
 * `color` alpha holds the effective sample count of that average:
 * min(length + 1, (2 - alpha) / alpha), what an exponential average with
 * weight alpha converges to (its variance is alpha / (2 - alpha) of one
 * sample's). mean_variance divides the moments' variance by it.
 * Debug outputs (optional, computed only when something reads them):
 *   disocclusion  1 on a surface pixel whose history restarted, else 0;
 *   reprojection  where the history was read, as svgf_reproject's (w: 1
 *                 bilinear, 2 the 3x3 fallback, 3 Catmull-Rom, 4 nearest);
 *   clamp         r: how far the neighbourhood clamp moved the slow history
 *                 (YCoCg distance, the illumination's units; 0 with
 *                 clamp_k = 0), g: the share of the way anti-lag then moved
 *                 it to the fast history (1 - 1 / cut).
 * The main dispatch already binds 16 slots, a dispatch's most, so a second
 * one (DEBUG) computes the same history again and writes only these; it
 * runs only when one of them is read. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"alpha", VRG_PARAM_FLOAT, 0.1, 0.001, 1, "weight of this frame in the slow history (at least 1 / (length + 1))"},
    {"fast_alpha", VRG_PARAM_FLOAT, 0.5, 0.001, 1, "weight of this frame in the fast history"},
    {"cubic", VRG_PARAM_INT, 0, 0, 1, "1: resample the history with Catmull-Rom where all 4 bilinear taps are on this surface"},
    {"nearest", VRG_PARAM_INT, 0, 0, 1, "1: take the passing history tap nearest the reprojected point alone (no bilinear blend)"},
    {"fallback", VRG_PARAM_INT, 1, 0, 1, "1: where no bilinear tap passes, average the passing taps of the 3x3 around the nearest (0: restart)"},
    {"footprints", VRG_PARAM_FLOAT, 0, 0, 100, "most distance of the previous point, in pixel steps on the surface (0: no limit)"},
    {"max_length", VRG_PARAM_INT, 32, 1, 1000, "cap on the history length (frames)"},
    {"clamp_k", VRG_PARAM_FLOAT, 1.5, 0, 100, "clamp the slow history to the 3x3 mean +- clamp_k sigma (0: no clamp)"},
    {"sun_span", VRG_PARAM_FLOAT, 0, 0, 360,
     "most degrees the key light may move within the slow history: its length is cut to sun_span / the degrees it moved since the last "
     "frame (0: no limit)"},
    {"antilag", VRG_PARAM_FLOAT, 1, 0, 100, "how strongly a slow/fast disagreement shortens the history (0: off)"},
    {"antilag_threshold", VRG_PARAM_FLOAT, 2, 0, 100, "disagreement (in the fast history's noise sigmas) that noise may explain"},
    {"normal_threshold", VRG_PARAM_FLOAT, 0.9, -1, 1, "least dot(normal, previous normal) of the same surface"},
    {"plane_distance", VRG_PARAM_FLOAT, 0.05, 0, 100, "most distance (blocks) of the previous point from this pixel's plane"},
};

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this frame's noisy illumination"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer motion vectors (pixels)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer world position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .help = "G-buffer ids (block, chunk + 1)"},
    {.name = "history", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "last frame's slow history: this pass's color@prev, or a filter's feedback@prev"},
    {.name = "prev_fast", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "this pass's fast@prev (the history length in its alpha)"},
    {.name = "prev_moments", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this pass's moments@prev"},
    {.name = "prev_position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "the G-buffer's position@prev"},
    {.name = "prev_normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "the G-buffer's normal@prev"},
    {.name = "prev_ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .help = "the G-buffer's ids@prev"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (camera)"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "accumulated illumination; alpha: effective sample count"},
    {.name = "fast", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "the fast history (weight fast_alpha); alpha: the history length, read back next frame"},
    {.name = "moments", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_SFLOAT,
     .help = "first and second moments of luminance, averaged like the colour"},
    {.name = "length", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .help = "history length in frames after anti-lag (0: restarted this frame)"},
    /* debug outputs: after the ones above, which set the dispatch size */
    {.name = "disocclusion", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL, .help = "1 on a surface pixel whose history restarted this frame, else 0 (written only when read)"},
    {.name = "reprojection", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "xy: the previous frame's point the history was read at (pixels); z: weight of the taps that passed; w: 1 bilinear, 2 3x3 "
             "fallback, 3 Catmull-Rom, 4 nearest, 0 none (written only when read)"},
    {.name = "clamp", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "r: how far the neighbourhood clamp moved the slow history (YCoCg); g: anti-lag's share of the way to the fast history "
             "(written only when read)"},
};

/* the DEBUG dispatch's debug_outputs: which debug outputs are read */
enum { DEBUG_DISOCCLUSION = 1, DEBUG_REPROJECTION = 2, DEBUG_CLAMP = 4 };

/* the dispatches execute() records: checked by `voxrg check`; their push
 * constants are the parameters by name, history_valid and (DEBUG)
 * debug_outputs. Both bind by the shader's binding names: the main one the
 * 16 slots before the debug outputs; the DEBUG one, recorded only when a
 * debug output is read, the inputs and the debug outputs. */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "clamped_reproject.comp", .pixel_loop = 1},
    {.shader = "clamped_reproject.comp", .defines = "DEBUG", .pixel_loop = 1,
     .domain = "color"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    /* the history images are read at reprojected positions: all at one size */
    static const char *same[] = {"illumination", "motion", "position", "normal", "ids", "history", "prev_fast", "prev_moments",
                                 "prev_position", "prev_normal", "prev_ids"};
    if (vrg_pass_require_same_size(pass, "color", same, sizeof same / sizeof same[0]) != 0)
        return;
    /* every input from last frame must hold it: after a reload some may not */
    static const char *past[] = {"history", "prev_fast", "prev_moments", "prev_position", "prev_normal", "prev_ids"};
    int valid = 1;
    for (unsigned i = 0; i < sizeof past / sizeof past[0]; i++)
        valid &= vrg_res_history_valid(pass, vrg_pass_res(pass, past[i]));
    vrg_push_int(pass, "history_valid", valid);
    if (vrg_dispatch(pass, cmd, &dispatches[0]) != 0)
        return;
    /* unread debug outputs are 1x1 stand-ins: the shader leaves them alone */
    int outputs = (vrg_res_connected(vrg_pass_res(pass, "disocclusion")) ? DEBUG_DISOCCLUSION : 0) |
                  (vrg_res_connected(vrg_pass_res(pass, "reprojection")) ? DEBUG_REPROJECTION : 0) |
                  (vrg_res_connected(vrg_pass_res(pass, "clamp")) ? DEBUG_CLAMP : 0);
    if (outputs) {
        vrg_push_int(pass, "history_valid", valid);
        vrg_push_int(pass, "debug_outputs", outputs);
        (void)vrg_dispatch(pass, cmd, &dispatches[1]);
    }
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "clamped_reproject",
    .kind = VRG_PLUGIN_PASS,
    .help = "temporal accumulation with neighbourhood clamping, a fast history, anti-lag and the effective sample count",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
