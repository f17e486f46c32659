/* voxrg bench --suite reload: save-to-frame latency of hot reload. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include <unistd.h>
#include "util.h"


static void save_text(const char *path, const char *text)
{
    char tmp[1200];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return;
    fputs(text, f);
    fclose(f);
    rename(tmp, path); /* as editors save */
}

/* Frames until the graph reports a reload newer than `before` (at most
 * 2000 frames); reloads the graph itself when its source changed. Returns
 * the save-to-frame milliseconds, or -1. */
static double frames_until_reload(vrg_graph **g, double before)
{
    for (int i = 0; i < 2000; i++) {
        if (vrg_graph_poll_changes(*g) && vrg_graph_reload(g) != 0)
            return -1;
        if (vrg_graph_frame(*g) != 0)
            return -1;
        double ms = vrg_graph_reload_ms(*g);
        if (ms >= 0 && ms != before)
            return ms;
    }
    return -1;
}

static const char *reload_shader =
    "#version 450\n"
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
    "vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }\n"
    "void main() {\n"
    "    vec2 uv = vec2(gl_GlobalInvocationID.xy) / 64.0;\n"
    "    vec3 c = vec3(0.0);\n"
    "    for (int i = 0; i < 8; i++) c += aces(vec3(uv, %d.0) * float(i));\n"
    "    imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(c / 8.0, 1.0));\n"
    "}\n";


/* A ray pass's shader saved: the thesis graph at 320x180 with the ao pass's
 * shader taken from a scratch copy ($VOXRG_SHADER_OVERRIDE, searched before
 * the pass's own folder), saved with a new random-stream constant each run
 * so that glslang and lavapipe's JIT both do the whole work. */
/* The first of two places (the source tree's, the installed prefix's,
 * relative to vrg_data_dir) that exists, in `out`. */
static void data_file(char *out, size_t cap, const char *in_tree, const char *installed)
{
    snprintf(out, cap, "%s/%s", vrg_data_dir(), in_tree);
    if (access(out, F_OK) != 0)
        snprintf(out, cap, "%s/%s", vrg_data_dir(), installed);
}

static int ray_shader_reload(vrg_context *ctx, const char *dir, int runs, double *ms)
{
    char path[1100], shader[1100];
    data_file(path, sizeof path, "passes/ao/ao.comp", "../../lib/voxrg/plugins/ao/ao.comp");
    char *src = vrg_cli_read_text(path);
    char *salt = src ? strstr(src, "const uint SALT = 0x414f0002u;") : NULL;
    if (!salt) {
        free(src);
        return -1;
    }
    snprintf(shader, sizeof shader, "%s/ao.comp", dir);
    save_text(shader, src);
    setenv("VOXRG_SHADER_OVERRIDE", dir, 1);
    snprintf(path, sizeof path, "%s/graphs/thesis.ini", vrg_data_dir());
    vrg_graph_desc d = {.path = path, .width = 320, .height = 180};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(ctx, &d, &g) == 0 && vrg_graph_watch(g, 1) == 0 && vrg_graph_frame(g) == 0 ? 0 : -1;
    size_t head = (size_t)(salt - src);
    const char *tail = strchr(salt, '\n');
    unsigned unique = (unsigned)(getpid() % 100000) * 100;
    for (int r = -1; r < runs && rc == 0; r++) { /* r = -1: warm-up, not counted */
        size_t cap = strlen(src) + 64;
        char *text = malloc(cap);
        snprintf(text, cap, "%.*sconst uint SALT = 0x%08xu;%s", (int)head, src, 0x414f0000u + unique + (unsigned)(r + 2), tail);
        double before = vrg_graph_reload_ms(g);
        save_text(shader, text);
        free(text);
        double t = frames_until_reload(&g, before);
        rc = t < 0 ? -1 : 0;
        if (r >= 0)
            ms[r] = t;
    }
    vrg_graph_destroy(g);
    unsetenv("VOXRG_SHADER_OVERRIDE");
    remove(shader);
    free(src);
    return rc;
}

int vrg_bench_reload(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    int runs = o->runs;
    char dir[] = "/tmp/voxrg-bench-reload-XXXXXX";
    if (!mkdtemp(dir))
        return -1;
    char shader[1100], graph[1100], text[4096];
    double ms[64];
    int n = *count, ok = 1;
    if (vrg_bench_room(n, 4))
        return -1;
    /* a shader saved: recompiled (glslang) and JIT-compiled (lavapipe) */
    snprintf(shader, sizeof shader, "%s/user.comp", dir);
    snprintf(text, sizeof text, reload_shader, 0);
    save_text(shader, text);
    snprintf(graph, sizeof graph, "%s/shader.ini", dir);
    save_text(graph, "[graph]\noutput = color\nwidth = 64\nheight = 64\n[pass user]\nplugin = shader_file\nout.color = color\n");
    setenv("VOXRG_SHADER_PATH", dir, 1);
    vrg_graph_desc d = {.path = graph};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0 || vrg_graph_watch(g, 1) != 0 || vrg_graph_frame(g) != 0) {
        fprintf(stderr, "bench reload: the shader graph needs the shader_file test plugin (build tree)\n");
        ok = 0;
    }
    /* a constant never compiled before: Mesa's disk cache must not hold it */
    int unique = (int)(getpid() % 100000) * 100;
    for (int r = -1; ok && r < runs; r++) { /* r = -1: warm-up, not counted */
        snprintf(text, sizeof text, reload_shader, unique + r + 2);
        double before = vrg_graph_reload_ms(g);
        save_text(shader, text);
        double t = frames_until_reload(&g, before);
        ok = t >= 0;
        if (r >= 0)
            ms[r] = t;
    }
    if (ok)
        out[n++] = vrg_bench_summarise("reload: shader saved -> first frame using it (small compute shader)", "ms", ms, runs);
    vrg_graph_destroy(g);
    unsetenv("VOXRG_SHADER_PATH");
    if (ok && ray_shader_reload(ctx, dir, runs, ms) == 0)
        out[n++] = vrg_bench_summarise("reload: ray pass shader saved (ao.comp in thesis.ini, 320x180) -> first frame using it", "ms", ms, runs);
    else
        ok = 0;
    /* a parameter of the thesis graph (320x180): reparse, revalidate, a new
     * graph instance sharing the generated world and its GPU side (the
     * [scene] is unchanged: the world buffer, atlas and BLASes are kept),
     * history carried over, pipelines kept */
    char src[1100];
    snprintf(src, sizeof src, "%s/graphs/thesis.ini", vrg_data_dir());
    FILE *f = vrg_fopen_regular(src, "r");
    size_t len = f ? fread(text, 1, sizeof text - 64, f) : 0;
    if (f)
        fclose(f);
    text[len] = '\0';
    snprintf(graph, sizeof graph, "%s/thesis.ini", dir);
    char *iter = strstr(text, "iterations      = 7");
    g = NULL;
    if (ok && iter) {
        save_text(graph, text);
        vrg_graph_desc td = {.path = graph, .width = 320, .height = 180};
        if (vrg_graph_load(ctx, &td, &g) != 0 || vrg_graph_watch(g, 1) != 0 || vrg_graph_frame(g) != 0)
            ok = 0;
        for (int r = -1; ok && r < runs; r++) { /* r = -1: warm-up, not counted */
            iter[18] = r & 1 ? '5' : '7'; /* the warm-up (r = -1) saves 5: the loaded file has 7 */
            double before = vrg_graph_reload_ms(g);
            save_text(graph, text);
            double t = frames_until_reload(&g, before);
            ok = t >= 0;
            if (r >= 0)
                ms[r] = t;
        }
        if (ok)
            out[n++] = vrg_bench_summarise("reload: thesis.ini parameter saved -> first frame (320x180, world kept)", "ms", ms, runs);
        vrg_graph_destroy(g);
    }
    /* a plugin rebuilt: private copy, dlopen, ABI checks, a new graph
     * instance with the state handed over (the compile itself not counted:
     * the clock starts at the file's mtime) */
    char plugin_src[1100], cmd[4096], so[1100], include[1100];
    data_file(include, sizeof include, "core/runtime/include", "../../include");
    snprintf(plugin_src, sizeof plugin_src, "%s/benchfill.c", dir);
    snprintf(so, sizeof so, "%s/benchfill.so", dir);
    save_text(plugin_src, "#include \"voxrg/plugin.h\"\n"
                          "static const vrg_slot_desc slots[] = {{.name = \"color\", .dir = VRG_OUT, .kind = VRG_IMAGE,\n"
                          "    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};\n"
                          "static void execute(vrg_pass *p, VkCommandBuffer cmd) {\n"
                          "    float c[4] = {VALUE, 0, 0, 1};\n"
                          "    (void)vrg_dispatch(p, cmd, &(vrg_dispatch_desc){.shader = \"fill.comp\", .push = c, .push_size = sizeof c}); }\n"
                          "static const vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = \"benchfill\", .kind = VRG_PLUGIN_PASS,\n"
                          "    .help = \"bench: hot reload\", .shader_dir = DIR, .slots = slots, .slot_count = 1, .execute = execute};\n"
                          "VRG_PLUGIN(desc)\n");
    snprintf(shader, sizeof shader, "%s/fill.comp", dir);
    save_text(shader, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                      "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\nlayout(push_constant) uniform P { vec4 c; } pc;\n"
                      "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n");
    snprintf(graph, sizeof graph, "%s/plugin.ini", dir);
    save_text(graph, "[graph]\nplugin_path = .\noutput = color\nwidth = 64\nheight = 64\n[pass fill]\nplugin = benchfill\nout.color = color\n");
    g = NULL;
    for (int r = -1; ok && r < runs; r++) {
        snprintf(cmd, sizeof cmd,
                 "cc -std=c11 -shared -fPIC -I'%s' -DVALUE=%d -DDIR='\"%s\"' '%s' -o '%s.new' 2>/dev/null && mv '%s.new' '%s'",
                 include, r + 2, dir, plugin_src, so, so, so);
        if (system(cmd) != 0) {
            printf("reload: plugin figure skipped: no working `cc` to rebuild a plugin with\n");
            break;
        }
        if (r < 0) { /* the first build: load it */
            vrg_graph_desc pd = {.path = graph};
            if (vrg_graph_load(ctx, &pd, &g) != 0 || vrg_graph_watch(g, 1) != 0 || vrg_graph_frame(g) != 0)
                ok = 0;
            continue;
        }
        double before = vrg_graph_reload_ms(g);
        ms[r] = frames_until_reload(&g, before);
        ok = ms[r] >= 0;
        if (ok && r + 1 == runs)
            out[n++] = vrg_bench_summarise("reload: plugin rebuilt -> first frame using it (build time not counted)", "ms", ms, runs);
    }
    vrg_graph_destroy(g);
    remove(so), remove(plugin_src), remove(shader), remove(graph);
    snprintf(graph, sizeof graph, "%s/thesis.ini", dir);
    remove(graph);
    snprintf(graph, sizeof graph, "%s/shader.ini", dir);
    remove(graph);
    snprintf(shader, sizeof shader, "%s/user.comp", dir);
    remove(shader);
    rmdir(dir);
    *count = n;
    return ok ? 0 : -1;
}

