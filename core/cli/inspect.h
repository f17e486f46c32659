#ifndef VOXRG_CLI_INSPECT_H
#define VOXRG_CLI_INSPECT_H
/* `voxrg inspect`: one pixel of every image of a graph after a frame. */
#include <stdint.h>
#include <stdio.h>
#include "voxrg/voxrg.h"

/* "X,Y": two whole numbers -> 0, else -1. */
int vrg_cli_parse_pixel(const char *s, uint32_t *x, uint32_t *y);
/* Reads pixel (x, y) of every image after the last frame (frame) and
 * prints the table to out, and to json (a file written whole) when given.
 * 0, or -1 after the runtime's error. */
int vrg_cli_inspect_report(vrg_graph *g, const char *graph_path, uint32_t x, uint32_t y, uint64_t frame, FILE *out, const char *json);
#endif
