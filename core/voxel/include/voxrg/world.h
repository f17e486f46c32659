/* The voxel layer (libvoxrg_voxel), built on the runtime's public API only.
 *
 * The voxel world: block ids, materials, 16^3 chunks, and the GPU layout the
 * traversal shaders read (shaders/include/world.glsl mirrors it).
 *
 * Coordinates: y is up. Block (x,y,z) lives in chunk (x>>4, y>>4, z>>4) at
 * local (x&15, y&15, z&15); inside a chunk, index = lx + 16*(lz + 16*ly). */
#ifndef VOXRG_WORLD_H
#define VOXRG_WORLD_H

#include <stdint.h>
#include "voxrg/plugin.h"
#include "voxrg/sky.h"
#include "voxrg/voxrg.h"

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_voxel (built
 * with -fvisibility=hidden); its internals stay hidden. */
#pragma GCC visibility push(default)

#define VRG_CHUNK_SIZE 16
#define VRG_CHUNK_VOXELS (VRG_CHUNK_SIZE * VRG_CHUNK_SIZE * VRG_CHUNK_SIZE)
#define VRG_BRICK_SIZE 8 /* voxels per side of a brick, the GPU layout's unit of occupancy (2^3 per chunk) */

typedef uint8_t vrg_block;

enum vrg_block_id {
    VRG_BLOCK_AIR = 0,
    VRG_BLOCK_GRASS,
    VRG_BLOCK_DIRT,
    VRG_BLOCK_STONE,
    VRG_BLOCK_SAND,
    VRG_BLOCK_SANDSTONE,
    VRG_BLOCK_WOOD,
    VRG_BLOCK_LEAVES,
    VRG_BLOCK_WATER,
    VRG_BLOCK_SNOW,
    VRG_BLOCK_GRAVEL,
    VRG_BLOCK_LAMP,
    VRG_BLOCK_RED,   /* plain coloured blocks for analytic test scenes */
    VRG_BLOCK_WHITE,
    VRG_BLOCK_COUNT
};

enum vrg_material_flags {
    VRG_MATERIAL_OPAQUE = 1u << 0, /* not see-through (water is solid to traversal but not opaque) */
};

typedef struct vrg_material {
    const char *name;
    uint8_t tile_top, tile_side, tile_bottom; /* texture atlas tiles */
    uint32_t flags;
    float albedo[3];   /* mean linear albedo (what the atlas tiles average to) */
    float emissive;    /* emitted radiance scale e: the block emits albedo x e; 0 for none */
} vrg_material;

/* The largest emissive scale: the light near an emitter, and its square (a
 * denoiser's moments), stay well inside half floats (65504). */
#define VRG_MATERIAL_EMISSIVE_MAX 100.0f

/* The built-in table, indexed by block id; VRG_BLOCK_COUNT entries. */
const vrg_material *vrg_materials(void);
/* Block id by name ("stone"), or -1. */
int vrg_block_by_name(const char *name);

/* ---- The world store: loaded chunks, CPU queries, GPU mirror ----------- */

/* Chunks live in a toroidal grid of (2*radius+1) x height x (2*radius+1)
 * slots: chunk (cx,cy,cz) goes to slot (cx mod G, cy, cz mod G), so the camera
 * can travel forever and only chunks that change are uploaded. Two chunks
 * closer than G columns never share a slot. */
typedef struct vrg_world vrg_world;

vrg_world *vrg_world_create(int radius_chunks, int height_chunks);
void vrg_world_destroy(vrg_world *w);
/* Bytes of the GPU buffer (header, material table, slots); see world.glsl. */
uint64_t vrg_world_gpu_bytes(int radius_chunks, int height_chunks);
void vrg_world_grid(const vrg_world *w, int dims[3]);
/* How far around the camera the world is surely loaded, blocks (a streamed
 * world: its radius; 0, the default: the whole scene is loaded). Frame
 * uniforms carry it (world_grid.w) for the haze that hides the edge. */
void vrg_world_set_view_radius(vrg_world *w, int blocks);
int vrg_world_view_radius(const vrg_world *w);
/* Stores a chunk (replacing whatever held its slot) and marks it for upload. */
void vrg_world_put_chunk(vrg_world *w, int cx, int cy, int cz, const vrg_block *blocks);
void vrg_world_drop_chunk(vrg_world *w, int cx, int cy, int cz);
/* Changes one block of a loaded chunk: only that chunk goes up again (and
 * its faces, with its neighbours', to the ray-query backend). -1 when the
 * chunk is not loaded. */
int vrg_world_set_block(vrg_world *w, int x, int y, int z, vrg_block b);
int vrg_world_has_chunk(const vrg_world *w, int cx, int cy, int cz);
/* The chunk's blocks, or NULL when it is not loaded. */
const vrg_block *vrg_world_chunk(const vrg_world *w, int cx, int cy, int cz);
int vrg_world_chunk_count(const vrg_world *w);

/* A world's block table: the built-in blocks (ids below VRG_BLOCK_COUNT),
 * then materials a scene defines before its first frame (a vox model's
 * palette colours). Each gets the next block id and its own atlas tile,
 * flat at its albedo (vrg_world_atlas_generate); the name is copied
 * (VRG_MATERIAL_NAME_MAX - 1 characters kept). Returns the id, or -1 when
 * no block id or tile is left or the emissive scale is not in
 * [0, VRG_MATERIAL_EMISSIVE_MAX]. */
#define VRG_MATERIAL_NAME_MAX 24
int vrg_world_add_material(vrg_world *w, const vrg_material *m);
/* How many more materials vrg_world_add_material accepts. */
int vrg_world_material_room(const vrg_world *w);
/* The table, indexed by block id; vrg_world_material_count entries. */
const vrg_material *vrg_world_materials(const vrg_world *w);
int vrg_world_material_count(const vrg_world *w);
/* Block at a world position; air where no chunk is loaded. */
vrg_block vrg_world_block(const vrg_world *w, int x, int y, int z);

typedef struct vrg_world_hit {
    int block[3];    /* the block hit */
    int normal[3];   /* face normal (axis unit vector); 0 when the ray starts inside */
    float distance;  /* along dir (normalised) */
    vrg_block id;
} vrg_world_hit;
/* First non-air block along a ray (Amanatides-Woo DDA); 1 on a hit. An
 * origin outside the world (VRG_WORLD_LIMIT) hits nothing. */
int vrg_world_pick(const vrg_world *w, const float origin[3], const float dir[3], float max_distance, vrg_world_hit *hit);

/* Records copies of changed chunks (at most what fits the staging memory)
 * into dst, the world buffer a scene writes with VRG_ACCESS_TRANSFER_DST.
 * staging is host-visible memory of staging_bytes the host may write now:
 * this frame's slice of a ring (vrg_pass_ring_slice).
 * Returns the number of slots uploaded; the rest wait for the next frame. */
int vrg_world_upload(vrg_world *w, VkCommandBuffer cmd, VkBuffer dst, void *staging, VkBuffer staging_buffer, uint64_t staging_bytes);
/* The box of the non-air blocks the GPU copy holds after the last upload,
 * in blocks (lo inclusive, hi exclusive); lo >= hi when it holds none. Rays
 * clip to it: nothing outside can be hit. */
void vrg_world_gpu_box(const vrg_world *w, int lo[3], int hi[3]);
/* The GPU copy was lost (new buffer): upload everything again. */
void vrg_world_invalidate_gpu(vrg_world *w);
/* Slots still waiting for upload. */
int vrg_world_dirty_count(const vrg_world *w);
/* The box of the blocks vrg_world_set_block changed whose chunks the
 * uploads since vrg_world_clear_uploaded_edits brought to the GPU copy,
 * in blocks (lo inclusive, hi exclusive; lo >= hi: none). A scene clears
 * it before each frame's upload, so that the frame uniforms' edit box
 * holds the edits that frame shows first (caches cut their history there). */
void vrg_world_uploaded_edits(const vrg_world *w, int lo[3], int hi[3]);
void vrg_world_clear_uploaded_edits(vrg_world *w);

/* A new ray-query backend on a world that holds chunks (a world shared
 * across a hot reload from an instance without one): every slot's faces
 * are to be taken again. */
void vrg_world_invalidate_meshes(vrg_world *w);
/* Slots whose exposed faces changed since the last call (at most max). */
int vrg_world_take_mesh_changes(vrg_world *w, int *slots, int max);
/* The chunk a slot holds: 1 and its coordinates, or 0 when empty. */
int vrg_world_slot_chunk(const vrg_world *w, int slot, int chunk[3]);
int vrg_world_slot_count(const vrg_world *w);

/* ---- Ray-query backend: per-chunk BLAS of exposed faces + a TLAS ---------
 * Faces between a solid block and air (also across chunk borders) become
 * quads, Morton-sorted (lavapipe builds BVHs in primitive order), two
 * triangles each, in one BLAS per chunk; the TLAS has one instance per
 * chunk with a BLAS (instanceCustomIndex = slot). Only changed chunks (and
 * their neighbours) are rebuilt; the TLAS is rebuilt every frame. */
typedef struct vrg_world_accel vrg_world_accel;
/* In create(): needs VK_KHR_acceleration_structure (NULL after an error). */
vrg_world_accel *vrg_world_accel_create(vrg_pass *pass, vrg_world *world);
void vrg_world_accel_destroy(vrg_world_accel *a);
/* In execute(): records BLAS rebuilds and the TLAS build into `tlas` (a
 * VRG_ACCEL output slot written with VRG_ACCESS_AS_BUILD). */
int vrg_world_accel_record(vrg_world_accel *a, VkCommandBuffer cmd, const char *tlas_slot);

/* ---- Block textures ---------------------------------------------------
 * Procedural 16x16 tiles (material tile_top/side/bottom index them) in a
 * 16 x 16 atlas of 256x256 sRGB texels with a full mip chain, each level box-
 * filtered in linear space. Tiles are power-of-two aligned, so no level mixes
 * two tiles. Each tile's mean linear colour is its material's albedo (grass
 * sides, half dirt and half grass, excepted). The built-in blocks use the
 * first VRG_ATLAS_BUILTIN_TILES tiles; a world's run-time materials the
 * others, one flat tile each. */
#define VRG_ATLAS_TILE 16
#define VRG_ATLAS_COLUMNS 16
#define VRG_ATLAS_TILES (VRG_ATLAS_COLUMNS * VRG_ATLAS_COLUMNS)
#define VRG_ATLAS_BUILTIN_TILES 16
#define VRG_ATLAS_SIZE (VRG_ATLAS_TILE * VRG_ATLAS_COLUMNS)
#define VRG_ATLAS_MIPS 9
/* Bytes of all levels, level 0 first, each row-major RGBA8 sRGB. */
uint64_t vrg_atlas_bytes(void);
uint64_t vrg_atlas_level_offset(uint32_t level);
/* The built-in blocks' atlas (other tiles mid-grey). */
void vrg_atlas_generate(uint8_t *out);
/* A world's atlas: the built-in tiles and one per run-time material. */
void vrg_world_atlas_generate(const vrg_world *w, uint8_t *out);
/* Records the upload of every level from staging (vrg_atlas_generate'd). */
void vrg_atlas_record_upload(vrg_pass *pass, VkCommandBuffer cmd, const char *slot, VkBuffer staging);

/* ---- Per-frame uniforms (std140; shaders/include/frame.glsl) ----------- */

typedef struct vrg_frame_uniforms {
    float view_proj[16];
    float inv_view_proj[16];
    float prev_view_proj[16];
    float camera_pos[4];      /* w: vertical field of view, radians */
    float prev_camera_pos[4];
    /* Primary rays: dir = normalize(forward + nx * right - ny * up) for the
     * pixel centre's NDC (nx, ny), y down. right and up are scaled by the
     * half-extent of the image plane, so no matrix inverse (and its float
     * error far from the origin) is involved. */
    float camera_right[4];
    float camera_up[4];
    float camera_forward[4];
    float sun_dir[4];         /* to the key light (vrg_sky_key_light: the sun, the moon by night); w: its elevation, degrees */
    float sun_radiance[4];
    float sky_zenith[4];
    float sky_horizon[4];
    float ambient[4];
    uint32_t frame_index, width, height, seed;
    float time_s, hours, pad0, pad1;
    /* The world's slot grid (x, y, z; chunks) and the box (blocks) around
     * the chunks its GPU copy holds after this frame's upload (empty: lo >=
     * hi). The traversal clips rays to it; it reads the grid here rather
     * than from the world header because a uniform is one scalar load on a
     * CPU device, a texel fetch a call per SIMD row. w: the view radius,
     * blocks (vrg_world_view_radius; 0: not streamed). */
    int32_t world_grid[4];
    float world_lo[4];
    float world_hi[4];
    /* Last frame's key light direction, for histories that must follow a
     * moving sun; w: the degrees between it and sun_dir (computed in
     * double: frame.glsl's frame_sun_moved_degrees), -1 where unknown (a
     * frame without history; then xyz = sun_dir). Added at the end: the
     * block's earlier offsets stay as they were. */
    float prev_sun_dir[4];
    /* The box of the blocks edited whose chunks this frame's upload brought
     * to the GPU (vrg_world_uploaded_edits; blocks, hi exclusive; empty:
     * lo >= hi): one box around all of them, for histories kept in world
     * space that must forget the light an edit changed (surface_cache's
     * edit_radius). Added at the end, as prev_sun_dir. */
    float edit_lo[4];
    float edit_hi[4];
} vrg_frame_uniforms;

/* prev_sun_dir is left unknown (w -1): vrg_frame_uniforms_prev_sun fills it. */
void vrg_frame_uniforms_fill(const vrg_frame_info *frame, const vrg_sky *sky, vrg_frame_uniforms *out);
/* prev_sun_dir: the key light of the sky `desc` at the last frame's time and
 * the degrees it moved since (unknown, w -1, without history). */
void vrg_frame_uniforms_prev_sun(const vrg_frame_info *frame, const vrg_sky_desc *desc, vrg_frame_uniforms *out);
/* The world part of the uniforms (world may be NULL: an empty box). */
void vrg_frame_uniforms_world(const vrg_world *world, vrg_frame_uniforms *out);
/* What a scene plugin does each frame for its `frame` output (a buffer with
 * VRG_ACCESS_TRANSFER_DST), after uploading its world: evaluate the sky at
 * this frame's time and record the uniforms into it. */
void vrg_scene_write_frame(vrg_pass *pass, VkCommandBuffer cmd, const char *slot, const vrg_sky_desc *sky, const vrg_world *world);

/* ---- What every scene plugin shares ---------------------------------
 * A scene declares VRG_SCENE_SLOTS among its slots and VRG_SCENE_PARAMS
 * among its parameters, builds its vrg_world, and calls the functions
 * below from check, create, execute and destroy (plugins/blocks/blocks.c is
 * the shortest example). */
/* designated: a plugin built with -Wextra gets no missing-field warning */
#define VRG_SCENE_PARAMS                                                                                         \
    {.name = "time_of_day", .type = VRG_PARAM_FLOAT, .default_value = 10, .min = 0, .max = 24,                   \
     .help = "hours at the start, 12 = noon"},                                                                   \
    {.name = "day_length", .type = VRG_PARAM_FLOAT, .default_value = 0, .min = 0, .max = 1e6,                    \
     .help = "seconds per 24-hour cycle; 0 keeps the time of day"},                                              \
    {.name = "traversal", .type = VRG_PARAM_STRING, .default_string = "dda",                                     \
     .help = "dda (voxel DDA only) or rayquery (also build BLAS/TLAS for ray queries)"}
/* VRG_SCENE_PARAMS's traversal is the last of them: a scene's
 * param_choices names its values at that index, so that hosts list them
 * (from vrg_find_plugin's descriptor) and the runtime checks them at load:
 *   static const char *const param_choices[N] = {[N - 1] = VRG_SCENE_TRAVERSAL_CHOICES};
 * (N: the scene's parameter count, VRG_SCENE_PARAMS last) */
#define VRG_SCENE_TRAVERSAL_CHOICES "dda,rayquery"

#define VRG_SCENE_SLOTS                                                                                          \
    {.name = "world", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 16,          \
     .format = VK_FORMAT_R32G32B32A32_UINT, .flags = VRG_SLOT_PERSISTENT,                                          \
     .help = "voxel world, read as 16-byte texels (shaders/include/world.glsl)"},                                  \
    {.name = "frame", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST,                      \
     .size = sizeof(vrg_frame_uniforms), .flags = VRG_SLOT_PERSISTENT, .help = "per-frame uniforms (shaders/include/frame.glsl)"}, \
    {.name = "atlas", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_TRANSFER_DST,                      \
     .format = VK_FORMAT_R8G8B8A8_SRGB, .width = VRG_ATLAS_SIZE, .height = VRG_ATLAS_SIZE, .flags = VRG_SLOT_PERSISTENT, \
     .help = "block textures, full mip chain (world.glsl: world_atlas_uv)", .mip_levels = VRG_MIPS_FULL},          \
    {.name = "tlas", .dir = VRG_OUT, .kind = VRG_ACCEL, .access = VRG_ACCESS_AS_BUILD,                            \
     .help = "top-level acceleration structure of the chunks (traversal = rayquery; empty otherwise)"}

typedef struct vrg_scene_gpu {
    vrg_world *world;
    vrg_ring *staging; /* world uploads: a slice per frame in flight */
    uint64_t staging_bytes;
    vrg_world_accel *accel; /* traversal = rayquery */
} vrg_scene_gpu;

/* check(): the traversal value, and the world and TLAS sizes for a toroidal
 * grid of grid_radius and height_chunks. */
int vrg_scene_check(vrg_pass *pass, int grid_radius, int height_chunks);
/* create(): takes the world; staging, the atlas, the ray-query structures if
 * asked for; hands the world to the runtime for host queries. */
int vrg_scene_create(vrg_pass *pass, vrg_scene_gpu *s, vrg_world *world);
/* create() of an instance a hot reload builds on its previous instance's
 * world (the same vrg_world, shared: previous is that instance's
 * vrg_scene_gpu): also keeps what the GPU holds of it. The world buffer and
 * atlas carry over when the reload succeeds (vrg_pass_keep_resource: no
 * chunk is uploaded again) and the ray-query backend shares the previous
 * one's BLASes (none is built again); the previous instance keeps working
 * until then, and on if the reload fails. previous NULL, or with another
 * world: vrg_scene_create. The frame stat gpu_world_kept is 1 on a first
 * frame whose world buffer was kept. */
int vrg_scene_create_from(vrg_pass *pass, vrg_scene_gpu *s, vrg_world *world, const vrg_scene_gpu *previous);
/* execute(): everything again after a reallocation, changed chunks, BLAS and
 * TLAS, and this frame's uniforms (sun and sky from the scene parameters). */
void vrg_scene_record(vrg_pass *pass, vrg_scene_gpu *s, VkCommandBuffer cmd);
/* destroy(): frees the world too. */
void vrg_scene_destroy(vrg_pass *pass, vrg_scene_gpu *s);
/* The name a scene shares its world under (vrg_pass_share). */
#define VRG_WORLD_SHARED_NAME "vrg_world"
/* The graph's world (NULL without a scene that shares one): CPU block queries. */
vrg_world *vrg_graph_world(const vrg_graph *g);

static inline int vrg_floor_div16(int v) { return v >= 0 ? v / 16 : -((15 - v) / 16); }
static inline int vrg_chunk_index(int lx, int ly, int lz) { return lx + VRG_CHUNK_SIZE * (lz + VRG_CHUNK_SIZE * ly); }

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
