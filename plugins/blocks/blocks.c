/* Scene plugin: a world made of boxes listed in the graph file, for exact,
 * analytic scenes (a floor, a wall, a corner, a pillar):
 *
 *   [scene]
 *   plugin = blocks
 *   box = 0 0 0 31 0 31 white    ; x0 y0 z0 x1 y1 z1 block (corners inclusive)
 *   box = 8 1 8 8 6 20 red       ; later boxes overwrite earlier ones
 *
 * Outputs the world buffer (world.glsl layout) and the per-frame uniforms. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/world.h"

static const vrg_param_desc params[] = {
    {"box", VRG_PARAM_STRING, 0, 0, 0, "x0 y0 z0 x1 y1 z1 block: a box of blocks, corners inclusive (repeat the key)", VRG_PARAM_REPEATABLE, ""},
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

#define MAX_EXTENT 1024 /* blocks from the origin: keeps the toroidal grid small */

typedef struct box {
    int lo[3], hi[3];
    vrg_block block;
} box;

typedef struct scene {
    vrg_world *world;
    void *staging;
    VkBuffer staging_buffer;
    VkBuffer atlas_staging;
    vrg_world_accel *accel; /* traversal = rayquery */
    uint64_t staging_bytes;
} scene;

/* Parses every box; reports each bad one at its line. Returns the count or -1. */
static int parse_boxes(vrg_pass *pass, box **out, int *radius, int *height)
{
    int n = vrg_param_count(pass, "box"), bad = 0;
    box *boxes = calloc(n ? (size_t)n : 1, sizeof *boxes);
    int max_c = 0, max_cy = 0;
    for (int i = 0; i < n; i++) {
        int line, c[6];
        char name[64], extra;
        const char *v = vrg_param_item(pass, "box", i, &line);
        if (sscanf(v, "%d %d %d %d %d %d %63s %c", &c[0], &c[1], &c[2], &c[3], &c[4], &c[5], name, &extra) != 7) {
            bad = vrg_pass_error_at(pass, line, "box = '%s': expected 'x0 y0 z0 x1 y1 z1 block'", v);
            continue;
        }
        char *end;
        long id = strtol(name, &end, 10);
        int block = *end == '\0' ? (id >= 0 && id < VRG_BLOCK_COUNT ? (int)id : -1) : vrg_block_by_name(name);
        if (block < 0) {
            char list[512] = "";
            for (int b = 0; b < VRG_BLOCK_COUNT; b++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", b ? ", " : "", vrg_materials()[b].name);
            bad = vrg_pass_error_at(pass, line, "box: unknown block '%s' (blocks: %s)", name, list);
            continue;
        }
        box *b = &boxes[i];
        for (int a = 0; a < 3; a++) {
            b->lo[a] = c[a] < c[a + 3] ? c[a] : c[a + 3];
            b->hi[a] = c[a] < c[a + 3] ? c[a + 3] : c[a];
        }
        b->block = (vrg_block)block;
        if (b->lo[1] < 0 || b->hi[0] >= MAX_EXTENT || b->hi[2] >= MAX_EXTENT || b->lo[0] < -MAX_EXTENT || b->lo[2] < -MAX_EXTENT ||
            b->hi[1] >= 256) {
            bad = vrg_pass_error_at(pass, line, "box = '%s': outside the world (0 <= y < 256, |x|, |z| < %d)", v, MAX_EXTENT);
            continue;
        }
        for (int a = 0; a < 3; a += 2) {
            int c0 = abs(vrg_floor_div16(b->lo[a])), c1 = abs(vrg_floor_div16(b->hi[a]));
            max_c = c0 > max_c ? c0 : max_c;
            max_c = c1 > max_c ? c1 : max_c;
        }
        max_cy = vrg_floor_div16(b->hi[1]) > max_cy ? vrg_floor_div16(b->hi[1]) : max_cy;
    }
    if (bad) {
        free(boxes);
        return -1;
    }
    *out = boxes;
    *radius = max_c;
    *height = max_cy + 1;
    return n;
}

static int check(vrg_pass *pass)
{
    box *boxes;
    int radius, height;
    if (parse_boxes(pass, &boxes, &radius, &height) < 0)
        return -1;
    free(boxes);
    const char *traversal = vrg_param_string(pass, "traversal");
    if (strcmp(traversal, "dda") != 0 && strcmp(traversal, "rayquery") != 0) {
        int line = 0;
        vrg_param_item(pass, "traversal", vrg_param_count(pass, "traversal") - 1, &line);
        return vrg_pass_error_at(pass, line, "traversal = '%s': expected dda or rayquery", traversal);
    }
    uint64_t slots = (uint64_t)(2 * radius + 1) * (2 * radius + 1) * height;
    vrg_pass_set_buffer_size(pass, "tlas", strcmp(traversal, "rayquery") == 0 ? slots : 0);
    return vrg_pass_set_buffer_size(pass, "world", vrg_world_gpu_bytes(radius, height));
}

static int create(vrg_pass *pass)
{
    box *boxes;
    int radius, height;
    int n = parse_boxes(pass, &boxes, &radius, &height);
    if (n < 0)
        return -1;
    scene *s = calloc(1, sizeof *s);
    vrg_pass_set_user(pass, s);
    s->world = vrg_world_create(radius, height);
    vrg_block *chunk = malloc(VRG_CHUNK_VOXELS);
    for (int cy = 0; cy < height; cy++)
        for (int cz = -radius; cz <= radius; cz++)
            for (int cx = -radius; cx <= radius; cx++) {
                memset(chunk, VRG_BLOCK_AIR, VRG_CHUNK_VOXELS);
                int any = 0;
                for (int i = 0; i < n; i++) {
                    /* the part of box i inside this chunk, in chunk-local coordinates */
                    const box *b = &boxes[i];
                    int base[3] = {cx * 16, cy * 16, cz * 16}, lo[3], hi[3], empty = 0;
                    for (int a = 0; a < 3; a++) {
                        lo[a] = (b->lo[a] > base[a] ? b->lo[a] : base[a]) - base[a];
                        hi[a] = (b->hi[a] < base[a] + 15 ? b->hi[a] : base[a] + 15) - base[a];
                        empty |= lo[a] > hi[a];
                    }
                    if (empty)
                        continue;
                    for (int y = lo[1]; y <= hi[1]; y++)
                        for (int z = lo[2]; z <= hi[2]; z++)
                            for (int x = lo[0]; x <= hi[0]; x++)
                                chunk[vrg_chunk_index(x, y, z)] = b->block;
                    any = 1;
                }
                if (any)
                    vrg_world_put_chunk(s->world, cx, cy, cz, chunk);
            }
    free(chunk);
    free(boxes);
    vrg_pass_set_world(pass, s->world);
    /* one upload of everything on the first frame */
    s->staging_bytes = vrg_world_gpu_bytes(radius, height);
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
    VkBuffer world = vrg_res_buffer(pass, vrg_pass_res(pass, "world"));
    if (vrg_pass_frame(pass)->resources_new) {
        vrg_world_invalidate_gpu(s->world);
        vrg_atlas_record_upload(pass, cmd, "atlas", s->atlas_staging);
    }
    if (vrg_world_dirty_count(s->world))
        vrg_world_upload(s->world, cmd, world, s->staging, s->staging_buffer, s->staging_bytes);
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
    vrg_world_destroy(s->world);
    free(s);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "blocks",
    .kind = VRG_PLUGIN_SCENE,
    .help = "a world of boxes listed in the graph (box = x0 y0 z0 x1 y1 z1 block)",
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
