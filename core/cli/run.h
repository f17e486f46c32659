#ifndef VOXRG_CLI_RUN_H
#define VOXRG_CLI_RUN_H
#include <stdint.h>
typedef struct vrg_run_options {
    const char *graph, *device, *camera, *screenshot;
    const char *ab;     /* a second graph shown right of a draggable divider */
    const char *record; /* write the flight as a camera path here */
    const char *show;   /* a resource to show instead of the output */
    const char *out;    /* the folder screenshots (P, F12) go to, created when the first is taken */
    const char *const *sets;
    uint32_t set_count;
    uint32_t window_w, window_h; /* 0: 1280x720, at most the screen */
    uint32_t width, height;      /* a fixed render size; 0: the window's times scale */
    double scale;                /* render size / window size, (0, 1] */
    int scale_auto;              /* neither --scale nor --size: on a CPU device, adapted (auto_scale.h) */
    int filter;                  /* the upscale to the window: 0 nearest, 1 bilinear */
    uint32_t frames;        /* 0: until the window closes */
    int validate;
    int check_finite;       /* NaN/Inf checks after each pass (vrg_graph_desc.check_finite) */
    double gpu_timeout_s;   /* 0: the default (vrg_context_desc) */
} vrg_run_options;
/* `voxrg run`: returns the exit status. */
int vrg_cli_run(const vrg_run_options *o);
#endif
