#define _POSIX_C_SOURCE 200809L
/* The vox scene: the MagicaVoxel reader on real and on synthetic (broken)
 * files, the edit journal (crash safety by kill -9), and rendering of a
 * model and of an edited world. Usage: PROGRAM CASE. */
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdint.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <zlib.h>
#include "harness.h"
#include "voxrg/edits.h"
#include "voxrg/world.h"
#include "vox_read.h"

#ifndef VOX_DIR
#define VOX_DIR "../shared/vox"
#endif

/* ---- building .vox files in memory ---- */

typedef struct buf {
    uint8_t *d;
    size_t n, cap;
} buf;

static void put(buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->d = realloc(b->d, b->cap);
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}
static void put32(buf *b, int32_t v)
{
    uint8_t p[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    put(b, p, 4);
}
static void put_str(buf *b, const char *s)
{
    put32(b, (int32_t)strlen(s));
    put(b, s, strlen(s));
}
/* a dictionary of n "key", "value" pairs */
static void put_dict(buf *b, int n, const char *const *kv)
{
    put32(b, n);
    for (int i = 0; i < 2 * n; i++)
        put_str(b, kv[i]);
}
static void chunk(buf *b, const char *id, const buf *content)
{
    put(b, id, 4);
    put32(b, (int32_t)content->n);
    put32(b, 0);
    put(b, content->d, content->n);
}
/* "VOX " 150, MAIN holding the children */
static buf file_of(const buf *children)
{
    buf f = {0};
    put(&f, "VOX ", 4);
    put32(&f, 150);
    put(&f, "MAIN", 4);
    put32(&f, 0);
    put32(&f, (int32_t)children->n);
    put(&f, children->d, children->n);
    return f;
}
static void model(buf *b, int sx, int sy, int sz, int n, const uint8_t *xyzi)
{
    buf c = {0};
    put32(&c, sx), put32(&c, sy), put32(&c, sz);
    chunk(b, "SIZE", &c);
    c.n = 0;
    put32(&c, n);
    put(&c, xyzi, 4 * (size_t)n);
    chunk(b, "XYZI", &c);
    free(c.d);
}
static void trn(buf *b, int id, int child, int layer, const char *r, const char *t, int hidden)
{
    buf c = {0};
    put32(&c, id);
    const char *h[] = {"_hidden", "1"};
    put_dict(&c, hidden, h);
    put32(&c, child), put32(&c, -1), put32(&c, layer), put32(&c, 1);
    const char *kv[4];
    int n = 0;
    if (r)
        kv[2 * n] = "_r", kv[2 * n + 1] = r, n++;
    if (t)
        kv[2 * n] = "_t", kv[2 * n + 1] = t, n++;
    put_dict(&c, n, kv);
    chunk(b, "nTRN", &c);
    free(c.d);
}
static void grp(buf *b, int id, int n, const int *children)
{
    buf c = {0};
    put32(&c, id);
    put_dict(&c, 0, NULL);
    put32(&c, n);
    for (int i = 0; i < n; i++)
        put32(&c, children[i]);
    chunk(b, "nGRP", &c);
    free(c.d);
}
static void shp(buf *b, int id, int model_id)
{
    buf c = {0};
    put32(&c, id);
    put_dict(&c, 0, NULL);
    put32(&c, 1);
    put32(&c, model_id);
    put_dict(&c, 0, NULL);
    chunk(b, "nSHP", &c);
    free(c.d);
}

static const uint8_t two_voxels[] = {0, 0, 0, 1, 1, 2, 3, 9};

/* A scene graph: root T0 -> G1 -> {T2 -> S3 (model 0), T4 -> S5 (model 1),
 * T6 hidden -> S7, T8 in hidden layer 1 -> S9}; T2 translates, T4 rotates. */
static buf scene_graph_file(void)
{
    buf b = {0};
    model(&b, 2, 3, 4, 2, two_voxels);
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 1, 0, NULL, NULL, 0);
    int kids[] = {2, 4, 6, 8};
    grp(&b, 1, 4, kids);
    trn(&b, 2, 3, 0, NULL, "10 -20 30", 0);
    shp(&b, 3, 0);
    char r[16];
    snprintf(r, sizeof r, "%d", (1 << 0) | (2 << 2) | (0 << 4) | (1 << 5) | (1 << 6)); /* the format's example */
    trn(&b, 4, 5, 0, r, "1 2 3", 0);
    shp(&b, 5, 1);
    trn(&b, 6, 7, 0, NULL, NULL, 1);
    shp(&b, 7, 0);
    trn(&b, 8, 9, 1, NULL, NULL, 0);
    shp(&b, 9, 0);
    buf layer = {0};
    put32(&layer, 1);
    const char *h[] = {"_hidden", "1"};
    put_dict(&layer, 1, h);
    put32(&layer, -1);
    chunk(&b, "LAYR", &layer);
    free(layer.d);
    buf f = file_of(&b);
    free(b.d);
    return f;
}

static void test_scene_graph(void)
{
    buf f = scene_graph_file();
    vox_scene s;
    char err[512];
    CHECK(vox_read(f.d, f.n, "sg.vox", &s, err, sizeof err) == 0, "%s", err);
    CHECK(s.model_count == 2, "%d models", s.model_count);
    CHECK(s.instance_count == 2, "%d instances: hidden nodes and layers are not shown", s.instance_count);
    if (s.instance_count == 2) {
        const vox_instance *a = &s.instances[0], *b = &s.instances[1];
        CHECK(a->model == 0 && a->t[0] == 10 && a->t[1] == -20 && a->t[2] == 30 && a->rot[0][0] == 1 && a->rot[1][1] == 1 && a->rot[2][2] == 1,
              "instance 0: model %d at %d %d %d", a->model, a->t[0], a->t[1], a->t[2]);
        const int want[3][3] = {{0, 1, 0}, {0, 0, -1}, {-1, 0, 0}};
        CHECK(b->model == 1 && memcmp(b->rot, want, sizeof want) == 0 && b->t[0] == 1 && b->t[2] == 3, "instance 1: rotation or translation");
    }
    CHECK(s.palette[1] == vox_default_palette[1] && s.palette[1] == 0xffffffffu, "no RGBA chunk: the default palette");
    vox_free(&s);
    free(f.d);
}

/* vox_read must fail with a message holding each of the words */
static void expect_error(const buf *f, const char *what, const char *w1, const char *w2)
{
    vox_scene s;
    char err[512] = "";
    int rc = vox_read(f->d, f->n, "bad.vox", &s, err, sizeof err);
    CHECK(rc != 0, "%s: accepted", what);
    if (rc == 0) {
        vox_free(&s);
        return;
    }
    CHECK(strstr(err, "bad.vox") && strstr(err, w1) && (!w2 || strstr(err, w2)), "%s: message '%s' lacks '%s' / '%s'", what, err, w1, w2 ? w2 : "");
}

static buf one_model(int sx, int sy, int sz, int n, const uint8_t *xyzi)
{
    buf b = {0};
    model(&b, sx, sy, sz, n, xyzi);
    buf f = file_of(&b);
    free(b.d);
    return f;
}

static void test_bad_files(void)
{
    buf f = one_model(2, 3, 4, 2, two_voxels);
    vox_scene s;
    char err[512];
    CHECK(vox_read(f.d, f.n, "ok.vox", &s, err, sizeof err) == 0, "the good file: %s", err);
    vox_free(&s);
    /* every truncation of it fails cleanly (ASan: no read past the end) */
    for (size_t n = 0; n < f.n; n++) {
        buf t = {f.d, n, n};
        expect_error(&t, "truncated", "bad.vox", NULL);
    }
    /* cut off in the header: truncated (its size said), not another format */
    for (size_t n = 1; n < 20; n++) {
        buf t = {f.d, n, n};
        char size[64];
        snprintf(size, sizeof size, "at byte %zu: the file is truncated: it ends after %zu bytes", n, n);
        expect_error(&t, "cut off in the header", size, "(20 bytes)");
    }
    f.d[0] = 'X';
    expect_error(&f, "wrong magic", "not a MagicaVoxel file", "at byte 0");
    free(f.d);

    f = one_model(2, 3, 4, 2, two_voxels);
    f.d[20 + 4] = 0xff, f.d[20 + 5] = 0xff, f.d[20 + 6] = 0xff, f.d[20 + 7] = 0x7f; /* SIZE's content size */
    expect_error(&f, "chunk past the end", "chunk 'SIZE' at byte 20", "run past");
    free(f.d);

    f = one_model(300, 3, 4, 2, two_voxels);
    expect_error(&f, "huge dimensions", "chunk 'SIZE' at byte 20", "outside 1..256");
    free(f.d);

    const uint8_t index0[] = {0, 0, 0, 0};
    f = one_model(2, 3, 4, 1, index0);
    expect_error(&f, "palette index 0", "chunk 'XYZI' at byte 44", "palette index 0");
    free(f.d);

    const uint8_t outside[] = {2, 0, 0, 5};
    f = one_model(2, 3, 4, 1, outside);
    expect_error(&f, "voxel outside the model", "chunk 'XYZI'", "outside the model's size");
    free(f.d);

    f = one_model(2, 3, 4, 2, two_voxels);
    f.d[20 + 24 + 12] = 0xff, f.d[20 + 24 + 13] = 0xff, f.d[20 + 24 + 14] = 0xff, f.d[20 + 24 + 15] = 0x0f; /* XYZI's count */
    expect_error(&f, "voxel count past the chunk", "chunk 'XYZI' at byte 44", "bytes");
    free(f.d);

    buf b = {0}, c = {0};
    model(&b, 1, 1, 1, 1, two_voxels);
    put(&c, "\1\2\3\4", 4);
    chunk(&b, "RGBA", &c);
    f = file_of(&b);
    expect_error(&f, "short palette", "chunk 'RGBA'", "1024 bytes");
    free(f.d), free(b.d), free(c.d);

    /* a cycle: T0 -> G1 -> T2 -> G1 */
    b = (buf){0};
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 1, 0, NULL, NULL, 0);
    int kid = 2;
    grp(&b, 1, 1, &kid);
    trn(&b, 2, 1, 0, NULL, NULL, 0);
    f = file_of(&b);
    expect_error(&f, "cycle", "chunk 'nGRP'", "reached twice");
    free(f.d), free(b.d);

    /* a dangling child: T0 -> 7 */
    b = (buf){0};
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 7, 0, NULL, NULL, 0);
    f = file_of(&b);
    expect_error(&f, "dangling node id", "chunk 'nTRN' at byte 64", "child node 7");
    free(f.d), free(b.d);

    /* a shape of a model the file lacks, a duplicate id, a bad rotation */
    b = (buf){0};
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 1, 0, NULL, NULL, 0);
    shp(&b, 1, 5);
    f = file_of(&b);
    expect_error(&f, "model out of range", "chunk 'nSHP'", "model 5");
    free(f.d), free(b.d);
    b = (buf){0};
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 1, 0, NULL, NULL, 0);
    shp(&b, 1, 0);
    shp(&b, 1, 0);
    f = file_of(&b);
    expect_error(&f, "duplicate node", "chunk 'nSHP'", "used twice");
    free(f.d), free(b.d);
    b = (buf){0};
    model(&b, 1, 1, 1, 1, two_voxels);
    trn(&b, 0, 1, 0, "15", NULL, 0); /* rows 0 and 1 both column 3 */
    shp(&b, 1, 0);
    f = file_of(&b);
    expect_error(&f, "bad rotation", "chunk 'nTRN'", "rotation byte 15");
    free(f.d), free(b.d);
}

/* A one-voxel model of palette index 9 and a MATL for material 9 of n
 * key-value pairs: MATL's header is at byte 64. */
static buf matl_file(int n, const char *const *kv)
{
    static const uint8_t voxel9[] = {0, 0, 0, 9};
    buf b = {0}, c = {0};
    model(&b, 1, 1, 1, 1, voxel9);
    put32(&c, 9);
    put_dict(&c, n, kv);
    chunk(&b, "MATL", &c);
    buf f = file_of(&b);
    free(b.d), free(c.d);
    return f;
}

static float emissive_of(int n, const char *const *kv)
{
    buf f = matl_file(n, kv);
    vox_scene s;
    char err[512] = "";
    float e = -1;
    if (vox_read(f.d, f.n, "ok.vox", &s, err, sizeof err) == 0) {
        e = s.emissive[9];
        vox_free(&s);
    }
    CHECK(e >= 0, "%s = %s: %s", kv[2], kv[3], err);
    free(f.d);
    return e;
}

/* MATL emission: _type _emit materials emit _emit (else _weight) x (1 +
 * _flux); a value that is no finite number >= 0, or an emission over
 * VOX_EMIT_MAX, is an error naming the file, the chunk's byte and the
 * material (not a silent 0, nor a NaN or infinity sent to the GPU). */
static void test_emit_values(void)
{
    const char *emit_flux[] = {"_type", "_emit", "_emit", "0.5", "_flux", "1"};
    CHECK(emissive_of(3, emit_flux) == 1.0f, "_emit 0.5, _flux 1: 0.5 x 2");
    const char *weight[] = {"_type", "_emit", "_weight", "0.25"};
    CHECK(emissive_of(2, weight) == 0.25f, "_weight: the strength of files without _emit");
    const char *diffuse[] = {"_type", "_diffuse", "_emit", "0.5"};
    CHECK(emissive_of(2, diffuse) == 0.0f, "a _diffuse material does not emit");
    const char *at_max[] = {"_type", "_emit", "_emit", "5", "_flux", "4"};
    CHECK(emissive_of(3, at_max) == (float)VOX_EMIT_MAX, "5 x (1 + 4) is the most allowed");

    static const struct {
        const char *key, *value, *says;
    } bad[] = {
        {"_emit", "nan", "_emit = 'nan' is not a finite number >= 0"},
        {"_emit", "inf", "_emit = 'inf' is not a finite number >= 0"},
        {"_emit", "-1", "_emit = '-1' is not a finite number >= 0"},
        {"_emit", "1e999", "_emit = '1e999' is not a finite number"},
        {"_emit", "bright", "_emit = 'bright' is not a finite number"},
        {"_emit", "", "_emit = ' ' is not a finite number"},
        {"_emit", "0.50000000000000000000000000000000001", "is not a finite number"}, /* longer than the reader keeps */
        {"_emit", "1e6", "_emit x (1 + _flux) = 1e+06 x (1 + 0) = 1e+06, more than 25"},
        {"_flux", "-2", "_flux = '-2' is not a finite number >= 0"},
        {"_flux", "nan", "_flux = 'nan' is not a finite number >= 0"},
        {"_flux", "\033[2J", "_flux = '?[2J' is not"}, /* the terminal sees no escape */
        {"_flux", "30", "= 1 x (1 + 30) = 31, more than 25"},
        {"_weight", "-0.5", "_weight = '-0.5' is not a finite number >= 0"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *kv[] = {"_type", "_emit", "_emit", "1", bad[i].key, bad[i].value};
        int n = 3;
        if (strcmp(bad[i].key, "_emit") == 0)
            kv[3] = bad[i].value, n = 2;
        else if (strcmp(bad[i].key, "_weight") == 0)
            kv[2] = "_weight", kv[3] = bad[i].value, n = 2;
        buf f = matl_file(n, kv);
        char what[128];
        snprintf(what, sizeof what, "%s = '%s'", bad[i].key, bad[i].value);
        expect_error(&f, what, "chunk 'MATL' at byte 64: material 9: ", bad[i].says);
        free(f.d);
    }
}

static uint8_t *read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *d = malloc((size_t)size + 1);
    *n = fread(d, 1, (size_t)size, f);
    fclose(f);
    return d;
}

static int vox_dir_or_skip(void)
{
    struct stat st;
    if (stat(VOX_DIR "/chr_knight.vox", &st) != 0) {
        printf("skipped: %s/chr_knight.vox is missing (VRG_VOX_DIR: the MagicaVoxel test models)\n", VOX_DIR);
        return SKIP;
    }
    return 0;
}

static int test_real_files(void)
{
    if (vox_dir_or_skip())
        return SKIP;
    static const struct {
        const char *name;
        int models, sx, sy, sz;
        int default_palette;
    } files[] = {{"chr_knight.vox", 1, 20, 21, 20, 0}, {"T-Rex.vox", 8, 24, 24, 26, 0}, {"monu10.vox", 1, 72, 72, 126, 0},
                 {"menger.vox", 1, 81, 81, 81, 1},      {"maze.vox", 1, 100, 100, 100, 1}};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[512], err[512];
        snprintf(path, sizeof path, "%s/%s", VOX_DIR, files[i].name);
        size_t n;
        uint8_t *d = read_file(path, &n);
        CHECK(d, "cannot read %s", path);
        if (!d)
            continue;
        vox_scene s;
        CHECK(vox_read(d, n, path, &s, err, sizeof err) == 0, "%s", err);
        CHECK(s.model_count == files[i].models && s.instance_count == 1, "%s: %d models, %d instances (animation frames are not placed)", path,
              s.model_count, s.instance_count);
        if (s.model_count)
            CHECK(s.models[0].size[0] == files[i].sx && s.models[0].size[1] == files[i].sy && s.models[0].size[2] == files[i].sz, "%s: size", path);
        CHECK((memcmp(s.palette, vox_default_palette, sizeof s.palette) == 0) == files[i].default_palette, "%s: palette", path);
        vox_free(&s);
        free(d);
    }
    return 0;
}

/* ---- the edit journal ---- */

static char tmpdir[256];

static void make_tmpdir(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/vrg_edits_XXXXXX");
    CHECK(mkdtemp(tmpdir) != NULL, "mkdtemp");
}

static vrg_world *small_world(void)
{
    vrg_world *w = vrg_world_create(1, 1);
    vrg_block chunk[VRG_CHUNK_VOXELS];
    memset(chunk, VRG_BLOCK_STONE, sizeof chunk);
    vrg_world_put_chunk(w, 0, 0, 0, chunk);
    return w;
}

static void test_edits_roundtrip(void)
{
    make_tmpdir();
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/g.ini.edits", tmpdir);
    vrg_world *w = small_world();
    vrg_edits *e = vrg_edits_open(path, "test seed=1", w, err, sizeof err);
    CHECK(e, "%s", err);
    CHECK(vrg_edits_set(e, w, 1, 2, 3, VRG_BLOCK_AIR, err, sizeof err) == 0, "%s", err);
    CHECK(vrg_edits_set(e, w, 4, 5, 6, VRG_BLOCK_RED, err, sizeof err) == 0, "%s", err);
    CHECK(vrg_world_block(w, 4, 5, 6) == VRG_BLOCK_RED, "the world changes with the edit");
    CHECK(vrg_edits_undo(e, w, err, sizeof err) == 0 && vrg_world_block(w, 4, 5, 6) == VRG_BLOCK_STONE, "undo restores the old block");
    CHECK(vrg_edits_redo(e, w, err, sizeof err) == 0 && vrg_world_block(w, 4, 5, 6) == VRG_BLOCK_RED, "redo");
    CHECK(vrg_edits_undo(e, w, err, sizeof err) == 0, "undo again");
    CHECK(vrg_edits_redo(e, w, err, sizeof err) == 0 && vrg_edits_redo(e, w, err, sizeof err) == 1, "nothing more to redo");
    CHECK(vrg_edits_undo(e, w, err, sizeof err) == 0, "undo (the file ends undone)");
    vrg_edits_close(e);
    vrg_world_destroy(w);

    /* a fresh world gets the edits back, from the file alone */
    w = small_world();
    e = vrg_edits_open(path, "test seed=1", w, err, sizeof err);
    CHECK(e && vrg_edits_records(e) == 7, "records: %d (%s)", e ? vrg_edits_records(e) : -1, err);
    if (e) {
        vrg_edits_apply_world(e, w);
        CHECK(vrg_world_block(w, 1, 2, 3) == VRG_BLOCK_AIR && vrg_world_block(w, 4, 5, 6) == VRG_BLOCK_STONE, "replayed state");
        CHECK(vrg_edits_redo(e, w, err, sizeof err) == 0 && vrg_world_block(w, 4, 5, 6) == VRG_BLOCK_RED, "redo after reopening");
        vrg_block chunk[VRG_CHUNK_VOXELS];
        memset(chunk, VRG_BLOCK_DIRT, sizeof chunk);
        CHECK(vrg_edits_apply_chunk(e, 0, 0, 0, chunk) == 2 && chunk[vrg_chunk_index(4, 5, 6)] == VRG_BLOCK_RED &&
                  chunk[vrg_chunk_index(1, 2, 3)] == VRG_BLOCK_AIR,
              "a regenerated chunk gets its edits");
        CHECK(vrg_edits_apply_chunk(e, 1, 0, 0, chunk) == 0, "another chunk none");
        vrg_edits_close(e);
    }
    /* another world's key is refused, naming the file */
    e = vrg_edits_open(path, "test seed=2", w, err, sizeof err);
    CHECK(!e && strstr(err, path) && strstr(err, "another world") && strstr(err, "test seed=1"), "key mismatch: '%s'", err);
    vrg_edits_close(e);
    /* a damaged record in the middle is reported at its offset */
    FILE *f = fopen(path, "r+b");
    long hdr = 8 + 4 + (long)strlen("test seed=1") + 4;
    fseek(f, hdr + 20 + 5, SEEK_SET);
    fputc(0x55, f);
    fclose(f);
    e = vrg_edits_open(path, "test seed=1", w, err, sizeof err);
    char at[64];
    snprintf(at, sizeof at, "at byte %ld", hdr + 20);
    CHECK(!e && strstr(err, at) && strstr(err, "damaged"), "corrupt record: '%s'", err);
    vrg_edits_close(e);
    vrg_world_destroy(w);
}

/* A journal from another world whose key holds a terminal escape and a
 * forged line: the refusal quotes the key escaped, no control byte in it. */
static void test_edits_foreign_key(void)
{
    make_tmpdir();
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/foreign.edits", tmpdir);
    unlink(path);
    vrg_world *w = small_world();
    vrg_edits *e = vrg_edits_open(path, "x\x1b[31mred\nother.ini:1: error[VRG-E001]: forged", w, err, sizeof err);
    CHECK(e && vrg_edits_set(e, w, 1, 2, 3, VRG_BLOCK_AIR, err, sizeof err) == 0, "%s", err);
    vrg_edits_close(e);
    e = vrg_edits_open(path, "test seed=1", w, err, sizeof err);
    int controls = 0;
    for (const char *c = err; *c; c++)
        controls += (unsigned char)*c < 0x20 || *c == 0x7f;
    CHECK(!e && strstr(err, "another world ('x\\x1b[31mred\\nother.ini:1: error[VRG-E001]: forged'), this scene is 'test seed=1'") && !controls,
          "key mismatch: '%s'", err);
    vrg_edits_close(e);
    vrg_world_destroy(w);
}

/* op i of the writer's fixed sequence, in a 4 x 4 x 4 corner of chunk 0 */
static int run_op(vrg_edits *e, vrg_world *w, long i, char *err, size_t n)
{
    if (i % 5 == 3)
        return vrg_edits_undo(e, w, err, n) < 0 ? -1 : 0;
    if (i % 7 == 5)
        return vrg_edits_redo(e, w, err, n) < 0 ? -1 : 0;
    return vrg_edits_set(e, w, (int)(i % 4), (int)(i / 4 % 4), (int)(i / 16 % 4), (vrg_block)(1 + i % (VRG_BLOCK_COUNT - 1)), err, n);
}

/* The blocks of the corner after ops 0..k-1: the journal's semantics
 * (edit, undo, redo stacks) modelled on their own, without a file. */
/* Returns the records they write (an undo or redo with nothing to do writes none). */
static int expected_state(long k, vrg_block out[64])
{
    typedef struct { int pos; vrg_block old, now; } model_op;
    model_op *done = malloc(sizeof *done * (size_t)(k + 1)), *undone = malloc(sizeof *undone * (size_t)(k + 1));
    int nd = 0, nu = 0, records = 0;
    memset(out, VRG_BLOCK_STONE, 64);
    for (long i = 0; i < k; i++) {
        if (i % 5 == 3) {
            if (nd)
                undone[nu] = done[--nd], out[undone[nu].pos] = undone[nu].old, nu++, records++;
        } else if (i % 7 == 5) {
            if (nu)
                done[nd] = undone[--nu], out[done[nd].pos] = done[nd].now, nd++, records++;
        } else {
            int pos = (int)(i % 4) + 4 * (int)(i / 4 % 4) + 16 * (int)(i / 16 % 4);
            done[nd++] = (model_op){pos, out[pos], (vrg_block)(1 + i % (VRG_BLOCK_COUNT - 1))};
            out[pos] = (vrg_block)(1 + i % (VRG_BLOCK_COUNT - 1));
            nu = 0;
            records++;
        }
    }
    free(done);
    free(undone);
    return records;
}

/* A writer killed (SIGKILL) at random instants, many times: every reopen
 * succeeds, and the state is the one after every op the writer reported
 * done, or after one more (the op in flight when it died). */
static void test_edits_kill(void)
{
    make_tmpdir();
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/kill.edits", tmpdir);
    srand(12345);
    long next = 0;
    int iterations = 80, torn_seen = 0;
    for (int it = 0; it < iterations && !failures; it++) {
        int fds[2];
        CHECK(pipe(fds) == 0, "pipe");
        pid_t pid = fork();
        if (pid == 0) {
            close(fds[0]);
            vrg_world *w = small_world();
            vrg_edits *e = vrg_edits_open(path, "kill", w, err, sizeof err);
            if (!e)
                _exit(3);
            vrg_edits_apply_world(e, w);
            for (long i = next;; i++) {
                if (run_op(e, w, i, err, sizeof err) != 0)
                    _exit(4);
                if (write(fds[1], &i, sizeof i) != sizeof i) /* op i is done */
                    _exit(5);
            }
        }
        close(fds[1]);
        /* the first op done, then a random instant among the next ones
         * (whatever the writer's startup costs, under ASan too) */
        long done = next - 1, v;
        if (read(fds[0], &v, sizeof v) == sizeof v)
            done = v;
        struct timespec ts = {0, (long)(rand() % 5000) * 1000};
        nanosleep(&ts, NULL);
        kill(pid, SIGKILL);
        int status;
        waitpid(pid, &status, 0);
        CHECK(WIFSIGNALED(status), "the writer ended by itself (status %d)", status);
        while (read(fds[0], &v, sizeof v) == sizeof v)
            done = v;
        close(fds[0]);
        vrg_world *w = small_world();
        vrg_edits *e = vrg_edits_open(path, "kill", w, err, sizeof err);
        CHECK(e, "reopening after kill %d: %s", it, err);
        if (!e) {
            vrg_world_destroy(w);
            break;
        }
        torn_seen += vrg_edits_dropped_bytes(e) != 0;
        vrg_edits_apply_world(e, w);
        vrg_block got[64], want[64], want_next[64];
        for (int i = 0; i < 64; i++)
            got[i] = vrg_world_block(w, i % 4, i / 4 % 4, i / 16);
        int records = vrg_edits_records(e);
        vrg_edits_close(e);
        vrg_world_destroy(w);
        /* the record count tells whether the op in flight made it (an
         * edit to the same block changes no block, but is a record) */
        int r0 = expected_state(done + 1, want), r1 = expected_state(done + 2, want_next);
        int same = records == r0 && memcmp(got, want, 64) == 0, one_more = records == r1 && memcmp(got, want_next, 64) == 0;
        CHECK(same || one_more, "kill %d: %d records and the blocks are neither the state after op %ld (%d records) nor after op %ld (%d)", it, records,
              done, r0, done + 1, r1);
        next = same ? done + 1 : done + 2;
    }
    printf("%d kills, %ld ops, %d torn tails dropped\n", iterations, next, torn_seen);
    CHECK(next > iterations, "the writer made too little progress (%ld ops) to test anything", next);
}

/* A torn last record (a crash inside a write) is dropped on opening and cut
 * before the next append. */
static void test_edits_torn(void)
{
    make_tmpdir();
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/torn.edits", tmpdir);
    vrg_world *w = small_world();
    vrg_edits *e = vrg_edits_open(path, "torn", w, err, sizeof err);
    CHECK(e && vrg_edits_set(e, w, 1, 1, 1, VRG_BLOCK_RED, err, sizeof err) == 0, "%s", err);
    vrg_edits_close(e);
    int fd = open(path, O_WRONLY | O_APPEND);
    CHECK(write(fd, "E\0\3\0\2\0\0", 7) == 7, "append a torn record");
    close(fd);
    e = vrg_edits_open(path, "torn", w, err, sizeof err);
    CHECK(e && vrg_edits_records(e) == 1 && vrg_edits_dropped_bytes(e) == 7, "the torn tail is dropped: %s", e ? "" : err);
    CHECK(e && vrg_edits_set(e, w, 2, 2, 2, VRG_BLOCK_WHITE, err, sizeof err) == 0, "append after a torn tail: %s", err);
    vrg_edits_close(e);
    e = vrg_edits_open(path, "torn", w, err, sizeof err);
    vrg_block b = 0;
    CHECK(e && vrg_edits_records(e) == 2 && vrg_edits_dropped_bytes(e) == 0 && vrg_edits_block(e, 2, 2, 2, &b) == 1 && b == VRG_BLOCK_WHITE,
          "the record after the cut is read: %s", e ? "" : err);
    vrg_edits_close(e);
    vrg_world_destroy(w);
}

static void le32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> 8 * i);
}

/* A journal whose second record is the writer's with (x, y, z) and the new
 * block replaced, its checksum made right (so what it holds is judged): refused at the record's byte
 * offset, naming the file, with `what` is wrong (NULL: accepted). */
static void check_forged(const char *path, vrg_world *w, int x, int y, int z, int block, const char *what)
{
    char err[1024];
    unlink(path);
    vrg_edits *e = vrg_edits_open(path, "forged", w, err, sizeof err);
    CHECK(e && vrg_edits_set(e, w, 1, 1, 1, VRG_BLOCK_RED, err, sizeof err) == 0 && vrg_edits_set(e, w, 2, 2, 2, VRG_BLOCK_RED, err, sizeof err) == 0,
          "writing the records: %s", err);
    vrg_edits_close(e);
    long at = 8 + 4 + (long)strlen("forged") + 4 + 20; /* the second: replaying it compares it with the first's position */
    uint8_t r[20];
    FILE *f = fopen(path, "r+b");
    CHECK(f && fseek(f, at, SEEK_SET) == 0 && fread(r, 1, 20, f) == 20, "reading the record back");
    if (!f)
        return;
    r[2] = (uint8_t)block;
    le32(r + 4, (uint32_t)x), le32(r + 8, (uint32_t)y), le32(r + 12, (uint32_t)z);
    le32(r + 16, (uint32_t)crc32(0, r, 16)); /* the journal's CRC-32 is zlib's */
    CHECK(fseek(f, at, SEEK_SET) == 0 && fwrite(r, 1, 20, f) == 20, "writing the forged record");
    fclose(f);
    e = vrg_edits_open(path, "forged", w, err, sizeof err);
    char offset[64];
    snprintf(offset, sizeof offset, "record at byte %ld", at);
    if (what)
        CHECK(!e && strstr(err, path) && strstr(err, offset) && strstr(err, what), "%d %d %d block %d: '%s'", x, y, z, block, e ? "accepted" : err);
    else
        CHECK(e, "%d %d %d block %d, within the world, refused: '%s'", x, y, z, block, err);
    vrg_edits_close(e);
}

/* Records outside the world (past VRG_WORLD_LIMIT, where chunk coordinates
 * overflow an int, or beyond its height), or naming a block id without a
 * material, are refused when read and when written. */
static void test_edits_bad_records(void)
{
    make_tmpdir();
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/forged.edits", tmpdir);
    vrg_world *w = small_world();
    check_forged(path, w, INT32_MIN, 1, 1, VRG_BLOCK_RED, "outside the world");
    check_forged(path, w, 1, 1, INT32_MAX, VRG_BLOCK_RED, "outside the world");
    check_forged(path, w, (int)VRG_WORLD_LIMIT, 1, 1, VRG_BLOCK_RED, "outside the world");
    check_forged(path, w, 1, -1, 1, VRG_BLOCK_RED, "outside the world");
    check_forged(path, w, 1, VRG_CHUNK_SIZE, 1, VRG_BLOCK_RED, "outside the world"); /* small_world: one chunk high */
    check_forged(path, w, 1, 1, 1, 100, "block id 100 has no material");
    check_forged(path, w, 1, 1, 1, 250, "block id 250 has no material");
    check_forged(path, w, 1, 1, 1, 255, "block id 255 has no material");
    check_forged(path, w, -(int)VRG_WORLD_LIMIT, VRG_CHUNK_SIZE - 1, (int)VRG_WORLD_LIMIT - 1, VRG_BLOCK_COUNT - 1, NULL);
    /* the writer refuses them too: a journal it wrote always opens */
    unlink(path);
    vrg_edits *e = vrg_edits_open(path, "forged", w, err, sizeof err);
    CHECK(e && vrg_edits_set(e, w, 1, 1, 1, 100, err, sizeof err) == -1 && strstr(err, "no material"), "block 100 written: '%s'", err);
    CHECK(e && vrg_edits_set(e, w, 1, VRG_CHUNK_SIZE, 1, VRG_BLOCK_RED, err, sizeof err) == -1 && strstr(err, "outside the world"),
          "a block above the world written: '%s'", err);
    CHECK(e && vrg_edits_records(e) == 0 && access(path, F_OK) != 0, "a refused edit left a record or a file");
    vrg_edits_close(e);
    vrg_world_destroy(w);
}

/* The journal deleted, or moved away, while edits go on: the next edit
 * writes it again at its path with every record, and says so; another
 * file put at the path is not written to. A FIFO at the path is refused
 * when opened, without blocking. */
static void test_edits_lost(void)
{
    make_tmpdir();
    char path[512], moved[600], err[1024];
    snprintf(path, sizeof path, "%s/lost.edits", tmpdir);
    snprintf(moved, sizeof moved, "%s/moved.edits", tmpdir);
    vrg_world *w = small_world();
    vrg_edits *e = vrg_edits_open(path, "lost", w, err, sizeof err);
    CHECK(e && vrg_edits_set(e, w, 1, 1, 1, VRG_BLOCK_RED, err, sizeof err) == 0 && !err[0], "first edit: '%s'", err);
    CHECK(unlink(path) == 0, "unlink");
    CHECK(vrg_edits_set(e, w, 2, 2, 2, VRG_BLOCK_WHITE, err, sizeof err) == 0 && strstr(err, path) && strstr(err, "deleted or moved"),
          "the edit after the unlink says nothing of it: '%s'", err);
    CHECK(rename(path, moved) == 0, "move");
    CHECK(vrg_edits_undo(e, w, err, sizeof err) == 0 && strstr(err, "written again with all 3 records"), "undo after the move: '%s'", err);
    CHECK(vrg_edits_set(e, w, 3, 3, 3, VRG_BLOCK_SAND, err, sizeof err) == 0 && !err[0], "an edit with the journal in place: '%s'", err);
    vrg_edits_close(e);
    e = vrg_edits_open(path, "lost", w, err, sizeof err);
    vrg_block b = 0;
    CHECK(e && vrg_edits_records(e) == 4 && vrg_edits_block(e, 1, 1, 1, &b) == 1 && b == VRG_BLOCK_RED && vrg_edits_block(e, 2, 2, 2, &b) == 1 &&
              b == VRG_BLOCK_STONE && vrg_edits_block(e, 3, 3, 3, &b) == 1 && b == VRG_BLOCK_SAND,
          "the journal at the path lacks edits: %d records (%s)", e ? vrg_edits_records(e) : -1, e ? "" : err);
    /* read, not yet appended to, then deleted: written again at the first edit */
    CHECK(unlink(path) == 0, "unlink");
    CHECK(e && vrg_edits_redo(e, w, err, sizeof err) == 1 && vrg_edits_set(e, w, 0, 0, 0, VRG_BLOCK_DIRT, err, sizeof err) == 0 &&
              strstr(err, "written again with all 5 records"),
          "the first edit after reopening: '%s'", err);
    /* another file at the path: refused, left as it is */
    CHECK(rename(moved, path) == 0, "put another file in place");
    struct stat before, after;
    stat(path, &before);
    CHECK(e && vrg_edits_set(e, w, 0, 1, 0, VRG_BLOCK_DIRT, err, sizeof err) == -1 && strstr(err, path) && strstr(err, "another file"),
          "an edit into another file: '%s'", err);
    CHECK(stat(path, &after) == 0 && after.st_size == before.st_size, "the other file changed");
    vrg_edits_close(e);
    /* a FIFO where the journal belongs (a blocking open would wait for a writer for ever) */
    alarm(30);
    CHECK(unlink(path) == 0 && mkfifo(path, 0644) == 0, "mkfifo");
    e = vrg_edits_open(path, "lost", w, err, sizeof err);
    CHECK(!e && strstr(err, path) && strstr(err, "not a regular file"), "a FIFO as the journal: '%s'", e ? "opened" : err);
    alarm(0);
    vrg_edits_close(e);
    unlink(path);
    vrg_world_destroy(w);
}

/* ---- rendering ---- */

static vrg_graph *load_vox(const char *edits, const char *scale) /* scale: part of the journal key */
{
    static char file[600], ed[600], sc[64];
    snprintf(file, sizeof file, "scene.file=%s/chr_knight.vox", VOX_DIR);
    snprintf(ed, sizeof ed, "scene.edits=%s", edits);
    snprintf(sc, sizeof sc, "scene.scale=%s", scale);
    const char *sets[] = {file, ed, sc};
    return load_with("vox_knight.ini", sets, 3, NULL, 0);
}

static int render(vrg_graph *g, vrg_image_data *img)
{
    int ok = g && vrg_graph_frame(g) == 0 && vrg_graph_read(g, "ldr", img) == 0;
    CHECK(ok, "render failed");
    return ok;
}

static int same_image(const vrg_image_data *a, const vrg_image_data *b)
{
    return a->width == b->width && a->height == b->height && memcmp(a->pixels, b->pixels, (size_t)a->width * a->height * 4 * sizeof(float)) == 0;
}

/* The knight renders (every palette colour is a material), an edit made
 * through the graph's journal shows, and the edited world renders the
 * same image twice from the file. */
static int test_vox_render(void)
{
    if (vox_dir_or_skip())
        return SKIP;
    make_tmpdir();
    char edits[512], err[1024];
    snprintf(edits, sizeof edits, "%s/knight.edits", tmpdir);
    vrg_image_data plain = {0}, edited = {0}, again = {0};
    vrg_graph *g = load_vox("none", "1");
    int ok = render(g, &plain);
    vrg_world *w = g ? vrg_graph_world(g) : NULL;
    CHECK(w && vrg_world_material_count(w) > VRG_BLOCK_COUNT + 5, "the knight's colours are materials (%d)", w ? vrg_world_material_count(w) : 0);
    vrg_graph_destroy(g);

    g = load_vox(edits, "1");
    vrg_edits *e = g ? vrg_graph_edits(g) : NULL;
    w = g ? vrg_graph_world(g) : NULL;
    CHECK(e && w, "the graph shares its journal and world");
    /* a red slab through the knight's middle */
    for (int x = -12; e && x <= 12; x++)
        for (int z = -12; z <= 12; z++)
            CHECK(vrg_edits_set(e, w, x, 10, z, VRG_BLOCK_RED, err, sizeof err) == 0, "%s", err);
    vrg_graph_destroy(g);
    g = load_vox(edits, "1");
    ok = ok && render(g, &edited);
    vrg_graph_destroy(g);
    g = load_vox(edits, "1");
    ok = ok && render(g, &again);
    vrg_graph_destroy(g);
    if (ok) {
        CHECK(!same_image(&plain, &edited), "the edits do not show");
        CHECK(same_image(&edited, &again), "the edited world renders differently twice");
    }
    free(plain.pixels), free(edited.pixels), free(again.pixels);
    return 0;
}

static void write_seed(const char *dir, const char *name, buf f);

/* Writes TMPDIR/emit-STRENGTH.vox, one voxel of default palette index 1
 * (white) whose MATL emits strength, and the --set naming it into set. */
static void write_emitter(const char *strength, char *set, size_t set_size)
{
    static const uint8_t voxel1[] = {0, 0, 0, 1};
    buf b = {0}, c = {0};
    model(&b, 1, 1, 1, 1, voxel1);
    put32(&c, 1);
    const char *kv[] = {"_type", "_emit", "_emit", strength};
    put_dict(&c, 2, kv);
    chunk(&b, "MATL", &c);
    char name[64];
    snprintf(name, sizeof name, "emit-%s.vox", strength);
    write_seed(tmpdir, name, file_of(&b));
    free(b.d), free(c.d);
    snprintf(set, set_size, "scene.file=%s/%s", tmpdir, name);
}

typedef struct emit_means {
    double emitter, ground; /* linear luminance of the emitter's pixels, of the ground within 2 blocks of it */
    int emitter_pixels, ground_pixels;
} emit_means;

static int render_emitter(const char *strength, emit_means *m)
{
    char file[700];
    write_emitter(strength, file, sizeof file);
    const char *sets[] = {file};
    static const char *const reads[] = {"color", "gbuffer.ids", "gbuffer.position"};
    vrg_graph *g = load_with("vox_emit.ini", sets, 1, reads, 3);
    vrg_image_data color = {0}, ids = {0}, pos = {0};
    int ok = g && vrg_graph_frame(g) == 0 && vrg_graph_read(g, "color", &color) == 0 && vrg_graph_read(g, "gbuffer.ids", &ids) == 0 &&
             vrg_graph_read(g, "gbuffer.position", &pos) == 0;
    CHECK(ok, "emit %s: render failed", strength);
    memset(m, 0, sizeof *m);
    for (uint32_t y = 0; ok && y < color.height; y++)
        for (uint32_t x = 0; x < color.width; x++) {
            double lum = 0.2126 * px(&color, x, y, 0) + 0.7152 * px(&color, x, y, 1) + 0.0722 * px(&color, x, y, 2);
            int id = (int)px(&ids, x, y, 0);
            /* the voxel takes the first free id; it sits on the ground near x = z = 0 */
            if (id == VRG_BLOCK_COUNT)
                m->emitter += lum, m->emitter_pixels++;
            else if (id == VRG_BLOCK_WHITE && fabsf(px(&pos, x, y, 0)) < 2 && fabsf(px(&pos, x, y, 2)) < 2)
                m->ground += lum, m->ground_pixels++;
        }
    CHECK(!ok || (m->emitter_pixels > 20 && m->ground_pixels > 50), "emit %s: the view holds %d pixels of the voxel, %d of the ground near it", strength,
          m->emitter_pixels, m->ground_pixels);
    if (m->emitter_pixels)
        m->emitter /= m->emitter_pixels;
    if (m->ground_pixels)
        m->ground /= m->ground_pixels;
    free(color.pixels), free(ids.pixels), free(pos.pixels);
    vrg_graph_destroy(g);
    return ok;
}

/* An emitting voxel at midnight: seen directly it shows its light (white,
 * emissive 4 x _emit), and the ground beside it is brighter than beside
 * the same voxel with _emit 0, lit through the indirect rays. A graph
 * whose vox file holds a bad _emit does not load, and says why. */
static void test_emit_light(void)
{
    make_tmpdir();
    emit_means dark, lit;
    if (!render_emitter("0", &dark) || !render_emitter("1", &lit))
        return;
    CHECK(dark.emitter < 0.5, "_emit 0: the voxel is lit by the moon and sky only (%.3f)", dark.emitter);
    CHECK(lit.emitter > 4.0, "_emit 1: the voxel shows albedo x (light + 4) (%.3f)", lit.emitter);
    CHECK(lit.ground > 1.5 * dark.ground + 0.05, "the ground beside the voxel: %.3f with _emit 1, %.3f with _emit 0", lit.ground, dark.ground);

    char file[700], graph[700], *log = NULL;
    size_t len = 0;
    write_emitter("nan", file, sizeof file);
    const char *sets[] = {file};
    snprintf(graph, sizeof graph, "%s/graphs/vox_emit.ini", TEST_DIR);
    FILE *diag = open_memstream(&log, &len);
    vrg_graph_desc d = {.path = graph, .overrides = sets, .override_count = 1, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(ctx, &d, &g);
    fclose(diag);
    CHECK(rc != 0, "a vox file with _emit = nan loaded");
    CHECK(log && strstr(log, "emit-nan.vox: chunk 'MATL' at byte 64: material 1: _emit = 'nan' is not a finite number >= 0"),
          "the error: %s", log ? log : "(no message)");
    vrg_graph_destroy(g);
    free(log);
}

/* Streaming terrain: an edit made through the graph's journal is in the
 * chunk when a new graph generates that chunk again (the integration hook). */
static void test_terrain_edits(void)
{
    make_tmpdir();
    char sets0[600], err[1024];
    snprintf(sets0, sizeof sets0, "scene.edits=%s/terrain.edits", tmpdir);
    const char *sets[] = {sets0};
    vrg_graph *g = load_with("terrain_probe.ini", sets, 1, NULL, 0);
    CHECK(g && vrg_graph_frame(g) == 0, "first frame");
    vrg_edits *e = g ? vrg_graph_edits(g) : NULL;
    vrg_world *w = g ? vrg_graph_world(g) : NULL;
    CHECK(e && w, "the terrain shares its journal");
    if (e && w) {
        CHECK(vrg_edits_set(e, w, 3, 2, 5, VRG_BLOCK_LAMP, err, sizeof err) == 0, "%s", err);
        CHECK(vrg_world_block(w, 3, 2, 5) == VRG_BLOCK_LAMP, "the loaded chunk changes at once");
    }
    vrg_graph_destroy(g);
    g = load_with("terrain_probe.ini", sets, 1, NULL, 0);
    CHECK(g && vrg_graph_frame(g) == 0, "frame of the new graph");
    w = g ? vrg_graph_world(g) : NULL;
    CHECK(w && vrg_world_has_chunk(w, 0, 0, 0) && vrg_world_block(w, 3, 2, 5) == VRG_BLOCK_LAMP, "the generated chunk lacks the edit (%d)",
          w ? vrg_world_block(w, 3, 2, 5) : -1);
    vrg_graph_destroy(g);
}

/* A model placed outside the world's limits (|x|, |z| <= 512, 0 <= y < 256)
 * is an error, not a world of that size: a position outside them at the
 * position's line, with the number as written (never wrapped to an int)
 * and the range; a model that reaches beyond them from inside at the
 * file's line, naming the file and the blocks it spans. */
static void test_too_large(void)
{
    make_tmpdir();
    static const uint8_t voxel[4] = {0, 0, 0, 1};
    char path[600];
    snprintf(path, sizeof path, "%s/small.vox", tmpdir);
    write_seed(tmpdir, "small.vox", one_model(4, 4, 4, 1, voxel));
    static const char spans[] = "too_large.ini:7: error[VRG-E058]: ";
    static const struct {
        const char *position, *scale, *message;
    } outside[] = {
        {"600 1 0", "1", "too_large.ini:8: error[VRG-E058]: position = '600 1 0': x = 600 is outside [-512, 512] (blocks)"},
        {"0 1 -700", "1", "too_large.ini:8: error[VRG-E058]: position = '0 1 -700': z = -700 is outside [-512, 512] (blocks)"},
        {"99999999999 1 0", "1", "too_large.ini:8: error[VRG-E058]: position = '99999999999 1 0': x = 99999999999 is outside [-512, 512] (blocks)"},
        {"0 -99999999999999999999 0", "1", "position = '0 -99999999999999999999 0': y = -99999999999999999999 is outside [0, 255] (blocks)"},
        {"0 1 0x10", "1", "too_large.ini:8: error[VRG-E058]: position = '0 1 0x10': expected 'X Y Z' (integers, blocks)"},
        {"0 254 0", "1", spans},
        {"500 1 0", "16", spans},
    };
    for (size_t i = 0; i < sizeof outside / sizeof outside[0]; i++) {
        char text[1600], *log = NULL;
        size_t len = 0;
        snprintf(text, sizeof text,
                 "[graph]\noutput = ldr\nwidth = 16\nheight = 16\n[scene]\nplugin = vox\nfile = %s\nposition = %s\nscale = %s\nedits = none\n"
                 "[pass gbuffer]\nplugin = gbuffer\nin.world = world\nin.frame = frame\nin.atlas = atlas\n"
                 "[pass tonemap]\nplugin = tonemap\nin.color = gbuffer.albedo\nout.ldr = ldr\n",
                 path, outside[i].position, outside[i].scale);
        FILE *diag = open_memstream(&log, &len);
        vrg_graph_desc d = {.path = "too_large.ini", .text = text, .diag = diag};
        vrg_graph *g = NULL;
        int rc = vrg_graph_load(ctx, &d, &g);
        fclose(diag);
        CHECK(rc != 0, "position %s scale %s: a model outside the world loaded", outside[i].position, outside[i].scale);
        if (outside[i].message == spans)
            CHECK(log && strstr(log, spans) && strstr(log, "small.vox: the model spans blocks") && strstr(log, "the world holds 0 <= y < 256"),
                  "position %s scale %s: %s", outside[i].position, outside[i].scale, log ? log : "(no message)");
        else
            CHECK(log && strstr(log, outside[i].message), "position %s scale %s: no '%s' in: %s", outside[i].position, outside[i].scale, outside[i].message,
                  log ? log : "(no message)");
        vrg_graph_destroy(g);
        free(log);
    }
}

static const test_case cases[] = {
    {"vox_too_large", test_too_large, 1, NULL},
    {"terrain_edits", test_terrain_edits, 1, NULL},
    {"vox_scene_graph", test_scene_graph, 0, NULL},
    {"vox_bad_files", test_bad_files, 0, NULL},
    {"vox_real_files", NULL, 0, test_real_files},
    {"edits_roundtrip", test_edits_roundtrip, 0, NULL},
    {"edits_torn", test_edits_torn, 0, NULL},
    {"edits_foreign_key", test_edits_foreign_key, 0, NULL},
    {"edits_kill", test_edits_kill, 0, NULL},
    {"edits_bad_records", test_edits_bad_records, 0, NULL},
    {"edits_lost", test_edits_lost, 0, NULL},
    {"vox_render", NULL, 1, test_vox_render},
    {"vox_emit_values", test_emit_values, 0, NULL},
    {"vox_emit_light", test_emit_light, 1, NULL},
};

static void write_seed(const char *dir, const char *name, buf f)
{
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *out = fopen(path, "wb");
    CHECK(out && fwrite(f.d, 1, f.n, out) == f.n, "cannot write the seed %s", path);
    if (out)
        CHECK(fclose(out) == 0, "cannot write the seed %s", path);
    free(f.d);
}

/* The fuzzer's seeds: small synthetic files covering every chunk kind. */
static int write_seeds(const char *dir)
{
    write_seed(dir, "scene_graph.vox", scene_graph_file());
    write_seed(dir, "one_model.vox", one_model(2, 3, 4, 2, two_voxels));
    buf b = {0}, c = {0};
    model(&b, 2, 3, 4, 2, two_voxels);
    for (int i = 0; i < 256; i++)
        put32(&c, (int32_t)(0xff000000u | (uint32_t)i * 0x010203u));
    chunk(&b, "RGBA", &c);
    c.n = 0;
    put32(&c, 9);
    const char *kv[] = {"_type", "_emit", "_emit", "0.5", "_flux", "1"};
    put_dict(&c, 3, kv);
    chunk(&b, "MATL", &c);
    write_seed(dir, "palette_matl.vox", file_of(&b));
    free(b.d), free(c.d);
    return failures ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "vox_seeds") == 0)
        return write_seeds(argv[2]);
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
