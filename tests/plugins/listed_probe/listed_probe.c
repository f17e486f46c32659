/* Test plugin for a pass with no execute: the runtime records its listed
 * dispatches in order. listed.comp with STEP=0 writes red 0.5, with STEP=1
 * reads that back and adds blue 0.25 and green 0.25 x the index of `level`
 * among its choices (param_choices: the runtime checks the value and packs
 * the index by name). Only both dispatches, in this order, give red 0.5
 * and blue 0.25. */
#include "voxrg/plugin.h"

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ_WRITE, .format = VK_FORMAT_R8G8B8A8_UNORM,
     .help = "red 0.5 (first dispatch), blue 0.25 and green 0.25 x level added (second)"},
};

static const vrg_param_desc params[] = {
    {.name = "level", .type = VRG_PARAM_STRING, .help = "green: low 0, mid 0.25, high 0.5", .default_string = "mid"},
};
static const char *const choices[] = {"low,mid,high"};

static const vrg_dispatch_desc dispatches[] = {
    {.shader = "listed.comp", .defines = "STEP=0"},
    {.shader = "listed.comp", .defines = "STEP=1"},
};

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "listed_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: no execute; the runtime records its two listed dispatches in order",
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
    .param_choices = choices,
};

VRG_PLUGIN(desc)
