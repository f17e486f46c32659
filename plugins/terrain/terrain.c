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
    {"seed", VRG_PARAM_INT, 1337, 0, 4294967295.0, "world seed", VRG_PARAM_RELOAD},
    {"radius", VRG_PARAM_INT, 13, 0, 64, "chunks generated around the camera (|dx|, |dz| <= radius)", VRG_PARAM_RELOAD},
    {"height_chunks", VRG_PARAM_INT, 3, 1, 16, "world height in 16-block chunks", VRG_PARAM_RELOAD},
    {"hysteresis", VRG_PARAM_INT, 2, 0, 16, "chunks beyond radius kept before they are dropped", VRG_PARAM_RELOAD},
    {"octaves", VRG_PARAM_INT, 5, 1, 16, "noise octaves (frequency doubles per octave)", VRG_PARAM_RELOAD},
    {"scale", VRG_PARAM_FLOAT, 96, 1, 100000, "horizontal size of the largest octave, blocks", VRG_PARAM_RELOAD},
    {"falloff", VRG_PARAM_FLOAT, 0.5, 0, 1, "amplitude multiplier per octave", VRG_PARAM_RELOAD},
    {"base_height", VRG_PARAM_FLOAT, 20, 0, 256, "mean surface height, blocks", VRG_PARAM_RELOAD},
    {"amplitude", VRG_PARAM_FLOAT, 14, 0, 256, "height variation, blocks", VRG_PARAM_RELOAD},
    {"biome_size", VRG_PARAM_FLOAT, 128, 8, 100000, "Voronoi cell size of biomes, blocks", VRG_PARAM_RELOAD},
    {"tree_density", VRG_PARAM_FLOAT, 0.02, 0, 1, "fraction of forest columns holding a tree", VRG_PARAM_RELOAD},
    {"sea_level", VRG_PARAM_INT, 12, 0, 256, "water fills air below this height", VRG_PARAM_RELOAD},
    {"threads", VRG_PARAM_INT, 0, 0, 64, "generator threads; 0: one per CPU", VRG_PARAM_RELOAD},
    {"stream", VRG_PARAM_STRING, 0, 0, 0, "wait (deterministic: each frame waits for its chunks) or budget", 0, "wait"},
    {"budget_ms", VRG_PARAM_FLOAT, 2, 0, 1000, "stream = budget: main-thread integration time per frame"},
    VRG_SCENE_PARAMS,
};

static const vrg_slot_desc slots[] = {VRG_SCENE_SLOTS};

static const char *const stream_modes[] = {"wait", "budget"};

typedef struct scene {
    vrg_scene_gpu gpu;
    terrain_params gen;
    stream *stream;
    int wait;
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
    if (vrg_param_choice(pass, "stream", stream_modes, 2) < 0)
        return -1;
    return vrg_scene_check(pass, grid_radius(pass), vrg_param_int(pass, "height_chunks"));
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
    s->wait = vrg_param_choice(pass, "stream", stream_modes, 2) == 0;
    int threads = vrg_param_int(pass, "threads");
    if (threads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    s->threads = threads;
    vrg_world *world = vrg_world_create(grid_radius(pass), s->gen.height_chunks);
    stream_desc sd = {.threads = threads,
                      .radius = vrg_param_int(pass, "radius"),
                      .hysteresis = vrg_param_int(pass, "hysteresis"),
                      .height_chunks = s->gen.height_chunks,
                      .generate = generate,
                      .user = s};
    s->stream = world ? stream_create(&sd) : NULL;
    if (!s->stream) {
        vrg_world_destroy(world);
        return vrg_pass_error(pass, "cannot create the world (out of memory?)");
    }
    return vrg_scene_create(pass, &s->gpu, world);
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    scene *s = vrg_pass_user(pass);
    vrg_world *world = s->gpu.world;
    const vrg_camera *cam = &vrg_pass_frame(pass)->camera;
    /* the runtime keeps cameras in the world; vrg_world_floor holds even if not */
    int cx = vrg_floor_div16(vrg_world_floor(cam->position[0])), cz = vrg_floor_div16(vrg_world_floor(cam->position[2]));
    double t0 = now_ms();
    stream_update(s->stream, cx, cz, drop, world);
    if (s->wait)
        stream_wait_idle(s->stream);
    double t1 = now_ms(), spent = 0;
    int integrated = stream_integrate(s->stream, s->wait ? 1e9 : vrg_param(pass, "budget_ms"), integrate, world, &spent);
    double t2 = now_ms();
    vrg_scene_record(pass, &s->gpu, cmd);
    /* figures for `voxrg bench` and --json (upload_ms includes BLAS/TLAS recording) */
    vrg_pass_stat(pass, "wait_ms", t1 - t0);
    vrg_pass_stat(pass, "integrate_ms", spent);
    vrg_pass_stat(pass, "upload_ms", now_ms() - t2);
    vrg_pass_stat(pass, "chunks_integrated", integrated);
    vrg_pass_stat(pass, "chunks_loaded", vrg_world_chunk_count(world));
    vrg_pass_stat(pass, "chunks_pending", stream_pending(s->stream));
    vrg_pass_stat(pass, "threads", s->threads);
}

static void destroy(vrg_pass *pass)
{
    scene *s = vrg_pass_user(pass);
    if (!s)
        return;
    stream_destroy(s->stream); /* workers stop before the world goes */
    vrg_scene_destroy(pass, &s->gpu);
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
