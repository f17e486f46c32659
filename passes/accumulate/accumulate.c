/* accumulate: progressive accumulation for a still camera, the converged
 * reference the denoisers are measured against. While the camera holds
 * still, colour = the mean of every frame since the last reset:
 *   n = previous n + 1, colour = previous + (this frame - previous) / n
 * (n in alpha, float32, so thousands of frames add up exactly enough). It
 * resets to this frame alone when the camera moves (any difference from the
 * previous frame's camera), when a reload changed parameters, and whenever
 * the runtime invalidates history (first frame, resize, structural reload). max_frames > 0 caps n: past it the mean
 * becomes a moving average of the last ~max_frames frames.
 * samples_per_frame asks hosts to render that many graph frames per output
 * frame with the camera held (vrg_pass_set_subframes): `voxrg render
 * reference.ini --camera PATH` then writes a converged image per path
 * frame. Each graph frame draws new random numbers (they are seeded by the
 * frame index). */
#include <string.h>
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"samples_per_frame", VRG_PARAM_INT, 1, 1, 1000000, "graph frames per output frame, camera held (hosts render them)",
     VRG_PARAM_RELOAD},
    {"max_frames", VRG_PARAM_INT, 0, 0, 100000000, "cap on the frames averaged (0: no cap)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "this frame"},
    {.name = "history", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "connect as this pass's color@prev"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "the mean of the frames since the last reset; alpha: how many"},
};

static int create(vrg_pass *pass)
{
    vrg_pass_set_subframes(pass, (uint32_t)vrg_param_int(pass, "samples_per_frame"));
    return 0;
}

static int camera_moved(const vrg_camera *a, const vrg_camera *b) { return memcmp(a, b, sizeof *a) != 0; }

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are max_frames by name and reset */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "accumulate.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    const vrg_frame_info *f = vrg_pass_frame(pass);
    int reset = !vrg_res_history_valid(pass, vrg_pass_res(pass, "history")) || f->params_changed || camera_moved(&f->camera, &f->prev_camera);
    vrg_pass_stat(pass, "reset", reset);
    vrg_push_int(pass, "reset", reset);
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "accumulate",
    .kind = VRG_PLUGIN_PASS,
    .help = "progressive accumulation for a still camera (resets when it moves); samples_per_frame renders a converged reference",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
