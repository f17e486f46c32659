/* shader.c: run-time GLSL compilation, for the dispatch helper
 * (dispatch.c), its one user. */
#ifndef VRG_SHADER_H
#define VRG_SHADER_H

#include "internal.h"
#include "reflect.h"

typedef struct _vrg_shader_module {
    VkShaderModule module;
    uint32_t local_size[3];
    char *deps; /* the file and every file it includes, real paths, one per line (free()) */
    _vrg_reflection refl; /* _vrg_reflection_free() */
} _vrg_shader_module;
/* VRG_GROUP_X/Y shaders are compiled with: the device's, or a GPU's without one. */
void _vrg_shader_group_size(const vrg_context *ctx, uint32_t out[2]);
/* ctx NULL: compiled and reflected for a GPU's workgroup shape, no module made. */
int _vrg_shader_compile(vrg_context *ctx, const char *path, const char *defines, _vrg_shader_module *out, FILE *diag);
/* The same, and on success the expanded source (includes inlined, with
 * #line directives) in *expanded (free()). */
int _vrg_shader_compile_source(vrg_context *ctx, const char *path, const char *defines, _vrg_shader_module *out, FILE *diag, char **expanded);
/* The file with its includes inlined (#line directives), not compiled:
 * what a shader-only pass's annotations are read from before it compiles
 * (free()); NULL after reporting. */
char *_vrg_shader_expand(const char *path, FILE *diag);
/* The file of a shader a pass names (docs/plugin-abi.md, "Shader path"): 0
 * with it in out, or -1 with the places searched in `searched` (searched_cap
 * 0: not said). */
int _vrg_shader_resolve(const vrg_pass *p, const char *name, char *out, size_t cap, char *searched, size_t searched_cap);
/* $VOXRG_SHADER_OVERRIDE/name where that file exists (0, the path in out);
 * -1 where it does not or the variable is unset. */
int _vrg_shader_override(const char *name, char *out, size_t cap);

#endif
