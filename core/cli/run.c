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
#include <unistd.h>
#include "auto_scale.h"
#include "bench.h"
#include "edit.h"
#include "overlay.h"
#include "panel.h"
#include "run.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/edits.h"
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

typedef struct display_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    VkExtent2D extent;
} display_image;

/* display.comp's push constants */
typedef struct display_push {
    int32_t mode, channel;
    float scale;
    int32_t linear_out, bilinear, split, overlay_on;
} display_push;

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
    int details;         /* F1: per-pass times and the keys */
    int paused;          /* Pause or F: no new frames, the last one stays shown */
    int srgb;            /* the output holds linear values: let the swapchain encode them */
    int bilinear;        /* the upscale to the window: N toggles */
    double scale;        /* render size / window size, unless fixed */
    int scale_auto;      /* the scale adapts to the frame time (a CPU device, no --scale) */
    vrg_auto_scale autos;
    uint32_t fixed_w, fixed_h; /* --size: the render size whatever the window */
    /* host-visible staging: the overlay layer (window-sized RGBA, read by the
     * display stage), then a screenshot of what is shown */
    VkBuffer staging;
    VkDeviceMemory staging_memory;
    uint8_t *staging_map;
    VkDeviceSize staging_size;
    vrg_overlay_layer layer;
    vrg_panel panel;
    int save_requested;  /* Ctrl+S; 2: Ctrl+Shift+S (save as: the name is asked for), 3: the name typed */
    int s_saves;         /* S went down with Ctrl: no flying back until it is up */
    int typing_began;    /* the key that began typing ('/') is not typed */
    vrg_graph *g, *gb;   /* this frame's graphs, for the panel's keys */
    int mouse_was_down, mouse_on_panel; /* a left press that fell on the panel drags there, not the divider */
    /* showing a resource other than the output: Tab / Shift+Tab / 0-9 */
    int shown;                /* index into vrg_graph_image_name, -1: the output */
    int shown_step;           /* pending key */
    char shown_name[160];
    /* block editing (edit.h): a right press that moves less than
     * CLICK_SLOP pixels before its release places; more is a look */
    vrg_cli_edit edit;
    char replayed[2][VRG_CLI_PATH + 64]; /* "replayed N ... from FILE" of A's and B's journals, shown up to the first edit */
    double right_moved;
    int right_hit;
    vrg_world_hit right_at; /* what was under the cursor at the right press */
    /* the display stage (shaders/display.comp): sources, result, pipeline */
    struct {
        display_image a, b, out;
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

static VkDeviceSize overlay_bytes(const window_state *w) { return (VkDeviceSize)w->sc.extent.width * w->sc.extent.height * 4; }

/* The staging buffer holds the overlay layer first, then a screenshot. */
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
                             .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT};
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

/* W/A/S/D move, Space up, Shift down, right mouse button dragged: look,
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
    /* Ctrl+S saves: its S does not fly, up to its release */
    float f = w->s_saves ? 0.0f : (float)(glfwGetKey(win, GLFW_KEY_W) == GLFW_PRESS) - (float)(glfwGetKey(win, GLFW_KEY_S) == GLFW_PRESS);
    float r = (float)(glfwGetKey(win, GLFW_KEY_D) == GLFW_PRESS) - (float)(glfwGetKey(win, GLFW_KEY_A) == GLFW_PRESS);
    if (w->panel.typing) /* the keys spell a filter or a file name */
        f = r = 0;
    /* Shift with an arrow is the panel's fine step, not a descent */
    int arrow = glfwGetKey(win, GLFW_KEY_LEFT) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_RIGHT) == GLFW_PRESS ||
                glfwGetKey(win, GLFW_KEY_UP) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_DOWN) == GLFW_PRESS;
    float u = (float)(glfwGetKey(win, GLFW_KEY_SPACE) == GLFW_PRESS) -
              (float)(glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS && !(w->panel.open && arrow));
    u = w->panel.typing ? 0 : u;
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
        w->right_moved += fabs(mx - w->mouse_x) + fabs(my - w->mouse_y);
        cam->yaw = remainderf(cam->yaw - (float)(mx - w->mouse_x) * 0.15f, 360.0f); /* in [-180, 180]: graphs and paths hold yaw to +-360 */
        cam->pitch -= (float)(my - w->mouse_y) * 0.15f;
        cam->pitch = cam->pitch > 89 ? 89 : cam->pitch < -89 ? -89 : cam->pitch;
    }
    if (look != w->looking)
        glfwSetInputMode(win, GLFW_CURSOR, look ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    w->looking = look;
    w->mouse_x = mx, w->mouse_y = my;
}

/* Pixels a right press may move and still be a click (a place), not a look. */
#define CLICK_SLOP 4.0

/* The cursor in framebuffer pixels, as the panel and the picture are laid out. */
static void cursor_fb(window_state *w, double *x, double *y, int *fw, int *fh)
{
    int ww, wh;
    glfwGetCursorPos(w->window, x, y);
    glfwGetFramebufferSize(w->window, fw, fh);
    glfwGetWindowSize(w->window, &ww, &wh);
    *x *= ww > 0 ? (double)*fw / ww : 1, *y *= wh > 0 ? (double)*fh / wh : 1;
}

/* The block under the cursor of the picture shown (A's: --ab's sides are
 * separate worlds and the left button drags the divider, so no editing). */
static int hovered(window_state *w, vrg_world_hit *hit)
{
    double x, y;
    int fw, fh;
    if (!w->g || w->gb || w->looking)
        return 0;
    cursor_fb(w, &x, &y, &fw, &fh);
    return !vrg_panel_contains(&w->panel, x, y) && vrg_cli_edit_pick(w->g, x, y, fw, fh, hit);
}

/* A journal read at start-up changes the world before the first frame:
 * said in the terminal and the overlay, with the file to remove to start
 * from the world as generated. */
static void say_replayed(window_state *w, int side, const vrg_graph *g)
{
    const vrg_edits *journal = vrg_graph_edits(g);
    int n = journal ? vrg_edits_records(journal) : 0;
    if (!n)
        return;
    snprintf(w->replayed[side], sizeof w->replayed[side], "%sreplayed %d edit record%s from %s", w->gb ? (side ? "B: " : "A: ") : "", n,
             n == 1 ? "" : "s", vrg_edits_path(journal));
    fprintf(stderr, "edits: %s (remove it to start from the unedited world)\n", w->replayed[side]);
}

/* Edits apply at once, between frames (events are polled then), on the
 * graph whose last frame the window shows. */
static void edit_action(window_state *w, vrg_cli_edit_action action, const vrg_world_hit *hit)
{
    if (!w->g)
        return;
    w->replayed[0][0] = w->replayed[1][0] = '\0';
    if (w->gb) {
        snprintf(w->edit.status, sizeof w->edit.status, "no editing with --ab (each side has its own world)");
        fprintf(stderr, "edit: %s\n", w->edit.status);
        return;
    }
    vrg_cli_edit_apply(&w->edit, w->g, action, hit);
}

/* Left press: remove; right press and release without a drag: place.
 * Buttons come as events so that a click within one poll is not missed. */
static void on_mouse_button(GLFWwindow *win, int button, int action, int mods)
{
    (void)mods;
    window_state *w = glfwGetWindowUserPointer(win);
    vrg_world_hit hit;
    double x, y;
    int fw, fh;
    cursor_fb(w, &x, &y, &fw, &fh);
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && !vrg_panel_contains(&w->panel, x, y) && !w->gb) {
        int got = hovered(w, &hit);
        edit_action(w, VRG_CLI_EDIT_REMOVE, got ? &hit : NULL);
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT && action == GLFW_PRESS) {
        w->right_moved = 0;
        w->right_hit = hovered(w, &w->right_at);
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT && action == GLFW_RELEASE && w->right_moved < CLICK_SLOP)
        edit_action(w, VRG_CLI_EDIT_PLACE, w->right_hit ? &w->right_at : NULL);
}

/* While the panel takes typing (its filter, a save-as name), keys edit the
 * text: Enter ends it, Esc cancels, Backspace takes a character back, Up
 * and Down still select; the characters come through on_char. */
static void typing_key(window_state *w, vrg_graph *edited, int key)
{
    if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER || key == GLFW_KEY_ESCAPE) {
        if (vrg_panel_type_end(&w->panel, key != GLFW_KEY_ESCAPE))
            w->save_requested = 3;
    } else if (key == GLFW_KEY_BACKSPACE)
        vrg_panel_backspace(&w->panel);
    else if (key == GLFW_KEY_UP || key == GLFW_KEY_DOWN)
        vrg_panel_select(&w->panel, edited, key == GLFW_KEY_DOWN ? 1 : -1);
}

static void on_char(GLFWwindow *win, unsigned int codepoint)
{
    window_state *w = glfwGetWindowUserPointer(win);
    if (w->panel.typing && !w->typing_began)
        vrg_panel_type(&w->panel, codepoint);
    w->typing_began = 0;
}

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    (void)scancode;
    window_state *w = glfwGetWindowUserPointer(win);
    int arrow = key == GLFW_KEY_UP || key == GLFW_KEY_DOWN || key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT;
    if (key == GLFW_KEY_S && action == GLFW_RELEASE)
        w->s_saves = 0;
    if (action != GLFW_PRESS && !(action == GLFW_REPEAT && (arrow || key == GLFW_KEY_BACKSPACE)))
        return;
    /* the panel's keys act at once, in order (several may come in one poll) */
    vrg_graph *edited = w->panel.side && w->gb ? w->gb : w->g;
    w->typing_began = 0;
    if (w->panel.typing)
        typing_key(w, edited, key);
    else if (w->panel.open && (key == GLFW_KEY_SLASH || key == GLFW_KEY_KP_DIVIDE)) {
        vrg_panel_filter_begin(&w->panel);
        w->typing_began = 1; /* the '/' itself comes as a character next: not part of the filter */
    } else if (w->panel.open && (key == GLFW_KEY_UP || key == GLFW_KEY_DOWN))
        vrg_panel_select(&w->panel, edited, key == GLFW_KEY_DOWN ? 1 : -1);
    else if (w->panel.open && (key == GLFW_KEY_PAGE_UP || key == GLFW_KEY_PAGE_DOWN))
        vrg_panel_jump(&w->panel, edited, key == GLFW_KEY_PAGE_DOWN ? 1 : -1);
    else if (w->panel.open && arrow)
        vrg_panel_step(&w->panel, edited, key == GLFW_KEY_RIGHT ? 1 : -1, (mods & GLFW_MOD_SHIFT) != 0);
    else if (key == GLFW_KEY_S && (mods & GLFW_MOD_CONTROL)) {
        w->save_requested = mods & GLFW_MOD_SHIFT ? 2 : 1;
        w->s_saves = 1;
        w->panel.open |= w->save_requested == 2; /* the name is typed in the panel */
    }
    else if (key == GLFW_KEY_Z && (mods & GLFW_MOD_CONTROL))
        edit_action(w, mods & GLFW_MOD_SHIFT ? VRG_CLI_EDIT_REDO : VRG_CLI_EDIT_UNDO, NULL);
    else if (key == GLFW_KEY_Y && (mods & GLFW_MOD_CONTROL))
        edit_action(w, VRG_CLI_EDIT_REDO, NULL);
    else if ((key == GLFW_KEY_E || key == GLFW_KEY_Q) && w->g)
        vrg_cli_edit_cycle(&w->edit, w->g, key == GLFW_KEY_E ? 1 : -1);
    else if (key == GLFW_KEY_M || key == GLFW_KEY_F2)
        w->panel.open = !w->panel.open;
    else if (key == GLFW_KEY_B && w->panel.open && w->gb)
        w->panel.side = !w->panel.side;
    else if (key == GLFW_KEY_F1)
        w->details = !w->details;
    else if (key == GLFW_KEY_N)
        w->bilinear = !w->bilinear;
    else if (key == GLFW_KEY_ESCAPE)
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

static void free_image(window_state *w, display_image *im)
{
    VkDevice dev = w->dev->device;
    vkDestroyImageView(dev, im->view, NULL);
    vkDestroyImage(dev, im->image, NULL);
    vkFreeMemory(dev, im->memory, NULL);
    *im = (display_image){0};
}

static int make_image(window_state *w, display_image *im, VkExtent2D ext, VkFormat format, VkImageUsageFlags usage)
{
    VkDevice dev = w->dev->device;
    free_image(w, im);
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D, .format = format,
                            .extent = {ext.width, ext.height, 1}, .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
                            .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage};
    if (vkCreateImage(dev, &ii, NULL, &im->image) != VK_SUCCESS || image_memory(w, im->image, &im->memory) != 0)
        return -1;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = im->image, .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                .format = format, .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    if (vkCreateImageView(dev, &vi, NULL, &im->view) != VK_SUCCESS)
        return -1;
    im->extent = ext;
    return 0;
}

static void display_free(window_state *w)
{
    VkDevice dev = w->dev->device;
    free_image(w, &w->disp.a);
    free_image(w, &w->disp.b);
    free_image(w, &w->disp.out);
    vkDestroyPipeline(dev, w->disp.pipeline, NULL);
    vkDestroyPipelineLayout(dev, w->disp.layout, NULL);
    vkDestroyDescriptorSetLayout(dev, w->disp.set_layout, NULL);
    vkDestroyDescriptorPool(dev, w->disp.pool, NULL);
    vkDestroySampler(dev, w->disp.sampler, NULL);
}

static int display_pipeline(window_state *w, const char *data_dir)
{
    VkDevice dev = w->dev->device;
    char path[1100];
    snprintf(path, sizeof path, "%s/shaders/display.comp", data_dir);
    VkShaderModule sm = vrg_compile_compute_shader(w->ctx, path, NULL);
    if (!sm)
        return -1;
    VkDescriptorSetLayoutBinding b[4] = {
        {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 2, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 3, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
    };
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 4, .pBindings = b};
    vkCreateDescriptorSetLayout(dev, &sli, NULL, &w->disp.set_layout);
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(display_push)};
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
    VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1, .poolSizeCount = 3, .pPoolSizes = sizes};
    vkCreateDescriptorPool(dev, &dpi, NULL, &w->disp.pool);
    VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = w->disp.pool,
                                       .descriptorSetCount = 1, .pSetLayouts = &w->disp.set_layout};
    vkAllocateDescriptorSets(dev, &dai, &w->disp.set);
    /* the shader filters itself (texelFetch): rgba32f need not be filterable */
    VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST, .minFilter = VK_FILTER_NEAREST,
                              .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    return vkCreateSampler(dev, &si, NULL, &w->disp.sampler) == VK_SUCCESS ? 0 : -1;
}

/* The display stage for these sizes: A's and B's sources as rgba32f at
 * their render sizes, the window-sized result, and the descriptors (written
 * each frame: the previous frame has ended, and the staging buffer may have
 * grown). */
static int display_prepare(window_state *w, VkExtent2D ext_a, VkExtent2D ext_b)
{
    const VkImageUsageFlags src_usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (!w->disp.pipeline && display_pipeline(w, vrg_data_dir()) != 0)
        return -1;
    if ((w->disp.a.extent.width != ext_a.width || w->disp.a.extent.height != ext_a.height) &&
        make_image(w, &w->disp.a, ext_a, VK_FORMAT_R32G32B32A32_SFLOAT, src_usage) != 0)
        return -1;
    if (ext_b.width && (w->disp.b.extent.width != ext_b.width || w->disp.b.extent.height != ext_b.height) &&
        make_image(w, &w->disp.b, ext_b, VK_FORMAT_R32G32B32A32_SFLOAT, src_usage) != 0)
        return -1;
    if ((w->disp.out.extent.width != w->sc.extent.width || w->disp.out.extent.height != w->sc.extent.height) &&
        make_image(w, &w->disp.out, w->sc.extent, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0)
        return -1;
    VkDescriptorImageInfo a = {.sampler = w->disp.sampler, .imageView = w->disp.a.view, .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo b = a;
    if (ext_b.width)
        b.imageView = w->disp.b.view;
    VkDescriptorImageInfo out = {.imageView = w->disp.out.view, .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo layer = {.buffer = w->staging, .offset = 0, .range = overlay_bytes(w)};
    VkWriteDescriptorSet wr[4] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 0, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = &a},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 1, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = &b},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 2, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &out},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = 3, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &layer},
    };
    vkUpdateDescriptorSets(w->dev->device, 4, wr, 0, NULL);
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

/* src (in TRANSFER_SRC, left so) to an rgba32f image the shader reads. */
static void to_float(VkCommandBuffer cmd, VkImage src, VkExtent2D ext, VkImage dst)
{
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT, cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    image_barrier(cmd, dst, cs, 0, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkImageBlit blit = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .srcOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .dstOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}}};
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    image_barrier(cmd, dst, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

/* Records the display stage: A (and B) upscaled to the window with the
 * overlay over them, into disp.out, left in TRANSFER_SRC for the swapchain. */
static void display_record(window_state *w, VkImage src, VkExtent2D ext, VkImage src_b, VkExtent2D ext_b, int as_is)
{
    VkCommandBuffer cmd = w->cmd;
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT, cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    to_float(cmd, src, ext, w->disp.a.image);
    if (src_b)
        to_float(cmd, src_b, ext_b, w->disp.b.image);
    image_barrier(cmd, w->disp.out.image, xfer, 0, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.layout, 0, 1, &w->disp.set, 0, NULL);
    uint32_t width = w->sc.extent.width, height = w->sc.extent.height;
    display_push pc = {as_is ? 6 : w->disp.mode, w->disp.channel, w->disp.scale, w->srgb, w->bilinear,
                       src_b ? (int32_t)(w->divider * (float)width) : (int32_t)width, !w->hide_overlay};
    vkCmdPushConstants(cmd, w->disp.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
    image_barrier(cmd, w->disp.out.image, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, xfer, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

/* How a resource is best seen, from its name (docs: voxrg run --help). */
static void display_mode(window_state *w, const char *name)
{
    w->disp.mode = 0, w->disp.channel = 0, w->disp.scale = 1;
    size_t n = strlen(name);
#define ENDS_WITH(s) (n >= sizeof(s) - 1 && strcmp(name + n - (sizeof(s) - 1), s) == 0)
    /* the temporal passes' debug outputs (default names PASS.SLOT), as grey */
    if (ENDS_WITH(".disocclusion"))
        w->disp.mode = 4; /* 1 where the history restarted */
    else if (ENDS_WITH(".reprojection"))
        w->disp.mode = 4, w->disp.channel = 3, w->disp.scale = 0.25f; /* how the history was read: 0 none .. 4 */
    else if (ENDS_WITH(".clamp"))
        w->disp.mode = 4, w->disp.scale = 4; /* how far the clamp moved the history */
    else if (ENDS_WITH(".occupancy"))
        w->disp.mode = 4, w->disp.scale = 1.0f / 64; /* the samples a surface cache's cells hold */
    else if (ENDS_WITH(".variance"))
        w->disp.mode = 4, w->disp.scale = 20; /* svgf_variance's and mean_variance's variance, in red */
    else if (strstr(name, "normal"))
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
#undef ENDS_WITH
}

/* A screenshot of what the window showed, from the staging buffer. */
static void write_screenshot(window_state *w, const char *screenshot)
{
    uint32_t sw = w->sc.extent.width, sh = w->sc.extent.height;
    int bgr = w->sc.format == VK_FORMAT_B8G8R8A8_UNORM || w->sc.format == VK_FORMAT_B8G8R8A8_SRGB;
    vrg_image_data img = {.width = sw, .height = sh, .channels = 4, .format = VK_FORMAT_R8G8B8A8_UNORM,
                          .pixels = malloc(sizeof(float) * 4 * sw * sh)};
    const uint8_t *px = w->staging_map + overlay_bytes(w);
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

/* The next screenshot's name, OUT/screenshot-NNN.png, the first number
 * from *shot on that no file has (earlier runs' screenshots stay), its
 * folder created if missing: 0, or -1 after a message. */
static int next_screenshot(const char *out, int *shot, char *file, size_t cap)
{
    if (vrg_cli_out_dir(out) != 0)
        return -1;
    for (; *shot < 100000; ++*shot) {
        snprintf(file, cap, "%s/screenshot-%03d.png", out, *shot);
        if (access(file, F_OK) != 0) {
            ++*shot;
            return 0;
        }
    }
    file[0] = '\0';
    fprintf(stderr, "error: %s holds screenshots up to screenshot-99999.png: no number left\n", out);
    return -1;
}

/* One presentation: the display stage's result copied onto the next
 * swapchain image (a blit: it converts to the swapchain's format). */
static int present(window_state *w, VkImage src, VkExtent2D src_ext, VkImage src_b, VkExtent2D ext_b, const char *screenshot, int as_is)
{
    VkDevice dev = w->dev->device;
    uint32_t index;
    VkResult res = vkAcquireNextImageKHR(dev, w->sc.handle, UINT64_MAX, w->acquired, VK_NULL_HANDLE, &index);
    if (res == VK_ERROR_OUT_OF_DATE_KHR)
        return 1;
    if (res != VK_SUCCESS && res != VK_SUBOPTIMAL_KHR)
        return -1;
    if (display_prepare(w, src_ext, src_b ? ext_b : (VkExtent2D){0, 0}) != 0)
        return -1;
    VkImage dst = w->sc.images[index];
    vkResetCommandBuffer(w->cmd, 0);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(w->cmd, &bi);
    display_record(w, src, src_ext, src_b, ext_b, as_is);
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    image_barrier(w->cmd, dst, xfer, 0, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    int32_t dw = (int32_t)w->sc.extent.width, dh = (int32_t)w->sc.extent.height;
    VkImageBlit blit = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .srcOffsets = {{0, 0, 0}, {dw, dh, 1}},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .dstOffsets = {{0, 0, 0}, {dw, dh, 1}}};
    vkCmdBlitImage(w->cmd, w->disp.out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   VK_FILTER_NEAREST);
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    if (screenshot) { /* what the window shows: both halves and the overlay */
        image_barrier(w->cmd, dst, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, xfer, VK_ACCESS_2_TRANSFER_READ_BIT, layout,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region = {.bufferOffset = overlay_bytes(w), .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    .imageExtent = {w->sc.extent.width, w->sc.extent.height, 1}};
        vkCmdCopyImageToBuffer(w->cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->staging, 1, &region);
        layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    image_barrier(w->cmd, dst, xfer, screenshot ? 0 : VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0, layout,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
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
    /* the display reads the graph's output: done before the graph writes it again */
    vkWaitForFences(dev, 1, &w->done, VK_TRUE, UINT64_MAX);
    if (screenshot)
        write_screenshot(w, screenshot);
    return res == VK_ERROR_OUT_OF_DATE_KHR || res == VK_SUBOPTIMAL_KHR ? 1 : res == VK_SUCCESS ? 0 : -1;
}

static double gpu_ms(vrg_graph *g)
{
    double sum = 0;
    for (uint32_t i = 0; i < vrg_graph_pass_count(g); i++)
        sum += vrg_graph_pass_ms(g, i) > 0 ? vrg_graph_pass_ms(g, i) : 0;
    return sum;
}

/* F1: per-pass GPU ms of each graph, and the keys. */
static void fill_details(vrg_overlay *ov, const vrg_run_options *o, vrg_graph *g, vrg_graph *gb)
{
    char line[160];
    for (int k = 0; k < 2 && both_graphs(g, gb, k); k++) {
        vrg_graph *x = both_graphs(g, gb, k);
        snprintf(line, sizeof line, "%s%.100s: gpu %.1f ms", gb ? (k ? "B " : "A ") : "", k ? o->ab : o->graph, gpu_ms(x));
        vrg_overlay_line(ov, line);
        for (uint32_t i = 0; i < vrg_graph_pass_count(x) && ov->lines < VRG_OVERLAY_LINES - 12; i++)
            if (vrg_graph_pass_ms(x, i) >= 0) {
                snprintf(line, sizeof line, "  %-18s %7.2f ms", vrg_graph_pass_name(x, i), vrg_graph_pass_ms(x, i));
                vrg_overlay_line(ov, line);
            }
    }
    static const char *keys[] = {
        "wasd space shift: fly, right drag: look, scroll + -: speed",
        "left click: remove block, right click: place, e q: block type",
        "ctrl+z: undo, ctrl+y ctrl+shift+z: redo",
        "tab 0-9: show an image, t [ ]: day, f: pause, p: screenshot",
        "n: nearest/bilinear, h: hide, f1: these details, esc: quit",
        "m f2: parameters (/: filter, pgup pgdn: pass, b: edit a or b)",
        "ctrl+s: save into the graph, ctrl+shift+s: save as a new file",
    };
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        vrg_overlay_line(ov, keys[i]);
}

/* The overlay layer: one compact line (rates, what is shown, the last
 * reload), the reload error if any, --ab's labels over their halves, the
 * details on F1 and the panel on M. */
static void fill_overlay(window_state *w, const vrg_run_options *o, vrg_graph *g, vrg_graph *gb, float dt)
{
    static double smooth_ms = 0;
    smooth_ms = smooth_ms > 0 ? 0.9 * smooth_ms + 0.1 * dt * 1e3 : dt * 1e3;
    static const uint8_t white[4] = {255, 255, 255, 255}, back[4] = {0, 0, 0, 140};
    vrg_overlay_layer *l = &w->layer;
    vrg_overlay_layer_clear(l);
    vrg_overlay ov;
    char line[160], reload[64] = "";
    uint32_t rw, rh;
    vrg_graph_size(g, &rw, &rh);
    if (vrg_graph_reload_error(g) || (gb && vrg_graph_reload_error(gb)))
        snprintf(reload, sizeof reload, "  reload failed");
    else if (vrg_graph_reload_ms(g) >= 0)
        snprintf(reload, sizeof reload, "  reloaded %.0f ms", vrg_graph_reload_ms(g));
    vrg_overlay_clear(&ov);
    char scale[48] = "";
    if (!w->fixed_w)
        snprintf(scale, sizeof scale, "  scale %g%s", w->scale, w->scale_auto ? " (auto, CPU)" : "");
    snprintf(line, sizeof line, "%.1f fps %.1f ms  %ux%u%s  %.60s%s%s", smooth_ms > 0 ? 1e3 / smooth_ms : 0.0, smooth_ms, rw, rh, scale,
             w->shown_name, reload, w->paused ? "  paused" : "");
    vrg_overlay_line(&ov, line);
    const char *err = vrg_graph_reload_error(g) ? vrg_graph_reload_error(g) : gb ? vrg_graph_reload_error(gb) : NULL;
    for (int n = 0; err && *err && n < 3; n++) { /* its first lines: FILE:LINE: error: ... */
        const char *end = strchr(err, '\n');
        size_t len = end ? (size_t)(end - err) : strlen(err);
        snprintf(line, sizeof line, "%.*s", (int)(len < 150 ? len : 150), err);
        vrg_overlay_line(&ov, line);
        err += len + (end ? 1 : 0);
    }
    for (int k = 0; k < 2; k++)
        if (w->replayed[k][0])
            vrg_overlay_line(&ov, w->replayed[k]);
    vrg_world_hit hover;
    int hover_on = hovered(w, &hover);
    /* only while there is something to say: the rates' line stays alone otherwise */
    if (!gb && vrg_graph_world(g) && (hover_on || w->edit.status[0])) {
        vrg_cli_edit_describe(&w->edit, g, hover_on ? &hover : NULL, line, sizeof line);
        vrg_overlay_line(&ov, line);
    }
    if (hover_on)
        vrg_cli_edit_outline(g, &hover, l);
    if (w->details)
        fill_details(&ov, o, g, gb);
    int bw, bh;
    if (gb) { /* each side's label at the top of its own half */
        int split = (int)(w->divider * (float)l->width), y = 4;
        snprintf(line, sizeof line, "A: %.70s", o->graph);
        vrg_overlay_box(l, split - vrg_overlay_text_width(line) - 12, y, vrg_overlay_text_width(line) + 8, VRG_OVERLAY_LINE_H + 4, back);
        vrg_overlay_text(l, split - vrg_overlay_text_width(line) - 8, y + 2, line, white);
        snprintf(line, sizeof line, "B: %.70s", o->ab);
        vrg_overlay_box(l, split + 4, y, vrg_overlay_text_width(line) + 8, VRG_OVERLAY_LINE_H + 4, back);
        vrg_overlay_text(l, split + 8, y + 2, line, white);
    }
    vrg_overlay_draw(&ov, l, 0, gb ? VRG_OVERLAY_LINE_H + 8 : 0, -1, &bw, &bh);
    if (w->panel.open)
        vrg_panel_draw(&w->panel, w->panel.side && gb ? gb : g, w->panel.side && gb ? o->ab : o->graph, l);
}

/* The graph's size for a window: fixed (--size), or the window's times the
 * scale (at least a pixel). */
static VkExtent2D render_size(const window_state *w, uint32_t width, uint32_t height)
{
    if (w->fixed_w)
        return (VkExtent2D){w->fixed_w, w->fixed_h};
    uint32_t rw = (uint32_t)lround(width * w->scale), rh = (uint32_t)lround(height * w->scale);
    return (VkExtent2D){rw ? rw : 1, rh ? rh : 1};
}

/* The graphs at the render size for the window (after a resize or a new
 * scale), said with why: 0, or -1 (the error printed). */
static int fit_graphs(window_state *w, vrg_graph *g, vrg_graph *gb, const char *why)
{
    uint32_t was_w, was_h, now_w, now_h;
    vrg_graph_size(g, &was_w, &was_h);
    VkExtent2D want = render_size(w, w->sc.extent.width, w->sc.extent.height);
    if ((want.width != was_w || want.height != was_h) &&
        (vrg_graph_resize(g, want.width, want.height) != 0 || (gb && vrg_graph_resize(gb, want.width, want.height) != 0)))
        return -1;
    vrg_graph_size(g, &now_w, &now_h);
    if (now_w != was_w || now_h != was_h)
        fprintf(stderr, "%s: graph%s now %ux%u, history reset\n", why, gb ? "s" : "", now_w, now_h);
    return 0;
}

/* A CPU device renders at a scale that keeps the window near
 * VRG_AUTO_SCALE_FPS, unless --scale or --size says otherwise. */
static void choose_scale_auto(window_state *w, const vrg_run_options *o)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(w->dev->physical_device, &props);
    if (!o->scale_auto || props.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU)
        return;
    w->scale_auto = 1;
    w->scale = w->autos.scale = VRG_AUTO_SCALE_START;
    fprintf(stderr, "render scale %g (auto: %s is a CPU device; it adapts towards %g fps, --scale S or --size WxH fixes it)\n", w->scale, w->dev->name,
            VRG_AUTO_SCALE_FPS);
}

/* The panel's mouse, on the graph it edits; Ctrl+S saves. */
static void drive_panel(window_state *w, const vrg_run_options *o, vrg_graph *g, vrg_graph *gb)
{
    vrg_graph *x = w->panel.side && gb ? gb : g;
    int held = glfwGetMouseButton(w->window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    double mx, my;
    glfwGetCursorPos(w->window, &mx, &my);
    int fw, fh, ww, wh; /* the panel is laid out in framebuffer pixels */
    glfwGetFramebufferSize(w->window, &fw, &fh);
    glfwGetWindowSize(w->window, &ww, &wh);
    mx *= ww > 0 ? (double)fw / ww : 1, my *= wh > 0 ? (double)fh / wh : 1;
    if (held && !w->mouse_was_down)
        w->mouse_on_panel = vrg_panel_press(&w->panel, x, mx, my);
    else if (held && w->panel.dragging)
        vrg_panel_drag(&w->panel, x, mx, glfwGetKey(w->window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS);
    if (!held)
        w->panel.dragging = w->mouse_on_panel = 0;
    w->mouse_was_down = held;
    const char *file = x == gb ? o->ab : o->graph;
    char name[VRG_CLI_PATH];
    if (w->save_requested == 1)
        (void)vrg_panel_save(&w->panel, x, file);
    else if (w->save_requested == 2) {
        vrg_panel_save_as_name(file, name, sizeof name);
        vrg_panel_save_as_begin(&w->panel, name);
    } else if (w->save_requested == 3)
        (void)vrg_panel_save_as(&w->panel, x, file, w->panel.save_name);
    w->save_requested = 0;
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
    window_state w = {.speed = 8.0f, .divider = 0.5f, .shown = -1, .edit = {.type = VRG_BLOCK_STONE}, .bilinear = o->filter, .scale = o->scale, .fixed_w = o->width,
                      .fixed_h = o->height};
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
    int win_w = (int)o->window_w, win_h = (int)o->window_h;
    if (!win_w) { /* the default fits the screen */
        const GLFWvidmode *mode = glfwGetPrimaryMonitor() ? glfwGetVideoMode(glfwGetPrimaryMonitor()) : NULL;
        win_w = mode && mode->width < 1280 ? mode->width : 1280;
        win_h = mode && mode->height < 720 ? mode->height : 720;
    }
    w.window = glfwCreateWindow(win_w, win_h, "voxrg", NULL, NULL);
    if (!w.window) {
        fprintf(stderr, "error: cannot open a window: use `voxrg render %s`\n", o->graph);
        goto out;
    }
    glfwSetWindowUserPointer(w.window, &w);
    glfwSetKeyCallback(w.window, on_key);
    glfwSetCharCallback(w.window, on_char);
    glfwSetScrollCallback(w.window, on_scroll);
    glfwSetMouseButtonCallback(w.window, on_mouse_button);
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

    choose_scale_auto(&w, o);
    int fb_w, fb_h;
    glfwGetFramebufferSize(w.window, &fb_w, &fb_h);
    VkExtent2D render = render_size(&w, fb_w > 0 ? (uint32_t)fb_w : (uint32_t)win_w, fb_h > 0 ? (uint32_t)fb_h : (uint32_t)win_h);
    /* --show reads its image back: an optional output that nothing else
     * reads (a pass's debug output) is then computed, and listed */
    const char *const *shown_read = o->show ? (const char *const *)&o->show : NULL;
    vrg_graph_desc d = {.path = o->graph, .overrides = o->sets, .override_count = o->set_count, .width = render.width, .height = render.height,
                        .keep_images = 1, .readback = shown_read, .readback_count = o->show ? 1u : 0u};
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
    w.gb = gb;
    say_replayed(&w, 0, g);
    if (gb)
        say_replayed(&w, 1, gb);
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
        w.g = g, w.gb = gb;
        glfwPollEvents();
        /* a saved graph reloads before this frame: the new graph renders
         * before anything reads its images */
        int changed = vrg_graph_poll_changes(g) + (gb ? vrg_graph_poll_changes(gb) : 0);
        if (vrg_graph_source_changed(g))
            (void)vrg_graph_reload(&g); /* a broken graph or plugin is reported; the running one stays */
        if (gb && vrg_graph_source_changed(gb))
            (void)vrg_graph_reload(&gb);
        w.g = g, w.gb = gb; /* a reload freed the graphs they pointed to */
        char why[1024];
        if (changed && gb && vrg_graph_same_world(g, gb, why, sizeof why) != 0) /* an edit may part them: say so, keep going */
            fprintf(stderr, "warning: --ab: %s: the sides no longer show the same frames\n", why);
        double t = now_s();
        float dt = (float)(t - last);
        last = t;
        if (path.count)
            vrg_camera_path_eval(&path, (float)(frames * vrg_graph_frame_seconds(g)), &cam);
        else
            fly(&w, &cam, dt);
        if (record) /* yaw in [-180, 180] (a path's is unwrapped past 360): the path unwraps it again when played */
            fprintf(record, "%.4f  %.3f %.3f %.3f  %.2f %.2f\n", frames * vrg_graph_frame_seconds(g), cam.position[0], cam.position[1],
                    cam.position[2], remainderf(cam.yaw, 360.0f), cam.pitch);
        drive_panel(&w, o, g, gb);
        if (gb && !w.mouse_on_panel && glfwGetMouseButton(w.window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) { /* drag the divider */
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
        if (vrg_graph_reload_ms(g) != reloaded) {
            reloaded = vrg_graph_reload_ms(g);
            fprintf(stderr, "reloaded: %.0f ms from save to frame\n", reloaded);
        }
        frames++;
        int last_frame = o->frames && (uint32_t)frames == o->frames;
        char file[VRG_CLI_PATH] = "";
        if (o->screenshot && last_frame)
            snprintf(file, sizeof file, "%s", o->screenshot);
        else if (w.screenshot_requested && next_screenshot(o->out, &shots, file, sizeof file) != 0)
            w.screenshot_failed = 1;
        w.screenshot_requested = 0;
        if (ensure_staging(&w, 2 * overlay_bytes(&w)) != 0) {
            rc = 1;
            break;
        }
        w.layer = (vrg_overlay_layer){w.staging_map, w.sc.extent.width, w.sc.extent.height};
        VkImage src, src_b = VK_NULL_HANDLE;
        VkExtent2D ext, ext_b = {0, 0};
        VkFormat fmt;
        int as_is = 1; /* the output goes to the swapchain as it is */
        if (show && vrg_graph_image(g, show, &src, &ext, &fmt) == 0) {
            /* integer images (ids) cannot be blitted: say so, show the output */
            int integer = fmt == VK_FORMAT_R32_UINT || fmt == VK_FORMAT_R32G32_UINT || fmt == VK_FORMAT_R32G32B32A32_UINT ||
                          fmt == VK_FORMAT_R16_UINT || fmt == VK_FORMAT_R8_UINT || fmt == VK_FORMAT_R32_SINT;
            if (integer)
                snprintf(w.shown_name, sizeof w.shown_name, "%s (an integer image: showing %s)", show, vrg_graph_output(g));
            else {
                display_mode(&w, show);
                as_is = 0;
            }
        }
        fill_overlay(&w, o, g, gb, dt);
        if ((as_is && vrg_graph_image(g, vrg_graph_output(g), &src, &ext, &fmt) != 0) ||
            (gb && vrg_graph_image(gb, vrg_graph_output(gb), &src_b, &ext_b, &fmt) != 0)) {
            rc = 1;
            break;
        }
        int pr = present(&w, src, ext, src_b, ext_b, file[0] ? file : NULL, as_is);
        if (pr < 0) {
            fprintf(stderr, "error: presenting to the window failed\n");
            rc = 1;
            break;
        }
        int fw, fh;
        glfwGetFramebufferSize(w.window, &fw, &fh);
        if (pr > 0 || (fw > 0 && fh > 0 && ((uint32_t)fw != w.sc.extent.width || (uint32_t)fh != w.sc.extent.height))) {
            vkDeviceWaitIdle(w.dev->device);
            /* the same scale of the new size (a fixed --size stays) */
            if (create_swapchain(&w, w.sc.handle) < 0 || fit_graphs(&w, g, gb, "window resized") != 0) {
                rc = 1;
                break;
            }
            vrg_auto_scale_restart(&w.autos);
        } else if (w.scale_auto && (w.paused || changed))
            vrg_auto_scale_restart(&w.autos); /* not frames rendered as usual */
        else if (w.scale_auto && vrg_auto_scale_frame(&w.autos, dt * 1e3)) { /* the frame rate seen: frames in flight make a frame's own calls no measure */
            char why[96];
            snprintf(why, sizeof why, "auto scale %g (%.1f fps at %g)", w.autos.scale, 1e3 / w.autos.mean_ms, w.scale);
            w.scale = w.autos.scale;
            vkDeviceWaitIdle(w.dev->device);
            if (fit_graphs(&w, g, gb, why) != 0) {
                rc = 1;
                break;
            }
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
        display_free(&w);
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
