/* voxrg compare: renders candidate graphs (and variants of them) along
 * a camera path, and a reference graph converged at every path frame
 * (cached on disk), and measures each candidate frame against the
 * reference frame: PSNR, SSIM, FLIP and temporal error, plus per-pass GPU
 * time. Writes metrics.csv, metrics.json, report.html (report.c) and the
 * PNGs used. The phases, in order: options, check (every graph loaded
 * without a device: errors and scene/size mismatches before any work),
 * reference frames, candidates, summaries, files. */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "compare_cases.h"
#include "compare_files.h"
#include "compare_result.h"
#include "compare_shard.h"
#include "warnings_once.h"
#include "ref_cache.h"
#include "report.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "voxrg/camera_path.h"
#include "voxrg/device_score.h"
#include "voxrg/metrics.h"
#include "voxrg/voxrg.h"

#define MAX_SETS 64
#define RESERVED_NAME "reference" /* frames/reference-NNNNN.png */

const char *const vrg_cli_compare_usage =
    "usage: voxrg compare A.ini [B.ini ...] --reference REF.ini [--variant NAME[@GRAPH]:PASS.PARAM=VALUE,...]...\n"
    "                     [--grid [@GRAPH:]PASS.PARAM=A,B,...]... [--baseline NAME]\n"
    "                     [--cases FILE | [--camera PATH] [--start N] [--frames N] [--size WxH] [--warmup N]] [--out DIR]\n"
    "                     [--ref-set PASS.PARAM=VALUE]... [--cache DIR] [--score cpu|device] [--validate] [--device NAME|INDEX]\n"
    "                     [--shard I/N] [--check-finite]\n"
    "       voxrg compare --merge OUT SHARD_DIR...\n"
    "Renders every candidate (each graph, and each --variant: the graph GRAPH names, a\n"
    "listed graph's candidate name, path or file name, else the first graph, with those\n"
    "parameters) and the reference on the same frames: same world, camera path, seeds\n"
    "and size. The reference is rendered converged at each path frame and cached in\n"
    "DIR (default $XDG_CACHE_HOME/voxrg/reference; one folder may be shared by many\n"
    "processes and machines), keyed by the content of all it is built from.\n"
    "Measures each candidate frame against the reference frame: PSNR, SSIM (luma,\n"
    "11x11 Gaussian), LDR-FLIP and temporal error |(D_t - D_t-1) - (R_t - R_t-1)|,\n"
    "and per-pass GPU ms (mean, p95); --score device computes them on the rendering\n"
    "device and reads back only the frames the report shows (default cpu). Frames before --warmup (default 5) are shown but\n"
    "left out of the summary. Writes DIR/report.html, metrics.csv, metrics.json and\n"
    "frames/*.png (default DIR: compare). --frames defaults to 30, --camera to the\n"
    "first graph's [camera]; --start N begins at the path's frame N (at the graph's\n"
    "fps; warm-up counts from there); --ref-set changes the reference (e.g. fewer samples:\n"
    "converge.samples_per_frame=64). Graphs whose scene, seed, fps or size differ are\n"
    "an error. --grid adds a variant per value (per combination of the values of\n"
    "several --grid of one graph), named GRAPH-PARAMVALUE..., of the first graph or GRAPH.\n"
    "--cases FILE runs every [case NAME] of the case file (camera, start, frames,\n"
    "warmup, size and scene.PARAM overrides) and judges each candidate against the\n"
    "--baseline candidate (default the first) over the cases.\n"
    "--shard I/N (I from 0 to N-1, or auto: $SLURM_ARRAY_TASK_ID or\n"
    "$JOB_COMPLETION_INDEX) runs the I-th of N contiguous slices of the (case,\n"
    "candidate) tasks and writes DIR/shard.txt and frames/ instead of a report;\n"
    "--merge OUT reads the N shards' folders and writes the run's report to OUT.\n"
    "--check-finite (as render's; --validate checks too) fails the run at the first NaN\n"
    "or infinity a pass writes into a float image through its slots (not its internal\n"
    "images), naming the pass, resource, pixel and frame.\n";

typedef struct options {
    const char **graphs; /* [argc] each, as the arguments are at most */
    int graph_count;
    const char **variants; /* given, then the grids' expanded (owned: from variant_count_given on) */
    int variant_count, variant_count_given;
    const char **grids;
    int grid_count;
    const char *reference, *camera, *out, *cache, *device, *cases, *baseline;
    int score_device; /* --score device */
    const char *ref_sets[MAX_SETS];
    int ref_set_count;
    uint32_t width, height, frames, warmup, start;
    int validate, help;
    int check_finite; /* NaN/Inf checks after each pass (vrg_graph_desc.check_finite) */
    int shard, shards; /* --shard I/N; shards 0: the whole run */
    /* the case being run: its scene.PARAM=VALUE overrides, for every graph */
    char *const *scene;
    int scene_count;
    /* where the graphs' messages go: each line once (a graph is loaded
     * once per case, and its warnings would repeat) */
    FILE *diag;
} options;

/* one candidate to render: a graph and its overrides */
typedef struct job {
    const char *graph;
    int base; /* a variant: the index of the listed graph it changes; -1 for a listed graph */
    const char *sets[MAX_SETS];
    int set_count;
    char buf[1024]; /* the variant's overrides, split in place */
} job;

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "error: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n%s", vrg_cli_compare_usage);
    return 2;
}

static int parse_count(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end;
    long n = strtol(s, &end, 10);
    if (*end || *s == '\0' || n < (long)lo || n > (long)hi)
        return -1;
    *out = (uint32_t)n;
    return 0;
}

/* --shard I/N, I a number or "auto": the array task's index from Slurm's
 * or a Kubernetes Indexed Job's environment */
static int parse_shard(const char *arg, options *o)
{
    char index[32];
    const char *slash = strchr(arg, '/');
    uint32_t i, n;
    if (!slash || (size_t)(slash - arg) >= sizeof index || parse_count(slash + 1, 1, 100000, &n) != 0)
        return usage_error("--shard '%s': expected I/N, I from 0 to N-1 (or auto), N from 1 to 100000", arg);
    snprintf(index, sizeof index, "%.*s", (int)(slash - arg), arg);
    const char *from = index;
    if (!strcmp(index, "auto") && !(from = getenv("SLURM_ARRAY_TASK_ID")) && !(from = getenv("JOB_COMPLETION_INDEX")))
        return usage_error("--shard %s: neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set", arg);
    if (parse_count(from, 0, n - 1, &i) != 0) {
        fprintf(stderr, "error: --shard %s: the index '%s' is not a whole number from 0 to %u\n%s", arg, from, n - 1, vrg_cli_compare_usage);
        return 2;
    }
    o->shard = (int)i, o->shards = (int)n;
    return 0;
}

/* A variant's name becomes part of file names under --out
 * (frames/NAME-NNNNN.png) and a CSV field: no path separators, no
 * hidden names, nothing to quote, and not the reference's frames' name. */
static int variant_name_ok(const char *name, size_t len)
{
    return vrg_cmp_name_ok(name, len) && !(len == strlen(RESERVED_NAME) && !strncmp(name, RESERVED_NAME, len));
}

static int parse_options(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->graphs = calloc((size_t)argc + 1, sizeof *o->graphs);
    o->variants = calloc((size_t)argc + 1, sizeof *o->variants);
    o->grids = calloc((size_t)argc + 1, sizeof *o->grids);
    if (!o->graphs || !o->variants || !o->grids)
        return usage_error("out of memory%s", "");
    o->frames = 30;
    o->warmup = 5;
    o->out = "compare";
    int warmup_given = 0;
    const char *case_option = NULL; /* the last given of the options a case file's keys replace */
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            o->help = 1;
            continue;
        }
        if (!strcmp(a, "--validate")) {
            o->validate = 1;
            continue;
        }
        if (!strcmp(a, "--check-finite")) {
            o->check_finite = 1;
            continue;
        }
        if (a[0] != '-') {
            o->graphs[o->graph_count++] = a;
            continue;
        }
        if (!next)
            return usage_error("%s needs a value", a);
        i++;
        if (!strcmp(a, "--camera") || !strcmp(a, "--start") || !strcmp(a, "--frames") || !strcmp(a, "--warmup") || !strcmp(a, "--size"))
            case_option = a;
        if (!strcmp(a, "--reference"))
            o->reference = next;
        else if (!strcmp(a, "--camera"))
            o->camera = next;
        else if (!strcmp(a, "--out"))
            o->out = next;
        else if (!strcmp(a, "--cache"))
            o->cache = next;
        else if (!strcmp(a, "--device"))
            o->device = next;
        else if (!strcmp(a, "--score")) {
            if (strcmp(next, "cpu") && strcmp(next, "device"))
                return usage_error("--score '%s': expected cpu or device", next);
            o->score_device = !strcmp(next, "device");
        } else if (!strcmp(a, "--shard")) {
            if (parse_shard(next, o) != 0)
                return 2;
        }
        else if (!strcmp(a, "--variant")) {
            /* a name has neither '@' nor ':', so whichever comes first ends it */
            size_t name_len = strcspn(next, "@:");
            const char *colon = strchr(next + name_len, ':');
            if (!colon || !name_len || !colon[1] || (next[name_len] == '@' && colon == next + name_len + 1))
                return usage_error("--variant '%s': expected NAME[@GRAPH]:PASS.PARAM=VALUE[,...]", next);
            if (!variant_name_ok(next, name_len))
                return usage_error("--variant '%s': a name is 1 to 63 of A-Z a-z 0-9 _ - and dots (not first or last), "
                                   "and not 'reference'", next);
            o->variants[o->variant_count++] = next;
        } else if (!strcmp(a, "--grid")) {
            const char *eq = strchr(next, '='), *at_end = next[0] == '@' ? strchr(next, ':') : next;
            if (!eq || !at_end || at_end > eq || !strchr(at_end, '.') || strchr(at_end, '.') > eq || !eq[1] || next[1] == ':')
                return usage_error("--grid '%s': expected [@GRAPH:]PASS.PARAM=VALUE,VALUE,...", next);
            o->grids[o->grid_count++] = next;
        } else if (!strcmp(a, "--cases"))
            o->cases = next;
        else if (!strcmp(a, "--baseline"))
            o->baseline = next; else if (!strcmp(a, "--ref-set")) {
            if (o->ref_set_count == MAX_SETS)
                return usage_error("too many --ref-set options%s", "");
            o->ref_sets[o->ref_set_count++] = next;
        } else if (!strcmp(a, "--size")) {
            if (vrg_cli_parse_size(next, &o->width, &o->height) != 0)
                return usage_error("--size '%s': expected WxH, " VRG_CLI_SIZE_RANGE ", e.g. 320x180", next);
            if (o->width < VRG_SSIM_WINDOW || o->height < VRG_SSIM_WINDOW)
                return usage_error("--size %s: compare needs at least " VRG_CLI_STR(VRG_SSIM_WINDOW) "x" VRG_CLI_STR(VRG_SSIM_WINDOW)
                                   " pixels (SSIM's window)", next);
        } else if (!strcmp(a, "--frames")) {
            if (parse_count(next, 1, 100000, &o->frames) != 0)
                return usage_error("--frames '%s': expected 1 to 100000", next);
        } else if (!strcmp(a, "--start")) {
            if (parse_count(next, 0, 10000000, &o->start) != 0)
                return usage_error("--start '%s': expected a frame number", next);
        } else if (!strcmp(a, "--warmup")) {
            if (parse_count(next, 0, 100000, &o->warmup) != 0)
                return usage_error("--warmup '%s': expected 0 or more frames", next);
            warmup_given = 1;
        } else
            return usage_error("unknown option '%s'", a);
    }
    if (o->help)
        return 0;
    o->variant_count_given = o->variant_count; /* the grids' come after, owned */
    if (o->cases && case_option)
        return usage_error("--cases with %s: --camera, --start, --frames, --warmup and --size are the case file's keys", case_option);
    if (!o->graph_count)
        return usage_error("no candidate graph given%s", "");
    if (!o->reference)
        return usage_error("no --reference graph given%s", "");
    if (o->warmup >= o->frames) {
        if (warmup_given)
            return usage_error("--warmup must be below --frames (%s)", "every frame would be left out");
        o->warmup = o->frames > 1 ? 1 : 0; /* the default on a short run */
    }
    return 0;
}

/* ---- check: every graph loaded without a device ---- */

static const char *stem(const char *path, char *buf, size_t cap)
{
    const char *slash = strrchr(path, '/');
    snprintf(buf, cap, "%s", slash ? slash + 1 : path);
    char *dot = strrchr(buf, '.');
    if (dot && dot != buf)
        *dot = '\0';
    return buf;
}

/* a graph with its overrides, then the case's scene overrides */
static vrg_graph *load(vrg_context *ctx, const char *graph, const char *const *sets, int set_count, const options *o)
{
    const char **all = malloc(sizeof *all * (size_t)(set_count + o->scene_count + 1));
    if (!all)
        return NULL;
    int n = 0;
    for (int i = 0; i < set_count; i++)
        all[n++] = sets[i];
    for (int i = 0; i < o->scene_count; i++)
        all[n++] = o->scene[i];
    vrg_graph_desc d = {.path = graph, .overrides = all, .override_count = (uint32_t)n, .width = o->width, .height = o->height,
                        .check_finite = o->check_finite, .diag = o->diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(ctx, &d, &g);
    free(all);
    if (rc != 0) {
        vrg_graph_destroy(g);
        return NULL;
    }
    return g;
}

/* ---- grids: each --grid's values, the product per graph, as variants ---- */

/* GRAPH's short form for names: its file name without the extension */
static void grid_prefix(const options *o, const char *grid, char *out, size_t cap)
{
    char buf[256];
    const char *graph = o->graphs[0];
    if (grid[0] == '@') {
        snprintf(buf, sizeof buf, "%.*s", (int)(strchr(grid, ':') - grid - 1), grid + 1);
        graph = buf;
    }
    stem(graph, out, cap);
}

/* the part of a grid after "@GRAPH:" */
static const char *grid_axis(const char *grid) { return grid[0] == '@' ? strchr(grid, ':') + 1 : grid; }

static int same_graph(const char *a, const char *b)
{
    size_t la = a[0] == '@' ? (size_t)(strchr(a, ':') - a) : 0, lb = b[0] == '@' ? (size_t)(strchr(b, ':') - b) : 0;
    return la == lb && !strncmp(a, b, la);
}

static long grid_values(const char *grid)
{
    long values = 1;
    for (const char *c = strchr(grid, '=') + 1; *c; c++)
        values += *c == ',';
    return values;
}

/* one variant of the grids axes[0..n) (one graph's): the combination
 * `index`, the first axis varying slowest, as "NAME[@GRAPH]:SETS"; NAME is
 * GRAPH's file name and "-PARAMVALUE" per axis, with what a name cannot
 * hold as '_' */
static char *grid_variant(const options *o, const char **axes, int n, long index)
{
    char name[512], sets[1024];
    size_t nl, sl = 0;
    grid_prefix(o, axes[0], name, sizeof name);
    nl = strlen(name);
    long stride = 1;
    for (int a = 1; a < n; a++)
        stride *= grid_values(axes[a]);
    for (int a = 0; a < n; a++) {
        const char *axis = grid_axis(axes[a]), *eq = strchr(axis, '='), *dot = strchr(axis, '.');
        long pick = index / stride % grid_values(axes[a]);
        stride /= a + 1 < n ? grid_values(axes[a + 1]) : 1;
        const char *v = eq + 1;
        for (long k = 0; k < pick; k++)
            v = strchr(v, ',') + 1;
        int vl = (int)strcspn(v, ",");
        if (nl < sizeof name)
            nl += (size_t)snprintf(name + nl, sizeof name - nl, "-%.*s%.*s", (int)(eq - dot - 1), dot + 1, vl, v);
        if (sl < sizeof sets)
            sl += (size_t)snprintf(sets + sl, sizeof sets - sl, "%s%.*s%.*s", a ? "," : "", (int)(eq - axis + 1), axis, vl, v);
    }
    if (sl >= sizeof sets) {
        fprintf(stderr, "error: --grid %s: a variant's overrides are longer than %zu characters\n", axes[0], sizeof sets - 1);
        return NULL;
    }
    for (char *c = name; *c; c++)
        if (!isalnum((unsigned char)*c) && !strchr("_-.", *c))
            *c = '_';
    size_t cap = sizeof name + sizeof sets + 8;
    char *spec = malloc(cap);
    if (spec)
        snprintf(spec, cap, "%s%.*s:%s", name, axes[0][0] == '@' ? (int)(strchr(axes[0], ':') - axes[0]) : 0, axes[0], sets);
    return spec;
}

/* Appends the grids' variants to o->variants: per graph (in the order of
 * its first --grid) the product of its grids' values. */
static int expand_grids(options *o)
{
    for (int g = 0; g < o->grid_count; g++) {
        int first = 1;
        for (int k = 0; k < g; k++)
            first &= !same_graph(o->grids[k], o->grids[g]);
        if (!first)
            continue;
        const char *axes[64];
        int n = 0;
        long total = 1;
        for (int k = g; k < o->grid_count; k++)
            if (same_graph(o->grids[k], o->grids[g])) {
                if (n == 64) {
                    fprintf(stderr, "error: more than 64 --grid of one graph\n");
                    return -1;
                }
                axes[n++] = o->grids[k];
                total *= grid_values(o->grids[k]);
                if (total > 100000) {
                    fprintf(stderr, "error: --grid %s: more than 100000 combinations\n", o->grids[k]);
                    return -1;
                }
            }
        const char **grown = realloc(o->variants, sizeof *grown * (size_t)(o->variant_count + total + 1));
        if (!grown)
            return -1;
        o->variants = grown;
        for (long i = 0; i < total; i++) {
            char *spec = grid_variant(o, axes, n, i);
            if (!spec)
                return -1;
            size_t len = strcspn(spec, "@:");
            if (!variant_name_ok(spec, len)) {
                fprintf(stderr, "error: --grid %s: the variant name '%.*s' is not 1 to 63 of A-Z a-z 0-9 _ - and dots\n", axes[0],
                        (int)len, spec);
                free(spec);
                return -1;
            }
            o->variants[o->variant_count++] = spec;
        }
    }
    return 0;
}

/* The listed graph whose candidate name, path as given or file name is
 * `want`, tried in that order: a candidate name is unique, while one path
 * or file name may be listed twice. Its index, or -1 after a usage error
 * that lists the candidates. */
static int variant_base(const options *o, const vrg_cmp_result *r, const char *variant, const char *want, size_t want_len)
{
    int count = 0, found = -1;
    for (int tier = 0; tier < 3 && !count; tier++)
        for (int i = 0; i < o->graph_count; i++) {
            const char *slash = strrchr(o->graphs[i], '/');
            const char *key = tier == 0 ? r->cand[i].name : tier == 1 ? o->graphs[i] : slash ? slash + 1 : o->graphs[i];
            if (strlen(key) == want_len && !strncmp(key, want, want_len))
                found = i, count++;
        }
    if (count == 1)
        return found;
    fprintf(stderr, "error: --variant %s: '%.*s' %s; the listed graphs are", variant, (int)want_len, want,
            count ? "is more than one listed graph, name it by its candidate name" : "is not a listed graph");
    for (int i = 0; i < o->graph_count; i++)
        fprintf(stderr, "%s %s (%s)", i ? "," : "", r->cand[i].name, o->graphs[i]);
    fprintf(stderr, "\n%s", vrg_cli_compare_usage);
    return -1;
}

/* Jobs and candidate names: each graph, then each variant of a listed
 * graph. -1 on an error, 2 on a usage error. */
static int make_jobs(const options *o, job *jobs, vrg_cmp_result *r)
{
    int n = 0;
    for (int i = 0; i < o->graph_count; i++, n++) {
        jobs[n].graph = o->graphs[i];
        jobs[n].base = -1;
        stem(o->graphs[i], r->cand[n].name, sizeof r->cand[n].name);
        int taken = !strcmp(r->cand[n].name, RESERVED_NAME);
        for (int k = 0; k < n; k++) /* two graphs of one name: number them */
            taken |= !strcmp(r->cand[k].name, r->cand[n].name);
        if (taken) { /* the number kept whole, the stem cut if need be */
            char *name = r->cand[n].name, suffix[16];
            int len = snprintf(suffix, sizeof suffix, "-%d", n + 1);
            size_t at = strlen(name) + len < sizeof r->cand[n].name ? strlen(name) : sizeof r->cand[n].name - 1 - len;
            memcpy(name + at, suffix, (size_t)len + 1);
        }
    }
    for (int v = 0; v < o->variant_count; v++, n++) {
        const char *spec = o->variants[v], *colon = strchr(spec, ':');
        size_t name_len = strcspn(spec, "@:");
        job *j = &jobs[n];
        j->base = 0; /* without @GRAPH: the first graph, as before GRAPH could be named */
        if (spec[name_len] == '@' && (j->base = variant_base(o, r, spec, spec + name_len + 1, (size_t)(colon - spec - name_len - 1))) < 0)
            return 2;
        j->graph = o->graphs[j->base];
        snprintf(r->cand[n].name, sizeof r->cand[n].name, "%.*s", (int)name_len, spec);
        snprintf(r->cand[n].overrides, sizeof r->cand[n].overrides, "%s", colon + 1);
        if ((size_t)snprintf(j->buf, sizeof j->buf, "%s", colon + 1) >= sizeof j->buf) {
            fprintf(stderr, "error: --variant %s: the overrides are longer than %zu characters\n", o->variants[v], sizeof j->buf - 1);
            return -1;
        }
        for (char *save, *tok = strtok_r(j->buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            if (j->set_count == MAX_SETS) {
                fprintf(stderr, "error: --variant %s: more than %d overrides\n", o->variants[v], MAX_SETS);
                return -1;
            }
            j->sets[j->set_count++] = tok;
        }
        for (int k = 0; k < n; k++)
            if (!strcmp(r->cand[k].name, r->cand[n].name)) {
                fprintf(stderr, "error: --variant %s: the name '%s' is taken\n", o->variants[v], r->cand[n].name);
                return -1;
            }
    }
    for (int i = 0; i < n; i++) {
        snprintf(r->cand[i].graph, sizeof r->cand[i].graph, "%s", jobs[i].graph);
        r->cand[i].base = jobs[i].base;
    }
    r->count = n;
    return 0;
}

/* A variant whose world differs from the first graph's: its listed graph
 * shares that world (it was checked first), so its overrides of the scene
 * are the cause. Names the variant once and each such override with the
 * value it replaces; the runtime's reason would name the one graph file's
 * [scene] line twice. */
static void variant_world_error(const options *o, const job *j, const vrg_cmp_result *r, int c, vrg_graph *first, vrg_graph *g, const char *why)
{
    int named = 0;
    fprintf(stderr, "error: --variant %s: ", o->variants[c - o->graph_count]);
    for (int pass = 0; pass < 2 && !named; pass++) /* numbers that differ; else any scene override (a text parameter) */
        for (int k = 0; k < j->set_count; k++) {
            const char *set = j->sets[k], *eq = strchr(set, '=');
            char key[256];
            double was = 0, is = 0;
            if (strncmp(set, "scene.", 6) != 0 || !eq || (size_t)(eq - set) >= sizeof key)
                continue;
            snprintf(key, sizeof key, "%.*s", (int)(eq - set), set);
            int numeric = vrg_graph_get_param(first, key, &was) == 0 && vrg_graph_get_param(g, key, &is) == 0 && was != is;
            if (pass == 0 && numeric)
                fprintf(stderr, "%s%s changes the scene (%s has %g)", named++ ? ", " : "", set, r->cand[0].name, was);
            else if (pass == 1)
                fprintf(stderr, "%s%s changes the scene", named++ ? ", " : "", set);
        }
    if (!named)
        fputs(why, stderr);
    fprintf(stderr, ": candidates must render the same frames; a variant sets parameters of passes, not of the scene\n");
}

/* Loads each candidate and the reference without a device: parameters,
 * variants, then the same world and size everywhere. Sets the size and
 * the camera (the first graph's, when no path is given). */
static int check_all(const options *o, job *jobs, vrg_cmp_result *r, vrg_camera *camera, double *frame_s)
{
    vrg_graph *first = NULL, *g = NULL;
    int rc = 0;
    for (int i = 0; i < r->count && rc == 0; i++) {
        g = load(NULL, jobs[i].graph, jobs[i].sets, jobs[i].set_count, o);
        if (!g) {
            fprintf(stderr, "error: candidate '%s' (%s%s%s) does not load\n", r->cand[i].name, jobs[i].graph, jobs[i].set_count ? " with " : "",
                    r->cand[i].overrides);
            rc = -1;
            break;
        }
        char why[1024];
        if (!first) {
            first = g;
            *camera = *vrg_graph_camera(g);
            *frame_s = vrg_graph_frame_seconds(g);
            vrg_graph_size(g, &r->width, &r->height);
        } else {
            if (vrg_graph_same_world(first, g, why, sizeof why) != 0) {
                if (jobs[i].base >= 0)
                    variant_world_error(o, &jobs[i], r, i, first, g, why);
                else
                    fprintf(stderr, "error: %s: candidates must render the same frames\n", why);
                rc = -1;
            }
            vrg_graph_destroy(g);
        }
        g = NULL;
    }
    if (rc == 0) {
        g = load(NULL, o->reference, o->ref_sets, o->ref_set_count, o);
        char why[1024];
        if (!g) {
            fprintf(stderr, "error: the reference %s does not load\n", o->reference);
            rc = -1;
        } else if (vrg_graph_same_world(first, g, why, sizeof why) != 0) {
            fprintf(stderr, "error: %s: the reference must render the candidates' frames\n", why);
            rc = -1;
        } else if (vrg_graph_resource_kind(g, vrg_graph_output(g)) != VRG_IMAGE) {
            fprintf(stderr, "error: the reference's output '%s' is not an image\n", vrg_graph_output(g));
            rc = -1;
        } else if (r->width < VRG_SSIM_WINDOW || r->height < VRG_SSIM_WINDOW) {
            fprintf(stderr, "error: the graphs render %ux%u: compare needs at least %dx%d pixels (SSIM's window): set --size\n", r->width,
                    r->height, VRG_SSIM_WINDOW, VRG_SSIM_WINDOW);
            rc = -1;
        }
    }
    vrg_graph_destroy(g);
    vrg_graph_destroy(first);
    return rc;
}

/* ---- the reference, cached (ref_cache.c) ---- */

static void progress(const char *what, uint32_t done, uint32_t total, int tty)
{
    if (!tty && done != total)
        return;
    int bar = total ? (int)(30.0 * done / total) : 30;
    fprintf(stderr, "\r%-24.24s [%.*s%*s] %u/%u", what, bar, "##############################", 30 - bar, "", done, total);
    if (done == total)
        fputc('\n', stderr);
}

/* rgb8 -> floats in [0, 1] */
static void to_float(const uint8_t *rgb, size_t n, float *out)
{
    for (size_t i = 0; i < n * 3; i++)
        out[i] = rgb[i] / 255.0f;
}

static void camera_at(const vrg_camera_path *path, const vrg_camera *fixed, double t, vrg_camera *out)
{
    *out = *fixed;
    if (path->count)
        vrg_camera_path_eval(path, (float)t, out);
}

static uint8_t *read_output(vrg_graph *g)
{
    vrg_image_data img;
    if (vrg_graph_read(g, vrg_graph_output(g), &img) != 0)
        return NULL;
    uint8_t *rgb = vrg_image_rgb8(&img);
    free(img.pixels);
    return rgb;
}

/* A moving sun (the scene's day_length > 0), held where the candidates
 * see it: the reference's clock runs `subframes` times as fast (frame
 * index k * subframes) and would run on during the accumulation, so its
 * clock is stopped and its time of day set per frame. */
typedef struct sun_clock {
    double start_hours, day_length; /* day_length 0: no moving sun */
} sun_clock;

static int stop_sun(vrg_graph *g, sun_clock *sun)
{
    sun->day_length = 0;
    if (vrg_graph_get_param(g, "scene.day_length", &sun->day_length) != 0 || sun->day_length <= 0) {
        sun->day_length = 0; /* none, or a scene without one */
        return 0;
    }
    return vrg_graph_get_param(g, "scene.time_of_day", &sun->start_hours) != 0 || vrg_graph_set_param(g, "scene.day_length", 0) != 0 ? -1 : 0;
}

/* the time of day the candidates' sun shows at t seconds */
static int set_sun(vrg_graph *g, const sun_clock *sun, double t)
{
    if (!sun->day_length)
        return 0;
    return vrg_graph_set_param(g, "scene.time_of_day", fmod(sun->start_hours + 24.0 * t / sun->day_length, 24.0));
}

/* The reference at every frame: each rendered on its own (history reset,
 * frame index k * subframes) so a frame is alike whether cached or not. */
static int reference_frames(vrg_context *ctx, const options *o, const vrg_camera_path *path, const vrg_camera *fixed, double frame_s,
                            uint8_t **ref, vrg_cmp_result *r, int tty)
{
    char dir[VRG_CLI_PATH], key[VRG_REF_KEY_HEX];
    vrg_ref_cache cache = {0};
    /* the key's overrides: the --ref-sets, then a case's scene (as load() applies them) */
    const char **sets = malloc(sizeof *sets * (size_t)(o->ref_set_count + o->scene_count + 1));
    int set_count = 0;
    for (int i = 0; sets && i < o->ref_set_count; i++)
        sets[set_count++] = o->ref_sets[i];
    for (int i = 0; sets && i < o->scene_count; i++)
        sets[set_count++] = o->scene[i];
    /* the key's files: those of the graph loaded as the check phase did */
    vrg_graph *g = sets ? load(NULL, o->reference, o->ref_sets, o->ref_set_count, o) : NULL;
    int rc = g ? vrg_ref_cache_open(&cache, vrg_ref_cache_dir(o->cache, dir, sizeof dir), o->reference, g, sets, set_count, vrg_context_device(ctx),
                                    r->width, r->height)
               : -1, cache_bad = rc != 0;
    free(sets);
    vrg_graph_destroy(g);
    g = NULL;
    sun_clock sun = {0};
    for (uint32_t k = 0; k < o->frames && rc == 0; k++) {
        vrg_camera cam;
        uint32_t index = o->start + k; /* the path's frame */
        camera_at(path, fixed, index * frame_s, &cam);
        vrg_ref_cache_key(&cache, index, index * frame_s, &cam, key);
        int cached = vrg_ref_cache_read(&cache, key, r->width, r->height, &ref[k]);
        if (cached < 0) {
            rc = -1, cache_bad = 1;
            break;
        }
        if (cached == 0) {
            r->reference_cached++;
            progress("reference (cached)", k + 1, o->frames, tty);
            continue;
        }
        if (!g && (!(g = load(ctx, o->reference, o->ref_sets, o->ref_set_count, o)) || stop_sun(g, &sun) != 0)) {
            rc = -1;
            break;
        }
        uint32_t sub = vrg_graph_subframes(g);
        vrg_graph_set_frame_index(g, (uint64_t)index * sub);
        if (set_sun(g, &sun, index * frame_s) != 0) {
            rc = -1;
            break;
        }
        vrg_graph_set_camera(g, &cam);
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            rc = vrg_graph_frame(g);
        if (rc == 0 && !(ref[k] = read_output(g)))
            rc = -1;
        if (rc == 0)
            vrg_ref_cache_write(&cache, key, g, ref[k], r->width, r->height);
        progress("reference", k + 1, o->frames, tty);
    }
    vrg_graph_destroy(g);
    vrg_ref_cache_close(&cache);
    if (rc != 0 && !cache_bad)
        fprintf(stderr, "\nerror: the reference %s failed to render\n", o->reference);
    return rc;
}

/* ---- candidates ---- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* mean and 95th percentile (nearest rank) of v[0..n) */
static void mean_p95(const double *v, uint32_t n, double *mean, double *p95)
{
    double *s = malloc(sizeof(double) * (n ? n : 1)), sum = 0;
    for (uint32_t i = 0; i < n; i++)
        sum += s[i] = v[i];
    qsort(s, n, sizeof *s, cmp_double);
    *mean = n ? sum / n : 0;
    *p95 = n ? s[(uint32_t)ceil(0.95 * n) - 1] : 0;
    free(s);
}

static int shown_slot(const vrg_cmp_result *r, uint32_t k)
{
    for (int i = 0; i < r->shown_count; i++)
        if (r->shown[i] == (int)k)
            return i;
    return -1;
}

/* frame k's GPU ms per pass and their sum (ms[k * (np + 1) + np]) */
static void record_ms(vrg_graph *g, uint32_t np, uint32_t k, double *ms)
{
    double total = 0;
    for (uint32_t i = 0; i < np; i++) {
        double v = vrg_graph_pass_ms(g, i);
        ms[k * (np + 1) + i] = v > 0 ? v : 0;
        total += v > 0 ? v : 0;
    }
    ms[k * (np + 1) + np] = total;
}

/* Frame k's scores from the device (and its FLIP map where the report shows it). */
static int collect_scores(vrg_device_scorer *s, vrg_cmp_candidate *c, vrg_cmp_result *r, uint32_t k)
{
    int slot = shown_slot(r, k);
    float *map = slot >= 0 ? (c->flip_map[slot] = malloc(sizeof(float) * r->width * r->height)) : NULL;
    vrg_device_scores d;
    if (vrg_device_score_collect(s, map, &d) != 0)
        return -1;
    c->per_frame[VRG_CMP_PSNR][k] = d.psnr;
    c->per_frame[VRG_CMP_SSIM][k] = d.ssim;
    c->per_frame[VRG_CMP_FLIP][k] = d.flip;
    c->per_frame[VRG_CMP_TEMPORAL][k] = d.temporal;
    return 0;
}

/* --score device, frame k just submitted: collects the sums of the frame
 * before (its scoring ran before this frame on the queue), queues frame k's
 * scoring (voxrg/device_score.h), and reads frame k back only where the
 * report shows it (and writes only those to frames/). */
static int score_on_device(vrg_device_scorer *s, vrg_graph *g, vrg_cmp_candidate *c, vrg_cmp_result *r, const uint8_t *ref, uint32_t k,
                           const char *frames_dir, int64_t *pending)
{
    if (*pending >= 0 && collect_scores(s, c, r, (uint32_t)*pending) != 0)
        return *pending = -1, -1;
    int slot = shown_slot(r, k);
    *pending = -1;
    if (vrg_device_score_submit(s, g, NULL, ref, slot >= 0) != 0)
        return -1;
    *pending = k;
    if (slot < 0)
        return 0;
    char file[VRG_CLI_PATH + VRG_CLI_PATH];
    snprintf(file, sizeof file, "%s/%s-%05u.png", frames_dir, c->name, k);
    if (!(c->shown[slot] = read_output(g)))
        return -1;
    return vrg_png_write_rgb8(file, c->shown[slot], r->width, r->height); /* says why it failed, naming the file */
}

static int render_candidate(vrg_context *ctx, const options *o, const job *j, vrg_cmp_candidate *c, const vrg_camera_path *path,
                            const vrg_camera *fixed, double frame_s, uint8_t *const *ref, vrg_cmp_result *r, const char *frames_dir, int tty,
                            vrg_device_scorer *scorer)
{
    vrg_graph *g = load(ctx, j->graph, j->sets, j->set_count, o);
    if (!g)
        return -1;
    size_t n = (size_t)r->width * r->height;
    float *cur = malloc(sizeof(float) * n * 3), *prev = malloc(sizeof(float) * n * 3);
    float *refc = malloc(sizeof(float) * n * 3), *refp = malloc(sizeof(float) * n * 3);
    uint32_t np = vrg_graph_pass_count(g) < VRG_CMP_MAX_PASSES ? vrg_graph_pass_count(g) : VRG_CMP_MAX_PASSES;
    double *ms = calloc((size_t)o->frames * (np + 1), sizeof *ms);
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        c->per_frame[m] = calloc(o->frames, sizeof(double));
    uint32_t sub = vrg_graph_subframes(g);
    /* the path's frame, as the reference's: the same simulated time (a moving sun) */
    if (o->start)
        vrg_graph_set_frame_index(g, (uint64_t)o->start * sub);
    sun_clock sun = {0}; /* a graph that accumulates runs its clock fast, as the reference's */
    int rc = sub > 1 ? stop_sun(g, &sun) : 0, written = 1;
    /* Each frame is scored and written as it comes, so memory holds no
     * more than two frames of a candidate whatever the frame count; on a
     * CPU device (lavapipe) the scoring between frames evicts caches the
     * next frame runs in (docs/compare.md, "GPU time"). */
    int64_t pending = -1; /* --score device: the frame whose sums are still to collect */
    if (scorer)
        vrg_device_scorer_restart(scorer);
    for (uint32_t k = 0; k < o->frames && rc == 0; k++) {
        vrg_camera cam;
        camera_at(path, fixed, (o->start + k) * frame_s, &cam);
        vrg_graph_set_camera(g, &cam);
        if ((rc = set_sun(g, &sun, (o->start + k) * frame_s)) != 0)
            break;
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            rc = vrg_graph_frame(g);
        if (scorer) {
            rc = rc ? rc : score_on_device(scorer, g, c, r, ref[k], k, frames_dir, &pending);
            if (rc == 0)
                record_ms(g, np, k, ms), progress(c->name, k + 1, o->frames, tty);
            continue;
        }
        uint8_t *rgb = NULL;
        if (rc == 0 && !(rgb = read_output(g)))
            rc = -1;
        if (rc != 0)
            break;
        record_ms(g, np, k, ms);
        char file[VRG_CLI_PATH + VRG_CLI_PATH];
        snprintf(file, sizeof file, "%s/%s-%05u.png", frames_dir, c->name, k);
        rc = vrg_png_write_rgb8(file, rgb, r->width, r->height); /* says why it failed, naming the file */
        written = rc == 0;
        to_float(rgb, n, cur);
        to_float(ref[k], n, refc);
        c->per_frame[VRG_CMP_PSNR][k] = vrg_metric_psnr(cur, refc, r->width, r->height);
        c->per_frame[VRG_CMP_SSIM][k] = vrg_metric_ssim(cur, refc, r->width, r->height);
        int slot = shown_slot(r, k);
        float *map = slot >= 0 ? (c->flip_map[slot] = malloc(sizeof(float) * n)) : NULL;
        c->per_frame[VRG_CMP_FLIP][k] = vrg_metric_flip(cur, refc, r->width, r->height, map);
        c->per_frame[VRG_CMP_TEMPORAL][k] = k ? vrg_metric_temporal(cur, prev, refc, refp, r->width, r->height) : NAN;
        if (slot >= 0)
            c->shown[slot] = rgb;
        else
            free(rgb);
        float *t = prev;
        prev = cur, cur = t;
        t = refp;
        refp = refc, refc = t;
        progress(c->name, k + 1, o->frames, tty);
    }
    if (pending >= 0 && collect_scores(scorer, c, r, (uint32_t)pending) != 0)
        rc = -1;
    if (rc == 0) { /* timings from warmup on */
        uint32_t from = o->warmup, count = o->frames - from;
        double *v = malloc(sizeof(double) * count);
        for (uint32_t i = 0; i <= np; i++) {
            for (uint32_t k = 0; k < count; k++)
                v[k] = ms[(from + k) * (np + 1) + i];
            double mean, p95;
            mean_p95(v, count, &mean, &p95);
            if (i == np)
                c->gpu_mean_ms = mean, c->gpu_p95_ms = p95;
            else if (!vrg_graph_pass_culled(g, vrg_graph_pass_name(g, i)) && vrg_graph_pass_ms(g, i) >= 0) {
                vrg_cmp_pass *p = &c->passes[c->pass_count++];
                snprintf(p->name, sizeof p->name, "%s", vrg_graph_pass_name(g, i));
                p->mean_ms = mean, p->p95_ms = p95;
            }
        }
        free(v);
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            double sum = 0;
            uint32_t cnt = 0;
            for (uint32_t k = from; k < o->frames; k++)
                if (!isnan(c->per_frame[m][k]))
                    sum += c->per_frame[m][k], cnt++;
            c->summary[m] = cnt ? sum / cnt : NAN;
        }
    } else if (written)
        fprintf(stderr, "\nerror: candidate '%s' (%s) failed to render\n", c->name, j->graph);
    free(cur), free(prev), free(refc), free(refp), free(ms);
    vrg_graph_destroy(g);
    return rc;
}


/* the settings of case c: compare's options with the case's keys */
static options case_options(const options *o, const vrg_cmp_case_spec *spec)
{
    options co = *o;
    co.camera = spec->camera[0] ? spec->camera : NULL;
    co.start = spec->start, co.frames = spec->frames, co.warmup = spec->warmup;
    co.width = spec->width, co.height = spec->height;
    co.scene = spec->scene, co.scene_count = spec->scene_count;
    return co;
}

/* what a case needs to run, checked and loaded before any case runs */
typedef struct case_setup {
    vrg_camera fixed;
    double frame_s;
    vrg_camera_path path;
    char frames_dir[VRG_CLI_PATH];
} case_setup;

/* The run's work: one task per (case, candidate), case by case; the
 * tasks of a case share its reference frames (rendered, or taken from the
 * cache, when its first task comes), so a slice of the tasks can run on
 * its own. */
typedef vrg_cmp_task task;

/* the current case's reference frames, kept for scoring its candidates */
typedef struct case_frames {
    int case_index; /* -1: none yet */
    uint8_t **ref;
    uint32_t frames;
} case_frames;

/* The frames case r's report shows: the first frame after warmup, the
 * middle, the last; of a case file's case only the last, where history
 * has had the longest to go wrong, so that a report of many cases stays
 * readable. Every shard of a run picks the same. */
static void pick_shown(vrg_cmp_result *r)
{
    uint32_t picks[3] = {r->warmup, r->warmup + (r->frames - 1 - r->warmup) / 2, r->frames - 1};
    for (int i = r->case_name[0] ? 2 : 0; i < 3; i++)
        if (!r->shown_count || r->shown[r->shown_count - 1] != (int)picks[i])
            r->shown[r->shown_count++] = (int)picks[i];
}

/* The reference frames of case c, written to its frames folder. */
static int case_begin(vrg_context *ctx, const options *co, vrg_cmp_result *r, case_setup *cs, case_frames *cf, int c, int tty)
{
    r->device = vrg_context_device(ctx)->name;
    if (r->case_name[0])
        fprintf(stderr, "case %s\n", r->case_name);
    cf->case_index = c;
    cf->frames = co->frames;
    cf->ref = calloc(co->frames, sizeof *cf->ref);
    int rc = cf->ref ? reference_frames(ctx, co, &cs->path, &cs->fixed, cs->frame_s, cf->ref, r, tty) : -1;
    char file[VRG_CLI_PATH + 32];
    for (uint32_t k = 0; rc == 0 && k < co->frames; k++) {
        snprintf(file, sizeof file, "%s/reference-%05u.png", cs->frames_dir, k);
        rc = vrg_png_write_rgb8(file, cf->ref[k], r->width, r->height);
    }
    return rc;
}

/* The end of a case: after its tasks succeeded (rc 0) its part of the
 * report goes to `sections` (a shard's: its FLIP maps to frames_dir, for
 * the merge's report); then its frames are freed. */
static int case_end(case_frames *cf, vrg_cmp_result *r, FILE *sections, const char *frames_dir, int rc)
{
    for (int s = 0; rc == 0 && s < r->shown_count; s++)
        r->reference_shown[s] = cf->ref[r->shown[s]], cf->ref[r->shown[s]] = NULL;
    for (uint32_t k = 0; cf->ref && k < cf->frames; k++)
        free(cf->ref[k]);
    free(cf->ref);
    cf->ref = NULL;
    cf->case_index = -1;
    if (rc == 0 && (sections ? vrg_cmp_report_case(sections, r) : vrg_cmp_shard_write_maps(frames_dir, r)) != 0)
        rc = -1;
    vrg_cmp_free_shown(r);
    return rc;
}

/* Runs tasks[0..n): each case's reference frames when its first task
 * comes, each candidate scored as it renders. `sections` NULL: a shard's. */
static int run_tasks(vrg_context *ctx, const options *o, const vrg_cmp_case_spec *specs, job *jobs, vrg_cmp_run *run, case_setup *setups,
                     const task *tasks, int n, FILE *sections, int tty)
{
    case_frames cf = {.case_index = -1};
    int rc = 0;
    vrg_device_scorer *scorer = NULL; /* --score device: for this size */
    uint32_t scorer_size[2] = {0, 0};
    for (int t = 0; t < n && rc == 0; t++) {
        int c = tasks[t].case_index, i = tasks[t].candidate;
        vrg_cmp_result *r = &run->cases[c];
        options co = case_options(o, &specs[c]);
        if (cf.case_index != c) {
            if (cf.case_index >= 0)
                rc = case_end(&cf, &run->cases[cf.case_index], sections, setups[cf.case_index].frames_dir, rc);
            if (rc == 0)
                rc = case_begin(ctx, &co, r, &setups[c], &cf, c, tty);
        }
        if (rc == 0 && o->score_device && (scorer_size[0] != r->width || scorer_size[1] != r->height)) {
            vrg_device_scorer_destroy(scorer);
            scorer = NULL;
            rc = vrg_device_scorer_create(ctx, r->width, r->height, &scorer);
            scorer_size[0] = r->width, scorer_size[1] = r->height;
        }
        if (rc == 0)
            rc = render_candidate(ctx, &co, &jobs[i], &r->cand[i], &setups[c].path, &setups[c].fixed, setups[c].frame_s, cf.ref, r,
                                  setups[c].frames_dir, tty, scorer);
    }
    vrg_device_scorer_destroy(scorer);
    return cf.case_index >= 0 ? case_end(&cf, &run->cases[cf.case_index], sections, setups[cf.case_index].frames_dir, rc) : rc;
}

/* --baseline: a candidate's name; its index, or -1 after a usage error */
static int find_baseline(const options *o, const vrg_cmp_result *r)
{
    if (!o->baseline)
        return 0;
    for (int i = 0; i < r->count; i++)
        if (!strcmp(r->cand[i].name, o->baseline))
            return i;
    fprintf(stderr, "error: --baseline %s: no candidate of that name; the candidates are", o->baseline);
    for (int i = 0; i < r->count; i++)
        fprintf(stderr, "%s %s", i ? "," : "", r->cand[i].name);
    fprintf(stderr, "\n%s", vrg_cli_compare_usage);
    return -1;
}

/* The run's cases (the case file's, or one from the options) with their
 * candidates named and each case checked and its camera path loaded:
 * every error before any rendering. 0, -1 (error) or 2 (usage). */
static int set_up(options *o, vrg_cmp_case_spec *specs, int spec_count, job **jobs, vrg_cmp_run *run, case_setup **setups)
{
    int count = o->graph_count + o->variant_count;
    *jobs = calloc((size_t)count, sizeof **jobs);
    run->cases = calloc((size_t)spec_count, sizeof *run->cases);
    *setups = calloc((size_t)spec_count, sizeof **setups);
    if (!*jobs || !run->cases || !*setups)
        return -1;
    run->case_count = spec_count;
    for (int c = 0; c < spec_count; c++)
        if (!(run->cases[c].cand = calloc((size_t)count, sizeof *run->cases[c].cand)))
            return -1;
    int rc = make_jobs(o, *jobs, &run->cases[0]);
    if (rc != 0)
        return rc;
    if ((run->baseline = find_baseline(o, &run->cases[0])) < 0)
        return 2;
    for (int c = 0; c < spec_count; c++) {
        vrg_cmp_result *r = &run->cases[c];
        options co = case_options(o, &specs[c]);
        for (int i = 0; c && i < count; i++) { /* the same candidates in every case */
            vrg_cmp_candidate *d = &r->cand[i], *s = &run->cases[0].cand[i];
            memcpy(d->name, s->name, sizeof d->name), memcpy(d->graph, s->graph, sizeof d->graph);
            memcpy(d->overrides, s->overrides, sizeof d->overrides), d->base = s->base;
        }
        r->count = count;
        snprintf(r->case_name, sizeof r->case_name, "%s", specs[c].name);
        for (int i = 0, n = 0; i < co.scene_count && n < (int)sizeof r->scene; i++)
            n += snprintf(r->scene + n, sizeof r->scene - (size_t)n, "%s%s", i ? "," : "", co.scene[i]);
        r->reference = o->reference;
        r->camera = co.camera;
        r->frames = co.frames, r->warmup = co.warmup, r->start = co.start;
        pick_shown(r);
        for (int i = 0, n = 0; i < o->ref_set_count && n < (int)sizeof r->reference_overrides; i++)
            n += snprintf(r->reference_overrides + n, sizeof r->reference_overrides - (size_t)n, "%s%s", i ? "," : "", o->ref_sets[i]);
        case_setup *cs = &(*setups)[c];
        if (r->case_name[0] && check_all(&co, *jobs, r, &cs->fixed, &cs->frame_s) != 0) {
            fprintf(stderr, "%s:%d: error: [case %s]: the graphs do not load, or differ, with its settings (above)\n", o->cases, specs[c].line,
                    r->case_name);
            return -1;
        }
        if (!r->case_name[0] && check_all(&co, *jobs, r, &cs->fixed, &cs->frame_s) != 0)
            return -1;
        if (co.camera && vrg_camera_path_load(co.camera, &cs->path, stderr) != 0)
            return -1;
        snprintf(cs->frames_dir, sizeof cs->frames_dir, "%s/frames%s%s", o->out, r->case_name[0] ? "/" : "", r->case_name);
    }
    return 0;
}

int vrg_cli_compare(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--merge"))
            return vrg_cmp_merge(argc, argv, vrg_cli_compare_usage);
    options o;
    int rc = parse_options(argc, argv, &o);
    if (rc || o.help) {
        free(o.graphs), free(o.variants), free(o.grids);
        return rc ? rc : (fputs(vrg_cli_compare_usage, stdout), 0);
    }
    vrg_cmp_case_spec *specs = NULL, one = {.start = o.start, .frames = o.frames, .warmup = o.warmup, .width = o.width, .height = o.height};
    int spec_count = 1;
    if (o.camera)
        snprintf(one.camera, sizeof one.camera, "%s", o.camera);
    vrg_cmp_run run = {.cases_file = o.cases, .score_device = o.score_device};
    job *jobs = NULL;
    case_setup *setups = NULL;
    vrg_context *ctx = NULL;
    FILE *sections = NULL;
    char file[VRG_CLI_PATH], cache[VRG_CLI_PATH];
    static const char *outputs[] = {"report.html", "metrics.json", "metrics.csv", VRG_CMP_SHARD_FILE};
    if (!(o.diag = vrg_cli_warnings_once(stderr))) {
        fprintf(stderr, "error: out of memory\n");
        rc = 1;
    } else if (access(o.reference, R_OK) != 0) {
        fprintf(stderr, "error: reference graph %s: %s\n", o.reference, strerror(errno));
        rc = 1;
    } else if (expand_grids(&o) != 0)
        rc = 2;
    else if (o.cases && vrg_cmp_cases_load(o.cases, &specs, &spec_count) != 0)
        rc = 1;
    if (rc)
        goto done;
    for (int i = 0; i < 4; i++) { /* nothing of an earlier report may pass for this run's, failed or not */
        snprintf(file, sizeof file, "%s/%s", o.out, outputs[i]);
        remove(file);
    }
    if ((rc = set_up(&o, specs ? specs : &one, spec_count, &jobs, &run, &setups)) != 0) {
        rc = rc > 0 ? rc : 1;
        goto done;
    }
    rc = vrg_cli_out_dir(o.out) != 0 || vrg_cli_out_dir(vrg_ref_cache_dir(o.cache, cache, sizeof cache)) != 0;
    snprintf(file, sizeof file, "%s/frames", o.out);
    rc = rc || vrg_cli_out_dir(file) != 0;
    for (int c = 0; c < spec_count && !rc; c++)
        rc = vrg_cli_out_dir(setups[c].frames_dir) != 0;
    vrg_context_desc cd = {.validate = o.validate, .device = o.device};
    if (rc || (!o.shards && !(sections = tmpfile())) || vrg_context_create(&cd, &ctx) != 0) {
        rc = 1;
        goto done;
    }
    /* the whole run's tasks, or a shard's slice of them */
    int count = run.cases[0].count, task_count = spec_count * count, first = 0, n = task_count;
    if (o.shards)
        vrg_cmp_shard_tasks(task_count, o.shard, o.shards, &first, &n);
    task *tasks = malloc(sizeof *tasks * (size_t)(n ? n : 1));
    for (int t = 0; tasks && t < n; t++)
        tasks[t] = (task){.case_index = (first + t) / count, .candidate = (first + t) % count};
    rc = tasks ? run_tasks(ctx, &o, specs ? specs : &one, jobs, &run, setups, tasks, n, sections, isatty(2)) : -1;
    uint32_t errors = vrg_context_validation_errors(ctx);
    if (errors) {
        fprintf(stderr, "error: %u validation message%s (see above)\n", errors, errors == 1 ? "" : "s");
        rc = 1;
    }
    if (rc == 0 && o.shards) {
        rc = vrg_cmp_shard_write(o.out, &run, o.shard, o.shards, vrg_context_device(ctx)->name, tasks, n) ? 1 : 0;
        if (rc == 0 && n)
            printf("shard %d of %d: tasks %d to %d of %d; wrote %s/" VRG_CMP_SHARD_FILE " and frames/\n", o.shard, o.shards, first, first + n - 1,
                   task_count, o.out);
        else if (rc == 0)
            printf("shard %d of %d: none of the %d tasks (more shards than tasks); wrote %s/" VRG_CMP_SHARD_FILE "\n", o.shard, o.shards,
                   task_count, o.out);
    } else if (rc == 0) {
        snprintf(file, sizeof file, "%s/report.html", o.out);
        rc = vrg_cmp_judge(&run) || vrg_cmp_write_metrics(o.out, &run) || vrg_cmp_write_report(file, &run, sections) ? 1 : 0;
        if (rc == 0) {
            vrg_cmp_print(&run);
            printf("wrote %s/report.html, metrics.json, metrics.csv and frames/\n", o.out);
        }
    }
    free(tasks);
    if (rc != 0) {
        for (int i = 0; i < 4; i++) { /* a failed run leaves no report */
            snprintf(file, sizeof file, "%s/%s", o.out, outputs[i]);
            remove(file);
        }
        rc = 1;
    }
done:
    if (sections)
        fclose(sections);
    if (o.diag)
        fclose(o.diag);
    for (int c = 0; setups && c < spec_count; c++)
        vrg_camera_path_free(&setups[c].path);
    free(setups);
    vrg_cmp_run_free(&run);
    free(jobs);
    vrg_cmp_cases_free(specs, specs ? spec_count : 0);
    for (int v = o.variant_count_given; v < o.variant_count; v++)
        free((char *)o.variants[v]);
    free(o.graphs), free(o.variants), free(o.grids);
    if (ctx) {
        vrg_cli_exit_if_gpu_busy(ctx, rc);
        vrg_context_destroy(ctx);
    }
    return rc;
}
