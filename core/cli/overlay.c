/* The window's overlay: lines of text drawn on the CPU with a built-in 3x5
 * pixel font (upper case; lower case is drawn as upper case), doubled, onto
 * a dark panel that run.c copies into the top-left corner of each
 * presented image. */
#include <string.h>
#include "overlay.h"

/* Each glyph: 5 rows of 3 pixels, '#' set. */
static const char *glyph(char c)
{
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    switch (c) {
    case '0': return "####.##.##.####";
    case '1': return ".#.##..#..#.###";
    case '2': return "###..#####..###";
    case '3': return "###..#.##..####";
    case '4': return "#.##.####..#..#";
    case '5': return "####..###..####";
    case '6': return "####..####.####";
    case '7': return "###..#..#.#..#.";
    case '8': return "####.#####.####";
    case '9': return "####.####..####";
    case 'A': return ".#.#.#####.##.#";
    case 'B': return "##.#.###.#.###.";
    case 'C': return ".###..#..#...##";
    case 'D': return "##.#.##.##.###.";
    case 'E': return "####..##.#..###";
    case 'F': return "####..##.#..#..";
    case 'G': return ".###..#.##.#.##";
    case 'H': return "#.##.#####.##.#";
    case 'I': return "###.#..#..#.###";
    case 'J': return "..#..#..##.#.#.";
    case 'K': return "#.##.###.#.##.#";
    case 'L': return "#..#..#..#..###";
    case 'M': return "#.########.##.#";
    case 'N': return "##.#.##.##.##.#";
    case 'O': return ".#.#.##.##.#.#.";
    case 'P': return "##.#.###.#..#..";
    case 'Q': return ".#.#.##.###..##";
    case 'R': return "##.#.###.#.##.#";
    case 'S': return ".###...#...###.";
    case 'T': return "###.#..#..#..#.";
    case 'U': return "#.##.##.##.####";
    case 'V': return "#.##.##.##.#.#.";
    case 'W': return "#.##.########.#";
    case 'X': return "#.##.#.#.#.##.#";
    case 'Y': return "#.##.#.#..#..#.";
    case 'Z': return "###..#.#.#..###";
    case '.': return ".............#.";
    case ',': return "..........#.#..";
    case ':': return "....#.....#....";
    case ';': return "....#.....#.#..";
    case '-': return "......###......";
    case '_': return "............###";
    case '/': return "..#..#.#.#..#..";
    case '(': return ".#.#..#..#...#.";
    case ')': return ".#...#..#..#.#.";
    case '[': return "##.#..#..#..##.";
    case ']': return ".##..#..#..#.##";
    case '%': return "#.#..#.#.#..#.#";
    case '=': return "...###...###...";
    case '+': return "....#.###.#....";
    case '\'': return ".#..#..........";
    case '"': return "#.##.#.........";
    case '!': return ".#..#..#.....#.";
    case '?': return "##...#.#.....#.";
    case '<': return "..#.#.#...#...#";
    case '>': return "#...#...#.#.#..";
    case '#': return "#.#####.#####.#";
    case '*': return "...#.#.#.#.#...";
    case '|': return ".#..#..#..#..#.";
    case '@': return ".#.#.##.##...##";
    case '&': return ".#.#.#.#.#.#.##";
    default: return "...............";
    }
}

void vrg_overlay_clear(vrg_overlay *o) { o->lines = 0; }

void vrg_overlay_line(vrg_overlay *o, const char *text)
{
    if (o->lines < VRG_OVERLAY_LINES)
        snprintf(o->text[o->lines++], sizeof o->text[0], "%s", text);
}

/* Rasterises the lines at 2x onto a dark panel of 4-byte pixels (grey and
 * white: the same in RGBA and BGRA), its size in *w and *h (at most the
 * given maximum). */
void vrg_overlay_draw(const vrg_overlay *o, uint8_t *pixels, uint32_t max_w, uint32_t max_h, uint32_t *w, uint32_t *h)
{
    const uint32_t scale = 2, cell_w = 4 * scale, cell_h = 6 * scale, pad = 4;
    size_t longest = 0;
    for (int i = 0; i < o->lines; i++)
        longest = strlen(o->text[i]) > longest ? strlen(o->text[i]) : longest;
    uint32_t pw = (uint32_t)longest * cell_w + 2 * pad, ph = (uint32_t)o->lines * cell_h + 2 * pad;
    pw = pw > max_w ? max_w : pw;
    ph = ph > max_h ? max_h : ph;
    for (uint32_t i = 0; i < pw * ph; i++) {
        uint8_t *p = pixels + 4 * i;
        p[0] = p[1] = p[2] = 24;
        p[3] = 255;
    }
    for (int l = 0; l < o->lines; l++)
        for (size_t c = 0; o->text[l][c]; c++) {
            const char *g = glyph(o->text[l][c]);
            for (uint32_t gy = 0; gy < 5; gy++)
                for (uint32_t gx = 0; gx < 3; gx++) {
                    if (g[gy * 3 + gx] != '#')
                        continue;
                    for (uint32_t sy = 0; sy < scale; sy++)
                        for (uint32_t sx = 0; sx < scale; sx++) {
                            uint32_t x = pad + (uint32_t)c * cell_w + gx * scale + sx, y = pad + (uint32_t)l * cell_h + gy * scale + sy;
                            if (x >= pw || y >= ph)
                                continue;
                            uint8_t *p = pixels + 4 * ((size_t)y * pw + x);
                            p[0] = p[1] = p[2] = 255;
                        }
                }
        }
    *w = pw;
    *h = ph;
}
