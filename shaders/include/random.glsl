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

struct Rng {
    uint state;
};

// salt separates the streams of different passes on the same pixel.
Rng rng_init(uvec2 pixel, uint frame_index, uint seed, uint salt)
{
    Rng r;
    r.state = pcg_hash(pixel.x + pcg_hash(pixel.y + pcg_hash(frame_index + pcg_hash(seed ^ (salt * 0x9E3779B9u)))));
    return r;
}

float rng_next(inout Rng r)
{
    r.state = pcg_hash(r.state);
    return float(r.state >> 8) * (1.0 / 16777216.0);
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
