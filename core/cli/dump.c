/* --dump's files (dump.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "dump.h"
#include "util.h"
#include "voxrg/exr.h"
#include "voxrg/output.h"

/* The EXR type that holds a format's stored values exactly; -1: none (8-bit
 * formats go as floats). */
static int exr_type_of(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32: return VRG_EXR_HALF;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT: return VRG_EXR_FLOAT;
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32B32A32_UINT: return VRG_EXR_UINT;
    default: return -1;
    }
}

int vrg_cli_dump_exr(vrg_graph *g, const char *resource, const char *path)
{
    vrg_resource_info info;
    if (vrg_graph_resource_info(g, resource, &info) != 0 || info.kind != VRG_IMAGE) {
        fprintf(stderr, "error: %s: the graph has no image resource '%s'\n", path, resource);
        return -1;
    }
    int type = exr_type_of(info.format);
    size_t n = (size_t)info.width * info.height;
    int rc;
    if (type < 0) { /* 8-bit: the floats vrg_graph_read gives, channels packed */
        vrg_image_data img;
        if (vrg_graph_read(g, resource, &img) != 0)
            return -1;
        for (size_t p = 0; p < n; p++)
            for (uint32_t c = 0; c < img.channels; c++)
                img.pixels[p * img.channels + c] = img.pixels[p * 4 + c];
        rc = vrg_write_exr(path, img.width, img.height, img.channels, VRG_EXR_FLOAT, img.pixels);
        free(img.pixels);
        return rc;
    }
    void *data;
    uint64_t size;
    if (vrg_graph_read_texels(g, resource, &data, &size) != 0)
        return -1;
    uint32_t channels = (uint32_t)(size / n / (type == VRG_EXR_HALF ? 2 : 4));
    if (info.format == VK_FORMAT_B10G11R11_UFLOAT_PACK32) {
        /* 11- and 10-bit floats are halves with fewer mantissa bits */
        uint16_t *half = malloc(n * 3 * sizeof *half);
        if (!half) {
            free(data);
            fprintf(stderr, "error: %s: out of memory\n", path);
            return -1;
        }
        for (size_t p = 0; p < n; p++) {
            uint32_t u;
            memcpy(&u, (const uint8_t *)data + 4 * p, 4);
            half[3 * p] = (uint16_t)((u & 0x7ff) << 4);
            half[3 * p + 1] = (uint16_t)(((u >> 11) & 0x7ff) << 4);
            half[3 * p + 2] = (uint16_t)((u >> 22) << 5);
        }
        free(data);
        data = half;
        channels = 3;
    }
    rc = vrg_write_exr(path, info.width, info.height, channels, (vrg_exr_type)type, data);
    free(data);
    return rc;
}

int vrg_cli_dump_buffer(vrg_graph *g, const char *resource, const char *dir, uint64_t frames)
{
    vrg_resource_info info;
    void *data;
    uint64_t size;
    char path[VRG_CLI_PATH];
    if (vrg_graph_resource_info(g, resource, &info) != 0 || vrg_graph_read_buffer(g, resource, &data, &size) != 0)
        return -1;
    snprintf(path, sizeof path, "%s/%s.bin", dir, resource);
    int rc = vrg_output_write(path, data, size);
    free(data);
    if (rc != 0)
        return -1;
    fprintf(stderr, "wrote %s\n", path);
    snprintf(path, sizeof path, "%s/%s.json", dir, resource);
    vrg_output *out = vrg_output_open(path);
    if (!out)
        return -1;
    char name[512], bin[600], writer[256];
    char binname[VRG_CLI_PATH];
    snprintf(binname, sizeof binname, "%s.bin", resource);
    FILE *f = vrg_output_stream(out);
    fprintf(f, "{\n  \"resource\": \"%s\",\n  \"kind\": \"buffer\",\n  \"file\": \"%s\",\n  \"bytes\": %llu,\n",
            vrg_cli_json_str(resource, name, sizeof name), vrg_cli_json_str(binname, bin, sizeof bin), (unsigned long long)size);
    if (info.format != VK_FORMAT_UNDEFINED)
        fprintf(f, "  \"texel_format\": \"%s\",\n", vrg_format_label(info.format));
    else
        fprintf(f, "  \"texel_format\": null,\n");
    if (info.writer)
        fprintf(f, "  \"written_by\": \"%s\",\n", vrg_cli_json_str(info.writer, writer, sizeof writer));
    else
        fprintf(f, "  \"written_by\": null,\n");
    fprintf(f, "  \"frames_rendered\": %llu\n}\n", (unsigned long long)frames);
    if (vrg_output_commit(out) != 0)
        return -1;
    fprintf(stderr, "wrote %s\n", path);
    return 0;
}
