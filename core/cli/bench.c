/* voxrg bench: figures measured several times after warm-up, reported as
 * median / min / max with the device and thread counts. Suites that need
 * later milestones (rays, graph, frame, reload) are not here yet. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "bench.h"

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

static double stat(vrg_graph *g, const char *name)
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
                wait[r - 1] = stat(g, "wait_ms");
                integ[r - 1] = stat(g, "integrate_ms");
                upload[r - 1] = stat(g, "upload_ms");
                chunks = (int)stat(g, "chunks_integrated");
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
    for (int i = 0; i < 2000 && (i == 0 || stat(g, "chunks_pending") > 0); i++)
        vrg_graph_frame(g);
    int frames = (int)(vrg_camera_path_duration(&path) / vrg_graph_frame_seconds(g));
    double *integ = calloc((size_t)frames, sizeof *integ), *main_ms = calloc((size_t)frames, sizeof *main_ms);
    int integrated = 0;
    for (int k = 0; k < frames; k++) {
        vrg_camera_path_eval(&path, (float)(k * vrg_graph_frame_seconds(g)), &cam);
        vrg_graph_set_camera(g, &cam);
        vrg_graph_frame(g);
        integ[k] = stat(g, "integrate_ms");
        main_ms[k] = stat(g, "integrate_ms") + stat(g, "upload_ms") + stat(g, "wait_ms");
        integrated += (int)stat(g, "chunks_integrated");
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

int vrg_cli_bench(const char *suite, const char *json, int runs, const char *device)
{
    if (strcmp(suite, "all") != 0 && strcmp(suite, "terrain") != 0) {
        fprintf(stderr, "error: --suite '%s': this build has: all, terrain (rays, graph, memory, reload and frame come with later milestones)\n",
                suite);
        return 2;
    }
    vrg_context *ctx;
    vrg_context_desc cd = {.device = device};
    if (vrg_context_create(&cd, &ctx) != 0)
        return 1;
    figure figs[32];
    int n = 0;
    if (bench_terrain(ctx, runs, figs, &n) != 0) {
        fprintf(stderr, "error: terrain benchmark failed\n");
        vrg_context_destroy(ctx);
        return 1;
    }
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
                fprintf(f, "%s\n    {\"suite\": \"terrain\", \"name\": \"%s\", \"unit\": \"%s\", \"median\": %.6g, \"min\": %.6g, \"max\": %.6g, \"p99\": %.6g, \"samples\": %d}",
                        i ? "," : "", figs[i].name, figs[i].unit, figs[i].median, figs[i].min, figs[i].max, figs[i].p99, figs[i].samples);
            fprintf(f, "\n  ]\n}\n");
            fclose(f);
        }
    }
    vrg_context_destroy(ctx);
    return rc;
}
