/* The world store. CPU side: a toroidal grid of chunk slots holding block
 * ids. GPU side: the same grid in one storage buffer, in the layout
 * shaders/include/world.glsl reads:
 *   uint header[16]   = {GX, GY, GZ, SLOT_UINTS, SLOTS_OFFSET, BLOCK_COUNT, ...}
 * (the box of the non-air blocks the GPU copy holds, which rays clip to,
 * travels in the frame uniforms: vrg_world_gpu_box)
 *   uint materials[256][8] = {albedo r,g,b (float bits), emissive, flags, tile top, side, bottom}
 *     (one entry per block id: the built-in blocks, then those a scene
 *     defines at run time, vrg_world_add_material)
 *   slots[GX*GY*GZ][SLOT_UINTS]:
 *     [0..1] sub-brick masks: bit 8*b + s is set when 4^3 sub-brick
 *         s = sx + 2*(sz + 2*sy) of brick b holds a solid voxel (bricks 0-3
 *         in word 0, 4-7 in word 1): the traversal skips empty ones
 *     [2] unused
 *     [3] brick mask (bits 0-7, bit b: brick b has a solid voxel)
 *         | (cx div GX) & 0x7ff << 8 | (cz div GZ) & 0x7ff << 19 | valid << 31
 *         (the toroidal "lap" of the chunk in its slot: a shader checks that a
 *         slot holds the chunk it wants with this one load, not four)
 *     [4..131] occupancy: 8 bricks x 16 uints, 1 bit per voxel
 *     [132..1155] block ids, 4 per uint
 * A brick is 8^3 voxels: brick b = bx + 2*(bz + 2*by) of local >> 3. Its 16
 * occupancy words hold its 4^3 sub-bricks s = sx + 2*(sz + 2*sy) two words
 * each: for v = local & 3 inside one, word 2*s + (v.y >> 1), bit
 * v.x + 4*(v.z + 4*(v.y & 1)). So one word is a 4x2x4 block and a 2^3 cell
 * a fixed pattern of 8 bits in it: the traversal skips empty 2^3 cells
 * with the word it already has.
 * Shaders read the buffer as 16-byte texels (VRG_SCENE_SLOTS' world slot):
 * every slot starts on a texel, so a slot's header words 0-3 (sub-brick
 * masks and word 3) are one fetch, as are a material's albedo. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/world.h"

#define HEADER_UINTS 16
#define MATERIAL_UINTS 8
#define MAX_MATERIALS 256 /* every block id (one byte) has an entry */
#define SLOTS_OFFSET (HEADER_UINTS + MAX_MATERIALS * MATERIAL_UINTS)
#define SLOT_HEADER 4
#define SLOT_OCC_UINTS (8 * 16)
#define SLOT_UINTS (SLOT_HEADER + SLOT_OCC_UINTS + VRG_CHUNK_VOXELS / 4)
_Static_assert(SLOTS_OFFSET % 4 == 0 && SLOT_UINTS % 4 == 0 && MATERIAL_UINTS % 4 == 0, "slots and materials start on 16-byte texels");

typedef struct slot {
    int cx, cy, cz;
    int valid;
    int dirty;
    int mesh_dirty;  /* its exposed faces may have changed (ray-query BLAS) */
    int gpu_valid;   /* what the GPU copy holds: valid and coords when last packed, */
    int gpu_c[3];
    int gpu_lo[3], gpu_hi[3]; /* and the box of its non-air blocks (world blocks, hi exclusive; lo >= hi: none) */
    int edit_lo[3], edit_hi[3]; /* the blocks vrg_world_set_block changed since it was last packed (lo >= hi: none) */
    vrg_block blocks[VRG_CHUNK_VOXELS];
} slot;

struct vrg_world {
    int gx, gy, gz;
    slot *slots;
    int *dirty_list; /* slot indices, each once */
    int dirty_count;
    int *mesh_list;  /* slots whose faces changed, each once */
    int mesh_count;
    int header_dirty;
    int loaded;
    /* vrg_world_gpu_box's answer, kept: it is asked every frame, and a scan
     * touches one cache line of every (4 KiB) slot */
    int box_lo[3], box_hi[3];
    int box_stale;
    /* vrg_world_uploaded_edits: the edit boxes of the slots packed since
     * vrg_world_clear_uploaded_edits */
    int edits_lo[3], edits_hi[3];
    int view_radius; /* blocks; 0: the whole scene is loaded */
    /* the block table: the built-in blocks, then the scene's own (a vox
     * model's palette colours), each with its own atlas tile */
    vrg_material materials[MAX_MATERIALS];
    char material_names[MAX_MATERIALS][VRG_MATERIAL_NAME_MAX];
    int material_count;
    int next_tile;
};

static const vrg_material materials[VRG_BLOCK_COUNT] = {
    [VRG_BLOCK_AIR] = {"air", 0, 0, 0, 0, {0, 0, 0}, 0},
    [VRG_BLOCK_GRASS] = {"grass", 0, 1, 2, VRG_MATERIAL_OPAQUE, {0.23f, 0.42f, 0.12f}, 0},
    [VRG_BLOCK_DIRT] = {"dirt", 2, 2, 2, VRG_MATERIAL_OPAQUE, {0.35f, 0.24f, 0.14f}, 0},
    [VRG_BLOCK_STONE] = {"stone", 3, 3, 3, VRG_MATERIAL_OPAQUE, {0.40f, 0.40f, 0.41f}, 0},
    [VRG_BLOCK_SAND] = {"sand", 4, 4, 4, VRG_MATERIAL_OPAQUE, {0.76f, 0.70f, 0.50f}, 0},
    [VRG_BLOCK_SANDSTONE] = {"sandstone", 5, 6, 5, VRG_MATERIAL_OPAQUE, {0.72f, 0.62f, 0.42f}, 0},
    [VRG_BLOCK_WOOD] = {"wood", 7, 8, 7, VRG_MATERIAL_OPAQUE, {0.36f, 0.27f, 0.16f}, 0},
    [VRG_BLOCK_LEAVES] = {"leaves", 9, 9, 9, VRG_MATERIAL_OPAQUE, {0.16f, 0.36f, 0.10f}, 0},
    [VRG_BLOCK_WATER] = {"water", 10, 10, 10, 0, {0.10f, 0.22f, 0.45f}, 0},
    [VRG_BLOCK_SNOW] = {"snow", 11, 11, 11, VRG_MATERIAL_OPAQUE, {0.85f, 0.87f, 0.90f}, 0},
    [VRG_BLOCK_GRAVEL] = {"gravel", 12, 12, 12, VRG_MATERIAL_OPAQUE, {0.45f, 0.42f, 0.40f}, 0},
    [VRG_BLOCK_LAMP] = {"lamp", 13, 13, 13, VRG_MATERIAL_OPAQUE, {0.95f, 0.85f, 0.60f}, 4.0f},
    [VRG_BLOCK_RED] = {"red", 14, 14, 14, VRG_MATERIAL_OPAQUE, {0.80f, 0.05f, 0.05f}, 0},
    [VRG_BLOCK_WHITE] = {"white", 15, 15, 15, VRG_MATERIAL_OPAQUE, {0.80f, 0.80f, 0.80f}, 0},
};

const vrg_material *vrg_materials(void) { return materials; }

int vrg_block_by_name(const char *name)
{
    for (int i = 0; i < VRG_BLOCK_COUNT; i++)
        if (strcmp(materials[i].name, name) == 0)
            return i;
    return -1;
}

static int wrap(int v, int n) { return ((v % n) + n) % n; }

static int slot_of(const vrg_world *w, int cx, int cy, int cz)
{
    if (cy < 0 || cy >= w->gy)
        return -1;
    return wrap(cx, w->gx) + w->gx * (wrap(cz, w->gz) + w->gz * cy);
}

vrg_world *vrg_world_create(int radius_chunks, int height_chunks)
{
    if (radius_chunks < 0 || height_chunks <= 0)
        return NULL;
    vrg_world *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    w->gx = w->gz = 2 * radius_chunks + 1;
    w->gy = height_chunks;
    size_t n = (size_t)w->gx * w->gy * w->gz;
    w->slots = calloc(n, sizeof *w->slots);
    w->dirty_list = calloc(n, sizeof *w->dirty_list);
    w->mesh_list = calloc(n, sizeof *w->mesh_list);
    if (!w->slots || !w->dirty_list || !w->mesh_list) {
        vrg_world_destroy(w);
        return NULL;
    }
    w->header_dirty = 1;
    w->box_stale = 1;
    memcpy(w->materials, materials, sizeof materials);
    w->material_count = VRG_BLOCK_COUNT;
    w->next_tile = VRG_ATLAS_BUILTIN_TILES;
    return w;
}

/* Tiles are a byte in the material table and the atlas holds
 * VRG_ATLAS_TILES: a run-time material needs a block id and a tile. */
int vrg_world_add_material(vrg_world *w, const vrg_material *m)
{
    if (w->material_count >= MAX_MATERIALS || w->next_tile >= VRG_ATLAS_TILES || !(m->emissive >= 0 && m->emissive <= VRG_MATERIAL_EMISSIVE_MAX))
        return -1;
    int id = w->material_count++;
    vrg_material *dst = &w->materials[id];
    *dst = *m;
    snprintf(w->material_names[id], sizeof w->material_names[id], "%s", m->name ? m->name : "");
    dst->name = w->material_names[id];
    dst->tile_top = dst->tile_side = dst->tile_bottom = (uint8_t)w->next_tile++;
    w->header_dirty = 1;
    return id;
}

int vrg_world_material_room(const vrg_world *w)
{
    int ids = MAX_MATERIALS - w->material_count, tiles = VRG_ATLAS_TILES - w->next_tile;
    return ids < tiles ? ids : tiles;
}

const vrg_material *vrg_world_materials(const vrg_world *w) { return w->materials; }
int vrg_world_material_count(const vrg_world *w) { return w->material_count; }

void vrg_world_destroy(vrg_world *w)
{
    if (!w)
        return;
    free(w->slots);
    free(w->dirty_list);
    free(w->mesh_list);
    free(w);
}

uint64_t vrg_world_gpu_bytes(int radius_chunks, int height_chunks)
{
    uint64_t g = 2 * (uint64_t)radius_chunks + 1;
    return 4 * (SLOTS_OFFSET + g * g * (uint64_t)height_chunks * SLOT_UINTS);
}

void vrg_world_set_view_radius(vrg_world *w, int blocks) { w->view_radius = blocks > 0 ? blocks : 0; }
int vrg_world_view_radius(const vrg_world *w) { return w->view_radius; }

void vrg_world_grid(const vrg_world *w, int dims[3])
{
    dims[0] = w->gx;
    dims[1] = w->gy;
    dims[2] = w->gz;
}

/* Boxes of blocks (lo inclusive, hi exclusive; lo >= hi: none), for the
 * edit boxes: grown by another (none leaves it), or emptied. */
static void box_add(int lo[3], int hi[3], const int add_lo[3], const int add_hi[3])
{
    if (add_lo[0] >= add_hi[0])
        return;
    int none = lo[0] >= hi[0];
    for (int a = 0; a < 3; a++) {
        lo[a] = none || add_lo[a] < lo[a] ? add_lo[a] : lo[a];
        hi[a] = none || add_hi[a] > hi[a] ? add_hi[a] : hi[a];
    }
}

static void box_clear(int lo[3], int hi[3])
{
    for (int a = 0; a < 3; a++)
        lo[a] = hi[a] = 0;
}

static void mark_dirty(vrg_world *w, int s)
{
    if (!w->slots[s].dirty) {
        w->slots[s].dirty = 1;
        w->dirty_list[w->dirty_count++] = s;
    }
}

/* A chunk's faces depend on its neighbours' border voxels: when a chunk
 * comes or goes, it and the six around it need new meshes. */
static void mark_mesh(vrg_world *w, int cx, int cy, int cz)
{
    static const int d[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int i = 0; i < 7; i++) {
        int s = slot_of(w, cx + d[i][0], cy + d[i][1], cz + d[i][2]);
        if (s < 0 || w->slots[s].mesh_dirty)
            continue;
        w->slots[s].mesh_dirty = 1;
        w->mesh_list[w->mesh_count++] = s;
    }
}

void vrg_world_invalidate_meshes(vrg_world *w)
{
    for (int s = 0; s < w->gx * w->gy * w->gz; s++)
        if (!w->slots[s].mesh_dirty) {
            w->slots[s].mesh_dirty = 1;
            w->mesh_list[w->mesh_count++] = s;
        }
}

int vrg_world_take_mesh_changes(vrg_world *w, int *slots, int max)
{
    int n = w->mesh_count < max ? w->mesh_count : max;
    for (int i = 0; i < n; i++) {
        slots[i] = w->mesh_list[i];
        w->slots[slots[i]].mesh_dirty = 0;
    }
    memmove(w->mesh_list, w->mesh_list + n, (size_t)(w->mesh_count - n) * sizeof *w->mesh_list);
    w->mesh_count -= n;
    return n;
}

int vrg_world_slot_chunk(const vrg_world *w, int slot, int c[3])
{
    if (slot < 0 || slot >= w->gx * w->gy * w->gz || !w->slots[slot].valid)
        return 0;
    c[0] = w->slots[slot].cx;
    c[1] = w->slots[slot].cy;
    c[2] = w->slots[slot].cz;
    return 1;
}

int vrg_world_slot_count(const vrg_world *w) { return w->gx * w->gy * w->gz; }

void vrg_world_put_chunk(vrg_world *w, int cx, int cy, int cz, const vrg_block *blocks)
{
    int s = slot_of(w, cx, cy, cz);
    if (s < 0)
        return;
    slot *sl = &w->slots[s];
    w->loaded += !sl->valid;
    sl->cx = cx;
    sl->cy = cy;
    sl->cz = cz;
    sl->valid = 1;
    memcpy(sl->blocks, blocks, VRG_CHUNK_VOXELS);
    box_clear(sl->edit_lo, sl->edit_hi); /* another chunk's edits, or a chunk streamed in: not an edit to show */
    mark_dirty(w, s);
    mark_mesh(w, cx, cy, cz);
}

int vrg_world_set_block(vrg_world *w, int x, int y, int z, vrg_block b)
{
    int cx = vrg_floor_div16(x), cy = vrg_floor_div16(y), cz = vrg_floor_div16(z);
    int s = slot_of(w, cx, cy, cz);
    slot *sl = s < 0 ? NULL : &w->slots[s];
    if (!sl || !sl->valid || sl->cx != cx || sl->cz != cz)
        return -1;
    vrg_block *at = &sl->blocks[vrg_chunk_index(x & 15, y & 15, z & 15)];
    if (*at == b)
        return 0;
    *at = b;
    const int lo[3] = {x, y, z}, hi[3] = {x + 1, y + 1, z + 1};
    box_add(sl->edit_lo, sl->edit_hi, lo, hi);
    mark_dirty(w, s);
    mark_mesh(w, cx, cy, cz);
    return 0;
}

void vrg_world_drop_chunk(vrg_world *w, int cx, int cy, int cz)
{
    int s = slot_of(w, cx, cy, cz);
    if (s < 0 || !w->slots[s].valid || w->slots[s].cx != cx || w->slots[s].cz != cz)
        return;
    w->slots[s].valid = 0;
    box_clear(w->slots[s].edit_lo, w->slots[s].edit_hi); /* its edits leave with it: no light to forget */
    w->loaded--;
    mark_dirty(w, s);
    mark_mesh(w, cx, cy, cz);
}

const vrg_block *vrg_world_chunk(const vrg_world *w, int cx, int cy, int cz)
{
    int s = slot_of(w, cx, cy, cz);
    if (s < 0)
        return NULL;
    const slot *sl = &w->slots[s];
    return sl->valid && sl->cx == cx && sl->cy == cy && sl->cz == cz ? sl->blocks : NULL;
}

int vrg_world_has_chunk(const vrg_world *w, int cx, int cy, int cz) { return vrg_world_chunk(w, cx, cy, cz) != NULL; }
int vrg_world_chunk_count(const vrg_world *w) { return w->loaded; }
void vrg_world_invalidate_gpu(vrg_world *w)
{
    w->header_dirty = 1;
    w->box_stale = 1;
    for (int s = 0; s < w->gx * w->gy * w->gz; s++) {
        w->slots[s].gpu_valid = 0; /* the new buffer holds nothing yet */
        mark_dirty(w, s); /* empty slots too: the buffer starts zeroed, but stay simple and exact */
    }
}

int vrg_world_dirty_count(const vrg_world *w) { return w->dirty_count + w->header_dirty; }

void vrg_world_uploaded_edits(const vrg_world *w, int lo[3], int hi[3])
{
    memcpy(lo, w->edits_lo, sizeof w->edits_lo);
    memcpy(hi, w->edits_hi, sizeof w->edits_hi);
}

void vrg_world_clear_uploaded_edits(vrg_world *w) { box_clear(w->edits_lo, w->edits_hi); }

vrg_block vrg_world_block(const vrg_world *w, int x, int y, int z)
{
    const vrg_block *c = vrg_world_chunk(w, vrg_floor_div16(x), vrg_floor_div16(y), vrg_floor_div16(z));
    return c ? c[vrg_chunk_index(x & 15, y & 15, z & 15)] : VRG_BLOCK_AIR;
}

int vrg_world_pick(const vrg_world *w, const float origin[3], const float dir_in[3], float max_distance, vrg_world_hit *hit)
{
    float len = sqrtf(dir_in[0] * dir_in[0] + dir_in[1] * dir_in[1] + dir_in[2] * dir_in[2]);
    /* outside the world no block exists, and its cells would not fit an int */
    if (!(len > 0) || !vrg_camera_position_in_world(origin))
        return 0;
    float dir[3] = {dir_in[0] / len, dir_in[1] / len, dir_in[2] / len};
    int cell[3], step[3], normal[3] = {0, 0, 0};
    float t_max[3], t_delta[3], t = 0;
    for (int a = 0; a < 3; a++) {
        cell[a] = (int)floorf(origin[a]);
        step[a] = dir[a] > 0 ? 1 : dir[a] < 0 ? -1 : 0;
        float next = step[a] > 0 ? (float)cell[a] + 1 - origin[a] : origin[a] - (float)cell[a];
        t_delta[a] = step[a] ? 1.0f / fabsf(dir[a]) : INFINITY;
        t_max[a] = step[a] ? next * t_delta[a] : INFINITY;
    }
    while (t <= max_distance) {
        vrg_block b = vrg_world_block(w, cell[0], cell[1], cell[2]);
        if (b != VRG_BLOCK_AIR) {
            memcpy(hit->block, cell, sizeof cell);
            memcpy(hit->normal, normal, sizeof normal);
            hit->distance = t;
            hit->id = b;
            return 1;
        }
        int a = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
        t = t_max[a];
        t_max[a] += t_delta[a];
        cell[a] += step[a];
        normal[0] = normal[1] = normal[2] = 0;
        normal[a] = -step[a];
    }
    return 0;
}

/* ---- GPU packing ---- */

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

void vrg_world_gpu_box(const vrg_world *w, int lo[3], int hi[3])
{
    vrg_world *cache = (vrg_world *)w; /* the cached box is not the world's state */
    if (cache->box_stale) {
        int any = 0;
        for (int a = 0; a < 3; a++)
            cache->box_lo[a] = cache->box_hi[a] = 0; /* none: lo >= hi */
        for (int s = 0; s < w->gx * w->gy * w->gz; s++) {
            const slot *sl = &w->slots[s];
            if (!sl->gpu_valid || sl->gpu_lo[0] >= sl->gpu_hi[0])
                continue;
            for (int a = 0; a < 3; a++) {
                cache->box_lo[a] = !any || sl->gpu_lo[a] < cache->box_lo[a] ? sl->gpu_lo[a] : cache->box_lo[a];
                cache->box_hi[a] = !any || sl->gpu_hi[a] > cache->box_hi[a] ? sl->gpu_hi[a] : cache->box_hi[a];
            }
            any = 1;
        }
        cache->box_stale = 0;
    }
    memcpy(lo, w->box_lo, sizeof w->box_lo);
    memcpy(hi, w->box_hi, sizeof w->box_hi);
}

static void pack_header(const vrg_world *w, uint32_t *out)
{
    memset(out, 0, SLOTS_OFFSET * 4);
    out[0] = (uint32_t)w->gx;
    out[1] = (uint32_t)w->gy;
    out[2] = (uint32_t)w->gz;
    out[3] = SLOT_UINTS;
    out[4] = SLOTS_OFFSET;
    out[5] = (uint32_t)w->material_count;
    for (int i = 0; i < w->material_count; i++) {
        uint32_t *m = out + HEADER_UINTS + i * MATERIAL_UINTS;
        const vrg_material *mt = &w->materials[i];
        m[0] = float_bits(mt->albedo[0]);
        m[1] = float_bits(mt->albedo[1]);
        m[2] = float_bits(mt->albedo[2]);
        m[3] = float_bits(mt->emissive);
        m[4] = mt->flags;
        m[5] = mt->tile_top;
        m[6] = mt->tile_side;
        m[7] = mt->tile_bottom;
    }
}

static int floor_div(int a, int n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }

#define BRICKS_PER_AXIS (VRG_CHUNK_SIZE / VRG_BRICK_SIZE)
_Static_assert(VRG_BRICK_SIZE == 8 && VRG_CHUNK_SIZE == 16,
               "the slot layout above (8 bricks of 16 occupancy words) and world.glsl hold 8^3 bricks in 16^3 chunks");

/* Packs a slot for the GPU and notes the box of its non-air blocks. */
static void pack_slot(const vrg_world *w, slot *sl, uint32_t *out)
{
    memset(out, 0, SLOT_UINTS * 4);
    int lo[3] = {16, 16, 16}, hi[3] = {0, 0, 0};
    for (int a = 0; a < 3; a++)
        sl->gpu_lo[a] = sl->gpu_hi[a] = 0;
    if (!sl->valid)
        return; /* valid bit 0: the shaders treat it as empty */
    uint32_t mask = 0;
    uint32_t *occ = out + SLOT_HEADER, *ids = out + SLOT_HEADER + SLOT_OCC_UINTS;
    for (int y = 0; y < 16; y++)
        for (int z = 0; z < 16; z++)
            for (int x = 0; x < 16; x++) {
                int i = vrg_chunk_index(x, y, z);
                vrg_block b = sl->blocks[i];
                ids[i >> 2] |= (uint32_t)b << (8 * (i & 3));
                if (b == VRG_BLOCK_AIR)
                    continue;
                const int l[3] = {x, y, z};
                for (int a = 0; a < 3; a++)
                    lo[a] = l[a] < lo[a] ? l[a] : lo[a], hi[a] = l[a] + 1 > hi[a] ? l[a] + 1 : hi[a];
                int brick = x / VRG_BRICK_SIZE + BRICKS_PER_AXIS * (z / VRG_BRICK_SIZE + BRICKS_PER_AXIS * (y / VRG_BRICK_SIZE));
                int sub = ((x >> 2) & 1) + 2 * (((z >> 2) & 1) + 2 * ((y >> 2) & 1));
                int word = 2 * sub + ((y & 3) >> 1), bit = (x & 3) + 4 * ((z & 3) + 4 * (y & 1));
                occ[brick * 16 + word] |= 1u << bit;
                mask |= 1u << brick;
                out[brick >> 2] |= 1u << (8 * (brick & 3) + sub);
            }
    uint32_t lap_x = (uint32_t)floor_div(sl->cx, w->gx) & 0x7ffu, lap_z = (uint32_t)floor_div(sl->cz, w->gz) & 0x7ffu;
    out[3] = mask | lap_x << 8 | lap_z << 19 | 1u << 31;
    const int c[3] = {sl->cx, sl->cy, sl->cz};
    for (int a = 0; mask && a < 3; a++)
        sl->gpu_lo[a] = c[a] * 16 + lo[a], sl->gpu_hi[a] = c[a] * 16 + hi[a];
}

int vrg_world_upload(vrg_world *w, VkCommandBuffer cmd, VkBuffer dst, void *staging, VkBuffer staging_buffer, uint64_t staging_bytes)
{
    /* Regions go out in batches; the staging memory is this frame's (a ring
     * slice: the host writes it again only after these copies ran). */
    VkBufferCopy regions[256];
    uint32_t nr = 0;
    uint64_t used = 0;
    if (w->header_dirty && staging_bytes >= SLOTS_OFFSET * 4) {
        pack_header(w, staging);
        regions[nr++] = (VkBufferCopy){.srcOffset = 0, .dstOffset = 0, .size = SLOTS_OFFSET * 4};
        used = SLOTS_OFFSET * 4;
        w->header_dirty = 0;
    }
    int done = 0;
    while (done < w->dirty_count && used + SLOT_UINTS * 4 <= staging_bytes) {
        int s = w->dirty_list[done++];
        slot *sl = &w->slots[s];
        sl->gpu_valid = sl->valid; /* what vrg_world_gpu_box reports */
        w->box_stale = 1;
        sl->gpu_c[0] = sl->cx, sl->gpu_c[1] = sl->cy, sl->gpu_c[2] = sl->cz;
        box_add(w->edits_lo, w->edits_hi, sl->edit_lo, sl->edit_hi);
        box_clear(sl->edit_lo, sl->edit_hi);
        pack_slot(w, sl, (uint32_t *)((char *)staging + used));
        regions[nr++] = (VkBufferCopy){.srcOffset = used, .dstOffset = 4 * (SLOTS_OFFSET + (uint64_t)s * SLOT_UINTS), .size = SLOT_UINTS * 4};
        used += SLOT_UINTS * 4;
        w->slots[s].dirty = 0;
        if (nr == 256) {
            vkCmdCopyBuffer(cmd, staging_buffer, dst, nr, regions);
            nr = 0;
        }
    }
    memmove(w->dirty_list, w->dirty_list + done, (size_t)(w->dirty_count - done) * sizeof *w->dirty_list);
    w->dirty_count -= done;
    if (nr)
        vkCmdCopyBuffer(cmd, staging_buffer, dst, nr, regions);
    return done;
}
