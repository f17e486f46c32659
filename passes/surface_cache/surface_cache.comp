#version 460
// The surface cache's four dispatches (EVICT, INSERT, RESOLVE, GATHER); the
// cells, the table and the weights are described in surface_cache.c.
#include "pixel.glsl"
#include "random.glsl"
#define FRAME_BINDING 3
#include "frame.glsl"

#if defined(RESOLVE) || defined(EVICT)
layout(local_size_x = 64) in;
#else
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
#endif
layout(binding = 0) uniform sampler2D in_signal;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 2) uniform sampler2D in_normal;
#if defined(INSERT) && defined(SPARSE)
// where each texel of a smaller signal was sampled: the full-size pixel
// whose position it holds takes its sample
layout(binding = 5) uniform sampler2D in_signal_position;
#endif
// the header, the slots' entries, the list of the slots given samples
// this frame. GATHER only reads it, as a texel buffer:
// lavapipe fetches texels with SIMD gathers but loads storage-buffer words
// at per-lane addresses one lane at a time.
#ifdef GATHER
layout(binding = 4) uniform usamplerBuffer out_table; // rgba32ui: 4 words a fetch
#else
layout(std430, binding = 4) buffer Table { uint words[]; } out_table;
#endif
#ifdef GATHER
layout(binding = 5, rgba16f) uniform writeonly image2D out_color;
layout(binding = 6) uniform sampler2D in_fallback;
#ifdef OCCUPANCY
layout(binding = 7, rgba32f) uniform writeonly image2D out_occupancy;
#endif
#endif
layout(push_constant) uniform Params {
    float cell_pixels, min_cell, sun_span;
    uint max_frames, evict_frames, mask, frame_index, channels;
    uint evict_first, evict_slots; // this frame's share of the table to look at for eviction
    int coarse_levels;             // 0: no coarse cells
    float young_samples;
    int use_fallback;              // in_fallback is connected
    int bilinear;                  // gather the 2x2 cells around a point, else its own cell
    float edit_radius;             // blocks around this frame's edits whose cells start over (0: none)
    int edit_shadows;              // also the cells whose ray to the key light crosses the edits
} params;

// header words
const uint UNCACHED = 0u, LISTED = 1u, HEADER = 16u;
// with a smaller signal (SPARSE): its hit texels this frame, and those
// that found the pixel they were sampled at (the host warns when none did)
const uint SPARSE_TEXELS = 2u, SPARSE_MATCHED = 3u;
// check words: a free slot, a freed one (lookups go on past it), else a cell's check value
const uint EMPTY = 0u, FREED = 1u;
// A run of full and freed slots (freed ones keep lookups going until the
// evict pass empties them) outgrew 32 in surface-cache-4ray.ini's sun
// table at 640x360 (the surface_cache README has the runs): samples were
// left out, their pixels then depending on thread order. Lookups stop at
// the first empty slot, so a longer limit costs only where runs are
// long. surface_cache.c's PROBES says the same.
const uint PROBES = 64u;
// the count word's top bit: a sample this frame lay where an edit changed
// the light (INSERT sets it, RESOLVE drops the cell's history)
const uint CUT = 0x80000000u;
#ifndef SLOTS_PER_INVOCATION // EVICT's: 16 on a CPU, 1 on a GPU (surface_cache.c says why)
#define SLOTS_PER_INVOCATION 16u
#endif
const float FIXED = 1024.0;      // fixed-point scale of the sums
const float MAX_SAMPLE = 1024.0; // a sample's largest value: larger ones are cached as this

// A slot's entry, C = channels: the check word, the last frame with
// samples, n (float bits), C means (float bits), C fixed-point sums of two
// words each (low, high: the low word's carries, so no count of samples
// overflows), the count; 8 words for one channel, else 16. A lookup
// misses the CPU's caches at each slot it reads (the table is far larger):
// an entry of a power of two words never straddles a 64-byte line, and
// what the gather reads comes first.
uint cells() { return params.mask + 1u; }
uint entry_size() { return params.channels == 1u ? 8u : 16u; }
uint entry_word(uint slot) { return HEADER + slot * entry_size(); }
uint check_word(uint slot) { return entry_word(slot); }
uint last_word(uint e) { return e + 1u; }
uint n_word(uint e) { return e + 2u; }
uint mean_word(uint e) { return e + 3u; }
uint sum_word(uint e, uint i) { return e + 3u + params.channels + 2u * i; } // and the next: its high word
uint count_word(uint e) { return e + 3u + 3u * params.channels; }
uint list_word(uint i) { return HEADER + cells() * entry_size() + i; }

// A cell not given samples for more than evict_frames frames holds nothing
// (the resolve starts it over, the gather skips it) whether or not the
// evict pass has freed its slot yet: when that happens depends on where
// the slot is, and so may depend on thread order; this does not.
// (from the last frame with samples; the gather reads it with the check word)
bool expired_since(uint last) { return params.frame_index - last > params.evict_frames; }
#ifndef GATHER
bool expired(uint e) { return expired_since(out_table.words[last_word(e)]); }
#endif

// A point's cell: its level, face and the cell's integer coordinates, with
// the continuous coordinates in the face's plane (in cells) for the gather.
struct Cell {
    int level, face;
    int layer;  // along the face's axis
    vec2 plane; // in the plane, in cells
};

// the level whose cells are at least cell_pixels pixels wide at x, and min_cell blocks
int level_of(vec3 x)
{
    float depth = max(dot(x - frame.camera_pos.xyz, frame.camera_forward.xyz), 1e-3);
    float pixel = depth * 2.0 * length(frame.camera_up.xyz) / float(frame.frame_info.z);
    return clamp(int(ceil(log2(max(params.cell_pixels * pixel, params.min_cell)))), -8, 8);
}

Cell cell_of(vec3 x, vec3 n, int level)
{
    Cell c;
    c.level = level;
    float s = exp2(float(c.level));
    vec3 a = abs(n);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    c.face = axis * 2 + (n[axis] < 0.0 ? 1 : 0);
    // a quarter cell into the surface: a face on a cell boundary (voxel
    // faces lie on whole numbers) gets one layer however its position rounds
    vec3 p = (x - n * (0.25 * s)) / s;
    c.layer = ifloor(p[axis]);
    c.plane = axis == 0 ? p.yz : (axis == 1 ? p.xz : p.xy);
    return c;
}

uvec2 hash_of(Cell c, ivec2 cell)
{
    uint tag = uint(c.level + 16) | uint(c.face) << 5;
    uint h = pcg_hash(uint(c.layer) ^ pcg_hash(uint(cell.x) ^ pcg_hash(uint(cell.y) ^ pcg_hash(tag))));
    // a second, independent hash tells apart the cells that share slots
    uint check = pcg_hash(uint(cell.y) + pcg_hash(uint(c.layer) + pcg_hash(uint(cell.x) + pcg_hash(tag ^ 0x5bd1e995u))));
    return uvec2(h, max(check, 2u)); // 0 and 1 mark free slots
}

#ifdef EVICT
// Cells without samples for evict_frames frames are freed. A freed slot
// right before an EMPTY one ends no run that reaches further, so it becomes
// EMPTY too; an invocation walks its slots from the last, so that carries
// backwards over its slots. With one slot per invocation (GPUs) a run of
// freed slots empties one slot per visit from its end instead: lookups
// give the same answers either way (a FREED slot only lets them go on),
// so only the probe runs are longer for a while.
void main()
{
    uint first = params.evict_first + gl_GlobalInvocationID.x * SLOTS_PER_INVOCATION;
    // EVICT only ever moves a check word toward EMPTY (cell, FREED, EMPTY),
    // so an EMPTY seen past the last slot, while another invocation may be
    // changing it, stays EMPTY; a FREED one seen there waits for a later visit
    bool next_empty = out_table.words[check_word((first + SLOTS_PER_INVOCATION) & params.mask)] == EMPTY;
    for (uint k = SLOTS_PER_INVOCATION; k-- > 0u;) {
        uint slot = first + k;
        if (slot >= params.evict_first + params.evict_slots || slot > params.mask)
            continue;
        uint was = out_table.words[check_word(slot)], c = was;
        uint e = entry_word(slot);
        if (c >= 2u && expired(e)) {
            for (uint i = 1u; i < entry_size(); i++) // all but the check word
                out_table.words[e + i] = 0u;
            c = FREED;
        }
        if (c == FREED && next_empty)
            c = EMPTY;
        if (c != was)
            out_table.words[check_word(slot)] = c;
        next_empty = c == EMPTY;
    }
}
#endif

#ifdef INSERT
// The slot holding the cell, or ~0u. A cell lies within PROBES slots of its
// hash with no EMPTY slot before it (FREED ones keep the run going).
uint find(uvec2 h)
{
    for (uint i = 0u; i < PROBES; i++) {
        uint slot = (h.x + i) & params.mask;
        uint c = out_table.words[check_word(slot)];
        if (c == h.y)
            return slot;
        if (c == EMPTY)
            break;
    }
    return ~0u;
}

// the slot holding the cell after claiming a free one if none did, or ~0u
uint find_or_claim(uvec2 h)
{
    uint slot = find(h);
    if (slot != ~0u)
        return slot;
    // the first free slot in the run, in order: threads claiming the same
    // cell try the same slots in the same order, so they agree on one
    for (uint i = 0u; i < PROBES; i++) {
        slot = (h.x + i) & params.mask;
        uint c = out_table.words[check_word(slot)];
        if (c == h.y)
            return slot;
        if (c != EMPTY && c != FREED)
            continue;
        uint was = atomicCompSwap(out_table.words[check_word(slot)], c, h.y);
        if (was == c || was == h.y)
            return slot;
    }
    return ~0u;
}

// Whether this frame's edits (the frame's edit box: one box around all of
// them, so two edits far apart cut what lies between) changed the light at
// point x: within edit_radius blocks of the box, or (edit_shadows) its ray
// toward the key light passes through the box (a block built there shades
// it now, or a block taken away no longer does) from a face that faces
// the light (one facing away is in its own shadow either way).
bool edit_cuts(vec3 x, vec3 n)
{
    vec3 lo = frame.edit_lo.xyz, hi = frame.edit_hi.xyz;
    if (any(greaterThanEqual(lo, hi)))
        return false;
    vec3 d = max(max(lo - x, x - hi), 0.0);
    if (params.edit_radius > 0.0 && dot(d, d) <= params.edit_radius * params.edit_radius)
        return true;
    vec3 dir = frame.sun_dir.xyz;
    if (params.edit_shadows == 0 || dot(n, dir) <= 0.0)
        return false;
    vec3 o = x + n * 1e-3;
    vec3 inv = vec3(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30, dir.z != 0.0 ? 1.0 / dir.z : 1e30);
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    return min(min(tf.x, tf.y), tf.z) >= max(max(max(tn.x, tn.y), tn.z), 0.0);
}

void add_sample(Cell c, uvec4 q, bool cut)
{
    uint slot = find_or_claim(hash_of(c, ifloor(c.plane)));
    if (slot == ~0u) {
        atomicAdd(out_table.words[UNCACHED], 1u);
        return;
    }
    uint e = entry_word(slot);
    for (uint i = 0u; i < params.channels; i++) {
        // the high word counts the low word's wraps: the same sum in any order
        uint was = atomicAdd(out_table.words[sum_word(e, i)], q[i]);
        if (was + q[i] < was)
            atomicAdd(out_table.words[sum_word(e, i) + 1u], 1u);
    }
    // the cell's first sample this frame lists it for the resolve
    if ((atomicAdd(out_table.words[count_word(e)], 1u) & ~CUT) == 0u)
        out_table.words[list_word(atomicAdd(out_table.words[LISTED], 1u))] = slot;
    if (cut)
        atomicOr(out_table.words[count_word(e)], CUT);
}

void add_pixel(ivec2 p, vec4 x, ivec2 s)
{
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    uvec4 q = uvec4(clamp(texelFetch(in_signal, s, 0), 0.0, MAX_SAMPLE) * FIXED + 0.5);
    int level = level_of(x.xyz);
    bool cut = (params.edit_radius > 0.0 || params.edit_shadows != 0) && edit_cuts(x.xyz, n);
    add_sample(cell_of(x.xyz, n, level), q, cut);
    for (int k = 1; k <= params.coarse_levels; k++)
        add_sample(cell_of(x.xyz, n, level + k), q, cut);
}

#ifdef SPARSE
// One invocation per texel of the smaller signal, not per pixel: the
// lanes that add samples are then not spread among the 3 in 4 pixels (at
// half size) that have none to add, which on a CPU device ran every
// lane's table loop for the one that had. The texel's sample goes to the
// pixel of its footprint (the pixels vrg_pixel_in maps to it) whose
// position it holds.
void shade(ivec2 s)
{
    ivec2 small = textureSize(in_signal, 0), size = textureSize(in_position, 0);
    if (any(greaterThanEqual(s, small)))
        return;
    vec4 sampled = texelFetch(in_signal_position, s, 0);
    if (sampled.w == 0.0)
        return;
    atomicAdd(out_table.words[SPARSE_TEXELS], 1u);
    // the footprint lies within these (a pixel either side of float rounding)
    vec2 ratio = vec2(size) / vec2(small);
    ivec2 lo = max(ifloor(vec2(s) * ratio) - 1, ivec2(0)), hi = min(ifloor(vec2(s + 1) * ratio), size - 1);
    for (int row = lo.y; row <= hi.y; row++)
        for (int column = lo.x; column <= hi.x; column++) {
            ivec2 p = ivec2(column, row);
            if (vrg_pixel_in(p, size, small) != s || texelFetch(in_position, p, 0) != sampled)
                continue;
            atomicAdd(out_table.words[SPARSE_MATCHED], 1u);
            add_pixel(p, sampled, s);
            return;
        }
}
#else
void shade(ivec2 p)
{
    if (any(greaterThanEqual(p, textureSize(in_position, 0))))
        return;
    vec4 x = texelFetch(in_position, p, 0);
    if (x.w == 0.0)
        return;
    add_pixel(p, x, p);
}
#endif
#endif

#ifdef RESOLVE
void resolve(uint slot)
{
    uint e = entry_word(slot);
    uint counted = out_table.words[count_word(e)], count = counted & ~CUT;
    // an edit changed the light here this frame: the cell starts over
    float n_before = expired(e) || (counted & CUT) != 0u ? 0.0 : uintBitsToFloat(out_table.words[n_word(e)]);
    // frames of samples the history may be worth: max_frames, fewer under a
    // moving sun (not rounded: a sun at a whole number of degrees a frame
    // and a whole sun_span would sit on floor()'s step)
    float frames = max(min(float(params.max_frames), frame_sun_history_frames(params.sun_span)), 1.0);
    float n = min(n_before, (frames - 1.0) * float(count)) + float(count);
    for (uint i = 0u; i < params.channels; i++) {
        float sum = float(out_table.words[sum_word(e, i)]) + 4294967296.0 * float(out_table.words[sum_word(e, i) + 1u]);
        float frame_mean = sum / (FIXED * float(count));
        float mean = uintBitsToFloat(out_table.words[mean_word(e) + i]);
        out_table.words[mean_word(e) + i] = floatBitsToUint(mix(mean, frame_mean, float(count) / n));
        out_table.words[sum_word(e, i)] = 0u;
        out_table.words[sum_word(e, i) + 1u] = 0u;
    }
    out_table.words[count_word(e)] = 0u;
    out_table.words[last_word(e)] = params.frame_index;
    out_table.words[n_word(e)] = floatBitsToUint(n);
}

// over the listed slots, a fixed number of invocations striding through them
void main()
{
    // the list holds at most one entry per slot: never read or write past it
    uint listed = min(out_table.words[LISTED], cells()), stride = gl_NumWorkGroups.x * 64u;
    for (uint i = gl_GlobalInvocationID.x; i < listed; i += stride)
        resolve(min(out_table.words[list_word(i)], params.mask));
}
#endif

#ifdef GATHER
// find() for the gather, by texels: an entry's first texel (entries start
// on one: 8 or 16 words) holds its check word, last frame, n and first
// mean, all the gather reads of one channel. The first texel of the slot
// holding the cell, or check word 0 (none holds it), and the entry's
// first word.
uvec4 find_entry(uvec2 h, out uint e)
{
    for (uint i = 0u; i < PROBES; i++) {
        e = entry_word((h.x + i) & params.mask);
        uvec4 t = texelFetch(out_table, int(e >> 2u));
        if (t.x == h.y)
            return t;
        if (t.x == EMPTY)
            break;
    }
    return uvec4(0u);
}

// The bilinear blend of the 2x2 cells whose centres surround the point (its
// own is one of them), over those that have samples, or (bilinear = 0) the
// point's own cell; n_blend: their blended n (samples). weight 0: none has.
#ifdef OCCUPANCY
float gather_age; // the last gather's: most frames since a found cell had samples
#endif
vec4 gather(Cell c, out float n_blend, out float weight)
{
#ifdef OCCUPANCY
    gather_age = 0.0;
#endif
    vec2 t = params.bilinear != 0 ? c.plane - 0.5 : c.plane;
    ivec2 i0 = ifloor(t);
    vec2 f = params.bilinear != 0 ? t - vec2(i0) : vec2(0.0);
    vec4 sum = vec4(0.0);
    n_blend = 0.0;
    weight = 0.0;
    for (int k = 0; k < (params.bilinear != 0 ? 4 : 1); k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        uint e;
        uvec4 first = find_entry(hash_of(c, i0 + o), e);
        float n = uintBitsToFloat(first.z);
        // not found, claimed and never resolved, or expired
        if (first.x == EMPTY || n == 0.0 || expired_since(first.y))
            continue;
        // the other means: the next texel (mean_word(e) is e + 3)
        vec4 m = vec4(uintBitsToFloat(first.w), params.channels > 1u ? uintBitsToFloat(texelFetch(out_table, int(e >> 2u) + 1).xyz) : vec3(0.0));
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        for (uint i = 0u; i < params.channels; i++)
            sum[i] += w * m[i];
        n_blend += w * n;
        weight += w;
#ifdef OCCUPANCY
        gather_age = max(gather_age, float(params.frame_index - first.y));
#endif
    }
    if (weight > 0.0) {
        sum /= weight;
        n_blend /= weight;
    }
    return sum;
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 x = texelFetch(in_position, p, 0);
    vec4 own = texelFetch(in_signal, vrg_pixel_in(p, imageSize(out_color), textureSize(in_signal, 0)), 0);
    if (x.w == 0.0) {
        imageStore(out_color, p, own);
#ifdef OCCUPANCY
        imageStore(out_occupancy, p, vec4(0.0));
#endif
        return;
    }
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    int level = level_of(x.xyz);
    float n_fine, w_fine;
    vec4 mean = gather(cell_of(x.xyz, n, level), n_fine, w_fine);
#ifdef OCCUPANCY
    // the fine cells' samples, found share, share of the colour, age
    vec4 occupancy = vec4(n_fine, w_fine, w_fine > 0.0 ? 1.0 : 0.0, gather_age);
#endif
    // A young cell (fewer than young_samples samples) leans on the cells
    // twice as wide, which gather 4 times the samples; young ones of those
    // on the next level up, and so on for coarse_levels levels; the last
    // level's young cells (or young fine cells without coarse levels) on
    // the fallback where it is connected. Each level keeps n / young_samples
    // of what is left: a chain of mixes from the top, computed from the
    // fine cells up so that it stops at the first level that is not young.
    if (n_fine < params.young_samples && (params.coarse_levels > 0 || params.use_fallback != 0)) {
        float keep = w_fine > 0.0 ? n_fine / params.young_samples : 0.0;
        vec4 sum = keep * mean, top = vec4(0.0);
        float rest = 1.0 - keep;
        bool found = false;
        for (int k = 1; k <= params.coarse_levels && rest > 0.0; k++) {
            float n_k, w_k;
            vec4 m = gather(cell_of(x.xyz, n, level + k), n_k, w_k);
            if (w_k == 0.0)
                continue;
            float a = min(n_k / params.young_samples, 1.0);
            sum += rest * a * m;
            rest *= 1.0 - a;
            top = m;
            found = true;
        }
        // what is left: the fallback's, else the coarsest cells found (the
        // fallback is not read when nothing is left: 0 * inf is NaN)
        if (params.use_fallback != 0 || found) {
            if (rest > 0.0)
                sum += rest * (params.use_fallback != 0 ? texelFetch(in_fallback, p, 0) : top);
            mean = sum;
            w_fine = 1.0;
#ifdef OCCUPANCY
            occupancy.b = keep;
#endif
        }
    }
    // channels past `channels` are the signal's own
    vec4 cached = own;
    for (uint i = 0u; i < params.channels; i++)
        cached[i] = mean[i];
    imageStore(out_color, p, w_fine > 0.0 ? cached : own);
#ifdef OCCUPANCY
    imageStore(out_occupancy, p, occupancy);
#endif
}
#endif

#if defined(INSERT) || defined(GATHER)
void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
#endif
