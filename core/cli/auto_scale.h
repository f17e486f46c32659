/* voxrg run's render scale on a CPU device (VkPhysicalDeviceType CPU),
 * unless --scale or --size sets it: measured and adapted so that the
 * window keeps near VRG_AUTO_SCALE_FPS. Rules, on the mean render time of
 * VRG_AUTO_SCALE_WINDOW frames (the first VRG_AUTO_SCALE_SKIP after a
 * change, which rebuild images and history, not counted): below the target
 * the scale halves (a quarter of the pixels), unless the last halving did
 * not make frames at least 1.5 times as fast (then the time goes elsewhere:
 * the window's own size, presenting); at four times the target or more it
 * doubles (four times the pixels still make the target); it stays within
 * [VRG_AUTO_SCALE_MIN, VRG_AUTO_SCALE_MAX]. */
#ifndef VOXRG_CLI_AUTO_SCALE_H
#define VOXRG_CLI_AUTO_SCALE_H
#define VRG_AUTO_SCALE_FPS 15.0
#define VRG_AUTO_SCALE_START 0.25
#define VRG_AUTO_SCALE_MIN 0.0625
#define VRG_AUTO_SCALE_MAX 1.0
#define VRG_AUTO_SCALE_SKIP 2
#define VRG_AUTO_SCALE_WINDOW 8
typedef struct vrg_auto_scale {
    double scale;
    int frames;     /* since the last change or restart */
    double sum_ms;  /* of the frames counted */
    double mean_ms; /* of the last window decided on */
    double halved_from_fps; /* the rate that made the last change a halving; 0 after a doubling */
} vrg_auto_scale;
/* The scale after frames of mean_ms at scale; halved_from_fps as above. */
double vrg_auto_scale_next(double scale, double mean_ms, double halved_from_fps);
/* A frame rendered in ms: 1 when the window is full and the scale changed
 * (a->scale, a->mean_ms), else 0. */
int vrg_auto_scale_frame(vrg_auto_scale *a, double ms);
/* Measure anew (the window was resized, a graph reloaded, frames paused). */
void vrg_auto_scale_restart(vrg_auto_scale *a);
#endif
