#version 460
// shadow_denoise (see shadow_denoise.c): with PACK the penumbra radius and
// the packing of visibility and surface; with BLUR one filter iteration.
#include "pixel.glsl"
// (an include is read once, whatever the #if around it: include here)
#if defined(PACK)
#define FRAME_BINDING 4
#else
#define FRAME_BINDING 1
#endif
#include "frame.glsl"
#include "random.glsl"

layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;

layout(push_constant) uniform Params {
    float sun_radians;   // the parameter sun_radius in radians
    float radius_scale;  // filter radius in penumbra half-widths
    float max_radius;    // pixels
    float sigma_z;
    int taps;
    int iteration;       // BLUR: the radius is halved this many times
} params;

// Iterations read and write a packed texel (rgba32ui): a tap is one fetch.
//   x = bits of the visibility, y = half2(radius px, footprint blocks/px),
//   z = bits of N . X, w = normal axis 0..5 (+x -x +y -y +z -z), SKY on sky
const uint SKY = 7u;

#if defined(PACK)
layout(binding = 0) uniform sampler2D in_visibility;
layout(binding = 1) uniform sampler2D in_occluder;
layout(binding = 2) uniform sampler2D in_position;
layout(binding = 3) uniform sampler2D in_normal;
layout(binding = 5, rgba32ui) uniform writeonly uimage2D out_pong;
layout(binding = 6, r16f) uniform writeonly image2D out_radius;

uint axis_of(vec3 n)
{
    vec3 a = abs(n);
    return a.x > 0.5 ? (n.x > 0.0 ? 0u : 1u) : a.y > 0.5 ? (n.y > 0.0 ? 2u : 3u) : (n.z > 0.0 ? 4u : 5u);
}

// Mean blocker distance over this plane's pixels of a 5x5 window (every
// other pixel): a lit pixel beside a penumbra saw no blocker itself but
// must be filtered like its neighbours; -1 when none saw one.
float occluder_near(ivec2 p, ivec2 size, vec3 n, float plane)
{
    float sum = 0.0;
    int count = 0;
    for (int dy = -2; dy <= 2; dy += 2)
        for (int dx = -2; dx <= 2; dx += 2) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
            float d = texelFetch(in_occluder, q, 0).r;
            // most pixels saw no blocker: their surface is not read
            if (!(d >= 0.0))
                continue;
            vec4 x = texelFetch(in_position, q, 0);
            if (x.w != 0.0 && dot(texelFetch(in_normal, q, 0).xyz, n) > 0.5 && abs(dot(n, x.xyz) - plane) < 0.5) {
                sum += d;
                count++;
            }
        }
    return count > 0 ? sum / float(count) : -1.0;
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_pong);
    if (any(greaterThanEqual(p, size)))
        return;
    float v = texelFetch(in_visibility, p, 0).r;
    vec4 x = texelFetch(in_position, p, 0);
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    float plane = dot(n, x.xyz);
    float radius = 0.0, footprint = 0.0;
    if (x.w != 0.0) {
        // blocks one pixel spans at this depth: |camera_up| = tan(fov / 2)
        float z = dot(x.xyz - frame.camera_pos.xyz, normalize(frame.camera_forward.xyz));
        footprint = z * 2.0 * length(frame.camera_up.xyz) / float(size.y);
        float d = occluder_near(p, size, n, plane);
        // penumbra half-width d tan(a), in pixels
        if (d >= 0.0)
            radius = min(params.radius_scale * d * tan(params.sun_radians) / max(footprint, 1e-6), params.max_radius);
    }
    imageStore(out_pong, p, uvec4(floatBitsToUint(v), packHalf2x16(vec2(radius, footprint)), floatBitsToUint(plane), x.w == 0.0 ? SKY : axis_of(n)));
#ifdef RADIUS_OUT
    imageStore(out_radius, p, vec4(radius));
#endif
}
#else
layout(binding = 0, rgba32ui) uniform readonly uimage2D in_src;
#if defined(TO_PACKED)
layout(binding = 2, rgba32ui) uniform writeonly uimage2D out_dst;
#else
layout(binding = 2, r16f) uniform writeonly image2D out_dst;
#endif

const uint SALT = 0x53484431u;  // this pass's random stream
const float GOLDEN_ANGLE = 2.39996323;

void store(ivec2 p, uvec4 t, float v)
{
#if defined(TO_PACKED)
    imageStore(out_dst, p, uvec4(floatBitsToUint(v), t.yzw));
#else
    imageStore(out_dst, p, vec4(v));
#endif
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_dst);
    if (any(greaterThanEqual(p, size)))
        return;
    uvec4 t = imageLoad(in_src, p);
    float v = uintBitsToFloat(t.x);
    vec2 rf = unpackHalf2x16(t.y);
    float radius = rf.x * exp2(-float(params.iteration));
    if (t.w == SKY || radius < 0.5) {
        store(p, t, v);
        return;
    }
    float plane = uintBitsToFloat(t.z);
    // a new turn of the spiral per pixel and frame: no fixed pattern
    Rng r = rng_init(uvec2(p), frame.frame_info.x + uint(params.iteration) * 7919u, frame.frame_info.w, SALT);
    float turn = rng_next(r) * 6.28318531;
    float sum = v, weight = 1.0;
    for (int k = 0; k < params.taps; k++) {
        float a = turn + float(k) * GOLDEN_ANGLE, rad = radius * sqrt((float(k) + 0.5) / float(params.taps));
        ivec2 o = ivec2(round(rad * vec2(cos(a), sin(a))));
        ivec2 q = p + o;
        if (o == ivec2(0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
            continue;
        uvec4 u = imageLoad(in_src, q);
        float dist = length(vec2(o));
        // same face orientation and plane (the plane test of svgf_atrous)
        bool same = u.w == t.w && abs(uintBitsToFloat(u.z) - plane) <= params.sigma_z * dist * rf.y;
        float w = same ? exp(-2.0 * dist * dist / (radius * radius)) : 0.0;
        sum += w * uintBitsToFloat(u.x);
        weight += w;
    }
    store(p, t, sum / weight);
}
#endif

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
