/* The window's overlay: text drawn on the CPU with a built-in 3x5 pixel
 * font (upper case; lower case is drawn as upper case), doubled, on
 * translucent boxes, into a window-sized RGBA layer that the display stage
 * (shaders/display.comp) blends over the picture: drawn at the window's
 * resolution, whatever the render scale. */
#include <math.h>
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

void vrg_overlay_layer_clear(vrg_overlay_layer *l) { memset(l->pixels, 0, (size_t)l->width * l->height * 4); }

void vrg_overlay_box(vrg_overlay_layer *l, int x, int y, int w, int h, const uint8_t rgba[4])
{
    for (int j = y < 0 ? 0 : y; j < y + h && j < (int)l->height; j++)
        for (int i = x < 0 ? 0 : x; i < x + w && i < (int)l->width; i++)
            memcpy(l->pixels + 4 * ((size_t)j * l->width + (size_t)i), rgba, 4);
}

void vrg_overlay_text(vrg_overlay_layer *l, int x, int y, const char *text, const uint8_t rgba[4])
{
    const int s = VRG_OVERLAY_GLYPH_SCALE;
    for (int c = 0; text[c]; c++) {
        const char *g = glyph(text[c]);
        for (int gy = 0; gy < 5; gy++)
            for (int gx = 0; gx < 3; gx++)
                if (g[gy * 3 + gx] == '#')
                    vrg_overlay_box(l, x + c * VRG_OVERLAY_CELL_W + gx * s, y + gy * s, s, s, rgba);
    }
}

int vrg_overlay_text_width(const char *text) { return (int)strlen(text) * VRG_OVERLAY_CELL_W; }

void vrg_overlay_draw(const vrg_overlay *o, vrg_overlay_layer *l, int x, int y, int highlight, int *w, int *h)
{
    static const uint8_t back[4] = {0, 0, 0, 140}, lit[4] = {70, 90, 140, 200}, white[4] = {255, 255, 255, 255};
    int longest = 0;
    for (int i = 0; i < o->lines; i++)
        longest = vrg_overlay_text_width(o->text[i]) > longest ? vrg_overlay_text_width(o->text[i]) : longest;
    *w = longest + 2 * VRG_OVERLAY_PAD;
    *h = o->lines * VRG_OVERLAY_LINE_H + 2 * VRG_OVERLAY_PAD;
    vrg_overlay_box(l, x, y, *w, *h, back);
    for (int i = 0; i < o->lines; i++) {
        int ty = y + VRG_OVERLAY_PAD + i * VRG_OVERLAY_LINE_H;
        if (i == highlight)
            vrg_overlay_box(l, x, ty - 2, *w, VRG_OVERLAY_LINE_H, lit);
        vrg_overlay_text(l, x + VRG_OVERLAY_PAD, ty, o->text[i], white);
    }
}

/* Liang-Barsky: the part of the segment inside [0, w) x [0, h), so a line
 * from far off screen costs only its visible pixels. */
static int clip_segment(double *x0, double *y0, double *x1, double *y1, double w, double h)
{
    double t0 = 0, t1 = 1, dx = *x1 - *x0, dy = *y1 - *y0;
    double p[4] = {-dx, dx, -dy, dy}, q[4] = {*x0, w - 1 - *x0, *y0, h - 1 - *y0};
    for (int i = 0; i < 4; i++) {
        if (p[i] == 0) {
            if (q[i] < 0)
                return 0;
            continue;
        }
        double t = q[i] / p[i];
        if (p[i] < 0 && t > t0)
            t0 = t;
        else if (p[i] > 0 && t < t1)
            t1 = t;
    }
    if (t0 > t1)
        return 0;
    double ax = *x0 + t0 * dx, ay = *y0 + t0 * dy;
    *x1 = *x0 + t1 * dx, *y1 = *y0 + t1 * dy;
    *x0 = ax, *y0 = ay;
    return 1;
}

void vrg_overlay_segment(vrg_overlay_layer *l, double x0, double y0, double x1, double y1, int thickness, const uint8_t rgba[4])
{
    if (!clip_segment(&x0, &y0, &x1, &y1, l->width, l->height))
        return;
    double dx = x1 - x0, dy = y1 - y0;
    int steps = (int)(fabs(dx) > fabs(dy) ? fabs(dx) : fabs(dy)) + 1;
    for (int i = 0; i <= steps; i++) {
        double t = (double)i / steps;
        int x = (int)floor(x0 + t * dx), y = (int)floor(y0 + t * dy);
        vrg_overlay_box(l, x - thickness / 2, y - thickness / 2, thickness, thickness, rgba);
    }
}
