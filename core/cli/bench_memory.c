/* voxrg bench --suite memory: transient memory without and with aliasing,
 * and the history kept across frames, for every shipped graph at 640x360
 * and 1920x1080 (allocated on the device: exact sizes). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "bench.h"

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* in the comma-separated list (NULL: every name is) */
static int listed(const char *list, const char *name)
{
    size_t len = strlen(name);
    for (const char *p = list; p && *p;) {
        size_t k = strcspn(p, ",");
        if (k == len && !strncmp(p, name, k))
            return 1;
        p += k + (p[k] == ',');
    }
    return !list;
}

/* Where graph dir/name shows a model file (`file = X.vox`, the vox scene)
 * that is not there: its path in `missing`, 1. The MagicaVoxel test models
 * live beside the project (docs/world.md), not in it. */
static int model_missing(const char *dir, const char *name, char *missing, size_t cap)
{
    char path[1400], line[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = vrg_fopen_regular(path, "r");
    int gone = 0;
    while (f && !gone && fgets(line, sizeof line, f)) {
        char file[1100];
        size_t len;
        if (sscanf(line, " file = %1099s", file) != 1 || (len = strlen(file)) < 4 || strcmp(file + len - 4, ".vox") != 0)
            continue;
        snprintf(missing, cap, "%s%s%s", file[0] == '/' ? "" : dir, file[0] == '/' ? "" : "/", file);
        gone = access(missing, R_OK) != 0;
    }
    if (f)
        fclose(f);
    return gone;
}

/* the graphs/ *.ini files of the source tree (those --graphs names), sorted;
 * returns the count (names malloc'd), or -1 after an error when --graphs
 * names a file that is not there */
int vrg_bench_shipped_graphs(const vrg_bench_opts *o, char **names, int max)
{
    char dir[1100];
    snprintf(dir, sizeof dir, "%s/graphs", vrg_data_dir());
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d))) {
        size_t len = strlen(e->d_name);
        char missing[2400];
        if (len <= 4 || strcmp(e->d_name + len - 4, ".ini") != 0 || !listed(o->graphs, e->d_name))
            continue;
        if (!o->graphs && model_missing(dir, e->d_name, missing, sizeof missing)) { /* named in --graphs: its load error says it */
            fprintf(stderr, "bench: skipping %s: its model %s is missing (the vox test models, docs/world.md)\n", e->d_name, missing);
            continue;
        }
        if (n == max) { /* never a graph silently left out */
            fprintf(stderr, "error: %s holds more than the %d graphs bench measures in one run; name some with --graphs\n", dir, max);
            for (int i = 0; i < n; i++)
                free(names[i]);
            closedir(d);
            return -1;
        }
        names[n++] = strdup(e->d_name);
    }
    if (d)
        closedir(d);
    qsort(names, (size_t)n, sizeof *names, by_name);
    for (const char *p = o->graphs; p && *p;) { /* each one asked for is there */
        size_t k = strcspn(p, ",");
        int found = 0;
        for (int i = 0; i < n && !found; i++)
            found = strlen(names[i]) == k && !strncmp(names[i], p, k);
        if (!found) {
            fprintf(stderr, "error: --graphs: '%.*s' is not a graph in %s\n", (int)k, p, dir);
            for (int i = 0; i < n; i++)
                free(names[i]);
            return -1;
        }
        p += k + (p[k] == ',');
    }
    return n;
}

/* Loads graphs/NAME with the device at w x h; in a smoke run the terrain
 * is shrunk to radius 2 so that loading takes no time. */
vrg_graph *vrg_bench_load_shipped(vrg_context *ctx, const char *name, uint32_t w, uint32_t h, int smoke)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/graphs/%s", vrg_data_dir(), name);
    int shrink = 0;
    if (smoke) { /* only graphs whose scene has a radius */
        FILE *quiet = fopen("/dev/null", "w"); /* a graph without a scene is no error here */
        vrg_graph_desc cd = {.path = path, .diag = quiet};
        vrg_graph *check = NULL;
        double r;
        if (vrg_graph_load(NULL, &cd, &check) == 0)
            shrink = vrg_graph_get_param(check, "scene.radius", &r) == 0;
        vrg_graph_destroy(check);
        if (quiet)
            fclose(quiet);
    }
    static const char *radius[] = {"scene.radius=2"};
    vrg_graph_desc d = {.path = path, .width = w, .height = h, .overrides = shrink ? radius : NULL, .override_count = shrink ? 1u : 0u};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        vrg_graph_destroy(g);
        return NULL;
    }
    return g;
}

int vrg_bench_memory(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count)
{
    char *names[64];
    int ng = vrg_bench_shipped_graphs(o, names, 64), n = *count, rc = 0;
    const uint32_t sizes[2][2] = {{640, 360}, {1920, 1080}}, smoke_sizes[2][2] = {{64, 36}, {96, 54}};
    for (int i = 0; i < ng && rc == 0; i++)
        for (int s = 0; s < 2 && rc == 0; s++) {
            uint32_t w = o->smoke ? smoke_sizes[s][0] : sizes[s][0], h = o->smoke ? smoke_sizes[s][1] : sizes[s][1];
            vrg_graph *g = vrg_bench_room(n, 4) ? NULL : vrg_bench_load_shipped(ctx, names[i], w, h, o->smoke);
            if (!g) {
                rc = -1;
                break;
            }
            vrg_memory_stats m = vrg_graph_memory(g);
            double mib = 1024.0 * 1024.0, v[4] = {m.naive_bytes / mib, m.aliased_bytes / mib,
                                                    m.naive_bytes ? 100.0 * (1.0 - (double)m.aliased_bytes / m.naive_bytes) : 0,
                                                    m.history_bytes / mib};
            static const char *what[4] = {"transient, naive", "transient, aliased", "saved by aliasing", "history kept across frames"};
            for (int k = 0; k < 4; k++) {
                char name[160];
                snprintf(name, sizeof name, "memory: %s %ux%u %s", names[i], w, h, what[k]);
                out[n++] = vrg_bench_summarise(name, k == 2 ? "%" : "MiB", &v[k], 1);
            }
            vrg_graph_destroy(g);
        }
    for (int i = 0; i < ng; i++)
        free(names[i]);
    *count = n;
    return ng > 0 ? rc : -1;
}
