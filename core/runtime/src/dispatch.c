/* The helper layer: "dispatch this compute shader over the output with these
 * resources bound". Pipelines are cached per pass; descriptors are pushed
 * (VK_KHR_push_descriptor), so there are no pools to manage; barriers for the
 * bound resources come from the same tracker the runtime uses between passes. */
#define _GNU_SOURCE /* open_memstream */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "reflect.h"
#include "shader.h"
#include "shader_pass.h"
#include "watch.h"
#include "capture.h"

/* What one dispatch binds: the pipeline cache's key beside shader and
 * defines, and what reflection checks the shader against. */
typedef struct bound_set {
    VkDescriptorType types[VRG_MAX_BINDINGS];
    VkFormat formats[VRG_MAX_BINDINGS]; /* storage images: the bound format, else UNDEFINED */
    vrg_access access[VRG_MAX_BINDINGS];
    /* without a device: an internal resource, which only create() makes, so
     * its type and format are not known */
    unsigned char unknown[VRG_MAX_BINDINGS];
    char labels[VRG_MAX_BINDINGS][2 * VRG_NAME_MAX + 32]; /* "slot 'out.color'" */
    int slot[VRG_MAX_BINDINGS]; /* the bound slot, -1: an internal resource */
    char internal[VRG_MAX_BINDINGS][VRG_NAME_MAX]; /* the internal resource bound (its name in the pass), else "" */
    int listed;         /* the dispatch's bindings[] chose them */
    uint32_t count;
    uint32_t push_size; /* the dispatch's */
} bound_set;

typedef struct _vrg_pipeline {
    char path[VRG_PATH_MAX];
    char shader[256]; /* as the pass named it */
    char *deps;       /* files it was compiled from (shader.c), for hot reload */
    char defines[256];
    bound_set bs;     /* from the dispatch that made it */
    uint32_t push_bytes; /* the shader's push-constant block */
    char push_where[VRG_PATH_MAX + 16];
    char push_name[64];
    _vrg_push_member *members; /* the block's, packed by name when the dispatch's push_size is 0 */
    int member_count;
    uint32_t local[3];
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    struct _vrg_pipeline *next;
} _vrg_pipeline;

static VkDescriptorType descriptor_type(vrg_resource_kind kind, vrg_access a)
{
    if (kind == VRG_ACCEL)
        return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    if (kind == VRG_BUFFER)
        return a == VRG_ACCESS_UNIFORM       ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
               : a == VRG_ACCESS_TEXEL_READ ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER
                                            : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return a == VRG_ACCESS_SAMPLED ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

static int is_storage(VkDescriptorType t)
{
    return t == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || t == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
}

/* readonly / writeonly against the bound access: a contradiction is an
 * error; a missing qualifier a warning, because a shader that writes what
 * others read at the same time, or reads what was bound for writing only
 * (its contents not kept), races or reads undefined values. */
static int check_access(vrg_pass *p, const bound_set *bs, const _vrg_reflected_binding *b, FILE *diag)
{
    const char *plugin = p->plugin->desc->name;
    uint32_t i = b->binding;
    vrg_access a = bs->access[i];
    const char *said = b->readonly ? "readonly" : b->writeonly ? "writeonly" : "neither readonly nor writeonly";
    if ((a == VRG_ACCESS_STORAGE_READ && b->writeonly) || (a == VRG_ACCESS_STORAGE_WRITE && b->readonly)) {
        fprintf(diag, "%s: error[%s]: binding %u '%s' is declared %s, but %s of pass '%s' (plugin %s) is bound with %s access\n", b->where,
                _vrg_diag_info_of(VRG_E_SHADER_ACCESS)->code, i, b->name, said, bs->labels[i], p->name, plugin, _vrg_access_name(a));
        return -1;
    }
    if ((a == VRG_ACCESS_STORAGE_READ && !b->readonly) || (a == VRG_ACCESS_STORAGE_WRITE && !b->writeonly))
        fprintf(diag, "%s: warning[%s]: binding %u '%s' is declared %s, but %s of pass '%s' (plugin %s) is bound with %s access: declare it %s\n", b->where,
                _vrg_diag_info_of(VRG_W_ACCESS_QUALIFIER)->code, i, b->name, said, bs->labels[i], p->name, plugin, _vrg_access_name(a),
                a == VRG_ACCESS_STORAGE_READ ? "readonly" : "writeonly");
    return 0;
}

/* The slot a binding's name names: in_X the input slot X, out_X the output
 * X, a uniform block `frame` (frame.glsl) the input `frame`; else -1. */
static int named_slot(const vrg_plugin_desc *pd, const _vrg_reflected_binding *b)
{
    const char *name = b->name;
    vrg_slot_dir dir = VRG_IN;
    if (strncmp(name, "in_", 3) == 0)
        name += 3;
    else if (strncmp(name, "out_", 4) == 0)
        name += 4, dir = VRG_OUT;
    else if (strcmp(name, "frame") != 0 || b->type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
        return -1;
    for (uint32_t s = 0; s < pd->slot_count; s++)
        if (pd->slots[s].dir == dir && strcmp(pd->slots[s].name, name) == 0)
            return (int)s;
    return -1;
}

/* The X of a binding named in_X or out_X that is not a slot of that
 * direction: an internal resource of the pass (vrg_pass_request_image or
 * _buffer), which only create() makes, so which one is known only with a
 * device. NULL for any other name. */
static const char *internal_name(const vrg_plugin_desc *pd, const _vrg_reflected_binding *b)
{
    const char *x = strncmp(b->name, "in_", 3) == 0 ? b->name + 3 : strncmp(b->name, "out_", 4) == 0 ? b->name + 4 : NULL;
    if (!x || !*x || strlen(x) >= VRG_NAME_MAX || named_slot(pd, b) >= 0)
        return NULL;
    return x;
}

/* "ping, pong": the pass's internal resources, for a message. */
static void internal_names(const vrg_pass *p, char *out, size_t cap)
{
    const vrg_graph *g = p->graph;
    size_t n = strlen(p->name);
    out[0] = 0;
    for (int i = 0; i < g->res_count; i++)
        if (g->res[i].internal_owner == (int)(p - g->passes) && strncmp(g->res[i].name, p->name, n) == 0 && g->res[i].name[n] == '.') {
            size_t len = strlen(out);
            snprintf(out + len, cap - len, "%s%s", len ? ", " : "", g->res[i].name + n + 1);
        }
}

/* A binding named after a slot is bound to that slot: a pair of bindings of
 * the same type swapped in the shader (or in the pass's bindings[]) passes
 * every other check and renders wrong. -1 after the error at its line. */
static int check_name(vrg_pass *p, const bound_set *bs, const _vrg_reflection *r, const _vrg_reflected_binding *b, FILE *diag)
{
    const vrg_plugin_desc *pd = p->plugin->desc;
    uint32_t i = b->binding;
    int want = named_slot(pd, b);
    const char *code = _vrg_diag_info_of(VRG_E_SHADER_BINDING_NAME)->code;
    const char *x = want < 0 ? internal_name(pd, b) : NULL;
    if (x && p->graph->ctx && strcmp(bs->internal[i], x) != 0) {
        /* in_X / out_X for an internal resource X: bound to X, in either
         * mode; one that names nothing is an error where the shader's
         * names bind (bindings[] gives other names, in_src, their image) */
        int res, prev, slot;
        if (_vrg_pass_lookup(p, x, &res, &prev, &slot) == 0 && slot < 0) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' is named after internal resource '%s', but pass '%s' (plugin %s) binds %s there\n", b->where,
                    code, i, b->name, x, p->name, pd->name, bs->labels[i]);
            return -1;
        }
        if (!bs->listed) {
            char internal[512];
            internal_names(p, internal, sizeof internal);
            fprintf(diag, "%s: error[%s]: binding %u '%s' is named after no slot or internal resource of pass '%s' (plugin %s): it has no %s slot '%s', "
                          "and its internal resources are %s\n",
                    b->where, code, i, b->name, p->name, pd->name, b->name[0] == 'i' ? "input" : "output", x,
                    internal[0] ? internal : "none (vrg_pass_request_image makes one)");
            return -1;
        }
    }
    if (want < 0 || bs->slot[i] == want)
        return 0;
    /* the binding named after the slot bound here, if it holds this one's */
    for (int k = 0; bs->slot[i] >= 0 && k < r->count; k++) {
        const _vrg_reflected_binding *o = &r->bindings[k];
        if (o == b || o->set != 0 || o->binding >= bs->count || named_slot(pd, o) != bs->slot[i])
            continue;
        if (bs->slot[o->binding] == want) {
            if (o->binding > i) /* the pair once, at its first binding */
                fprintf(diag, "%s: error[%s]: bindings %u '%s' and %u '%s' (%s) are swapped: pass '%s' (plugin %s) binds %s at binding %u and %s at %u\n",
                        b->where, code, i, b->name, o->binding, o->name, o->where, p->name, pd->name, bs->labels[i], i, bs->labels[o->binding], o->binding);
            return -1;
        }
        fprintf(diag, "%s: error[%s]: binding %u '%s' is named after slot '%s.%s', but pass '%s' (plugin %s) binds %s there, which binding %u '%s' (%s) is named after\n",
                b->where, code, i, b->name, pd->slots[want].dir == VRG_IN ? "in" : "out", pd->slots[want].name, p->name, pd->name, bs->labels[i], o->binding,
                o->name, o->where);
        return -1;
    }
    fprintf(diag, "%s: error[%s]: binding %u '%s' is named after slot '%s.%s', but pass '%s' (plugin %s) binds %s there\n", b->where, code, i, b->name,
            pd->slots[want].dir == VRG_IN ? "in" : "out", pd->slots[want].name, p->name, pd->name, bs->labels[i]);
    return -1;
}

static const char *scalar_name(int s)
{
    return s == VRG_PUSH_FLOAT ? "float" : s == VRG_PUSH_INT ? "int" : s == VRG_PUSH_UINT ? "uint" : s == VRG_PUSH_BOOL ? "bool" : "no scalar";
}

static const char *param_type_name(vrg_param_type t)
{
    return t == VRG_PARAM_FLOAT ? "float" : t == VRG_PARAM_INT ? "int" : t == VRG_PARAM_BOOL ? "bool" : "string";
}

/* Whether parameter pd fits member m packed by name (plugin.h, vrg_push_float). */
static int param_fits(const vrg_param_desc *pd, const _vrg_push_member *m)
{
    switch (pd->type) {
    case VRG_PARAM_FLOAT: return m->scalar == VRG_PUSH_FLOAT;
    case VRG_PARAM_INT: return m->scalar == VRG_PUSH_INT || (m->scalar == VRG_PUSH_UINT && pd->min >= 0 && !(pd->min == 0 && pd->max == 0));
    case VRG_PARAM_BOOL: return m->scalar == VRG_PUSH_BOOL || m->scalar == VRG_PUSH_INT || m->scalar == VRG_PUSH_UINT;
    default: return 0;
    }
}

static const vrg_param_desc *param_named(const vrg_plugin_desc *pd, const char *name)
{
    for (uint32_t i = 0; i < pd->param_count; i++)
        if (strcmp(pd->params[i].name, name) == 0)
            return &pd->params[i];
    return NULL;
}

/* A member packed by name: a scalar, or an array of them (set by the pass). */
static int member_scalar(const _vrg_push_member *m) { return m->scalar != VRG_PUSH_OTHER && m->vecsize == 1 && m->columns == 1 && !m->array_dims; }
static int member_array(const _vrg_push_member *m)
{
    return m->scalar != VRG_PUSH_OTHER && m->vecsize == 1 && m->columns == 1 && m->array_dims == 1 && m->array_len > 0 && m->array_len <= 32;
}

/* Members packed by name: each a scalar (or an array of them), and one
 * named after a parameter a scalar of a type that fits (plugin.h); errors
 * at the member's line. */
static int check_members(vrg_pass *p, const _vrg_push_member *members, int count, FILE *diag)
{
    const vrg_plugin_desc *pd = p->plugin->desc;
    const char *code = _vrg_diag_info_of(VRG_E_SHADER_PUSH_MEMBER)->code;
    int errors = 0;
    for (int m = 0; m < count; m++) {
        const _vrg_push_member *pm = &members[m];
        const vrg_param_desc *param = param_named(pd, pm->name);
        if (!member_scalar(pm) && !member_array(pm)) {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' is not a scalar float, int, uint or bool (or an array of them), which pass '%s' "
                          "(plugin %s) packs by name (push_size 0): compute vectors in the shader from scalars\n", pm->where, code, pm->name, p->name, pd->name);
            errors++;
        } else if (param && member_array(pm)) {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' is an array, which no parameter fills, but pass '%s' (plugin %s) has a parameter '%s': "
                          "set the array with vrg_push_floats (or _ints, _uints)\n", pm->where, code, pm->name, p->name, pd->name, param->name);
            errors++;
        } else if (param && param->type == VRG_PARAM_STRING && _vrg_param_choices(pd, (uint32_t)(param - pd->params)) && pm->scalar != VRG_PUSH_INT &&
                   pm->scalar != VRG_PUSH_UINT) {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' is a %s, but parameter '%s' of pass '%s' (plugin %s) is a choice among %s, "
                          "whose index an int or uint member gets\n", pm->where, code, pm->name, scalar_name(pm->scalar), param->name, p->name, pd->name,
                    _vrg_param_choices(pd, (uint32_t)(param - pd->params)));
            errors++;
        } else if (param && param->type != VRG_PARAM_STRING && !param_fits(param, pm)) {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' is a %s, but parameter '%s' of pass '%s' (plugin %s) is a%s %s%s\n", pm->where, code, pm->name,
                    scalar_name(pm->scalar), param->name, p->name, pd->name, param->type == VRG_PARAM_INT ? "n" : "", param_type_name(param->type),
                    param->type == VRG_PARAM_INT && pm->scalar == VRG_PUSH_UINT ? " that may be negative (give it min >= 0)" : "");
            errors++;
        }
    }
    return errors;
}

/* The shader's declarations against what the dispatch binds: every error
 * and warning at the declaring line; -1 when any is an error. */
static int check_reflection(vrg_pass *p, const char *path, const bound_set *bs, const _vrg_reflection *r, FILE *diag)
{
    const char *plugin = p->plugin->desc->name;
    const vrg_context *ctx = p->graph->ctx;
    int errors = 0;
    for (int k = 0; k < r->count; k++) {
        const _vrg_reflected_binding *b = &r->bindings[k];
        uint32_t i = b->binding;
        if (b->set == 0 && i < bs->count && !bs->unknown[i] && check_name(p, bs, r, b, diag) != 0) {
            errors++;
        } else if (b->set != 0) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' is in set %u, but pass '%s' (plugin %s) binds set 0 only\n", b->where,
                    _vrg_diag_info_of(VRG_E_SHADER_BINDING_UNBOUND)->code, i, b->name, b->set, p->name, plugin);
            errors++;
        } else if (i >= bs->count) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' is bound to nothing: pass '%s' (plugin %s) binds %u resource%s (bindings 0 to %d)\n", b->where,
                    _vrg_diag_info_of(VRG_E_SHADER_BINDING_UNBOUND)->code, i, b->name, p->name, plugin, bs->count, bs->count == 1 ? "" : "s", (int)bs->count - 1);
            errors++;
        } else if (bs->unknown[i]) {
            continue; /* checked with a device */
        } else if (b->type != bs->types[i]) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' is %s, but %s of pass '%s' (plugin %s) is bound as %s\n", b->where,
                    _vrg_diag_info_of(VRG_E_SHADER_BINDING_TYPE)->code, i, b->name, _vrg_descriptor_type_name(b->type), bs->labels[i], p->name, plugin,
                    _vrg_descriptor_type_name(bs->types[i]));
            errors++;
        } else if (b->format && bs->formats[i] && b->format != bs->formats[i]) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' is %s, but %s of pass '%s' (plugin %s) is %s\n", b->where, _vrg_diag_info_of(VRG_E_SHADER_IMAGE_FORMAT)->code,
                    i, b->name, _vrg_glsl_format_name(b->format), bs->labels[i], p->name, plugin, _vrg_glsl_format_name(bs->formats[i]));
            errors++;
        } else if (b->type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE && !b->format && !b->writeonly && ctx && !ctx->read_without_format) {
            fprintf(diag, "%s: error[%s]: binding %u '%s' has no format qualifier and is read, which '%s' cannot do (shaderStorageImageReadWithoutFormat): "
                          "declare layout(%s) like %s of pass '%s' (plugin %s)\n", b->where, _vrg_diag_info_of(VRG_E_SHADER_IMAGE_FORMAT)->code, i, b->name,
                    ctx->device_name, _vrg_glsl_format_name(bs->formats[i]), bs->labels[i], p->name, plugin);
            errors++;
        } else if (is_storage(b->type) && check_access(p, bs, b, diag) != 0)
            errors++;
    }
    if (!bs->push_size)
        errors += check_members(p, r->push_members, r->push_member_count, diag);
    else if (r->push_bytes != bs->push_size) {
        /* a C struct of another size than the block: the members' offsets cannot agree */
        fprintf(diag, "%s: error[%s]: push-constant block '%s' is %u bytes, but pass '%s' (plugin %s) pushes %u (vrg_dispatch_desc.push_size): "
                      "set push_size 0 to push by name (vrg_push_float)\n", r->push_bytes ? r->push_where : path, _vrg_diag_info_of(VRG_E_SHADER_PUSH_SIZE)->code,
                r->push_name, r->push_bytes, p->name, plugin, bs->push_size);
        errors++;
    }
    /* every shipped pass declares each slot it binds, in either mode */
    for (uint32_t i = 0; i < bs->count; i++) {
        int declared = 0;
        for (int k = 0; k < r->count && !declared; k++)
            declared = r->bindings[k].set == 0 && r->bindings[k].binding == i;
        if (!declared)
            fprintf(diag, "%s: warning[%s]: %s of pass '%s' (plugin %s) is bound at binding %u, which the shader does not declare\n", path,
                    _vrg_diag_info_of(VRG_W_UNUSED_BINDING)->code, bs->labels[i], p->name, plugin, i);
    }
    return errors ? -1 : 0;
}

/* Compiles pl->path with pl->defines and makes its layouts and pipeline.
 * On failure pl's Vulkan objects stay unset and -1 is returned after the
 * compile errors (FILE:LINE) went to the graph's diagnostics. */
static int build_pipeline(vrg_pass *p, _vrg_pipeline *pl)
{
    vrg_context *ctx = p->graph->ctx;
    VkDevice dev = ctx->dev.device;
    _vrg_shader_module sm;
    FILE *diag = p->graph->diag.out ? p->graph->diag.out : stderr;
    if (_vrg_shader_compile(ctx, pl->path, pl->defines, &sm, diag) != 0) {
        _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader %s failed to compile", pl->path);
        return -1;
    }
    int mismatch = check_reflection(p, pl->path, &pl->bs, &sm.refl, diag);
    pl->push_bytes = sm.refl.push_bytes;
    snprintf(pl->push_where, sizeof pl->push_where, "%s", sm.refl.push_bytes ? sm.refl.push_where : pl->path);
    snprintf(pl->push_name, sizeof pl->push_name, "%s", sm.refl.push_name);
    pl->members = sm.refl.push_members;
    pl->member_count = sm.refl.push_member_count;
    sm.refl.push_members = NULL;
    _vrg_reflection_free(&sm.refl);
    if (mismatch != 0) {
        free(pl->members);
        pl->members = NULL;
        vkDestroyShaderModule(dev, sm.module, NULL);
        free(sm.deps);
        _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader %s does not match what the pass binds", pl->path);
        return -1;
    }
    pl->deps = sm.deps;
    memcpy(pl->local, sm.local_size, sizeof pl->local);
    VkDescriptorSetLayoutBinding b[VRG_MAX_BINDINGS];
    for (uint32_t i = 0; i < pl->bs.count; i++)
        b[i] = (VkDescriptorSetLayoutBinding){.binding = i, .descriptorType = pl->bs.types[i], .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    VkDescriptorSetLayoutCreateInfo sli = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
        .bindingCount = pl->bs.count,
        .pBindings = b,
    };
    vkCreateDescriptorSetLayout(dev, &sli, NULL, &pl->set_layout);
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, 128};
    VkPipelineLayoutCreateInfo pli = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &pl->set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &range,
    };
    vkCreatePipelineLayout(dev, &pli, NULL, &pl->layout);
    VkComputePipelineCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = sm.module, .pName = "main"},
        .layout = pl->layout,
    };
    VkResult res = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, NULL, &pl->pipeline);
    vkDestroyShaderModule(dev, sm.module, NULL);
    if (res != VK_SUCCESS) {
        vkDestroyPipelineLayout(dev, pl->layout, NULL);
        vkDestroyDescriptorSetLayout(dev, pl->set_layout, NULL);
        free(pl->deps);
        pl->deps = NULL;
        free(pl->members);
        pl->members = NULL;
        pl->layout = VK_NULL_HANDLE;
        pl->set_layout = VK_NULL_HANDLE;
        _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "vkCreateComputePipelines failed for %s (%d)", pl->path, res);
        return -1;
    }
    _vrg_name_object(ctx, VK_OBJECT_TYPE_PIPELINE, (uint64_t)pl->pipeline, "%s/%s: %s", p->graph->name, p->name, pl->shader);
    return 0;
}

static void free_pipeline_objects(VkDevice dev, _vrg_pipeline *pl)
{
    vkDestroyPipeline(dev, pl->pipeline, NULL);
    vkDestroyPipelineLayout(dev, pl->layout, NULL);
    vkDestroyDescriptorSetLayout(dev, pl->set_layout, NULL);
    free(pl->deps);
    free(pl->members);
}

/* A replaced pipeline: earlier frames in flight may still run it. */
typedef struct retired_pipeline {
    VkDevice dev;
    _vrg_pipeline objects;
} retired_pipeline;

static void free_retired_pipeline(void *user)
{
    retired_pipeline *r = user;
    free_pipeline_objects(r->dev, &r->objects);
    free(r);
}

static int same_bindings(const bound_set *a, const bound_set *b)
{
    uint32_t n = a->count;
    return n == b->count && memcmp(a->types, b->types, n * sizeof *a->types) == 0 && memcmp(a->formats, b->formats, n * sizeof *a->formats) == 0 &&
           memcmp(a->access, b->access, n * sizeof *a->access) == 0 && memcmp(a->slot, b->slot, n * sizeof *a->slot) == 0;
}

/* The file of a shader the pass names; -1 after reporting where it looked. */
static int shader_path(vrg_pass *p, const char *shader, char *path, size_t cap)
{
    char searched[2048];
    if (_vrg_shader_resolve(p, shader, path, cap, searched, sizeof searched) == 0)
        return 0;
    return _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader '%s' not found (searched %s)", shader, searched);
}

/* pixel.glsl's vrg_pixel: a group shades a tile of the device's shape, so a
 * pixel loop's local size is the device's group (-1 after reporting). */
static int pixel_loop_fits(vrg_pass *p, const char *shader, const uint32_t local[3])
{
    uint32_t group[2];
    _vrg_shader_group_size(p->graph->ctx, group);
    if (local[0] == group[0] && local[1] == group[1] && local[2] == 1)
        return 0;
    return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "pixel_loop dispatch of %s: local size %ux%ux%u, a pixel loop needs VRG_GROUP_X x VRG_GROUP_Y (%ux%u)", shader,
                          local[0], local[1], local[2], group[0], group[1]);
}

static _vrg_pipeline *get_pipeline(vrg_pass *p, const char *shader, const char *defines, const bound_set *bs)
{
    if (!defines)
        defines = "";
    if (strlen(shader) >= sizeof((_vrg_pipeline *)0)->shader || strlen(defines) >= sizeof((_vrg_pipeline *)0)->defines) {
        _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader name '%.40s...' or its defines are too long (at most 255 characters each)", shader);
        return NULL;
    }
    /* looked up by the name the pass gave: a shader is resolved to a file
     * once, when its pipeline is built, not with file-system calls on every
     * dispatch of every frame */
    for (_vrg_pipeline *pl = p->pipelines; pl; pl = pl->next)
        if (strcmp(pl->shader, shader) == 0 && strcmp(pl->defines, defines) == 0 && same_bindings(&pl->bs, bs))
            return pl;
    char path[VRG_PATH_MAX];
    if (shader_path(p, shader, path, sizeof path) != 0)
        return NULL;
    _vrg_pipeline *pl = calloc(1, sizeof *pl);
    if (!pl) {
        _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "out of memory for a pipeline of %s", shader);
        return NULL;
    }
    snprintf(pl->path, sizeof pl->path, "%s", path);
    snprintf(pl->shader, sizeof pl->shader, "%s", shader);
    snprintf(pl->defines, sizeof pl->defines, "%s", defines);
    pl->bs = *bs;
    if (build_pipeline(p, pl) != 0) {
        free(pl);
        return NULL;
    }
    pl->next = p->pipelines;
    p->pipelines = pl;
    _vrg_graph_watch_pipeline(p->graph, pl->deps);
    return pl;
}

/* What a shader declares at set 0 (these defines), and how its names bind
 * it: read once per shader and defines, for a dispatch without bindings[]
 * (by name) and for a bindings[] entry that leaves its access to the
 * shader. */
typedef struct _vrg_name_plan {
    char shader[256], defines[256];
    char path[VRG_PATH_MAX];
    int by_name;  /* 1: binding i is slot slot[i], or the internal resource internal[i] */
    uint32_t count;
    int slot[VRG_MAX_BINDINGS]; /* -1: internal[i] */
    char internal[VRG_MAX_BINDINGS][VRG_NAME_MAX];
    /* binding i of set 0 as the shader declares it */
    unsigned char declared[VRG_MAX_BINDINGS], readonly[VRG_MAX_BINDINGS], writeonly[VRG_MAX_BINDINGS];
    VkDescriptorType type[VRG_MAX_BINDINGS];
    char name[VRG_MAX_BINDINGS][64];
    struct _vrg_name_plan *next;
} _vrg_name_plan;

void _vrg_name_plans_free(vrg_pass *p)
{
    while (p->name_plans) {
        _vrg_name_plan *n = p->name_plans;
        p->name_plans = n->next;
        free(n);
    }
}

static int uses_file(const char *deps, const char *path)
{
    size_t n = strlen(path);
    for (const char *d = deps; d && *d;) {
        const char *end = strchr(d, '\n');
        size_t len = end ? (size_t)(end - d) : strlen(d);
        if (len == n && strncmp(d, path, n) == 0)
            return 1;
        d = end ? end + 1 : d + len;
    }
    return 0;
}

int _vrg_pipelines_reload(vrg_pass *p, char (*changed)[VRG_PATH_MAX], int count)
{
    VkDevice dev = p->graph->ctx->dev.device;
    int swapped = 0, failed = 0;
    for (_vrg_pipeline *pl = p->pipelines; pl; pl = pl->next) {
        int hit = 0;
        for (int i = 0; i < count && !hit; i++)
            hit = uses_file(pl->deps, changed[i]);
        if (!hit)
            continue;
        /* build the new version beside the old; the old objects go once
         * the frames in flight that may run them have ended */
        _vrg_pipeline fresh = *pl;
        fresh.deps = NULL;
        fresh.members = NULL;
        fresh.pipeline = VK_NULL_HANDLE;
        fresh.layout = VK_NULL_HANDLE;
        fresh.set_layout = VK_NULL_HANDLE;
        if (build_pipeline(p, &fresh) != 0) {
            failed = 1;
            continue;
        }
        retired_pipeline *old = malloc(sizeof *old);
        if (old) {
            *old = (retired_pipeline){.dev = dev, .objects = *pl};
            _vrg_retire(p->graph, free_retired_pipeline, old);
        } else { /* cannot defer: wait for the GPU instead */
            vkDeviceWaitIdle(dev);
            free_pipeline_objects(dev, pl);
        }
        _vrg_pipeline *next = pl->next;
        *pl = fresh;
        pl->next = next;
        _vrg_graph_watch_pipeline(p->graph, pl->deps);
        swapped++;
    }
    if (swapped || failed)
        _vrg_name_plans_free(p); /* a saved shader may name its bindings otherwise */
    p->failed = 0; /* a failed reload keeps the pass running on its old pipeline */
    return failed ? -1 : swapped;
}

void _vrg_pipelines_deps(vrg_pass *p, void (*fn)(void *user, const char *path), void *user)
{
    for (_vrg_pipeline *pl = p->pipelines; pl; pl = pl->next)
        for (const char *d = pl->deps; d && *d;) {
            const char *end = strchr(d, '\n');
            char path[VRG_PATH_MAX];
            snprintf(path, sizeof path, "%.*s", (int)(end ? end - d : (ptrdiff_t)strlen(d)), d);
            fn(user, path);
            d = end ? end + 1 : d + strlen(d);
        }
}

void _vrg_pipelines_destroy(vrg_pass *p)
{
    _vrg_name_plans_free(p);
    VkDevice dev = p->graph->ctx ? p->graph->ctx->dev.device : VK_NULL_HANDLE;
    while (p->pipelines) {
        _vrg_pipeline *pl = p->pipelines;
        p->pipelines = pl->next;
        free_pipeline_objects(dev, pl);
        free(pl);
    }
}

typedef struct bound {
    int res, prev;
    vrg_access access;
    int slot;          /* -1: an internal resource */
    const char *named; /* the name it was bound by, for messages */
} bound;

/* Whether an acceleration structure exists to be bound: one was made
 * (allocate.c), or without a device, one would be (its writer sized it). */
static int accel_exists(const vrg_graph *g, int r)
{
    return g->ctx ? g->res[r].accel != VK_NULL_HANDLE : g->res[r].size > 0;
}

static int names_slot(const vrg_plugin_desc *pd, const char *name)
{
    if (strncmp(name, "in.", 3) == 0)
        name += 3;
    else if (strncmp(name, "out.", 4) == 0)
        name += 4;
    for (uint32_t s = 0; s < pd->slot_count; s++)
        if (strcmp(pd->slots[s].name, name) == 0)
            return 1;
    return 0;
}

/* A dispatch without bindings[] binds by the shader's names when every
 * binding it declares (this variant, these defines) is named after a
 * connected slot (in_X, out_X, frame) or an internal resource (in_X,
 * out_X for the resource X), in set 0, numbered 0 to n-1: each where the
 * shader says, and the slots it does not declare not at all. Else (a
 * binding of another name, an acceleration structure, which is numbered by
 * VRG_ACCEL_BINDING) every slot in declaration order. The plan is cached
 * per shader and defines, with what the shader declares at each binding
 * (its access, when the pass does not give it); a shader that does not
 * compile has none (its pipeline reports the error). */
static const _vrg_name_plan *shader_plan(vrg_pass *p, const vrg_dispatch_desc *d)
{
    const char *defines = d->defines ? d->defines : "";
    for (_vrg_name_plan *n = p->name_plans; n; n = n->next)
        if (strcmp(n->shader, d->shader) == 0 && strcmp(n->defines, defines) == 0)
            return n;
    char path[VRG_PATH_MAX];
    if (strlen(d->shader) >= sizeof((_vrg_name_plan *)0)->shader || strlen(defines) >= sizeof((_vrg_name_plan *)0)->defines ||
        _vrg_shader_resolve(p, d->shader, path, sizeof path, NULL, 0) != 0)
        return NULL;
    /* its messages come when its pipeline is built */
    char *text = NULL;
    size_t len = 0;
    FILE *quiet = open_memstream(&text, &len);
    if (!quiet)
        return NULL;
    _vrg_shader_module sm;
    int rc = _vrg_shader_compile(NULL, path, defines, &sm, quiet);
    fclose(quiet);
    free(text);
    if (rc != 0)
        return NULL;
    _vrg_name_plan *n = calloc(1, sizeof *n);
    if (!n) {
        free(sm.deps);
        _vrg_reflection_free(&sm.refl);
        return NULL;
    }
    snprintf(n->shader, sizeof n->shader, "%s", d->shader);
    snprintf(n->defines, sizeof n->defines, "%s", defines);
    snprintf(n->path, sizeof n->path, "%s", path);
    const vrg_plugin_desc *pd = p->plugin->desc;
    for (int k = 0; k < sm.refl.count; k++) {
        const _vrg_reflected_binding *b = &sm.refl.bindings[k];
        if (b->set != 0 || b->binding >= VRG_MAX_BINDINGS || n->declared[b->binding])
            continue;
        n->declared[b->binding] = 1;
        n->type[b->binding] = b->type;
        n->readonly[b->binding] = (unsigned char)b->readonly;
        n->writeonly[b->binding] = (unsigned char)b->writeonly;
        snprintf(n->name[b->binding], sizeof n->name[b->binding], "%s", b->name);
    }
    n->by_name = sm.refl.count > 0 && sm.refl.count <= VRG_MAX_BINDINGS;
    n->count = (uint32_t)sm.refl.count;
    for (int i = 0; i < VRG_MAX_BINDINGS; i++)
        n->slot[i] = -1;
    for (int k = 0; k < sm.refl.count && n->by_name; k++) {
        const _vrg_reflected_binding *b = &sm.refl.bindings[k];
        int s = named_slot(pd, b);
        const char *internal = s < 0 ? internal_name(pd, b) : NULL;
        n->by_name = b->set == 0 && b->binding < n->count && n->slot[b->binding] < 0 && !n->internal[b->binding][0] &&
                     ((s >= 0 && p->slots[s].res >= 0 && pd->slots[s].kind != VRG_ACCEL) || internal);
        if (n->by_name && s >= 0)
            n->slot[b->binding] = s;
        else if (n->by_name)
            snprintf(n->internal[b->binding], sizeof n->internal[b->binding], "%s", internal);
    }
    free(sm.deps);
    _vrg_reflection_free(&sm.refl);
    n->next = p->name_plans;
    p->name_plans = n;
    return n;
}

/* The access of a binding whose dispatch does not give it (bound by name,
 * or a bindings[] entry with access 0), from the shader's declaration at
 * binding i: a slot keeps its declared access where the shader declares
 * the descriptor type that access gives (so that readonly and writeonly
 * are checked against it, VRG-E068); otherwise, and for an internal
 * resource (sd NULL), a sampler is sampled, a uniform block uniform, a
 * texel buffer texel-read, a storage image or buffer declared readonly
 * storage-read, writeonly storage-write, neither: an input slot read, an
 * output slot written (VRG-W005 then asks for the qualifier), an internal
 * resource read and written. A slot the shader declares as another kind
 * of resource (a sampler for a buffer) keeps its access, and reflection
 * reports the mismatch (VRG-E065). */
static vrg_access declared_access(const vrg_slot_desc *sd, const _vrg_name_plan *n, int i)
{
    vrg_access fallback = sd ? sd->access : VRG_ACCESS_STORAGE_READ_WRITE;
    if (!n || i < 0 || i >= VRG_MAX_BINDINGS || !n->declared[i] || (sd && descriptor_type(sd->kind, sd->access) == n->type[i]))
        return fallback;
    vrg_resource_kind kind = sd ? sd->kind : VRG_IMAGE;
    switch (n->type[i]) {
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return sd && kind != VRG_IMAGE ? fallback : VRG_ACCESS_SAMPLED;
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return sd && kind != VRG_BUFFER ? fallback : VRG_ACCESS_UNIFORM;
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: return sd && kind != VRG_BUFFER ? fallback : VRG_ACCESS_TEXEL_READ;
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        if (sd && kind != (n->type[i] == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VRG_IMAGE : VRG_BUFFER))
            return fallback;
        return n->readonly[i]    ? VRG_ACCESS_STORAGE_READ
               : n->writeonly[i] ? VRG_ACCESS_STORAGE_WRITE
               : !sd             ? VRG_ACCESS_STORAGE_READ_WRITE
               : sd->dir == VRG_IN ? VRG_ACCESS_STORAGE_READ
                                   : VRG_ACCESS_STORAGE_WRITE;
    default: return fallback;
    }
}

/* n, or -1 after reporting; unknown[i]: an internal resource not made yet. */
static int resolve_bindings(vrg_pass *p, const vrg_dispatch_desc *d, bound *out, unsigned char *unknown)
{
    const vrg_plugin_desc *pd = p->plugin->desc;
    int n = 0;
    int derived = !d->bindings[0].res; /* some access left to the shader */
    for (int i = 0; i < VRG_MAX_BINDINGS && d->bindings[i].res && !derived; i++)
        derived = !d->bindings[i].access;
    const _vrg_name_plan *plan = derived && d->shader ? shader_plan(p, d) : NULL;
    int fallback = 0;
    if (plan && plan->by_name && !d->bindings[0].res) {
        for (uint32_t i = 0; i < plan->count && !fallback; i++) {
            int s = plan->slot[i];
            unknown[i] = 0;
            if (s >= 0) {
                out[i] = (bound){p->slots[s].res, p->slots[s].prev, declared_access(&pd->slots[s], plan, (int)i), s, NULL};
                continue;
            }
            int res, prev, slot;
            vrg_access a = declared_access(NULL, plan, (int)i);
            if (_vrg_pass_lookup(p, plan->internal[i], &res, &prev, &slot) == 0 && slot < 0) {
                out[i] = (bound){res, 0, a, -1, plan->internal[i]};
            } else if (!p->graph->ctx) { /* create() did not run: checked with a device */
                unknown[i] = 1;
                out[i] = (bound){-1, -1, a, -1, plan->internal[i]};
            } else { /* no such resource: declaration order, whose check names the binding */
                fallback = 1;
            }
        }
        if (!fallback)
            return (int)plan->count;
    }
    if (!d->bindings[0].res) {
        for (uint32_t s = 0; s < pd->slot_count; s++) {
            int r = p->slots[s].res;
            /* acceleration structures that do not exist (unconnected, or a scene
             * of size 0) are left out: declare them last */
            if (r < 0 || (p->graph->res[r].kind == VRG_ACCEL && !accel_exists(p->graph, r)))
                continue;
            if (n == VRG_MAX_BINDINGS)
                return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "its slots need more than the %d bindings of a dispatch: name the ones the shader uses in bindings[]",
                                      VRG_MAX_BINDINGS);
            unknown[n] = 0;
            out[n++] = (bound){r, p->slots[s].prev, pd->slots[s].access, (int)s, NULL};
        }
        return n;
    }
    for (; n < VRG_MAX_BINDINGS && d->bindings[n].res; n++) {
        int res, prev, slot;
        vrg_access a = d->bindings[n].access;
        unknown[n] = 0;
        if (_vrg_pass_lookup(p, d->bindings[n].res, &res, &prev, &slot) != 0) {
            /* without a device create() did not run: its internal resources
             * are not there to look up */
            if (!p->graph->ctx && !names_slot(pd, d->bindings[n].res)) {
                unknown[n] = 1;
                out[n] = (bound){-1, -1, a ? a : declared_access(NULL, plan, n), -1, d->bindings[n].res};
                continue;
            }
            return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "binding %d names '%s', which is neither a slot nor an internal resource of this pass", n,
                                  d->bindings[n].res);
        }
        if (!a)
            a = declared_access(slot >= 0 ? &pd->slots[slot] : NULL, plan, n);
        out[n] = (bound){res, prev, a, slot, d->bindings[n].res};
    }
    return n;
}

/* How messages name a bound resource: "slot 'out.color'" or "internal resource 'tmp'". */
static void label_binding(const vrg_pass *p, const bound *b, const char *named, char *out, size_t cap)
{
    if (b->slot < 0) {
        snprintf(out, cap, "internal resource '%s'", b->res >= 0 ? p->graph->res[b->res].name : named);
        return;
    }
    const vrg_slot_desc *sd = vrg_slot(p, b->slot);
    snprintf(out, cap, "slot '%s.%s'", sd->dir == VRG_IN ? "in" : "out", sd->name);
}

/* The dispatch's bindings (b, n returned), what they are (bs) and the
 * defines its pipeline is compiled with; -1 after reporting. */
static int describe_dispatch(vrg_pass *p, const vrg_dispatch_desc *d, bound *b, bound_set *bs, char *defines, size_t cap)
{
    vrg_graph *g = p->graph;
    memset(bs, 0, sizeof *bs);
    int n = resolve_bindings(p, d, b, bs->unknown);
    if (n < 0)
        return -1;
    bs->count = (uint32_t)n;
    bs->listed = d->bindings[0].res != NULL;
    bs->push_size = d->push_size;
    for (int i = 0; i < n; i++) {
        bs->access[i] = b[i].access;
        bs->slot[i] = b[i].slot;
        if (b[i].slot < 0 && b[i].res >= 0) {
            const char *full = g->res[b[i].res].name;
            size_t len = strlen(p->name);
            snprintf(bs->internal[i], sizeof bs->internal[i], "%s", strncmp(full, p->name, len) == 0 && full[len] == '.' ? full + len + 1 : full);
        }
        label_binding(p, &b[i], b[i].named, bs->labels[i], sizeof bs->labels[i]);
        if (b[i].access == VRG_ACCESS_TRANSFER_SRC || b[i].access == VRG_ACCESS_TRANSFER_DST || b[i].access == VRG_ACCESS_AS_BUILD)
            return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "binding %d: %s access cannot be bound to a shader", i, _vrg_access_name(b[i].access));
        if (bs->unknown[i])
            continue;
        if (g->res[b[i].res].kind == VRG_ACCEL && !accel_exists(g, b[i].res))
            return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "binding %d: acceleration structure '%s' was not built (its writer made none: size 0)", i,
                                  g->res[b[i].res].name);
        bs->types[i] = descriptor_type(g->res[b[i].res].kind, b[i].access);
        if (bs->types[i] == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)
            bs->formats[i] = g->res[b[i].res].format;
    }
    if (d->push_size > 128)
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "push constants of %u bytes (at most 128)", d->push_size);
    if (!d->shader)
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "dispatch names no shader");
    if (strlen(d->shader) >= sizeof((_vrg_pipeline *)0)->shader)
        return _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader name of %zu characters (at most %zu)", strlen(d->shader), sizeof((_vrg_pipeline *)0)->shader - 1);
    /* room for the define added below */
    size_t max_defines = cap - sizeof " VRG_ACCEL_BINDING=99";
    if (d->defines && strlen(d->defines) > max_defines)
        return _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "defines of %zu characters (at most %zu)", strlen(d->defines), max_defines);
    /* A bound acceleration structure is announced to the shader as
     * VRG_ACCEL_BINDING (the voxel layer's trace.glsl then traces it). */
    snprintf(defines, cap, "%s", d->defines ? d->defines : "");
    for (int i = 0; i < n; i++)
        if (!bs->unknown[i] && g->res[b[i].res].kind == VRG_ACCEL) {
            size_t len = strlen(defines);
            snprintf(defines + len, cap - len, " VRG_ACCEL_BINDING=%d", i);
            break;
        }
    return n;
}

static int same_string(const char *a, const char *b) { return strcmp(a ? a : "", b ? b : "") == 0; }

/* Whether d is one the plugin lists in vrg_plugin_desc.dispatches. */
static int declared(const vrg_plugin_desc *pd, const vrg_dispatch_desc *d)
{
    for (uint32_t k = 0; k < pd->dispatch_count; k++) {
        const vrg_dispatch_desc *e = &pd->dispatches[k];
        int same = same_string(e->shader, d->shader) && same_string(e->defines, d->defines) && e->push_size == d->push_size;
        for (int i = 0; same && i < VRG_MAX_BINDINGS; i++)
            same = same_string(e->bindings[i].res, d->bindings[i].res) && e->bindings[i].access == d->bindings[i].access;
        if (same)
            return 1;
    }
    return 0;
}

/* ---- push constants by name ---- */

static void push_value(vrg_pass *p, const char *setter, const char *member, int scalar, uint32_t word)
{
    if (!member || !*member || strlen(member) >= VRG_NAME_MAX) {
        _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "%s: member name '%.64s' is empty or longer than %d characters", setter, member ? member : "(null)",
                       VRG_NAME_MAX - 1);
        return;
    }
    _vrg_push_value *v = NULL;
    for (int i = 0; i < p->push_count && !v; i++)
        if (strcmp(p->push_values[i].name, member) == 0)
            v = &p->push_values[i];
    if (!v) {
        if (p->push_count == p->push_cap) {
            int cap = p->push_cap ? 2 * p->push_cap : 16;
            _vrg_push_value *grown = realloc(p->push_values, (size_t)cap * sizeof *grown);
            if (!grown) {
                _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "%s(\"%s\"): out of memory", setter, member);
                return;
            }
            p->push_values = grown;
            p->push_cap = cap;
        }
        v = &p->push_values[p->push_count++];
    }
    *v = (_vrg_push_value){.scalar = scalar, .setter = setter, .word = word};
    snprintf(v->name, sizeof v->name, "%s", member);
}

static void push_array(vrg_pass *p, const char *setter, const char *member, int scalar, const void *values, uint32_t count)
{
    if (!values || count == 0 || count > 32) {
        _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "%s(\"%.64s\"): %u values (1 to 32, the most 128 bytes of push constants hold)", setter,
                       member ? member : "(null)", count);
        return;
    }
    push_value(p, setter, member, scalar, 0);
    for (int i = 0; i < p->push_count; i++)
        if (member && strcmp(p->push_values[i].name, member) == 0) {
            memcpy(p->push_values[i].words, values, count * sizeof(uint32_t));
            p->push_values[i].count = count;
        }
}

void vrg_push_floats(vrg_pass *pass, const char *member, const float *values, uint32_t count)
{
    push_array(pass, "vrg_push_floats", member, VRG_PUSH_FLOAT, values, count);
}
void vrg_push_ints(vrg_pass *pass, const char *member, const int32_t *values, uint32_t count)
{
    push_array(pass, "vrg_push_ints", member, VRG_PUSH_INT, values, count);
}
void vrg_push_uints(vrg_pass *pass, const char *member, const uint32_t *values, uint32_t count)
{
    push_array(pass, "vrg_push_uints", member, VRG_PUSH_UINT, values, count);
}

void vrg_push_float(vrg_pass *pass, const char *member, float value)
{
    uint32_t word;
    memcpy(&word, &value, sizeof word);
    push_value(pass, "vrg_push_float", member, VRG_PUSH_FLOAT, word);
}

void vrg_push_int(vrg_pass *pass, const char *member, int32_t value) { push_value(pass, "vrg_push_int", member, VRG_PUSH_INT, (uint32_t)value); }
void vrg_push_uint(vrg_pass *pass, const char *member, uint32_t value) { push_value(pass, "vrg_push_uint", member, VRG_PUSH_UINT, value); }
void vrg_push_bool(vrg_pass *pass, const char *member, int value) { push_value(pass, "vrg_push_bool", member, VRG_PUSH_BOOL, value != 0); }

static int value_fits(int setter, _vrg_push_scalar member)
{
    return setter == (int)member || (setter == VRG_PUSH_BOOL && (member == VRG_PUSH_INT || member == VRG_PUSH_UINT));
}

/* The block's bytes from the values set (vrg_push_*) and the parameters,
 * each at its member's offset; -1 after the errors at the members' lines. */
static int pack_by_name(vrg_pass *p, const _vrg_pipeline *pl, unsigned char *out, FILE *diag)
{
    const vrg_plugin_desc *pd = p->plugin->desc;
    const char *code = _vrg_diag_info_of(VRG_E_SHADER_PUSH_MEMBER)->code;
    if (pl->push_bytes > 128) {
        fprintf(diag, "%s: error[%s]: push-constant block '%s' is %u bytes, more than the 128 a dispatch pushes\n", pl->push_where,
                _vrg_diag_info_of(VRG_E_SHADER_PUSH_SIZE)->code, pl->push_name, pl->push_bytes);
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "push constants of %s: a block of %u bytes (at most 128)", pl->path, pl->push_bytes);
    }
    int errors = 0; /* the members' types against the parameters: checked once, when pl was built (check_reflection) */
    memset(out, 0, 128);
    for (int i = 0; i < p->push_count; i++)
        p->push_values[i].used = 0;
    for (int m = 0; m < pl->member_count; m++) {
        const _vrg_push_member *pm = &pl->members[m];
        if (!member_scalar(pm) && !member_array(pm))
            continue; /* check_members said */
        _vrg_push_value *v = NULL;
        for (int i = 0; i < p->push_count && !v; i++)
            if (strcmp(p->push_values[i].name, pm->name) == 0)
                v = &p->push_values[i];
        const vrg_param_desc *param = param_named(pd, pm->name);
        uint32_t word = 0;
        if (member_array(pm)) {
            if (!v) {
                if (!param) /* else check_members said */
                    fprintf(diag, "%s: error[%s]: push-constant member '%s' (an array of %u) has no value: pass '%s' (plugin %s) set none with "
                                  "vrg_push_floats (or _ints, _uints) before this dispatch\n", pm->where, code, pm->name, pm->array_len, p->name, pd->name);
                errors += !param;
                continue;
            }
            v->used = 1;
            if (v->count != pm->array_len || v->scalar != (int)pm->scalar) {
                fprintf(diag, "%s: error[%s]: push-constant member '%s' is an array of %u %s, but pass '%s' (plugin %s) sets it with %s, %u %s\n", pm->where,
                        code, pm->name, pm->array_len, scalar_name(pm->scalar), p->name, pd->name, v->setter, v->count ? v->count : 1, scalar_name(v->scalar));
                errors++;
                continue;
            }
            for (uint32_t k = 0; k < v->count; k++)
                memcpy(out + pm->offset + k * pm->array_stride, &v->words[k], sizeof(uint32_t));
            continue;
        }
        if (v) {
            v->used = 1;
            if (v->count) {
                fprintf(diag, "%s: error[%s]: push-constant member '%s' is a %s, but pass '%s' (plugin %s) sets it with %s, %u values\n", pm->where, code,
                        pm->name, scalar_name(pm->scalar), p->name, pd->name, v->setter, v->count);
                errors++;
                continue;
            }
            if (!value_fits(v->scalar, pm->scalar)) {
                fprintf(diag, "%s: error[%s]: push-constant member '%s' is a %s, but pass '%s' (plugin %s) sets it with %s, a %s\n", pm->where, code, pm->name,
                        scalar_name(pm->scalar), p->name, pd->name, v->setter, scalar_name(v->scalar));
                errors++;
                continue;
            }
            word = v->word;
        } else if (param && param->type == VRG_PARAM_STRING && _vrg_param_choices(pd, (uint32_t)(param - pd->params))) {
            if (pm->scalar != VRG_PUSH_INT && pm->scalar != VRG_PUSH_UINT)
                continue; /* check_members said */
            int k = _vrg_pass_choice(p, (uint32_t)(param - pd->params));
            if (k < 0) { /* validation refused such a graph: a value set since */
                fprintf(diag, "%s: error[%s]: push-constant member '%s': parameter '%s' of pass '%s' (plugin %s) is '%s', none of %s\n", pm->where, code,
                        pm->name, param->name, p->name, pd->name, vrg_param_string(p, param->name), _vrg_param_choices(pd, (uint32_t)(param - pd->params)));
                errors++;
                continue;
            }
            word = (uint32_t)k;
        } else if (param && param->type == VRG_PARAM_STRING) {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' has no value: parameter '%s' of pass '%s' (plugin %s) is a string, which is not pushed: "
                          "set the member with vrg_push_int (e.g. vrg_param_choice's index) before this dispatch\n", pm->where, code, pm->name, param->name, p->name,
                    pd->name);
            errors++;
            continue;
        } else if (param) {
            if (!param_fits(param, pm))
                continue; /* check_members said */
            double x = vrg_param(p, param->name);
            if (pm->scalar == VRG_PUSH_FLOAT) {
                float f = (float)x;
                memcpy(&word, &f, sizeof word);
            } else if (param->type == VRG_PARAM_BOOL)
                word = x != 0;
            else if (pm->scalar == VRG_PUSH_INT)
                word = (uint32_t)(int32_t)x;
            else
                word = (uint32_t)x;
        } else {
            fprintf(diag, "%s: error[%s]: push-constant member '%s' has no value: pass '%s' (plugin %s) has no parameter '%s' and set none with vrg_push_* "
                          "before this dispatch\n", pm->where, code, pm->name, p->name, pd->name, pm->name);
            errors++;
            continue;
        }
        memcpy(out + pm->offset, &word, sizeof word);
    }
    for (int i = 0; i < p->push_count; i++) {
        const _vrg_push_value *v = &p->push_values[i];
        if (v->used)
            continue;
        char names[512] = "";
        for (int m = 0; m < pl->member_count; m++) {
            size_t len = strlen(names);
            snprintf(names + len, sizeof names - len, "%s%s", m ? ", " : "", pl->members[m].name);
        }
        if (pl->member_count)
            fprintf(diag, "%s: error[%s]: pass '%s' (plugin %s) sets '%s' (%s), but push-constant block '%s' has no member '%s' (its members: %s)\n", pl->push_where,
                    code, p->name, pd->name, v->name, v->setter, pl->push_name, v->name, names);
        else
            fprintf(diag, "%s: error[%s]: pass '%s' (plugin %s) sets '%s' (%s), but the shader declares no push-constant block\n", pl->push_where, code, p->name,
                    pd->name, v->name, v->setter);
        errors++;
    }
    if (errors)
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "push constants of %s do not match what the pass pushes by name (above)", pl->path);
    return 0;
}

static int dispatch_one(vrg_pass *p, VkCommandBuffer cmd, const vrg_dispatch_desc *d);

int vrg_dispatch(vrg_pass *p, VkCommandBuffer cmd, const vrg_dispatch_desc *d)
{
    int rc = dispatch_one(p, cmd, d);
    p->push_count = 0; /* consumed, whatever happened */
    return rc;
}

static int dispatch_one(vrg_pass *p, VkCommandBuffer cmd, const vrg_dispatch_desc *d)
{
    vrg_graph *g = p->graph;
    const vrg_plugin_desc *pd = p->plugin->desc;
    if (pd->dispatch_count && !declared(pd, d))
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH,
                              "dispatch of %s (defines '%s', push_size %u) is none of the %u its plugin lists in vrg_plugin_desc.dispatches: list every variant it records",
                              d->shader ? d->shader : "(no shader)", d->defines ? d->defines : "", d->push_size, pd->dispatch_count);
    bound b[VRG_MAX_BINDINGS];
    bound_set bs;
    char defines[sizeof((_vrg_pipeline *)0)->defines];
    int n = describe_dispatch(p, d, b, &bs, defines, sizeof defines);
    if (n < 0)
        return -1;
    const VkDescriptorType *types = bs.types;
    _vrg_pipeline *pl = get_pipeline(p, d->shader, defines, &bs);
    if (!pl)
        return -1;
    FILE *diag = g->diag.out ? g->diag.out : stderr;
    const void *push = d->push;
    uint32_t push_size = d->push_size;
    unsigned char packed[128];
    if (!d->push_size) {
        if (pack_by_name(p, pl, packed, diag) != 0)
            return -1;
        push = packed;
        push_size = pl->push_bytes;
    } else if (p->push_count) {
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "'%s' was set with %s, but this dispatch of %s pushes its own %u bytes (push_size): push_size 0 packs by name",
                              p->push_values[0].name, p->push_values[0].setter, pl->path, d->push_size);
    } else if (pl->push_bytes != d->push_size) { /* another dispatch of the same pipeline */
        fprintf(diag, "%s: error[%s]: push-constant block is %u bytes, but pass '%s' (plugin %s) pushes %u (vrg_dispatch_desc.push_size)\n", pl->push_where,
                _vrg_diag_info_of(VRG_E_SHADER_PUSH_SIZE)->code, pl->push_bytes, p->name, p->plugin->desc->name, d->push_size);
        return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "push constants of %u bytes for shader %s, which reads %u", d->push_size, pl->path, pl->push_bytes);
    }

    _vrg_barrier_rec bars[VRG_MAX_BINDINGS];
    int nb = 0;
    VkWriteDescriptorSet w[VRG_MAX_BINDINGS];
    VkDescriptorImageInfo ii[VRG_MAX_BINDINGS];
    VkDescriptorBufferInfo bi[VRG_MAX_BINDINGS];
    VkWriteDescriptorSetAccelerationStructureKHR ai[VRG_MAX_BINDINGS];
    VkBufferView tv[VRG_MAX_BINDINGS];
    for (int i = 0; i < n; i++) {
        _vrg_resource *r = &g->res[b[i].res];
        int copy = _vrg_copy_of(g, b[i].res, b[i].prev);
        if (_vrg_resource_barrier(g, b[i].res, copy, b[i].access, &bars[nb]))
            nb++;
        w[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstBinding = (uint32_t)i, .descriptorCount = 1, .descriptorType = types[i]};
        if (r->kind == VRG_ACCEL) {
            ai[i] = (VkWriteDescriptorSetAccelerationStructureKHR){
                .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR, .accelerationStructureCount = 1, .pAccelerationStructures = &r->accel};
            w[i].pNext = &ai[i];
        } else if (r->kind == VRG_IMAGE) {
            _vrg_access_info info = _vrg_access_info_of(b[i].access, VRG_IMAGE);
            VkSampler sampler = r->mips > 1 ? g->ctx->sampler_mips : g->ctx->sampler_linear;
            ii[i] = (VkDescriptorImageInfo){.sampler = sampler, .imageView = r->view[copy], .imageLayout = info.layout};
            w[i].pImageInfo = &ii[i];
        } else if (types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
            /* the writer's texel format (validate.c); internal buffers: words */
            VkFormat texel = r->format ? r->format : VK_FORMAT_R32_UINT;
            uint64_t texels = r->size / _vrg_format_bytes(texel), max = g->ctx->dev.features.max_texel_buffer_texels;
            if (texels > max)
                return _vrg_pass_fail(p, VRG_E_DEVICE_UNSUPPORTED, "binding %d: buffer '%s' holds %llu %s texels, more than this device's texel buffers can (%llu)", i, r->name,
                                      (unsigned long long)texels, _vrg_format_name(texel), (unsigned long long)max);
            if (!r->texel_view[copy]) {
                VkBufferViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO, .buffer = r->buffer[copy],
                                             .format = texel, .range = VK_WHOLE_SIZE};
                if (vkCreateBufferView(g->ctx->dev.device, &vi, NULL, &r->texel_view[copy]) != VK_SUCCESS)
                    return _vrg_pass_fail(p, VRG_E_VULKAN_FAILED, "binding %d: cannot create a texel view of buffer '%s'", i, r->name);
            }
            tv[i] = r->texel_view[copy];
            w[i].pTexelBufferView = &tv[i];
        } else {
            bi[i] = (VkDescriptorBufferInfo){.buffer = r->buffer[copy], .offset = 0, .range = VK_WHOLE_SIZE};
            w[i].pBufferInfo = &bi[i];
        }
    }
    _vrg_emit_barriers(g, cmd, bars, nb);

    const vrg_dispatch_desc groups = _vrg_dispatch_desc_defaults(d);
    uint32_t gx = groups.groups_x, gy = groups.groups_y, gz = groups.groups_z;
    if (!gx) {
        int dom = -1;
        if (d->domain) {
            int prev, slot;
            if (_vrg_pass_lookup(p, d->domain, &dom, &prev, &slot) != 0)
                return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "dispatch domain '%s' is not a resource of this pass", d->domain);
        } else {
            for (uint32_t s = 0; s < p->plugin->desc->slot_count && dom < 0; s++)
                if (vrg_slot(p, (int)s)->dir == VRG_OUT && vrg_slot(p, (int)s)->kind == VRG_IMAGE)
                    dom = p->slots[s].res;
            if (dom < 0)
                return _vrg_pass_fail(p, VRG_E_BAD_DISPATCH, "dispatch has no domain: no image output; set domain or groups_x");
        }
        uint32_t tile[2] = {pl->local[0], pl->local[1]};
        if (d->pixel_loop) {
            if (pixel_loop_fits(p, d->shader, pl->local) != 0)
                return -1;
            tile[0] = g->ctx->pixel_tile[0], tile[1] = g->ctx->pixel_tile[1];
        }
        gx = (g->res[dom].width + tile[0] - 1) / tile[0];
        gy = (g->res[dom].height + tile[1] - 1) / tile[1];
        if (d->pixel_loop)
            gy = (gy + g->ctx->pixel_rows - 1) / g->ctx->pixel_rows;
        gz = 1;
    }
    if (g->capture)
        _vrg_capture_dispatch(g->capture, pl->pipeline, pl->layout, (uint32_t)n, w, push, push_size, (const uint32_t[3]){gx, gy, gz});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pl->pipeline);
    if (n)
        g->ctx->push_descriptor(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pl->layout, 0, (uint32_t)n, w);
    if (push_size)
        vkCmdPushConstants(cmd, pl->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size, push);
    vkCmdDispatch(cmd, gx, gy, gz);
    return 0;
}

/* Whether a shader-only pass's optional slot counts as connected for its
 * variant: an acceleration structure only where it exists (a scene of
 * size 0 builds none, and nothing stands in for it). */
static int shader_slot_present(const vrg_pass *pass, int slot)
{
    vrg_res h = vrg_pass_res(pass, pass->plugin->shader_pass->binding_res[slot]);
    if (!vrg_res_connected(h))
        return 0;
    return pass->plugin->desc->slots[slot].kind != VRG_ACCEL || accel_exists(pass->graph, h.id >> 1);
}

/* The variant a shader-only pass records: the index into its dispatches. */
static uint32_t shader_variant(vrg_pass *pass)
{
    const struct _vrg_shader_pass *sp = pass->plugin->shader_pass;
    uint32_t k = 0, stride = 1;
    for (int a = 0; a < sp->axis_count; a++) {
        const struct _vrg_shader_axis *ax = &sp->axes[a];
        int v = ax->slot >= 0 ? shader_slot_present(pass, ax->slot) : _vrg_pass_choice(pass, (uint32_t)ax->param);
        k += (uint32_t)(v < 0 ? 0 : v) * stride;
        stride *= (uint32_t)ax->count;
    }
    return k;
}

/* A shader-only pass (shader_pass.c) is one dispatch of its shader, its
 * push constants packed by name from its parameters (push_size 0): the
 * variant its optional slots' connections and its variant choices pick. */
void _vrg_shader_pass_execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    (void)vrg_dispatch(pass, cmd, &pass->plugin->shader_pass->dispatches[shader_variant(pass)]);
}

/* Whether variant k of a shader-only pass can be recorded in this graph:
 * its optional acceleration structures connected exactly where they exist
 * (the variants that bind an absent one, or leave out a present one, are
 * never picked). Every other axis's values can be. */
static int shader_variant_possible(const vrg_pass *pass, uint32_t k)
{
    const struct _vrg_shader_pass *sp = pass->plugin->shader_pass;
    for (int a = 0; sp && a < sp->axis_count; k /= (uint32_t)sp->axes[a].count, a++) {
        const struct _vrg_shader_axis *ax = &sp->axes[a];
        if (ax->slot >= 0 && sp->slots[ax->slot].kind == VRG_ACCEL && (int)(k % (uint32_t)ax->count) != shader_slot_present(pass, ax->slot))
            return 0;
    }
    return 1;
}

/* A pass without execute: its listed dispatches, in order (loader: a pass
 * plugin may leave execute NULL only when it lists some). */
void _vrg_dispatch_listed(vrg_pass *pass, VkCommandBuffer cmd)
{
    const vrg_plugin_desc *d = pass->plugin->desc;
    for (uint32_t i = 0; i < d->dispatch_count && !pass->failed; i++)
        (void)vrg_dispatch(pass, cmd, &d->dispatches[i]);
}

/* ---- vrg_graph_check_shaders: every declared dispatch, before any frame ---- */

typedef struct shader_check_count {
    uint32_t dispatches, failed, unknown;
} shader_check_count;

/* One declared dispatch: resolved, compiled (with the device's workgroup
 * shape, or a GPU's without one) and reflected against its bindings, as
 * its first vrg_dispatch would. */
static int check_declared(vrg_pass *p, const vrg_dispatch_desc *d, shader_check_count *count)
{
    vrg_graph *g = p->graph;
    FILE *diag = g->diag.out ? g->diag.out : stderr;
    bound b[VRG_MAX_BINDINGS];
    bound_set bs;
    char defines[sizeof((_vrg_pipeline *)0)->defines], path[VRG_PATH_MAX];
    if (describe_dispatch(p, d, b, &bs, defines, sizeof defines) < 0)
        return -1;
    for (uint32_t i = 0; i < bs.count; i++)
        count->unknown += bs.unknown[i];
    if (shader_path(p, d->shader, path, sizeof path) != 0)
        return -1;
    _vrg_shader_module sm;
    if (_vrg_shader_compile(g->ctx, path, defines, &sm, diag) != 0)
        return _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader %s failed to compile", path);
    if (sm.module)
        vkDestroyShaderModule(g->ctx->dev.device, sm.module, NULL);
    free(sm.deps);
    int rc = check_reflection(p, path, &bs, &sm.refl, diag);
    _vrg_reflection_free(&sm.refl);
    if (rc == 0 && d->pixel_loop)
        return pixel_loop_fits(p, path, sm.local_size);
    if (rc != 0)
        return _vrg_pass_fail(p, VRG_E_SHADER_FAILED, "shader %s does not match what the pass binds", path);
    return 0;
}

int vrg_graph_check_shaders(vrg_graph *g, FILE *report)
{
    int failed = 0;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        const vrg_plugin_desc *pd = p->plugin->desc;
        shader_check_count count = {0};
        int was_failed = p->failed;
        for (uint32_t i = 0; i < pd->dispatch_count; i++) {
            if (!shader_variant_possible(p, i))
                continue;
            count.dispatches++;
            if (check_declared(p, &pd->dispatches[i], &count) != 0)
                count.failed++;
        }
        p->failed = was_failed; /* a check, not a frame: the return value says it */
        failed |= count.failed != 0;
        if (!report)
            continue;
        if (!pd->dispatch_count)
            fprintf(report, "  %-16s %-16s lists no dispatches (vrg_plugin_desc.dispatches): what it dispatches is checked when it runs\n", p->name, pd->name);
        else
            fprintf(report, "  %-16s %-16s %u dispatch%s compiled and reflected%s%s", p->name, pd->name, count.dispatches, count.dispatches == 1 ? "" : "es",
                    count.failed ? ", FAILED" : "", count.unknown ? "" : "\n");
        if (count.unknown)
            fprintf(report, "; %u binding%s to internal resources checked with a device only\n", count.unknown, count.unknown == 1 ? "" : "s");
    }
    return failed ? -1 : 0;
}
