// The tonemap pass's mapping of linear colour to display values, shared by
// passes/tonemap and passes/shade (which runs the whole chain in one pass).
#ifndef VOXRG_TONEMAP_GLSL
#define VOXRG_TONEMAP_GLSL

// Krzysztof Narkowicz, "ACES Filmic Tone Mapping Curve" (2016)
vec3 tonemap_aces(vec3 x)
{
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 tonemap_srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

// srgb_encode(curve(exposure x c)); curve 0 aces, 1 reinhard, 2 linear
vec3 tonemap_encode(vec3 c, float exposure, int curve)
{
    c *= exposure;
    if (any(isnan(c)))
        c = vec3(0.0);
    c = clamp(c, 0.0, 65504.0); // negative and infinite values would make the curves NaN
    vec3 m = curve == 0 ? tonemap_aces(c) : curve == 1 ? c / (1.0 + c) : clamp(c, 0.0, 1.0);
    return tonemap_srgb_encode(m);
}
#endif
