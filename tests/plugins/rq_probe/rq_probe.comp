#version 460
#extension GL_EXT_ray_query : require
#define FRAME_BINDING 1
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform accelerationStructureEXT tlas;
layout(binding = 2, r32f) uniform writeonly image2D distance_out;

void main()
{
    ivec2 size = imageSize(distance_out);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 o = frame.camera_pos.xyz, d = frame_ray_dir(vec2(p), vec2(size));
    rayQueryEXT q;
    rayQueryInitializeEXT(q, tlas, gl_RayFlagsOpaqueEXT, 0xff, o, 0.0, d, 512.0);
    while (rayQueryProceedEXT(q)) {
    }
    float t = rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT ? rayQueryGetIntersectionTEXT(q, true) : 0.0;
    imageStore(distance_out, p, vec4(t));
}
