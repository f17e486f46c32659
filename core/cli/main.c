/* voxrg: check, render and list plugins from the command line. Exit status:
 * 0 success, 1 a graph, plugin or GPU error (or a validation message under
 * --validate), 2 a usage error. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "bench.h"
#include "compare.h"
#include "run.h"
#include "util.h"
#include "png_writer.h"
#include "dump.h"
#include "inspect.h"
#include "new_pass.h"
#include "voxrg/voxrg.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "voxrg/camera_path.h"

#define MAX_SETS 64
#define MAX_DUMPS 32
#define VRG_STR_(x) #x
#define VRG_STR(x) VRG_STR_(x)
#define JSON_FRAMES_DEFAULT 4096 /* docs/graph-format.md */

static const char *usage_main =
    "usage: voxrg COMMAND [options]\n"
    "commands:\n"
    "  check GRAPH     validate a graph; print schedule, resources, barriers, memory\n"
    "  render GRAPH    render frames headless; write PNGs and timings\n"
    "  run GRAPH       render in a window with a fly camera and hot reload\n"
    "  plugins [NAME]  list plugins, or one plugin's slots and parameters\n"
    "  compare A.ini.. measure graphs against a converged reference: metrics, HTML report\n"
    "  bench           measure the figures in docs/benchmarks.md\n"
    "  new-pass NAME   write a pass to build outside the tree (docs/out-of-tree.md)\n"
    "'voxrg COMMAND --help' describes each; 'voxrg --version' prints the version.\n";

static const char *usage_new_pass =
    "usage: voxrg new-pass NAME [--dir DIR] [--shader]\n"
    "Writes a ready out-of-tree pass into DIR (default: NAME; created if missing):\n"
    "NAME.c (a tint of an input image, hazed toward the horizon with the scene's\n"
    "frame uniforms: camera and sky), NAME.comp, a CMakeLists.txt that builds it\n"
    "against an installed voxrg (find_package(voxrg CONFIG), voxrg_add_pass),\n"
    "README.md (what it does, slots, parameters, cost, debug outputs) and NAME.ini,\n"
    "a graph that runs it between shipped passes. NAME is a C identifier.\n"
    "--shader writes a one-file pass instead: NAME.comp, whose slots and parameters\n"
    "are declared in the shader (docs/plugin-abi.md, \"A pass in one file\"), README.md\n"
    "and NAME.ini, which finds NAME.comp beside it: no build step.\n"
    "Existing files are never overwritten. docs/out-of-tree.md.\n";

static const char *usage_check =
    "usage: voxrg check GRAPH [--dot FILE] [--set PASS.PARAM=VALUE]... [--size WxH]\n"
    "                         [--no-device] [--device NAME|INDEX] [--validate]\n"
    "Validates GRAPH and prints the schedule, culled passes, every resource (format,\n"
    "size, lifetime, memory placement), the barriers of each pass and the memory\n"
    "saved by aliasing. Errors name FILE:LINE. --dot writes a Graphviz file.\n"
    "--no-device checks without Vulkan (memory sizes then are estimates).\n";

static const char *usage_render =
    "usage: voxrg render GRAPH [--frames N] [--size WxH] [--out DIR] [--set PASS.PARAM=VALUE]...\n"
    "                          [--camera PATH] [--dump RES[,RES...]] [--dump-format exr|png] [--json FILE]\n"
    "                          [--validate] [--check-finite] [--watch] [--sequence] [--interval MS]\n"
    "                          [--json-frames N] [--gpu-timeout S] [--device NAME|INDEX]\n"
    "Renders N frames (default 1) headless and writes DIR/OUTPUT.png (default DIR: out),\n"
    "plus DIR/RES.exr for each dumped image: OpenEXR, halves and floats as stored (NaN\n"
    "and Inf kept), uint formats as uint channels, 8-bit ones as floats (--dump-format png:\n"
    "DIR/RES.png, 8-bit as the output), and DIR/RES.bin with DIR/RES.json (bytes, texel\n"
    "format, writer) for buffers. --json writes\n"
    "per-pass GPU timings: means over every frame, per-frame lists of the last N\n"
    "frames (--json-frames, default 4096). Every file is written whole or not at\n"
    "all, and DIR and the folder of --json are checked before the first frame.\n"
    "--camera plays a camera path (graphs/paths/*.path) at the\n"
    "graph's fps. --validate turns on the Khronos validation layer with\n"
    "synchronization validation; any message fails the run. --check-finite checks every\n"
    "float image each pass writes through its slots (not its internal images), on the\n"
    "device right after the pass: the first NaN or\n"
    "infinity fails the run (exit 1) naming the pass, resource, channel, pixel and frame,\n"
    "with the pass's inputs at that pixel (every image is then kept to the end of the\n"
    "frame, one frame in flight); --validate checks too, without the inputs. A graph that accumulates\n"
    "(the accumulate pass's samples_per_frame) gets that many graph frames per output\n"
    "frame, the camera held still: a converged reference per camera-path frame.\n"
    "--watch reloads saved shaders (and the files they #include), the graph file and\n"
    "rebuilt plugins between frames; a shader or graph with errors is reported with\n"
    "FILE:LINE, a refused plugin with its path, and the last good one keeps running.\n"
    "--sequence writes every frame as DIR/NAME-NNNNN.png (dumped images .exr; output and\n"
    "dumps, each file complete when it appears), --interval paces frames to at least MS\n"
    "apart, and\n"
    "--frames 0 renders until interrupted: with --watch, a script's edit loop.\n"
    "SIGINT or SIGTERM ends the run after the current frame, writing the files; a frame\n"
    "the GPU does not finish within a second of the signal fails instead (exit 1, naming\n"
    "the pass that was running). --gpu-timeout fails a frame whose GPU work takes more\n"
    "than S seconds, naming the pass (default: $VOXRG_GPU_TIMEOUT, else 120).\n";

static const char *usage_plugins =
    "usage: voxrg plugins [NAME]\n"
    "Lists the plugins on the search path (<exe>/plugins, <exe>/../lib/voxrg/plugins,\n"
    "then $VOXRG_PLUGIN_PATH; a graph adds its [graph] plugin_path after those),\n"
    "or NAME's file, slots and parameters. Files that do not load are reported,\n"
    "the rest listed, and the exit status is 1.\n";

typedef struct options {
    const char *graph, *dot, *out, *json, *device, *camera, *screenshot, *ab, *record, *show;
    const char *sets[MAX_SETS];
    int set_count;
    const char *dumps[MAX_DUMPS];
    int dump_count;
    char dump_buf[4096];
    uint32_t width, height, frames; /* frames 0: until interrupted */
    uint32_t window_w, window_h;    /* run: the window's size */
    double scale;                   /* run: render size / window size; 0: not given */
    int filter;                     /* run: the upscale, 0 nearest, 1 bilinear, -1 not given */
    uint32_t json_frames;           /* per-frame timings kept for --json: the last N */
    double interval_ms, gpu_timeout_s;
    int validate, no_device, help, watch, sequence;
    int dump_exr;                   /* --dump-format: 1 exr (default), 0 png */
    int check_finite;               /* render, run: NaN/Inf checks after each pass */
    int keep_images;                /* inspect: every image readable after the frame */
    const char *pixel;              /* inspect: --pixel X,Y as given */
    uint32_t pixel_x, pixel_y, frame;
} options;

static int usage_error(const char *usage, const char *fmt, const char *arg)
{
    fprintf(stderr, "error: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n%s", usage);
    return 2;
}


static int is_valued_option(const char *a)
{
    static const char *valued[] = {"--dot", "--out", "--json", "--device", "--set", "--size", "--frames", "--dump", "--camera",
                                   "--screenshot", "--ab", "--record", "--show", "--interval", "--json-frames", "--gpu-timeout",
                                   "--window", "--scale", "--filter", "--dump-format", "--pixel", "--frame"};
    for (size_t i = 0; i < sizeof valued / sizeof valued[0]; i++)
        if (!strcmp(a, valued[i]))
            return 1;
    return 0;
}

static const char *usage_run, *usage_inspect;

/* The window's options: given to another command they would do nothing. */
static int run_only(const char *a) { return !strcmp(a, "--window") || !strcmp(a, "--scale") || !strcmp(a, "--filter"); }
static int inspect_only(const char *a) { return !strcmp(a, "--pixel") || !strcmp(a, "--frame"); }

static int parse_options(int argc, char **argv, options *o, const char *usage)
{
    memset(o, 0, sizeof *o);
    o->filter = -1;
    o->frames = 1;
    o->json_frames = JSON_FRAMES_DEFAULT;
    o->out = "out";
    o->dump_exr = 1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            o->help = 1;
            takes = 0;
        } else if (!strcmp(a, "--validate"))
            o->validate = 1, takes = 0;
        else if (!strcmp(a, "--watch"))
            o->watch = 1, takes = 0;
        else if (!strcmp(a, "--sequence"))
            o->sequence = 1, takes = 0;
        else if (!strcmp(a, "--no-device"))
            o->no_device = 1, takes = 0;
        else if (!strcmp(a, "--check-finite")) {
            if (usage != usage_render && usage != usage_run)
                return usage_error(usage, "%s is an option of `voxrg render`, `run` and `compare`", a);
            o->check_finite = 1, takes = 0;
        }
        else if (a[0] == '-' && !is_valued_option(a))
            return usage_error(usage, "unknown option '%s'", a);
        else if (a[0] == '-' && !next)
            return usage_error(usage, "%s needs a value", a);
        else if (run_only(a) && usage != usage_run)
            return usage_error(usage, "%s is an option of `voxrg run` (the window)", a);
        else if (inspect_only(a) && usage != usage_inspect)
            return usage_error(usage, "%s is an option of `voxrg inspect`", a);
        else if (!strcmp(a, "--dump-format") && usage != usage_render)
            return usage_error(usage, "%s is an option of `voxrg render`", a);
        else if (!strcmp(a, "--dump-format")) {
            o->dump_exr = !strcmp(next, "exr") ? 1 : !strcmp(next, "png") ? 0 : -1;
            if (o->dump_exr < 0)
                return usage_error(usage, "--dump-format '%s': expected exr or png", next);
        } else if (!strcmp(a, "--pixel")) {
            if (vrg_cli_parse_pixel(next, &o->pixel_x, &o->pixel_y) != 0)
                return usage_error(usage, "--pixel '%s': expected X,Y, two whole numbers with a comma between, e.g. 160,90", next);
            o->pixel = next;
        } else if (!strcmp(a, "--frame")) {
            char *end;
            long n = strtol(next, &end, 10);
            if (*end || end == next || n < 0 || n > 1000000)
                return usage_error(usage, "--frame '%s': expected a frame number from 0 to 1000000", next);
            o->frame = (uint32_t)n;
        }
        else if (!strcmp(a, "--dot"))
            o->dot = next;
        else if (!strcmp(a, "--out"))
            o->out = next;
        else if (!strcmp(a, "--json"))
            o->json = next;
        else if (!strcmp(a, "--device"))
            o->device = next;
        else if (!strcmp(a, "--camera"))
            o->camera = next;
        else if (!strcmp(a, "--screenshot"))
            o->screenshot = next;
        else if (!strcmp(a, "--ab"))
            o->ab = next;
        else if (!strcmp(a, "--record"))
            o->record = next;
        else if (!strcmp(a, "--show"))
            o->show = next;
        else if (!strcmp(a, "--set")) {
            if (o->set_count == MAX_SETS)
                return usage_error(usage, "too many --set options%s", "");
            o->sets[o->set_count++] = next;
        } else if (!strcmp(a, "--size")) {
            if (vrg_cli_parse_size(next, &o->width, &o->height) != 0)
                return usage_error(usage, "--size '%s': expected WxH, " VRG_CLI_SIZE_RANGE ", e.g. 320x180", next);
        } else if (!strcmp(a, "--window")) {
            if (vrg_cli_parse_size(next, &o->window_w, &o->window_h) != 0)
                return usage_error(usage, "--window '%s': expected WxH, " VRG_CLI_SIZE_RANGE ", e.g. 1280x720", next);
        } else if (!strcmp(a, "--scale")) {
            char *end;
            o->scale = strtod(next, &end);
            if (*end || end == next || !(o->scale > 0 && o->scale <= 1))
                return usage_error(usage, "--scale '%s': expected a number in (0, 1], e.g. 0.5", next);
        } else if (!strcmp(a, "--filter")) {
            o->filter = !strcmp(next, "nearest") ? 0 : !strcmp(next, "bilinear") ? 1 : -2;
            if (o->filter == -2)
                return usage_error(usage, "--filter '%s': expected nearest or bilinear", next);
        } else if (!strcmp(a, "--frames")) {
            char *end;
            long n = strtol(next, &end, 10);
            if (*end || n < 0 || n > 10000000)
                return usage_error(usage, "--frames '%s': expected a positive integer (0: until interrupted)", next);
            o->frames = (uint32_t)n;
        } else if (!strcmp(a, "--json-frames")) {
            char *end;
            long n = strtol(next, &end, 10);
            if (*end || n < 1 || n > 1000000)
                return usage_error(usage, "--json-frames '%s': expected 1 to 1000000 frames", next);
            o->json_frames = (uint32_t)n;
        } else if (!strcmp(a, "--interval")) {
            char *end;
            double ms = strtod(next, &end);
            if (*end || !(ms >= 0 && ms <= 60000))
                return usage_error(usage, "--interval '%s': expected milliseconds in 0..60000", next);
            o->interval_ms = ms;
        } else if (!strcmp(a, "--gpu-timeout")) {
            if (vrg_cli_parse_seconds(next, &o->gpu_timeout_s) != 0)
                return usage_error(usage, "--gpu-timeout '%s': expected seconds > 0", next);
        } else if (!strcmp(a, "--dump")) {
            size_t used = strlen(o->dump_buf);
            if ((size_t)snprintf(o->dump_buf + used, sizeof o->dump_buf - used, "%s%s", used ? "," : "", next) >= sizeof o->dump_buf - used)
                return usage_error(usage, "--dump: the names given add up to more than %s characters", "4095");
        } else if (!o->graph)
            o->graph = a, takes = 0;
        else
            return usage_error(usage, "unexpected argument '%s'", a);
        i += takes;
    }
    for (char *tok = strtok(o->dump_buf, ","); tok; tok = strtok(NULL, ",")) {
        if (o->dump_count == MAX_DUMPS)
            return usage_error(usage, "--dump: more than %s resources", VRG_STR(MAX_DUMPS));
        o->dumps[o->dump_count++] = tok;
    }
    if (!o->help && !o->graph && usage != usage_run) /* run has a default graph */
        return usage_error(usage, "no graph file given%s", "");
    return 0;
}

static int load(const options *o, vrg_context **ctx, vrg_graph **g)
{
    *ctx = NULL;
    if (!o->no_device) {
        vrg_context_desc cd = {.validate = o->validate, .device = o->device, .gpu_timeout_s = o->gpu_timeout_s};
        if (vrg_context_create(&cd, ctx) != 0)
            return 1;
    }
    vrg_graph_desc gd = {
        .path = o->graph,
        .overrides = o->sets,
        .override_count = (uint32_t)o->set_count,
        .width = o->width,
        .height = o->height,
        .readback = o->dumps,
        .readback_count = (uint32_t)o->dump_count,
        .keep_images = o->keep_images,
        .check_finite = o->check_finite,
    };
    if (vrg_graph_load(*ctx, &gd, g) != 0) {
        fprintf(stderr, "%s: graph not loaded\n", o->graph);
        return 1;
    }
    return 0;
}

static int finish(vrg_context *ctx, vrg_graph *g, int rc)
{
    vrg_cli_exit_if_gpu_busy(ctx, rc);
    vrg_graph_destroy(g);
    if (ctx && vrg_context_validation_errors(ctx)) {
        fprintf(stderr, "error: %u validation message%s (see above)\n", vrg_context_validation_errors(ctx),
                vrg_context_validation_errors(ctx) == 1 ? "" : "s");
        rc = 1;
    }
    vrg_context_destroy(ctx);
    return rc;
}

static int cmd_check(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o, usage_check);
    if (rc || o.help)
        return rc ? rc : (fputs(usage_check, stdout), 0);
    vrg_context *ctx;
    vrg_graph *g = NULL;
    if (load(&o, &ctx, &g) != 0)
        return finish(ctx, g, 1);
    vrg_graph_report(g, stdout);
    printf("shaders%s:\n", ctx ? "" : " (compiled without a device)");
    if (vrg_graph_check_shaders(g, stdout) != 0) {
        fprintf(stderr, "error: shaders of %s do not compile or do not match their passes (see above)\n", o.graph);
        return finish(ctx, g, 1);
    }
    if (o.dot) {
        vrg_output *out = vrg_output_open(o.dot);
        if (!out)
            return finish(ctx, g, 1);
        vrg_graph_write_dot(g, vrg_output_stream(out));
        if (vrg_output_commit(out) != 0)
            return finish(ctx, g, 1);
    }
    return finish(ctx, g, 0);
}


/* DIR/NAME.exr for an image (exr 0: DIR/NAME.png, as the output always is),
 * DIR/NAME.bin and its NAME.json for a buffer; with frame >= 0
 * DIR/NAME-NNNNN.png (.exr), not announced, a PNG encoded by `writer` when
 * given (while the next frame renders). Every file appears complete
 * (vrg_output), so a script polling for a frame never reads half a file. */
static int write_resource(vrg_graph *g, const char *dir, const char *name, long frame, vrg_cli_png_writer *writer, int exr, uint64_t frames)
{
    char path[VRG_CLI_PATH];
    int rc;
    if (vrg_graph_resource_kind(g, name) == VRG_IMAGE) {
        const char *ext = exr ? "exr" : "png";
        if (frame < 0)
            snprintf(path, sizeof path, "%s/%s.%s", dir, name, ext);
        else
            snprintf(path, sizeof path, "%s/%s-%05ld.%s", dir, name, frame, ext);
        if (exr)
            rc = vrg_cli_dump_exr(g, name, path);
        else {
            vrg_image_data img;
            if (vrg_graph_read(g, name, &img) != 0)
                return -1;
            if (writer)
                return vrg_cli_png_writer_push(writer, path, &img);
            rc = vrg_write_png(path, &img);
            free(img.pixels);
        }
    } else {
        /* buffers: only at the end, announced by the writer */
        return frame >= 0 ? 0 : vrg_cli_dump_buffer(g, name, dir, frames);
    }
    if (rc == 0 && frame < 0)
        fprintf(stderr, "wrote %s\n", path);
    return rc;
}

/* Per-pass GPU ms of the last `keep` frames, a ring, so that an endless
 * run (--frames 0) holds bounded memory; the sums cover every frame, so
 * the means stay exact. np: the pass count when rendering began (a reload
 * under --watch may change it). */
typedef struct timings {
    double *ring, *sum;
    uint32_t np, keep, frames;
} timings;

static int timings_init(timings *t, uint32_t np, uint32_t keep)
{
    *t = (timings){.np = np, .keep = keep};
    t->ring = calloc((size_t)keep * (np ? np : 1), sizeof *t->ring);
    t->sum = calloc(np ? np : 1, sizeof *t->sum);
    if (t->ring && t->sum)
        return 0;
    fprintf(stderr, "error: out of memory for %u frames of timings (--json-frames)\n", keep);
    return -1;
}

/* the frame's timings; returns its whole-frame GPU ms */
static double timings_add(timings *t, vrg_graph *g)
{
    double *row = t->ring + (size_t)(t->frames % t->keep) * t->np, total = 0;
    for (uint32_t i = 0; i < t->np; i++) {
        row[i] = i < vrg_graph_pass_count(g) ? vrg_graph_pass_ms(g, i) : -1;
        t->sum[i] += row[i];
        if (row[i] > 0)
            total += row[i];
    }
    t->frames++;
    return total;
}

static double timing_at(const timings *t, uint32_t frame, uint32_t pass) { return t->ring[(size_t)(frame % t->keep) * t->np + pass]; }

static int write_json(const char *path, vrg_context *ctx, vrg_graph *g, const options *o, const timings *t, double wall_ms)
{
    vrg_output *out = vrg_output_open(path);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    uint32_t frames = t->frames, first = frames > t->keep ? frames - t->keep : 0;
    uint32_t w, h, np = vrg_graph_pass_count(g) < t->np ? vrg_graph_pass_count(g) : t->np;
    vrg_graph_size(g, &w, &h);
    vrg_memory_stats m = vrg_graph_memory(g);
    char g_esc[2048], d_esc[1024], p_esc[256];
    fprintf(f, "{\n  \"graph\": \"%s\",\n  \"device\": \"%s\",\n  \"width\": %u,\n  \"height\": %u,\n  \"frames\": %u,\n",
            vrg_cli_json_str(o->graph, g_esc, sizeof g_esc), vrg_cli_json_str(vrg_context_device(ctx)->name, d_esc, sizeof d_esc), w, h, frames);
    fprintf(f, "  \"frames_dropped\": %u,\n", first);
    fprintf(f, "  \"wall_ms_per_frame\": %.4f,\n", wall_ms / frames);
    fprintf(f, "  \"memory\": {\"transient_naive_bytes\": %llu, \"transient_aliased_bytes\": %llu, \"history_bytes\": %llu},\n",
            (unsigned long long)m.naive_bytes, (unsigned long long)m.aliased_bytes, (unsigned long long)m.history_bytes);
    fprintf(f, "  \"passes\": [");
    int comma = 0;
    for (uint32_t i = 0; i < np; i++) {
        if (vrg_graph_pass_ms(g, i) < 0 && timing_at(t, first, i) < 0)
            continue; /* culled or not timed */
        fprintf(f, "%s\n    {\"name\": \"%s\", \"gpu_ms\": [", comma ? "," : "", vrg_cli_json_str(vrg_graph_pass_name(g, i), p_esc, sizeof p_esc));
        for (uint32_t k = first; k < frames; k++)
            fprintf(f, "%s%.4f", k > first ? ", " : "", timing_at(t, k, i));
        fprintf(f, "], \"mean_gpu_ms\": %.4f", t->sum[i] / frames);
        double v;
        const char *name;
        for (uint32_t k = 0; (name = vrg_graph_stat_at(g, i, k, &v)); k++)
            fprintf(f, ", \"%s\": %.6g", name, v);
        fprintf(f, "}");
        comma = 1;
    }
    fprintf(f, "\n  ]\n}\n");
    return vrg_output_commit(out);
}

static volatile sig_atomic_t interrupted;
static void on_interrupt(int sig)
{
    (void)sig;
    interrupted = 1;
    vrg_interrupt(); /* a frame the GPU does not finish soon fails */
}

/* Sleeps until `start_ms` + `interval_ms` (frame pacing for --interval). */
static void pace(double start_ms, double interval_ms)
{
    double left = start_ms + interval_ms - vrg_cli_now_ms();
    if (left > 0) {
        struct timespec ts = {(time_t)(left / 1e3), (long)(fmod(left, 1e3) * 1e6)};
        nanosleep(&ts, NULL);
    }
}

static int cmd_render(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o, usage_render);
    if (rc || o.help)
        return rc ? rc : (fputs(usage_render, stdout), 0);
    if (o.no_device)
        return usage_error(usage_render, "render needs a device%s", "");
    vrg_context *ctx;
    vrg_graph *g = NULL;
    if (load(&o, &ctx, &g) != 0)
        return finish(ctx, g, 1);
    vrg_camera_path path = {0};
    if (o.camera && vrg_camera_path_load(o.camera, &path, stderr) != 0)
        return finish(ctx, g, 1);
    /* every folder written to, before the first frame rather than after the last */
    if (vrg_cli_out_dir(o.out) != 0 || (o.json && vrg_cli_out_file_dir(o.json) != 0)) {
        vrg_camera_path_free(&path);
        return finish(ctx, g, 1);
    }
    vrg_camera camera = *vrg_graph_camera(g);
    timings times;
    if (timings_init(&times, vrg_graph_pass_count(g), o.frames && o.frames < o.json_frames ? o.frames : o.json_frames) != 0) {
        free(times.ring), free(times.sum);
        vrg_camera_path_free(&path);
        return finish(ctx, g, 1);
    }
    double start = vrg_cli_now_ms();
    int isatty_err = isatty(2);
    /* two frames queued: one encoding, one waiting, while a third renders */
    vrg_cli_png_writer *writer = o.sequence ? vrg_cli_png_writer_start(2) : NULL;
    if ((o.sequence && !writer) || (o.watch && vrg_graph_watch(g, 1) != 0)) {
        vrg_cli_png_writer_finish(writer);
        free(times.ring), free(times.sum);
        vrg_camera_path_free(&path);
        return finish(ctx, g, 1);
    }
    /* Ctrl-C or a script's kill: finish the frame (if the GPU does so within
     * VRG_INTERRUPT_GRACE_S), write the files */
    interrupted = 0;
    struct sigaction sa = {.sa_handler = on_interrupt}, old_int, old_term;
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    uint32_t sub = vrg_graph_subframes(g), done = 0;
    double reloaded = -1;
    for (uint32_t k = 0; (o.frames == 0 || k < o.frames) && rc == 0 && !interrupted; k++) {
        double frame_start = vrg_cli_now_ms();
        /* a saved graph file or rebuilt plugin: load it beside the running
         * graph, swap on success, before this frame (no frame of the old
         * graph after the save); errors are printed, the running graph stays */
        if (o.watch && vrg_graph_poll_changes(g) && vrg_graph_reload(&g) == 0)
            sub = vrg_graph_subframes(g);
        if (path.count) {
            vrg_camera_path_eval(&path, (float)(k * vrg_graph_frame_seconds(g)), &camera);
            vrg_graph_set_camera(g, &camera);
        }
        /* a graph that accumulates (vrg_pass_set_subframes) gets its frames
         * per output frame with the camera held */
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            if (vrg_graph_frame(g) != 0) {
                fprintf(stderr, "error: frame %u failed\n", k);
                rc = 1;
            }
        /* the frame's readbacks and GPU timings: it must end first; the
         * writer encodes its files while the next frame runs */
        if (rc == 0 && vrg_graph_wait(g) != 0) {
            fprintf(stderr, "error: frame %u failed\n", k);
            rc = 1;
        }
        if (rc)
            break;
        done = k + 1;
        if (o.sequence) {
            rc |= write_resource(g, o.out, vrg_graph_output(g), k, writer, 0, k + 1) != 0;
            for (int i = 0; rc == 0 && i < o.dump_count; i++)
                rc |= write_resource(g, o.out, o.dumps[i], k, writer, o.dump_exr, k + 1) != 0;
        }
        if (o.watch && vrg_graph_reload_ms(g) != reloaded) {
            reloaded = vrg_graph_reload_ms(g);
            fprintf(stderr, "\nframe %u: reloaded, %.0f ms from save to frame\n", k, reloaded);
        }
        double total = timings_add(&times, g);
        if (isatty_err || k + 1 == o.frames) {
            char of[16] = "";
            if (o.frames)
                snprintf(of, sizeof of, "/%u", o.frames);
            fprintf(stderr, "\rframe %u%s  gpu %.2f ms  wall %.1f ms/frame%s", k + 1, of, total, (vrg_cli_now_ms() - start) / (k + 1),
                    k + 1 == o.frames ? "\n" : "");
        }
        pace(frame_start, o.interval_ms);
    }
    rc |= vrg_cli_png_writer_finish(writer) != 0; /* every queued frame is on disk */
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (interrupted)
        fprintf(stderr, "\ninterrupted after %u frames\n", done);
    double wall = vrg_cli_now_ms() - start;
    vrg_camera_path_free(&path);
    if (rc == 0 && done == 0) {
        fprintf(stderr, "error: no frame was rendered\n");
        rc = 1;
    }
    if (rc == 0)
        rc |= write_resource(g, o.out, vrg_graph_output(g), -1, NULL, 0, done) != 0;
    for (int i = 0; rc == 0 && i < o.dump_count; i++)
        rc |= write_resource(g, o.out, o.dumps[i], -1, NULL, o.dump_exr, done) != 0;
    if (rc == 0 && o.json)
        rc |= write_json(o.json, ctx, g, &o, &times, wall) != 0;
    free(times.ring), free(times.sum);
    return finish(ctx, g, rc);
}

static const char *usage_inspect =
    "usage: voxrg inspect GRAPH --pixel X,Y [--frame N] [--size WxH] [--camera PATH] [--json FILE]\n"
    "                           [--set PASS.PARAM=VALUE]... [--validate] [--device NAME|INDEX]\n"
    "Renders frames 0 to N (default 0) headless, as render does (--camera: the path's\n"
    "camera at each frame), and prints pixel X,Y of every image resource the graph\n"
    "computes after frame N, in schedule order: the pass that writes it, the resource,\n"
    "its format, the texel read (X,Y scaled to the resource's size) and every channel's\n"
    "stored value exactly (halves and floats to 17 significant digits, nan and inf as\n"
    "such, uint as integers), each history resource followed by its @prev copy (what\n"
    "frame N read). An optional output no pass reads (gbuffer's depth in most graphs)\n"
    "is not computed, so not listed: render --dump NAME computes and writes it. Where\n"
    "the graph computes a motion image (the gbuffer's motion, in pixels), the pixel of\n"
    "the previous frame its vector points to. --json writes the same as JSON (values,\n"
    "and each channel's stored bits). X,Y outside the graph's size is an error.\n";

static int cmd_inspect(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o, usage_inspect);
    if (rc || o.help)
        return rc ? rc : (fputs(usage_inspect, stdout), 0);
    if (!o.pixel)
        return usage_error(usage_inspect, "--pixel X,Y is missing%s", "");
    /* render's options would do nothing here */
    static const char *render_only[] = {"--dump", "--frames", "--out", "--watch", "--sequence", "--interval", "--json-frames", "--dot", "--no-device"};
    for (int i = 0; i < argc; i++)
        for (size_t k = 0; k < sizeof render_only / sizeof render_only[0]; k++)
            if (!strcmp(argv[i], render_only[k]))
                return usage_error(usage_inspect, "%s is not an option of `voxrg inspect` (--frame N picks the frame)", argv[i]);
    o.keep_images = 1; /* every image stays readable to the end of the frame */
    vrg_context *ctx;
    vrg_graph *g = NULL;
    if (load(&o, &ctx, &g) != 0)
        return finish(ctx, g, 1);
    uint32_t w, h;
    vrg_graph_size(g, &w, &h);
    if (o.pixel_x >= w || o.pixel_y >= h) {
        fprintf(stderr, "error: --pixel %s is outside the graph's %ux%u (X from 0 to %u, Y from 0 to %u)\n", o.pixel, w, h, w - 1, h - 1);
        return finish(ctx, g, 2);
    }
    vrg_camera_path path = {0};
    if ((o.camera && vrg_camera_path_load(o.camera, &path, stderr) != 0) || (o.json && vrg_cli_out_file_dir(o.json) != 0)) {
        vrg_camera_path_free(&path);
        return finish(ctx, g, 1);
    }
    vrg_camera camera = *vrg_graph_camera(g);
    uint32_t sub = vrg_graph_subframes(g);
    for (uint32_t k = 0; k <= o.frame && rc == 0; k++) {
        if (path.count) {
            vrg_camera_path_eval(&path, (float)(k * vrg_graph_frame_seconds(g)), &camera);
            vrg_graph_set_camera(g, &camera);
        }
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            if (vrg_graph_frame(g) != 0) {
                fprintf(stderr, "error: frame %u failed\n", k);
                rc = 1;
            }
    }
    vrg_camera_path_free(&path);
    if (rc == 0 && vrg_graph_wait(g) != 0)
        rc = 1;
    if (rc == 0 && vrg_cli_inspect_report(g, o.graph, o.pixel_x, o.pixel_y, o.frame, stdout, o.json) != 0)
        rc = 1;
    return finish(ctx, g, rc);
}

static const char *usage_run =
    "usage: voxrg run [GRAPH] [--ab GRAPH_B] [--window WxH] [--scale S | --size WxH] [--filter nearest|bilinear]\n"
    "                       [--frames N] [--set PASS.PARAM=VALUE]... [--out DIR]\n"
    "                       [--camera PATH] [--record PATH] [--show RESOURCE] [--screenshot FILE] [--validate]\n"
    "                       [--check-finite] [--gpu-timeout S] [--device NAME|INDEX]\n"
    "Renders GRAPH (default: the shipped graphs/interactive.ini) in a window until it is\n"
    "closed (or for N frames), presenting its output.\n"
    "The window is --window WxH (default 1280x720, at most the screen; with --size\n"
    "alone, that size). The graph renders at the window's size times --scale S\n"
    "(0 < S <= 1; default 0.5, 1 with --size) or at a fixed --size WxH, and is\n"
    "upscaled to the window (--filter, default bilinear; N toggles); resizing the\n"
    "window resizes the graph at the same scale. On a CPU device (lavapipe)\n"
    "without --scale or --size the scale starts at 0.25 and adapts to keep near\n"
    "15 fps: halved below 15 fps, doubled at 60 or more, within 1/16..1 (said in\n"
    "the terminal, and as 'scale S (auto, CPU)' in the overlay).\n"
    "W/A/S/D move, Space up, Shift down, hold the right mouse button to look around,\n"
    "scroll or +/- change the speed, T starts or stops the day cycle, [ and ] step the\n"
    "time of day, F or Pause freezes the frame (G renders one more), H hides the\n"
    "overlay, F1 shows per-pass times and\n"
    "the keys, P or F12 saves DIR/screenshot-NNN.png (--out DIR, default out, created\n"
    "when needed; the next free number), Esc quits.\n"
    "M or F2 opens the parameter panel: Up/Down (or a click) select a parameter,\n"
    "PgUp/PgDn jump to the previous/next pass, / filters the rows by what is typed\n"
    "(PASS.PARAM, any case; Enter keeps the filter, Esc clears it), Left/Right (or\n"
    "a drag) step it by a twentieth of its range (Shift: a tenth of that); it\n"
    "applies at once (those marked 'reload' on save); a value set back to what it\n"
    "was is no change. Ctrl+S writes the changed values into the graph file (only\n"
    "their text changes; its mode stays; a read-only file is refused), which then\n"
    "reloads; Ctrl+Shift+S writes them to a new file, GRAPH-edited.ini beside it or\n"
    "a name typed (Enter writes, Esc cancels); with --ab, B switches the side the\n"
    "panel edits. A block edit journal (GRAPH.ini.edits) found at start-up is\n"
    "replayed and said so.\n"
    "--ab renders GRAPH_B\n"
    "every frame with the same camera and shows it right of a divider (drag it with the\n"
    "left mouse button) at A's size; both need the same [scene], [graph] seed and fps.\n"
    "--record writes the flight as a\n"
    "camera path (graphs/paths/*.path format). Tab / Shift+Tab or 1-9 show the graph's\n"
    "other images (0: the output as it is; with --ab, B's image of the same name too)\n"
    "in the view they read best in (colour; normals by -1..1; positions and data by\n"
    "each channel's range; depth, history length, moments and variance (alpha) in\n"
    "false colour; motion as direction; one channel and the temporal passes' debug\n"
    "outputs as grey); --show NAME starts with one, and reads it back, so that a\n"
    "pass's optional debug output nothing else reads is computed and shown.\n"
    "The viewer: V / Shift+V the view (colour, range, false colour, direction),\n"
    "C / Shift+C the channel (rgb, r, g, b, a, luma), R holds the range (again:\n"
    "auto, each frame's least and greatest), , and . exposure by half a stop (the\n"
    "range's top), Shift+, and Shift+. its low end by a tenth; a scale bar says what\n"
    "the colours mean (NaN magenta, Inf cyan) and the overlay prints the value under\n"
    "the cursor. I: the inspector, every image's value at the pixel under the cursor\n"
    "in schedule order (a left click pins the pixel, another follows the cursor\n"
    "again).\n"
    "Saved shaders, the graph file and rebuilt plugins reload while it runs; errors\n"
    "are printed with FILE:LINE and the last good version keeps running. --camera\n"
    "plays a camera path instead of the fly camera; --screenshot writes the last of\n"
    "N frames to FILE. --check-finite stops at the first NaN or infinity a pass writes\n"
    "(as render's). Without a display, use `voxrg render`.\n";

static int cmd_run(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o, usage_run);
    if (rc || o.help)
        return rc ? rc : (fputs(usage_run, stdout), 0);
    char default_graph[1100];
    if (!o.graph) { /* the shipped graph made to be interactive on a CPU */
        snprintf(default_graph, sizeof default_graph, "%s/graphs/interactive.ini", vrg_data_dir());
        o.graph = default_graph;
        fprintf(stderr, "voxrg: no graph given: running %s\n", default_graph);
    }
    int frames_given = 0;
    for (int i = 0; i < argc; i++)
        frames_given |= !strcmp(argv[i], "--frames");
    if (o.screenshot && !frames_given)
        return usage_error(usage_run, "--screenshot needs --frames N (the frame it is taken after)%s", "");
    if (o.scale > 0 && o.width)
        return usage_error(usage_run, "--scale and --size both set the render size: give one%s", "");
    /* --size alone: a window that shows the render pixel for pixel */
    vrg_run_options r = {.graph = o.graph, .device = o.device, .camera = o.camera, .screenshot = o.screenshot, .ab = o.ab, .record = o.record,
                         .show = o.show, .out = o.out,
                         .sets = o.sets,
                         .set_count = (uint32_t)o.set_count,
                         .window_w = o.window_w ? o.window_w : o.width, .window_h = o.window_h ? o.window_h : o.height,
                         .width = o.width, .height = o.height,
                         .scale = o.scale > 0 ? o.scale : o.width ? 1.0 : 0.5, .scale_auto = !(o.scale > 0) && !o.width, .filter = o.filter < 0 ? 1 : o.filter,
                         .frames = frames_given ? o.frames : 0, .validate = o.validate, .check_finite = o.check_finite,
                         .gpu_timeout_s = o.gpu_timeout_s};
    return vrg_cli_run(&r);
}

static const char *kind_name(vrg_resource_kind k) { return k == VRG_IMAGE ? "image" : k == VRG_BUFFER ? "buffer" : "accel"; }

static int cmd_plugins(int argc, char **argv)
{
    if (argc > 0 && (!strcmp(argv[0], "--help") || !strcmp(argv[0], "-h"))) {
        fputs(usage_plugins, stdout);
        return 0;
    }
    const char *want = argc > 0 ? argv[0] : NULL;
    const vrg_plugin_desc *list[256];
    const char *paths[256];
    int n, failed = 0;
    if (want) {
        /* one plugin: found as a graph finds it, and if it does not load, why */
        if (vrg_find_plugin(want, stderr, &list[0], &paths[0]) != 0)
            return 1;
        n = 1;
    } else if ((n = vrg_list_plugins(list, paths, 256, stderr, &failed)) > 256) {
        fprintf(stderr, "error: %d plugins on the search path; this listing shows at most 256\n", n);
        return 1;
    }
    int found = 0;
    for (int i = 0; i < n; i++) {
        const vrg_plugin_desc *d = list[i];
        if (!want) {
            printf("%-18s %-5s %s\n", d->name, d->kind == VRG_PLUGIN_SCENE ? "scene" : "pass", d->help ? d->help : "");
            continue;
        }
        if (strcmp(d->name, want) != 0)
            continue;
        found = 1;
        size_t plen = strlen(paths[i]);
        int one_file = plen > 5 && strcmp(paths[i] + plen - 5, ".comp") == 0; /* slots and parameters from the shader */
        printf("%s (%s, ABI %u)\n  %s\n  file: %s\n", d->name, one_file ? "shader-only pass" : d->kind == VRG_PLUGIN_SCENE ? "scene plugin" : "pass plugin",
               d->abi_version, d->help ? d->help : "", paths[i]);
        printf("slots:\n");
        for (uint32_t s = 0; s < d->slot_count; s++) {
            const vrg_slot_desc *sd = &d->slots[s];
            char size[64] = "";
            if (sd->kind == VRG_ACCEL)
                snprintf(size, sizeof size, "instances set by the plugin");
            else if (sd->kind == VRG_BUFFER)
                snprintf(size, sizeof size, "%llu bytes", (unsigned long long)sd->size);
            else if (sd->width)
                snprintf(size, sizeof size, "%ux%u", sd->width, sd->height);
            else if (sd->scale > 0 || sd->dir == VRG_OUT)
                snprintf(size, sizeof size, "scale %g", sd->scale > 0 ? sd->scale : 1.0);
            else
                snprintf(size, sizeof size, "any size");
            char slot[80];
            snprintf(slot, sizeof slot, "%s.%s", sd->dir == VRG_IN ? "in" : "out", sd->name);
            printf("  %-18s %-6s %-10s %-18s %-14s%s%s  %s\n", slot, kind_name(sd->kind),
                   sd->kind == VRG_IMAGE ? (sd->format ? vrg_format_label(sd->format) : "any") : "-", vrg_access_label(sd->access), size,
                   sd->flags & VRG_SLOT_OPTIONAL ? " optional" : "", sd->flags & VRG_SLOT_PERSISTENT ? " persistent" : "", sd->help ? sd->help : "");
        }
        printf("parameters:%s\n", d->param_count ? "" : " none");
        for (uint32_t p = 0; p < d->param_count; p++) {
            const vrg_param_desc *pd = &d->params[p];
            const char *t = pd->type == VRG_PARAM_INT ? "int" : pd->type == VRG_PARAM_BOOL ? "bool" : pd->type == VRG_PARAM_STRING ? "text" : "float";
            char numbers[64] = "", def[64];
            if (pd->type == VRG_PARAM_STRING)
                snprintf(def, sizeof def, "'%s'", pd->default_string ? pd->default_string : "");
            else
                snprintf(def, sizeof def, "%g", pd->default_value);
            const char *choices = d->param_choices ? d->param_choices[p] : NULL, *range = numbers;
            /* the names it takes, a|b|c, each one whole however many */
            char *choice_list = choices ? strdup(choices) : NULL;
            for (char *c = choice_list; c && *c; c++)
                *c = *c == ',' ? '|' : *c;
            if (choices)
                range = choice_list ? choice_list : choices; /* no memory: as the plugin wrote them */
            else if (pd->flags & VRG_PARAM_REPEATABLE)
                snprintf(numbers, sizeof numbers, "(repeatable)");
            else if (pd->type != VRG_PARAM_STRING && (pd->min != 0 || pd->max != 0))
                snprintf(numbers, sizeof numbers, "[%g, %g]", pd->min, pd->max);
            printf("  %-16s %-5s default %-8s %-16s %s\n", pd->name, t, def, range, pd->help ? pd->help : "");
            free(choice_list);
        }
    }
    if (failed) { /* the rest is listed; the status says not all of it loaded */
        fprintf(stderr, "error: %d plugin file%s on the search path did not load (reported above)\n", failed, failed == 1 ? "" : "s");
        return 1;
    }
    return want && !found;
}

static const char *usage_bench =
    "usage: voxrg bench [--suite all|rays|graph|memory|terrain|reload|frame] [--runs N] [--size WxH]\n"
    "                   [--radius N] [--graphs A.ini,B.ini] [--json FILE] [--smoke] [--device NAME|INDEX]\n"
    "Measures each figure N times (default 5) after warm-up and prints the median,\n"
    "min, max and p99 with the device and thread counts (LP_NUM_THREADS sets\n"
    "lavapipe's). rays: GPU ms and Mrays/s of primary, sun-shadow, AO and indirect rays\n"
    "on the default terrain, each traversal backend, at --size (default 640x360).\n"
    "graph: the runtime's CPU time per frame of thesis.ini (recording, barriers,\n"
    "submission) against the same barriers and dispatches recorded directly with\n"
    "Vulkan, and graph compile time. memory: transient memory without and with\n"
    "aliasing and history memory of every shipped graph at 640x360 and 1920x1080.\n"
    "terrain: radius-13 world generation with 1 and 2 threads, chunks/s per thread,\n"
    "streaming time per frame along graphs/paths/walk.path. reload: save-to-frame\n"
    "latency of a shader, a ray pass's shader, a graph parameter, a plugin rebuild.\n"
    "frame: whole-frame GPU and wall ms of every shipped graph along walk.path at\n"
    "--size, with each pass's GPU ms. --smoke runs every figure once on tiny inputs\n"
    "(for CI: checks the suites run, not figures to quote). --radius sets the terrain\n"
    "radius of rays and terrain (default 13); --graphs limits memory and frame to some\n"
    "shipped graphs. docs/benchmarks.md.\n";

static int cmd_bench(int argc, char **argv)
{
    vrg_bench_opts o = {.suite = "all", .runs = 5, .width = 640, .height = 360, .radius = 13};
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage_bench, stdout);
            return 0;
        }
        if (!strcmp(argv[i], "--smoke")) {
            o.smoke = 1;
            continue;
        }
        if (i + 1 >= argc)
            return usage_error(usage_bench, "unknown option or missing value '%s'", argv[i]);
        if (!strcmp(argv[i], "--suite"))
            o.suite = argv[++i];
        else if (!strcmp(argv[i], "--json"))
            o.json = argv[++i];
        else if (!strcmp(argv[i], "--device"))
            o.device = argv[++i];
        else if (!strcmp(argv[i], "--graphs"))
            o.graphs = argv[++i];
        else if (!strcmp(argv[i], "--radius")) {
            o.radius = atoi(argv[++i]);
            if (o.radius < 1 || o.radius > 32)
                return usage_error(usage_bench, "--radius '%s': 1 to 32", argv[i]);
        } else if (!strcmp(argv[i], "--size")) {
            if (vrg_cli_parse_size(argv[++i], &o.width, &o.height) != 0)
                return usage_error(usage_bench, "--size '%s': expected WxH, " VRG_CLI_SIZE_RANGE ", e.g. 640x360", argv[i]);
        } else if (!strcmp(argv[i], "--runs")) {
            o.runs = atoi(argv[++i]);
            if (o.runs < 1 || o.runs > 64)
                return usage_error(usage_bench, "--runs '%s': 1 to 64", argv[i]);
        } else
            return usage_error(usage_bench, "unknown option '%s'", argv[i]);
    }
    if (o.smoke) {
        o.runs = 1;
        o.width = 64, o.height = 36;
    }
    return vrg_cli_bench(&o);
}

static int cmd_new_pass(int argc, char **argv)
{
    const char *name = NULL, *dir = NULL;
    int shader = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage_new_pass, stdout);
            return 0;
        } else if (!strcmp(argv[i], "--shader")) {
            shader = 1;
        } else if (!strcmp(argv[i], "--dir")) {
            if (i + 1 >= argc)
                return usage_error(usage_new_pass, "%s needs a folder", "--dir");
            dir = argv[++i];
        } else if (argv[i][0] == '-')
            return usage_error(usage_new_pass, "unknown option '%s'", argv[i]);
        else if (name)
            return usage_error(usage_new_pass, "unexpected argument '%s' (one NAME only)", argv[i]);
        else
            name = argv[i];
    }
    if (!name)
        return usage_error(usage_new_pass, "%s missing", "NAME");
    return vrg_cli_new_pass(name, dir ? dir : name, shader);
}

int main(int argc, char **argv)
{
    /* a write past the file size limit (ulimit -f) is then an error the
     * writer reports (EFBIG), not the end of the process */
    signal(SIGXFSZ, SIG_IGN);
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        fputs(usage_main, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("voxrg %s\n", vrg_version());
        return 0;
    }
    if (!strcmp(argv[1], "new-pass"))
        return cmd_new_pass(argc - 2, argv + 2);
    if (!strcmp(argv[1], "check"))
        return cmd_check(argc - 2, argv + 2);
    if (!strcmp(argv[1], "render"))
        return cmd_render(argc - 2, argv + 2);
    if (!strcmp(argv[1], "run"))
        return cmd_run(argc - 2, argv + 2);
    if (!strcmp(argv[1], "inspect"))
        return cmd_inspect(argc - 2, argv + 2);
    if (!strcmp(argv[1], "plugins"))
        return cmd_plugins(argc - 2, argv + 2);
    if (!strcmp(argv[1], "bench"))
        return cmd_bench(argc - 2, argv + 2);
    if (!strcmp(argv[1], "compare"))
        return vrg_cli_compare(argc - 2, argv + 2);
    fprintf(stderr, "error: unknown command '%s'\n%s", argv[1], usage_main);
    return 2;
}
