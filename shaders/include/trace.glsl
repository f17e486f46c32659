// Ray traversal of the voxel world, one interface for every pass:
//   Hit trace_closest(origin, unit direction, tmax)   closest hit
//   bool trace_any(origin, unit direction, tmax)      occlusion
// Backend 1 (default): a two-level DDA (Amanatides & Woo) that steps over 8^3
// bricks using the chunk's brick mask, and over voxels only inside bricks
// that hold something, crossing their empty 4^3 sub-bricks in one step. Backend 2 (#define TRACE_RAYQUERY, TLAS_BINDING):
// VK_KHR_ray_query against the scene's per-chunk BLASes. Include world.glsl
// and frame.glsl first.
//
// What the DDA is shaped by (measured on lavapipe, docs/benchmarks.md): a
// buffer load with a per-invocation address is a scalar loop over the SIMD
// lanes, integer division is scalar, and a dynamically indexed vector spills
// to memory. So steps are one-hot masks, a chunk costs one load (world_chunk)
// and its brick mask is kept in a register, voxel words are reloaded only
// when the word changes, and the ray is clipped to the world's height first.
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
layout(binding = TLAS_BINDING) uniform accelerationStructureEXT trace_tlas;

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
    rayQueryInitializeEXT(q, trace_tlas, gl_RayFlagsOpaqueEXT, 0xff, o, 0.0, d, tmax);
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
    rayQueryInitializeEXT(q, trace_tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xff, o, 0.0, d, tmax);
    while (rayQueryProceedEXT(q)) {
    }
    return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT;
}
#else
// Voxel DDA inside one brick (cell = brick coordinate), from distance t.
// sub: the brick's 4^3 sub-brick mask; an empty sub-brick is crossed in one
// step (to where the ray leaves it) instead of voxel by voxel.
bool trace_brick(vec3 o, vec3 d, vec3 inv, ivec3 stp, int base, ivec3 brick, uint sub, float t, ivec3 entry_normal, float tmax, bool any_hit,
                 inout Hit h)
{
    ivec3 lo = brick * 8, hi = lo + 7;
    ivec3 v = clamp(ifloor(o + d * t), lo, hi);
    vec3 tnext = (vec3(v) + max(vec3(stp), vec3(0.0)) - o) * inv;
    vec3 tdelta = abs(inv);
    ivec3 n = entry_normal;
    ivec3 chunk_origin = (brick >> 1) * 16;
    // consecutive voxels often share an occupancy word, and every buffer
    // load with a per-lane address is a scalar loop on a CPU device
    uint brick_words = uint(base) + WORLD_OCC + uint((brick.x & 1) + 2 * ((brick.z & 1) + 2 * (brick.y & 1))) * 16u;
    uint cached_word = 0xffffffffu, bits = 0u;
    vec3 up = max(vec3(stp), vec3(0.0));
    ivec3 beyond = ivec3(greaterThan(stp, ivec3(0))) * 5 - 1; // from a 4^3 cell's low corner: +4 or -1
    for (int i = 0; i < 25; i++) {
        if (t > tmax)
            return false;
        ivec3 l = v & 7;
        ivec3 s = l >> 2;
        if ((sub & (1u << uint(s.x + 2 * (s.z + 2 * s.y)))) == 0u) {
            // leave the empty sub-brick: its exit face, and the voxel past it
            ivec3 c4 = v & ~3;
            vec3 t4 = ((vec3(c4) + up * 4.0) - o) * inv;
            ivec3 m = trace_step_mask(t4);
            t = dot(vec3(m), t4);
            ivec3 pv = clamp(ifloor(o + d * t), c4, c4 + 3);
            v = pv + m * (c4 + beyond - pv);
            tnext = (vec3(v) + up - o) * inv;
            n = -m * stp;
            if (any(lessThan(v, lo)) || any(greaterThan(v, hi)))
                return false;
            continue;
        }
        uint vbit = uint(l.x + 8 * (l.z + 8 * l.y));
        if ((vbit >> 5) != cached_word) {
            cached_word = vbit >> 5;
            bits = world_word(brick_words + cached_word);
        }
        if ((bits & (1u << (vbit & 31u))) != 0u) {
            h.hit = true;
            h.t = t;
            h.voxel = v;
            h.normal = n;
            if (!any_hit)  // occlusion needs no block id: save the fetch
                h.block = world_block_local(base, v - chunk_origin);
            h.chunk = int((uint(base) - WORLD_SLOTS) / WORLD_SLOT_UINTS);
            return true;
        }
        ivec3 m = trace_step_mask(tnext);
        t = dot(vec3(m), tnext);
        tnext += vec3(m) * tdelta;
        v += m * stp;
        n = -m * stp;
        if (any(lessThan(v, lo)) || any(greaterThan(v, hi)))
            return false;
    }
    return false;
}

// The DDA for both queries: any_hit skips what only the closest hit needs.
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
    // Only the box around the loaded chunks holds blocks: start where the
    // ray enters it and stop where it leaves (primary rays from above the
    // terrain skip their empty descent; rays toward the horizon stop at the
    // last loaded chunk instead of stepping through unloaded space).
    // the world's box and grid from the frame uniforms: scalar loads,
    // where the world header would be texel fetches per ray
    vec3 lo = frame.world_lo.xyz, hi = frame.world_hi.xyz;
    if (any(greaterThanEqual(lo, hi)))  // nothing loaded
        return h;
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tin = min(t0, t1), tout = max(t0, t1);
    float t = max(max(tin.x, max(tin.y, tin.z)), 0.0);
    tmax = min(tmax, min(tout.x, min(tout.y, tout.z)));
    if (t > tmax)
        return h;
    // entering the box: the face crossed last, facing the ray
    ivec3 n = t > 0.0 ? -trace_step_mask(-tin) * stp : ivec3(0);
    // the brick at the entry point, inside the box (t is on its boundary)
    ivec3 cell = clamp(ifloor((o + d * t) / 8.0), ifloor(lo / 8.0), ifloor(hi / 8.0) - 1);
    vec3 tnext = ((vec3(cell) + max(vec3(stp), vec3(0.0))) * 8.0 - o) * inv;
    vec3 tdelta = abs(8.0 * inv);
    int base = -1;
    uint chunk_mask = 0u;
    uvec2 chunk_sub = uvec2(0u);
    ivec3 grid = frame.world_grid.xyz;
    vec2 inv_grid = 1.0 / vec2(grid.xz);
    ivec3 base_chunk = ivec3(-2147483647);
    int steps = ifloor(min((tmax - t) / 8.0, 1e6)) * 3 + 8;
    for (int i = 0; i < steps && t <= tmax; i++) {
        ivec3 chunk = cell >> 1;
        if (chunk != base_chunk) {
            base_chunk = chunk;
            base = world_chunk_in(grid, inv_grid, chunk);
            chunk_mask = base >= 0 ? world_brick_mask(base) : 0u;
            if (chunk_mask != 0u)
                chunk_sub = uvec2(world_word(uint(base)), world_word(uint(base) + 1u));
        }
        ivec3 b = cell & 1;
        uint bi = uint(b.x + 2 * (b.z + 2 * b.y));
        uint sub = ((bi < 4u ? chunk_sub.x : chunk_sub.y) >> (8u * (bi & 3u))) & 0xffu;
        if ((chunk_mask & (1u << bi)) != 0u && trace_brick(o, d, inv, stp, base, cell, sub, t, n, tmax, any_hit, h))
            return h;
        ivec3 m = trace_step_mask(tnext);
        t = dot(vec3(m), tnext);
        tnext += vec3(m) * tdelta;
        cell += m * stp;
        n = -m * stp;
    }
    return h;
}

// Anything between o and o + d * tmax?
// Closest hit along unit direction d from o, up to tmax.
Hit trace_closest(vec3 o, vec3 d, float tmax) { return trace_dda(o, d, tmax, false); }

bool trace_any(vec3 o, vec3 d, float tmax) { return trace_dda(o, d, tmax, true).hit; }
#endif
#endif
