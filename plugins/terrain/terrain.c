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
#include <stdio.h>
#include "voxrg/edits.h"
#include "stream.h"
#include "terrain_gen.h"

/* the parameter with a list of names (param_choices): placed at its index
 * in both lists, so that the two cannot drift apart: an entry added before
 * it makes -Woverride-init warn, one removed leaves an entry with no name,
 * which the loader refuses */
enum { STREAM_PARAM = 13 };

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
    [STREAM_PARAM] = {"stream", VRG_PARAM_STRING, 0, 0, 0, "wait (deterministic: each frame waits for its chunks) or budget", 0, "wait"},
    {"budget_ms", VRG_PARAM_FLOAT, 2, 0, 1000, "stream = budget: main-thread integration time per frame"},
    {.name = "edits", .type = VRG_PARAM_STRING, .default_string = "",
     .help = "edit journal; empty: the graph file's path + .edits; none: no edits"},
    VRG_SCENE_PARAMS,
};

static const vrg_slot_desc slots[] = {VRG_SCENE_SLOTS};

/* the runtime checks stream's and traversal's (VRG_SCENE_PARAMS's last)
 * values against these */
static const char *const param_choices[sizeof params / sizeof params[0]] = {
    [STREAM_PARAM] = "wait,budget", [sizeof params / sizeof params[0] - 1] = VRG_SCENE_TRAVERSAL_CHOICES};

/* The generated world and what generates it. A hot reload of a graph whose
 * world parameters are unchanged shares it with the new instance
 * (vrg_pass_previous_instance) instead of generating it again; each
 * instance's destroy() releases its share. */
typedef struct terrain_world {
    int refs;
    char journal[4096]; /* the edit journal applied to it ("": none) */
    terrain_params gen;
    int radius, hysteresis, threads;
    vrg_world *world;
    stream *stream;
} terrain_world;

typedef struct scene {
    vrg_scene_gpu gpu;
    terrain_world *tw;
    vrg_edits *edits;
    int wait;
    int world_kept; /* shared from the instance a reload replaced */
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

static void journal_path(vrg_pass *pass, char *path, size_t cap);

static int check(vrg_pass *pass)
{
    char journal[4096];
    journal_path(pass, journal, sizeof journal);
    if (journal[0] && vrg_pass_input_file(pass, journal) != 0) /* its edits are part of the world */
        return -1;
    return vrg_scene_check(pass, grid_radius(pass), vrg_param_int(pass, "height_chunks"));
}

static void generate(void *user, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS])
{
    terrain_generate_chunk(&((terrain_world *)user)->gen, cx, cy, cz, out);
}

/* A generated chunk gets the journal's edits before it enters the world:
 * a chunk dropped and generated again shows them too. */
static void integrate(void *user, int cx, int cy, int cz, const vrg_block *blocks)
{
    scene *s = user;
    vrg_block edited[VRG_CHUNK_VOXELS];
    if (s->edits) {
        memcpy(edited, blocks, sizeof edited);
        if (vrg_edits_apply_chunk(s->edits, cx, cy, cz, edited) > 0)
            blocks = edited;
    }
    vrg_world_put_chunk(s->gpu.world, cx, cy, cz, blocks);
}
static void drop(void *user, int cx, int cy, int cz) { vrg_world_drop_chunk(user, cx, cy, cz); }

static void release_world(terrain_world *tw)
{
    if (!tw || --tw->refs > 0)
        return;
    stream_destroy(tw->stream); /* workers stop before the world goes */
    vrg_world_destroy(tw->world);
    free(tw);
}

/* the parameters the world's blocks and streaming depend on (time of day,
 * traversal and the stream mode do not) */
static void world_params(vrg_pass *pass, terrain_world *tw)
{
    params_from(pass, &tw->gen);
    tw->radius = vrg_param_int(pass, "radius");
    tw->hysteresis = vrg_param_int(pass, "hysteresis");
    int threads = vrg_param_int(pass, "threads");
    if (threads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    tw->threads = threads;
}

/* The instance a reload replaces, when its world's parameters are these
 * (terrain_params holds only 4-byte fields: memcmp sees no padding). */
static scene *previous_scene(vrg_pass *pass, const terrain_world *want)
{
    vrg_pass *prev = vrg_pass_previous_instance(pass);
    scene *old = prev ? vrg_pass_user(prev) : NULL;
    terrain_world *tw = old ? old->tw : NULL;
    /* its chunks hold its journal's edits: kept only with the same journal */
    if (!tw || memcmp(&tw->gen, &want->gen, sizeof want->gen) != 0 || tw->radius != want->radius || tw->hysteresis != want->hysteresis ||
        tw->threads != want->threads || strcmp(tw->journal, want->journal) != 0)
        return NULL;
    return old;
}

static terrain_world *new_world(const terrain_world *want)
{
    terrain_world *tw = malloc(sizeof *tw);
    if (!tw)
        return NULL;
    *tw = *want;
    tw->refs = 1;
    tw->world = vrg_world_create(tw->radius + tw->hysteresis, tw->gen.height_chunks);
    if (tw->world) /* chunks within radius of the camera's are wanted: at least radius * 16 blocks */
        vrg_world_set_view_radius(tw->world, tw->radius * 16);
    stream_desc sd = {.threads = tw->threads,
                      .radius = tw->radius,
                      .hysteresis = tw->hysteresis,
                      .height_chunks = tw->gen.height_chunks,
                      .generate = generate,
                      .user = tw};
    tw->stream = tw->world ? stream_create(&sd) : NULL;
    if (!tw->stream) {
        vrg_world_destroy(tw->world);
        free(tw);
        return NULL;
    }
    return tw;
}

/* The edit journal's path ("": none; a graph from text has no folder to
 * keep edits in). */
static void journal_path(vrg_pass *pass, char *path, size_t cap)
{
    const char *param = vrg_param_string(pass, "edits"), *graph = vrg_pass_graph_path(pass), *slash = strrchr(graph, '/');
    if (strcmp(param, "none") == 0 || (!param[0] && !graph[0]))
        snprintf(path, cap, "%s", "");
    else if (!param[0])
        snprintf(path, cap, "%s.edits", graph);
    else if (param[0] == '/' || !slash)
        snprintf(path, cap, "%s", param);
    else
        snprintf(path, cap, "%.*s/%s", (int)(slash - graph), graph, param);
}

/* The journal, keyed by every parameter the blocks depend on. */
static int open_edits(vrg_pass *pass, scene *s)
{
    const char *path = s->tw->journal;
    char key[VRG_EDITS_KEY_MAX], err[1024];
    if (!path[0])
        return 0;
    const terrain_params *g = &s->tw->gen;
    snprintf(key, sizeof key, "terrain seed=%u octaves=%d scale=%g falloff=%g base_height=%g amplitude=%g height_chunks=%d biome_size=%g tree_density=%g sea_level=%d",
             g->seed, g->octaves, g->scale, g->falloff, g->base_height, g->amplitude, g->height_chunks, g->biome_size, g->tree_density, g->sea_level);
    s->edits = vrg_edits_open(path, key, s->tw->world, err, sizeof err);
    if (!s->edits)
        return vrg_pass_error_at(pass, vrg_param_line(pass, "edits"), "%s", err);
    if (vrg_edits_dropped_bytes(s->edits))
        vrg_pass_warn_at(pass, vrg_param_line(pass, "edits"), "%s: dropped a torn last record (%ld bytes) left by a crash", path,
                         vrg_edits_dropped_bytes(s->edits));
    vrg_edits_apply_world(s->edits, s->tw->world); /* chunks a reload kept */
    return vrg_pass_share(pass, VRG_EDITS_SHARED_NAME, s->edits);
}

static void destroy(vrg_pass *pass);

static int create(vrg_pass *pass)
{
    scene *s = calloc(1, sizeof *s);
    if (!s)
        return vrg_pass_error(pass, "out of memory");
    vrg_pass_set_user(pass, s);
    s->wait = vrg_param_choice(pass, "stream", NULL, 0) == 0;
    terrain_world want = {0};
    world_params(pass, &want);
    journal_path(pass, want.journal, sizeof want.journal);
    scene *old = previous_scene(pass, &want);
    if (old)
        old->tw->refs++;
    s->tw = old ? old->tw : new_world(&want);
    if (!s->tw)
        return vrg_pass_error(pass, "cannot create the world (out of memory?)");
    s->world_kept = old != NULL;
    /* with the world, what the GPU holds of it (buffer, atlas, BLASes) */
    if (vrg_scene_create_from(pass, &s->gpu, s->tw->world, old ? &old->gpu : NULL) != 0 || open_edits(pass, s) != 0) {
        /* destroy() runs only after a create() that succeeded: free here */
        destroy(pass);
        return -1;
    }
    return 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    scene *s = vrg_pass_user(pass);
    vrg_world *world = s->gpu.world;
    stream *st = s->tw->stream;
    const vrg_camera *cam = &vrg_pass_frame(pass)->camera;
    /* the runtime keeps cameras in the world; vrg_world_floor holds even if not */
    int cx = vrg_floor_div16(vrg_world_floor(cam->position[0])), cz = vrg_floor_div16(vrg_world_floor(cam->position[2]));
    double t0 = now_ms();
    stream_update(st, cx, cz, drop, world);
    if (s->wait)
        stream_wait_idle(st);
    double t1 = now_ms(), spent = 0;
    int integrated = stream_integrate(st, s->wait ? 1e9 : vrg_param(pass, "budget_ms"), integrate, s, &spent);
    double t2 = now_ms();
    vrg_scene_record(pass, &s->gpu, cmd);
    /* figures for `voxrg bench` and --json (upload_ms includes BLAS/TLAS recording) */
    vrg_pass_stat(pass, "wait_ms", t1 - t0);
    vrg_pass_stat(pass, "integrate_ms", spent);
    vrg_pass_stat(pass, "upload_ms", now_ms() - t2);
    vrg_pass_stat(pass, "chunks_integrated", integrated);
    vrg_pass_stat(pass, "chunks_loaded", vrg_world_chunk_count(world));
    vrg_pass_stat(pass, "chunks_pending", stream_pending(st));
    vrg_pass_stat(pass, "threads", s->tw->threads);
    vrg_pass_stat(pass, "world_kept", s->world_kept);
}

static void destroy(vrg_pass *pass)
{
    scene *s = vrg_pass_user(pass);
    if (!s)
        return;
    if (s->edits)
        vrg_pass_share(pass, VRG_EDITS_SHARED_NAME, NULL);
    vrg_edits_close(s->edits);
    s->gpu.world = NULL; /* the world is the terrain_world's, maybe shared */
    vrg_scene_destroy(pass, &s->gpu);
    release_world(s->tw);
    free(s);
    vrg_pass_set_user(pass, NULL);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "terrain",
    .kind = VRG_PLUGIN_SCENE,
    .help = "procedural terrain: Perlin heights, Voronoi biomes, trees, chunks streamed around the camera",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .destroy = destroy,
    .param_choices = param_choices,
};

VRG_PLUGIN(desc)
