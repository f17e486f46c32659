#define _GNU_SOURCE
/* GLSL → SPIR-V at run time with glslang's C API. #include "x.glsl" is
 * resolved next to the including file, then in the data folder's
 * shaders/include and shaders/ (vrg_data_dir: PREFIX/share/voxrg installed,
 * the source tree in the build). The order for a pass's shader file is in
 * docs/plugin-abi.md ("Where shaders are found").
 * Errors come out as FILE:LINE: error[VRG-E063]: MESSAGE (warnings VRG-W003). */
#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "internal.h"
#include "shader.h"

#define SOURCE_CODE (_vrg_diag_info_of(VRG_E_SHADER_SOURCE)->code)

static pthread_once_t glslang_once = PTHREAD_ONCE_INIT;
static void glslang_init(void) { glslang_initialize_process(); }

/* A file's text, NUL-terminated; NULL, said on diag with the path, when it
 * cannot be read or there is no memory for it. */
static char *read_file(const char *path, size_t *len, FILE *diag)
{
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f) {
        fprintf(diag, "%s: error[%s]: cannot read shader\n", path, SOURCE_CODE);
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (!buf) {
        fclose(f);
        if (n < 0)
            fprintf(diag, "%s: error[%s]: cannot read shader\n", path, SOURCE_CODE);
        else
            fprintf(diag, "%s: error[%s]: out of memory reading %ld bytes\n", path, _vrg_diag_info_of(VRG_E_OUT_OF_MEMORY)->code, n);
        return NULL;
    }
    size_t got = fread(buf, 1, (size_t)n, f);
    buf[got] = '\0';
    fclose(f);
    if (len)
        *len = got;
    return buf;
}

/* A pass's own shader file: read_file's text, and an empty file an error
 * naming it (an editor truncates the file before writing it: hot reload
 * then keeps the last good version rather than compiling nothing). */
static char *read_shader(const char *path, FILE *diag)
{
    size_t len = 0;
    char *src = read_file(path, &len, diag);
    if (src && len == 0) {
        fprintf(diag, "%s: error[%s]: the shader is empty\n", path, SOURCE_CODE);
        free(src);
        return NULL;
    }
    return src;
}

static int exists(const char *p) { return access(p, R_OK) == 0; }

/* $VOXRG_SHADER_OVERRIDE: a folder searched before everything else, for
 * shaders and included files alike: try a changed copy of a shipped
 * pass's shader without touching the tree. */
int _vrg_shader_override(const char *name, char *out, size_t cap)
{
    const char *dir = getenv("VOXRG_SHADER_OVERRIDE");
    if (!dir || !*dir)
        return -1;
    snprintf(out, cap, "%s/%s", dir, name);
    return exists(out) ? 0 : -1;
}

/* A plugin's own shader folder: NAME/ beside its NAME.so. Installed, that
 * is PREFIX/lib/voxrg/plugins/NAME/; in voxrg's build the build links it
 * to the pass's source folder. 0 with the shader's file in out; 1 when the
 * folder exists and lacks the shader; -1 when there is no such folder. */
static int own_folder_shader(const vrg_pass *p, const char *name, char *out, size_t cap)
{
    const char *so = p->plugin->source;
    const char *slash = strrchr(so, '/');
    if (!slash)
        return -1;
    snprintf(out, cap, "%.*s/%s", (int)(slash - so), so, p->plugin->name);
    struct stat st;
    if (stat(out, &st) != 0 || !S_ISDIR(st.st_mode))
        return -1;
    snprintf(out, cap, "%.*s/%s/%s", (int)(slash - so), so, p->plugin->name, name);
    if (!exists(out))
        return 1;
    /* the folder is a link to the sources in a build: messages and watches
     * name the file the user edits */
    char real[PATH_MAX];
    if (realpath(out, real) && strlen(real) < cap)
        memcpy(out, real, strlen(real) + 1);
    return 0;
}

/* Appends a place to the list of places searched; a list that does not fit
 * ends in "..." (said, not silently cut). */
static void searched_add(char *searched, size_t cap, const char *place)
{
    static const char more[] = ", ...";
    if (!searched || cap < sizeof more)
        return;
    size_t n = strlen(searched);
    if (n >= sizeof more - 1 && strcmp(searched + n - (sizeof more - 1), more) == 0)
        return; /* already cut */
    int w = snprintf(searched + n, cap - n, "%s%s", n ? ", " : "", place);
    if (w < 0 || (size_t)w >= cap - n) /* did not fit: mark the cut */
        memcpy(searched + cap - sizeof more, more, sizeof more);
}

int _vrg_shader_resolve(const vrg_pass *p, const char *name, char *out, size_t cap, char *searched, size_t searched_cap)
{
    if (searched_cap)
        searched[0] = '\0';
    if (name[0] == '/') {
        /* a one-file pass's own file (its plugin): a changed copy in
         * $VOXRG_SHADER_OVERRIDE comes first, as for a C pass's shaders */
        const char *base = strrchr(name, '/') + 1;
        if (p && p->plugin && strcmp(p->plugin->source, name) == 0 && _vrg_shader_override(base, out, cap) == 0)
            return 0;
        snprintf(out, cap, "%s", name);
        if (exists(out))
            return 0;
        searched_add(searched, searched_cap, out);
        return -1;
    }
    if (_vrg_shader_override(name, out, cap) == 0)
        return 0;
    if (getenv("VOXRG_SHADER_OVERRIDE"))
        searched_add(searched, searched_cap, "$VOXRG_SHADER_OVERRIDE");
    /* a plugin with its own folder (every installed one) reads its shaders
     * there and nowhere else of its own: never from the folder it was
     * built in, which shader_dir may name */
    int own = p ? own_folder_shader(p, name, out, cap) : -1;
    if (own == 0)
        return 0;
    if (own == 1)
        searched_add(searched, searched_cap, out);
    if (own < 0 && p && p->plugin->desc->shader_dir) {
        snprintf(out, cap, "%s/%s", p->plugin->desc->shader_dir, name);
        if (exists(out))
            return 0;
        searched_add(searched, searched_cap, out);
    }
    const char *env = getenv("VOXRG_SHADER_PATH");
    if (env && *env)
        searched_add(searched, searched_cap, "$VOXRG_SHADER_PATH");
    while (env && *env) {
        const char *c = strchr(env, ':');
        int len = c ? (int)(c - env) : (int)strlen(env);
        snprintf(out, cap, "%.*s/%s", len, env, name);
        if (exists(out))
            return 0;
        env = c ? c + 1 : env + len;
    }
    const char *data = vrg_data_dir();
    if (!*data)
        return -1;
    snprintf(out, cap, "%s/shaders/%s", data, name);
    if (exists(out))
        return 0;
    searched_add(searched, searched_cap, out);
    snprintf(out, cap, "%s/%s", data, name);
    if (exists(out))
        return 0;
    searched_add(searched, searched_cap, out);
    return -1;
}

/* glslang 12's C API has no include callbacks, so #include is expanded
 * here, with #line directives (GL_GOOGLE_cpp_style_line_directive) so that
 * errors name the right file and line. Each file is included once. */
typedef struct expand_ctx {
    const char *defines; /* "A=1 B" : #define lines after #version */
    char *out;
    size_t len, cap;
    char (*seen)[VRG_PATH_MAX]; /* every file included, grown as needed */
    int seen_count, seen_cap;
    FILE *diag;
    const char *path; /* the shader expanded, for an out-of-memory message */
    int failed, out_of_memory;
} expand_ctx;

static void emit(expand_ctx *e, const char *s, size_t n)
{
    if (e->out_of_memory)
        return;
    if (e->len + n + 1 > e->cap) {
        size_t cap = (e->len + n + 1) * 2;
        char *grown = realloc(e->out, cap);
        if (!grown) { /* said once; the expansion fails */
            fprintf(e->diag, "%s: error[%s]: out of memory expanding the shader\n", e->path, _vrg_diag_info_of(VRG_E_OUT_OF_MEMORY)->code);
            e->failed = e->out_of_memory = 1;
            return;
        }
        e->out = grown;
        e->cap = cap;
    }
    memcpy(e->out + e->len, s, n);
    e->len += n;
    e->out[e->len] = '\0';
}

static void emitf(expand_ctx *e, const char *fmt, const char *file, int line)
{
    char buf[1200];
    int n = snprintf(buf, sizeof buf, fmt, line, file);
    emit(e, buf, (size_t)(n < (int)sizeof buf ? n : (int)sizeof buf - 1));
}

static int resolve_include(const char *includer, const char *name, char *out, size_t cap)
{
    if (_vrg_shader_override(name, out, cap) == 0)
        return 0;
    const char *slash = strrchr(includer, '/');
    snprintf(out, cap, "%.*s/%s", slash ? (int)(slash - includer) : 1, slash ? includer : ".", name);
    if (exists(out))
        return 0;
    const char *data = vrg_data_dir();
    const char *dirs[] = {"shaders/include/", "shaders/", ""};
    for (int i = 0; i < 3 && *data; i++) {
        snprintf(out, cap, "%s/%s%s", data, dirs[i], name);
        if (exists(out))
            return 0;
    }
    return -1;
}

/* Adds a file to the included ones; -1 (reported) when out of memory. */
static int remember_include(expand_ctx *e, const char *resolved)
{
    if (e->seen_count == e->seen_cap) {
        int cap = e->seen_cap ? 2 * e->seen_cap : 16;
        char (*grown)[VRG_PATH_MAX] = realloc(e->seen, (size_t)cap * sizeof *grown);
        if (!grown) {
            fprintf(e->diag, "%s: error[%s]: out of memory\n", resolved, _vrg_diag_info_of(VRG_E_OUT_OF_MEMORY)->code);
            e->failed = 1;
            return -1;
        }
        e->seen = grown;
        e->seen_cap = cap;
    }
    snprintf(e->seen[e->seen_count++], sizeof e->seen[0], "%s", resolved);
    return 0;
}

static void expand(expand_ctx *e, const char *path, const char *text, int depth)
{
    int line = 0;
    const char *p = text;
    while (*p) {
        line++;
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        const char *s = p;
        while (s < p + n && (*s == ' ' || *s == '\t'))
            s++;
        int is_include = 0;
        if (s < p + n && *s == '#') {
            const char *d = s + 1;
            while (d < p + n && (*d == ' ' || *d == '\t'))
                d++;
            is_include = (size_t)(p + n - d) > 7 && strncmp(d, "include", 7) == 0;
            if (is_include) {
                const char *q = d + 7;
                while (q < p + n && (*q == ' ' || *q == '\t'))
                    q++;
                char close = *q == '"' ? '"' : *q == '<' ? '>' : 0;
                const char *qe = close ? memchr(q + 1, close, (size_t)(p + n - q - 1)) : NULL;
                char name[512], resolved[VRG_PATH_MAX], quoted[4 * 512];
                if (!qe || (size_t)(qe - q - 1) >= sizeof name) {
                    fprintf(e->diag, "%s:%d: error[%s]: malformed #include\n", path, line, SOURCE_CODE);
                    e->failed = 1;
                } else {
                    snprintf(name, sizeof name, "%.*s", (int)(qe - q - 1), q + 1);
                    if (resolve_include(path, name, resolved, sizeof resolved) != 0) {
                        fprintf(e->diag, "%s:%d: error[%s]: cannot find include file \"%s\"\n", path, line, SOURCE_CODE,
                                vrg_escape(quoted, sizeof quoted, name, strlen(name)));
                        e->failed = 1;
                    } else if (depth > 16) {
                        fprintf(e->diag, "%s:%d: error[%s]: #include nested too deeply\n", path, line, SOURCE_CODE);
                        e->failed = 1;
                    } else {
                        int seen = 0;
                        for (int i = 0; i < e->seen_count; i++)
                            seen |= strcmp(e->seen[i], resolved) == 0;
                        if (!seen && remember_include(e, resolved) == 0) {
                            char *inc = read_file(resolved, NULL, e->diag);
                            if (inc) {
                                emitf(e, "#line %d \"%s\"\n", resolved, 1);
                                expand(e, resolved, inc, depth + 1);
                                free(inc);
                                emitf(e, "#line %d \"%s\"\n", path, line + 1);
                            } else
                                e->failed = 1;
                        } else
                            emit(e, "\n", 1);
                    }
                }
                if (e->failed)
                    emit(e, "\n", 1);
            }
        }
        if (!is_include) {
            emit(e, p, n);
            emit(e, "\n", 1);
            /* #line "file" (from includes) needs this extension, which may
             * only come after #version; #line keeps the numbering. */
            if (depth == 0 && (size_t)(p + n - s) > 8 && strncmp(s, "#version", 8) == 0) {
                static const char ext[] = "#extension GL_GOOGLE_cpp_style_line_directive : enable\n";
                emit(e, ext, sizeof ext - 1);
                /* the pass's defines: NAME or NAME=VALUE, separated by spaces or ';' */
                for (const char *d = e->defines; d && *d;) {
                    while (*d == ' ' || *d == ';')
                        d++;
                    size_t len = strcspn(d, " ;");
                    if (len) {
                        char def[256];
                        snprintf(def, sizeof def, "#define %.*s\n", (int)(len < 200 ? len : 200), d);
                        char *eq = strchr(def, '=');
                        if (eq)
                            *eq = ' ';
                        emit(e, def, strlen(def));
                    }
                    d += len;
                }
                emitf(e, "#line %d \"%s\"\n", path, line + 1);
            }
        }
        p = end ? end + 1 : p + n;
    }
}

/* glslang says "ERROR: 0:12: msg" for the main file and "ERROR: path:12:
 * msg" after a #line naming an include; print each as PATH:LINE: error[CODE]: msg. */
static void print_log(FILE *f, const char *path, const char *log)
{
    while (log && *log) {
        const char *end = strchr(log, '\n');
        int n = end ? (int)(end - log) : (int)strlen(log);
        int is_err = strncmp(log, "ERROR: ", 7) == 0, is_warn = strncmp(log, "WARNING: ", 9) == 0;
        if (is_err || is_warn) {
            const char *rest = log + (is_err ? 7 : 9), *stop = log + n;
            const char *kind = is_err ? "error" : "warning";
            const char *code = _vrg_diag_info_of(is_err ? VRG_E_SHADER_SOURCE : VRG_W_SHADER_WARNING)->code;
            /* FILE:LINE: where LINE is digits; FILE is "0" for the main file */
            const char *colon = memchr(rest, ':', (size_t)(stop - rest));
            const char *num = colon ? colon + 1 : NULL, *q = num;
            while (q && q < stop && *q >= '0' && *q <= '9')
                q++;
            char quoted[4096]; /* glslang quotes the shader's text: escaped */
            if (colon && q > num && q < stop && *q == ':') {
                int main_file = colon - rest == 1 && rest[0] == '0';
                fprintf(f, "%.*s:%.*s: %s[%s]:%s\n", main_file ? (int)strlen(path) : (int)(colon - rest), main_file ? path : rest, (int)(q - num),
                        num, kind, code, vrg_escape(quoted, sizeof quoted, q + 1, (size_t)(stop - q - 1)));
            } else
                fprintf(f, "%s: %s[%s]: %s\n", path, kind, code, vrg_escape(quoted, sizeof quoted, rest, (size_t)(stop - rest)));
        }
        log = end ? end + 1 : log + n;
    }
}

/* The local size from OpExecutionMode LocalSize, or from OpExecutionModeId
 * LocalSizeId with the ids' constant values (glslang writes the latter for
 * SPIR-V 1.6 when the shader does not use gl_WorkGroupSize). */
static void local_size_of(const uint32_t *spv, size_t words, uint32_t out[3])
{
    out[0] = out[1] = out[2] = 1;
    uint32_t ids[3] = {0, 0, 0};
    for (size_t i = 5; i < words;) {
        uint32_t op = spv[i] & 0xffff, wc = spv[i] >> 16;
        if (wc == 0 || i + wc > words)
            break;
        if (op == 16 /* OpExecutionMode */ && wc >= 6 && spv[i + 2] == 17 /* LocalSize */) {
            out[0] = spv[i + 3];
            out[1] = spv[i + 4];
            out[2] = spv[i + 5];
        }
        if (op == 331 /* OpExecutionModeId */ && wc >= 6 && spv[i + 2] == 38 /* LocalSizeId */)
            memcpy(ids, spv + i + 3, sizeof ids);
        i += wc;
    }
    for (size_t i = 5; ids[0] && i < words;) { /* constants come after the execution modes */
        uint32_t op = spv[i] & 0xffff, wc = spv[i] >> 16;
        if (wc == 0 || i + wc > words)
            break;
        if ((op == 43 /* OpConstant */ || op == 50 /* OpSpecConstant */) && wc == 4)
            for (int a = 0; a < 3; a++)
                if (spv[i + 2] == ids[a])
                    out[a] = spv[i + 3];
        i += wc;
    }
}

VkShaderModule vrg_compile_compute_shader(vrg_context *ctx, const char *path, const char *defines)
{
    _vrg_shader_module sm;
    if (_vrg_shader_compile(ctx, path, defines, &sm, stderr) != 0)
        return VK_NULL_HANDLE;
    free(sm.deps);
    _vrg_reflection_free(&sm.refl);
    return sm.module;
}

void _vrg_shader_group_size(const vrg_context *ctx, uint32_t out[2])
{
    /* without a device (vrg_graph_check_shaders offline): a GPU's shape */
    out[0] = ctx ? ctx->group_size[0] : 8;
    out[1] = ctx ? ctx->group_size[1] : 8;
}

char *_vrg_shader_expand(const char *path, FILE *diag)
{
    char *src = read_shader(path, diag);
    if (!src)
        return NULL;
    expand_ctx e = {.diag = diag, .path = path, .defines = ""};
    expand(&e, path, src, 0);
    free(src);
    free(e.seen);
    if (e.failed) {
        free(e.out);
        return NULL;
    }
    return e.out;
}

int _vrg_shader_compile(vrg_context *ctx, const char *path, const char *defines, _vrg_shader_module *out, FILE *diag)
{
    return _vrg_shader_compile_source(ctx, path, defines, out, diag, NULL);
}

int _vrg_shader_compile_source(vrg_context *ctx, const char *path, const char *defines, _vrg_shader_module *out, FILE *diag, char **expanded)
{
    if (expanded)
        *expanded = NULL;
    pthread_once(&glslang_once, glslang_init);
    memset(&out->refl, 0, sizeof out->refl);
    char *src = read_shader(path, diag);
    if (!src)
        return -1;
    /* Every shader sees the device's preferred workgroup shape and pixel
     * loop (pixel.glsl). On a CPU device: one SIMD row per group shading a
     * 4x2 tile, 32 tiles per invocation. lavapipe runs every 8 invocations
     * as a coroutine with its own allocation and set-up, so fewer, fuller
     * invocations win: 8x1 groups over 8x8, several rows per invocation,
     * 32 tiles over 8 rows on ray passes, and 4x2 tiles over rows of 8
     * pixels (the lanes' rays are more alike); docs/benchmarks.md has each
     * step's figure. On a GPU: 8x8 groups, one pixel per invocation. */
    uint32_t group[2];
    _vrg_shader_group_size(ctx, group);
    const uint32_t tile[2] = {ctx ? ctx->pixel_tile[0] : 8, ctx ? ctx->pixel_tile[1] : 8};
    char all_defines[1200];
    snprintf(all_defines, sizeof all_defines, "VRG_GROUP_X=%u VRG_GROUP_Y=%u VRG_TILE_W=%uu VRG_TILE_H=%uu VRG_PIXEL_ROWS=%uu %s", group[0], group[1], tile[0],
             tile[1], ctx ? ctx->pixel_rows : 1, defines ? defines : "");
    expand_ctx e = {.diag = diag, .path = path, .defines = all_defines};
    expand(&e, path, src, 0);
    free(src);
    src = e.out;
    out->deps = NULL;
    if (e.failed) {
        free(e.seen);
        free(src);
        return -1;
    }
    /* the files this module was made of, for hot reload */
    size_t cap = (size_t)(e.seen_count + 1) * (PATH_MAX + 1) + 1, used = 0;
    out->deps = calloc(1, cap);
    for (int i = -1; out->deps && i < e.seen_count; i++) {
        char real[PATH_MAX];
        if (realpath(i < 0 ? path : e.seen[i], real))
            used += (size_t)snprintf(out->deps + used, cap - used, "%s\n", real);
    }
    free(e.seen);
    glslang_input_t input = {
        .language = GLSLANG_SOURCE_GLSL,
        .stage = GLSLANG_STAGE_COMPUTE,
        .client = GLSLANG_CLIENT_VULKAN,
        .client_version = GLSLANG_TARGET_VULKAN_1_3,
        .target_language = GLSLANG_TARGET_SPV,
        .target_language_version = GLSLANG_TARGET_SPV_1_6,
        .code = src,
        .default_version = 450,
        .default_profile = GLSLANG_NO_PROFILE,
        .force_default_version_and_profile = 0,
        .forward_compatible = 0,
        .messages = GLSLANG_MSG_DEFAULT_BIT | GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT,
        .resource = glslang_default_resource(),
    };
    glslang_shader_t *shader = glslang_shader_create(&input);
    int ok = glslang_shader_preprocess(shader, &input) && glslang_shader_parse(shader, &input);
    glslang_program_t *program = NULL;
    if (ok) {
        program = glslang_program_create();
        glslang_program_add_shader(program, shader);
        ok = glslang_program_link(program, GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT);
        if (!ok)
            print_log(diag, path, glslang_program_get_info_log(program));
    } else
        print_log(diag, path, glslang_shader_get_info_log(shader));
    int rc = -1;
    if (ok) {
        glslang_program_SPIRV_generate(program, GLSLANG_STAGE_COMPUTE);
        size_t words = glslang_program_SPIRV_get_size(program);
        const uint32_t *spv = glslang_program_SPIRV_get_ptr(program);
        local_size_of(spv, words, out->local_size);
        if (_vrg_reflect(spv, words, src, path, &out->refl, diag) != 0)
            goto done;
        out->module = VK_NULL_HANDLE;
        if (!ctx) { /* checked, not to be run */
            rc = 0;
            goto done;
        }
        VkShaderModuleCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = words * 4, .pCode = spv};
        if (vkCreateShaderModule(ctx->dev.device, &ci, NULL, &out->module) == VK_SUCCESS) {
            _vrg_name_object(ctx, VK_OBJECT_TYPE_SHADER_MODULE, (uint64_t)out->module, "%s", path);
            rc = 0;
        } else
            fprintf(diag, "%s: error[%s]: vkCreateShaderModule failed\n", path, _vrg_diag_info_of(VRG_E_VULKAN_FAILED)->code);
    }
done:
    if (program)
        glslang_program_delete(program);
    glslang_shader_delete(shader);
    if (rc == 0 && expanded)
        *expanded = src;
    else
        free(src);
    if (rc != 0) {
        free(out->deps);
        out->deps = NULL;
        _vrg_reflection_free(&out->refl);
    }
    return rc;
}
