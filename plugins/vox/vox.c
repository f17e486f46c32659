/* Scene plugin: a MagicaVoxel model (.vox) placed in the voxel world.
 *
 *   [scene]
 *   plugin   = vox
 *   file     = ../../shared/vox/chr_knight.vox  ; relative to the graph file
 *   position = 0 1 0     ; where the model's bottom centre goes, in blocks
 *   scale    = 1         ; each voxel becomes scale^3 blocks
 *   ground   = white     ; a ground plane at y = 0, or none
 *
 * MagicaVoxel is z-up, voxrg y-up: vox (x, y, z) becomes (x, z, -y), a
 * rotation, so nothing is mirrored. Each palette colour a voxel uses
 * becomes a block material with a flat atlas tile (vrg_world_add_material).
 * Edits (voxrg/edits.h) are kept beside the graph and applied at start. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/edits.h"
#include "vox_read.h"

static const vrg_param_desc params[] = {
    {.name = "file", .type = VRG_PARAM_STRING, .default_string = "", .help = "the .vox file, relative to the graph file's folder"},
    {.name = "position", .type = VRG_PARAM_STRING, .default_string = "0 1 0",
     .help = "X Y Z: the block where the model's bottom centre goes"},
    {.name = "scale", .type = VRG_PARAM_INT, .default_value = 1, .min = 1, .max = 16, .help = "blocks per voxel along each axis"},
    {.name = "ground", .type = VRG_PARAM_STRING, .default_string = "none", .help = "block of a ground plane at y = 0 under the model, or none"},
    {.name = "edits", .type = VRG_PARAM_STRING, .default_string = "",
     .help = "edit journal; empty: the graph file's path + .edits; none: no edits"},
    VRG_SCENE_PARAMS,
};

/* traversal, VRG_SCENE_PARAMS's last: its names, for hosts and the load's check */
static const char *const param_choices[sizeof params / sizeof params[0]] = {
    [sizeof params / sizeof params[0] - 1] = VRG_SCENE_TRAVERSAL_CHOICES};

static const vrg_slot_desc slots[] = {VRG_SCENE_SLOTS};

#define WORLD_XZ 512     /* |x|, |z| of any block: keeps the toroidal grid (and its GPU buffer) bounded */
#define VOX_MAX_PLACED (1 << 26) /* blocks written by all instances: a bound on the work, beside the world's */
#define WORLD_HEIGHT 256 /* y in [0, 256): 16 chunks, the terrain's largest height */
#define GROUND_MARGIN 2  /* chunks of ground around the model: its shadow lands on it */
#define EMISSIVE_SCALE 4 /* MagicaVoxel's _emit 1 shines like the lamp block */
_Static_assert(EMISSIVE_SCALE * VOX_EMIT_MAX <= (int)VRG_MATERIAL_EMISSIVE_MAX, "the reader's limit keeps every vox material within the world's");

typedef struct placed {
    vox_scene vox;
    uint8_t *bytes;        /* the file: models point into it */
    size_t size;
    char path[4096];
    int origin[3];         /* world block of the model's (scaled) box corner lo */
    int lo[3], hi[3];      /* world blocks, hi exclusive */
    int radius, height;    /* the grid */
    int scale, ground;
} placed;

typedef struct scene {
    vrg_scene_gpu gpu;
    vrg_edits *edits;
} scene;

static const char *file_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* The file parameter, relative to the graph's folder unless absolute. */
static void resolve(vrg_pass *pass, const char *file, char *out, size_t n)
{
    const char *graph = vrg_pass_graph_path(pass), *slash = strrchr(graph, '/');
    if (file[0] == '/' || !slash)
        snprintf(out, n, "%s", file);
    else
        snprintf(out, n, "%.*s/%s", (int)(slash - graph), graph, file);
}

/* 0, or -1 (errno set) when the file cannot be read whole. Regular files
 * only: a FIFO would block, a folder's "size" from fseek can be LONG_MAX. */
static int read_all(const char *path, uint8_t **data, size_t *size)
{
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f)
        return -1;
    int err;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        n = ftell(f);
    uint8_t *d = n >= 0 && fseek(f, 0, SEEK_SET) == 0 ? malloc(n ? (size_t)n : 1) : NULL;
    if (!d || fread(d, 1, (size_t)n, f) != (size_t)n) {
        /* fseek, ftell and malloc set errno; a short read need not */
        err = d ? EIO : errno;
        free(d);
        fclose(f);
        errno = err;
        return -1;
    }
    fclose(f);
    *data = d;
    *size = (size_t)n;
    return 0;
}

static int floor_half(int v) { return v >= 0 ? v / 2 : -((1 - v) / 2); }

/* Voxel v of an instance in MagicaVoxel's space (vox_read.h), then in
 * voxrg's: (x, y, z) -> (x, z, -1 - y), the block below vox y's face. */
static void voxel_block(const vox_instance *in, const int size[3], const uint8_t v[3], int out[3])
{
    int c[3], p[3];
    for (int a = 0; a < 3; a++)
        c[a] = 2 * v[a] + 1 - size[a];
    for (int a = 0; a < 3; a++)
        p[a] = in->t[a] + floor_half(in->rot[a][0] * c[0] + in->rot[a][1] * c[1] + in->rot[a][2] * c[2]);
    out[0] = p[0];
    out[1] = p[2];
    out[2] = -1 - p[1];
}

/* The box of every placed voxel, from each instance's box corners. */
static void model_box(const vox_scene *s, int lo[3], int hi[3])
{
    for (int a = 0; a < 3; a++)
        lo[a] = 1 << 30, hi[a] = -(1 << 30);
    for (int i = 0; i < s->instance_count; i++) {
        const vox_instance *in = &s->instances[i];
        const vox_model *m = &s->models[in->model];
        for (int k = 0; k < 8; k++) {
            uint8_t v[3] = {(uint8_t)(k & 1 ? m->size[0] - 1 : 0), (uint8_t)(k & 2 ? m->size[1] - 1 : 0), (uint8_t)(k & 4 ? m->size[2] - 1 : 0)};
            int b[3];
            voxel_block(in, m->size, v, b);
            for (int a = 0; a < 3; a++)
                lo[a] = b[a] < lo[a] ? b[a] : lo[a], hi[a] = b[a] + 1 > hi[a] ? b[a] + 1 : hi[a];
        }
    }
}

static void placed_free(placed *p)
{
    vox_free(&p->vox);
    free(p->bytes);
    memset(p, 0, sizeof *p);
}

/* position = X Y Z: three decimal integers, each within the world (x and
 * z in [-WORLD_XZ, WORLD_XZ], y in [0, WORLD_HEIGHT)). Read with range
 * checks, so a number beyond int's range is named as written, not wrapped. */
static int parse_position(vrg_pass *pass, const char *ps, int pos[3])
{
    static const long long lo[3] = {-WORLD_XZ, 0, -WORLD_XZ}, hi[3] = {WORLD_XZ, WORLD_HEIGHT - 1, WORLD_XZ};
    int line = vrg_param_line(pass, "position");
    const char *s = ps;
    for (int a = 0; a < 3; a++) {
        s += strspn(s, " \t");
        size_t len = strcspn(s, " \t");
        char *end;
        errno = 0;
        long long v = strtoll(s, &end, 10);
        if (len == 0 || end != s + len)
            return vrg_pass_error_at(pass, line, "position = '%s': expected 'X Y Z' (integers, blocks)", ps);
        if (errno == ERANGE || v < lo[a] || v > hi[a])
            return vrg_pass_error_at(pass, line, "position = '%s': %c = %.*s is outside [%lld, %lld] (blocks)", ps, "xyz"[a], (int)len, s, lo[a], hi[a]);
        pos[a] = (int)v;
        s += len;
    }
    if (s[strspn(s, " \t")] != '\0')
        return vrg_pass_error_at(pass, line, "position = '%s': expected 'X Y Z' (integers, blocks)", ps);
    return 0;
}

/* Reads the file and places the model: everything check() and create()
 * need, every error at its parameter's line. */
static int place(vrg_pass *pass, placed *p)
{
    memset(p, 0, sizeof *p);
    const char *file = vrg_param_string(pass, "file");
    int file_line = vrg_param_line(pass, "file");
    if (!file[0])
        return vrg_pass_error(pass, "file = the .vox file to show (relative to the graph file)");
    resolve(pass, file, p->path, sizeof p->path);
    if (read_all(p->path, &p->bytes, &p->size) != 0) {
        int missing = errno == ENOENT; /* only then is the shipped graphs' model folder the likely cause */
        return vrg_pass_error_at(pass, file_line, "file = '%s': cannot read %s: %s%s", file, p->path, vrg_open_strerror(errno),
                                 missing ? " (the shipped vox graphs expect ../shared/vox beside the project, docs/world.md)" : "");
    }
    char err[512];
    if (vox_read(p->bytes, p->size, p->path, &p->vox, err, sizeof err) != 0) {
        int rc = vrg_pass_error_at(pass, file_line, "%s", err);
        placed_free(p);
        return rc;
    }
    int pos[3], scale = vrg_param_int(pass, "scale");
    const char *ps = vrg_param_string(pass, "position");
    if (parse_position(pass, ps, pos) != 0) {
        placed_free(p);
        return -1;
    }
    const char *ground = vrg_param_string(pass, "ground");
    int no_ground = strcmp(ground, "none") == 0;
    p->ground = no_ground ? 0 : vrg_block_by_name(ground);
    if (!no_ground && p->ground <= 0) {
        placed_free(p);
        return vrg_pass_error_at(pass, vrg_param_line(pass, "ground"), "ground = '%s': expected none or a block name (stone, grass, white, ...)", ground);
    }
    /* every object or layer hidden: nothing to place (and no box) */
    if (p->vox.instance_count == 0) {
        int rc = vrg_pass_error_at(pass, file_line, "%s: nothing is visible: every object or layer of the scene is hidden", p->path);
        placed_free(p);
        return rc;
    }
    /* the work is instances x voxels x scale^3 however small the file: bound it */
    long long placed_blocks = 0;
    for (int i = 0; i < p->vox.instance_count; i++)
        placed_blocks += (long long)p->vox.models[p->vox.instances[i].model].count * scale * scale * scale;
    if (placed_blocks > VOX_MAX_PLACED) {
        int rc = vrg_pass_error_at(pass, file_line, "%s: %d instances place %lld blocks at scale %d, more than %d: lower scale, or show fewer instances",
                                   p->path, p->vox.instance_count, placed_blocks, scale, VOX_MAX_PLACED);
        placed_free(p);
        return rc;
    }
    int mlo[3], mhi[3];
    model_box(&p->vox, mlo, mhi);
    /* the scaled model's bottom centre goes to pos: long long, no overflow for any input */
    long long lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        long long extent = (long long)(mhi[a] - mlo[a]) * scale;
        lo[a] = pos[a] - (a == 1 ? 0 : extent / 2);
        hi[a] = lo[a] + extent;
    }
    if (lo[1] < 0 || hi[1] > WORLD_HEIGHT || lo[0] < -WORLD_XZ || hi[0] > WORLD_XZ || lo[2] < -WORLD_XZ || hi[2] > WORLD_XZ) {
        int rc = vrg_pass_error_at(pass, file_line,
                                   "%s: the model spans blocks %lld..%lld x %lld..%lld x %lld..%lld (scale %d, position %s); the world holds 0 <= y < %d and |x|, |z| <= %d",
                                   p->path, lo[0], hi[0] - 1, lo[1], hi[1] - 1, lo[2], hi[2] - 1, scale, ps, WORLD_HEIGHT, WORLD_XZ);
        placed_free(p); /* after the message: it names p->path */
        return rc;
    }
    int r = 0;
    for (int a = 0; a < 3; a++) {
        p->lo[a] = (int)lo[a], p->hi[a] = (int)hi[a];
        p->origin[a] = (int)lo[a] - mlo[a] * scale; /* world block of voxrg model block 0 */
    }
    for (int a = 0; a < 3; a += 2) {
        int c0 = abs(vrg_floor_div16(p->lo[a])), c1 = abs(vrg_floor_div16(p->hi[a] - 1));
        r = c0 > r ? c0 : r;
        r = c1 > r ? c1 : r;
    }
    p->radius = r + (p->ground ? GROUND_MARGIN : 0);
    p->height = vrg_floor_div16(p->hi[1] - 1) + 1;
    p->scale = scale;
    return 0;
}

/* The edit journal's path; 0 for none ("none", or a graph from text,
 * which has no folder to keep edits in). */
static int journal_path(vrg_pass *pass, char *path, size_t cap)
{
    const char *param = vrg_param_string(pass, "edits");
    if (strcmp(param, "none") == 0)
        return 0;
    if (param[0])
        resolve(pass, param, path, cap);
    else if (vrg_pass_graph_path(pass)[0])
        snprintf(path, cap, "%s.edits", vrg_pass_graph_path(pass));
    else
        return 0;
    return 1;
}

static int check(vrg_pass *pass)
{
    placed p;
    char journal[4096];
    if (place(pass, &p) != 0)
        return -1;
    int radius = p.radius, height = p.height;
    /* the model and its edits are the world */
    int rc = vrg_pass_input_file(pass, p.path);
    placed_free(&p);
    if (rc == 0 && journal_path(pass, journal, sizeof journal))
        rc = vrg_pass_input_file(pass, journal);
    return rc != 0 ? -1 : vrg_scene_check(pass, radius, height);
}

static float srgb_to_linear(uint8_t c)
{
    float v = c / 255.0f;
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static float colour_distance(uint32_t a, uint32_t b)
{
    float d = 0;
    for (int c = 0; c < 3; c++) {
        float x = srgb_to_linear((uint8_t)(a >> 8 * c)) - srgb_to_linear((uint8_t)(b >> 8 * c));
        d += x * x;
    }
    return d;
}

/* Whether kept colour a stands in better than kept colour b for colour c:
 * one that emits as c does (or not at all, as c) first, then the nearest. */
static int better_stand_in(const vox_scene *v, int c, int a, int b)
{
    int a_same = v->emissive[a] == v->emissive[c], b_same = v->emissive[b] == v->emissive[c];
    if (a_same != b_same)
        return a_same;
    return colour_distance(v->palette[c], v->palette[a]) < colour_distance(v->palette[c], v->palette[b]);
}

/* Whether colour a takes a block id before colour b: emitting colours
 * first (an emitter must not lose its light to a stand-in), then the most
 * used; ties by index, so the same file gives the same ids. */
static int takes_id_first(const vox_scene *v, const long long used[256], int a, int b)
{
    if ((v->emissive[a] > 0) != (v->emissive[b] > 0))
        return v->emissive[a] > 0;
    return used[a] > used[b] || (used[a] == used[b] && a < b);
}

/* Palette index -> block id: the used colours become materials, emitting
 * and most used first; when the world has fewer free ids than colours, the
 * rest take their nearest kept colour (one that emits alike where there
 * is one), and the user is told. */
static int make_materials(vrg_pass *pass, const placed *p, vrg_world *w, vrg_block block_of[256])
{
    long long used[256] = {0};
    for (int i = 0; i < p->vox.instance_count; i++) {
        const vox_model *m = &p->vox.models[p->vox.instances[i].model];
        for (int k = 0; k < m->count; k++)
            used[m->xyzi[4 * k + 3]]++;
    }
    int order[255], n = 0;
    for (int c = 1; c < 256; c++)
        if (used[c])
            order[n++] = c;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && takes_id_first(&p->vox, used, order[j], order[j - 1]); j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    int room = vrg_world_material_room(w), kept = n < room ? n : room;
    for (int i = 0; i < kept; i++) {
        int c = order[i];
        uint32_t rgba = p->vox.palette[c];
        char name[VRG_MATERIAL_NAME_MAX];
        snprintf(name, sizeof name, "vox%d", c);
        vrg_material m = {.name = name, .flags = VRG_MATERIAL_OPAQUE, .emissive = EMISSIVE_SCALE * p->vox.emissive[c]};
        for (int a = 0; a < 3; a++)
            m.albedo[a] = srgb_to_linear((uint8_t)(rgba >> 8 * a));
        int id = vrg_world_add_material(w, &m);
        if (id < 0)
            return vrg_pass_error(pass, "no block id left for palette colour %d", c);
        block_of[c] = (vrg_block)id;
    }
    for (int i = kept; i < n; i++) {
        int c = order[i], best = order[0];
        for (int j = 1; j < kept; j++)
            if (better_stand_in(&p->vox, c, order[j], best))
                best = order[j];
        block_of[c] = block_of[best];
    }
    if (n > kept)
        vrg_pass_warn_at(pass, vrg_param_line(pass, "file"), "%s uses %d palette colours and the world has %d free block ids: the %d least used take their nearest kept colour",
                         p->path, n, kept, n - kept);
    return 0;
}

static void put_model(const placed *p, vrg_world *w, const vrg_block block_of[256])
{
    int s = p->scale;
    for (int i = 0; i < p->vox.instance_count; i++) {
        const vox_instance *in = &p->vox.instances[i];
        const vox_model *m = &p->vox.models[in->model];
        for (int k = 0; k < m->count; k++) {
            const uint8_t *v = m->xyzi + 4 * k;
            int b[3];
            voxel_block(in, m->size, v, b);
            for (int dy = 0; dy < s; dy++)
                for (int dz = 0; dz < s; dz++)
                    for (int dx = 0; dx < s; dx++)
                        vrg_world_set_block(w, p->origin[0] + b[0] * s + dx, p->origin[1] + b[1] * s + dy, p->origin[2] + b[2] * s + dz, block_of[v[3]]);
        }
    }
}

/* Every chunk of the grid is loaded (air where nothing is), so an edit can
 * place a block anywhere in it. */
static vrg_world *build_world(vrg_pass *pass, const placed *p)
{
    vrg_world *w = vrg_world_create(p->radius, p->height);
    vrg_block *chunk = calloc(1, VRG_CHUNK_VOXELS);
    if (!w || !chunk) {
        free(chunk);
        vrg_world_destroy(w);
        vrg_pass_error(pass, "out of memory for the world");
        return NULL;
    }
    for (int cy = 0; cy < p->height; cy++)
        for (int cz = -p->radius; cz <= p->radius; cz++)
            for (int cx = -p->radius; cx <= p->radius; cx++) {
                memset(chunk, VRG_BLOCK_AIR, VRG_CHUNK_VOXELS);
                if (cy == 0 && p->ground)
                    memset(chunk, p->ground, VRG_CHUNK_SIZE * VRG_CHUNK_SIZE); /* layer y = 0 */
                vrg_world_put_chunk(w, cx, cy, cz, chunk);
            }
    free(chunk);
    vrg_block block_of[256] = {0};
    if (make_materials(pass, p, w, block_of) != 0) {
        vrg_world_destroy(w);
        return NULL;
    }
    put_model(p, w, block_of);
    return w;
}

static uint64_t fnv1a(const uint8_t *d, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++)
        h = (h ^ d[i]) * 0x100000001b3ull;
    return h;
}

/* The journal, keyed by what decides where the blocks are. */
static int open_edits(vrg_pass *pass, scene *s, const placed *p)
{
    char path[4096], key[VRG_EDITS_KEY_MAX], err[1024];
    if (!journal_path(pass, path, sizeof path))
        return 0;
    snprintf(key, sizeof key, "vox file=%s bytes=%zu fnv1a=%016llx position=%s scale=%d ground=%s", file_name(p->path), p->size,
             (unsigned long long)fnv1a(p->bytes, p->size), vrg_param_string(pass, "position"), p->scale, vrg_param_string(pass, "ground"));
    s->edits = vrg_edits_open(path, key, s->gpu.world, err, sizeof err);
    if (!s->edits)
        return vrg_pass_error_at(pass, vrg_param_line(pass, "edits"), "%s", err);
    if (vrg_edits_dropped_bytes(s->edits))
        vrg_pass_warn_at(pass, vrg_param_line(pass, "edits"), "%s: dropped a torn last record (%ld bytes) left by a crash", path,
                         vrg_edits_dropped_bytes(s->edits));
    vrg_edits_apply_world(s->edits, s->gpu.world);
    return vrg_pass_share(pass, VRG_EDITS_SHARED_NAME, s->edits);
}

static void destroy(vrg_pass *pass);

static int create(vrg_pass *pass)
{
    scene *s = calloc(1, sizeof *s);
    if (!s)
        return vrg_pass_error(pass, "out of memory");
    vrg_pass_set_user(pass, s);
    placed p;
    int placed_ok = place(pass, &p) == 0, rc = -1; /* place() frees p when it fails */
    vrg_world *w = placed_ok ? build_world(pass, &p) : NULL;
    if (w) {
        s->gpu.world = w;
        rc = open_edits(pass, s, &p);
    }
    if (placed_ok)
        placed_free(&p);
    /* after the edits: the world's first upload has them */
    if (!w || rc != 0 || vrg_scene_create(pass, &s->gpu, w) != 0) {
        /* destroy() runs only after a create() that succeeded: free here */
        destroy(pass);
        return -1;
    }
    return 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    scene *s = vrg_pass_user(pass);
    vrg_scene_record(pass, &s->gpu, cmd);
}

static void destroy(vrg_pass *pass)
{
    scene *s = vrg_pass_user(pass);
    if (!s)
        return;
    if (s->edits)
        vrg_pass_share(pass, VRG_EDITS_SHARED_NAME, NULL);
    vrg_edits_close(s->edits);
    if (s->gpu.world)
        vrg_scene_destroy(pass, &s->gpu); /* frees the world too */
    free(s);
    vrg_pass_set_user(pass, NULL);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "vox",
    .kind = VRG_PLUGIN_SCENE,
    .help = "a MagicaVoxel model (.vox): models, palette, materials and scene graph placed in the world",
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
