/* Camera, keyframed camera paths and the sun/sky model. Pure C, no Vulkan:
 * the host computes these per frame and uploads the results.
 *
 * World: right-handed, y up, units are blocks.
 *
 * Angles (degrees):
 *   yaw    rotation around +y, counter-clockwise seen from above (the
 *          right-hand rule): yaw 0 looks down -z, 90 down -x, 180 down +z,
 *          270 (= -90) down +x.
 *   pitch  + looks up, - down; clamped to [-89, 89] wherever it is used so
 *          the view never degenerates at the poles.
 *   forward = (-sin(yaw)cos(pitch), sin(pitch), -cos(yaw)cos(pitch))
 *   right   = ( cos(yaw), 0, -sin(yaw))          (horizontal, roll is 0)
 *   up      = right x forward
 *
 * Matrices: float[16], column-major (m[col*4 + row]) as GLSL's mat4 reads
 * them; vectors are columns, so clip = P * V * world. The view matrix maps
 * world to view space, where the camera looks down -z with +y up. The
 * projection targets Vulkan: depth 0 at near, 1 at far (not reverse-Z), and
 * NDC +y pointing DOWN the screen (P[1][1] is negated), so NDC (-1,-1) is
 * the top-left corner and pixel (px,py) of a WxH image covers
 * NDC x in [2px/W-1, 2(px+1)/W-1], likewise y with H. */
#ifndef VOXRG_CAMERA_H
#define VOXRG_CAMERA_H

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg (built with
 * -fvisibility=hidden); the runtime's internals stay hidden. */
#pragma GCC visibility push(default)

typedef struct vrg_camera {
    float position[3];
    float yaw, pitch;  /* degrees, see above */
    float fov_y;       /* vertical field of view, degrees (default 70; used clamped to [1, 179]) */
    float near_plane;  /* default 0.05; <= 0 means the default */
    float far_plane;   /* default 1000; <= near means near * 2 */
} vrg_camera;

/* The world's extent in blocks: every coordinate of a camera position (x, y
 * and z) lies in [-VRG_WORLD_LIMIT, VRG_WORLD_LIMIT] (docs/world.md says why
 * this value). Graph files, camera paths and vrg_graph_set_camera refuse
 * positions outside it; a camera path's curve and `voxrg run`'s fly camera
 * stop at its edge. */
#define VRG_WORLD_LIMIT 1048576.0f
/* 1 when all three coordinates are finite and within VRG_WORLD_LIMIT. */
int vrg_camera_position_in_world(const float position[3]);
/* v clamped to [-VRG_WORLD_LIMIT, VRG_WORLD_LIMIT]; NaN gives 0. */
float vrg_world_clamp(float v);
/* floor(v) as an int for any float: v is clamped to the world first, so a
 * conversion can never be out of int's range. */
int vrg_world_floor(float v);

/* Origin, yaw 0, pitch 0 and the defaults above. */
void vrg_camera_default(vrg_camera *c);
/* Unit view direction (the formula above). */
void vrg_camera_forward(const vrg_camera *c, float out[3]);
void vrg_camera_view(const vrg_camera *c, float out[16]);
/* aspect = width / height (<= 0 or NaN: 1). Standard 0..1 depth. */
void vrg_camera_projection(const vrg_camera *c, float aspect, float out[16]);
/* projection * view */
void vrg_camera_view_projection(const vrg_camera *c, float aspect, float out[16]);
/* out = a * b (column-major, so b is applied first); out may alias a or b. */
void vrg_mat4_mul(const float a[16], const float b[16], float out[16]);
/* Returns 0 and the inverse, or -1 (out untouched) when m is singular. out
 * may alias m. */
int vrg_mat4_invert(const float m[16], float out[16]);
/* Unit world-space direction of the primary ray through the centre
 * (px + 0.5, py + 0.5) of pixel (px, py) in a width x height image, starting
 * at c->position; it projects back onto that pixel under
 * vrg_camera_view_projection(c, width / height). Integer px, py give pixel
 * centres; the ray through the image centre is the forward vector. */
void vrg_camera_ray(const vrg_camera *c, uint32_t width, uint32_t height, float px, float py, float dir[3]);

/* ---- camera paths ----
 * A text file, one keyframe per line:  time x y z yaw pitch
 * (seconds, blocks, degrees), fields separated by spaces or tabs. '#' or ';'
 * starts a comment (to the end of the line); blank lines are ignored. Times
 * strictly increase; pitch is within [-89, 89]; x, y and z are within
 * VRG_WORLD_LIMIT; at least one keyframe. Numbers are decimal, as in graph
 * files: hexadecimal, "inf" and "nan" are refused. */
typedef struct vrg_camera_key {
    float time, position[3], yaw, pitch;
} vrg_camera_key;

typedef struct vrg_camera_path {
    vrg_camera_key *keys; /* as written in the file */
    int count;
    char path[512];       /* the name used in messages */
} vrg_camera_path;

/* Both return 0, or -1 after printing "NAME:LINE: error: message" and a
 * "  hint: ..." line to diag (NULL: stderr) for every bad line: wrong field
 * count, not a number (hexadecimal included), NaN/inf, pitch out of range,
 * a position outside the world, time not increasing; and
 * "NAME:1: error: ..." when there is no keyframe at all (load: "FILE: error:
 * cannot open/read camera path: why" when the file itself fails). On -1, *out holds no
 * keys (count 0, keys NULL) and needs no free; on 0, free it with
 * vrg_camera_path_free. Numbers are read with strtod: the C locale is
 * assumed. */
int vrg_camera_path_load(const char *file, vrg_camera_path *out, FILE *diag);
int vrg_camera_path_parse(const char *name_for_messages, const char *text, vrg_camera_path *out, FILE *diag);
void vrg_camera_path_free(vrg_camera_path *p);

/* Writes position, yaw and pitch at `time` (seconds; the keys' own clock).
 * The curve is Catmull-Rom with the key times as knots (cubic Hermite whose
 * tangent at key i is the time-weighted mean of the slopes of its two
 * segments): it passes through every key at its time, its velocity is
 * continuous, and for evenly spaced keys it is exactly uniform Catmull-Rom.
 * The ends are clamped by duplicating the first and last key. Before the
 * first key: the first key; after the last: the last key.
 * Yaw is unwrapped first: each key's yaw is moved by a multiple of 360 so it
 * is within (-180, 180] of the previous key's, so 350 -> 10 turns +20, not
 * -340 (a step of exactly 180 turns +180: put a key in between to pick the
 * direction). The yaw written is that continuous value: at a key it equals
 * the file's yaw modulo 360 (exactly the file's value when consecutive file
 * yaws already differ by at most 180). Pitch is clamped to [-89, 89], and
 * the position to VRG_WORLD_LIMIT (the curve can overshoot keys at the edge).
 * A NULL or empty path leaves *inout untouched. */
void vrg_camera_path_eval(const vrg_camera_path *p, float time, vrg_camera *inout);
/* Time of the last key (paths play from t = 0; a path whose first key is
 * later holds that key until then). 0 for an empty path. */
float vrg_camera_path_duration(const vrg_camera_path *p);

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
} vrg_sky;

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
