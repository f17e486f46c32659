// The haze pass's blend toward the sky, shared by passes/haze and
// passes/shade. Include frame.glsl first (camera, sky, view radius).
#ifndef VOXRG_HAZE_GLSL
#define VOXRG_HAZE_GLSL
#ifndef VOXRG_FRAME_GLSL
#error "haze.glsl needs frame.glsl included first"
#endif

// c seen at pixel p of an image of `size`, whose G-buffer position is pos
// (w = 0: the ray missed), hazed toward the sky's colour at the horizon
// in the ray's direction (its glow included).
vec3 haze_blend(vec3 c, vec4 pos, ivec2 p, ivec2 size, float density, float start)
{
    vec3 dir = frame_ray_dir(vec2(p), vec2(size));
    vec3 flat_dir = vec3(dir.x, max(dir.y, 0.0), dir.z);
    vec3 haze = frame_sky(length(flat_dir) > 1e-6 ? normalize(flat_dir) : vec3(0.0, 1.0, 0.0));
    float f;
    if (pos.w > 0.5) {
        vec3 to = pos.xyz - frame.camera_pos.xyz;
        f = 1.0 - exp(-density * length(to));
        float radius = float(frame.world_grid.w);
        if (radius > 0.0) // a streamed world: gone by its view radius
            f = max(f, smoothstep(start * radius, radius, length(to.xz)));
    } else
        f = dir.y < 0.0 ? 1.0 : 0.0; // below the horizon a miss is beyond the world
    return mix(c, haze, f);
}
#endif
