/* `voxrg new-pass NAME [--dir DIR]`: a ready out-of-tree pass (after
 * Falcor's new-render-pass script). It writes NAME.c (a tint of an input
 * image, with haze from the scene's frame uniforms: the camera and the
 * sky), NAME.comp, a CMakeLists.txt that builds it
 * against an installed voxrg (find_package(voxrg CONFIG), voxrg_add_pass)
 * and NAME.ini, a graph that runs it between shipped passes, so that the
 * folder builds and renders as written (docs/out-of-tree.md). Existing files
 * are never overwritten: all four are checked before any is written. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "new_pass.h"
#include "voxrg/output.h"
#include "voxrg/voxrg.h"

/* Every "@NAME@" in the templates becomes the pass's name. */
static const char *c_template =
    "/* @NAME@: colour = input x tint, hazed toward the horizon, a pass built\n"
    " * outside the voxrg tree.\n"
    " * Scaffolded by `voxrg new-pass`; docs/plugin-abi.md describes the ABI. */\n"
    "#include \"voxrg/plugin.h\"\n"
    "\n"
    "static const vrg_param_desc params[] = {\n"
    "    {.name = \"red\", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 16, .help = \"multiplies red\"},\n"
    "    {.name = \"green\", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 16, .help = \"multiplies green\"},\n"
    "    {.name = \"blue\", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 16, .help = \"multiplies blue\"},\n"
    "    {.name = \"strength\", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 1,\n"
    "     .help = \"0: the input as it is, 1: fully tinted\"},\n"
    "    {.name = \"haze\", .type = VRG_PARAM_FLOAT, .default_value = 0, .min = 0, .max = 1,\n"
    "     .help = \"the sky's colour mixed in where the view ray meets the horizon (0: none)\"},\n"
    "};\n"
    "\n"
    "static const vrg_slot_desc slots[] = {\n"
    "    {.name = \"color\", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = \"linear colour\"},\n"
    "    /* the scene's per-frame uniforms: camera, sun, sky (frame.glsl) */\n"
    "    {.name = \"frame\", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM,\n"
    "     .help = \"the scene's per-frame uniforms\"},\n"
    "    {.name = \"tinted\", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,\n"
    "     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = \"the colour, tinted\"},\n"
    "};\n"
    "\n"
    "/* every dispatch execute() records: `voxrg check` compiles and reflects\n"
    " * each against the slots before any frame, even without a device. Its\n"
    " * push constants are packed by name (push_size 0): each member of the\n"
    " * shader's block takes the parameter of its name (docs/plugin-abi.md,\n"
    " * \"Push constants and bindings by name\") */\n"
    "static const vrg_dispatch_desc dispatches[] = {\n"
    "    {.shader = \"@NAME@.comp\", .pixel_loop = 1},\n"
    "};\n"
    "\n"
    "static void execute(vrg_pass *pass, VkCommandBuffer cmd)\n"
    "{\n"
    "    /* a value the pass computes is set by name before the dispatch, e.g.\n"
    "     * vrg_push_uint(pass, \"frame_index\", (uint32_t)vrg_pass_frame(pass)->frame_index); */\n"
    "    (void)vrg_dispatch(pass, cmd, &dispatches[0]);\n"
    "}\n"
    "\n"
    "static const vrg_plugin_desc desc = {\n"
    "    .abi_version = VRG_ABI_VERSION,\n"
    "    .name = \"@NAME@\",\n"
    "    .kind = VRG_PLUGIN_PASS,\n"
    "    .help = \"colour x tint, hazed toward the horizon (an out-of-tree pass)\",\n"
    "    .params = params,\n"
    "    .param_count = sizeof params / sizeof params[0],\n"
    "    .slots = slots,\n"
    "    .slot_count = sizeof slots / sizeof slots[0],\n"
    "    .execute = execute,\n"
    "    .dispatches = dispatches,\n"
    "    .dispatch_count = sizeof dispatches / sizeof dispatches[0],\n"
    "};\n"
    "\n"
    "VRG_PLUGIN(desc)\n";

static const char *comp_template =
    "#version 460\n"
    "// @NAME@: colour x tint, hazed toward the horizon. pixel.glsl and frame.glsl\n"
    "// come with voxrg (share/voxrg/shaders/include).\n"
    "#include \"pixel.glsl\"\n"
    "\n"
    "layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;\n"
    "// bindings in the order of the plugin's slots\n"
    "layout(binding = 0) uniform sampler2D in_color;\n"
    "// The frame slot is binding 1: frame.glsl declares the block `frame` there\n"
    "// (camera_pos, camera_forward, sun_dir, sky colours, frame_info, ...;\n"
    "// docs/plugin-abi.md lists every field) and frame_ray_dir, frame_sky.\n"
    "#define FRAME_BINDING 1\n"
    "#include \"frame.glsl\"\n"
    "layout(binding = 2, rgba16f) uniform writeonly image2D out_tinted;\n"
    "// the plugin's parameters, by name\n"
    "layout(push_constant) uniform Push {\n"
    "    float red, green, blue;\n"
    "    float strength;\n"
    "    float haze;\n"
    "} pc;\n"
    "\n"
    "void shade(ivec2 p)\n"
    "{\n"
    "    ivec2 size = imageSize(out_tinted);\n"
    "    if (any(greaterThanEqual(p, size)))\n"
    "        return;\n"
    "    vec4 c = texelFetch(in_color, vrg_pixel_in(p, size, textureSize(in_color, 0)), 0);\n"
    "    // this pixel's view ray from the camera, and the sky's colour along it:\n"
    "    // haze, strongest where the ray is level with the horizon\n"
    "    vec3 dir = frame_ray_dir(vec2(p), vec2(size));\n"
    "    float level = 1.0 - abs(dir.y);\n"
    "    c.rgb = mix(c.rgb, frame_sky(dir), pc.haze * level * level * level * level);\n"
    "    vec3 tint = mix(vec3(1.0), vec3(pc.red, pc.green, pc.blue), pc.strength);\n"
    "    imageStore(out_tinted, p, vec4(c.rgb * tint, c.a));\n"
    "}\n"
    "\n"
    "void main()\n"
    "{\n"
    "    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)\n"
    "        shade(vrg_pixel(k));\n"
    "}\n";

static const char *cmake_template =
    "# The out-of-tree pass @NAME@, built against an installed voxrg:\n"
    "#   cmake -S . -B build -DCMAKE_PREFIX_PATH=<voxrg prefix> && cmake --build build\n"
    "#   voxrg render @NAME@.ini --out out   (its [graph] plugin_path is build)\n"
    "cmake_minimum_required(VERSION 3.20)\n"
    "project(@NAME@ LANGUAGES C)\n"
    "set(CMAKE_C_STANDARD 11)\n"
    "add_compile_options(-Wall -Wextra)\n"
    "find_package(voxrg CONFIG REQUIRED)\n"
    "# @NAME@.so in the build folder; `cmake --install` puts it and its shader\n"
    "# in lib/voxrg/plugins of the install prefix\n"
    "voxrg_add_pass(@NAME@ SOURCES @NAME@.c SHADERS @NAME@.comp)\n"
    "set_target_properties(@NAME@ PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})\n";

/* The one form of a pass's README (docs/plugin-abi.md, "A pass's README"). */
static const char *readme_template =
    "# @NAME@\n"
    "\n"
    "## What it does\n"
    "\n"
    "Multiplies its input's colour by a tint and mixes in the sky's colour\n"
    "where the view ray meets the horizon (the frame uniforms' camera and sky).\n"
    "Put it after `modulate`, before `tonemap`.\n"
    "\n"
    "## Slots\n"
    "\n"
    "| slot | kind | format | access | size | holds |\n"
    "|---|---|---|---|---|---|\n"
    "| `in.color` | image | any | sampled | any size | linear colour |\n"
    "| `in.frame` | buffer | - | uniform | any | the scene's per-frame uniforms (camera, sun, sky) |\n"
    "| `out.tinted` | image | rgba16f | storage-write | scale 1 | the colour, tinted and hazed |\n"
    "\n"
    "## Parameters\n"
    "\n"
    "| parameter | type | default | range | what it does |\n"
    "|---|---|---|---|---|\n"
    "| `red` | float | 1 | [0, 16] | multiplies red |\n"
    "| `green` | float | 1 | [0, 16] | multiplies green |\n"
    "| `blue` | float | 1 | [0, 16] | multiplies blue |\n"
    "| `strength` | float | 1 | [0, 1] | 0: the input as it is, 1: fully tinted |\n"
    "| `haze` | float | 0 | [0, 1] | the sky's colour mixed in where the view ray meets the horizon (0: none) |\n"
    "\n"
    "## Cost\n"
    "\n"
    "One texel read and one write per pixel; measure it with\n"
    "`voxrg render @NAME@.ini --json timings.json`.\n"
    "\n"
    "## Debug outputs\n"
    "\n"
    "None.\n";

static const char *graph_template =
    "; @NAME@ between shipped passes: the G-buffer's albedo, tinted and hazed,\n"
    "; tonemapped.\n"
    "; Needs build/@NAME@.so (cmake, see CMakeLists.txt):\n"
    ";   voxrg render @NAME@.ini --out out\n"
    "[graph]\n"
    "name        = @NAME@\n"
    "output      = ldr\n"
    "width       = 320\n"
    "height      = 180\n"
    "plugin_path = build\n"
    "\n"
    "[camera]\n"
    "position = -40 80 40\n"
    "yaw      = -40\n"
    "pitch    = -35\n"
    "\n"
    "[scene]\n"
    "plugin      = terrain\n"
    "seed        = 1337\n"
    "radius      = 2\n"
    "time_of_day = 15\n"
    "\n"
    "[pass gbuffer]\n"
    "plugin     = gbuffer\n"
    "in.world   = world\n"
    "in.frame   = frame\n"
    "in.atlas   = atlas\n"
    "out.albedo = albedo\n"
    "\n"
    "[pass @NAME@]\n"
    "plugin     = @NAME@\n"
    "in.color   = albedo\n"
    "in.frame   = frame\n"
    "out.tinted = tinted\n"
    "red        = 1\n"
    "green      = 0.6\n"
    "blue       = 0.3\n"
    "strength   = 0.8\n"
    "haze       = 0.5\n"
    "\n"
    "[pass tonemap]\n"
    "plugin   = tonemap\n"
    "in.color = tinted\n"
    "out.ldr  = ldr\n";

/* --shader: a one-file pass, its interface declared in the shader itself
 * (docs/plugin-abi.md, "A pass in one file"): no build step. */
static const char *shader_template =
    "#version 460\n"
    "// @NAME@: colour x tint, hazed toward the sky where the view ray meets the horizon\n"
    "#define FRAME_BINDING 0\n"
    "#include \"frame.glsl\"\n"
    "#include \"pixel.glsl\"\n"
    "\n"
    "layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;\n"
    "layout(binding = 1) uniform sampler2D in_color;\n"
    "layout(binding = 2, rgba16f) uniform writeonly image2D out_tinted;\n"
    "// layout(binding = 3) uniform sampler2D in_mask; // @optional help=\"read it under #ifdef HAS_MASK (defined where connected)\"\n"
    "layout(push_constant) uniform Params {\n"
    "    float red;      // @param default=1 min=0 max=16 help=\"multiplies red\"\n"
    "    float green;    // @param default=1 min=0 max=16 help=\"multiplies green\"\n"
    "    float blue;     // @param default=1 min=0 max=16 help=\"multiplies blue\"\n"
    "    float strength; // @param default=1 min=0 max=1 help=\"0: the input as it is, 1: fully tinted\"\n"
    "    float haze;     // @param default=0 min=0 max=1 help=\"the sky's colour mixed in where the view ray meets the horizon (0: none)\"\n"
    "    // int look; // @param choices=plain,warm default=plain help=\"a name the graph picks; look is its index (0, 1)\"\n"
    "} params;\n"
    "\n"
    "void shade(ivec2 p)\n"
    "{\n"
    "    ivec2 size = imageSize(out_tinted);\n"
    "    if (any(greaterThanEqual(p, size)))\n"
    "        return;\n"
    "    vec4 c = texelFetch(in_color, vrg_pixel_in(p, size, textureSize(in_color, 0)), 0);\n"
    "    vec3 dir = frame_ray_dir(vec2(p), vec2(size));\n"
    "    float level = 1.0 - abs(dir.y);\n"
    "    c.rgb = mix(c.rgb, frame_sky(dir), params.haze * level * level * level * level);\n"
    "    vec3 tint = mix(vec3(1.0), vec3(params.red, params.green, params.blue), params.strength);\n"
    "    imageStore(out_tinted, p, vec4(c.rgb * tint, c.a));\n"
    "}\n"
    "\n"
    "void main()\n"
    "{\n"
    "    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)\n"
    "        shade(vrg_pixel(k));\n"
    "}\n";

/* A C identifier that is also a portable file name: [A-Za-z_][A-Za-z0-9_]*,
 * at most NEW_PASS_NAME_MAX characters. */
#define NEW_PASS_NAME_MAX 48
static int valid_name(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n > NEW_PASS_NAME_MAX || isdigit((unsigned char)name[0]))
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!isalnum((unsigned char)name[i]) && name[i] != '_')
            return 0;
    return 1;
}

/* Target names CMake keeps for itself (policy CMP0037, and the targets its
 * Makefile and Visual Studio generators add): the scaffold's CMakeLists.txt
 * names its target after the pass. Compared without case: ALL_BUILD is
 * Visual Studio's, INSTALL its install target. */
static const char *const cmake_reserved[] = {
    "all", "clean", "help", "install", "test", "package", "package_source", "depend", "edit_cache", "rebuild_cache",
    "list_install_components", "all_build", "zero_check", "run_tests",
};

static const char *cmake_reserved_name(const char *name)
{
    for (size_t i = 0; i < sizeof cmake_reserved / sizeof *cmake_reserved; i++)
        if (strcasecmp(name, cmake_reserved[i]) == 0)
            return cmake_reserved[i];
    return NULL;
}

/* 1 (file in `file`) when a plugin NAME is on the search path already: a
 * shipped pass comes first and is never shadowed, so a new pass of that
 * name would never load, and one of the user's own is a second NAME. */
static int plugin_exists(const char *name, char *file, size_t cap)
{
    char *why = NULL;
    size_t why_len = 0;
    FILE *quiet = open_memstream(&why, &why_len); /* "not found" is the answer wanted, not an error */
    const vrg_plugin_desc *desc;
    const char *path;
    int found = vrg_find_plugin(name, quiet ? quiet : stderr, &desc, &path) == 0;
    if (found)
        snprintf(file, cap, "%s", path);
    if (quiet)
        fclose(quiet);
    free(why);
    return found;
}

/* The template with @NAME@ replaced, malloc'd. */
static char *instantiate(const char *tmpl, const char *name)
{
    size_t cap = strlen(tmpl) + 1, nlen = strlen(name);
    for (const char *p = strstr(tmpl, "@NAME@"); p; p = strstr(p + 6, "@NAME@"))
        cap += nlen;
    char *out = malloc(cap), *o = out;
    if (!out)
        return NULL;
    for (const char *p = tmpl; *p;) {
        if (strncmp(p, "@NAME@", 6) == 0) {
            memcpy(o, name, nlen);
            o += nlen, p += 6;
        } else
            *o++ = *p++;
    }
    *o = '\0';
    return out;
}

typedef struct scaffold_file {
    const char *suffix; /* after NAME, or a whole name when fixed */
    int fixed;
    const char *tmpl;
} scaffold_file;

static const scaffold_file files[] = {
    {".c", 0, NULL}, {".comp", 0, NULL}, {"CMakeLists.txt", 1, NULL}, {".ini", 0, NULL}, {"README.md", 1, NULL},
};
/* --shader: NAME.comp, NAME.ini and README.md (entries of files[]) */
static const int shader_files[] = {1, 3, 4};

static void file_path(char *out, size_t cap, const char *dir, const char *name, int i)
{
    if (files[i].fixed)
        snprintf(out, cap, "%s/%s", dir, files[i].suffix);
    else
        snprintf(out, cap, "%s/%s%s", dir, name, files[i].suffix);
}

static int make_dir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return 0;
        fprintf(stderr, "error: --dir '%s' exists and is not a folder\n", dir);
        return -1;
    }
    if (mkdir(dir, 0777) != 0) {
        fprintf(stderr, "error: cannot create the folder '%s': %s (its parent must exist)\n", dir, strerror(errno));
        return -1;
    }
    return 0;
}

/* The graph for a one-file pass: the C scaffold's, with the pass found
 * beside the graph and no build step named. */
static char *shader_graph(const char *name, const char **why)
{
    *why = "out of memory";
    char *g = instantiate(graph_template, name);
    if (!g)
        return NULL;
    const char *from = strstr(g, "[graph]");
    const char *old_path = "plugin_path = build\n";
    char *at = strstr(g, old_path);
    if (!from || !at || at < from) {
        /* the C scaffold's graph changed under this edit: a bug of voxrg, not of the user's input */
        *why = "internal error: the C scaffold's graph template has no [graph] section followed by 'plugin_path = build' to replace "
               "(core/cli/new_pass.c, shader_graph)";
        free(g);
        return NULL;
    }
    const char *head = "; @NAME@ between shipped passes: the G-buffer's albedo, tinted and hazed,\n"
                       "; tonemapped. @NAME@.comp beside this graph is the whole pass (no build):\n"
                       ";   voxrg render @NAME@.ini --out out\n";
    char *h = instantiate(head, name);
    size_t cap = strlen(g) + (h ? strlen(h) : 0) + 64;
    char *out = h ? malloc(cap) : NULL;
    if (out)
        snprintf(out, cap, "%s%.*splugin_path = .\n%s", h, (int)(at - from), from, at + strlen(old_path));
    free(h);
    free(g);
    return out;
}

int vrg_cli_new_pass(const char *name, const char *dir, int shader)
{
    if (!valid_name(name)) {
        fprintf(stderr, "error: new-pass: '%s' is not a valid pass name: a C identifier ([A-Za-z_][A-Za-z0-9_]*, "
                        "at most %d characters), used for the plugin, its files and its symbols\n", name, NEW_PASS_NAME_MAX);
        return 2;
    }
    const char *reserved = cmake_reserved_name(name);
    if (reserved) {
        fprintf(stderr, "error: new-pass: '%s' is a target name CMake keeps for itself ('%s'): the scaffold's CMakeLists.txt "
                        "could not build it; choose another name\n", name, reserved);
        return 2;
    }
    char existing_file[4200];
    if (plugin_exists(name, existing_file, sizeof existing_file)) {
        fprintf(stderr, "error: new-pass: a plugin named '%s' is on the search path already (%s): graphs would load that one "
                        "(built-in and installed plugins are never shadowed); choose another name\n", name, existing_file);
        return 2;
    }
    const char *tmpls[] = {c_template, comp_template, cmake_template, graph_template, readme_template};
    _Static_assert(sizeof tmpls / sizeof tmpls[0] == sizeof files / sizeof files[0], "a template for every scaffold file");
    const int count = shader ? (int)(sizeof shader_files / sizeof shader_files[0]) : (int)(sizeof files / sizeof files[0]);
    char path[4200];
    int existing = 0;
    for (int k = 0; k < count; k++) {
        int i = shader ? shader_files[k] : k;
        file_path(path, sizeof path, dir, name, i);
        if (access(path, F_OK) == 0) {
            fprintf(stderr, "error: new-pass: %s exists; nothing was written (new-pass never overwrites a file: "
                            "choose another NAME or --dir)\n", path);
            existing++;
        }
    }
    if (existing || make_dir(dir) != 0)
        return 1;
    for (int k = 0; k < count; k++) {
        int i = shader ? shader_files[k] : k;
        file_path(path, sizeof path, dir, name, i);
        const char *why = "out of memory";
        char *text = !shader ? instantiate(tmpls[i], name) : i == 1 ? instantiate(shader_template, name) : i == 3 ? shader_graph(name, &why) : instantiate(readme_template, name);
        int rc = text ? vrg_output_write(path, text, strlen(text)) : -1;
        if (!text)
            fprintf(stderr, "error: new-pass: %s: %s was not written\n", why, path);
        free(text);
        if (rc != 0)
            return 1;
        printf("wrote %s\n", path);
    }
    if (shader) {
        printf("next: voxrg render %s/%s.ini --out %s/out --validate   (edit %s/%s.comp while `voxrg run` shows it: it reloads)\n", dir, name, dir, dir, name);
        return 0;
    }
    printf("next: cmake -S %s -B %s/build -DCMAKE_PREFIX_PATH=<voxrg prefix> && cmake --build %s/build\n"
           "      voxrg render %s/%s.ini --out %s/out --validate\n", dir, dir, dir, dir, name, dir);
    return 0;
}
