// Ray traversal of the voxel world, one interface for every pass:
//   Hit trace_closest(origin, unit direction, tmax)   closest hit
//   bool trace_any(origin, unit direction, tmax)      occlusion
// Backend 1 (default): a two-level DDA (Amanatides & Woo) that steps over 8^3
// bricks using the chunk's brick mask, and over voxels only inside bricks
// that hold something. Backend 2 (#define TRACE_RAYQUERY, TLAS_BINDING):
// VK_KHR_ray_query against the scene's per-chunk BLASes. Include world.glsl
// first.
#ifndef VOXRG_TRACE_GLSL
#define VOXRG_TRACE_GLSL

struct Hit {
    bool hit;
    float t;        // distance along the (unit) direction
    ivec3 voxel;    // the block hit
    ivec3 normal;   // face normal (zero if the ray started inside a block)
    uint block;     // block id
    int chunk;      // the world slot of its chunk (an object id, the same in both backends)
};

int trace_min_axis(vec3 v) { return v.x < v.y ? (v.x < v.z ? 0 : 2) : (v.y < v.z ? 1 : 2); }

// Voxel DDA inside one brick (cell = brick coordinate), from distance t.
bool trace_brick(vec3 o, vec3 d, vec3 inv, ivec3 stp, int base, ivec3 brick, float t, ivec3 entry_normal, float tmax, inout Hit h)
{
    ivec3 lo = brick * 8, hi = lo + 7;
    ivec3 v = clamp(ivec3(floor(o + d * t)), lo, hi);
    vec3 tnext = (vec3(v) + max(vec3(stp), vec3(0.0)) - o) * inv;
    vec3 tdelta = abs(inv);
    ivec3 n = entry_normal;
    ivec3 chunk_origin = (brick >> 1) * 16;
    for (int i = 0; i < 25; i++) {
        if (t > tmax)
            return false;
        if (world_voxel_solid(base, v - chunk_origin)) {
            h.hit = true;
            h.t = t;
            h.voxel = v;
            h.normal = n;
            h.block = world_block_local(base, v - chunk_origin);
            h.chunk = int((uint(base) - WORLD_SLOTS) / WORLD_SLOT_UINTS);
            return true;
        }
        int a = trace_min_axis(tnext);
        t = tnext[a];
        tnext[a] += tdelta[a];
        v[a] += stp[a];
        n = ivec3(0);
        n[a] = -stp[a];
        if (v[a] < lo[a] || v[a] > hi[a])
            return false;
    }
    return false;
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
    h.voxel = ivec3(floor(p - vec3(n) * 0.5));
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
// Closest hit along unit direction d from o, up to tmax.
Hit trace_closest(vec3 o, vec3 d, float tmax)
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
    ivec3 stp = ivec3(sign(d));
    ivec3 cell = ivec3(floor(o / 8.0));
    vec3 tnext = ((vec3(cell) + max(vec3(stp), vec3(0.0))) * 8.0 - o) * inv;
    vec3 tdelta = abs(8.0 * inv);
    float t = 0.0;
    ivec3 n = ivec3(0);
    int top_brick = world_height() / 8;
    int base = -1;
    ivec3 base_chunk = ivec3(-2147483647);
    int steps = int(tmax / 8.0) * 3 + 8;
    for (int i = 0; i < steps && t <= tmax; i++) {
        // above or below the world and moving away: nothing more to hit
        if ((cell.y < 0 && stp.y <= 0) || (cell.y >= top_brick && stp.y >= 0))
            break;
        ivec3 chunk = cell >> 1;
        if (chunk != base_chunk) {
            base_chunk = chunk;
            base = world_chunk(chunk);
        }
        if (base >= 0 && world_brick_solid(base, cell & 1) && trace_brick(o, d, inv, stp, base, cell, t, n, tmax, h))
            return h;
        int a = trace_min_axis(tnext);
        t = tnext[a];
        tnext[a] += tdelta[a];
        cell[a] += stp[a];
        n = ivec3(0);
        n[a] = -stp[a];
    }
    h.hit = false;
    h.t = tmax;
    return h;
}

// Anything between o and o + d * tmax?
bool trace_any(vec3 o, vec3 d, float tmax) { return trace_closest(o, d, tmax).hit; }
#endif
#endif
