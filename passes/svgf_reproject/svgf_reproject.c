/* svgf_reproject: temporal accumulation of SVGF (Schied et al. 2017) and of
 * the thesis. Each pixel's surface point is looked up where the previous
 * camera saw it (motion vectors); the previous frame's G-buffer decides
 * whether that history belongs to the same surface:
 *   - object id (the chunk) equal,
 *   - normals agree: dot >= normal_threshold,
 *   - the previous point lies on this pixel's plane: |N.(X' - X)| <=
 *     plane_distance blocks (voxel normals are axis-aligned, so neighbouring
 *     faces share normals and the plane test is what separates them).
 * Bilinear 2x2 taps that pass are renormalised; if none pass, the 3x3 taps
 * around the nearest pixel are averaged (as the SVGF paper does); if none of
 * those pass either, history restarts: length 0, colour and moments from
 * this frame alone. Otherwise
 *   length  = min(previous length + 1, max_length)   (frames in the history)
 *   a       = length_alpha ? max(alpha, 1 / (length + 1)) : alpha
 *   colour  = mix(history, this frame, a)
 *   moments = mix(previous moments, (l, l^2), max(moments_alpha, 1 / (length + 1)) or moments_alpha)
 * with l the luminance of this frame. The thesis's k = 0.8 is alpha = 0.2.
 * Sky pixels pass through with length 0. On the first frame, after a resize
 * or reload (frame history_valid = 0) every pixel restarts.
 * Debug outputs (optional, computed only when something reads them: the
 * DEBUG variant, which also writes them, runs only then):
 *   disocclusion  1 on a surface pixel whose history restarted, else 0;
 *   reprojection  where the history was read: xy the previous frame's
 *                 point (pixel centres at +0.5, p + 0.5 - motion), z the
 *                 weight of the taps that passed (bilinear: their weights'
 *                 sum; fallback: the passing share of the 3x3), w the way it
 *                 was read (1 bilinear, 2 the 3x3 fallback, 0 none); all 0
 *                 where the history was not looked up (sky, history_valid 0). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"alpha", VRG_PARAM_FLOAT, 0.2, 0.001, 1, "weight of this frame's colour (thesis k = 0.8 => alpha = 0.2)"},
    {"moments_alpha", VRG_PARAM_FLOAT, 0.2, 0.001, 1, "weight of this frame's luminance moments"},
    {"length_alpha", VRG_PARAM_INT, 1, 0, 1, "1: use max(alpha, 1 / (length + 1)) so young history averages evenly"},
    {"max_length", VRG_PARAM_INT, 32, 1, 1000, "cap on the history length (frames)"},
    {"normal_threshold", VRG_PARAM_FLOAT, 0.9, -1, 1, "least dot(normal, previous normal) of the same surface"},
    {"plane_distance", VRG_PARAM_FLOAT, 0.05, 0, 100, "most distance (blocks) of the previous point from this pixel's plane"},
};

static const vrg_slot_desc slots[] = {
    {.name = "illumination", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this frame's noisy illumination (combine)"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer motion vectors (pixels)"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer world position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .help = "G-buffer ids (block, chunk + 1)"},
    {.name = "history", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "last frame's accumulated colour: this pass's color@prev, or svgf_atrous's feedback@prev"},
    {.name = "prev_moments", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this pass's moments@prev"},
    {.name = "prev_length", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this pass's length@prev"},
    {.name = "prev_position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "the G-buffer's position@prev"},
    {.name = "prev_normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "the G-buffer's normal@prev"},
    {.name = "prev_ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .help = "the G-buffer's ids@prev"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "accumulated illumination"},
    {.name = "moments", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_SFLOAT,
     .help = "accumulated first and second moments of luminance"},
    {.name = "length", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .help = "history length: earlier frames in the accumulation (0: restarted this frame)"},
    /* debug outputs: after the ones above, which set the dispatch size */
    {.name = "disocclusion", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL, .help = "1 on a surface pixel whose history restarted this frame, else 0 (written only when read)"},
    {.name = "reprojection", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "xy: the previous frame's point the history was read at (pixels); z: weight of the taps that passed; w: 1 bilinear, 2 3x3 "
             "fallback, 0 none (written only when read)"},
};

/* the DEBUG variant's debug_outputs: which debug outputs are read */
enum { DEBUG_DISOCCLUSION = 1, DEBUG_REPROJECTION = 2 };

/* every dispatch execute() records: checked by `voxrg check`; their push
 * constants are the parameters by name, history_valid and (DEBUG)
 * debug_outputs. The first
 * binds the slots before the debug outputs; the second, recorded instead
 * when a debug output is read, every slot: both by the shader's binding
 * names */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "svgf_reproject.comp", .pixel_loop = 1},
    {.shader = "svgf_reproject.comp", .defines = "DEBUG", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    /* the history images are read at reprojected positions: all at one size */
    static const char *same[] = {"illumination", "motion", "position", "normal", "ids", "history", "prev_moments", "prev_length",
                                 "prev_position", "prev_normal", "prev_ids"};
    if (vrg_pass_require_same_size(pass, "color", same, sizeof same / sizeof same[0]) != 0)
        return;
    /* every input from last frame must hold it: after a reload some may not */
    static const char *past[] = {"history", "prev_moments", "prev_length", "prev_position", "prev_normal", "prev_ids"};
    int valid = 1;
    for (unsigned i = 0; i < sizeof past / sizeof past[0]; i++)
        valid &= vrg_res_history_valid(pass, vrg_pass_res(pass, past[i]));
    /* unread debug outputs are 1x1 stand-ins: the shader leaves them alone */
    int outputs = (vrg_res_connected(vrg_pass_res(pass, "disocclusion")) ? DEBUG_DISOCCLUSION : 0) |
                  (vrg_res_connected(vrg_pass_res(pass, "reprojection")) ? DEBUG_REPROJECTION : 0);
    vrg_push_int(pass, "history_valid", valid);
    if (outputs)
        vrg_push_int(pass, "debug_outputs", outputs);
    (void)vrg_dispatch(pass, cmd, &dispatches[outputs ? 1 : 0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "svgf_reproject",
    .kind = VRG_PLUGIN_PASS,
    .help = "SVGF temporal accumulation: reprojected history with disocclusion tests (id, normal, plane), colour and luminance moments",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
