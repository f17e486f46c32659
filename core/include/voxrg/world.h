/* The voxel world: block ids, materials, 16^3 chunks, and the GPU layout the
 * traversal shaders read (shaders/include/world.glsl mirrors it).
 *
 * Coordinates: y is up. Block (x,y,z) lives in chunk (x>>4, y>>4, z>>4) at
 * local (x&15, y&15, z&15); inside a chunk, index = lx + 16*(lz + 16*ly). */
#ifndef VOXRG_WORLD_H
#define VOXRG_WORLD_H

#include <stdint.h>
#include "voxrg/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VRG_CHUNK_SIZE 16
#define VRG_CHUNK_VOXELS (VRG_CHUNK_SIZE * VRG_CHUNK_SIZE * VRG_CHUNK_SIZE)
#define VRG_BRICK_SIZE 8

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
    VRG_MATERIAL_OPAQUE = 1u << 0, /* blocks rays; water and leaves are solid but not opaque */
};

typedef struct vrg_material {
    const char *name;
    uint8_t tile_top, tile_side, tile_bottom; /* texture atlas tiles */
    uint32_t flags;
    float albedo[3];   /* mean linear albedo (what the atlas tiles average to) */
    float emissive;    /* emitted radiance scale, 0 for none */
} vrg_material;

/* The table, indexed by block id; VRG_BLOCK_COUNT entries. */
const vrg_material *vrg_materials(void);
/* Block id by name ("stone"), or -1. */
int vrg_block_by_name(const char *name);

static inline int vrg_floor_div16(int v) { return v >= 0 ? v / 16 : -((15 - v) / 16); }
static inline int vrg_chunk_index(int lx, int ly, int lz) { return lx + VRG_CHUNK_SIZE * (lz + VRG_CHUNK_SIZE * ly); }

#ifdef __cplusplus
}
#endif
#endif
