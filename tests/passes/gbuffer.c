#define _POSIX_C_SOURCE 200809L
/* The G-buffer pass against the CPU pick ray, and its two traversal backends
 * against each other.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"

static const char *gbuffer_reads[] = {"gbuffer.position", "gbuffer.depth", "gbuffer.normal", "gbuffer.ids", "gbuffer.motion"};

/* Normals are unit axis vectors and equal the CPU pick ray's face; ids and
 * depth agree with it too; sky pixels are zero. */
static void test_gbuffer_normals(void)
{
    vrg_graph *g = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data n, depth, ids;
    CHECK(vrg_graph_read(g, "gbuffer.normal", &n) == 0 && vrg_graph_read(g, "gbuffer.depth", &depth) == 0 &&
              vrg_graph_read(g, "gbuffer.ids", &ids) == 0,
          "readback failed");
    const vrg_world *w = vrg_graph_world(g);
    const vrg_camera *cam = vrg_graph_camera(g);
    float fwd[3];
    vrg_camera_forward(cam, fwd);
    int not_axis = 0, wrong = 0, hits = 0, total = (int)(n.width * n.height);
    for (uint32_t y = 0; y < n.height; y++)
        for (uint32_t x = 0; x < n.width; x++) {
            float nx = px(&n, x, y, 0), ny = px(&n, x, y, 1), nz = px(&n, x, y, 2);
            float len = fabsf(nx) + fabsf(ny) + fabsf(nz);
            int axis = (nx != 0) + (ny != 0) + (nz != 0);
            float dir[3];
            vrg_camera_ray(cam, n.width, n.height, (float)x, (float)y, dir);
            vrg_world_hit hit;
            int h = vrg_world_pick(w, cam->position, dir, 1024, &hit);
            if (!h) {
                wrong += len != 0 || px(&ids, x, y, 0) != 0;
                continue;
            }
            hits++;
            not_axis += axis != 1 || len != 1;
            float want_depth = hit.distance * (dir[0] * fwd[0] + dir[1] * fwd[1] + dir[2] * fwd[2]);
            wrong += nx != (float)hit.normal[0] || ny != (float)hit.normal[1] || nz != (float)hit.normal[2] ||
                     px(&ids, x, y, 0) != (float)hit.id || fabsf(px(&depth, x, y, 0) - want_depth) > 1e-3f * want_depth;
        }
    CHECK(not_axis == 0, "%d normals are not unit axis vectors", not_axis);
    CHECK(wrong <= total / 200, "%d of %d pixels disagree with the CPU pick ray (normal, id, depth)", wrong, total);
    CHECK(hits > total / 3, "only %d hits", hits);
    free(n.pixels);
    free(depth.pixels);
    free(ids.pixels);
    vrg_graph_destroy(g);
}

/* docs/lighting.md's motion convention, units and sign: the camera moved
 * by `step` blocks along its own right (axis 0) or up (axis 1) vector moves
 * a point at view depth z by step * f * height / (2 z) pixels on screen
 * (f = 1 / tan(fov_y / 2)), left or up (pixel y grows down), and motion is
 * now minus before: -that along x, +that along y, 0 across. */
static void check_motion_along(vrg_graph *g, vrg_camera cam, int axis, float step)
{
    float f[3], r[3], u[3], yaw = cam.yaw * 3.14159265f / 180.0f;
    vrg_camera_forward(&cam, f);
    r[0] = cosf(yaw), r[1] = 0, r[2] = -sinf(yaw);
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    for (int i = 0; i < 3; i++)
        cam.position[i] += step * (axis == 0 ? r[i] : u[i]);
    vrg_graph_set_camera(g, &cam);
    vrg_image_data m, depth;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_read(g, "gbuffer.motion", &m) == 0 && vrg_graph_read(g, "gbuffer.depth", &depth) == 0,
          "readback failed");
    double focal = 1.0 / tan((cam.fov_y > 0 ? cam.fov_y : 70.0) * 3.14159265358979 / 360.0), worst = 0;
    int bad = 0, checked = 0;
    for (uint32_t y = 0; y < m.height; y++)
        for (uint32_t x = 0; x < m.width; x++) {
            double z = px(&depth, x, y, 0);
            if (z <= 0)
                continue;
            double shift = step * focal * m.height / (2.0 * z);
            double want[2] = {axis == 0 ? -shift : 0, axis == 1 ? shift : 0};
            double e = fabs(px(&m, x, y, 0) - want[0]) + fabs(px(&m, x, y, 1) - want[1]);
            worst = fmax(worst, e);
            bad += e > 0.02 + 0.01 * shift; /* rg16f keeps 11 bits */
            checked++;
        }
    CHECK(checked > 1000 && bad == 0, "camera moved %g blocks along its %s: %d of %d motion vectors off (worst %g px)", step,
          axis == 0 ? "right" : "up", bad, checked, worst);
    free(m.pixels);
    free(depth.pixels);
}

static void check_motion_units(vrg_graph *g)
{
    vrg_camera cam = *vrg_graph_camera(g);
    cam.position[0] = 16, cam.position[1] = 14, cam.position[2] = 40;
    cam.yaw = 20, cam.pitch = -25;
    check_motion_along(g, cam, 0, 0.5f);
    check_motion_along(g, cam, 1, 0.5f);
}

/* Motion vectors: zero for a still camera; for a moving one, each surface
 * pixel minus where the previous camera saw that world point. */
static void test_gbuffer_motion(void)
{
    vrg_graph *g = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    if (!g)
        return;
    vrg_image_data m, pos;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0, "readback failed");
    double worst = 0;
    for (uint32_t i = 0; i < m.width * m.height; i++)
        worst = fmax(worst, fabs(m.pixels[i * 4]) + fabs(m.pixels[i * 4 + 1]));
    CHECK(worst < 0.02, "still camera: motion up to %g px", worst);
    free(m.pixels);

    vrg_camera before = *vrg_graph_camera(g), after = before;
    after.position[0] += 1.0f;
    after.yaw += 2.0f;
    vrg_graph_set_camera(g, &after);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0, "readback failed");
    float vp[16];
    vrg_camera_view_projection(&before, (float)m.width / (float)m.height, vp);
    int bad = 0, checked = 0;
    worst = 0;
    for (uint32_t y = 0; y < m.height; y++)
        for (uint32_t x = 0; x < m.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            float P[4] = {px(&pos, x, y, 0), px(&pos, x, y, 1), px(&pos, x, y, 2), 1}, c[4];
            for (int r = 0; r < 4; r++)
                c[r] = vp[r] * P[0] + vp[4 + r] * P[1] + vp[8 + r] * P[2] + vp[12 + r] * P[3];
            float prev_x = (c[0] / c[3] * 0.5f + 0.5f) * m.width - 0.5f, prev_y = (c[1] / c[3] * 0.5f + 0.5f) * m.height - 0.5f;
            double e = fabs(px(&m, x, y, 0) - ((float)x - prev_x)) + fabs(px(&m, x, y, 1) - ((float)y - prev_y));
            worst = fmax(worst, e);
            bad += e > 0.05;
            checked++;
        }
    CHECK(checked > 1000 && bad == 0, "moving camera: %d of %d motion vectors off (worst %g px)", bad, checked, worst);
    free(m.pixels);
    free(pos.pixels);

    /* a 150-degree turn: points behind the previous camera must not be
     * mirrored onto its screen, their previous pixel is far off screen */
    before.position[0] = before.position[2] = 16.0f; /* above the middle of the floor, looking down */
    before.position[1] = 10.0f;
    before.pitch = -50.0f;
    vrg_graph_set_camera(g, &before);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    after = before;
    after.yaw += 150.0f;
    vrg_graph_set_camera(g, &after);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    CHECK(vrg_graph_read(g, "gbuffer.motion", &m) == 0 && vrg_graph_read(g, "gbuffer.position", &pos) == 0, "readback failed");
    vrg_camera_view_projection(&before, (float)m.width / (float)m.height, vp);
    int behind = 0, mirrored = 0;
    for (uint32_t y = 0; y < m.height; y++)
        for (uint32_t x = 0; x < m.width; x++) {
            if (px(&pos, x, y, 3) == 0)
                continue;
            float P[4] = {px(&pos, x, y, 0), px(&pos, x, y, 1), px(&pos, x, y, 2), 1};
            float w = vp[3] * P[0] + vp[7] * P[1] + vp[11] * P[2] + vp[15];
            if (w > 0)
                continue;
            behind++;
            float prev_x = (float)x - px(&m, x, y, 0), prev_y = (float)y - px(&m, x, y, 1);
            mirrored += prev_x > -1000 && prev_x < (float)m.width + 1000 && prev_y > -1000 && prev_y < (float)m.height + 1000;
        }
    CHECK(behind > 100 && mirrored == 0, "turn: %d of %d points behind the previous camera reproject onto its screen", mirrored, behind);
    free(m.pixels);
    free(pos.pixels);
    check_motion_units(g);
    vrg_graph_destroy(g);
}

/* DDA and ray-query backends render the same G-buffer: same hit/miss per
 * pixel, depth within a small tolerance, same normals and ids. */
static int test_backends_agree(void)
{
    if (!vrg_context_device(ctx)->features.ray_query) {
        printf("backends_agree: skipped: device '%s' has no VK_KHR_ray_query\n", vrg_context_device(ctx)->name);
        return SKIP;
    }
    vrg_graph *a = load_with("gbuffer_blocks.ini", NULL, 0, gbuffer_reads, 5);
    vrg_graph *b = load_with("gbuffer_blocks_rq.ini", NULL, 0, gbuffer_reads, 5);
    if (!a || !b) {
        vrg_graph_destroy(a);
        vrg_graph_destroy(b);
        return 0;
    }
    CHECK(vrg_graph_frame(a) == 0 && vrg_graph_frame(b) == 0, "frame failed");
    vrg_image_data da, db, na, nb, ia, ib;
    CHECK(vrg_graph_read(a, "gbuffer.depth", &da) == 0 && vrg_graph_read(b, "gbuffer.depth", &db) == 0 && vrg_graph_read(a, "gbuffer.normal", &na) == 0 &&
              vrg_graph_read(b, "gbuffer.normal", &nb) == 0 && vrg_graph_read(a, "gbuffer.ids", &ia) == 0 && vrg_graph_read(b, "gbuffer.ids", &ib) == 0,
          "readback failed");
    int miss_mismatch = 0, other = 0, total = (int)(da.width * da.height);
    double worst = 0;
    for (int i = 0; i < total; i++) {
        int ha = da.pixels[i * 4] > 0, hb = db.pixels[i * 4] > 0;
        if (ha != hb) {
            miss_mismatch++;
            continue;
        }
        if (!ha)
            continue;
        worst = fmax(worst, fabs(da.pixels[i * 4] - db.pixels[i * 4]) / da.pixels[i * 4]);
        other += memcmp(na.pixels + i * 4, nb.pixels + i * 4, 3 * sizeof(float)) != 0 || ia.pixels[i * 4] != ib.pixels[i * 4] ||
                 ia.pixels[i * 4 + 1] != ib.pixels[i * 4 + 1];
    }
    CHECK(miss_mismatch <= total / 500, "%d pixels hit in one backend and miss in the other", miss_mismatch);
    CHECK(worst < 1e-3, "depth differs by %.4f%% between backends", worst * 100);
    CHECK(other <= total / 200, "%d pixels differ in normal or ids between backends", other);
    free(da.pixels), free(db.pixels), free(na.pixels), free(nb.pixels), free(ia.pixels), free(ib.pixels);
    vrg_graph_destroy(a);
    vrg_graph_destroy(b);
    return 0;
}

/* The G-buffer's scene and camera, gbuffer_downsample connected to its
 * position and normal and, where asked, its ids and motion. */
static vrg_graph *load_optional(int half_ids, int half_motion, const char *const *reads, uint32_t nreads)
{
    char *text = NULL;
    size_t len = 0;
    append(&text, &len,
           "[graph]\nname = optional\noutput = gbuffer.albedo\nwidth = 96\nheight = 64\n"
           "[camera]\nposition = 16 14 40\nyaw = 0\npitch = -25\n"
           "[scene]\nplugin = blocks\nbox = 0 0 0 31 0 31 white\nbox = 8 1 8 23 6 8 red\nbox = 24 1 20 25 9 21 stone\n"
           "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\n"
           "[pass half]\nplugin = gbuffer_downsample\nin.position = gbuffer.position\nin.normal = gbuffer.normal\n%s%s",
           half_ids ? "in.ids = gbuffer.ids\n" : "", half_motion ? "in.motion = gbuffer.motion\n" : "");
    vrg_graph *g = load_text(text, reads, nreads);
    free(text);
    if (!g)
        return NULL;
    /* two frames, the camera moved between them: motion is not zero */
    vrg_camera cam = *vrg_graph_camera(g);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    cam.position[0] += 1.0f;
    cam.yaw += 2.0f;
    vrg_graph_set_camera(g, &cam);
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    return g;
}

/* Whether `resource`'s line in the graph's report says it is a stand-in. */
static int stand_in(vrg_graph *g, const char *resource)
{
    char *report = NULL, want[64];
    size_t report_len = 0;
    FILE *f = open_memstream(&report, &report_len);
    if (!f)
        return 0;
    vrg_graph_report(g, f);
    fclose(f);
    snprintf(want, sizeof want, "  %s ", resource);
    const char *line = strstr(report, want), *end = line ? strchr(line, '\n') : NULL;
    const char *note = line ? strstr(line, "(unread optional output)") : NULL;
    int yes = note && (!end || note < end);
    free(report);
    return yes;
}

/* gbuffer's depth, ids and motion and gbuffer_downsample's ids and motion
 * are written only where read (an unread one is a 1x1 stand-in: a store
 * and its arithmetic less per pixel). Read one at a time, each is what a
 * graph reading all of them gets, bit for bit (a wrong WRITE_* bit leaves
 * it unwritten), and the ones not read are stand-ins; gbuffer_downsample's
 * position still copies the full pixel under it. */
static void test_optional_outputs(void)
{
    static const char *const all[] = {"gbuffer.position", "gbuffer.depth", "gbuffer.ids", "gbuffer.motion", "half.position", "half.ids", "half.motion"};
    enum { N = sizeof all / sizeof all[0] };
    vrg_graph *g = load_optional(1, 1, all, N);
    if (!g)
        return;
    vrg_image_data want[N];
    int read = read_images(g, all, want, N);
    vrg_graph_destroy(g);
    if (read != 0)
        return;
    int moving = 0;
    for (uint32_t i = 0; i < want[3].width * want[3].height; i++)
        moving += fabsf(want[3].pixels[i * 4]) > 0.5f;
    CHECK(moving > 1000, "the camera's step does not test motion: %d moving pixels", moving);
    /* one optional output read at a time: gbuffer's (nothing connected to
     * half's optional inputs), then half's (its input connected) */
    for (int k = 1; k < N; k++) {
        if (k == 4)
            continue; /* half.position is not optional: read beside each of the others */
        int half = k >= 5;
        const char *reads[] = {all[0], all[4], all[k]};
        g = load_optional(k == 5, k == 6, reads, 3);
        if (!g)
            break;
        for (int r = 1; r < 3; r++) {
            int w = r == 1 ? 4 : k;
            vrg_image_data got;
            if (vrg_graph_read(g, reads[r], &got) != 0) {
                CHECK(0, "%s read alone: readback of %s failed", all[k], reads[r]);
                continue;
            }
            int differ = got.width != want[w].width || got.height != want[w].height;
            for (uint32_t i = 0; !differ && i < got.width * got.height * 4; i++)
                differ += memcmp(&got.pixels[i], &want[w].pixels[i], sizeof(float)) != 0;
            CHECK(!differ, "%s read alone: %s differs from the graph that reads every output", all[k], reads[r]);
            free(got.pixels);
        }
        for (int u = 1; u < N; u++)
            if (u != 4 && u != k && !(half && u == k - 3))
                CHECK(stand_in(g, all[u]), "%s read alone: %s is not an unread stand-in", all[k], all[u]);
        vrg_graph_destroy(g);
    }
    for (int i = 0; i < N; i++)
        free(want[i].pixels);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"gbuffer_normals", test_gbuffer_normals, 1},
        {"gbuffer_motion", test_gbuffer_motion, 1},
        {"backends_agree", NULL, 1, test_backends_agree},
        {"gbuffer_optional_outputs", test_optional_outputs, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
