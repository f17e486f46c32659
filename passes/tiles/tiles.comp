#version 460
// Up to 9 images in a grid, remapped to display values: tiles.c has the rules.
#include "pixel.glsl"
#include "color.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D t0;
layout(binding = 1) uniform sampler2D t1;
layout(binding = 2) uniform sampler2D t2;
layout(binding = 3) uniform sampler2D t3;
layout(binding = 4) uniform sampler2D t4;
layout(binding = 5) uniform sampler2D t5;
layout(binding = 6) uniform sampler2D t6;
layout(binding = 7) uniform sampler2D t7;
layout(binding = 8) uniform sampler2D t8;
layout(binding = 9, rgba8) uniform writeonly image2D out_view;
layout(push_constant) uniform Params {
    int columns, rows;
    uint connected;
    uint modes[2];
    float lo[9], hi[9];
} params;

ivec2 tile_size(int i)
{
    switch (i) {
    case 0: return textureSize(t0, 0);
    case 1: return textureSize(t1, 0);
    case 2: return textureSize(t2, 0);
    case 3: return textureSize(t3, 0);
    case 4: return textureSize(t4, 0);
    case 5: return textureSize(t5, 0);
    case 6: return textureSize(t6, 0);
    case 7: return textureSize(t7, 0);
    default: return textureSize(t8, 0);
    }
}

vec4 fetch(int i, ivec2 q)
{
    switch (i) {
    case 0: return texelFetch(t0, q, 0);
    case 1: return texelFetch(t1, q, 0);
    case 2: return texelFetch(t2, q, 0);
    case 3: return texelFetch(t3, q, 0);
    case 4: return texelFetch(t4, q, 0);
    case 5: return texelFetch(t5, q, 0);
    case 6: return texelFetch(t6, q, 0);
    case 7: return texelFetch(t7, q, 0);
    default: return texelFetch(t8, q, 0);
    }
}

// black, blue, cyan, green, yellow, red, white over [0, 1]
vec3 heat(float v)
{
    const vec3 stops[7] = vec3[](vec3(0.0), vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 1.0), vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0),
                                 vec3(1.0, 0.0, 0.0), vec3(1.0));
    float s = v * 6.0;
    int k = min(int(s), 5);
    return mix(stops[k], stops[k + 1], s - float(k));
}

bool finite(float v) { return !isnan(v) && !isinf(v); }

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_view);
    if (any(greaterThanEqual(p, size)))
        return;
    ivec2 tile = max(size / ivec2(params.columns, params.rows), ivec2(1));
    ivec2 cell = p / tile;
    int i = cell.y * params.columns + cell.x;
    vec3 c = vec3(0.0);
    if (cell.x < params.columns && cell.y < params.rows && i < 9 && (params.connected & (1u << i)) != 0u) {
        ivec2 src = tile_size(i);
        ivec2 q = min(ivec2((vec2(p - cell * tile) + 0.5) * vec2(src) / vec2(tile)), src - 1);
        vec4 v = fetch(i, q);
        uint mode = (params.modes[i / 8] >> (4u * uint(i % 8))) & 15u;
        uint channel = mode & 7u;
        float lo = params.lo[i], range = params.hi[i] - params.lo[i];
        if (channel == 0u) {
            c = finite(v.r) && finite(v.g) && finite(v.b) ? clamp((v.rgb - lo) / range, 0.0, 1.0) : vec3(1.0, 0.0, 1.0);
        } else {
            float s = channel == 5u ? luminance(v.rgb) : v[channel - 1u];
            if (!finite(s))
                c = vec3(1.0, 0.0, 1.0);
            else {
                s = clamp((s - lo) / range, 0.0, 1.0);
                c = (mode & 8u) != 0u ? heat(s) : vec3(s);
            }
        }
    }
    imageStore(out_view, p, vec4(c, 1.0));
}

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
