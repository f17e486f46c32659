/* What each access a slot declares means: to Vulkan (the pipeline stage,
 * access and image layout a use needs, which the barrier tracker, the
 * validator and the dispatch helper all read) and to a reader (its name
 * in messages and `check`). */
#include "internal.h"

_vrg_access_info _vrg_access_info_of(vrg_access a, vrg_resource_kind kind)
{
    const VkPipelineStageFlags2 cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    int img = kind == VRG_IMAGE;
    switch (a) {
    case VRG_ACCESS_SAMPLED:
        return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0};
    case VRG_ACCESS_STORAGE_READ:
        return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, img ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED, 0};
    case VRG_ACCESS_STORAGE_WRITE:
        return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, img ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED, 1};
    case VRG_ACCESS_STORAGE_READ_WRITE:
        return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                 img ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED, 1};
    case VRG_ACCESS_UNIFORM:
        return (_vrg_access_info){cs, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, 0};
    case VRG_ACCESS_TRANSFER_SRC:
        return (_vrg_access_info){xfer, VK_ACCESS_2_TRANSFER_READ_BIT, img ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED, 0};
    case VRG_ACCESS_TRANSFER_DST:
        return (_vrg_access_info){xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, img ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED, 1};
    case VRG_ACCESS_AS_BUILD:
        return (_vrg_access_info){VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                 VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                                 VK_IMAGE_LAYOUT_UNDEFINED, 1};
    case VRG_ACCESS_RAY_QUERY:
        return (_vrg_access_info){cs, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED, 0};
    case VRG_ACCESS_TEXEL_READ:
        return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, 0};
    }
    return (_vrg_access_info){cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, 0};
}

const char *_vrg_access_name(vrg_access a)
{
    static const char *names[] = {"?",           "sampled",      "storage-read", "storage-write", "storage-read-write",
                                  "uniform",     "transfer-src", "transfer-dst", "as-build",      "ray-query",
                                  "texel-read"};
    return a >= 1 && a <= VRG_ACCESS_TEXEL_READ ? names[a] : "?";
}

const char *vrg_access_label(vrg_access a) { return _vrg_access_name(a); }
