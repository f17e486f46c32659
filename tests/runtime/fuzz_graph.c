/* libFuzzer target: graph text → parse + validate + compile + aliasing plan,
 * without a device (memory sizes estimated). Plugins come from the build's
 * plugins/ folder. Any crash, leak or sanitizer report is a bug, and so is a
 * message without a code of the catalogue (core/runtime/src/diag_codes.h). */
#define _DEFAULT_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/voxrg.h"
#include "diag_codes.h"

#define CODE_STRING(name, code, short_name, meaning) code,
static const char *const codes[] = {VRG_DIAG_CODES(CODE_STRING)};

static int known_code(const char *s, size_t len)
{
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        if (strlen(codes[i]) == len && strncmp(codes[i], s, len) == 0)
            return 1;
    return 0;
}

/* After "fuzz.ini:LINE: " or at the start: error[CODE]: or warning[CODE]: */
static int coded(const char *s)
{
    const char *kind = strncmp(s, "error[", 6) == 0 ? s + 6 : strncmp(s, "warning[", 8) == 0 ? s + 8 : NULL;
    const char *close = kind ? strchr(kind, ']') : NULL;
    return close && close[1] == ':' && known_code(kind, (size_t)(close - kind));
}

/* Every message line names its code; what follows a message (its hint, a
 * list it carries) is indented. */
static void check_messages(const char *text)
{
    for (const char *line = text; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        const char *body = line;
        if (strncmp(line, "fuzz.ini:", 9) == 0) {
            body = line + 9;
            while (*body >= '0' && *body <= '9')
                body++;
            body = strncmp(body, ": ", 2) == 0 ? body + 2 : line;
        }
        if (len && strncmp(line, "  ", 2) != 0 && !coded(body)) {
            fprintf(stderr, "message without a code of the catalogue: %.*s\n", (int)len, line);
            abort();
        }
        line += len + (end ? 1 : 0);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 16384)
        return 0;
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    char *messages = NULL;
    size_t messages_len = 0;
    FILE *diag = open_memstream(&messages, &messages_len);
    if (!diag)
        abort();
    /* no --set: an override naming a pass the input lacks would stop every
     * such input before compile */
    vrg_graph_desc desc = {.path = "fuzz.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    if (vrg_graph_load(NULL, &desc, &g) == 0) {
        vrg_graph_report(g, devnull);
        vrg_graph_write_dot(g, devnull);
        vrg_graph_destroy(g);
    }
    fclose(diag);
    check_messages(messages);
    free(messages);
    free(text);
    return 0;
}
