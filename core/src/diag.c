/* Diagnostics: every error names file:line where there is one, plus a hint. */
#include "internal.h"

static FILE *diag_out(vrg_diag *d) { return d->out ? d->out : stderr; }

void vrg_error_at(vrg_diag *d, int line, const char *hint, const char *fmt, ...)
{
    FILE *f = diag_out(d);
    va_list ap;
    fprintf(f, "%s:%d: error: ", d->file ? d->file : "<graph>", line > 0 ? line : 1);
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
    if (hint)
        fprintf(f, "  hint: %s\n", hint);
    d->errors++;
}

void vrg_error(vrg_diag *d, const char *fmt, ...)
{
    FILE *f = diag_out(d);
    va_list ap;
    fputs("error: ", f);
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
    d->errors++;
}

void vrg_note(vrg_diag *d, const char *fmt, ...)
{
    FILE *f = diag_out(d);
    va_list ap;
    fputs("note: ", f);
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
}
