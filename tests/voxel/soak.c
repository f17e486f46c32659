#define _POSIX_C_SOURCE 200809L
/* The default graph for thousands of frames while chunks stream in and out.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"
#include "voxrg/camera_path.h"

static double resident_mib(void)
{
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2)
            resident = 0;
        fclose(f);
    }
    return (double)resident * (double)sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

/* Soak: the default (thesis) graph at a tiny size for thousands of frames
 * along walk.path, which streams chunks in and out (radius 3): every frame
 * succeeds under validation (a message fails the run), and resident memory
 * after warm-up stays flat (release build). Leaks are LSan's (the sanitizer
 * build, where the quarantine makes resident memory grow by design). */
static void test_soak(void)
{
    char path[1024], camera_path[1024];
    snprintf(path, sizeof path, "%s/../graphs/thesis.ini", TEST_DIR);
    snprintf(camera_path, sizeof camera_path, "%s/../graphs/paths/walk.path", TEST_DIR);
    static const char *sets[] = {"scene.radius=3", "scene.hysteresis=1"};
    vrg_graph_desc d = {.path = path, .width = 32, .height = 18, .overrides = sets, .override_count = 2};
    vrg_graph *g = NULL;
    vrg_camera_path cp = {0};
    if (vrg_graph_load(ctx, &d, &g) != 0 || vrg_camera_path_load(camera_path, &cp, stderr) != 0) {
        CHECK(0, "cannot load the soak graph or path");
        vrg_graph_destroy(g);
        return;
    }
    const int frames = 3000;
    double warm = 0, last = 0, loaded_max = 0;
    int failed = 0;
    vrg_camera cam = *vrg_graph_camera(g);
    for (int k = 0; k < frames && !failed; k++) {
        /* the 20 s path, played at 10x, back and forth */
        float t = (float)(k % 400) * 0.05f;
        vrg_camera_path_eval(&cp, (k / 400) % 2 ? 20.0f - t : t, &cam);
        vrg_graph_set_camera(g, &cam);
        failed = vrg_graph_frame(g) != 0;
        double loaded = 0;
        vrg_graph_stat(g, "scene", "chunks_loaded", &loaded);
        loaded_max = loaded > loaded_max ? loaded : loaded_max;
        if (k == 500)
            warm = resident_mib();
    }
    last = resident_mib();
    CHECK(!failed, "a frame failed during the soak");
    CHECK(loaded_max > 0, "the soak streamed nothing");
    printf("soak: %d frames, resident %.1f MiB after 500, %.1f MiB at the end\n", frames, warm, last);
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VRG_TEST_ASAN 1
#endif
#endif
#ifndef VRG_TEST_ASAN
    /* ASan keeps freed memory in quarantine, so resident memory climbs there
     * by design; leaks are LSan's business in that build */
    CHECK(last - warm < 16.0, "resident memory grew by %.1f MiB over %d frames", last - warm, frames - 500);
#endif
    vrg_camera_path_free(&cp);
    vrg_graph_destroy(g);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"soak", test_soak, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
