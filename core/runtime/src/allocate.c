/* Phase 4, allocate: create every image and buffer, place transient ones in
 * shared heap blocks (aliasing, planned in alias.c), give kept ones (@prev
 * and persistent) their own memory, and name everything for debuggers. */
#include <math.h>
#include <string.h>
#include "internal.h"
#include "phases.h"

/* A relative size scales the graph's; an absolute one is as written. */
static void resource_extent(const vrg_graph *g, const _vrg_resource *r, uint32_t *w, uint32_t *h)
{
    if (r->abs_width) {
        *w = r->abs_width;
        *h = r->abs_height;
        return;
    }
    float s = r->scale > 0 ? r->scale : 1.0f;
    *w = (uint32_t)fmaxf(1.0f, floorf((float)g->width * s + 0.5f));
    *h = (uint32_t)fmaxf(1.0f, floorf((float)g->height * s + 0.5f));
}

static VkImageUsageFlags image_usage(const vrg_context *ctx, VkFormat format)
{
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(ctx->dev.physical_device, format, &fp);
    VkFormatFeatureFlags f = fp.optimalTilingFeatures;
    VkImageUsageFlags u = 0;
    if (f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)
        u |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (f & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT)
        u |= VK_IMAGE_USAGE_STORAGE_BIT;
    if (f & VK_FORMAT_FEATURE_TRANSFER_SRC_BIT)
        u |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (f & VK_FORMAT_FEATURE_TRANSFER_DST_BIT)
        u |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    return u;
}

static VkImageUsageFlags usage_for(vrg_access a)
{
    switch (a) {
    case VRG_ACCESS_SAMPLED: return VK_IMAGE_USAGE_SAMPLED_BIT;
    case VRG_ACCESS_TRANSFER_SRC: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case VRG_ACCESS_TRANSFER_DST: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    default: return VK_IMAGE_USAGE_STORAGE_BIT;
    }
}

/* The usage a resource needs: every declared access to it, plus transfers
 * for readback and clears. Missing format support is an error, not a crash. */
static int needed_usage(vrg_graph *g, int ri, VkImageUsageFlags *need)
{
    _vrg_resource *r = &g->res[ri];
    *need = 0;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++)
            if (p->slots[s].res == ri)
                *need |= usage_for(vrg_slot(p, s)->access);
    }
    if (r->internal_owner >= 0)
        *need |= usage_for(r->internal_first_access);
    if (r->is_output || r->readback)
        *need |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (r->history || r->persistent)
        *need |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    return 0;
}

/* An acceleration structure and its backing buffer, sized for r->size
 * instances. */
static int create_accel(vrg_graph *g, _vrg_resource *r)
{
    vrg_context *ctx = g->ctx;
    VkDevice dev = ctx->dev.device;
    if (!r->size)
        return 0;
    if (!ctx->dev.features.acceleration_structure) {
        _vrg_error_at(&g->diag, r->writer_line, VRG_E_DEVICE_UNSUPPORTED, "this device cannot build acceleration structures: use a graph that needs none", "resource '%s' needs VK_KHR_acceleration_structure, which '%s' lacks",
                     r->name, ctx->device_name);
        return -1;
    }
    VkAccelerationStructureGeometryKHR geom = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .geometry.instances = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR},
    };
    VkAccelerationStructureBuildGeometryInfoKHR info = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = &geom,
    };
    uint32_t count = (uint32_t)r->size;
    VkAccelerationStructureBuildSizesInfoKHR sizes = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    ctx->as.sizes(dev, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &count, &sizes);
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                             .size = sizes.accelerationStructureSize,
                             .usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT};
    if (vkCreateBuffer(dev, &bi, NULL, &r->buffer[0]) != VK_SUCCESS)
        return -1;
    vkGetBufferMemoryRequirements(dev, r->buffer[0], &r->req);
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO, .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    int type = _vrg_find_memory_type(ctx, r->req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .pNext = &flags, .allocationSize = r->req.size,
                               .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(dev, &ai, NULL, &r->own_memory[0]) != VK_SUCCESS ||
        vkBindBufferMemory(dev, r->buffer[0], r->own_memory[0], 0) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "out of device memory for acceleration structure '%s'", r->name);
        return -1;
    }
    VkAccelerationStructureCreateInfoKHR ci = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
                                               .buffer = r->buffer[0],
                                               .size = sizes.accelerationStructureSize,
                                               .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR};
    if (ctx->as.create(dev, &ci, NULL, &r->accel) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "cannot create acceleration structure '%s'", r->name);
        return -1;
    }
    _vrg_name_object(ctx, VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, (uint64_t)r->accel, "%s/%s", g->name, r->name);
    _vrg_name_object(ctx, VK_OBJECT_TYPE_BUFFER, (uint64_t)r->buffer[0], "%s/%s (storage)", g->name, r->name);
    return 0;
}

static int create_objects(vrg_graph *g, int ri)
{
    vrg_context *ctx = g->ctx;
    VkDevice dev = ctx->dev.device;
    _vrg_resource *r = &g->res[ri];
    int copies = r->history ? 2 : 1;
    if (r->kind == VRG_ACCEL)
        return create_accel(g, r);
    resource_extent(g, r, &r->width, &r->height);
    r->mips = 1;
    if (r->kind == VRG_IMAGE && r->mip_request > 1) {
        uint32_t full = 1, m = r->width > r->height ? r->width : r->height;
        while (m >>= 1)
            full++;
        r->mips = r->mip_request < full ? r->mip_request : full;
    }
    uint32_t max_dim = ctx->props.limits.maxImageDimension2D;
    if (r->kind == VRG_IMAGE && (r->width > max_dim || r->height > max_dim)) {
        _vrg_error_at(&g->diag, r->line, VRG_E_DEVICE_UNSUPPORTED, "lower its scale or the graph size", "resource '%s' would be %ux%u, larger than '%s' allows (%u)", r->name,
                     r->width, r->height, ctx->device_name, max_dim);
        return -1;
    }
    for (int c = 0; c < copies; c++) {
        if (r->kind == VRG_IMAGE) {
            VkImageUsageFlags need;
            needed_usage(g, ri, &need);
            VkImageUsageFlags have = image_usage(ctx, r->format);
            if ((need & have) != need) {
                _vrg_error_at(&g->diag, r->line, VRG_E_DEVICE_UNSUPPORTED, "choose another format in its [resource] section",
                             "resource '%s': format %s does not support the uses the graph makes of it on this device", r->name,
                             _vrg_format_name(r->format));
                return -1;
            }
            /* Also every use the format allows, so passes may vrg_pass_use() it other ways. */
            r->image_usage = have;
            VkImageCreateInfo ci = {
                .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                .imageType = VK_IMAGE_TYPE_2D,
                .format = r->format,
                .extent = {r->width, r->height, 1},
                .mipLevels = r->mips,
                .arrayLayers = 1,
                .samples = VK_SAMPLE_COUNT_1_BIT,
                .tiling = VK_IMAGE_TILING_OPTIMAL,
                .usage = have,
                .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
            };
            if (vkCreateImage(dev, &ci, NULL, &r->image[c]) != VK_SUCCESS) {
                _vrg_error_at(&g->diag, r->line, VRG_E_VULKAN_FAILED, NULL, "resource '%s': vkCreateImage failed (%ux%u %s)", r->name, r->width, r->height,
                             _vrg_format_name(r->format));
                return -1;
            }
            _vrg_name_object(ctx, VK_OBJECT_TYPE_IMAGE, (uint64_t)r->image[c], "%s/%s%s", g->name, r->name, c ? " (copy 1)" : "");
            vkGetImageMemoryRequirements(dev, r->image[c], &r->req);
        } else {
            r->buffer_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
            VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = r->size, .usage = r->buffer_usage};
            if (vkCreateBuffer(dev, &ci, NULL, &r->buffer[c]) != VK_SUCCESS) {
                _vrg_error_at(&g->diag, r->line, VRG_E_VULKAN_FAILED, NULL, "resource '%s': vkCreateBuffer failed (%llu bytes)", r->name, (unsigned long long)r->size);
                return -1;
            }
            _vrg_name_object(ctx, VK_OBJECT_TYPE_BUFFER, (uint64_t)r->buffer[c], "%s/%s%s", g->name, r->name, c ? " (copy 1)" : "");
            vkGetBufferMemoryRequirements(dev, r->buffer[c], &r->req);
        }
    }
    /* Images and buffers may share a block: keep them a granularity apart. */
    VkDeviceSize gran = ctx->props.limits.bufferImageGranularity;
    if (r->req.alignment < gran)
        r->req.alignment = gran;
    return 0;
}

static int bind_memory(vrg_graph *g, _vrg_resource *r, int c, VkDeviceMemory mem, VkDeviceSize offset)
{
    VkResult res = r->kind == VRG_IMAGE ? vkBindImageMemory(g->ctx->dev.device, r->image[c], mem, offset)
                                        : vkBindBufferMemory(g->ctx->dev.device, r->buffer[c], mem, offset);
    return res == VK_SUCCESS ? 0 : -1;
}

static int alloc_memory(vrg_graph *g, VkDeviceSize size, uint32_t type_bits, VkDeviceMemory *out, const char *what)
{
    int type = _vrg_find_memory_type(g->ctx, type_bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0)
        type = _vrg_find_memory_type(g->ctx, type_bits, 0);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = size, .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(g->ctx->dev.device, &ai, NULL, out) != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "out of device memory allocating %llu bytes for %s", (unsigned long long)size, what);
        return -1;
    }
    _vrg_name_object(g->ctx, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)*out, "%s/%s", g->name, what);
    return 0;
}

static void estimate_requirements(vrg_graph *g, _vrg_resource *r)
{
    resource_extent(g, r, &r->width, &r->height);
    uint64_t bytes = r->kind == VRG_IMAGE ? (uint64_t)r->width * r->height * _vrg_format_bytes(r->format)
                   : r->kind == VRG_ACCEL  ? r->size * 128 /* about a node per instance */
                                           : r->size;
    r->req = (VkMemoryRequirements){.size = (bytes + 255) / 256 * 256, .alignment = 256, .memoryTypeBits = 1};
}

int _vrg_allocate(vrg_graph *g)
{
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        memset(r->sync, 0, sizeof r->sync);
        r->carried = 0;
        if (r->first_use < 0)
            continue;
        if (!g->ctx)
            estimate_requirements(g, r);
        else if (create_objects(g, i) != 0)
            return -1;
    }
    if (_vrg_plan_aliasing(g) != 0)
        return -1;
    if (!g->ctx)
        return 0;
    for (int b = 0; b < g->block_count; b++) {
        char what[64];
        snprintf(what, sizeof what, "alias block %d", b);
        if (g->blocks[b].size && alloc_memory(g, g->blocks[b].size, g->blocks[b].type_bits, &g->blocks[b].memory, what) != 0)
            return -1;
    }
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->first_use < 0 || r->kind == VRG_ACCEL) /* accel: bound in create_accel */
            continue;
        int copies = r->history ? 2 : 1;
        for (int c = 0; c < copies; c++) {
            VkDeviceMemory mem;
            VkDeviceSize offset = 0;
            if (r->block >= 0) {
                mem = g->blocks[r->block].memory;
                offset = r->offset;
            } else {
                if (alloc_memory(g, r->req.size, r->req.memoryTypeBits, &r->own_memory[c], r->name) != 0)
                    return -1;
                mem = r->own_memory[c];
            }
            if (bind_memory(g, r, c, mem, offset) != 0) {
                _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "binding memory for resource '%s' failed", r->name);
                return -1;
            }
            if (r->kind == VRG_IMAGE) {
                VkImageViewCreateInfo vi = {
                    .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                    .image = r->image[c],
                    .viewType = VK_IMAGE_VIEW_TYPE_2D,
                    .format = r->format,
                    .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1},
                };
                if (vkCreateImageView(g->ctx->dev.device, &vi, NULL, &r->view[c]) != VK_SUCCESS) {
                    _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "cannot create a view of resource '%s'", r->name);
                    return -1;
                }
                _vrg_name_object(g->ctx, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)r->view[c], "%s/%s%s", g->name, r->name, c ? " (copy 1)" : "");
            }
        }
    }
    g->allocated = 1;
    g->fresh = 1;
    g->history_reset = 1;
    return 0;
}

void _vrg_free_resources(vrg_graph *g)
{
    if (!g->ctx)
        return;
    VkDevice dev = g->ctx->dev.device;
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->accel)
            g->ctx->as.destroy(dev, r->accel, NULL);
        r->accel = VK_NULL_HANDLE;
        for (int c = 0; c < 2; c++) {
            vkDestroyImageView(dev, r->view[c], NULL);
            vkDestroyBufferView(dev, r->texel_view[c], NULL);
            r->texel_view[c] = VK_NULL_HANDLE;
            vkDestroyImage(dev, r->image[c], NULL);
            vkDestroyBuffer(dev, r->buffer[c], NULL);
            vkFreeMemory(dev, r->own_memory[c], NULL);
            r->view[c] = VK_NULL_HANDLE;
            r->image[c] = VK_NULL_HANDLE;
            r->buffer[c] = VK_NULL_HANDLE;
            r->own_memory[c] = VK_NULL_HANDLE;
        }
    }
    for (int b = 0; b < g->block_count; b++) {
        vkFreeMemory(dev, g->blocks[b].memory, NULL);
        g->blocks[b].memory = VK_NULL_HANDLE;
    }
    g->allocated = 0;
}
