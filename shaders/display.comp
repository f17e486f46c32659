#version 450
// voxrg run's display stage (core/cli/run.c, viewer.c): what the window
// shows, at the window's size. A is the graph's output or another of its
// images, B (with --ab) the other graph's, from column `split` on; both were
// copied at their render size (float and UNORM formats by a blit to an
// rgba32f image, unsigned integer ones as they are into a storage buffer)
// and are upscaled here (nearest or bilinear; integers nearest), then the overlay
// layer (RGBA8, window-sized, drawn on the CPU) is blended over them, so its
// text stays sharp at any render scale, and the scale bar is drawn on top.
//
// Run twice a frame while the viewer is on: pass 0 over the sources' texels
// measures them (each channel's, luma's and the (r, g) length's least and
// greatest finite value, NaN and Inf counts) and copies the texel under the
// cursor; pass 1 draws. The views (viewer.h): 0 colour (times 2^ev,
// linear -> sRGB; 8-bit UNORM as stored), 1 range (lo..hi to black..white,
// per channel), 2 false colour (one value lo..hi through the map below), 3
// direction (hue = direction of (r, g), brightness = length / hi), 6 the
// output as it is (already what the swapchain takes).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src_a;
layout(binding = 1) uniform sampler2D src_b;
layout(binding = 2, rgba16f) uniform writeonly image2D dst;
layout(binding = 3, std430) readonly buffer Overlay { uint overlay[]; };
// [0..5] greatest keys, [6..11] ~least keys (both by atomicMax, so zero is
// "none"), [12] NaN and [13] Inf texels, [14..17] A's and [18..21] B's texel
// under the cursor as bits
layout(binding = 4, std430) buffer Stats { uint stats[]; };
// integer images: their texels row by row, uint_a (uint_b) channels each
layout(binding = 5, std430) readonly buffer IntsA { uint ints_a[]; };
layout(binding = 6, std430) readonly buffer IntsB { uint ints_b[]; };
layout(push_constant) uniform P {
    vec4 lo, hi;       // the range of each channel (one value: [0])
    ivec4 bar;         // the scale bar: x, y, width, height (width 0: none)
    ivec2 probe_a, probe_b; // the texels under the cursor (-1: none)
    ivec2 size_a, size_b;   // the integer images' sizes
    int pass;          // 0 measure, 1 draw
    int view, channel; // channel: 0 rgb, 1..4 r g b a, 5 luma
    int uint_a, uint_b; // an integer image of that many channels (in ints_a, ints_b), 0: in src_a, src_b
    float ev;
    int split;         // first column showing B (the width: no B)
    int flags;         // the bits below
} pc;
const int UNORM_A = 1, UNORM_B = 2; // 8-bit UNORM: display values already
const int LINEAR_OUT = 4;           // the swapchain encodes to sRGB itself: write linear values
const int BILINEAR = 8, OVERLAY_ON = 16;
const int B_VIEWED = 32;            // B through the same view (else its output as it is)
bool flag(int f) { return (pc.flags & f) != 0; }

vec3 srgb(vec3 c) { return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308))); }

vec3 linear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045))); }

vec3 hue(float h) { return clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0); }

// The false-colour map: dark violet, blue, teal, yellow, red, as t goes
// 0..1; the brightness rises steadily up to yellow so that order reads in
// grey too.
vec3 false_colour(float t)
{
    const vec3 k[5] = vec3[5](vec3(0.10, 0.02, 0.25), vec3(0.13, 0.32, 0.85), vec3(0.10, 0.72, 0.60), vec3(0.98, 0.86, 0.15),
                              vec3(0.85, 0.12, 0.08));
    float x = clamp(t, 0.0, 1.0) * 4.0;
    int i = min(int(x), 3);
    return mix(k[i], k[i + 1], x - float(i));
}

ivec2 source_size(int side)
{
    if (side == 0)
        return pc.uint_a != 0 ? pc.size_a : textureSize(src_a, 0);
    return pc.uint_b != 0 ? pc.size_b : textureSize(src_b, 0);
}

// A texel's channels as stored: float bits, or an integer image's uints.
uvec4 texel_bits(int side, ivec2 t)
{
    int n = side == 0 ? pc.uint_a : pc.uint_b;
    if (n == 0)
        return floatBitsToUint(side == 0 ? texelFetch(src_a, t, 0) : texelFetch(src_b, t, 0));
    uvec4 u = uvec4(0u);
    int base = (t.y * source_size(side).x + t.x) * n;
    for (int c = 0; c < n; c++)
        u[c] = side == 0 ? ints_a[base + c] : ints_b[base + c];
    return u;
}

// A texel as values: an integer image's as integers (the channels it lacks
// 0, alpha 1, as vrg_graph_read gives them).
vec4 texel(int side, ivec2 t)
{
    int n = side == 0 ? pc.uint_a : pc.uint_b;
    if (n == 0)
        return side == 0 ? texelFetch(src_a, t, 0) : texelFetch(src_b, t, 0);
    uvec4 u = texel_bits(side, t);
    vec4 v = vec4(0.0, 0.0, 0.0, 1.0);
    for (int c = 0; c < n; c++)
        v[c] = float(u[c]);
    return v;
}

// The source texel under window pixel p: the pixel centres map onto each
// other, so at equal sizes every texel is read as it is.
vec4 upscaled(int side, ivec2 p, ivec2 size)
{
    ivec2 src = source_size(side);
    vec2 at = (vec2(p) + 0.5) * vec2(src) / vec2(size) - 0.5;
    ivec2 hi = src - 1;
    if (!flag(BILINEAR) || (side == 0 ? pc.uint_a : pc.uint_b) != 0) // integers are not blended
        return texel(side, clamp(ivec2(floor(at + 0.5)), ivec2(0), hi));
    ivec2 i = ivec2(floor(at));
    vec2 f = at - vec2(i);
    vec4 a = texel(side, clamp(i, ivec2(0), hi)), b = texel(side, clamp(i + ivec2(1, 0), ivec2(0), hi));
    vec4 c = texel(side, clamp(i + ivec2(0, 1), ivec2(0), hi)), d = texel(side, clamp(i + ivec2(1, 1), ivec2(0), hi));
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

float luma(vec4 v) { return dot(v.rgb, vec3(0.2126, 0.7152, 0.0722)); }

// The one value the range, false-colour and direction views map.
float scalar(vec4 v)
{
    if (pc.view == 3)
        return length(v.xy);
    return pc.channel == 0 || pc.channel == 5 ? luma(v) : v[pc.channel - 1];
}

// Display values (sRGB-encoded) of a texel through the view.
vec3 visualised(vec4 v, bool unorm)
{
    vec3 c;
    if (any(isnan(v)))
        return vec3(1.0, 0.0, 1.0);
    if (any(isinf(v)))
        return vec3(0.0, 1.0, 1.0);
    if (pc.view == 0) {
        c = (pc.channel == 0 ? v.rgb : vec3(pc.channel == 5 ? luma(v) : v[pc.channel - 1])) * exp2(pc.ev);
        c = clamp(c, 0.0, 1.0);
        return unorm ? c : srgb(c);
    }
    if (pc.view == 1 && pc.channel == 0)
        return clamp((v.rgb - pc.lo.rgb) / (pc.hi.rgb - pc.lo.rgb), 0.0, 1.0);
    float t = clamp((scalar(v) - pc.lo.x) / (pc.hi.x - pc.lo.x), 0.0, 1.0);
    if (pc.view == 1)
        return vec3(t);
    if (pc.view == 2)
        return false_colour(t);
    return hue(atan(v.y, v.x) / 6.2831853 + 0.5) * t;
}

// The scale bar at t = 0..1 of its width: the colours the view gives the
// values its labels name.
vec3 bar_colour(float t)
{
    if (pc.view == 0)
        return flag(UNORM_A) ? vec3(t) : srgb(vec3(t));
    if (pc.view == 2)
        return false_colour(t);
    if (pc.view == 3)
        return hue(t);
    return vec3(t);
}

uint key(float f) // order-keeping: a greater float has a greater key
{
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

// A workgroup's figures, gathered in shared memory first: one global
// atomic per figure and workgroup, not per texel.
shared uint group[14];

void measure(vec4 v)
{
    if (any(isnan(v))) {
        atomicAdd(group[12], 1u);
        return;
    }
    if (any(isinf(v))) {
        atomicAdd(group[13], 1u);
        return;
    }
    float s[6] = float[6](v.x, v.y, v.z, v.w, luma(v), length(v.xy));
    for (int i = 0; i < 6; i++) {
        atomicMax(group[i], key(s[i]));
        atomicMax(group[6 + i], ~key(s[i]));
    }
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    bool b_shown = pc.split < size.x;
    if (pc.pass == 0) { // over the larger source's texels (uniform: every invocation reaches the barriers)
        uint i = gl_LocalInvocationIndex;
        if (i < 14u)
            group[i] = 0u;
        barrier();
        if (all(lessThan(p, source_size(0)))) {
            measure(texel(0, p));
            if (p == pc.probe_a) {
                uvec4 u = texel_bits(0, p);
                for (int c = 0; c < 4; c++)
                    stats[14 + c] = u[c];
            }
        }
        if (b_shown && flag(B_VIEWED) && all(lessThan(p, source_size(1)))) {
            measure(texel(1, p));
            if (p == pc.probe_b) {
                uvec4 u = texel_bits(1, p);
                for (int c = 0; c < 4; c++)
                    stats[18 + c] = u[c];
            }
        }
        barrier();
        if (i < 12u && group[i] != 0u)
            atomicMax(stats[i], group[i]);
        else if (i >= 12u && i < 14u && group[i] != 0u)
            atomicAdd(stats[i], group[i]);
        return;
    }
    if (any(greaterThanEqual(p, size)))
        return;
    int side = p.x < pc.split ? 0 : 1;
    bool viewed = pc.view != 6 && (side == 0 || flag(B_VIEWED));
    vec3 c = viewed ? visualised(upscaled(side, p, size), flag(side == 0 ? UNORM_A : UNORM_B)) : upscaled(side, p, size).rgb;
    // the views give display values; the output as it is is what the swapchain takes
    if (viewed && flag(LINEAR_OUT))
        c = linear(c);
    // --ab: the divider, a white line edged in black, seen on any picture
    // (under the overlay's words)
    int d = p.x - pc.split;
    if (b_shown && d >= -2 && d <= 1)
        c = d == -2 || d == 1 ? vec3(0.0) : vec3(1.0);
    if (flag(OVERLAY_ON)) {
        vec4 o = unpackUnorm4x8(overlay[p.y * size.x + p.x]);
        c = mix(c, flag(LINEAR_OUT) ? linear(o.rgb) : o.rgb, o.a);
        ivec2 in_bar = p - pc.bar.xy;
        if (pc.bar.z > 0 && all(greaterThanEqual(in_bar, ivec2(0))) && all(lessThan(in_bar, pc.bar.zw))) {
            vec3 b = bar_colour((float(in_bar.x) + 0.5) / float(pc.bar.z));
            c = flag(LINEAR_OUT) ? linear(b) : b;
        }
    }
    imageStore(dst, p, vec4(c, 1.0));
}
