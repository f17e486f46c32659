/* What a host reads of the last frame: the read-back copies of the output
 * and dumped resources (converted to floats), and the images themselves
 * for a viewer, which picks one to show (kept in TRANSFER_SRC after each
 * frame, as the output is). */
#include <math.h>
#include <stdio.h>
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

static float half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h >> 15) << 31, exp = (h >> 10) & 0x1f, mant = h & 0x3ff, bits;
    if (exp == 0) {
        if (mant == 0)
            bits = sign;
        else { /* subnormal */
            exp = 127 - 14;
            while (!(mant & 0x400)) {
                mant <<= 1;
                exp--;
            }
            bits = sign | (exp << 23) | ((mant & 0x3ff) << 13);
        }
    } else if (exp == 31)
        bits = sign | 0x7f800000u | (mant << 13);
    else
        bits = sign | ((exp + 127 - 15) << 23) | (mant << 13);
    float f;
    memcpy(&f, &bits, 4);
    return f;
}

static float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f); }

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
            case VK_FORMAT_R8G8B8A8_UNORM: v[c] = src[p * ch + c] / 255.0f; break;
            case VK_FORMAT_R8G8B8A8_SRGB: v[c] = c < 3 ? srgb_to_linear(src[p * 4 + c] / 255.0f) : src[p * 4 + c] / 255.0f; break;
            case VK_FORMAT_R16_SFLOAT:
            case VK_FORMAT_R16G16_SFLOAT:
            case VK_FORMAT_R16G16B16A16_SFLOAT: {
                uint16_t h;
                memcpy(&h, src + (p * ch + c) * 2, 2);
                v[c] = half_to_float(h);
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
                v[c] = half_to_float((uint16_t)bits[c]);
                break;
            }
            default: memcpy(&v[c], src + (p * ch + c) * 4, 4); break;
            }
        }
        memcpy(out->pixels + p * 4, v, sizeof v);
    }
    return 0;
}

int vrg_graph_read_buffer(vrg_graph *g, const char *name, void **data, uint64_t *size)
{
    *data = NULL;
    *size = 0;
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_BUFFER) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is an image: use vrg_graph_read", name);
        return -1;
    }
    *data = malloc(r->size);
    memcpy(*data, last_readback(g) + g->readback_offset[i], r->size);
    *size = r->size;
    return 0;
}

int vrg_graph_read_texels(vrg_graph *g, const char *name, void **data, uint64_t *size)
{
    *data = NULL;
    *size = 0;
    int i = find_readable(g, name);
    if (i < 0)
        return -1;
    _vrg_resource *r = &g->res[i];
    if (r->kind != VRG_IMAGE) {
        _vrg_error(&g->diag, VRG_E_WRONG_READ, "resource '%s' is a buffer: use vrg_graph_read_buffer", name);
        return -1;
    }
    uint64_t bytes = (uint64_t)r->width * r->height * _vrg_format_bytes(r->format);
    if (!(*data = malloc(bytes))) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "resource '%s': out of memory for %llu bytes", name, (unsigned long long)bytes);
        return -1;
    }
    memcpy(*data, last_readback(g) + g->readback_offset[i], bytes);
    *size = bytes;
    return 0;
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

/* Whether resource i still holds what the frame wrote: no resource that
 * shares its memory was used after it. */
static int kept_to_end(const vrg_graph *g, int i)
{
    const _vrg_resource *r = &g->res[i];
    for (int k = 0; k < r->overlap_count; k++)
        if (g->res[g->overlaps[r->overlap_first + k]].first_use > r->last_use)
            return 0;
    return 1;
}

/* One texel's stored channels, as bits and as exact values. */
static void decode_texel(const uint8_t *src, VkFormat format, vrg_pixel_value *v)
{
    for (uint32_t c = 0; c < v->channels; c++) {
        uint32_t bits = 0;
        double value;
        switch (format) {
        case VK_FORMAT_R8_UNORM:
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
            bits = src[c];
            value = bits / 255.0;
            break;
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SFLOAT: {
            uint16_t h;
            memcpy(&h, src + 2 * c, 2);
            bits = h;
            value = half_to_float(h);
            break;
        }
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32B32A32_UINT:
            memcpy(&bits, src + 4 * c, 4);
            value = bits;
            break;
        case VK_FORMAT_B10G11R11_UFLOAT_PACK32: {
            uint32_t u;
            memcpy(&u, src, 4);
            bits = c == 0 ? u & 0x7ff : c == 1 ? (u >> 11) & 0x7ff : u >> 22;
            /* 11/11/10-bit floats share half's exponent: widen them to halves */
            value = half_to_float((uint16_t)(c < 2 ? bits << 4 : bits << 5));
            break;
        }
        default: {
            float f;
            memcpy(&bits, src + 4 * c, 4);
            memcpy(&f, &bits, 4);
            value = f;
            break;
        }
        }
        v->bits[c] = bits;
        v->value[c] = value;
    }
}

static int is_uint_format(VkFormat f) { return f == VK_FORMAT_R32_UINT || f == VK_FORMAT_R32G32_UINT || f == VK_FORMAT_R32G32B32A32_UINT; }

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

int _vrg_read_texels_at(vrg_graph *g, int n, const int *res, const int *prev, const uint32_t *tx, const uint32_t *ty, vrg_pixel_value *out)
{
    if (_vrg_wait_frames(g) != 0)
        return -1;
    /* every frame has ended: the next slot's command buffer and fence are free */
    struct _vrg_frame_slot *s = &g->slots[g->submitted % g->frames_in_flight];
    VkCommandBuffer cmd = s->cmd;
    vkResetCommandBuffer(cmd, 0);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &bi);
    _vrg_barrier_rec b[2 * VRG_MAX_RESOURCES] = {0};
    int nb = 0, kept[2 * VRG_MAX_RESOURCES];
    /* The last frame's copy of a history resource: the frame counter moved
     * on, so it is now the "previous" one, and its @prev the current one. */
    for (int e = 0; e < n; e++) {
        int i = res[e], c = _vrg_copy_of(g, i, g->res[i].history && !prev[e]);
        kept[e] = prev[e] || _vrg_resource_kept(&g->res[i]) || kept_to_end(g, i);
        if (kept[e] && _vrg_resource_barrier(g, i, c, VRG_ACCESS_TRANSFER_SRC, &b[nb]))
            nb++;
    }
    _vrg_emit_barriers(g, cmd, b, nb);
    for (int e = 0; e < n; e++) {
        const _vrg_resource *r = &g->res[res[e]];
        if (!kept[e])
            continue;
        VkBufferImageCopy region = {
            .bufferOffset = g->pixel_offset + (VkDeviceSize)e * VRG_PIXEL_BYTES,
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .imageOffset = {(int32_t)tx[e], (int32_t)ty[e], 0},
            .imageExtent = {1, 1, 1},
        };
        vkCmdCopyImageToBuffer(cmd, r->image[_vrg_copy_of(g, res[e], r->history && !prev[e])], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               g->readback_buffer, 1, &region);
    }
    VkBufferMemoryBarrier2 host = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
        .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = g->readback_buffer,
        .offset = g->pixel_offset,
        .size = 2 * VRG_MAX_RESOURCES * VRG_PIXEL_BYTES,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &host};
    vkCmdPipelineBarrier2(cmd, &dep);
    vkEndCommandBuffer(cmd);
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
    vkResetFences(g->ctx->dev.device, 1, &s->fence);
    if (vkQueueSubmit2(g->ctx->dev.queue, 1, &si, s->fence) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "reading pixels: submitting the copies failed");
        return -1;
    }
    double waited;
    _vrg_wait_result w = _vrg_wait_fence(g->ctx, s->fence, &waited);
    if (w != VRG_WAIT_DONE) {
        _vrg_error(&g->diag, w == VRG_WAIT_FAILED ? VRG_E_DEVICE_LOST : VRG_E_GPU_TIMEOUT, "reading pixels: the copies %s after %.1f s",
                   w == VRG_WAIT_FAILED ? "failed" : w == VRG_WAIT_INTERRUPTED ? "were interrupted" : "timed out", waited);
        return -1;
    }
    for (int e = 0; e < n; e++) {
        const _vrg_resource *r = &g->res[res[e]];
        vrg_pixel_value *v = &out[e];
        memset(v, 0, sizeof *v);
        v->resource = r->name;
        v->pass = r->writer >= 0 ? g->passes[r->writer].name : "";
        v->format = r->format;
        v->channels = _vrg_format_channels(r->format);
        v->x = tx[e];
        v->y = ty[e];
        v->width = r->width;
        v->height = r->height;
        v->prev = prev[e];
        v->is_uint = is_uint_format(r->format);
        v->kept = kept[e];
        if (kept[e])
            decode_texel((const uint8_t *)g->readback_map + g->pixel_offset + (size_t)e * VRG_PIXEL_BYTES, r->format, v);
    }
    return 0;
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
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "pixel (%u, %u): out of memory", x, y);
        return -1;
    }
    for (int e = 0; e < n; e++) {
        tx[e] = (uint32_t)((uint64_t)x * g->res[res[e]].width / g->width);
        ty[e] = (uint32_t)((uint64_t)y * g->res[res[e]].height / g->height);
    }
    int rc = _vrg_read_texels_at(g, n, res, prev, tx, ty, all);
    if (rc == 0)
        memcpy(out, all, (size_t)(n < (int)max ? n : (int)max) * sizeof *out);
    free(all);
    return rc == 0 ? n : -1;
}

const char *vrg_pixel_value_text(const vrg_pixel_value *v, char *buf, size_t cap)
{
    if (!cap)
        return buf;
    if (!v->kept) {
        snprintf(buf, cap, "(not kept)");
        return buf;
    }
    size_t used = 0;
    buf[0] = 0;
    for (uint32_t c = 0; c < v->channels && used < cap; c++) {
        const char *sep = c ? ", " : "(";
        int n = v->is_uint ? snprintf(buf + used, cap - used, "%s%u", sep, v->bits[c]) : snprintf(buf + used, cap - used, "%s%.17g", sep, v->value[c]);
        used += n > 0 ? (size_t)n : 0;
    }
    if (used < cap)
        snprintf(buf + used, cap - used, ")");
    return buf;
}
