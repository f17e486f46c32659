/* NaN and infinity tracing (vrg_graph_desc.check_finite, and the context's
 * validation): after each pass, shaders/check_finite.comp reads every float
 * image the pass wrote and keeps the first non-finite value's pixel, channel
 * and kind in a word of the readback buffer (one word per check, each bound
 * alone so that the checks need no barriers between them). When the frame
 * has ended, the first check in schedule order that found one is the pass
 * that made it: later passes that spread it are not blamed. Off, none of
 * this is recorded. */
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "phases.h"

typedef struct _vrg_finite_check {
    int k;   /* schedule position of the pass */
    int res; /* the image it wrote */
} _vrg_finite_check;

struct _vrg_finite {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkSampler sampler;
    _vrg_finite_check *checks;
    int count;
};

static int is_float(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32: return 1;
    default: return 0;
    }
}

int _vrg_finite_create(vrg_graph *g)
{
    vrg_context *ctx = g->ctx;
    VkDevice dev = ctx->dev.device;
    struct _vrg_finite *f = calloc(1, sizeof *f);
    g->finite = f;
    if (!f) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "check_finite: out of memory");
        return -1;
    }
    char path[VRG_PATH_MAX];
    snprintf(path, sizeof path, "%s/shaders/check_finite.comp", vrg_data_dir());
    VkShaderModule sm = vrg_compile_compute_shader(ctx, path, NULL); /* says why it failed */
    if (!sm) {
        _vrg_error(&g->diag, VRG_E_SHADER_FAILED, "check_finite: %s does not compile (see above)", path);
        return -1;
    }
    VkDescriptorSetLayoutBinding b[2] = {
        {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
    };
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, .bindingCount = 2, .pBindings = b};
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
    VkResult res = vkCreateDescriptorSetLayout(dev, &sli, NULL, &f->set_layout);
    if (res == VK_SUCCESS) {
        VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1, .pSetLayouts = &f->set_layout,
                                          .pushConstantRangeCount = 1, .pPushConstantRanges = &range};
        res = vkCreatePipelineLayout(dev, &pli, NULL, &f->layout);
    }
    if (res == VK_SUCCESS) {
        VkComputePipelineCreateInfo ci = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = sm, .pName = "main"},
            .layout = f->layout,
        };
        res = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, NULL, &f->pipeline);
    }
    vkDestroyShaderModule(dev, sm, NULL);
    /* texelFetch only; nearest, so that a format without linear filtering is fine */
    VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST, .minFilter = VK_FILTER_NEAREST,
                              .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    if (res == VK_SUCCESS)
        res = vkCreateSampler(dev, &si, NULL, &f->sampler);
    if (res != VK_SUCCESS) {
        _vrg_error(&g->diag, VRG_E_VULKAN_FAILED, "check_finite: creating its pipeline failed (%d)", res);
        return -1;
    }
    _vrg_name_object(ctx, VK_OBJECT_TYPE_PIPELINE, (uint64_t)f->pipeline, "%s/check_finite", g->name);
    return 0;
}

void _vrg_finite_destroy(vrg_graph *g)
{
    struct _vrg_finite *f = g->finite;
    if (!f)
        return;
    VkDevice dev = g->ctx->dev.device;
    vkDestroyPipeline(dev, f->pipeline, NULL);
    vkDestroyPipelineLayout(dev, f->layout, NULL);
    vkDestroyDescriptorSetLayout(dev, f->set_layout, NULL);
    vkDestroySampler(dev, f->sampler, NULL);
    free(f->checks);
    free(f);
    g->finite = NULL;
}

/* Whether pass p writes resource i through one of its slots (a write
 * access: output, or an input it also writes). */
static int writes(const vrg_pass *p, int i)
{
    for (int s = 0; s < (int)p->plugin->desc->slot_count; s++)
        if (p->slots[s].res == i && !p->slots[s].prev && !p->slots[s].dummy &&
            _vrg_access_info_of(vrg_slot(p, s)->access, VRG_IMAGE).writes)
            return 1;
    return 0;
}

/* The shader's key is (pixel * 4 + channel) * 4 + kind in 32 bits. */
#define FINITE_MAX_TEXELS (1u << 28)

int _vrg_finite_plan(vrg_graph *g)
{
    struct _vrg_finite *f = g->finite;
    free(f->checks);
    f->count = 0;
    f->checks = calloc((size_t)g->schedule_count * VRG_MAX_SLOTS + 1, sizeof *f->checks);
    if (!f->checks) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_MEMORY, "checking for NaN and infinity: out of memory");
        return -1;
    }
    for (int k = 0; k < g->schedule_count; k++) {
        const vrg_pass *p = &g->passes[g->schedule[k]];
        for (int i = 0; i < g->res_count; i++) {
            const _vrg_resource *r = &g->res[i];
            if (!(r->kind == VRG_IMAGE && r->first_use >= 0 && is_float(r->format) && writes(p, i)))
                continue;
            if ((uint64_t)r->width * r->height > FINITE_MAX_TEXELS) {
                _vrg_error(&g->diag, VRG_E_DEVICE_UNSUPPORTED,
                           "checking for NaN and infinity: resource '%s' (%ux%u) has more than %u texels, which the check cannot number",
                           r->name, r->width, r->height, FINITE_MAX_TEXELS);
                return -1;
            }
            f->checks[f->count++] = (_vrg_finite_check){k, i};
        }
    }
    return f->count;
}

void _vrg_finite_begin(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base)
{
    struct _vrg_finite *f = g->finite;
    if (!f->count)
        return;
    /* no value found yet: the largest key */
    vkCmdFillBuffer(cmd, g->readback_buffer, slot_base + g->finite_offset, (VkDeviceSize)f->count * g->finite_stride, 0xffffffffu);
    VkBufferMemoryBarrier2 to_shader = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = g->readback_buffer,
        .offset = slot_base + g->finite_offset,
        .size = (VkDeviceSize)f->count * g->finite_stride,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &to_shader};
    vkCmdPipelineBarrier2(cmd, &dep);
}

void _vrg_finite_after_pass(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base, int k)
{
    struct _vrg_finite *f = g->finite;
    int first = 0;
    while (first < f->count && f->checks[first].k < k)
        first++;
    if (first == f->count || f->checks[first].k != k)
        return;
    _vrg_barrier_rec b[VRG_MAX_SLOTS] = {0}; /* a check per slot at most: writes() goes through slots */
    int nb = 0, last = first;
    for (; last < f->count && f->checks[last].k == k; last++) {
        int i = f->checks[last].res;
        if (_vrg_resource_barrier(g, i, _vrg_copy_of(g, i, 0), VRG_ACCESS_SAMPLED, &b[nb]))
            nb++;
    }
    _vrg_emit_barriers(g, cmd, b, nb);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, f->pipeline);
    for (int c = first; c < last; c++) {
        const _vrg_resource *r = &g->res[f->checks[c].res];
        VkDescriptorImageInfo img = {.sampler = f->sampler, .imageView = r->view[_vrg_copy_of(g, f->checks[c].res, 0)],
                                     .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorBufferInfo word = {.buffer = g->readback_buffer, .offset = slot_base + g->finite_offset + (VkDeviceSize)c * g->finite_stride,
                                       .range = 4};
        VkWriteDescriptorSet w[2] = {
            {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstBinding = 0, .descriptorCount = 1,
             .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = &img},
            {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstBinding = 1, .descriptorCount = 1,
             .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &word},
        };
        g->ctx->push_descriptor(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, f->layout, 0, 2, w);
        uint32_t channels = _vrg_format_channels(r->format);
        vkCmdPushConstants(cmd, f->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof channels, &channels);
        vkCmdDispatch(cmd, (r->width + g->ctx->group_size[0] - 1) / g->ctx->group_size[0],
                      (r->height + g->ctx->group_size[1] - 1) / g->ctx->group_size[1], 1);
    }
}

void _vrg_finite_end(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base)
{
    struct _vrg_finite *f = g->finite;
    if (!f->count)
        return;
    VkBufferMemoryBarrier2 host = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        .srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
        .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = g->readback_buffer,
        .offset = slot_base + g->finite_offset,
        .size = (VkDeviceSize)f->count * g->finite_stride,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &host};
    vkCmdPipelineBarrier2(cmd, &dep);
}

int _vrg_finite_failed(vrg_graph *g)
{
    if (!g->finite_failed)
        return 0;
    g->finite_failed = 0;
    return -1;
}

static const char *channel_name(uint32_t channels, uint32_t c)
{
    static const char *rgba[] = {"R", "G", "B", "A"};
    return channels == 1 ? "the only channel" : rgba[c & 3];
}

int _vrg_finite_collect(vrg_graph *g, VkDeviceSize slot_base, uint64_t frame_index)
{
    struct _vrg_finite *f = g->finite;
    const uint8_t *words = (const uint8_t *)g->readback_map + slot_base + g->finite_offset;
    int c = 0;
    uint32_t key = 0xffffffffu;
    for (; c < f->count; c++) {
        memcpy(&key, words + (size_t)c * g->finite_stride, 4);
        if (key != 0xffffffffu)
            break;
    }
    if (c == f->count)
        return 0;
    const vrg_pass *p = &g->passes[g->schedule[f->checks[c].k]];
    int ri = f->checks[c].res;
    const _vrg_resource *r = &g->res[ri];
    uint32_t kind = key & 3, channel = (key >> 2) & 3, pixel = key >> 4;
    uint32_t x = pixel % r->width, y = pixel / r->width, channels = _vrg_format_channels(r->format);
    static const char *kinds[] = {"NaN", "+Inf", "-Inf", "?"};
    char inputs[4096] = "";
    size_t used = 0;
    if (g->check_finite == 2) {
        /* the pass's image inputs at that pixel, as `voxrg inspect` prints them */
        int res[VRG_MAX_SLOTS + 1], prev[VRG_MAX_SLOTS + 1], n = 0;
        uint32_t tx[VRG_MAX_SLOTS + 1], ty[VRG_MAX_SLOTS + 1];
        /* the graph pixel the texel lies in, then each input's texel there */
        uint32_t gx = (uint32_t)(((uint64_t)x * 2 + 1) * g->width / (2 * (uint64_t)r->width));
        uint32_t gy = (uint32_t)(((uint64_t)y * 2 + 1) * g->height / (2 * (uint64_t)r->height));
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
            const _vrg_binding_ref *b = &p->slots[s];
            if (vrg_slot(p, s)->dir != VRG_IN || b->res < 0 || b->dummy || g->res[b->res].kind != VRG_IMAGE)
                continue;
            const _vrg_resource *in = &g->res[b->res];
            res[n] = b->res, prev[n] = b->prev;
            tx[n] = (uint32_t)((uint64_t)gx * in->width / g->width);
            ty[n] = (uint32_t)((uint64_t)gy * in->height / g->height);
            n++;
        }
        vrg_pixel_value v[VRG_MAX_SLOTS + 1];
        if (n && _vrg_read_texels_at(g, n, res, prev, tx, ty, v) == 0)
            for (int e = 0; e < n && used < sizeof inputs; e++) {
                char text[256];
                int w = snprintf(inputs + used, sizeof inputs - used, "%s%s%s (%s) at %u,%u: %s", e ? "; " : " ", v[e].resource, v[e].prev ? "@prev" : "",
                                 _vrg_format_name(v[e].format), v[e].x, v[e].y, vrg_pixel_value_text(&v[e], text, sizeof text));
                used += w > 0 ? (size_t)w : 0;
            }
        else if (!n)
            snprintf(inputs, sizeof inputs, " none (it reads no image)");
    }
    _vrg_error_hint(&g->diag, VRG_E_NOT_FINITE,
                    g->check_finite == 2 ? "`voxrg inspect GRAPH --pixel X,Y --frame N` prints every image at that pixel"
                                         : "--check-finite (vrg_graph_desc.check_finite) also prints the pass's inputs at that pixel",
                    "frame %llu: pass '%s' (plugin %s) wrote %s to '%s' (%s), channel %u (%s) of pixel %u,%u, the first in row order; no "
                    "earlier pass wrote a NaN or infinity%s%s",
                    (unsigned long long)frame_index, p->name, p->plugin->name, kinds[kind], r->name, _vrg_format_name(r->format), channel,
                    channel_name(channels, channel), x, y, g->check_finite == 2 ? ". Its inputs there:" : "", inputs);
    return -1;
}
