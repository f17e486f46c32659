/* Test plugin whose second parameter has no name (a NULL where a string
 * belongs): the loader must refuse it with a message, where comparing
 * parameter names used to dereference the NULL. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {.name = "gain", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 2},
    {.name = NULL, .type = VRG_PARAM_FLOAT, .default_value = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)pass;
    (void)cmd;
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "bad_params",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a parameter with a NULL name",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
