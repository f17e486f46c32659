/* Phase 1, parse: INI text → sections and keys with their line numbers.
 * inih does the tokenising; we feed it lines through our own reader so we
 * know which line each key came from (Debian's inih is built without
 * INI_HANDLER_LINENO). Meaning is given to the keys in validate.c. */
#include <ini.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

typedef struct line_reader {
    const char *text; /* whole file */
    size_t pos, len;
    int line;         /* line number of the line last handed to inih */
    vrg_ast *ast;
    vrg_diag *d;
} line_reader;

static char *read_line(char *str, int num, void *stream)
{
    line_reader *r = stream;
    if (r->pos >= r->len)
        return NULL;
    size_t n = 0;
    /* inih asks for at most num-1 chars; a longer line is cut and the rest
     * skipped so line numbers stay right. */
    while (r->pos + n < r->len && r->text[r->pos + n] != '\n')
        n++;
    size_t copy = n < (size_t)(num - 1) ? n : (size_t)(num - 1);
    if (n > copy) {
        vrg_error_at(r->d, r->line + 1, "split the value or shorten names", "line is longer than %d characters", num - 2);
        copy = 0; /* hand inih a blank line: no follow-on syntax error */
    }
    memcpy(str, r->text + r->pos, copy);
    str[copy] = '\0';
    r->pos += n + (r->pos + n < r->len ? 1 : 0);
    r->line++;
    return str;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    line_reader *r = user;
    vrg_ast *a = r->ast;
    /* The key belongs to the nearest header above it with this name
     * (sections were found by scan_sections, duplicates included). */
    int sec = -1;
    for (int i = a->section_count - 1; i >= 0; i--)
        if (a->sections[i].line <= r->line && strcmp(a->sections[i].name, section) == 0) { sec = i; break; }
    if (sec < 0) {
        vrg_error_at(r->d, r->line, "put every key under a [section] header", "key '%s' outside any section", name);
        return 1;
    }
    if (a->key_count >= VRG_MAX_KEYS) {
        vrg_error_at(r->d, r->line, NULL, "too many keys (at most %d)", VRG_MAX_KEYS);
        a->fatal = 1;
        return 0;
    }
    vrg_key *k = &a->keys[a->key_count++];
    snprintf(k->section, sizeof k->section, "%s", section);
    snprintf(k->name, sizeof k->name, "%s", name);
    if (strlen(value) >= sizeof k->value)
        vrg_error_at(r->d, r->line, NULL, "value of '%s' is too long (at most %zu characters)", name, sizeof k->value - 1);
    snprintf(k->value, sizeof k->value, "%s", value);
    k->line = r->line;
    k->section_index = sec;
    return 1;
}

/* Section headers are found by a scan of our own: inih does not report empty
 * sections, and a duplicate [pass a] must be seen as a second section. */
static int scan_sections(const char *text, vrg_ast *a, vrg_diag *d)
{
    int line = 0;
    const char *p = text;
    while (*p) {
        line++;
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        const char *s = p;
        while (s < p + n && (*s == ' ' || *s == '\t'))
            s++;
        if (s < p + n && *s == '[') {
            const char *close = memchr(s, ']', (size_t)(p + n - s));
            if (close) {
                if (a->section_count >= (int)(sizeof a->sections / sizeof a->sections[0])) {
                    vrg_error_at(d, line, NULL, "too many sections (at most %d)", (int)(sizeof a->sections / sizeof a->sections[0]));
                    a->fatal = 1; /* the rest of the file was not read: checking it would only mislead */
                    return -1;
                }
                vrg_section *sec = &a->sections[a->section_count++];
                size_t len = (size_t)(close - s - 1);
                /* inih strips whitespace around the name; match it */
                const char *b = s + 1;
                while (len && (*b == ' ' || *b == '\t')) { b++; len--; }
                while (len && (b[len - 1] == ' ' || b[len - 1] == '\t')) len--;
                if (len >= sizeof sec->name)
                    len = sizeof sec->name - 1;
                memcpy(sec->name, b, len);
                sec->name[len] = '\0';
                sec->line = line;
            }
        }
        p = end ? end + 1 : p + n;
    }
    return 0;
}

int vrg_parse(const char *path, const char *text, vrg_ast *ast, vrg_diag *d)
{
    char *owned = NULL;
    memset(ast, 0, sizeof *ast);
    if (!text) {
        FILE *f = fopen(path, "rb");
        if (!f) {
            vrg_error(d, "cannot open graph file '%s'", path);
            return -1;
        }
        fseek(f, 0, SEEK_END);
        long n = ftell(f);
        fseek(f, 0, SEEK_SET);
        if (n < 0 || n > (1 << 20)) {
            fclose(f);
            vrg_error(d, "graph file '%s' is not a readable text file under 1 MiB", path);
            return -1;
        }
        owned = malloc((size_t)n + 1);
        size_t got = fread(owned, 1, (size_t)n, f);
        owned[got] = '\0';
        fclose(f);
        /* a NUL would silently end the text here */
        if (strlen(owned) != got) {
            int line = 1;
            for (const char *c = owned; *c; c++)
                line += *c == '\n';
            vrg_error_at(d, line, "graph files are text", "NUL byte in the file");
            ast->fatal = 1;
            free(owned);
            return -1;
        }
        text = owned;
    }
    int errors_before = d->errors;
    if (scan_sections(text, ast, d) != 0) {
        free(owned);
        return -1;
    }
    line_reader r = {.text = text, .len = strlen(text), .ast = ast, .d = d};
    /* An indented line is a line like any other, not a continuation of the
     * previous value (inih's default follows Python's configparser). */
    ini_allow_multiline = false;
    /* Scan again with inih, keeping section indices in step with the scan above. */
    int err = ini_parse_stream(read_line, &r, on_key, &r);
    if (err > 0) {
        ast->syntax_error_line = err;
        vrg_error_at(d, err, "lines are '[section]', 'key = value' or comments starting with ';'", "syntax error");
    } else if (err < 0) {
        vrg_error(d, "graph file '%s' could not be read", path);
    }
    free(owned);
    return d->errors > errors_before ? -1 : 0;
}
