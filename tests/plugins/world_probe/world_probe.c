/* Test plugin: reads the world buffer at pseudo-random positions, so a test
 * can compare the GPU layout with the CPU store. Pixel i (row-major) probes
 * p = lo + (pcg(3i), pcg(3i+1), pcg(3i+2)) mod extent and writes
 * (block id, solid bit | brick bit << 1 | chunk loaded << 2). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"x0", VRG_PARAM_INT, 0, -100000, 100000, "lowest x probed"},
    {"y0", VRG_PARAM_INT, 0, -1000, 1000, "lowest y probed"},
    {"z0", VRG_PARAM_INT, 0, -100000, 100000, "lowest z probed"},
    {"sx", VRG_PARAM_INT, 32, 1, 100000, "x extent"},
    {"sy", VRG_PARAM_INT, 32, 1, 1000, "y extent"},
    {"sz", VRG_PARAM_INT, 32, 1, 100000, "z extent"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ},
    {.name = "probes", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_UINT},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    int32_t pc[8] = {vrg_param_int(pass, "x0"), vrg_param_int(pass, "y0"), vrg_param_int(pass, "z0"), 0,
                     vrg_param_int(pass, "sx"), vrg_param_int(pass, "sy"), vrg_param_int(pass, "sz"), 0};
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "world_probe.comp", .push = pc, .push_size = sizeof pc});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "world_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: world buffer contents at pseudo-random positions",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
