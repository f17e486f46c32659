/* vrg_escape (voxrg/plugin.h): file text quoted in messages reaches the
 * terminal as text. Plain C, no Vulkan: the tools layer's camera paths and
 * the CPU-only tests use it too. */
#include <stdint.h>
#include <string.h>
#include "voxrg/plugin.h"

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
