/* Shader-only passes: a graph's `plugin = NAME` that finds NAME.comp. The
 * pass's interface is read from the shader itself (docs/plugin-abi.md,
 * "A pass in one file"):
 *   - each image or buffer binding whose instance name is in_X or out_X is
 *     the input or output slot X, its kind, access and format taken from
 *     the declaration; the uniform block `frame` (frame.glsl) is the input
 *     slot `frame`;
 *   - each member of the push-constant block is a parameter, its default,
 *     range and help from the `// @param ...` annotation on its line; the
 *     runtime packs the values by name at the members' reflected offsets,
 *     as it does for a C pass's dispatch with push_size 0 (dispatch.c);
 *   - a binding marked `// @optional` is an optional slot, and a
 *     member's `choices=a,b` makes it a string parameter whose index the
 *     member gets; each connection of the optional slots and
 *     each value of a `variant` choice compiles a variant (HAS_X, NAME=k);
 *     the interface is read with every optional slot connected, so an
 *     optional acceleration structure (no stand-in exists for one) is
 *     declared only under its HAS_X, as the last binding, and its variant
 *     is the one recorded where the structure exists (dispatch.c);
 *   - the first image output that is not optional (lowest binding) sets
 *     the dispatch size; a shader that includes pixel.glsl runs its pixel
 *     loop.
 * Reflection is by name, so nothing is stated twice: the same member and
 * binding names are what a C pass would bind by (reflect.h). */
#define _GNU_SOURCE
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "reflect.h"
#include "shader.h"
#include "shader_pass.h"

/* An error at a line of the shader (or a file it includes), counted in d. */
static void shader_error(_vrg_diag *d, const char *file, int line, const char *hint, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static void shader_error(_vrg_diag *d, const char *file, int line, const char *hint, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    _vrg_diag sd = {.out = d->out ? d->out : stderr, .file = file};
    _vrg_error_at(&sd, line > 0 ? line : 1, VRG_E_SHADER_INTERFACE, hint, "%s", msg);
    d->errors += sd.errors;
}

/* "FILE:LINE" (reflect.c's `where`) split; line 0 when none is known. */
static int split_where(const char *where, char *file, size_t cap)
{
    const char *colon = strrchr(where, ':');
    char *end = NULL;
    long line = colon ? strtol(colon + 1, &end, 10) : 0;
    if (!colon || !end || *end || line <= 0) {
        snprintf(file, cap, "%s", where);
        return 0;
    }
    snprintf(file, cap, "%.*s", (int)(colon - where), where);
    return (int)line;
}

/* ---- the expanded source, line by line, with its #line bookkeeping ---- */

typedef struct src_line {
    const char *text;
    size_t len;
    char file[VRG_PATH_MAX];
    int line;
} src_line;

typedef struct src_reader {
    const char *p;
    char file[VRG_PATH_MAX];
    int line;
} src_reader;

static int next_line(src_reader *r, src_line *out)
{
    while (r->p && *r->p) {
        const char *end = strchr(r->p, '\n');
        size_t n = end ? (size_t)(end - r->p) : strlen(r->p);
        const char *s = r->p;
        while (s < r->p + n && (*s == ' ' || *s == '\t'))
            s++;
        const char *start = r->p;
        r->p = end ? end + 1 : r->p + n;
        r->line++;
        if ((size_t)(start + n - s) >= 5 && strncmp(s, "#line", 5) == 0) {
            char *q;
            long l = strtol(s + 5, &q, 10);
            const char *quote = memchr(q, '"', (size_t)(start + n - q));
            const char *close = quote ? memchr(quote + 1, '"', (size_t)(start + n - quote - 1)) : NULL;
            if (close)
                snprintf(r->file, sizeof r->file, "%.*s", (int)(close - quote - 1), quote + 1);
            r->line = (int)l - 1;
            continue;
        }
        out->text = start;
        out->len = n;
        snprintf(out->file, sizeof out->file, "%s", r->file);
        out->line = r->line;
        return 1;
    }
    return 0;
}

static int word_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

/* The name a line of code declares: the last word before its `;` (n:
 * the code's length, without its comment). -1 where there is none or it
 * does not fit in VRG_NAME_MAX. */
static int declared_name(const char *text, size_t n, char name[VRG_NAME_MAX])
{
    const char *e = memchr(text, ';', n);
    while (e && e > text && isspace((unsigned char)e[-1]))
        e--;
    const char *b = e;
    while (b && b > text && word_char(b[-1]))
        b--;
    if (!b || b == e || (size_t)(e - b) >= VRG_NAME_MAX)
        return -1;
    snprintf(name, VRG_NAME_MAX, "%.*s", (int)(e - b), b);
    return 0;
}

/* " DEFINE=value" appended to the list out[0..*o); -1 (out cut back to
 * *o) where it does not fit. */
static int append_define(char *out, size_t cap, size_t *o, const char *define, const char *value)
{
    int w = snprintf(out + *o, cap - *o, "%s%s=%s", *o ? " " : "", define, value);
    if (w < 0 || (size_t)w >= cap - *o) {
        out[*o] = '\0';
        return -1;
    }
    *o += (size_t)w;
    return 0;
}

/* Whether `word` occurs as a whole word in s[0..n). */
static int has_word(const char *s, size_t n, const char *word)
{
    size_t w = strlen(word);
    for (size_t i = 0; w && i + w <= n; i++)
        if (strncmp(s + i, word, w) == 0 && (i == 0 || !word_char(s[i - 1])) && (i + w == n || !word_char(s[i + w])))
            return 1;
    return 0;
}

/* The code part of a line (before any // comment) and the comment's text. */
static size_t code_len(const char *s, size_t n, const char **comment)
{
    *comment = NULL;
    for (size_t i = 0; i + 1 < n; i++)
        if (s[i] == '/' && s[i + 1] == '/') {
            *comment = s + i + 2;
            return i;
        }
    return n;
}

/* ---- variants ---- */

/* prefix + name in upper case: a define (HAS_EMISSION, CURVE) */
static void upper_define(char *out, size_t cap, const char *prefix, const char *name)
{
    size_t o = (size_t)snprintf(out, cap, "%s", prefix);
    for (; *name && o + 1 < cap; name++)
        out[o++] = (char)toupper((unsigned char)*name);
    out[o < cap ? o : cap - 1] = '\0';
}

/* ---- @param annotations ---- */

typedef struct annotation {
    int has_default, has_min, has_max, has_help, has_choices, variant;
    double def, min, max;
    char def_text[VRG_NAME_MAX];
    char choices[VRG_SHADER_PASS_CHOICES_MAX];
    char help[VRG_SHADER_PASS_HELP_MAX];
} annotation;

/* A value of key=value: up to white space, into out. NULL, or why not. */
static const char *annotation_value(const char **sp, const char *end, const char *key, size_t klen, char *out, size_t cap, char *why, size_t wcap)
{
    const char *v = *sp, *s = *sp;
    while (s < end && !isspace((unsigned char)*s))
        s++;
    *sp = s;
    if (s == v)
        return snprintf(why, wcap, "%.*s has no value", (int)klen, key), why;
    if ((size_t)(s - v) >= cap)
        return snprintf(why, wcap, "%.*s's value is longer than %zu characters", (int)klen, key, cap - 1), why;
    snprintf(out, cap, "%.*s", (int)(s - v), v);
    return NULL;
}

static const char *annotation_number(const char *key, const char *value, int is_bool, double *x, char *why, size_t cap)
{
    char *stop;
    if (is_bool && strcmp(value, "true") == 0)
        *x = 1;
    else if (is_bool && strcmp(value, "false") == 0)
        *x = 0;
    else {
        *x = strtod(value, &stop);
        if (*stop || !isfinite(*x))
            return snprintf(why, cap, "%s=%s is not a number", key, value), why;
    }
    return NULL;
}

/* Parses "@param key=value ..." (text of len n after "//"); NULL, or why
 * not. Keys: default, min, max, help="...", choices=a,b,c (a string
 * parameter whose index the member gets; default= is then a name) and the
 * word variant (each choice compiles a variant: NAME=index). */
static const char *parse_annotation(const char *s, size_t n, int is_bool, annotation *a, char *why, size_t cap)
{
    memset(a, 0, sizeof *a);
    const char *end = s + n;
    char min_text[64] = "", max_text[64] = "";
    while (s < end && isspace((unsigned char)*s))
        s++;
    if ((size_t)(end - s) < 6 || strncmp(s, "@param", 6) != 0 || (end - s > 6 && !isspace((unsigned char)s[6])))
        return "its comment is not a @param annotation";
    s += 6;
    for (;;) {
        while (s < end && isspace((unsigned char)*s))
            s++;
        if (s >= end || *s == '\r')
            break;
        const char *key = s;
        while (s < end && (isalnum((unsigned char)*s) || *s == '_'))
            s++;
        size_t klen = (size_t)(s - key);
        if (klen == 7 && strncmp(key, "variant", 7) == 0 && (s >= end || isspace((unsigned char)*s))) {
            if (a->variant)
                return "variant is given twice";
            a->variant = 1;
            continue;
        }
        if (!klen || s >= end || *s != '=')
            return snprintf(why, cap, "expected key=value at '%.*s'", (int)(end - key > 24 ? 24 : end - key), key), why;
        s++;
        if (klen == 4 && strncmp(key, "help", 4) == 0) {
            if (a->has_help)
                return "help is given twice";
            if (s >= end || *s != '"')
                return "help's value is a \"quoted text\"";
            s++;
            size_t o = 0;
            while (s < end && *s != '"') {
                if (*s == '\\' && s + 1 < end)
                    s++;
                if (o + 1 < sizeof a->help)
                    a->help[o++] = *s;
                s++;
            }
            if (s >= end)
                return "help's quoted text has no closing '\"'";
            s++;
            a->help[o] = '\0';
            if (o + 1 >= sizeof a->help)
                return snprintf(why, cap, "help is longer than %d characters", VRG_SHADER_PASS_HELP_MAX - 2), why;
            a->has_help = 1;
            continue;
        }
        int is_default = klen == 7 && strncmp(key, "default", 7) == 0, is_min = klen == 3 && strncmp(key, "min", 3) == 0,
            is_max = klen == 3 && strncmp(key, "max", 3) == 0, is_choices = klen == 7 && strncmp(key, "choices", 7) == 0;
        if (!is_default && !is_min && !is_max && !is_choices)
            return snprintf(why, cap, "unknown key '%.*s' (default, min, max, help, choices, variant)", (int)klen, key), why;
        int *has = is_default ? &a->has_default : is_min ? &a->has_min : is_max ? &a->has_max : &a->has_choices;
        if (*has)
            return snprintf(why, cap, "%.*s is given twice", (int)klen, key), why;
        *has = 1;
        char *to = is_default ? a->def_text : is_min ? min_text : is_max ? max_text : a->choices;
        size_t to_cap = is_default ? sizeof a->def_text : is_min ? sizeof min_text : is_max ? sizeof max_text : sizeof a->choices;
        const char *problem = annotation_value(&s, end, key, klen, to, to_cap, why, cap);
        if (problem)
            return problem;
    }
    if (!a->has_default)
        return a->has_choices ? "it has no default= (one of its choices)" : "it has no default=";
    if (!a->has_help)
        return "it has no help=\"...\"";
    if (a->variant && !a->has_choices)
        return "variant picks a compiled variant per choice: give choices= too";
    if (a->has_choices) {
        if (a->has_min || a->has_max)
            return "a parameter with choices= has no min= or max=: its values are the names";
        return NULL; /* default= is a name, checked against the list by the caller */
    }
    if (a->has_min != a->has_max)
        return "give both min= and max=, or neither";
    const char *problem = annotation_number("default", a->def_text, is_bool, &a->def, why, cap);
    if (!problem && a->has_min)
        problem = annotation_number("min", min_text, is_bool, &a->min, why, cap);
    if (!problem && a->has_max)
        problem = annotation_number("max", max_text, is_bool, &a->max, why, cap);
    return problem;
}

/* The push-constant block's lines: from the line with `push_constant` to
 * the closing brace. Each member is found on its line by name. */
typedef struct member_line {
    char file[VRG_PATH_MAX];
    int line;
    int members_on_line;
    int is_bool;
    const char *comment;
    size_t comment_len;
} member_line;

/* The source with each block comment blanked out (its newlines kept, so
 * the lines still count): a brace or `push_constant` in a comment is no
 * code. A block comment's opener inside a // comment is comment text. */
static char *strip_block_comments(const char *src)
{
    char *out = strdup(src);
    if (!out)
        return NULL;
    for (char *c = out; *c; c++) {
        if (c[0] == '/' && c[1] == '/') {
            while (c[1] && c[1] != '\n')
                c++;
        } else if (c[0] == '/' && c[1] == '*') {
            c[0] = c[1] = ' ';
            for (c += 2; *c && !(c[0] == '*' && c[1] == '/'); c++)
                if (*c != '\n')
                    *c = ' ';
            if (!*c)
                break;
            c[0] = c[1] = ' ';
            c++;
        }
    }
    return out;
}

/* Where `word` occurs as a whole word in s[0..n), or -1. */
static long word_at(const char *s, size_t n, const char *word)
{
    size_t w = strlen(word);
    for (size_t i = 0; w && i + w <= n; i++)
        if (strncmp(s + i, word, w) == 0 && (i == 0 || !word_char(s[i - 1])) && (i + w == n || !word_char(s[i + w])))
            return (long)i;
    return -1;
}

/* src: the source without block comments. The member is the first whole
 * word `member` inside the block's braces, on any of its lines: the one
 * with `{`, or the one with `}` before the brace. */
static int find_member(const char *src, const char *member, const _vrg_reflection *r, member_line *out)
{
    src_reader rd = {.p = src};
    src_line l;
    int in_block = 0, depth = 0;
    while (next_line(&rd, &l)) {
        const char *comment;
        size_t n = code_len(l.text, l.len, &comment);
        if (!in_block) {
            if (!has_word(l.text, n, "push_constant"))
                continue;
            in_block = 1;
        }
        int entered = depth > 0;
        for (size_t i = 0, from = 0; i <= n; i++) {
            if (i < n && l.text[i] != '{' && l.text[i] != '}')
                continue;
            /* the code between braces: inside the block when depth > 0 */
            long at = depth > 0 ? word_at(l.text + from, i - from, member) : -1;
            if (at >= 0) {
                snprintf(out->file, sizeof out->file, "%s", l.file);
                out->line = l.line;
                out->members_on_line = 0;
                for (int m = 0; m < r->push_member_count; m++)
                    out->members_on_line += has_word(l.text, n, r->push_members[m].name);
                out->is_bool = has_word(l.text, n, "bool");
                out->comment = comment;
                out->comment_len = comment ? l.len - (size_t)(comment - l.text) : 0;
                return 0;
            }
            if (i < n) {
                depth += l.text[i] == '{' ? 1 : -1;
                entered |= depth > 0;
                from = i + 1;
                if (entered && depth <= 0)
                    return -1; /* the block's closing brace */
            }
        }
    }
    return -1;
}

static int parse_params(struct _vrg_shader_pass *sp, vrg_plugin_desc *desc, const char *src, const _vrg_reflection *r, _vrg_diag *d)
{
    char pfile[VRG_PATH_MAX];
    int pline = split_where(r->push_where, pfile, sizeof pfile);
    int errors = d->errors;
    if (r->push_member_count > VRG_MAX_PARAMS) {
        shader_error(d, pfile, pline, NULL, "push-constant block '%s' has %d members, more than the %d parameters a pass may have", r->push_name,
                     r->push_member_count, VRG_MAX_PARAMS);
        return -1;
    }
    static const char *form = "one member per line: `float density; // @param default=0.02 min=0 max=1 help=\"what it does\"` (docs/plugin-abi.md)";
    char *code = strip_block_comments(src);
    if (!code) {
        _vrg_error(d, VRG_E_OUT_OF_MEMORY, "%s: out of memory reading the push-constant block", pfile);
        return -1;
    }
    /* the runtime packs the values into this many bytes (dispatch.c), the
     * push-constant size every Vulkan device has */
    int past_limit = 0;
    for (int m = 0; m < r->push_member_count; m++) {
        const _vrg_push_member *pm = &r->push_members[m];
        member_line ml;
        int found = find_member(code, pm->name, r, &ml) == 0;
        if ((uint64_t)pm->offset + pm->size > VRG_SHADER_PASS_PUSH_MAX) {
            past_limit = 1;
            shader_error(d, found ? ml.file : pfile, found ? ml.line : pline, "a pass's parameters take at most 128 bytes: 32 scalars at offsets 0 to 124",
                         "push-constant member '%s' lies at bytes %u to %u of block '%s', past the %d bytes a pass's parameters may take", pm->name, pm->offset,
                         pm->offset + pm->size - 1, r->push_name, VRG_SHADER_PASS_PUSH_MAX);
        }
    }
    if (r->push_bytes > VRG_SHADER_PASS_PUSH_MAX && !past_limit)
        shader_error(d, pfile, pline, "a pass's parameters take at most 128 bytes: 32 scalars at offsets 0 to 124",
                     "push-constant block '%s' is %u bytes, more than the %d a pass's parameters may take", r->push_name, r->push_bytes, VRG_SHADER_PASS_PUSH_MAX);
    if (d->errors > errors) {
        free(code);
        return -1;
    }
    for (int m = 0; m < r->push_member_count; m++) {
        const _vrg_push_member *pm = &r->push_members[m];
        member_line ml;
        if (find_member(code, pm->name, r, &ml) != 0) {
            shader_error(d, pfile, pline, form, "push-constant member '%s' of block '%s': its declaring line is not found (a member named by a macro?)", pm->name,
                         r->push_name);
            continue;
        }
        if (pm->scalar == VRG_PUSH_OTHER || pm->vecsize != 1 || pm->columns != 1 || pm->array_dims) {
            shader_error(d, ml.file, ml.line, "a pass computes vectors from scalar parameters in the shader",
                         "push-constant member '%s' is not a scalar float, int, uint or bool: each member is a parameter", pm->name);
            continue;
        }
        if (ml.members_on_line != 1) {
            shader_error(d, ml.file, ml.line, form, "push-constant members share line %d: declare each parameter on its own line with its @param annotation", ml.line);
            continue;
        }
        int is_bool = pm->scalar == VRG_PUSH_BOOL || ml.is_bool;
        if (strcmp(pm->name, "plugin") == 0 || strcmp(pm->name, "output_scale") == 0) {
            shader_error(d, ml.file, ml.line, "plugin and output_scale are the graph's keys in a [pass] section: rename the member",
                         "push-constant member '%s' has a name the graph file keeps for itself", pm->name);
            continue;
        }
        if (!ml.comment) {
            shader_error(d, ml.file, ml.line, form, "push-constant member '%s' has no @param annotation", pm->name);
            continue;
        }
        annotation a;
        char why[256];
        const char *problem = parse_annotation(ml.comment, ml.comment_len, is_bool, &a, why, sizeof why);
        if (problem) {
            shader_error(d, ml.file, ml.line, form, "push-constant member '%s': malformed @param annotation: %s", pm->name, problem);
            continue;
        }
        if (a.has_choices) { /* a string parameter: the member gets its index */
            static const char *choice_form = "`int curve; // @param choices=aces,reinhard,linear default=aces help=\"...\"` (docs/plugin-abi.md)";
            if (is_bool || (pm->scalar != VRG_PUSH_INT && pm->scalar != VRG_PUSH_UINT)) {
                shader_error(d, ml.file, ml.line, choice_form, "push-constant member '%s' has choices=, but it is a %s: the index of the choice goes into an int or uint",
                             pm->name, is_bool ? "bool" : "float");
                continue;
            }
            snprintf(sp->choice_text[m], sizeof sp->choice_text[m], "%s", a.choices);
            snprintf(sp->param_default[m], sizeof sp->param_default[m], "%s", a.def_text);
            snprintf(sp->param_names[m], sizeof sp->param_names[m], "%s", pm->name);
            snprintf(sp->param_help[m], sizeof sp->param_help[m], "%s", a.help);
            vrg_param_desc *pd = &sp->params[m];
            *pd = (vrg_param_desc){.name = sp->param_names[m], .type = VRG_PARAM_STRING, .help = sp->param_help[m], .default_string = sp->param_default[m]};
            if ((problem = _vrg_choices_problem(pd, sp->choice_text[m], why, sizeof why))) {
                shader_error(d, ml.file, ml.line, choice_form, "push-constant member '%s': @param %s", pm->name, problem);
                continue;
            }
            sp->choices[m] = sp->choice_text[m];
            if (a.variant) {
                if (sp->axis_count == (int)(sizeof sp->axes / sizeof sp->axes[0])) {
                    shader_error(d, ml.file, ml.line, NULL, "push-constant member '%s': more than %d optional slots and variant choices", pm->name,
                                 (int)(sizeof sp->axes / sizeof sp->axes[0]));
                    continue;
                }
                struct _vrg_shader_axis *ax = &sp->axes[sp->axis_count++];
                *ax = (struct _vrg_shader_axis){.slot = -1, .param = m, .count = _vrg_choice_count(sp->choice_text[m])};
                upper_define(ax->define, sizeof ax->define, "", pm->name);
                snprintf(sp->axis_where[sp->axis_count - 1], sizeof sp->axis_where[0], "%s:%d", ml.file, ml.line);
            }
            continue;
        }
        /* what the member's type holds: the value is cast to it when packed */
        if (!is_bool) {
            double lo = pm->scalar == VRG_PUSH_INT ? -2147483648.0 : pm->scalar == VRG_PUSH_UINT ? 0 : -FLT_MAX;
            double hi = pm->scalar == VRG_PUSH_INT ? 2147483647.0 : pm->scalar == VRG_PUSH_UINT ? 4294967295.0 : FLT_MAX;
            const char *type = pm->scalar == VRG_PUSH_INT ? "an int" : pm->scalar == VRG_PUSH_UINT ? "a uint" : "a float";
            const char *key = NULL;
            double v = 0;
            if (a.def < lo || a.def > hi)
                key = "default", v = a.def;
            else if (a.has_min && (a.min < lo || a.min > hi))
                key = "min", v = a.min;
            else if (a.has_max && (a.max < lo || a.max > hi))
                key = "max", v = a.max;
            if (key) {
                shader_error(d, ml.file, ml.line, NULL, "push-constant member '%s' is %s: its %s= is %g, outside [%.10g, %.10g], what it holds", pm->name, type, key, v, lo, hi);
                continue;
            }
        }
        vrg_param_desc *pd = &sp->params[m];
        snprintf(sp->param_names[m], sizeof sp->param_names[m], "%s", pm->name);
        snprintf(sp->param_help[m], sizeof sp->param_help[m], "%s", a.help);
        *pd = (vrg_param_desc){.name = sp->param_names[m], .default_value = a.def, .min = a.min, .max = a.max, .help = sp->param_help[m]};
        pd->type = is_bool ? VRG_PARAM_BOOL : pm->scalar == VRG_PUSH_FLOAT ? VRG_PARAM_FLOAT : VRG_PARAM_INT;
        if (pm->scalar == VRG_PUSH_UINT && !is_bool) {
            if (!a.has_min)
                pd->min = 0, pd->max = 4294967295.0;
            else if (a.min < 0) {
                shader_error(d, ml.file, ml.line, NULL, "push-constant member '%s' is a uint: its min= is %g, below 0", pm->name, a.min);
                continue;
            }
        }
        if (is_bool && !a.has_min)
            pd->min = 0, pd->max = 1;
        if (pm->scalar == VRG_PUSH_INT && !is_bool && !a.has_min) /* what the member holds */
            pd->min = -2147483648.0, pd->max = 2147483647.0;
        /* the descriptor's checks (range, whole numbers), here at the line */
        if ((problem = _vrg_param_problem(pd, why, sizeof why)))
            shader_error(d, ml.file, ml.line, form, "push-constant member '%s': @param %s", pm->name, problem);
    }
    free(code);
    desc->params = sp->params;
    desc->param_count = (uint32_t)r->push_member_count;
    for (int m = 0; m < r->push_member_count; m++)
        if (sp->choices[m])
            desc->param_choices = sp->choices;
    return d->errors > errors ? -1 : 0;
}

/* ---- slots from bindings ---- */

static int by_binding(const void *a, const void *b)
{
    const _vrg_reflected_binding *x = *(const _vrg_reflected_binding *const *)a, *y = *(const _vrg_reflected_binding *const *)b;
    return x->binding < y->binding ? -1 : x->binding > y->binding;
}

/* The text of FILE:LINE in the expanded source, 0 if it is not there. */
static int line_text(const char *src, const char *file, int line, const char **text, size_t *len)
{
    src_reader rd = {.p = src};
    src_line l;
    while (next_line(&rd, &l))
        if (l.line == line && strcmp(l.file, file) == 0) {
            *text = l.text, *len = l.len;
            return 1;
        }
    return 0;
}

/* A binding line's annotation: `// @optional [help="..."]`; a comment not
 * starting with @ is no annotation. NULL, or why it cannot be read. */
static const char *parse_slot_annotation(const char *text, size_t len, int *optional, char *help, size_t help_cap, char *why, size_t cap)
{
    const char *comment;
    code_len(text, len, &comment);
    *optional = 0;
    help[0] = '\0';
    if (!comment)
        return NULL;
    const char *s = comment, *end = text + len;
    while (s < end && isspace((unsigned char)*s))
        s++;
    if (s >= end || *s != '@')
        return NULL;
    const char *word = s;
    while (s < end && !isspace((unsigned char)*s))
        s++;
    if ((size_t)(s - word) != 9 || strncmp(word, "@optional", 9) != 0)
        return snprintf(why, cap, "unknown annotation '%.*s' on a binding (a binding takes @optional [help=\"...\"])", (int)(s - word > 32 ? 32 : s - word), word), why;
    *optional = 1;
    while (s < end && isspace((unsigned char)*s))
        s++;
    if (s < end && *s != '\r') {
        if ((size_t)(end - s) < 6 || strncmp(s, "help=\"", 6) != 0)
            return snprintf(why, cap, "expected help=\"...\" after @optional at '%.*s'", (int)(end - s > 24 ? 24 : end - s), s), why;
        s += 6;
        size_t o = 0;
        while (s < end && *s != '"') {
            if (*s == '\\' && s + 1 < end)
                s++;
            if (o + 1 < help_cap)
                help[o++] = *s;
            s++;
        }
        if (s >= end)
            return "help's quoted text has no closing '\"'";
        help[o] = '\0';
        for (s++; s < end && isspace((unsigned char)*s); s++)
            ;
        if (s < end)
            return snprintf(why, cap, "unexpected '%.*s' after help=\"...\"", (int)(end - s > 24 ? 24 : end - s), s), why;
    }
    return NULL;
}

static int parse_slots(struct _vrg_shader_pass *sp, vrg_plugin_desc *desc, const char *src, const _vrg_reflection *r, _vrg_diag *d)
{
    static const char *naming = "a shader-only pass's bindings are its slots by name: in_X (input X), out_X (output X), or frame.glsl's `frame` block";
    int errors = d->errors;
    const _vrg_reflected_binding *sorted[VRG_MAX_BINDINGS];
    char file[VRG_PATH_MAX];
    if (r->count > VRG_MAX_BINDINGS) {
        int line = split_where(r->bindings[VRG_MAX_BINDINGS].where, file, sizeof file);
        shader_error(d, file, line, NULL, "the shader declares %d bindings, more than the %d a dispatch binds", r->count, VRG_MAX_BINDINGS);
        return -1;
    }
    for (int i = 0; i < r->count; i++)
        sorted[i] = &r->bindings[i];
    qsort(sorted, (size_t)r->count, sizeof *sorted, by_binding);
    for (int i = 0; i < r->count; i++) {
        const _vrg_reflected_binding *b = sorted[i];
        int line = split_where(b->where, file, sizeof file);
        vrg_slot_desc *s = &sp->slots[i];
        const char *name = b->name;
        int is_in = strncmp(name, "in_", 3) == 0 && name[3], is_out = strncmp(name, "out_", 4) == 0 && name[4];
        int is_frame = strcmp(name, "frame") == 0 && b->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        if (b->set != 0) {
            shader_error(d, file, line, NULL, "binding '%s' is in set %u: a pass binds set 0 only", name, b->set);
            continue;
        }
        if ((int)b->binding != i) {
            shader_error(d, file, line, "number the bindings 0, 1, 2, ... in any order of slots", "binding '%s' is binding %u, but the shader's bindings are not numbered 0 to %d without gaps",
                         name, b->binding, r->count - 1);
            continue;
        }
        if (!is_in && !is_out && !is_frame) {
            shader_error(d, file, line, naming, "binding '%s' is neither in_NAME nor out_NAME, so it is no slot", name);
            continue;
        }
        const char *slot = is_frame ? name : name + (is_in ? 3 : 4);
        snprintf(sp->slot_names[i], sizeof sp->slot_names[i], "%s", slot);
        *s = (vrg_slot_desc){.name = sp->slot_names[i], .dir = is_out ? VRG_OUT : VRG_IN, .help = sp->slot_help[i]};
        const char *what = NULL;
        switch (b->type) {
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            s->kind = VRG_IMAGE, s->access = VRG_ACCESS_SAMPLED, what = "sampled image";
            if (is_out)
                shader_error(d, file, line, "an output is a storage image or buffer the shader writes", "binding '%s' is a sampler, which cannot be written: an output is a writeonly storage image", name);
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
            s->kind = VRG_IMAGE, what = "storage image";
            s->access = b->readonly ? VRG_ACCESS_STORAGE_READ : b->writeonly ? VRG_ACCESS_STORAGE_WRITE : VRG_ACCESS_STORAGE_READ_WRITE;
            s->format = b->format;
            if (is_in && s->access != VRG_ACCESS_STORAGE_READ)
                shader_error(d, file, line, "declare it `readonly`, or name it out_X", "binding '%s' is an input, but its storage image is not declared readonly", name);
            if (is_out && s->access == VRG_ACCESS_STORAGE_READ)
                shader_error(d, file, line, "an output is writeonly (or read and written)", "binding '%s' is an output, but it is declared readonly", name);
            if (b->spv_format && (!b->format || _vrg_format_parse(_vrg_format_name(b->format)) != b->format)) { /* not one a graph can name */
                const char *q = _vrg_spv_format_glsl(b->spv_format);
                char unknown[48];
                if (!q)
                    snprintf(unknown, sizeof unknown, "(SPIR-V image format %d)", b->spv_format), q = unknown;
                shader_error(d, file, line, "use one a graph can name, as GLSL writes it (r11g11b10f is r11f_g11f_b10f)",
                             "binding '%s': format qualifier %s is not one voxrg allocates (%s)", name, q, _vrg_format_list());
            } else if (is_out && !b->format)
                shader_error(d, file, line, "layout(binding = N, rgba16f) uniform writeonly image2D out_X;", "binding '%s' is an output with no format qualifier: its format is the output's", name);
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
            s->kind = VRG_BUFFER, what = "storage buffer";
            s->access = b->readonly ? VRG_ACCESS_STORAGE_READ : b->writeonly ? VRG_ACCESS_STORAGE_WRITE : VRG_ACCESS_STORAGE_READ_WRITE;
            if (is_in && s->access != VRG_ACCESS_STORAGE_READ)
                shader_error(d, file, line, "declare it `readonly`, or name it out_X", "binding '%s' is an input, but its buffer is not declared readonly", name);
            if (is_out && (b->runtime_array || !b->block_bytes))
                shader_error(d, file, line, "give the array a length: the output's size is the block's", "binding '%s' is an output buffer of no fixed size (it ends in an unsized array)", name);
            if (is_out)
                s->size = b->block_bytes;
            break;
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
            s->kind = VRG_BUFFER, s->access = VRG_ACCESS_UNIFORM, what = "uniform block";
            if (is_out)
                shader_error(d, file, line, NULL, "binding '%s' is a uniform block, which cannot be written: an output is a storage buffer", name);
            break;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
            s->kind = VRG_BUFFER, s->access = VRG_ACCESS_TEXEL_READ, what = "texel buffer";
            if (is_out)
                shader_error(d, file, line, NULL, "binding '%s' is a texel buffer, which cannot be written: an output is a storage buffer", name);
            break;
        case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
            s->kind = VRG_ACCEL, s->access = VRG_ACCESS_RAY_QUERY, what = "acceleration structure";
            if (is_out)
                shader_error(d, file, line, NULL, "binding '%s' is an acceleration structure, which a shader cannot write", name);
            break;
        default:
            shader_error(d, file, line, "a slot is a sampler2D, image2D, buffer, uniform block, usamplerBuffer or accelerationStructureEXT",
                         "binding '%s' is %s, which no slot binds", name, _vrg_descriptor_type_name(b->type));
            break;
        }
        if (s->kind == VRG_IMAGE && b->image_dim != 1 /* SpvDim2D */)
            shader_error(d, file, line, NULL, "binding '%s' is not a 2D image: slots hold 2D images", name);
        const char *text;
        size_t len;
        int optional = 0;
        char help[VRG_SHADER_PASS_HELP_MAX] = "", why[256];
        const char *problem = line_text(src, file, line, &text, &len) ? parse_slot_annotation(text, len, &optional, help, sizeof help, why, sizeof why) : NULL;
        if (problem)
            shader_error(d, file, line, "`layout(binding = 3) uniform sampler2D in_emission; // @optional help=\"...\"` (docs/plugin-abi.md)", "binding '%s': %s", name,
                         problem);
        if (optional && s->kind == VRG_ACCEL && i != r->count - 1)
            shader_error(d, file, line, "declare it last: where it is not bound, its variant does not declare it",
                         "binding '%s': an optional acceleration structure is the last binding (binding %d here)", name, r->count - 1);
        if (optional) {
            s->flags |= VRG_SLOT_OPTIONAL;
            if (sp->axis_count == (int)(sizeof sp->axes / sizeof sp->axes[0]))
                shader_error(d, file, line, NULL, "binding '%s': more than %d optional slots and variant choices", name, (int)(sizeof sp->axes / sizeof sp->axes[0]));
            else {
                struct _vrg_shader_axis *ax = &sp->axes[sp->axis_count];
                *ax = (struct _vrg_shader_axis){.slot = i, .param = -1, .count = 2};
                upper_define(ax->define, sizeof ax->define, "HAS_", slot);
                snprintf(sp->axis_where[sp->axis_count++], sizeof sp->axis_where[0], "%s", b->where);
            }
        }
        if (help[0])
            snprintf(sp->slot_help[i], sizeof sp->slot_help[i], "%s", help);
        else
            snprintf(sp->slot_help[i], sizeof sp->slot_help[i], "%s %s (%s)", what ? what : "binding", name, b->where);
        snprintf(sp->slot_where[i], sizeof sp->slot_where[i], "%s", b->where);
        for (int j = 0; j < i; j++)
            if (strcmp(sp->slot_names[j], slot) == 0 && sp->slots[j].dir == s->dir)
                shader_error(d, file, line, NULL, "binding '%s' names slot %s.%s a second time", name, is_out ? "out" : "in", slot);
        snprintf(sp->binding_res[i], sizeof sp->binding_res[i], "%s.%s", is_out ? "out" : "in", slot);
        sp->dispatch.bindings[i].res = sp->binding_res[i];
    }
    desc->slots = sp->slots;
    desc->slot_count = (uint32_t)r->count;
    /* the dispatch covers the first image output always written: an
     * optional one unread is a 1x1 stand-in */
    for (int i = 0; i < r->count && !sp->domain[0]; i++)
        if (sp->slots[i].dir == VRG_OUT && sp->slots[i].kind == VRG_IMAGE && !(sp->slots[i].flags & VRG_SLOT_OPTIONAL))
            snprintf(sp->domain, sizeof sp->domain, "out.%s", sp->slot_names[i]);
    for (int i = 0; i < r->count && !sp->domain[0]; i++)
        if (sp->slots[i].dir == VRG_OUT && sp->slots[i].kind == VRG_IMAGE) {
            int line = split_where(sp->slot_where[i], file, sizeof file);
            shader_error(d, file, line, "leave one image output required: it sets the dispatch size",
                         "binding 'out_%s': every image output is @optional, and an unread one is 1x1: none sets the dispatch size", sp->slot_names[i]);
            break;
        }
    return d->errors > errors ? -1 : 0;
}

/* One listed dispatch per variant: the product of the axes' values, the
 * first axis varying fastest (_vrg_shader_pass_execute picks by that). */
static int make_variants(struct _vrg_shader_pass *sp, vrg_plugin_desc *desc, _vrg_diag *d)
{
    char file[VRG_PATH_MAX];
    int total = 1;
    for (int a = 0; a < sp->axis_count; a++) {
        for (int b = 0; b < a; b++)
            if (strcmp(sp->axes[a].define, sp->axes[b].define) == 0) {
                int line = split_where(sp->axis_where[a], file, sizeof file);
                shader_error(d, file, line, NULL, "its variant's define %s is also that of %s: rename one", sp->axes[a].define, sp->axis_where[b]);
                return -1;
            }
        total *= sp->axes[a].count;
        if (total > VRG_SHADER_PASS_VARIANTS) {
            int line = split_where(sp->axis_where[a], file, sizeof file);
            shader_error(d, file, line, "read an optional slot's or a choice's value at run time instead (a push member, not #ifdef)",
                         "the optional slots and variant choices up to here make %d variants, more than the %d a shader-only pass compiles", total,
                         VRG_SHADER_PASS_VARIANTS);
            return -1;
        }
    }
    for (int k = 0; k < total; k++) {
        vrg_dispatch_desc *v = &sp->dispatches[k];
        *v = sp->dispatch;
        char *defs = sp->defines[k];
        size_t o = 0;
        defs[0] = '\0';
        for (int a = 0, rest = k; a < sp->axis_count; rest /= sp->axes[a].count, a++) {
            int value = rest % sp->axes[a].count;
            if (sp->axes[a].slot >= 0 && !value)
                continue; /* HAS_X only when X is connected */
            char text[16];
            snprintf(text, sizeof text, "%d", sp->axes[a].slot >= 0 ? 1 : value);
            if (append_define(defs, sizeof sp->defines[k], &o, sp->axes[a].define, text) != 0) {
                int line = split_where(sp->axis_where[a], file, sizeof file);
                shader_error(d, file, line, NULL, "the variants' defines take more than %zu characters", sizeof sp->defines[k] - 1);
                return -1;
            }
        }
        v->defines = o ? defs : NULL;
        /* an optional acceleration structure has no stand-in: where it is
         * absent its binding (the last, parse_slots) is not bound, and the
         * variant does not declare it */
        for (int a = 0, rest = k; a < sp->axis_count; rest /= sp->axes[a].count, a++)
            if (sp->axes[a].slot >= 0 && !(rest % sp->axes[a].count) && sp->slots[sp->axes[a].slot].kind == VRG_ACCEL)
                v->bindings[sp->axes[a].slot].res = NULL;
    }
    desc->dispatches = sp->dispatches;
    desc->dispatch_count = (uint32_t)total;
    return 0;
}

/* "NAME=0 ..." for each push member annotated `variant` (read before the
 * shader compiles, which needs them): the first variant's defines. A
 * member is the last word before the `;` of the annotated line's code. */
static void variant_defines(const char *expanded, char *out, size_t cap)
{
    src_reader rd = {.p = expanded};
    src_line l;
    size_t o = 0;
    out[0] = '\0';
    while (next_line(&rd, &l)) {
        const char *comment;
        size_t n = code_len(l.text, l.len, &comment);
        annotation a;
        char why[256];
        if (!comment || parse_annotation(comment, l.len - (size_t)(comment - l.text), 0, &a, why, sizeof why) || !a.variant)
            continue;
        char name[VRG_NAME_MAX], define[VRG_NAME_MAX + 8];
        if (declared_name(l.text, n, name) != 0)
            continue; /* not a member: parse_params says so at its line */
        upper_define(define, sizeof define, "", name);
        if (append_define(out, cap, &o, define, "0") != 0)
            return; /* make_variants reports defines past their room */
    }
}

/* "HAS_X=1 ..." for each binding annotated @optional (read before the
 * shader compiles): the interface is read with every optional slot
 * connected, so that a binding its variant declares only where it is
 * bound (an acceleration structure, which has no stand-in) is seen. The
 * binding is the last word before the `;` of the annotated line's code. */
static void optional_defines(const char *expanded, char *out, size_t cap)
{
    src_reader rd = {.p = expanded};
    src_line l;
    size_t o = strlen(out);
    while (next_line(&rd, &l)) {
        int optional;
        char help[8], why[256];
        if (parse_slot_annotation(l.text, l.len, &optional, help, sizeof help, why, sizeof why) || !optional)
            continue;
        const char *comment;
        size_t n = code_len(l.text, l.len, &comment);
        char name[VRG_NAME_MAX], define[VRG_NAME_MAX + 8];
        if (declared_name(l.text, n, name) != 0)
            continue; /* not a binding: parse_slots says so at its line */
        if (strncmp(name, "in_", 3) != 0 && strncmp(name, "out_", 4) != 0)
            continue;
        upper_define(define, sizeof define, "HAS_", name + (name[0] == 'i' ? 3 : 4));
        if (append_define(out, cap, &o, define, "1") != 0)
            return; /* make_variants reports defines past their room */
    }
}

/* ---- the pass ---- */

/* The first // comment of the file itself (before any code but #version
 * and #define): the help. */
static void first_comment(const char *src, const char *path, char *out, size_t cap)
{
    snprintf(out, cap, "shader-only pass");
    src_reader rd = {.p = src};
    src_line l;
    while (next_line(&rd, &l)) {
        if (l.file[0] && strcmp(l.file, path) != 0)
            continue; /* an included file's */
        const char *s = l.text, *end = l.text + l.len;
        while (s < end && isspace((unsigned char)*s))
            s++;
        if (s == end || strncmp(s, "#version", 8) == 0 || strncmp(s, "#extension", 10) == 0 || strncmp(s, "#define", 7) == 0)
            continue;
        if (end - s >= 2 && s[0] == '/' && s[1] == '/') {
            s += 2;
            while (s < end && *s == ' ')
                s++;
            while (end > s && isspace((unsigned char)end[-1]))
                end--;
            snprintf(out, cap, "%.*s", (int)(end - s), s);
        }
        return;
    }
}

int _vrg_shader_pass_load(_vrg_plugin *p, _vrg_diag *d, int line)
{
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    FILE *out = d->out ? d->out : stderr;
    _vrg_shader_module sm;
    char *src = NULL;
    /* the interface is read from the first variant of the choices (each
     * variant choice at index 0: its define must exist to compile) with
     * every optional slot connected (HAS_X=1), where every binding is
     * declared */
    char first_variant[448] = "";
    /* the shader: the plugin's file, or a changed copy of it in
     * $VOXRG_SHADER_OVERRIDE, as for a C pass's shaders */
    char overridden[VRG_PATH_MAX];
    const char *base = strrchr(p->source, '/');
    const char *path = _vrg_shader_override(base ? base + 1 : p->source, overridden, sizeof overridden) == 0 ? overridden : p->source;
    char *expanded = _vrg_shader_expand(path, mem ? mem : out);
    int expands = expanded != NULL;
    if (expanded) {
        variant_defines(expanded, first_variant, sizeof first_variant);
        optional_defines(expanded, first_variant, sizeof first_variant);
    }
    free(expanded);
    /* without a device: what the shader declares does not depend on it */
    int rc = expands ? _vrg_shader_compile_source(NULL, path, first_variant, &sm, mem ? mem : out, &src) : -1;
    if (mem) {
        fclose(mem);
        fputs(text ? text : "", out);
        free(text);
    }
    if (rc != 0) {
        _vrg_diag_code code = VRG_E_SHADER_FAILED;
        if (line > 0)
            _vrg_error_at(d, line, code, NULL, "plugin '%s' (%s): the shader does not compile (above)", p->name, path);
        else
            _vrg_error(d, code, "plugin '%s' (%s): the shader does not compile (above)", p->name, path);
        return -1;
    }
    struct _vrg_shader_pass *sp = calloc(1, sizeof *sp);
    if (!sp) {
        free(src);
        free(sm.deps);
        _vrg_reflection_free(&sm.refl);
        _vrg_error(d, VRG_E_OUT_OF_MEMORY, "plugin '%s' (%s): out of memory", p->name, p->source);
        return -1;
    }
    vrg_plugin_desc *desc = &p->desc_copy;
    memset(desc, 0, sizeof *desc);
    desc->abi_version = VRG_ABI_VERSION;
    /* the plugin's file: each compile looks for an override again */
    snprintf(sp->shader, sizeof sp->shader, "%s", p->source);
    first_comment(src, path, sp->help, sizeof sp->help);
    *desc = (vrg_plugin_desc){.abi_version = VRG_ABI_VERSION, .name = p->name, .kind = VRG_PLUGIN_PASS, .help = sp->help};
    /* no execute: each frame the runtime records one dispatch, of the variant the pass's
     * connections and choices pick (record.c, _vrg_shader_pass_execute) */
    int errors = d->errors;
    if (strlen(p->source) >= sizeof sp->shader)
        _vrg_error(d, VRG_E_SHADER_INTERFACE, "plugin '%s': its path %s is longer than %zu characters", p->name, p->source, sizeof sp->shader - 1);
    parse_slots(sp, desc, src, &sm.refl, d);
    parse_params(sp, desc, src, &sm.refl, d);
    /* pixel.glsl's loop when the shader includes it, else one invocation per pixel */
    int pixel_loop = 0;
    for (const char *dep = sm.deps; dep && *dep;) {
        const char *nl = strchr(dep, '\n');
        size_t n = nl ? (size_t)(nl - dep) : strlen(dep);
        pixel_loop |= n >= 11 && strncmp(dep + n - 11, "/pixel.glsl", 11) == 0;
        dep = nl ? nl + 1 : dep + n;
    }
    sp->dispatch.shader = sp->shader;
    sp->dispatch.push_size = 0; /* packed by name (dispatch.c), as a C pass's */
    sp->dispatch.pixel_loop = pixel_loop;
    sp->dispatch.domain = sp->domain[0] ? sp->domain : NULL;
    if (d->errors == errors)
        make_variants(sp, desc, d);
    free(src);
    free(sm.deps);
    _vrg_reflection_free(&sm.refl);
    if (d->errors > errors) {
        if (line > 0)
            _vrg_error_at(d, line, VRG_E_SHADER_INTERFACE, "docs/plugin-abi.md, \"A pass in one file\"", "plugin '%s' (%s): its interface has errors (above)",
                          p->name, p->source);
        free(sp);
        memset(desc, 0, sizeof *desc);
        return -1;
    }
    p->shader_pass = sp;
    p->desc = desc;
    return 0;
}

const char *_vrg_shader_pass_slot_where(const _vrg_plugin *p, const vrg_slot_desc *sd)
{
    const struct _vrg_shader_pass *sp = p ? p->shader_pass : NULL;
    if (!sp || sd < sp->slots || sd >= sp->slots + VRG_MAX_SLOTS)
        return NULL;
    return sp->slot_where[sd - sp->slots];
}

void _vrg_shader_pass_free(_vrg_plugin *p)
{
    free(p->shader_pass);
    p->shader_pass = NULL;
}
