// Per-frame uniforms written by scene plugins (vrg_frame_uniforms in
// core/voxel/include/voxrg/world.h; std140, same order). Before including, define
// FRAME_BINDING to the binding of the pass's `frame` slot.
#ifndef VOXRG_FRAME_GLSL
#define VOXRG_FRAME_GLSL

layout(std140, binding = FRAME_BINDING) uniform FrameUniforms {
    mat4 view_proj;
    mat4 inv_view_proj;
    mat4 prev_view_proj;
    vec4 camera_pos;       // w: vertical field of view, radians
    vec4 prev_camera_pos;
    vec4 camera_right;     // scaled by the image plane's half-width at distance 1
    vec4 camera_up;        // scaled by its half-height
    vec4 camera_forward;
    vec4 sun_dir;          // to the key light (the sun, the moon by night); w: its elevation in degrees
    vec4 sun_radiance;
    vec4 sky_zenith;
    vec4 sky_horizon;
    vec4 ambient;
    uvec4 frame_info;      // frame index, width, height, seed
    vec4 time_info;        // simulated seconds, hours of the day, 0, 0
    ivec4 world_grid;      // the world's slot grid, chunks (world.glsl: world_grid()); w: view radius, blocks (0: not streamed)
    vec4 world_lo;         // the box of the non-air blocks the world buffer holds,
    vec4 world_hi;         //   blocks, hi exclusive; empty when lo >= hi (trace.glsl clips rays to it)
    vec4 prev_sun_dir;     // last frame's key light direction; w: the degrees it moved since (-1: unknown, no history)
    vec4 edit_lo;          // the box around the edited blocks whose chunks this frame's upload brought to the GPU,
    vec4 edit_hi;          //   blocks, hi exclusive; empty when lo >= hi (surface_cache's edit_radius)
} frame;

// World-space direction of the primary ray through pixel centre p + 0.5
// (vrg_camera_ray in core/runtime/src/camera.c; NDC y points down).
vec3 frame_ray_dir(vec2 pixel, vec2 size)
{
    vec2 ndc = (pixel + 0.5) / size * 2.0 - 1.0;
    return normalize(frame.camera_forward.xyz + ndc.x * frame.camera_right.xyz - ndc.y * frame.camera_up.xyz);
}

// Degrees the key light moved since the last frame (0 where unknown).
// Computed on the host in double: from 32-bit directions a slow sun's
// angle rounds to 0 or 0.02 degrees.
float frame_sun_moved_degrees() { return max(frame.prev_sun_dir.w, 0.0); }

// The most frames a history may span while the key light moves at most
// `span` degrees in them (the history's lag under a moving sun): 1e30 with
// span 0 (no limit) or a still light. A history that is older lights the
// surface with a sun that is no longer there.
float frame_sun_history_frames(float span)
{
    float moved = frame_sun_moved_degrees();
    return span > 0.0 && moved > 0.0 ? span / moved : 1e30;
}

// Sky radiance along a unit direction: vrg_sky_radiance in core/voxel/src/sky.c,
// the same formula (keep them in step): a horizon-to-zenith gradient by
// sqrt(dir.y), a darkened horizon below it, and a glow around the key light.
vec3 frame_sky(vec3 dir)
{
    float c = max(dot(dir, frame.sun_dir.xyz), 0.0);
    float c4 = c * c * c * c;
    float c32 = c4 * c4 * c4 * c4 * c4 * c4 * c4 * c4;
    float glow = 0.25 * c32 + 0.05 * c4;
    vec3 base = dir.y >= 0.0 ? mix(frame.sky_horizon.rgb, frame.sky_zenith.rgb, sqrt(dir.y))
                             : frame.sky_horizon.rgb * (0.3 + 0.7 * exp(8.0 * dir.y));
    return base + frame.sun_radiance.rgb * glow;
}
#endif
