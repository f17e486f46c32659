/* The camera: per-frame view data of the runtime (vrg_frame_info carries this
 * frame's and the last frame's, in step with history; docs/architecture.md
 * says why the runtime owns it). Pure C, no Vulkan.
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
 * positions outside it; hosts that move a camera (a path's curve, a fly
 * camera) stop it at the edge. */
#define VRG_WORLD_LIMIT 1048576.0f
/* 1 when all three coordinates are finite and within VRG_WORLD_LIMIT. */
int vrg_camera_position_in_world(const float position[3]);
/* v clamped to [-VRG_WORLD_LIMIT, VRG_WORLD_LIMIT]; NaN gives 0. */
float vrg_world_clamp(float v);
/* floor(v) as an int for any float: v is clamped to the world first, so a
 * conversion can never be out of int's range. */
int vrg_world_floor(float v);

/* The range, in degrees, of each camera angle a file gives: "yaw" in
 * [-360, 360] (any direction, turning either way), "pitch" in [-89, 89]
 * (never straight up or down), "fov" in [1, 179]. A graph's [camera] and
 * camera paths refuse values outside it. 0 with *lo and *hi set, or -1 for
 * another name. */
int vrg_camera_angle_range(const char *angle, double *lo, double *hi);
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

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif

#endif
