#version 460
// Luminance variance for SVGF: svgf_variance.c has the definitions.
#include "pixel.glsl"
#include "color.glsl"

// The device's workgroup shape and rows per invocation: pixel.glsl.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(push_constant) uniform Params {
    int radius, min_history;
} params;

#if defined(ROWS)
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 2, rgba32f) uniform writeonly image2D out_rows;

// sums of l, l^2 and the count of non-sky pixels in the row window
void shade(ivec2 p)
{
    ivec2 size = imageSize(out_rows);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 s = vec3(0.0);
    for (int dx = -params.radius; dx <= params.radius; dx++) {
        ivec2 q = ivec2(p.x + dx, p.y);
        if (q.x < 0 || q.x >= size.x || texelFetch(in_position, q, 0).w == 0.0)
            continue;
        float l = luminance(texelFetch(in_illumination, q, 0).rgb);
        s += vec3(l, l * l, 1.0);
    }
    imageStore(out_rows, p, vec4(s, 0.0));
}
#elif defined(COLUMNS)
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_position;
layout(binding = 2, rgba32f) uniform readonly image2D in_rows;
layout(binding = 3, rgba16f) uniform writeonly image2D out_color;
#ifdef VARIANCE
layout(binding = 4, rg16f) uniform writeonly image2D out_variance;
#endif

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_illumination, p, 0).rgb;
    if (texelFetch(in_position, p, 0).w == 0.0) { // sky
        imageStore(out_color, p, vec4(c, 0.0));
#ifdef VARIANCE
        imageStore(out_variance, p, vec4(0.0));
#endif
        return;
    }
    vec3 s = vec3(0.0);
    for (int dy = -params.radius; dy <= params.radius; dy++) {
        int y = p.y + dy;
        if (y >= 0 && y < size.y)
            s += imageLoad(in_rows, ivec2(p.x, y)).xyz;
    }
    // Bessel's correction: sum (l - mean)^2 / (n - 1) = (S2 - S1^2 / n) / (n - 1)
    float var = s.z > 1.5 ? max(0.0, (s.y - s.x * s.x / s.z) / (s.z - 1.0)) : 0.0;
    imageStore(out_color, p, vec4(c, var));
#ifdef VARIANCE
    imageStore(out_variance, p, vec4(var, 0.0, 0.0, 0.0));
#endif
}
#else // TEMPORAL
layout(binding = 0) uniform sampler2D in_illumination;
layout(binding = 1) uniform sampler2D in_moments;
layout(binding = 2) uniform sampler2D in_length;
layout(binding = 3) uniform sampler2D in_position;
layout(binding = 4) uniform sampler2D in_normal;
layout(binding = 5, rgba16f) uniform writeonly image2D out_color;
#ifdef VARIANCE
layout(binding = 6, rg16f) uniform writeonly image2D out_variance;
#endif

void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 c = texelFetch(in_illumination, p, 0).rgb;
    vec4 x = texelFetch(in_position, p, 0);
    float var = 0.0;
#ifdef VARIANCE
    float own = 0.0; // 1: from the pixel's own moments
#endif
    if (x.w != 0.0) {
        vec2 m;
        if (texelFetch(in_length, p, 0).r + 1.0 >= float(params.min_history)) {
            m = texelFetch(in_moments, p, 0).xy;
#ifdef VARIANCE
            own = 1.0;
#endif
        } else { // young history: moments of the window's pixels on this surface
            vec3 n = texelFetch(in_normal, p, 0).xyz;
            vec3 s = vec3(0.0);
            for (int dy = -params.radius; dy <= params.radius; dy++)
                for (int dx = -params.radius; dx <= params.radius; dx++) {
                    ivec2 q = p + ivec2(dx, dy);
                    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                        continue;
                    vec4 xq = texelFetch(in_position, q, 0);
                    if (xq.w == 0.0 || dot(texelFetch(in_normal, q, 0).xyz, n) < 0.9 ||
                        abs(dot(xq.xyz - x.xyz, n)) > 0.1 * float(max(abs(dx), abs(dy))))
                        continue;
                    s += vec3(texelFetch(in_moments, q, 0).xy, 1.0);
                }
            m = s.xy / s.z; // the centre always counts
        }
        var = max(0.0, m.y - m.x * m.x);
    }
    imageStore(out_color, p, vec4(c, var));
#ifdef VARIANCE
    imageStore(out_variance, p, vec4(var, own, 0.0, 0.0));
#endif
}
#endif

void main()
{
    for (uint k = 0u; k < VRG_PIXEL_ROWS; k++)
        shade(vrg_pixel(k));
}
