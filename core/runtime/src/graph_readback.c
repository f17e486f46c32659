/* What a host reads of the last frame: the read-back copies of the output
 * and dumped resources (converted to floats), and the images themselves
 * for a viewer, which picks one to show (kept in TRANSFER_SRC after each
 * frame, as the output is). */
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "phases.h"

static int find_readable(vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0) {
            if (!(g->res[i].is_output || g->res[i].readback || i == g->shown) || g->res[i].first_use < 0) {
                _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "resource '%s' is not read back (ask for it in vrg_graph_desc.readback)", name);
                return -1;
            }
            if (g->last_slot < 0) {
                _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "resource '%s': no frame rendered yet", name);
                return -1;
            }
            /* what is read is the last submitted frame's: it must end first */
            return _vrg_wait_frames(g) == 0 ? i : -1;
        }
    _vrg_error(&g->diag, VRG_E_UNKNOWN_RESOURCE, "the graph has no resource '%s'", name);
    return -1;
}

/* The last submitted frame's part of the readback buffer. */
static const uint8_t *last_readback(const vrg_graph *g) { return (const uint8_t *)g->readback_map + g->slots[g->last_slot].readback_base; }

VkImageView vrg_graph_image_view(vrg_graph *g, const char *name)
{
    int i = find_readable(g, name);
    return i < 0 || g->res[i].kind != VRG_IMAGE ? VK_NULL_HANDLE : g->res[i].view[_vrg_copy_of(g, i, g->res[i].history)];
}

int vrg_graph_image(vrg_graph *g, const char *name, VkImage *image, VkExtent2D *extent, VkFormat *format)
{
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_IMAGE) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is not an image", name);
        return -1;
    }
    /* the frame counter moved on: last frame's copy is now the "previous" one */
    *image = r->image[_vrg_copy_of(g, i, r->history)];
    *extent = (VkExtent2D){r->width, r->height};
    *format = r->format;
    return 0;
}

int vrg_graph_read(vrg_graph *g, const char *name, vrg_image_data *out)
{
    memset(out, 0, sizeof *out);
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_IMAGE) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is a buffer: use vrg_graph_read_buffer", name);
        return -1;
    }
    const uint8_t *src = last_readback(g) + g->readback_offset[i];
    uint32_t ch = _vrg_format_channels(r->format);
    size_t n = (size_t)r->width * r->height;
    out->width = r->width;
    out->height = r->height;
    out->channels = ch;
    out->format = r->format;
    out->pixels = calloc(n * 4, sizeof(float));
    for (size_t p = 0; p < n; p++) {
        float v[4] = {0, 0, 0, 1};
        for (uint32_t c = 0; c < ch; c++) {
            switch (r->format) {
            case VK_FORMAT_R8_UNORM:
            case VK_FORMAT_R8G8_UNORM:
            case VK_FORMAT_R8G8B8A8_UNORM: v[c] = _vrg_unorm8_to_float(src[p * ch + c], 0); break;
            case VK_FORMAT_R8G8B8A8_SRGB: v[c] = _vrg_unorm8_to_float(src[p * 4 + c], c < 3); break;
            case VK_FORMAT_R16_SFLOAT:
            case VK_FORMAT_R16G16_SFLOAT:
            case VK_FORMAT_R16G16B16A16_SFLOAT: {
                uint16_t h;
                memcpy(&h, src + (p * ch + c) * 2, 2);
                v[c] = _vrg_half_to_float(h);
                break;
            }
            case VK_FORMAT_R32_UINT:
            case VK_FORMAT_R32G32_UINT:
            case VK_FORMAT_R32G32B32A32_UINT: {
                uint32_t u;
                memcpy(&u, src + (p * ch + c) * 4, 4);
                v[c] = (float)u;
                break;
            }
            case VK_FORMAT_B10G11R11_UFLOAT_PACK32: {
                uint32_t u;
                memcpy(&u, src + p * 4, 4);
                /* 11/11/10-bit floats share half's exponent: widen them to halves */
                uint32_t bits[3] = {(u & 0x7ff) << 4, ((u >> 11) & 0x7ff) << 4, ((u >> 22) & 0x3ff) << 5};
                v[c] = _vrg_half_to_float((uint16_t)bits[c]);
                break;
            }
            default: memcpy(&v[c], src + (p * ch + c) * 4, 4); break;
            }
        }
        memcpy(out->pixels + p * 4, v, sizeof v);
    }
    return 0;
}

/* A malloc'd copy of readable resource `name`'s bytes as the last frame
 * left them, when it is of `kind` (else the error names `other`, the read
 * for the other kind); its size is the buffer's, or the image's texels. */
static int copy_readback(vrg_graph *g, const char *name, vrg_resource_kind kind, const char *other, void **data, uint64_t *size)
{
    *data = NULL;
    *size = 0;
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != kind) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is %s: use %s", name, kind == VRG_BUFFER ? "an image" : "a buffer", other);
        return -1;
    }
    uint64_t bytes = kind == VRG_BUFFER ? r->size : (uint64_t)r->width * r->height * _vrg_format_bytes(r->format);
    if (!(*data = malloc(bytes ? bytes : 1))) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "resource '%s': out of memory for %llu bytes", name, (unsigned long long)bytes);
        return -1;
    }
    memcpy(*data, last_readback(g) + g->readback_offset[i], bytes);
    *size = bytes;
    return 0;
}

int vrg_graph_read_buffer(vrg_graph *g, const char *name, void **data, uint64_t *size)
{
    return copy_readback(g, name, VRG_BUFFER, "vrg_graph_read", data, size);
}

int vrg_graph_read_texels(vrg_graph *g, const char *name, void **data, uint64_t *size)
{
    return copy_readback(g, name, VRG_IMAGE, "vrg_graph_read_buffer", data, size);
}

static int showable(const vrg_graph *g, int i)
{
    const _vrg_resource *r = &g->res[i];
    return r->kind == VRG_IMAGE && r->first_use >= 0 && r->writer >= 0 && r->internal_owner < 0 && !r->dummy;
}

uint32_t vrg_graph_image_count(const vrg_graph *g)
{
    uint32_t n = 0;
    for (int i = 0; g->desc.keep_images && i < g->res_count; i++)
        n += showable(g, i);
    return n;
}

const char *vrg_graph_image_name(const vrg_graph *g, uint32_t k)
{
    for (int i = 0; g->desc.keep_images && i < g->res_count; i++)
        if (showable(g, i) && k-- == 0)
            return g->res[i].name;
    return NULL;
}

int vrg_graph_show(vrg_graph *g, const char *name)
{
    g->shown = -1;
    if (!name)
        return 0;
    for (int i = 0; i < g->res_count; i++)
        if (strcmp(g->res[i].name, name) == 0 && g->desc.keep_images && showable(g, i)) {
            g->shown = i;
            return 0;
        }
    _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "show %s: not an image this graph keeps for viewing (load it with keep_images)", name);
    return -1;
}

/* The entries of vrg_graph_read_pixels, in order: resource and copy. */
static int pixel_entries(const vrg_graph *g, int *res, int *prev)
{
    int n = 0;
    uint8_t listed[VRG_MAX_RESOURCES] = {0};
    for (int k = 0; k < g->schedule_count; k++) {
        int pi = g->schedule[k];
        const vrg_pass *p = &g->passes[pi];
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
            int i = p->slots[s].res;
            if (i < 0 || listed[i] || g->res[i].writer != pi || !showable(g, i))
                continue;
            listed[i] = 1;
            res[n] = i, prev[n] = 0, n++;
            if (g->res[i].history)
                res[n] = i, prev[n] = 1, n++;
        }
    }
    return n;
}

int vrg_graph_read_pixels(vrg_graph *g, uint32_t x, uint32_t y, vrg_pixel_value *out, uint32_t max)
{
    if (!g->ctx) {
        _vrg_error(&g->diag, VRG_E_NO_DEVICE, "graph '%s' was loaded without a device: no pixel to read", g->name);
        return -1;
    }
    if (g->last_slot < 0) {
        _vrg_error(&g->diag, VRG_E_NOT_READ_BACK, "pixel (%u, %u): no frame rendered yet", x, y);
        return -1;
    }
    if (x >= g->width || y >= g->height) {
        _vrg_error(&g->diag, VRG_E_PIXEL_OUTSIDE, "pixel (%u, %u) is outside the graph's %ux%u (0..%u, 0..%u)", x, y, g->width, g->height,
                   g->width - 1, g->height - 1);
        return -1;
    }
    int res[2 * VRG_MAX_RESOURCES], prev[2 * VRG_MAX_RESOURCES];
    uint32_t tx[2 * VRG_MAX_RESOURCES], ty[2 * VRG_MAX_RESOURCES];
    int n = pixel_entries(g, res, prev);
    vrg_pixel_value *all = malloc(((size_t)n + 1) * sizeof *all);
    if (!all) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "pixel (%u, %u): out of memory", x, y);
        return -1;
    }
    for (int e = 0; e < n; e++) {
        tx[e] = (uint32_t)((uint64_t)x * g->res[res[e]].width / g->width);
        ty[e] = (uint32_t)((uint64_t)y * g->res[res[e]].height / g->height);
    }
    int rc = _vrg_wait_frames(g) == 0 ? _vrg_read_texels_at(g, n, res, prev, tx, ty, all) : -1;
    if (rc == 0 && max > 0) /* max 0: the count alone (out may be NULL) */
        memcpy(out, all, (size_t)(n < (int)max ? n : (int)max) * sizeof *out);
    free(all);
    return rc == 0 ? n : -1;
}
