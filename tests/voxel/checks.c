#define _POSIX_C_SOURCE 200809L
/* Checks of the voxel layer's graph keys and camera that need no device.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"
#include "voxrg/world.h"
#include "voxrg/camera.h"

/* traversal = rayquery is refused clearly, naming its line, where the device lacks it. */
static void test_traversal_errors(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = v\nwidth = 8\nheight = 8\n[scene]\nplugin = blocks\ntraversal = rtx\nbox = 0 0 0 1 1 1 red\n"
                       "[pass v]\nplugin = world_debug\nin.world = world\nin.frame = frame\nout.color = v\n";
    vrg_graph_desc d = {.path = "traversal.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(NULL, &d, &g);
    fclose(diag);
    CHECK(rc != 0 && strstr(buf, "traversal.ini:7: error[VRG-E047]: traversal = 'rtx': expected dda or rayquery"), "bad traversal message:\n%s", buf);
    free(buf);
    vrg_graph_destroy(g);
}

/* vrg_graph_set_camera refuses a position outside the world, naming the
 * parameter, and keeps the camera it had (check-only: no device needed). */
static void test_camera_range(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    const char *text = "[graph]\noutput = g\nwidth = 8\nheight = 8\n[camera]\nposition = 1 40 2\n"
                       "[pass gen]\nplugin = pattern\nout.color = g\n";
    vrg_graph_desc d = {.path = "camera.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    CHECK(vrg_graph_load(NULL, &d, &g) == 0, "graph not loaded");
    if (g) {
        vrg_camera far = *vrg_graph_camera(g), nan_cam = far, edge = far;
        far.position[0] = 3e9f;
        nan_cam.position[2] = NAN;
        edge.position[1] = -VRG_WORLD_LIMIT;
        CHECK(vrg_graph_set_camera(g, &far) == -1, "3e9 accepted");
        CHECK(vrg_graph_set_camera(g, &nan_cam) == -1, "NaN accepted");
        CHECK(vrg_graph_camera(g)->position[0] == 1 && vrg_graph_camera(g)->position[2] == 2, "a refused camera was kept");
        CHECK(vrg_graph_set_camera(g, &edge) == 0, "the world's edge refused");
        CHECK(vrg_graph_camera(g)->position[1] == -VRG_WORLD_LIMIT, "the camera at the edge was not kept");
        vrg_graph_destroy(g);
    }
    fclose(diag);
    CHECK(buf && strstr(buf, "vrg_graph_set_camera: camera->position (3e+09, 40, 2) is outside the world"), "message:\n%s", buf ? buf : "");
    free(buf);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"traversal_errors", test_traversal_errors, 0},
        {"camera_range", test_camera_range, 0},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
