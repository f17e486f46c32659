/* voxrg bench --suite frame: whole-frame GPU and wall time of every shipped
 * graph along graphs/paths/walk.path at --size (default 640x360), with
 * each pass's GPU time; for graphs with the four ray passes, the whole
 * frame over their sum (the goal: <= 1.15). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/camera_path.h"

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
        for (uint32_t i = 0; i < np && n < VRG_BENCH_MAX - 8; i++) {
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

int vrg_bench_frame(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    char file[1100], *names[64];
    snprintf(file, sizeof file, "%s/graphs/paths/walk.path", vrg_source_dir());
    vrg_camera_path path;
    if (vrg_camera_path_load(file, &path, stderr) != 0)
        return -1;
    int ng = vrg_bench_shipped_graphs(o, names, 64), rc = ng > 0 ? 0 : -1;
    for (int i = 0; i < ng && rc == 0; i++)
        rc = measure(ctx, o, names[i], &path, out, count);
    for (int i = 0; i < ng; i++)
        free(names[i]);
    vrg_camera_path_free(&path);
    return rc;
}
