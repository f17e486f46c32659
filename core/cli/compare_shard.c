/* Shards of `voxrg compare`: the slice of the tasks a shard runs, its
 * results file (shard.txt) and the merge of the shards' results into the
 * one report (docs/compare.md, "On a cluster").
 *
 * shard.txt is lines of space-separated tokens: the header, "shard I N",
 * the run's settings (lines "run ...", the same in every shard of a run),
 * the shard's device, then per task its timings, summary and per-frame
 * metrics, and "end". Numbers are %.17g, which reads back to the same
 * double; strings are "=" and their bytes, those up to space, '\\' and
 * DEL as \xHH; "-" is no string (no camera, no case file). */
#define _POSIX_C_SOURCE 200809L
#include "compare_shard.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "compare_files.h"
#include "report.h"
#include "util.h"
#include "voxrg/output.h"
#include "voxrg/png.h"

#define MAGIC "voxrg-compare-shard 1"
static const char *const merge_outputs[] = {"report.html", "metrics.json", "metrics.csv"};

void vrg_cmp_shard_tasks(int count, int shard, int shards, int *first, int *n)
{
    long begin = (long)count * shard / shards, end = (long)count * (shard + 1) / shards;
    *first = (int)begin, *n = (int)(end - begin);
}

/* ---- writing ---- */

static void put_str(FILE *f, const char *s)
{
    if (!s) {
        fputs(" -", f);
        return;
    }
    fputs(" =", f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c <= ' ' || c == '\\' || c == 0x7f)
            fprintf(f, "\\x%02x", c);
        else
            fputc(c, f);
    }
}

static void put_num(FILE *f, double v)
{
    if (isnan(v))
        fputs(" nan", f);
    else
        fprintf(f, " %.17g", v);
}

static void frames_dir(const char *dir, const vrg_cmp_result *r, char *out, size_t cap)
{
    snprintf(out, cap, "%s/frames%s%s", dir, r->case_name[0] ? "/" : "", r->case_name);
}

int vrg_cmp_shard_write_maps(const char *dir, const vrg_cmp_result *r)
{
    char file[VRG_CLI_PATH + 128];
    for (int i = 0; i < r->count; i++)
        for (int s = 0; s < r->shown_count; s++)
            if (r->cand[i].flip_map[s]) {
                snprintf(file, sizeof file, "%s/%s-%05d.flip", dir, r->cand[i].name, r->shown[s]);
                if (vrg_output_write(file, r->cand[i].flip_map[s], sizeof(float) * r->width * r->height) != 0)
                    return -1;
            }
    return 0;
}

/* the run's settings: what every shard of one run has alike */
static void put_run(FILE *f, const vrg_cmp_run *run)
{
    const vrg_cmp_result *r0 = &run->cases[0];
    fputs("run cases_file", f);
    put_str(f, run->cases_file);
    fprintf(f, "\nrun score %s\nrun candidates %d baseline %d\n", run->score_device ? "device" : "cpu", r0->count, run->baseline);
    for (int i = 0; i < r0->count; i++) {
        fputs("run candidate", f);
        put_str(f, r0->cand[i].name);
        fprintf(f, " %d", r0->cand[i].base);
        put_str(f, r0->cand[i].graph);
        put_str(f, r0->cand[i].overrides);
        fputc('\n', f);
    }
    fprintf(f, "run cases %d\n", run->case_count);
    for (int c = 0; c < run->case_count; c++) {
        const vrg_cmp_result *r = &run->cases[c];
        fputs("run case", f);
        put_str(f, r->case_name);
        put_str(f, r->scene);
        put_str(f, r->reference);
        put_str(f, r->reference_overrides);
        put_str(f, r->camera);
        fprintf(f, " %u %u %u %u %u %d", r->width, r->height, r->frames, r->warmup, r->start, r->shown_count);
        for (int s = 0; s < r->shown_count; s++)
            fprintf(f, " %d", r->shown[s]);
        fputc('\n', f);
    }
}

int vrg_cmp_shard_write(const char *dir, const vrg_cmp_run *run, int shard, int shards, const char *device, const vrg_cmp_task *tasks, int n)
{
    char path[VRG_CLI_PATH + 16];
    snprintf(path, sizeof path, "%s/" VRG_CMP_SHARD_FILE, dir);
    vrg_output *out = vrg_output_open(path);
    if (!out)
        return -1;
    FILE *f = vrg_output_stream(out);
    fprintf(f, MAGIC "\nshard %d %d\n", shard, shards);
    put_run(f, run);
    fputs("device", f);
    put_str(f, device);
    fputc('\n', f);
    for (int t = 0; t < n; t++) {
        const vrg_cmp_result *r = &run->cases[tasks[t].case_index];
        const vrg_cmp_candidate *c = &r->cand[tasks[t].candidate];
        if (t == 0 || tasks[t - 1].case_index != tasks[t].case_index)
            fprintf(f, "cached %d %u\n", tasks[t].case_index, r->reference_cached);
        fprintf(f, "task %d %d", tasks[t].case_index, tasks[t].candidate);
        put_num(f, c->gpu_mean_ms);
        put_num(f, c->gpu_p95_ms);
        fprintf(f, " %d\n", c->pass_count);
        for (int p = 0; p < c->pass_count; p++) {
            fputs("pass", f);
            put_str(f, c->passes[p].name);
            put_num(f, c->passes[p].mean_ms);
            put_num(f, c->passes[p].p95_ms);
            fputc('\n', f);
        }
        fputs("summary", f);
        for (int m = 0; m < VRG_CMP_METRICS; m++)
            put_num(f, c->summary[m]);
        for (uint32_t k = 0; k < r->frames; k++) {
            fputs("\nframe", f);
            for (int m = 0; m < VRG_CMP_METRICS; m++)
                put_num(f, c->per_frame[m][k]);
        }
        fputc('\n', f);
    }
    fputs("end\n", f);
    return vrg_output_commit(out);
}

/* ---- reading ---- */

/* a shard's file, its lines split in place as they are read */
typedef struct shard_file {
    const char *dir;
    char path[VRG_CLI_PATH + 16];
    char *text, *next, *save;
    int line;
    int index, count;
    const char *run_begin; /* its "run" lines, in the text as read */
    size_t run_len;
} shard_file;

static int bad(const shard_file *s, const char *what)
{
    fprintf(stderr, "%s:%d: error: %s\n", s->path, s->line, what);
    return -1;
}

/* the next line's first token (its keyword), NULL at the end */
static char *next_line(shard_file *s)
{
    if (!s->next || !*s->next)
        return NULL;
    char *line = s->next, *nl = strchr(line, '\n');
    s->next = nl ? nl + 1 : NULL;
    if (nl)
        *nl = '\0';
    s->line++;
    return strtok_r(line, " ", &s->save);
}

static int expect_line(shard_file *s, const char *keyword)
{
    char *k = next_line(s);
    if (k && !strcmp(k, keyword))
        return 0;
    char what[128];
    snprintf(what, sizeof what, "expected a '%s' line%s", keyword, k ? "" : ", the file ends");
    return bad(s, what);
}

/* a "run WHAT ..." line, its tokens after WHAT next */
static int expect_run(shard_file *s, const char *what)
{
    if (expect_line(s, "run") != 0)
        return -1;
    char *t = strtok_r(NULL, " ", &s->save);
    if (t && !strcmp(t, what))
        return 0;
    char msg[128];
    snprintf(msg, sizeof msg, "expected a 'run %s' line", what);
    return bad(s, msg);
}

static int get_long(shard_file *s, long lo, long hi, long *out)
{
    char *t = strtok_r(NULL, " ", &s->save), *end;
    long v = t ? strtol(t, &end, 10) : 0;
    if (!t || *end || end == t || v < lo || v > hi)
        return bad(s, "a number is missing or out of range");
    *out = v;
    return 0;
}

static int get_int(shard_file *s, long lo, long hi, int *out)
{
    long v;
    if (get_long(s, lo, hi, &v) != 0)
        return -1;
    *out = (int)v;
    return 0;
}

static int get_u32(shard_file *s, uint32_t *out)
{
    long v;
    if (get_long(s, 0, UINT32_MAX, &v) != 0)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int get_num(shard_file *s, double *out)
{
    char *t = strtok_r(NULL, " ", &s->save), *end;
    if (!t || (*out = strtod(t, &end), *end) || end == t)
        return bad(s, "a number is missing or not a number");
    return 0;
}

static int hex(char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1; }

/* a string token into buf; *is_null for "-" when null_ok */
static int get_str(shard_file *s, char *buf, size_t cap, int *is_null)
{
    char *t = strtok_r(NULL, " ", &s->save);
    if (is_null)
        *is_null = t && !strcmp(t, "-");
    if (is_null && *is_null) {
        buf[0] = '\0';
        return 0;
    }
    if (!t || t[0] != '=')
        return bad(s, "a string is missing");
    size_t n = 0;
    for (t++; *t; t++) {
        int c = (unsigned char)*t;
        if (c == '\\') {
            if (t[1] != 'x' || hex(t[2]) < 0 || hex(t[3]) < 0)
                return bad(s, "a string has a bad \\x escape");
            c = hex(t[2]) * 16 + hex(t[3]);
            t += 3;
        }
        if (n + 1 >= cap)
            return bad(s, "a string is too long");
        buf[n++] = (char)c;
    }
    buf[n] = '\0';
    return 0;
}

static int read_shard(shard_file *s, const char *dir)
{
    memset(s, 0, sizeof *s);
    s->dir = dir;
    snprintf(s->path, sizeof s->path, "%s/" VRG_CMP_SHARD_FILE, dir);
    errno = 0;
    if (!(s->next = s->text = vrg_cli_read_text(s->path))) {
        fprintf(stderr, "error: %s: %s (not a shard's --out, or its shard did not finish)\n", s->path, errno ? strerror(errno) : "cannot read");
        return -1;
    }
    if (strncmp(s->text, MAGIC "\n", strlen(MAGIC) + 1) != 0) {
        s->line = 1;
        return bad(s, "not a voxrg compare shard file (" MAGIC ")");
    }
    s->next += strlen(MAGIC) + 1, s->line = 1;
    if (expect_line(s, "shard") != 0 || get_int(s, 0, 1000000, &s->index) != 0 || get_int(s, 1, 1000000, &s->count) != 0)
        return -1;
    if (s->index >= s->count)
        return bad(s, "the shard index is not below the shard count");
    s->run_begin = s->next;
    const char *end = s->next;
    while (end && !strncmp(end, "run ", 4))
        end = strchr(end, '\n') ? strchr(end, '\n') + 1 : end + strlen(end);
    s->run_len = (size_t)(end - s->run_begin);
    return 0;
}

/* The merge's state: the shards, the run they rebuild, and per task the
 * shard that ran it. */
typedef struct merge {
    shard_file *shards;
    int shard_count;
    vrg_cmp_run run;
    int count;   /* candidates */
    int *owner;  /* [case * count + candidate]: the shard, -1 none yet */
    char **owned; /* the strings the run points to */
    int owned_count, owned_cap;
} merge;

/* a copy of s the merge owns; NULL for no string (or out of memory) */
static const char *keep(merge *m, const char *s, int is_null)
{
    if (is_null)
        return NULL;
    if (m->owned_count == m->owned_cap) {
        int cap = m->owned_cap ? 2 * m->owned_cap : 64;
        char **grown = realloc(m->owned, sizeof *grown * (size_t)cap);
        if (!grown)
            return NULL;
        m->owned = grown, m->owned_cap = cap;
    }
    char *copy = strdup(s);
    if (copy)
        m->owned[m->owned_count++] = copy;
    return copy;
}

/* the run's settings from the first shard's "run" lines */
static int read_run(merge *m, shard_file *s)
{
    char buf[VRG_CLI_PATH];
    int null, cases;
    vrg_cmp_run *run = &m->run;
    if (expect_run(s, "cases_file") != 0 || get_str(s, buf, sizeof buf, &null) != 0)
        return -1;
    run->cases_file = keep(m, buf, null);
    char *word;
    if (expect_run(s, "score") != 0 || !(word = strtok_r(NULL, " ", &s->save)) || (strcmp(word, "cpu") && strcmp(word, "device")))
        return bad(s, "expected 'run score cpu' or 'run score device'");
    run->score_device = !strcmp(word, "device");
    if (expect_run(s, "candidates") != 0 || get_int(s, 1, 10000000, &m->count) != 0 || !(word = strtok_r(NULL, " ", &s->save)) ||
        strcmp(word, "baseline") || get_int(s, 0, m->count - 1, &run->baseline) != 0)
        return bad(s, "expected 'run candidates N baseline B'");
    vrg_cmp_candidate *cand = calloc((size_t)m->count, sizeof *cand);
    if (!cand)
        return -1;
    for (int i = 0; i < m->count; i++) {
        vrg_cmp_candidate *c = &cand[i];
        if (expect_run(s, "candidate") != 0 || get_str(s, c->name, sizeof c->name, NULL) != 0 ||
            get_int(s, -1, i - 1, &c->base) != 0 || get_str(s, c->graph, sizeof c->graph, NULL) != 0 ||
            get_str(s, c->overrides, sizeof c->overrides, NULL) != 0) {
            free(cand);
            return -1;
        }
    }
    int rc = expect_run(s, "cases") != 0 || get_int(s, 1, 1000000, &cases) != 0 ||
             !(run->cases = calloc((size_t)cases, sizeof *run->cases));
    for (int c = 0; rc == 0 && c < cases; c++) {
        vrg_cmp_result *r = &run->cases[c];
        run->case_count++;
        r->count = m->count;
        if (!(r->cand = calloc((size_t)m->count, sizeof *r->cand))) {
            rc = -1;
            break;
        }
        memcpy(r->cand, cand, sizeof *cand * (size_t)m->count);
        rc = expect_run(s, "case") != 0 || get_str(s, r->case_name, sizeof r->case_name, NULL) != 0 ||
             get_str(s, r->scene, sizeof r->scene, NULL) != 0 || get_str(s, buf, sizeof buf, NULL) != 0;
        r->reference = rc ? NULL : keep(m, buf, 0);
        rc = rc || get_str(s, r->reference_overrides, sizeof r->reference_overrides, NULL) != 0 || get_str(s, buf, sizeof buf, &null) != 0;
        r->camera = rc ? NULL : keep(m, buf, null);
        rc = rc || get_u32(s, &r->width) || get_u32(s, &r->height) || get_u32(s, &r->frames) || get_u32(s, &r->warmup) || get_u32(s, &r->start) ||
             get_int(s, 0, VRG_CMP_MAX_SHOWN, &r->shown_count);
        for (int k = 0; !rc && k < r->shown_count; k++)
            rc = get_int(s, 0, (long)r->frames - 1, &r->shown[k]);
        if (!rc && (r->width == 0 || r->height == 0 || r->width > 100000 || r->height > 100000 || r->frames == 0))
            rc = bad(s, "a case's size or frame count is out of range");
        rc = rc || !r->reference;
    }
    free(cand);
    return rc ? -1 : 0;
}

/* One task's results from a shard, after its "task C I" */
static int read_task(merge *m, shard_file *s, int sh, const char *device, const uint32_t *cached)
{
    int c, i;
    if (get_int(s, 0, m->run.case_count - 1, &c) != 0 || get_int(s, 0, m->count - 1, &i) != 0)
        return -1;
    vrg_cmp_result *r = &m->run.cases[c];
    vrg_cmp_candidate *cand = &r->cand[i];
    int *owner = &m->owner[c * m->count + i];
    if (*owner >= 0) {
        fprintf(stderr, "error: candidate %s on case %s is in two shards: %s and %s\n", cand->name, r->case_name[0] ? r->case_name : "(the run)",
                m->shards[*owner].path, s->path);
        return -1;
    }
    *owner = sh;
    if (i == 0) /* the case's first task: its device and cache count, as one process reports them */
        r->device = device, r->reference_cached = cached[c];
    if (get_num(s, &cand->gpu_mean_ms) != 0 || get_num(s, &cand->gpu_p95_ms) != 0 || get_int(s, 0, VRG_CMP_MAX_PASSES, &cand->pass_count) != 0)
        return -1;
    for (int p = 0; p < cand->pass_count; p++)
        if (expect_line(s, "pass") != 0 || get_str(s, cand->passes[p].name, sizeof cand->passes[p].name, NULL) != 0 ||
            get_num(s, &cand->passes[p].mean_ms) != 0 || get_num(s, &cand->passes[p].p95_ms) != 0)
            return -1;
    if (expect_line(s, "summary") != 0)
        return -1;
    for (int k = 0; k < VRG_CMP_METRICS; k++)
        if (get_num(s, &cand->summary[k]) != 0 || !(cand->per_frame[k] = calloc(r->frames, sizeof(double))))
            return -1;
    for (uint32_t f = 0; f < r->frames; f++) {
        if (expect_line(s, "frame") != 0)
            return -1;
        for (int k = 0; k < VRG_CMP_METRICS; k++)
            if (get_num(s, &cand->per_frame[k][f]) != 0)
                return -1;
    }
    return 0;
}

/* a shard's device and tasks, after its "run" lines */
static int read_tasks(merge *m, int sh)
{
    shard_file *s = &m->shards[sh];
    char buf[1024];
    uint32_t *cached = calloc((size_t)m->run.case_count, sizeof *cached);
    const char *device;
    if (!cached || expect_line(s, "device") != 0 || get_str(s, buf, sizeof buf, NULL) != 0 || !(device = keep(m, buf, 0))) {
        free(cached);
        return -1;
    }
    int rc = 0, ended = 0;
    for (char *k; rc == 0 && !ended && (k = next_line(s));) {
        int c;
        if (!strcmp(k, "cached"))
            rc = get_int(s, 0, m->run.case_count - 1, &c) || get_u32(s, &cached[c]);
        else if (!strcmp(k, "task"))
            rc = read_task(m, s, sh, device, cached);
        else if (!strcmp(k, "end"))
            ended = 1;
        else
            rc = bad(s, "expected a 'cached', 'task' or 'end' line");
    }
    if (rc == 0 && !ended)
        rc = bad(s, "the file ends before its 'end' line");
    free(cached);
    return rc ? -1 : 0;
}

/* ---- the shards checked against each other ---- */

/* the line of a's run lines (counted from a's file: they begin on its
 * third) where b's differ; past them when they do not */
static int differing_line(const shard_file *a, const shard_file *b)
{
    int line = 3;
    for (size_t i = 0; i < a->run_len && i < b->run_len && a->run_begin[i] == b->run_begin[i]; i++)
        line += a->run_begin[i] == '\n';
    return line;
}

static int check_shards(const merge *m)
{
    const shard_file *first = &m->shards[0];
    for (int i = 1; i < m->shard_count; i++) {
        const shard_file *s = &m->shards[i];
        if (s->count != first->count) {
            fprintf(stderr, "error: %s is shard %d of %d, but %s is of %d: shards of different runs\n", s->path, s->index, s->count, first->path,
                    first->count);
            return -1;
        }
        if (s->run_len != first->run_len || memcmp(s->run_begin, first->run_begin, s->run_len)) {
            fprintf(stderr, "error: %s:%d: a shard of another run: its settings differ from %s's (candidates, cases, sizes or reference)\n",
                    s->path, differing_line(s, first), first->path);
            return -1;
        }
        for (int k = 0; k < i; k++)
            if (m->shards[k].index == s->index) {
                fprintf(stderr, "error: %s and %s are both shard %d of %d\n", m->shards[k].path, s->path, s->index, s->count);
                return -1;
            }
    }
    for (int want = 0; want < first->count; want++) {
        int found = 0;
        for (int i = 0; i < m->shard_count; i++)
            found |= m->shards[i].index == want;
        if (!found) {
            fprintf(stderr, "error: shard %d of %d is missing: none of the folders given holds it\n", want, first->count);
            return -1;
        }
    }
    return 0;
}

/* ---- files: frames copied, shown frames and maps read back ---- */

static int read_all(const char *path, void **data, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "error: %s: %s\n", path, strerror(errno));
        return -1;
    }
    size_t cap = 1 << 16, n = 0, got;
    char *buf = malloc(cap);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0)
        if ((n += got) == cap) {
            char *grown = realloc(buf, cap *= 2);
            if (!grown)
                free(buf);
            buf = grown;
        }
    int err = ferror(f);
    fclose(f);
    if (!buf || err) {
        fprintf(stderr, "error: %s: cannot read\n", path);
        free(buf);
        return -1;
    }
    *data = buf, *size = n;
    return 0;
}

static int copy_file(const char *from, const char *to)
{
    void *data;
    size_t size;
    if (read_all(from, &data, &size) != 0)
        return -1;
    int rc = vrg_output_write(to, data, size);
    free(data);
    return rc;
}

/* a case's frames into OUT/frames: the reference's from the shard of its
 * first task, each candidate's from the shard that ran it (scored on the
 * device, only those the report shows: the others were not read back) */
static int copy_frames(const merge *m, int c, const char *out)
{
    const vrg_cmp_result *r = &m->run.cases[c];
    char from_dir[VRG_CLI_PATH], to_dir[VRG_CLI_PATH], from[VRG_CLI_PATH + 128], to[VRG_CLI_PATH + 128];
    frames_dir(out, r, to_dir, sizeof to_dir);
    if (vrg_cli_out_dir(to_dir) != 0)
        return -1;
    for (int i = -1; i < r->count; i++) {
        frames_dir(m->shards[m->owner[c * m->count + (i < 0 ? 0 : i)]].dir, r, from_dir, sizeof from_dir);
        for (uint32_t k = 0; k < r->frames; k++) {
            int shown = 0;
            for (int s = 0; s < r->shown_count; s++)
                shown |= r->shown[s] == (int)k;
            if (i >= 0 && m->run.score_device && !shown)
                continue;
            const char *name = i < 0 ? "reference" : r->cand[i].name;
            snprintf(from, sizeof from, "%s/%s-%05u.png", from_dir, name, k);
            snprintf(to, sizeof to, "%s/%s-%05u.png", to_dir, name, k);
            if (copy_file(from, to) != 0)
                return -1;
        }
    }
    return 0;
}

static int read_png(const char *path, const vrg_cmp_result *r, uint8_t **rgb)
{
    uint32_t w, h;
    if (vrg_png_read_rgb8(path, rgb, &w, &h) != 0)
        return -1;
    if (w != r->width || h != r->height) {
        fprintf(stderr, "error: %s: %ux%u, the run's frames are %ux%u\n", path, w, h, r->width, r->height);
        return -1;
    }
    return 0;
}

/* the shown frames and maps of case c, for its part of the report */
static int load_shown(const merge *m, int c, const char *out)
{
    vrg_cmp_result *r = &m->run.cases[c];
    char dir[VRG_CLI_PATH], file[VRG_CLI_PATH + 128];
    frames_dir(out, r, dir, sizeof dir);
    for (int s = 0; s < r->shown_count; s++) {
        snprintf(file, sizeof file, "%s/reference-%05d.png", dir, r->shown[s]);
        if (read_png(file, r, &r->reference_shown[s]) != 0)
            return -1;
        for (int i = 0; i < r->count; i++) {
            snprintf(file, sizeof file, "%s/%s-%05d.png", dir, r->cand[i].name, r->shown[s]);
            if (read_png(file, r, &r->cand[i].shown[s]) != 0)
                return -1;
            char from[VRG_CLI_PATH];
            frames_dir(m->shards[m->owner[c * m->count + i]].dir, r, from, sizeof from);
            snprintf(file, sizeof file, "%s/%s-%05d.flip", from, r->cand[i].name, r->shown[s]);
            void *map;
            size_t size;
            if (read_all(file, &map, &size) != 0)
                return -1;
            r->cand[i].flip_map[s] = map;
            if (size != sizeof(float) * r->width * r->height) {
                fprintf(stderr, "error: %s: %zu bytes, a %ux%u map has %zu\n", file, size, r->width, r->height, sizeof(float) * r->width * r->height);
                return -1;
            }
        }
    }
    return 0;
}

/* ---- the merge ---- */

static int merge_usage(const char *usage, const char *fmt, const char *arg)
{
    fprintf(stderr, "error: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n%s", usage);
    return 2;
}

/* reads and checks the shards, and rebuilds the run from them */
static int read_shards(merge *m, char **dirs, int n)
{
    m->shard_count = n;
    if (!(m->shards = calloc((size_t)n, sizeof *m->shards)))
        return -1;
    for (int i = 0; i < n; i++)
        if (read_shard(&m->shards[i], dirs[i]) != 0)
            return -1;
    if (check_shards(m) != 0 || read_run(m, &m->shards[0]) != 0)
        return -1;
    int tasks = m->run.case_count * m->count;
    if (!(m->owner = malloc(sizeof *m->owner * (size_t)tasks)))
        return -1;
    for (int t = 0; t < tasks; t++)
        m->owner[t] = -1;
    for (int i = 0; i < n; i++) {
        m->shards[i].next = (char *)m->shards[i].run_begin + m->shards[i].run_len;
        m->shards[i].line = differing_line(&m->shards[i], &m->shards[i]) - 1; /* the last "run" line's */
        if (read_tasks(m, i) != 0)
            return -1;
    }
    for (int t = 0; t < tasks; t++)
        if (m->owner[t] < 0) {
            const vrg_cmp_result *r = &m->run.cases[t / m->count];
            fprintf(stderr, "error: no shard holds candidate %s on case %s\n", r->cand[t % m->count].name, r->case_name[0] ? r->case_name : "(the run)");
            return -1;
        }
    return 0;
}

/* the report's files from the merged run */
static int write_merged(merge *m, const char *out)
{
    char file[VRG_CLI_PATH + 32];
    snprintf(file, sizeof file, "%s/frames", out);
    FILE *sections = NULL;
    int rc = vrg_cli_out_dir(out) != 0 || vrg_cli_out_dir(file) != 0 || !(sections = tmpfile());
    for (int c = 0; rc == 0 && c < m->run.case_count; c++) {
        rc = copy_frames(m, c, out) || load_shown(m, c, out) || vrg_cmp_report_case(sections, &m->run.cases[c]);
        vrg_cmp_free_shown(&m->run.cases[c]);
    }
    snprintf(file, sizeof file, "%s/report.html", out);
    rc = rc || vrg_cmp_judge(&m->run) || vrg_cmp_write_metrics(out, &m->run) || vrg_cmp_write_report(file, &m->run, sections);
    if (sections)
        fclose(sections);
    return rc ? 1 : 0;
}

int vrg_cmp_merge(int argc, char **argv, const char *usage)
{
    const char *out = NULL;
    char **dirs = calloc((size_t)argc + 1, sizeof *dirs);
    int n = 0, rc = 0;
    if (!dirs)
        return 1;
    for (int i = 0; i < argc && rc == 0; i++) {
        if (!strcmp(argv[i], "--merge")) {
            if (out || i + 1 == argc)
                rc = merge_usage(usage, "--merge %s", out ? "given twice" : "needs OUT, the folder of the merged report");
            else
                out = argv[++i];
        } else if (!strcmp(argv[i], "--shard"))
            rc = merge_usage(usage, "--shard with --merge: a shard runs tasks, the merge reads the shards' results%s", "");
        else if (argv[i][0] == '-')
            rc = merge_usage(usage, "--merge takes OUT and the shards' folders, not '%s' (the shards' settings are in their shard.txt)", argv[i]);
        else
            dirs[n++] = argv[i];
    }
    if (rc == 0 && !n)
        rc = merge_usage(usage, "--merge %s: no shard folder given", out);
    if (rc) {
        free(dirs);
        return rc;
    }
    char file[VRG_CLI_PATH + 32];
    for (int i = 0; i < 3; i++) { /* nothing of an earlier report may pass for this merge's */
        snprintf(file, sizeof file, "%s/%s", out, merge_outputs[i]);
        remove(file);
    }
    merge m = {0};
    rc = read_shards(&m, dirs, n) != 0 ? 1 : write_merged(&m, out);
    if (rc == 0) {
        vrg_cmp_print(&m.run);
        printf("merged %d shards: wrote %s/report.html, metrics.json, metrics.csv and frames/\n", n, out);
    } else
        for (int i = 0; i < 3; i++) {
            snprintf(file, sizeof file, "%s/%s", out, merge_outputs[i]);
            remove(file);
        }
    for (int i = 0; m.shards && i < n; i++)
        free(m.shards[i].text);
    for (int i = 0; i < m.owned_count; i++)
        free(m.owned[i]);
    free(m.owned), free(m.owner), free(m.shards), free(dirs);
    vrg_cmp_run_free(&m.run);
    return rc;
}
