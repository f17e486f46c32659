/* voxrg run's image viewer, the host's side (viewer.h): the view each
 * image starts with, the keys' changes, the range the shader maps and the
 * words of the scale bar. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "viewer.h"

static const char *const view_names[VRG_VIEW_COUNT] = {"colour", "range", "false colour", "direction"};
static const char *const channel_names[VRG_CH_COUNT] = {"rgb", "r", "g", "b", "a", "luma"};

const char *vrg_view_name(vrg_view view) { return view == VRG_VIEW_AS_IS ? "as is" : view_names[view]; }
const char *vrg_view_channel_name(vrg_view_channel ch) { return channel_names[ch]; }

int vrg_view_format_uint(VkFormat f)
{
    return f == VK_FORMAT_R32_UINT || f == VK_FORMAT_R32G32_UINT || f == VK_FORMAT_R32G32B32A32_UINT || f == VK_FORMAT_R16_UINT ||
           f == VK_FORMAT_R8_UINT;
}

int vrg_view_format_unorm(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_R8_UNORM || f == VK_FORMAT_R8G8_UNORM;
}

uint32_t vrg_view_format_channels(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT: return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT: return 2;
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32: return 3;
    default: return 4;
    }
}

void vrg_viewer_defaults(vrg_viewer *v, const char *name, VkFormat format)
{
    *v = (vrg_viewer){.view = VRG_VIEW_COLOUR, .channel = VRG_CH_RGB, .range_auto = 1};
    uint32_t ch = vrg_view_format_channels(format);
    size_t n = strlen(name);
    /* the temporal passes' debug outputs (default names PASS.SLOT), as grey
     * over the range their values take */
    static const struct {
        const char *suffix;
        vrg_view_channel channel;
        float lo, hi;
    } debug[] = {
        {".disocclusion", VRG_CH_R, 0, 1},    /* 1 where the history restarted */
        {".reprojection", VRG_CH_A, 0, 4},    /* how the history was read: 0 none .. 4 */
        {".clamp", VRG_CH_R, 0, 0.25f},       /* how far the clamp moved the history */
        {".occupancy", VRG_CH_R, 0, 64},      /* the samples a surface cache's cells hold */
        {".variance", VRG_CH_R, 0, 0.05f},    /* svgf_variance's and mean_variance's variance output */
    };
    for (size_t i = 0; i < sizeof debug / sizeof debug[0]; i++) {
        size_t k = strlen(debug[i].suffix);
        if (n >= k && strcmp(name + n - k, debug[i].suffix) == 0) {
            v->view = VRG_VIEW_RANGE, v->channel = debug[i].channel, v->range_auto = 0;
            v->lo[0] = debug[i].lo, v->hi[0] = debug[i].hi;
            return;
        }
    }
    if (strstr(name, "normal")) { /* unit vectors: the fixed range shows their direction as colour */
        v->view = VRG_VIEW_RANGE, v->range_auto = 0;
        for (int c = 0; c < 4; c++)
            v->lo[c] = -1, v->hi[c] = 1;
    } else if (strstr(name, "motion"))
        v->view = VRG_VIEW_DIRECTION;
    else if (strstr(name, "variance") && ch == 4) /* svgf_variance: colour, its variance in alpha */
        v->view = VRG_VIEW_FALSE, v->channel = VRG_CH_A;
    else if (strstr(name, "depth") || strstr(name, "length") || strstr(name, "moments") || strstr(name, "variance"))
        v->view = VRG_VIEW_FALSE, v->channel = VRG_CH_R; /* moments: the mean's */
    else if (vrg_view_format_uint(format) || strstr(name, "position") || ch == 2)
        v->view = VRG_VIEW_RANGE; /* data: each channel by its own range */
    else if (ch == 1) /* sun, ao: one value as grey, not red */
        v->view = VRG_VIEW_RANGE, v->channel = VRG_CH_R;
}

void vrg_viewer_next_view(vrg_viewer *v, int dir)
{
    v->view = (vrg_view)(((int)(v->view == VRG_VIEW_AS_IS ? VRG_VIEW_COLOUR : v->view) + dir + VRG_VIEW_COUNT) % VRG_VIEW_COUNT);
    v->changed = 1;
}

void vrg_viewer_next_channel(vrg_viewer *v, int dir)
{
    v->channel = (vrg_view_channel)(((int)v->channel + dir + VRG_CH_COUNT) % VRG_CH_COUNT);
    if (v->view == VRG_VIEW_AS_IS)
        v->view = VRG_VIEW_COLOUR;
    v->changed = 1;
}

void vrg_viewer_expose(vrg_viewer *v, float stops)
{
    v->ev += stops;
    if (v->view == VRG_VIEW_AS_IS)
        v->view = VRG_VIEW_COLOUR;
    v->changed = 1;
}

int vrg_viewer_slot(const vrg_viewer *v)
{
    if (v->view == VRG_VIEW_DIRECTION)
        return VRG_VIEW_STAT_LENGTH;
    if (v->channel == VRG_CH_RGB)
        return v->view == VRG_VIEW_RANGE ? -1 : VRG_VIEW_STAT_LUMA; /* -1: each channel its own */
    return v->channel == VRG_CH_LUMA ? VRG_VIEW_STAT_LUMA : (int)v->channel - 1;
}

/* The range before exposure: held, or this frame's (per channel for the
 * range view of rgb); 0..1 until a frame was measured. */
static void base_range(const vrg_viewer *v, const vrg_view_stats *s, float lo[4], float hi[4])
{
    int slot = vrg_viewer_slot(v);
    for (int c = 0; c < 4; c++) {
        int from = slot < 0 ? c : slot;
        if (!v->range_auto)
            lo[c] = v->lo[slot < 0 ? c : 0], hi[c] = v->hi[slot < 0 ? c : 0];
        else if (s && s->valid && s->max[from] >= s->min[from])
            lo[c] = s->min[from], hi[c] = s->max[from];
        else
            lo[c] = 0, hi[c] = 1;
        if (v->view == VRG_VIEW_DIRECTION)
            lo[c] = 0; /* a length: from none */
        if (!(hi[c] > lo[c])) { /* one value: it sits mid-range */
            float at = isfinite(lo[c]) ? lo[c] : 0;
            lo[c] = at - 0.5f, hi[c] = at + 0.5f;
        }
    }
}

void vrg_viewer_range(const vrg_viewer *v, const vrg_view_stats *s, float lo[4], float hi[4])
{
    if (v->view == VRG_VIEW_COLOUR) { /* what the bar shows: linear 0 .. the value that shows white */
        for (int c = 0; c < 4; c++)
            lo[c] = 0, hi[c] = exp2f(-v->ev);
        return;
    }
    base_range(v, s, lo, hi);
    for (int c = 0; c < 4; c++)
        hi[c] = lo[c] + (hi[c] - lo[c]) * exp2f(-v->ev);
}

void vrg_viewer_hold_range(vrg_viewer *v, const vrg_view_stats *s)
{
    if (v->range_auto) { /* held where it is now */
        float lo[4], hi[4];
        base_range(v, s, lo, hi);
        memcpy(v->lo, lo, sizeof lo);
        memcpy(v->hi, hi, sizeof hi);
    }
    v->range_auto = !v->range_auto;
    if (v->view == VRG_VIEW_AS_IS)
        v->view = VRG_VIEW_COLOUR;
    v->changed = 1;
}

void vrg_viewer_move_low(vrg_viewer *v, const vrg_view_stats *s, int dir)
{
    if (v->range_auto) /* held where it is, then moved */
        vrg_viewer_hold_range(v, s);
    for (int c = 0; c < 4; c++) {
        float lo = v->lo[c] + 0.1f * (float)dir * (v->hi[c] - v->lo[c]);
        v->lo[c] = lo < v->hi[c] ? lo : v->lo[c]; /* never past the top */
    }
    if (v->view == VRG_VIEW_AS_IS)
        v->view = VRG_VIEW_COLOUR;
    v->changed = 1;
}

void vrg_view_value(char *out, size_t cap, double v)
{
    if (isnan(v))
        snprintf(out, cap, "nan");
    else if (isinf(v))
        snprintf(out, cap, "%sinf", v < 0 ? "-" : "");
    else
        snprintf(out, cap, "%.6g", v);
}

/* The range view of rgb with one range for all three channels: said as one. */
static int one_range(const float lo[4], const float hi[4]) { return lo[0] == lo[1] && lo[1] == lo[2] && hi[0] == hi[1] && hi[1] == hi[2]; }

void vrg_viewer_caption(const vrg_viewer *v, const vrg_view_stats *s, int unorm, char *caption, size_t cap)
{
    float lo[4], hi[4];
    vrg_viewer_range(v, s, lo, hi);
    int n = 0;
    const char *ch = channel_names[v->channel];
    if (v->view == VRG_VIEW_COLOUR)
        n = snprintf(caption, cap, "colour%s%s%s", v->channel == VRG_CH_RGB ? "" : " of ", v->channel == VRG_CH_RGB ? "" : ch,
                     unorm ? " as stored" : ", linear as sRGB");
    else if (v->view == VRG_VIEW_DIRECTION)
        n = snprintf(caption, cap, "direction of (r, g) as hue, length as brightness (full at %.4g)", hi[0]);
    else if (vrg_viewer_slot(v) < 0 && !one_range(lo, hi)) {
        char l[3][32], h[3][32];
        for (int c = 0; c < 3; c++)
            vrg_view_value(l[c], sizeof l[c], lo[c]), vrg_view_value(h[c], sizeof h[c], hi[c]);
        n = snprintf(caption, cap, "each channel: r %s..%s g %s..%s b %s..%s", l[0], h[0], l[1], h[1], l[2], h[2]);
    } else if (vrg_viewer_slot(v) < 0)
        n = snprintf(caption, cap, "rgb");
    else
        n = snprintf(caption, cap, "%s of %s", v->view == VRG_VIEW_FALSE ? "false colour" : "grey", v->channel == VRG_CH_RGB ? "luma" : ch);
    if (n < 0 || (size_t)n >= cap)
        return;
    if (v->view != VRG_VIEW_COLOUR)
        n += snprintf(caption + n, cap - (size_t)n, ", %s", v->range_auto ? "auto" : "held");
    if (v->ev != 0 && (size_t)n < cap)
        n += snprintf(caption + n, cap - (size_t)n, ", %+g EV", v->ev);
    if (s && s->valid && (s->nan || s->inf) && (size_t)n < cap)
        snprintf(caption + n, cap - (size_t)n, "; %u NaN (magenta), %u Inf (cyan)", s->nan, s->inf);
}

void vrg_viewer_bar_labels(const vrg_viewer *v, const vrg_view_stats *s, char left[32], char mid[32], char right[32])
{
    float lo[4], hi[4];
    vrg_viewer_range(v, s, lo, hi);
    if (v->view == VRG_VIEW_DIRECTION) { /* the hue of each direction, then the length that shows full */
        snprintf(left, 32, "-x");
        snprintf(mid, 32, "+x");
        snprintf(right, 32, "-x");
    } else if (vrg_viewer_slot(v) < 0 && v->view != VRG_VIEW_COLOUR && !one_range(lo, hi)) {
        snprintf(left, 32, "low");
        snprintf(mid, 32, "mid");
        snprintf(right, 32, "high");
    } else {
        vrg_view_value(left, 32, lo[0]);
        vrg_view_value(mid, 32, 0.5 * ((double)lo[0] + hi[0]));
        vrg_view_value(right, 32, hi[0]);
    }
}

float vrg_view_unkey(uint32_t key)
{
    uint32_t bits = key & 0x80000000u ? key & 0x7fffffffu : ~key;
    float f;
    memcpy(&f, &bits, 4);
    return f;
}

void vrg_view_texel(char *out, size_t cap, const uint32_t bits[4], uint32_t channels, int is_uint)
{
    static const char names[4] = {'r', 'g', 'b', 'a'};
    size_t n = 0;
    out[0] = '\0';
    for (uint32_t c = 0; c < channels && c < 4 && n < cap; c++) {
        char value[32];
        if (is_uint)
            snprintf(value, sizeof value, "%u", bits[c]);
        else {
            float f;
            memcpy(&f, &bits[c], 4);
            vrg_view_value(value, sizeof value, f);
        }
        int k = snprintf(out + n, cap - n, "%s%c %s", c ? " " : "", names[c], value);
        n += k > 0 ? (size_t)k : 0;
    }
}
