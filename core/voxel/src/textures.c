/* Procedural block textures: one 16x16 tile per look, made from integer
 * hashes (deterministic, no image files), normalised so each tile averages
 * to its material's albedo, then mip-mapped in linear space. */
#include <math.h>
#include <string.h>
#include "voxrg/world.h"

#define TILES (VRG_ATLAS_COLUMNS * VRG_ATLAS_COLUMNS)

uint64_t vrg_atlas_level_offset(uint32_t level)
{
    uint64_t off = 0;
    for (uint32_t k = 0; k < level; k++) {
        uint64_t s = VRG_ATLAS_SIZE >> k;
        off += s * s * 4;
    }
    return off;
}

uint64_t vrg_atlas_bytes(void) { return vrg_atlas_level_offset(VRG_ATLAS_MIPS); }

static float hash01(uint32_t tile, int x, int y, uint32_t salt)
{
    uint32_t h = tile * 0x9E3779B1u ^ (uint32_t)x * 0x85EBCA77u ^ (uint32_t)y * 0xC2B2AE3Du ^ salt * 0x27D4EB2Fu;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return (float)(h >> 8) / 16777216.0f;
}

/* The pattern of a tile: brightness variation (mean near 1) and, for the
 * grass side, which texels are grass. */
static float pattern(int tile, int x, int y, int *grass_texel)
{
    float n = hash01((uint32_t)tile, x, y, 1), m = hash01((uint32_t)tile, x >> 1, y >> 1, 2);
    *grass_texel = 0;
    switch (tile) {
    case 0: return 0.8f + 0.4f * n;                                  /* grass top */
    case 1: *grass_texel = y < 3 + (int)(hash01(1, x, 0, 3) * 3); /* grass side: fringe */
        return 0.8f + 0.4f * n;
    case 2: return 0.75f + 0.35f * n + (m > 0.85f ? -0.3f : 0.0f);  /* dirt: pebbles */
    case 3: return 0.8f + 0.25f * n + (m > 0.8f ? -0.25f : 0.0f);   /* stone: blotches */
    case 4: return 0.92f + 0.16f * n;                                /* sand */
    case 5: return 0.95f + 0.1f * n;                                 /* sandstone top */
    case 6: return (y % 5 == 0 ? 0.8f : 1.05f) + 0.08f * n;          /* sandstone side: bands */
    case 7: {                                                        /* wood top: rings */
        float dx = (float)x - 7.5f, dy = (float)y - 7.5f;
        return 0.85f + 0.3f * (fmodf(sqrtf(dx * dx + dy * dy), 3.0f) < 1.0f) + 0.1f * n;
    }
    case 8: return (x % 4 == 0 ? 0.7f : 1.05f) + 0.15f * n;          /* bark */
    case 9: return n < 0.2f ? 0.35f : 0.9f + 0.3f * m;               /* leaves with holes */
    case 10: return 0.85f + 0.3f * (((x + 2 * (y / 4)) % 8) < 2);    /* water ripples */
    case 11: return 0.95f + 0.1f * n;                                /* snow */
    case 12: return 0.6f + 0.8f * m * n;                             /* gravel */
    case 13: return (x % 8 == 0 || y % 8 == 0) ? 0.7f : 1.05f;       /* lamp grid */
    default: return 1.0f;                                            /* flat colours: test blocks, run-time materials */
    }
}

static float srgb_encode(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

/* The albedo a tile averages to: the material whose top it is, else whose
 * side, else whose bottom (dirt is also grass's bottom, but it is dirt). */
static void tile_albedo(const vrg_material *m, int count, int tile, float out[3])
{
    for (int face = 0; face < 3; face++)
        for (int b = 1; b < count; b++)
            if ((face == 0 ? m[b].tile_top : face == 1 ? m[b].tile_side : m[b].tile_bottom) == tile) {
                memcpy(out, m[b].albedo, 3 * sizeof(float));
                return;
            }
    out[0] = out[1] = out[2] = 0.5f;
}

static void generate(const vrg_material *materials, int count, uint8_t *out)
{
    /* level 0, in linear light; then each level in place */
    static float linear[VRG_ATLAS_SIZE * VRG_ATLAS_SIZE * 3];
    float grass[3], dirt[3];
    memcpy(grass, vrg_materials()[VRG_BLOCK_GRASS].albedo, sizeof grass);
    memcpy(dirt, vrg_materials()[VRG_BLOCK_DIRT].albedo, sizeof dirt);
    for (int tile = 0; tile < TILES; tile++) {
        float albedo[3], v[VRG_ATLAS_TILE][VRG_ATLAS_TILE], mean = 0;
        int is_grass[VRG_ATLAS_TILE][VRG_ATLAS_TILE];
        tile_albedo(materials, count, tile, albedo);
        for (int y = 0; y < VRG_ATLAS_TILE; y++)
            for (int x = 0; x < VRG_ATLAS_TILE; x++)
                mean += v[y][x] = pattern(tile, x, y, &is_grass[y][x]);
        mean /= VRG_ATLAS_TILE * VRG_ATLAS_TILE;
        int tx = (tile % VRG_ATLAS_COLUMNS) * VRG_ATLAS_TILE, ty = (tile / VRG_ATLAS_COLUMNS) * VRG_ATLAS_TILE;
        for (int y = 0; y < VRG_ATLAS_TILE; y++)
            for (int x = 0; x < VRG_ATLAS_TILE; x++)
                for (int c = 0; c < 3; c++) {
                    /* brightness / mean keeps the tile's average exactly at its albedo */
                    const float *base = tile == 1 ? (is_grass[y][x] ? grass : dirt) : albedo;
                    linear[((ty + y) * VRG_ATLAS_SIZE + tx + x) * 3 + c] = base[c] * v[y][x] / mean;
                }
    }
    /* level 0, then each level the 2x2 mean of the one above, in linear light */
    float *level = linear;
    for (uint32_t k = 0; k < VRG_ATLAS_MIPS; k++) {
        uint32_t size = VRG_ATLAS_SIZE >> k;
        uint8_t *dst = out + vrg_atlas_level_offset(k);
        if (k > 0)
            for (uint32_t y = 0; y < size; y++)
                for (uint32_t x = 0; x < size; x++)
                    for (int c = 0; c < 3; c++) {
                        uint32_t up = size * 2;
                        float sum = level[((2 * y) * up + 2 * x) * 3 + c] + level[((2 * y) * up + 2 * x + 1) * 3 + c] +
                                    level[((2 * y + 1) * up + 2 * x) * 3 + c] + level[((2 * y + 1) * up + 2 * x + 1) * 3 + c];
                        /* in place: row y of the new level only reads rows 2y, 2y+1 of the old, never rows already written */
                        level[(y * size + x) * 3 + c] = sum / 4;
                    }
        for (uint32_t i = 0; i < size * size; i++) {
            for (int c = 0; c < 3; c++)
                dst[i * 4 + c] = (uint8_t)lrintf(srgb_encode(level[i * 3 + c]) * 255.0f);
            dst[i * 4 + 3] = 255;
        }
    }
}

void vrg_atlas_generate(uint8_t *out) { generate(vrg_materials(), VRG_BLOCK_COUNT, out); }
void vrg_world_atlas_generate(const vrg_world *w, uint8_t *out) { generate(vrg_world_materials(w), vrg_world_material_count(w), out); }

void vrg_atlas_record_upload(vrg_pass *pass, VkCommandBuffer cmd, const char *slot, VkBuffer staging)
{
    VkBufferImageCopy regions[VRG_ATLAS_MIPS];
    for (uint32_t k = 0; k < VRG_ATLAS_MIPS; k++)
        regions[k] = (VkBufferImageCopy){
            .bufferOffset = vrg_atlas_level_offset(k),
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, k, 0, 1},
            .imageExtent = {VRG_ATLAS_SIZE >> k, VRG_ATLAS_SIZE >> k, 1},
        };
    vkCmdCopyBufferToImage(cmd, staging, vrg_res_image(pass, vrg_pass_res(pass, slot)), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VRG_ATLAS_MIPS,
                           regions);
}
