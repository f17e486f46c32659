/* MagicaVoxel .vox reader (vox_read.h). The file is RIFF-like: "VOX ",
 * a version, then chunk MAIN whose children are the models, the palette,
 * materials and the scene graph. Every chunk header is (id, content bytes,
 * children bytes); both sizes are checked against the bytes left in the
 * enclosing chunk before they are used. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "vox_read.h"

const uint32_t vox_default_palette[256] = {
    0x00000000u, 0xffffffffu, 0xffccffffu, 0xff99ffffu, 0xff66ffffu, 0xff33ffffu, 0xff00ffffu, 0xffffccffu,
    0xffccccffu, 0xff99ccffu, 0xff66ccffu, 0xff33ccffu, 0xff00ccffu, 0xffff99ffu, 0xffcc99ffu, 0xff9999ffu,
    0xff6699ffu, 0xff3399ffu, 0xff0099ffu, 0xffff66ffu, 0xffcc66ffu, 0xff9966ffu, 0xff6666ffu, 0xff3366ffu,
    0xff0066ffu, 0xffff33ffu, 0xffcc33ffu, 0xff9933ffu, 0xff6633ffu, 0xff3333ffu, 0xff0033ffu, 0xffff00ffu,
    0xffcc00ffu, 0xff9900ffu, 0xff6600ffu, 0xff3300ffu, 0xff0000ffu, 0xffffffccu, 0xffccffccu, 0xff99ffccu,
    0xff66ffccu, 0xff33ffccu, 0xff00ffccu, 0xffffccccu, 0xffccccccu, 0xff99ccccu, 0xff66ccccu, 0xff33ccccu,
    0xff00ccccu, 0xffff99ccu, 0xffcc99ccu, 0xff9999ccu, 0xff6699ccu, 0xff3399ccu, 0xff0099ccu, 0xffff66ccu,
    0xffcc66ccu, 0xff9966ccu, 0xff6666ccu, 0xff3366ccu, 0xff0066ccu, 0xffff33ccu, 0xffcc33ccu, 0xff9933ccu,
    0xff6633ccu, 0xff3333ccu, 0xff0033ccu, 0xffff00ccu, 0xffcc00ccu, 0xff9900ccu, 0xff6600ccu, 0xff3300ccu,
    0xff0000ccu, 0xffffff99u, 0xffccff99u, 0xff99ff99u, 0xff66ff99u, 0xff33ff99u, 0xff00ff99u, 0xffffcc99u,
    0xffcccc99u, 0xff99cc99u, 0xff66cc99u, 0xff33cc99u, 0xff00cc99u, 0xffff9999u, 0xffcc9999u, 0xff999999u,
    0xff669999u, 0xff339999u, 0xff009999u, 0xffff6699u, 0xffcc6699u, 0xff996699u, 0xff666699u, 0xff336699u,
    0xff006699u, 0xffff3399u, 0xffcc3399u, 0xff993399u, 0xff663399u, 0xff333399u, 0xff003399u, 0xffff0099u,
    0xffcc0099u, 0xff990099u, 0xff660099u, 0xff330099u, 0xff000099u, 0xffffff66u, 0xffccff66u, 0xff99ff66u,
    0xff66ff66u, 0xff33ff66u, 0xff00ff66u, 0xffffcc66u, 0xffcccc66u, 0xff99cc66u, 0xff66cc66u, 0xff33cc66u,
    0xff00cc66u, 0xffff9966u, 0xffcc9966u, 0xff999966u, 0xff669966u, 0xff339966u, 0xff009966u, 0xffff6666u,
    0xffcc6666u, 0xff996666u, 0xff666666u, 0xff336666u, 0xff006666u, 0xffff3366u, 0xffcc3366u, 0xff993366u,
    0xff663366u, 0xff333366u, 0xff003366u, 0xffff0066u, 0xffcc0066u, 0xff990066u, 0xff660066u, 0xff330066u,
    0xff000066u, 0xffffff33u, 0xffccff33u, 0xff99ff33u, 0xff66ff33u, 0xff33ff33u, 0xff00ff33u, 0xffffcc33u,
    0xffcccc33u, 0xff99cc33u, 0xff66cc33u, 0xff33cc33u, 0xff00cc33u, 0xffff9933u, 0xffcc9933u, 0xff999933u,
    0xff669933u, 0xff339933u, 0xff009933u, 0xffff6633u, 0xffcc6633u, 0xff996633u, 0xff666633u, 0xff336633u,
    0xff006633u, 0xffff3333u, 0xffcc3333u, 0xff993333u, 0xff663333u, 0xff333333u, 0xff003333u, 0xffff0033u,
    0xffcc0033u, 0xff990033u, 0xff660033u, 0xff330033u, 0xff000033u, 0xffffff00u, 0xffccff00u, 0xff99ff00u,
    0xff66ff00u, 0xff33ff00u, 0xff00ff00u, 0xffffcc00u, 0xffcccc00u, 0xff99cc00u, 0xff66cc00u, 0xff33cc00u,
    0xff00cc00u, 0xffff9900u, 0xffcc9900u, 0xff999900u, 0xff669900u, 0xff339900u, 0xff009900u, 0xffff6600u,
    0xffcc6600u, 0xff996600u, 0xff666600u, 0xff336600u, 0xff006600u, 0xffff3300u, 0xffcc3300u, 0xff993300u,
    0xff663300u, 0xff333300u, 0xff003300u, 0xffff0000u, 0xffcc0000u, 0xff990000u, 0xff660000u, 0xff330000u,
    0xff0000eeu, 0xff0000ddu, 0xff0000bbu, 0xff0000aau, 0xff000088u, 0xff000077u, 0xff000055u, 0xff000044u,
    0xff000022u, 0xff000011u, 0xff00ee00u, 0xff00dd00u, 0xff00bb00u, 0xff00aa00u, 0xff008800u, 0xff007700u,
    0xff005500u, 0xff004400u, 0xff002200u, 0xff001100u, 0xffee0000u, 0xffdd0000u, 0xffbb0000u, 0xffaa0000u,
    0xff880000u, 0xff770000u, 0xff550000u, 0xff440000u, 0xff220000u, 0xff110000u, 0xffeeeeeeu, 0xffddddddu,
    0xffbbbbbbu, 0xffaaaaaau, 0xff888888u, 0xff777777u, 0xff555555u, 0xff444444u, 0xff222222u, 0xff111111u,
};

enum node_kind { NODE_TRN, NODE_GRP, NODE_SHP };

typedef struct node {
    int id, kind;
    size_t offset;   /* of its chunk, for messages */
    int hidden;
    int layer;       /* nTRN */
    int rot[3][3], t[3];
    int child_count; /* nTRN: 1; nGRP: n; nSHP: 0 */
    int *children;   /* nSHP: children[0] is the model */
    int visiting, done;
} node;

typedef struct layer {
    int id, hidden;
} layer;

typedef struct reader {
    const uint8_t *data;
    size_t size;
    const char *name;
    char *err;
    size_t err_size;
    char chunk[5];  /* the chunk being read, for messages */
    size_t offset;  /* its header's byte offset */
    vox_scene *out;
    node *nodes;
    int node_count, node_cap;
    layer *layers;
    int layer_count, layer_cap;
    int models_cap;
} reader;

/* The cursor in one chunk's content: reads fail past its end. */
typedef struct cursor {
    const uint8_t *p;
    size_t left;
} cursor;

static int fail(reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(reader *r, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (r->chunk[0])
        snprintf(r->err, r->err_size, "%s: chunk '%s' at byte %zu: %s", r->name, r->chunk, r->offset, msg);
    else
        snprintf(r->err, r->err_size, "%s: at byte %zu: %s", r->name, r->offset, msg);
    return -1;
}

static uint32_t le32(const uint8_t *p) { return p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

static int get_i32(reader *r, cursor *c, int32_t *v, const char *what)
{
    if (c->left < 4)
        return fail(r, "ends inside %s", what);
    *v = (int32_t)le32(c->p);
    c->p += 4;
    c->left -= 4;
    return 0;
}

/* A STRING: its bytes stay in the file; *len <= the bytes left. */
static int get_string(reader *r, cursor *c, const uint8_t **s, uint32_t *len)
{
    int32_t n = 0;
    if (get_i32(r, c, &n, "a string's length") != 0)
        return -1;
    if (n < 0 || (size_t)n > c->left)
        return fail(r, "a string of %d bytes, %zu left in the chunk", n, c->left);
    *s = c->p;
    *len = (uint32_t)n;
    c->p += n;
    c->left -= (size_t)n;
    return 0;
}

#define MATL_NUMBER_CHARS 32 /* a MATL number's text, NUL included: longer ones are errors */

/* The attributes this reader uses, from a DICT (others are skipped). */
typedef struct attrs {
    int hidden;
    int has_r, r;
    int has_t, t[3];
    int emit;        /* _type is _emit */
    /* MATL numbers as written ("" when absent): checked where the material id is known */
    char emit_value[MATL_NUMBER_CHARS], weight[MATL_NUMBER_CHARS], flux[MATL_NUMBER_CHARS];
} attrs;

static int key_is(const uint8_t *k, uint32_t n, const char *want) { return n == strlen(want) && memcmp(k, want, n) == 0; }

/* value as a NUL-terminated copy (attribute values that matter are short) */
static void value_text(const uint8_t *v, uint32_t n, char *out, size_t out_size)
{
    size_t m = n < out_size - 1 ? n : out_size - 1;
    memcpy(out, v, m);
    out[m] = '\0';
}

/* A number's text. Empty, too long for out or holding a NUL, it is made
 * text that parses as no number ("" is kept for an absent key). */
static void number_text(const uint8_t *v, uint32_t n, char *out, size_t out_size)
{
    value_text(v, n, out, out_size);
    if (n == 0)
        snprintf(out, out_size, " ");
    else if (n >= out_size || memchr(v, 0, n))
        memcpy(out + strlen(out) - (strlen(out) < 3 ? strlen(out) : 3), "...", 4);
}

static int get_dict(reader *r, cursor *c, attrs *a)
{
    memset(a, 0, sizeof *a);
    int32_t n = 0;
    if (get_i32(r, c, &n, "a dictionary's size") != 0)
        return -1;
    if (n < 0 || (size_t)n > c->left / 8) /* a pair is at least two lengths */
        return fail(r, "a dictionary of %d pairs, %zu bytes left in the chunk", n, c->left);
    for (int i = 0; i < n; i++) {
        const uint8_t *k, *v;
        uint32_t kn, vn;
        if (get_string(r, c, &k, &kn) != 0 || get_string(r, c, &v, &vn) != 0)
            return -1;
        char text[64], *end;
        value_text(v, vn, text, sizeof text);
        if (key_is(k, kn, "_hidden"))
            a->hidden = strcmp(text, "1") == 0;
        else if (key_is(k, kn, "_r")) {
            long rot = strtol(text, &end, 10);
            if (*end || rot < 0 || rot > 255)
                return fail(r, "rotation _r = '%s' is not a byte", text);
            a->has_r = 1;
            a->r = (int)rot;
        } else if (key_is(k, kn, "_t")) {
            if (sscanf(text, "%d %d %d", &a->t[0], &a->t[1], &a->t[2]) != 3)
                return fail(r, "translation _t = '%s' is not three integers", text);
            for (int j = 0; j < 3; j++)
                if (a->t[j] < -(1 << 20) || a->t[j] > (1 << 20))
                    return fail(r, "translation _t = '%s' lies beyond +-%d voxels", text, 1 << 20);
            a->has_t = 1;
        } else if (key_is(k, kn, "_type"))
            a->emit = strcmp(text, "_emit") == 0;
        else if (key_is(k, kn, "_emit"))
            number_text(v, vn, a->emit_value, sizeof a->emit_value);
        else if (key_is(k, kn, "_weight"))
            number_text(v, vn, a->weight, sizeof a->weight);
        else if (key_is(k, kn, "_flux"))
            number_text(v, vn, a->flux, sizeof a->flux);
    }
    return 0;
}

/* The packed rotation byte: bits 0-1 and 2-3 the column of the non-zero
 * entry in rows 0 and 1 (row 2 takes the remaining one), bits 4-6 the signs. */
static int unpack_rotation(reader *r, int bits, int m[3][3])
{
    int c0 = bits & 3, c1 = (bits >> 2) & 3;
    if (c0 > 2 || c1 > 2 || c0 == c1)
        return fail(r, "rotation byte %d names no rotation (rows 0 and 1 use columns %d and %d)", bits, c0, c1);
    int col[3] = {c0, c1, 3 - c0 - c1};
    memset(m, 0, 9 * sizeof(int));
    for (int row = 0; row < 3; row++)
        m[row][col[row]] = (bits >> (4 + row)) & 1 ? -1 : 1;
    return 0;
}

static void identity(int m[3][3])
{
    memset(m, 0, 9 * sizeof(int));
    m[0][0] = m[1][1] = m[2][2] = 1;
}

static node *add_node(reader *r, int id, int kind)
{
    if (r->node_count == r->node_cap) {
        int cap = r->node_cap ? 2 * r->node_cap : 16;
        node *n = realloc(r->nodes, (size_t)cap * sizeof *n);
        if (!n) {
            fail(r, "out of memory");
            return NULL;
        }
        r->nodes = n;
        r->node_cap = cap;
    }
    node *n = &r->nodes[r->node_count++];
    memset(n, 0, sizeof *n);
    n->id = id;
    n->kind = kind;
    n->offset = r->offset;
    identity(n->rot);
    return n;
}

static int get_children(reader *r, cursor *c, node *n, int count, int stride_dict)
{
    /* each child takes at least 4 bytes (8 with its dictionary): bounded by the chunk */
    if (count < 0 || (size_t)count > c->left / (stride_dict ? 8 : 4))
        return fail(r, "%d children, %zu bytes left in the chunk", count, c->left);
    n->children = malloc((size_t)(count ? count : 1) * sizeof(int));
    if (!n->children)
        return fail(r, "out of memory");
    n->child_count = count;
    for (int i = 0; i < count; i++) {
        attrs a;
        if (get_i32(r, c, &n->children[i], "a child id") != 0 || (stride_dict && get_dict(r, c, &a) != 0))
            return -1;
    }
    return 0;
}

static int read_trn(reader *r, cursor *c)
{
    int32_t id = 0, child = 0, reserved = 0, layer_id = 0, frames = 0;
    attrs a;
    if (get_i32(r, c, &id, "the node id") != 0 || get_dict(r, c, &a) != 0)
        return -1;
    node *n = add_node(r, id, NODE_TRN);
    if (!n || get_i32(r, c, &child, "the child id") != 0 || get_i32(r, c, &reserved, "the reserved id") != 0 ||
        get_i32(r, c, &layer_id, "the layer id") != 0 || get_i32(r, c, &frames, "the frame count") != 0)
        return -1;
    n->hidden = a.hidden;
    n->layer = layer_id;
    if (frames < 1)
        return fail(r, "transform node %d has %d frames (at least 1)", id, frames);
    n->children = malloc(sizeof(int));
    if (!n->children)
        return fail(r, "out of memory");
    n->children[0] = child;
    n->child_count = 1;
    /* frame 0 is the scene as MagicaVoxel shows it; later frames animate */
    if (get_dict(r, c, &a) != 0 || (a.has_r && unpack_rotation(r, a.r, n->rot) != 0))
        return -1;
    if (a.has_t)
        memcpy(n->t, a.t, sizeof n->t);
    return 0;
}

static int read_grp(reader *r, cursor *c)
{
    int32_t id = 0, count = 0;
    attrs a;
    if (get_i32(r, c, &id, "the node id") != 0 || get_dict(r, c, &a) != 0)
        return -1;
    node *n = add_node(r, id, NODE_GRP);
    if (!n || get_i32(r, c, &count, "the child count") != 0)
        return -1;
    n->hidden = a.hidden;
    return get_children(r, c, n, count, 0);
}

static int read_shp(reader *r, cursor *c)
{
    int32_t id = 0, count = 0;
    attrs a;
    if (get_i32(r, c, &id, "the node id") != 0 || get_dict(r, c, &a) != 0)
        return -1;
    node *n = add_node(r, id, NODE_SHP);
    if (!n || get_i32(r, c, &count, "the model count") != 0)
        return -1;
    n->hidden = a.hidden;
    if (count < 1)
        return fail(r, "shape node %d has %d models (at least 1)", id, count);
    /* models after the first are animation frames: only the first is kept */
    return get_children(r, c, n, count, 1);
}

static int read_layer(reader *r, cursor *c)
{
    int32_t id = 0;
    attrs a;
    if (get_i32(r, c, &id, "the layer id") != 0 || get_dict(r, c, &a) != 0)
        return -1;
    if (r->layer_count == r->layer_cap) {
        int cap = r->layer_cap ? 2 * r->layer_cap : 8;
        layer *l = realloc(r->layers, (size_t)cap * sizeof *l);
        if (!l)
            return fail(r, "out of memory");
        r->layers = l;
        r->layer_cap = cap;
    }
    r->layers[r->layer_count++] = (layer){id, a.hidden};
    return 0;
}

static int read_size(reader *r, cursor *c, int size[3])
{
    for (int a = 0; a < 3; a++) {
        int32_t v;
        if (get_i32(r, c, &v, "the model size") != 0)
            return -1;
        if (v < 1 || v > VOX_MAX_DIM)
            return fail(r, "model size %d on axis %c is outside 1..%d", v, "xyz"[a], VOX_MAX_DIM);
        size[a] = v;
    }
    return 0;
}

static int read_xyzi(reader *r, cursor *c, const int size[3])
{
    int32_t n = 0;
    if (get_i32(r, c, &n, "the voxel count") != 0)
        return -1;
    if (n < 0 || (size_t)n > c->left / 4)
        return fail(r, "%d voxels need %lld bytes, the chunk holds %zu", n, 4LL * n, c->left);
    for (int i = 0; i < n; i++) {
        const uint8_t *v = c->p + 4 * (size_t)i;
        if (v[0] >= size[0] || v[1] >= size[1] || v[2] >= size[2])
            return fail(r, "voxel %d at (%d %d %d) lies outside the model's size %d x %d x %d", i, v[0], v[1], v[2], size[0], size[1], size[2]);
        if (v[3] == 0)
            return fail(r, "voxel %d at (%d %d %d) has palette index 0, which means empty (indices are 1..255)", i, v[0], v[1], v[2]);
    }
    vox_scene *s = r->out;
    if (s->model_count == r->models_cap) {
        int cap = r->models_cap ? 2 * r->models_cap : 4;
        vox_model *m = realloc(s->models, (size_t)cap * sizeof *m);
        if (!m)
            return fail(r, "out of memory");
        s->models = m;
        r->models_cap = cap;
    }
    vox_model *m = &s->models[s->model_count++];
    memcpy(m->size, size, sizeof m->size);
    m->count = n;
    m->xyzi = c->p;
    return 0;
}

static int read_rgba(reader *r, cursor *c)
{
    if (c->left < 1024)
        return fail(r, "a palette needs 1024 bytes, the chunk holds %zu", c->left);
    /* entry i is palette index i + 1; the 256th entry has no index */
    for (int i = 0; i < 255; i++)
        r->out->palette[i + 1] = le32(c->p + 4 * i);
    return 0;
}

/* A MATL number: absent is 0; else a finite decimal >= 0. The text is shown
 * with bytes outside printable ASCII as '?' (it is the file's, not ours). */
static int matl_number(reader *r, int id, const char *key, const char *text, double *out)
{
    char *end;
    *out = 0;
    if (!text[0])
        return 0;
    double v = strtod(text, &end);
    if (*end == '\0' && isfinite(v) && v >= 0) {
        *out = v;
        return 0;
    }
    char shown[MATL_NUMBER_CHARS];
    size_t n = strlen(text);
    for (size_t i = 0; i <= n; i++)
        shown[i] = i < n && (text[i] < 0x20 || text[i] > 0x7e) ? '?' : text[i];
    return fail(r, "material %d: %s = '%s' is not a finite number >= 0", id, key, shown);
}

static int read_matl(reader *r, cursor *c)
{
    int32_t id = 0;
    attrs a;
    if (get_i32(r, c, &id, "the material id") != 0 || get_dict(r, c, &a) != 0)
        return -1;
    if (id < 0 || id > 256)
        return fail(r, "material id %d is outside 0..256", id);
    /* MagicaVoxel writes ids 0..256; only 1..255 name palette colours a voxel can use */
    if (id < 1 || id > 255 || !a.emit)
        return 0;
    /* the strength is _emit; files of MagicaVoxel 0.99.1 (the format's
     * description) give it as _weight */
    int weight = !a.emit_value[0] && a.weight[0];
    const char *key = weight ? "_weight" : "_emit";
    double strength, flux;
    if (matl_number(r, id, key, weight ? a.weight : a.emit_value, &strength) != 0 || matl_number(r, id, "_flux", a.flux, &flux) != 0)
        return -1;
    double emit = strength * (1 + flux);
    if (emit > VOX_EMIT_MAX)
        return fail(r, "material %d: %s x (1 + _flux) = %g x (1 + %g) = %g, more than %d", id, key, strength, flux, emit, VOX_EMIT_MAX);
    r->out->emissive[id] = (float)emit;
    return 0;
}

static int by_id(const void *a, const void *b)
{
    const node *x = a, *y = b;
    return x->id < y->id ? -1 : x->id > y->id;
}

/* nodes are sorted by id (build_instances) */
static int find_node(const reader *r, int id)
{
    node key = {.id = id};
    const node *n = bsearch(&key, r->nodes, (size_t)r->node_count, sizeof key, by_id);
    return n ? (int)(n - r->nodes) : -1;
}

static int layer_hidden(const reader *r, int id)
{
    for (int i = 0; i < r->layer_count; i++)
        if (r->layers[i].id == id)
            return r->layers[i].hidden;
    return 0;
}

static int add_instance(reader *r, int model, int rot[3][3], const int t[3], int *cap)
{
    vox_scene *s = r->out;
    if (s->instance_count == *cap) {
        int ncap = *cap ? 2 * *cap : 8;
        vox_instance *in = realloc(s->instances, (size_t)ncap * sizeof *in);
        if (!in)
            return fail(r, "out of memory");
        s->instances = in;
        *cap = ncap;
    }
    vox_instance *in = &s->instances[s->instance_count++];
    in->model = model;
    memcpy(in->rot, rot, sizeof in->rot);
    memcpy(in->t, t, sizeof in->t);
    return 0;
}

/* Walks the graph from node index i under the transform (rot, t). Each
 * node is reached once: a second visit is a cycle or a shared child, which
 * MagicaVoxel never writes. */
#define MAX_DEPTH 256 /* MagicaVoxel nests a few levels; the bound keeps the recursion's stack small */

static int walk(reader *r, int i, int rot[3][3], const int t[3], int *cap, int depth)
{
    node *n = &r->nodes[i];
    r->offset = n->offset;
    snprintf(r->chunk, sizeof r->chunk, "%s", n->kind == NODE_TRN ? "nTRN" : n->kind == NODE_GRP ? "nGRP" : "nSHP");
    if (depth > MAX_DEPTH)
        return fail(r, "node %d lies deeper than %d nodes in the scene graph", n->id, MAX_DEPTH);
    if (n->visiting || n->done)
        return fail(r, "node %d is reached twice: the scene graph has a cycle or a shared node", n->id);
    if (n->hidden || (n->kind == NODE_TRN && layer_hidden(r, n->layer)))
        return 0; /* hidden nodes and layers are not shown */
    n->visiting = 1;
    int rc = 0;
    if (n->kind == NODE_SHP) {
        int model = n->children[0];
        if (model < 0 || model >= r->out->model_count)
            return fail(r, "shape node %d uses model %d, the file has %d", n->id, model, r->out->model_count);
        rc = add_instance(r, model, rot, t, cap);
    } else {
        int nrot[3][3], nt[3];
        if (n->kind == NODE_TRN) { /* world = rot * (R p + T) + t */
            for (int a = 0; a < 3; a++) {
                nt[a] = t[a];
                for (int b = 0; b < 3; b++) {
                    nt[a] += rot[a][b] * n->t[b];
                    nrot[a][b] = 0;
                    for (int k = 0; k < 3; k++)
                        nrot[a][b] += rot[a][k] * n->rot[k][b];
                }
            }
        } else {
            memcpy(nrot, rot, sizeof nrot);
            memcpy(nt, t, sizeof nt);
        }
        for (int k = 0; rc == 0 && k < n->child_count; k++) {
            int child = find_node(r, n->children[k]);
            r->offset = n->offset;
            snprintf(r->chunk, sizeof r->chunk, "%s", n->kind == NODE_TRN ? "nTRN" : "nGRP");
            if (child < 0)
                return fail(r, "node %d names child node %d, which the file does not have", n->id, n->children[k]);
            int want_trn = n->kind == NODE_GRP, is_trn = r->nodes[child].kind == NODE_TRN;
            if (want_trn != is_trn)
                return fail(r, "node %d's child %d is a %s node (a %s's children are %s)", n->id, n->children[k], is_trn ? "transform" : "group or shape",
                            want_trn ? "group" : "transform", want_trn ? "transforms" : "groups or shapes");
            rc = walk(r, child, nrot, nt, cap, depth + 1);
        }
    }
    n->visiting = 0;
    n->done = 1;
    return rc;
}

static int build_instances(reader *r)
{
    int rot[3][3], t[3] = {0, 0, 0}, cap = 0;
    identity(rot);
    if (r->node_count == 0) {
        /* no scene graph (files before MagicaVoxel 0.99): model 0 is the
         * scene; further models are animation frames (PACK) */
        r->chunk[0] = '\0';
        r->offset = 0;
        return r->out->model_count ? add_instance(r, 0, rot, t, &cap) : fail(r, "the file holds no model (SIZE and XYZI chunks)");
    }
    qsort(r->nodes, (size_t)r->node_count, sizeof *r->nodes, by_id);
    for (int i = 1; i < r->node_count; i++)
        if (r->nodes[i].id == r->nodes[i - 1].id) {
            node *second = r->nodes[i].offset > r->nodes[i - 1].offset ? &r->nodes[i] : &r->nodes[i - 1];
            r->offset = second->offset;
            snprintf(r->chunk, sizeof r->chunk, "%s", second->kind == NODE_TRN ? "nTRN" : second->kind == NODE_GRP ? "nGRP" : "nSHP");
            return fail(r, "node id %d is used twice", second->id);
        }
    int root = find_node(r, 0);
    if (root < 0 || r->nodes[root].kind != NODE_TRN) {
        r->chunk[0] = '\0';
        return fail(r, "the scene graph has no root transform node (nTRN with id 0)");
    }
    return walk(r, root, rot, t, &cap, 0);
}

static int read_chunk(reader *r, const char *id, cursor *c, int *pending_size, int size[3])
{
    if (strcmp(id, "SIZE") == 0) {
        if (read_size(r, c, size) != 0)
            return -1;
        *pending_size = 1;
        return 0;
    }
    if (strcmp(id, "XYZI") == 0) {
        if (!*pending_size)
            return fail(r, "voxels without a SIZE chunk before them");
        *pending_size = 0;
        return read_xyzi(r, c, size);
    }
    if (strcmp(id, "RGBA") == 0)
        return read_rgba(r, c);
    if (strcmp(id, "MATL") == 0)
        return read_matl(r, c);
    if (strcmp(id, "nTRN") == 0)
        return read_trn(r, c);
    if (strcmp(id, "nGRP") == 0)
        return read_grp(r, c);
    if (strcmp(id, "nSHP") == 0)
        return read_shp(r, c);
    if (strcmp(id, "LAYR") == 0)
        return read_layer(r, c);
    return 0; /* PACK, MATT, rOBJ, rCAM, NOTE, IMAP: nothing to place */
}

static void chunk_id(const uint8_t *p, char out[5])
{
    for (int i = 0; i < 4; i++)
        out[i] = p[i] >= 32 && p[i] < 127 ? (char)p[i] : '?';
    out[4] = '\0';
}

static int read_main(reader *r)
{
    const uint8_t *d = r->data;
    r->offset = 0;
    size_t head = r->size < 4 ? r->size : 4;
    if (r->size == 0)
        return fail(r, "the file is empty: a MagicaVoxel file starts with 'VOX '");
    if (memcmp(d, "VOX ", head) != 0)
        return fail(r, "not a MagicaVoxel file (it does not start with 'VOX ')");
    if (r->size < 20) { /* "VOX " and its start both: cut off, not another format */
        r->offset = r->size;
        return fail(r, "the file is truncated: it ends after %zu bytes, before 'VOX ', its version and MAIN's chunk header (20 bytes) are whole",
                    r->size);
    }
    r->offset = 8;
    chunk_id(d + 8, r->chunk);
    if (memcmp(d + 8, "MAIN", 4) != 0)
        return fail(r, "the first chunk is not MAIN");
    uint64_t content = le32(d + 12), children = le32(d + 16);
    if (20 + content + children > r->size)
        return fail(r, "content %llu and children %llu bytes run past the file's end (%zu bytes)", (unsigned long long)content,
                    (unsigned long long)children, r->size);
    size_t pos = 20 + (size_t)content, end = pos + (size_t)children;
    int pending = 0, size[3] = {0, 0, 0};
    while (pos < end) {
        r->offset = pos;
        r->chunk[0] = '\0';
        if (end - pos < 12)
            return fail(r, "a chunk header needs 12 bytes, %zu are left in MAIN", end - pos);
        chunk_id(d + pos, r->chunk);
        uint64_t n = le32(d + pos + 4), m = le32(d + pos + 8);
        if (12 + n + m > end - pos)
            return fail(r, "content %llu and children %llu bytes run past MAIN's end (%zu bytes left)", (unsigned long long)n, (unsigned long long)m,
                        end - pos - 12);
        cursor c = {d + pos + 12, (size_t)n};
        if (read_chunk(r, r->chunk, &c, &pending, size) != 0)
            return -1;
        pos += 12 + (size_t)n + (size_t)m;
    }
    if (pending) {
        r->offset = end;
        r->chunk[0] = '\0';
        return fail(r, "a SIZE chunk has no XYZI chunk after it");
    }
    return build_instances(r);
}

int vox_read(const uint8_t *data, size_t size, const char *name, vox_scene *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    memcpy(out->palette, vox_default_palette, sizeof out->palette);
    reader r = {.data = data, .size = size, .name = name, .err = err, .err_size = err_size, .out = out};
    int rc = read_main(&r);
    for (int i = 0; i < r.node_count; i++)
        free(r.nodes[i].children);
    free(r.nodes);
    free(r.layers);
    if (rc != 0)
        vox_free(out);
    return rc;
}

void vox_free(vox_scene *s)
{
    free(s->models);
    free(s->instances);
    s->models = NULL;
    s->instances = NULL;
    s->model_count = s->instance_count = 0;
}
