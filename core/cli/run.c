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
#include "viewer.h"
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
    float lo[4], hi[4];
    int32_t bar[4];
    int32_t probe_a[2], probe_b[2];
    int32_t size_a[2], size_b[2];
    int32_t pass, view, channel, uint_a, uint_b;
    float ev;
    int32_t split, flags;
} display_push;
enum { DISPLAY_UNORM_A = 1, DISPLAY_UNORM_B = 2, DISPLAY_LINEAR_OUT = 4, DISPLAY_BILINEAR = 8, DISPLAY_OVERLAY_ON = 16, DISPLAY_B_VIEWED = 32 };
/* display.comp's Stats buffer: greatest keys, ~least keys, NaN, Inf, A's and B's texel under the cursor */
enum { STATS_MAX = 0, STATS_MIN = 6, STATS_NAN = 12, STATS_INF = 13, STATS_PROBE_A = 14, STATS_PROBE_B = 18, STATS_WORDS = 22 };

/* What one side shows this frame: an image of its graph, and how it is read. */
typedef struct display_source {
    VkImage image;
    VkExtent2D ext;
    VkFormat format;
    uint32_t uint_channels; /* an unsigned integer image: copied as it is, shown from its values */
    int unorm;              /* 8-bit UNORM: display values */
    int viewed;             /* through the viewer (else as it is: the output) */
    const char *name;
} display_source;

/* A buffer of the display stage's own (host-visible: read after the frame). */
typedef struct display_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    VkDeviceSize size;
    void *map;
} display_buffer;

/* One of the viewer's keys: what it changes and which way (viewer_key). */
typedef enum { VIEWER_KEY_VIEW, VIEWER_KEY_CHANNEL, VIEWER_KEY_EXPOSE, VIEWER_KEY_HOLD, VIEWER_KEY_LOW } viewer_key_kind;
typedef struct viewer_key_press {
    viewer_key_kind kind;
    int dir; /* +1 or -1 (V, C, the exposure and the low end); 0 for R */
} viewer_key_press;
#define PENDING_KEYS 64

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
    char shown_name[256];
    char showing[160];        /* the image the last frame left readable ("": the output) */
    int shown_pending;        /* another is asked for: shown after the next frame */
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
        display_buffer stats, ints_a, ints_b; /* the frame's figures; A's and B's integer images */
    } disp;
    /* the viewer (viewer.h): how the shown image reads, the figures of the
     * last frame's, the texel under the cursor */
    vrg_viewer viewer;
    vrg_view_stats stats;
    char viewer_for[160]; /* the image the viewer's settings belong to ("" none yet) */
    int viewer_reset;     /* 0: back to the output as it is */
    /* The viewer's keys (V, C, R, , and .) pressed while another image is
     * on its way (Tab, a number key, or a frozen frame's next), in order:
     * they are for that image, applied once it is shown, after its own
     * view is set (viewer_key) */
    viewer_key_press pending[PENDING_KEYS];
    int pending_count;
    int probe_side;       /* the side under the cursor: 0 A, 1 B, -1 none */
    int probe[2][2];      /* its texel in A's and B's shown image */
    display_source shown_src[2];
    /* the inspector (I): every image's value at a pixel of the graph */
    int inspect;        /* on */
    int pinned;         /* a click fixed the pixel (else it follows the cursor) */
    int pin_x, pin_y, pin_side;
    int step;           /* G: one frame while paused */
    uint64_t frames_rendered; /* A's */
    vrg_pixel_value *table; /* the inspector's rows (vrg_graph_read_pixels) */
    uint32_t table_rows, table_cap;
    int table_side, table_x, table_y; /* where they were read: -1 side, none */
    char table_error[160];
    int probed_side;      /* the texel the last frame's figures copied: side (-1 none) */
    int probed[2][2];
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

static int inspect_pixel(window_state *w, vrg_graph *g, int *side, uint32_t *px, uint32_t *py);

/* Left press: remove (with the inspector on: pin the pixel); right press
 * and release without a drag: place.
 * Buttons come as events so that a click within one poll is not missed. */
static void on_mouse_button(GLFWwindow *win, int button, int action, int mods)
{
    (void)mods;
    window_state *w = glfwGetWindowUserPointer(win);
    vrg_world_hit hit;
    double x, y;
    int fw, fh;
    cursor_fb(w, &x, &y, &fw, &fh);
    if (w->inspect && button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && !vrg_panel_contains(&w->panel, x, y)) {
        /* the inspector's click: pin that pixel, or follow the cursor again */
        int side;
        uint32_t px, py;
        w->pinned = !w->pinned && w->g && inspect_pixel(w, w->g, &side, &px, &py);
        if (w->pinned)
            w->pin_side = side, w->pin_x = (int)px, w->pin_y = (int)py;
    } else if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && !vrg_panel_contains(&w->panel, x, y) && !w->gb) {
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

/* A viewer key on the shown image: 1, or 0 where it must wait. R and
 * Shift+, and Shift+. hold the range where the image's figures put it, and
 * an image newly shown through the viewer has none until its first frame
 * (shown as it is, it gets none: they apply at once, as before a frame). */
static int apply_viewer_key(window_state *w, viewer_key_press k)
{
    if ((k.kind == VIEWER_KEY_HOLD || k.kind == VIEWER_KEY_LOW) && !w->stats.valid && w->viewer.view != VRG_VIEW_AS_IS)
        return 0;
    switch (k.kind) {
    case VIEWER_KEY_VIEW:
        vrg_viewer_next_view(&w->viewer, k.dir);
        break;
    case VIEWER_KEY_CHANNEL:
        vrg_viewer_next_channel(&w->viewer, k.dir);
        break;
    case VIEWER_KEY_EXPOSE:
        vrg_viewer_expose(&w->viewer, 0.5f * (float)k.dir);
        break;
    case VIEWER_KEY_HOLD:
        vrg_viewer_hold_range(&w->viewer, &w->stats);
        break;
    case VIEWER_KEY_LOW:
        vrg_viewer_move_low(&w->viewer, &w->stats, k.dir);
        break;
    }
    return 1;
}

/* A viewer key pressed while another image is on its way (Tab, a number
 * key, a frozen frame's next) is that image's: it waits, in order, with
 * any that wait already (else the new image's own view, set when it is
 * shown, would replace what the key did to the old one). A full queue
 * drops the key, saying so. */
static void viewer_key(window_state *w, viewer_key_press k)
{
    if (!w->shown_step && !w->viewer_reset && !w->shown_pending && !w->pending_count && apply_viewer_key(w, k))
        return;
    if (w->pending_count == PENDING_KEYS) {
        fprintf(stderr, "voxrg run: a viewer key ignored: %d keys already wait for the image on its way\n", PENDING_KEYS);
        return;
    }
    w->pending[w->pending_count++] = k;
}

/* The keys that waited, in order, as far as they go now (choose_sources,
 * once the image they are for is shown with its own view). */
static void apply_pending_keys(window_state *w)
{
    int done = 0;
    while (done < w->pending_count && apply_viewer_key(w, w->pending[done]))
        done++;
    memmove(w->pending, w->pending + done, (size_t)(w->pending_count - done) * sizeof w->pending[0]);
    w->pending_count -= done;
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
    else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) {
        w->shown = key - GLFW_KEY_0 - 1, w->shown_step = 0; /* 0: the output, 1..9: the list */
        w->viewer_reset = 1; /* the image's own view, the output as it is */
    } else if (key == GLFW_KEY_V || key == GLFW_KEY_C)
        viewer_key(w, (viewer_key_press){key == GLFW_KEY_V ? VIEWER_KEY_VIEW : VIEWER_KEY_CHANNEL, mods & GLFW_MOD_SHIFT ? -1 : 1});
    else if (key == GLFW_KEY_R)
        viewer_key(w, (viewer_key_press){VIEWER_KEY_HOLD, 0});
    else if ((key == GLFW_KEY_COMMA || key == GLFW_KEY_PERIOD) && (mods & GLFW_MOD_SHIFT))
        viewer_key(w, (viewer_key_press){VIEWER_KEY_LOW, key == GLFW_KEY_PERIOD ? 1 : -1});
    else if (key == GLFW_KEY_COMMA || key == GLFW_KEY_PERIOD)
        viewer_key(w, (viewer_key_press){VIEWER_KEY_EXPOSE, key == GLFW_KEY_PERIOD ? 1 : -1});
    else if (key == GLFW_KEY_I)
        w->inspect = !w->inspect, w->pinned = 0;
    else if (key == GLFW_KEY_G)
        w->step = 1;
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

/* A host-visible buffer of at least size bytes (kept when big enough). */
static int ensure_buffer(window_state *w, display_buffer *b, VkDeviceSize size, VkBufferUsageFlags usage)
{
    if (b->size >= size)
        return 0;
    VkDevice dev = w->dev->device;
    if (b->buffer) {
        vkUnmapMemory(dev, b->memory);
        vkDestroyBuffer(dev, b->buffer, NULL);
        vkFreeMemory(dev, b->memory, NULL);
        *b = (display_buffer){0};
    }
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    if (vkCreateBuffer(dev, &bi, NULL, &b->buffer) != VK_SUCCESS)
        return -1;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, b->buffer, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(w->dev->physical_device, &mp);
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t i = 0; i < mp.memoryTypeCount; i++)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) {
            VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = i};
            if (vkAllocateMemory(dev, &ai, NULL, &b->memory) != VK_SUCCESS)
                break;
            VkResult r = vkBindBufferMemory(dev, b->buffer, b->memory, 0);
            if (r == VK_SUCCESS)
                r = vkMapMemory(dev, b->memory, 0, VK_WHOLE_SIZE, 0, &b->map);
            if (r != VK_SUCCESS || !b->map) {
                fprintf(stderr, "error: binding or mapping the window's display buffer of %llu bytes failed (%d)\n", (unsigned long long)size, r);
                vkDestroyBuffer(dev, b->buffer, NULL);
                vkFreeMemory(dev, b->memory, NULL);
                *b = (display_buffer){0};
                return -1;
            }
            b->size = size;
            return 0;
        }
    fprintf(stderr, "error: no host-visible memory for the window's display buffers\n");
    vkDestroyBuffer(dev, b->buffer, NULL);
    b->buffer = VK_NULL_HANDLE;
    return -1;
}

static void free_buffer(window_state *w, display_buffer *b)
{
    if (!b->buffer)
        return;
    vkUnmapMemory(w->dev->device, b->memory);
    vkDestroyBuffer(w->dev->device, b->buffer, NULL);
    vkFreeMemory(w->dev->device, b->memory, NULL);
    *b = (display_buffer){0};
}

static void display_free(window_state *w)
{
    VkDevice dev = w->dev->device;
    free_buffer(w, &w->disp.stats);
    free_buffer(w, &w->disp.ints_a);
    free_buffer(w, &w->disp.ints_b);
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
    VkDescriptorSetLayoutBinding b[7];
    for (uint32_t i = 0; i < 7; i++) /* the sources, the result, then the overlay, the figures, A's and B's integers */
        b[i] = (VkDescriptorSetLayoutBinding){.binding = i, .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
                                              .descriptorType = i < 2    ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                                : i == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                                         : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 7, .pBindings = b};
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
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4}};
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

/* The display stage for these sources: A's and B's float copies (rgba32f
 * at their render sizes; an integer image goes to its buffer instead), the
 * window-sized result, the figures' buffer, and the descriptors (written
 * each frame: the previous frame has ended, and buffers may have grown). */
static int display_prepare(window_state *w, const display_source *a, const display_source *b)
{
    const VkImageUsageFlags src_usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    const VkBufferUsageFlags ints_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (!w->disp.pipeline && display_pipeline(w, vrg_data_dir()) != 0)
        return -1;
    if ((w->disp.a.extent.width != a->ext.width || w->disp.a.extent.height != a->ext.height) &&
        make_image(w, &w->disp.a, a->ext, VK_FORMAT_R32G32B32A32_SFLOAT, src_usage) != 0)
        return -1;
    if (b->image && (w->disp.b.extent.width != b->ext.width || w->disp.b.extent.height != b->ext.height) &&
        make_image(w, &w->disp.b, b->ext, VK_FORMAT_R32G32B32A32_SFLOAT, src_usage) != 0)
        return -1;
    if ((w->disp.out.extent.width != w->sc.extent.width || w->disp.out.extent.height != w->sc.extent.height) &&
        make_image(w, &w->disp.out, w->sc.extent, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0)
        return -1;
    if (ensure_buffer(w, &w->disp.stats, STATS_WORDS * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT) != 0 ||
        ensure_buffer(w, &w->disp.ints_a, a->uint_channels ? 4ull * a->uint_channels * a->ext.width * a->ext.height : 16, ints_usage) != 0 ||
        ensure_buffer(w, &w->disp.ints_b, b->uint_channels ? 4ull * b->uint_channels * b->ext.width * b->ext.height : 16, ints_usage) != 0)
        return -1;
    VkDescriptorImageInfo ia = {.sampler = w->disp.sampler, .imageView = w->disp.a.view, .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo ib = ia;
    if (b->image)
        ib.imageView = w->disp.b.view;
    VkDescriptorImageInfo out = {.imageView = w->disp.out.view, .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo bufs[4] = {{w->staging, 0, overlay_bytes(w)},
                                      {w->disp.stats.buffer, 0, VK_WHOLE_SIZE},
                                      {w->disp.ints_a.buffer, 0, VK_WHOLE_SIZE},
                                      {w->disp.ints_b.buffer, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet wr[7];
    for (uint32_t i = 0; i < 7; i++)
        wr[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->disp.set, .dstBinding = i, .descriptorCount = 1,
                                       .descriptorType = i < 2    ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                         : i == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                                  : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                       .pImageInfo = i == 0 ? &ia : i == 1 ? &ib : i == 2 ? &out : NULL,
                                       .pBufferInfo = i >= 3 ? &bufs[i - 3] : NULL};
    vkUpdateDescriptorSets(w->dev->device, 7, wr, 0, NULL);
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

static void buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkBufferMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2, .srcStageMask = src_stage, .srcAccessMask = src_access,
                                .dstStageMask = dst_stage, .dstAccessMask = dst_access, .buffer = buffer, .size = VK_WHOLE_SIZE};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1, .pBufferMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

/* src (in TRANSFER_SRC, left so) to what the shader reads: an rgba32f
 * image, or an integer image's texels as they are into its buffer. */
static void to_float(VkCommandBuffer cmd, const display_source *src, VkImage dst, VkBuffer ints)
{
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT, cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    VkExtent2D ext = src->ext;
    if (src->uint_channels) { /* the last frame's display read it */
        buffer_barrier(cmd, ints, cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {ext.width, ext.height, 1}};
        vkCmdCopyImageToBuffer(cmd, src->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ints, 1, &region);
        buffer_barrier(cmd, ints, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        /* the float copy is bound all the same: in the layout it is bound in, unread */
        image_barrier(cmd, dst, cs, 0, cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        return;
    }
    image_barrier(cmd, dst, cs, 0, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkImageBlit blit = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .srcOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                        .dstOffsets = {{0, 0, 0}, {(int32_t)ext.width, (int32_t)ext.height, 1}}};
    vkCmdBlitImage(cmd, src->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    image_barrier(cmd, dst, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, cs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

/* The scale bar's place: along the bottom of the window, under its caption
 * (fill_overlay draws the words around it, the shader the colours); none
 * in a window under VRG_BAR_MIN_W x VRG_BAR_MIN_H, where it would hide
 * most of the picture (width 0). */
#define VRG_BAR_MIN_W 240
#define VRG_BAR_MIN_H 200
static void scale_bar_rect(const window_state *w, int32_t rect[4])
{
    int width = (int)w->sc.extent.width, height = (int)w->sc.extent.height;
    if (width < VRG_BAR_MIN_W || height < VRG_BAR_MIN_H) {
        rect[0] = rect[1] = rect[2] = rect[3] = 0;
        return;
    }
    int bar_w = width - 2 * VRG_OVERLAY_PAD - 16 < 320 ? width - 2 * VRG_OVERLAY_PAD - 16 : 320;
    rect[0] = 8 + VRG_OVERLAY_PAD, rect[2] = bar_w > 16 ? bar_w : 0, rect[3] = 10;
    rect[1] = height - VRG_OVERLAY_PAD - VRG_OVERLAY_LINE_H - 4 - rect[3];
}

/* Records the display stage: A (and B) upscaled to the window with the
 * overlay over them, into disp.out, left in TRANSFER_SRC for the swapchain.
 * With the viewer on, first the figures of the shown images and the texels
 * under the cursor (read after the frame: the next frame's auto range). */
static void display_record(window_state *w, const display_source *a, const display_source *b)
{
    VkCommandBuffer cmd = w->cmd;
    const VkPipelineStageFlags2 xfer = VK_PIPELINE_STAGE_2_TRANSFER_BIT, cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    to_float(cmd, a, w->disp.a.image, w->disp.ints_a.buffer);
    if (b->image)
        to_float(cmd, b, w->disp.b.image, w->disp.ints_b.buffer);
    image_barrier(cmd, w->disp.out.image, xfer, 0, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w->disp.layout, 0, 1, &w->disp.set, 0, NULL);
    uint32_t width = w->sc.extent.width, height = w->sc.extent.height;
    int viewed = a->viewed;
    display_push pc = {.view = viewed ? (int32_t)w->viewer.view : VRG_VIEW_AS_IS, .channel = (int32_t)w->viewer.channel,
                       .uint_a = (int32_t)a->uint_channels, .uint_b = (int32_t)b->uint_channels, .ev = w->viewer.ev,
                       .split = b->image ? (int32_t)(w->divider * (float)width) : (int32_t)width,
                       .size_a = {(int32_t)a->ext.width, (int32_t)a->ext.height}, .size_b = {(int32_t)b->ext.width, (int32_t)b->ext.height},
                       .probe_a = {w->probe[0][0], w->probe[0][1]}, .probe_b = {w->probe[1][0], w->probe[1][1]}};
    pc.flags = (a->unorm ? DISPLAY_UNORM_A : 0) | (b->unorm ? DISPLAY_UNORM_B : 0) | (w->srgb ? DISPLAY_LINEAR_OUT : 0) |
               (w->bilinear ? DISPLAY_BILINEAR : 0) | (!w->hide_overlay ? DISPLAY_OVERLAY_ON : 0) | (b->viewed ? DISPLAY_B_VIEWED : 0);
    w->probed_side = viewed ? w->probe_side : -1;
    memcpy(w->probed, w->probe, sizeof w->probed);
    if (viewed) {
        vrg_viewer_range(&w->viewer, &w->stats, pc.lo, pc.hi);
        scale_bar_rect(w, pc.bar);
        /* the figures start from none: the last frame's reads of them ended */
        buffer_barrier(cmd, w->disp.stats.buffer, cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, xfer,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdFillBuffer(cmd, w->disp.stats.buffer, 0, STATS_WORDS * 4, 0);
        buffer_barrier(cmd, w->disp.stats.buffer, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, cs,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        uint32_t mw = a->ext.width > b->ext.width ? a->ext.width : b->ext.width, mh = a->ext.height > b->ext.height ? a->ext.height : b->ext.height;
        vkCmdPushConstants(cmd, w->disp.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
        vkCmdDispatch(cmd, (mw + 7) / 8, (mh + 7) / 8, 1);
        buffer_barrier(cmd, w->disp.stats.buffer, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }
    pc.pass = 1;
    vkCmdPushConstants(cmd, w->disp.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
    image_barrier(cmd, w->disp.out.image, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, xfer, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

/* After the frame: the figures the display stage measured, for the next
 * frame's range and the overlay. */
static void read_stats(window_state *w)
{
    const uint32_t *u = w->disp.stats.map;
    vrg_view_stats *s = &w->stats;
    for (int i = 0; i < VRG_VIEW_STAT_SLOTS; i++) {
        s->max[i] = u[STATS_MAX + i] ? vrg_view_unkey(u[STATS_MAX + i]) : 0.0f;
        s->min[i] = u[STATS_MIN + i] ? vrg_view_unkey(~u[STATS_MIN + i]) : 1.0f; /* none finite: min > max */
    }
    s->nan = u[STATS_NAN], s->inf = u[STATS_INF];
    s->valid = 1;
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
static int present(window_state *w, const display_source *a, const display_source *b, const char *screenshot)
{
    VkDevice dev = w->dev->device;
    uint32_t index;
    VkResult res = vkAcquireNextImageKHR(dev, w->sc.handle, UINT64_MAX, w->acquired, VK_NULL_HANDLE, &index);
    if (res == VK_ERROR_OUT_OF_DATE_KHR)
        return 1;
    if (res != VK_SUCCESS && res != VK_SUBOPTIMAL_KHR)
        return -1;
    if (display_prepare(w, a, b) != 0)
        return -1;
    VkImage dst = w->sc.images[index];
    vkResetCommandBuffer(w->cmd, 0);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(w->cmd, &bi);
    display_record(w, a, b);
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
    if (a->viewed)
        read_stats(w);
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
        for (uint32_t i = 0; i < vrg_graph_pass_count(x) && ov->lines < VRG_OVERLAY_LINES - 14; i++) /* room for the keys */
            if (vrg_graph_pass_ms(x, i) >= 0) {
                snprintf(line, sizeof line, "  %-18s %7.2f ms", vrg_graph_pass_name(x, i), vrg_graph_pass_ms(x, i));
                vrg_overlay_line(ov, line);
            }
    }
    static const char *keys[] = {
        "wasd space shift: fly, right drag: look, scroll + -: speed",
        "left click: remove block, right click: place, e q: block type",
        "ctrl+z: undo, ctrl+y ctrl+shift+z: redo",
        "tab 0-9: show an image, t [ ]: day, p: screenshot",
        "v c: view, channel, r: hold range, , .: exposure (shift: low end)",
        "i: inspect (click: pin), f: freeze, g: one more frame",
        "n: nearest/bilinear, h: hide, f1: these details, esc: quit",
        "m f2: parameters (/: filter, pgup pgdn: pass, b: edit a or b)",
        "ctrl+s: save into the graph, ctrl+shift+s: save as a new file",
    };
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        vrg_overlay_line(ov, keys[i]);
}

/* A graph's label: its file's name (the folder is in the title). */
static const char *file_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash && slash[1] ? slash + 1 : path;
}

/* --ab: each side's label over its own half, the graph's file and the image
 * shown, kept inside the window however far the divider went (one side's
 * under the other's where both do not fit). */
static void ab_labels(window_state *w, const vrg_run_options *o, vrg_overlay_layer *l)
{
    static const uint8_t white[4] = {255, 255, 255, 255}, back[4] = {0, 0, 0, 140};
    int split = (int)(w->divider * (float)l->width), width = (int)l->width;
    char label[2][256];
    for (int k = 0; k < 2; k++) {
        const display_source *s = &w->shown_src[k];
        int other = k && s->name && w->shown_src[0].name && strcmp(s->name, w->shown_src[0].name) != 0;
        snprintf(label[k], sizeof label[k], "%c: %s%s%s", k ? 'B' : 'A', file_name(k ? o->ab : o->graph), other ? ", " : "",
                 other ? s->name : "");
    }
    int lw[2] = {vrg_overlay_text_width(label[0]) + 8, vrg_overlay_text_width(label[1]) + 8};
    int x[2] = {split - lw[0] - 4, split + 4}, y[2] = {4, 4};
    for (int k = 0; k < 2; k++)
        x[k] = x[k] + lw[k] > width ? width - lw[k] : x[k], x[k] = x[k] < 0 ? 0 : x[k];
    if (x[0] + lw[0] > x[1]) /* they would overlap: B's under A's */
        y[1] += VRG_OVERLAY_LINE_H + 4;
    for (int k = 0; k < 2; k++) {
        vrg_overlay_box(l, x[k], y[k], lw[k], VRG_OVERLAY_LINE_H + 4, back);
        vrg_overlay_text(l, x[k] + 4, y[k] + 2, label[k], white);
    }
}

/* The viewer's line: the value under the cursor in the image shown on that
 * side, as stored (the last frame's). */
static void viewer_lines(window_state *w, vrg_overlay *ov)
{
    int k = w->probed_side;
    if (k < 0 || !w->stats.valid)
        return;
    const display_source *s = &w->shown_src[k];
    if (!s->viewed || !s->name)
        return;
    const uint32_t *u = (const uint32_t *)w->disp.stats.map + (k ? STATS_PROBE_B : STATS_PROBE_A);
    char value[160], line[512];
    uint32_t ch = s->uint_channels ? s->uint_channels : vrg_view_format_channels(s->format);
    vrg_view_texel(value, sizeof value, u, ch, s->uint_channels != 0);
    snprintf(line, sizeof line, "%s%s %d,%d: %s", w->gb ? (k ? "B " : "A ") : "", s->name, w->probed[k][0], w->probed[k][1], value);
    vrg_overlay_wrap(ov, line, (int)w->layer.width);
}

/* The scale bar's words: what is mapped above it, the values at its ends
 * and middle under it (the shader draws its colours between). */
static void scale_bar_words(window_state *w, vrg_overlay_layer *l)
{
    static const uint8_t white[4] = {255, 255, 255, 255}, back[4] = {0, 0, 0, 160};
    int32_t bar[4];
    scale_bar_rect(w, bar);
    if (!bar[2])
        return;
    char what[320], caption[512], lo[32], mid[32], hi[32];
    vrg_viewer_caption(&w->viewer, &w->stats, w->shown_src[0].unorm, what, sizeof what);
    snprintf(caption, sizeof caption, "%s: %s", w->shown_src[0].name, what); /* the name whole here, wrapped, whatever the window */
    vrg_viewer_bar_labels(&w->viewer, &w->stats, lo, mid, hi);
    vrg_overlay cap;
    vrg_overlay_clear(&cap);
    vrg_overlay_wrap(&cap, caption, (int)l->width - bar[0] + 8);
    int top = bar[1] - 4 - cap.lines * VRG_OVERLAY_LINE_H - VRG_OVERLAY_PAD;
    int box_w = bar[2] + 16;
    for (int i = 0; i < cap.lines; i++)
        box_w = vrg_overlay_text_width(cap.text[i]) + 2 * VRG_OVERLAY_PAD > box_w ? vrg_overlay_text_width(cap.text[i]) + 2 * VRG_OVERLAY_PAD : box_w;
    vrg_overlay_box(l, bar[0] - 8, top, box_w, (int)l->height - top, back);
    for (int i = 0; i < cap.lines; i++)
        vrg_overlay_text(l, bar[0] - 8 + VRG_OVERLAY_PAD, top + VRG_OVERLAY_PAD + i * VRG_OVERLAY_LINE_H, cap.text[i], white);
    int ly = bar[1] + bar[3] + 3;
    vrg_overlay_text(l, bar[0], ly, lo, white);
    int mw = vrg_overlay_text_width(mid), hw = vrg_overlay_text_width(hi);
    if (bar[0] + vrg_overlay_text_width(lo) + 12 < bar[0] + bar[2] / 2 - mw / 2 && bar[0] + bar[2] / 2 + mw / 2 + 12 < bar[0] + bar[2] - hw)
        vrg_overlay_text(l, bar[0] + bar[2] / 2 - mw / 2, ly, mid, white);
    vrg_overlay_text(l, bar[0] + bar[2] - hw, ly, hi, white);
}

/* The inspector's pixel: the pinned one, or the one under the cursor, in
 * the graph's pixels, and the side it is on; 0 when there is none. */
static int inspect_pixel(window_state *w, vrg_graph *g, int *side, uint32_t *px, uint32_t *py)
{
    uint32_t rw, rh;
    vrg_graph_size(g, &rw, &rh);
    if (w->pinned) {
        *side = w->pin_side, *px = (uint32_t)w->pin_x, *py = (uint32_t)w->pin_y;
        return *px < rw && *py < rh; /* a resize may have left it outside */
    }
    double x, y;
    int fw, fh;
    cursor_fb(w, &x, &y, &fw, &fh);
    if (w->looking || x < 0 || y < 0 || x >= w->sc.extent.width || y >= w->sc.extent.height)
        return 0;
    *side = w->gb && x >= (int)(w->divider * (float)w->sc.extent.width);
    *px = (uint32_t)floor((floor(x) + 0.5) * rw / w->sc.extent.width);
    *py = (uint32_t)floor((floor(y) + 0.5) * rh / w->sc.extent.height);
    return 1;
}

/* I: every image's value at the pixel, read after this frame (the last one
 * rendered when frozen). */
static void inspect_read(window_state *w, vrg_graph *g, vrg_graph *gb)
{
    int side;
    uint32_t x, y;
    w->table_rows = 0, w->table_side = -1, w->table_error[0] = '\0';
    if (!inspect_pixel(w, g, &side, &x, &y))
        return;
    vrg_graph *x_graph = side && gb ? gb : g;
    int n = vrg_graph_read_pixels(x_graph, x, y, w->table, w->table_cap);
    if (n > (int)w->table_cap) { /* room for all of them, and again */
        vrg_pixel_value *more = realloc(w->table, sizeof *more * (size_t)n);
        if (!more) {
            snprintf(w->table_error, sizeof w->table_error, "out of memory for %d rows", n);
            return;
        }
        w->table = more, w->table_cap = (uint32_t)n;
        n = vrg_graph_read_pixels(x_graph, x, y, w->table, w->table_cap);
    }
    if (n < 0) {
        snprintf(w->table_error, sizeof w->table_error, "pixel %u,%u not read (see the terminal)", x, y);
        return;
    }
    w->table_rows = (uint32_t)n, w->table_side = side, w->table_x = (int)x, w->table_y = (int)y;
}

/* The inspector's table: a title (the pixel, how it is chosen, the frame),
 * then a row per image in schedule order: pass, resource, value. */
static void inspector_lines(window_state *w, vrg_overlay *ov)
{
    char line[512];
    if (w->table_side < 0) {
        snprintf(line, sizeof line, "inspect: %s", w->table_error[0] ? w->table_error : "move the cursor over the picture, or click a pixel");
        vrg_overlay_wrap(ov, line, (int)w->layer.width);
        return;
    }
    snprintf(line, sizeof line, "inspect %s%d,%d (%s), frame %llu%s", w->gb ? (w->table_side ? "B " : "A ") : "", w->table_x, w->table_y,
             w->pinned ? "pinned: click to follow the cursor" : "under the cursor: click to pin", (unsigned long long)w->frames_rendered,
             w->paused ? " frozen (f: go on, g: one more)" : "");
    vrg_overlay_wrap(ov, line, (int)w->layer.width);
    int pass_w = 4, res_w = 8;
    for (uint32_t i = 0; i < w->table_rows; i++) {
        const vrg_pixel_value *r = &w->table[i];
        int pl = (int)strlen(r->pass), rl = (int)strlen(r->resource) + (r->prev ? 5 : 0);
        pass_w = pl > pass_w ? pl : pass_w, res_w = rl > res_w ? rl : res_w;
    }
    pass_w = pass_w > 24 ? 24 : pass_w, res_w = res_w > 32 ? 32 : res_w;
    uint32_t drawn = 0;
    int room = ((int)w->layer.height - 2 * VRG_OVERLAY_PAD) / VRG_OVERLAY_LINE_H - 2; /* lines the window holds, less the rates' and this one's */
    room = room > VRG_OVERLAY_LINES - 2 ? VRG_OVERLAY_LINES - 2 : room;
    for (uint32_t i = 0; i < w->table_rows && ov->lines < room; i++, drawn++) {
        const vrg_pixel_value *r = &w->table[i];
        char res[160], value[160] = "";
        snprintf(res, sizeof res, "%s%s", r->resource, r->prev ? "@prev" : "");
        size_t n = 0;
        for (uint32_t c = 0; r->kept && c < r->channels && c < 4 && n < sizeof value; c++) {
            char one[40];
            if (r->is_uint)
                snprintf(one, sizeof one, "%.0f", r->value[c]);
            else
                vrg_view_value(one, sizeof one, r->value[c]);
            int k = snprintf(value + n, sizeof value - n, "%s%s", c ? " " : "", one);
            n += k > 0 ? (size_t)k : 0;
        }
        size_t rn = strlen(r->resource);
        int motion = r->channels == 2 && !r->prev && r->kept && (!strcmp(r->resource, "motion") || (rn > 7 && !strcmp(r->resource + rn - 7, ".motion")));
        if (motion && isfinite(r->value[0]) && isfinite(r->value[1]) && n < sizeof value) /* passes/gbuffer: p saw last frame's point at p + 0.5 - motion */
            snprintf(value + n, sizeof value - n, " (last frame at %.0f,%.0f)", floor(r->x + 0.5 - r->value[0]), floor(r->y + 0.5 - r->value[1]));
        snprintf(line, sizeof line, "%-*.*s %-*.*s %s", pass_w, pass_w, r->pass, res_w, res_w, res, r->kept ? value : "(not kept)");
        vrg_overlay_wrap(ov, line, (int)w->layer.width);
    }
    if (drawn < w->table_rows) { /* said, not dropped silently */
        snprintf(line, sizeof line, "(%u more row%s: a taller window shows them)", w->table_rows - drawn, w->table_rows - drawn == 1 ? "" : "s");
        vrg_overlay_line(ov, line);
    }
}

/* The overlay layer: one compact line (rates, what is shown, the last
 * reload), the reload error if any, --ab's labels over their halves, the
 * details on F1 and the panel on M. */
static void fill_overlay(window_state *w, const vrg_run_options *o, vrg_graph *g, vrg_graph *gb, float dt)
{
    static double smooth_ms = 0;
    smooth_ms = smooth_ms > 0 ? 0.9 * smooth_ms + 0.1 * dt * 1e3 : dt * 1e3;
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
    char first[512];
    snprintf(first, sizeof first, "%.1f fps %.1f ms  %ux%u%s  %s%s%s", smooth_ms > 0 ? 1e3 / smooth_ms : 0.0, smooth_ms, rw, rh, scale,
             w->shown_name, reload, w->paused ? "  paused" : "");
    vrg_overlay_line(&ov, first);
    if (w->shown_pending)
        vrg_overlay_line(&ov, "another image from the next frame (g steps one)");
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
    if (w->shown_src[0].viewed)
        viewer_lines(w, &ov);
    if (w->inspect)
        inspector_lines(w, &ov);
    if (w->details)
        fill_details(&ov, o, g, gb);
    int bw, bh;
    if (gb) /* each side's label at the top of its own half */
        ab_labels(w, o, l);
    vrg_overlay_draw(&ov, l, 0, gb ? VRG_OVERLAY_LINE_H + 8 : 0, -1, &bw, &bh);
    if (w->shown_src[0].viewed)
        scale_bar_words(w, l);
    if (w->panel.open)
        vrg_panel_draw(&w->panel, w->panel.side && gb ? gb : g, w->panel.side && gb ? o->ab : o->graph, l);
}

static int has_image(const vrg_graph *g, const char *name)
{
    for (uint32_t i = 0; i < vrg_graph_image_count(g); i++)
        if (strcmp(vrg_graph_image_name(g, i), name) == 0)
            return 1;
    return 0;
}

/* Integer formats the display stage reads from their 32-bit words; others
 * (16- and 8-bit, signed) it cannot show. */
static uint32_t uint_channels(VkFormat f)
{
    return f == VK_FORMAT_R32_UINT ? 1 : f == VK_FORMAT_R32G32_UINT ? 2 : f == VK_FORMAT_R32G32B32A32_UINT ? 4 : 0;
}

static int shown_integer(VkFormat f)
{
    return f == VK_FORMAT_R16_UINT || f == VK_FORMAT_R8_UINT || f == VK_FORMAT_R32_SINT || f == VK_FORMAT_R16_SINT || f == VK_FORMAT_R8_SINT ||
           f == VK_FORMAT_R32G32_SINT || f == VK_FORMAT_R32G32B32A32_SINT || f == VK_FORMAT_R16G16B16A16_UINT || f == VK_FORMAT_R8G8B8A8_UINT;
}

static int source_of(vrg_graph *g, const char *name, display_source *s)
{
    *s = (display_source){.name = name};
    if (vrg_graph_image(g, name, &s->image, &s->ext, &s->format) != 0)
        return -1;
    s->uint_channels = uint_channels(s->format);
    s->unorm = vrg_view_format_unorm(s->format);
    return 0;
}

/* This frame's sources: A's shown image (or its output), B's image of the
 * same name (or its output), whether the viewer maps them, the viewer's
 * settings for a newly shown image, and the texel under the cursor. */
static int choose_sources(window_state *w, vrg_graph *g, vrg_graph *gb, const char *show, display_source src[2])
{
    const char *name = show ? show : vrg_graph_output(g);
    if (source_of(g, name, &src[0]) != 0)
        return -1;
    if (shown_integer(src[0].format)) { /* as before the viewer: said, and the output shown */
        snprintf(w->shown_name, sizeof w->shown_name, "%s (a %s image the viewer cannot show: showing %s)", show, vrg_format_label(src[0].format),
                 vrg_graph_output(g));
        show = NULL;
        if (source_of(g, name = vrg_graph_output(g), &src[0]) != 0)
            return -1;
    }
    if (w->viewer_reset || strcmp(w->viewer_for, name) != 0) { /* another image: the view it reads best in */
        vrg_viewer_defaults(&w->viewer, name, src[0].format);
        if (!show) /* the output as it is, unless a key asks otherwise */
            w->viewer.view = VRG_VIEW_AS_IS;
        snprintf(w->viewer_for, sizeof w->viewer_for, "%s", name);
        w->stats.valid = 0;
        w->viewer_reset = 0;
    }
    if (!w->shown_pending)
        apply_pending_keys(w);
    src[0].viewed = w->viewer.view != VRG_VIEW_AS_IS;
    if (gb) {
        const char *name_b = show && has_image(gb, show) ? show : vrg_graph_output(gb);
        if (source_of(gb, name_b, &src[1]) != 0)
            return -1;
        /* B through A's view where it shows the same image (its output when A shows A's) */
        src[1].viewed = src[0].viewed && (!show || name_b == show);
        if (!src[1].viewed)
            src[1].uint_channels = 0;
    }
    /* the texel under the cursor on each side (the shader copies it) */
    double x, y;
    int fw, fh;
    cursor_fb(w, &x, &y, &fw, &fh);
    int split = gb ? (int)(w->divider * (float)w->sc.extent.width) : (int)w->sc.extent.width;
    int inside = !w->looking && x >= 0 && y >= 0 && x < w->sc.extent.width && y < w->sc.extent.height;
    w->probe_side = inside ? (x >= split) : -1;
    for (int k = 0; k < 2; k++) {
        w->probe[k][0] = w->probe[k][1] = -1;
        if (inside && src[k].image && w->probe_side == k) {
            w->probe[k][0] = (int)floor((floor(x) + 0.5) * src[k].ext.width / w->sc.extent.width);
            w->probe[k][1] = (int)floor((floor(y) + 0.5) * src[k].ext.height / w->sc.extent.height);
        }
    }
    w->shown_src[0] = src[0], w->shown_src[1] = src[1];
    return 0;
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
                        .keep_images = 1, .readback = shown_read, .readback_count = o->show ? 1u : 0u, .check_finite = o->check_finite};
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
        vrg_graph_desc db = {.path = o->ab, .width = aw, .height = ah, .keep_images = 1,
                             .check_finite = o->check_finite}; /* Tab shows B's image of the same name */
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
        if (gb && !w.mouse_on_panel && !w.inspect && glfwGetMouseButton(w.window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) { /* drag the divider */
            int ww, wh;
            double mx, my;
            glfwGetWindowSize(w.window, &ww, &wh);
            glfwGetCursorPos(w.window, &mx, &my);
            w.divider = ww > 0 ? (float)(mx / ww) : 0.5f;
            w.divider = w.divider < 0 ? 0 : w.divider > 1 ? 1 : w.divider;
        }
        /* which image A shows: the output, or another of its images; B the
         * same where its graph has one of that name. A frozen frame keeps
         * the image its last frame left readable: another is shown from the
         * next frame on (G steps one). */
        int count = (int)vrg_graph_image_count(g);
        if (w.shown_step)
            w.shown = (w.shown + 1 + w.shown_step + count + 1) % (count + 1) - 1;
        w.shown_step = 0;
        if (w.shown >= count)
            w.shown = -1;
        const char *want = w.shown >= 0 ? vrg_graph_image_name(g, (uint32_t)w.shown) : NULL;
        if (want && strcmp(want, vrg_graph_output(g)) == 0)
            want = NULL;
        int render = !w.paused || w.step;
        w.step = 0;
        if (render) {
            snprintf(w.showing, sizeof w.showing, "%s", want ? want : "");
            vrg_graph_show(g, want);
            if (gb)
                vrg_graph_show(gb, want && has_image(gb, want) ? want : NULL);
        }
        const char *show = w.showing[0] ? w.showing : NULL;
        snprintf(w.shown_name, sizeof w.shown_name, "%s", show ? show : vrg_graph_output(g));
        w.shown_pending = strcmp(want ? want : "", w.showing) != 0;
        vrg_graph *both[2] = {g, gb};
        for (int k = 0; k < 2 && both[k]; k++) {
            double v;
            if (w.day_toggle && vrg_graph_get_param(both[k], "scene.day_length", &v) == 0)
                vrg_graph_set_param(both[k], "scene.day_length", v > 0 ? 0 : 120); /* a day in two minutes */
            if (w.time_step != 0 && vrg_graph_get_param(both[k], "scene.time_of_day", &v) == 0)
                vrg_graph_set_param(both[k], "scene.time_of_day", fmod(v + w.time_step + 24.0, 24.0));
            vrg_graph_set_camera(both[k], &cam);
            if (render && vrg_graph_frame(both[k]) != 0)
                rc = 1;
        }
        w.frames_rendered += (uint64_t)render;
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
        if (w.inspect) /* before the display copies the shown image: the table's reads leave the images as they were */
            inspect_read(&w, g, gb);
        display_source src[2] = {{0}, {0}};
        if (choose_sources(&w, g, gb, show, src) != 0) {
            rc = 1;
            break;
        }
        fill_overlay(&w, o, g, gb, dt);
        int pr = present(&w, &src[0], &src[1], file[0] ? file : NULL);
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
        free(w.table);
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
