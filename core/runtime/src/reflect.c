/* What a compiled compute shader declares, read from its SPIR-V with
 * SPIRV-Cross's C API: each descriptor binding (set, number, descriptor
 * type, a storage image's format qualifier, name) and the push-constant
 * block's size and members, each with the GLSL line that declares it, so that
 * dispatch.c can check them against what a pass binds. */
#include <spirv_cross_c.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "reflect.h"

/* GLSL's image format qualifiers, as SPIR-V and Vulkan name them. */
static const struct {
    SpvImageFormat spv;
    VkFormat vk;
    const char *glsl;
} image_formats[] = {
    {SpvImageFormatRgba32f, VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32f"},
    {SpvImageFormatRgba16f, VK_FORMAT_R16G16B16A16_SFLOAT, "rgba16f"},
    {SpvImageFormatR32f, VK_FORMAT_R32_SFLOAT, "r32f"},
    {SpvImageFormatRgba8, VK_FORMAT_R8G8B8A8_UNORM, "rgba8"},
    {SpvImageFormatRgba8Snorm, VK_FORMAT_R8G8B8A8_SNORM, "rgba8_snorm"},
    {SpvImageFormatRg32f, VK_FORMAT_R32G32_SFLOAT, "rg32f"},
    {SpvImageFormatRg16f, VK_FORMAT_R16G16_SFLOAT, "rg16f"},
    {SpvImageFormatR11fG11fB10f, VK_FORMAT_B10G11R11_UFLOAT_PACK32, "r11f_g11f_b10f"},
    {SpvImageFormatR16f, VK_FORMAT_R16_SFLOAT, "r16f"},
    {SpvImageFormatRgba16, VK_FORMAT_R16G16B16A16_UNORM, "rgba16"},
    {SpvImageFormatRgb10A2, VK_FORMAT_A2B10G10R10_UNORM_PACK32, "rgb10_a2"},
    {SpvImageFormatRg16, VK_FORMAT_R16G16_UNORM, "rg16"},
    {SpvImageFormatRg8, VK_FORMAT_R8G8_UNORM, "rg8"},
    {SpvImageFormatR16, VK_FORMAT_R16_UNORM, "r16"},
    {SpvImageFormatR8, VK_FORMAT_R8_UNORM, "r8"},
    {SpvImageFormatRgba16Snorm, VK_FORMAT_R16G16B16A16_SNORM, "rgba16_snorm"},
    {SpvImageFormatRg16Snorm, VK_FORMAT_R16G16_SNORM, "rg16_snorm"},
    {SpvImageFormatRg8Snorm, VK_FORMAT_R8G8_SNORM, "rg8_snorm"},
    {SpvImageFormatR16Snorm, VK_FORMAT_R16_SNORM, "r16_snorm"},
    {SpvImageFormatR8Snorm, VK_FORMAT_R8_SNORM, "r8_snorm"},
    {SpvImageFormatRgba32i, VK_FORMAT_R32G32B32A32_SINT, "rgba32i"},
    {SpvImageFormatRgba16i, VK_FORMAT_R16G16B16A16_SINT, "rgba16i"},
    {SpvImageFormatRgba8i, VK_FORMAT_R8G8B8A8_SINT, "rgba8i"},
    {SpvImageFormatR32i, VK_FORMAT_R32_SINT, "r32i"},
    {SpvImageFormatRg32i, VK_FORMAT_R32G32_SINT, "rg32i"},
    {SpvImageFormatRg16i, VK_FORMAT_R16G16_SINT, "rg16i"},
    {SpvImageFormatRg8i, VK_FORMAT_R8G8_SINT, "rg8i"},
    {SpvImageFormatR16i, VK_FORMAT_R16_SINT, "r16i"},
    {SpvImageFormatR8i, VK_FORMAT_R8_SINT, "r8i"},
    {SpvImageFormatRgba32ui, VK_FORMAT_R32G32B32A32_UINT, "rgba32ui"},
    {SpvImageFormatRgba16ui, VK_FORMAT_R16G16B16A16_UINT, "rgba16ui"},
    {SpvImageFormatRgba8ui, VK_FORMAT_R8G8B8A8_UINT, "rgba8ui"},
    {SpvImageFormatR32ui, VK_FORMAT_R32_UINT, "r32ui"},
    {SpvImageFormatRgb10a2ui, VK_FORMAT_A2B10G10R10_UINT_PACK32, "rgb10_a2ui"},
    {SpvImageFormatRg32ui, VK_FORMAT_R32G32_UINT, "rg32ui"},
    {SpvImageFormatRg16ui, VK_FORMAT_R16G16_UINT, "rg16ui"},
    {SpvImageFormatRg8ui, VK_FORMAT_R8G8_UINT, "rg8ui"},
    {SpvImageFormatR16ui, VK_FORMAT_R16_UINT, "r16ui"},
    {SpvImageFormatR8ui, VK_FORMAT_R8_UINT, "r8ui"},
};

const char *_vrg_glsl_format_name(VkFormat f)
{
    for (size_t i = 0; i < sizeof image_formats / sizeof image_formats[0]; i++)
        if (image_formats[i].vk == f)
            return image_formats[i].glsl;
    return _vrg_format_name(f);
}

const char *_vrg_spv_format_glsl(int spv_format)
{
    for (size_t i = 0; i < sizeof image_formats / sizeof image_formats[0]; i++)
        if ((int)image_formats[i].spv == spv_format)
            return image_formats[i].glsl;
    return NULL;
}

static VkFormat vk_format_of(SpvImageFormat f)
{
    for (size_t i = 0; i < sizeof image_formats / sizeof image_formats[0]; i++)
        if (image_formats[i].spv == f)
            return image_formats[i].vk;
    return VK_FORMAT_UNDEFINED;
}

const char *_vrg_descriptor_type_name(VkDescriptorType t)
{
    switch (t) {
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "a storage image";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "a sampled image (sampler2D)";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return "a separate image (texture2D)";
    case VK_DESCRIPTOR_TYPE_SAMPLER: return "a separate sampler";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "a storage buffer";
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "a uniform buffer";
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: return "a uniform texel buffer (samplerBuffer)";
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: return "a storage texel buffer (imageBuffer)";
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR: return "an acceleration structure";
    default: return "another descriptor type";
    }
}

/* ---- the declaring line, from the expanded source ---- */

static int is_word_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

static int has_word(const char *s, size_t n, const char *word)
{
    size_t w = strlen(word);
    if (!w)
        return 0;
    for (size_t i = 0; i + w <= n; i++)
        if (strncmp(s + i, word, w) == 0 && (i == 0 || !is_word_char(s[i - 1])) && (i + w == n || !is_word_char(s[i + w])))
            return 1;
    return 0;
}

/* "binding = N" with a literal N on this line: N, else -1. */
static long literal_binding(const char *s, size_t n)
{
    for (size_t i = 0; i + 7 <= n; i++) {
        if (strncmp(s + i, "binding", 7) != 0 || (i && is_word_char(s[i - 1])))
            continue;
        size_t j = i + 7;
        while (j < n && (s[j] == ' ' || s[j] == '\t'))
            j++;
        if (j >= n || s[j] != '=')
            continue;
        j++;
        while (j < n && (s[j] == ' ' || s[j] == '\t'))
            j++;
        if (j < n && s[j] >= '0' && s[j] <= '9')
            return strtol(s + j, NULL, 10);
    }
    return -1;
}

#define ANY_LINE (-2L)

/* A `#line N "FILE"` directive at p (n bytes): file and line follow it
 * (line counts the next line as N); 0 for any other line. */
static int line_directive(const char *p, size_t n, char *file, size_t cap, int *line)
{
    const char *s = p;
    while (s < p + n && (*s == ' ' || *s == '\t'))
        s++;
    if (strncmp(s, "#line", 5) != 0)
        return 0;
    char *q;
    long l = strtol(s + 5, &q, 10);
    const char *quote = memchr(q, '"', (size_t)(p + n - q));
    const char *close = quote ? memchr(quote + 1, '"', (size_t)(p + n - quote - 1)) : NULL;
    if (close)
        snprintf(file, cap, "%.*s", (int)(close - quote - 1), quote + 1);
    *line = (int)l - 1;
    return 1;
}

/* The source expanded by shader.c carries `#line N "file"` where an include
 * starts and ends; FILE:LINE of the declaration of a resource: the line
 * with `key` (binding, push_constant) and its name (or block name), preferring one whose literal
 * binding number matches (an #ifdef may declare a name twice), then any
 * line with a literal `binding = N`. where stays the shader's path when no
 * line is found (bindings from macros of other names). */
static void find_line(const char *src, const char *path, const char *key, const char *name, const char *block, long binding, char *where, size_t cap)
{
    char file[VRG_PATH_MAX];
    snprintf(file, sizeof file, "%s", path);
    int line = 0, best_rank = 0;
    snprintf(where, cap, "%s", path);
    for (const char *p = src; p && *p;) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        line++;
        if (!line_directive(p, n, file, sizeof file, &line) && has_word(p, n, key)) {
            int named = has_word(p, n, name) || (block && has_word(p, n, block));
            long lit = literal_binding(p, n);
            int rank = named && lit == binding ? 3 : named ? 2 : lit == binding || binding == ANY_LINE ? 1 : 0;
            if (rank > best_rank) {
                best_rank = rank;
                snprintf(where, cap, "%s:%d", file, line);
                if (rank == 3)
                    return;
            }
        }
        p = end ? end + 1 : NULL;
    }
}

/* FILE:LINE of a push-constant member: the first line after the one with
 * `push_constant` that has its name as a word (the block's own line when
 * the member is declared on it). `where` keeps its value when none is. */
static void find_member_line(const char *src, const char *member, char *where, size_t cap)
{
    char file[VRG_PATH_MAX] = "";
    int line = 0, in_block = 0;
    for (const char *p = src; p && *p;) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        line++;
        if (!line_directive(p, n, file, sizeof file, &line)) {
            const char *comment = NULL;
            for (size_t i = 0; i + 1 < n && !comment; i++)
                if (p[i] == '/' && p[i + 1] == '/')
                    comment = p + i;
            size_t code = comment ? (size_t)(comment - p) : n;
            in_block |= has_word(p, code, "push_constant");
            if (in_block && has_word(p, code, member)) {
                if (file[0])
                    snprintf(where, cap, "%s:%d", file, line);
                return;
            }
        }
        p = end ? end + 1 : NULL;
    }
}

/* ---- reflection ---- */

static VkDescriptorType descriptor_type_of(spvc_resource_type rt, spvc_type type)
{
    int buffer_dim = (rt == SPVC_RESOURCE_TYPE_STORAGE_IMAGE || rt == SPVC_RESOURCE_TYPE_SAMPLED_IMAGE || rt == SPVC_RESOURCE_TYPE_SEPARATE_IMAGE) &&
                     spvc_type_get_image_dimension(type) == SpvDimBuffer;
    switch (rt) {
    case SPVC_RESOURCE_TYPE_UNIFORM_BUFFER: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case SPVC_RESOURCE_TYPE_STORAGE_BUFFER: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case SPVC_RESOURCE_TYPE_STORAGE_IMAGE: return buffer_dim ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case SPVC_RESOURCE_TYPE_SAMPLED_IMAGE: return buffer_dim ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case SPVC_RESOURCE_TYPE_SEPARATE_IMAGE: return buffer_dim ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS: return VK_DESCRIPTOR_TYPE_SAMPLER;
    default: return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    }
}

static int add_binding(_vrg_reflection *r, const _vrg_reflected_binding *b)
{
    if (r->count == r->cap) {
        int cap = r->cap ? 2 * r->cap : 8;
        _vrg_reflected_binding *grown = realloc(r->bindings, (size_t)cap * sizeof *grown);
        if (!grown)
            return -1;
        r->bindings = grown;
        r->cap = cap;
    }
    r->bindings[r->count++] = *b;
    return 0;
}

/* readonly / writeonly: on an image variable; glslang puts a buffer's on
 * each member of its block. */
static void access_qualifiers(spvc_compiler comp, const spvc_reflected_resource *r, int buffer, _vrg_reflected_binding *b)
{
    b->readonly = spvc_compiler_has_decoration(comp, r->id, SpvDecorationNonWritable);
    b->writeonly = spvc_compiler_has_decoration(comp, r->id, SpvDecorationNonReadable);
    if (!buffer || b->readonly || b->writeonly)
        return;
    unsigned members = spvc_type_get_num_member_types(spvc_compiler_get_type_handle(comp, r->base_type_id));
    int all_nw = members > 0, all_nr = members > 0;
    for (unsigned m = 0; m < members; m++) {
        all_nw &= spvc_compiler_has_member_decoration(comp, r->base_type_id, m, SpvDecorationNonWritable) != 0;
        all_nr &= spvc_compiler_has_member_decoration(comp, r->base_type_id, m, SpvDecorationNonReadable) != 0;
    }
    b->readonly = all_nw;
    b->writeonly = all_nr;
}

static _vrg_push_scalar scalar_of(spvc_basetype t)
{
    switch (t) {
    case SPVC_BASETYPE_FP32: return VRG_PUSH_FLOAT;
    case SPVC_BASETYPE_INT32: return VRG_PUSH_INT;
    case SPVC_BASETYPE_UINT32: return VRG_PUSH_UINT;
    case SPVC_BASETYPE_BOOLEAN: return VRG_PUSH_BOOL;
    default: return VRG_PUSH_OTHER;
    }
}

/* Each member of the push-constant block: name, offset, size and type. */
static int push_members(spvc_compiler comp, spvc_type_id base_id, spvc_type type, const char *src, _vrg_reflection *out)
{
    unsigned n = spvc_type_get_num_member_types(type);
    out->push_members = calloc(n ? n : 1, sizeof *out->push_members);
    if (!out->push_members)
        return -1;
    for (unsigned m = 0; m < n; m++) {
        _vrg_push_member *pm = &out->push_members[m];
        spvc_type mt = spvc_compiler_get_type_handle(comp, spvc_type_get_member_type(type, m));
        const char *name = spvc_compiler_get_member_name(comp, base_id, m);
        unsigned offset = 0;
        size_t size = 0;
        if (spvc_compiler_type_struct_member_offset(comp, type, m, &offset) != SPVC_SUCCESS ||
            spvc_compiler_get_declared_struct_member_size(comp, type, m, &size) != SPVC_SUCCESS)
            return -1;
        snprintf(pm->name, sizeof pm->name, "%s", name ? name : "");
        pm->offset = offset;
        pm->size = (uint32_t)size;
        pm->scalar = scalar_of(spvc_type_get_basetype(mt));
        pm->vecsize = spvc_type_get_vector_size(mt);
        pm->columns = spvc_type_get_columns(mt);
        pm->array_dims = spvc_type_get_num_array_dimensions(mt);
        unsigned stride = 0;
        if (pm->array_dims == 1 && spvc_type_array_dimension_is_literal(mt, 0) &&
            spvc_compiler_type_struct_member_array_stride(comp, type, m, &stride) == SPVC_SUCCESS) {
            pm->array_len = (uint32_t)spvc_type_get_array_dimension(mt, 0);
            pm->array_stride = stride;
        }
        snprintf(pm->where, sizeof pm->where, "%s", out->push_where);
        find_member_line(src, pm->name, pm->where, sizeof pm->where);
    }
    out->push_member_count = (int)n;
    return 0;
}

static int reflect_resources(spvc_compiler comp, spvc_resources res, const char *src, const char *path, _vrg_reflection *out)
{
    static const spvc_resource_type kinds[] = {
        SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, SPVC_RESOURCE_TYPE_STORAGE_BUFFER,   SPVC_RESOURCE_TYPE_STORAGE_IMAGE,         SPVC_RESOURCE_TYPE_SAMPLED_IMAGE,
        SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS, SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE,
    };
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        const spvc_reflected_resource *list;
        size_t count;
        if (spvc_resources_get_resource_list_for_type(res, kinds[k], &list, &count) != SPVC_SUCCESS)
            return -1;
        for (size_t i = 0; i < count; i++) {
            spvc_type type = spvc_compiler_get_type_handle(comp, list[i].type_id);
            _vrg_reflected_binding b = {
                .set = spvc_compiler_get_decoration(comp, list[i].id, SpvDecorationDescriptorSet),
                .binding = spvc_compiler_get_decoration(comp, list[i].id, SpvDecorationBinding),
                .type = descriptor_type_of(kinds[k], type),
            };
            b.image_dim = -1;
            if (kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_IMAGE || kinds[k] == SPVC_RESOURCE_TYPE_SAMPLED_IMAGE || kinds[k] == SPVC_RESOURCE_TYPE_SEPARATE_IMAGE)
                b.image_dim = (int)spvc_type_get_image_dimension(type);
            if (kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_BUFFER || kinds[k] == SPVC_RESOURCE_TYPE_UNIFORM_BUFFER) {
                spvc_type base = spvc_compiler_get_type_handle(comp, list[i].base_type_id);
                size_t bytes = 0;
                if (spvc_compiler_get_declared_struct_size(comp, base, &bytes) == SPVC_SUCCESS)
                    b.block_bytes = bytes;
                unsigned members = spvc_type_get_num_member_types(base);
                if (members) {
                    spvc_type last = spvc_compiler_get_type_handle(comp, spvc_type_get_member_type(base, members - 1));
                    unsigned dims = spvc_type_get_num_array_dimensions(last);
                    b.runtime_array = dims > 0 && spvc_type_get_array_dimension(last, 0) == 0;
                }
            }
            if (kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_IMAGE) {
                b.spv_format = (int)spvc_type_get_image_storage_format(type);
                b.format = vk_format_of(spvc_type_get_image_storage_format(type));
            }
            if (kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_IMAGE || kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_BUFFER)
                access_qualifiers(comp, &list[i], kinds[k] == SPVC_RESOURCE_TYPE_STORAGE_BUFFER, &b);
            const char *name = spvc_compiler_get_name(comp, list[i].id);
            const char *block = spvc_compiler_get_name(comp, list[i].base_type_id);
            snprintf(b.name, sizeof b.name, "%s", name && *name ? name : list[i].name);
            find_line(src, path, "binding", b.name, block, (long)b.binding, b.where, sizeof b.where);
            if (add_binding(out, &b) != 0)
                return -1;
        }
    }
    const spvc_reflected_resource *push;
    size_t push_count;
    if (spvc_resources_get_resource_list_for_type(res, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, &push, &push_count) != SPVC_SUCCESS)
        return -1;
    for (size_t i = 0; i < push_count; i++) {
        size_t size = 0;
        spvc_type type = spvc_compiler_get_type_handle(comp, push[i].base_type_id);
        if (spvc_compiler_get_declared_struct_size(comp, type, &size) != SPVC_SUCCESS)
            return -1;
        out->push_bytes = (uint32_t)size;
        const char *block = spvc_compiler_get_name(comp, push[i].base_type_id);
        snprintf(out->push_name, sizeof out->push_name, "%s", block && *block ? block : push[i].name);
        find_line(src, path, "push_constant", out->push_name, NULL, ANY_LINE, out->push_where, sizeof out->push_where);
        if (push_members(comp, push[i].base_type_id, type, src, out) != 0)
            return -1;
    }
    return 0;
}

int _vrg_reflect(const uint32_t *spv, size_t words, const char *src, const char *path, _vrg_reflection *out, FILE *diag)
{
    memset(out, 0, sizeof *out);
    spvc_context ctx = NULL;
    spvc_parsed_ir ir = NULL;
    spvc_compiler comp = NULL;
    spvc_resources res = NULL;
    int rc = -1;
    if (spvc_context_create(&ctx) == SPVC_SUCCESS && spvc_context_parse_spirv(ctx, spv, words, &ir) == SPVC_SUCCESS &&
        spvc_context_create_compiler(ctx, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &comp) == SPVC_SUCCESS &&
        spvc_compiler_create_shader_resources(comp, &res) == SPVC_SUCCESS)
        rc = reflect_resources(comp, res, src, path, out);
    if (rc != 0) {
        fprintf(diag, "%s: error[%s]: cannot reflect the compiled shader: %s\n", path, _vrg_diag_info_of(VRG_E_SHADER_FAILED)->code,
                ctx ? spvc_context_get_last_error_string(ctx) : "out of memory");
        _vrg_reflection_free(out);
    }
    if (ctx)
        spvc_context_destroy(ctx);
    return rc;
}

void _vrg_reflection_free(_vrg_reflection *r)
{
    free(r->bindings);
    free(r->push_members);
    memset(r, 0, sizeof *r);
}
