#define _DEFAULT_SOURCE
/* Diagnostics: every error names file:line where there is one, its code of
 * the catalogue (diag_codes.h) and a hint, as compilers do:
 *   graph.ini:12: error[VRG-E012]: unknown key 'foo' in [graph]
 * file:line comes first so that editors jump to it. While a graph loads they
 * are collected and printed sorted by line, so one run lists every problem in
 * file order; afterwards they print at once. Their text quotes files (a
 * graph's values, a plugin's words about its own files): it is escaped
 * (vrg_escape), so no byte of a file reaches the terminal as a control. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

#define VRG_DIAG_INFO(name, code, short_name, meaning) [name] = {#name, code, short_name, meaning},
static const _vrg_diag_info catalogue[VRG_DIAG_CODE_COUNT] = {VRG_DIAG_CODES(VRG_DIAG_INFO)};
#undef VRG_DIAG_INFO

const _vrg_diag_info *_vrg_diag_info_of(_vrg_diag_code code)
{
    return (unsigned)code < VRG_DIAG_CODE_COUNT ? &catalogue[code] : NULL;
}

/* A whole message escaped: its text comes from files (graph values,
 * plugins' messages about their files). Escaped text is at most 4 times as
 * long. NULL when out of memory. */
static char *escaped(const char *text, size_t len)
{
    char *out = malloc(4 * len + 1);
    return out ? (char *)vrg_escape(out, 4 * len + 1, text, len) : NULL;
}

static FILE *diag_out(_vrg_diag *d) { return d->out ? d->out : stderr; }

static void add(_vrg_diag *d, int line, const char *text)
{
    if (!d->collect) {
        fputs(text, diag_out(d));
        return;
    }
    if (d->count == d->cap) {
        int cap = d->cap ? d->cap * 2 : 16;
        _vrg_diag_entry *grown = realloc(d->entries, (size_t)cap * sizeof *grown);
        if (!grown) { /* printed now rather than lost */
            fputs(text, diag_out(d));
            return;
        }
        d->entries = grown;
        d->cap = cap;
    }
    char *copy = strdup(text);
    if (!copy) {
        fputs(text, diag_out(d));
        return;
    }
    d->entries[d->count] = (_vrg_diag_entry){line, d->count, copy};
    d->count++;
}

/* Messages are as long as they need: a file name of any length, the whole
 * message after it. */
static void vadd(_vrg_diag *d, int line, const char *kind, _vrg_diag_code code, const char *hint, const char *fmt, va_list ap)
{
    char *file = NULL, *body = NULL, *text = NULL;
    size_t fn = 0, bn = 0, tn = 0;
    FILE *f = open_memstream(&file, &fn), *b = open_memstream(&body, &bn), *t = open_memstream(&text, &tn);
    if (f && b && t) {
        const _vrg_diag_info *info = _vrg_diag_info_of(code);
        const char *id = info ? info->code : "VRG-E000";
        if (line == INT_MAX)
            fprintf(f, "%s[%s]: ", kind, id);
        else
            fprintf(f, "%s:%d: %s[%s]: ", d->file ? d->file : "<graph>", line, kind, id);
        vfprintf(b, fmt, ap);
        fclose(f), f = NULL;
        fclose(b), b = NULL;
        char *safe_file = escaped(file, fn), *safe_body = escaped(body, bn), *safe_hint = hint ? escaped(hint, strlen(hint)) : NULL;
        fprintf(t, "%s%s\n", safe_file ? safe_file : "", safe_body ? safe_body : "(out of memory escaping a message)");
        if (safe_hint)
            fprintf(t, "  hint: %s\n", safe_hint);
        fclose(t), t = NULL;
        free(safe_file);
        free(safe_body);
        free(safe_hint);
        add(d, line, text);
    } else
        fprintf(diag_out(d), "%s: (out of memory formatting a message)\n", kind);
    if (f)
        fclose(f);
    if (b)
        fclose(b);
    if (t)
        fclose(t);
    free(file);
    free(body);
    free(text);
}

void _vrg_error_at(_vrg_diag *d, int line, _vrg_diag_code code, const char *hint, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd(d, line > 0 ? line : 1, "error", code, hint, fmt, ap);
    va_end(ap);
    d->errors++;
}

void _vrg_error(_vrg_diag *d, _vrg_diag_code code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd(d, INT_MAX, "error", code, NULL, fmt, ap);
    va_end(ap);
    d->errors++;
}

void _vrg_error_hint(_vrg_diag *d, _vrg_diag_code code, const char *hint, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd(d, INT_MAX, "error", code, hint, fmt, ap);
    va_end(ap);
    d->errors++;
}

void _vrg_warning_at(_vrg_diag *d, int line, _vrg_diag_code code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd(d, line, "warning", code, NULL, fmt, ap);
    va_end(ap);
}

static int by_line(const void *a, const void *b)
{
    const _vrg_diag_entry *x = a, *y = b;
    if (x->line != y->line)
        return x->line < y->line ? -1 : 1;
    return x->seq - y->seq;
}

void _vrg_diag_flush(_vrg_diag *d)
{
    if (d->count)
        qsort(d->entries, (size_t)d->count, sizeof *d->entries, by_line);
    for (int i = 0; i < d->count; i++) {
        fputs(d->entries[i].text, diag_out(d));
        free(d->entries[i].text);
    }
    free(d->entries);
    d->entries = NULL;
    d->count = d->cap = 0;
    d->collect = 0;
}
