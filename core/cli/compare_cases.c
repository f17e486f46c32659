/* Case files of `voxrg compare --cases FILE`: one [case NAME] section per
 * case; keys camera (a path file relative to the case file), start,
 * frames, warmup, size, and scene.PARAM overrides applied to every
 * candidate and the reference. Comments start with ';' or '#'. */
#define _POSIX_C_SOURCE 200809L
#include "compare_cases.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "compare_result.h"
#include "util.h"
#include "voxrg/metrics.h"
#include "voxrg/voxrg.h"

#define KEYS_HINT "keys are camera, start, frames, warmup, size and scene.PARAM"

typedef struct reader {
    const char *file;
    int line, errors;
} reader;

static void error_at(reader *rd, const char *hint, const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "%s:%d: error: ", rd->file, rd->line);
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    if (hint)
        fprintf(stderr, "  hint: %s\n", hint);
    rd->errors++;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n && strchr(" \t\r\n", s[n - 1]))
        s[--n] = '\0';
    return s;
}

static int count_value(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end;
    errno = 0;
    long n = strtol(s, &end, 10);
    if (*end || !*s || errno || n < (long)lo || n > (long)hi)
        return -1;
    *out = (uint32_t)n;
    return 0;
}

/* the path file relative to the case file's folder (unless absolute) */
static void camera_path(const char *file, const char *value, char *out, size_t cap)
{
    const char *slash = strrchr(file, '/');
    if (value[0] == '/' || !slash)
        snprintf(out, cap, "%s", value);
    else
        snprintf(out, cap, "%.*s/%s", (int)(slash - file + 1), file, value);
}

static int add_scene(vrg_cmp_case_spec *c, const char *key, const char *value)
{
    char **grown = realloc(c->scene, sizeof *grown * (size_t)(c->scene_count + 1));
    if (!grown)
        return -1;
    c->scene = grown;
    size_t n = strlen(key) + strlen(value) + 2;
    if (!(c->scene[c->scene_count] = malloc(n)))
        return -1;
    snprintf(c->scene[c->scene_count++], n, "%s=%s", key, value);
    return 0;
}

static void set_key(reader *rd, vrg_cmp_case_spec *c, const char *key, const char *value)
{
    if (!*value)
        error_at(rd, KEYS_HINT, "'%s' has no value%s", key, "");
    else if (!strcmp(key, "camera"))
        camera_path(rd->file, value, c->camera, sizeof c->camera);
    else if (!strcmp(key, "start")) {
        if (count_value(value, 0, 10000000, &c->start) != 0)
            error_at(rd, "start is the camera path's first frame, 0 or more", "start = %s: not a frame number%s", value, "");
    } else if (!strcmp(key, "frames")) {
        if (count_value(value, 1, 100000, &c->frames) != 0)
            error_at(rd, NULL, "frames = %s: expected 1 to 100000%s", value, "");
    } else if (!strcmp(key, "warmup")) {
        if (count_value(value, 0, 100000, &c->warmup) != 0)
            error_at(rd, NULL, "warmup = %s: expected 0 or more frames%s", value, "");
        c->warmup_given = 1;
    } else if (!strcmp(key, "size")) {
        if (vrg_cli_parse_size(value, &c->width, &c->height) != 0)
            error_at(rd, "e.g. size = 320x180", "size = %s: expected WxH, %s", value, VRG_CLI_SIZE_RANGE);
        else if (c->width < VRG_SSIM_WINDOW || c->height < VRG_SSIM_WINDOW)
            error_at(rd, NULL, "size = %s: compare needs at least %s pixels (SSIM's window)", value,
                     VRG_CLI_STR(VRG_SSIM_WINDOW) "x" VRG_CLI_STR(VRG_SSIM_WINDOW));
    } else if (!strncmp(key, "scene.", 6) && key[6] && !strchr(key + 6, '.')) {
        for (int i = 0; i < c->scene_count; i++)
            if (!strncmp(c->scene[i], key, strlen(key)) && c->scene[i][strlen(key)] == '=')
                error_at(rd, NULL, "'%s' is given twice in [case %s]", key, c->name);
        if (add_scene(c, key, value) != 0)
            error_at(rd, NULL, "out of memory%s%s", "", "");
    } else
        error_at(rd, KEYS_HINT, "unknown key '%s' in [case %s]", key, c->name);
}

/* a [case NAME] header: a new case, or an error */
static vrg_cmp_case_spec *open_case(reader *rd, char *header, vrg_cmp_case_spec **cases, int *count)
{
    char *close = strchr(header, ']');
    if (!close || *trim(close + 1)) {
        error_at(rd, "a section header is [case NAME]", "'%s': expected [case NAME]%s", header, "");
        return NULL;
    }
    *close = '\0';
    char *inner = trim(header + 1);
    if (strncmp(inner, "case", 4) || (inner[4] != ' ' && inner[4] != '\t')) {
        error_at(rd, "a case file holds only [case NAME] sections", "unknown section '[%s]'%s", inner, "");
        return NULL;
    }
    const char *name = trim(inner + 4);
    if (!vrg_cmp_name_ok(name, strlen(name))) {
        error_at(rd, "a case's name is part of file names: 1 to 63 of A-Z a-z 0-9 _ - and dots (not first or last)",
                 "[case %s]: not a usable case name%s", name, "");
        return NULL;
    }
    for (int i = 0; i < *count; i++)
        if (!strcmp((*cases)[i].name, name)) {
            char first[32];
            snprintf(first, sizeof first, "%d", (*cases)[i].line);
            error_at(rd, NULL, "[case %s] is given twice (first at line %s)", name, first);
            return NULL;
        }
    vrg_cmp_case_spec *grown = realloc(*cases, sizeof *grown * (size_t)(*count + 1));
    if (!grown)
        return NULL;
    *cases = grown;
    vrg_cmp_case_spec *c = &grown[(*count)++];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", name);
    c->frames = 30;
    c->warmup = 5;
    c->line = rd->line;
    return c;
}

/* the compare defaults' rule: warm-up below the frames */
static void finish_case(reader *rd, vrg_cmp_case_spec *c)
{
    if (c->warmup < c->frames)
        return;
    if (c->warmup_given) {
        int at = rd->line;
        rd->line = c->line;
        error_at(rd, "frames before warmup are left out of the summary", "[case %s]: warmup must be below frames%s", c->name, "");
        rd->line = at;
    } else
        c->warmup = c->frames > 1 ? 1 : 0;
}

int vrg_cmp_cases_load(const char *file, vrg_cmp_case_spec **cases, int *count)
{
    *cases = NULL;
    *count = 0;
    char *text = vrg_cli_read_text(file);
    if (!text) {
        fprintf(stderr, "%s: error: cannot read the case file: %s\n", file, vrg_open_strerror(errno));
        return -1;
    }
    reader rd = {.file = file};
    vrg_cmp_case_spec *cur = NULL;
    int in_bad_section = 0;
    for (char *raw = text, *nl; raw; raw = nl ? nl + 1 : NULL) {
        nl = strchr(raw, '\n');
        if (nl)
            *nl = '\0';
        rd.line++;
        char *s = trim(raw);
        if (!*s || *s == ';' || *s == '#')
            continue;
        if (*s == '[') {
            if (cur)
                finish_case(&rd, cur);
            cur = open_case(&rd, s, cases, count);
            in_bad_section = !cur;
            continue;
        }
        char *eq = strchr(s, '=');
        if (!eq) {
            error_at(&rd, KEYS_HINT, "'%s': expected KEY = VALUE%s", s, "");
            continue;
        }
        *eq = '\0';
        char *key = trim(s), *value = trim(eq + 1);
        if (!cur) {
            if (!in_bad_section)
                error_at(&rd, "start a case with [case NAME]", "'%s' is outside a [case NAME] section%s", key, "");
            continue;
        }
        set_key(&rd, cur, key, value);
    }
    if (cur)
        finish_case(&rd, cur);
    free(text);
    if (!rd.errors && !*count) {
        fprintf(stderr, "%s: error: no [case NAME] section\n", file);
        rd.errors++;
    }
    if (rd.errors) {
        vrg_cmp_cases_free(*cases, *count);
        *cases = NULL, *count = 0;
        return -1;
    }
    return 0;
}

void vrg_cmp_cases_free(vrg_cmp_case_spec *cases, int count)
{
    for (int i = 0; i < count; i++) {
        for (int k = 0; k < cases[i].scene_count; k++)
            free(cases[i].scene[k]);
        free(cases[i].scene);
    }
    free(cases);
}
