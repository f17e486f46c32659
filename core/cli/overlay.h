#ifndef VOXRG_CLI_OVERLAY_H
#define VOXRG_CLI_OVERLAY_H
#include <stdint.h>
#include <stdio.h>
#define VRG_OVERLAY_LINES 40
typedef struct vrg_overlay {
    char text[VRG_OVERLAY_LINES][160];
    int lines;
} vrg_overlay;
void vrg_overlay_clear(vrg_overlay *o);
void vrg_overlay_line(vrg_overlay *o, const char *text);
void vrg_overlay_draw(const vrg_overlay *o, uint8_t *pixels, uint32_t max_w, uint32_t max_h, uint32_t *w, uint32_t *h);
#endif
