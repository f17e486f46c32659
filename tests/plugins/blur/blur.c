/* Test plugin: 3x3 box blur with clamped texelFetch. No filtering and no
 * border colour are involved, so tests can compute every pixel on the CPU:
 * dst(x,y) = 1/9 * sum over dx,dy in -1..1 of src(clamp(x+dx), clamp(y+dy)). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "any image"},
    {.name = "dst", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "3x3 box average of src"},
};

/* listed: `voxrg check` compiles it (graphs/runtime-demo.ini uses this plugin) */
static const vrg_dispatch_desc dispatches[] = {{.shader = "blur.comp"}};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "blur.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "blur",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: 3x3 box blur, edges clamped",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
