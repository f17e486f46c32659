/* Parts of `voxrg run` that need no window: the overlay's font (every
 * printable character its own glyph, lower case apart from upper case,
 * descenders below the line), the panel's step sizes (a share of the
 * parameter's range, whatever its value) and save-as name, and the rules of
 * the automatic render scale on a CPU device, the image viewer's views
 * (each shipped image's first view, the range the shader maps, the scale
 * bar's words, the order-keeping keys of its figures) and the overlay's
 * wrapped lines. No device.
 * Usage: test_window_parts font|step|auto_scale|viewer */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "auto_scale.h"
#include "check.h"
#include "overlay.h"
#include "panel.h"
#include "viewer.h"

static int failures;

static int near(double a, double b) { return a > b - 1e-12 && a < b + 1e-12; }

/* c drawn alone into a layer of one cell: its pixels (alpha) in px. */
static void draw(char c, uint8_t *px, uint32_t w, uint32_t h)
{
    static const uint8_t white[4] = {255, 255, 255, 255};
    uint8_t *rgba = calloc((size_t)w * h, 4);
    vrg_overlay_layer l = {rgba, w, h};
    char text[2] = {c, 0};
    vrg_overlay_text(&l, 0, 0, text, white);
    for (size_t i = 0; i < (size_t)w * h; i++)
        px[i] = rgba[4 * i + 3];
    free(rgba);
}

static int test_font(void)
{
    enum { W = VRG_OVERLAY_CELL_W, H = 2 * VRG_OVERLAY_LINE_H };
    static uint8_t px[95][W * H];
    for (int c = 32; c < 127; c++)
        draw((char)c, px[c - 32], W, H);
    /* every printable character looks unlike every other (space aside, each has ink) */
    for (int a = 33; a < 127; a++) {
        int ink = 0;
        for (int i = 0; i < W * H; i++)
            ink += px[a - 32][i] != 0;
        CHECK(ink > 0, "'%c' draws nothing", a);
        for (int b = a + 1; b < 127; b++)
            CHECK(memcmp(px[a - 32], px[b - 32], sizeof px[0]) != 0, "'%c' and '%c' look the same", a, b);
    }
    /* pairs that a small font merges: they differ in more than a pixel or two */
    static const char *pairs[] = {"MN", "UV", "O0", "Il", "l1", "B8", "S5", "Z2", "aA", "nN", "mM", "uU", "vV"};
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        int differ = 0;
        for (int i = 0; i < W * H; i++)
            differ += (px[pairs[p][0] - 32][i] != 0) != (px[pairs[p][1] - 32][i] != 0);
        CHECK(differ >= 3 * VRG_OVERLAY_GLYPH_SCALE * VRG_OVERLAY_GLYPH_SCALE, "%c and %c differ in %d pixels", pairs[p][0], pairs[p][1], differ);
    }
    /* g, p, y reach below the baseline, where no capital does */
    int base = (VRG_OVERLAY_GLYPH_H - 1) * VRG_OVERLAY_GLYPH_SCALE;
    for (const char *c = "gpyjq"; *c; c++) {
        int below = 0;
        for (int i = base * W; i < H * W; i++)
            below += px[*c - 32][i] != 0;
        CHECK(below > 0, "'%c' has no descender", *c);
    }
    for (int c = 'A'; c <= 'Z'; c++)
        for (int i = base * W; i < H * W; i++)
            CHECK(px[c - 32][i] == 0, "'%c' reaches below the baseline", c);
    return 0;
}

static int test_step(void)
{
    /* a range of its own scale: a twentieth of it, a tenth of that with Shift */
    vrg_param_desc falloff = {"falloff", VRG_PARAM_FLOAT, 0.5, 0, 1, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&falloff, 0), 0.05), "falloff: %g", vrg_panel_step_size(&falloff, 0));
    CHECK(near(vrg_panel_step_size(&falloff, 1), 0.005), "falloff fine: %g", vrg_panel_step_size(&falloff, 1));
    vrg_param_desc angle = {"angle", VRG_PARAM_FLOAT, 30, 0, 90, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&angle, 0), 2), "0..90: %g (4.5 rounded down to 1-2-5)", vrg_panel_step_size(&angle, 0));
    /* a bound far beyond the default (exposure 0..1e6): a fifth of the default */
    vrg_param_desc exposure = {"exposure", VRG_PARAM_FLOAT, 1, 0, 1e6, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&exposure, 0), 0.2), "exposure: %g", vrg_panel_step_size(&exposure, 0));
    vrg_param_desc sun = {"sun_radius", VRG_PARAM_FLOAT, 0.27, 0, 45, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&sun, 0), 0.05), "sun_radius: %g", vrg_panel_step_size(&sun, 0));
    vrg_param_desc free_ = {"free", VRG_PARAM_FLOAT, 0, 0, 0, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&free_, 0), 0.1), "unbounded, default 0: %g", vrg_panel_step_size(&free_, 0));
    /* whole numbers: at least 1 */
    vrg_param_desc iterations = {"iterations", VRG_PARAM_INT, 3, 1, 8, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&iterations, 0), 1) && near(vrg_panel_step_size(&iterations, 1), 1), "1..8: %g", vrg_panel_step_size(&iterations, 0));
    vrg_param_desc distance = {"max_distance", VRG_PARAM_INT, 256, 1, 16384, "", 0, NULL};
    CHECK(near(vrg_panel_step_size(&distance, 0), 500) && near(vrg_panel_step_size(&distance, 1), 50), "1..16384: %g, fine %g",
          vrg_panel_step_size(&distance, 0), vrg_panel_step_size(&distance, 1));
    char name[256];
    vrg_panel_save_as_name("graphs/thesis.ini", name, sizeof name);
    CHECK(!strcmp(name, "graphs/thesis-edited.ini"), "%s", name);
    vrg_panel_save_as_name("mine", name, sizeof name);
    CHECK(!strcmp(name, "mine-edited.ini"), "%s", name);
    return 0;
}

/* frames of ms each until the scale changes or n frames passed: the frames taken */
static int frames_until_change(vrg_auto_scale *a, double ms, int n)
{
    for (int i = 1; i <= n; i++)
        if (vrg_auto_scale_frame(a, ms))
            return i;
    return 0;
}

static int test_auto_scale(void)
{
    vrg_auto_scale a = {.scale = VRG_AUTO_SCALE_START};
    /* 100 fps: after the skipped frames and a window, double, twice, then stay at the top */
    CHECK(frames_until_change(&a, 10, 100) == VRG_AUTO_SCALE_SKIP + VRG_AUTO_SCALE_WINDOW && a.scale == 0.5, "scale %g", a.scale);
    CHECK(frames_until_change(&a, 10, 100) && a.scale == 1, "scale %g", a.scale);
    CHECK(frames_until_change(&a, 10, 100) == 0 && a.scale == VRG_AUTO_SCALE_MAX, "past the top: %g", a.scale);
    /* 30 fps: between the target and four times it, the scale stays */
    CHECK(frames_until_change(&a, 1000.0 / 30, 100) == 0 && a.scale == 1, "30 fps: %g", a.scale);
    /* 5 fps: halve; 20 fps after it (four times as fast): stay */
    CHECK(frames_until_change(&a, 200, 100) && a.scale == 0.5, "5 fps: %g", a.scale);
    CHECK(frames_until_change(&a, 50, 100) == 0 && a.scale == 0.5, "20 fps: %g", a.scale);
    /* slow frames that a halving does not speed up (the window's own costs): one halving, no more */
    vrg_auto_scale b = {.scale = 0.5};
    CHECK(frames_until_change(&b, 100, 100) && b.scale == 0.25, "10 fps: %g", b.scale);
    CHECK(frames_until_change(&b, 90, 100) == 0 && b.scale == 0.25, "11 fps after halving: %g", b.scale);
    /* never below the bottom */
    vrg_auto_scale c = {.scale = VRG_AUTO_SCALE_MIN};
    CHECK(frames_until_change(&c, 1000, 100) == 0 && c.scale == VRG_AUTO_SCALE_MIN, "1 fps at the bottom: %g", c.scale);
    /* a restart counts the skipped frames again */
    vrg_auto_scale d = {.scale = 0.25};
    for (int i = 0; i < VRG_AUTO_SCALE_SKIP + VRG_AUTO_SCALE_WINDOW - 1; i++)
        vrg_auto_scale_frame(&d, 10);
    vrg_auto_scale_restart(&d);
    CHECK(frames_until_change(&d, 10, 100) == VRG_AUTO_SCALE_SKIP + VRG_AUTO_SCALE_WINDOW, "after a restart");
    return 0;
}

/* display.comp's key(), as the shader computes it */
static uint32_t shader_key(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u & 0x80000000u ? ~u : u | 0x80000000u;
}

static int test_viewer(void)
{
    static const struct {
        const char *name;
        VkFormat format;
        vrg_view view;
        vrg_view_channel channel;
        int range_auto;
    } first[] = {
        {"ldr", VK_FORMAT_R8G8B8A8_UNORM, VRG_VIEW_COLOUR, VRG_CH_RGB, 1},
        {"hazed", VK_FORMAT_R16G16B16A16_SFLOAT, VRG_VIEW_COLOUR, VRG_CH_RGB, 1},
        {"sun", VK_FORMAT_R16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_R, 1}, /* grey, not red */
        {"ao", VK_FORMAT_R16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_R, 1},
        {"gbuffer.position", VK_FORMAT_R32G32B32A32_SFLOAT, VRG_VIEW_RANGE, VRG_CH_RGB, 1}, /* each channel's range, not fract */
        {"gbuffer.normal", VK_FORMAT_R16G16B16A16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_RGB, 0},
        {"gbuffer.depth", VK_FORMAT_R32_SFLOAT, VRG_VIEW_FALSE, VRG_CH_R, 1},
        {"gbuffer.motion", VK_FORMAT_R16G16_SFLOAT, VRG_VIEW_DIRECTION, VRG_CH_RGB, 1},
        {"gbuffer.ids", VK_FORMAT_R32G32_UINT, VRG_VIEW_RANGE, VRG_CH_RGB, 1},
        {"reproject.moments", VK_FORMAT_R32G32_SFLOAT, VRG_VIEW_FALSE, VRG_CH_R, 1},
        {"reproject.length", VK_FORMAT_R16_SFLOAT, VRG_VIEW_FALSE, VRG_CH_R, 1},
        {"variance.color", VK_FORMAT_R16G16B16A16_SFLOAT, VRG_VIEW_FALSE, VRG_CH_A, 1}, /* the variance in alpha */
        {"variance.variance", VK_FORMAT_R16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_R, 0},      /* the debug outputs: grey, their range */
        {"reproject.reprojection", VK_FORMAT_R16G16B16A16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_A, 0},
        {"cache.occupancy", VK_FORMAT_R16G16B16A16_SFLOAT, VRG_VIEW_RANGE, VRG_CH_R, 0},
    };
    for (size_t i = 0; i < sizeof first / sizeof first[0]; i++) {
        vrg_viewer v;
        vrg_viewer_defaults(&v, first[i].name, first[i].format);
        CHECK(v.view == first[i].view && v.channel == first[i].channel && v.range_auto == first[i].range_auto,
              "%s starts as %s of %s (%s), not %s of %s", first[i].name, vrg_view_name(v.view), vrg_view_channel_name(v.channel),
              v.range_auto ? "auto" : "held", vrg_view_name(first[i].view), vrg_view_channel_name(first[i].channel));
    }
    /* the range: the frame's, per channel for rgb; exposure moves the top; one value sits mid-range */
    vrg_view_stats s = {.valid = 1, .min = {-4, 0, 2, 1, 0.5f, 0}, .max = {4, 10, 2, 1, 6, 3}};
    vrg_viewer v;
    vrg_viewer_defaults(&v, "gbuffer.position", VK_FORMAT_R32G32B32A32_SFLOAT);
    float lo[4], hi[4];
    vrg_viewer_range(&v, &s, lo, hi);
    CHECK(lo[0] == -4 && hi[0] == 4 && lo[1] == 0 && hi[1] == 10 && lo[2] == 1.5f && hi[2] == 2.5f, "position's ranges: %g..%g %g..%g %g..%g", lo[0],
          hi[0], lo[1], hi[1], lo[2], hi[2]);
    char caption[256], l[32], m[32], h[32];
    vrg_viewer_caption(&v, &s, 0, caption, sizeof caption);
    CHECK(!strcmp(caption, "each channel: r -4..4 g 0..10 b 1.5..2.5, auto"), "caption '%s'", caption);
    vrg_viewer_next_channel(&v, 1); /* r */
    vrg_viewer_next_view(&v, 1);    /* false colour */
    vrg_viewer_expose(&v, 1);       /* the top halfway */
    vrg_viewer_range(&v, &s, lo, hi);
    CHECK(v.view == VRG_VIEW_FALSE && v.channel == VRG_CH_R && lo[0] == -4 && hi[0] == 0, "r, +1 EV: %g..%g", lo[0], hi[0]);
    vrg_viewer_caption(&v, &s, 0, caption, sizeof caption);
    vrg_viewer_bar_labels(&v, &s, l, m, h);
    CHECK(!strcmp(caption, "false colour of r, auto, +1 EV") && !strcmp(l, "-4") && !strcmp(m, "-2") && !strcmp(h, "0"), "'%s': %s %s %s", caption,
          l, m, h);
    vrg_viewer_hold_range(&v, &s); /* held: later frames do not move it */
    vrg_view_stats later = {.valid = 1, .min = {100, 0, 0, 0, 0, 0}, .max = {200, 1, 1, 1, 1, 1}, .nan = 3, .inf = 1};
    vrg_viewer_range(&v, &later, lo, hi);
    vrg_viewer_caption(&v, &later, 0, caption, sizeof caption);
    CHECK(lo[0] == -4 && hi[0] == 0 && !strcmp(caption, "false colour of r, held, +1 EV; 3 NaN (magenta), 1 Inf (cyan)"), "held: %g..%g '%s'", lo[0],
          hi[0], caption);
    vrg_viewer_move_low(&v, &later, 1); /* the held -4..4 a tenth up: -3.2..4, +1 EV: the top at -3.2 + 7.2 / 2 */
    vrg_viewer_range(&v, &later, lo, hi);
    CHECK(fabsf(lo[0] + 3.2f) < 1e-5f && fabsf(hi[0] - 0.4f) < 1e-5f, "low end moved: %g..%g", lo[0], hi[0]);
    /* the figures' keys keep the order of the floats, and come back as they were */
    const float values[] = {-INFINITY, -1e30f, -2.5f, -1e-40f, -0.0f, 0.0f, 1e-40f, 0.75f, 3e38f, INFINITY};
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++) {
        CHECK(i == 0 || shader_key(values[i - 1]) <= shader_key(values[i]), "key(%g) > key(%g)", values[i - 1], values[i]);
        float back = vrg_view_unkey(shader_key(values[i]));
        CHECK(!memcmp(&back, &values[i], 4), "key(%g) comes back as %g", values[i], back);
    }
    /* the texel under the cursor as printed */
    float f[4] = {0.5f, -2.0f, NAN, INFINITY};
    uint32_t bits[4];
    memcpy(bits, f, sizeof bits);
    vrg_view_texel(caption, sizeof caption, bits, 4, 0);
    CHECK(!strcmp(caption, "r 0.5 g -2 b nan a inf"), "texel '%s'", caption);
    uint32_t ids[4] = {4000000000u, 7, 0, 0};
    vrg_view_texel(caption, sizeof caption, ids, 2, 1);
    CHECK(!strcmp(caption, "r 4000000000 g 7"), "integer texel '%s'", caption);
    /* wrapped lines: broken at spaces, the rest indented, a long word cut */
    vrg_overlay o;
    vrg_overlay_clear(&o);
    vrg_overlay_wrap(&o, "each channel: r -4..4 g 0..10", 2 * VRG_OVERLAY_PAD + 16 * VRG_OVERLAY_CELL_W);
    CHECK(o.lines == 2 && !strcmp(o.text[0], "each channel: r") && !strcmp(o.text[1], "  -4..4 g 0..10"), "wrapped: %d '%s' '%s'", o.lines, o.text[0],
          o.lines > 1 ? o.text[1] : "");
    vrg_overlay_clear(&o);
    vrg_overlay_wrap(&o, "abcdefghijklmnopqrstuvwxyz", 2 * VRG_OVERLAY_PAD + 10 * VRG_OVERLAY_CELL_W);
    CHECK(o.lines == 3 && !strcmp(o.text[0], "abcdefghij") && !strcmp(o.text[1], "  klmnopqr"), "a long word: %d '%s' '%s'", o.lines, o.text[0],
          o.text[1]);
    return 0;
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(void);
    } cases[] = {{"font", test_font}, {"step", test_step}, {"auto_scale", test_auto_scale}, {"viewer", test_viewer}};
    for (size_t i = 0; argc == 2 && i < sizeof cases / sizeof cases[0]; i++)
        if (!strcmp(argv[1], cases[i].name)) {
            cases[i].fn();
            printf("%s: %s\n", cases[i].name, failures ? "FAILED" : "ok");
            return failures != 0;
        }
    fprintf(stderr, "usage: test_window_parts font|step|auto_scale|viewer\n");
    return 2;
}
