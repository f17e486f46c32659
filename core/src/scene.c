#define _DEFAULT_SOURCE
/* Helpers every scene plugin shares: the per-frame uniform block. */
#include <math.h>
#include <string.h>
#include "voxrg/world.h"

static void fill_camera(const vrg_camera *c, float aspect, float vp[16], float pos[4])
{
    vrg_camera_view_projection(c, aspect, vp);
    memcpy(pos, c->position, 3 * sizeof(float));
    pos[3] = c->fov_y * (float)M_PI / 180.0f;
}

static void ray_basis(const vrg_camera *c, float aspect, float right[4], float up[4], float forward[4])
{
    /* the conventions and clamps of voxrg/camera.h */
    const float deg = (float)M_PI / 180.0f;
    float fov = !(c->fov_y >= 1) ? 1 : c->fov_y > 179 ? 179 : c->fov_y;
    float yaw = c->yaw * deg, t = tanf(fov * deg / 2);
    vrg_camera_forward(c, forward);
    float r[3] = {cosf(yaw), 0, -sinf(yaw)};
    float u[3] = {r[1] * forward[2] - r[2] * forward[1], r[2] * forward[0] - r[0] * forward[2], r[0] * forward[1] - r[1] * forward[0]};
    for (int i = 0; i < 3; i++) {
        right[i] = r[i] * t * aspect;
        up[i] = u[i] * t;
    }
    right[3] = up[3] = forward[3] = 0;
}

void vrg_frame_uniforms_fill(const vrg_frame_info *f, const vrg_sky *sky, vrg_frame_uniforms *u)
{
    memset(u, 0, sizeof *u);
    float aspect = f->height ? (float)f->width / (float)f->height : 1.0f;
    fill_camera(&f->camera, aspect, u->view_proj, u->camera_pos);
    fill_camera(&f->prev_camera, aspect, u->prev_view_proj, u->prev_camera_pos);
    ray_basis(&f->camera, aspect, u->camera_right, u->camera_up, u->camera_forward);
    if (vrg_mat4_invert(u->view_proj, u->inv_view_proj) != 0)
        memset(u->inv_view_proj, 0, sizeof u->inv_view_proj);
    memcpy(u->sun_dir, sky->sun_dir, sizeof sky->sun_dir);
    u->sun_dir[3] = sky->sun_elevation;
    memcpy(u->sun_radiance, sky->sun_radiance, sizeof sky->sun_radiance);
    memcpy(u->sky_zenith, sky->sky_zenith, sizeof sky->sky_zenith);
    memcpy(u->sky_horizon, sky->sky_horizon, sizeof sky->sky_horizon);
    memcpy(u->ambient, sky->ambient, sizeof sky->ambient);
    u->frame_index = (uint32_t)f->frame_index;
    u->width = f->width;
    u->height = f->height;
    u->seed = f->seed;
    u->time_s = (float)f->time_s;
    u->hours = sky->hours;
}

void vrg_scene_write_frame(vrg_pass *pass, VkCommandBuffer cmd, const char *slot, const vrg_sky_desc *desc)
{
    const vrg_frame_info *f = vrg_pass_frame(pass);
    vrg_sky sky;
    vrg_sky_eval(desc, f->time_s, &sky);
    vrg_frame_uniforms u;
    vrg_frame_uniforms_fill(f, &sky, &u);
    vkCmdUpdateBuffer(cmd, vrg_res_buffer(pass, vrg_pass_res(pass, slot)), 0, sizeof u, &u);
}
