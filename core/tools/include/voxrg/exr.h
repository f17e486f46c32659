/* OpenEXR files of rendered images (tools layer), written with
 * OpenEXRCore: float images keep their values (NaN and infinity too). */
#ifndef VOXRG_EXR_H
#define VOXRG_EXR_H
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_tools (built with
 * -fvisibility=hidden). */
#pragma GCC visibility push(default)

typedef enum vrg_exr_type { VRG_EXR_UINT = 0, VRG_EXR_HALF = 1, VRG_EXR_FLOAT = 2 } vrg_exr_type;

/* A scanline EXR (ZIP, lossless) of width x height pixels of `channels`
 * channels of `type`, interleaved in `texels` (rows top to bottom, 2 bytes
 * a half, 4 a float or uint). Channels are named Y for one, else R, G, B,
 * A. Written whole or not at all (vrg_output); 0, or -1 after a message
 * naming path. */
int vrg_write_exr(const char *path, uint32_t width, uint32_t height, uint32_t channels, vrg_exr_type type, const void *texels);
/* The channel name vrg_write_exr gives channel c of an image of n. */
const char *vrg_exr_channel_name(uint32_t n, uint32_t c);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
