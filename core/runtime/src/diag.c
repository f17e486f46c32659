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

/* The length of the character at s (n bytes left) when a terminal shows
 * it as text; 0 for a control character (C0, DEL, C1), a line or paragraph
 * separator, a bidirectional control, or bytes that are not UTF-8. */
static size_t shown_char(const unsigned char *s, size_t n)
{
    if (s[0] >= 0x20 && s[0] < 0x7f)
        return 1;
    size_t len = s[0] >= 0xc2 && s[0] < 0xe0 ? 2 : s[0] >= 0xe0 && s[0] < 0xf0 ? 3 : s[0] >= 0xf0 && s[0] < 0xf5 ? 4 : 0;
    if (!len || len > n)
        return 0;
    uint32_t c = s[0] & (0x7fu >> len);
    for (size_t i = 1; i < len; i++) {
        if ((s[i] & 0xc0) != 0x80)
            return 0;
        c = c << 6 | (s[i] & 0x3fu);
    }
    static const uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (c < least[len] || c > 0x10ffff || (c >= 0xd800 && c < 0xe000))
        return 0; /* overlong, beyond Unicode, a surrogate */
    if (c < 0xa0 || c == 0x061c || c == 0x200e || c == 0x200f || (c >= 0x2028 && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069))
        return 0;
    return len;
}

/* One character of text as shown: itself, or its bytes escaped. Writes at
 * most 4 bytes to piece; returns how many, and in *used the bytes read. */
static size_t shown(const char *text, size_t left, char piece[4], size_t *used)
{
    size_t n = shown_char((const unsigned char *)text, left);
    if (n) {
        memcpy(piece, text, n);
        *used = n;
        return n;
    }
    static const char hex[] = "0123456789abcdef";
    unsigned char b = (unsigned char)*text;
    char named = b == '\n' ? 'n' : b == '\r' ? 'r' : b == '\t' ? 't' : 0;
    *used = 1;
    piece[0] = '\\';
    if (named) {
        piece[1] = named;
        return 2;
    }
    piece[1] = 'x', piece[2] = hex[b >> 4], piece[3] = hex[b & 15];
    return 4;
}

const char *vrg_escape(char *out, size_t cap, const char *text, size_t len)
{
    if (!cap)
        return out;
    char piece[4];
    size_t total = 0, used, o = 0;
    for (size_t i = 0; i < len; i += used)
        total += shown(text + i, len - i, piece, &used);
    size_t room = total < cap ? total : cap - 1 < 3 ? 0 : cap - 1 - 3; /* cut: "..." after */
    for (size_t i = 0, n; i < len && o + (n = shown(text + i, len - i, piece, &used)) <= room; i += used, o += n)
        memcpy(out + o, piece, n);
    if (total >= cap)
        for (size_t k = 0; k < 3 && o < cap - 1; k++)
            out[o++] = '.';
    out[o] = '\0';
    return out;
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
