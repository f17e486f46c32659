/* surface_cache: a signal averaged over the surfaces it lights, in world
 * space, across frames: the path-space filtering of a hashed grid.
 * Every pixel's sample goes to the cell of a grid over the surfaces that
 * holds its G-buffer point; each cell keeps a running mean of everything
 * it was given; every pixel reads back the bilinear blend of the 2x2 cells
 * around its point (or its point's own cell). For lighting that depends on
 * the point alone (diffuse irradiance, sun visibility: not on the view)
 * and a scene that changes only by edits it is told of (below) this is
 * the whole denoiser: nothing is reprojected,
 * so nothing is resampled and blurred frame after frame, a surface seen
 * again finds its history, and a cell averages the samples of all the
 * pixels it covers.
 *
 * Cells. A cell is a square of side s = 2^L blocks on one face direction
 * (the normal's dominant axis and sign) and one layer along that axis,
 * where L makes s the smallest power of two of at least cell_pixels
 * pixels at the point's distance: near the camera cells are small, far
 * away large, so a cell covers about cell_pixels^2 pixels wherever it is;
 * and at least min_cell blocks: near the camera, where a fraction of a
 * pixel is a sliver of a block, a cell still gathers a few pixels' samples.
 * Cells sit in a hash table of `cells` slots (a power of two) found by
 * linear probing over at most PROBES (64) slots; a 32-bit check value tells cells
 * in one slot apart. A slot is one entry of 8 or 16 words (the check value
 * first), so that each slot a lookup reads is one cache line.
 *
 * Per frame, four dispatches (surface_cache.comp):
 *   evict:   a quarter of the table per frame is looked at, and the
 *            slots of expired cells are freed (a cell expires once it has
 *            had no samples for more than evict_frames frames: from then
 *            the resolve starts it over and the gather skips it, so the
 *            image does not depend on when this pass reaches its slot);
 *   insert:  each pixel finds or claims its cell and adds its sample, in
 *            fixed point, with integer atomics: the sums do not depend on
 *            the order threads run in, so neither does the image (with a
 *            smaller signal, signal_position: one invocation per texel,
 *            for the pixel of its footprint it was sampled at);
 *   resolve: each cell given samples this frame (listed by its first
 *            sample) blends their mean into its own with weight count / n,
 *            n = min(n_before, (max_frames - 1) * count) + count, so the
 *            history is worth at most max_frames frames of this frame's
 *            samples; under a moving key light, at most sun_span / (the
 *            degrees it moved since the last frame) frames, so that a
 *            cell averages light from at most sun_span degrees of the
 *            sun's path (the cache otherwise lags a moving sun by up to
 *            max_frames frames; sun_span 0: no limit);
 *   gather:  each pixel blends the 2x2 cells around its point (bilinear,
 *            over the cells that exist), or with bilinear = 0 reads its
 *            point's own cell. With coarse_levels = k, samples also go to
 *            the cells 2, 4, ... 2^k times wider (the same grid's cells of
 *            the next levels: a farther pixel's own cells may be a nearer
 *            one's coarse cells, which carries a surface's history across
 *            its change of level). Cells holding fewer than young_samples
 *            samples lean on the next level up, its young ones on the
 *            level above, and the widest level's (or, with no coarse
 *            levels, the fine cells') on the `fallback` input where it is
 *            connected: each keeps n / young_samples of what is left.
 * A sample that finds no free slot in PROBES probes is not cached (its pixel
 * shows the cells it reads that exist, else its own sample), and which
 * samples those are then depends on thread order; their count is read back
 * a few frames later and reported as the stat `uncached` and a warning
 * naming `cells`.
 * A reload with new parameters or a reset empties the table.
 * Edits: the frame uniforms carry the box of the blocks an edit changed,
 * in the frame that first shows it. The insert marks the cells of the
 * points within edit_radius blocks of that box and, with edit_shadows,
 * of those whose ray to the key light passes through it (the count
 * word's top bit, set after the count so that the cell is still listed
 * once), and the resolve starts those cells over from the frame's own
 * samples: the light an edit changed shows at once instead of fading in
 * over max_frames frames. Cells out of view in that frame, and points
 * farther than edit_radius whose indirect light the edit changed, keep
 * their history.
 * Debug output (optional, computed only when something reads it: the
 * gather's OCCUPANCY variant): `occupancy`, per pixel, of the point's fine
 * cells (those the gather blends): r the samples they hold (n, blended),
 * g the share of the bilinear weight whose cells hold samples (0: none
 * found), b the share of the pixel's colour that comes from them (the rest
 * from coarse levels or the fallback; 0 where the pixel shows its own
 * sample), a the most frames since one of them was last given samples;
 * all 0 on sky pixels. */
#include <stdlib.h>
#include <string.h>
#include "voxrg/plugin.h"

#define HEADER_WORDS 16u /* [0]: samples not cached this frame, [1]: cells listed, [2], [3]: a smaller signal's hit texels and those that found their pixel */

static const vrg_param_desc params[] = {
    {"cell_pixels", VRG_PARAM_FLOAT, 2, 0.25, 64, "least side of a cell, in pixels at the point's distance"},
    {"min_cell", VRG_PARAM_FLOAT, 1.0 / 256, 1.0 / 256, 256,
     "least side of a cell, in blocks (the power of two at or above it), whatever cell_pixels gives near the camera (1/256: no floor)"},
    {"max_frames", VRG_PARAM_INT, 32, 1, 4096, "frames of samples a cell's history is worth at most"},
    {"sun_span", VRG_PARAM_FLOAT, 0, 0, 360,
     "most degrees the key light may move within a cell's history: max_frames is cut to sun_span / the degrees it moved since the last "
     "frame (0: no limit)"},
    {"evict_frames", VRG_PARAM_INT, 8, 1, 1 << 20, "frames without samples after which a cell expires (its slot is freed within 4 more)"},
    {"cells", VRG_PARAM_INT, 1 << 21, 1 << 10, 1 << 26, "hash table slots (a power of two)"},
    {"coarse_levels", VRG_PARAM_INT, 0, 0, 4, "also keep the cells 2, 4, ... 2^coarse_levels times wider, a chain for young cells to lean on (0: none)"},
    {"young_samples", VRG_PARAM_FLOAT, 8, 0.001, 1e6, "samples from which a cell no longer leans on the next level up (or the fallback)"},
    {"bilinear", VRG_PARAM_BOOL, 1, 0, 1,
     "read the bilinear blend of the 2x2 cells around each point (0: the point's own cell, a quarter of the reads: for cells under a pixel wide)"},
    {"channels", VRG_PARAM_INT, 4, 1, 4, "the signal's channels that are cached (the first ones; the rest pass through)"},
    {"edit_radius", VRG_PARAM_FLOAT, 0, 0, 256,
     "blocks around the blocks edited this frame whose cells start over (their light changed; 0: edits do not cut histories)"},
    {"edit_shadows", VRG_PARAM_BOOL, 0, 0, 1, "also start over the cells whose ray to the key light passes through the blocks edited this frame"},
    {"slot_invocations", VRG_PARAM_INT, -1, -1, 1,
     "evict and resolve: one invocation per slot (1, for GPUs) or few long ones (0, for CPUs); -1: by device type. The same image either way "
     "(a change empties the table, as any parameter's)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "signal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED,
     .help = "this frame's samples (rgba; cached clamped to [0, 1024])"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer world position; w = 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .help = "G-buffer normal"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms (camera)"},
    {.name = "fallback", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "what the widest level's young cells lean on (e.g. a spatial filter of the signal)"},
    {.name = "signal_position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "a signal smaller than position comes with the positions its texels were sampled at (gbuffer_downsample's, "
             "exact copies of position's); the pixel at each such position takes that texel's sample"},
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "the cached signal; sky pixels, and pixels with no cell around them: the signal itself (a smaller signal's texel the pixel lies in)"},
    {.name = "table", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_STORAGE_READ_WRITE, .flags = VRG_SLOT_PERSISTENT,
     .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the hash table of cells (kept across frames)"},
    {.name = "occupancy", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "r: samples the point's cells hold; g: share of the 2x2 cells found; b: share of the colour from them; a: frames since they "
             "last had samples (written only when read)"},
};

static uint64_t table_bytes(const vrg_pass *pass)
{
    /* per slot: an entry of 8 words for one channel, else 16 (its check
     * word, 3 words per channel + 3, padded: surface_cache.comp), and a
     * word of the list of cells given samples this frame */
    uint64_t entry_words = vrg_param_int(pass, "channels") == 1 ? 8u : 16u;
    return 4u * (HEADER_WORDS + (uint64_t)vrg_param_int(pass, "cells") * (1u + entry_words));
}

static int check(vrg_pass *pass)
{
    int cells = vrg_param_int(pass, "cells");
    /* sized first, so that a bad value is the only error */
    if (vrg_pass_set_buffer_size(pass, "table", table_bytes(pass)) != 0)
        return -1;
    if (cells & (cells - 1))
        return vrg_pass_error(pass, "cells = %d: the hash table needs a power of two (e.g. %d)", cells, 1 << (31 - __builtin_clz((unsigned)cells)));
    /* the shaders bind the whole table as one storage buffer */
    const vrg_device *dev = vrg_pass_device(pass);
    if (dev) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(dev->physical_device, &props);
        if (table_bytes(pass) > props.limits.maxStorageBufferRange)
            return vrg_pass_error(pass, "cells = %d needs a table of %llu bytes, more than this device binds as one storage buffer (%u): lower cells",
                                  cells, (unsigned long long)table_bytes(pass), props.limits.maxStorageBufferRange);
        /* the gather reads it as a texel buffer of 4 words a texel */
        if (table_bytes(pass) / 16 > dev->features.max_texel_buffer_texels)
            return vrg_pass_error(pass, "cells = %d needs a table of %llu texels of 4 words, more than this device's texel buffers hold (%u): lower cells",
                                  cells, (unsigned long long)(table_bytes(pass) / 16), dev->features.max_texel_buffer_texels);
    }
    return 0;
}

typedef struct surface_cache_state {
    vrg_ring *readback;   /* each frame slot's copy of the table's header, for `uncached` */
    uint64_t slots_read;  /* frame slots whose ring slice the GPU has written */
    int warned;
    int warned_sparse;    /* signal_position matched no pixel (said once) */
    int cpu;              /* a CPU device: slot_invocations = -1 means 0 */
    uint32_t max_groups;  /* maxComputeWorkGroupCount[0]: 65535 on many GPUs */
} surface_cache_state;

static int create(vrg_pass *pass)
{
    surface_cache_state *s = calloc(1, sizeof *s);
    if (!s)
        return vrg_pass_error(pass, "out of memory");
    vrg_pass_set_user(pass, s);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(vrg_pass_device(pass)->physical_device, &props);
    s->cpu = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    s->max_groups = props.limits.maxComputeWorkGroupCount[0];
    s->readback = vrg_pass_host_ring(pass, "uncached readback", 4 * HEADER_WORDS, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    return s->readback ? 0 : -1;
}

enum { EVICT, INSERT, RESOLVE, GATHER, EVICT_PER_SLOT, GATHER_OCCUPANCY, INSERT_SPARSE }; /* EVICT on a GPU; GATHER when occupancy is read */
/* How evict and resolve split their slots among invocations. A CPU device
 * (lavapipe) runs every invocation with its own set-up, so few long ones
 * win: 16 slots each for evict, 256 groups striding through the listed
 * cells for resolve. On a GPU each slot is a memory latency, and an
 * invocation walking 16 of them in turn makes the whole dispatch wait for
 * 16 latencies: one slot per invocation, and enough resolve groups for
 * every cell the frame can list (each pixel lists at most one per level).
 * The images are the same either way (slot_invocations picks one; test
 * cache_slot_invocations): docs/benchmarks.md has the times. */
#define GROUP 64u                    /* RESOLVE and EVICT's local size */
#define PROBES 64u /* surface_cache.comp's: the longest run a lookup walks */
#define CPU_SLOTS_PER_INVOCATION 16u /* EVICT's on a CPU: surface_cache.comp's default */
#define EVICT_SHARES 4u              /* each frame looks at one share of the table for cells to free */
#define CPU_RESOLVE_GROUPS 256u      /* invocations striding through the listed cells, on a CPU */
/* Push constants: the parameters by name, and what the pass computes each
 * frame (set before each dispatch). Bindings: by the shader's names; the
 * table (out_table) is a storage buffer, which GATHER reads as a texel
 * buffer (its access is the shader's declaration). */
static const vrg_dispatch_desc dispatches[] = {
    [EVICT] = {.shader = "surface_cache.comp", .defines = "EVICT", .groups_x = 1, .groups_y = 1,
               .groups_z = 1},
    [INSERT] = {.shader = "surface_cache.comp", .defines = "INSERT", .pixel_loop = 1,
                .domain = "color"},
    [INSERT_SPARSE] = {.shader = "surface_cache.comp", .defines = "INSERT SPARSE", .pixel_loop = 1,
                       .domain = "signal"}, /* a smaller signal's texels */
    [RESOLVE] = {.shader = "surface_cache.comp", .defines = "RESOLVE", .groups_x = CPU_RESOLVE_GROUPS,
                 .groups_y = 1, .groups_z = 1},
    [GATHER] = {.shader = "surface_cache.comp", .defines = "GATHER", .pixel_loop = 1,
                .domain = "color"},
    [EVICT_PER_SLOT] = {.shader = "surface_cache.comp", .defines = "EVICT SLOTS_PER_INVOCATION=1u",
                        .groups_x = 1, .groups_y = 1, .groups_z = 1},
    [GATHER_OCCUPANCY] = {.shader = "surface_cache.comp", .defines = "GATHER OCCUPANCY", .pixel_loop = 1,
                          .domain = "color"},
};

/* the count the GPU wrote into this ring slice when it last ran this frame
 * slot (none yet on a slot's first frame: the slice holds nothing defined) */
static void report_uncached(vrg_pass *pass, surface_cache_state *s, const vrg_ring_slice *slice)
{
    uint64_t bit = 1ull << vrg_pass_frame(pass)->frame_slot;
    uint32_t header[4] = {0};
    if (s->slots_read & bit)
        memcpy(header, slice->map, sizeof header);
    s->slots_read &= ~bit; /* set again once this frame's copy is recorded */
    uint32_t uncached = header[0];
    vrg_pass_stat(pass, "uncached", uncached);
    if (vrg_res_connected(vrg_pass_res(pass, "signal_position"))) {
        vrg_pass_stat(pass, "sparse_texels", header[2]);
        vrg_pass_stat(pass, "sparse_matched", header[3]);
        if (header[2] > 0 && header[3] == 0 && !s->warned_sparse) {
            s->warned_sparse = 1;
            vrg_pass_warn_at(pass, vrg_pass_slot_line(pass, "signal_position"),
                             "none of the %u hit texels of signal_position holds the position of a pixel of position: nothing reaches the "
                             "cache (signal_position must be the copy of position the signal was sampled at, as gbuffer_downsample's)",
                             header[2]);
        }
    }
    if (uncached > 0 && !s->warned) {
        s->warned = 1;
        vrg_pass_warn_at(pass, 0, "%u samples of a frame found no free cell in %u probes of the hash table (cells = %d): raise cells", uncached, PROBES,
                         vrg_param_int(pass, "cells"));
    }
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    int sparse = vrg_res_connected(vrg_pass_res(pass, "signal_position"));
    static const char *const same[] = {"position", "normal", "fallback"}, *sampled[] = {"signal_position"}, *signal[] = {"signal"};
    /* an unconnected fallback is skipped */
    if (vrg_pass_require_same_size(pass, "color", same, 3) != 0 ||
        vrg_pass_require_same_size(pass, sparse ? "signal" : "color", sparse ? sampled : signal, 1) != 0)
        return;
    surface_cache_state *s = vrg_pass_user(pass);
    vrg_ring_slice slice = vrg_pass_ring_slice(pass, s->readback, 4 * HEADER_WORDS);
    if (!slice.map)
        return;
    report_uncached(pass, s, &slice);
    const vrg_frame_info *f = vrg_pass_frame(pass);
    vrg_res table = vrg_pass_res(pass, "table");
    VkBuffer buf = vrg_res_buffer(pass, table);
    if (!vrg_res_fresh(pass, table) && (f->params_changed || !f->history_valid)) {
        /* the history is of other parameters, or the host asked for a restart */
        vrg_use clear = {table, VRG_ACCESS_TRANSFER_DST};
        vrg_pass_use(pass, cmd, &clear, 1);
        vkCmdFillBuffer(cmd, buf, 0, VK_WHOLE_SIZE, 0);
    }
    uint32_t cells = (uint32_t)vrg_param_int(pass, "cells"), share = cells / EVICT_SHARES;
    int per_slot = vrg_param_int(pass, "slot_invocations");
    if (per_slot < 0)
        per_slot = !s->cpu;
    /* within the device's group count: a share too large for one slot per
     * invocation (2^24 cells on a device that allows 65535 groups) is
     * evicted 16 slots per invocation; resolve strides, so fewer groups
     * than listed cells only take longer */
    int evict_per_slot = per_slot && (share + GROUP - 1) / GROUP <= s->max_groups;
    uint32_t evict_run = evict_per_slot ? 1u : CPU_SLOTS_PER_INVOCATION;
    uint32_t resolve_groups = CPU_RESOLVE_GROUPS;
    if (per_slot) {
        VkExtent2D size = vrg_res_extent(pass, vrg_pass_res(pass, "color"));
        uint64_t listed_most = (uint64_t)size.width * size.height * (1u + (uint32_t)vrg_param_int(pass, "coarse_levels"));
        if (listed_most > cells)
            listed_most = cells;
        uint64_t groups = (listed_most + GROUP - 1) / GROUP;
        resolve_groups = groups > s->max_groups ? s->max_groups : (uint32_t)groups;
    }
    /* which split ran (test cache_slot_invocations reads them) */
    vrg_pass_stat(pass, "evict_slots_per_invocation", evict_run);
    vrg_pass_stat(pass, "resolve_groups", resolve_groups);
    /* the unread debug output is a 1x1 stand-in: the gather leaves it out */
    int occupancy = vrg_res_connected(vrg_pass_res(pass, "occupancy"));
    for (int i = EVICT; i <= GATHER; i++) {
        vrg_dispatch_desc d = dispatches[i == EVICT && evict_per_slot ? EVICT_PER_SLOT : i == GATHER && occupancy ? GATHER_OCCUPANCY : i == INSERT && sparse ? INSERT_SPARSE : i];
        vrg_push_uint(pass, "mask", cells - 1);
        vrg_push_uint(pass, "frame_index", (uint32_t)f->frame_index);
        vrg_push_uint(pass, "evict_first", (uint32_t)(f->frame_index % EVICT_SHARES) * share);
        vrg_push_uint(pass, "evict_slots", share);
        vrg_push_int(pass, "use_fallback", vrg_res_connected(vrg_pass_res(pass, "fallback")));
        if (i == EVICT)
            d.groups_x = (share + GROUP * evict_run - 1) / (GROUP * evict_run);
        if (i == RESOLVE)
            d.groups_x = resolve_groups;
        if (vrg_dispatch(pass, cmd, &d) != 0)
            return;
    }
    /* the header to this slice (read when the slice comes round again), then zeroed */
    vrg_use copy = {table, VRG_ACCESS_TRANSFER_SRC};
    vrg_pass_use(pass, cmd, &copy, 1);
    vkCmdCopyBuffer(cmd, buf, slice.buffer, 1, &(VkBufferCopy){0, 0, 4 * HEADER_WORDS});
    /* the host reads the copy after the frame's fence: make it visible there */
    VkMemoryBarrier to_host = {VK_STRUCTURE_TYPE_MEMORY_BARRIER, NULL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL, 0, NULL);
    s->slots_read |= 1ull << f->frame_slot;
    vrg_use zero = {table, VRG_ACCESS_TRANSFER_DST};
    vrg_pass_use(pass, cmd, &zero, 1);
    vkCmdFillBuffer(cmd, buf, 0, 4 * HEADER_WORDS, 0);
}

static void destroy(vrg_pass *pass) { free(vrg_pass_user(pass)); }

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "surface_cache",
    .kind = VRG_PLUGIN_PASS,
    .help = "world-space cache: samples averaged per cell of a hashed grid over the surfaces, across frames",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .destroy = destroy,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
