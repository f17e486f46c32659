/* Test plugin that is otherwise valid but claims ABI version 999: the loader
 * must refuse it, naming its path, before using any other field. */
#include "voxrg/plugin.h"

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)pass;
    (void)cmd;
}

static const vrg_plugin_desc desc = {
    .abi_version = 999,
    .name = "bad_abi",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: wrong ABI version",
    .execute = execute,
};

VRG_PLUGIN(desc)
