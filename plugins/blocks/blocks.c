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
    VRG_SCENE_PARAMS,
};

/* traversal, VRG_SCENE_PARAMS's last: its names, for hosts and the load's check */
static const char *const param_choices[sizeof params / sizeof params[0]] = {
    [sizeof params / sizeof params[0] - 1] = VRG_SCENE_TRAVERSAL_CHOICES};

static const vrg_slot_desc slots[] = {VRG_SCENE_SLOTS};

#define MAX_EXTENT 1024 /* blocks from the origin: keeps the toroidal grid small */

typedef struct box {
    int lo[3], hi[3];
    vrg_block block;
} box;

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
    return vrg_scene_check(pass, radius, height);
}

static int create(vrg_pass *pass)
{
    box *boxes;
    int radius, height;
    int n = parse_boxes(pass, &boxes, &radius, &height);
    if (n < 0)
        return -1;
    vrg_world *world = vrg_world_create(radius, height);
    vrg_block *chunk = malloc(VRG_CHUNK_VOXELS);
    for (int cy = 0; world && cy < height; cy++)
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
                    vrg_world_put_chunk(world, cx, cy, cz, chunk);
            }
    free(chunk);
    free(boxes);
    if (!world)
        return vrg_pass_error(pass, "out of memory for the world");
    vrg_scene_gpu *s = calloc(1, sizeof *s);
    vrg_pass_set_user(pass, s);
    return vrg_scene_create(pass, s, world);
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd) { vrg_scene_record(pass, vrg_pass_user(pass), cmd); }

static void destroy(vrg_pass *pass)
{
    vrg_scene_gpu *s = vrg_pass_user(pass);
    if (s)
        vrg_scene_destroy(pass, s);
    free(s);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "blocks",
    .kind = VRG_PLUGIN_SCENE,
    .help = "a world of boxes listed in the graph (box = x0 y0 z0 x1 y1 z1 block)",
    .params = params,
    .param_choices = param_choices,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .destroy = destroy,
};

VRG_PLUGIN(desc)
