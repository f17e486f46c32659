/* The sun and sky model of the voxel world (voxel layer). Pure C, no Vulkan:
 * scene plugins evaluate it per frame into the frame uniforms. */
#ifndef VOXRG_SKY_H
#define VOXRG_SKY_H

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_voxel (built with
 * -fvisibility=hidden). */
#pragma GCC visibility push(default)

/* ---- sun and sky ----
 * Units: relative linear radiance (linear sRGB primaries). sun_radiance is
 * what a white Lambertian surface facing the sun reflects from it (multiply
 * by albedo * max(N.L, 0)); it is ~(3,3,3) with the sun high. Sky colours
 * are radiance seen directly in the same units (~0.2-0.8 by day), so the
 * sun:sky lighting ratio is a plausible ~5:1 for a filmic tonemap. */
typedef struct vrg_sky_desc {
    float time_of_day;   /* hours 0..24 at time 0; 12 = noon (default 10) */
    float day_length;    /* seconds per 24 h cycle; <= 0: frozen (default 0) */
    float latitude_tilt; /* degrees the sun's arc leans from the zenith (default 30; used clamped to [-89, 89]) */
    float sun_azimuth;   /* degrees (default 30): the sunrise direction is +x rotated by this around +y
                          * (the yaw convention: 90 puts sunrise at -z); sunset is opposite */
} vrg_sky_desc;

typedef struct vrg_sky {
    float sun_dir[3];       /* unit, pointing TO the sun */
    float sun_elevation;    /* degrees above the horizon (negative at night) */
    float sun_radiance[3];  /* warmer and dimmer near the horizon, 0 below it */
    float sky_zenith[3];    /* gradient colours; at night dim blue, not black */
    float sky_horizon[3];
    float ambient[3];       /* cosine-weighted mean sky radiance over the upper hemisphere, sun glow excluded:
                             * what a white up-facing surface reflects from an unoccluded sky */
    float hours;            /* the time of day used, [0, 24) */
    /* The moon, opposite the sun (a full moon): lights the night. */
    float moon_dir[3];      /* unit, pointing TO the moon: -sun_dir */
    float moon_elevation;   /* -sun_elevation */
    float moon_radiance[3]; /* dim and bluish; 0 below the horizon */
} vrg_sky;

/* The directional light that shades the world: the sun while it is above
 * the horizon, else the moon (both are 0 at the horizon, so the switch is
 * continuous). Frame uniforms carry it as sun_dir / sun_radiance. */
void vrg_sky_key_light(const vrg_sky *s, float dir[3], float *elevation, float radiance[3]);

void vrg_sky_default(vrg_sky_desc *d);
/* time_s: simulated seconds since the start. hours = time_of_day +
 * 24 * time_s / day_length (mod 24) when day_length > 0, else time_of_day.
 * The sun rises at 6:00 in the sunrise direction, is highest at 12:00
 * (elevation 90 - |latitude_tilt|), sets at 18:00 and is lowest at 0:00. */
void vrg_sky_eval(const vrg_sky_desc *d, double time_s, vrg_sky *out);
/* Radiance of the sky seen along unit world direction dir: a horizon ->
 * zenith gradient, a darkened horizon colour below the horizon, plus a glow
 * around the sun (the sun's disc itself is NOT included: light it as a
 * directional light with sun_radiance). The formula is in sky.c; a GLSL
 * copy must match it. */
void vrg_sky_radiance(const vrg_sky *s, const float dir[3], float out[3]);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
