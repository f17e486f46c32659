// floor(x) as integers, for |x| < 2^22: adding 1.5 * 2^23 puts an integral
// float's value in the low mantissa bits. A plain int(floor(x)) is a scalar
// saturating conversion per lane on a CPU device (lavapipe: ~6 instructions
// per component and lane), and the traversal does it in its inner loops.
#ifndef VOXRG_IFLOOR_GLSL
#define VOXRG_IFLOOR_GLSL
int ifloor(float x) { return floatBitsToInt(floor(x) + 12582912.0) - 0x4B400000; }
ivec2 ifloor(vec2 x) { return floatBitsToInt(floor(x) + 12582912.0) - 0x4B400000; }
ivec3 ifloor(vec3 x) { return floatBitsToInt(floor(x) + 12582912.0) - 0x4B400000; }
#endif
