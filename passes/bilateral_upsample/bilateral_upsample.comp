#version 460
// Joint bilateral upsampling of demodulated illumination: bilateral_upsample.c
// says what counts as the pixel's surface and why.
#include "pixel.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_low_position;
layout(binding = 2) uniform sampler2D in_low_normal;
layout(binding = 3) uniform sampler2D in_position;
layout(binding = 4) uniform sampler2D in_normal;
layout(binding = 5, rgba16f) uniform writeonly image2D out_illumination;

layout(push_constant) uniform Params
{
    int mode; // 0 bilateral, 1 bilinear, 2 nearest
    float plane_tolerance;
    int surface_ring;
    int orientation_fallback;
} params;

// a fallback texel's weight by its offset t in texels from the pixel's centre
float offset_weight(ivec2 o, vec2 f)
{
    vec2 t = vec2(o) - f;
    return 1.0 / (1.0 + dot(t, t));
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_illumination), low = textureSize(in_illumination, 0);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 x = texelFetch(in_position, p, 0);
    if (x.w == 0.0) {
        imageStore(out_illumination, p, vec4(1.0));
        return;
    }
    if (params.mode == 2) {
        imageStore(out_illumination, p, texelFetch(in_illumination, vrg_pixel_in(p, size, low), 0));
        return;
    }
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    // Texel q holds the full-resolution pixel vrg_pixel_in picked for it,
    // whose centre lies vrg_pixel_in_offset texels past q's own centre: this
    // pixel's centre in those units, and its 2x2 texels.
    vec2 c = (vec2(p) + 0.5) * vec2(low) / vec2(size) - 0.5 - vrg_pixel_in_offset(low, size);
    ivec2 base = ivec2(floor(c));
    vec2 f = c - vec2(base);
    vec4 sum = vec4(0.0), ring_sum = vec4(0.0), facing_sum = vec4(0.0);
    float wsum = 0.0, ring_wsum = 0.0, facing_wsum = 0.0, nearest_d = 1e30;
    vec4 nearest = vec4(1.0);
    bool inner_hit = false;
    // the 2x2 texels, then, when none of them is on the pixel's surface,
    // the ring of the 4x4 around them: with surface_ring, its texels on
    // the surface weighted by their distance in texels; with
    // orientation_fallback, the texels read that face the pixel's way on
    // other planes, weighted alike; the nearest hit otherwise (of the 2x2
    // if one is a hit, else of the ring)
    for (int j = 0; j < 20; j++) {
        bool inner = j < 4;
        ivec2 o = inner ? ivec2(j & 1, j >> 1) : ivec2((j - 4) % 4 - 1, (j - 4) / 4 - 1);
        if (j == 4) {
            inner_hit = nearest_d < 1e30;
            if (wsum > 1e-6 || (params.surface_ring == 0 && inner_hit))
                break; // a texel of the 2x2 is on the surface (without surface_ring: is a hit)
        }
        if (!inner && o.x >= 0 && o.x <= 1 && o.y >= 0 && o.y <= 1)
            continue;
        ivec2 q = clamp(base + o, ivec2(0), low - 1);
        vec4 xq = texelFetch(in_low_position, q, 0);
        if (!inner) {
            // the ring: its illumination is read only where it is used
            if (xq.w == 0.0)
                continue;
            vec3 d = xq.xyz - x.xyz;
            float dist = length(d);
            // the ring's texels count for the pixel's surface and its
            // orientation with surface_ring only (without it the ring is
            // read only for the nearest hit, when all the 2x2 are sky)
            bool facing = params.surface_ring != 0 && dot(texelFetch(in_low_normal, q, 0).xyz, n) >= 0.9;
            float wr = offset_weight(o, f);
            if (facing && abs(dot(d, n)) <= params.plane_tolerance * dist + 1e-3) {
                ring_wsum += wr;
                ring_sum += wr * texelFetch(in_illumination, q, 0);
            }
            else if (params.orientation_fallback != 0 && facing) {
                facing_wsum += wr;
                facing_sum += wr * texelFetch(in_illumination, q, 0);
            }
            else if (dist < nearest_d && !inner_hit) // the nearest hit of the 2x2 is kept over any of the ring's
                nearest_d = dist, nearest = texelFetch(in_illumination, q, 0);
            continue;
        }
        vec4 l = texelFetch(in_illumination, q, 0);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (params.mode == 0) {
            if (xq.w == 0.0)
                continue;
            vec3 d = xq.xyz - x.xyz;
            float dist = length(d);
            if (dist < nearest_d)
                nearest_d = dist, nearest = l;
            bool facing = dot(texelFetch(in_low_normal, q, 0).xyz, n) >= 0.9;
            if (facing && abs(dot(d, n)) <= params.plane_tolerance * dist + 1e-3) {
                sum += w * l;
                wsum += w;
            }
            else if (params.orientation_fallback != 0 && facing) {
                float wr = offset_weight(o, f);
                facing_wsum += wr;
                facing_sum += wr * l;
            }
            continue;
        }
        sum += w * l;
        wsum += w;
    }
    imageStore(out_illumination, p, wsum > 1e-6 ? sum / wsum : ring_wsum > 0.0 ? ring_sum / ring_wsum : facing_wsum > 0.0 ? facing_sum / facing_wsum : nearest);
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
