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
#include "compare_result.h"
#include "report.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "voxrg/camera_path.h"
#include "voxrg/metrics.h"
#include "voxrg/voxrg.h"

#define MAX_SETS 64
#define MAX_GRAPHS 8
#define RESERVED_NAME "reference" /* frames/reference-NNNNN.png */

const char *const vrg_cli_compare_usage =
    "usage: voxrg compare A.ini [B.ini ...] --reference REF.ini [--variant NAME[@GRAPH]:PASS.PARAM=VALUE,...]...\n"
    "                     [--camera PATH] [--start N] [--frames N] [--size WxH] [--warmup N] [--out DIR]\n"
    "                     [--ref-set PASS.PARAM=VALUE]... [--cache DIR] [--validate] [--device NAME|INDEX]\n"
    "Renders every candidate (each graph, and each --variant: the graph GRAPH names, a\n"
    "listed graph's candidate name, path or file name, else the first graph, with those\n"
    "parameters) and the reference on the same frames: same world, camera path, seeds\n"
    "and size. The reference is rendered converged at each path frame and cached in\n"
    "DIR (default $XDG_CACHE_HOME/voxrg/reference), keyed by its graph, parameters,\n"
    "size, frame and camera, and checked against its plugins' and shaders' files.\n"
    "Measures each candidate frame against the reference frame: PSNR, SSIM (luma,\n"
    "11x11 Gaussian), LDR-FLIP and temporal error |(D_t - D_t-1) - (R_t - R_t-1)|,\n"
    "and per-pass GPU ms (mean, p95). Frames before --warmup (default 5) are shown but\n"
    "left out of the summary. Writes DIR/report.html, metrics.csv, metrics.json and\n"
    "frames/*.png (default DIR: compare). --frames defaults to 30, --camera to the\n"
    "first graph's [camera]; --start N begins at the path's frame N (at the graph's\n"
    "fps; warm-up counts from there); --ref-set changes the reference (e.g. fewer samples:\n"
    "converge.samples_per_frame=64). Graphs whose scene, seed, fps or size differ are\n"
    "an error.\n";

typedef struct options {
    const char *graphs[MAX_GRAPHS];
    int graph_count;
    const char *variants[VRG_CMP_MAX_CANDIDATES];
    int variant_count;
    const char *reference, *camera, *out, *cache, *device;
    const char *ref_sets[MAX_SETS];
    int ref_set_count;
    uint32_t width, height, frames, warmup, start;
    int validate, help;
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

/* A variant's name becomes part of file names under --out
 * (frames/NAME-NNNNN.png) and a CSV field: no path separators, no
 * hidden names, nothing to quote, and not the reference's frames' name. */
static int variant_name_ok(const char *name, size_t len)
{
    if (len < 1 || len > 63 || name[0] == '.' || name[len - 1] == '.')
        return 0;
    for (size_t i = 0; i < len; i++)
        if (!isalnum((unsigned char)name[i]) && !strchr("_-.", name[i]))
            return 0;
    return !(len == strlen(RESERVED_NAME) && !strncmp(name, RESERVED_NAME, len));
}

static int parse_options(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->frames = 30;
    o->warmup = 5;
    o->out = "compare";
    int warmup_given = 0;
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
        if (a[0] != '-') {
            if (o->graph_count == MAX_GRAPHS)
                return usage_error("at most %s graphs", "8");
            o->graphs[o->graph_count++] = a;
            continue;
        }
        if (!next)
            return usage_error("%s needs a value", a);
        i++;
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
        else if (!strcmp(a, "--variant")) {
            /* a name has neither '@' nor ':', so whichever comes first ends it */
            size_t name_len = strcspn(next, "@:");
            const char *colon = strchr(next + name_len, ':');
            if (!colon || !name_len || !colon[1] || (next[name_len] == '@' && colon == next + name_len + 1))
                return usage_error("--variant '%s': expected NAME[@GRAPH]:PASS.PARAM=VALUE[,...]", next);
            if (!variant_name_ok(next, name_len))
                return usage_error("--variant '%s': a name is 1 to 63 of A-Z a-z 0-9 _ - and dots (not first or last), "
                                   "and not 'reference'", next);
            if (o->variant_count == VRG_CMP_MAX_CANDIDATES)
                return usage_error("too many --variant options (at most %s)", "16");
            o->variants[o->variant_count++] = next;
        } else if (!strcmp(a, "--ref-set")) {
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

static vrg_graph *load(vrg_context *ctx, const char *graph, const char *const *sets, int set_count, const options *o)
{
    vrg_graph_desc d = {.path = graph, .overrides = sets, .override_count = (uint32_t)set_count, .width = o->width, .height = o->height};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        vrg_graph_destroy(g);
        return NULL;
    }
    return g;
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
        if (n == VRG_CMP_MAX_CANDIDATES) {
            fprintf(stderr, "error: at most %d candidates\n", VRG_CMP_MAX_CANDIDATES);
            return -1;
        }
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

/* ---- the reference, cached ---- */

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

typedef struct manifest {
    FILE *f;
    int stale; /* while checking: a file differs */
} manifest;

/* deps file lines: "SIZE MTIME_NS PATH" of every file the frame came from */
static void write_dep(void *user, const char *path)
{
    struct stat st;
    if (stat(path, &st) == 0)
        fprintf(((manifest *)user)->f, "%lld %lld %s\n", (long long)st.st_size,
                (long long)st.st_mtim.tv_sec * 1000000000ll + st.st_mtim.tv_nsec, path);
}

static int deps_current(const char *deps_path)
{
    FILE *f = vrg_fopen_regular(deps_path, "r");
    if (!f)
        return 0;
    char line[2200];
    int ok = 1, lines = 0;
    while (ok && fgets(line, sizeof line, f)) {
        long long size, mtime;
        char path[2048];
        struct stat st;
        line[strcspn(line, "\n")] = '\0';
        ok = sscanf(line, "%lld %lld %2047[^\n]", &size, &mtime, path) == 3 && stat(path, &st) == 0 && st.st_size == size &&
             (long long)st.st_mtim.tv_sec * 1000000000ll + st.st_mtim.tv_nsec == mtime;
        lines++;
    }
    fclose(f);
    return ok && lines > 0;
}

/* --cache, or the user's cache folder */
static const char *cache_dir(const options *o, char *buf, size_t cap)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (o->cache)
        snprintf(buf, cap, "%s", o->cache);
    else if (xdg && *xdg)
        snprintf(buf, cap, "%s/voxrg/reference", xdg);
    else
        snprintf(buf, cap, "%s/.cache/voxrg/reference", home && *home ? home : "/tmp");
    return buf;
}

/* A cache entry is a regular file or absent: anything else under its name
 * (a FIFO would block the reader, and the writer, for ever) is an error
 * naming it. */
static int cache_entry_ok(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return 0;
    fprintf(stderr, "error: the reference cache's %s is not a regular file: remove it\n", path);
    return -1;
}

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

/* The reference at every frame: each rendered on its own (history reset,
 * frame index k * subframes) so a frame is alike whether cached or not. */
static int reference_frames(vrg_context *ctx, const options *o, const vrg_camera_path *path, const vrg_camera *fixed, double frame_s,
                            uint8_t **ref, vrg_cmp_result *r, int tty)
{
    char cache[VRG_CLI_PATH], file[VRG_CLI_PATH], deps[VRG_CLI_PATH];
    cache_dir(o, cache, sizeof cache); /* checked writable before any work */
    char *text = vrg_cli_read_text(o->reference);
    if (!text) {
        fprintf(stderr, "error: cannot read %s: %s\n", o->reference, vrg_open_strerror(errno));
        return -1;
    }
    uint64_t base = fnv(1469598103934665603ull, text, strlen(text));
    free(text);
    for (int i = 0; i < o->ref_set_count; i++)
        base = fnv(base, o->ref_sets[i], strlen(o->ref_sets[i]) + 1);
    base = fnv(base, &r->width, sizeof r->width);
    base = fnv(base, &r->height, sizeof r->height);
    vrg_graph *g = NULL;
    int rc = 0, cache_bad = 0;
    for (uint32_t k = 0; k < o->frames && rc == 0; k++) {
        vrg_camera cam;
        uint32_t index = o->start + k; /* the path's frame */
        camera_at(path, fixed, index * frame_s, &cam);
        uint64_t key = fnv(fnv(base, &index, sizeof index), cam.position, sizeof cam.position);
        key = fnv(fnv(fnv(key, &cam.yaw, sizeof cam.yaw), &cam.pitch, sizeof cam.pitch), &cam.fov_y, sizeof cam.fov_y);
        snprintf(file, sizeof file, "%s/%016llx.png", cache, (unsigned long long)key);
        snprintf(deps, sizeof deps, "%s/%016llx.deps", cache, (unsigned long long)key);
        if (cache_entry_ok(file) != 0 || cache_entry_ok(deps) != 0) {
            rc = -1, cache_bad = 1;
            break;
        }
        uint32_t w, h;
        if (deps_current(deps) && vrg_png_read_rgb8(file, &ref[k], &w, &h) == 0) {
            if (w == r->width && h == r->height) {
                r->reference_cached++;
                progress("reference (cached)", k + 1, o->frames, tty);
                continue;
            }
            free(ref[k]);
            ref[k] = NULL;
        }
        if (!g && !(g = load(ctx, o->reference, o->ref_sets, o->ref_set_count, o))) {
            rc = -1;
            break;
        }
        uint32_t sub = vrg_graph_subframes(g);
        vrg_graph_set_frame_index(g, (uint64_t)index * sub);
        vrg_graph_set_camera(g, &cam);
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            rc = vrg_graph_frame(g);
        if (rc == 0 && !(ref[k] = read_output(g)))
            rc = -1;
        /* the PNG first, the deps (which make it valid) after */
        if (rc == 0 && vrg_png_write_rgb8(file, ref[k], r->width, r->height) == 0) {
            vrg_output *out = vrg_output_open(deps);
            if (out) { /* a cache entry that cannot be written is only not cached */
                manifest m = {.f = vrg_output_stream(out)};
                vrg_graph_sources(g, write_dep, &m);
                vrg_output_commit(out);
            }
        }
        progress("reference", k + 1, o->frames, tty);
    }
    vrg_graph_destroy(g);
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

static int render_candidate(vrg_context *ctx, const options *o, const job *j, vrg_cmp_candidate *c, const vrg_camera_path *path,
                            const vrg_camera *fixed, double frame_s, uint8_t *const *ref, vrg_cmp_result *r, const char *frames_dir, int tty)
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
    /* Every frame first, back to back, then the metrics and files: on a
     * CPU device the metrics computed between frames evicted the caches the
     * graph's next frame runs in, so the timings measured compare as much
     * as the graph (docs/compare.md). The frames are kept in memory, as the
     * reference's are. */
    uint8_t **frames = calloc(o->frames, sizeof *frames);
    int rc = frames ? 0 : -1, written = 1;
    for (uint32_t k = 0; k < o->frames && rc == 0; k++) {
        vrg_camera cam;
        camera_at(path, fixed, (o->start + k) * frame_s, &cam);
        vrg_graph_set_camera(g, &cam);
        for (uint32_t s = 0; s < sub && rc == 0; s++)
            rc = vrg_graph_frame(g);
        if (rc == 0 && !(frames[k] = read_output(g)))
            rc = -1;
        if (rc != 0)
            break;
        double total = 0;
        for (uint32_t i = 0; i < np; i++) {
            double v = vrg_graph_pass_ms(g, i);
            ms[k * (np + 1) + i] = v > 0 ? v : 0;
            total += v > 0 ? v : 0;
        }
        ms[k * (np + 1) + np] = total;
        progress(c->name, k + 1, o->frames, tty);
    }
    for (uint32_t k = 0; k < o->frames && rc == 0; k++) {
        uint8_t *rgb = frames[k];
        frames[k] = NULL;
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
        char what[112]; /* progress() shows 24 characters: the name last */
        snprintf(what, sizeof what, "scoring %s", c->name);
        progress(what, k + 1, o->frames, tty);
    }
    for (uint32_t k = 0; frames && k < o->frames; k++)
        free(frames[k]);
    free(frames);
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

/* ---- files ---- */

/* a number for JSON and CSV: NAN (no value) as null / empty */
static void num(FILE *f, double v, int json)
{
    if (isnan(v))
        fputs(json ? "null" : "", f);
    else
        fprintf(f, "%.9g", v);
}

/* a CSV field, quoted when it holds a separator, a quote or a line break
 * (RFC 4180): graph names come from file names, which may */
static void csv_field(FILE *f, const char *s)
{
    if (!s[strcspn(s, ",\"\r\n")]) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static int write_csv(const char *dir, const vrg_cmp_result *r)
{
    char final[VRG_CLI_PATH];
    snprintf(final, sizeof final, "%s/metrics.csv", dir);
    vrg_output *out = vrg_output_open(final);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    fprintf(f, "candidate,frame,warmup,psnr,ssim,flip,temporal\n");
    for (int i = 0; i < r->count; i++)
        for (uint32_t k = 0; k < r->frames; k++) {
            csv_field(f, r->cand[i].name);
            fprintf(f, ",%u,%d", k, k < r->warmup);
            for (int m = 0; m < VRG_CMP_METRICS; m++) {
                fputc(',', f);
                num(f, r->cand[i].per_frame[m][k], 0);
            }
            fputc('\n', f);
        }
    return vrg_output_commit(out);
}

static int write_json(const char *dir, const vrg_cmp_result *r)
{
    char final[VRG_CLI_PATH], e1[2100], e2[2100], e3[2100];
    snprintf(final, sizeof final, "%s/metrics.json", dir);
    vrg_output *out = vrg_output_open(final);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    fprintf(f, "{\n  \"reference\": {\"graph\": \"%s\", \"overrides\": \"%s\", \"frames_from_cache\": %u},\n",
            vrg_cli_json_str(r->reference, e1, sizeof e1), vrg_cli_json_str(r->reference_overrides, e2, sizeof e2), r->reference_cached);
    fprintf(f, "  \"camera\": %s%s%s,\n", r->camera ? "\"" : "", r->camera ? vrg_cli_json_str(r->camera, e1, sizeof e1) : "null",
            r->camera ? "\"" : "");
    fprintf(f, "  \"device\": \"%s\",\n  \"width\": %u,\n  \"height\": %u,\n  \"start\": %u,\n  \"frames\": %u,\n  \"warmup\": %u,\n",
            vrg_cli_json_str(r->device, e1, sizeof e1), r->width, r->height, r->start, r->frames, r->warmup);
    fprintf(f, "  \"psnr_cap_db\": %g,\n  \"candidates\": [", VRG_PSNR_MAX_DB);
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        fprintf(f, "%s\n    {\"name\": \"%s\", \"graph\": \"%s\", \"overrides\": \"%s\", ", i ? "," : "",
                vrg_cli_json_str(c->name, e1, sizeof e1), vrg_cli_json_str(c->graph, e2, sizeof e2),
                vrg_cli_json_str(c->overrides, e3, sizeof e3));
        /* the listed graph a variant changes, by its candidate name: two listings may share a path */
        if (c->base >= 0)
            fprintf(f, "\"variant_of\": \"%s\",\n      \"summary\": {", vrg_cli_json_str(r->cand[c->base].name, e1, sizeof e1));
        else
            fputs("\"variant_of\": null,\n      \"summary\": {", f);
        for (int m = 0; m < VRG_CMP_METRICS; m++) {
            fprintf(f, "\"%s\": ", vrg_cmp_metric_names[m]);
            num(f, c->summary[m], 1);
            fputs(", ", f);
        }
        fprintf(f, "\"gpu_ms_mean\": %.9g, \"gpu_ms_p95\": %.9g},\n      \"passes\": [", c->gpu_mean_ms, c->gpu_p95_ms);
        for (int p = 0; p < c->pass_count; p++)
            fprintf(f, "%s{\"name\": \"%s\", \"mean_ms\": %.9g, \"p95_ms\": %.9g}", p ? ", " : "",
                    vrg_cli_json_str(c->passes[p].name, e1, sizeof e1), c->passes[p].mean_ms, c->passes[p].p95_ms);
        fputs("],\n      \"frames\": [", f);
        for (uint32_t k = 0; k < r->frames; k++) {
            fprintf(f, "%s\n        {\"frame\": %u", k ? "," : "", k);
            for (int m = 0; m < VRG_CMP_METRICS; m++) {
                fprintf(f, ", \"%s\": ", vrg_cmp_metric_names[m]);
                num(f, c->per_frame[m][k], 1);
            }
            fputc('}', f);
        }
        fputs("\n      ]}", f);
    }
    fputs("\n  ]\n}\n", f);
    return vrg_output_commit(out);
}

static void print_summary(const vrg_cmp_result *r)
{
    printf("\n%u frames at %ux%u, summary from frame %u on; reference %s%s%s\n", r->frames, r->width, r->height, r->warmup, r->reference,
           r->reference_overrides[0] ? " with " : "", r->reference_overrides);
    printf("%-20s %11s %8s %8s %10s %10s %10s\n", "candidate", "PSNR dB", "SSIM", "FLIP", "temporal", "GPU ms", "p95 ms");
    int best[VRG_CMP_METRICS + 1];
    for (int m = 0; m < VRG_CMP_METRICS; m++)
        best[m] = vrg_cmp_best(r, m);
    best[VRG_CMP_METRICS] = vrg_cmp_best(r, -1);
    for (int i = 0; i < r->count; i++) {
        const vrg_cmp_candidate *c = &r->cand[i];
        printf("%-20.20s %10.2f%s %7.4f%s %7.4f%s %9.5f%s %9.2f%s %10.2f\n", c->name, c->summary[0], best[0] == i ? "*" : " ", c->summary[1],
               best[1] == i ? "*" : " ", c->summary[2], best[2] == i ? "*" : " ", c->summary[3], best[3] == i ? "*" : " ", c->gpu_mean_ms,
               best[4] == i ? "*" : " ", c->gpu_p95_ms);
    }
    printf("* best in the column\n");
}

static void free_result(vrg_cmp_result *r)
{
    for (int i = 0; i < r->count; i++) {
        for (int m = 0; m < VRG_CMP_METRICS; m++)
            free(r->cand[i].per_frame[m]);
        for (int s = 0; s < VRG_CMP_MAX_SHOWN; s++)
            free(r->cand[i].shown[s]), free(r->cand[i].flip_map[s]);
    }
}

int vrg_cli_compare(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o);
    if (rc || o.help)
        return rc ? rc : (fputs(vrg_cli_compare_usage, stdout), 0);
    if (access(o.reference, R_OK) != 0) {
        fprintf(stderr, "error: reference graph %s: %s\n", o.reference, strerror(errno));
        return 1;
    }
    static vrg_cmp_result r;
    static job jobs[VRG_CMP_MAX_CANDIDATES];
    memset(&r, 0, sizeof r);
    memset(jobs, 0, sizeof jobs);
    r.reference = o.reference;
    r.camera = o.camera;
    r.frames = o.frames;
    r.warmup = o.warmup;
    r.start = o.start;
    for (int i = 0, n = 0; i < o.ref_set_count; i++)
        n += snprintf(r.reference_overrides + n, sizeof r.reference_overrides - (size_t)n, "%s%s", i ? "," : "", o.ref_sets[i]);
    /* nothing of an earlier report may pass for this run's, failed or not */
    char frames_dir[VRG_CLI_PATH], file[VRG_CLI_PATH];
    snprintf(frames_dir, sizeof frames_dir, "%s/frames", o.out);
    static const char *outputs[] = {"report.html", "metrics.json", "metrics.csv"};
    for (int i = 0; i < 3; i++) {
        snprintf(file, sizeof file, "%s/%s", o.out, outputs[i]);
        remove(file);
    }
    vrg_camera fixed;
    double frame_s = 0;
    vrg_camera_path path = {0};
    if ((rc = make_jobs(&o, jobs, &r)) != 0)
        return rc > 0 ? rc : 1;
    if (check_all(&o, jobs, &r, &fixed, &frame_s) != 0)
        return 1;
    if (o.camera && vrg_camera_path_load(o.camera, &path, stderr) != 0)
        return 1;
    char cache[VRG_CLI_PATH];
    if (vrg_cli_out_dir(o.out) != 0 || vrg_cli_out_dir(frames_dir) != 0 || vrg_cli_out_dir(cache_dir(&o, cache, sizeof cache)) != 0) {
        vrg_camera_path_free(&path);
        return 1;
    }
    /* shown in the report: the first frame after warmup, the middle, the last */
    uint32_t picks[3] = {o.warmup, o.warmup + (o.frames - 1 - o.warmup) / 2, o.frames - 1};
    for (int i = 0; i < 3; i++)
        if (!r.shown_count || r.shown[r.shown_count - 1] != (int)picks[i])
            r.shown[r.shown_count++] = (int)picks[i];
    vrg_context *ctx = NULL;
    vrg_context_desc cd = {.validate = o.validate, .device = o.device};
    if (vrg_context_create(&cd, &ctx) != 0) {
        vrg_camera_path_free(&path);
        return 1;
    }
    r.device = vrg_context_device(ctx)->name;
    int tty = isatty(2);
    uint8_t **ref = calloc(o.frames, sizeof *ref);
    rc = reference_frames(ctx, &o, &path, &fixed, frame_s, ref, &r, tty);
    for (uint32_t k = 0; rc == 0 && k < o.frames; k++) {
        snprintf(file, sizeof file, "%s/reference-%05u.png", frames_dir, k);
        rc = vrg_png_write_rgb8(file, ref[k], r.width, r.height);
    }
    for (int i = 0; rc == 0 && i < r.count; i++)
        rc = render_candidate(ctx, &o, &jobs[i], &r.cand[i], &path, &fixed, frame_s, ref, &r, frames_dir, tty);
    for (int s = 0; rc == 0 && s < r.shown_count; s++)
        r.reference_shown[s] = ref[r.shown[s]], ref[r.shown[s]] = NULL;
    uint32_t errors = vrg_context_validation_errors(ctx);
    if (errors) {
        fprintf(stderr, "error: %u validation message%s (see above)\n", errors, errors == 1 ? "" : "s");
        rc = 1;
    }
    if (rc == 0) {
        snprintf(file, sizeof file, "%s/report.html", o.out);
        rc = write_csv(o.out, &r) || write_json(o.out, &r) || vrg_cmp_write_report(file, &r) ? 1 : 0;
    }
    if (rc == 0) {
        print_summary(&r);
        printf("wrote %s/report.html, metrics.json, metrics.csv and frames/\n", o.out);
    } else {
        for (int i = 0; i < 3; i++) { /* a failed run leaves no report */
            snprintf(file, sizeof file, "%s/%s", o.out, outputs[i]);
            remove(file);
        }
        rc = 1;
    }
    for (uint32_t k = 0; k < o.frames; k++)
        free(ref[k]);
    free(ref);
    for (int s = 0; s < r.shown_count; s++)
        free(r.reference_shown[s]);
    free_result(&r);
    vrg_camera_path_free(&path);
    vrg_cli_exit_if_gpu_busy(ctx, rc);
    vrg_context_destroy(ctx);
    return rc;
}
