#version 460
// Clamped temporal accumulation with a fast history and anti-lag:
// clamped_reproject.c has the rules.
#include "pixel.glsl"
#include "color.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_motion;
layout(binding = 2) uniform sampler2D in_position;
layout(binding = 3) uniform sampler2D in_normal;
layout(binding = 4, rg32ui) uniform readonly uimage2D in_ids;
layout(binding = 5) uniform sampler2D in_history;
layout(binding = 6) uniform sampler2D in_prev_fast;
layout(binding = 7) uniform sampler2D in_prev_moments;
layout(binding = 8) uniform sampler2D in_prev_position;
layout(binding = 9) uniform sampler2D in_prev_normal;
layout(binding = 10, rg32ui) uniform readonly uimage2D in_prev_ids;
#define FRAME_BINDING 11
#include "frame.glsl"
#ifndef DEBUG
layout(binding = 12, rgba16f) uniform writeonly image2D out_color;
layout(binding = 13, rgba16f) uniform writeonly image2D out_fast;
layout(binding = 14, rg32f) uniform writeonly image2D out_moments;
layout(binding = 15, r16f) uniform writeonly image2D out_length;
#else
// The debug dispatch: the same history computed again, only the debug
// outputs written (1x1 stand-ins unless read: debug_outputs says which are)
layout(binding = 12, r16f) uniform writeonly image2D out_disocclusion;
layout(binding = 13, rgba32f) uniform writeonly image2D out_reprojection;
layout(binding = 14, rg16f) uniform writeonly image2D out_clamp;
#endif
layout(push_constant) uniform Params {
    float alpha, fast_alpha, clamp_k, antilag, antilag_threshold, normal_threshold, plane_distance, footprints, sun_span;
    int max_length, cubic, nearest, fallback, history_valid;
#ifdef DEBUG
    int debug_outputs; // 1: disocclusion, 2: reprojection, 4: clamp
#endif
} params;

#ifdef DEBUG
// where the history was read (xy, pixel centres at +0.5), the weight of
// the taps that passed, and how: 1 bilinear, 2 the 3x3 fallback,
// 3 Catmull-Rom, 4 nearest, 0 none
vec4 debug_target;
#define DEBUG_TARGET(v) debug_target = (v)
#else
#define DEBUG_TARGET(v)
#endif

// YCoCg: the clamp box is tighter around real colours than one in RGB
vec3 to_ycocg(vec3 c) { return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b); }
vec3 from_ycocg(vec3 y) { return vec3(y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z); }

// the range of the history taps that passed the surface tests
vec3 lo, hi;

// How far (blocks) the previous point may lie from x: `footprints` pixel
// steps on the surface at x. Far away a pixel spans several blocks, and a
// voxel world's coplanar faces (canopy tops, terraces) in one chunk pass
// the plane test blocks apart; 0: no limit
float reach;

// Does the previous frame's pixel t show this pixel's surface (x, n, chunk)?
bool same_surface(ivec2 t, ivec2 size, vec3 x, vec3 n, uint chunk)
{
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size)))
        return false;
    vec4 px = texelFetch(in_prev_position, t, 0);
    if (px.w == 0.0 || imageLoad(in_prev_ids, t).y != chunk)
        return false;
    if (dot(texelFetch(in_prev_normal, t, 0).xyz, n) < params.normal_threshold)
        return false;
    return abs(dot(px.xyz - x, n)) <= params.plane_distance && (reach == 0.0 || distance(px.xyz, x) <= reach);
}

// Catmull-Rom weights of the 4 taps around f in [0, 1)
vec4 catmull_rom_weights(float f)
{
    float f2 = f * f, f3 = f2 * f;
    return vec4(-0.5 * f3 + f2 - 0.5 * f, 1.5 * f3 - 2.5 * f2 + 1.0, -1.5 * f3 + 2.0 * f2 + 0.5 * f, 0.5 * f3 - 0.5 * f2);
}

// The history at q resampled with a 4x4 Catmull-Rom: repeated bilinear
// resampling blurs the history a little more every frame, which costs
// small shadows and texture-scale detail under a moving camera
vec3 catmull_rom(vec2 q, ivec2 size)
{
    ivec2 q0 = ifloor(q);
    vec2 f = q - vec2(q0);
    vec4 wx = catmull_rom_weights(f.x), wy = catmull_rom_weights(f.y);
    vec3 s = vec3(0.0);
    for (int j = 0; j < 4; j++) {
        vec3 row = vec3(0.0);
        for (int i = 0; i < 4; i++)
            row += wx[i] * texelFetch(in_history, clamp(q0 + ivec2(i - 1, j - 1), ivec2(0), size - 1), 0).rgb;
        s += wy[j] * row;
    }
    return s;
}

struct History {
    vec3 color, fast;
    vec2 moments;
    float frames;
};

void add_tap(inout History h, ivec2 t, float w)
{
    vec3 c = texelFetch(in_history, t, 0).rgb;
    lo = min(lo, c), hi = max(hi, c);
    h.color += w * c;
    vec4 fast = texelFetch(in_prev_fast, t, 0); // history length in alpha
    h.fast += w * fast.rgb;
    h.moments += w * texelFetch(in_prev_moments, t, 0).xy;
    h.frames += w * fast.a;
}

// The reprojected history of p (weights normalised); wsum 0: none
float reproject(ivec2 p, ivec2 size, vec3 x, out History h)
{
    h = History(vec3(0.0), vec3(0.0), vec2(0.0), 0.0);
    lo = vec3(1e30), hi = vec3(-1e30);
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    reach = 0.0;
    if (params.footprints > 0.0) {
        vec3 v = x - frame.camera_pos.xyz;
        float d = length(v);
        // a pixel step at distance d, stretched on a surface seen at a slant
        float step = d * 2.0 * tan(0.5 * frame.camera_pos.w) / float(size.y) / max(abs(dot(n, v / d)), 0.1);
        reach = params.footprints * step;
    }
    uint chunk = imageLoad(in_ids, p).y;
    vec2 q = vec2(p) - texelFetch(in_motion, p, 0).xy;
    ivec2 q0 = ifloor(q);
    vec2 f = q - vec2(q0);
    float wsum = 0.0, best_w = 0.0;
    ivec2 best = ivec2(0);
    for (int i = 0; i < 4; i++) {
        ivec2 o = ivec2(i & 1, i >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (w > 0.0 && same_surface(q0 + o, size, x, n, chunk)) {
            add_tap(h, q0 + o, w);
            wsum += w;
            best = w > best_w ? o : best;
            best_w = max(best_w, w);
        }
    }
    DEBUG_TARGET(vec4(q + 0.5, wsum, 1.0));
    // nearest: the passing tap that bilinear weighs most, alone
    if (params.nearest != 0 && wsum >= 1e-4) {
        h = History(vec3(0.0), vec3(0.0), vec2(0.0), 0.0);
        add_tap(h, q0 + best, 1.0);
        wsum = 1.0;
        DEBUG_TARGET(vec4(q + 0.5, debug_target.z, 4.0));
    }
    bool all_taps = wsum > 0.999;
    if (wsum < 1e-4 && params.fallback != 0) { // no bilinear tap: the 3x3 around the nearest pixel
        h = History(vec3(0.0), vec3(0.0), vec2(0.0), 0.0);
        wsum = 0.0;
        ivec2 r = ifloor(q + 0.5);
        for (int i = 0; i < 9; i++) {
            ivec2 t = r + ivec2(i % 3 - 1, i / 3 - 1);
            if (same_surface(t, size, x, n, chunk)) {
                add_tap(h, t, 1.0);
                wsum += 1.0;
            }
        }
        DEBUG_TARGET(vec4(q + 0.5, wsum / 9.0, 2.0));
    }
    if (wsum >= 1e-4) {
        h.color /= wsum;
        // every bilinear tap on this surface: the sharper cubic, kept
        // within the taps' range (no ringing, no other surface's colour)
        if (params.cubic != 0 && params.nearest == 0 && all_taps) {
            h.color = clamp(catmull_rom(q, size), lo, hi);
            DEBUG_TARGET(vec4(q + 0.5, 1.0, 3.0));
        }
        h.fast /= wsum;
        h.moments /= wsum;
        h.frames /= wsum;
    }
    return wsum;
}

// mean and sigma of this frame's 3x3 non-sky neighbourhood, in YCoCg, and
// the sigma of its luminance (w)
void neighbourhood(ivec2 p, ivec2 size, out vec3 mean, out vec4 sigma)
{
    vec3 s1 = vec3(0.0), s2 = vec3(0.0);
    vec2 l = vec2(0.0);
    float n = 0.0;
    for (int i = 0; i < 9; i++) {
        ivec2 q = clamp(p + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1);
        if (texelFetch(in_position, q, 0).w == 0.0)
            continue;
        vec3 c = texelFetch(in_illumination, q, 0).rgb, y = to_ycocg(c);
        float lq = luminance(c);
        s1 += y, s2 += y * y, l += vec2(lq, lq * lq), n += 1.0;
    }
    // p itself is not sky, so n >= 1
    mean = s1 / n;
    sigma = sqrt(max(vec4(s2 / n - mean * mean, l.y / n - (l.x / n) * (l.x / n)), vec4(0.0)));
}

#ifdef DEBUG
// what the debug dispatch writes where the main one writes its outputs
void debug_store(ivec2 p, bool restarted, vec2 moved)
{
    if ((params.debug_outputs & 1) != 0)
        imageStore(out_disocclusion, p, vec4(restarted ? 1.0 : 0.0));
    if ((params.debug_outputs & 2) != 0)
        imageStore(out_reprojection, p, restarted ? vec4(debug_target.xy, 0.0, 0.0) : debug_target);
    if ((params.debug_outputs & 4) != 0)
        imageStore(out_clamp, p, vec4(moved, 0.0, 0.0));
}
#endif

#ifdef DEBUG
bool debug_surface; // restart(): p is a surface pixel, whose history restarted
#endif

void restart(ivec2 p, vec3 c, float l)
{
#ifdef DEBUG
    debug_store(p, debug_surface, vec2(0.0));
#else
    imageStore(out_color, p, vec4(c, 1.0));
    imageStore(out_fast, p, vec4(c, 0.0));
    imageStore(out_moments, p, vec4(l, l * l, 0.0, 0.0));
    imageStore(out_length, p, vec4(0.0));
#endif
}

void shade(ivec2 p)
{
#ifdef DEBUG
    ivec2 size = textureSize(in_position, 0); // every input is at the outputs' size
#else
    ivec2 size = imageSize(out_color);
#endif
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_illumination, p, 0).rgb;
    float l = luminance(c);
    vec4 pos = texelFetch(in_position, p, 0);
    History h;
    DEBUG_TARGET(vec4(0.0));
    if (pos.w == 0.0 || params.history_valid == 0 || reproject(p, size, pos.xyz, h) < 1e-4) {
#ifdef DEBUG
        debug_surface = pos.w != 0.0;
#endif
        restart(p, c, l);
        return;
    }
    vec3 mean;
    vec4 sigma;
    neighbourhood(p, size, mean, sigma);
    vec3 slow = h.color;
#ifdef DEBUG
    float clamped = 0.0, antilag_share = 0.0;
#endif
    if (params.clamp_k > 0.0) {
        vec3 box = params.clamp_k * sigma.xyz;
#ifdef DEBUG
        // measured in YCoCg, where the box is: 0 inside it, exactly
        clamped = distance(clamp(to_ycocg(slow), mean - box, mean + box), to_ycocg(slow));
#endif
        slow = from_ycocg(clamp(to_ycocg(slow), mean - box, mean + box));
    }
    float len = min(floor(h.frames + 0.5) + 1.0, min(float(params.max_length), frame_sun_history_frames(params.sun_span)));
    vec3 fast = mix(h.fast, c, max(params.fast_alpha, 1.0 / (len + 1.0)));
    if (params.antilag > 0.0) {
        float noise = sigma.w * sqrt(params.fast_alpha / (2.0 - params.fast_alpha)) + 1e-4;
        float excess = max(0.0, abs(luminance(fast) - luminance(slow)) / noise - params.antilag_threshold);
        float cut = 1.0 + params.antilag * excess;
        slow = mix(slow, fast, 1.0 - 1.0 / cut);
        len = floor(len / cut);
#ifdef DEBUG
        antilag_share = 1.0 - 1.0 / cut;
#endif
    }
#ifdef DEBUG
    debug_store(p, false, vec2(clamped, antilag_share));
#else
    float a = max(params.alpha, 1.0 / (len + 1.0));
    float samples = min(len + 1.0, (2.0 - params.alpha) / params.alpha);
    imageStore(out_color, p, vec4(mix(slow, c, a), samples));
    imageStore(out_fast, p, vec4(fast, len));
    imageStore(out_moments, p, vec4(mix(h.moments, vec2(l, l * l), a), 0.0, 0.0));
    imageStore(out_length, p, vec4(len));
#endif
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
