/* What every test that drives the runtime shares: the context, CHECK, graph
 * loading and readback helpers, and main's dispatch to one named case.
 * Each program runs one case per invocation (ctest registers one test per
 * case), on lavapipe, with validation and synchronization validation on:
 * any validation message fails the case. */
#ifndef VRG_TEST_HARNESS_H
#define VRG_TEST_HARNESS_H

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "voxrg/voxrg.h"
#include "check.h"

#ifndef TEST_DIR
#define TEST_DIR "."
#endif

/* ctest's SKIP_RETURN_CODE: the device lacks what the case needs */
#define SKIP 77

extern int failures;
/* set by a case that provokes validation messages on purpose */
extern int expect_validation_messages;
/* the case's context: NULL for cases that need no device */
extern vrg_context *ctx;

/* A graph of tests/graphs/, with --set overrides and resources to read back. */
vrg_graph *load_with(const char *name, const char *const *sets, uint32_t nsets, const char *const *reads, uint32_t nreads);
vrg_graph *load(const char *name);
/* A graph given as text (path: for messages only). */
vrg_graph *load_text(const char *text, const char *const *reads, uint32_t nreads);

float px(const vrg_image_data *img, uint32_t x, uint32_t y, int c);
/* Reads names[0..n) back into img[0..n): 0, or -1 after a failed CHECK
 * naming the image (what was read is freed). */
int read_images(vrg_graph *g, const char *const *names, vrg_image_data *img, int n);
/* Degrees the key light (the frame uniforms' sun_dir) moves from frame - 1
 * to frame, frame_s seconds apart, in the default sky with this start time
 * and day length: what a history's sun_span is measured against. */
double sun_moved_degrees(double time_of_day, double day_length, double frame_s, uint64_t frame);
double max_diff(const vrg_image_data *img, const float *want, int channels);

/* printf onto a growing heap string */
void append(char **text, size_t *len, const char *fmt, ...);
/* Writes text to path the way editors save: a new file renamed over the old.
 * A file that cannot be written fails the case (CHECK), saying why. */
void save_file(const char *path, const char *text);

/* A case: `run`, or `run_or_skip` where it may return SKIP; `device`: the
 * runner creates the context (with validation) before and checks its
 * validation messages after. */
typedef struct {
    const char *name;
    void (*run)(void);
    int device;
    int (*run_or_skip)(void);
} test_case;

/* main of a test program: runs the case argv[1] names. */
int run_case(int argc, char **argv, const test_case *cases, size_t count);

#endif
