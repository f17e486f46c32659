/* One texel of images after a frame, as stored: copied to the readback
 * buffer's pixel area and decoded to bits and exact values
 * (vrg_graph_read_pixels, and --check-finite's report of a pass's inputs). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

float _vrg_half_to_float(uint16_t h)
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

float _vrg_unorm8_to_float(uint8_t byte, int srgb)
{
    float c = byte / 255.0f;
    return !srgb ? c : c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
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
            /* the float an EXR dump holds (vrg_graph_read's), exactly */
            value = _vrg_unorm8_to_float(src[c], format == VK_FORMAT_R8G8B8A8_SRGB && c < 3);
            break;
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SFLOAT: {
            uint16_t h;
            memcpy(&h, src + 2 * c, 2);
            bits = h;
            value = _vrg_half_to_float(h);
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
            value = _vrg_half_to_float((uint16_t)(c < 2 ? bits << 4 : bits << 5));
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

int _vrg_read_texels_at(vrg_graph *g, int n, const int *res, const int *prev, const uint32_t *tx, const uint32_t *ty, vrg_pixel_value *out)
{
    /* every frame has ended (the caller waited): the next slot's command
     * buffer and fence are free */
    struct _vrg_frame_slot *s = &g->slots[g->submitted % g->frames_in_flight];
    VkCommandBuffer cmd = s->cmd;
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VkResult vr = vkResetCommandBuffer(cmd, 0);
    if (vr == VK_SUCCESS)
        vr = vkBeginCommandBuffer(cmd, &bi);
    if (vr != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "reading pixels: beginning the copies' command buffer failed (%d)", vr);
        return -1;
    }
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
    vr = vkEndCommandBuffer(cmd);
    if (vr != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "reading pixels: recording the copies failed (%d)", vr);
        return -1;
    }
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi};
    if (vkResetFences(g->ctx->dev.device, 1, &s->fence) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "reading pixels: resetting the fence failed");
        return -1;
    }
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
        used += (size_t)snprintf(buf + used, cap - used, ")");
    /* an 8-bit value is the float an EXR dump holds; the byte is what is stored */
    int unorm8 = v->format == VK_FORMAT_R8_UNORM || v->format == VK_FORMAT_R8G8_UNORM || v->format == VK_FORMAT_R8G8B8A8_UNORM ||
                 v->format == VK_FORMAT_R8G8B8A8_SRGB;
    for (uint32_t c = 0; unorm8 && c < v->channels && used < cap; c++) {
        int n = snprintf(buf + used, cap - used, "%s%u", c ? ", " : " bytes (", v->bits[c]);
        used += n > 0 ? (size_t)n : 0;
    }
    if (unorm8 && used < cap)
        snprintf(buf + used, cap - used, ")");
    return buf;
}
