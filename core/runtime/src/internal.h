/* Internal data model shared by the phases: parse → validate → compile →
 * allocate → record. Each phase lives in its own file and fills in the part
 * of these structs it owns. Beside the model: the helpers most files use.
 * What only a few files use has its own header: the phases (phases.h), the
 * AST (parse.h), plugin loading (plugin_loader.h), shaders (shader.h,
 * reflect.h), the file watch (watch.h), frame capture (capture.h). */
#ifndef VRG_INTERNAL_H
#define VRG_INTERNAL_H

#include <limits.h>
#define VRG_PATH_MAX 4096 /* as PATH_MAX, which <limits.h> defines only for some feature macros */
#include <stdarg.h>
#include <stdio.h>
#include "voxrg/voxrg.h"
#include "diag_codes.h"

#define VRG_NAME_MAX 64
#define VRG_MAX_PASSES 128
#define VRG_MAX_RESOURCES 512
#define VRG_MAX_SLOTS 32
#define VRG_MAX_PARAMS 64
#define VRG_MAX_KEYS 2048
#define VRG_MAX_PLUGINS 128
#define VRG_FRAMES_IN_FLIGHT_DEFAULT 2
#define VRG_PIXEL_BYTES 16 /* a texel of the widest format (rgba32f) */

/* ---- diagnostics (diag.c) ---- */
typedef struct _vrg_diag_entry {
    int line, seq;
    char *text;
} _vrg_diag_entry;
typedef struct _vrg_diag {
    FILE *out;
    const char *file;
    int errors;
    int collect; /* hold messages until _vrg_diag_flush, then print sorted by line */
    _vrg_diag_entry *entries;
    int count, cap;
} _vrg_diag;
/* Every message carries a code of the catalogue (diag_codes.h): errors a
 * VRG_E_ one, warnings a VRG_W_ one. */
#define VRG_DIAG_ENUM(name, code, short_name, meaning) name,
typedef enum { VRG_DIAG_CODES(VRG_DIAG_ENUM) VRG_DIAG_CODE_COUNT } _vrg_diag_code;
#undef VRG_DIAG_ENUM
typedef struct _vrg_diag_info {
    const char *enum_name;  /* "VRG_E_UNKNOWN_KEY": a test checks it agrees with the code */
    const char *code;       /* "VRG-E012" */
    const char *short_name; /* "unknown-key" */
    const char *meaning;
} _vrg_diag_info;
const _vrg_diag_info *_vrg_diag_info_of(_vrg_diag_code code);
void _vrg_error_at(_vrg_diag *d, int line, _vrg_diag_code code, const char *hint, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
void _vrg_error(_vrg_diag *d, _vrg_diag_code code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* An error without a line, with a hint. */
void _vrg_error_hint(_vrg_diag *d, _vrg_diag_code code, const char *hint, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void _vrg_warning_at(_vrg_diag *d, int line, _vrg_diag_code code, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void _vrg_diag_flush(_vrg_diag *d);
/* vrg_pass_error with the code of a problem the runtime finds (pass_api.c) */
int _vrg_pass_fail(vrg_pass *p, _vrg_diag_code code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* ---- defaults (defaults.c): one function per descriptor kind ---- */
vrg_slot_desc _vrg_slot_desc_defaults(const vrg_slot_desc *sd);
vrg_dispatch_desc _vrg_dispatch_desc_defaults(const vrg_dispatch_desc *desc);

/* ---- context (context.c) ---- */
struct vrg_context {
    vrg_device dev;
    char device_name[256];
    VkDebugUtilsMessengerEXT messenger;
    uint32_t validation_errors;
    int validate;
    VkCommandPool cmd_pool;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties mem_props;
    PFN_vkSetDebugUtilsObjectNameEXT set_name;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor;
    VkSampler sampler_linear;
    VkSampler sampler_mips;   /* nearest texels, linear between levels (mip-mapped sampled images) */
    uint32_t group_size[2];   /* VRG_GROUP_X/Y for shaders: see shader.c */
    uint32_t pixel_tile[2];   /* VRG_TILE_W/H: the pixels of a group of a pixel loop (pixel.glsl) */
    uint32_t pixel_rows;      /* VRG_PIXEL_ROWS: tile rows per invocation of a pixel loop */
    int read_without_format;  /* shaderStorageImageReadWithoutFormat enabled (dispatch.c's check) */
    int want_swapchain;       /* vrg_context_desc.swapchain */
    double gpu_timeout_s;     /* resolved: desc, $VOXRG_GPU_TIMEOUT or the default */
    int gpu_busy;             /* a wait gave up: the device never idles (vrg_context_gpu_busy) */
    struct {
        PFN_vkCreateAccelerationStructureKHR create;
        PFN_vkDestroyAccelerationStructureKHR destroy;
        PFN_vkGetAccelerationStructureBuildSizesKHR sizes;
        PFN_vkCmdBuildAccelerationStructuresKHR build;
        PFN_vkGetAccelerationStructureDeviceAddressKHR address;
    } as;
};
/* Waits for fence in short slices, giving up after the context's GPU
 * timeout or an interrupt (vrg_interrupt) plus its grace; either marks the
 * device busy. *waited_s: the seconds waited. */
typedef enum { VRG_WAIT_DONE, VRG_WAIT_TIMEOUT, VRG_WAIT_INTERRUPTED, VRG_WAIT_FAILED } _vrg_wait_result;
_vrg_wait_result _vrg_wait_fence(vrg_context *ctx, VkFence fence, double *waited_s);
void _vrg_name_object(vrg_context *ctx, VkObjectType type, uint64_t handle, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int _vrg_find_memory_type(const vrg_context *ctx, uint32_t bits, VkMemoryPropertyFlags want);

/* ---- a loaded plugin (plugin_loader.h finds and loads them) ---- */
typedef struct _vrg_plugin {
    char name[VRG_NAME_MAX];
    char path[VRG_PATH_MAX];   /* the file loaded: the source, or a reload's private copy */
    char source[VRG_PATH_MAX]; /* the file the build writes (hot reload watches it) */
    void *handle;
    const vrg_plugin_desc *desc; /* &desc_copy once kept */
    vrg_plugin_desc desc_copy;   /* the plugin's descriptor at this runtime's size */
    int keep_fd;                 /* its in-memory copy (a noexec $TMPDIR), else -1 */
    void **libs;                 /* libraries it needs, opened from its RUNPATH before the copy */
    int lib_count;
    unsigned generation; /* load order: the highest of a name is its current version */
    int users;           /* passes of live graphs running it (_vrg_plugin_acquire) */
    struct _vrg_shader_pass *shader_pass; /* a shader-only pass (NAME.comp): its interface, else NULL */
} _vrg_plugin;
/* Why a parameter's descriptor is malformed (why: room for the reason), or NULL (param_desc.c). */
const char *_vrg_param_problem(const vrg_param_desc *pd, char *why, size_t cap);
/* A string parameter's choices (vrg_plugin_desc.param_choices, "a,b,c"):
 * params[i]'s list or NULL; a value's index in it or -1; how many; "a, b
 * or c" for a message, each name whole (to free; NULL when out of
 * memory); why a list is malformed for pd, or NULL. */
const char *_vrg_param_choices(const vrg_plugin_desc *desc, uint32_t i);
int _vrg_choice_index(const char *choices, const char *value);
int _vrg_choice_count(const char *choices);
char *_vrg_choice_words(const char *choices);
const char *_vrg_choices_problem(const vrg_param_desc *pd, const char *choices, char *why, size_t cap);
/* ---- crash reports (crash.c) ---- */
/* What plugin code this thread runs now: a fatal signal names it. */
typedef struct _vrg_running {
    const char *what, *pass, *plugin, *file;
} _vrg_running;
_vrg_running _vrg_running_enter(const char *what, const char *pass, const _vrg_plugin *plugin);
void _vrg_running_leave(_vrg_running before);
/* A plugin copy being loaded, removed if loading dies (NULLs: none). */
void _vrg_crash_cleanup_set(const char *dir, const char *file);
/* ---- the validated graph ---- */
enum { VRG_RES_GRAPH = 0, VRG_RES_INTERNAL = 1 };

typedef struct _vrg_sync {
    VkImageLayout layout;
    VkPipelineStageFlags2 write_stages; /* stages of the last write */
    VkAccessFlags2 write_access;
    VkPipelineStageFlags2 read_stages;  /* stages that read since the last write */
    VkPipelineStageFlags2 visible_stages; /* stages the last write is visible to */
    VkAccessFlags2 visible_access;
} _vrg_sync;

typedef struct _vrg_resource {
    char name[VRG_NAME_MAX + VRG_NAME_MAX + 2];
    int line;                /* [resource] section or first mention */
    vrg_resource_kind kind;
    VkFormat format;         /* images; buffers: the texel format of TEXEL_READ views */
    float scale;
    uint32_t abs_width, abs_height;
    uint64_t size;           /* buffers */
    uint32_t mip_request;    /* as the writer's slot asks: 0/1 one, VRG_MIPS_FULL all */
    uint32_t mips;           /* allocated levels */
    int format_line, size_line; /* where an override was written, 0 if none */
    int bytes_line, extent_line;  /* size = (buffers) / scale, width, height (images) */
    int writer;              /* pass index, -1 none */
    int writer_slot;
    int writer_line;
    int writer_unknown;      /* written by a pass whose plugin failed to load */
    int history;             /* read through @prev somewhere: two copies, kept */
    int history_kept;        /* a reload copied it over: survives the next history reset */
    int history_cleared;     /* cleared at the start of this frame: @prev holds no past */
    int persistent;          /* written by a VRG_SLOT_PERSISTENT slot: kept, not aliased */
    int carried;             /* a reload handed over the previous instance's (vrg_pass_keep_resource): not cleared */
    int fresh;               /* this frame: just allocated and cleared (vrg_res_fresh) */
    int is_output, readback;
    int internal_owner;      /* pass index for internal resources, -1 otherwise (a pass's internal resources: no table of their own) */
    vrg_access internal_first_access;
    /* compile */
    int first_use, last_use; /* schedule positions; -1 unused */
    /* allocate */
    uint32_t width, height;
    VkImageUsageFlags image_usage;
    VkBufferUsageFlags buffer_usage;
    VkImage image[2];
    VkImageView view[2];
    VkBuffer buffer[2];
    VkBufferView texel_view[2];   /* views of the texel format (format) for VRG_ACCESS_TEXEL_READ, made on first use */
    VkDeviceMemory own_memory[2]; /* kept resources have their own memory */
    VkAccelerationStructureKHR accel;
    VkMemoryRequirements req;
    int block;               /* alias heap index, -1 own memory */
    VkDeviceSize offset;
    int overlap_first, overlap_count; /* resources sharing memory: a run of vrg_graph.overlaps */
    _vrg_sync sync[2];
    int touched[2];          /* used already this frame (else its contents are discarded) */
    int dummy;               /* 1x1 stand-in bound to an unconnected optional input */
} _vrg_resource;

typedef struct _vrg_binding_ref {
    int bad;       /* the graph tried to connect it and failed: already reported */
    int res;       /* resource index, -1 unconnected (optional inputs get a dummy) */
    int dummy;     /* res is the 1x1 stand-in: the slot reports unconnected */
    int prev;      /* reads last frame's copy (@prev) */
    int line;
} _vrg_binding_ref;

struct vrg_pass {
    char name[VRG_NAME_MAX];
    int line;
    int is_scene;
    const _vrg_plugin *plugin;
    double params[VRG_MAX_PARAMS];
    _vrg_binding_ref slots[VRG_MAX_SLOTS];
    float output_scale;       /* [pass] output_scale: its relative-size image outputs' scale factor (0: 1) */
    int culled;
    int order;                /* position in schedule, -1 culled */
    vrg_graph *graph;
    void *user;
    int created;
    /* shader pipelines cached by the dispatch helper */
    struct _vrg_pipeline *pipelines;
    int failed;               /* an error during execute: frame fails */
    int plugin_rebuilt;       /* its plugin's file was rebuilt: vrg_graph_reload loads it */
    uint64_t buffer_size[VRG_MAX_SLOTS]; /* vrg_pass_set_buffer_size, 0 if not set */
    uint32_t keep_slots;      /* vrg_pass_keep_resource: bit s, slot s */
    struct _vrg_param_value *strings;     /* string parameter values, in file order */
    int string_count;
    struct _vrg_host_buffer *host_buffers;
    struct vrg_ring *rings;
    struct _vrg_pass_figure *stats; /* vrg_pass_stat: this frame's, grown as named */
    int stat_count, stat_cap;
    VkCommandBuffer cmd;      /* during execute */
    struct _vrg_shared *shared; /* vrg_pass_share */
    char **inputs;            /* vrg_pass_input_file: data files, in the order named */
    int input_count;
    struct _vrg_name_plan *name_plans;   /* dispatch.c: bindings derived from a shader's names */
    struct _vrg_push_value *push_values; /* vrg_push_*: set since the pass's last dispatch */
    int push_count, push_cap;
};

/* A push-constant member's value set by name (vrg_push_float, ...), packed
 * by the pass's next vrg_dispatch (dispatch.c). */
typedef struct _vrg_push_value {
    char name[VRG_NAME_MAX];
    int scalar; /* reflect.h's _vrg_push_scalar of the setter */
    const char *setter;
    uint32_t word;          /* a scalar's */
    uint32_t words[32];     /* an array's (vrg_push_floats, ...): count of them */
    uint32_t count;         /* 0: a scalar */
    int used; /* packed into a member by the dispatch */
} _vrg_push_value;

typedef struct _vrg_pass_figure {
    char *name;
    double value;
} _vrg_pass_figure;

typedef struct _vrg_param_value {
    int param; /* index into the plugin's parameter table */
    char *value;
    int line;  /* 0: --set */
} _vrg_param_value;

typedef struct _vrg_host_buffer {
    char name[VRG_NAME_MAX];
    int host_visible;
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *map;
    VkDeviceAddress address;
    uint64_t size;
    struct _vrg_host_buffer *next;
} _vrg_host_buffer;

/* vrg_pass_host_ring: a host-visible buffer per frame slot, so that the
 * host writes the slot of the frame it records while the GPU reads the
 * others. Slices grow on demand (vrg_pass_ring_slice's min_bytes). */
struct vrg_ring {
    char name[VRG_NAME_MAX];
    VkBufferUsageFlags usage;
    _vrg_host_buffer *slice[VRG_MAX_FRAMES_IN_FLIGHT];
    struct vrg_ring *next;
};

/* Freed once every frame that may use it has finished (frames in flight):
 * a buffer of vrg_pass_free_buffer, or what vrg_pass_defer frees. */
typedef struct _vrg_retired {
    uint64_t serial; /* the frame recording when it was retired: free after it */
    _vrg_host_buffer *buffer;
    void (*fn)(void *user);
    void *user;
    struct _vrg_retired *next;
} _vrg_retired;

void _vrg_pass_free_params(vrg_pass *p);
void _vrg_pass_free_host_buffers(vrg_pass *p);
void _vrg_pass_free_shared(vrg_pass *p);
/* fn(user) once the frames in flight now have ended (the graph has a device). */
void _vrg_retire(vrg_graph *g, void (*fn)(void *user), void *user);
/* Frees what was retired before the newest finished frame; all: everything
 * (the GPU is idle). */
void _vrg_free_retired(vrg_graph *g, int all);
/* Forgets the figures of vrg_pass_stat (a new frame); free: also the table. */
void _vrg_pass_clear_stats(vrg_pass *p, int free_table);
int _vrg_pass_add_string(vrg_pass *p, int param, const char *value, int line, int replace);
/* Every string parameter with choices holds one (else VRG-E047 at its line, -1);
 * the index of params[param]'s value among its choices, -1 if it has none. */
int _vrg_pass_check_choices(vrg_pass *p);
int _vrg_pass_choice(const vrg_pass *p, uint32_t param);
/* A slot ("in.NAME", "out.NAME" or NAME) or internal resource of the pass:
 * its resource, whether it reads @prev, its slot (-1: internal); -1 if the
 * pass has none connected. */
int _vrg_pass_lookup(const vrg_pass *p, const char *name, int *res, int *prev, int *slot);

typedef struct _vrg_barrier_rec {
    int res, copy;
    VkPipelineStageFlags2 src_stage, dst_stage;
    VkAccessFlags2 src_access, dst_access;
    VkImageLayout old_layout, new_layout;
    int aliasing;  /* first use of memory another resource used before */
} _vrg_barrier_rec;

typedef struct _vrg_heap_block {
    VkDeviceMemory memory;
    VkDeviceSize size;
    uint32_t type_bits;
} _vrg_heap_block;

struct vrg_graph {
    vrg_context *ctx;
    /* hot reload (graph_watch.c: vrg_graph_watch) */
    struct _vrg_watch *watch;
    char reload_error[4096];   /* the last failed reload's messages; "" after a good one */
    double reload_ms;          /* save-to-frame time of the last reload, -1 if none */
    double pending_since;      /* newest save (epoch seconds) reloaded in this frame, 0: none */
    int source_changed;        /* the graph file or a plugin was saved since load (reload.c) */
    double source_saved_at;    /* newest mtime of those saves (epoch seconds), 0: none seen */
    int plugins_rebuilt;       /* passes with plugin_rebuilt set wait for vrg_graph_reload */
    int params_changed;        /* the next frame is the first after a parameter-only reload */
    int history_carried;       /* a structural reload copied matching history resources over */
    vrg_graph *predecessor;    /* while a reload builds this graph: the one it replaces (vrg_pass_previous_instance) */
    struct vrg_capture *capture; /* vrg_graph_capture_frame: this frame's commands are kept */
    double cpu_ms;             /* the last frame's recording and submission, CPU ms */
    vrg_graph_desc desc;       /* as loaded (the host keeps its arrays): reload reuses it */
    int shown;                 /* vrg_graph_show: a resource left in TRANSFER_SRC after frames, -1 none */
    int loaded_from_file;
    uint32_t subframes; /* graph frames per output frame (vrg_pass_set_subframes), 0 or 1: one */
    _vrg_diag diag;
    char path[VRG_PATH_MAX];
    char name[VRG_NAME_MAX];
    char output_name[VRG_NAME_MAX];
    int output_line;
    uint32_t width, height, seed;
    double fps;
    vrg_pass passes[VRG_MAX_PASSES];
    int pass_count;
    _vrg_resource res[VRG_MAX_RESOURCES];
    int res_count;
    int output;               /* resource index */
    int schedule[VRG_MAX_PASSES];
    int schedule_count;
    /* allocate */
    _vrg_heap_block blocks[VK_MAX_MEMORY_TYPES]; /* disjoint type sets: see alias.c */
    int block_count;
    int *overlaps;            /* every resource's list of those it shares memory with */
    int overlap_used, overlap_cap;
    uint64_t naive_bytes, aliased_bytes, history_bytes;
    int allocated;
    /* record */
    vrg_frame_info frame;
    int history_reset;        /* clear @prev copies at the next frame */
    int fresh;                /* resources just allocated: clear persistent ones */
    /* frames in flight: the CPU records into one slot while the GPU runs
     * the others; a slot is reused once its last frame finished */
    uint32_t frames_in_flight;
    struct _vrg_frame_slot {
        VkCommandBuffer cmd;
        VkFence fence;
        VkQueryPool queries;
        VkDeviceSize readback_base; /* its part of the readback buffer */
        uint64_t frame_index;       /* the frame it last ran */
        uint64_t serial;            /* that frame's submission number (from 1) */
        int pending;                /* submitted and not yet waited for */
        int schedule_count;         /* timestamps it holds */
    } slots[VRG_MAX_FRAMES_IN_FLIGHT];
    uint64_t submitted;       /* frames submitted; the recording frame's serial is submitted + 1 */
    uint64_t finished;        /* serial of the newest frame known finished */
    int last_slot;            /* the slot of the last submitted frame, -1 none */
    _vrg_retired *retired;
    double pass_ms[VRG_MAX_PASSES];
    int64_t timed_frame;      /* the frame pass_ms describe, -1 none */
    double pass_cpu_ms[VRG_MAX_PASSES]; /* the last frame's execute callback, CPU ms */
    VkBuffer readback_buffer;
    VkDeviceMemory readback_memory;
    VkDeviceSize readback_size;
    void *readback_map;
    VkDeviceSize readback_offset[VRG_MAX_RESOURCES]; /* within a slot's part */
    VkDeviceSize progress_offset; /* within a slot's part: a word per scheduled pass, 1 once it ended */
    VkDeviceSize timestamp_offset; /* within a slot's part: the frame's timestamps, copied by the GPU */
    VkDeviceSize readback_slot_bytes;
    VkDeviceSize pixel_offset;    /* after the slots' parts: vrg_graph_read_pixels's texels, VRG_PIXEL_BYTES each */
    vrg_camera camera;        /* for the next frame */
    vrg_camera last_camera;   /* the last frame's */
    /* NaN/Inf checks after each pass (check_finite.c): 2 with
     * vrg_graph_desc.check_finite (the pass's inputs reported too), 1 under
     * the context's validation alone, 0 off */
    int check_finite;
    int finite_failed;            /* a frame that ended wrote one: reported, not yet returned by a frame or wait */
    struct _vrg_finite *finite;
    VkDeviceSize finite_offset;   /* within a slot's part: a result word per check, finite_stride apart */
    VkDeviceSize finite_stride;
};

/* ---- the dispatch helper's pipelines (dispatch.c) ---- */
/* Records a pass whose plugin has no execute: each listed dispatch, in order. */
void _vrg_dispatch_listed(vrg_pass *pass, VkCommandBuffer cmd);
void _vrg_pipelines_destroy(vrg_pass *p);
/* The bindings dispatch.c derived from shaders' names (made with or without a device). */
void _vrg_name_plans_free(vrg_pass *p);
/* Hot reload: recompile this pass's pipelines that use any of the changed
 * files; a pipeline whose new version fails keeps running (the errors go to
 * diag). Returns how many were swapped, -1 if any failed. */
int _vrg_pipelines_reload(vrg_pass *p, char (*changed)[VRG_PATH_MAX], int count);
/* Calls fn for every file the pass's pipelines read (hot reload watches them). */
void _vrg_pipelines_deps(vrg_pass *p, void (*fn)(void *user, const char *path), void *user);

/* ---- alias.c: memory placement of transient resources ---- */
/* Place resources with the given sizes into heap blocks; fills block/offset/overlaps.
 * Returns 0, or -1 after reporting. */
int _vrg_plan_aliasing(vrg_graph *g);
/* A kept resource survives the frame: never aliased, never culled away. */
static inline int _vrg_resource_kept(const _vrg_resource *r) { return r->history || r->persistent; }

/* ---- access.c: what a declared access means ---- */
typedef struct _vrg_access_info {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
    int writes;
} _vrg_access_info;
_vrg_access_info _vrg_access_info_of(vrg_access a, vrg_resource_kind kind);
const char *_vrg_access_name(vrg_access a);

/* ---- barrier.c: the barrier that brings a resource to a use ---- */
/* Updates *s for a use; returns 1 and fills *b when a barrier is needed. */
int _vrg_sync_use(_vrg_sync *s, _vrg_access_info need, int discard, _vrg_barrier_rec *b);
/* Barriers to bring a pass's resources to their declared accesses. */
int _vrg_pass_barriers(vrg_graph *g, vrg_pass *p, _vrg_barrier_rec *out, int max);
void _vrg_emit_barriers(vrg_graph *g, VkCommandBuffer cmd, const _vrg_barrier_rec *b, int n);
int _vrg_resource_barrier(vrg_graph *g, int res, int copy, vrg_access access, _vrg_barrier_rec *out);

/* ---- resource.c: the graph's resource table ---- */
int _vrg_graph_find_resource(const vrg_graph *g, const char *name);
/* Finds or adds a resource by name (a graph file's, or an internal one a
 * pass's create() asks for); -1 when the table is full. */
int _vrg_graph_add_resource(vrg_graph *g, const char *name);
/* Which copy of resource res this frame uses (prev: the @prev one). */
int _vrg_copy_of(const vrg_graph *g, int res, int prev);

/* ---- check_finite.c: NaN and infinity in the float images passes write ---- */
/* The pipeline (on load when g->check_finite). 0, or -1 after the error. */
int _vrg_finite_create(vrg_graph *g);
void _vrg_finite_destroy(vrg_graph *g);
/* The checks of the schedule: how many result words a slot's part needs,
 * or -1 after the error (out of memory; an image of more than 2^28 texels,
 * which the shader's 32-bit key cannot number). */
int _vrg_finite_plan(vrg_graph *g);
/* Recording: the frame's result words reset, the checks after scheduled
 * pass k, the results made visible to the host. */
void _vrg_finite_begin(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base);
void _vrg_finite_after_pass(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base, int k);
void _vrg_finite_end(vrg_graph *g, VkCommandBuffer cmd, VkDeviceSize slot_base);
/* After the frame of that slot ended: 0, or -1 after the error naming the
 * first pass, resource, channel, pixel and frame (and the pass's inputs). */
int _vrg_finite_collect(vrg_graph *g, VkDeviceSize slot_base, uint64_t frame_index);
/* -1 once after a collect found one (the failure goes to the host's next
 * vrg_graph_frame or vrg_graph_wait), else 0. */
int _vrg_finite_failed(vrg_graph *g);

/* ---- pixels.c: one texel of images after a frame ---- */
/* Texel (tx[e], ty[e]) of entry e (resource res[e], its @prev copy where
 * prev[e]) after the last frame, as vrg_graph_read_pixels reads them; every
 * frame must have ended (_vrg_wait_frames). 0, or -1 after the error. */
int _vrg_read_texels_at(vrg_graph *g, int n, const int *res, const int *prev, const uint32_t *tx, const uint32_t *ty, vrg_pixel_value *out);
float _vrg_half_to_float(uint16_t h);
/* An 8-bit UNORM channel as vrg_graph_read (and so an EXR dump) gives it:
 * byte / 255 in float, an sRGB colour channel (srgb) decoded to linear. */
float _vrg_unorm8_to_float(uint8_t byte, int srgb);

/* ---- format.c: the image formats a graph names ---- */
uint64_t _vrg_format_bytes(VkFormat f);
const char *_vrg_format_name(VkFormat f);
const char *_vrg_format_list(void);
VkFormat _vrg_format_parse(const char *s);
uint32_t _vrg_format_channels(VkFormat f);

/* ---- install.c ---- */
/* The folder of libvoxrg's own file; "" if unknown. */
const char *_vrg_lib_dir(void);
/* The build's plugin folder while libvoxrg (or a program linking it
 * statically) runs from voxrg's build, told by the file voxrg-build-tree
 * beside it; "" for an installed copy. */
const char *_vrg_build_plugin_dir(void);

static inline const vrg_slot_desc *vrg_slot(const vrg_pass *p, int i) { return &p->plugin->desc->slots[i]; }

#endif
