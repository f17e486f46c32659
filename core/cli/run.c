/* voxrg run: a GLFW window presenting a graph's output, with a fly camera
 * and hot reload. The graph renders as under `voxrg render`; each frame its
 * output (idle in TRANSFER_SRC after the frame's readback) is blitted to a
 * swapchain image and presented. */
#define _POSIX_C_SOURCE 200809L
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bench.h"
#include "overlay.h"
#include "run.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/world.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "voxrg/camera_path.h"
#include "voxrg/voxrg.h"

typedef struct swapchain {
    VkSwapchainKHR handle;
    VkFormat format;
    VkExtent2D extent;
    uint32_t count;
    VkImage images[8];
} swapchain;

typedef struct window_state {
    vrg_context *ctx;
    const vrg_device *dev;
    GLFWwindow *window;
    VkSurfaceKHR surface;
    swapchain sc;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkSemaphore acquired, rendered;
    VkFence done;
    float speed;
    int looking;
    double mouse_x, mouse_y;
    int screenshot_requested;
    int screenshot_failed;
    int day_toggle;      /* T: start or stop the day cycle */
    float time_step;     /* [ and ]: hours to step the time of day */
    float divider;       /* --ab: where A ends, 0..1 of the width */
    int hide_overlay;    /* H */
    int paused;          /* Pause or F: no new frames, the last one stays shown */
    int srgb;            /* the output holds linear values: let the swapchain encode them */
    /* host-visible staging: the overlay panel, and screenshots of what is shown */
    VkBuffer staging;
    VkDeviceMemory staging_memory;
    uint8_t *staging_map;
    VkDeviceSize staging_size;
    vrg_overlay overlay;
    /* showing a resource other than the output: Tab / Shift+Tab / 0-9 */
    int shown;                /* index into vrg_graph_image_name, -1: the output */
    int shown_step;           /* pending key */
    char shown_name[160];
    struct {
        VkExtent2D extent;
        VkImage tmp, out;     /* the resource as rgba32f (blit), the visualisation */
        VkDeviceMemory tmp_mem, out_mem;
        VkImageView tmp_view, out_view;
        VkSampler sampler;
        VkDescriptorSetLayout set_layout;
        VkPipelineLayout layout;
        VkPipeline pipeline;
        VkDescriptorPool pool;
        VkDescriptorSet set;
        int mode, channel;
        float scale;
    } disp;
} window_state;

#define OVERLAY_MAX_W 1024u
#define OVERLAY_MAX_H 512u

/* The staging buffer holds the overlay panel first, then a screenshot. */
static int ensure_staging(window_state *w, VkDeviceSize size)
{
    if (w->staging_size >= size)
        return 0;
    VkDevice dev = w->dev->device;
    if (w->staging) {
        vkUnmapMemory(dev, w->staging_memory);
        vkDestroyBuffer(dev, w->staging, NULL);
        vkFreeMemory(dev, w->staging_memory, NULL);
    }
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size,
                             .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    vkCreateBuffer(dev, &bi, NULL, &w->staging);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, w->staging, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(w->dev->physical_device, &mp);
    uint32_t type = UINT32_MAX;
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t i = 0; i < mp.memoryTypeCount && type == UINT32_MAX; i++)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want)
            type = i;
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = type};
    if (type == UINT32_MAX || vkAllocateMemory(dev, &ai, NULL, &w->staging_memory) != VK_SUCCESS) {
        fprintf(stderr, "error: no host-visible memory for the window's staging buffer\n");
        return -1;
    }
    vkBindBufferMemory(dev, w->staging, w->staging_memory, 0);
    vkMapMemory(dev, w->staging_memory, 0, VK_WHOLE_SIZE, 0, (void **)&w->staging_map);
    w->staging_size = size;
    return 0;
}

static double now_s(void) { return vrg_cli_now_ms() * 1e-3; }

static int create_swapchain(window_state *w, VkSwapchainKHR old)
{
    VkPhysicalDevice pd = w->dev->physical_device;
    VkSurfaceCapabilitiesKHR caps;
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, w->surface, &caps);
    uint32_t nf = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(pd, w->surface, &nf, NULL);
    VkSurfaceFormatKHR formats[64];
    nf = nf > 64 ? 64 : nf;
    vkGetPhysicalDeviceSurfaceFormatsKHR(pd, w->surface, &nf, formats);
    /* 8-bit UNORM outputs are display-encoded already (tonemap writes sRGB
     * values): a UNORM swapchain. Float outputs hold linear values: an SRGB
     * swapchain encodes them in the blit, as the PNG writer does. */
    VkSurfaceFormatKHR fmt = formats[0];
    for (uint32_t i = 0; i < nf; i++)
        if (w->srgb ? formats[i].format == VK_FORMAT_B8G8R8A8_SRGB || formats[i].format == VK_FORMAT_R8G8B8A8_SRGB
                    : formats[i].format == VK_FORMAT_B8G8R8A8_UNORM || formats[i].format == VK_FORMAT_R8G8B8A8_UNORM) {
            fmt = formats[i];
            break;
        }
    int fw, fh;
    glfwGetFramebufferSize(w->window, &fw, &fh);
    VkExtent2D ext = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : (VkExtent2D){(uint32_t)fw, (uint32_t)fh};
    if (!ext.width || !ext.height)
        return 1; /* minimised: try again later */
    uint32_t count = caps.minImageCount + 1;
    if (caps.maxImageCount && count > caps.maxImageCount)
        count = caps.maxImageCount;
    VkSwapchainCreateInfoKHR ci = {
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
        .surface = w->surface,
        .minImageCount = count,
        .imageFormat = fmt.format,
        .imageColorSpace = fmt.colorSpace,
        .imageExtent = ext,
        .imageArrayLayers = 1,
        .imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, /* blits in, screenshots out */
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
        .presentMode = VK_PRESENT_MODE_FIFO_KHR,
        .clipped = VK_TRUE,
        .oldSwapchain = old,
    };
    VkSwapchainKHR sc;
    if (vkCreateSwapchainKHR(w->dev->device, &ci, NULL, &sc) != VK_SUCCESS) {
        fprintf(stderr, "error: cannot create the window's swapchain\n");
        return -1;
    }
    if (old)
        vkDestroySwapchainKHR(w->dev->device, old, NULL);
    w->sc.handle = sc;
    w->sc.format = fmt.format;
    w->sc.extent = ext;
    w->sc.count = 8;
    vkGetSwapchainImagesKHR(w->dev->device, sc, &w->sc.count, w->sc.images);
    return 0;
}

/* Blocks per second: a speed that grew to infinity would make 0 * inf = NaN
 * of a still axis; at the top the world is crossed in a second. */
static float capped_speed(float speed) { return speed > VRG_WORLD_LIMIT ? VRG_WORLD_LIMIT : speed; }

/* W/A/S/D move, Space up, Shift down, right mouse button held: look,
 * scroll or +/-: speed. */
static void fly(window_state *w, vrg_camera *cam, float dt)
{
    GLFWwindow *win = w->window;
    float fwd[3], right[3];
    vrg_camera_forward(cam, fwd);
    float yaw = cam->yaw * 3.14159265f / 180.0f;
    right[0] = cosf(yaw), right[1] = 0, right[2] = -sinf(yaw);
    /* yaw 0 looks down -z and + turns left: right is +x at yaw 0 */
    float move[3] = {0, 0, 0};
    float f = (float)(glfwGetKey(win, GLFW_KEY_W) == GLFW_PRESS) - (float)(glfwGetKey(win, GLFW_KEY_S) == GLFW_PRESS);
    float r = (float)(glfwGetKey(win, GLFW_KEY_D) == GLFW_PRESS) - (float)(glfwGetKey(win, GLFW_KEY_A) == GLFW_PRESS);
    float u = (float)(glfwGetKey(win, GLFW_KEY_SPACE) == GLFW_PRESS) - (float)(glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS);
    for (int i = 0; i < 3; i++)
        move[i] = f * fwd[i] + r * right[i];
    move[1] += u;
    /* the camera stops at the world's edge (vrg_graph_set_camera refuses beyond) */
    for (int i = 0; i < 3; i++)
        cam->position[i] = vrg_world_clamp(cam->position[i] + move[i] * w->speed * dt);
    int look = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    double mx, my;
    glfwGetCursorPos(win, &mx, &my);
    if (look && w->looking) {
        cam->yaw -= (float)(mx - w->mouse_x) * 0.15f;
        cam->pitch -= (float)(my - w->mouse_y) * 0.15f;
        cam->pitch = cam->pitch > 89 ? 89 : cam->pitch < -89 ? -89 : cam->pitch;
    }
    if (look != w->looking)
        glfwSetInputMode(win, GLFW_CURSOR, look ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    w->looking = look;
    w->mouse_x = mx, w->mouse_y = my;
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    (void)scancode;
    window_state *w = glfwGetWindowUserPointer(win);
    if (action != GLFW_PRESS)
        return;
    if (key == GLFW_KEY_ESCAPE)
        glfwSetWindowShouldClose(win, 1);
    else if (key == GLFW_KEY_F12 || key == GLFW_KEY_P)
        w->screenshot_requested = 1;
    else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD)
        w->speed = capped_speed(w->speed * 1.5f);
    else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT)
        w->speed /= 1.5f;
    else if (key == GLFW_KEY_T)
        w->day_toggle = 1;
    else if (key == GLFW_KEY_H)
        w->hide_overlay = !w->hide_overlay;
    else if (key == GLFW_KEY_PAUSE || key == GLFW_KEY_F)
        w->paused = !w->paused;
    else if (key == GLFW_KEY_TAB)
        w->shown_step = mods & GLFW_MOD_SHIFT ? -1 : 1;
    else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9)
        w->shown = key - GLFW_KEY_0 - 1, w->shown_step = 0; /* 0: the output, 1..9: the list */
    else if (key == GLFW_KEY_LEFT_BRACKET)
        w->time_step -= 0.5f;
    else if (key == GLFW_KEY_RIGHT_BRACKET)
        w->time_step += 0.5f;
}

static void on_scroll(GLFWwindow *win, double dx, double dy)
{
    (void)dx;
    window_state *w = glfwGetWindowUserPointer(win);
    w->speed = capped_speed(w->speed * (dy > 0 ? 1.25f : 0.8f));
}

static vrg_graph *both_graphs(vrg_graph *a, vrg_graph *b, int k) { return k ? b : a; }

static int image_memory(window_state *w, VkImage image, VkDeviceMemory *mem)
{
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(w->dev->device, image, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(w->dev->physical_device, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; i++)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) {
            VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = i};
            if (vkAllocateMemory(w->dev->device, &ai, NULL, mem) != VK_SUCCESS)
                return -1;
            return vkBindImageMemory(w->dev->device, image, *mem, 0) == VK_SUCCESS ? 0 : -1;
        }
    return -1;
}

static void display_free_images(window_state *w)
{
    VkDevice dev = w->dev->device;
    vkDestroyImageView(dev, w->disp.tmp_view, NULL);
    vkDestroyImageView(dev, w->disp.out_view, NULL);
    vkDestroyImage(dev, w->disp.tmp, NULL);
    vkDestroyImage(dev, w->disp.out, NULL);
    vkFreeMemory(dev, w->disp.tmp_mem, NULL);
    vkFreeMemory(dev, w->disp.out_mem, NULL);
    w->disp.tmp = w->disp.out = VK_NULL_HANDLE;
    w->disp.tmp_view = w->disp.out_view = VK_NULL_HANDLE;
    w->disp.tmp_mem = w->disp.out_mem = VK_NULL_HANDLE;
    w->disp.extent = (VkExtent2D){0, 0};
}

/* The display stage's pipeline (shaders/display.comp) and, for this size,
 * its two images. */
static int display_prepare(window_state *w, VkExtent2D ext, const char *source_dir)
{
    VkDevice dev = w->dev->device;
    if (!w->disp.pipeline) {
        char path[1100];
        snprintf(path, sizeof path, "%s/shaders/display.comp", source_dir);
        VkShaderModule sm = vrg_compile_compute_shader(w->ctx, path, NULL);
        if (!sm)
            return -1;
        VkDescriptorSetLayoutBinding b[2] = {
            {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
            {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        };
        VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 2, .pBindings = b};
        vkCreateDescriptorSetLayout(dev, &sli, NULL, &w->disp.set_layout);
        VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, 16};
        VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                          .pSetLayouts = &w->disp.set_layout, .pushConstantRangeCount = 1, .pPushConstantRanges = &range};
        vkCreatePipelineLayout(dev, &pli, NULL, &w->disp.layout);
        VkComputePipelineCreateInfo ci = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = sm, .pName = "main"},
            .layout = w->disp.layout,
        };
        VkResult res = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, NULL, &w->disp.pipeline);
        vkDestroyShaderModule(dev, sm, NULL);
        if (res != VK_SUCCESS)
            return -1;
        VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
        VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1, .poolSizeCount = 2, .pPoolSizes = sizes};
        vkCreateDescriptorPool(dev, &dpi, NULL, &w->disp.pool);
        VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = w->disp.pool,
                                           .descriptorSetCount = 1, .pSetLayouts = &w->disp.set_layout};
        vkAllocateDescriptorSets(dev, &dai, &w->disp.set);
        VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST, .minFilter = VK_FILTER_NEAREST,
                                  .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                  .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
        vkCreateSampler(dev, &si, NULL, &w->disp.sampler);
    }
    if (w->disp.extent.width == ext.width && w->disp.extent.height == ext.height)
        return 0;
    display_free_images(w);
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                            .extent = {ext.width, ext.height, 1}, .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
                            .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
    if (vkCreateImage(dev, &ii, NULL, &w->disp.tmp) != VK_SUCCESS || image_memory(w, w->disp.tmp, &w->disp.tmp_mem) != 0)
        return -1;
    ii.format = VK_FORMAT_R8G8B8A8_UNORM;
    ii.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (vkCreateImage(dev, &ii, NULL, &w->disp.out) != VK_SUCCESS || image_memory(w, w->disp.out, &w->disp.out_mem) != 0)
        return -1;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = w->disp.tmp, .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                .format = VK_FORMAT_R32G32B32A32_SFLOAT, .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCreateImageView(dev, &vi, NULL, &w->disp.tmp_view);
    vi.image = w->disp.out;
    vi.format = VK_FORMAT_R8G8B8A8_UNORM;
    vkCreateImageView(dev, &vi, NULL, &w->disp.out_view);
    VkDescriptorImageInfo src = {.sampler = w->disp.sampler, .imageView = w->disp.tmp_view, .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo dst = {.imageView = w->disp.out_view, .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet wr[2] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 0, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = &src},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 1, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &dst},
    };
    vkUpdateDescriptorSets(dev, 2, wr, 0, NULL);
    w->disp.extent = ext;
    return 0;
}

static void image_barrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                          VkAccessFlags2 dst_access, VkImageLayout from, VkImageLayout to)
{
    VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = src_stage, .srcAccessMask = src_access,
                               .dstStageMask = dst_stage, .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to, .image = image,
                               .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1, .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

/* Records the display of src (in TRANSFER_SRC, left so): blit to rgba32f,
 * visualise into disp.out, which ends in TRANSFER_SRC for the swapchain blit. */
static void display_record(window_state *w, VkImage src, VkExtent2D ext)
{
    VkCommandBuffer cmd = w->cmd;
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT, cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    image_barrier(cmd, w->disp.tmp, cs, 0, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkImageBlit blit = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .srcOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .dstOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}}};
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->disp.tmp, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    image_barrier(cmd, w->disp.tmp, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    image_barrier(cmd, w->disp.out, xfer, 0, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.layout, 0, 1, &w->disp.set, 0, NULL);
    struct {
        int32_t mode, channel;
        float scale;
        int32_t linear_out;
    } pc = {w->disp.mode, w->disp.channel, w->disp.scale, w->srgb};
    vkCmdPushConstants(cmd, w->disp.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
    vkCmdDispatch(cmd, (ext.width + 7) / 8, (ext.height + 7) / 8, 1);
    image_barrier(cmd, w->disp.out, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, xfer, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

/* How a resource is best seen, from its name (docs: voxrg run --help). */
static void display_mode(window_state *w, const char *name)
{
    w->disp.mode = 0, w->disp.channel = 0, w->disp.scale = 1;
    if (strstr(name, "normal"))
        w->disp.mode = 1;
    else if (strstr(name, "depth"))
        w->disp.mode = 2, w->disp.scale = 300;
    else if (strstr(name, "motion"))
        w->disp.mode = 3, w->disp.scale = 0.1f;
    else if (strstr(name, "length"))
        w->disp.mode = 4, w->disp.scale = 1.0f / 32;
    else if (strstr(name, "variance"))
        w->disp.mode = 4, w->disp.channel = 3, w->disp.scale = 20;
    else if (strstr(name, "position"))
        w->disp.mode = 5;
}

/* One presentation: the graph's output blitted onto the next swapchain
 * image; with a second source (--ab), A left of the divider and B right. */
static int present(window_state *w, VkImage src, VkExtent2D src_ext, VkImage src_b, VkExtent2D ext_b, const char *screenshot, int via_display)
{
    VkDevice dev = w->dev->device;
    uint32_t index;
    VkResult res = vkAcquireNextImageKHR(dev, w->sc.handle, UINT64_MAX, w->acquired, VK_NULL_HANDLE, &index);
    if (res == VK_ERROR_OUT_OF_DATE_KHR)
        return 1;
    if (res != VK_SUCCESS && res != VK_SUBOPTIMAL_KHR)
        return -1;
    VkImage dst = w->sc.images[index];
    vkResetCommandBuffer(w->cmd, 0);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(w->cmd, &bi);
    if (via_display) { /* a resource other than the output: visualised first */
        display_record(w, src, src_ext);
        src = w->disp.out;
    }
    VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageMemoryBarrier2 to_dst = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT,
        .srcAccessMask = 0,
        .dstStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT,
        .dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
        .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
        .newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
        .image = dst,
        .subresourceRange = range,
    };
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1, .pImageMemoryBarriers = &to_dst};
    vkCmdPipelineBarrier2(w->cmd, &dep);
    float split = src_b ? w->divider : 1.0f;
    int32_t dw = (int32_t)w->sc.extent.width, dh = (int32_t)w->sc.extent.height, dsplit = (int32_t)(split * (float)dw);
    if (dsplit > 0) {
        VkImageBlit blit = {
            .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .srcOffsets = {{0, 0, 0}, {(int32_t)(split * (float)src_ext.width), (int32_t)src_ext.height, 1}},
            .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .dstOffsets = {{0, 0, 0}, {dsplit, dh, 1}},
        };
        if (blit.srcOffsets[1].x > 0)
            vkCmdBlitImage(w->cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    if (src_b && dsplit < dw) {
        VkImageBlit blit = {
            .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .srcOffsets = {{(int32_t)(split * (float)ext_b.width), 0, 0}, {(int32_t)ext_b.width, (int32_t)ext_b.height, 1}},
            .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .dstOffsets = {{dsplit, 0, 0}, {dw, dh, 1}},
        };
        if (blit.srcOffsets[0].x < blit.srcOffsets[1].x)
            vkCmdBlitImage(w->cmd, src_b, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                           VK_FILTER_LINEAR);
    }
    /* the overlay panel over the top-left corner (after the blits: a write
     * after a write) */
    uint32_t pw = 0, ph = 0;
    if (!w->hide_overlay && w->overlay.lines) {
        uint32_t max_w = w->sc.extent.width < OVERLAY_MAX_W ? w->sc.extent.width : OVERLAY_MAX_W;
        uint32_t max_h = w->sc.extent.height < OVERLAY_MAX_H ? w->sc.extent.height : OVERLAY_MAX_H;
        vrg_overlay_draw(&w->overlay, w->staging_map, max_w, max_h, &pw, &ph);
        VkImageMemoryBarrier2 waw = to_dst;
        waw.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        waw.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        dep.pImageMemoryBarriers = &waw;
        vkCmdPipelineBarrier2(w->cmd, &dep);
        VkBufferImageCopy region = {.bufferRowLength = pw, .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {pw, ph, 1}};
        vkCmdCopyBufferToImage(w->cmd, w->staging, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    VkDeviceSize shot_at = (VkDeviceSize)OVERLAY_MAX_W * OVERLAY_MAX_H * 4;
    if (screenshot) { /* what the window shows: both halves and the overlay */
        VkImageMemoryBarrier2 to_src = to_dst;
        to_src.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        to_src.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
        to_src.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        to_src.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        dep.pImageMemoryBarriers = &to_src;
        vkCmdPipelineBarrier2(w->cmd, &dep);
        VkBufferImageCopy region = {.bufferOffset = shot_at, .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    .imageExtent = {w->sc.extent.width, w->sc.extent.height, 1}};
        vkCmdCopyImageToBuffer(w->cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->staging, 1, &region);
        layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    VkImageMemoryBarrier2 to_present = to_dst;
    to_present.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    to_present.srcAccessMask = screenshot ? 0 : VK_ACCESS_2_TRANSFER_WRITE_BIT;
    to_present.dstStageMask = VK_PIPELINE_STAGE_2_NONE;
    to_present.dstAccessMask = 0;
    to_present.oldLayout = layout;
    to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    dep.pImageMemoryBarriers = &to_present;
    vkCmdPipelineBarrier2(w->cmd, &dep);
    vkEndCommandBuffer(w->cmd);
    VkSemaphoreSubmitInfo wait = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = w->acquired,
                                  .stageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT};
    VkSemaphoreSubmitInfo signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = w->rendered,
                                    .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = w->cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = 1, .pWaitSemaphoreInfos = &wait,
                        .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi, .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &signal};
    vkResetFences(dev, 1, &w->done);
    if (vkQueueSubmit2(w->dev->queue, 1, &si, w->done) != VK_SUCCESS)
        return -1;
    VkPresentInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .waitSemaphoreCount = 1, .pWaitSemaphores = &w->rendered,
                           .swapchainCount = 1, .pSwapchains = &w->sc.handle, .pImageIndices = &index};
    res = vkQueuePresentKHR(w->dev->queue, &pi);
    /* the blit reads the graph's output: done before the graph writes it again */
    vkWaitForFences(dev, 1, &w->done, VK_TRUE, UINT64_MAX);
    if (screenshot) {
        uint32_t sw = w->sc.extent.width, sh = w->sc.extent.height;
        int bgr = w->sc.format == VK_FORMAT_B8G8R8A8_UNORM || w->sc.format == VK_FORMAT_B8G8R8A8_SRGB;
        vrg_image_data img = {.width = sw, .height = sh, .channels = 4, .format = VK_FORMAT_R8G8B8A8_UNORM,
                              .pixels = malloc(sizeof(float) * 4 * sw * sh)};
        const uint8_t *px = w->staging_map + shot_at;
        for (size_t i = 0; img.pixels && i < (size_t)sw * sh; i++)
            for (int c = 0; c < 4; c++)
                img.pixels[4 * i + c] = (float)px[4 * i + (bgr && c < 3 ? 2 - c : c)] / 255.0f;
        if (!img.pixels)
            fprintf(stderr, "error: cannot write %s: out of memory\n", screenshot);
        if (img.pixels && vrg_write_png(screenshot, &img) == 0)
            fprintf(stderr, "wrote %s\n", screenshot);
        else
            w->screenshot_failed = 1; /* the run's exit status says so */
        free(img.pixels);
    }
    return res == VK_ERROR_OUT_OF_DATE_KHR || res == VK_SUBOPTIMAL_KHR ? 1 : res == VK_SUCCESS ? 0 : -1;
}

/* The overlay's lines: rates, per-pass GPU ms, what is shown, reloads. */
static void fill_overlay(window_state *w, const vrg_run_options *o, vrg_graph *g, vrg_graph *gb, float dt)
{
    static double smooth_ms = 0;
    smooth_ms = smooth_ms > 0 ? 0.9 * smooth_ms + 0.1 * dt * 1e3 : dt * 1e3;
    vrg_overlay *ov = &w->overlay;
    char line[160];
    vrg_overlay_clear(ov);
    snprintf(line, sizeof line, "%s   %.1f fps   frame %.1f ms", o->graph, smooth_ms > 0 ? 1e3 / smooth_ms : 0.0, smooth_ms);
    vrg_overlay_line(ov, line);
    for (int k = 0; k < 2; k++) {
        vrg_graph *x = k ? gb : g;
        if (!x)
            continue;
        double sum = 0;
        for (uint32_t i = 0; i < vrg_graph_pass_count(x); i++)
            sum += vrg_graph_pass_ms(x, i) > 0 ? vrg_graph_pass_ms(x, i) : 0;
        snprintf(line, sizeof line, "%s%s: gpu %.1f ms, shown: %s", k ? "B " : gb ? "A " : "", k ? o->ab : "graph", sum,
                 k ? vrg_graph_output(x) : w->shown_name);
        vrg_overlay_line(ov, line);
        for (uint32_t i = 0; i < vrg_graph_pass_count(x) && ov->lines < VRG_OVERLAY_LINES - 6; i++)
            if (vrg_graph_pass_ms(x, i) >= 0) {
                snprintf(line, sizeof line, "  %-18s %7.2f ms", vrg_graph_pass_name(x, i), vrg_graph_pass_ms(x, i));
                vrg_overlay_line(ov, line);
            }
    }
    if (vrg_graph_reload_ms(g) >= 0) {
        snprintf(line, sizeof line, "reloaded: %.0f ms from save to frame", vrg_graph_reload_ms(g));
        vrg_overlay_line(ov, line);
    }
    const char *err = vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : gb ? vrg_graph_reload_error(gb) : NULL;
    if (err) { /* its first lines: FILE:LINE: error: ... */
        vrg_overlay_line(ov, "reload error (the last good version runs):");
        for (int n = 0; *err && n < 3; n++) {
            const char *end = strchr(err, '\n');
            size_t len = end ? (size_t)(end - err) : strlen(err);
            snprintf(line, sizeof line, "  %.*s", (int)(len < 150 ? len : 150), err);
            vrg_overlay_line(ov, line);
            err += len + (end ? 1 : 0);
        }
    }
    if (w->paused)
        vrg_overlay_line(ov, "paused (f or pause to go on)");
    vrg_overlay_line(ov, "wasd space shift, right mouse: look, tab 0-9: show, t [ ]: day, f: pause, p: shot, h: hide, esc");
}

int vrg_cli_run(const vrg_run_options *o)
{
    if (!glfwInit()) {
        fprintf(stderr, "error: no display to open a window on (is $DISPLAY set?): use `voxrg render %s` to render headless\n", o->graph);
        return 1;
    }
    if (!glfwVulkanSupported()) {
        fprintf(stderr, "error: GLFW finds no Vulkan loader for windows: use `voxrg render %s`\n", o->graph);
        glfwTerminate();
        return 1;
    }
    window_state w = {.speed = 8.0f, .divider = 0.5f, .shown = -1};
    uint32_t next = 0;
    const char **exts = glfwGetRequiredInstanceExtensions(&next);
    vrg_context_desc cd = {.validate = o->validate, .device = o->device, .gpu_timeout_s = o->gpu_timeout_s, .instance_extensions = exts, .instance_extension_count = next,
                           .swapchain = 1};
    int rc = 1;
    vrg_graph *g = NULL, *gb = NULL;
    vrg_output *record_out = NULL;
    FILE *record = NULL;
    if (vrg_context_create(&cd, &w.ctx) != 0)
        goto out;
    w.dev = vrg_context_device(w.ctx);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    w.window = glfwCreateWindow((int)o->width, (int)o->height, "voxrg", NULL, NULL);
    if (!w.window) {
        fprintf(stderr, "error: cannot open a window: use `voxrg render %s`\n", o->graph);
        goto out;
    }
    glfwSetWindowUserPointer(w.window, &w);
    glfwSetKeyCallback(w.window, on_key);
    glfwSetScrollCallback(w.window, on_scroll);
    if (glfwCreateWindowSurface(w.dev->instance, w.window, NULL, &w.surface) != VK_SUCCESS) {
        fprintf(stderr, "error: cannot make a Vulkan surface for the window\n");
        goto out;
    }
    VkBool32 can_present = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(w.dev->physical_device, w.dev->queue_family, w.surface, &can_present);
    if (!can_present) {
        fprintf(stderr, "error: device '%s' cannot present to this window: use `voxrg render %s`\n", w.dev->name, o->graph);
        goto out;
    }
    VkCommandPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                   .queueFamilyIndex = w.dev->queue_family};
    vkCreateCommandPool(w.dev->device, &pci, NULL, &w.pool);
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = w.pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    vkAllocateCommandBuffers(w.dev->device, &ai, &w.cmd);
    VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    vkCreateSemaphore(w.dev->device, &sci, NULL, &w.acquired);
    vkCreateSemaphore(w.dev->device, &sci, NULL, &w.rendered);
    VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCreateFence(w.dev->device, &fci, NULL, &w.done);

    vrg_graph_desc d = {.path = o->graph, .overrides = o->sets, .override_count = o->set_count, .width = o->width, .height = o->height,
                        .keep_images = 1};
    if (vrg_graph_load(w.ctx, &d, &g) != 0)
        goto out;
    vrg_graph_watch(g, 1); /* hot reload is what the window is for */
    for (uint32_t i = 0; o->show && i < vrg_graph_image_count(g); i++)
        if (strcmp(vrg_graph_image_name(g, i), o->show) == 0)
            w.shown = (int)i;
    if (o->show && w.shown < 0 && strcmp(o->show, vrg_graph_output(g)) != 0) {
        fprintf(stderr, "error: --show %s: the graph has no image of that name\n", o->show);
        goto out;
    }
    if (o->ab) { /* B: its own graph file at A's size, the same world, camera and seed */
        uint32_t aw, ah;
        vrg_graph_size(g, &aw, &ah);
        vrg_graph_desc db = {.path = o->ab, .width = aw, .height = ah};
        if (vrg_graph_load(w.ctx, &db, &gb) != 0)
            goto out;
        char why[1024];
        if (vrg_graph_same_world(g, gb, why, sizeof why) != 0) {
            fprintf(stderr, "error: --ab: %s: the two sides would not show the same frames\n", why);
            goto out;
        }
        vrg_graph_watch(gb, 1);
    }
    /* the files written, checked before the first frame */
    if (o->screenshot && vrg_cli_out_file_dir(o->screenshot) != 0)
        goto out;
    if (o->record && !(record_out = vrg_output_open(o->record)))
        goto out;
    record = record_out ? vrg_output_stream(record_out) : NULL;
    if (record)
        fprintf(record, "# recorded by voxrg run %s\n# time  x y z  yaw pitch\n", o->graph);
    {
        VkImage img;
        VkExtent2D e;
        VkFormat f = VK_FORMAT_UNDEFINED;
        /* the output's format decides the swapchain's: known after a frame */
        if (vrg_graph_frame(g) != 0 || vrg_graph_image(g, vrg_graph_output(g), &img, &e, &f) != 0)
            goto out;
        w.srgb = !(f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_R8G8B8A8_SRGB ||
                   f == VK_FORMAT_B8G8R8A8_SRGB);
    }
    if (create_swapchain(&w, VK_NULL_HANDLE) != 0)
        goto out;
    vrg_camera_path path = {0};
    if (o->camera && vrg_camera_path_load(o->camera, &path, stderr) != 0)
        goto out;
    vrg_camera cam = *vrg_graph_camera(g);
    double last = now_s(), title_at = 0, reloaded = -1;
    int frames = 0, shots = 0;
    rc = 0;
    while (!glfwWindowShouldClose(w.window) && (!o->frames || (uint32_t)frames < o->frames)) {
        glfwPollEvents();
        double t = now_s();
        float dt = (float)(t - last);
        last = t;
        if (path.count)
            vrg_camera_path_eval(&path, (float)(frames * vrg_graph_frame_seconds(g)), &cam);
        else
            fly(&w, &cam, dt);
        if (record)
            fprintf(record, "%.4f  %.3f %.3f %.3f  %.2f %.2f\n", frames * vrg_graph_frame_seconds(g), cam.position[0], cam.position[1],
                    cam.position[2], cam.yaw, cam.pitch);
        if (gb && glfwGetMouseButton(w.window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) { /* drag the divider */
            int ww, wh;
            double mx, my;
            glfwGetWindowSize(w.window, &ww, &wh);
            glfwGetCursorPos(w.window, &mx, &my);
            w.divider = ww > 0 ? (float)(mx / ww) : 0.5f;
            w.divider = w.divider < 0 ? 0 : w.divider > 1 ? 1 : w.divider;
        }
        /* which resource A shows: the output, or one of its images */
        int count = (int)vrg_graph_image_count(g);
        if (w.shown_step)
            w.shown = (w.shown + 1 + w.shown_step + count + 1) % (count + 1) - 1;
        w.shown_step = 0;
        if (w.shown >= count)
            w.shown = -1;
        const char *show = w.shown >= 0 ? vrg_graph_image_name(g, (uint32_t)w.shown) : NULL;
        if (show && strcmp(show, vrg_graph_output(g)) == 0)
            show = NULL;
        vrg_graph_show(g, show);
        snprintf(w.shown_name, sizeof w.shown_name, "%s", show ? show : vrg_graph_output(g));
        vrg_graph *both[2] = {g, gb};
        for (int k = 0; k < 2 && both[k]; k++) {
            double v;
            if (w.day_toggle && vrg_graph_get_param(both[k], "scene.day_length", &v) == 0)
                vrg_graph_set_param(both[k], "scene.day_length", v > 0 ? 0 : 120); /* a day in two minutes */
            if (w.time_step != 0 && vrg_graph_get_param(both[k], "scene.time_of_day", &v) == 0)
                vrg_graph_set_param(both[k], "scene.time_of_day", fmod(v + w.time_step + 24.0, 24.0));
            vrg_graph_set_camera(both[k], &cam);
            if (!w.paused && vrg_graph_frame(both[k]) != 0)
                rc = 1;
        }
        w.day_toggle = 0;
        w.time_step = 0;
        if (rc)
            break;
        int changed = vrg_graph_source_changed(g) || (gb && vrg_graph_source_changed(gb));
        if (vrg_graph_source_changed(g))
            (void)vrg_graph_reload(&g); /* a broken graph or plugin is reported; the running one stays */
        if (gb && vrg_graph_source_changed(gb))
            (void)vrg_graph_reload(&gb);
        char why[1024];
        if (changed && gb && vrg_graph_same_world(g, gb, why, sizeof why) != 0) /* an edit may part them: say so, keep going */
            fprintf(stderr, "warning: --ab: %s: the sides no longer show the same frames\n", why);
        if (vrg_graph_reload_ms(g) != reloaded) {
            reloaded = vrg_graph_reload_ms(g);
            fprintf(stderr, "reloaded: %.0f ms from save to frame\n", reloaded);
        }
        frames++;
        int last_frame = o->frames && (uint32_t)frames == o->frames;
        char file[VRG_CLI_PATH] = "";
        if (o->screenshot && last_frame)
            snprintf(file, sizeof file, "%s", o->screenshot);
        else if (w.screenshot_requested)
            snprintf(file, sizeof file, "screenshot-%03d.png", shots++);
        w.screenshot_requested = 0;
        fill_overlay(&w, o, g, gb, dt);
        VkImage src, src_b = VK_NULL_HANDLE;
        VkExtent2D ext, ext_b = {0, 0};
        VkFormat fmt;
        int via_display = 0;
        if (show && vrg_graph_image(g, show, &src, &ext, &fmt) == 0) {
            /* integer images (ids) cannot be blitted: say so, show the output */
            int integer = fmt == VK_FORMAT_R32_UINT || fmt == VK_FORMAT_R32G32_UINT || fmt == VK_FORMAT_R32G32B32A32_UINT ||
                          fmt == VK_FORMAT_R16_UINT || fmt == VK_FORMAT_R8_UINT || fmt == VK_FORMAT_R32_SINT;
            if (integer)
                snprintf(w.shown_name, sizeof w.shown_name, "%s (an integer image: showing %s)", show, vrg_graph_output(g));
            else if (display_prepare(&w, ext, vrg_data_dir()) == 0) {
                display_mode(&w, show);
                via_display = 1;
            }
        }
        if ((!via_display && vrg_graph_image(g, vrg_graph_output(g), &src, &ext, &fmt) != 0) ||
            (gb && vrg_graph_image(gb, vrg_graph_output(gb), &src_b, &ext_b, &fmt) != 0)) {
            rc = 1;
            break;
        }
        if (ensure_staging(&w, (VkDeviceSize)OVERLAY_MAX_W * OVERLAY_MAX_H * 4 + (VkDeviceSize)w.sc.extent.width * w.sc.extent.height * 4) != 0) {
            rc = 1;
            break;
        }
        int pr = present(&w, src, ext, src_b, ext_b, file[0] ? file : NULL, via_display);
        if (pr < 0) {
            fprintf(stderr, "error: presenting to the window failed\n");
            rc = 1;
            break;
        }
        int fw, fh;
        glfwGetFramebufferSize(w.window, &fw, &fh);
        if (pr > 0 || (fw > 0 && fh > 0 && ((uint32_t)fw != w.sc.extent.width || (uint32_t)fh != w.sc.extent.height))) {
            vkDeviceWaitIdle(w.dev->device);
            uint32_t was_w, was_h, now_w, now_h;
            vrg_graph_size(g, &was_w, &was_h);
            if (create_swapchain(&w, w.sc.handle) < 0 || vrg_graph_resize(g, w.sc.extent.width, w.sc.extent.height) != 0 ||
                (gb && vrg_graph_resize(gb, w.sc.extent.width, w.sc.extent.height) != 0)) {
                rc = 1;
                break;
            }
            vrg_graph_size(g, &now_w, &now_h);
            if (now_w != was_w || now_h != was_h)
                fprintf(stderr, "window resized: graph%s now %ux%u, history reset\n", gb ? "s" : "", now_w, now_h);
        }
        if (t - title_at > 0.5) { /* the figures in the title too */
            double gpu[2] = {0, 0};
            for (int k = 0; k < 2 && both_graphs(g, gb, k); k++)
                for (uint32_t i = 0; i < vrg_graph_pass_count(both_graphs(g, gb, k)); i++) {
                    double ms = vrg_graph_pass_ms(both_graphs(g, gb, k), i);
                    gpu[k] += ms > 0 ? ms : 0;
                }
            char title[768];
            int n = snprintf(title, sizeof title, "voxrg - %s - %.1f fps, %.1f ms GPU", o->graph, dt > 0 ? 1.0 / dt : 0.0, gpu[0]);
            if (gb)
                n += snprintf(title + n, sizeof title - (size_t)n, " | B: %s - %.1f ms GPU", o->ab, gpu[1]);
            snprintf(title + n, sizeof title - (size_t)n, "%s",
                     vrg_graph_reload_error(g) || (gb && vrg_graph_reload_error(gb)) ? " - reload error (see terminal)" : "");
            glfwSetWindowTitle(w.window, title);
            title_at = t;
        }
    }
    vrg_camera_path_free(&path);
out:
    /* what was flown, a failed run too: written before a busy GPU ends the process */
    if (record_out && vrg_output_commit(record_out) == 0)
        fprintf(stderr, "wrote %s\n", o->record);
    else if (record_out)
        rc = 1;
    record_out = NULL;
    vrg_cli_exit_if_gpu_busy(w.ctx, rc);
    if (w.dev) {
        vkDeviceWaitIdle(w.dev->device);
        vrg_graph_destroy(g);
        vrg_graph_destroy(gb);
        vkDestroyFence(w.dev->device, w.done, NULL);
        vkDestroySemaphore(w.dev->device, w.acquired, NULL);
        vkDestroySemaphore(w.dev->device, w.rendered, NULL);
        vkDestroyCommandPool(w.dev->device, w.pool, NULL);
        if (w.sc.handle)
            vkDestroySwapchainKHR(w.dev->device, w.sc.handle, NULL);
        display_free_images(&w);
        vkDestroyPipeline(w.dev->device, w.disp.pipeline, NULL);
        vkDestroyPipelineLayout(w.dev->device, w.disp.layout, NULL);
        vkDestroyDescriptorSetLayout(w.dev->device, w.disp.set_layout, NULL);
        vkDestroyDescriptorPool(w.dev->device, w.disp.pool, NULL);
        vkDestroySampler(w.dev->device, w.disp.sampler, NULL);
        if (w.staging) {
            vkUnmapMemory(w.dev->device, w.staging_memory);
            vkDestroyBuffer(w.dev->device, w.staging, NULL);
            vkFreeMemory(w.dev->device, w.staging_memory, NULL);
        }
        if (w.surface)
            vkDestroySurfaceKHR(w.dev->instance, w.surface, NULL);
    }
    if (w.screenshot_failed)
        rc = 1;
    if (w.window)
        glfwDestroyWindow(w.window);
    if (w.ctx) {
        if (vrg_context_validation_errors(w.ctx))
            rc = 1;
        vrg_context_destroy(w.ctx);
    }
    glfwTerminate();
    return rc;
}
