/* reflect.c: what a compiled shader declares (its bindings and push
 * constants), which the dispatch helper checks against what it binds. */
#ifndef VRG_REFLECT_H
#define VRG_REFLECT_H

#include "internal.h"

typedef struct _vrg_reflected_binding {
    uint32_t set, binding;
    VkDescriptorType type;
    VkFormat format; /* storage images: the format qualifier (UNDEFINED: none, or one with no VkFormat here) */
    int spv_format;  /* storage images: the qualifier as SPIR-V has it (0, SpvImageFormatUnknown: none) */
    int readonly, writeonly; /* storage images and buffers: declared so (every member of a buffer) */
    int image_dim;           /* images: SpvDim (1: 2D), else -1 */
    uint64_t block_bytes;    /* buffers: the block's declared size (a runtime array counts 0) */
    int runtime_array;       /* buffers: the block ends in an unsized array */
    char name[64];
    char where[VRG_PATH_MAX + 16]; /* FILE:LINE of its declaration */
} _vrg_reflected_binding;
/* A member of the push-constant block, by name: what a runtime that packs
 * push constants from named values needs (shader_pass.c). */
typedef enum { VRG_PUSH_OTHER, VRG_PUSH_FLOAT, VRG_PUSH_INT, VRG_PUSH_UINT, VRG_PUSH_BOOL } _vrg_push_scalar;
typedef struct _vrg_push_member {
    char name[64];
    uint32_t offset, size;
    _vrg_push_scalar scalar; /* the element's scalar type (OTHER: a struct, double, 16-bit, ...) */
    uint32_t vecsize, columns, array_dims;
    uint32_t array_len, array_stride; /* a one-dimensional array of literal length: its length and stride, else 0 */
    char where[VRG_PATH_MAX + 16]; /* FILE:LINE of its declaration (the block's when not found) */
} _vrg_push_member;
typedef struct _vrg_reflection {
    _vrg_reflected_binding *bindings;
    int count, cap;
    _vrg_push_member *push_members; /* declaration order */
    int push_member_count;
    uint32_t push_bytes; /* the push-constant block's size, 0: none */
    char push_name[64];
    char push_where[VRG_PATH_MAX + 16];
} _vrg_reflection;
/* src: the expanded GLSL (with shader.c's #line directives), for the lines. */
int _vrg_reflect(const uint32_t *spv, size_t words, const char *src, const char *path, _vrg_reflection *out, FILE *diag);
void _vrg_reflection_free(_vrg_reflection *r);
const char *_vrg_glsl_format_name(VkFormat f);
/* A SPIR-V image format's GLSL qualifier, or NULL for one not in reflect.c's table. */
const char *_vrg_spv_format_glsl(int spv_format);
const char *_vrg_descriptor_type_name(VkDescriptorType t);
#endif
