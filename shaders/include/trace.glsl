// Ray traversal of the voxel world, one interface for every pass:
//   Hit trace_closest(origin, unit direction, tmax)   closest hit
//   bool trace_any(origin, unit direction, tmax)      occlusion
// Backend 1 (default): a hierarchical DDA (Amanatides & Woo) over the
// world's occupancy: empty chunks, 8^3 bricks, 4^3 sub-bricks, 2^3 cells
// and 2x1x2 layers of cells are each crossed in one step, voxels are
// stepped only where such a layer holds something. Backend 2 (#define
// TRACE_RAYQUERY, TLAS_BINDING; world.glsl defines them when the runtime
// says VRG_ACCEL_BINDING): VK_KHR_ray_query against the scene's per-chunk
// BLASes; a pass that declares the TLAS binding itself (a one-file pass's
// `in_tlas`, with its annotation) defines TRACE_TLAS to its name instead of
// TLAS_BINDING. Include world.glsl and frame.glsl first.
//
// What the DDA is shaped by (measured on lavapipe, docs/benchmarks.md): a
// buffer load with a per-invocation address is a scalar loop over the SIMD
// lanes, integer division is scalar, a dynamically indexed vector spills to
// memory, and lanes run in lockstep. So steps are one-hot masks, a chunk
// costs one load (world_chunk_in) and its masks stay in registers, voxel
// words are reloaded only when the word changes, the ray is clipped to the
// box of non-air blocks first, and there is one loop for all levels.
#ifndef VOXRG_TRACE_GLSL
#define VOXRG_TRACE_GLSL
#if !defined(VOXRG_WORLD_GLSL) || !defined(VOXRG_FRAME_GLSL)
#error "include world.glsl and frame.glsl before trace.glsl"
#endif

struct Hit {
    bool hit;
    float t;        // distance along the (unit) direction
    ivec3 voxel;    // the block hit
    ivec3 normal;   // face normal (zero if the ray started inside a block)
    uint block;     // block id
    int chunk;      // the world slot of its chunk (an object id, the same in both backends)
};

// One-hot mask of the axis whose boundary comes first (ties: x, then y, z).
ivec3 trace_step_mask(vec3 tnext)
{
    bool x = tnext.x <= tnext.y && tnext.x <= tnext.z;
    bool y = !x && tnext.y <= tnext.z;
    return ivec3(x, y, !x && !y);
}

#ifdef TRACE_RAYQUERY
#ifndef TRACE_TLAS
layout(binding = TLAS_BINDING) uniform accelerationStructureEXT trace_tlas;
#define TRACE_TLAS trace_tlas
#endif

// The face a ray hit: the axis whose block boundary the hit point lies on
// (the BLAS holds no per-face data), facing against the ray.
Hit trace_closest(vec3 o, vec3 d, float tmax)
{
    Hit h;
    h.hit = false;
    h.t = tmax;
    h.voxel = ivec3(0);
    h.normal = ivec3(0);
    h.block = 0u;
    h.chunk = -1;
    rayQueryEXT q;
    rayQueryInitializeEXT(q, TRACE_TLAS, gl_RayFlagsOpaqueEXT, 0xff, o, 0.0, d, tmax);
    while (rayQueryProceedEXT(q)) {
    }
    if (rayQueryGetIntersectionTypeEXT(q, true) != gl_RayQueryCommittedIntersectionTriangleEXT)
        return h;
    float t = rayQueryGetIntersectionTEXT(q, true);
    vec3 p = o + d * t;
    vec3 off = abs(p - round(p));
    int a = off.x < off.y ? (off.x < off.z ? 0 : 2) : (off.y < off.z ? 1 : 2);
    ivec3 n = ivec3(0);
    n[a] = d[a] > 0.0 ? -1 : 1;
    h.hit = true;
    h.t = t;
    h.normal = n;
    h.voxel = ifloor(p - vec3(n) * 0.5);
    h.block = world_block(h.voxel);
    h.chunk = rayQueryGetIntersectionInstanceCustomIndexEXT(q, true);
    return h;
}

bool trace_any(vec3 o, vec3 d, float tmax)
{
    rayQueryEXT q;
    rayQueryInitializeEXT(q, TRACE_TLAS, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xff, o, 0.0, d, tmax);
    while (rayQueryProceedEXT(q)) {
    }
    return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT;
}
#else
// The DDA, in one loop: each iteration leaves the largest empty cell
// around the current voxel (an empty or unloaded chunk, an empty 8^3 brick,
// 4^3 sub-brick, 2^3 cell or 2x1x2 layer of one) or tests one voxel and
// steps past it. On a CPU device the lanes of a SIMD row then wait for
// each other only at the end; nested loops (bricks, then voxels) made a
// lane that entered a brick wait for the others' bricks (measured slower:
// docs/benchmarks.md).
// any_hit skips what only the closest hit needs.
Hit trace_dda(vec3 o, vec3 d, float tmax, bool any_hit)
{
    Hit h;
    h.hit = false;
    h.t = tmax;
    h.voxel = ivec3(0);
    h.normal = ivec3(0);
    h.block = 0u;
    h.chunk = -1;
    // no division by zero: a tiny component behaves like a parallel ray
    d = mix(d, vec3(1e-7), lessThan(abs(d), vec3(1e-7)));
    vec3 inv = 1.0 / d;
    ivec3 stp = ivec3(greaterThan(d, vec3(0.0))) * 2 - 1;  // d has no zero component here
    ivec3 fwd = ivec3(greaterThan(stp, ivec3(0)));  // 1 where the ray goes up an axis
    // Only the box of the world's non-air blocks can be hit: start where the
    // ray enters it and stop where it leaves (primary rays from above the
    // terrain skip their empty descent, shadow rays stop above the highest
    // block instead of at the top of the chunks). Box and grid come from the
    // frame uniforms: scalar loads, where the world header would be texel
    // fetches per ray.
    vec3 lo = frame.world_lo.xyz, hi = frame.world_hi.xyz;
    if (any(greaterThanEqual(lo, hi)))
        return h;
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tin = min(t0, t1), tout = max(t0, t1);
    float t = max(max(tin.x, max(tin.y, tin.z)), 0.0);
    tmax = min(tmax, min(tout.x, min(tout.y, tout.z)));
    if (t > tmax)
        return h;
    ivec3 v = clamp(ifloor(o + d * t), ivec3(lo), ivec3(hi) - 1);  // t is on the box's boundary
    // entering the box: the face crossed last, facing the ray
    ivec3 n = t > 0.0 ? -trace_step_mask(-tin) * stp : ivec3(0);
    ivec3 grid = frame.world_grid.xyz;
    vec2 inv_grid = 1.0 / vec2(grid.xz);
    ivec3 chunk_of_base = ivec3(-2147483647);
    int base = -1, hit_base = -1;
    uint chunk_mask = 0u;
    uvec2 chunk_sub = uvec2(0u);
    uint cached_word = 0xffffffffu, bits = 0u;
    // every iteration crosses at least one voxel boundary
    int steps = ifloor(min(tmax - t, 1e6)) * 3 + 8;
    for (int i = 0; i < steps && t <= tmax; i++) {
        ivec3 chunk = v >> 4;
        if (chunk != chunk_of_base) {
            chunk_of_base = chunk;
            uint word3;
            base = world_chunk_in(grid, inv_grid, chunk, word3, chunk_sub);
            chunk_mask = word3 & 0xffu;
        }
        ivec3 l = v & 15;
        ivec3 b = l >> 3, s = (l >> 2) & 1;
        uint bi = uint(b.x + 2 * (b.z + 2 * b.y));
        uint sub = chunk_mask == 0u ? 0u : ((bi < 4u ? chunk_sub.x : chunk_sub.y) >> (8u * (bi & 3u))) & 0xffu;
        int size = chunk_mask == 0u ? 16 : sub == 0u ? 8 : (sub & (1u << uint(s.x + 2 * (s.z + 2 * s.y)))) == 0u ? 4 : 2;
        // Each `if` is a branch on "any lane" on a CPU device: one for the
        // word's fetch, one for a hit, the rest selects (faster than nested
        // ifs with the hit's work inside the loop: docs/benchmarks.md).
        uint word = uint(base) + world_occ_word(l);
        if (size == 2 && word != cached_word) {
            cached_word = word;
            bits = world_word(word);
        }
        bool cell = size == 2 && (bits & world_cell2_bits(l)) != 0u;
        if (cell && (bits & (1u << world_occ_bit(l))) != 0u) {
            h.hit = true;
            h.t = t;
            h.voxel = v;
            h.normal = n;
            hit_base = base;
            break;
        }
        // In a non-empty 2^3 cell the 2x1x2 layer of it holding v may still
        // be empty: rays along a floor cross that air 2 voxels at a time
        // (fewer iterations for AO rays: docs/benchmarks.md).
        ivec3 box = !cell ? ivec3(size) : (bits & world_layer2_bits(l)) == 0u ? ivec3(2, 1, 2) : ivec3(1);
        // leave the empty box (or the voxel): its exit face, and the voxel
        // past it from the exit point (no error adds up over the steps)
        ivec3 c = v & ~(box - 1);
        vec3 tc = (vec3(c + fwd * box) - o) * inv;
        ivec3 m = trace_step_mask(tc);
        t = min(tc.x, min(tc.y, tc.z));  // = tc[m], off m's dependency chain
        ivec3 pv = clamp(ifloor(o + d * t), c, c + (box - 1));
        v = pv + m * (c + fwd * (box + 1) - 1 - pv);
        n = -m * stp;
    }
    if (h.hit) {
        if (!any_hit)  // occlusion needs no block id: save the fetch
            h.block = world_block_local(hit_base, h.voxel & 15);
        h.chunk = int((uint(hit_base) - WORLD_SLOTS) / WORLD_SLOT_UINTS);
    }
    return h;
}

// Closest hit along unit direction d from o, up to tmax.
Hit trace_closest(vec3 o, vec3 d, float tmax) { return trace_dda(o, d, tmax, false); }

// Anything between o and o + d * tmax?
bool trace_any(vec3 o, vec3 d, float tmax) { return trace_dda(o, d, tmax, true).hit; }
#endif
#endif
