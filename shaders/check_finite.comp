#version 450
// --check-finite (core/runtime/src/check_finite.c): after a pass, the first
// NaN or infinity of one float image it wrote. key = (pixel * 4 + channel) * 4
// + kind (0 NaN, 1 +Inf, 2 -Inf), pixel = y * width + x; the smallest key
// wins, so the report is the first in row order whatever the scheduling.
// The bits decide, not isnan()/isinf(), which a compiler may fold away.
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;

layout(set = 0, binding = 0) uniform sampler2D img;
layout(set = 0, binding = 1, std430) buffer Result { uint first; } result;
layout(push_constant) uniform P { uint channels; } pc;

void main()
{
    ivec2 size = textureSize(img, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 v = texelFetch(img, p, 0);
    for (uint c = 0u; c < pc.channels; c++) {
        uint bits = floatBitsToUint(v[c]);
        if ((bits & 0x7f800000u) == 0x7f800000u) {
            uint kind = (bits & 0x007fffffu) != 0u ? 0u : (bits >> 31) != 0u ? 2u : 1u;
            uint pixel = uint(p.y) * uint(size.x) + uint(p.x);
            atomicMin(result.first, (pixel * 4u + c) * 4u + kind);
            return;
        }
    }
}
