/* voxrg plugin ABI.
 *
 * A plugin is a shared object exporting one function, vrg_plugin_entry, that
 * returns a const vrg_plugin_desc. The descriptor tells the runtime everything
 * it needs before any Vulkan object exists: parameters, slots (the resources
 * the plugin reads and writes) and callbacks. The runtime owns every resource;
 * a pass only records commands. See docs/plugin-abi.md for a complete pass. */
#ifndef VOXRG_PLUGIN_H
#define VOXRG_PLUGIN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <vulkan/vulkan.h>
#include "voxrg/camera.h"

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg (built with
 * -fvisibility=hidden); the runtime's internals stay hidden. */
#pragma GCC visibility push(default)

/* Bumped on any incompatible change to what plugins see: the structs and
 * functions below, voxrg/camera.h's, and the voxel layer's voxrg/world.h
 * and voxrg/sky.h, which scene plugins use (VRG_SCENE_SLOTS,
 * vrg_scene_gpu, the frame uniforms). Additions at the end of
 * vrg_plugin_desc are compatible. 2: the layers split (the scene glue moved
 * to libvoxrg_voxel; vrg_pass_set_world became vrg_pass_share) and frames
 * in flight (what the host may write when; vrg_scene_gpu's staging ring). */
#define VRG_ABI_VERSION 3u
#define VRG_PLUGIN_ENTRY_SYMBOL "vrg_plugin_entry"
#define VRG_EXPORT __attribute__((visibility("default")))

typedef enum vrg_plugin_kind {
    VRG_PLUGIN_PASS = 1,  /* a stage of the graph: [pass NAME] */
    VRG_PLUGIN_SCENE = 2, /* the world: [scene]; runs first every frame, never culled */
} vrg_plugin_kind;

typedef enum vrg_param_type {
    VRG_PARAM_FLOAT = 1,
    VRG_PARAM_INT = 2,
    VRG_PARAM_BOOL = 3,
    VRG_PARAM_STRING = 4, /* text the plugin interprets (check it in the check callback) */
} vrg_param_type;

enum vrg_param_flags {
    VRG_PARAM_REPEATABLE = 1u << 0, /* the key may appear many times: a list (e.g. box = ...) */
    /* Read only when the pass is created: vrg_graph_set_param refuses it (it
     * would change nothing), a viewer's panel says it takes a reload. */
    VRG_PARAM_RELOAD = 1u << 1,
};

typedef struct vrg_param_desc {
    const char *name;
    vrg_param_type type;
    double default_value;
    double min, max; /* inclusive; min == max == 0 means unbounded */
    const char *help;
    uint32_t flags;             /* vrg_param_flags */
    const char *default_string; /* VRG_PARAM_STRING: the value when none is given */
} vrg_param_desc;

typedef enum vrg_slot_dir {
    VRG_IN = 1,
    VRG_OUT = 2,
} vrg_slot_dir;

typedef enum vrg_resource_kind {
    VRG_IMAGE = 1,
    VRG_BUFFER = 2,
    /* A top-level acceleration structure (VK_KHR_acceleration_structure).
     * Its `size` is the most instances it holds; 0 creates nothing (a scene
     * not using the ray-query backend). Never aliased. */
    VRG_ACCEL = 3,
} vrg_resource_kind;

/* How a pass touches a resource. The runtime derives usage flags, layouts,
 * pipeline stages and access masks (and so every barrier) from this. */
typedef enum vrg_access {
    VRG_ACCESS_SAMPLED = 1,      /* image: combined image sampler, SHADER_READ_ONLY_OPTIMAL */
    VRG_ACCESS_STORAGE_READ,     /* image: storage image read / buffer: storage buffer read */
    VRG_ACCESS_STORAGE_WRITE,    /* write only; previous contents are not needed */
    VRG_ACCESS_STORAGE_READ_WRITE,
    VRG_ACCESS_UNIFORM,          /* buffer: uniform buffer */
    VRG_ACCESS_TRANSFER_SRC,
    VRG_ACCESS_TRANSFER_DST,
    VRG_ACCESS_AS_BUILD,     /* acceleration structure: built (or updated) by this pass */
    VRG_ACCESS_RAY_QUERY,    /* acceleration structure: traced with ray queries in compute */
    /* buffer: read as a uniform texel buffer (GLSL `usamplerBuffer`,
     * texelFetch) whose texels are the buffer's texel format: 32-bit words
     * (R32_UINT) unless its writer's slot names R32G32_UINT or
     * R32G32B32A32_UINT (see vrg_slot_desc.format). For data read at
     * addresses that differ per invocation: lavapipe fetches texels with
     * SIMD gathers but loads such storage-buffer words one lane at a time
     * (the world is read this way; docs/benchmarks.md has the gain). At most the
     * device's maxTexelBufferElements texels. */
    VRG_ACCESS_TEXEL_READ,
} vrg_access;

enum vrg_slot_flags {
    /* Inputs: may stay unconnected. Image outputs: unconnected unless some
     * pass reads it, it is the graph's output or it is read back. Either way
     * vrg_res_connected() says, and a 1x1 stand-in is bound. */
    VRG_SLOT_OPTIONAL = 1u << 0,
    VRG_SLOT_PERSISTENT = 1u << 1, /* output keeps its contents across frames: never aliased */
};

typedef struct vrg_slot_desc {
    const char *name;
    vrg_slot_dir dir;
    vrg_resource_kind kind;
    vrg_access access;
    /* Images. Outputs: the default format ([resource X] format= overrides it).
     * Inputs: the format required, or VK_FORMAT_UNDEFINED for any.
     * Buffers: the texel format of VRG_ACCESS_TEXEL_READ views, one of
     * VK_FORMAT_R32_UINT, R32G32_UINT, R32G32B32A32_UINT. Outputs: the
     * format every reader's view has (UNDEFINED: R32_UINT), so the writer
     * defines the layout; its size must be whole texels. TEXEL_READ inputs:
     * the format required, or UNDEFINED for the writer's. (One fetch of a
     * 16-byte texel costs about what one of a word does on lavapipe: the
     * world's chunk header is one fetch.) */
    VkFormat format;
    /* Images. Outputs: size as a fraction of the graph size (0 means 1), or
     * absolute when width and height are set. Inputs: the size required in
     * the same terms, or all zero for any size. */
    float scale;
    uint32_t width, height;
    /* Buffers. Outputs: size in bytes. Inputs: minimum size, 0 for any. */
    uint64_t size;
    uint32_t flags; /* vrg_slot_flags */
    const char *help;
    /* Images: mip levels (0 or 1: one; VRG_MIPS_FULL: down to 1x1). Views
     * and barriers cover every level; sampled images with several levels
     * get a trilinear-in-mip, nearest-in-texel sampler. */
    uint32_t mip_levels;
} vrg_slot_desc;

#define VRG_MIPS_FULL 0xffffffffu

/* A pass (or scene) instance inside a graph. Opaque; see the functions below. */
typedef struct vrg_pass vrg_pass;

typedef struct vrg_plugin_desc {
    uint32_t abi_version; /* VRG_ABI_VERSION of the headers the plugin was built with */
    const char *name;
    vrg_plugin_kind kind;
    const char *help;
    /* A folder of this plugin's shaders, searched only when the folder
     * NAME/ beside its NAME.so does not exist (where voxrg_add_pass and
     * voxrg's own build put them, installed or not). An absolute path here
     * is compiled into the plugin: prefer NAME/. May be NULL. */
    const char *shader_dir;
    const vrg_param_desc *params;
    uint32_t param_count;
    const vrg_slot_desc *slots;
    uint32_t slot_count;

    /* Called once the graph is valid, before allocation: request internal
     * resources here and prepare pipelines. Return 0 on success; on failure
     * call vrg_pass_error() first. May be NULL. */
    int (*create)(vrg_pass *pass);
    /* Called after resources are (re)allocated, at start and on every resize.
     * Resource handles and extents are valid from here on. May be NULL. */
    int (*resize)(vrg_pass *pass);
    /* Record the pass. Every slot is already in the layout and access its
     * declaration names. NULL in a pass that lists dispatches: the runtime
     * records each listed dispatch, in order, as vrg_dispatch would (its
     * push constants packed by name from the parameters). Required in a
     * scene and in a pass that lists none. */
    void (*execute)(vrg_pass *pass, VkCommandBuffer cmd);
    /* Free what create() made. May be NULL. */
    void (*destroy)(vrg_pass *pass);
    /* Hot reload: copy state to keep into dst (at most cap bytes); return the
     * size used. restore_state gets it back in the new instance after create. */
    size_t (*save_state)(vrg_pass *pass, void *dst, size_t cap);
    int (*restore_state)(vrg_pass *pass, const void *src, size_t size);
    /* Called while the graph is validated, without a device (also when the
     * graph is loaded with no context at all): check string parameters,
     * reporting with vrg_pass_error_at(), and size outputs with
     * vrg_pass_set_buffer_size(). Return 0 if all is well. May be NULL. */
    int (*check)(vrg_pass *pass);
    /* Every dispatch the pass records (vrg_dispatch): shader, bindings,
     * defines and push_size of each variant; push, domain and the group
     * counts are not read here. vrg_graph_check_shaders compiles and
     * reflects each against the slots before any frame, even without a
     * device; a pass that lists its dispatches records only these
     * (another one fails with VRG-E061). May be NULL: the shaders are then
     * checked at their first dispatch only. */
    const struct vrg_dispatch_desc *dispatches;
    uint32_t dispatch_count; /* at most VRG_MAX_DISPATCHES */
    /* The names a string parameter takes: param_choices[i], for params[i],
     * is NULL or a comma-separated list ("aces,reinhard,linear") whose
     * entries include the parameter's default_string. NULL: no parameter
     * has choices. The runtime checks the graph's value against the list
     * (VRG-E047 at its line) and packs its index into an int or uint
     * push-constant member of the parameter's name; hosts show the list
     * (from vrg_find_plugin's descriptor). A string parameter, not
     * repeatable. */
    const char *const *param_choices;
} vrg_plugin_desc;

#define VRG_MAX_DISPATCHES 256

/* What a plugin exports: its entry (host_abi is the runtime's
 * VRG_ABI_VERSION) and the size of vrg_plugin_desc in the headers it was
 * built with. Fields are only ever added at the end of vrg_plugin_desc
 * within one ABI version: the runtime reads an older plugin's shorter
 * descriptor with the new fields zero (NULL callbacks), and refuses a newer
 * plugin's longer one only if it sets a field the runtime does not know. */
typedef const vrg_plugin_desc *(*vrg_plugin_entry_fn)(uint32_t host_abi);
#define VRG_PLUGIN_DESC_SIZE_SYMBOL "vrg_plugin_desc_size"

/* Every plugin's source defines its entry with this macro. */
#define VRG_PLUGIN(desc_var) \
    VRG_EXPORT const vrg_plugin_desc *vrg_plugin_entry(uint32_t host_abi) { (void)host_abi; return &(desc_var); } \
    VRG_EXPORT extern const uint32_t vrg_plugin_desc_size; \
    const uint32_t vrg_plugin_desc_size = (uint32_t)sizeof(vrg_plugin_desc);

/* ---- What the runtime gives a pass ------------------------------------- */

typedef struct vrg_features {
    int ray_query;              /* VK_KHR_ray_query enabled */
    int acceleration_structure; /* VK_KHR_acceleration_structure enabled */
    int ray_tracing_pipeline;   /* VK_KHR_ray_tracing_pipeline enabled */
    int timestamps;             /* per-pass GPU timestamps work */
    float timestamp_period_ns;
    uint32_t subgroup_size;
    uint32_t max_texel_buffer_texels; /* maxTexelBufferElements: the most texels a VRG_ACCESS_TEXEL_READ view holds */
} vrg_features;

typedef struct vrg_device {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    const char *name;
    vrg_features features;
} vrg_device;

typedef struct vrg_frame_info {
    uint64_t frame_index;   /* frames since the graph was built */
    uint32_t width, height; /* graph size */
    uint32_t seed;          /* [graph] seed */
    int history_valid;      /* 0 on the first frame, after resize, a reset, or a reload that
                             * lost some history (vrg_res_history_valid: per input) */
    double time_s;          /* simulated time: frame_index / [graph] fps */
    vrg_camera camera;      /* this frame's camera ([camera] section, or the host's vrg_graph_set_camera) */
    vrg_camera prev_camera; /* last frame's; equal to camera when history is not valid */
    int resources_new;      /* every resource was just (re)allocated: persistent ones are
                             * cleared, so upload their contents again (but those a
                             * reload kept: vrg_res_fresh tells each) */
    int params_changed;     /* first frame after a reload of the graph (new parameter
                             * values or structure) or vrg_graph_set_param: history
                             * carried over stays valid, but accumulations restart */
    /* Frames in flight ([graph] frames_in_flight): the GPU may still run up
     * to frames_in_flight - 1 earlier frames while this one is recorded.
     * frame_slot (0 .. frames_in_flight - 1) names the slot this frame
     * records into; its ring slices are this frame's alone. (Added at the
     * end: the runtime allocates vrg_frame_info, plugins only read it.) */
    uint32_t frame_slot;
    uint32_t frames_in_flight;
} vrg_frame_info;

#define VRG_MAX_FRAMES_IN_FLIGHT 4

/* A resource a pass can name: one of its slots or an internal resource. */
typedef struct vrg_res {
    int id; /* -1: not connected */
} vrg_res;

const vrg_device *vrg_pass_device(const vrg_pass *pass);
const vrg_frame_info *vrg_pass_frame(const vrg_pass *pass);
const char *vrg_pass_name(const vrg_pass *pass);
void *vrg_pass_user(const vrg_pass *pass);
void vrg_pass_set_user(vrg_pass *pass, void *user);
/* While a hot reload builds the graph that replaces a running one (from
 * create() until the reload ends: create, resize, restore_state): the pass
 * of the same name in the graph being replaced, if it runs the same loaded
 * plugin (the same file version, so its vrg_pass_user() is the same kind of
 * object) and was created; else NULL. The old graph stays whole until the
 * reload ends: destroyed after the new graph is ready, or running on if the
 * reload fails. A pass may share what its predecessor built (the terrain
 * scene its generated world, reference-counted) instead of building it
 * again; each instance's destroy() then releases its share. */
vrg_pass *vrg_pass_previous_instance(const vrg_pass *pass);
/* Report an error that names this pass (and its plugin); returns -1. */
int vrg_pass_error(vrg_pass *pass, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The graph line that connects slot `slot` (its in.NAME / out.NAME key),
 * for vrg_pass_error_at; 0 where the graph does not connect it. */
int vrg_pass_slot_line(const vrg_pass *pass, const char *slot);
/* An error at a line of the graph file (e.g. a parameter's, from vrg_param_item). */
int vrg_pass_error_at(vrg_pass *pass, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* A warning at a line of the graph file (0: naming the pass instead): the
 * pass goes on (VRG-W006). */
void vrg_pass_warn_at(vrg_pass *pass, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Text read from a file, made safe to quote in a message: copies `len`
 * bytes of `text` into `out` (`cap` bytes, always terminated) as a
 * terminal shows them, with every byte that is not shown as text written
 * \xNN (\n, \r, \t for those): control characters, DEL, C1 controls,
 * line separators, bidirectional controls and bytes that are not UTF-8.
 * So a file's bytes cannot move the cursor, recolour the terminal or forge
 * a line of their own. Backslashes stay, so escaping twice changes
 * nothing. Too long for `cap`, it is cut at a character and ends in
 * "...". Messages of the runtime (vrg_pass_error...) are escaped so
 * already; a plugin needs this for text it prints itself. Returns out. */
const char *vrg_escape(char *out, size_t cap, const char *text, size_t len);
/* The graph file's path as the host gave it ("" for a graph loaded from
 * text): files a parameter names are relative to its folder. */
const char *vrg_pass_graph_path(const vrg_pass *pass);
/* Names a data file whose content decides what the pass renders (a
 * scene's model, its edit journal), from check(), which runs on every
 * load, with or without a device. A path that does not exist is named
 * too: creating the file changes the frames. Hosts compare and cache
 * frames by these files' content (vrg_graph_sources lists them,
 * vrg_graph_same_world compares a scene's). 0, or -1 after the error. */
int vrg_pass_input_file(vrg_pass *pass, const char *path);
/* Opens an existing file to read (or append to) only when it is a regular
 * file, without blocking: a FIFO, a device or a socket named where a file
 * belongs would block the open or never end. flags as open(2)'s, O_CLOEXEC
 * added; mode as fopen's, "r" or "a" forms (nothing is created). The
 * descriptor or stream, or -1 / NULL with errno set: EISDIR for a folder,
 * EINVAL for anything else that is not a regular file. vrg_open_strerror
 * says "not a regular file" for EINVAL, else strerror's text. */
int vrg_open_regular(const char *path, int flags);
FILE *vrg_fopen_regular(const char *path, const char *mode);
const char *vrg_open_strerror(int err);

/* GPU milliseconds of a pass (NULL: this one) in the newest frame known to
 * have finished: with frames in flight an earlier one than this frame
 * (at least frame_index - frames_in_flight); -1 if unknown. */
double vrg_pass_gpu_ms(const vrg_pass *pass, const char *other_pass);

/* A named figure of this frame (e.g. chunks integrated, milliseconds spent
 * on the CPU) that hosts read with vrg_graph_stat / vrg_graph_stat_at. */
void vrg_pass_stat(vrg_pass *pass, const char *name, double value);

/* Parameters by name, after defaults, graph values and the host's overrides
 * (vrg_graph_desc.overrides). */
double vrg_param(const vrg_pass *pass, const char *name);
int vrg_param_int(const vrg_pass *pass, const char *name);
/* String parameters: the value (the last given, or the default). */
const char *vrg_param_string(const vrg_pass *pass, const char *name);
/* Repeatable parameters: how many values, and value i with its graph line
 * (0 when it came from an override or the default). */
int vrg_param_count(const vrg_pass *pass, const char *name);
const char *vrg_param_item(const vrg_pass *pass, const char *name, int i, int *line);
/* Graph line of the string value in effect (0: the default or an override). */
int vrg_param_line(const vrg_pass *pass, const char *name);
/* A string parameter that names one of `choices`: its index, or -1 after
 * reporting "NAME = 'VALUE': expected A, B or C" at the value's line.
 * choices NULL (count ignored): the plugin's own list for it
 * (param_choices), so that the names are written once. */
int vrg_param_choice(vrg_pass *pass, const char *name, const char *const *choices, int count);

/* In check() or create(): the byte size of a buffer output, when it depends
 * on parameters (readers' minimum sizes are checked against it). */
int vrg_pass_set_buffer_size(vrg_pass *pass, const char *slot, uint64_t bytes);
/* What a pass may write from the host, with frames in flight (the GPU may
 * still run earlier frames while execute() records this one):
 *  - its ring slice of this frame (vrg_pass_ring_slice), in execute(), any
 *    number of times until execute() returns;
 *  - memory of vrg_pass_host_buffer and host-visible vrg_pass_buffer only
 *    before the first frame that uses it is submitted (e.g. the atlas
 *    staging, filled in create()); data that changes per frame goes through
 *    a ring.
 * Host writes made before vrg_graph_frame submits are visible to the frame. */

/* In create(): host-visible, coherent, persistently mapped memory owned by
 * the runtime (staging for uploads, written before its first use). Returns
 * the mapping; *buffer is usable as a transfer source. */
void *vrg_pass_host_buffer(vrg_pass *pass, const char *name, uint64_t bytes, VkBuffer *buffer);
/* In create(): a ring of host-visible, coherent, mapped buffers, one per
 * frame slot, each of at least `bytes`, with `usage` (0: TRANSFER_SRC).
 * NULL after reporting an error. */
typedef struct vrg_ring vrg_ring;
vrg_ring *vrg_pass_host_ring(vrg_pass *pass, const char *name, uint64_t bytes, VkBufferUsageFlags usage);
/* In execute(): this frame's slice of the ring, the only ring memory the
 * host may write now (the GPU has finished the frame that used it before).
 * min_bytes larger than the slice grows it (the old buffer is freed once
 * the frames that used it finished). map NULL after reporting an error. */
typedef struct vrg_ring_slice {
    void *map;               /* the host's view, size bytes */
    VkBuffer buffer;         /* this slice alone: offsets start at 0 */
    uint64_t size;
    VkDeviceAddress address; /* when usage has SHADER_DEVICE_ADDRESS, else 0 */
} vrg_ring_slice;
vrg_ring_slice vrg_pass_ring_slice(vrg_pass *pass, vrg_ring *ring, uint64_t min_bytes);
/* In create() or execute(): a buffer kept for the pass's lifetime and owned by the
 * runtime (freed with the pass, or earlier with vrg_pass_free_buffer, which
 * frees it once the frames in flight that may use it have finished).
 * Returns the mapping when host_visible (else a non-NULL token); *address
 * gets the device address when usage has SHADER_DEVICE_ADDRESS. NULL after
 * reporting an error. */
typedef struct vrg_buffer_desc {
    const char *name;
    uint64_t size;
    VkBufferUsageFlags usage;
    int host_visible;
} vrg_buffer_desc;
void *vrg_pass_buffer(vrg_pass *pass, const vrg_buffer_desc *desc, VkBuffer *buffer, VkDeviceAddress *address);
void vrg_pass_free_buffer(vrg_pass *pass, VkBuffer buffer);
/* Frees something the pass made itself (an acceleration structure, a
 * pipeline) once no frame in flight can use it: fn(user) runs after every
 * frame recorded so far has finished, at the latest when the graph is
 * destroyed (after the passes' destroy(), before plugins are unloaded);
 * at once without a device. Things deferred together are freed in reverse
 * order. Returns 0, or -1 after reporting an error. */
int vrg_pass_defer(vrg_pass *pass, void (*fn)(void *user), void *user);
/* The acceleration structure of a VRG_ACCEL slot (VK_NULL_HANDLE if none). */
VkAccelerationStructureKHR vrg_res_accel(const vrg_pass *pass, vrg_res res);

/* In check() or create(): this pass wants n graph frames rendered per output
 * frame with the camera held still (a progressive accumulation converging to
 * a reference). Hosts read the largest request with vrg_graph_subframes. */
void vrg_pass_set_subframes(vrg_pass *pass, uint32_t n);

/* An object of the pass's that hosts look up by name with vrg_graph_shared
 * (a scene shares its voxel world this way: world.h's vrg_graph_world). The
 * runtime keeps only the pointer, until the pass is destroyed or it is
 * shared again under the name (NULL: no longer). Returns 0, or -1 after
 * reporting an error. */
int vrg_pass_share(vrg_pass *pass, const char *name, void *object);
/* Names a Vulkan object the pass made itself ("GRAPH/PASS.NAME") for the
 * validation layer's messages and debuggers; nothing without debug utils. */
void vrg_pass_name_object(vrg_pass *pass, VkObjectType type, uint64_t handle, const char *name);

/* In create() only: a transient resource private to this pass. It lives for
 * the pass's execution alone, so the runtime aliases its memory with other
 * resources. scale: fraction of the graph size. */
vrg_res vrg_pass_request_image(vrg_pass *pass, const char *name, VkFormat format, float scale, vrg_access first_access);
vrg_res vrg_pass_request_buffer(vrg_pass *pass, const char *name, uint64_t size);

/* A slot or internal resource by name. An input and an output may share a
 * name: "in.color" / "out.color" choose; a bare name is the first declared. */
vrg_res vrg_pass_res(const vrg_pass *pass, const char *name);
int vrg_res_connected(vrg_res res);
VkImage vrg_res_image(const vrg_pass *pass, vrg_res res);
VkImageView vrg_res_view(const vrg_pass *pass, vrg_res res);
VkBuffer vrg_res_buffer(const vrg_pass *pass, vrg_res res);
VkExtent2D vrg_res_extent(const vrg_pass *pass, vrg_res res);
/* In execute(): 1 when the resource was allocated at the start of this
 * frame (the graph's first frame, after a resize, or after a reload that
 * did not keep it: vrg_pass_keep_resource; persistent resources are then
 * cleared, transient ones hold nothing defined), so what it held is to be
 * written again; 0 when it holds what earlier frames wrote. Per resource,
 * where frame->resources_new is the graph's. 0 when not connected. */
int vrg_res_fresh(const vrg_pass *pass, vrg_res res);
/* In create(), while a hot reload builds this instance: the resource of
 * persistent output `slot` (a buffer or image) is to continue the one the
 * same slot of vrg_pass_previous_instance wrote, contents, layout and all,
 * instead of starting cleared. For contents derived from state the pass
 * shares with its previous instance (a scene's world buffer). The hand-over
 * happens only when the reload succeeds, after the previous instance's
 * frames have ended, and only when both resources have the same kind,
 * format, size and mip levels; vrg_res_fresh on the first frame tells
 * whether it did. Outside a reload nothing is kept. 0, or -1 after
 * reporting an error (after create(), no such persistent output). */
int vrg_pass_keep_resource(vrg_pass *pass, const char *slot);
/* For an @prev input: 1 when it holds last frame's value, 0 when it was
 * cleared this frame (first frame, resize, reset, or a structural reload
 * that could not carry this resource over). Finer than the frame's
 * history_valid, which is 0 when any history was lost. Other resources:
 * the frame's history_valid. */
int vrg_res_history_valid(const vrg_pass *pass, vrg_res res);
/* 0 when every named slot has the extent of slot `ref`; else reports the
 * first that differs ("input 'X' is WxH, 'ref' WxH: ...") and returns -1.
 * An unconnected slot of `names` (an optional one's 1x1 stand-in) is
 * skipped; `ref` must be connected, and a name that is no slot of the pass
 * fails (VRG-E062, the API's misuse). */
int vrg_pass_require_same_size(vrg_pass *pass, const char *ref, const char *const *names, int count);
/* An image's format; a buffer's texel format (vrg_slot_desc.format). */
VkFormat vrg_res_format(const vrg_pass *pass, vrg_res res);
uint64_t vrg_res_size(const vrg_pass *pass, vrg_res res);
uint32_t vrg_res_mips(const vrg_pass *pass, vrg_res res);

/* For commands the pass records itself: bring resources to an access with
 * exact barriers (needed between two uses of an internal resource, or when
 * a pass uses a slot in a way other than declared). Batched: as few barrier
 * commands as the runtime's batch size allows, any number of uses. */
typedef struct vrg_use {
    vrg_res res;
    vrg_access access;
} vrg_use;
void vrg_pass_use(vrg_pass *pass, VkCommandBuffer cmd, const vrg_use *uses, uint32_t count);

/* ---- The helper layer: one compute dispatch ---------------------------- */

#define VRG_MAX_BINDINGS 16

typedef struct vrg_binding {
    const char *res;   /* slot ("src", or "in.color"/"out.color") or internal resource name */
    vrg_access access; /* 0: the shader's declaration's (readonly, writeonly, sampler, ...;
                          a slot whose descriptor type it agrees with: the slot's declared access) */
} vrg_binding;

typedef struct vrg_dispatch_desc {
    /* GLSL compute shader. A relative path is searched in the folder NAME/
     * beside the plugin's NAME.so (else its shader_dir), then
     * $VOXRG_SHADER_PATH, then the data folder's shaders/ (docs/plugin-abi.md,
     * "The dispatch helper"). */
    const char *shader;
    /* Set 0, binding i = bindings[i]: list them only for what the shader
     * cannot say, e.g. which of two internal images an iteration reads.
     * When none are given and every binding the shader declares is named
     * after a connected slot (in_X: input X, out_X: output X, a uniform
     * block `frame`: input frame) or an internal resource (in_X, out_X:
     * the resource X), numbered 0 to n-1, each is bound to it, with the
     * access its declaration gives (the slots it does not declare are not
     * bound). Otherwise, with none given, every slot of
     * the pass is bound in declaration order (unconnected optional inputs
     * through their 1x1 stand-ins), except acceleration structures that do
     * not exist, which is why they are declared last. Whenever one is bound
     * at binding i, the shader is compiled with VRG_ACCEL_BINDING=i (the
     * voxel layer's trace.glsl then uses its ray-query backend on it).
     * Either way a shader binding named after a slot (in_X: input X,
     * out_X: output X, a uniform block `frame`: input frame) or an
     * internal resource must be bound to it: a swapped pair is an error
     * naming both (VRG-E083), as is, bound by name, an in_X or out_X
     * that names neither. */
    vrg_binding bindings[VRG_MAX_BINDINGS];
    /* Preprocessor definitions for this variant, "NAME" or "NAME=VALUE",
     * separated by spaces or ';' (each set is its own cached pipeline). */
    const char *defines;
    /* Push constants. push_size 0 (and push NULL): packed by name, the
     * way to push them (vrg_push_float below). Else the bytes at push,
     * exactly the size of the shader's push-constant block (a struct
     * mirroring the block in C: another size is an error), at most 128. */
    const void *push;
    uint32_t push_size;
    /* Dispatch domain: this resource's extent (default: the first image
     * output), divided by the shader's local size, rounded up. */
    const char *domain;
    uint32_t groups_x, groups_y, groups_z; /* explicit group counts, if set */
    /* The shader shades VRG_PIXEL_ROWS rows per invocation (pixel.glsl's
     * vrg_pixel(k) for k < VRG_PIXEL_ROWS): the runtime divides the group
     * count in y by it. VRG_PIXEL_ROWS is 32 on a CPU device, 1 on a GPU. */
    int pixel_loop;
} vrg_dispatch_desc;

/* Push constants by name. A dispatch with push_size 0 whose shader
 * declares a push-constant block fills each member of the block by its
 * name, at the offset reflection reads from the SPIR-V: with the value set
 * by vrg_push_* since the pass's last dispatch, else with the pass's
 * parameter of that name. A member with neither, a value or parameter of
 * another type (a float parameter or vrg_push_float: a float member; an
 * int parameter: int or uint, uint only when its min is 0 or more; a bool
 * parameter or vrg_push_bool: a bool (uint in SPIR-V), int or uint;
 * vrg_push_int: int; vrg_push_uint: uint; a string parameter is not
 * pushed: set its member, e.g. vrg_param_choice's index), a member that
 * is neither a scalar nor an array of them, an array set with another
 * count than its length, or
 * a value set that names no member, is an error at the member's (or the
 * block's) FILE:LINE and fails the dispatch. Values are consumed by the
 * pass's next vrg_dispatch, whatever it returns: set them before each; one
 * set after execute()'s last dispatch fails the frame (VRG-E062). */
void vrg_push_float(vrg_pass *pass, const char *member, float value);
void vrg_push_int(vrg_pass *pass, const char *member, int32_t value);
void vrg_push_uint(vrg_pass *pass, const char *member, uint32_t value);
void vrg_push_bool(vrg_pass *pass, const char *member, int value);
/* An array member (`float lo[9];`): count values, the array's length, of
 * its element type; arrays take only values set so, never a parameter. */
void vrg_push_floats(vrg_pass *pass, const char *member, const float *values, uint32_t count);
void vrg_push_ints(vrg_pass *pass, const char *member, const int32_t *values, uint32_t count);
void vrg_push_uints(vrg_pass *pass, const char *member, const uint32_t *values, uint32_t count);

/* Compiles (once, cached per pass) and records the dispatch, with barriers
 * for bound resources whose state differs from what the binding needs.
 * Returns 0, or -1 after reporting the error (shader compile errors name
 * file:line). */
int vrg_dispatch(vrg_pass *pass, VkCommandBuffer cmd, const vrg_dispatch_desc *desc);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
