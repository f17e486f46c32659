/* gbuffer_downsample: the G-buffer at a lower resolution (half by default),
 * so that lighting and the temporal denoisers, which need a G-buffer of
 * their own size, can run on fewer pixels; bilateral_upsample brings the
 * result back to the full G-buffer. Each low-resolution pixel copies one
 * full-resolution pixel, the one vrg_pixel_in() maps it to (a point sample,
 * not an average: an averaged position or normal lies on no surface), and
 * scales its motion vector to the new size. With jitter, each frame copies
 * another pixel of the footprint, so that over the cycle every pixel is
 * sampled: for a pass that places each texel by the position it holds
 * (surface_cache's signal_position), not for bilateral_upsample, which
 * places a texel where vrg_pixel_in's pixel lies, or for the screen-space
 * temporal filters, whose history would then hold another point each
 * frame. ids and motion are optional, in pairs: an output nothing reads is
 * not written, and its input may then stay unconnected (so that the
 * G-buffer need not write it either); an output that is read needs its
 * input. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {.name = "jitter", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,
     .help = "1: each frame takes another pixel of each footprint (at half size a 4-frame cycle over the 2x2), so that every pixel is sampled in turn"},
};

static const vrg_slot_desc slots[] = {
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "full-resolution G-buffer position"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "full-resolution G-buffer normal"},
    {.name = "ids", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32_UINT,
     .flags = VRG_SLOT_OPTIONAL, .help = "full-resolution G-buffer ids (needed where out.ids is read)"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL, .help = "full-resolution motion vectors, pixels (needed where out.motion is read)"},
    /* outputs: half the graph's size unless their [resource] sections say otherwise */
    {.name = "position", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .scale = 0.5f, .help = "position (w = 1 on a hit, 0 on sky)"},
    {.name = "normal", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .scale = 0.5f, .help = "normal"},
    {.name = "ids", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_UINT, .scale = 0.5f,
     .flags = VRG_SLOT_OPTIONAL, .help = "block and chunk ids (written only when read)"},
    {.name = "motion", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .scale = 0.5f, .flags = VRG_SLOT_OPTIONAL, .help = "motion vectors in pixels of this size (written only when read)"},
};

/* the one dispatch execute() records (every slot, in order), over the
 * low-resolution position: checked by `voxrg check`; push constants
 * jitter by name, offset and writes */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "gbuffer_downsample.comp", .pixel_loop = 1},
};

static uint32_t gcd(uint32_t a, uint32_t b) { return b ? gcd(b, a % b) : a; }

/* The optional pairs (gbuffer_downsample.comp's WRITE_* bits, in order) */
static const char *const optional_in[] = {"in.ids", "in.motion"}, *const optional_out[] = {"out.ids", "out.motion"};

/* An output that is read needs its input: else there is nothing to copy.
 * In create(), not check(): which optional outputs are read is known only
 * once every reader is (after check() runs), so `voxrg check` finds this
 * when it creates the passes (with a device). */
static int create(vrg_pass *pass)
{
    for (int i = 0; i < 2; i++)
        if (vrg_res_connected(vrg_pass_res(pass, optional_out[i])) && !vrg_res_connected(vrg_pass_res(pass, optional_in[i])))
            return vrg_pass_error(pass, "'%s' is read, but '%s' is not connected: connect the full-size G-buffer's (%s = GBUFFER.%s)", optional_out[i],
                                  optional_in[i], optional_in[i], optional_in[i] + 3);
    return 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const char *low[] = {"out.normal", "out.ids", "out.motion"}, *full[] = {"in.normal", "in.ids", "in.motion"};
    if (vrg_pass_require_same_size(pass, "out.position", low, 3) != 0 || vrg_pass_require_same_size(pass, "in.position", full, 3) != 0)
        return;
    uint32_t writes = 0;
    for (int i = 0; i < 2; i++)
        writes |= vrg_res_connected(vrg_pass_res(pass, optional_out[i])) ? 1u << i : 0u;
    vrg_push_uint(pass, "writes", writes);
    vrg_push_ints(pass, "offset", (int32_t[2]){0, 0}, 2);
    if (vrg_param_int(pass, "jitter")) {
        /* the footprint's n pixels in turn: frame f takes the one at
         * (f * step) mod n in raster order, step the footprint's width + 1
         * or, where that shares a factor with n, the next number that does
         * not (so that every pixel comes round); at 2x2 the diagonals
         * alternate: (0,0) (1,1) (0,1) (1,0) */
        VkExtent2D full = vrg_res_extent(pass, vrg_pass_res(pass, "in.position")), low = vrg_res_extent(pass, vrg_pass_res(pass, "out.position"));
        uint32_t w = (full.width + low.width - 1) / low.width, h = (full.height + low.height - 1) / low.height, n = w * h, step = w + 1;
        while (gcd(step, n) != 1)
            step++;
        uint32_t k = (uint32_t)((vrg_pass_frame(pass)->frame_index * step) % n);
        vrg_push_ints(pass, "offset", (int32_t[2]){(int32_t)(k % w), (int32_t)(k / w)}, 2);
    }
    vrg_dispatch_desc d = dispatches[0];
    (void)vrg_dispatch(pass, cmd, &d);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "gbuffer_downsample",
    .kind = VRG_PLUGIN_PASS,
    .help = "the G-buffer at half resolution (position, normal, ids, motion), one full-resolution pixel per pixel",
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
