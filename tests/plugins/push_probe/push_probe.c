/* Test plugin for push constants packed by name (no C struct): one dispatch
 * of push.comp, found on $VOXRG_SHADER_PATH where tests/cli/test_push_names.sh
 * writes shaders that get one thing wrong. The block's members take the
 * parameters gain (float) and steps (int) by name, and frame_index, which
 * the pass computes (vrg_push_uint); set_extra = 1 also sets a value
 * 'extra' (vrg_push_float), set_late = 1 one after the dispatch,
 * set_array = N the array 'weights' to N values (vrg_push_floats). Its
 * outputs are bound by the shader's names (out_color, out_mask,
 * out_values), or with listed = 1 by a list, color, mask and values at
 * bindings 0, 1 and 2, against which the names are checked (color and mask
 * both rgba16f, so that a swapped pair passes every check of type and
 * format). With scratch = 1 it dispatches push.comp twice, with FIRST and
 * then SECOND defined, both bound by the shader's names: the test's shader
 * writes the internal image 'scratch' (create() requests it) in the first
 * and reads it in the second, as the shader declares it (readonly storage
 * image or sampler). */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "binding 0: rgba16f storage image"},
    {.name = "mask", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "binding 1: rgba16f storage image"},
    {.name = "values", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_WRITE, .size = 16,
     .help = "binding 2: what the shader read from its push constants"},
};

static const vrg_param_desc params[] = {
    {.name = "gain", .type = VRG_PARAM_FLOAT, .default_value = 0.5, .min = 0, .max = 1, .help = "packed into the member 'gain'"},
    {.name = "steps", .type = VRG_PARAM_INT, .default_value = 3, .min = 0, .max = 100, .help = "packed into the member 'steps'"},
    {.name = "set_extra", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1, .help = "also sets 'extra' (vrg_push_float)"},
    {.name = "set_late", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1, .help = "sets 'frame_index' again after the dispatch"},
    {.name = "set_array", .type = VRG_PARAM_INT, .default_value = 0, .min = 0, .max = 3,
     .help = "sets 'weights' to that many floats (0.25, 0.75, 1; 0: not at all) with vrg_push_floats"},
    {.name = "listed", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,
     .help = "the dispatch that lists its bindings (color, mask, values), not the one bound by the shader's names"},
    {.name = "scratch", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,
     .help = "two dispatches by name, FIRST then SECOND defined, through the internal image 'scratch'"},
};

static int create(vrg_pass *pass)
{
    return vrg_res_connected(vrg_pass_request_image(pass, "scratch", VK_FORMAT_R16G16B16A16_SFLOAT, 1.0f, VRG_ACCESS_STORAGE_WRITE)) ? 0 : -1;
}

static const vrg_dispatch_desc dispatches[] = {
    {.shader = "push.comp"},
    {.shader = "push.comp", .bindings = {{"color"}, {"mask"}, {"values"}}},
    {.shader = "push.comp", .defines = "FIRST"},
    {.shader = "push.comp", .defines = "SECOND"},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_push_uint(pass, "frame_index", (uint32_t)vrg_pass_frame(pass)->frame_index);
    static const float weights[] = {0.25f, 0.75f, 1.0f};
    if (vrg_param_int(pass, "set_array"))
        vrg_push_floats(pass, "weights", weights, (uint32_t)vrg_param_int(pass, "set_array"));
    if (vrg_param_int(pass, "set_extra"))
        vrg_push_float(pass, "extra", 1.0f);
    if (vrg_param_int(pass, "scratch")) {
        if (vrg_dispatch(pass, cmd, &dispatches[2]) != 0)
            return;
        vrg_push_uint(pass, "frame_index", (uint32_t)vrg_pass_frame(pass)->frame_index);
        (void)vrg_dispatch(pass, cmd, &dispatches[3]);
        return;
    }
    (void)vrg_dispatch(pass, cmd, &dispatches[vrg_param_int(pass, "listed")]);
    if (vrg_param_int(pass, "set_late"))
        vrg_push_uint(pass, "frame_index", 0);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "push_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: runs push.comp from $VOXRG_SHADER_PATH, its push constants packed by name",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
