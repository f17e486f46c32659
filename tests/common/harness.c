#define _POSIX_C_SOURCE 200809L
#include "harness.h"
#include "voxrg/sky.h"

#include <errno.h>

int failures;
int expect_validation_messages;
vrg_context *ctx;

vrg_graph *load_with(const char *name, const char *const *sets, uint32_t nsets, const char *const *reads, uint32_t nreads)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/graphs/%s", TEST_DIR, name);
    vrg_graph_desc d = {.path = path, .overrides = sets, .override_count = nsets, .readback = reads, .readback_count = nreads};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        fprintf(stderr, "cannot load %s\n", path);
        failures++;
        return NULL;
    }
    return g;
}

vrg_graph *load(const char *name) { return load_with(name, NULL, 0, NULL, 0); }

double sun_moved_degrees(double time_of_day, double day_length, double frame_s, uint64_t frame)
{
    vrg_sky_desc d;
    vrg_sky_default(&d);
    d.time_of_day = (float)time_of_day;
    d.day_length = (float)day_length;
    float dir[2][3], elevation, radiance[3];
    for (int i = 0; i < 2; i++) {
        vrg_sky sky;
        vrg_sky_eval(&d, (double)(frame - (uint64_t)i) * frame_s, &sky);
        vrg_sky_key_light(&sky, dir[i], &elevation, radiance);
    }
    /* atan2 of |a x b| and a.b: acos of the dot of two float directions a
     * thousandth of a degree apart is mostly their rounding */
    const float *a = dir[0], *b = dir[1];
    double c[3] = {(double)a[1] * b[2] - (double)a[2] * b[1], (double)a[2] * b[0] - (double)a[0] * b[2], (double)a[0] * b[1] - (double)a[1] * b[0]};
    double dot = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180.0 / 3.14159265358979323846;
}

int read_images(vrg_graph *g, const char *const *names, vrg_image_data *img, int n)
{
    for (int i = 0; i < n; i++)
        if (vrg_graph_read(g, names[i], &img[i]) != 0) {
            CHECK(0, "readback of %s failed", names[i]);
            for (int k = 0; k < i; k++)
                free(img[k].pixels);
            return -1;
        }
    return 0;
}

float px(const vrg_image_data *img, uint32_t x, uint32_t y, int c) { return img->pixels[((size_t)y * img->width + x) * 4 + c]; }

double max_diff(const vrg_image_data *img, const float *want, int channels)
{
    double worst = 0;
    for (size_t p = 0; p < (size_t)img->width * img->height; p++)
        for (int c = 0; c < channels; c++)
            worst = fmax(worst, fabs(img->pixels[p * 4 + c] - want[p * 4 + c]));
    return worst;
}

vrg_graph *load_text(const char *text, const char *const *reads, uint32_t nreads)
{
    vrg_graph_desc d = {.path = "generated.ini", .text = text, .readback = reads, .readback_count = nreads};
    vrg_graph *g = NULL;
    if (vrg_graph_load(ctx, &d, &g) != 0) {
        fprintf(stderr, "cannot load the generated graph\n");
        failures++;
        return NULL;
    }
    return g;
}

void append(char **text, size_t *len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    *text = realloc(*text, *len + (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(*text + *len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    *len += (size_t)n;
}

void save_file(const char *path, const char *text)
{
    char tmp[1100];
    if (!CHECK((size_t)snprintf(tmp, sizeof tmp, "%s.tmp", path) < sizeof tmp, "save_file: path too long: %s", path))
        return;
    FILE *f = fopen(tmp, "w");
    if (!CHECK(f, "save_file: cannot create %s: %s", tmp, strerror(errno)))
        return;
    int wrote = fputs(text, f) >= 0 && fflush(f) == 0 && !ferror(f);
    int saved_errno = errno;
    if (fclose(f) != 0 && wrote) {
        wrote = 0;
        saved_errno = errno;
    }
    if (!CHECK(wrote, "save_file: cannot write %s: %s", tmp, strerror(saved_errno))) {
        remove(tmp);
        return;
    }
    if (!CHECK(rename(tmp, path) == 0, "save_file: cannot rename %s to %s: %s", tmp, path, strerror(errno)))
        remove(tmp);
}

static int run_one(const char *name, const test_case *c)
{
    if (c->device) {
        vrg_context_desc cd = {.validate = 1, .quiet = 1};
        if (vrg_context_create(&cd, &ctx) != 0)
            return 1;
    }
    int rc = 0;
    if (c->run_or_skip)
        rc = c->run_or_skip();
    else
        c->run();
    if (ctx) {
        uint32_t v = vrg_context_validation_errors(ctx);
        CHECK(v == 0 || expect_validation_messages, "%u validation messages", v);
        vrg_context_destroy(ctx);
    }
    if (rc == SKIP && !failures)
        return SKIP;
    printf("%s: %s\n", name, failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}

int run_case(int argc, char **argv, const test_case *cases, size_t count)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s CASE\n", argv[0]);
        return 2;
    }
    for (size_t i = 0; i < count; i++)
        if (strcmp(cases[i].name, argv[1]) == 0)
            return run_one(argv[1], &cases[i]);
    fprintf(stderr, "unknown case '%s'\n", argv[1]);
    return 2;
}
