/* voxrg run's automatic render scale (auto_scale.h). */
#include "auto_scale.h"

double vrg_auto_scale_next(double scale, double mean_ms, double halved_from_fps)
{
    double fps = mean_ms > 0 ? 1e3 / mean_ms : 4 * VRG_AUTO_SCALE_FPS;
    int halving_helped = !(halved_from_fps > 0) || fps >= 1.5 * halved_from_fps;
    if (fps < VRG_AUTO_SCALE_FPS && scale / 2 >= VRG_AUTO_SCALE_MIN && halving_helped)
        return scale / 2;
    if (fps >= 4 * VRG_AUTO_SCALE_FPS && scale * 2 <= VRG_AUTO_SCALE_MAX)
        return scale * 2;
    return scale;
}

int vrg_auto_scale_frame(vrg_auto_scale *a, double ms)
{
    if (++a->frames <= VRG_AUTO_SCALE_SKIP)
        return 0;
    a->sum_ms += ms;
    if (a->frames < VRG_AUTO_SCALE_SKIP + VRG_AUTO_SCALE_WINDOW)
        return 0;
    a->mean_ms = a->sum_ms / VRG_AUTO_SCALE_WINDOW;
    double next = vrg_auto_scale_next(a->scale, a->mean_ms, a->halved_from_fps);
    vrg_auto_scale_restart(a);
    if (next == a->scale)
        return 0;
    a->halved_from_fps = next < a->scale ? 1e3 / a->mean_ms : 0;
    a->scale = next;
    return 1;
}

void vrg_auto_scale_restart(vrg_auto_scale *a) { a->frames = 0, a->sum_ms = 0; }
