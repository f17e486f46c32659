/* Values of a graph file rewritten in place (voxrg/graph_edit.h). The lines
 * are read the way the runtime's parser (inih) reads them: ';' and '#' start
 * comment lines, a key ends at the first '=' or ':', an inline comment starts
 * at a ';' after a blank; CRLF, CR-less and last lines without an end all
 * stay as they are. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/graph_edit.h"
#include "voxrg/plugin.h"
#include "voxrg/output.h"

typedef struct span {
    size_t start, end;
} span;

/* Where a key line's value and its line end lie, found by scan_section. */
typedef struct section_scan {
    int found;          /* the section's header */
    int has_key;        /* the key's line, its value in `value` */
    span value;
    size_t insert_at;   /* just after the section's last key line (or header) */
    const char *eol;    /* that line's end, for a line added after it */
} section_scan;

static int blank(char c) { return c == ' ' || c == '\t'; }

static span trimmed(const char *t, span s)
{
    while (s.start < s.end && blank(t[s.start]))
        s.start++;
    while (s.end > s.start && blank(t[s.end - 1]))
        s.end--;
    return s;
}

/* Header names compare with runs of blanks as one ("pass  a" is "pass a"). */
static int same_name(const char *t, span s, const char *name)
{
    size_t i = s.start;
    while (*name == ' ')
        name++;
    while (i < s.end && *name) {
        if (blank(t[i]) && *name == ' ') {
            while (i < s.end && blank(t[i]))
                i++;
            while (*name == ' ')
                name++;
        } else if (t[i++] != *name++)
            return 0;
    }
    while (*name == ' ')
        name++;
    return i == s.end && !*name;
}

/* The text of line [start, end) without its line end. */
static size_t content_end(const char *t, size_t start, size_t end)
{
    while (end > start && (t[end - 1] == '\n' || t[end - 1] == '\r'))
        end--;
    return end;
}

/* The value of a key line: after the separator and blanks, up to an inline
 * comment (';' after a blank) or the line's end, trailing blanks dropped. */
static span value_of(const char *t, size_t sep, size_t end)
{
    span v = {sep + 1, sep + 1};
    while (v.start < end && blank(t[v.start]))
        v.start++;
    v.end = v.start;
    while (v.end < end && !(t[v.end] == ';' && v.end > sep + 1 && blank(t[v.end - 1])))
        v.end++;
    while (v.end > v.start && blank(t[v.end - 1]))
        v.end--;
    return v;
}

static void scan_section(const char *t, const char *section, const char *key, section_scan *out)
{
    memset(out, 0, sizeof *out);
    int inside = 0;
    for (size_t pos = 0; t[pos];) {
        size_t next = pos;
        while (t[next] && t[next] != '\n' && t[next] != '\r')
            next++;
        const char *eol = t[next] == '\r' && t[next + 1] == '\n' ? "\r\n" : t[next] == '\r' ? "\r" : t[next] ? "\n" : NULL;
        size_t line_end = next + (eol ? strlen(eol) : 0);
        span line = trimmed(t, (span){pos, content_end(t, pos, line_end)});
        if (line.start < line.end && t[line.start] == '[') {
            const char *close = memchr(t + line.start, ']', line.end - line.start);
            if (inside || !close) /* a later section with the same name is not edited */
                inside = 0;
            else if (same_name(t, trimmed(t, (span){line.start + 1, (size_t)(close - t)}), section)) {
                inside = out->found = 1;
                out->insert_at = line_end, out->eol = eol;
            }
        } else if (inside && line.start < line.end && t[line.start] != ';' && t[line.start] != '#') {
            size_t sep = line.start + strcspn(t + line.start, "=:");
            if (sep < line.end) {
                span k = trimmed(t, (span){line.start, sep});
                if (k.end - k.start == strlen(key) && memcmp(t + k.start, key, k.end - k.start) == 0)
                    out->has_key = 1, out->value = value_of(t, sep, line.end);
                out->insert_at = line_end, out->eol = eol;
            }
        }
        pos = line_end;
    }
}

/* The file's own line end (its first one), "\n" in a file of one line. */
static const char *file_eol(const char *t)
{
    const char *c = t + strcspn(t, "\r\n");
    return c[0] == '\r' && c[1] == '\n' ? "\r\n" : c[0] == '\r' ? "\r" : "\n";
}

/* text with [at, at + cut) replaced by the parts a, b, c; NULL when out of memory. */
static char *spliced(const char *text, size_t at, size_t cut, const char *a, const char *b, const char *c)
{
    size_t n = strlen(text), add = strlen(a) + strlen(b) + strlen(c);
    char *out = malloc(n - cut + add + 1);
    if (!out)
        return NULL;
    memcpy(out, text, at);
    snprintf(out + at, add + 1, "%s%s%s", a, b, c);
    memcpy(out + at + add, text + at + cut, n - at - cut + 1);
    return out;
}

static char *apply_one(const char *path, const char *text, const vrg_graph_edit *e, FILE *diag)
{
    section_scan s;
    scan_section(text, e->section, e->key, &s);
    if (!s.found) {
        fprintf(diag, "error: %s: no [%s] section to set %s in\n", path, e->section, e->key);
        return NULL;
    }
    char *out;
    if (s.has_key) /* "key =" with no blank after it gets one */
        out = spliced(text, s.value.start, s.value.end - s.value.start,
                      s.value.start == s.value.end && !blank(text[s.value.start - 1]) ? " " : "", e->value, "");
    else {
        char line[1024];
        const char *eol = s.eol ? s.eol : file_eol(text);
        snprintf(line, sizeof line, "%s%s = %s%s", s.eol ? "" : eol, e->key, e->value, s.eol ? eol : "");
        out = spliced(text, s.insert_at, 0, line, "", "");
    }
    if (!out)
        fprintf(diag, "error: %s: out of memory\n", path);
    return out;
}

char *vrg_graph_edit_text(const char *path, const char *text, const vrg_graph_edit *edits, int count, FILE *diag)
{
    char *cur = strdup(text);
    for (int i = 0; cur && i < count; i++) {
        char *next = apply_one(path, cur, &edits[i], diag);
        free(cur);
        cur = next;
    }
    return cur;
}

/* The whole file (malloc'd), or NULL after a message. */
static char *read_all(const char *path, FILE *diag)
{
    FILE *f = vrg_fopen_regular(path, "rb");
    int open_errno = errno;
    char *text = NULL;
    size_t len = 0, cap = 0;
    while (f) {
        if (len + 4096 + 1 > cap) {
            char *grown = realloc(text, cap = 2 * cap + 4096 + 1);
            if (!grown)
                break;
            text = grown;
        }
        size_t got = fread(text + len, 1, cap - len - 1, f);
        len += got;
        if (got == 0) {
            text[len] = '\0';
            int failed = ferror(f) || strlen(text) != len; /* a NUL would end the text early */
            fclose(f);
            if (!failed)
                return text;
            fprintf(diag, "error: %s: cannot read it as a text file\n", path);
            free(text);
            return NULL;
        }
    }
    fprintf(diag, "error: cannot read %s: %s\n", path, f ? "out of memory" : vrg_open_strerror(open_errno));
    if (f)
        fclose(f);
    free(text);
    return NULL;
}

int vrg_graph_edit_file(const char *path, const vrg_graph_edit *edits, int count, FILE *diag)
{
    char *text = read_all(path, diag);
    char *edited = text ? vrg_graph_edit_text(path, text, edits, count, diag) : NULL;
    int rc = edited && vrg_output_write(path, edited, strlen(edited)) == 0 ? 0 : -1;
    free(text);
    free(edited);
    return rc;
}
