/* voxrg bench: figures measured several times after warm-up, reported as
 * median / min / max / p99 with the device and thread counts; one file per
 * suite (bench_*.c), run in the order of the table below. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "bench.h"
#include "util.h"
#include "voxrg/output.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int vrg_bench_room(int n, int k)
{
    if (n + k <= VRG_BENCH_MAX)
        return 0;
    fprintf(stderr, "error: bench: more than %d figures\n", VRG_BENCH_MAX);
    return -1;
}

vrg_bench_figure vrg_bench_summarise(const char *name, const char *unit, double *v, int n)
{
    vrg_bench_figure f = {0};
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

static const struct {
    const char *name;
    int (*run)(vrg_context *, const vrg_bench_opts *, vrg_bench_figure *, int *);
} suites[] = {
    {"rays", vrg_bench_rays},     {"graph", vrg_bench_graph}, {"memory", vrg_bench_memory},
    {"terrain", vrg_bench_terrain}, {"reload", vrg_bench_reload}, {"frame", vrg_bench_frame},
};
enum { SUITES = sizeof suites / sizeof suites[0] };

static void write_json(FILE *f, vrg_context *ctx, const vrg_bench_opts *o, const vrg_bench_figure *figs, const char *const *of, int n,
                       const char *lp, long cpus)
{
    char e1[512], e2[512];
    fprintf(f, "{\n  \"device\": \"%s\",\n  \"cpus\": %ld,\n  \"lp_num_threads\": \"%s\",\n  \"runs\": %d,\n  \"smoke\": %s,\n",
            vrg_cli_json_str(vrg_context_device(ctx)->name, e1, sizeof e1), cpus, lp ? lp : "", o->runs, o->smoke ? "true" : "false");
    fprintf(f, "  \"size\": [%u, %u],\n  \"suites\": [", o->width, o->height);
    int first = 1;
    for (int s = 0; s < SUITES; s++)
        if (!strcmp(o->suite, "all") || !strcmp(o->suite, suites[s].name)) {
            fprintf(f, "%s\"%s\"", first ? "" : ", ", suites[s].name);
            first = 0;
        }
    fputs("],\n  \"figures\": [", f);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s\n    {\"suite\": \"%s\", \"name\": \"%s\", \"unit\": \"%s\", \"median\": %.6g, \"min\": %.6g, \"max\": %.6g, \"p99\": %.6g, \"samples\": %d}",
                i ? "," : "", of[i], vrg_cli_json_str(figs[i].name, e1, sizeof e1), vrg_cli_json_str(figs[i].unit, e2, sizeof e2), figs[i].median,
                figs[i].min, figs[i].max, figs[i].p99, figs[i].samples);
    fputs("\n  ]\n}\n", f);
}

int vrg_cli_bench(const vrg_bench_opts *o)
{
    int any = 0;
    for (int s = 0; s < SUITES; s++)
        any |= !strcmp(o->suite, "all") || !strcmp(o->suite, suites[s].name);
    if (!any) {
        fprintf(stderr, "error: --suite '%s': one of all, rays, graph, memory, terrain, reload, frame\n", o->suite);
        return 2;
    }
    if (o->json && vrg_cli_out_file_dir(o->json) != 0) /* before the runs, not after */
        return 1;
    vrg_context *ctx;
    vrg_context_desc cd = {.device = o->device};
    if (vrg_context_create(&cd, &ctx) != 0)
        return 1;
    static vrg_bench_figure figs[VRG_BENCH_MAX];
    static const char *of[VRG_BENCH_MAX];
    int n = 0, rc = 0;
    for (int s = 0; s < SUITES && rc == 0; s++) {
        if (strcmp(o->suite, "all") && strcmp(o->suite, suites[s].name))
            continue;
        int before = n;
        if (suites[s].run(ctx, o, figs, &n) != 0) {
            fprintf(stderr, "error: %s benchmark failed\n", suites[s].name);
            rc = 1;
        }
        for (; before < n; before++)
            of[before] = suites[s].name;
    }
    const char *lp = getenv("LP_NUM_THREADS");
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    printf("device: %s; CPUs: %ld; LP_NUM_THREADS: %s; %d runs after warm-up%s\n", vrg_context_device(ctx)->name, cpus, lp ? lp : "(unset)",
           o->runs, o->smoke ? " (smoke: tiny inputs, not figures to quote)" : "");
    printf("%-100s %10s %10s %10s %10s\n", "figure", "median", "min", "max", "p99");
    for (int i = 0; i < n; i++)
        printf("%-100s %10.3f %10.3f %10.3f %10.3f %s\n", figs[i].name, figs[i].median, figs[i].min, figs[i].max, figs[i].p99, figs[i].unit);
    if (rc == 0 && o->json) {
        vrg_output *out = vrg_output_open(o->json);
        if (out)
            write_json(vrg_output_stream(out), ctx, o, figs, of, n, lp, cpus);
        if (!out || vrg_output_commit(out) != 0)
            rc = 1;
    }
    vrg_context_destroy(ctx);
    return rc;
}
