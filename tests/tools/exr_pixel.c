/* An independent reader of voxrg's OpenEXR dumps for the tests: OpenEXR's
 * own C library (OpenEXRCore), none of voxrg's code. Prints the file's size,
 * then one line per channel of pixel (X, Y): its name, type (uint, half,
 * float), stored bits as an unsigned integer and the header's pLinear, in
 * the file's channel order (sorted by name).
 * Usage: exr_pixel FILE X Y; exit 1 on any error. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <openexr.h>

static int fail(const char *what, exr_result_t rc)
{
    fprintf(stderr, "exr_pixel: %s: %s\n", what, exr_get_default_error_message(rc));
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: exr_pixel FILE X Y\n");
        return 2;
    }
    int x = atoi(argv[2]), y = atoi(argv[3]);
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_result_t rc = exr_start_read(&ctx, argv[1], &init);
    if (rc != EXR_ERR_SUCCESS)
        return fail(argv[1], rc);
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chl;
    if ((rc = exr_get_data_window(ctx, 0, &dw)) != EXR_ERR_SUCCESS || (rc = exr_get_channels(ctx, 0, &chl)) != EXR_ERR_SUCCESS)
        return fail("header", rc);
    int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    printf("size %d %d\n", w, h);
    if (x < 0 || y < 0 || x >= w || y >= h) {
        fprintf(stderr, "exr_pixel: %d,%d outside %dx%d\n", x, y, w, h);
        return 1;
    }
    exr_chunk_info_t chunk;
    if ((rc = exr_read_scanline_chunk_info(ctx, 0, dw.min.y + y, &chunk)) != EXR_ERR_SUCCESS)
        return fail("chunk", rc);
    exr_decode_pipeline_t dec = {0};
    if ((rc = exr_decoding_initialize(ctx, 0, &chunk, &dec)) != EXR_ERR_SUCCESS)
        return fail("decoding", rc);
    /* every channel as stored, 4 bytes a value (halves in the low 2) */
    uint32_t *buf = calloc((size_t)dec.channel_count * chunk.width * chunk.height, 4);
    for (int c = 0; c < dec.channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec.channels[c];
        ch->decode_to_ptr = (uint8_t *)(buf + (size_t)c * chunk.width * chunk.height);
        ch->user_pixel_stride = 4;
        ch->user_line_stride = 4 * chunk.width;
        ch->user_bytes_per_element = ch->bytes_per_element;
        ch->user_data_type = ch->data_type;
    }
    if ((rc = exr_decoding_choose_default_routines(ctx, 0, &dec)) != EXR_ERR_SUCCESS || (rc = exr_decoding_run(ctx, 0, &dec)) != EXR_ERR_SUCCESS)
        return fail("decoding", rc);
    int row = dw.min.y + y - chunk.start_y;
    for (int c = 0; c < dec.channel_count; c++) {
        const exr_coding_channel_info_t *ch = &dec.channels[c];
        const uint8_t *p = (const uint8_t *)(buf + (size_t)c * chunk.width * chunk.height + (size_t)row * chunk.width + x);
        uint32_t bits = 0;
        memcpy(&bits, p, ch->bytes_per_element);
        const char *type = ch->data_type == EXR_PIXEL_UINT ? "uint" : ch->data_type == EXR_PIXEL_HALF ? "half" : "float";
        /* the header's pLinear of that channel (the chlist is sorted by name, as the decoder's channels) */
        int plinear = -1;
        for (int k = 0; k < chl->num_channels; k++)
            if (!strcmp(chl->entries[k].name.str, ch->channel_name))
                plinear = chl->entries[k].p_linear;
        printf("%s %s %u %d\n", ch->channel_name, type, bits, plinear);
    }
    exr_decoding_destroy(ctx, &dec);
    free(buf);
    exr_finish(&ctx);
    return 0;
}
