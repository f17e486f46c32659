// Colour helpers shared by the passes.
#ifndef VOXRG_COLOR_GLSL
#define VOXRG_COLOR_GLSL
// Relative luminance of linear Rec. 709 / sRGB primaries.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
#endif
