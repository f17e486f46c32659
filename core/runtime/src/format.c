/* The image formats a graph may name: their names in graph files, sizes
 * and channel counts. */
#include <string.h>
#include "internal.h"

static const struct {
    const char *name;
    VkFormat format;
    uint32_t bytes, channels;
} formats[] = {
    {"r8", VK_FORMAT_R8_UNORM, 1, 1},
    {"rg8", VK_FORMAT_R8G8_UNORM, 2, 2},
    {"rgba8", VK_FORMAT_R8G8B8A8_UNORM, 4, 4},
    {"rgba8_srgb", VK_FORMAT_R8G8B8A8_SRGB, 4, 4},
    {"r16f", VK_FORMAT_R16_SFLOAT, 2, 1},
    {"rg16f", VK_FORMAT_R16G16_SFLOAT, 4, 2},
    {"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT, 8, 4},
    {"r32f", VK_FORMAT_R32_SFLOAT, 4, 1},
    {"rg32f", VK_FORMAT_R32G32_SFLOAT, 8, 2},
    {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT, 16, 4},
    {"r32ui", VK_FORMAT_R32_UINT, 4, 1},
    {"rg32ui", VK_FORMAT_R32G32_UINT, 8, 2},
    {"rgba32ui", VK_FORMAT_R32G32B32A32_UINT, 16, 4},
    {"r11g11b10f", VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4, 3},
};

VkFormat _vrg_format_parse(const char *s)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (strcmp(formats[i].name, s) == 0)
            return formats[i].format;
    return VK_FORMAT_UNDEFINED;
}

const char *_vrg_format_list(void)
{
    static char list[512];
    if (!list[0]) {
        strcat(list, "one of");
        for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++) {
            strcat(list, i ? ", " : " ");
            strcat(list, formats[i].name);
        }
    }
    return list;
}

const char *_vrg_format_name(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].name;
    return "unknown-format";
}

uint64_t _vrg_format_bytes(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].bytes;
    return 16;
}

uint32_t _vrg_format_channels(VkFormat f)
{
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (formats[i].format == f)
            return formats[i].channels;
    return 4;
}

const char *vrg_format_label(VkFormat f) { return _vrg_format_name(f); }
