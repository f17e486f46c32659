/* Test plugin for the dispatch helper's limits: more slots than a dispatch
 * has bindings (bound by default, all of them), or with `long_defines` a
 * defines string longer than the helper takes. Either is an error of the
 * frame naming the limit, never a binding or define left out. */
#include <string.h>
#include "voxrg/plugin.h"

#define IN(n) {.name = n, .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL, .help = "unused"}
static const vrg_slot_desc slots[] = {
    IN("i0"), IN("i1"), IN("i2"),   IN("i3"),   IN("i4"),   IN("i5"),   IN("i6"),   IN("i7"),
    IN("i8"), IN("i9"), IN("i10"), IN("i11"), IN("i12"), IN("i13"), IN("i14"), IN("i15"),
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "never written: the dispatch fails"},
};

static const vrg_param_desc params[] = {
    {"long_defines", VRG_PARAM_BOOL, 0, 0, 1, "a dispatch with defines over the limit (and only the output bound)"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    if (vrg_param_int(pass, "long_defines")) {
        char defines[400];
        memset(defines, 'A', sizeof defines - 1);
        defines[sizeof defines - 1] = '\0';
        (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "pattern.comp", .defines = defines, .bindings = {{"color"}}});
    } else
        (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "pattern.comp"});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "many_slots",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: a dispatch over the binding and defines limits",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
};

VRG_PLUGIN(desc)
