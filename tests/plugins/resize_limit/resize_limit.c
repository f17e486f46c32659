/* Test plugin: clears its output to grey, and refuses sizes wider than
 * max_width in resize() (as a pass with a size limit would), so that a
 * failed vrg_graph_resize can be tested. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {.name = "max_width", .type = VRG_PARAM_INT, .default_value = 32, .min = 1, .max = 16384, .help = "widest output resize() accepts"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_TRANSFER_DST, .help = "grey"},
};

static int resize(vrg_pass *pass)
{
    VkExtent2D e = vrg_res_extent(pass, vrg_pass_res(pass, "color"));
    if ((int)e.width > vrg_param_int(pass, "max_width"))
        return vrg_pass_error(pass, "output %ux%u is wider than max_width %d", e.width, e.height, vrg_param_int(pass, "max_width"));
    return 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    VkClearColorValue grey = {{0.5f, 0.5f, 0.5f, 1.0f}};
    VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, vrg_res_image(pass, vrg_pass_res(pass, "color")), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &range);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "resize_limit",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a grey output; resize() refuses widths over max_width",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .resize = resize,
    .execute = execute,
};

VRG_PLUGIN(desc)
