/* Test plugin for shader reflection: three slots of different descriptor
 * types and formats, bound in declaration order, and push constants of
 * push_bytes bytes; the shader, reflect.comp, is found on $VOXRG_SHADER_PATH,
 * where tests write shaders that get one thing wrong. It lists the
 * dispatches it may record, so `voxrg check` finds the same mistakes. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "binding 0: rgba16f storage image"},
    {.name = "mask", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R8G8B8A8_UNORM, .help = "binding 1: rgba8 storage image"},
    {.name = "counts", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_WRITE, .size = 64,
     .help = "binding 2: storage buffer"},
};

static const vrg_param_desc params[] = {
    {.name = "push_bytes", .type = VRG_PARAM_INT, .default_value = 16, .min = 0, .max = 128, .help = "push_size of the dispatch"},
};

/* push_size 16, the size of a vec4 block; another push_bytes is a
 * dispatch the plugin does not list, which the runtime refuses */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "reflect.comp", .push_size = 16},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    static const float push[32]; /* 128 bytes of zeros */
    (void)vrg_dispatch(pass, cmd, &(vrg_dispatch_desc){.shader = "reflect.comp", .push = push, .push_size = (uint32_t)vrg_param_int(pass, "push_bytes")});
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "reflect_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: runs reflect.comp from $VOXRG_SHADER_PATH with three bindings and push constants",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
