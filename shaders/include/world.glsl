// The voxel world buffer a scene plugin writes (layout: core/voxel/src/world.c).
// Before including, define WORLD_BINDING to the binding of the pass's
// `world` slot (a texel buffer, below), or declare that binding yourself
// and define WORLD_TEXELS to its name (a one-file pass's `in_world`).
#ifndef VOXRG_WORLD_GLSL
#define VOXRG_WORLD_GLSL
#include "ifloor.glsl"
// The runtime defines VRG_ACCEL_BINDING when a dispatch binds an
// acceleration structure: trace.glsl's ray-query backend traces it.
#if defined(VRG_ACCEL_BINDING) && !defined(TRACE_RAYQUERY)
#define TRACE_RAYQUERY
#define TLAS_BINDING VRG_ACCEL_BINDING
#endif
#ifdef TRACE_RAYQUERY
// extensions come before any declaration (trace.glsl's ray-query backend)
#extension GL_EXT_ray_query : require
#endif

// The pass's world slot is read as a texel buffer (VRG_ACCESS_TEXEL_READ)
// of 16-byte texels (the scene's world slot names R32G32B32A32_UINT): on a
// CPU device texel fetches are SIMD gathers, storage-buffer loads with
// per-invocation addresses a scalar loop per lane; and lavapipe fetches
// four words for about the price of one (a call per fetch), so a chunk's
// header is one fetch, not three (docs/benchmarks.md has the gain).
#ifndef WORLD_TEXELS
layout(binding = WORLD_BINDING) uniform usamplerBuffer world_texels;
#define WORLD_TEXELS world_texels
#endif
uvec4 world_texel(uint t) { return texelFetch(WORLD_TEXELS, int(t)); }
// Word c of a texel: selects, because a dynamically indexed vector spills
// to memory on a CPU device.
uint world_pick(uvec4 w, uint c) { return c == 0u ? w.x : c == 1u ? w.y : c == 2u ? w.z : w.w; }
uint world_word(uint i) { return world_pick(world_texel(i >> 2u), i & 3u); }

const uint WORLD_MATERIALS = 16u;  // header uints before the material table
const uint WORLD_SLOTS = 2064u;    // header + 256 materials x 8 uints
const uint WORLD_SLOT_UINTS = 1156u;
const uint WORLD_OCC = 4u;         // slot-relative: occupancy bits (8 bricks x 16 uints)
const uint WORLD_IDS = 132u;       // slot-relative: block ids, 4 per uint

ivec3 world_grid() { return ivec3(world_texel(0u).xyz); }

// First uint of the slot holding chunk c of a world with grid g, or -1 when
// c is not loaded (the toroidal slot is empty or holds another chunk), and
// the slot's header: word 3 (its brick mask in bits 0-7) and words 0-1
// (its sub-brick masks), all 0 when not loaded. Slot word 3 holds the valid
// bit and the chunk's lap (c div grid) in x and z, so the header's one
// fetch checks it; the division is in floats (exact here, fixed up by one
// step) because integer division has no SIMD instruction on a CPU device.
int world_chunk_in(ivec3 g, vec2 inv_gxz, ivec3 c, out uint word3, out uvec2 sub)
{
    word3 = 0u;
    sub = uvec2(0u);
    if (c.y < 0 || c.y >= g.y)
        return -1;
    ivec2 gxz = g.xz, cxz = c.xz;
    ivec2 lap = ifloor(vec2(cxz) * inv_gxz);  // inv_gxz = 1 / g.xz
    ivec2 m = cxz - lap * gxz;
    lap += ivec2(greaterThanEqual(m, gxz)) - ivec2(lessThan(m, ivec2(0)));
    m = cxz - lap * gxz;
    uint base = WORLD_SLOTS + uint(m.x + g.x * (m.y + g.z * c.y)) * WORLD_SLOT_UINTS;
    uvec4 header = world_texel(base >> 2u);  // slots start on a texel (world.c)
    uint w = header.w;
    uint want = 0x80000000u | (uint(lap.x) & 0x7ffu) << 8 | (uint(lap.y) & 0x7ffu) << 19;
    if ((w & 0xffffff00u) != want)
        return -1;
    word3 = w;
    sub = header.xy;
    return int(base);
}
int world_chunk_in(ivec3 g, vec2 inv_gxz, ivec3 c)
{
    uint word3;
    uvec2 sub;
    return world_chunk_in(g, inv_gxz, c, word3, sub);
}
// The same for one lookup (g = world_grid(): hot loops fetch it once).
int world_chunk(ivec3 c)
{
    ivec3 g = world_grid();
    return world_chunk_in(g, 1.0 / vec2(g.xz), c);
}

// Brick b = bx + 2*(bz + 2*by) of a loaded chunk holds a solid voxel.
bool world_brick_solid(int base, ivec3 brick) { return (world_texel(uint(base) >> 2u).w & (1u << uint(brick.x + 2 * (brick.z + 2 * brick.y)))) != 0u; }

// Occupancy of chunk-local voxel l (world.c): the slot-relative word and
// the bit in it. Brick b's 16 words hold its 4^3 sub-bricks s two words
// each, a word a 4x2x4 block: a 2^3 cell is 8 bits of one word
// (world_cell2_bits).
uint world_occ_word(ivec3 l)
{
    ivec3 b = l >> 3, s = (l >> 2) & 1;
    return WORLD_OCC + uint(b.x + 2 * (b.z + 2 * b.y)) * 16u + uint(s.x + 2 * (s.z + 2 * s.y)) * 2u + uint((l.y >> 1) & 1);
}
uint world_occ_bit(ivec3 l) { return uint((l.x & 3) + 4 * ((l.z & 3) + 4 * (l.y & 1))); }
// The bits of the 2^3 cell holding l in its occupancy word.
uint world_cell2_bits(ivec3 l) { return 0x00330033u << uint((l.x & 2) + 4 * (l.z & 2)); }
// The bits of the 2x1x2 layer of that cell holding l.
uint world_layer2_bits(ivec3 l) { return 0x33u << uint((l.x & 2) + 4 * (l.z & 2) + 16 * (l.y & 1)); }

bool world_voxel_solid(int base, ivec3 l)
{
    return (world_word(uint(base) + world_occ_word(l)) & (1u << world_occ_bit(l))) != 0u;
}

uint world_block_local(int base, ivec3 l)
{
    uint i = uint(l.x + 16 * (l.z + 16 * l.y));
    return (world_word(uint(base) + WORLD_IDS + (i >> 2)) >> (8u * (i & 3u))) & 0xffu;
}

// Block id at a world position; 0 (air) where no chunk is loaded.
uint world_block(ivec3 p)
{
    int base = world_chunk(p >> 4);
    return base < 0 ? 0u : world_block_local(base, p & 15);
}

// A material's first texel: its albedo (xyz) and emissive scale (w; the
// block emits albedo x w).
vec4 material_albedo_emissive(uint id) { return uintBitsToFloat(world_texel((WORLD_MATERIALS + id * 8u) >> 2u)); }
vec3 material_albedo(uint id) { return material_albedo_emissive(id).xyz; }
float material_emissive(uint id) { return material_albedo_emissive(id).w; }
uint material_flags(uint id) { return world_word(uint(WORLD_MATERIALS + id * 8u + 4u)); }
// Atlas tile of a face: 0 top, 1 side, 2 bottom.
uint material_tile(uint id, int face) { return world_word(uint(WORLD_MATERIALS + id * 8u + 5u + uint(face))); }

// ---- Block textures (core/voxel/src/textures.c: a 16 x 16 atlas of 16x16 tiles) ----
const uint WORLD_ATLAS_COLUMNS = 16u;

// The thesis's LOD rule: the mip whose texel matches the pixel's footprint on
// the surface at distance t (pixel_angle: radians per pixel; cos_incidence:
// |N.D|, limited so grazing faces do not blur away).
float world_texture_lod(float t, float pixel_angle, float cos_incidence)
{
    float texels = t * pixel_angle / max(cos_incidence, 0.25) * 16.0;
    // level 4 is one texel per tile; beyond it levels mix tiles
    return clamp(log2(max(texels, 1e-6)), 0.0, 4.0);
}

// Texture coordinates of a hit inside its face, in [0,1]^2, v down the face.
vec2 world_face_uv(vec3 p, ivec3 n)
{
    vec3 f = fract(p);
    if (n.x != 0)
        return vec2(n.x > 0 ? 1.0 - f.z : f.z, 1.0 - f.y);
    if (n.z != 0)
        return vec2(n.z > 0 ? f.x : 1.0 - f.x, 1.0 - f.y);
    return f.xz;
}

// Atlas coordinates of (uv in a face) of block id's tile for face normal n.
vec2 world_atlas_uv(uint id, ivec3 n, vec2 uv)
{
    uint tile = material_tile(id, n.y > 0 ? 0 : n.y < 0 ? 2 : 1);
    // keep half a level-0 texel inside the tile: nearest sampling never crosses
    uv = clamp(uv, vec2(0.5 / 16.0), vec2(1.0 - 0.5 / 16.0));
    return (vec2(tile % WORLD_ATLAS_COLUMNS, tile / WORLD_ATLAS_COLUMNS) + uv) / float(WORLD_ATLAS_COLUMNS);
}
#endif
