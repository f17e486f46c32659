#define _DEFAULT_SOURCE /* opendir */
/* Camera, camera paths and sky: `test_camera CASE` prints "CASE: ok" or the
 * failed checks and exits non-zero. Pure CPU, no Vulkan. */
#include <dirent.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/camera.h"
#include "voxrg/sky.h"
#include "voxrg/camera_path.h"
#include "check.h"

#ifndef VRG_SOURCE_DIR
#error "VRG_SOURCE_DIR must name the source tree (for graphs/paths)"
#endif

static int failures;

/* clip = m * (x, y, z, 1) */
static void transform(const float m[16], const double p[3], double clip[4])
{
    for (int r = 0; r < 4; r++)
        clip[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* ---------------------------------------------------------------- projection */

static void check_camera_rays(const vrg_camera *c, uint32_t w, uint32_t h)
{
    float vp[16];
    vrg_camera_view_projection(c, (float)w / (float)h, vp);
    /* corners, fractional positions, the centre; all inside the image */
    const float pixels[][2] = {{0, 0}, {(float)w - 1, 0}, {0, (float)h - 1}, {(float)w - 1, (float)h - 1},
                               {(float)w / 3, (float)h / 5}, {(float)w / 2, (float)h / 2}, {0.25f, 0.75f},
                               {(float)w - 0.9f, (float)h * 0.6f}};
    /* The float matrix stores the camera translation with an absolute error
     * of ~|position| * 2^-24, which shows as a pixel error ~ that / w: a
     * point nearer than |position| / 8 is float-limited, not a mismatch, so
     * only its depth is checked there. Cameras near the origin are checked
     * at every distance. */
    double pos_len = sqrt((double)c->position[0] * c->position[0] + (double)c->position[1] * c->position[1] +
                          (double)c->position[2] * c->position[2]);
    for (size_t i = 0; i < sizeof pixels / sizeof *pixels; i++) {
        float px = pixels[i][0], py = pixels[i][1], dir[3];
        vrg_camera_ray(c, w, h, px, py, dir);
        CHECK(fabs(sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) - 1.0) < 1e-5, "ray not unit");
        /* Several distances: the point must stay on the pixel and its depth
         * must grow from 0 (near) towards 1 (far). */
        const double ts[] = {1.0, 7.5, 60.0, 400.0};
        double prev_depth = -1.0;
        for (int k = 0; k < 4; k++) {
            double p[3], clip[4];
            for (int j = 0; j < 3; j++)
                p[j] = c->position[j] + ts[k] * dir[j];
            transform(vp, p, clip);
            double sx = (clip[0] / clip[3] + 1.0) * 0.5 * w - 0.5;
            double sy = (clip[1] / clip[3] + 1.0) * 0.5 * h - 0.5;
            double depth = clip[2] / clip[3];
            if (clip[3] >= pos_len / 8.0)
                CHECK(fabs(sx - px) < 1e-3 && fabs(sy - py) < 1e-3,
                      "%ux%u pixel (%g, %g) t=%g projects to (%.5f, %.5f)", w, h, px, py, ts[k], sx, sy);
            CHECK(clip[3] > 0.0 && depth > prev_depth && depth > 0.0 && depth < 1.0,
                  "depth %g after %g at t=%g", depth, prev_depth, ts[k]);
            prev_depth = depth;
        }
    }
    /* Odd sizes have a pixel whose centre is the image centre: its ray is
     * the forward vector. */
    if (w % 2 && h % 2) {
        float dir[3], f[3];
        vrg_camera_ray(c, w, h, (float)(w / 2), (float)(h / 2), dir);
        vrg_camera_forward(c, f);
        for (int j = 0; j < 3; j++)
            CHECK(fabsf(dir[j] - f[j]) < 1e-6f, "centre ray %g vs forward %g", dir[j], f[j]);
    }
    /* inverse(vp) * vp = I, to float rounding: each product element may be
     * off by a few ulps of the sum of |inv_ik * vp_kj| it adds up (large:
     * near 0.05 vs far 1000, translations of hundreds). */
    float inv[16], id[16];
    CHECK(vrg_mat4_invert(vp, inv) == 0, "view-projection not invertible");
    vrg_mat4_mul(inv, vp, id);
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double mag = 0.0;
            for (int k = 0; k < 4; k++)
                mag += fabs((double)inv[k * 4 + row] * vp[col * 4 + k]);
            double err = fabs(id[col * 4 + row] - (row == col ? 1.0 : 0.0));
            CHECK(err <= 16.0 * FLT_EPSILON * mag, "inv*vp[%d][%d] off by %g (scale %g)", col, row, err, mag);
        }
}

static int test_projection(void)
{
    vrg_camera c;
    vrg_camera_default(&c);
    CHECK(c.fov_y == 70.0f && c.near_plane == 0.05f && c.far_plane == 1000.0f, "defaults");

    /* The documented axes: yaw 0 -> -z, 90 -> -x, -90 -> +x; pitch up -> +y. */
    const float axes[][5] = {{0, 0, 0, 0, -1}, {90, 0, -1, 0, 0}, {-90, 0, 1, 0, 0}, {180, 0, 0, 0, 1}, {0, 89, 0, 1, 0}};
    for (int i = 0; i < 5; i++) {
        float f[3];
        c.yaw = axes[i][0];
        c.pitch = axes[i][1];
        vrg_camera_forward(&c, f);
        for (int j = 0; j < 3; j++)
            CHECK(fabsf(f[j] - axes[i][2 + j]) < 0.02f, "yaw %g pitch %g forward[%d] = %g", axes[i][0], axes[i][1], j, f[j]);
    }

    /* Vulkan conventions: a point above the view centre lands in the top
     * half (NDC y < 0); near -> depth 0, far -> depth 1. */
    vrg_camera_default(&c);
    float vp[16];
    vrg_camera_view_projection(&c, 1.0f, vp);
    double clip[4];
    transform(vp, (double[3]){0, 1, -5}, clip);
    CHECK(clip[1] / clip[3] < 0.0, "up is not NDC -y");
    transform(vp, (double[3]){1, 0, -5}, clip);
    CHECK(clip[0] / clip[3] > 0.0, "right is not NDC +x");
    transform(vp, (double[3]){0, 0, -0.05}, clip);
    CHECK(fabs(clip[2] / clip[3]) < 1e-5, "near depth %g", clip[2] / clip[3]);
    transform(vp, (double[3]){0, 0, -1000}, clip);
    CHECK(fabs(clip[2] / clip[3] - 1.0) < 1e-5, "far depth %g", clip[2] / clip[3]);

    /* Rays for assorted cameras and image sizes. */
    const float cams[][6] = {/* x y z yaw pitch fov */
                             {0, 0, 0, 0, 0, 70},       {10, 35, -4, 37, -12, 70}, {-150, 60, 200, 215, 30, 90},
                             {3, 40, 3, -90, -89, 50}, {0, 30, 0, 1000, 89, 120}, {5, 5, 5, 45, 95, 20}};
    const uint32_t sizes[][2] = {{1, 1}, {3, 3}, {64, 64}, {1920, 1080}, {1279, 721}, {97, 311}};
    for (size_t i = 0; i < sizeof cams / sizeof *cams; i++)
        for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
            vrg_camera_default(&c);
            memcpy(c.position, cams[i], sizeof c.position);
            c.yaw = cams[i][3];
            c.pitch = cams[i][4];
            c.fov_y = cams[i][5];
            check_camera_rays(&c, sizes[s][0], sizes[s][1]);
        }

    /* mat4 helpers: multiplication order and a singular matrix. */
    float a[16] = {0}, b[16] = {0}, ab[16];
    for (int i = 0; i < 4; i++)
        a[i * 5] = b[i * 5] = 1.0f;
    a[12] = 3.0f;  /* translate x by 3 */
    b[0] = 2.0f;   /* scale x by 2 */
    vrg_mat4_mul(a, b, ab); /* scale first, then translate */
    transform(ab, (double[3]){1, 0, 0}, clip);
    CHECK(fabs(clip[0] - 5.0) < 1e-6, "a*b applies b first: %g", clip[0]);
    float zero[16] = {0}, out[16];
    CHECK(vrg_mat4_invert(zero, out) == -1, "zero matrix inverted");
    float rank3[16] = {1, 2, 3, 0, 2, 4, 6, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(vrg_mat4_invert(rank3, out) == -1, "singular matrix inverted");
    return 0;
}

/* ---------------------------------------------------------------- paths */

static int parse_ok(const char *text, vrg_camera_path *p)
{
    int r = vrg_camera_path_parse("test.path", text, p, stderr);
    CHECK(r == 0, "parse failed:\n%s", text);
    return r;
}

static double yaw_diff(double a, double b)
{
    double d = fmod(a - b, 360.0);
    return d > 180.0 ? d - 360.0 : d < -180.0 ? d + 360.0 : d;
}

/* Sampling every dt, no step may exceed the speed bound of a Hermite
 * segment: |v| <= 1.5 S + |m0| + |m1| <= 3.5 S, S = the steepest slope
 * between consecutive keys. */
static void check_continuous(const vrg_camera_path *p)
{
    double max_slope = 0.0, yaw_slope = 0.0;
    for (int i = 1; i < p->count; i++) {
        double dt = p->keys[i].time - p->keys[i - 1].time;
        for (int j = 0; j < 3; j++)
            max_slope = fmax(max_slope, fabs(p->keys[i].position[j] - p->keys[i - 1].position[j]) / dt);
        max_slope = fmax(max_slope, fabs(p->keys[i].pitch - p->keys[i - 1].pitch) / dt);
        yaw_slope = fmax(yaw_slope, fabs(yaw_diff(p->keys[i].yaw, p->keys[i - 1].yaw)) / dt);
    }
    const double dt = 1e-3;
    double t0 = p->keys[0].time - 0.5, t1 = vrg_camera_path_duration(p) + 0.5;
    vrg_camera prev, cur;
    vrg_camera_default(&prev);
    vrg_camera_path_eval(p, (float)t0, &prev);
    for (double t = t0 + dt; t <= t1; t += dt) {
        cur = prev;
        vrg_camera_path_eval(p, (float)t, &cur);
        for (int j = 0; j < 3; j++)
            CHECK(fabs(cur.position[j] - prev.position[j]) <= 3.5 * max_slope * dt + 1e-4, "t=%g position[%d] jumps %g -> %g",
                  t, j, prev.position[j], cur.position[j]);
        /* yaw is continuous as a number, not just modulo 360 */
        CHECK(fabs(cur.yaw - prev.yaw) <= 3.5 * yaw_slope * dt + 1e-3, "t=%g yaw jumps %g -> %g", t, prev.yaw, cur.yaw);
        CHECK(fabs(cur.pitch - prev.pitch) <= 3.5 * max_slope * dt + 1e-4, "t=%g pitch jumps", t);
        if (failures > 20)
            return;
        prev = cur;
    }
}

static void check_hits_keys(const vrg_camera_path *p)
{
    for (int i = 0; i < p->count; i++) {
        vrg_camera c;
        vrg_camera_default(&c);
        vrg_camera_path_eval(p, p->keys[i].time, &c);
        const vrg_camera_key *k = &p->keys[i];
        for (int j = 0; j < 3; j++)
            CHECK(fabsf(c.position[j] - k->position[j]) < 1e-4f, "key %d position[%d] %g vs %g", i, j, c.position[j], k->position[j]);
        CHECK(fabs(yaw_diff(c.yaw, k->yaw)) < 1e-4, "key %d yaw %g vs %g", i, c.yaw, k->yaw);
        CHECK(fabsf(c.pitch - k->pitch) < 1e-4f, "key %d pitch %g vs %g", i, c.pitch, k->pitch);
    }
}

static int test_path_keys(void)
{
    vrg_camera_path p;
    vrg_camera c;
    /* Uneven gaps, comments of both kinds, blank lines, CRLF, tabs. */
    const char *text = "# a test path\n"
                       "\n"
                       "0    0 30 0   0  0   ; start\r\n"
                       "1.5  6 31 -2  40 10\n"
                       "\t2   9 35 -2  80 -20 # short gap\n"
                       "6   20 30  8  10 5\n"
                       "6.25 21 30 8 12 5";
    if (parse_ok(text, &p))
        return 1;
    CHECK(p.count == 5, "count %d", p.count);
    CHECK(vrg_camera_path_duration(&p) == 6.25f, "duration %g", vrg_camera_path_duration(&p));
    CHECK(strcmp(p.path, "test.path") == 0, "name '%s'", p.path);
    check_hits_keys(&p);
    check_continuous(&p);

    /* Clamping outside the keys (NaN counts as before). */
    const float outside[] = {-100.0f, -0.001f, NAN, 6.2501f, 1e9f};
    for (int i = 0; i < 5; i++) {
        const vrg_camera_key *k = i < 3 ? &p.keys[0] : &p.keys[4];
        vrg_camera_default(&c);
        vrg_camera_path_eval(&p, outside[i], &c);
        CHECK(c.position[0] == k->position[0] && c.position[1] == k->position[1] && c.position[2] == k->position[2] &&
                  c.yaw == k->yaw && c.pitch == k->pitch,
              "t=%g not clamped to key", outside[i]);
    }
    /* Only position/yaw/pitch are written. */
    vrg_camera_default(&c);
    c.fov_y = 33.0f;
    vrg_camera_path_eval(&p, 3.0f, &c);
    CHECK(c.fov_y == 33.0f && c.near_plane == 0.05f && c.far_plane == 1000.0f, "eval wrote lens fields");
    vrg_camera_path_free(&p);
    CHECK(p.keys == NULL && p.count == 0, "free leaves keys");

    /* Evenly spaced keys: the midpoint is uniform Catmull-Rom's
     * (-p0 + 9 p1 + 9 p2 - p3) / 16. */
    if (parse_ok("0 0 0 0 0 0\n1 1 4 2 0 0\n2 3 1 7 0 0\n3 10 0 -5 0 0\n", &p))
        return 1;
    vrg_camera_path_eval(&p, 1.5f, &c);
    const float want[3] = {(-0.0f + 9 * 1 + 9 * 3 - 10) / 16.0f, (-0.0f + 9 * 4 + 9 * 1 - 0) / 16.0f,
                           (-0.0f + 9 * 2 + 9 * 7 + 5) / 16.0f};
    for (int j = 0; j < 3; j++)
        CHECK(fabsf(c.position[j] - want[j]) < 1e-5f, "uniform CR [%d] %g vs %g", j, c.position[j], want[j]);
    /* A straight line at constant speed stays exactly on it (the clamped
     * ends ease in/out, but never leave the line). */
    vrg_camera_path_free(&p);
    if (parse_ok("0 0 0 0 0 0\n1 4 0 0 0 0\n2 8 0 0 0 0\n3 12 0 0 0 0\n", &p))
        return 1;
    vrg_camera_path_eval(&p, 1.25f, &c);
    CHECK(fabsf(c.position[0] - 5.0f) < 1e-5f, "interior of a uniform line: %g", c.position[0]);
    vrg_camera_path_free(&p);

    /* Uneven gaps: with the key times as knots, constant acceleration
     * (x = t^2, y linear) is reproduced exactly between interior keys. */
    if (parse_ok("0 0 5 0 0 0\n0.5 0.25 4 0 0 0\n2 4 1 0 0 0\n2.25 5.0625 0.5 0 0 0\n4 16 -3 0 0 0\n", &p))
        return 1;
    for (float t = 0.5f; t <= 2.25f; t += 0.0625f) {
        vrg_camera_path_eval(&p, t, &c);
        CHECK(fabsf(c.position[0] - t * t) < 1e-4f && fabsf(c.position[1] - (5 - 2 * t)) < 1e-4f,
              "t=%g: (%g, %g) is not (t^2, 5-2t)", t, c.position[0], c.position[1]);
    }
    vrg_camera_path_free(&p);

    /* Yaw unwrap: 350 -> 10 turns +20 through 360. */
    if (parse_ok("0 0 0 0 350 0\n1 0 0 0 10 0\n", &p))
        return 1;
    vrg_camera_path_eval(&p, 0.5f, &c);
    CHECK(fabs(yaw_diff(c.yaw, 0.0)) < 1e-3, "350->10 midpoint yaw %g", c.yaw);
    CHECK(c.yaw > 350.0f && c.yaw < 370.0f, "350->10 went the long way: %g", c.yaw);
    vrg_camera_path_eval(&p, 0.25f, &c);
    CHECK(c.yaw > 350.0f && c.yaw < 360.0f, "350->10 quarter yaw %g", c.yaw);
    check_hits_keys(&p);
    check_continuous(&p);
    vrg_camera_path_free(&p);
    /* ... and the other way, over several keys and a full extra turn. */
    if (parse_ok("0 0 0 0 10 0\n1 0 0 0 -10 0\n2 0 0 0 200 0\n3 0 0 0 100 0\n4 0 0 0 0 0\n5 0 0 0 -100 0\n", &p))
        return 1;
    vrg_camera_path_eval(&p, 0.5f, &c);
    CHECK(c.yaw > -10.0f && c.yaw < 10.0f, "10->-10 midpoint yaw %g", c.yaw);
    vrg_camera_path_eval(&p, 1.5f, &c);
    CHECK(c.yaw < -10.0f && c.yaw > -160.0f, "-10->200 (= -160) should turn -150: %g", c.yaw);
    check_hits_keys(&p);
    check_continuous(&p);
    vrg_camera_path_free(&p);

    /* One key: constant. */
    if (parse_ok("2 1 2 3 45 -30\n", &p))
        return 1;
    const float ts[] = {0.0f, 2.0f, 5.0f};
    for (int i = 0; i < 3; i++) {
        vrg_camera_path_eval(&p, ts[i], &c);
        CHECK(c.position[0] == 1 && c.position[1] == 2 && c.position[2] == 3 && c.yaw == 45 && c.pitch == -30, "single key");
    }
    vrg_camera_path_free(&p);
    /* Empty/NULL path: untouched. */
    vrg_camera_default(&c);
    c.yaw = 12.0f;
    vrg_camera_path_eval(NULL, 1.0f, &c);
    CHECK(c.yaw == 12.0f && vrg_camera_path_duration(NULL) == 0.0f, "NULL path");
    return 0;
}

/* Parses text, expecting -1 and, in order, each expected string in the
 * messages (one per bad line). */
static void expect_errors(const char *text, const char *const *expected, int n_expected)
{
    FILE *diag = tmpfile();
    if (!diag) {
        CHECK(0, "tmpfile failed");
        return;
    }
    vrg_camera_path p;
    int r = vrg_camera_path_parse("bad.path", text, &p, diag);
    char out[4096] = {0};
    rewind(diag);
    size_t n = fread(out, 1, sizeof out - 1, diag);
    out[n] = '\0';
    fclose(diag);
    CHECK(r == -1, "accepted:\n%s", text);
    CHECK(p.keys == NULL && p.count == 0, "keys left after an error");
    const char *at = out;
    for (int i = 0; i < n_expected; i++) {
        const char *hit = strstr(at, expected[i]);
        CHECK(hit != NULL, "missing '%s' in:\n%s---- text:\n%s", expected[i], out, text);
        if (hit)
            at = hit + strlen(expected[i]);
    }
    /* exactly one error (and one hint) per expected message */
    int errors = 0, hints = 0;
    for (const char *s = out; (s = strstr(s, ": error: ")) != NULL; s++)
        errors++;
    for (const char *s = out; (s = strstr(s, "\n  hint: ")) != NULL; s++)
        hints++;
    CHECK(errors == n_expected && hints == n_expected, "%d errors, %d hints, want %d:\n%s", errors, hints, n_expected, out);
}

/* The world's range: positions are checked, conversions to int cannot
 * overflow, and a path's curve stays inside even where it overshoots keys. */
static int test_world_range(void)
{
    float inside[3] = {VRG_WORLD_LIMIT, -VRG_WORLD_LIMIT, 0}, outside[3] = {0, 3e9f, 0}, nan_pos[3] = {0, NAN, 0};
    CHECK(vrg_camera_position_in_world(inside), "the limit itself is in the world");
    CHECK(!vrg_camera_position_in_world(outside), "3e9 is in the world");
    CHECK(!vrg_camera_position_in_world(nan_pos), "NaN is in the world");
    CHECK(vrg_world_floor(3e9f) == (int)VRG_WORLD_LIMIT, "floor(3e9) = %d", vrg_world_floor(3e9f));
    CHECK(vrg_world_floor(-INFINITY) == -(int)VRG_WORLD_LIMIT, "floor(-inf) = %d", vrg_world_floor(-INFINITY));
    CHECK(vrg_world_floor(NAN) == 0, "floor(NaN) = %d", vrg_world_floor(NAN));
    CHECK(vrg_world_floor(-2.5f) == -3, "floor(-2.5) = %d", vrg_world_floor(-2.5f));
    /* a quick turn at the edge: Catmull-Rom overshoots the middle key */
    char text[256];
    snprintf(text, sizeof text, "0 0 0 0 0 0\n10 %.1f 0 0 0 0\n10.01 %.1f 0 0 0 0\n", (double)VRG_WORLD_LIMIT, (double)VRG_WORLD_LIMIT);
    vrg_camera_path p;
    CHECK(vrg_camera_path_parse("edge.path", text, &p, NULL) == 0, "edge path refused");
    float most = 0;
    for (int i = 0; i <= 1000; i++) {
        vrg_camera c;
        vrg_camera_default(&c);
        vrg_camera_path_eval(&p, 9.0f + (float)i * 0.002f, &c);
        CHECK(vrg_camera_position_in_world(c.position), "t %g: x %g left the world", 9.0 + i * 0.002, c.position[0]);
        most = c.position[0] > most ? c.position[0] : most;
    }
    CHECK(most == VRG_WORLD_LIMIT, "the curve did not reach the edge (%g)", most);
    vrg_camera_path_free(&p);
    return 0;
}

static int test_path_errors(void)
{
    struct {
        const char *text;
        const char *expected[4];
    } corpus[] = {
        {"0 0 0 0 0 0\n1 2 3 4 5\n", {"bad.path:2: error: expected 6 fields (time x y z yaw pitch), found 5"}},
        {"# c\n\n0 0 0 0 0 0 0\n", {"bad.path:3: error: expected 6 fields (time x y z yaw pitch), found 7"}},
        {"0 0 0 0 0 0\n1 2 abc 4 5 6\n", {"bad.path:2: error: 'abc' is not a number"}},
        {"0 0 0 0 0 0\n1 2 3 4 5 6x\n", {"bad.path:2: error: '6x' is not a number"}},
        {"0 0 0 0 0 0\n1 nan 3 4 5 6\n", {"bad.path:2: error: 'nan' is not a finite number"}},
        {"0 0 0 0 0 0\n1 2 3 4 -inf 6\n", {"bad.path:2: error: '-inf' is not a finite number"}},
        {"0 0 0 0 0 0\n1 2 3 1e300 5 6\n", {"bad.path:2: error: '1e300' is not a finite number"}},
        {"0 0 0 0 0 0\n1 0 0 0 0 0\n1 0 0 0 0 0\n", {"bad.path:3: error: time 1 is not after 1 (the keyframe on line 2)"}},
        {"5 0 0 0 0 0\n\n; c\n2 0 0 0 0 0\n", {"bad.path:4: error: time 2 is not after 5 (the keyframe on line 1)"}},
        {"0 0 0 0 0 95\n", {"bad.path:1: error: pitch 95 is outside [-89, 89]"}},
        /* numbers as graph files read them: decimal only */
        {"0 0 0 0 0 0\n0x10 0 0 0 0 0\n", {"bad.path:2: error: '0x10' is not a decimal number"}},
        {"0 0 0 0 0 0\n1 0 0 0 0x1p2 0\n", {"bad.path:2: error: '0x1p2' is not a decimal number"}},
        /* positions within the world (VRG_WORLD_LIMIT) */
        {"0 0 40 0 0 0\n1 3e9 40 0 0 0\n", {"bad.path:2: error: position 3e9 40 0 is outside the world"}},
        {"0 0 40 -1048577 0 0\n", {"bad.path:1: error: position 0 40 -1048577 is outside the world"}},
        /* yaw within [camera]'s range (vrg_camera_angle_range), the value as written */
        {"0 0 0 0 1e30 0\n", {"bad.path:1: error: yaw 1e30 is outside [-360, 360]"}},
        {"0 0 0 0 -360.5 0\n", {"bad.path:1: error: yaw -360.5 is outside [-360, 360]"}},
        /* two times written apart that are one float: said so, not "0 is not after 0" */
        {"0 0 0 0 0 0\n1e-300 0 0 0 0 0\n",
         {"bad.path:2: error: time 1e-300 is not after 0 (the keyframe on line 1): as 32-bit floats, which hold times, both are 0"}},
        {"1 0 0 0 0 0\n1.00000001 0 0 0 0 0\n",
         {"bad.path:2: error: time 1.00000001 is not after 1 (the keyframe on line 1): as 32-bit floats, which hold times, both are 1"}},
        /* a field's text is quoted escaped: no terminal control from the file */
        {"0 0 0 0 0 0\n1 \x1b[2J\x1b[31m 0 0 0 0\n", {"bad.path:2: error: '\\x1b[2J\\x1b[31m' is not a number"}},
        {"", {"bad.path:1: error: no keyframes"}},
        {"# only comments\n\n; and blanks\n   \n", {"bad.path:1: error: no keyframes"}},
        /* every bad line is reported, and an order check skips bad lines */
        {"0 0 0 0 0 0\nx 0 0 0 0 0\n1 0 0\n2 0 0 0 0 0\n1.5 0 0 0 0 0\n",
         {"bad.path:2: error: 'x' is not a number", "bad.path:3: error: expected 6 fields",
          "bad.path:5: error: time 1.5 is not after 2 (the keyframe on line 4)"}},
        {"0 0 0 0 0 0 # fine\n1 0 0 0 0 ; 0\n", {"bad.path:2: error: expected 6 fields (time x y z yaw pitch), found 5"}},
    };
    for (size_t i = 0; i < sizeof corpus / sizeof *corpus; i++) {
        int n = 0;
        while (n < 4 && corpus[i].expected[n])
            n++;
        expect_errors(corpus[i].text, corpus[i].expected, n);
    }

    /* A missing file is named. */
    FILE *diag = tmpfile();
    vrg_camera_path p;
    const char *missing = "/nonexistent-dir/no-such.path";
    CHECK(vrg_camera_path_load(missing, &p, diag) == -1, "missing file loaded");
    char out[1024] = {0};
    rewind(diag);
    size_t n = fread(out, 1, sizeof out - 1, diag);
    out[n] = '\0';
    fclose(diag);
    CHECK(strstr(out, "/nonexistent-dir/no-such.path: error: cannot open camera path") != NULL, "message: %s", out);
    CHECK(p.keys == NULL && p.count == 0, "keys after a failed load");
    return 0;
}

/* ---------------------------------------------------------------- sky */

static void sky_at(float hours, vrg_sky *s)
{
    vrg_sky_desc d;
    vrg_sky_default(&d);
    d.time_of_day = hours;
    vrg_sky_eval(&d, 0.0, s);
}

static double sum3(const float v[3]) { return (double)v[0] + v[1] + v[2]; }

static int test_sun(void)
{
    vrg_sky_desc d;
    vrg_sky_default(&d);
    CHECK(d.time_of_day == 10.0f && d.day_length == 0.0f && d.latitude_tilt == 30.0f && d.sun_azimuth == 30.0f, "defaults");

    vrg_sky s, noon, night, sunset, h;
    sky_at(12.0f, &noon);
    sky_at(0.0f, &night);
    sky_at(17.5f, &sunset);
    CHECK(night.sun_elevation < 0.0f, "sun up at midnight: %g", night.sun_elevation);
    CHECK(fabsf(noon.sun_elevation - 60.0f) < 1e-3f, "noon elevation %g (tilt 30)", noon.sun_elevation);
    for (int hour = 0; hour < 24; hour++) {
        if (hour == 12)
            continue;
        sky_at((float)hour, &h);
        CHECK(h.sun_elevation < noon.sun_elevation, "%d:00 elevation %g >= noon", hour, h.sun_elevation);
    }
    for (float t = 0.0f; t < 24.0f; t += 0.25f) {
        sky_at(t, &s);
        CHECK(fabs(sqrt(sum3((float[3]){s.sun_dir[0] * s.sun_dir[0], s.sun_dir[1] * s.sun_dir[1], s.sun_dir[2] * s.sun_dir[2]})) - 1.0) < 1e-5,
              "sun_dir not unit at %g", t);
        CHECK(fabsf(asinf(s.sun_dir[1]) * 57.29578f - s.sun_elevation) < 1e-2f, "elevation vs dir at %g", t);
        /* below the horizon no sunlight at all; it rises in the morning */
        if (s.sun_elevation <= 0.0f)
            CHECK(sum3(s.sun_radiance) == 0.0, "sun radiance %g below the horizon at %g", sum3(s.sun_radiance), t);
        if (t != 6.0f && t != 18.0f) /* on the horizon there: +-1e-14 */
            CHECK((t > 6.0f && t < 18.0f) == (s.sun_elevation > 0.0f), "elevation %g at %g h", s.sun_elevation, t);
    }
    sky_at(6.0f, &s);
    CHECK(fabsf(s.sun_elevation) < 1.0f, "6:00 elevation %g", s.sun_elevation);
    sky_at(18.0f, &h);
    CHECK(fabsf(h.sun_elevation) < 1.0f, "18:00 elevation %g", h.sun_elevation);
    /* sunrise is +x rotated 30 degrees around +y: (cos 30, 0, -sin 30) */
    CHECK(fabsf(s.sun_dir[0] - 0.8660254f) < 1e-4f && fabsf(s.sun_dir[2] + 0.5f) < 1e-4f, "sunrise direction");
    CHECK(fabsf(h.sun_dir[0] + 0.8660254f) < 1e-4f && fabsf(h.sun_dir[2] - 0.5f) < 1e-4f, "sunset direction");

    /* Sun colour: ~3 at noon, dimmer and redder towards sunset. */
    CHECK(noon.sun_radiance[0] > 2.5f && noon.sun_radiance[0] < 3.5f, "noon sun %g", noon.sun_radiance[0]);
    CHECK(sum3(noon.sun_radiance) > sum3(sunset.sun_radiance), "sunset not dimmer");
    double rb_noon = noon.sun_radiance[0] / noon.sun_radiance[2], rb_sunset = sunset.sun_radiance[0] / sunset.sun_radiance[2];
    CHECK(rb_sunset > 2.0 * rb_noon, "sunset not redder: r/b %g vs noon %g", rb_sunset, rb_noon);
    CHECK(sunset.sun_radiance[0] > sunset.sun_radiance[1] && sunset.sun_radiance[1] > sunset.sun_radiance[2], "sunset order r>g>b");
    CHECK(noon.sun_radiance[2] > 0.8f * noon.sun_radiance[0], "noon sun should be near white");
    double prev = 1e9;
    for (float t = 12.0f; t < 18.0f; t += 0.5f) {
        sky_at(t, &s);
        CHECK(sum3(s.sun_radiance) < prev, "sun brightness not falling at %g", t);
        prev = sum3(s.sun_radiance);
    }

    /* Sky: night dim blue but not black, day brighter; zenith bluer than the horizon by day. */
    for (int c = 0; c < 3; c++) {
        CHECK(night.sky_zenith[c] > 0.005f && night.sky_horizon[c] > 0.005f && night.ambient[c] > 0.005f, "night is black [%d]", c);
        CHECK(noon.sky_zenith[c] > 3.0f * night.sky_zenith[c] && noon.ambient[c] > 3.0f * night.ambient[c], "night not dimmer [%d]", c);
    }
    CHECK(night.sky_zenith[2] > night.sky_zenith[0], "night not bluish");
    CHECK(noon.sky_zenith[2] / noon.sky_zenith[0] > noon.sky_horizon[2] / noon.sky_horizon[0], "zenith vs horizon hue");
    CHECK(sum3(noon.sun_radiance) > 3.0 * sum3(noon.ambient), "sun should dominate sky light");
    /* vrg_sky_radiance: zenith/horizon, darker below, glow towards the sun. */
    float up[3] = {0, 1, 0}, flat[3], down[3] = {0, -1, 0}, rad[3], rad_flat[3], rad_down[3];
    /* look horizontally away from the sun so the glow is 0 */
    float away = sqrtf(noon.sun_dir[0] * noon.sun_dir[0] + noon.sun_dir[2] * noon.sun_dir[2]);
    flat[0] = -noon.sun_dir[0] / away;
    flat[1] = 0.0f;
    flat[2] = -noon.sun_dir[2] / away;
    vrg_sky night_dark = night;
    vrg_sky_radiance(&night_dark, up, rad);
    /* by night the glow is the moon's: at the zenith c = the moon's dir.y */
    float mc = night.moon_dir[1], mc4 = mc * mc * mc * mc, mc32 = powf(mc, 32.0f);
    for (int c = 0; c < 3; c++)
        CHECK(fabsf(rad[c] - (night.sky_zenith[c] + night.moon_radiance[c] * (0.25f * mc32 + 0.05f * mc4))) < 1e-6f, "night zenith radiance");
    vrg_sky_radiance(&noon, flat, rad_flat);
    vrg_sky_radiance(&noon, down, rad_down);
    for (int c = 0; c < 3; c++) {
        CHECK(fabsf(rad_flat[c] - noon.sky_horizon[c]) < 1e-6f, "horizon radiance [%d] %g", c, rad_flat[c]);
        CHECK(rad_down[c] < rad_flat[c] && rad_down[c] > 0.0f, "below the horizon [%d]", c);
    }
    vrg_sky_radiance(&noon, noon.sun_dir, rad);
    float off[3] = {noon.sun_dir[0] + 0.3f, noon.sun_dir[1], noon.sun_dir[2]};
    float len = sqrtf(off[0] * off[0] + off[1] * off[1] + off[2] * off[2]), rad_off[3];
    for (int c = 0; c < 3; c++)
        off[c] /= len;
    vrg_sky_radiance(&noon, off, rad_off);
    CHECK(sum3(rad) > sum3(rad_off), "no glow towards the sun");

    /* The moon lights the night: opposite the sun, dim and bluish, the key
     * light while the sun is down, and nothing lights at the switch. */
    float kd[3], ke, kr[3];
    CHECK(fabsf(night.moon_elevation - 60.0f) < 1e-3f && night.moon_dir[1] > 0.8f, "midnight moon elevation %g", night.moon_elevation);
    CHECK(night.moon_radiance[2] > night.moon_radiance[0] && sum3(night.moon_radiance) > 0.3 && sum3(night.moon_radiance) < 0.2 * sum3(noon.sun_radiance),
          "moonlight %g %g %g", night.moon_radiance[0], night.moon_radiance[1], night.moon_radiance[2]);
    CHECK(sum3(noon.moon_radiance) == 0.0, "a moon below the horizon shines");
    vrg_sky_key_light(&noon, kd, &ke, kr);
    CHECK(kd[1] == noon.sun_dir[1] && ke == noon.sun_elevation && kr[0] == noon.sun_radiance[0], "noon's key light is not the sun");
    vrg_sky_key_light(&night, kd, &ke, kr);
    CHECK(kd[1] == night.moon_dir[1] && ke == night.moon_elevation && kr[2] == night.moon_radiance[2], "midnight's key light is not the moon");
    for (float t = 17.995f; t < 18.005f; t += 0.001f) { /* elevation within 0.1 degree of 0 */
        sky_at(t, &s);
        vrg_sky_key_light(&s, kd, &ke, kr);
        CHECK(sum3(kr) < 0.1, "key light jumps at %g h: %g", t, sum3(kr));
    }

    /* Cycling: half a day_length advances 12 hours; frozen when 0. */
    vrg_sky_default(&d);
    d.time_of_day = 9.0f;
    d.day_length = 600.0f;
    vrg_sky_eval(&d, 300.0, &s);
    CHECK(fabsf(s.hours - 21.0f) < 1e-4f, "9 + half a day = %g", s.hours);
    vrg_sky_eval(&d, 600.0 * 3 + 150.0, &s);
    CHECK(fabsf(s.hours - 15.0f) < 1e-4f, "wrap: %g", s.hours);
    vrg_sky_eval(&d, -150.0, &s);
    CHECK(fabsf(s.hours - 3.0f) < 1e-4f, "negative time: %g", s.hours);
    d.day_length = 0.0f;
    vrg_sky_eval(&d, 0.0, &h);
    vrg_sky_eval(&d, 12345.0, &s);
    CHECK(s.hours == 9.0f && memcmp(&s, &h, sizeof s) == 0, "frozen sky changed");
    d.time_of_day = 30.0f;
    vrg_sky_eval(&d, 0.0, &s);
    CHECK(fabsf(s.hours - 6.0f) < 1e-5f, "time_of_day wraps: %g", s.hours);
    return 0;
}

/* ---------------------------------------------------------------- shipped */

static int test_shipped_paths(void)
{
    const char *dir = VRG_SOURCE_DIR "/graphs/paths";
    DIR *d = opendir(dir);
    CHECK(d != NULL, "cannot open %s", dir);
    if (!d)
        return 1;
    int found = 0, named = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n < 6 || strcmp(e->d_name + n - 5, ".path") != 0)
            continue;
        char file[1024];
        snprintf(file, sizeof file, "%s/%s", dir, e->d_name);
        vrg_camera_path p;
        CHECK(vrg_camera_path_load(file, &p, stderr) == 0, "%s does not load", file);
        found++;
        named += !strcmp(e->d_name, "orbit.path") || !strcmp(e->d_name, "walk.path") || !strcmp(e->d_name, "fast-turn.path");
        if (p.count == 0)
            continue;
        CHECK(vrg_camera_path_duration(&p) > 1.0f, "%s is too short", file);
        check_hits_keys(&p);
        check_continuous(&p);
        /* The camera stays in the world (+-208 blocks) and above ground. */
        for (float t = 0.0f; t <= vrg_camera_path_duration(&p); t += 0.01f) {
            vrg_camera c;
            vrg_camera_default(&c);
            vrg_camera_path_eval(&p, t, &c);
            CHECK(fabsf(c.position[0]) < 208.0f && fabsf(c.position[2]) < 208.0f && c.position[1] > 20.0f &&
                      c.position[1] < 128.0f,
                  "%s leaves the world at t=%g", file, t);
        }
        vrg_camera_path_free(&p);
    }
    closedir(d);
    CHECK(named == 3, "orbit, walk and fast-turn: found %d of them", named);
    CHECK(found >= 3, "only %d paths", found);
    return 0;
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(void);
    } cases[] = {{"projection", test_projection}, {"path_keys", test_path_keys}, {"path_errors", test_path_errors}, {"world_range", test_world_range},
                 {"sun", test_sun},               {"shipped_paths", test_shipped_paths}};
    if (argc != 2) {
        fprintf(stderr, "usage: test_camera CASE\n");
        return 2;
    }
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        if (strcmp(argv[1], cases[i].name) == 0) {
            int r = cases[i].fn();
            if (r || failures) {
                fprintf(stderr, "%s: FAILED (%d checks)\n", argv[1], failures);
                return 1;
            }
            printf("%s: ok\n", argv[1]);
            return 0;
        }
    fprintf(stderr, "test_camera: unknown case '%s'\n", argv[1]);
    return 2;
}
