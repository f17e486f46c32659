#ifndef VOXRG_CLI_RUN_H
#define VOXRG_CLI_RUN_H
#include <stdint.h>
typedef struct vrg_run_options {
    const char *graph, *device, *camera, *screenshot;
    const char *ab;     /* a second graph shown right of a draggable divider */
    const char *record; /* write the flight as a camera path here */
    const char *show;   /* a resource to show instead of the output */
    const char *const *sets;
    uint32_t set_count;
    uint32_t width, height; /* window size */
    uint32_t frames;        /* 0: until the window closes */
    int validate;
    double gpu_timeout_s;   /* 0: the default (vrg_context_desc) */
} vrg_run_options;
/* `voxrg run`: returns the exit status. */
int vrg_cli_run(const vrg_run_options *o);
#endif
