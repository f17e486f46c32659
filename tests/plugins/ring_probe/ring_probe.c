/* Test plugin: what a pass uploads every frame through its host ring.
 * execute() writes the frame index into this frame's ring slice, keeps the
 * GPU busy (`spin` iterations), then copies the slice into word
 * frame_index % 64 of `log`. If the host wrote a slice the GPU still reads
 * (one slice for all frames in flight), a frame's word holds a later
 * frame's index. It also records the frame index as the stat "frame", and
 * frees a buffer of its own in destroy() (freed after the frames in flight
 * end: a leak under LSan if the runtime forgot it). */
#include <stdlib.h>
#include "voxrg/plugin.h"

typedef struct probe {
    vrg_ring *ring;
    VkBuffer own;
} probe;

#define LOG_WORDS 64

static const vrg_param_desc params[] = {
    {"spin", VRG_PARAM_FLOAT, 200000.0, 0.0, 1e9, "iterations the GPU spends before the copy"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32_SFLOAT, .scale = 1.0f,
     .help = "the spin counter (texel 0, 0)"},
    {.name = "log", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 4 * LOG_WORDS, .flags = VRG_SLOT_PERSISTENT,
     .help = "word k % 64: the value frame k's ring slice held when its copy ran"},
};

static int create(vrg_pass *pass)
{
    probe *p = calloc(1, sizeof *p);
    if (!p)
        return vrg_pass_error(pass, "out of memory");
    vrg_pass_set_user(pass, p);
    p->ring = vrg_pass_host_ring(pass, "frame index", sizeof(uint32_t), 0);
    vrg_buffer_desc own = {.name = "own", .size = 64, .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT, .host_visible = 1};
    return p->ring && vrg_pass_buffer(pass, &own, &p->own, NULL) ? 0 : -1;
}

static void destroy(vrg_pass *pass)
{
    probe *p = vrg_pass_user(pass);
    vrg_pass_free_buffer(pass, p->own);
    free(p);
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    const vrg_frame_info *f = vrg_pass_frame(pass);
    probe *p = vrg_pass_user(pass);
    vrg_ring_slice slice = vrg_pass_ring_slice(pass, p->ring, sizeof(uint32_t));
    if (!slice.map)
        return;
    *(uint32_t *)slice.map = (uint32_t)f->frame_index;
    vrg_pass_stat(pass, "frame", (double)f->frame_index);
    float stop = (float)vrg_param(pass, "spin");
    vrg_dispatch_desc d = {.shader = "ring_probe.comp", .bindings = {{"color"}}, .push = &stop, .push_size = sizeof stop};
    if (vrg_dispatch(pass, cmd, &d) != 0)
        return;
    /* the copy starts after the spin has ended */
    VkMemoryBarrier2 after = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                              .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT};
    vkCmdPipelineBarrier2(cmd, &(VkDependencyInfo){.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &after});
    VkBufferCopy region = {.dstOffset = 4 * (f->frame_index % LOG_WORDS), .size = sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, slice.buffer, vrg_res_buffer(pass, vrg_pass_res(pass, "log")), 1, &region);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "ring_probe",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: copies the frame index from its host ring after a slow dispatch",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .execute = execute,
    .destroy = destroy,
};

VRG_PLUGIN(desc)
