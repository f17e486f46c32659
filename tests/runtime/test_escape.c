/* vrg_escape: text from files quoted in messages reaches the terminal as
 * text. Control characters, DEL, C1 controls, line separators, bidi
 * controls and bytes that are not UTF-8 come out as \xNN (\n, \r, \t);
 * printable ASCII and UTF-8 text stay; escaping twice changes nothing; a
 * cut keeps whole characters and says so with "...". */
#include <string.h>
#include "check.h"
#include "voxrg/voxrg.h"

static int failures;

static void same(const char *in, size_t len, size_t cap, const char *want)
{
    char out[256];
    memset(out, '#', sizeof out);
    const char *got = vrg_escape(out, cap, in, len);
    CHECK(got == out && strcmp(out, want) == 0, "escape of %zu bytes into %zu: got '%s', want '%s'", len, cap, out, want);
    CHECK(strlen(out) < cap, "escape into %zu bytes wrote %zu and the end", cap, strlen(out));
    char twice[256];
    if (strcmp(out, want) == 0 && strlen(want) + 1 < sizeof twice)
        CHECK(strcmp(vrg_escape(twice, sizeof twice, out, strlen(out)), out) == 0, "escaping '%s' again gives '%s'", out, twice);
}

#define TEXT(s) s, sizeof s - 1

int main(void)
{
    same(TEXT("terrain seed=1 a\\b 'q'"), 256, "terrain seed=1 a\\b 'q'");
    /* a forged line and a terminal escape */
    same(TEXT("key\n/tmp/x.ini:1: error[VRG-E001]: forged"), 256, "key\\n/tmp/x.ini:1: error[VRG-E001]: forged");
    same(TEXT("\x1b[2J\x1b]0;title\x07\r\t\x7f"), 256, "\\x1b[2J\\x1b]0;title\\x07\\r\\t\\x7f");
    same("a\0b", 3, 256, "a\\x00b");
    /* UTF-8 text stays; C1 controls (U+009B), separators, bidi overrides,
     * overlong forms, surrogates and stray bytes do not */
    same(TEXT("gr\xc3\xbcn \xe2\x82\xac \xf0\x9f\x99\x82"), 256, "gr\xc3\xbcn \xe2\x82\xac \xf0\x9f\x99\x82");
    same(TEXT("\xc2\x9b" "31m"), 256, "\\xc2\\x9b31m");
    same(TEXT("a\xe2\x80\xa8" "b\xe2\x80\xae" "c"), 256, "a\\xe2\\x80\\xa8b\\xe2\\x80\\xaec");
    same(TEXT("\xc0\xaf \xed\xa0\x80 \xff \xc3"), 256, "\\xc0\\xaf \\xed\\xa0\\x80 \\xff \\xc3");
    /* cuts: exactly fits; one byte short ends in "..." at a character */
    same(TEXT("abcde"), 6, "abcde");
    same(TEXT("abcdef"), 6, "ab...");
    same(TEXT("\x1b\x1b"), 9, "\\x1b\\x1b");
    same(TEXT("\x1b\x1b"), 8, "\\x1b...");
    same(TEXT("\x1b\x1b"), 7, "...");
    same(TEXT("\xc3\xbc\xc3\xbc\xc3\xbc"), 6, "\xc3\xbc...");
    same(TEXT("abc"), 3, "..");
    same(TEXT("abc"), 2, ".");
    same(TEXT("abc"), 1, "");
    char none = '#';
    CHECK(vrg_escape(&none, 0, "abc", 3) == &none && none == '#', "cap 0 wrote a byte");
    if (failures)
        fprintf(stderr, "%d failures\n", failures);
    return failures != 0;
}
