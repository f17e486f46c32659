#version 460
// SVGF temporal accumulation: svgf_reproject.c has the rules.
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
layout(binding = 6) uniform sampler2D in_prev_moments;
layout(binding = 7) uniform sampler2D in_prev_length;
layout(binding = 8) uniform sampler2D in_prev_position;
layout(binding = 9) uniform sampler2D in_prev_normal;
layout(binding = 10, rg32ui) uniform readonly uimage2D in_prev_ids;
layout(binding = 11, rgba16f) uniform writeonly image2D out_color;
layout(binding = 12, rg32f) uniform writeonly image2D out_moments;
layout(binding = 13, r16f) uniform writeonly image2D out_length;
#ifdef DEBUG
// debug outputs, bound in the DEBUG variant only (1x1 stand-ins unless read)
layout(binding = 14, r16f) uniform writeonly image2D out_disocclusion;
layout(binding = 15, rgba32f) uniform writeonly image2D out_reprojection;
#endif
layout(push_constant) uniform Params {
    float alpha, moments_alpha, normal_threshold, plane_distance;
    int length_alpha, max_length, history_valid;
#ifdef DEBUG
    int debug_outputs; // 1: disocclusion is read, 2: reprojection is read
#endif
} params;

#ifdef DEBUG
// where the history was read (xy, pixel centres at +0.5), the weight of
// the taps that passed, and how: 1 bilinear, 2 the 3x3 fallback, 0 none
vec4 debug_target;
void debug_store(ivec2 p, bool restarted)
{
    if ((params.debug_outputs & 1) != 0)
        imageStore(out_disocclusion, p, vec4(restarted ? 1.0 : 0.0));
    if ((params.debug_outputs & 2) != 0)
        imageStore(out_reprojection, p, restarted ? vec4(debug_target.xy, 0.0, 0.0) : debug_target);
}
#define DEBUG_STORE(p, restarted) debug_store(p, restarted)
#define DEBUG_TARGET(v) debug_target = (v)
#else
#define DEBUG_STORE(p, restarted)
#define DEBUG_TARGET(v)
#endif

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
    return abs(dot(px.xyz - x, n)) <= params.plane_distance;
}

struct History {
    vec3 color;
    vec2 moments;
    float frames;
};

void add_tap(inout History h, ivec2 t, float w)
{
    h.color += w * texelFetch(in_history, t, 0).rgb;
    h.moments += w * texelFetch(in_prev_moments, t, 0).xy;
    h.frames += w * texelFetch(in_prev_length, t, 0).r;
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_illumination, p, 0).rgb;
    float l = luminance(c);
    vec4 pos = texelFetch(in_position, p, 0);
    History h = History(vec3(0.0), vec2(0.0), 0.0);
    float wsum = 0.0;
    DEBUG_TARGET(vec4(0.0));
    if (pos.w != 0.0 && params.history_valid != 0) {
        vec3 n = texelFetch(in_normal, p, 0).xyz;
        uint chunk = imageLoad(in_ids, p).y;
        // where the previous camera saw this point, in pixel coordinates
        vec2 q = vec2(p) - texelFetch(in_motion, p, 0).xy;
        ivec2 q0 = ifloor(q);
        vec2 f = q - vec2(q0);
        for (int i = 0; i < 4; i++) {
            ivec2 o = ivec2(i & 1, i >> 1);
            float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
            if (w > 0.0 && same_surface(q0 + o, size, pos.xyz, n, chunk)) {
                add_tap(h, q0 + o, w);
                wsum += w;
            }
        }
        DEBUG_TARGET(vec4(q + 0.5, wsum, 1.0));
        if (wsum < 1e-4) { // no bilinear tap: the 3x3 around the nearest pixel
            h = History(vec3(0.0), vec2(0.0), 0.0);
            wsum = 0.0;
            ivec2 r = ifloor(q + 0.5);
            for (int i = 0; i < 9; i++) {
                ivec2 t = r + ivec2(i % 3 - 1, i / 3 - 1);
                if (same_surface(t, size, pos.xyz, n, chunk)) {
                    add_tap(h, t, 1.0);
                    wsum += 1.0;
                }
            }
            DEBUG_TARGET(vec4(q + 0.5, wsum / 9.0, 2.0));
        }
    }
    DEBUG_STORE(p, pos.w != 0.0 && wsum < 1e-4);
    if (wsum < 1e-4) { // history restarts here
        imageStore(out_color, p, vec4(c, 1.0));
        imageStore(out_moments, p, vec4(l, l * l, 0.0, 0.0));
        imageStore(out_length, p, vec4(0.0));
        return;
    }
    h.color /= wsum;
    h.moments /= wsum;
    float len = min(floor(h.frames / wsum + 0.5) + 1.0, float(params.max_length));
    float young = 1.0 / (len + 1.0);
    float a = params.length_alpha != 0 ? max(params.alpha, young) : params.alpha;
    float am = params.length_alpha != 0 ? max(params.moments_alpha, young) : params.moments_alpha;
    imageStore(out_color, p, vec4(mix(h.color, c, a), 1.0));
    imageStore(out_moments, p, vec4(mix(h.moments, vec2(l, l * l), am), 0.0, 0.0));
    imageStore(out_length, p, vec4(len));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
