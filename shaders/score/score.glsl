// The device scorer's buffers (core/tools/src/device_score.c): compare's
// metrics (core/tools/src/metrics.c is the reference, docs/compare.md the
// definitions) computed where the frame was rendered. Pixels are RGBA8
// words, R in the low byte: the bytes compare writes to PNG. The buffers
// read and written per pixel come by address (on lavapipe those accesses
// are vector gathers and scatters, a storage buffer's are bounds-checked
// per lane); the kernels, read at uniform offsets, are bound.
#extension GL_EXT_buffer_reference : require
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Words { uint u[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float f[]; };
// the filter kernels, from the CPU metrics' own code (K_*)
layout(std430, binding = 0) buffer Kernels { float kern[]; };
layout(push_constant) uniform P {
    uint width, height;
    // this frame's and the previous frame's pixels
    Words cand, ref_px, cand_prev, ref_prev;
    // the horizontal filters' results, width * height floats each (T_*),
    // by column (pixel (x, y) at x * height + y), as the vertical filters
    // read them
    Floats tmp;
    // FLIP's error per pixel, row by row (the map compare shows)
    Floats flip_map;
    // per strip of an invocation, its sums in pixel order: first the
    // horizontal stage's (squared and temporal error in 8-bit steps, exact
    // integers), row y's strip s at 2 (s · height + y); then the vertical
    // stage's (FLIP and SSIM, float bits), column x's strip s at
    // P_COLUMNS + 2 (s · width + x)
    Words partials;
    // not 0: FLIP's map is wanted (else its values are only added)
    uint want_map;
} pc;

// tmp: per image the CSF terms A, RG, BY0, BY1 (0-7), the feature responses
// d·x, d2·x, g·x (8-13), SSIM's five moments (14-18)
#define T_CSF 0u
#define T_FEAT 8u
#define T_SSIM 14u
#define TMP_PLANES 19u
// CSF_R and FEAT_R come as defines (the radii of the CPU's kernels), and
// STRIP: the pixels an invocation of a filter stage walks along its axis
#define STRIPS_X ((pc.width + uint(STRIP) - 1u) / uint(STRIP))
#define P_COLUMNS (2u * STRIPS_X * pc.height)
#define CSF_TAPS (2 * CSF_R + 1)
#define FEAT_TAPS (2 * FEAT_R + 1)
#define K_CSF 0                        // four kernels: A, RG, BY0, BY1
#define K_SHARE (4 * CSF_TAPS)         // each term's share of its channel's filter
#define K_FEAT (K_SHARE + 4)           // d, d2, g
#define K_SSIM (K_FEAT + 3 * FEAT_TAPS)
#define SSIM_W 11
// SSIM's lumas are taken less this: the moments' variances E[a²] - E[a]²
// (shift-invariant) then cancel less of the float precision
#define SSIM_SHIFT 0.5

uint plane(uint p, uint i) { return p * pc.width * pc.height + i; }

int clamp_x(int x) { return clamp(x, 0, int(pc.width) - 1); }
int clamp_y(int y) { return clamp(y, 0, int(pc.height) - 1); }

uvec3 bytes(uint p) { return uvec3(p & 255u, (p >> 8) & 255u, (p >> 16) & 255u); }

// linear sRGB (D65) <-> CIE XYZ, row by row as the CPU multiplies
vec3 mul3(vec3 r0, vec3 r1, vec3 r2, vec3 v)
{
    return vec3(r0.x * v.x + r0.y * v.y + r0.z * v.z, r1.x * v.x + r1.y * v.y + r1.z * v.z, r2.x * v.x + r2.y * v.y + r2.z * v.z);
}

vec3 rgb_to_xyz(vec3 v)
{
    return mul3(vec3(0.4124564, 0.3575761, 0.1804375), vec3(0.2126729, 0.7151522, 0.0721750), vec3(0.0193339, 0.1191920, 0.9503041), v);
}

vec3 xyz_to_rgb(vec3 v)
{
    return mul3(vec3(3.2404542, -1.5371385, -0.4985314), vec3(-0.9692660, 1.8760108, 0.0415560), vec3(0.0556434, -0.2040259, 1.0572252), v);
}

// the white point: XYZ of linear RGB (1, 1, 1)
vec3 white() { return rgb_to_xyz(vec3(1.0)); }
