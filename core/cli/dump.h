#ifndef VOXRG_CLI_DUMP_H
#define VOXRG_CLI_DUMP_H
/* --dump's files: images as OpenEXR (or PNG), buffers as raw bytes with a
 * JSON sidecar that says what they hold. */
#include "voxrg/voxrg.h"

/* An image resource read back after the last frame as an OpenEXR file at
 * path: half and float formats as stored (NaN, Inf kept), 32-bit uint
 * formats as EXR uint channels, r11g11b10f widened to halves exactly,
 * 8-bit formats as floats (byte / 255, sRGB decoded to linear). 0 or -1. */
int vrg_cli_dump_exr(vrg_graph *g, const char *resource, const char *path);
/* A buffer resource as DIR/NAME.bin (its bytes) and DIR/NAME.json (name,
 * bytes, texel format, writer, frame). Each file whole or not at all. */
int vrg_cli_dump_buffer(vrg_graph *g, const char *resource, const char *dir, uint64_t frames);
#endif
