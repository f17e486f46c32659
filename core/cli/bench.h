#ifndef VOXRG_CLI_BENCH_H
#define VOXRG_CLI_BENCH_H
/* voxrg bench: the driver (bench.c) and one file per suite. */
#include <stdint.h>
#include "voxrg/voxrg.h"

typedef struct vrg_bench_figure {
    char name[160];
    char unit[16];
    double median, min, max, p99;
    int samples;
} vrg_bench_figure;

typedef struct vrg_bench_opts {
    const char *suite, *json, *device;
    int runs;              /* samples per figure, after warm-up */
    uint32_t width, height; /* --size: the rays and frame suites' size (default 640x360) */
    int smoke;             /* --smoke: every figure, measured once on tiny inputs (CI) */
    int radius;            /* --radius: the terrain radius of the rays and terrain suites (default 13) */
    const char *graphs;    /* --graphs a.ini,b.ini: the shipped graphs the memory and frame suites use (default all) */
} vrg_bench_opts;

/* median, min, max, p99 of v[0..n) (v is sorted) */
vrg_bench_figure vrg_bench_summarise(const char *name, const char *unit, double *v, int n);

/* Each suite appends its figures to out[*count...] (room for VRG_BENCH_MAX)
 * and asks vrg_bench_room(n, k) before appending k more: past the room it
 * is an error saying so, never a dropped or overrun figure. */
#define VRG_BENCH_MAX 4096
int vrg_bench_room(int n, int k);
int vrg_bench_terrain(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);
int vrg_bench_rays(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);
int vrg_bench_reload(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);
int vrg_bench_graph(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);
int vrg_bench_memory(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);
int vrg_bench_frame(vrg_context *ctx, const vrg_bench_opts *o, vrg_bench_figure *out, int *count);

/* Shared by the suites: the names of graphs/ *.ini that --graphs names
 * (malloc'd, sorted; -1 after an error on a name that is not there), and
 * one of them loaded at w x h (smoke: terrain radius 2). */
int vrg_bench_shipped_graphs(const vrg_bench_opts *o, char **names, int max);
vrg_graph *vrg_bench_load_shipped(vrg_context *ctx, const char *name, uint32_t w, uint32_t h, int smoke);

/* `voxrg bench`; returns the exit status. */
int vrg_cli_bench(const vrg_bench_opts *o);
#endif
