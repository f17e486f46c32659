// Deterministic per-pixel random numbers: a PCG hash stream seeded from the
// pixel, the frame index and the graph seed, so the same graph, seed, camera
// path and size give the same image on any device or thread count.
#ifndef VOXRG_RANDOM_GLSL
#define VOXRG_RANDOM_GLSL

uint pcg_hash(uint v)
{
    uint s = v * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

// state: the PCG state; the rest: where it was seeded, for rng_pair's
// stratified points
struct Rng {
    uint state;
    uvec2 pixel;
    uint frame_index, stream;
};

// salt separates the streams of different passes on the same pixel.
Rng rng_init(uvec2 pixel, uint frame_index, uint seed, uint salt)
{
    Rng r;
    r.pixel = pixel;
    r.frame_index = frame_index;
    r.stream = pcg_hash(seed ^ (salt * 0x9E3779B9u));
    r.state = pcg_hash(pixel.x + pcg_hash(pixel.y + pcg_hash(frame_index + r.stream)));
    return r;
}

float rng_next(inout Rng r)
{
    r.state = pcg_hash(r.state);
    return float(r.state >> 8) * (1.0 / 16777216.0);
}

// Stratified sample points: the R2 sequence (Roberts 2018: a Kronecker
// sequence, fract(k * alpha), alpha from the plastic number), point k =
// (frame * 23 + rank) * count + i, rank the pixel's place in its 4x4 tile.
// With one ray (count = 1) the 16 pixels of a tile take 16 consecutive
// points in a frame, which cover the square evenly; the ranks are placed
// so that every 2x2 and 3x3 window of pixels holds points far apart (a
// Bayer matrix puts neighbours 8 apart, nearly the same u1); and each
// pixel's points over the frames are a Kronecker sequence too. With count
// rays a pixel's rays in a frame are consecutive points and its step
// between frames is 23 * count points: the tile still covers the square
// each frame, but the stride was scored for one ray only. The stride is
// over 16, so no two pixels of a tile share a point; 23 is among the
// strides 16..40 with the lowest error for windows of 1 to 9 pixels over 1
// to 8 frames (16 is among the worst: 16 * alpha is nearly (0.08, 0.12)).
// scripts/stratified_ranks.py made the table and scored the strides. Each
// tile shifts the sequence by its own random offset (Cranley-Patterson
// rotation), so that tiles are not copies of each other. Fixed point in 32
// bits: exactly fract(k * A / 2^32), A = alpha rounded to 32 bits, however
// large k grows (no float precision lost).
vec2 stratified_point(uvec2 pixel, uint frame_index, uint stream, uint i, uint count)
{
    const uint RANK[16] = uint[16](13u, 3u, 2u, 12u, 14u, 0u, 1u, 15u, 8u, 6u, 7u, 9u, 11u, 5u, 4u, 10u);
    uint rank = RANK[(pixel.y & 3u) * 4u + (pixel.x & 3u)];
    uint k = (frame_index * 23u + rank) * count + i;
    uint tile = pcg_hash((pixel.x >> 2u) + pcg_hash((pixel.y >> 2u) + stream));
    uvec2 shift = uvec2(tile, pcg_hash(tile));
    uvec2 x = uvec2(k * 3242174889u, k * 2447445414u) + shift; // 2^32 * (0.7548776662, 0.5698402910)
    return vec2(x >> 8u) * (1.0 / 16777216.0);
}

// The two numbers in [0, 1) of ray i of `count` at r's pixel: the next two
// of its stream, or with `stratified` its stratified point.
vec2 rng_pair(inout Rng r, bool stratified, uint i, uint count)
{
    if (stratified)
        return stratified_point(r.pixel, r.frame_index, r.stream, i, count);
    float u1 = rng_next(r);
    return vec2(u1, rng_next(r));
}

// An orthonormal basis around unit n (Duff et al. 2017, branchless).
void basis_of(vec3 n, out vec3 t, out vec3 b)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction in the hemisphere around n (pdf = cos / pi).
// Unit length by construction (an orthonormal basis, r^2 + z^2 = 1), to a
// few ulps: no normalize (its square root and division were a measurable
// part of the AO pass on lavapipe: docs/benchmarks.md).
vec3 sample_cosine(vec3 n, float u1, float u2)
{
    float r = sqrt(u1), phi = 6.28318530718 * u2;
    vec3 t, b;
    basis_of(n, t, b);
    return t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(0.0, 1.0 - u1));
}

// Uniform direction inside the cone of half-angle `angle` around unit d;
// unit length by construction, as above.
vec3 sample_cone(vec3 d, float angle, float u1, float u2)
{
    float cos_max = cos(angle);
    float c = 1.0 - u1 * (1.0 - cos_max), s = sqrt(max(0.0, 1.0 - c * c)), phi = 6.28318530718 * u2;
    vec3 t, b;
    basis_of(d, t, b);
    return t * (s * cos(phi)) + b * (s * sin(phi)) + d * c;
}
#endif
