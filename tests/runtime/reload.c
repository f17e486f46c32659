#define _POSIX_C_SOURCE 200809L
/* Hot reload of shaders, graphs and plugins (rebuilt with cc) while a graph
 * runs: edits take effect, broken edits keep the running version.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include <fcntl.h>
#include <sys/stat.h>
#include <time.h>
#include "harness.h"

static const char *user_shader =
    "#version 450\n#include \"tint.glsl\"\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
    "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(TINT, 1.0)); }\n";

/* A folder of user.comp and the tint.glsl it includes, on VOXRG_SHADER_PATH
 * for tests/graphs/shader_file.ini; dir is a mkdtemp template. */
static int shader_folder(char *dir, char user[1100], char tint[1100])
{
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return -1;
    }
    snprintf(user, 1100, "%s/user.comp", dir);
    snprintf(tint, 1100, "%s/tint.glsl", dir);
    save_file(user, user_shader);
    save_file(tint, "#define TINT vec3(0.25, 0.5, 0.75)\n");
    setenv("VOXRG_SHADER_PATH", dir, 1);
    return 0;
}

/* Hot reload of shaders: a saved shader (or a file it #includes) is in use
 * on the next frame; a broken one is reported with FILE:LINE while the last
 * good pipeline keeps rendering; fixing it brings the new version. */
static void test_hot_reload_shader(void)
{
    char dir[] = "/tmp/voxrg-reload-XXXXXX", user[1100], tint[1100];
    if (shader_folder(dir, user, tint) != 0)
        return;
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/shader_file.ini", TEST_DIR);
    static const char *reads[] = {"color"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load shader_file.ini");
        fclose(diag);
        free(log);
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    float want[4][3] = {{0.25f, 0.5f, 0.75f}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (int step = 0; step < 4; step++) {
        if (step == 1) /* the included file changes */
            save_file(tint, "#define TINT vec3(1.0, 0.0, 0.0)\n");
        if (step == 2) /* a syntax error in the main file */
            save_file(user, "#version 450\nlayout(local_size_x = 8) in;\nvoid main() { this is not glsl }\n");
        if (step == 3) { /* fixed again, and a new colour */
            save_file(user, user_shader);
            save_file(tint, "#define TINT vec3(0.0, 1.0, 0.0)\n");
        }
        CHECK(vrg_graph_frame(g) == 0, "step %d: the frame failed: a reload must not stop the graph", step);
        CHECK(vrg_graph_read(g, "color", &img) == 0, "readback failed");
        for (int c = 0; c < 3; c++)
            CHECK(fabsf(px(&img, 5, 7, c) - want[step][c]) < 1e-3f, "step %d: channel %d is %g, want %g", step, c, px(&img, 5, 7, c),
                  want[step][c]);
        free(img.pixels);
        const char *err = vrg_graph_reload_error(g);
        if (step == 2) {
            fflush(diag);
            CHECK(err && strstr(err, "user.comp:3: error[VRG-E063]"), "no FILE:LINE reload error: %s", err ? err : "(none)");
            CHECK(log && strstr(log, "user.comp:3: error[VRG-E063]"), "the error was not printed: %s", log ? log : "");
        } else
            CHECK(!err, "step %d: unexpected reload error %s", step, err);
        if (step == 1 || step == 3)
            CHECK(vrg_graph_reload_ms(g) >= 0 && vrg_graph_reload_ms(g) < 60000, "step %d: reload time %g ms", step, vrg_graph_reload_ms(g));
    }
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    unsetenv("VOXRG_SHADER_PATH");
    remove(user), remove(tint), rmdir(dir);
}

/* A shader saved while earlier frames are still in flight (none waited
 * for): its old pipeline stays alive until those frames end (the validation
 * layer reports destroying a pipeline in use otherwise) and the next frame
 * uses the new one. */
static void test_hot_reload_shader_in_flight(void)
{
    char dir[] = "/tmp/voxrg-reload-XXXXXX", user[1100], tint[1100], path[1024];
    if (shader_folder(dir, user, tint) != 0)
        return;
    snprintf(path, sizeof path, "%s/graphs/shader_file.ini", TEST_DIR);
    static const char *reads[] = {"color"};
    vrg_graph_desc d = {.path = path, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(ctx, &d, &g) == 0, "cannot load shader_file.ini");
    if (g) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        for (int k = 0; k < 3; k++) /* frames in flight, never waited for here */
            CHECK(vrg_graph_frame(g) == 0, "frame %d failed", k);
        save_file(tint, "#define TINT vec3(1.0, 0.0, 0.0)\n");
        CHECK(vrg_graph_frame(g) == 0, "the frame after the save failed");
        vrg_image_data img;
        CHECK(vrg_graph_read(g, "color", &img) == 0, "readback failed");
        if (img.pixels) {
            CHECK(fabsf(px(&img, 5, 7, 0) - 1.0f) < 1e-3f && fabsf(px(&img, 5, 7, 1)) < 1e-3f, "the saved shader is not in use: (%g, %g)",
                  px(&img, 5, 7, 0), px(&img, 5, 7, 1));
            free(img.pixels);
        }
        vrg_graph_destroy(g);
    }
    unsetenv("VOXRG_SHADER_PATH");
    remove(user), remove(tint), rmdir(dir);
}

/* variant 0: as loaded; 1: an unrelated pass added (structural, every
 * history resource keeps its name); 2: the counter's resource renamed */
static const char *reload_graph_text(float step, int variant, int broken)
{
    static char text[1024];
    const char *count = variant == 2 ? "total" : "count";
    snprintf(text, sizeof text,
             "[graph]\noutput = mean.color\nwidth = 8\nheight = 8\n"
             "[pass counter]\nplugin = counter\nin.prev = %s@prev\nout.count = %s\nstep = %g\n"
             "[pass mean]\nplugin = accumulate\nin.src = %s\nin.history = mean.color@prev\n%s%s",
             count, count, step, count, variant == 1 ? "[pass other]\nplugin = counter\nout.count = other\n" : "",
             broken ? "this line is not ini\n" : "");
    return text;
}

/* Hot reload of the graph file: a parameter-only change keeps history (the
 * counter continues) and restarts accumulations; a structural change keeps
 * the history resources whose name, format and size are unchanged and
 * starts the others anew; a broken file leaves the running graph as it was,
 * with the error kept at FILE:LINE. */
static void test_hot_reload_graph(void)
{
    char dir[] = "/tmp/voxrg-graph-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100];
    snprintf(path, sizeof path, "%s/reload.ini", dir);
    save_file(path, reload_graph_text(1, 0, 0));
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    static const char *reads[] = {"mean.color"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load the reload graph");
        fclose(diag);
        free(log);
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    /* each step: the file saved before it, then one frame that notices the
     * save (still the old graph), the reload, and one frame read back */
    struct {
        float step;
        int variant, broken;
        float mean, frames;
    } steps[] = {
        {1, 0, 0, 2, 3},  /* frames 1..3 as loaded: counts 1 2 3 */
        {2, 0, 0, 6, 1},  /* parameters only: 4 (noticing), then 4 + 2 = 6 kept going; the mean restarts */
        {2, 1, 0, 10, 1}, /* a pass added: 8 (noticing), the count kept: 10; the mean restarts */
        {2, 2, 0, 2, 1},  /* the count renamed: its history starts anew: 2 */
        {5, 2, 1, 4, 3},  /* broken: the running graph goes on: 4, 6, mean of 2 4 6 */
    };
    int step_count = (int)(sizeof steps / sizeof steps[0]);
    for (int s = 0; s < step_count; s++) {
        if (s > 0) {
            save_file(path, reload_graph_text(steps[s].step, steps[s].variant, steps[s].broken));
            CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices the save */
            CHECK(vrg_graph_source_changed(g), "step %d: the save was not noticed", s);
            int rc = vrg_graph_reload(&g);
            CHECK((rc == 0) == !steps[s].broken, "step %d: reload returned %d", s, rc);
            if (steps[s].broken) {
                const char *err = vrg_graph_reload_error(g);
                CHECK(err && strstr(err, "reload.ini:14: error"), "no FILE:LINE error for the broken graph: %s", err ? err : "(none)");
            }
        } else
            for (int i = 0; i < 2; i++)
                CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "step %d: frame failed", s);
        CHECK(px(&img, 2, 3, 0) == steps[s].mean && px(&img, 2, 3, 3) == steps[s].frames, "step %d: mean %g over %g frames, want %g over %g",
              s, px(&img, 2, 3, 0), px(&img, 2, 3, 3), steps[s].mean, steps[s].frames);
        free(img.pixels);
    }
    /* a host that polls before its frame reloads with no frame of the old
     * graph after the save: 6 + 3 = 9, the mean restarted */
    save_file(path, reload_graph_text(3, 2, 0));
    CHECK(vrg_graph_poll_changes(g) == 1, "the save was not noticed before a frame");
    CHECK(vrg_graph_reload(&g) == 0, "reload failed");
    CHECK(vrg_graph_poll_changes(g) == 0, "the new graph reports the save it was loaded from");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "mean.color", &img) == 0, "frame failed");
    CHECK(px(&img, 2, 3, 0) == 9 && px(&img, 2, 3, 3) == 1, "mean %g over %g frames, want 9 over 1", px(&img, 2, 3, 0), px(&img, 2, 3, 3));
    free(img.pixels);
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    remove(path), rmdir(dir);
}

/* keep_probe's graph: `keep` the output its create() asks to keep (NULL:
 * none); limited adds a pass whose resize() refuses the graph's width, so
 * the load fails after every create() and the allocation. */
static const char *keep_graph_text(int value, const char *keep, int limited)
{
    static char text[512];
    snprintf(text, sizeof text,
             "[graph]\noutput = %s\nwidth = 8\nheight = 8\n"
             "[pass probe]\nplugin = keep_probe\nout.data = data\nout.color = color\nvalue = %d\n%s%s%s%s",
             limited ? "grey" : "color", value, keep ? "keep = " : "", keep ? keep : "", keep ? "\n" : "",
             limited ? "[pass limit]\nplugin = resize_limit\nout.color = grey\nmax_width = 4\n" : "");
    return text;
}

/* vrg_pass_keep_resource: a reload whose pass asks to keep its persistent
 * output hands the old contents over (vrg_res_fresh 0, nothing cleared);
 * without the request the output starts anew. A reload that fails after
 * create() leaves the old graph's resource as it was; a resize makes it
 * new. Asking for an output that is not persistent, or none, is an error
 * naming it. */
static void test_hot_reload_keep_resource(void)
{
    char dir[] = "/tmp/voxrg-keep-XXXXXX", path[1100];
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    snprintf(path, sizeof path, "%s/keep.ini", dir);
    save_file(path, keep_graph_text(1, "data", 0));
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    static const char *reads[] = {"data"};
    vrg_graph_desc d = {.path = path, .diag = diag, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load the keep graph");
        fclose(diag);
        free(log);
        return;
    }
    struct {
        int value;
        const char *keep;
        int limited, resize;
        const char *error; /* the reload fails with it */
        uint32_t data;
        double fresh;
    } steps[] = {
        {1, "data", 0, 0, NULL, 1, 1},                       /* as loaded */
        {2, "data", 0, 0, NULL, 1, 0},                       /* kept: the old value */
        {3, NULL, 0, 0, NULL, 3, 1},                         /* not asked: anew */
        {4, "data", 1, 0, "max_width 4", 3, 0},              /* fails after create(): the old graph's, untouched */
        {5, "data", 0, 1, NULL, 5, 1},                       /* kept, then resized: anew */
        {6, "color", 0, 0, "output 'color' is not a persistent", 5, 0},
        {7, "nothing", 0, 0, "no output 'nothing'", 5, 0},
    };
    for (int s = 0; s < (int)(sizeof steps / sizeof steps[0]); s++) {
        if (s > 0) {
            save_file(path, keep_graph_text(steps[s].value, steps[s].keep, steps[s].limited));
            int rc = vrg_graph_reload(&g);
            CHECK((rc == 0) == !steps[s].error, "step %d: reload returned %d", s, rc);
            const char *err = vrg_graph_reload_error(g);
            if (steps[s].error)
                CHECK(err && strstr(err, steps[s].error) && strstr(err, "keep.ini:"), "step %d: reload error %s", s, err ? err : "(none)");
        }
        if (steps[s].resize)
            CHECK(vrg_graph_resize(g, 8, 8) == 0, "step %d: resize failed", s);
        void *data = NULL;
        uint64_t size = 0;
        double fresh = -1;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read_buffer(g, "data", &data, &size) == 0 && size == 16, "step %d: frame failed", s);
        CHECK(vrg_graph_stat(g, "probe", "fresh", &fresh) == 0 && fresh == steps[s].fresh, "step %d: fresh %g", s, fresh);
        const uint32_t *u = data;
        CHECK(u && u[0] == steps[s].data && u[3] == steps[s].data, "step %d: data %u, want %u", s, u ? u[0] : 0, steps[s].data);
        free(data);
    }
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    unlink(path);
    rmdir(dir);
}

/* reloadme.comp beside the test plugin: the colour its push constant says */
static const char *const reloadme_shader = "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                                           "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                                           "layout(push_constant) uniform P { vec4 c; } pc;\n"
                                           "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n";

static const char *reloadme_source =
    "#include <stdlib.h>\n#include <string.h>\n#include \"voxrg/plugin.h\"\n"
    "static const vrg_slot_desc slots[] = {{.name = \"color\", .dir = VRG_OUT, .kind = VRG_IMAGE,\n"
    "    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};\n"
    "typedef struct { int frames; } state;\n"
    "static int create(vrg_pass *p) {\n"
    "#ifdef LONG_MESSAGES\n    char m[3001];\n    memset(m, 'm', 3000);\n    memcpy(m + 2990, \"end_of_it\", 10);\n"
    "    vrg_pass_warn_at(p, 0, \"warned %s\", m);\n    return vrg_pass_error(p, \"failed %s\", m);\n#endif\n"
    "#ifdef CHOICE_WITHOUT_LIST\n    if (vrg_param_choice(p, \"level\", NULL, 0) < 0)\n        return -1;\n#endif\n"
    "#ifdef SAME_SIZE_TYPO\n    static const char *const names[] = {\"colour\"};\n"
    "    if (vrg_pass_require_same_size(p, \"color\", names, 1) != 0)\n        return -1;\n#endif\n"
    "    vrg_pass_set_user(p, calloc(1, sizeof(state)));\n    return 0;\n}\n"
    "static void destroy(vrg_pass *p) { free(vrg_pass_user(p)); }\n"
    "static void execute(vrg_pass *p, VkCommandBuffer cmd) {\n"
    "    state *s = vrg_pass_user(p);\n    s->frames++;\n"
    "    float pc[4] = {VERSION == 1, VERSION == 2, s->frames / 100.0f, 1};\n"
    "    (void)vrg_dispatch(p, cmd, &(vrg_dispatch_desc){.shader = \"reloadme.comp\", .push = pc, .push_size = sizeof pc});\n}\n"
    "static size_t save(vrg_pass *p, void *dst, size_t cap) {\n"
    "#ifdef SAVE_TOO_MUCH\n    (void)p, (void)dst;\n    return cap + 1;\n#endif\n"
    "    if (cap < sizeof(state)) return 0;\n    memcpy(dst, vrg_pass_user(p), sizeof(state));\n    return sizeof(state);\n}\n"
    "static int restore(vrg_pass *p, const void *src, size_t n) {\n"
    "    if (n != sizeof(state)) return -1;\n    memcpy(vrg_pass_user(p), src, n);\n    return 0;\n}\n"
    "#ifndef NAME\n#define NAME \"reloadme\"\n#endif\n"
    "#ifdef CHOICE_WITHOUT_LIST\n"
    "static const vrg_param_desc params[] = {{.name = \"level\", .type = VRG_PARAM_STRING, .default_string = \"mid\"}};\n"
    "#define PARAMS .params = params, .param_count = 1,\n#else\n#define PARAMS\n#endif\n"
    "static const vrg_plugin_desc desc = {.abi_version = ABI, .name = NAME, .kind = VRG_PLUGIN_PASS,\n"
    "    .help = \"test: hot reload\", .shader_dir = DIR, .slots = slots, .slot_count = 1, .create = create, PARAMS\n"
    "    .destroy = destroy, .execute = execute, .save_state = save, .restore_state = restore};\n"
    "VRG_PLUGIN(desc)\n";

/* Builds the test plugin `reloadme` (VERSION paints red or green, ABI its
 * declared ABI version) into dir/reloadme.so with the system compiler. */
static int build_plugin_flags(const char *dir, const char *name, int version, const char *abi, const char *flags)
{
    char src[1100], cmd[4096];
    snprintf(src, sizeof src, "%s/%s.c", dir, name);
    save_file(src, reloadme_source);
    snprintf(cmd, sizeof cmd,
             "cc -std=c11 -shared -fPIC -I'%s/../core/runtime/include' %s -DNAME='\"%s\"' -DVERSION=%d -DABI=%s -DDIR='\"%s\"' '%s' -o '%s/%s.so.new' && "
             "mv '%s/%s.so.new' '%s/%s.so'",
             TEST_DIR, flags, name, version, abi, dir, src, dir, name, dir, name, dir, name);
    return system(cmd);
}

static int build_plugin_named(const char *dir, const char *name, int version, const char *abi)
{
    return build_plugin_flags(dir, name, version, abi, "");
}

static int build_reloadme(const char *dir, int version, const char *abi) { return build_plugin_named(dir, "reloadme", version, abi); }

/* How many distinct files named like `name` are mapped into this process:
 * the versions of a plugin still loaded. */
static int mapped_versions(const char *name)
{
    char seen[16][512];
    int n = 0;
    char line[1024];
    FILE *f = fopen("/proc/self/maps", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *path = strchr(line, '/');
        if (!path || !strstr(path, name))
            continue;
        path[strcspn(path, "\n")] = '\0';
        int known = 0;
        for (int i = 0; i < n; i++)
            known |= strcmp(seen[i], path) == 0;
        if (!known && n < 16)
            snprintf(seen[n++], sizeof seen[0], "%s", path);
    }
    if (f)
        fclose(f);
    return n;
}

/* More rebuilt plugins in one reload than there once was room for: every
 * one of them runs its new version afterwards. */
static void test_hot_reload_many_plugins(void)
{
    enum { PLUGINS = 10 };
    char dir[] = "/tmp/voxrg-plugins-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100], name[PLUGINS][32], *text = NULL;
    const char *reads[PLUGINS];
    size_t tlen = 0;
    snprintf(path, sizeof path, "%s/many.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    save_file(shader, reloadme_shader);
    append(&text, &tlen, "[graph]\noutput = c0\nwidth = 8\nheight = 8\n");
    for (int i = 0; i < PLUGINS; i++) {
        snprintf(name[i], sizeof name[i], "reloadme%d", i);
        append(&text, &tlen, "[pass p%d]\nplugin = %s\nout.color = c%d\n", i, name[i], i);
        CHECK(build_plugin_named(dir, name[i], 1, "VRG_ABI_VERSION") == 0, "cannot build %s with cc", name[i]);
    }
    save_file(path, text);
    free(text);
    char cname[PLUGINS][16];
    for (int i = 0; i < PLUGINS; i++) {
        snprintf(cname[i], sizeof cname[i], "c%d", i);
        reads[i] = cname[i];
    }
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    vrg_graph_desc d = {.path = path, .readback = reads, .readback_count = PLUGINS};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < PLUGINS; i++)
            CHECK(build_plugin_named(dir, name[i], 2, "VRG_ABI_VERSION") == 0, "cannot rebuild %s", name[i]);
        CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices every rebuild at once */
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "reload failed: %s",
              vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : "");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        for (int i = 0; i < PLUGINS; i++) {
            vrg_image_data img;
            CHECK(vrg_graph_read(g, cname[i], &img) == 0, "readback of %s failed", cname[i]);
            CHECK(px(&img, 1, 1, 0) == 0 && px(&img, 1, 1, 1) == 1, "%s still runs version 1 (%g %g)", name[i], px(&img, 1, 1, 0),
                  px(&img, 1, 1, 1));
            free(img.pixels);
        }
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", path);
    unsetenv("VOXRG_PLUGIN_PATH");
    for (int i = 0; i < PLUGINS; i++) {
        char f[1100];
        snprintf(f, sizeof f, "%s/%s.so", dir, name[i]);
        remove(f);
        snprintf(f, sizeof f, "%s/%s.c", dir, name[i]);
        remove(f);
    }
    remove(shader), remove(path), rmdir(dir);
}

/* More saved files in one poll than there once was room for (the last were
 * dropped): one pass's shader with many includes, all saved again, then the
 * one file that matters, another pass's shader (pattern.comp, taken from
 * $VOXRG_SHADER_OVERRIDE), saved last with a new colour. The includes also
 * outnumber the include table there once was (the last were left out of the
 * source: TINT, in the last include, was undeclared). */
static void test_hot_reload_many_files(void)
{
    enum { INCLUDES = 40 };
    char dir[] = "/tmp/voxrg-includes-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char user[1100], graph[1100], pattern[1100], inc[INCLUDES][1100], *text = NULL;
    size_t tlen = 0;
    snprintf(user, sizeof user, "%s/user.comp", dir);
    snprintf(graph, sizeof graph, "%s/g.ini", dir);
    snprintf(pattern, sizeof pattern, "%s/pattern.comp", dir);
    append(&text, &tlen, "#version 450\n");
    for (int i = 0; i < INCLUDES; i++) {
        snprintf(inc[i], sizeof inc[i], "%s/inc%d.glsl", dir, i);
        append(&text, &tlen, "#include \"inc%d.glsl\"\n", i);
    }
    append(&text, &tlen, "layout(local_size_x = 8, local_size_y = 8) in;\nlayout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                         "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(TINT, 1.0)); }\n");
    static const char pattern_shader[] = "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                                         "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
                                         "layout(push_constant) uniform P { float value; } pc;\n"
                                         "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(%d.0, 0.5, 0.0, 1.0)); }\n";
    char pattern_text[sizeof pattern_shader + 16];
    save_file(graph, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass s]\nplugin = shader_file\nout.color = color\n"
                     "[pass p]\nplugin = pattern\nout.color = grad\n");
    for (int i = 0; i < INCLUDES - 1; i++)
        save_file(inc[i], "\n");
    save_file(inc[INCLUDES - 1], "#define TINT vec3(1.0, 0.0, 0.0)\n");
    save_file(user, text);
    snprintf(pattern_text, sizeof pattern_text, pattern_shader, 1);
    save_file(pattern, pattern_text);
    setenv("VOXRG_SHADER_PATH", dir, 1);
    setenv("VOXRG_SHADER_OVERRIDE", dir, 1);
    static const char *reads[] = {"grad"};
    vrg_graph_desc d = {.path = graph, .readback = reads, .readback_count = 1};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        vrg_image_data img;
        for (int step = 0; step < 2; step++) {
            if (step == 1) { /* the first pass's files saved again unchanged, the change last */
                save_file(user, text);
                for (int i = 0; i < INCLUDES - 1; i++)
                    save_file(inc[i], "\n");
                save_file(inc[INCLUDES - 1], "#define TINT vec3(1.0, 0.0, 0.0)\n");
                snprintf(pattern_text, sizeof pattern_text, pattern_shader, 2);
                save_file(pattern, pattern_text);
            }
            CHECK(vrg_graph_frame(g) == 0, "step %d: frame failed", step);
            CHECK(vrg_graph_read(g, "color", &img) == 0, "readback failed");
            CHECK(px(&img, 3, 3, 0) == 1.0f && px(&img, 3, 3, 1) == 0.0f, "step %d: colour %g %g", step, px(&img, 3, 3, 0), px(&img, 3, 3, 1));
            free(img.pixels);
            CHECK(vrg_graph_read(g, "grad", &img) == 0, "readback failed");
            CHECK(px(&img, 3, 3, 0) == (float)(step + 1), "step %d: pattern.comp's colour is %g, want %d (its save was not seen)", step,
                  px(&img, 3, 3, 0), step + 1);
            free(img.pixels);
            CHECK(!vrg_graph_reload_error(g), "step %d: reload error %s", step, vrg_graph_reload_error(g));
        }
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", graph);
    free(text);
    unsetenv("VOXRG_SHADER_PATH");
    unsetenv("VOXRG_SHADER_OVERRIDE");
    for (int i = 0; i < INCLUDES; i++)
        remove(inc[i]);
    remove(user), remove(graph), remove(pattern), rmdir(dir);
}

/* A save_state() that claims more bytes than it may write: the new instance
 * starts afresh with a message naming the limit (it was once dropped without
 * a word). */
static void test_hot_reload_state_too_big(void)
{
    char dir[] = "/tmp/voxrg-state-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100], so[1100], src[1100];
    snprintf(path, sizeof path, "%s/state.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    snprintf(so, sizeof so, "%s/bigstate.so", dir);
    snprintf(src, sizeof src, "%s/bigstate.c", dir);
    save_file(path, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass r]\nplugin = bigstate\nout.color = color\n");
    save_file(shader, reloadme_shader);
    CHECK(build_plugin_flags(dir, "bigstate", 1, "VRG_ABI_VERSION", "-DSAVE_TOO_MUCH") == 0, "cannot build the test plugin with cc");
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    vrg_graph_desc d = {.path = path, .diag = diag};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) == 0) {
        CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
        for (int i = 0; i < 3; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(build_plugin_flags(dir, "bigstate", 2, "VRG_ABI_VERSION", "-DSAVE_TOO_MUCH") == 0, "rebuild failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "reload failed");
        vrg_image_data img;
        CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
        CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.01f) < 1e-3f, "version 2 did not start afresh: %g %g %g", px(&img, 1, 1, 0),
              px(&img, 1, 1, 1), px(&img, 1, 1, 2));
        free(img.pixels);
        vrg_graph_destroy(g);
    } else
        CHECK(0, "cannot load %s", path);
    fclose(diag);
    CHECK(log && strstr(log, "save_state() returned 65537 bytes, more than the 65536 it may write"), "no message: %s", log ? log : "");
    free(log);
    unsetenv("VOXRG_PLUGIN_PATH");
    remove(so), remove(src), remove(shader), remove(path), rmdir(dir);
}

/* Builds the test plugin with `flags` as `name` into a folder of its own,
 * loads a graph of one pass of it and returns what the load said (NULL
 * after a failure to build); *loaded: whether the graph loaded. */
static char *load_log_of(const char *name, const char *flags, int *loaded)
{
    char dir[] = "/tmp/voxrg-plugin-XXXXXX";
    *loaded = 0;
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return NULL;
    }
    char path[1100], shader[1100], so[1100], src[1100], text[256];
    snprintf(path, sizeof path, "%s/graph.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    snprintf(so, sizeof so, "%s/%s.so", dir, name);
    snprintf(src, sizeof src, "%s/%s.c", dir, name);
    snprintf(text, sizeof text, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass r]\nplugin = %s\nout.color = color\n", name);
    save_file(path, text);
    save_file(shader, reloadme_shader);
    char *log = NULL;
    if (build_plugin_flags(dir, name, 1, "VRG_ABI_VERSION", flags) == 0) {
        setenv("VOXRG_PLUGIN_PATH", dir, 1);
        size_t len = 0;
        FILE *diag = open_memstream(&log, &len);
        vrg_graph_desc d = {.path = path, .diag = diag};
        vrg_graph *g = NULL;
        *loaded = vrg_graph_load(ctx, &d, &g) == 0;
        if (*loaded)
            vrg_graph_destroy(g);
        fclose(diag);
        unsetenv("VOXRG_PLUGIN_PATH");
    } else
        CHECK(0, "cannot build the test plugin with cc");
    remove(so), remove(src), remove(shader), remove(path), rmdir(dir);
    return log;
}

/* A plugin's warning and error reach the diagnostics whole, however long
 * (they were once cut at 1536 bytes). */
static void test_long_plugin_messages(void)
{
    int loaded;
    char *log = load_log_of("longmsg", "-DLONG_MESSAGES", &loaded);
    CHECK(!loaded, "a graph whose pass fails in create() loaded");
    const char *warned = log ? strstr(log, "warned mmm") : NULL, *failed = log ? strstr(log, "failed mmm") : NULL;
    CHECK(warned && strncmp(warned + 7 + 2990, "end_of_it", 9) == 0, "the warning is cut: %.80s...", warned ? warned : "(none)");
    CHECK(failed && strncmp(failed + 7 + 2990, "end_of_it", 9) == 0, "the error is cut: %.80s...", failed ? failed : "(none)");
    free(log);
}

/* The test plugin built with `flags` fails in create() with the pass
 * API's misuse (VRG-E062) and `message`. */
static void check_misuse(const char *name, const char *flags, const char *message)
{
    int loaded;
    char *log = load_log_of(name, flags, &loaded);
    CHECK(!loaded, "%s: a graph whose pass fails in create() loaded", name);
    CHECK(log && strstr(log, "VRG-E062") && strstr(log, message), "%s: no misuse error: %s", name, log ? log : "(none)");
    free(log);
}

/* vrg_param_choice with no list of its own (NULL) for a string parameter
 * the plugin lists no choices for (param_choices): an error naming the
 * API's misuse. */
static void test_param_choice_without_list(void)
{
    check_misuse("nochoice", "-DCHOICE_WITHOUT_LIST", "vrg_param_choice('level', NULL): the plugin lists no choices for it");
}

/* vrg_pass_require_same_size given a name that is no slot of the pass (it
 * skips unconnected optional slots, not misspelt ones): an error naming
 * the API's misuse and the name. */
static void test_same_size_unknown_slot(void)
{
    check_misuse("typo", "-DSAME_SIZE_TYPO", "vrg_pass_require_same_size: 'colour' names no slot of this pass");
}

/* Hot reload of a rebuilt plugin: the new build runs from the next graph
 * instance on, with the old instance's state handed over (save_state ->
 * restore_state: its frame count goes on); a rebuild with another ABI
 * version is refused and the running version keeps going. */
static void test_hot_reload_plugin(void)
{
    char dir[] = "/tmp/voxrg-plugin-test-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char path[1100], shader[1100];
    snprintf(path, sizeof path, "%s/reload.ini", dir);
    snprintf(shader, sizeof shader, "%s/reloadme.comp", dir);
    save_file(path, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass r]\nplugin = reloadme\nout.color = color\n");
    /* the graph was saved an hour before the plugin is rebuilt: the reload
     * is timed from the rebuilt .so, not from the graph file */
    struct timespec hour_ago[2];
    clock_gettime(CLOCK_REALTIME, &hour_ago[0]);
    hour_ago[0].tv_sec -= 3600;
    hour_ago[1] = hour_ago[0];
    CHECK(utimensat(AT_FDCWD, path, hour_ago, 0) == 0, "cannot set the graph file's mtime");
    save_file(shader, reloadme_shader);
    if (build_reloadme(dir, 1, "VRG_ABI_VERSION") != 0) {
        CHECK(0, "cannot build the test plugin with cc");
        return;
    }
    setenv("VOXRG_PLUGIN_PATH", dir, 1);
    char *log = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&log, &len);
    vrg_graph_desc d = {.path = path, .diag = diag};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        CHECK(0, "cannot load the plugin reload graph");
        fclose(diag);
        free(log);
        unsetenv("VOXRG_PLUGIN_PATH");
        return;
    }
    CHECK(vrg_graph_watch(g, 1) == 0, "watch failed");
    vrg_image_data img;
    for (int i = 0; i < 3; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "color", &img) == 0 && px(&img, 1, 1, 0) == 1 && fabsf(px(&img, 1, 1, 2) - 0.03f) < 1e-3f,
          "version 1 after 3 frames: %g %g %g", px(&img, 1, 1, 0), px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);

    CHECK(build_reloadme(dir, 2, "VRG_ABI_VERSION") == 0, "rebuild failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed"); /* notices the rebuild: frame 4 */
    CHECK(vrg_graph_source_changed(g), "the rebuilt plugin was not noticed");
    CHECK(vrg_graph_reload(&g) == 0, "reload failed:\n%s", vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : "");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 0) == 0 && px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.05f) < 1e-3f,
          "version 2, state carried over (5 frames): %g %g %g", px(&img, 1, 1, 0), px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    CHECK(vrg_graph_reload_ms(g) >= 0 && vrg_graph_reload_ms(g) < 5 * 60 * 1000,
          "a plugin rebuilt now, an hour after the graph file was saved: reload time %g ms", vrg_graph_reload_ms(g));
    /* the old graph is gone, so is version 1: an edit loop does not pile up versions */
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after a reload, want 1", mapped_versions("reloadme.so"));

    CHECK(build_reloadme(dir, 1, "999") == 0, "rebuild failed");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_reload(&g) != 0, "a plugin with ABI version 999 was accepted");
    const char *err = vrg_graph_reload_error(g);
    CHECK(err && strstr(err, "ABI version 999"), "no ABI error: %s", err ? err : "(none)");
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.07f) < 1e-3f, "the running version stopped: %g %g %g", px(&img, 1, 1, 0),
          px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after a refused rebuild, want 1", mapped_versions("reloadme.so"));
    /* more rebuilds: still one version, the state still carried (frames 8..) */
    for (int v = 0; v < 3; v++) {
        CHECK(build_reloadme(dir, 2 - v % 2, "VRG_ABI_VERSION") == 0, "rebuild failed");
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_source_changed(g) && vrg_graph_reload(&g) == 0, "rebuild %d was not reloaded", v);
    }
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &img) == 0, "frame failed");
    CHECK(px(&img, 1, 1, 1) == 1 && fabsf(px(&img, 1, 1, 2) - 0.11f) < 1e-3f, "after three more rebuilds: %g %g %g", px(&img, 1, 1, 0),
          px(&img, 1, 1, 1), px(&img, 1, 1, 2));
    free(img.pixels);
    CHECK(mapped_versions("reloadme.so") == 1, "%d versions of the plugin loaded after 5 rebuilds, want 1", mapped_versions("reloadme.so"));
    vrg_graph_destroy(g);
    fclose(diag);
    free(log);
    unsetenv("VOXRG_PLUGIN_PATH");
    char so[1100], src[1100];
    snprintf(so, sizeof so, "%s/reloadme.so", dir);
    snprintf(src, sizeof src, "%s/reloadme.c", dir);
    remove(so), remove(src), remove(shader), remove(path), rmdir(dir);
}

/* The harness's save_file fails the case, saying why, where the file
 * cannot be written: a folder that does not exist, a name that is a folder. */
static void test_save_file_errors(void)
{
    char dir[] = "/tmp/vrg_save_XXXXXX", missing[1100], folder[1100], inside[1100];
    if (!CHECK(mkdtemp(dir), "mkdtemp failed"))
        return;
    snprintf(missing, sizeof missing, "%s/no/such/folder.txt", dir);
    snprintf(folder, sizeof folder, "%s/folder", dir);
    snprintf(inside, sizeof inside, "%s/folder/file", dir);
    mkdir(folder, 0700);
    save_file(inside, "x"); /* a folder that is not empty cannot be renamed over */
    int before = failures;
    save_file(missing, "text\n");
    int missing_failed = failures - before;
    before = failures;
    save_file(folder, "text\n");
    int folder_failed = failures - before;
    failures = 0; /* the two failures asked for are not the case's */
    CHECK(missing_failed == 1, "save_file into a missing folder: %d failures counted, want 1", missing_failed);
    CHECK(folder_failed == 1, "save_file over a folder: %d failures counted, want 1", folder_failed);
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", folder);
    CHECK(access(tmp, F_OK) != 0, "save_file left %s behind", tmp);
    remove(inside), rmdir(folder), rmdir(dir);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"hot_reload_shader", test_hot_reload_shader, 1},
        {"hot_reload_shader_in_flight", test_hot_reload_shader_in_flight, 1},
        {"hot_reload_graph", test_hot_reload_graph, 1},
        {"hot_reload_keep_resource", test_hot_reload_keep_resource, 1},
        {"hot_reload_plugin", test_hot_reload_plugin, 1},
        {"hot_reload_many_plugins", test_hot_reload_many_plugins, 1},
        {"hot_reload_many_files", test_hot_reload_many_files, 1},
        {"hot_reload_state_too_big", test_hot_reload_state_too_big, 1},
        {"long_plugin_messages", test_long_plugin_messages, 1},
        {"param_choice_without_list", test_param_choice_without_list, 1},
        {"same_size_unknown_slot", test_same_size_unknown_slot, 1},
        {"save_file_errors", test_save_file_errors, 0},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
