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
    int kernel;          // 0 screen: a disc in pixels; 1 surface: a disc on the face, projected
} params;
const int KERNEL_SURFACE = 1;

// Iterations read and write a packed texel (rgba32ui): a tap is one fetch.
//   x = bits of the visibility, y = half2(radius, footprint blocks/px), the
//       radius in pixels (kernel screen) or blocks on the face (surface),
//   z = bits of N . X, w = normal axis 0..5 (+x -x +y -y +z -z), SKY on sky
const uint SKY = 7u;

// The pixel a world point projects to (centres at + 0.5, as frame_ray_dir).
vec2 pixel_of(vec3 x, vec2 size)
{
    vec4 clip = frame.view_proj * vec4(x, 1.0);
    return (clip.xy / max(clip.w, 1e-6) * 0.5 + 0.5) * size - 0.5;
}

// kernel surface: the disc of radius r (blocks) on the face of axis
// `axis` at x, as the screen shows it: the ellipse through the images
// e1, e2 (pixels) of r along the face's two other axes (conjugate
// semi-diameters), each scaled down to max_radius (an iteration's r is
// halved before the cap, so a capped reach does not halve). Seen at a
// grazing angle (the ground ahead of a walker) the disc is foreshortened,
// where a disc in pixels would spread the shadow over blocks far beyond
// the penumbra.
void surface_ellipse(vec3 x, uint axis, float r, vec2 size, out vec2 e1, out vec2 e2)
{
    vec3 u = vec3(0.0), v = vec3(0.0);
    u[(axis >> 1) == 0u ? 1 : 0] = r;
    v[(axis >> 1) == 2u ? 1 : 2] = r;
    vec2 c = pixel_of(x, size);
    e1 = pixel_of(x + u, size) - c;
    e2 = pixel_of(x + v, size) - c;
    float l1 = length(e1), l2 = length(e2);
    if (l1 > params.max_radius)
        e1 *= params.max_radius / l1;
    if (l2 > params.max_radius)
        e2 *= params.max_radius / l2;
}

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
        // penumbra half-width d tan(a): blocks (surface), pixels (screen)
        if (d >= 0.0) {
            radius = params.radius_scale * d * tan(params.sun_radians);
            if (params.kernel != KERNEL_SURFACE)
                radius = min(radius / max(footprint, 1e-6), params.max_radius);
        }
    }
    imageStore(out_pong, p, uvec4(floatBitsToUint(v), packHalf2x16(vec2(radius, footprint)), floatBitsToUint(plane), x.w == 0.0 ? SKY : axis_of(n)));
#ifdef RADIUS_OUT
    // the pixels of the filter's longest reach
    float shown = radius;
    if (params.kernel == KERNEL_SURFACE && radius > 0.0) {
        vec2 e1, e2;
        surface_ellipse(x.xyz, axis_of(n), radius, vec2(size), e1, e2);
        shown = max(length(e1), length(e2));
    }
    imageStore(out_radius, p, vec4(shown));
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
    if (t.w == SKY || radius <= 0.0) {
        store(p, t, v);
        return;
    }
    float plane = uintBitsToFloat(t.z);
    // kernel surface: the taps' offsets are rho (cos, sin) through the
    // ellipse's semi-axes e1, e2 (pixels), and a tap may lie off p's plane
    // by sigma_z times its distance on the face, rho r
    vec2 e1 = vec2(0.0), e2 = vec2(0.0);
    if (params.kernel == KERNEL_SURFACE) {
        // p's surface point: where its pixel's ray meets the plane N.X = plane
        vec3 n = vec3(0.0);
        n[t.w >> 1] = (t.w & 1u) == 0u ? 1.0 : -1.0;
        vec3 dir = frame_ray_dir(vec2(p), vec2(size));
        float facing = dot(n, dir);
        // a face seen edge-on: no point to reconstruct (the pixel's own
        // ray hit it, so this is rounding, not a visible face)
        if (abs(facing) < 1e-6) {
            store(p, t, v);
            return;
        }
        vec3 x = frame.camera_pos.xyz + dir * ((plane - dot(n, frame.camera_pos.xyz)) / facing);
        surface_ellipse(x, t.w, radius, vec2(size), e1, e2);
        if (max(dot(e1, e1), dot(e2, e2)) < 0.25) {
            store(p, t, v);
            return;
        }
    } else if (radius < 0.5) {
        store(p, t, v);
        return;
    }
    // a new turn of the spiral per pixel and frame: no fixed pattern
    Rng r = rng_init(uvec2(p), frame.frame_info.x + uint(params.iteration) * 7919u, frame.frame_info.w, SALT);
    float turn = rng_next(r) * 6.28318531;
    float sum = v, weight = 1.0;
    for (int k = 0; k < params.taps; k++) {
        float a = turn + float(k) * GOLDEN_ANGLE;
        ivec2 o;
        float w, reach;  // the tap's Gaussian weight; its allowed distance from p's plane
        if (params.kernel == KERNEL_SURFACE) {
            float rho = sqrt((float(k) + 0.5) / float(params.taps));
            vec2 cs = vec2(cos(a), sin(a));
            o = ivec2(round(rho * (cs.x * e1 + cs.y * e2)));
            w = exp(-2.0 * rho * rho);
            reach = params.sigma_z * rho * radius;
        } else {
            float rad = radius * sqrt((float(k) + 0.5) / float(params.taps));
            o = ivec2(round(rad * vec2(cos(a), sin(a))));
            float dist = length(vec2(o));
            w = exp(-2.0 * dist * dist / (radius * radius));
            reach = params.sigma_z * dist * rf.y;
        }
        ivec2 q = p + o;
        if (o == ivec2(0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
            continue;
        uvec4 u = imageLoad(in_src, q);
        // same face orientation and plane (the plane test of svgf_atrous)
        bool same = u.w == t.w && abs(uintBitsToFloat(u.z) - plane) <= reach;
        w = same ? w : 0.0;
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
