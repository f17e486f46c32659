/* Scene plugin: the procedural terrain of the thesis. Improved Perlin noise
 * heights, Voronoi biomes and trees (terrain_gen.c), generated in 16^3 chunks
 * on a worker pool around the camera and streamed as it moves (stream.c).
 *
 * By default every frame waits until the chunks it needs are in (stream =
 * wait), so the same graph, seed, camera path and size give the same image
 * whatever the thread count. stream = budget integrates finished chunks for
 * at most budget_ms per frame instead, for interactive use. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <unistd.h>
#include "stream.h"
#include "terrain_gen.h"

static const vrg_param_desc params[] = {
    {"seed", VRG_PARAM_INT, 1337, 0, 4294967295.0, "world seed"},
    {"radius", VRG_PARAM_INT, 13, 0, 64, "chunks generated around the camera (|dx|, |dz| <= radius)"},
    {"height_chunks", VRG_PARAM_INT, 3, 1, 16, "world height in 16-block chunks"},
    {"hysteresis", VRG_PARAM_INT, 2, 0, 16, "chunks beyond radius kept before they are dropped"},
    {"octaves", VRG_PARAM_INT, 5, 1, 16, "noise octaves (frequency doubles per octave)"},
    {"scale", VRG_PARAM_FLOAT, 96, 1, 100000, "horizontal size of the largest octave, blocks"},
    {"falloff", VRG_PARAM_FLOAT, 0.5, 0, 1, "amplitude multiplier per octave"},
    {"base_height", VRG_PARAM_FLOAT, 20, 0, 256, "mean surface height, blocks"},
    {"amplitude", VRG_PARAM_FLOAT, 14, 0, 256, "height variation, blocks"},
    {"biome_size", VRG_PARAM_FLOAT, 128, 8, 100000, "Voronoi cell size of biomes, blocks"},
    {"tree_density", VRG_PARAM_FLOAT, 0.02, 0, 1, "fraction of forest columns holding a tree"},
    {"sea_level", VRG_PARAM_INT, 12, 0, 256, "water fills air below this height"},
    {"threads", VRG_PARAM_INT, 0, 0, 64, "generator threads; 0: one per CPU"},
    {"stream", VRG_PARAM_STRING, 0, 0, 0, "wait (deterministic: each frame waits for its chunks) or budget", 0, "wait"},
    {"budget_ms", VRG_PARAM_FLOAT, 2, 0, 1000, "stream = budget: main-thread integration time per frame"},
    {"time_of_day", VRG_PARAM_FLOAT, 10, 0, 24, "hours at the start, 12 = noon"},
    {"day_length", VRG_PARAM_FLOAT, 0, 0, 1e6, "seconds per 24-hour cycle; 0 keeps the time of day"},
    {"traversal", VRG_PARAM_STRING, 0, 0, 0, "dda (voxel DDA only) or rayquery (also build BLAS/TLAS for ray queries)", 0, "dda"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST, .size = 16,
     .flags = VRG_SLOT_PERSISTENT, .help = "voxel world (shaders/include/world.glsl)"},
    {.name = "frame", .dir = VRG_OUT, .kind = VRG_BUFFER, .access = VRG_ACCESS_TRANSFER_DST,
     .size = sizeof(vrg_frame_uniforms), .flags = VRG_SLOT_PERSISTENT, .help = "per-frame uniforms (shaders/include/frame.glsl)"},
    VRG_ATLAS_SLOT,
    {.name = "tlas", .dir = VRG_OUT, .kind = VRG_ACCEL, .access = VRG_ACCESS_AS_BUILD,
     .help = "top-level acceleration structure of the chunks (traversal = rayquery; empty otherwise)"},
};

typedef struct scene {
    terrain_params gen;
    vrg_world *world;
    stream *stream;
    int wait;
    void *staging;
    VkBuffer staging_buffer;
    VkBuffer atlas_staging;
    vrg_world_accel *accel; /* traversal = rayquery */
    uint64_t staging_bytes;
    int threads;
} scene;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static void params_from(vrg_pass *pass, terrain_params *g)
{
    terrain_params_default(g);
    g->seed = (uint32_t)vrg_param(pass, "seed");
    g->octaves = vrg_param_int(pass, "octaves");
    g->scale = (float)vrg_param(pass, "scale");
    g->falloff = (float)vrg_param(pass, "falloff");
    g->base_height = (float)vrg_param(pass, "base_height");
    g->amplitude = (float)vrg_param(pass, "amplitude");
    g->height_chunks = vrg_param_int(pass, "height_chunks");
    g->biome_size = (float)vrg_param(pass, "biome_size");
    g->tree_density = (float)vrg_param(pass, "tree_density");
    g->sea_level = vrg_param_int(pass, "sea_level");
}

static int grid_radius(vrg_pass *pass) { return vrg_param_int(pass, "radius") + vrg_param_int(pass, "hysteresis"); }

static int check(vrg_pass *pass)
{
    const char *mode = vrg_param_string(pass, "stream");
    if (strcmp(mode, "wait") != 0 && strcmp(mode, "budget") != 0) {
        int line = 0;
        vrg_param_item(pass, "stream", vrg_param_count(pass, "stream") - 1, &line);
        return vrg_pass_error_at(pass, line, "stream = '%s': expected wait or budget", mode);
    }
    const char *traversal = vrg_param_string(pass, "traversal");
    if (strcmp(traversal, "dda") != 0 && strcmp(traversal, "rayquery") != 0) {
        int line = 0;
        vrg_param_item(pass, "traversal", vrg_param_count(pass, "traversal") - 1, &line);
        return vrg_pass_error_at(pass, line, "traversal = '%s': expected dda or rayquery", traversal);
    }
    uint64_t g = 2 * (uint64_t)grid_radius(pass) + 1, slots = g * g * (uint64_t)vrg_param_int(pass, "height_chunks");
    vrg_pass_set_buffer_size(pass, "tlas", strcmp(traversal, "rayquery") == 0 ? slots : 0);
    return vrg_pass_set_buffer_size(pass, "world", vrg_world_gpu_bytes(grid_radius(pass), vrg_param_int(pass, "height_chunks")));
}

static void generate(void *user, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS])
{
    terrain_generate_chunk(&((scene *)user)->gen, cx, cy, cz, out);
}

static void integrate(void *user, int cx, int cy, int cz, const vrg_block *blocks) { vrg_world_put_chunk(user, cx, cy, cz, blocks); }
static void drop(void *user, int cx, int cy, int cz) { vrg_world_drop_chunk(user, cx, cy, cz); }

static int create(vrg_pass *pass)
{
    scene *s = calloc(1, sizeof *s);
    vrg_pass_set_user(pass, s);
    params_from(pass, &s->gen);
    s->wait = strcmp(vrg_param_string(pass, "stream"), "wait") == 0;
    int threads = vrg_param_int(pass, "threads");
    if (threads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    s->threads = threads;
    s->world = vrg_world_create(grid_radius(pass), s->gen.height_chunks);
    stream_desc sd = {.threads = threads,
                      .radius = vrg_param_int(pass, "radius"),
                      .hysteresis = vrg_param_int(pass, "hysteresis"),
                      .height_chunks = s->gen.height_chunks,
                      .generate = generate,
                      .user = s};
    s->stream = s->world ? stream_create(&sd) : NULL;
    if (!s->stream)
        return vrg_pass_error(pass, "cannot create the world (out of memory?)");
    vrg_pass_set_world(pass, s->world);
    /* Room to upload the whole grid in one frame (the first frame, or a
     * teleport); uploads are per changed chunk after that. */
    s->staging_bytes = vrg_world_gpu_bytes(grid_radius(pass), s->gen.height_chunks);
    s->staging = vrg_pass_host_buffer(pass, "staging", s->staging_bytes, &s->staging_buffer);
    void *atlas = vrg_pass_host_buffer(pass, "atlas staging", vrg_atlas_bytes(), &s->atlas_staging);
    if (!s->staging || !atlas)
        return -1;
    vrg_atlas_generate(atlas);
    if (strcmp(vrg_param_string(pass, "traversal"), "rayquery") == 0) {
        const vrg_features *f = &vrg_pass_device(pass)->features;
        if (!f->ray_query || !f->acceleration_structure) {
            int line = 0;
            vrg_param_item(pass, "traversal", vrg_param_count(pass, "traversal") - 1, &line);
            return vrg_pass_error_at(pass, line, "traversal = rayquery needs VK_KHR_ray_query, which device '%s' lacks (use traversal = dda)",
                                     vrg_pass_device(pass)->name);
        }
        s->accel = vrg_world_accel_create(pass, s->world);
        if (!s->accel)
            return -1;
    }
    return 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    scene *s = vrg_pass_user(pass);
    const vrg_camera *cam = &vrg_pass_frame(pass)->camera;
    int cx = vrg_floor_div16((int)floorf(cam->position[0])), cz = vrg_floor_div16((int)floorf(cam->position[2]));
    double t0 = now_ms();
    stream_update(s->stream, cx, cz, drop, s->world);
    if (s->wait)
        stream_wait_idle(s->stream);
    double t1 = now_ms(), spent = 0;
    int integrated = stream_integrate(s->stream, s->wait ? 1e9 : vrg_param(pass, "budget_ms"), integrate, s->world, &spent);
    double t2 = now_ms();
    int uploaded = 0;
    if (vrg_pass_frame(pass)->resources_new) {
        vrg_world_invalidate_gpu(s->world);
        vrg_atlas_record_upload(pass, cmd, "atlas", s->atlas_staging);
    }
    if (vrg_world_dirty_count(s->world))
        uploaded = vrg_world_upload(s->world, cmd, vrg_res_buffer(pass, vrg_pass_res(pass, "world")), s->staging, s->staging_buffer, s->staging_bytes);
    /* figures for `voxrg bench` and --json */
    vrg_pass_stat(pass, "wait_ms", t1 - t0);
    vrg_pass_stat(pass, "integrate_ms", spent);
    vrg_pass_stat(pass, "upload_ms", now_ms() - t2);
    vrg_pass_stat(pass, "chunks_integrated", integrated);
    vrg_pass_stat(pass, "chunks_uploaded", uploaded);
    vrg_pass_stat(pass, "chunks_loaded", vrg_world_chunk_count(s->world));
    vrg_pass_stat(pass, "chunks_pending", stream_pending(s->stream));
    vrg_pass_stat(pass, "threads", s->threads);
    if (s->accel)
        vrg_world_accel_record(s->accel, cmd, "tlas");
    vrg_sky_desc sky;
    vrg_sky_default(&sky);
    sky.time_of_day = (float)vrg_param(pass, "time_of_day");
    sky.day_length = (float)vrg_param(pass, "day_length");
    vrg_scene_write_frame(pass, cmd, "frame", &sky);
}

static void destroy(vrg_pass *pass)
{
    scene *s = vrg_pass_user(pass);
    if (!s)
        return;
    vrg_pass_set_world(pass, NULL);
    vrg_world_accel_destroy(s->accel);
    stream_destroy(s->stream);
    vrg_world_destroy(s->world);
    free(s);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "terrain",
    .kind = VRG_PLUGIN_SCENE,
    .help = "procedural terrain: Perlin heights, Voronoi biomes, trees, chunks streamed around the camera",
    .shader_dir = VRG_PLUGIN_DIR,
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .destroy = destroy,
};

VRG_PLUGIN(desc)
