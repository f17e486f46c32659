/* Test plugin for vrg_pass_keep_resource: `data`, a persistent buffer of
 * four uints, is filled with `value` on the frames it is new
 * (vrg_res_fresh) and left alone on the others, so it shows whether a
 * reload kept the previous instance's; the stat "fresh" says the same.
 * `keep` names the output create() asks a reload to keep ("": none). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"value", VRG_PARAM_INT, 1, 0, 1000, "what a new `data` is filled with"},
    {"fill", VRG_PARAM_INT, 1, 0, 1, "0: never write `data` (it shows what the runtime left in it)"},
    {.name = "keep", .type = VRG_PARAM_STRING, .default_string = "", .help = "the output to keep across a reload (\"\": none)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "data", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 16, .flags = VRG_SLOT_PERSISTENT,
     .help = "four uints: value, written when new"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_TRANSFER_DST, .format = VK_FORMAT_R32_SFLOAT,
     .help = "cleared to value every frame"},
};

static int create(vrg_pass *pass)
{
    const char *keep = vrg_param_string(pass, "keep");
    return keep[0] ? vrg_pass_keep_resource(pass, keep) : 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_res data = vrg_pass_res(pass, "data");
    int fresh = vrg_res_fresh(pass, data);
    uint32_t value = (uint32_t)vrg_param_int(pass, "value");
    if (fresh && vrg_param_int(pass, "fill"))
        vkCmdFillBuffer(cmd, vrg_res_buffer(pass, data), 0, VK_WHOLE_SIZE, value);
    vrg_pass_stat(pass, "fresh", fresh);
    VkClearColorValue c = {{(float)value, 0, 0, 0}};
    VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, vrg_res_image(pass, vrg_pass_res(pass, "color")), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1, &range);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "keep_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a persistent buffer a reload may keep (vrg_pass_keep_resource)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .execute = execute,
};

VRG_PLUGIN(desc)
