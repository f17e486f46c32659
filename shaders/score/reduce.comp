#version 450
// The device scorer's sums: workgroup g adds elements g·CHUNK .. (g+1)·CHUNK
// of FLIP's error, SSIM's windows and the integer errors, each thread a
// fixed stride of them, then a fixed tree in shared memory: the same sums
// on every run, whatever the scheduling. The host adds the partials in
// order, in double.
#include "score.glsl"
#define THREADS 256u
#define CHUNK (THREADS * 16u)
layout(local_size_x = 256) in;

shared float s_flip[THREADS], s_ssim[THREADS];
shared uint s_sq[THREADS], s_temporal[THREADS];

void main()
{
    uint t = gl_LocalInvocationID.x, g = gl_WorkGroupID.x, n = pc.width * pc.height;
    float flip = 0.0, ssim = 0.0;
    uint sq = 0u, temporal = 0u;
    for (uint j = 0u; j < CHUNK / THREADS; j++) {
        uint i = g * CHUNK + j * THREADS + t;
        if (i < n) {
            flip += planes[plane(P_FLIP, i)];
            ssim += planes[plane(P_SSIM, i)];
            sq += ints[2u * i];
            temporal += ints[2u * i + 1u];
        }
    }
    s_flip[t] = flip, s_ssim[t] = ssim, s_sq[t] = sq, s_temporal[t] = temporal;
    barrier();
    for (uint stride = THREADS / 2u; stride > 0u; stride /= 2u) {
        if (t < stride) {
            s_flip[t] += s_flip[t + stride];
            s_ssim[t] += s_ssim[t + stride];
            s_sq[t] += s_sq[t + stride];
            s_temporal[t] += s_temporal[t + stride];
        }
        barrier();
    }
    if (t == 0u) {
        partials[4u * g] = floatBitsToUint(s_flip[0]);
        partials[4u * g + 1u] = floatBitsToUint(s_ssim[0]);
        partials[4u * g + 2u] = s_sq[0];
        partials[4u * g + 3u] = s_temporal[0];
    }
}
