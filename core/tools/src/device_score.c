/* Scoring on the device (voxrg/device_score.h): two compute stages on the
 * context's queue (shaders/score/): along rows, the per-pixel conversions,
 * the horizontal filters and the integer errors; down columns, the
 * vertical filters with FLIP's and SSIM's per-pixel values. Each
 * invocation adds the values of its strip of pixels in order, and the
 * host adds the strips' sums in order in double: the same scores on every
 * run. The candidate and reference of the previous frame stay on the
 * device (two slots, used in turn) for the temporal error. The filter
 * kernels come from the CPU metrics' own code (metrics_kernels.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/device_score.h"
#include "voxrg/metrics.h"
#include "metrics_kernels.h"

/* as shaders/score/score.glsl lays them out */
enum { TMP_PLANES = 19, MAX_TAPS = 64 };
/* Pixels an invocation of a stage walks along its axis, its windows in
 * registers, one read per input and pixel: on a CPU device (lavapipe) the
 * reads, the writes and the windows' shifts are most of the work, not the
 * sums (docs/benchmarks.md has what each shape cost). */
enum { STRIP = 128 };
enum { STAGE_FILTER_X, STAGE_FILTER_Y, STAGES };
static const char *const stage_files[STAGES] = {"filter_x.comp", "filter_y.comp"};

typedef struct scorer_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped; /* host-visible ones */
    VkDeviceSize size;
    VkDeviceAddress address;
} scorer_buffer;

struct vrg_device_scorer {
    vrg_context *ctx;
    const vrg_device *dev;
    uint32_t width, height;
    uint32_t strips_x, strips_y; /* per row, per column */
    /* cand, ref: a slot each per parity; the other slot is the previous frame */
    scorer_buffer cand[2], ref[2], flip, tmp, partials, kernels, upload, map;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipelines[STAGES];
    VkDescriptorPool pool;
    VkDescriptorSet set; /* the kernels; the rest by address (push constants) */
    VkCommandPool cmd_pool;
    VkCommandBuffer cmd;
    VkFence fence;
    uint32_t parity;
    int have_prev, in_flight, want_map;
};

static int memory_type(const vrg_device *dev, uint32_t bits, VkMemoryPropertyFlags want, VkMemoryPropertyFlags need)
{
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(dev->physical_device, &mp);
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t i = 0; i < mp.memoryTypeCount; i++) {
            VkMemoryPropertyFlags f = mp.memoryTypes[i].propertyFlags, req = pass ? need : want | need;
            if ((bits & (1u << i)) && (f & req) == req)
                return (int)i;
        }
    return -1;
}

/* host: mapped (coherent, cached where there is such memory); else device-local where there is */
static int make_buffer(vrg_device_scorer *s, scorer_buffer *b, VkDeviceSize size, VkBufferUsageFlags usage, int host)
{
    VkDevice dev = s->dev->device;
    b->size = size;
    int address = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage, .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    if (vkCreateBuffer(dev, &bi, NULL, &b->buffer) != VK_SUCCESS)
        return -1;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, b->buffer, &req);
    const VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    int type = host ? memory_type(s->dev, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_CACHED_BIT, coherent)
                    : memory_type(s->dev, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO, .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .pNext = address ? &flags : NULL, .allocationSize = req.size,
                               .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(dev, &ai, NULL, &b->memory) != VK_SUCCESS || vkBindBufferMemory(dev, b->buffer, b->memory, 0) != VK_SUCCESS)
        return -1;
    if (address) {
        VkBufferDeviceAddressInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = b->buffer};
        b->address = vkGetBufferDeviceAddress(dev, &info);
    }
    return host ? (vkMapMemory(dev, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped) == VK_SUCCESS ? 0 : -1) : 0;
}

static void free_buffer(VkDevice dev, scorer_buffer *b)
{
    vkDestroyBuffer(dev, b->buffer, NULL);
    vkFreeMemory(dev, b->memory, NULL); /* unmaps */
}

/* two words per strip: the rows' strips, then the columns' */
static VkDeviceSize partial_words(const vrg_device_scorer *s)
{
    return 2 * ((VkDeviceSize)s->strips_x * s->height + (VkDeviceSize)s->strips_y * s->width);
}

static int make_buffers(vrg_device_scorer *s, uint32_t csf_r, uint32_t feat_r)
{
    /* per-pixel buffers by address: on lavapipe the stages' reads and
     * writes through an address are vector gathers and scatters, through
     * a storage buffer binding a bounds-checked access per lane */
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, addressed = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    const VkBufferUsageFlags copied = addressed | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    VkDeviceSize n = (VkDeviceSize)s->width * s->height;
    uint32_t kernel_floats = 4 * (2 * csf_r + 1) + 4 + 3 * (2 * feat_r + 1) + VRG_SSIM_WINDOW;
    int rc = 0;
    for (int p = 0; p < 2; p++) {
        rc |= make_buffer(s, &s->cand[p], n * 4, copied, 0);
        rc |= make_buffer(s, &s->ref[p], n * 4, copied, 0);
    }
    rc |= make_buffer(s, &s->flip, n * 4, copied, 0);
    rc |= make_buffer(s, &s->tmp, n * 4 * TMP_PLANES, addressed, 0);
    rc |= make_buffer(s, &s->partials, partial_words(s) * 4, addressed, 1);
    rc |= make_buffer(s, &s->kernels, (VkDeviceSize)kernel_floats * 4, storage, 1);
    rc |= make_buffer(s, &s->upload, n * 4 * 2, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, 1);
    rc |= make_buffer(s, &s->map, n * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, 1);
    if (rc != 0)
        fprintf(stderr, "error: device scorer: out of device memory for %ux%u frames\n", s->width, s->height);
    return rc;
}

/* k[r - i] == sign · k[r + i]: the filter stages add the two pixels at ±i
 * (or subtract them) before weighting them once. */
static int mirrored(const float *k, int r, float sign)
{
    for (int i = 1; i <= r; i++)
        if (k[r - i] != sign * k[r + i])
            return 0;
    return 1;
}

/* The kernels as shaders/score/score.glsl reads them (K_*), rounded to
 * float. Returns -1 after saying which is not (anti)symmetric. */
static int write_kernels(vrg_device_scorer *s, int csf_r, int feat_r)
{
    double ppd = vrg_flip_pixels_per_degree(), k[MAX_TAPS];
    float *out = s->kernels.mapped, share[4];
    static const int channel[4] = {0, 1, 2, 2}, term[4] = {0, 0, 0, 1};
    int symmetric = 1;
    for (int t = 0; t < 4; t++) {
        share[t] = (float)_vrg_flip_csf_kernel(channel[t], term[t], ppd, csf_r, k);
        for (int i = 0; i <= 2 * csf_r; i++)
            out[i] = (float)k[i];
        symmetric &= mirrored(out, csf_r, 1);
        out += 2 * csf_r + 1;
    }
    for (int t = 0; t < 4; t++)
        *out++ = share[t];
    double d[MAX_TAPS], d2[MAX_TAPS], g[MAX_TAPS];
    _vrg_flip_feature_kernels(ppd, 0, feat_r, d, g);
    _vrg_flip_feature_kernels(ppd, 1, feat_r, d2, g);
    const double *feat[3] = {d, d2, g};
    for (int f = 0; f < 3; f++) {
        for (int i = 0; i <= 2 * feat_r; i++)
            out[i] = (float)feat[f][i];
        symmetric &= mirrored(out, feat_r, f == 0 ? -1 : 1); /* d is antisymmetric */
        out += 2 * feat_r + 1;
    }
    _vrg_ssim_kernel(k);
    for (int i = 0; i < VRG_SSIM_WINDOW; i++)
        *out++ = (float)k[i];
    if (!symmetric) {
        fprintf(stderr, "error: device scorer: FLIP's filter kernels are not symmetric (d antisymmetric), as the filter stages take them\n");
        return -1;
    }
    return 0;
}

/* as shaders/score/score.glsl's push constants: the frame's size and the
 * addresses of the buffers the stages read and write per pixel */
typedef struct scorer_push {
    uint32_t width, height;
    VkDeviceAddress cand, ref, cand_prev, ref_prev, tmp, flip, partials;
    uint32_t want_map; /* FLIP's map written (else only summed) */
} scorer_push;

static int make_pipelines(vrg_device_scorer *s, int csf_r, int feat_r)
{
    VkDevice dev = s->dev->device;
    VkDescriptorSetLayoutBinding b = {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1,
                                      .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 1, .pBindings = &b};
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(scorer_push)};
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1, .pSetLayouts = &s->set_layout,
                                      .pushConstantRangeCount = 1, .pPushConstantRanges = &range};
    if (vkCreateDescriptorSetLayout(dev, &sli, NULL, &s->set_layout) != VK_SUCCESS || vkCreatePipelineLayout(dev, &pli, NULL, &s->layout) != VK_SUCCESS)
        return -1;
    char defines[64], path[1200];
    snprintf(defines, sizeof defines, "CSF_R=%d FEAT_R=%d STRIP=%d", csf_r, feat_r, STRIP);
    for (int i = 0; i < STAGES; i++) {
        snprintf(path, sizeof path, "%s/shaders/score/%s", vrg_data_dir(), stage_files[i]);
        VkShaderModule sm = vrg_compile_compute_shader(s->ctx, path, defines); /* says why it failed */
        if (!sm)
            return -1;
        VkComputePipelineCreateInfo ci = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = sm, .pName = "main"},
            .layout = s->layout,
        };
        VkResult res = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, NULL, &s->pipelines[i]);
        vkDestroyShaderModule(dev, sm, NULL);
        if (res != VK_SUCCESS) {
            fprintf(stderr, "%s: error: the device scorer's pipeline was not created (VkResult %d)\n", path, (int)res);
            return -1;
        }
    }
    return 0;
}

/* The kernels are the one buffer bound: they are read at uniform
 * offsets. */
static int make_set(vrg_device_scorer *s)
{
    VkDevice dev = s->dev->device;
    VkDescriptorPoolSize size = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1, .poolSizeCount = 1, .pPoolSizes = &size};
    VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorSetCount = 1, .pSetLayouts = &s->set_layout};
    if (vkCreateDescriptorPool(dev, &dpi, NULL, &s->pool) != VK_SUCCESS)
        return -1;
    dai.descriptorPool = s->pool;
    if (vkAllocateDescriptorSets(dev, &dai, &s->set) != VK_SUCCESS)
        return -1;
    VkDescriptorBufferInfo info = {s->kernels.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet wr = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = s->set, .dstBinding = 0, .descriptorCount = 1,
                               .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &info};
    vkUpdateDescriptorSets(dev, 1, &wr, 0, NULL);
    return 0;
}

static int make_commands(vrg_device_scorer *s)
{
    VkDevice dev = s->dev->device;
    VkCommandPoolCreateInfo cpi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                   .queueFamilyIndex = s->dev->queue_family};
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (vkCreateCommandPool(dev, &cpi, NULL, &s->cmd_pool) != VK_SUCCESS || vkCreateFence(dev, &fi, NULL, &s->fence) != VK_SUCCESS)
        return -1;
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = s->cmd_pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    return vkAllocateCommandBuffers(dev, &ai, &s->cmd) == VK_SUCCESS ? 0 : -1;
}

int vrg_device_scorer_create(vrg_context *ctx, uint32_t width, uint32_t height, vrg_device_scorer **out)
{
    *out = NULL;
    if (!width || !height) {
        fprintf(stderr, "error: device scorer: empty frame size %ux%u\n", width, height);
        return -1;
    }
    vrg_device_scorer *s = calloc(1, sizeof *s);
    if (!s)
        return -1;
    s->ctx = ctx;
    s->dev = vrg_context_device(ctx);
    /* the context enables it wherever the device has it */
    VkPhysicalDeviceVulkan12Features v12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &v12};
    vkGetPhysicalDeviceFeatures2(s->dev->physical_device, &f2);
    if (!v12.bufferDeviceAddress) {
        fprintf(stderr, "error: device scorer: %s lacks bufferDeviceAddress, through which the scoring stages reach their buffers\n", s->dev->name);
        free(s);
        return -1;
    }
    s->width = width, s->height = height;
    s->strips_x = (width + STRIP - 1) / STRIP, s->strips_y = (height + STRIP - 1) / STRIP;
    double ppd = vrg_flip_pixels_per_degree();
    int csf_r = _vrg_flip_csf_radius(ppd), feat_r = _vrg_flip_feature_radius(ppd);
    if (2 * csf_r + 1 > MAX_TAPS || 2 * feat_r + 1 > MAX_TAPS) { /* write_kernels' arrays */
        fprintf(stderr, "error: device scorer: FLIP's kernels (radius %d, %d) are wider than %d taps\n", csf_r, feat_r, MAX_TAPS);
        free(s);
        return -1;
    }
    if (make_buffers(s, (uint32_t)csf_r, (uint32_t)feat_r) != 0 || make_pipelines(s, csf_r, feat_r) != 0 || make_set(s) != 0 ||
        make_commands(s) != 0) {
        fprintf(stderr, "error: the device scorer could not be set up on %s\n", s->dev->name);
        vrg_device_scorer_destroy(s);
        return -1;
    }
    if (write_kernels(s, csf_r, feat_r) != 0) {
        vrg_device_scorer_destroy(s);
        return -1;
    }
    *out = s;
    return 0;
}

void vrg_device_scorer_destroy(vrg_device_scorer *s)
{
    if (!s)
        return;
    VkDevice dev = s->dev->device;
    if (s->in_flight)
        vkWaitForFences(dev, 1, &s->fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(dev, s->fence, NULL);
    vkDestroyCommandPool(dev, s->cmd_pool, NULL);
    vkDestroyDescriptorPool(dev, s->pool, NULL);
    for (int i = 0; i < STAGES; i++)
        vkDestroyPipeline(dev, s->pipelines[i], NULL);
    vkDestroyPipelineLayout(dev, s->layout, NULL);
    vkDestroyDescriptorSetLayout(dev, s->set_layout, NULL);
    scorer_buffer *bufs[] = {&s->cand[0], &s->cand[1], &s->ref[0], &s->ref[1], &s->flip, &s->tmp, &s->partials, &s->kernels, &s->upload, &s->map};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        free_buffer(dev, bufs[i]);
    free(s);
}

void vrg_device_scorer_restart(vrg_device_scorer *s) { s->have_prev = 0; }

static void pack_rgba(const uint8_t *rgb, size_t n, uint8_t *rgba)
{
    for (size_t i = 0; i < n; i++) {
        memcpy(rgba + 4 * i, rgb + 3 * i, 3);
        rgba[4 * i + 3] = 255;
    }
}

static void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = src_access, .dstAccessMask = dst_access};
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &mb, 0, NULL, 0, NULL);
}

/* The candidate into slot p: the graph's output image, or the uploaded bytes. */
static int copy_candidate(vrg_device_scorer *s, vrg_graph *g, VkCommandBuffer cmd)
{
    VkDeviceSize bytes = (VkDeviceSize)s->width * s->height * 4;
    if (!g) {
        VkBufferCopy c = {0, 0, bytes};
        vkCmdCopyBuffer(cmd, s->upload.buffer, s->cand[s->parity].buffer, 1, &c);
        return 0;
    }
    VkImage image;
    VkExtent2D ext;
    VkFormat format;
    const char *output = vrg_graph_output(g);
    if (vrg_graph_image(g, output, &image, &ext, &format) != 0)
        return -1;
    if (format != VK_FORMAT_R8G8B8A8_UNORM || ext.width != s->width || ext.height != s->height) {
        fprintf(stderr, "error: the device scorer takes an R8G8B8A8_UNORM output of %ux%u; the graph's output '%s' is %s, %ux%u\n", s->width, s->height,
                output, vrg_format_label(format), ext.width, ext.height);
        return -1;
    }
    VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {s->width, s->height, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s->cand[s->parity].buffer, 1, &c);
    return 0;
}

static void dispatch(vrg_device_scorer *s, VkCommandBuffer cmd, int stage, uint32_t x, uint32_t y)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->pipelines[stage]);
    vkCmdDispatch(cmd, x, y, 1);
}

static void record(vrg_device_scorer *s, VkCommandBuffer cmd)
{
    const VkPipelineStageFlags both = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    const VkAccessFlags shader = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    const VkAccessFlags transfer = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    VkDeviceSize bytes = (VkDeviceSize)s->width * s->height * 4;
    VkBufferCopy ref = {bytes, 0, bytes};
    vkCmdCopyBuffer(cmd, s->upload.buffer, s->ref[s->parity].buffer, 1, &ref);
    barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, shader);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->layout, 0, 1, &s->set, 0, NULL);
    /* slot parity is this frame; the other slot the previous one */
    uint32_t p = s->parity;
    scorer_push push = {s->width,           s->height,     s->cand[p].address, s->ref[p].address,     s->cand[1 - p].address,
                        s->ref[1 - p].address, s->tmp.address, s->flip.address,    s->partials.address, (uint32_t)s->want_map};
    vkCmdPushConstants(cmd, s->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    /* 8 rows (columns) per group, a strip of each per invocation */
    dispatch(s, cmd, STAGE_FILTER_X, (s->height + 7) / 8, s->strips_x);
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, shader);
    dispatch(s, cmd, STAGE_FILTER_Y, (s->width + 7) / 8, s->strips_y);
    if (s->want_map) {
        barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy map = {0, 0, bytes};
        vkCmdCopyBuffer(cmd, s->flip.buffer, s->map.buffer, 1, &map);
    }
    /* what the host reads, and what the next frame's work (also another
     * submission on this queue) overwrites, ordered after all of this */
    barrier(cmd, both, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    barrier(cmd, both, shader | transfer, both, shader | transfer);
}

int vrg_device_score_submit(vrg_device_scorer *s, vrg_graph *g, const uint8_t *test, const uint8_t *ref, int want_map)
{
    if (s->in_flight) {
        fprintf(stderr, "error: device scorer: a frame was submitted before the last one was collected\n");
        return -1;
    }
    if ((!g && !test) || !ref) {
        fprintf(stderr, "error: device scorer: no %s to score\n", ref ? "candidate" : "reference");
        return -1;
    }
    size_t n = (size_t)s->width * s->height;
    if (!g)
        pack_rgba(test, n, s->upload.mapped);
    pack_rgba(ref, n, (uint8_t *)s->upload.mapped + 4 * n);
    s->want_map = want_map;
    VkCommandBuffer cmd = s->cmd;
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkResetCommandBuffer(cmd, 0);
    vkBeginCommandBuffer(cmd, &bi);
    int rc = copy_candidate(s, g, cmd);
    if (rc == 0)
        record(s, cmd);
    vkEndCommandBuffer(cmd);
    if (rc != 0)
        return -1;
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    vkResetFences(s->dev->device, 1, &s->fence);
    if (vkQueueSubmit(s->dev->queue, 1, &si, s->fence) != VK_SUCCESS) {
        fprintf(stderr, "error: device scorer: the frame's scoring could not be submitted\n");
        return -1;
    }
    s->in_flight = 1;
    return 0;
}

int vrg_device_score_collect(vrg_device_scorer *s, float *map, vrg_device_scores *out)
{
    if (!s->in_flight) {
        fprintf(stderr, "error: device scorer: no frame submitted to collect\n");
        return -1;
    }
    s->in_flight = 0;
    if (vkWaitForFences(s->dev->device, 1, &s->fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS) {
        fprintf(stderr, "error: device scorer: the device failed while scoring a frame\n");
        return -1;
    }
    /* the strips' sums, added in order */
    double flip = 0, ssim = 0, sq = 0, temporal = 0;
    const uint32_t *part = s->partials.mapped;
    size_t rows = (size_t)s->strips_x * s->height, columns = (size_t)s->strips_y * s->width;
    for (size_t i = 0; i < rows; i++) {
        sq += part[2 * i];
        temporal += part[2 * i + 1];
    }
    for (size_t i = 0; i < columns; i++) {
        float f[2];
        memcpy(f, part + 2 * rows + 2 * i, sizeof f);
        flip += f[0];
        ssim += f[1];
    }
    double n = (double)s->width * s->height, channels = 3 * n;
    double mse = sq / (255.0 * 255.0 * channels);
    double db = mse > 0 ? 10.0 * log10(1.0 / mse) : VRG_PSNR_MAX_DB;
    out->psnr = db < VRG_PSNR_MAX_DB ? db : VRG_PSNR_MAX_DB;
    uint32_t sw = s->width >= VRG_SSIM_WINDOW ? s->width - VRG_SSIM_WINDOW + 1 : 0, sh = s->height >= VRG_SSIM_WINDOW ? s->height - VRG_SSIM_WINDOW + 1 : 0;
    out->ssim = sw && sh ? ssim / ((double)sw * sh) : -1;
    out->flip = flip / n;
    out->temporal = s->have_prev ? temporal / (255.0 * channels) : NAN;
    if (map && s->want_map)
        memcpy(map, s->map.mapped, sizeof(float) * (size_t)n);
    s->have_prev = 1;
    s->parity ^= 1;
    return 0;
}
