/* Procedural terrain: a pure function of (params, chunk coordinates).
 *
 * Nothing here keeps state between calls, so every function is safe to call
 * from any number of threads at once, and a chunk comes out the same whatever
 * order (or thread) it is generated in. Every random choice is an integer
 * hash of the seed and coordinates.
 *
 * Heights are in blocks: a column of height h is solid for y in [0, h), its
 * top block is at y = h - 1, and water fills y in [h, sea_level). Depth d
 * counts down from the top block (d = 0):
 *   desert:                 sand d < 3, sandstone d < 6, stone below
 *   shore (h - 1 <= sea):   sand d < 3, stone below (grassland and forest)
 *   grassland and forest:   grass (snow if h - 1 >= base_height + 0.75 amplitude)
 *                           at d = 0, dirt d <= 3, stone below
 * The biome of a column is its nearest one (terrain_biome_at). */
#ifndef VOXRG_TERRAIN_GEN_H
#define VOXRG_TERRAIN_GEN_H

#include <stdint.h>
#include "voxrg/world.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct terrain_params {
    uint32_t seed;
    int octaves;          /* fBm octaves, clamped to [1, 16]; default 5 */
    float scale;          /* horizontal size of the largest octave, in blocks; default 96 */
    float falloff;        /* amplitude multiplier per octave (persistence); default 0.5.
                             Frequency always doubles per octave. */
    float base_height;    /* default 20 */
    float amplitude;      /* default 14 */
    int height_chunks;    /* world height in chunks; default 3 (48 blocks) */
    float biome_size;     /* Voronoi cell size in blocks; default 128 */
    float tree_density;   /* fraction of forest columns that hold a tree; default 0.02 */
    int sea_level;        /* water fills air below it; default 12 */
} terrain_params;

void terrain_params_default(terrain_params *p);

typedef enum { BIOME_GRASSLAND, BIOME_FOREST, BIOME_DESERT, BIOME_COUNT } terrain_biome;

/* Improved Perlin noise (Perlin 2002) on the plane z = 0 of the 3D noise:
 * quintic fade, a permutation shuffled from the seed, the paper's 16
 * gradients. In [-1, 1]; exactly 0 at integer lattice points. */
float terrain_noise2(uint32_t seed, float x, float y);

/* Octaves of terrain_noise2 (frequency x2, amplitude x falloff per octave,
 * each octave shifted by a seeded offset), divided by the amplitude sum so
 * the result stays in [-1, 1]. */
float terrain_fbm(const terrain_params *p, float x, float z);

/* The control point of Voronoi cell (ci, cj): one point per biome_size
 * square, jittered anywhere inside it, and the biome it carries. */
terrain_biome terrain_biome_cell(const terrain_params *p, int ci, int cj, float *px, float *pz);

/* Biome of the column (x, z): that of the control point nearest to the
 * column centre (x + 0.5, z + 0.5). If edge is not NULL it gets the distance
 * to the second nearest point minus the distance to the nearest, in blocks
 * (0 on a cell border). */
terrain_biome terrain_biome_at(const terrain_params *p, int x, int z, float *edge);

/* Surface height of the column: in [1, 16 * height_chunks - 8] (the 8 leave
 * room for trees). Biome heights are blended near cell borders, so the
 * surface is continuous across them. */
int terrain_height_at(const terrain_params *p, int x, int z);

/* A tree: trunk of wood from y = base up to base + trunk - 1 at column
 * (x, z); leaves in four layers from the third-highest trunk block up to one
 * above the trunk, radius 2, 2, 1, 1. shape holds the hash bits that decide
 * which leaf corners are present. */
typedef struct terrain_tree {
    int x, z, base, trunk;
    uint32_t shape;
} terrain_tree;

/* Whether column (x, z) holds a tree, and which; trees grow in forests (and
 * sparsely in grassland), on grass above the waterline, at least 3 columns
 * apart (Chebyshev). */
int terrain_tree_at(const terrain_params *p, int x, int z, terrain_tree *out);
/* What the tree alone puts at world block (x, y, z): WOOD, LEAVES or AIR.
 * In the world, leaves only fill air and wood only air or leaves. */
vrg_block terrain_tree_block(const terrain_tree *t, int x, int y, int z);

/* Chunk (cx, cy, cz) into out (index = lx + 16 * (lz + 16 * ly)). Chunks
 * with cy outside [0, height_chunks) are all air. */
void terrain_generate_chunk(const terrain_params *p, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS]);

#ifdef __cplusplus
}
#endif
#endif
