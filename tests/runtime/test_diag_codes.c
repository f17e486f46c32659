/* The catalogue of diagnostic codes (core/runtime/src/diag_codes.h) against its
 * documentation (docs/graph-format.md, "Codes"), both ways: every code in
 * the table has a row `| CODE | short-name |` there, and every code the page
 * mentions exists in the table. The table itself: well-formed, unique codes
 * and names, errors VRG-E, warnings VRG-W.
 *
 * usage: test_diag_codes DOCS/graph-format.md */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "internal.h"

static int failures;

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    size_t len = 0, cap = 0, n;
    char buf[4096];
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        if (len + n + 1 > cap) {
            cap = (len + n + 1) * 2;
            char *grown = realloc(text, cap);
            if (!grown) {
                free(text);
                fclose(f);
                return NULL;
            }
            text = grown;
        }
        memcpy(text + len, buf, n);
        len += n;
    }
    fclose(f);
    if (text)
        text[len] = '\0';
    return text;
}

/* VRG-E123 or VRG-W123, exactly */
static int well_formed(const char *code)
{
    return strlen(code) == 8 && strncmp(code, "VRG-", 4) == 0 && (code[4] == 'E' || code[4] == 'W') && isdigit((unsigned char)code[5]) &&
           isdigit((unsigned char)code[6]) && isdigit((unsigned char)code[7]);
}

static int in_table(const char *code, size_t len)
{
    for (int i = 0; i < VRG_DIAG_CODE_COUNT; i++) {
        const char *c = _vrg_diag_info_of((_vrg_diag_code)i)->code;
        if (strlen(c) == len && strncmp(c, code, len) == 0)
            return 1;
    }
    return 0;
}

static void check_table(void)
{
    for (int i = 0; i < VRG_DIAG_CODE_COUNT; i++) {
        const _vrg_diag_info *a = _vrg_diag_info_of((_vrg_diag_code)i);
        CHECK(a && a->code && a->short_name && a->meaning && a->meaning[0], "entry %d is incomplete", i);
        if (!a || !a->code)
            continue;
        CHECK(well_formed(a->code), "'%s' is not VRG-E### or VRG-W###", a->code);
        /* VRG_E_... is an error's code, VRG_W_... a warning's */
        CHECK(strncmp(a->enum_name, "VRG_", 4) == 0 && a->enum_name[4] == a->code[4] && a->enum_name[5] == '_', "%s has code %s", a->enum_name,
              a->code);
        for (int j = 0; j < i; j++) {
            const _vrg_diag_info *b = _vrg_diag_info_of((_vrg_diag_code)j);
            CHECK(strcmp(a->code, b->code) != 0, "%s and %s share code %s", a->enum_name, b->enum_name, a->code);
            CHECK(strcmp(a->short_name, b->short_name) != 0, "%s and %s share the name %s", a->code, b->code, a->short_name);
        }
    }
    CHECK(_vrg_diag_info_of(VRG_DIAG_CODE_COUNT) == NULL, "a code past the table has an entry");
}

static void check_docs(const char *doc)
{
    for (int i = 0; i < VRG_DIAG_CODE_COUNT; i++) {
        const _vrg_diag_info *a = _vrg_diag_info_of((_vrg_diag_code)i);
        char row[128];
        snprintf(row, sizeof row, "\n| %s | %s |", a->code, a->short_name);
        const char *at = strstr(doc, row);
        CHECK(at != NULL, "docs/graph-format.md has no row '%s'", row + 1);
        CHECK(!at || !strstr(at + 1, row), "docs/graph-format.md lists '%s' twice", row + 1);
    }
    for (const char *s = doc; (s = strstr(s, "VRG-")) != NULL; s += 4) {
        size_t len = 4;
        while (isalnum((unsigned char)s[len]))
            len++;
        /* a pattern such as VRG-E0xx stands for many codes, not one */
        if (len != 8 || (s[4] != 'E' && s[4] != 'W') || !isdigit((unsigned char)s[5]) || !isdigit((unsigned char)s[6]) || !isdigit((unsigned char)s[7]))
            continue;
        CHECK(in_table(s, len), "docs/graph-format.md mentions %.*s, which core/runtime/src/diag_codes.h does not list", (int)len, s);
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DOCS/graph-format.md\n", argv[0]);
        return 2;
    }
    char *doc = read_all(argv[1]);
    if (!doc) {
        fprintf(stderr, "error: cannot read %s\n", argv[1]);
        return 2;
    }
    check_table();
    check_docs(doc);
    free(doc);
    if (failures) {
        fprintf(stderr, "%d failures\n", failures);
        return 1;
    }
    printf("ok: %d codes, documented both ways\n", VRG_DIAG_CODE_COUNT);
    return 0;
}
