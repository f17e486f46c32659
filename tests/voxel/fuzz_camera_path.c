/* libFuzzer target: camera-path text → parse, then evaluate the curve at
 * times around and between its keys. Any crash, leak or sanitizer report is
 * a bug; so is a parsed path whose curve leaves the world's range. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/camera.h"
#include "voxrg/camera_path.h"

static void check_inside(const vrg_camera *c)
{
    for (int a = 0; a < 3; a++)
        if (!(fabsf(c->position[a]) <= VRG_WORLD_LIMIT))
            abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 16384)
        return 0;
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    vrg_camera_path path;
    if (vrg_camera_path_parse("fuzz.path", text, &path, devnull) == 0) {
        vrg_camera cam;
        vrg_camera_default(&cam);
        float end = vrg_camera_path_duration(&path);
        /* before, at and between the keys, and past the end */
        for (int i = 0; i < path.count; i++) {
            float t = path.keys[i].time;
            float next = i + 1 < path.count ? path.keys[i + 1].time : t + 1.0f;
            for (int s = 0; s < 4; s++) {
                vrg_camera_path_eval(&path, t + (next - t) * (float)s / 4.0f, &cam);
                check_inside(&cam);
            }
        }
        vrg_camera_path_eval(&path, end + 1.0f, &cam);
        vrg_camera_path_eval(&path, -1.0f, &cam);
        vrg_camera_path_eval(&path, NAN, &cam);
        check_inside(&cam);
        vrg_camera_path_free(&path);
    }
    free(text);
    return 0;
}
