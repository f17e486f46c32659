/* Procedural terrain: Perlin fBm heights shaped per Voronoi biome, layered
 * columns, water and trees. The contract is in terrain_gen.h. */
#include "terrain_gen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    MAX_OCTAVES = 16,
    CELL_WINDOW = 5,      /* Voronoi cells searched per axis; see biome_eval */
    TREE_REACH = 2,       /* leaf radius: how far a tree reaches from its trunk */
    TREE_SPACING = 2,     /* a tree candidate yields to any smaller hash this close */
    TREE_HEIGHT_MIN = 4,
    TREE_HEIGHT_SPAN = 3, /* trunks are 4..6 blocks */
    TREE_HEIGHT_MAX = TREE_HEIGHT_MIN + TREE_HEIGHT_SPAN - 1,
    TOPSOIL_DEPTH = 3,    /* dirt under grass, sand on shores and in deserts */
    SANDSTONE_DEPTH = 3,
};

/* Grassland keeps this fraction of the forest tree density. */
#define GRASSLAND_TREE_FRACTION 0.08f
/* Normalised fBm rarely leaves [-0.5, 0.5] (standard deviation ~0.15 at the
 * default 5 octaves, persistence 0.5); scaling it by 2.5 makes amplitude
 * the height of the tall hills rather than of the rare extremes. */
#define HEIGHT_CONTRAST 2.5f
/* Width of the biome height blend, in blocks; capped at half a cell (see
 * biome_eval for why that bound matters). */
#define BLEND_WIDTH 32.0f

/* Each random decision draws from its own hash stream. */
enum salt { SALT_PERM = 1, SALT_OCTAVE, SALT_CELL_X, SALT_CELL_Z, SALT_BIOME, SALT_TREE, SALT_TRUNK, SALT_SHAPE };
/* Extra noise layers after the octave offsets. */
enum { NOISE_DETAIL = MAX_OCTAVES, NOISE_DUNES, NOISE_LAYERS };

void terrain_params_default(terrain_params *p)
{
    *p = (terrain_params){ .seed = 1, .octaves = 5, .scale = 96.0f, .falloff = 0.5f,
                           .base_height = 20.0f, .amplitude = 14.0f, .height_chunks = 3,
                           .biome_size = 128.0f, .tree_density = 0.02f, .sea_level = 12 };
}

/* ---- hashing ---- */

/* A 32-bit finaliser with full avalanche (every input bit flips each output
 * bit with probability ~1/2), so nearby coordinates give unrelated values. */
static uint32_t mix32(uint32_t h)
{
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

static uint32_t hash2(uint32_t seed, enum salt salt, int a, int b)
{
    uint32_t h = mix32(seed ^ mix32((uint32_t)salt));
    h = mix32(h ^ (uint32_t)a);
    return mix32(h ^ ((uint32_t)b * 0x9e3779b9u));
}

/* Top 24 bits as a float in [0, 1): exact, and never rounds up to 1. */
static float unit(uint32_t h) { return (float)(h >> 8) * (1.0f / 16777216.0f); }

/* Snow caps the peaks: a top block at y >= base_height + 0.75 amplitude
 * (compared as floats, since neither need be an integer). */
static int snowy(const terrain_params *p, int y) { return (float)y >= p->base_height + 0.75f * p->amplitude; }

/* ---- improved Perlin noise ---- */

static void perm_init(uint8_t perm[512], uint32_t seed)
{
    for (int i = 0; i < 256; i++)
        perm[i] = (uint8_t)i;
    for (int i = 255; i > 0; i--) { /* Fisher-Yates */
        uint32_t j = hash2(seed, SALT_PERM, i, 0) % (uint32_t)(i + 1);
        uint8_t t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    /* Doubled so perm[a] + b never needs wrapping. */
    memcpy(perm + 256, perm, 256);
}

/* The 2002 gradient set (the 12 cube-edge directions, 4 of them twice so a
 * 4-bit hash picks one) dotted with (x, y, z) at z = 0. */
static float grad(int h, float x, float y)
{
    h &= 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : (h == 12 || h == 14) ? x : 0.0f;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
static float lerp(float t, float a, float b) { return a + t * (b - a); }

/* 3D improved noise at z = 0: the fade weight of the z + 1 corners is
 * fade(0) = 0, so only the four z = 0 corners (hashed with Z = 0) remain. */
static float noise_perm(const uint8_t *perm, float x, float y)
{
    float fx = floorf(x), fy = floorf(y);
    unsigned X = (unsigned)(int)fx & 255u, Y = (unsigned)(int)fy & 255u;
    x -= fx;
    y -= fy;
    float u = fade(x), v = fade(y);
    unsigned A = perm[X] + Y, B = perm[X + 1] + Y;
    float n = lerp(v, lerp(u, grad(perm[perm[A]], x, y), grad(perm[perm[B]], x - 1.0f, y)),
                   lerp(u, grad(perm[perm[A + 1]], x, y - 1.0f), grad(perm[perm[B + 1]], x - 1.0f, y - 1.0f)));
    /* The extreme is 1 (all four diagonal gradients aimed at the cell centre;
     * checked over every gradient combination), so the clamp only absorbs
     * float rounding. */
    return n > 1.0f ? 1.0f : n < -1.0f ? -1.0f : n;
}

float terrain_noise2(uint32_t seed, float x, float y)
{
    uint8_t perm[512];
    perm_init(perm, seed);
    return noise_perm(perm, x, y);
}

/* ---- per-call context: the seeded tables, built once per chunk ---- */

typedef struct gen_ctx {
    terrain_params p; /* sanitised copy */
    int max_height;
    float blend;
    float norm; /* 1 / sum of octave amplitudes */
    float offset[NOISE_LAYERS][2];
    uint8_t perm[512];
    /* Control points of the CELL_WINDOW^2 cells around cell (cell_i, cell_j):
     * neighbouring columns mostly share a cell, so this is rarely refilled. */
    int cell_i, cell_j, cell_valid;
    float point_x[CELL_WINDOW * CELL_WINDOW], point_z[CELL_WINDOW * CELL_WINDOW];
    uint8_t point_biome[CELL_WINDOW * CELL_WINDOW];
} gen_ctx;

static void ctx_init(gen_ctx *c, const terrain_params *in, int with_noise)
{
    c->p = *in;
    terrain_params *p = &c->p;
    /* Negated comparisons also catch NaN. */
    if (p->octaves < 1)
        p->octaves = 1;
    if (p->octaves > MAX_OCTAVES)
        p->octaves = MAX_OCTAVES;
    if (!(p->scale >= 1e-3f))
        p->scale = 1e-3f;
    if (!(p->biome_size >= 1.0f))
        p->biome_size = 1.0f;
    c->max_height = 16 * p->height_chunks - 8;
    c->blend = fminf(BLEND_WIDTH, 0.5f * p->biome_size);
    c->cell_valid = 0;
    if (!with_noise)
        return;
    perm_init(c->perm, p->seed);
    float amp = 1.0f, sum = 0.0f;
    for (int o = 0; o < p->octaves; o++, amp *= p->falloff)
        sum += fabsf(amp);
    c->norm = sum > 0.0f ? 1.0f / sum : 1.0f;
    /* Shifting each layer by up to one permutation period decorrelates them
     * (otherwise every octave would vanish together at the origin). */
    for (int o = 0; o < NOISE_LAYERS; o++) {
        c->offset[o][0] = 256.0f * unit(hash2(p->seed, SALT_OCTAVE, o, 0));
        c->offset[o][1] = 256.0f * unit(hash2(p->seed, SALT_OCTAVE, o, 1));
    }
}

static float layer_noise(const gen_ctx *c, int layer, float x, float z)
{
    return noise_perm(c->perm, x + c->offset[layer][0], z + c->offset[layer][1]);
}

static float fbm_ctx(const gen_ctx *c, float x, float z)
{
    float freq = 1.0f / c->p.scale, amp = 1.0f, sum = 0.0f;
    for (int o = 0; o < c->p.octaves; o++, freq *= 2.0f, amp *= c->p.falloff)
        sum += amp * layer_noise(c, o, x * freq, z * freq);
    return sum * c->norm;
}

float terrain_fbm(const terrain_params *p, float x, float z)
{
    gen_ctx c;
    ctx_init(&c, p, 1);
    return fbm_ctx(&c, x, z);
}

/* ---- Voronoi biomes ---- */

static terrain_biome cell_point(uint32_t seed, float size, int ci, int cj, float *px, float *pz)
{
    *px = ((float)ci + unit(hash2(seed, SALT_CELL_X, ci, cj))) * size;
    *pz = ((float)cj + unit(hash2(seed, SALT_CELL_Z, ci, cj))) * size;
    return (terrain_biome)(hash2(seed, SALT_BIOME, ci, cj) % BIOME_COUNT);
}

terrain_biome terrain_biome_cell(const terrain_params *p, int ci, int cj, float *px, float *pz)
{
    float size = p->biome_size >= 1.0f ? p->biome_size : 1.0f; /* as ctx_init */
    return cell_point(p->seed, size, ci, cj, px, pz);
}

/* Nearest control point to (fx, fz), searching the 5x5 cells around its
 * cell. Why that is exact: in cell units, put the column in cell [0,1)^2 and,
 * by symmetry, in its quarter [1/2,1)^2. The points of cells (0,0), (1,0)
 * and (0,1) are then all closer than sqrt(1.5^2 + 1^2) ~ 1.80, so both the
 * nearest and the second nearest are closer than 1.80, while every cell
 * outside the 5x5 window (3 or more cells away along an axis) is at least 2
 * away. A 3x3 window would not do: the own point can be almost sqrt(2) away
 * while a point two cells over is just over 1 away. Blend weights vanish for
 * points farther than d1 + blend; since d1 < sqrt(2) and blend <= 1/2, every
 * point outside the window is beyond that too. w (if not NULL) gets per-biome
 * blend weights, continuous in (fx, fz) because each depends only on
 * d_i - min_j d_j. */
static terrain_biome biome_eval(gen_ctx *c, float fx, float fz, float *edge, float w[BIOME_COUNT])
{
    const float size = c->p.biome_size;
    int ci = (int)floorf(fx / size), cj = (int)floorf(fz / size);
    if (!c->cell_valid || ci != c->cell_i || cj != c->cell_j) {
        int k = 0;
        for (int dj = -CELL_WINDOW / 2; dj <= CELL_WINDOW / 2; dj++)
            for (int di = -CELL_WINDOW / 2; di <= CELL_WINDOW / 2; di++, k++)
                c->point_biome[k] = (uint8_t)cell_point(c->p.seed, size, ci + di, cj + dj, &c->point_x[k], &c->point_z[k]);
        c->cell_i = ci;
        c->cell_j = cj;
        c->cell_valid = 1;
    }
    enum { N = CELL_WINDOW * CELL_WINDOW };
    float d2[N], best = INFINITY, second = INFINITY;
    int nearest = 0;
    for (int k = 0; k < N; k++) {
        float dx = fx - c->point_x[k], dz = fz - c->point_z[k];
        d2[k] = dx * dx + dz * dz;
        if (d2[k] < best) {
            second = best;
            best = d2[k];
            nearest = k;
        } else if (d2[k] < second) {
            second = d2[k];
        }
    }
    float d1 = sqrtf(best);
    if (edge)
        *edge = sqrtf(second) - d1;
    if (w) {
        w[0] = w[1] = w[2] = 0.0f;
        float reach = (d1 + c->blend) * (d1 + c->blend);
        for (int k = 0; k < N; k++) {
            if (d2[k] >= reach)
                continue;
            float t = 1.0f - (sqrtf(d2[k]) - d1) / c->blend;
            w[c->point_biome[k]] += t * t * (3.0f - 2.0f * t);
        }
    }
    return (terrain_biome)c->point_biome[nearest];
}

terrain_biome terrain_biome_at(const terrain_params *p, int x, int z, float *edge)
{
    gen_ctx c;
    ctx_init(&c, p, 0);
    return biome_eval(&c, (float)x + 0.5f, (float)z + 0.5f, edge, NULL);
}

/* ---- heights ---- */

/* The height character of one biome at a column with base fBm value n. */
static float biome_height(const gen_ctx *c, terrain_biome b, float n, float fx, float fz)
{
    const terrain_params *p = &c->p;
    float f = 1.0f / p->scale;
    switch (b) {
    case BIOME_FOREST: { /* hilly: steeper fBm plus bumps at a quarter of the scale */
        float bumps = layer_noise(c, NOISE_DETAIL, fx * 4.0f * f, fz * 4.0f * f);
        return p->base_height + 1.0f + p->amplitude * (1.15f * n + 0.25f * bumps);
    }
    case BIOME_DESERT: { /* flat, with low dune ridges stretched along z */
        float ridge = 1.0f - fabsf(layer_noise(c, NOISE_DUNES, fx * 5.0f * f, fz * 2.5f * f));
        return p->base_height + p->amplitude * 0.3f * n + 3.0f * ridge * ridge;
    }
    default: /* grassland: gentle rolling */
        return p->base_height - 1.0f + p->amplitude * 0.8f * n;
    }
}

static int height_eval(gen_ctx *c, int x, int z, terrain_biome *biome)
{
    float fx = (float)x + 0.5f, fz = (float)z + 0.5f;
    float w[BIOME_COUNT];
    *biome = biome_eval(c, fx, fz, NULL, w);
    float n = HEIGHT_CONTRAST * fbm_ctx(c, fx, fz), sum = 0.0f, wsum = 0.0f;
    for (int b = 0; b < BIOME_COUNT; b++) {
        if (w[b] > 0.0f) {
            sum += w[b] * biome_height(c, (terrain_biome)b, n, fx, fz);
            wsum += w[b];
        }
    }
    float h = sum / wsum; /* wsum >= 1: the nearest point has weight 1 */
    if (!(h >= 1.0f)) /* also NaN from broken params */
        return 1;
    return h >= (float)c->max_height ? (c->max_height > 1 ? c->max_height : 1) : (int)h;
}

int terrain_height_at(const terrain_params *p, int x, int z)
{
    gen_ctx c;
    terrain_biome b;
    ctx_init(&c, p, 1);
    return height_eval(&c, x, z, &b);
}

/* ---- trees ---- */

/* Order-independent spacing: a candidate survives only if no column within
 * TREE_SPACING has a smaller hash (on equal hashes the column with the
 * smaller (z, x) wins, which both columns agree on). */
static int tree_wins_spacing(uint32_t seed, int x, int z, uint32_t h)
{
    for (int dz = -TREE_SPACING; dz <= TREE_SPACING; dz++)
        for (int dx = -TREE_SPACING; dx <= TREE_SPACING; dx++) {
            if (!dx && !dz)
                continue;
            uint32_t o = hash2(seed, SALT_TREE, x + dx, z + dz);
            if (o < h || (o == h && (dz < 0 || (dz == 0 && dx < 0))))
                return 0;
        }
    return 1;
}

static int tree_eval(gen_ctx *c, int x, int z, terrain_tree *t)
{
    const terrain_params *p = &c->p;
    uint32_t h = hash2(p->seed, SALT_TREE, x, z);
    float u = unit(h);
    if (!(u < p->tree_density) || !tree_wins_spacing(p->seed, x, z, h))
        return 0;
    terrain_biome b;
    int height = height_eval(c, x, z, &b);
    if (b == BIOME_DESERT || (b == BIOME_GRASSLAND && !(u < p->tree_density * GRASSLAND_TREE_FRACTION)))
        return 0;
    if (height - 1 <= p->sea_level || snowy(p, height - 1)) /* on grass only */
        return 0;
    t->x = x;
    t->z = z;
    t->base = height;
    t->trunk = TREE_HEIGHT_MIN + (int)(hash2(p->seed, SALT_TRUNK, x, z) % TREE_HEIGHT_SPAN);
    t->shape = hash2(p->seed, SALT_SHAPE, x, z);
    return 1;
}

int terrain_tree_at(const terrain_params *p, int x, int z, terrain_tree *out)
{
    gen_ctx c;
    ctx_init(&c, p, 1);
    return tree_eval(&c, x, z, out);
}

vrg_block terrain_tree_block(const terrain_tree *t, int x, int y, int z)
{
    int dx = x - t->x, dz = z - t->z, dy = y - t->base;
    if (!dx && !dz && dy >= 0 && dy < t->trunk)
        return VRG_BLOCK_WOOD;
    int layer = dy - (t->trunk - 3); /* 0 at the third-highest trunk block */
    if (layer < 0 || layer > 3)
        return VRG_BLOCK_AIR;
    int r = layer < 2 ? TREE_REACH : 1;
    int ax = abs(dx), az = abs(dz);
    if (ax > r || az > r)
        return VRG_BLOCK_AIR;
    if (ax == r && az == r) {
        /* Corners: layers 0 and 2 keep each with probability 1/2, layer 1 is
         * rounded, the top layer is a plus. */
        if (layer == 1 || layer == 3)
            return VRG_BLOCK_AIR;
        int corner = (dx > 0) + 2 * (dz > 0);
        if (!((t->shape >> (layer * 4 + corner)) & 1u))
            return VRG_BLOCK_AIR;
    }
    return VRG_BLOCK_LEAVES;
}

/* ---- chunks ---- */

static vrg_block column_block(const terrain_params *p, int height, terrain_biome b, int y)
{
    if (y >= height)
        return y < p->sea_level ? VRG_BLOCK_WATER : VRG_BLOCK_AIR;
    int depth = height - 1 - y;
    if (b == BIOME_DESERT)
        return depth < TOPSOIL_DEPTH                     ? VRG_BLOCK_SAND
               : depth < TOPSOIL_DEPTH + SANDSTONE_DEPTH ? VRG_BLOCK_SANDSTONE
                                                         : VRG_BLOCK_STONE;
    if (height - 1 <= p->sea_level) /* shore or sea floor */
        return depth < TOPSOIL_DEPTH ? VRG_BLOCK_SAND : VRG_BLOCK_STONE;
    if (depth == 0)
        return snowy(p, y) ? VRG_BLOCK_SNOW : VRG_BLOCK_GRASS;
    return depth <= TOPSOIL_DEPTH ? VRG_BLOCK_DIRT : VRG_BLOCK_STONE;
}

static void fill_terrain(gen_ctx *c, int x0, int y0, int z0, vrg_block *out)
{
    int height[16 * 16];
    terrain_biome biome[16 * 16];
    int top = c->p.sea_level;
    for (int lz = 0; lz < 16; lz++)
        for (int lx = 0; lx < 16; lx++) {
            int i = lx + 16 * lz;
            height[i] = height_eval(c, x0 + lx, z0 + lz, &biome[i]);
            if (height[i] > top)
                top = height[i];
        }
    if (y0 >= top) /* entirely above land and water: stays air */
        return;
    int y1 = top - y0 < 16 ? top - y0 : 16;
    for (int ly = 0; ly < y1; ly++)
        for (int i = 0; i < 16 * 16; i++)
            out[i + 256 * ly] = column_block(&c->p, height[i], biome[i], y0 + ly);
}

/* Writes the part of tree t inside the chunk at (x0, y0, z0). The rules
 * (leaves only into air, wood only into air or leaves) make the result
 * independent of the order trees are stamped in. */
static void stamp_tree(const terrain_tree *t, int x0, int y0, int z0, vrg_block *out)
{
    int ya = t->base > y0 ? t->base : y0, yb = t->base + t->trunk < y0 + 15 ? t->base + t->trunk : y0 + 15;
    int xa = t->x - TREE_REACH > x0 ? t->x - TREE_REACH : x0, xb = t->x + TREE_REACH < x0 + 15 ? t->x + TREE_REACH : x0 + 15;
    int za = t->z - TREE_REACH > z0 ? t->z - TREE_REACH : z0, zb = t->z + TREE_REACH < z0 + 15 ? t->z + TREE_REACH : z0 + 15;
    for (int y = ya; y <= yb; y++)
        for (int z = za; z <= zb; z++)
            for (int x = xa; x <= xb; x++) {
                vrg_block b = terrain_tree_block(t, x, y, z);
                vrg_block *dst = &out[vrg_chunk_index(x - x0, y - y0, z - z0)];
                if (b == VRG_BLOCK_LEAVES ? *dst == VRG_BLOCK_AIR
                                          : b == VRG_BLOCK_WOOD && (*dst == VRG_BLOCK_AIR || *dst == VRG_BLOCK_LEAVES))
                    *dst = b;
            }
}

static void plant_trees(gen_ctx *c, int x0, int y0, int z0, vrg_block *out)
{
    /* Trees stand on grass above the shore (base >= sea_level + 2) and reach
     * at most TREE_HEIGHT_MAX above their base. */
    if (y0 + 15 < c->p.sea_level + 2 || y0 > c->max_height + TREE_HEIGHT_MAX)
        return;
    for (int z = z0 - TREE_REACH; z < z0 + 16 + TREE_REACH; z++)
        for (int x = x0 - TREE_REACH; x < x0 + 16 + TREE_REACH; x++) {
            terrain_tree t;
            if (tree_eval(c, x, z, &t))
                stamp_tree(&t, x0, y0, z0, out);
        }
}

void terrain_generate_chunk(const terrain_params *p, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS])
{
    memset(out, VRG_BLOCK_AIR, VRG_CHUNK_VOXELS);
    if (cy < 0 || cy >= p->height_chunks)
        return;
    gen_ctx c;
    ctx_init(&c, p, 1);
    fill_terrain(&c, cx * 16, cy * 16, cz * 16, out);
    plant_trees(&c, cx * 16, cy * 16, cz * 16, out);
}
