/* vrg_cli_warnings_once (warnings_once.h): a glibc fopencookie stream. */
#define _GNU_SOURCE
#include "warnings_once.h"
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

typedef struct warnings_once {
    FILE *out;
    char *line; /* the line being written: len bytes, cap allocated */
    size_t len, cap;
    char **seen; /* the warnings' lines passed on */
    size_t count, seen_cap;
    int head_passed; /* the last line not indented went on: so do the indented ones after it */
} warnings_once;

static int is_warning(const char *line)
{
    const char *w = strstr(line, "warning[VRG-"), *e = strstr(line, "error[VRG-");
    return w && (!e || w < e);
}

static int seen_before(const warnings_once *s)
{
    for (size_t i = 0; i < s->count; i++)
        if (!strcmp(s->seen[i], s->line))
            return 1;
    return 0;
}

/* the line in s->line (NUL-terminated) to out, unless it is a warning's
 * first line that went before, or an indented line after one; -1: out
 * of memory */
static int pass_on(warnings_once *s)
{
    if (s->line[0] != ' ') { /* else a continuation: its head decided */
        int warning = is_warning(s->line);
        s->head_passed = !warning || !seen_before(s);
        if (s->head_passed && warning) {
            if (s->count == s->seen_cap) {
                size_t cap = s->seen_cap ? 2 * s->seen_cap : 16;
                char **seen = realloc(s->seen, sizeof *seen * cap);
                if (!seen)
                    return -1;
                s->seen = seen, s->seen_cap = cap;
            }
            if (!(s->seen[s->count] = strdup(s->line)))
                return -1;
            s->count++;
        }
    }
    if (s->head_passed) {
        fputs(s->line, s->out);
        fflush(s->out);
    }
    return 0;
}

static ssize_t warnings_once_write(void *cookie, const char *buf, size_t size)
{
    warnings_once *s = cookie;
    for (size_t i = 0; i < size; i++) {
        if (s->len + 2 > s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 256;
            char *line = realloc(s->line, cap);
            if (!line)
                return -1;
            s->line = line, s->cap = cap;
        }
        s->line[s->len++] = buf[i];
        if (buf[i] == '\n') {
            s->line[s->len] = '\0';
            s->len = 0;
            if (pass_on(s) != 0)
                return -1;
        }
    }
    return (ssize_t)size;
}

static int warnings_once_close(void *cookie)
{
    warnings_once *s = cookie;
    int rc = 0;
    if (s->len) {
        s->line[s->len] = '\0';
        rc = pass_on(s);
    }
    for (size_t i = 0; i < s->count; i++)
        free(s->seen[i]);
    free(s->seen);
    free(s->line);
    free(s);
    return rc;
}

FILE *vrg_cli_warnings_once(FILE *out)
{
    warnings_once *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->out = out;
    FILE *f = fopencookie(s, "w", (cookie_io_functions_t){.write = warnings_once_write, .close = warnings_once_close});
    if (!f) {
        free(s);
        return NULL;
    }
    setvbuf(f, NULL, _IONBF, 0);
    return f;
}
