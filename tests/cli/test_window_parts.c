/* Parts of `voxrg run` that need no window: the overlay's font (every
 * printable character its own glyph, lower case apart from upper case,
 * descenders below the line), the panel's step sizes (a share of the
 * parameter's range, whatever its value) and save-as name, and the rules of
 * the automatic render scale on a CPU device. No device.
 * Usage: test_window_parts font|step|auto_scale */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "auto_scale.h"
#include "check.h"
#include "overlay.h"
#include "panel.h"

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

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(void);
    } cases[] = {{"font", test_font}, {"step", test_step}, {"auto_scale", test_auto_scale}};
    for (size_t i = 0; argc == 2 && i < sizeof cases / sizeof cases[0]; i++)
        if (!strcmp(argv[1], cases[i].name)) {
            cases[i].fn();
            printf("%s: %s\n", cases[i].name, failures ? "FAILED" : "ok");
            return failures != 0;
        }
    fprintf(stderr, "usage: test_window_parts font|step|auto_scale\n");
    return 2;
}
