/* PNG output with libspng. How values become 8-bit sRGB (see docs):
 *   8-bit UNORM/sRGB formats: written as stored.
 *   integer formats: divided by the image's maximum.
 *   float formats: a signed image (minimum < 0, e.g. normals, motion) maps
 *   [-1,1] to [0,1]; a one-channel image above 1 (e.g. depth) is divided by
 *   its maximum; anything else is linear colour: clamped, sRGB-encoded. */
#include <math.h>
#include <spng.h>
#include <stdio.h>
#include <stdlib.h>
#include "voxrg/output.h"
#include "voxrg/png.h"

static float linear_to_srgb(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

static int is_unorm8(VkFormat f)
{
    return f == VK_FORMAT_R8_UNORM || f == VK_FORMAT_R8G8_UNORM || f == VK_FORMAT_R8G8B8A8_UNORM;
}

static int is_uint(VkFormat f)
{
    return f == VK_FORMAT_R32_UINT || f == VK_FORMAT_R32G32_UINT || f == VK_FORMAT_R32G32B32A32_UINT;
}

uint8_t *vrg_image_rgb8(const vrg_image_data *img)
{
    size_t n = (size_t)img->width * img->height;
    uint32_t ch = img->channels < 3 ? img->channels : 3;
    float lo = INFINITY, hi = -INFINITY;
    for (size_t p = 0; p < n; p++)
        for (uint32_t c = 0; c < ch; c++) {
            float v = img->pixels[p * 4 + c];
            if (isfinite(v)) {
                lo = fminf(lo, v);
                hi = fmaxf(hi, v);
            }
        }
    enum { AS_IS, SRGB, SIGNED, BY_MAX } mode = SRGB;
    if (is_unorm8(img->format))
        mode = AS_IS;
    else if (is_uint(img->format))
        mode = BY_MAX;
    else if (lo < 0)
        mode = SIGNED;
    else if (ch == 1 && hi > 1)
        mode = BY_MAX;
    uint8_t *rgb = malloc(n * 3 + 1);
    if (!rgb)
        return NULL;
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < 3; c++) {
            /* one channel: grey; two channels: red/green, blue 0 */
            float v = (uint32_t)c < ch ? img->pixels[p * 4 + c] : ch == 1 ? img->pixels[p * 4] : 0.0f;
            if (!isfinite(v))
                v = 0;
            switch (mode) {
            case AS_IS: break;
            case SRGB: v = linear_to_srgb(v); break;
            case SIGNED: v = v * 0.5f + 0.5f; break;
            case BY_MAX: v = hi > 0 ? v / hi : 0; break;
            }
            if (img->format == VK_FORMAT_R8G8B8A8_SRGB)
                v = linear_to_srgb(img->pixels[p * 4 + c]);
            v = v < 0 ? 0 : v > 1 ? 1 : v;
            rgb[p * 3 + c] = (uint8_t)lrintf(v * 255.0f);
        }
    return rgb;
}

static spng_ctx *encoder(const uint8_t *rgb, uint32_t w, uint32_t h, int *err)
{
    spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
    if (!ctx) {
        *err = SPNG_EMEM;
        return NULL;
    }
    spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
    /* Fast settings (zlib level 1, the Sub filter on every row): `render
     * --sequence` and compare write a file per frame, and on a CPU device
     * the encoder takes its time from the renderer. The pixels are the
     * same; docs/benchmarks.md has the cost in time and bytes. */
    spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, 1);
    spng_set_option(ctx, SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_SUB);
    struct spng_ihdr ihdr = {.width = w, .height = h, .bit_depth = 8, .color_type = SPNG_COLOR_TYPE_TRUECOLOR};
    spng_set_ihdr(ctx, &ihdr);
    *err = spng_encode_image(ctx, rgb, (size_t)w * h * 3, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    return ctx;
}

int vrg_png_write_rgb8(const char *path, const uint8_t *rgb, uint32_t w, uint32_t h)
{
    /* encoded in memory, so that the file is written in one piece by the
     * one writer of output files, and an I/O error keeps its reason */
    void *png;
    size_t size;
    if (vrg_png_encode_rgb8(rgb, w, h, &png, &size) != 0) {
        fprintf(stderr, "error: PNG encoding of %s failed\n", path);
        return -1;
    }
    int rc = vrg_output_write(path, png, size);
    free(png);
    return rc;
}

int vrg_png_encode_rgb8(const uint8_t *rgb, uint32_t w, uint32_t h, void **png, size_t *size)
{
    int err;
    spng_ctx *ctx = encoder(rgb, w, h, &err);
    *png = err ? NULL : spng_get_png_buffer(ctx, size, &err); /* ours to free */
    spng_ctx_free(ctx);
    return *png && !err ? 0 : -1;
}

int vrg_png_read_rgb8(const char *path, uint8_t **rgb, uint32_t *w, uint32_t *h)
{
    *rgb = NULL;
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f)
        return -1;
    spng_ctx *ctx = spng_ctx_new(0);
    spng_set_png_file(ctx, f);
    struct spng_ihdr ihdr;
    size_t len = 0;
    int err = spng_get_ihdr(ctx, &ihdr);
    if (!err)
        err = spng_decoded_image_size(ctx, SPNG_FMT_RGB8, &len);
    if (!err && !(*rgb = malloc(len)))
        err = SPNG_EMEM;
    if (!err)
        err = spng_decode_image(ctx, *rgb, len, SPNG_FMT_RGB8, 0);
    spng_ctx_free(ctx);
    fclose(f);
    if (err) {
        free(*rgb);
        *rgb = NULL;
        return -1;
    }
    *w = ihdr.width;
    *h = ihdr.height;
    return 0;
}

int vrg_write_png(const char *path, const vrg_image_data *img)
{
    uint8_t *rgb = vrg_image_rgb8(img);
    int rc = rgb ? vrg_png_write_rgb8(path, rgb, img->width, img->height) : -1;
    free(rgb);
    return rc;
}
