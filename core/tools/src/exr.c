/* OpenEXR output through OpenEXRCore's C API: the file is built in memory
 * (the library writes chunks and then seeks back for the offset table) and
 * handed to vrg_output_write, so that it appears whole or not at all. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <openexr.h>
#include "voxrg/exr.h"
#include "voxrg/output.h"

typedef struct memfile {
    uint8_t *data;
    uint64_t size, cap;
    int failed;
    char error[512]; /* the library's message (it would print it itself) */
} memfile;

static int64_t write_mem(exr_const_context_t ctxt, void *user, const void *buf, uint64_t sz, uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    memfile *m = user;
    if (offset + sz > m->cap) {
        uint64_t cap = m->cap ? m->cap : 65536;
        while (cap < offset + sz)
            cap *= 2;
        uint8_t *grown = realloc(m->data, cap);
        if (!grown) {
            m->failed = 1;
            return error_cb(ctxt, EXR_ERR_OUT_OF_MEMORY, "out of memory for %llu bytes", (unsigned long long)cap);
        }
        memset(grown + m->cap, 0, cap - m->cap);
        m->data = grown;
        m->cap = cap;
    }
    memcpy(m->data + offset, buf, sz);
    if (offset + sz > m->size)
        m->size = offset + sz;
    return (int64_t)sz;
}

static void keep_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    if (exr_get_user_data(ctxt, &user) == EXR_ERR_SUCCESS && user)
        snprintf(((memfile *)user)->error, sizeof ((memfile *)user)->error, "%s (%s)", msg, exr_get_default_error_message(code));
}

const char *vrg_exr_channel_name(uint32_t n, uint32_t c)
{
    static const char *rgba[] = {"R", "G", "B", "A"};
    return n == 1 ? "Y" : c < 4 ? rgba[c] : "?";
}

int vrg_write_exr(const char *path, uint32_t width, uint32_t height, uint32_t channels, vrg_exr_type type, const void *texels)
{
    memfile m = {0};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &m;
    init.write_fn = write_mem;
    init.error_handler_fn = keep_error;
    exr_context_t ctx = NULL;
    int part = 0, lines = 1;
    size_t bytes = type == VRG_EXR_HALF ? 2 : 4, pixel = bytes * channels;
    exr_result_t rc;
    if (channels < 1 || channels > 4 || !width || !height) {
        fprintf(stderr, "error: %s: cannot write %ux%u pixels of %u channels as OpenEXR\n", path, width, height, channels);
        return -1;
    }
    rc = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_add_part(ctx, "image", EXR_STORAGE_SCANLINE, &part);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_initialize_required_attr_simple(ctx, part, (int32_t)width, (int32_t)height, EXR_COMPRESSION_ZIP);
    /* pLinear 0: linear light and data (depth, ids), not perceptually
     * uniform values, which lossy compressors would quantize evenly */
    for (uint32_t c = 0; c < channels && rc == EXR_ERR_SUCCESS; c++)
        rc = exr_add_channel(ctx, part, vrg_exr_channel_name(channels, c), (exr_pixel_type_t)type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_write_header(ctx);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_get_scanlines_per_chunk(ctx, part, &lines);
    exr_encode_pipeline_t enc = {0};
    int have_enc = 0;
    for (int32_t y = 0; y < (int32_t)height && rc == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rc = exr_write_scanline_chunk_info(ctx, part, y, &chunk);
        if (rc != EXR_ERR_SUCCESS)
            break;
        rc = have_enc ? exr_encoding_update(ctx, part, &chunk, &enc) : exr_encoding_initialize(ctx, part, &chunk, &enc);
        if (rc != EXR_ERR_SUCCESS)
            break;
        /* the file's channels are sorted by name: find each one's source */
        for (int k = 0; k < enc.channel_count; k++) {
            exr_coding_channel_info_t *ch = &enc.channels[k];
            uint32_t c = 0;
            while (c < channels && strcmp(ch->channel_name, vrg_exr_channel_name(channels, c)) != 0)
                c++;
            ch->user_pixel_stride = (int32_t)pixel;
            ch->user_line_stride = (int32_t)(pixel * width);
            ch->user_bytes_per_element = (int16_t)bytes;
            ch->user_data_type = (uint16_t)type;
            ch->encode_from_ptr = (const uint8_t *)texels + (size_t)chunk.start_y * pixel * width + c * bytes;
        }
        if (!have_enc) {
            rc = exr_encoding_choose_default_routines(ctx, part, &enc);
            have_enc = 1;
        }
        if (rc == EXR_ERR_SUCCESS)
            rc = exr_encoding_run(ctx, part, &enc);
    }
    if (have_enc)
        exr_encoding_destroy(ctx, &enc);
    exr_result_t fin = exr_finish(&ctx);
    if (rc == EXR_ERR_SUCCESS)
        rc = fin;
    if (rc != EXR_ERR_SUCCESS || m.failed) {
        fprintf(stderr, "error: %s: OpenEXR encoding failed: %s\n", path, m.error[0] ? m.error : exr_get_default_error_message(rc));
        free(m.data);
        return -1;
    }
    int out = vrg_output_write(path, m.data, m.size);
    free(m.data);
    return out;
}
