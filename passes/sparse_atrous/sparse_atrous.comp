#version 460
// One iteration of the sparse à-trous filter (FILTER); PACK packs the
// input before the first, COPY writes the feedback. sparse_atrous.c has
// the weights.
#include "pixel.glsl"
#include "color.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;

// Iterations read and write a packed texel (rgba32ui): a tap is one fetch.
//   x = half2(r, g), y = half2(b, variance), z = bits of N . X,
//   w = normal axis 0..5 (+x -x +y -y +z -z) or SKY in the low byte, the
//       history length (frames, at most 255) in the next
const uint SKY = 7u;

vec4 packed_color(uvec4 t) { return vec4(unpackHalf2x16(t.x), unpackHalf2x16(t.y)); }
uvec4 pack_texel(vec4 c, float plane, uint surface) { return uvec4(packHalf2x16(c.rg), packHalf2x16(c.ba), floatBitsToUint(plane), surface); }

#if defined(PACK)
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 2) uniform sampler2D in_normal;
layout(binding = 3, rgba32ui) uniform writeonly uimage2D out_pong;
#if defined(WITH_LENGTH)
layout(binding = 4) uniform sampler2D in_length;
#endif

void shade(ivec2 p)
{
    if (any(greaterThanEqual(p, imageSize(out_pong))))
        return;
    vec4 x = texelFetch(in_position, p, 0);
    vec3 n = texelFetch(in_normal, p, 0).xyz;
    vec3 a = abs(n);
    uint axis = a.x > 0.5 ? (n.x > 0.0 ? 0u : 1u) : a.y > 0.5 ? (n.y > 0.0 ? 2u : 3u) : (n.z > 0.0 ? 4u : 5u);
    uint len = 0u;
#if defined(WITH_LENGTH)
    len = uint(clamp(texelFetch(in_length, p, 0).r, 0.0, 255.0));
#endif
    imageStore(out_pong, p, pack_texel(texelFetch(in_illumination, p, 0), dot(n, x.xyz), (x.w == 0.0 ? SKY : axis) | (len << 8)));
}
#elif defined(COPY)
#if defined(FROM_PACKED)
layout(binding = 0, rgba32ui) uniform readonly uimage2D in_src;
#else
layout(binding = 0) uniform sampler2D in_src;
#endif
layout(binding = 1, rgba16f) uniform writeonly image2D out_feedback;

void shade(ivec2 p)
{
    if (any(greaterThanEqual(p, imageSize(out_feedback))))
        return;
#if defined(FROM_PACKED)
    imageStore(out_feedback, p, packed_color(imageLoad(in_src, p)));
#else
    imageStore(out_feedback, p, texelFetch(in_src, p, 0));
#endif
}
#else // FILTER
#define FRAME_BINDING 2
#include "frame.glsl"
layout(binding = 0, rgba32ui) uniform readonly uimage2D in_src;
layout(binding = 1) uniform sampler2D in_position;
#if defined(TO_PACKED)
layout(binding = 3, rgba32ui) uniform writeonly uimage2D out_dst;
#else
layout(binding = 3, rgba16f) uniform writeonly image2D out_dst;
#endif
layout(push_constant) uniform Params {
    float sigma_z, sigma_l, skip_variance;
    int step, long_history;
} params;

void store(ivec2 p, vec4 c, uvec4 own)
{
#if defined(TO_PACKED)
    imageStore(out_dst, p, pack_texel(c, uintBitsToFloat(own.z), own.w));
#else
    imageStore(out_dst, p, c);
#endif
}

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_dst);
    if (any(greaterThanEqual(p, size)))
        return;
    uvec4 own = imageLoad(in_src, p);
    vec4 c = packed_color(own);
    uint face = own.w & 0xffu;
    bool settled = params.long_history > 0 && int(own.w >> 8) >= params.long_history;
    if (face == SKY || c.a < params.skip_variance || settled) {
        store(p, c, own);
        return;
    }
    float dp = uintBitsToFloat(own.z);
    vec3 x = texelFetch(in_position, p, 0).xyz;
    float lp = luminance(c.rgb);
    float inv_l = 1.0 / (params.sigma_l * sqrt(max(c.a, 0.0)) + 1e-6);
    // world size of one pixel step at p's distance (vertical fov in camera_pos.w)
    float footprint = distance(x, frame.camera_pos.xyz) * 2.0 * tan(0.5 * frame.camera_pos.w) / float(size.y);
    float z_step = params.sigma_z * float(params.step) * footprint;
    const float G3[2] = float[2](1.0 / 2.0, 1.0 / 4.0);
    vec3 sum = vec3(0.0);
    float var = 0.0, wsum = 0.0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 q = p + ivec2(dx, dy) * params.step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            uvec4 t = imageLoad(in_src, q);
            if ((t.w & 0xffu) != face) // sky, or another face
                continue;
            vec4 cq = packed_color(t);
            float w = G3[abs(dx)] * G3[abs(dy)] *
                      exp(-abs(uintBitsToFloat(t.z) - dp) / (z_step * length(vec2(dx, dy)) + 1e-6) - abs(lp - luminance(cq.rgb)) * inv_l);
            sum += w * cq.rgb;
            var += w * w * cq.a;
            wsum += w;
        }
    // the centre tap has w = 1/4 > 0
    store(p, vec4(sum / wsum, var / (wsum * wsum)), own);
}
#endif

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
