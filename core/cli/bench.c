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

int vrg_cli_bench(const char *suite, const char *json, int runs, const char *device)
{
    int want_terrain = !strcmp(suite, "all") || !strcmp(suite, "terrain"), want_rays = !strcmp(suite, "all") || !strcmp(suite, "rays");
    if (!want_terrain && !want_rays) {
        fprintf(stderr, "error: --suite '%s': this build has: all, terrain, rays (graph, memory, reload and frame come with later milestones)\n",
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
