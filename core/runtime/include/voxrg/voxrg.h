/* voxrg host API: what a program that renders graphs calls (the voxrg
 * command, the tests and embedding programs alike). */
#ifndef VOXRG_H
#define VOXRG_H

#include <stdio.h>
#include "voxrg/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg (built with
 * -fvisibility=hidden); the runtime's internals stay hidden. */
#pragma GCC visibility push(default)

/* The project's version, "MAJOR.MINOR.PATCH" (VRG_VERSION_STRING of
 * voxrg/version.h for the headers a program was built with). */
const char *vrg_version(void);
/* The folder of voxrg's shipped data (shaders/, graphs/, graphs/paths/):
 * PREFIX/share/voxrg next to an installed libvoxrg, found from the
 * library's own location; the source tree while it runs from its build
 * folder. "" if the library cannot tell where it is. */
const char *vrg_data_dir(void);

typedef struct vrg_context vrg_context;
typedef struct vrg_graph vrg_graph;

typedef struct vrg_context_desc {
    int validate;       /* VK_LAYER_KHRONOS_validation + synchronization validation; messages count as errors */
    const char *device; /* index or part of the name; NULL: prefer a real GPU, else lavapipe */
    int quiet;          /* no "using device" line */
    /* For presenting to a window: the instance extensions the window system
     * needs (glfwGetRequiredInstanceExtensions) and VK_KHR_swapchain on the
     * device. The device's queue must then be able to present. */
    const char *const *instance_extensions;
    uint32_t instance_extension_count;
    int swapchain;
    /* Seconds one frame's GPU work may take before vrg_graph_frame gives up,
     * naming the pass still running. 0: $VOXRG_GPU_TIMEOUT when set, else
     * VRG_GPU_TIMEOUT_DEFAULT_S. */
    double gpu_timeout_s;
} vrg_context_desc;

/* Generous for the slowest shipped graph (reference.ini) on a CPU device. */
#define VRG_GPU_TIMEOUT_DEFAULT_S 120.0
/* After vrg_interrupt, how long a GPU wait under way still lets its frame
 * finish (so that an interrupted run can end after a complete frame). */
#define VRG_INTERRUPT_GRACE_S 1.0

/* Returns 0 and a context, or -1 after printing why to stderr. */
int vrg_context_create(const vrg_context_desc *desc, vrg_context **out);
void vrg_context_destroy(vrg_context *ctx);
const vrg_device *vrg_context_device(const vrg_context *ctx);
/* A compute shader module compiled from GLSL the way passes' shaders are
 * (#include, the device defines); errors go to stderr. For host-side
 * stages such as a viewer's display. VK_NULL_HANDLE on failure. */
VkShaderModule vrg_compile_compute_shader(vrg_context *ctx, const char *path, const char *defines);
/* Validation messages seen so far (each also printed to stderr). */
uint32_t vrg_context_validation_errors(const vrg_context *ctx);
/* Async-signal-safe (a SIGINT/SIGTERM handler may call it): every GPU wait
 * of this process, the one under way and all later ones, gives up once the
 * work has had VRG_INTERRUPT_GRACE_S more; that frame then fails, naming the
 * pass that was running. There is no undoing it: the process is ending. */
void vrg_interrupt(void);
/* 1 once a GPU wait gave up (timeout or vrg_interrupt): the device still
 * runs that work and waiting for it could block forever, so
 * vrg_graph_destroy and vrg_context_destroy then leave the Vulkan objects
 * (and the memory they hold) alone. The process should flush its output and
 * end with _exit (exit's handlers could touch the busy driver). */
int vrg_context_gpu_busy(const vrg_context *ctx);

typedef struct vrg_graph_desc {
    const char *path;             /* the graph file (also used in messages) */
    const char *text;             /* optional: graph text instead of reading path */
    const char *const *overrides; /* "pass.param=value", applied over the file's values */
    uint32_t override_count;
    uint32_t width, height;       /* 0: the graph's own size */
    const char *const *readback;  /* resources to keep readable after a frame (output is always) */
    uint32_t readback_count;
    FILE *diag;                   /* where errors go; NULL: stderr */
    /* Keep every image resource alive to the end of the frame (they then do
     * not share memory), so that a viewer can show any of them
     * (vrg_graph_show). */
    int keep_images;
    /* After each pass a compute shader checks every float image it writes
     * through its slots (images of a half, float or r11g11b10f format; not
     * the pass's internal images, vrg_pass_request_image, which stay
     * unchecked); an image of more than 2^28 texels fails the load. The first
     * NaN or infinity fails the frame (vrg_graph_frame or the wait that
     * ends it) with an error (VRG-E081) naming the pass, resource, channel,
     * pixel (the first in row order) and frame, and the pass's inputs at
     * that pixel. It implies keep_images and one frame in flight, so that
     * the inputs are still there when the frame ends. A context with
     * validation checks too, keeping memory and frames in flight as loaded,
     * without the inputs. */
    int check_finite;
} vrg_graph_desc;

/* Parse, validate, compile. With ctx, also create the passes and allocate:
 * the graph can render. Without ctx (check-only, fuzzing) memory sizes are
 * estimated from formats. Returns 0, or -1 after printing every error. */
int vrg_graph_load(vrg_context *ctx, const vrg_graph_desc *desc, vrg_graph **out);
void vrg_graph_destroy(vrg_graph *g);

/* Records and submits one frame. With frames in flight ([graph]
 * frames_in_flight, default 2) it returns once the frame is submitted,
 * having waited only for the frame frames_in_flight before this one, so
 * the CPU records the next frame while the GPU runs this one. Returns 0, or
 * -1 on error (also when that wait outlasts the context's gpu_timeout_s,
 * naming the frame and the pass still running).
 *
 * What describes a frame:
 *  - readbacks (vrg_graph_read, vrg_graph_read_buffer, vrg_graph_image)
 *    are of the last frame submitted: they wait for it to end first;
 *  - figures of vrg_pass_stat (vrg_graph_stat) and the CPU times are of the
 *    last frame recorded, known at once;
 *  - GPU timings (vrg_graph_pass_ms) are of the newest frame known to have
 *    ended, vrg_graph_timed_frame; after vrg_graph_wait (or a readback)
 *    that is the last frame submitted. */
/* The first frame that uses a reload or a saved shader waits for the GPU
 * before it returns (vrg_graph_reload_ms ends there). */
int vrg_graph_frame(vrg_graph *g);
/* Waits for every frame in flight: 0, or -1 after reporting a GPU timeout
 * (naming the frame and pass) or an earlier one. */
int vrg_graph_wait(vrg_graph *g);
/* The frame index the GPU timings describe; -1 before any frame ended. */
int64_t vrg_graph_timed_frame(const vrg_graph *g);
/* [graph] frames_in_flight (1..VRG_MAX_FRAMES_IN_FLIGHT, default 2). */
uint32_t vrg_graph_frames_in_flight(const vrg_graph *g);
/* CPU time of the last frame's recording and submission (barriers, the
 * passes' execute callbacks, the submit), without the wait for the GPU. */
double vrg_graph_cpu_ms(const vrg_graph *g);
/* CPU time of pass i's execute callback in the last frame (0 if culled). */
double vrg_graph_pass_cpu_ms(const vrg_graph *g, uint32_t i);
/* For benchmarks: renders one frame (and waits for it) keeping its
 * barriers and dispatches (pipeline, pushed descriptors, push constants,
 * group counts) as data;
 * vrg_capture_record records exactly those commands with direct Vulkan
 * calls, valid when the resources are in the state the captured frame
 * found them in (a frame of the same parity just ran). */
typedef struct vrg_capture vrg_capture;
vrg_capture *vrg_graph_capture_frame(vrg_graph *g);
void vrg_capture_record(const vrg_capture *c, VkCommandBuffer cmd);
void vrg_capture_counts(const vrg_capture *c, uint32_t *dispatches, uint32_t *barrier_batches);
void vrg_capture_free(vrg_capture *c);
/* New graph size: waits for the frames in flight, re-allocates every
 * resource and resets history. */
int vrg_graph_resize(vrg_graph *g, uint32_t width, uint32_t height);
/* Next frame sees history_valid = 0 and cleared @prev images (camera cut). */
void vrg_graph_reset_history(vrg_graph *g);
/* The next frame's index (random sequences, simulated time), so that a
 * frame can be rendered alike however it is reached; history restarts. */
void vrg_graph_set_frame_index(vrg_graph *g, uint64_t index);
/* The camera for the next frame (the previous one becomes prev_camera).
 * Returns 0, or -1 after an error naming the parameter when the position is
 * not finite or outside the world (VRG_WORLD_LIMIT); the camera then stays. */
int vrg_graph_set_camera(vrg_graph *g, const vrg_camera *camera);
const vrg_camera *vrg_graph_camera(const vrg_graph *g);
/* Simulated seconds per frame (1 / [graph] fps). */
double vrg_graph_frame_seconds(const vrg_graph *g);

/* Readback of a resource written in the last frame, as float RGBA per pixel
 * (channels the format lacks are 0, alpha 1). Caller frees pixels. */
typedef struct vrg_image_data {
    uint32_t width, height;
    uint32_t channels; /* channels the format has */
    VkFormat format;
    float *pixels;     /* width * height * 4 */
} vrg_image_data;
int vrg_graph_read(vrg_graph *g, const char *resource, vrg_image_data *out);
/* For presenting: the image of a read-back image resource (the output, or
 * one named in vrg_graph_desc.readback) after the last frame, in
 * VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL and idle (it waits for the frame). A host may copy or blit
 * from it on the graph's queue before the next vrg_graph_frame. */
int vrg_graph_image(vrg_graph *g, const char *resource, VkImage *image, VkExtent2D *extent, VkFormat *format);
/* With keep_images: the image resources a viewer may show (written, not
 * internal), and the one to leave in TRANSFER_SRC after each frame for
 * vrg_graph_image / vrg_graph_image_view (NULL: none besides the output). */
uint32_t vrg_graph_image_count(const vrg_graph *g);
const char *vrg_graph_image_name(const vrg_graph *g, uint32_t i);
int vrg_graph_show(vrg_graph *g, const char *resource);
/* A view of that image (for sampling after moving it to GENERAL and back). */
VkImageView vrg_graph_image_view(vrg_graph *g, const char *resource);
/* A figure a pass recorded with vrg_pass_stat in the last frame: 0, or -1. */
int vrg_graph_stat(const vrg_graph *g, const char *pass, const char *name, double *value);
/* Its i-th figure (for listing): name, or NULL past the end. */
const char *vrg_graph_stat_at(const vrg_graph *g, uint32_t pass, uint32_t i, double *value);

/* One pixel of one image resource as stored after the last frame
 * (vrg_graph_read_pixels). */
typedef struct vrg_pixel_value {
    const char *resource;   /* its name (valid while the graph lives) */
    const char *pass;       /* the pass that writes it */
    VkFormat format;
    uint32_t channels;      /* the channels the format has */
    uint32_t x, y;          /* the texel read: the graph's pixel scaled to the resource's size */
    uint32_t width, height; /* the resource's size */
    int prev;               /* 1: the @prev copy, as the last frame read it */
    int is_uint;            /* an integer format: value holds integers */
    /* 0: not read (bits and value are 0): its memory held another resource
     * later in the frame (load the graph with keep_images to keep it) */
    int kept;
    /* Each channel as stored: the bits of a half (low 16), a float or a
     * uint; a unorm's byte; r11g11b10f's 11-, 11- and 10-bit floats. */
    uint32_t bits[4];
    /* Each channel's exact value: a half or float as that float (NaN and
     * Inf kept), a uint as that integer, a unorm as the float32 of
     * byte / 255 (rgba8_srgb's R, G, B decoded to linear first): the float
     * vrg_graph_read gives and an EXR dump holds, exactly. */
    double value[4];
} vrg_pixel_value;
/* The pixel (x, y) of the graph's size of every image resource the last
 * frame wrote (as vrg_graph_image_count lists them, internal ones left
 * out), in schedule order of the passes that write them, a pass's in slot
 * order, each followed by its @prev copy where the graph reads one. A
 * resource of another size is read at (x * width / graph width, ...).
 * Fills up to max entries and returns how many there are (at most
 * 2 * the graph's resources), or -1 after an error (no frame rendered yet,
 * (x, y) outside the graph's size). Waits for the frames in flight; the
 * next frame may follow at once (the images are left as its barriers
 * expect). */
int vrg_graph_read_pixels(vrg_graph *g, uint32_t x, uint32_t y, vrg_pixel_value *out, uint32_t max);
/* Its channels as `voxrg inspect` prints them: "(c0, c1, ...)", a float
 * to 17 significant digits (read as a double, the value exactly), nan /
 * inf as such, a uint as an integer, an 8-bit format's value followed by
 * its stored bytes: "(v0, ...) bytes (b0, ...)"; "(not kept)" where kept
 * is 0. Returns buf. */
const char *vrg_pixel_value_text(const vrg_pixel_value *v, char *buf, size_t cap);

/* VRG_IMAGE or VRG_BUFFER, or -1 if the graph has no such resource. */
int vrg_graph_resource_kind(const vrg_graph *g, const char *resource);
/* A resource as the graph declares and allocated it. */
typedef struct vrg_resource_info {
    vrg_resource_kind kind;
    VkFormat format;         /* images; buffers: their texel-read views' format, VK_FORMAT_UNDEFINED if none */
    uint32_t width, height;  /* images */
    uint64_t size;           /* buffers: bytes */
    const char *writer;      /* the pass that writes it; NULL: none */
    int history;             /* read through @prev: two copies */
} vrg_resource_info;
/* 0, or -1 if the graph has no such resource. */
int vrg_graph_resource_info(const vrg_graph *g, const char *resource, vrg_resource_info *out);
/* An image resource's bytes as stored, read back after the last frame
 * (as vrg_graph_read): rows of texels of its format, tightly packed. Caller
 * frees *data. */
int vrg_graph_read_texels(vrg_graph *g, const char *resource, void **data, uint64_t *size);
/* Bytes of a buffer resource written in the last frame. Caller frees *data. */
int vrg_graph_read_buffer(vrg_graph *g, const char *resource, void **data, uint64_t *size);

/* The graph as compiled, for people: schedule, resources, barriers, culled
 * passes, memory. */
void vrg_graph_report(const vrg_graph *g, FILE *f);
void vrg_graph_write_dot(const vrg_graph *g, FILE *f);
/* Compiles and reflects every dispatch each pass declares
 * (vrg_plugin_desc.dispatches) and checks it against what the dispatch
 * binds, as the first dispatch would, reporting each mismatch at the
 * shader's FILE:LINE to the graph's diagnostics. Works without a device
 * (the shaders are then compiled for a GPU's workgroup shape; bindings that
 * name a pass's internal resources, which create() makes, are checked for
 * their type and format only with a device). Writes one line per pass to
 * `report` (NULL: none). Returns 0, or -1 when any shader failed. */
int vrg_graph_check_shaders(vrg_graph *g, FILE *report);
uint32_t vrg_graph_pass_count(const vrg_graph *g);
const char *vrg_graph_pass_name(const vrg_graph *g, uint32_t i);
/* Pass i's plugin descriptor (its parameters for a settings UI), NULL past
 * the end. Valid until the graph is destroyed or reloaded. */
const vrg_plugin_desc *vrg_graph_pass_plugin(const vrg_graph *g, uint32_t i);
/* Pass i's GPU milliseconds in frame vrg_graph_timed_frame (the newest
 * that ended; vrg_graph_wait makes it the last one); -1 where not measured. */
double vrg_graph_pass_ms(const vrg_graph *g, uint32_t i);
const char *vrg_graph_output(const vrg_graph *g);
/* Graph frames per output frame: the largest vrg_pass_set_subframes request,
 * at least 1. A host holds the camera for that many frames per output frame
 * (a reference graph's accumulation converges meanwhile). */
uint32_t vrg_graph_subframes(const vrg_graph *g);

/* Hot reload. With on = 1 the graph watches (inotify) every shader file its
 * passes compiled, #included ones too; when one is saved (a completed write
 * or a rename into place) the pipelines that read it are recompiled before
 * the next frame and swapped in. A file that fails to compile leaves the
 * previous pipeline running; its FILE:LINE messages are printed and kept
 * for vrg_graph_reload_error until a reload succeeds. */
int vrg_graph_watch(vrg_graph *g, int on);
const char *vrg_graph_reload_error(const vrg_graph *g);
/* Milliseconds from the save (the newest mtime among the files that
 * changed: shaders, the graph file, a rebuilt plugin's .so) to the end of
 * the first frame that used it, for the last reload; -1 if none. */
double vrg_graph_reload_ms(const vrg_graph *g);
/* Sets a numeric parameter while the graph runs ("pass.param", as in
 * vrg_graph_desc.overrides), checked against its type and range; passes see it from the next
 * frame on, with frame params_changed set once (history stays valid,
 * accumulations restart). String parameters and those flagged
 * VRG_PARAM_RELOAD (read only in create(), e.g. the terrain's radius) are
 * refused (VRG-E045): they need a reload, edit the file. */
int vrg_graph_set_param(vrg_graph *g, const char *pass_param, double value);
/* The value in effect (numeric parameters; strings read as 0). */
int vrg_graph_get_param(vrg_graph *g, const char *pass_param, double *value);
/* Calls fn for each file the graph is built from: the graph file, its
 * plugins, the shaders (with their #includes) compiled so far, i.e.
 * after a frame all those its passes use, and the data files its passes
 * read (vrg_pass_input_file: a scene's model and edit journal), which
 * may not exist. Paths may repeat. */
void vrg_graph_sources(const vrg_graph *g, void (*fn)(void *user, const char *path), void *user);
/* While watching: the graph file was saved since it was loaded. */
int vrg_graph_source_changed(const vrg_graph *g);
/* While watching: reads the files' change events now (vrg_graph_frame
 * does so before it records) and applies saved shaders; returns
 * vrg_graph_source_changed. A host that calls it before each frame and
 * reloads when it returns 1 renders no frame of the old graph after the
 * save, and its reload waits for one frame in flight fewer. */
int vrg_graph_poll_changes(vrg_graph *g);
/* Loads the graph's file again. On any error the running graph stays (*g is
 * unchanged; the messages are printed and kept for vrg_graph_reload_error).
 * On success *g is the new graph and the old one is destroyed: with the same
 * structure (only parameter values changed) history resources are copied
 * over and stay valid; otherwise those whose name, format and size are
 * unchanged are copied and the rest start cleared (vrg_res_history_valid).
 * Frame params_changed tells passes once either way. Frame counter, camera
 * and size carry over. The
 * host's arrays in the original vrg_graph_desc must still be alive. */
int vrg_graph_reload(vrg_graph **g);
void vrg_graph_size(const vrg_graph *g, uint32_t *width, uint32_t *height);
/* 0 when a and b render the same world the same way: equal size, [graph]
 * seed and fps, and the same scene plugin with the same parameters and
 * data files of the same content (a model, an edit journal: both absent
 * or byte for byte equal, wherever they are) (A/B comparisons need it);
 * else -1 with the first difference in `why`. */
int vrg_graph_same_world(const vrg_graph *a, const vrg_graph *b, char *why, size_t cap);

typedef struct vrg_memory_stats {
    uint64_t naive_bytes;    /* every transient resource in its own memory */
    uint64_t aliased_bytes;  /* what the runtime allocated for them */
    uint64_t history_bytes;  /* @prev and persistent resources (both copies) */
    uint32_t transient_count, alias_shared; /* resources, and how many share memory with another */
} vrg_memory_stats;
vrg_memory_stats vrg_graph_memory(const vrg_graph *g);
/* Memory placement of a resource: block (-1 own memory) and byte offset. */
int vrg_graph_placement(const vrg_graph *g, const char *resource, int *block, uint64_t *offset, uint64_t *size);
/* The object a pass shared under name (vrg_pass_share): the first pass in
 * graph order (a scene comes first) that shared one; NULL if none did. */
void *vrg_graph_shared(const vrg_graph *g, const char *name);
/* 1 if the named pass was culled. -1 if no such pass. */
int vrg_graph_pass_culled(const vrg_graph *g, const char *pass);

/* Plugins on the search path, sorted by name, with their file paths;
 * returns how many there are (if more than max, the first max are filled).
 * A file on the path that does not load (or is refused) is reported to
 * `problems` (NULL: not reported) and counted in *failed (NULL: not
 * counted). */
int vrg_list_plugins(const vrg_plugin_desc **descs, const char **paths, int max, FILE *problems, int *failed);
/* The plugin NAME as a graph without plugin_path would load it: 0 with its
 * descriptor and file, or -1 after writing why to `diag` (the folders
 * searched, or why the file found did not load). */
int vrg_find_plugin(const char *name, FILE *diag, const vrg_plugin_desc **desc, const char **path);
const char *vrg_format_label(VkFormat f);
const char *vrg_access_label(vrg_access a);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
