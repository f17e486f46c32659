#ifndef VOXRG_CLI_OVERLAY_H
#define VOXRG_CLI_OVERLAY_H
#include <stdint.h>
#define VRG_OVERLAY_LINES 64
#define VRG_OVERLAY_GLYPH_W 5 /* a glyph's pixels, before the scale */
#define VRG_OVERLAY_GLYPH_H 8
#define VRG_OVERLAY_GLYPH_SCALE 2
#define VRG_OVERLAY_CELL_W ((VRG_OVERLAY_GLYPH_W + 1) * VRG_OVERLAY_GLYPH_SCALE)
#define VRG_OVERLAY_LINE_H ((VRG_OVERLAY_GLYPH_H + 1) * VRG_OVERLAY_GLYPH_SCALE)
#define VRG_OVERLAY_PAD 4
/* Lines of text for one box. */
typedef struct vrg_overlay {
    char text[VRG_OVERLAY_LINES][160];
    int lines;
} vrg_overlay;
/* What the display stage blends over the picture: RGBA, alpha 0 where the
 * picture shows, at the window's size. */
typedef struct vrg_overlay_layer {
    uint8_t *pixels;
    uint32_t width, height;
} vrg_overlay_layer;
void vrg_overlay_clear(vrg_overlay *o);
/* Lines past VRG_OVERLAY_LINES are not kept: callers leave room. */
void vrg_overlay_line(vrg_overlay *o, const char *text);
/* text as lines of a box at most width pixels wide: broken at spaces (a
 * word longer than a line mid-word), the lines after the first indented. */
void vrg_overlay_wrap(vrg_overlay *o, const char *text, int width);
void vrg_overlay_layer_clear(vrg_overlay_layer *l);
void vrg_overlay_box(vrg_overlay_layer *l, int x, int y, int w, int h, const uint8_t rgba[4]);
/* The glyph of c: VRG_OVERLAY_GLYPH_H rows, bit VRG_OVERLAY_GLYPH_W - 1 the leftmost pixel. */
const uint8_t *vrg_overlay_glyph(char c);
/* text with its top-left at (x, y), each glyph pixel a square of VRG_OVERLAY_GLYPH_SCALE. */
void vrg_overlay_text(vrg_overlay_layer *l, int x, int y, const char *text, const uint8_t rgba[4]);
int vrg_overlay_text_width(const char *text);
/* A line from (x0, y0) to (x1, y1), window pixels, thickness pixels wide;
 * the part outside the layer is skipped. */
void vrg_overlay_segment(vrg_overlay_layer *l, double x0, double y0, double x1, double y1, int thickness, const uint8_t rgba[4]);
/* The lines in white on a translucent box with its top-left at (x, y), line
 * `highlight` (-1: none) on a lighter band; the box's size in *w, *h. */
void vrg_overlay_draw(const vrg_overlay *o, vrg_overlay_layer *l, int x, int y, int highlight, int *w, int *h);
#endif
