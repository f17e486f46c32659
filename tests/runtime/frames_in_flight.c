#define _POSIX_C_SOURCE 200809L
/* Frames in flight ([graph] frames_in_flight), under validation with
 * synchronization validation: a plugin's host ring never races the GPU,
 * readbacks, stats and GPU timings describe the frame they say, a resize,
 * a capture and a timeout with frames in flight.
 * Usage: test_frames_in_flight CASE (ctest registers one test per case). */
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "voxrg/voxrg.h"
#include "check.h"

static int failures;
static vrg_context *ctx;


/* The ring_probe graph with `frames` in flight and a spin of `spin`;
 * messages to diag (NULL: stderr). */
static vrg_graph *probe_graph_to(int frames, double spin, FILE *diag)
{
    char text[512], set[64];
    snprintf(text, sizeof text,
             "[graph]\nname = probe\noutput = color\nwidth = 16\nheight = 16\nframes_in_flight = %d\n\n"
             "[pass probe]\nplugin = ring_probe\nout.color = color\nout.log = log\n",
             frames);
    snprintf(set, sizeof set, "probe.spin=%g", spin);
    static const char *reads[] = {"log"};
    const char *sets[] = {set};
    vrg_graph_desc d = {.path = "<ring_probe>", .text = text, .overrides = sets, .override_count = 1, .readback = reads, .readback_count = 1, .diag = diag};
    vrg_graph *g = NULL;
    if (!CHECK(vrg_graph_load(ctx, &d, &g) == 0, "the ring_probe graph (%d frames, spin %g) does not load", frames, spin))
        return NULL;
    return g;
}

static vrg_graph *probe_graph(int frames, double spin) { return probe_graph_to(frames, spin, NULL); }

static uint32_t log_word(vrg_graph *g, uint64_t frame)
{
    void *data = NULL;
    uint64_t size = 0;
    uint32_t v = 0xffffffffu;
    if (vrg_graph_read_buffer(g, "log", &data, &size) == 0 && size >= 4 * (frame % 64 + 1))
        memcpy(&v, (uint8_t *)data + 4 * (frame % 64), 4);
    free(data);
    return v;
}

/* Frames recorded back to back: each frame's copy runs after the host has
 * recorded the next one, and must still see its own index. With one slice
 * for all frames (the ring made single) frame k's word reads k + 1. */
static void ring_run(int frames_in_flight)
{
    vrg_graph *g = probe_graph(frames_in_flight, 200000);
    if (!g)
        return;
    CHECK(vrg_graph_frames_in_flight(g) == (uint32_t)frames_in_flight, "frames_in_flight %u", vrg_graph_frames_in_flight(g));
    enum { FRAMES = 8 };
    for (int k = 0; k < FRAMES; k++)
        CHECK(vrg_graph_frame(g) == 0, "frame %d failed", k);
    for (uint64_t k = 0; k < FRAMES; k++) {
        uint32_t v = log_word(g, k);
        CHECK(v == k, "frame %llu's ring slice held %u when its copy ran", (unsigned long long)k, v);
    }
    vrg_graph_destroy(g);
}

static void test_ring(void) { ring_run(2); }
static void test_ring_deep(void) { ring_run(4); }
static void test_ring_single_frame(void) { ring_run(1); }

/* Readbacks wait for the frame they describe; stats are the frame recorded. */
static void test_attribution(void)
{
    vrg_graph *g = probe_graph(2, 20000);
    if (!g)
        return;
    for (uint64_t k = 0; k < 6; k++) {
        CHECK(vrg_graph_frame(g) == 0, "frame %llu failed", (unsigned long long)k);
        double stat = -1;
        CHECK(vrg_graph_stat(g, "probe", "frame", &stat) == 0 && stat == (double)k, "after frame %llu: stat frame = %g", (unsigned long long)k, stat);
        uint32_t v = log_word(g, k);
        CHECK(v == k, "after frame %llu: its word reads %u", (unsigned long long)k, v);
    }
    vrg_graph_destroy(g);
}

/* GPU timings arrive a frame later: after frame k is submitted they are of
 * frame k - frames_in_flight (the one waited for), and of frame k after
 * vrg_graph_wait. Odd frames spin long, even ones not at all: every timing
 * must match its frame's parity. The medians are compared, not the
 * extremes: on a loaded machine the CPU device may be preempted in the
 * middle of any one frame, fast or slow. */
static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void test_timings(void)
{
    const int n = 2;
    vrg_graph *g = probe_graph(n, 0);
    if (!g)
        return;
    double slow[8], fast[8];
    int slow_count = 0, fast_count = 0;
    for (int64_t k = 0; k < 10; k++) {
        CHECK(vrg_graph_set_param(g, "probe.spin", k % 2 ? 1000000 : 0) == 0, "set_param failed");
        CHECK(vrg_graph_frame(g) == 0, "frame %lld failed", (long long)k);
        int64_t t = vrg_graph_timed_frame(g);
        CHECK(t == (k >= n ? k - n : -1), "after frame %lld the timings are of frame %lld", (long long)k, (long long)t);
        double ms = vrg_graph_pass_ms(g, 0);
        if (t >= 1 && ms >= 0) { /* frame 0 also pays for lavapipe's first run of the shader */
            if (t % 2)
                slow[slow_count++] = ms;
            else
                fast[fast_count++] = ms;
        }
    }
    CHECK(vrg_graph_wait(g) == 0, "wait failed");
    CHECK(vrg_graph_timed_frame(g) == 9, "after the wait the timings are of frame %lld", (long long)vrg_graph_timed_frame(g));
    if (vrg_context_device(ctx)->features.timestamps) {
        CHECK(slow_count == 4 && fast_count == 3, "%d slow and %d fast frames timed (want 4 and 3)", slow_count, fast_count);
        double slow_median = slow_count ? median(slow, slow_count) : 0, fast_median = fast_count ? median(fast, fast_count) : 0;
        CHECK(vrg_graph_pass_ms(g, 0) >= slow_median * 0.5, "frame 9 (slow) took %g ms, the slow frames' median %g", vrg_graph_pass_ms(g, 0),
              slow_median);
        CHECK(slow_median > 2 * fast_median, "slow frames' timings (median %g ms) are not those of odd frames (fast median %g ms)", slow_median,
              fast_median);
    }
    vrg_graph_destroy(g);
}

/* A resize and a capture with frames in flight: both drain first, and the
 * frames after them are still right. */
static void test_resize_capture(void)
{
    vrg_graph *g = probe_graph(2, 100000);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frames failed");
    CHECK(vrg_graph_resize(g, 8, 8) == 0, "resize failed");
    uint64_t next = 2;
    for (int k = 0; k < 3; k++, next++)
        CHECK(vrg_graph_frame(g) == 0, "frame after resize failed");
    vrg_capture *c = vrg_graph_capture_frame(g);
    CHECK(c != NULL, "capture failed");
    vrg_capture_free(c);
    next++;
    CHECK(vrg_graph_frame(g) == 0, "frame after capture failed");
    next++;
    /* the persistent log was cleared by the resize: frames 2.. are in it */
    for (uint64_t k = 2; k < next; k++)
        CHECK(log_word(g, k) == k, "frame %llu's word reads %u", (unsigned long long)k, log_word(g, k));
    vrg_graph_destroy(g);
}

/* A frame that never ends, found by the next frame that needs its slot:
 * frames 0 and 1 are submitted at once, frame 2 waits for frame 0 and
 * gives up after the context's GPU timeout, naming frame 0 and its pass.
 * (A float count past 2^24 stops growing: the spin never ends.) The GPU
 * still runs it, so the process ends without freeing anything. */
static void test_timeout(void)
{
    FILE *diag = tmpfile();
    vrg_graph *g = probe_graph_to(2, 1e9, diag);
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frames 0 and 1 were not submitted at once");
    CHECK(vrg_graph_frame(g) == -1, "frame 2 did not time out waiting for frame 0");
    CHECK(vrg_context_gpu_busy(ctx), "the device is not marked busy");
    char text[2048] = "";
    rewind(diag);
    size_t n = fread(text, 1, sizeof text - 1, diag);
    text[n] = 0;
    CHECK(strstr(text, "frame 0: pass 'probe' (plugin ring_probe) has run for more than 1 s on the GPU") != NULL, "message: %s", text);
    CHECK(vrg_graph_wait(g) == -1, "a wait after the timeout succeeded");
    uint32_t v = vrg_context_validation_errors(ctx);
    CHECK(v == 0, "%u validation messages", v);
    printf("timeout: %s\n", failures ? "FAILED" : "ok");
    fflush(NULL);
    _exit(failures ? 1 : 0); /* the GPU never idles: nothing may be freed */
}

/* A host that gives up on a graph whose frames never end: destroying it
 * waits for its frames in flight with the GPU timeout, not forever, and
 * waits after that report the busy device at once (no second timeout). */
static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void test_destroy_timeout(void)
{
    FILE *diag = tmpfile();
    vrg_graph *g = probe_graph_to(2, 1e9, diag);
    vrg_graph *other = probe_graph_to(2, 0, diag); /* loaded first: lavapipe creates no view while a frame spins */
    if (!g)
        return;
    CHECK(vrg_graph_frame(g) == 0 && vrg_graph_frame(g) == 0, "frames 0 and 1 were not submitted at once");
    double t0 = seconds();
    vrg_graph_destroy(g); /* returns after the timeout, leaving what the GPU may use */
    double t1 = seconds();
    CHECK(t1 - t0 < 30, "destroy took %.1f s", t1 - t0);
    CHECK(vrg_context_gpu_busy(ctx), "the device is not marked busy");
    vrg_image_data img = {0};
    CHECK(other && vrg_graph_frame(other) == -1, "a frame on the busy device succeeded");
    CHECK(other && vrg_graph_read(other, "color", &img) == -1, "a read on the busy device succeeded");
    CHECK(seconds() - t1 < 0.5, "waits on the busy device took %.1f s: a second timeout", seconds() - t1);
    free(img.pixels);
    char text[4096] = "";
    rewind(diag);
    size_t n = fread(text, 1, sizeof text - 1, diag);
    text[n] = 0;
    CHECK(strstr(text, "error[VRG-E072]: frame 0: pass 'probe'") != NULL, "no timeout message: %s", text);
    CHECK(strstr(text, "VRG-E073") != NULL, "no busy-device message: %s", text);
    printf("destroy_timeout: %s\n", failures ? "FAILED" : "ok");
    fflush(NULL);
    _exit(failures ? 1 : 0); /* the GPU never idles: nothing may be freed */
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*fn)(void);
    } cases[] = {
        {"ring", test_ring},
        {"ring_deep", test_ring_deep},
        {"ring_single_frame", test_ring_single_frame},
        {"attribution", test_attribution},
        {"timings", test_timings},
        {"resize_capture", test_resize_capture},
        {"timeout", test_timeout},
        {"destroy_timeout", test_destroy_timeout},
    };
    if (argc != 2) {
        fprintf(stderr, "usage: test_frames_in_flight CASE\n");
        return 2;
    }
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (strcmp(cases[i].name, argv[1]) != 0)
            continue;
        vrg_context_desc cd = {.validate = 1, .quiet = 1, .gpu_timeout_s = strstr(argv[1], "timeout") ? 1.0 : 0.0};
        if (vrg_context_create(&cd, &ctx) != 0)
            return 1;
        cases[i].fn();
        uint32_t v = vrg_context_validation_errors(ctx);
        CHECK(v == 0, "%u validation messages", v);
        vrg_context_destroy(ctx);
        printf("%s: %s\n", argv[1], failures ? "FAILED" : "ok");
        return failures ? 1 : 0;
    }
    fprintf(stderr, "unknown case '%s'\n", argv[1]);
    return 2;
}
