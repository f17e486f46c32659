/* shader_pass.c: a shader-only pass (NAME.comp), its interface read from
 * the shader by name; dispatch.c records it (_vrg_shader_pass_execute). */
#ifndef VRG_SHADER_PASS_H
#define VRG_SHADER_PASS_H

#include "internal.h"
#include "reflect.h"

#define VRG_SHADER_PASS_HELP_MAX 256
/* the bytes _vrg_shader_pass_execute (dispatch.c) packs the parameters into:
 * the push-constant size every Vulkan device has */
#define VRG_SHADER_PASS_PUSH_MAX 128

/* the most variants (optional slots connected or not, variant choices) a
 * shader-only pass compiles: `voxrg check` compiles each */
#define VRG_SHADER_PASS_VARIANTS 32
#define VRG_SHADER_PASS_CHOICES_MAX 512

/* One thing that picks a variant: an optional slot (HAS_X defined when
 * connected) or a parameter's choice with `variant` (NAME=index). */
struct _vrg_shader_axis {
    int slot;  /* the optional slot's index, else -1 */
    int param; /* the parameter's index, else -1 */
    int count; /* values: 2 for a slot, the choices for a parameter */
    char define[VRG_NAME_MAX + 8];
};

struct _vrg_shader_pass {
    vrg_param_desc params[VRG_MAX_PARAMS];
    char param_names[VRG_MAX_PARAMS][VRG_NAME_MAX];
    char param_help[VRG_MAX_PARAMS][VRG_SHADER_PASS_HELP_MAX];
    vrg_slot_desc slots[VRG_MAX_SLOTS];
    char slot_names[VRG_MAX_SLOTS][VRG_NAME_MAX];
    char slot_help[VRG_MAX_SLOTS][VRG_SHADER_PASS_HELP_MAX];
    char slot_where[VRG_MAX_SLOTS][VRG_PATH_MAX + 16]; /* FILE:LINE of the declaration */
    char binding_res[VRG_MAX_BINDINGS][VRG_NAME_MAX + 8];
    const char *choices[VRG_MAX_PARAMS]; /* the descriptor's param_choices */
    char choice_text[VRG_MAX_PARAMS][VRG_SHADER_PASS_CHOICES_MAX];
    char param_default[VRG_MAX_PARAMS][VRG_NAME_MAX]; /* a choice's default */
    struct _vrg_shader_axis axes[8];
    char axis_where[8][VRG_PATH_MAX + 16]; /* FILE:LINE of each axis's annotation */
    int axis_count;
    char domain[VRG_NAME_MAX + 8]; /* the first output always written */
    vrg_dispatch_desc dispatch;    /* what every variant shares: shader, bindings, domain */
    vrg_dispatch_desc dispatches[VRG_SHADER_PASS_VARIANTS]; /* one per variant, the first axis varying fastest */
    char defines[VRG_SHADER_PASS_VARIANTS][224];
    char shader[256];
    char help[VRG_SHADER_PASS_HELP_MAX];
};

/* The plugin made from p->source (NAME.comp): its descriptor from what the
 * shader declares, execute NULL. 0, or -1 after reporting (the shader's
 * FILE:LINE, then the graph's `line` if > 0). */
int _vrg_shader_pass_load(_vrg_plugin *p, _vrg_diag *d, int line);
void _vrg_shader_pass_free(_vrg_plugin *p);
/* FILE:LINE of the binding a shader-only pass's slot comes from, NULL for
 * another plugin's slot: graph errors about the slot name both sides. */
const char *_vrg_shader_pass_slot_where(const _vrg_plugin *p, const vrg_slot_desc *sd);
/* Records a shader-only pass (dispatch.c): the dispatch of the variant
 * its optional slots and variant choices pick, its push constants packed
 * by name from the parameters. */
void _vrg_shader_pass_execute(vrg_pass *pass, VkCommandBuffer cmd);
#endif
