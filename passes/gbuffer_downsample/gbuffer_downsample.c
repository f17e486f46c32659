/* gbuffer_downsample: the G-buffer at a lower resolution (half by default),
 * so that lighting and the temporal denoisers, which need a G-buffer of
 * their own size, can run on fewer pixels; bilateral_upsample brings the
 * result back to the full G-buffer. Each low-resolution pixel copies one
 * full-resolution pixel, the one vrg_pixel_in() maps it to (a point sample,
 * not an average: an averaged position or normal lies on no surface), and
 * scales its motion vector to the new size. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "full-resolution G-buffer position"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "full-resolution G-buffer normal"},
    {.name = "ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .help = "full-resolution G-buffer ids"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16_SFLOAT,
     .help = "full-resolution motion vectors (pixels)"},
    /* outputs: half the graph's size unless their [resource] sections say otherwise */
    {.name = "position", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .scale = 0.5f, .help = "position (w = 1 on a hit, 0 on sky)"},
    {.name = "normal", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .scale = 0.5f, .help = "normal"},
    {.name = "ids", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_UINT, .scale = 0.5f,
     .help = "block and chunk ids"},
    {.name = "motion", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .scale = 0.5f, .help = "motion vectors in pixels of this size"},
};

/* the one dispatch execute() records (every slot, in order), over the
 * low-resolution position: checked by `voxrg check` */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "gbuffer_downsample.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *low[] = {"out.normal", "out.ids", "out.motion"}, *full[] = {"in.normal", "in.ids", "in.motion"};
    if (vrg_pass_require_same_size(pass, "out.position", low, 3) != 0 || vrg_pass_require_same_size(pass, "in.position", full, 3) != 0)
        return;
    vrg_dispatch_desc d = dispatches[0];
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "gbuffer_downsample",
    .kind = VRG_PLUGIN_PASS,
    .help = "the G-buffer at half resolution (position, normal, ids, motion), one full-resolution pixel per pixel",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
