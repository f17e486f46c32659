/* Phase 1, parse: INI text → sections and keys with their line numbers.
 * inih does the tokenising; we feed it lines through our own reader so we
 * know which line each key came from (Debian's inih is built without
 * INI_HANDLER_LINENO). Meaning is given to the keys in validate.c. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <stdbool.h>
#include <sys/stat.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "parse.h"

typedef struct line_reader {
    const char *text; /* whole file */
    size_t pos, len;
    int line;         /* line number of the line last handed to inih */
    int next_section; /* index of the next header scan_sections found */
    _vrg_ast *ast;
    _vrg_diag *d;
} line_reader;

/* A section header goes to inih as "[#INDEX]", INDEX into ast->sections:
 * inih's section-name buffer is shorter than the names a graph may use, and
 * on_key then needs no search by name. */
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
        _vrg_error_at(r->d, r->line + 1, VRG_E_LINE_TOO_LONG, "split the value or shorten names", "line is longer than %d characters", num - 2);
        copy = 0; /* hand inih a blank line: no follow-on syntax error */
    }
    const _vrg_ast *a = r->ast;
    if (r->next_section < a->section_count && a->sections[r->next_section].line == r->line + 1)
        snprintf(str, (size_t)num, "[#%d]", r->next_section++);
    else {
        memcpy(str, r->text + r->pos, copy);
        str[copy] = '\0';
    }
    r->pos += n + (r->pos + n < r->len ? 1 : 0);
    r->line++;
    return str;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    line_reader *r = user;
    _vrg_ast *a = r->ast;
    if (section[0] != '#') { /* "" before the first header */
        _vrg_error_at(r->d, r->line, VRG_E_KEY_OUTSIDE_SECTION, "put every key under a [section] header", "key '%s' outside any section", name);
        return 1;
    }
    if (a->key_count >= VRG_MAX_KEYS) {
        /* once, not per key: keys past the limit are not kept */
        if (!a->fatal)
            _vrg_error_at(r->d, r->line, VRG_E_TOO_MANY, NULL, "too many keys (at most %d)", VRG_MAX_KEYS);
        a->fatal = 1;
        return 1;
    }
    if (strlen(name) >= sizeof a->keys[0].name) { /* reported, not kept cut short: no follow-on errors */
        _vrg_error_at(r->d, r->line, VRG_E_TOO_LONG, NULL, "key '%.*s...' is longer than %zu characters", 20, name, sizeof a->keys[0].name - 1);
        return 1;
    }
    _vrg_key *k = &a->keys[a->key_count++];
    snprintf(k->name, sizeof k->name, "%s", name);
    if (strlen(value) >= sizeof k->value)
        _vrg_error_at(r->d, r->line, VRG_E_TOO_LONG, NULL, "value of '%s' is too long (at most %zu characters)", name, sizeof k->value - 1);
    snprintf(k->value, sizeof k->value, "%s", value);
    k->line = r->line;
    k->section_index = atoi(section + 1);
    return 1;
}

/* After a header's ']' only blanks and a comment may follow. */
static int header_tail_ok(const char *c, const char *end)
{
    while (c < end && (*c == ' ' || *c == '\t'))
        c++;
    return c == end || *c == ';' || *c == '#';
}

/* Section headers are found by a scan of our own: inih does not report empty
 * sections, and a duplicate [pass a] must be seen as a second section. */
static int scan_sections(const char *text, _vrg_ast *a, _vrg_diag *d)
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
                    _vrg_error_at(d, line, VRG_E_TOO_MANY, NULL, "too many sections (at most %d)", (int)(sizeof a->sections / sizeof a->sections[0]));
                    a->fatal = 1; /* the rest of the file was not read: checking it would only mislead */
                    return -1;
                }
                if (!header_tail_ok(close + 1, p + n))
                    _vrg_error_at(d, line, VRG_E_SYNTAX, "a header is '[NAME]', optionally followed by a comment", "text after ']' of the section header");
                _vrg_section *sec = &a->sections[a->section_count++];
                size_t len = (size_t)(close - s - 1);
                /* blanks around the name do not count (as in inih) */
                const char *b = s + 1;
                while (len && (*b == ' ' || *b == '\t')) { b++; len--; }
                while (len && (b[len - 1] == ' ' || b[len - 1] == '\t')) len--;
                /* only a line too long to read (reported as such) can be cut here */
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

/* A copy with line ends made '\n' and a leading UTF-8 byte-order mark
 * dropped. CR-only and CRLF files are accepted rather than refused: they are
 * text files of lines like any other, and a message would only make the
 * user convert them. NULL when out of memory. */
static char *normalised(const char *text)
{
    if ((unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB && (unsigned char)text[2] == 0xBF)
        text += 3;
    char *out = malloc(strlen(text) + 1), *o = out;
    if (!out)
        return NULL;
    for (const char *c = text; *c; c++) {
        if (*c == '\r') {
            *o++ = '\n';
            if (c[1] == '\n')
                c++;
        } else
            *o++ = *c;
    }
    *o = '\0';
    return out;
}

/* The whole file, or NULL after reporting. Only a regular file is read: a
 * FIFO or a device would block or never end. */
static char *read_graph_file(const char *path, _vrg_ast *ast, _vrg_diag *d)
{
    int fd = vrg_open_regular(path, O_RDONLY);
    if (fd < 0 && (errno == EINVAL || errno == EISDIR)) {
        _vrg_error(d, VRG_E_GRAPH_UNREADABLE, "graph file '%s' is not a regular file", path);
        return NULL;
    }
    if (fd < 0) {
        _vrg_error(d, VRG_E_GRAPH_UNREADABLE, "cannot open graph file '%s': %s", path, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || st.st_size > (1 << 20)) {
        close(fd);
        _vrg_error(d, VRG_E_GRAPH_UNREADABLE, "graph file '%s' is not a readable text file under 1 MiB", path);
        return NULL;
    }
    char *text = malloc((size_t)st.st_size + 1);
    size_t got = 0;
    ssize_t n = 1;
    while (text && got < (size_t)st.st_size && (n = read(fd, text + got, (size_t)st.st_size - got)) > 0)
        got += (size_t)n;
    close(fd);
    if (!text || n < 0) {
        free(text);
        _vrg_error(d, VRG_E_GRAPH_UNREADABLE, "graph file '%s' is not a readable text file under 1 MiB", path);
        return NULL;
    }
    text[got] = '\0';
    /* a NUL would silently end the text here */
    if (strlen(text) != got) {
        int line = 1;
        for (const char *c = text; *c; c++)
            line += *c == '\n';
        _vrg_error_at(d, line, VRG_E_NOT_TEXT, "graph files are text", "NUL byte in the file");
        ast->fatal = 1;
        free(text);
        return NULL;
    }
    return text;
}

int _vrg_parse(const char *path, const char *text, _vrg_ast *ast, _vrg_diag *d)
{
    char *read = NULL;
    memset(ast, 0, sizeof *ast);
    if (!text) {
        read = read_graph_file(path, ast, d);
        if (!read)
            return -1;
        text = read;
    }
    char *owned = normalised(text);
    free(read);
    if (!owned) {
        _vrg_error(d, VRG_E_OUT_OF_MEMORY, "graph file '%s': out of memory", path);
        return -1;
    }
    text = owned;
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
        _vrg_error_at(d, err, VRG_E_SYNTAX, "lines are '[section]', 'key = value' or comments starting with ';'", "syntax error");
    } else if (err < 0) {
        _vrg_error(d, VRG_E_GRAPH_UNREADABLE, "graph file '%s' could not be read", path);
    }
    free(owned);
    return d->errors > errors_before ? -1 : 0;
}
