/* voxrg bench --suite terrain: world generation, chunks/s per thread,
 * streaming along a camera path. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "voxrg/camera.h"
#include "voxrg/camera_path.h"


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

int vrg_bench_terrain(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    int runs = o->runs, radius = o->smoke ? 2 : o->radius; /* smoke: a small world, a short walk */
    int n = *count;
    if (vrg_bench_room(n, 2 * 4 + 2)) /* two thread counts x 4, the walk's 2 */
        return -1;
    /* whole-world generation (radius 13: 27 x 27 x 3 chunks), 1 and 2 threads */
    for (int threads = 1; threads <= 2; threads++) {
        double wait[64], per_thread[64], integ[64], upload[64];
        int chunks = 0;
        for (int r = 0; r < runs + 1; r++) {
            vrg_graph *g = terrain_graph(ctx, threads, "wait", radius);
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
        snprintf(name, sizeof name, "terrain: generate radius-%d world (%d chunks), %d thread%s", radius, chunks, threads, threads > 1 ? "s" : "");
        out[n++] = vrg_bench_summarise(name, "ms", wait, runs);
        snprintf(name, sizeof name, "terrain: chunks/s per thread, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = vrg_bench_summarise(name, "chunks/s", per_thread, runs);
        snprintf(name, sizeof name, "terrain: integrate whole world on main thread, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = vrg_bench_summarise(name, "ms", integ, runs);
        snprintf(name, sizeof name, "terrain: pack + record upload of whole world, %d thread%s", threads, threads > 1 ? "s" : "");
        out[n++] = vrg_bench_summarise(name, "ms", upload, runs);
    }
    /* streaming along graphs/paths/walk.path, budget 2 ms: main-thread time per frame */
    vrg_camera_path path;
    char path_file[1024];
    snprintf(path_file, sizeof path_file, "%s/graphs/paths/walk.path", vrg_data_dir());
    if (vrg_camera_path_load(path_file, &path, stderr) != 0)
        return -1;
    vrg_graph *g = terrain_graph(ctx, 2, "budget", radius);
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
    int frames = o->smoke ? 30 : (int)(vrg_camera_path_duration(&path) / vrg_graph_frame_seconds(g));
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
    out[n++] = vrg_bench_summarise(name, "ms", integ, frames);
    snprintf(name, sizeof name, "terrain: streaming main-thread total per frame (update + integrate + upload)");
    out[n++] = vrg_bench_summarise(name, "ms", main_ms, frames);
    free(integ);
    free(main_ms);
    vrg_graph_destroy(g);
    vrg_camera_path_free(&path);
    *count = n;
    return 0;
}
