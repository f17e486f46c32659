#define _DEFAULT_SOURCE
/* Helpers every scene plugin shares: the per-frame uniform block. */
#include <math.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>
#include "voxel_internal.h"

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
    float fov = isnan(c->fov_y) ? 70 : c->fov_y < 1 ? 1 : c->fov_y > 179 ? 179 : c->fov_y; /* camera.c's rule */
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

/* std140 as frame.glsl declares it: 3 mat4, then vec4s only */
_Static_assert(offsetof(vrg_frame_uniforms, camera_pos) == 192 && offsetof(vrg_frame_uniforms, frame_index) == 352 &&
                   offsetof(vrg_frame_uniforms, world_grid) == 384 && offsetof(vrg_frame_uniforms, prev_sun_dir) == 432 &&
                   offsetof(vrg_frame_uniforms, edit_lo) == 448 && offsetof(vrg_frame_uniforms, edit_hi) == 464 &&
                   sizeof(vrg_frame_uniforms) == 480,
               "vrg_frame_uniforms must keep frame.glsl's std140 offsets");

void vrg_frame_uniforms_fill(const vrg_frame_info *f, const vrg_sky *sky, vrg_frame_uniforms *u)
{
    memset(u, 0, sizeof *u);
    float aspect = f->height ? (float)f->width / (float)f->height : 1.0f;
    fill_camera(&f->camera, aspect, u->view_proj, u->camera_pos);
    fill_camera(&f->prev_camera, aspect, u->prev_view_proj, u->prev_camera_pos);
    ray_basis(&f->camera, aspect, u->camera_right, u->camera_up, u->camera_forward);
    if (vrg_mat4_invert(u->view_proj, u->inv_view_proj) != 0)
        memset(u->inv_view_proj, 0, sizeof u->inv_view_proj);
    vrg_sky_key_light(sky, u->sun_dir, &u->sun_dir[3], u->sun_radiance); /* the moon by night */
    memcpy(u->sky_zenith, sky->sky_zenith, sizeof sky->sky_zenith);
    memcpy(u->sky_horizon, sky->sky_horizon, sizeof sky->sky_horizon);
    memcpy(u->ambient, sky->ambient, sizeof sky->ambient);
    u->frame_index = (uint32_t)f->frame_index;
    u->width = f->width;
    u->height = f->height;
    u->seed = f->seed;
    u->time_s = (float)f->time_s;
    u->hours = sky->hours;
    /* unknown until vrg_frame_uniforms_prev_sun: the light of now */
    memcpy(u->prev_sun_dir, u->sun_dir, 3 * sizeof(float));
    u->prev_sun_dir[3] = -1;
}

void vrg_frame_uniforms_world(const vrg_world *world, vrg_frame_uniforms *u)
{
    int grid[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    if (world) {
        vrg_world_grid(world, grid);
        vrg_world_gpu_box(world, lo, hi);
    }
    for (int a = 0; a < 3; a++) {
        u->world_grid[a] = grid[a];
        u->world_lo[a] = (float)lo[a];
        u->world_hi[a] = (float)hi[a];
    }
    u->world_grid[3] = world ? vrg_world_view_radius(world) : 0;
    u->world_lo[3] = u->world_hi[3] = 0;
    int elo[3] = {0, 0, 0}, ehi[3] = {0, 0, 0};
    if (world)
        vrg_world_uploaded_edits(world, elo, ehi);
    for (int a = 0; a < 3; a++) {
        u->edit_lo[a] = (float)elo[a];
        u->edit_hi[a] = (float)ehi[a];
    }
    u->edit_lo[3] = u->edit_hi[3] = 0;
}

/* The degrees between two unit directions, in double: a 32-bit dot
 * product near 1 rounds a sun that moves a hundredth of a degree a frame
 * (a 7-minute day at 60 fps) to 0 or to 0.02 degrees. */
static double degrees_between(const float a[3], const float b[3])
{
    double c[3] = {(double)a[1] * b[2] - (double)a[2] * b[1], (double)a[2] * b[0] - (double)a[0] * b[2], (double)a[0] * b[1] - (double)a[1] * b[0]};
    double d = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), d) * 180.0 / M_PI;
}

void vrg_frame_uniforms_prev_sun(const vrg_frame_info *f, const vrg_sky_desc *desc, vrg_frame_uniforms *u)
{
    memcpy(u->prev_sun_dir, u->sun_dir, 3 * sizeof(float));
    u->prev_sun_dir[3] = -1;
    if (!f->history_valid || f->frame_index == 0)
        return;
    /* time_s is frame_index / fps, so the last frame's time is
     * time_s (frame_index - 1) / frame_index */
    vrg_sky prev;
    vrg_sky_eval(desc, f->time_s * (double)(f->frame_index - 1) / (double)f->frame_index, &prev);
    float elevation, radiance[3];
    vrg_sky_key_light(&prev, u->prev_sun_dir, &elevation, radiance);
    u->prev_sun_dir[3] = (float)degrees_between(u->sun_dir, u->prev_sun_dir);
}

void vrg_scene_write_frame(vrg_pass *pass, VkCommandBuffer cmd, const char *slot, const vrg_sky_desc *desc, const vrg_world *world)
{
    const vrg_frame_info *f = vrg_pass_frame(pass);
    vrg_sky sky;
    vrg_sky_eval(desc, f->time_s, &sky);
    vrg_frame_uniforms u;
    vrg_frame_uniforms_fill(f, &sky, &u);
    vrg_frame_uniforms_world(world, &u);
    vrg_frame_uniforms_prev_sun(f, desc, &u);
    vrg_res res = vrg_pass_res(pass, slot);
    /* a scene plugin built against older headers sized its buffer for an
     * older, shorter block (VRG_SCENE_SLOTS: sizeof at its build) */
    if (vrg_res_size(pass, res) < sizeof u) {
        vrg_pass_error(pass, "slot '%s' is %llu bytes, the frame uniforms of this voxrg %zu: rebuild the scene plugin against this voxrg's headers",
                       slot, (unsigned long long)vrg_res_size(pass, res), sizeof u);
        return;
    }
    vkCmdUpdateBuffer(cmd, vrg_res_buffer(pass, res), 0, sizeof u, &u);
}

static const char *const traversals[] = {"dda", "rayquery"};

int vrg_scene_check(vrg_pass *pass, int grid_radius, int height_chunks)
{
    int traversal = vrg_param_choice(pass, "traversal", traversals, 2);
    if (traversal < 0)
        return -1;
    int rayquery = traversal == 1;
    uint64_t g = 2 * (uint64_t)grid_radius + 1;
    vrg_pass_set_buffer_size(pass, "tlas", rayquery ? g * g * (uint64_t)height_chunks : 0);
    /* passes read the world as a texel buffer of 16-byte texels
     * (VRG_ACCESS_TEXEL_READ, VRG_SCENE_SLOTS) */
    uint64_t bytes = vrg_world_gpu_bytes(grid_radius, height_chunks);
    const vrg_device *dev = vrg_pass_device(pass);
    if (dev && bytes / 16 > dev->features.max_texel_buffer_texels)
        return vrg_pass_error(pass, "a world of radius %d and %d chunks height needs %llu texels, more than this device's texel buffers hold (%u): lower radius",
                              grid_radius, height_chunks, (unsigned long long)(bytes / 16), dev->features.max_texel_buffer_texels);
    return vrg_pass_set_buffer_size(pass, "world", bytes);
}

/* The ray-query backend: the previous instance's BLASes when it has them
 * for this world; else new ones, which need every chunk's faces (a kept
 * world holds chunks already). */
static int create_accel(vrg_pass *pass, vrg_scene_gpu *s, const vrg_scene_gpu *previous)
{
    const vrg_device *dev = vrg_pass_device(pass);
    if (!dev->features.ray_query || !dev->features.acceleration_structure)
        return vrg_pass_error_at(pass, vrg_param_line(pass, "traversal"), "traversal = rayquery needs VK_KHR_ray_query, which device '%s' lacks (use traversal = dda)",
                                 dev->name);
    if (previous && previous->accel) {
        s->accel = _vrg_world_accel_share(pass, previous->accel);
        return s->accel ? 0 : -1;
    }
    s->accel = vrg_world_accel_create(pass, s->world);
    if (!s->accel)
        return -1;
    if (previous)
        vrg_world_invalidate_meshes(s->world);
    return 0;
}

int vrg_scene_create_from(vrg_pass *pass, vrg_scene_gpu *s, vrg_world *world, const vrg_scene_gpu *previous)
{
    s->world = world;
    vrg_pass_share(pass, VRG_WORLD_SHARED_NAME, world);
    if (previous && previous->world != world)
        previous = NULL;
    int dims[3];
    vrg_world_grid(world, dims);
    /* room to upload the whole grid in one frame (the first, or after a
     * teleport or reallocation); later only changed chunks go up */
    s->staging_bytes = vrg_world_gpu_bytes((dims[0] - 1) / 2, dims[1]);
    s->staging = vrg_pass_host_ring(pass, "world staging", s->staging_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (!s->staging)
        return -1;
    /* the GPU copy of a kept world stays valid: its buffer and atlas go to
     * the new instance with the world's record of what they hold */
    if (previous && (vrg_pass_keep_resource(pass, "world") != 0 || vrg_pass_keep_resource(pass, "atlas") != 0))
        return -1;
    if (vrg_param_choice(pass, "traversal", traversals, 2) == 1)
        return create_accel(pass, s, previous);
    return 0;
}

int vrg_scene_create(vrg_pass *pass, vrg_scene_gpu *s, vrg_world *world) { return vrg_scene_create_from(pass, s, world, NULL); }

/* Is the slot's resource new and cleared this frame? */
static int slot_fresh(vrg_pass *pass, const char *slot)
{
    vrg_res r = vrg_pass_res(pass, slot);
    return vrg_res_connected(r) ? vrg_res_fresh(pass, r) : vrg_pass_frame(pass)->resources_new;
}

/* The atlas, generated for the frames that need it (a new atlas image):
 * the staging memory goes once this frame has copied it. */
static int upload_atlas(vrg_pass *pass, vrg_scene_gpu *s, VkCommandBuffer cmd)
{
    VkBuffer staging;
    vrg_buffer_desc d = {.name = "atlas staging", .size = vrg_atlas_bytes(), .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT, .host_visible = 1};
    void *map = vrg_pass_buffer(pass, &d, &staging, NULL);
    if (!map)
        return -1;
    vrg_world_atlas_generate(s->world, map);
    vrg_atlas_record_upload(pass, cmd, "atlas", staging);
    vrg_pass_free_buffer(pass, staging);
    return 0;
}

void vrg_scene_record(vrg_pass *pass, vrg_scene_gpu *s, VkCommandBuffer cmd)
{
    /* new and cleared (not kept by a reload): everything goes up again */
    int world_fresh = slot_fresh(pass, "world");
    if (world_fresh)
        vrg_world_invalidate_gpu(s->world);
    if (slot_fresh(pass, "atlas") && upload_atlas(pass, s, cmd) != 0)
        return;
    vrg_pass_stat(pass, "gpu_world_kept", vrg_pass_frame(pass)->resources_new && !world_fresh);
    int uploaded = 0;
    vrg_world_clear_uploaded_edits(s->world); /* the frame uniforms' edit box: this frame's upload */
    if (vrg_world_dirty_count(s->world)) {
        /* this frame's slice: earlier frames may still copy from theirs */
        vrg_ring_slice slice = vrg_pass_ring_slice(pass, s->staging, s->staging_bytes);
        if (slice.map)
            uploaded = vrg_world_upload(s->world, cmd, vrg_res_buffer(pass, vrg_pass_res(pass, "world")), slice.map, slice.buffer, s->staging_bytes);
    }
    vrg_pass_stat(pass, "chunks_uploaded", uploaded);
    if (s->accel)
        vrg_world_accel_record(s->accel, cmd, "tlas");
    vrg_sky_desc sky;
    vrg_sky_default(&sky);
    sky.time_of_day = (float)vrg_param(pass, "time_of_day");
    sky.day_length = (float)vrg_param(pass, "day_length");
    vrg_scene_write_frame(pass, cmd, "frame", &sky, s->world);
}

void vrg_scene_destroy(vrg_pass *pass, vrg_scene_gpu *s)
{
    vrg_pass_share(pass, VRG_WORLD_SHARED_NAME, NULL);
    vrg_world_accel_destroy(s->accel);
    vrg_world_destroy(s->world);
    memset(s, 0, sizeof *s);
}

vrg_world *vrg_graph_world(const vrg_graph *g) { return vrg_graph_shared(g, VRG_WORLD_SHARED_NAME); }
