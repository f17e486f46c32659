/* voxrg bench: figures measured several times after warm-up, reported as
 * median / min / max with the device and thread counts. Suites that need
 * later milestones (graph, memory, frame) are not here yet. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <sys/stat.h>
#include <string.h>
#include <unistd.h>
#include "bench.h"
#include "util.h"

typedef struct figure {
    char name[96];
    char unit[16];
    double median, min, max, p99;
    int samples;
} figure;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static figure summarise(const char *name, const char *unit, double *v, int n)
{
    figure f = {0};
    snprintf(f.name, sizeof f.name, "%s", name);
    snprintf(f.unit, sizeof f.unit, "%s", unit);
    f.samples = n;
    if (n == 0)
        return f;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    f.min = v[0];
    f.max = v[n - 1];
    f.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    int k = (int)(0.99 * (n - 1) + 0.5);
    f.p99 = v[k];
    return f;
}

/* A terrain graph with the smallest real pass, so the scene's figures are
 * what is measured. */
static vrg_graph *terrain_graph(vrg_context *ctx, int threads, const char *stream, int radius)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[graph]\nname = bench-terrain\noutput = view\nwidth = 16\nheight = 16\n"
             "[camera]\nposition = 0 50 0\n"
             "[scene]\nplugin = terrain\nseed = 1337\nradius = %d\nthreads = %d\nstream = %s\nbudget_ms = 2\n"
             "[pass view]\nplugin = world_debug\nin.world = world\nin.frame = frame\nout.color = view\nshadows = 0\n",
             radius, threads, stream);
    vrg_graph_desc d = {.path = "<bench terrain>", .text = text};
    vrg_graph *g = NULL;
    return vrg_graph_load(ctx, &d, &g) == 0 ? g : NULL;
}

static double scene_stat(vrg_graph *g, const char *name)
{
    double v = 0;
    vrg_graph_stat(g, "scene", name, &v);
    return v;
}

static int bench_terrain(vrg_context *ctx, int runs, figure *out, int *count)
{
    int n = 0;
    /* whole-world generation, radius 13 (27 x 27 x 3 chunks), 1 and 2 threads */
    for (int threads = 1; threads <= 2; threads++) {
        double wait[64], per_thread[64], integ[64], upload[64];
        int chunks = 0;
        for (int r = 0; r < runs + 1; r++) {
            vrg_graph *g = terrain_graph(ctx, threads, "wait", 13);
            if (!g || vrg_graph_frame(g) != 0) {
                vrg_graph_destroy(g);
                return -1;
            }
            if (r > 0) { /* run 0 warms caches and the shader JIT */
                wait[r - 1] = scene_stat(g, "wait_ms");
                integ[r - 1] = scene_stat(g, "integrate_ms");
                upload[r - 1] = scene_stat(g, "upload_ms");
                chunks = (int)scene_stat(g, "chunks_integrated");
                per_thread[r - 1] = chunks / (wait[r - 1] / 1000.0) / threads;
            }
            vrg_graph_destroy(g);
        }
        char name[96];
        snprintf(name, sizeof name, "terrain: generate radius-13 world (%d chunks), %d thread%s", chunks, threads, threads > 1 ? "s" : "");
        out[n++] = summarise(name, "ms", wait, runs);
        snprintf(name, sizeof name, "terrain: chunks/s per thread, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = summarise(name, "chunks/s", per_thread, runs);
        snprintf(name, sizeof name, "terrain: integrate whole world on main thread, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = summarise(name, "ms", integ, runs);
        snprintf(name, sizeof name, "terrain: pack + record upload of whole world, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = summarise(name, "ms", upload, runs);
    }
    /* streaming along graphs/paths/walk.path, budget 2 ms: main-thread time per frame */
    vrg_camera_path path;
    char path_file[1024];
    snprintf(path_file, sizeof path_file, "%s/graphs/paths/walk.path", vrg_source_dir());
    if (vrg_camera_path_load(path_file, &path, stderr) != 0)
        return -1;
    vrg_graph *g = terrain_graph(ctx, 2, "budget", 13);
    if (!g) {
        vrg_camera_path_free(&path);
        return -1;
    }
    vrg_camera cam = *vrg_graph_camera(g);
    vrg_camera_path_eval(&path, 0, &cam);
    vrg_graph_set_camera(g, &cam);
    /* warm-up: stand at the start until the world is in */
    for (int i = 0; i < 2000 && (i == 0 || scene_stat(g, "chunks_pending") > 0); i++)
        vrg_graph_frame(g);
    int frames = (int)(vrg_camera_path_duration(&path) / vrg_graph_frame_seconds(g));
    double *integ = calloc((size_t)frames, sizeof *integ), *main_ms = calloc((size_t)frames, sizeof *main_ms);
    int integrated = 0;
    for (int k = 0; k < frames; k++) {
        vrg_camera_path_eval(&path, (float)(k * vrg_graph_frame_seconds(g)), &cam);
        vrg_graph_set_camera(g, &cam);
        vrg_graph_frame(g);
        integ[k] = scene_stat(g, "integrate_ms");
        main_ms[k] = scene_stat(g, "integrate_ms") + scene_stat(g, "upload_ms") + scene_stat(g, "wait_ms");
        integrated += (int)scene_stat(g, "chunks_integrated");
    }
    char name[128];
    snprintf(name, sizeof name, "terrain: streaming integration per frame, walk.path (%d frames, %d chunks)", frames, integrated);
    out[n++] = summarise(name, "ms", integ, frames);
    snprintf(name, sizeof name, "terrain: streaming main-thread total per frame (update + integrate + upload)");
    out[n++] = summarise(name, "ms", main_ms, frames);
    free(integ);
    free(main_ms);
    vrg_graph_destroy(g);
    vrg_camera_path_free(&path);
    *count = n;
    return 0;
}

/* Rays: primary, sun shadow, AO and indirect rays on the default terrain
 * from a fixed camera, one ray per pixel per pass, for each backend. Ray
 * counts are the rays actually traced: the G-buffer is read back to count
 * surface pixels (and those facing the sun for shadow rays). The indirect
 * pass runs without its secondary shadow rays so its count is exact. */
static int bench_rays(vrg_context *ctx, int runs, uint32_t width, uint32_t height, figure *out, int *count)
{
    int n = *count;
    static const char *backends[] = {"dda", "rayquery"};
    for (int b = 0; b < 2; b++) {
        int rq = b == 1;
        if (rq && !vrg_context_device(ctx)->features.ray_query) {
            printf("rays: rayquery backend skipped: no VK_KHR_ray_query on this device\n");
            continue;
        }
        char text[2048];
        const char *tlas = rq ? "in.tlas = tlas\n" : "";
        snprintf(text, sizeof text,
                 "[graph]\nname = bench-rays\noutput = gbuffer.albedo\nwidth = %u\nheight = %u\n"
                 "[camera]\nposition = -120 90 120\nyaw = -40\npitch = -25\n"
                 "[scene]\nplugin = terrain\nseed = 1337\nradius = 13\ntime_of_day = 15\ntraversal = %s\n"
                 "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n%s"
                 "[pass shadow]\nplugin = sun_shadow\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\n"
                 "in.normal = gbuffer.normal\nrays = 1\nsun_radius = 0\n%s"
                 "[pass ao]\nplugin = ao\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\nin.normal = gbuffer.normal\n"
                 "rays = 1\nradius = 4\n%s"
                 "[pass indirect]\nplugin = indirect\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\n"
                 "in.normal = gbuffer.normal\nrays = 1\nshadow = 0\n%s",
                 width, height, backends[b], tlas, tlas, tlas, tlas);
        static const char *reads[] = {"gbuffer.normal", "shadow.visibility", "ao.ao", "indirect.irradiance"};
        vrg_graph_desc d = {.path = "<bench rays>", .text = text, .readback = reads, .readback_count = 4};
        vrg_graph *g = NULL;
        if (vrg_graph_load(ctx, &d, &g) != 0)
            return -1;
        static const char *passes[] = {"gbuffer", "shadow", "ao", "indirect"};
        static const char *kinds[] = {"primary", "sun shadow", "AO", "indirect"};
        double ms[4][64];
        for (int r = 0; r < runs + 2; r++) { /* two warm-up frames: the JIT, the world */
            if (vrg_graph_frame(g) != 0) {
                vrg_graph_destroy(g);
                return -1;
            }
            for (int k = 0; r >= 2 && k < 4; k++)
                for (uint32_t i = 0; i < vrg_graph_pass_count(g); i++)
                    if (strcmp(vrg_graph_pass_name(g, i), passes[k]) == 0)
                        ms[k][r - 2] = vrg_graph_pass_ms(g, i);
        }
        /* rays traced: every pixel; surface pixels; those facing the sun */
        vrg_image_data nrm;
        vrg_graph_read(g, "gbuffer.normal", &nrm);
        vrg_sky_desc sd;
        vrg_sky_default(&sd);
        sd.time_of_day = 15;
        vrg_sky sky;
        vrg_sky_eval(&sd, 0, &sky);
        double surface = 0, lit = 0;
        for (uint32_t i = 0; i < nrm.width * nrm.height; i++) {
            const float *v = nrm.pixels + 4 * i;
            if (v[0] == 0 && v[1] == 0 && v[2] == 0)
                continue;
            surface++;
            lit += sky.sun_elevation > 0 && v[0] * sky.sun_dir[0] + v[1] * sky.sun_dir[1] + v[2] * sky.sun_dir[2] > 0;
        }
        free(nrm.pixels);
        double rays[4] = {(double)width * height, lit, surface, surface};
        for (int k = 0; k < 4; k++) {
            double mr[64];
            for (int r = 0; r < runs; r++)
                mr[r] = ms[k][r] > 0 ? rays[k] / (ms[k][r] * 1e3) : 0;
            char name[128];
            snprintf(name, sizeof name, "rays: %s pass GPU time, %s, %ux%u", kinds[k], backends[b], width, height);
            out[n++] = summarise(name, "ms", ms[k], runs);
            snprintf(name, sizeof name, "rays: %s Mrays/s, %s (%.0f rays)", kinds[k], backends[b], rays[k]);
            out[n++] = summarise(name, "Mrays/s", mr, runs);
        }
        vrg_graph_destroy(g);
    }
    *count = n;
    return 0;
}

/* ---- reload: save-to-frame latency of hot reload ---- */

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
        if (vrg_graph_frame(*g) != 0)
            return -1;
        if (vrg_graph_source_changed(*g) && vrg_graph_reload(g) != 0)
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


/* A ray pass's shader saved: the thesis graph at 320x180 with a private
 * build of the ao pass whose shader folder is `dir` (the graph's folder
 * comes before the build's plugins on the search path), its ao.comp saved
 * with a new random-stream constant each run, so glslang and lavapipe's
 * JIT both do the whole work. Returns 0, 1 when there is no `cc`, -1. */
static int ray_shader_reload(vrg_context *ctx, const char *dir, int runs, double *ms)
{
    char path[1100], cmd[4096], graph[1100], shader[1100];
    snprintf(path, sizeof path, "%s/passes/ao/ao.comp", vrg_source_dir());
    char *src = vrg_cli_read_text(path);
    snprintf(path, sizeof path, "%s/graphs/thesis.ini", vrg_source_dir());
    char *thesis = vrg_cli_read_text(path);
    char *salt = src ? strstr(src, "const uint SALT = 0x414f0002u;") : NULL;
    int rc = -1;
    vrg_graph *g = NULL;
    if (!salt || !thesis)
        goto done;
    snprintf(cmd, sizeof cmd, "cc -std=c11 -shared -fPIC -I'%s/core/include' -DVRG_PLUGIN_DIR='\"%s\"' '%s/passes/ao/ao.c' -o '%s/ao.so' 2>/dev/null",
             vrg_source_dir(), dir, vrg_source_dir(), dir);
    if (system(cmd) != 0) {
        rc = 1;
        goto done;
    }
    snprintf(shader, sizeof shader, "%s/ao.comp", dir);
    snprintf(graph, sizeof graph, "%s/thesis.ini", dir);
    save_text(shader, src);
    save_text(graph, thesis);
    vrg_graph_desc d = {.path = graph, .width = 320, .height = 180};
    if (vrg_graph_load(ctx, &d, &g) != 0 || vrg_graph_watch(g, 1) != 0 || vrg_graph_frame(g) != 0)
        goto done;
    size_t head = (size_t)(salt - src);
    const char *tail = strchr(salt, '\n');
    unsigned unique = (unsigned)(getpid() % 100000) * 100;
    for (int r = 0; r < runs; r++) {
        size_t cap = strlen(src) + 64;
        char *text = malloc(cap);
        snprintf(text, cap, "%.*sconst uint SALT = 0x%08xu;%s", (int)head, src, 0x414f0000u + unique + (unsigned)r + 1, tail);
        double before = vrg_graph_reload_ms(g);
        save_text(shader, text);
        free(text);
        ms[r] = frames_until_reload(&g, before);
        if (ms[r] < 0)
            goto done;
    }
    rc = 0;
done:
    vrg_graph_destroy(g);
    free(src);
    free(thesis);
    return rc; /* the files stay: this ao is now the process's (removed at the end) */
}

static int bench_reload(vrg_context *ctx, int runs, figure *out, int *count)
{
    char dir[] = "/tmp/voxrg-bench-reload-XXXXXX";
    if (!mkdtemp(dir))
        return -1;
    char shader[1100], graph[1100], text[4096];
    double ms[64];
    int n = *count, ok = 1;
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
    for (int r = 0; ok && r < runs; r++) {
        snprintf(text, sizeof text, reload_shader, unique + r + 1);
        double before = vrg_graph_reload_ms(g);
        save_text(shader, text);
        ms[r] = frames_until_reload(&g, before);
        ok = ms[r] >= 0;
    }
    if (ok)
        out[n++] = summarise("reload: shader saved -> first frame using it (small compute shader)", "ms", ms, runs);
    vrg_graph_destroy(g);
    unsetenv("VOXRG_SHADER_PATH");
    /* before anything loads the build's ao: plugins are loaded once per process */
    char ray_dir[1100];
    snprintf(ray_dir, sizeof ray_dir, "%s/ray", dir);
    mkdir(ray_dir, 0700);
    int ray = ok ? ray_shader_reload(ctx, ray_dir, runs, ms) : -1;
    if (ray == 0)
        out[n++] = summarise("reload: ray pass shader saved (ao.comp in thesis.ini, 320x180) -> first frame using it", "ms", ms, runs);
    else if (ray > 0)
        printf("reload: ray pass shader figure skipped: no working `cc` to build the pass with\n");
    else
        ok = 0;
    /* a parameter of the thesis graph (320x180): reparse, revalidate, a new
     * graph instance with its world, history carried over, pipelines kept */
    char src[1100];
    snprintf(src, sizeof src, "%s/graphs/thesis.ini", vrg_source_dir());
    FILE *f = fopen(src, "r");
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
        for (int r = 0; ok && r < runs; r++) {
            iter[18] = r % 2 ? '7' : '5';
            double before = vrg_graph_reload_ms(g);
            save_text(graph, text);
            ms[r] = frames_until_reload(&g, before);
            ok = ms[r] >= 0;
        }
        if (ok)
            out[n++] = summarise("reload: thesis.ini parameter saved -> first frame (320x180, world regenerated)", "ms", ms, runs);
        vrg_graph_destroy(g);
    }
    /* a plugin rebuilt: private copy, dlopen, ABI checks, a new graph
     * instance with the state handed over (the compile itself not counted:
     * the clock starts at the file's mtime) */
    char plugin_src[1100], cmd[4096], so[1100];
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
    save_text(graph, "[graph]\noutput = color\nwidth = 64\nheight = 64\n[pass fill]\nplugin = benchfill\nout.color = color\n");
    g = NULL;
    for (int r = -1; ok && r < runs; r++) {
        snprintf(cmd, sizeof cmd,
                 "cc -std=c11 -shared -fPIC -I'%s/core/include' -DVALUE=%d -DDIR='\"%s\"' '%s' -o '%s.new' 2>/dev/null && mv '%s.new' '%s'",
                 vrg_source_dir(), r + 2, dir, plugin_src, so, so, so);
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
            out[n++] = summarise("reload: plugin rebuilt -> first frame using it (build time not counted)", "ms", ms, runs);
    }
    vrg_graph_destroy(g);
    remove(so), remove(plugin_src), remove(shader), remove(graph);
    snprintf(graph, sizeof graph, "%s/thesis.ini", dir);
    remove(graph);
    snprintf(graph, sizeof graph, "%s/shader.ini", dir);
    remove(graph);
    snprintf(shader, sizeof shader, "%s/user.comp", dir);
    remove(shader);
    static const char *ray_files[] = {"ao.so", "ao.comp", "thesis.ini"};
    for (int i = 0; i < 3; i++) {
        snprintf(shader, sizeof shader, "%s/%s", ray_dir, ray_files[i]);
        remove(shader);
    }
    rmdir(ray_dir);
    rmdir(dir);
    *count = n;
    return ok ? 0 : -1;
}

int vrg_cli_bench(const char *suite, const char *json, int runs, const char *device)
{
    int want_terrain = !strcmp(suite, "all") || !strcmp(suite, "terrain"), want_rays = !strcmp(suite, "all") || !strcmp(suite, "rays"),
        want_reload = !strcmp(suite, "all") || !strcmp(suite, "reload");
    if (!want_terrain && !want_rays && !want_reload) {
        fprintf(stderr, "error: --suite '%s': this build has: all, terrain, rays, reload (graph, memory and frame come with later milestones)\n",
                suite);
        return 2;
    }
    vrg_context *ctx;
    vrg_context_desc cd = {.device = device};
    if (vrg_context_create(&cd, &ctx) != 0)
        return 1;
    figure figs[64];
    const char *suites[64];
    int n = 0, before = 0;
    if (want_terrain && bench_terrain(ctx, runs, figs, &n) != 0) {
        fprintf(stderr, "error: terrain benchmark failed\n");
        vrg_context_destroy(ctx);
        return 1;
    }
    for (; before < n; before++)
        suites[before] = "terrain";
    if (want_rays && bench_rays(ctx, runs, 640, 360, figs, &n) != 0) {
        fprintf(stderr, "error: rays benchmark failed\n");
        vrg_context_destroy(ctx);
        return 1;
    }
    for (; before < n; before++)
        suites[before] = "rays";
    if (want_reload && bench_reload(ctx, runs, figs, &n) != 0) {
        fprintf(stderr, "error: reload benchmark failed\n");
        vrg_context_destroy(ctx);
        return 1;
    }
    for (; before < n; before++)
        suites[before] = "reload";
    const char *lp = getenv("LP_NUM_THREADS");
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    printf("device: %s; CPUs: %ld; LP_NUM_THREADS: %s; %d runs after warm-up\n", vrg_context_device(ctx)->name, cpus, lp ? lp : "(unset)", runs);
    printf("%-86s %10s %10s %10s %10s\n", "figure", "median", "min", "max", "p99");
    for (int i = 0; i < n; i++)
        printf("%-86s %10.3f %10.3f %10.3f %10.3f %s\n", figs[i].name, figs[i].median, figs[i].min, figs[i].max, figs[i].p99, figs[i].unit);
    int rc = 0;
    if (json) {
        FILE *f = fopen(json, "w");
        if (!f) {
            fprintf(stderr, "error: cannot write %s\n", json);
            rc = 1;
        } else {
            fprintf(f, "{\n  \"device\": \"%s\",\n  \"cpus\": %ld,\n  \"lp_num_threads\": \"%s\",\n  \"runs\": %d,\n  \"figures\": [", vrg_context_device(ctx)->name,
                    cpus, lp ? lp : "", runs);
            for (int i = 0; i < n; i++)
                fprintf(f, "%s\n    {\"suite\": \"%s\", \"name\": \"%s\", \"unit\": \"%s\", \"median\": %.6g, \"min\": %.6g, \"max\": %.6g, \"p99\": %.6g, \"samples\": %d}",
                        i ? "," : "", suites[i], figs[i].name, figs[i].unit, figs[i].median, figs[i].min, figs[i].max, figs[i].p99, figs[i].samples);
            fprintf(f, "\n  ]\n}\n");
            fclose(f);
        }
    }
    vrg_context_destroy(ctx);
    return rc;
}
