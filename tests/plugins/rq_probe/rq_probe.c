/* Test plugin: primary rays traced with VK_KHR_ray_query against the scene's
 * TLAS; writes the hit distance (0 on a miss) so a test can compare the
 * ray-query backend with the CPU pick ray and the DDA. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "tlas", .dir = VRG_IN, .kind = VRG_ACCEL, .access = VRG_ACCESS_RAY_QUERY},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM},
    {.name = "distance", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32_SFLOAT},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "rq_probe.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "rq_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: primary-ray hit distance through ray queries",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
