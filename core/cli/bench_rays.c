/* voxrg bench --suite rays: primary, sun shadow, AO and indirect rays on
 * the default terrain from a fixed camera, one ray per pixel per pass, for
 * each backend. Ray counts are the rays actually traced: the G-buffer is
 * read back to count surface pixels (and those facing the sun for shadow
 * rays). The indirect pass runs without its secondary shadow rays so its
 * count is exact. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "voxrg/camera.h"
#include "voxrg/world.h"

int vrg_bench_rays(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    int runs = o->runs;
    uint32_t width = o->width, height = o->height;
    int n = *count;
    if (vrg_bench_room(n, 2 * 4 * 2)) /* backends x ray kinds x (ms, Mrays/s) */
        return -1;
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
                 "[scene]\nplugin = terrain\nseed = 1337\nradius = %d\ntime_of_day = 15\ntraversal = %s\n"
                 "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n%s"
                 "[pass shadow]\nplugin = sun_shadow\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\n"
                 "in.normal = gbuffer.normal\nrays = 1\nsun_radius = 0\n%s"
                 "[pass ao]\nplugin = ao\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\nin.normal = gbuffer.normal\n"
                 "rays = 1\nradius = 4\n%s"
                 "[pass indirect]\nplugin = indirect\nin.world = world\nin.frame = frame\nin.position = gbuffer.position\n"
                 "in.normal = gbuffer.normal\nrays = 1\nshadow = 0\n%s",
                 width, height, o->radius, backends[b], tlas, tlas, tlas, tlas);
        static const char *reads[] = {"gbuffer.normal", "shadow.visibility", "ao.ao", "indirect.irradiance"};
        vrg_graph_desc d = {.path = "<bench rays>", .text = text, .readback = reads, .readback_count = 4};
        vrg_graph *g = NULL;
        if (vrg_graph_load(ctx, &d, &g) != 0)
            return -1;
        static const char *passes[] = {"gbuffer", "shadow", "ao", "indirect"};
        static const char *kinds[] = {"primary", "sun shadow", "AO", "indirect"};
        double ms[4][64];
        for (int r = 0; r < runs + 2; r++) { /* two warm-up frames: the JIT, the world */
            if (vrg_graph_frame(g) != 0 || vrg_graph_wait(g) != 0) { /* the wait: timings of this frame */
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
            snprintf(name, sizeof name, "rays: %s pass GPU time, %s, %ux%u, radius %d", kinds[k], backends[b], width, height, o->radius);
            out[n++] = vrg_bench_summarise(name, "ms", ms[k], runs);
            snprintf(name, sizeof name, "rays: %s Mrays/s, %s (%.0f rays)", kinds[k], backends[b], rays[k]);
            out[n++] = vrg_bench_summarise(name, "Mrays/s", mr, runs);
        }
        vrg_graph_destroy(g);
    }
    *count = n;
    return 0;
}
