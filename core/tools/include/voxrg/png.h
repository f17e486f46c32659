/* PNG files of rendered images (tools layer), written with libspng. */
#ifndef VOXRG_PNG_H
#define VOXRG_PNG_H
#include <stdint.h>
#include "voxrg/voxrg.h"
#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_tools (built with
 * -fvisibility=hidden). */
#pragma GCC visibility push(default)

/* PNG of float RGBA data; see docs/graph-format.md for how floats map. */
int vrg_write_png(const char *path, const vrg_image_data *img);
/* The 8-bit RGB bytes vrg_write_png would write (malloc'd, width*height*3). */
uint8_t *vrg_image_rgb8(const vrg_image_data *img);
int vrg_png_write_rgb8(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height);
/* A PNG file in memory (*png malloc'd, the caller frees it). */
int vrg_png_encode_rgb8(const uint8_t *rgb, uint32_t width, uint32_t height, void **png, size_t *size);
/* Any PNG, decoded to 8-bit RGB (*rgb malloc'd). -1 if unreadable. */
int vrg_png_read_rgb8(const char *path, uint8_t **rgb, uint32_t *width, uint32_t *height);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
