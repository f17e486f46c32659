#define _DEFAULT_SOURCE
/* Diagnostics: every error names file:line where there is one, plus a hint.
 * While a graph loads they are collected and printed sorted by line, so one
 * run lists every problem in file order; afterwards they print at once. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

static FILE *diag_out(vrg_diag *d) { return d->out ? d->out : stderr; }

static void add(vrg_diag *d, int line, const char *text)
{
    if (!d->collect) {
        fputs(text, diag_out(d));
        return;
    }
    if (d->count == d->cap) {
        d->cap = d->cap ? d->cap * 2 : 16;
        d->entries = realloc(d->entries, d->cap * sizeof *d->entries);
    }
    d->entries[d->count++] = (vrg_diag_entry){line, d->count, strdup(text)};
}

static void vadd(vrg_diag *d, int line, const char *prefix, const char *hint, const char *fmt, va_list ap)
{
    char msg[2048];
    int n = snprintf(msg, sizeof msg, "%s", prefix);
    if (n < (int)sizeof msg)
        n += vsnprintf(msg + n, sizeof msg - (size_t)n, fmt, ap);
    if (n < (int)sizeof msg)
        n += snprintf(msg + n, sizeof msg - (size_t)n, "\n");
    if (hint && n < (int)sizeof msg)
        snprintf(msg + n, sizeof msg - (size_t)n, "  hint: %s\n", hint);
    add(d, line, msg);
}

void vrg_error_at(vrg_diag *d, int line, const char *hint, const char *fmt, ...)
{
    char prefix[1100];
    snprintf(prefix, sizeof prefix, "%s:%d: error: ", d->file ? d->file : "<graph>", line > 0 ? line : 1);
    va_list ap;
    va_start(ap, fmt);
    vadd(d, line > 0 ? line : 1, prefix, hint, fmt, ap);
    va_end(ap);
    d->errors++;
}

void vrg_error(vrg_diag *d, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd(d, INT_MAX, "error: ", NULL, fmt, ap);
    va_end(ap);
    d->errors++;
}

void vrg_note_at(vrg_diag *d, int line, const char *fmt, ...)
{
    char prefix[1100];
    snprintf(prefix, sizeof prefix, "%s:%d: note: ", d->file ? d->file : "<graph>", line);
    va_list ap;
    va_start(ap, fmt);
    vadd(d, line, prefix, NULL, fmt, ap);
    va_end(ap);
}

static int by_line(const void *a, const void *b)
{
    const vrg_diag_entry *x = a, *y = b;
    if (x->line != y->line)
        return x->line < y->line ? -1 : 1;
    return x->seq - y->seq;
}

void vrg_diag_flush(vrg_diag *d)
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
