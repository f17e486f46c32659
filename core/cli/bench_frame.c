/* voxrg bench --suite frame: whole-frame GPU and wall time of every shipped
 * graph along graphs/paths/walk.path at --size (default 640x360), with
 * each pass's GPU time; for graphs with the four ray passes, the whole
 * frame over their sum (the goal: <= 1.15). Then the same frames
 * with a PNG written per frame as `render --sequence` does (the writer
 * thread encoding frame k while frame k + 1 renders): steady-state wall
 * over GPU time (the goal: <= 1.1). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "util.h"
#include "png_writer.h"
#include <unistd.h>
#include "voxrg/camera.h"
#include "voxrg/camera_path.h"
#include "voxrg/png.h"

enum { MAX_PASSES = 64 };

static int measure(vrg_context *ctx, const vrg_bench_opts *o, const char *name, const vrg_camera_path *path, vrg_bench_figure *out, int *count)
{
    vrg_graph *g = vrg_bench_load_shipped(ctx, name, o->width, o->height, o->smoke);
    if (!g)
        return -1;
    uint32_t np = vrg_graph_pass_count(g) < MAX_PASSES ? vrg_graph_pass_count(g) : MAX_PASSES;
    int frames = o->smoke ? 1 : (o->runs > 10 ? o->runs : 10), n = *count;
    double *gpu = calloc((size_t)frames, sizeof *gpu), *wall = calloc((size_t)frames, sizeof *wall);
    double *ratio = calloc((size_t)frames, sizeof *ratio), *pass = calloc((size_t)frames * np, sizeof *pass);
    static const char *rays[] = {"gbuffer", "shadow", "ao", "indirect"};
    int ray_passes = 0;
    for (uint32_t i = 0; i < np; i++)
        for (int k = 0; k < 4; k++)
            ray_passes += !strcmp(vrg_graph_pass_name(g, i), rays[k]);
    vrg_camera cam = *vrg_graph_camera(g);
    int rc = 0, warm = o->smoke ? 1 : 3; /* the JIT, the world's first upload */
    for (int f = -warm; f < frames && rc == 0; f++) {
        vrg_camera_path_eval(path, (float)((f < 0 ? 0 : f) * vrg_graph_frame_seconds(g)), &cam);
        vrg_graph_set_camera(g, &cam);
        double t0 = vrg_cli_now_ms();
        rc = vrg_graph_frame(g);
        rc = rc ? rc : vrg_graph_wait(g); /* the frame's timings; the wait counts as wall */
        if (f < 0 || rc)
            continue;
        wall[f] = vrg_cli_now_ms() - t0;
        double sum = 0, ray_sum = 0;
        for (uint32_t i = 0; i < np; i++) {
            double ms = vrg_graph_pass_ms(g, i);
            pass[(size_t)f * np + i] = ms;
            sum += ms > 0 ? ms : 0;
            for (int k = 0; k < 4; k++)
                ray_sum += !strcmp(vrg_graph_pass_name(g, i), rays[k]) && ms > 0 ? ms : 0;
        }
        gpu[f] = sum;
        ratio[f] = ray_sum > 0 ? sum / ray_sum : 0;
    }
    if (rc == 0)
        rc = vrg_bench_room(n, 3 + (int)np);
    if (rc == 0) {
        char fig[160];
        snprintf(fig, sizeof fig, "frame: %s whole frame GPU, %ux%u, walk.path", name, o->width, o->height);
        out[n++] = vrg_bench_summarise(fig, "ms", gpu, frames);
        snprintf(fig, sizeof fig, "frame: %s whole frame wall (record, submit, wait, readback)", name);
        out[n++] = vrg_bench_summarise(fig, "ms", wall, frames);
        if (ray_passes == 4) {
            snprintf(fig, sizeof fig, "frame: %s whole frame / its four ray passes (GPU)", name);
            out[n++] = vrg_bench_summarise(fig, "x", ratio, frames);
        }
        double *v = malloc(sizeof(double) * (size_t)frames);
        for (uint32_t i = 0; i < np; i++) {
            if (pass[i] < 0) /* culled, or no timestamps */
                continue;
            for (int f = 0; f < frames; f++)
                v[f] = pass[(size_t)f * np + i];
            snprintf(fig, sizeof fig, "frame: %s pass %s GPU", name, vrg_graph_pass_name(g, i));
            out[n++] = vrg_bench_summarise(fig, "ms", v, frames);
        }
        free(v);
    }
    free(gpu), free(wall), free(ratio), free(pass);
    vrg_graph_destroy(g);
    *count = n;
    return rc;
}

/* What `render --sequence` does per frame: camera, frame, wait, read the
 * output, queue its PNG (threaded) or write it before the next frame (as
 * render did before the writer thread: the figure to compare with).
 * Steady state: the first `warm` of `frames` are not counted; the wall runs
 * to the last file written. */
static int measure_output(vrg_context *ctx, const vrg_bench_opts *o, const char *name, const vrg_camera_path *path, int threaded,
                          vrg_bench_figure *out, int *count)
{
    char file[VRG_CLI_PATH];
    const char *tmp = getenv("TMPDIR");
    char where[VRG_CLI_PATH];
    snprintf(where, sizeof where, "%s/voxrg-bench-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(where)) {
        fprintf(stderr, "error: cannot create a folder in %s for the PNG files\n", tmp && *tmp ? tmp : "/tmp");
        return -1;
    }
    vrg_graph *g = vrg_bench_load_shipped(ctx, name, o->width, o->height, o->smoke);
    vrg_cli_png_writer *writer = g && threaded ? vrg_cli_png_writer_start(2) : NULL;
    int frames = o->smoke ? 2 : 16, warm = o->smoke ? 1 : 4, rc = g && (writer || !threaded) ? 0 : -1, n = *count;
    double gpu = 0, start = 0;
    vrg_camera cam = g ? *vrg_graph_camera(g) : (vrg_camera){0};
    for (int f = 0; f < frames && rc == 0; f++) {
        if (f == warm)
            start = vrg_cli_now_ms();
        vrg_camera_path_eval(path, (float)(f * vrg_graph_frame_seconds(g)), &cam);
        vrg_graph_set_camera(g, &cam);
        vrg_image_data img;
        rc = vrg_graph_frame(g) || vrg_graph_wait(g) || vrg_graph_read(g, vrg_graph_output(g), &img);
        if (rc)
            break;
        snprintf(file, sizeof file, "%s/%s-%05d.png", where, vrg_graph_output(g), f);
        if (writer)
            rc = vrg_cli_png_writer_push(writer, file, &img);
        else {
            rc = vrg_write_png(file, &img);
            free(img.pixels);
        }
        for (uint32_t i = 0; f >= warm && i < vrg_graph_pass_count(g); i++)
            gpu += vrg_graph_pass_ms(g, i) > 0 ? vrg_graph_pass_ms(g, i) : 0;
    }
    rc |= vrg_cli_png_writer_finish(writer);
    double wall = vrg_cli_now_ms() - start;
    for (int f = 0; f < frames; f++) {
        snprintf(file, sizeof file, "%s/%s-%05d.png", where, g ? vrg_graph_output(g) : "", f);
        unlink(file);
    }
    rmdir(where);
    if (rc == 0)
        rc = vrg_bench_room(n, 2);
    if (rc == 0) {
        char fig[160];
        double per_frame = wall / (frames - warm), ratio = gpu > 0 ? wall / gpu : 0;
        const char *how = threaded ? "written by a thread (render --sequence)" : "written before the next frame";
        snprintf(fig, sizeof fig, "frame: %s with a PNG per frame %s, wall per frame", name, how);
        out[n++] = vrg_bench_summarise(fig, "ms", &per_frame, 1);
        snprintf(fig, sizeof fig, "frame: %s with a PNG per frame %s, wall / GPU (frames %d-%d)", name, how, warm, frames - 1);
        out[n++] = vrg_bench_summarise(fig, "x", &ratio, 1);
    }
    vrg_graph_destroy(g);
    *count = n;
    return rc ? -1 : 0;
}

int vrg_bench_frame(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    char file[1100], *names[64];
    snprintf(file, sizeof file, "%s/graphs/paths/walk.path", vrg_data_dir());
    vrg_camera_path path;
    if (vrg_camera_path_load(file, &path, stderr) != 0)
        return -1;
    int ng = vrg_bench_shipped_graphs(o, names, 64), rc = ng > 0 ? 0 : -1;
    for (int i = 0; i < ng && rc == 0; i++)
        rc = measure(ctx, o, names[i], &path, out, count);
    for (int i = 0; i < ng && rc == 0; i++) {
        rc = measure_output(ctx, o, names[i], &path, 0, out, count);
        rc = rc ? rc : measure_output(ctx, o, names[i], &path, 1, out, count);
    }
    for (int i = 0; i < ng; i++)
        free(names[i]);
    vrg_camera_path_free(&path);
    return rc;
}
