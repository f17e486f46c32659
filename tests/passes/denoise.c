#define _POSIX_C_SOURCE 200809L
/* The issue-18 denoiser stages: clamped_reproject (neighbourhood clamp,
 * anti-lag with the fast history), mean_variance (variance of the
 * accumulated mean) and sparse_atrous (the cheaper filter).
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/camera.h"
#include "voxrg/edits.h"
#include "voxrg/sky.h"
#include "voxrg/world.h"

/* Mean and largest blue of reproject.color, and mean history length, over
 * non-sky pixels. */
typedef struct {
    double blue, worst_blue, length;
} light_state;

static light_state read_light(vrg_graph *g)
{
    light_state s = {0, 0, 0};
    vrg_image_data col, len, pos;
    CHECK(vrg_graph_read(g, "reproject.color", &col) == 0 && vrg_graph_read(g, "reproject.length", &len) == 0 &&
              vrg_graph_read(g, "gbuffer.position", &pos) == 0,
          "readback failed");
    if (!col.pixels || !len.pixels || !pos.pixels)
        return s;
    int n = 0;
    for (uint32_t y = 0; y < col.height; y++)
        for (uint32_t x = 0; x < col.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            s.blue += px(&col, x, y, 2);
            s.worst_blue = fmax(s.worst_blue, px(&col, x, y, 2));
            s.length += px(&len, x, y, 0);
            n++;
        }
    CHECK(n > (int)(col.width * col.height) / 2, "only %d pixels see the floor", n);
    s.blue /= n > 0 ? n : 1;
    s.length /= n > 0 ? n : 1;
    free(col.pixels), free(len.pixels), free(pos.pixels);
    return s;
}

/* The light (blue) drops from 1 to 0 after 10 still frames: the state one
 * frame after, with the given settings. */
static light_state after_light_change(const char *clamp, const char *antilag, light_state *before)
{
    static const char *reads[] = {"reproject.color", "reproject.length", "gbuffer.position"};
    const char *sets[] = {clamp, antilag};
    light_state s = {0, 0, 0};
    vrg_graph *g = load_with("denoise_light.ini", sets, 2, reads, 3);
    if (!g)
        return s;
    for (int i = 0; i < 10; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    *before = read_light(g);
    CHECK(vrg_graph_set_param(g, "light.value", 0.0) == 0, "light.value not set");
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    s = read_light(g);
    vrg_graph_destroy(g);
    return s;
}

/* Neighbourhood clamping: once the light has changed, the reprojected
 * history is clamped to this frame's 3x3 neighbourhood, so no pixel keeps
 * the old light; without the clamp 80% of it stays (alpha 0.2). */
static void test_denoise_clamp(void)
{
    light_state before, off = after_light_change("reproject.clamp_k=0", "reproject.antilag=0", &before);
    light_state on = after_light_change("reproject.clamp_k=1.5", "reproject.antilag=0", &before);
    printf("denoise_clamp: blue left %.4f unclamped, %.4f clamped (worst %.4f)\n", off.blue, on.blue, on.worst_blue);
    CHECK(before.blue > 0.99, "before the change the light is %g, want 1", before.blue);
    CHECK(off.blue > 0.75, "unclamped history keeps only %g of the old light: the case no longer shows lag", off.blue);
    CHECK(on.worst_blue < 0.05, "clamped history keeps up to %g of the old light", on.worst_blue);
}

/* Anti-lag: without the clamp, the fast history sees the change within a
 * frame; the slow one moves to it and the history length is cut, where
 * without anti-lag it lags. A still, unchanged light (noise free) must not
 * trigger it: the history grows to full length first. */
static void test_denoise_antilag(void)
{
    light_state before_on, before_off;
    light_state on = after_light_change("reproject.clamp_k=0", "reproject.antilag=1", &before_on);
    light_state off = after_light_change("reproject.clamp_k=0", "reproject.antilag=0", &before_off);
    printf("denoise_antilag: blue left %.4f with anti-lag (length %.2f), %.4f without (length %.2f)\n", on.blue, on.length, off.blue,
           off.length);
    CHECK(before_on.length > 8.5, "anti-lag cut a still history to %g frames (want 9)", before_on.length);
    CHECK(on.blue < 0.6 * off.blue, "anti-lag leaves %g of the old light, without %g", on.blue, off.blue);
    CHECK(on.length < 3 && off.length > 8.5, "history length %g with anti-lag, %g without", on.length, off.length);
}

/* The history length after `frames` frames of a still light under a sun
 * that moves (day_length seconds a day; 0: still) with the given sun_span,
 * no clamp or anti-lag (the light itself does not change: only the stage
 * can cut the history). */
static double length_under_sun(double day_length, double sun_span, int frames)
{
    static const char *reads[] = {"reproject.color", "reproject.length", "gbuffer.position"};
    char day[64], span[64];
    snprintf(day, sizeof day, "scene.day_length=%.17g", day_length);
    snprintf(span, sizeof span, "reproject.sun_span=%.17g", sun_span);
    const char *sets[] = {"reproject.clamp_k=0", "reproject.antilag=0", day, span};
    vrg_graph *g = load_with("denoise_light.ini", sets, 4, reads, 3);
    if (!g)
        return -1;
    for (int i = 0; i < frames; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    light_state s = read_light(g);
    vrg_graph_destroy(g);
    return s.length;
}

/* sun_span: under a moving sun the history is cut to sun_span / the
 * degrees the sun moved since the last frame (here 3.5 frames' worth, not
 * rounded), for a fast day and a slow one (an hour: a few thousandths of a
 * degree a frame, which a 32-bit angle would round to 0); a still sun,
 * even with a tiny sun_span, or sun_span 0 leaves it to grow (to 9 frames
 * after 10, to max_length 32 after 40). */
static void test_denoise_sun_span(void)
{
    vrg_graph *g = load("denoise_light.ini");
    double frame_s = g ? vrg_graph_frame_seconds(g) : 1.0 / 60;
    vrg_graph_destroy(g);
    const double days[] = {20, 3600}; /* seconds: about 0.3 and 0.0017 degrees a frame at 60 fps */
    for (int d = 0; d < 2; d++) {
        double moved = sun_moved_degrees(10, days[d], frame_s, 9);
        CHECK(moved > 1e-3, "the sun moves only %g degrees a frame: the case shows nothing", moved);
        double off = length_under_sun(days[d], 0, 10), on = length_under_sun(days[d], 3.5 * moved, 10);
        printf("denoise_sun_span: a %g s day, sun %.6f degrees a frame; history length %.3f (sun_span %.6f), %.3f (sun_span 0)\n", days[d],
               moved, on, 3.5 * moved, off);
        CHECK(off > 8.99 && off < 9.01, "sun_span 0 cut the history to %g frames (want 9)", off);
        CHECK(fabs(on - 3.5) < 0.01, "a %g s day: the history is %g frames long, want 3.5 (sun_span: 3.5 frames of its motion)", days[d], on);
    }
    double still = length_under_sun(0, 0.01, 40);
    printf("denoise_sun_span: a still sun with sun_span 0.01: history length %.3f\n", still);
    CHECK(still > 31.99 && still < 32.01, "a still sun cut the history to %g frames (want max_length 32)", still);
}

/* mean_variance on a still noisy scene: equal to (m2 - m1^2) / N (N the
 * effective sample count in reproject.color's alpha) once history is
 * old, and falling as the history grows: the variance of the mean, not of
 * one sample (whose estimate stays put). */
static void test_denoise_variance(void)
{
    static const char *reads[] = {"reproject.color", "reproject.moments", "reproject.length", "gbuffer.position", "variance.color"};
    vrg_graph *g = load_with("denoise_blocks.ini", NULL, 0, reads, 5);
    if (!g)
        return;
    double mean_var[2] = {0, 0}, mean_sample_var[2] = {0, 0};
    int frames[2] = {6, 30}, done = 0;
    for (int round = 0; round < 2; round++) {
        for (; done < frames[round]; done++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        vrg_image_data col, mom, len, pos, var;
        CHECK(vrg_graph_read(g, "reproject.color", &col) == 0 && vrg_graph_read(g, "reproject.moments", &mom) == 0 &&
                  vrg_graph_read(g, "reproject.length", &len) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0 &&
                  vrg_graph_read(g, "variance.color", &var) == 0,
              "readback failed");
        int n = 0, bad = 0;
        for (uint32_t y = 0; y < col.height; y++)
            for (uint32_t x = 0; x < col.width; x++) {
                if (px(&pos, x, y, 3) == 0 || px(&len, x, y, 0) + 1 < 4)
                    continue;
                double m1 = px(&mom, x, y, 0), m2 = px(&mom, x, y, 1), sample = fmax(0.0, m2 - m1 * m1);
                double want = sample / fmax(px(&col, x, y, 3), 1.0), got = px(&var, x, y, 3);
                /* half-float output; m2 - m1^2 cancels in float */
                if (fabs(got - want) > 2e-3 * want + 1e-4 * m2 / fmax(px(&col, x, y, 3), 1.0) + 1e-7) {
                    if (bad < 3)
                        fprintf(stderr, "  (%u, %u): gpu %.6g cpu %.6g\n", x, y, got, want);
                    bad++;
                }
                mean_var[round] += got, mean_sample_var[round] += sample, n++;
            }
        CHECK(n > 5000, "round %d: only %d pixels with old history", round, n);
        CHECK(bad == 0, "after %d frames %d pixels differ from (m2 - m1^2) / N", frames[round], bad);
        mean_var[round] /= n > 0 ? n : 1;
        mean_sample_var[round] /= n > 0 ? n : 1;
        vrg_image_data *all[] = {&col, &mom, &len, &pos, &var};
        for (int i = 0; i < 5; i++)
            free(all[i]->pixels);
    }
    printf("denoise_variance: mean %.3g after 6 frames, %.3g after 30 (one sample's: %.3g, %.3g)\n", mean_var[0], mean_var[1],
           mean_sample_var[0], mean_sample_var[1]);
    CHECK(mean_var[1] < 0.5 * mean_var[0], "the variance of the mean fell only from %g to %g", mean_var[0], mean_var[1]);
    CHECK(mean_sample_var[1] > 0.5 * mean_sample_var[0], "one sample's variance fell from %g to %g: the scene is not still",
          mean_sample_var[0], mean_sample_var[1]);
    vrg_graph_destroy(g);
}

static double mse_rgb(const vrg_image_data *a, const vrg_image_data *b)
{
    double e = 0;
    for (uint32_t i = 0; i < a->width * a->height; i++)
        for (int c = 0; c < 3; c++) {
            double d = (double)a->pixels[4 * i + c] - b->pixels[4 * i + c];
            e += d * d;
        }
    return e / (3.0 * a->width * a->height);
}

/* sparse_atrous on the young history of a still scene (4 frames): closer to
 * the converged reference than its input, the accumulated mean (the same
 * graph with every pixel skipped); and with long_history = 1,
 * long_iterations = 0 every pixel with history is copied through. */
static double denoised_mse(const char *set, const vrg_image_data *ref)
{
    static const char *reads[] = {"denoised.color"};
    vrg_graph *g = load_with("denoise_blocks.ini", &set, set ? 1 : 0, reads, 1);
    if (!g)
        return 0;
    for (int i = 0; i < 4; i++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data den;
    double e = 0;
    if (vrg_graph_read(g, "denoised.color", &den) == 0) {
        e = mse_rgb(&den, ref);
        free(den.pixels);
    } else
        CHECK(0, "readback failed");
    vrg_graph_destroy(g);
    return e;
}

static void test_denoise_atrous(void)
{
    static const char *reads[] = {"variance.color", "atrous.color", "reproject.length"};
    static const char *ref_reads[] = {"converge.color"};
    vrg_graph *r = load_with("svgf_blocks_ref.ini", NULL, 0, ref_reads, 1);
    if (!r)
        return;
    for (uint32_t i = 0; i < vrg_graph_subframes(r); i++)
        CHECK(vrg_graph_frame(r) == 0, "reference frame failed");
    vrg_image_data ref;
    CHECK(vrg_graph_read(r, "converge.color", &ref) == 0, "readback failed");
    vrg_graph_destroy(r);
    if (!ref.pixels)
        return;
    double e_in = denoised_mse("atrous.skip_variance=1000000", &ref), e_den = denoised_mse(NULL, &ref);
    printf("denoise_atrous: accumulated mean %.3g, filtered %.3g (%.2fx) after 4 frames\n", e_in, e_den, e_in / e_den);
    CHECK(e_den < 0.6 * e_in, "filtered MSE %.3g against the unfiltered %.3g", e_den, e_in);
    free(ref.pixels);

    const char *sets[] = {"atrous.long_history=1", "atrous.long_iterations=0"};
    vrg_graph *g = load_with("denoise_blocks.ini", sets, 2, reads, 3);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data in, out, len;
    CHECK(vrg_graph_read(g, "variance.color", &in) == 0 && vrg_graph_read(g, "atrous.color", &out) == 0 &&
              vrg_graph_read(g, "reproject.length", &len) == 0,
          "readback failed");
    int kept = 0, changed = 0;
    for (uint32_t i = 0; in.pixels && out.pixels && len.pixels && i < in.width * in.height; i++) {
        if (len.pixels[4 * i] < 1)
            continue;
        kept++;
        for (int c = 0; c < 4; c++)
            /* through a packed half and back: exact */
            changed += in.pixels[4 * i + c] != out.pixels[4 * i + c];
    }
    CHECK(kept > 5000 && changed == 0, "long history: %d of %d pixels' values changed", changed, kept);
    free(in.pixels), free(out.pixels), free(len.pixels);
    vrg_graph_destroy(g);
}

/* Bad settings are errors naming the parameter: feedback past the last
 * iteration, an even window. */
static void test_denoise_settings(void)
{
    static const struct {
        const char *set, *want;
    } cases[] = {
        {"atrous.feedback=9", "feedback = 9: there are only 3 iterations"},
        {"variance.size=4", "size = 4: the window needs a centre"},
    };
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char *buf = NULL;
        size_t len = 0;
        FILE *diag = open_memstream(&buf, &len);
        vrg_graph_desc d = {.path = TEST_DIR "/graphs/denoise_blocks.ini", .diag = diag, .overrides = &cases[c].set, .override_count = 1};
        vrg_graph *g = NULL;
        int rc = vrg_graph_load(ctx, &d, &g);
        fclose(diag);
        CHECK(rc != 0 && buf && strstr(buf, cases[c].want), "%s: not refused with '%s':\n%s", cases[c].set, cases[c].want, buf ? buf : "");
        free(buf);
        vrg_graph_destroy(g);
    }
}

/* A graph's indirect light after a world edit (the case file has none): a
 * camera 16 blocks from a point of the terrain, 40 still frames, then a
 * stone wall 25 wide and 16 high built 3 blocks behind the point. The
 * ground in front of the wall sees the wall instead of sky, and its
 * indirect light (the graph's resource that combine reads) moves toward
 * that of a graph given the same wall 40 frames before (the settled value:
 * the mean of its last 10 frames). */
#define EDIT_FRAMES 32
typedef struct {
    double before, settled, after[EDIT_FRAMES];
    vrg_image_data last, last_position; /* the last frame's indirect light and positions (freed by the caller) */
} edit_response;

/* The graph measured: its file relative to graphs/, the image of its
 * indirect light and up to two parameter settings (NULL: none). */
typedef struct {
    const char *graph, *indirect, *set[2];
} edit_graph;

static int build_wall(vrg_graph *g, vrg_edits *e, const float p[3])
{
    char err[512];
    for (int y = 1; y <= 16; y++)
        for (int x = -12; x <= 12; x++)
            if (vrg_edits_set(e, vrg_graph_world(g), (int)floorf(p[0]) + x, (int)floorf(p[1]) + y, (int)floorf(p[2]) - 3, VRG_BLOCK_STONE, err,
                              sizeof err) != 0) {
                fprintf(stderr, "%s\n", err);
                return -1;
            }
    return 0;
}

/* Mean indirect light (r+g+b)/3 of the pixels whose point lies in front of
 * the wall, not on it: within 4 blocks of p across, 0.5 to 3 blocks in front
 * of the wall's face and 2 of p in height. */
static double front_of_wall(vrg_graph *g, const char *indirect, const float p[3], int *count)
{
    vrg_image_data ind, pos;
    double sum = 0;
    int n = 0;
    if (vrg_graph_read(g, indirect, &ind) != 0 || vrg_graph_read(g, "gbuffer.position", &pos) != 0) {
        CHECK(0, "readback failed");
        return 0;
    }
    for (uint32_t y = 0; y < pos.height; y++)
        for (uint32_t x = 0; x < pos.width; x++) {
            float dx = px(&pos, x, y, 0) - p[0], dz = px(&pos, x, y, 2) - (floorf(p[2]) - 2.0f);
            if (px(&pos, x, y, 3) == 0 || fabsf(dx) > 4 || dz < 0.5f || dz > 3 || fabsf(px(&pos, x, y, 1) - p[1]) > 2)
                continue;
            sum += (px(&ind, x, y, 0) + px(&ind, x, y, 1) + px(&ind, x, y, 2)) / 3;
            n++;
        }
    free(ind.pixels), free(pos.pixels);
    *count = n;
    return n > 0 ? sum / n : 0;
}

/* The graph at 160x90 with its settings, no edit journal, 4 chunks of
 * terrain around the camera: 16 blocks in front of p looking down at it,
 * or (no p) high over the world's middle looking almost straight down. */
static vrg_graph *graph_at(const edit_graph *eg, const float *p)
{
    const char *reads[] = {eg->indirect, "gbuffer.position"};
    const char *sets[4] = {"scene.edits=none", "scene.radius=4"};
    int set_count = 2;
    for (int i = 0; i < 2; i++)
        if (eg->set[i])
            sets[set_count++] = eg->set[i];
    char path[1024];
    snprintf(path, sizeof path, "%s/../graphs/%s", TEST_DIR, eg->graph);
    vrg_graph_desc d = {
        .path = path, .overrides = sets, .override_count = set_count, .width = 160, .height = 90, .readback = reads, .readback_count = 2};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(ctx, &d, &g) == 0, "cannot load %s", path);
    if (!g)
        return NULL;
    vrg_camera cam = *vrg_graph_camera(g);
    if (p) {
        cam.position[0] = p[0], cam.position[1] = p[1] + 10, cam.position[2] = p[2] + 16;
        cam.yaw = 0, cam.pitch = -32;
    } else {
        cam.position[0] = 8, cam.position[1] = 120, cam.position[2] = 8;
        cam.yaw = 0, cam.pitch = -80;
    }
    CHECK(vrg_graph_set_camera(g, &cam) == 0, "camera not set");
    return g;
}

/* The share of the change made over frames from to from + 4 after the edit
 * (their mean: one frame's region mean moves by about a fifth of the
 * change with the noise): (mean - before) / (settled - before). */
static double share_over(const edit_response *r, int from)
{
    double mean = 0;
    for (int k = from - 1; k < from + 4; k++)
        mean += r->after[k] / 5;
    return (mean - r->before) / (r->settled - r->before);
}

/* The point the camera looks at: the terrain at the middle of the view
 * from high over the world (the chunks stream in over the first frames). */
static int edit_point(const edit_graph *eg, float p[3])
{
    vrg_graph *probe = graph_at(eg, NULL);
    if (!probe)
        return -1;
    vrg_image_data pos = {0};
    for (int i = 0; i < 4; i++)
        CHECK(vrg_graph_frame(probe) == 0, "probe frame failed");
    CHECK(vrg_graph_read(probe, "gbuffer.position", &pos) == 0, "probe readback failed");
    int ok = pos.pixels && px(&pos, pos.width / 2, pos.height / 2, 3) != 0;
    if (pos.pixels)
        for (int c = 0; c < 3; c++)
            p[c] = px(&pos, pos.width / 2, pos.height / 2, c);
    CHECK(ok, "the probe sees sky at the centre");
    free(pos.pixels);
    vrg_graph_destroy(probe);
    return ok ? 0 : -1;
}

/* Two graphs of eg at p (g, edited after its first frames, and fresh,
 * given the same edit early on: the light it settles to) and an edit
 * journal in a folder of its own. */
typedef struct {
    char dir[32], path[64];
    vrg_graph *g, *fresh;
    vrg_edits *e;
} edit_session;

static int edit_session_open(edit_session *s, const edit_graph *eg, const float p[3])
{
    char err[512] = "no graph";
    memset(s, 0, sizeof *s);
    snprintf(s->dir, sizeof s->dir, "/tmp/vrg_edit_XXXXXX");
    CHECK(mkdtemp(s->dir) != NULL, "mkdtemp failed");
    snprintf(s->path, sizeof s->path, "%s/test.edits", s->dir);
    s->g = graph_at(eg, p), s->fresh = graph_at(eg, p);
    s->e = s->g ? vrg_edits_open(s->path, "edit-test", vrg_graph_world(s->g), err, sizeof err) : NULL;
    CHECK(s->e != NULL, "%s", err);
    return s->g && s->fresh && s->e ? 0 : -1;
}

static void edit_session_close(edit_session *s)
{
    if (s->e)
        vrg_edits_close(s->e);
    vrg_graph_destroy(s->fresh);
    vrg_graph_destroy(s->g);
    unlink(s->path);
    rmdir(s->dir);
}

static void edit_response_of(const edit_graph *eg, const float p[3], edit_response *r)
{
    edit_session es;
    int n = 0;
    memset(r, 0, sizeof *r);
    if (edit_session_open(&es, eg, p) == 0) {
        vrg_graph *g = es.g, *fresh = es.fresh;
        vrg_edits *e = es.e;
        for (int i = 0; i < 40; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        r->before = front_of_wall(g, eg->indirect, p, &n);
        CHECK(n >= 40, "only %d pixels in front of the wall", n);
        for (int i = 0; i < 4; i++) /* its chunks streamed in, so that the edits land */
            CHECK(vrg_graph_frame(fresh) == 0, "frame failed");
        CHECK(build_wall(g, e, p) == 0 && build_wall(fresh, e, p) == 0, "the edits failed");
        for (int i = 0; i < 40; i++) {
            CHECK(vrg_graph_frame(fresh) == 0, "frame failed");
            if (i >= 30)
                r->settled += front_of_wall(fresh, eg->indirect, p, &n) / 10;
        }
        for (int k = 0; k < EDIT_FRAMES; k++) {
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            r->after[k] = front_of_wall(g, eg->indirect, p, &n);
        }
        CHECK(vrg_graph_read(g, eg->indirect, &r->last) == 0 && vrg_graph_read(g, "gbuffer.position", &r->last_position) == 0,
              "readback failed");
    }
    edit_session_close(&es);
}

/* The pixels whose point lies farther than `margin` blocks from the box
 * lo..hi (blocks) and whose value differs between a and b (two runs of one
 * view); *far: how many lie that far. A cell cut by an edit changes only
 * what reads it, so beyond the cut radius plus the widest cell the two
 * runs of a graph with and without the cut are the same image. */
static int far_differ(const vrg_image_data *a, const vrg_image_data *b, const vrg_image_data *pos, const float lo[3], const float hi[3],
                      float margin, int *far)
{
    int differ = 0;
    *far = 0;
    for (uint32_t y = 0; a->pixels && b->pixels && pos->pixels && y < pos->height; y++)
        for (uint32_t x = 0; x < pos->width; x++) {
            float d2 = 0;
            for (int c = 0; c < 3; c++) {
                float v = px(pos, x, y, c), d = v < lo[c] ? lo[c] - v : v > hi[c] ? v - hi[c] : 0;
                d2 += d * d;
            }
            if (px(pos, x, y, 3) == 0 || d2 <= margin * margin)
                continue;
            (*far)++;
            for (int c = 0; c < 4; c++)
                if (px(a, x, y, c) != px(b, x, y, c)) {
                    differ++;
                    break;
                }
        }
    return differ;
}

/* The screen-space chain interactive.ini shipped with until it took a
 * surface cache (tests/graphs/interactive-chain.ini: no neighbourhood
 * clamp, anti-lag on): most of an edit's change of indirect light shows
 * within 8 to 12 frames despite the history's alpha of 0.05; without
 * anti-lag it lags (so the case sees lag). clamp_k 1.5, the value before
 * the sweep over the case file, answers about as fast: the clamp is not
 * what answers an edit here. (interactive.ini's cache: cache_edit_light.) */
static void test_denoise_edit_light(void)
{
#define CHAIN "../tests/graphs/interactive-chain.ini", "upsample.illumination"
    static const edit_graph shipped_g = {CHAIN, {"reproject.clamp_k=0", "reproject.antilag=1"}},
                            clamped_g = {CHAIN, {"reproject.clamp_k=1.5", "reproject.antilag=1"}},
                            lagging_g = {CHAIN, {"reproject.clamp_k=0", "reproject.antilag=0"}};
#undef CHAIN
    float p[3];
    if (edit_point(&shipped_g, p) != 0)
        return;
    edit_response shipped, clamped, lagging;
    edit_response_of(&shipped_g, p, &shipped);
    edit_response_of(&clamped_g, p, &clamped);
    edit_response_of(&lagging_g, p, &lagging);
    double s = share_over(&shipped, 8), c = share_over(&clamped, 8), l = share_over(&lagging, 8);
    printf("denoise_edit_light: point %.1f %.1f %.1f; indirect in front of the wall before %.4f, settled %.4f\n", p[0], p[1], p[2],
           shipped.before, shipped.settled);
    for (int k = 0; k < 20; k++)
        printf("  frame %2d after the edit: as shipped %.4f, clamp_k 1.5 %.4f, no anti-lag %.4f\n", k + 1, shipped.after[k], clamped.after[k],
               lagging.after[k]);
    printf("denoise_edit_light: share of the change over frames 8 to 12 after the edit: %.2f as shipped, %.2f with clamp_k 1.5, %.2f without "
           "anti-lag\n",
           s, c, l);
    CHECK(fabs(shipped.settled - shipped.before) > 0.05 * shipped.before, "the wall changed the light by only %g of %g: the case shows nothing",
          fabs(shipped.settled - shipped.before), shipped.before);
    CHECK(l < 0.6, "without anti-lag %g of the change showed by frames 8 to 12: the case shows no lag", l);
    CHECK(s > 0.7 && s > l + 0.2, "as shipped only %g of the change showed by frames 8 to 12 (without anti-lag %g)", s, l);
    CHECK(c > 0.7 && fabs(c - s) < 0.15, "with clamp_k 1.5 %g of the change showed by frames 8 to 12, as shipped %g: the clamp answers the edit", c,
          s);
    edit_response *all[] = {&shipped, &clamped, &lagging};
    for (int i = 0; i < 3; i++)
        free(all[i]->last.pixels), free(all[i]->last_position.pixels);
}

/* The world-space caches of surface-cache-4ray.ini, surface-cache-1ray.ini
 * and interactive.ini (half-size samples read at full size) after the
 * same edit. A cell's history is worth up to max_frames (64)
 * frames of its samples; the cells within edit_radius blocks of the blocks
 * an edit changed start over (the frame uniforms' edit box), so the
 * change shows within a few frames. Without it (edit_radius 0) it comes
 * in over about max_frames frames (so the case sees lag). */
static void test_cache_edit_light(void)
{
    static const edit_graph graphs[][2] = {
        {{"surface-cache-4ray.ini", "indirect_cache.color", {NULL, NULL}},
         {"surface-cache-4ray.ini", "indirect_cache.color", {"indirect_cache.edit_radius=0", NULL}}},
        {{"surface-cache-1ray.ini", "indirect_cache.color", {NULL, NULL}},
         {"surface-cache-1ray.ini", "indirect_cache.color", {"indirect_cache.edit_radius=0", NULL}}},
        {{"interactive.ini", "indirect_cache.color", {NULL, NULL}},
         {"interactive.ini", "indirect_cache.color", {"indirect_cache.edit_radius=0", NULL}}},
    };
    for (unsigned i = 0; i < sizeof graphs / sizeof graphs[0]; i++) {
        float p[3];
        edit_response r, lagging;
        if (edit_point(&graphs[i][0], p) != 0)
            return;
        edit_response_of(&graphs[i][0], p, &r);
        edit_response_of(&graphs[i][1], p, &lagging);
        double s = share_over(&r, 8), l = share_over(&lagging, 8);
        printf("cache_edit_light: %s: indirect in front of the wall before %.4f, settled %.4f; share of the change over frames 2 to 6 after the "
               "edit %.2f, 8 to 12 %.2f (edit_radius 0: %.2f, %.2f; 28 to 32 %.2f)\n",
               graphs[i][0].graph, r.before, r.settled, share_over(&r, 2), s, share_over(&lagging, 2), l, share_over(&lagging, 28));
        CHECK(fabs(r.settled - r.before) > 0.05 * r.before, "%s: the wall changed the light by only %g of %g: the case shows nothing",
              graphs[i][0].graph, fabs(r.settled - r.before), r.before);
        CHECK(l < 0.6, "%s: with edit_radius 0 %g of the change showed by frames 8 to 12: the case shows no lag", graphs[i][0].graph, l);
        CHECK(s > 0.7 && s > l + 0.2, "%s: as shipped only %g of the change showed by frames 8 to 12 (with edit_radius 0 %g)", graphs[i][0].graph, s,
              l);
        /* far from the wall (beyond edit_radius 8 and the widest cells'
         * reach) nothing is cut: the same image as without the cut */
        const float lo[3] = {floorf(p[0]) - 12, floorf(p[1]) + 1, floorf(p[2]) - 3}, hi[3] = {floorf(p[0]) + 13, floorf(p[1]) + 17, floorf(p[2]) - 2};
        int far, differ = far_differ(&r.last, &lagging.last, &r.last_position, lo, hi, 24, &far);
        CHECK(far >= 500 && differ == 0, "%s: %d of %d pixels more than 24 blocks from the wall differ from the run without the cut: it cuts too "
              "much", graphs[i][0].graph, differ, far);
        free(r.last.pixels), free(r.last_position.pixels), free(lagging.last.pixels), free(lagging.last_position.pixels);
    }
}

/* A roof of 5x5 blocks 5 above the ground, placed so that its shadow
 * falls on the ground by p (the key light's direction dir) and the view
 * from graph_at's camera to p passes beside it. */
static int build_roof(vrg_graph *g, vrg_edits *e, const float p[3], const float dir[3])
{
    char err[512];
    float reach = 5.0f / dir[1]; /* along dir to 5 blocks up */
    int cx = (int)floorf(p[0] + dir[0] * reach), cz = (int)floorf(p[2] + dir[2] * reach), y = (int)floorf(p[1]) + 5;
    for (int z = cz - 2; z <= cz + 2; z++)
        for (int x = cx - 2; x <= cx + 2; x++)
            if (vrg_edits_set(e, vrg_graph_world(g), x, y, z, VRG_BLOCK_STONE, err, sizeof err) != 0) {
                fprintf(stderr, "%s\n", err);
                return -1;
            }
    return 0;
}

/* Over the ground pixels within 4 blocks of p that the roof shades (sun
 * visibility above 0.7 before it, below 0.3 in a graph given it 40 frames
 * before), the share of the change shown over frames 8 to 12 after it was
 * built: sum(mean - before) / sum(settled - before). */
static double shadow_share(const edit_graph *eg, const float p[3], const float dir[3], int *region, vrg_image_data *last, vrg_image_data *last_position)
{
    edit_session es;
    vrg_image_data before = {0}, settled = {0}, now = {0}, pos = {0};
    double moved = 0, change = 0;
    float *mean = NULL;
    *region = 0;
    if (edit_session_open(&es, eg, p) == 0) {
        vrg_graph *g = es.g, *fresh = es.fresh;
        vrg_edits *e = es.e;
        for (int i = 0; i < 40; i++)
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
        CHECK(vrg_graph_read(g, eg->indirect, &before) == 0, "readback failed");
        for (int i = 0; i < 4; i++) /* its chunks streamed in, so that the edits land */
            CHECK(vrg_graph_frame(fresh) == 0, "frame failed");
        CHECK(build_roof(g, e, p, dir) == 0 && build_roof(fresh, e, p, dir) == 0, "the edits failed");
        for (int i = 0; i < 40; i++)
            CHECK(vrg_graph_frame(fresh) == 0, "frame failed");
        CHECK(vrg_graph_read(fresh, eg->indirect, &settled) == 0, "readback failed");
        mean = before.pixels ? calloc((size_t)before.width * before.height, sizeof *mean) : NULL;
        for (int k = 1; mean && k <= 12; k++) {
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            if (k < 8)
                continue;
            CHECK(vrg_graph_read(g, eg->indirect, &now) == 0, "readback failed");
            for (uint32_t i = 0; now.pixels && i < now.width * now.height; i++)
                mean[i] += now.pixels[4 * i] / 5;
            free(now.pixels);
            now.pixels = NULL;
        }
        CHECK(vrg_graph_read(g, "gbuffer.position", &pos) == 0 && vrg_graph_read(g, eg->indirect, last) == 0, "readback failed");
    }
    for (uint32_t y = 0; mean && settled.pixels && pos.pixels && y < pos.height; y++)
        for (uint32_t x = 0; x < pos.width; x++) {
            float b = px(&before, x, y, 0), s = px(&settled, x, y, 0);
            if (px(&pos, x, y, 3) == 0 || fabsf(px(&pos, x, y, 0) - p[0]) > 4 || fabsf(px(&pos, x, y, 2) - p[2]) > 4 ||
                fabsf(px(&pos, x, y, 1) - p[1]) > 2 || b < 0.7f || s > 0.3f)
                continue;
            moved += mean[y * pos.width + x] - b;
            change += s - b;
            (*region)++;
        }
    free(mean), free(before.pixels), free(settled.pixels);
    *last_position = pos; /* the caller's */
    edit_session_close(&es);
    return change != 0 ? moved / change : 0;
}

/* surface-cache-4ray.ini's sun cache after a roof is built between the
 * ground and the sun: with edit_shadows the cells whose ray to the sun
 * crosses the new blocks start over and the shadow shows within a few
 * frames; without, it comes in over the cells' history (so the case sees
 * lag). */
static void test_cache_edit_shadow(void)
{
    static const edit_graph shipped = {"surface-cache-4ray.ini", "sun_cache.color", {NULL, NULL}},
                            lagging = {"surface-cache-4ray.ini", "sun_cache.color", {"sun_cache.edit_shadows=0", NULL}};
    float p[3], dir[3], elevation, radiance[3];
    if (edit_point(&shipped, p) != 0)
        return;
    vrg_sky_desc desc;
    vrg_sky sky;
    vrg_sky_default(&desc);
    desc.time_of_day = 15; /* the graph's */
    vrg_sky_eval(&desc, 0, &sky);
    vrg_sky_key_light(&sky, dir, &elevation, radiance);
    int region = 0, lag_region = 0;
    vrg_image_data last = {0}, last_pos = {0}, lag_last = {0}, lag_pos = {0};
    double s = shadow_share(&shipped, p, dir, &region, &last, &last_pos), l = shadow_share(&lagging, p, dir, &lag_region, &lag_last, &lag_pos);
    printf("cache_edit_shadow: %d ground pixels the roof shades; share of the change over frames 8 to 12 after it: %.2f, with edit_shadows 0 "
           "%.2f\n",
           region, s, l);
    CHECK(region >= 40, "the roof shades only %d ground pixels in view: the case shows nothing", region);
    CHECK(l < 0.6, "with edit_shadows 0 %g of the change showed by frames 8 to 12: the case shows no lag", l);
    CHECK(s > 0.8 && s > l + 0.2, "as shipped only %g of the change showed by frames 8 to 12 (with edit_shadows 0 %g)", s, l);
    /* far from the roof (its shadow falls within 8 blocks of it here)
     * nothing is cut: the same image as without the cut */
    float reach = 5.0f / dir[1], cx = floorf(p[0] + dir[0] * reach), cz = floorf(p[2] + dir[2] * reach);
    const float lo[3] = {cx - 2, floorf(p[1]) + 5, cz - 2}, hi[3] = {cx + 3, floorf(p[1]) + 6, cz + 3};
    int far, differ = far_differ(&last, &lag_last, &last_pos, lo, hi, 24, &far);
    CHECK(far >= 500 && differ == 0, "%d of %d pixels more than 24 blocks from the roof differ from the run without the cut: it cuts too much",
          differ, far);
    free(last.pixels), free(last_pos.pixels), free(lag_last.pixels), free(lag_pos.pixels);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"denoise_clamp", test_denoise_clamp, 1},
        {"denoise_antilag", test_denoise_antilag, 1},
        {"denoise_sun_span", test_denoise_sun_span, 1},
        {"denoise_variance", test_denoise_variance, 1},
        {"denoise_atrous", test_denoise_atrous, 1},
        {"denoise_settings", test_denoise_settings, 1},
        {"denoise_edit_light", test_denoise_edit_light, 1},
        {"cache_edit_light", test_cache_edit_light, 1},
        {"cache_edit_shadow", test_cache_edit_shadow, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
