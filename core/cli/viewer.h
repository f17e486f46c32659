/* voxrg run's image viewer: how the shown image's values become colours
 * (the view, the channel, the range, the exposure), chosen per image from
 * its name and format and changed by keys; the figures the display stage
 * measures of each frame (each channel's range, NaN and Inf counts, the
 * texel under the cursor); and the words the overlay says about them. The
 * mapping itself runs in shaders/display.comp; this is the host's side. */
#ifndef VOXRG_CLI_VIEWER_H
#define VOXRG_CLI_VIEWER_H
#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>
#include "overlay.h"

/* display.comp's views (the numbers are the shader's) */
typedef enum vrg_view {
    VRG_VIEW_COLOUR,    /* linear colour times 2^exposure, sRGB-encoded (8-bit UNORM: as stored) */
    VRG_VIEW_RANGE,     /* lo..hi to black..white, each channel by its own range for rgb */
    VRG_VIEW_FALSE,     /* one value (rgb: luma) lo..hi through the false-colour map */
    VRG_VIEW_DIRECTION, /* x, y as a vector: hue the direction, brightness the length / hi */
    VRG_VIEW_COUNT,
    VRG_VIEW_AS_IS = 6  /* the output, unchanged (what the swapchain takes): the viewer is off */
} vrg_view;

/* Channels: rgb (all), one of them, or Rec. 709 luma. */
typedef enum vrg_view_channel { VRG_CH_RGB, VRG_CH_R, VRG_CH_G, VRG_CH_B, VRG_CH_A, VRG_CH_LUMA, VRG_CH_COUNT } vrg_view_channel;

/* The figures display.comp keeps: for r, g, b, a, luma and the length of
 * (r, g), the least and greatest finite value; NaN and Inf counts. */
#define VRG_VIEW_STAT_SLOTS 6
#define VRG_VIEW_STAT_LUMA 4
#define VRG_VIEW_STAT_LENGTH 5
typedef struct vrg_view_stats {
    int valid; /* of the image and channel now shown */
    float min[VRG_VIEW_STAT_SLOTS], max[VRG_VIEW_STAT_SLOTS];
    uint32_t nan, inf;
} vrg_view_stats;

typedef struct vrg_viewer {
    vrg_view view;
    vrg_view_channel channel;
    int range_auto; /* the range follows each frame's least and greatest value */
    float lo[4], hi[4]; /* held or set: per channel (rgb in the range view), else [0] */
    float ev;           /* exposure in stops: the colour view's scale, else the range's top at lo + (hi - lo) / 2^ev */
    int changed;        /* a key moved it off the image's default: the output is then shown through it too */
} vrg_viewer;

/* How an image reads best, from its name and format: colour for colour,
 * normals by the fixed range -1..1, positions and two-channel data by each
 * channel's range, depth, history length, moments and variance (alpha) in
 * false colour, motion as direction, one channel (sun, ao) as grey. */
void vrg_viewer_defaults(vrg_viewer *v, const char *name, VkFormat format);
/* Keys: the next (+1) or previous (-1) view and channel; the range auto or
 * held at what it is now; exposure by half stops. */
void vrg_viewer_next_view(vrg_viewer *v, int dir);
void vrg_viewer_next_channel(vrg_viewer *v, int dir);
void vrg_viewer_hold_range(vrg_viewer *v, const vrg_view_stats *s);
void vrg_viewer_expose(vrg_viewer *v, float stops);
/* The range's low end a tenth of its width down (-1) or up (+1), the top
 * kept: the range is held from then on. */
void vrg_viewer_move_low(vrg_viewer *v, const vrg_view_stats *s, int dir);
/* The range the shader maps, per channel (lo, hi: 4 each), exposure
 * applied; never empty (a constant image's range is its value +- 0.5). */
void vrg_viewer_range(const vrg_viewer *v, const vrg_view_stats *s, float lo[4], float hi[4]);
/* The stats slot a channel's scalar reads (the range and false-colour
 * views): 0..3 the channel, luma for rgb or luma, the length for direction. */
int vrg_viewer_slot(const vrg_viewer *v);
/* The words of the scale bar: its caption (what is mapped) and the values
 * at its left end, middle and right end. */
void vrg_viewer_caption(const vrg_viewer *v, const vrg_view_stats *s, int unorm, char *caption, size_t cap);
void vrg_viewer_bar_labels(const vrg_viewer *v, const vrg_view_stats *s, char left[32], char mid[32], char right[32]);
/* Names, as the overlay prints them. */
const char *vrg_view_name(vrg_view view);
const char *vrg_view_channel_name(vrg_view_channel ch);
/* A value as the overlay prints it: %.6g, nan, inf, -inf. */
void vrg_view_value(char *out, size_t cap, double v);
/* The texel's channels as "r 0.5 g 0.25 b 0.5 a 1" (channels the format
 * has; integer formats as integers) from display.comp's raw bits (a float
 * image: float32 bits, an integer one: the uint). */
void vrg_view_texel(char *out, size_t cap, const uint32_t bits[4], uint32_t channels, int is_uint);
/* 1 for the 8-, 16- and 32-bit unsigned integer formats (shown from their bits). */
int vrg_view_format_uint(VkFormat f);
/* 1 for 8-bit UNORM colour: display values already. */
int vrg_view_format_unorm(VkFormat f);
uint32_t vrg_view_format_channels(VkFormat f);
/* From display.comp's order-keeping keys (float bits made unsigned and
 * comparable) back to the float. */
float vrg_view_unkey(uint32_t key);
#endif
