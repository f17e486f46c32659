/* Terrain generation and chunk streaming: `test_terrain CASE` prints
 * "CASE: ok" and exits 0, or says what failed and exits 1. No GPU needed. */
#define _POSIX_C_SOURCE 200809L
#include "stream.h"
#include "terrain_gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"

static int failures;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void sleep_ms(double ms)
{
    struct timespec ts = { 0, (long)(ms * 1e6) };
    nanosleep(&ts, NULL);
}

static uint64_t fnv1a64(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}
#define FNV_OFFSET 0xcbf29ce484222325ull

/* The test's own random numbers (xorshift64*), independent of the terrain's. */
static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static int rng_range(int lo, int hi)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return lo + (int)((rng_state * 0x2545f4914f6cdd1dull >> 33) % (uint64_t)(hi - lo + 1));
}

static void generate_cb(void *user, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS])
{
    terrain_generate_chunk(user, cx, cy, cz, out);
}

/* ---- noise ---- */

static int test_noise(void)
{
    float lo = 1.0f, hi = -1.0f;
    for (int i = 0; i < 200000; i++) {
        float x = (float)rng_range(-100000, 100000) / 97.0f, y = (float)rng_range(-100000, 100000) / 89.0f;
        float n = terrain_noise2(7, x, y);
        CHECK(n >= -1.0f && n <= 1.0f, "noise(%g, %g) = %g", x, y, n);
        lo = fminf(lo, n);
        hi = fmaxf(hi, n);
        /* Continuity: the gradient is bounded, so a 1e-3 step moves little. */
        float m = terrain_noise2(7, x + 1e-3f, y - 1e-3f);
        CHECK(fabsf(m - n) < 0.01f, "jump %g -> %g at (%g, %g)", n, m, x, y);
    }
    CHECK(lo < -0.5f && hi > 0.5f, "range [%g, %g] too narrow", lo, hi);
    for (int y = -40; y <= 40; y++)
        for (int x = -40; x <= 40; x++)
            CHECK(terrain_noise2(7, (float)x, (float)y) == 0.0f, "nonzero at lattice (%d, %d)", x, y);
    CHECK(terrain_noise2(7, 3.3f, 1.7f) != terrain_noise2(8, 3.3f, 1.7f), "seed ignored");

    terrain_params p;
    terrain_params_default(&p);
    for (int i = 0; i < 20000; i++) {
        float f = terrain_fbm(&p, (float)rng_range(-5000, 5000) + 0.37f, (float)rng_range(-5000, 5000) + 0.61f);
        CHECK(f >= -1.0f && f <= 1.0f, "fbm %g", f);
    }
    printf("noise range [%.3f, %.3f]\n", lo, hi);
    return 0;
}

/* ---- determinism ---- */

enum { DET_R = 4, DET_SIDE = 2 * DET_R + 1, DET_H = 3 };

typedef struct det_grid {
    uint64_t hash[DET_SIDE][DET_SIDE][DET_H];
    int count[DET_SIDE][DET_SIDE][DET_H];
    int bad;
} det_grid;

static void det_integrate(void *user, int cx, int cy, int cz, const vrg_block *blocks)
{
    det_grid *g = user;
    if (cx < -DET_R || cx > DET_R || cz < -DET_R || cz > DET_R || cy < 0 || cy >= DET_H) {
        g->bad++;
        return;
    }
    g->hash[cx + DET_R][cz + DET_R][cy] = fnv1a64(FNV_OFFSET, blocks, VRG_CHUNK_VOXELS);
    g->count[cx + DET_R][cz + DET_R][cy]++;
}

static uint64_t combine(const det_grid *g)
{
    uint64_t h = FNV_OFFSET;
    for (int x = 0; x < DET_SIDE; x++)
        for (int z = 0; z < DET_SIDE; z++)
            h = fnv1a64(h, g->hash[x][z], sizeof g->hash[x][z]);
    return h;
}

static void det_direct(const terrain_params *p, det_grid *g)
{
    static vrg_block buf[VRG_CHUNK_VOXELS];
    memset(g, 0, sizeof *g);
    for (int cx = -DET_R; cx <= DET_R; cx++)
        for (int cz = -DET_R; cz <= DET_R; cz++)
            for (int cy = 0; cy < DET_H; cy++) {
                terrain_generate_chunk(p, cx, cy, cz, buf);
                det_integrate(g, cx, cy, cz, buf);
            }
}

static int det_streamed(terrain_params *p, int threads, det_grid *g)
{
    memset(g, 0, sizeof *g);
    stream_desc d = { .threads = threads, .radius = DET_R, .hysteresis = 0, .height_chunks = DET_H,
                      .generate = generate_cb, .user = p };
    stream *s = stream_create(&d);
    if (!CHECK(s, "stream_create"))
        return 1;
    stream_update(s, 0, 0, NULL, NULL);
    while (stream_pending(s) > 0) {
        stream_wait_idle(s);
        stream_integrate(s, 1e9, det_integrate, g, NULL);
    }
    stream_destroy(s);
    CHECK(!g->bad, "chunk outside the area integrated");
    for (int x = 0; x < DET_SIDE; x++)
        for (int z = 0; z < DET_SIDE; z++)
            for (int y = 0; y < DET_H; y++)
                CHECK(g->count[x][z][y] == 1, "chunk (%d,%d,%d) integrated %d times", x - DET_R, y, z - DET_R, g->count[x][z][y]);
    return 0;
}

static int test_determinism(void)
{
    terrain_params p;
    terrain_params_default(&p);
    p.seed = 1234;
    static det_grid ref, got;
    det_direct(&p, &ref);
    uint64_t ref_hash = combine(&ref);
    int threads[] = { 0, 1, 2, 4 };
    for (size_t i = 0; i < sizeof threads / sizeof *threads; i++) {
        if (det_streamed(&p, threads[i], &got))
            return 1;
        CHECK(memcmp(ref.hash, got.hash, sizeof ref.hash) == 0, "per-chunk hashes differ with %d threads", threads[i]);
        CHECK(combine(&got) == ref_hash, "area hash differs with %d threads", threads[i]);
    }
    det_direct(&p, &got);
    CHECK(combine(&got) == ref_hash, "second single-threaded run differs");
    p.seed = 1235;
    det_direct(&p, &got);
    CHECK(combine(&got) != ref_hash, "seeds 1234 and 1235 give the same world");
    printf("area hash %016llx\n", (unsigned long long)ref_hash);
    return 0;
}

/* ---- trees ---- */

/* A 3x3-chunk area, full height, composed from separately generated chunks. */
enum { AREA = 48, AREA_H = 48 };
typedef struct area {
    int x0, z0; /* world block coordinates of the area's corner */
    vrg_block b[AREA_H][AREA][AREA];
} area;

static vrg_block area_get(const area *a, int x, int y, int z) { return a->b[y][z - a->z0][x - a->x0]; }

static void area_build(const terrain_params *p, int ccx, int ccz, area *a)
{
    static vrg_block buf[VRG_CHUNK_VOXELS];
    a->x0 = (ccx - 1) * 16;
    a->z0 = (ccz - 1) * 16;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            for (int cy = 0; cy < 3; cy++) {
                terrain_generate_chunk(p, ccx - 1 + i, cy, ccz - 1 + k, buf);
                for (int ly = 0; ly < 16; ly++)
                    for (int lz = 0; lz < 16; lz++)
                        memcpy(&a->b[cy * 16 + ly][k * 16 + lz][i * 16], &buf[vrg_chunk_index(0, ly, lz)], 16);
            }
}

static int is_terrain(vrg_block b) { return b != VRG_BLOCK_AIR && b != VRG_BLOCK_WATER && b != VRG_BLOCK_WOOD && b != VRG_BLOCK_LEAVES; }

/* Every tree rooted where its whole footprint lies inside the area appears
 * exactly as terrain_tree_block builds it; returns trees checked, -1 on a
 * mismatch, and counts leaves that landed in another chunk than the trunk. */
static int check_trees(const terrain_params *p, const area *a, int *crossing)
{
    int trees = 0;
    for (int z = a->z0 + 2; z < a->z0 + AREA - 2; z++)
        for (int x = a->x0 + 2; x < a->x0 + AREA - 2; x++) {
            terrain_tree t;
            if (!terrain_tree_at(p, x, z, &t))
                continue;
            trees++;
            int crossed = 0;
            for (int y = t.base; y <= t.base + t.trunk; y++)
                for (int tz = z - 2; tz <= z + 2; tz++)
                    for (int tx = x - 2; tx <= x + 2; tx++) {
                        vrg_block want = terrain_tree_block(&t, tx, y, tz), got = area_get(a, tx, y, tz);
                        if (want == VRG_BLOCK_WOOD && got != VRG_BLOCK_WOOD) {
                            fprintf(stderr, "tree (%d,%d): no wood at (%d,%d,%d)\n", x, z, tx, y, tz);
                            return -1;
                        }
                        if (want == VRG_BLOCK_LEAVES && (got == VRG_BLOCK_AIR || got == VRG_BLOCK_WATER)) {
                            fprintf(stderr, "tree (%d,%d): missing leaves at (%d,%d,%d)\n", x, z, tx, y, tz);
                            return -1;
                        }
                        if (want == VRG_BLOCK_LEAVES && got == VRG_BLOCK_LEAVES &&
                            (vrg_floor_div16(tx) != vrg_floor_div16(x) || vrg_floor_div16(tz) != vrg_floor_div16(z)))
                            crossed = 1;
                    }
            *crossing += crossed;
        }
    return trees;
}

static int test_trees_across_borders(void)
{
    terrain_params p;
    terrain_params_default(&p);
    p.seed = 4242;
    /* Find a tree two blocks or less from an x border of its chunk. */
    terrain_tree t;
    int found = 0;
    for (int z = 0; z < 4000 && !found; z++)
        for (int x = -2; x <= 1 && !found; x++)
            found = terrain_tree_at(&p, x + 16 * (z % 7), z, &t);
    if (!CHECK(found, "no tree near a chunk border"))
        return 1;
    int tcx = vrg_floor_div16(t.x), tcz = vrg_floor_div16(t.z), tcy = vrg_floor_div16(t.base + t.trunk - 1);
    int ncx = (t.x & 15) < 8 ? tcx - 1 : tcx + 1; /* the chunk across the border */
    printf("tree at (%d, %d), base %d, trunk %d; chunks x %d and %d\n", t.x, t.z, t.base, t.trunk, tcx, ncx);

    static area a;
    area_build(&p, tcx, tcz, &a);
    /* Each chunk alone, and the pair in both orders, match the composed area. */
    static vrg_block ca[VRG_CHUNK_VOXELS], cb[VRG_CHUNK_VOXELS], ca2[VRG_CHUNK_VOXELS], cb2[VRG_CHUNK_VOXELS];
    terrain_generate_chunk(&p, tcx, tcy, tcz, ca);
    terrain_generate_chunk(&p, ncx, tcy, tcz, cb);
    terrain_generate_chunk(&p, ncx, tcy, tcz, cb2);
    terrain_generate_chunk(&p, tcx, tcy, tcz, ca2);
    CHECK(!memcmp(ca, ca2, sizeof ca) && !memcmp(cb, cb2, sizeof cb), "order changes a chunk");
    for (int ly = 0; ly < 16; ly++)
        for (int lz = 0; lz < 16; lz++)
            for (int lx = 0; lx < 16; lx++) {
                int y = tcy * 16 + ly, z = tcz * 16 + lz;
                CHECK(ca[vrg_chunk_index(lx, ly, lz)] == area_get(&a, tcx * 16 + lx, y, z), "tree chunk differs");
                CHECK(cb[vrg_chunk_index(lx, ly, lz)] == area_get(&a, ncx * 16 + lx, y, z), "neighbour chunk differs");
            }

    /* The found tree, and every other one in the area, comes out whole. */
    int crossing = 0, trees = check_trees(&p, &a, &crossing);
    CHECK(trees > 0, "check_trees failed or found nothing");
    CHECK(crossing > 0, "no tree put leaves into a neighbouring chunk");
    int leaves_across = 0;
    for (int y = t.base; y <= t.base + t.trunk; y++)
        for (int z = t.z - 2; z <= t.z + 2; z++)
            for (int x = t.x - 2; x <= t.x + 2; x++)
                if (vrg_floor_div16(x) == ncx && terrain_tree_block(&t, x, y, z) == VRG_BLOCK_LEAVES)
                    leaves_across += area_get(&a, x, y, z) == VRG_BLOCK_LEAVES;
    CHECK(leaves_across > 0, "the found tree has no leaves across the border");

    /* Every wood column is capped by leaves, and all wood belongs to a tree. */
    for (int z = a.z0; z < a.z0 + AREA; z++)
        for (int x = a.x0; x < a.x0 + AREA; x++)
            for (int y = 0; y < AREA_H; y++) {
                if (area_get(&a, x, y, z) != VRG_BLOCK_WOOD)
                    continue;
                if (!CHECK(y + 1 < AREA_H, "wood at the top of the world"))
                    continue;
                vrg_block above = area_get(&a, x, y + 1, z);
                CHECK(above == VRG_BLOCK_WOOD || above == VRG_BLOCK_LEAVES, "wood at (%d,%d,%d) not capped", x, y, z);
                terrain_tree own;
                if (!CHECK(terrain_tree_at(&p, x, z, &own) && y >= own.base && y < own.base + own.trunk,
                           "stray wood at (%d,%d,%d)", x, y, z))
                    continue;
                CHECK(is_terrain(area_get(&a, x, own.base - 1, z)), "tree at (%d,%d) floats", x, z);
            }
    printf("%d trees in the area, %d with leaves in another chunk; %d leaves across the found tree's border\n", trees,
           crossing, leaves_across);
    return 0;
}

/* ---- biomes ---- */

static void biomes_case(float biome_size, int samples)
{
    terrain_params p;
    terrain_params_default(&p);
    p.seed = 99;
    p.biome_size = biome_size;
    enum { WIN = 8 };
    int seen[BIOME_COUNT] = { 0 };
    for (int i = 0; i < samples; i++) {
        int x = rng_range(-2000, 2000), z = rng_range(-2000, 2000);
        float edge;
        terrain_biome b = terrain_biome_at(&p, x, z, &edge);
        float fx = (float)x + 0.5f, fz = (float)z + 0.5f;
        int ci = (int)floorf(fx / biome_size), cj = (int)floorf(fz / biome_size);
        float d1 = INFINITY, d2 = INFINITY;
        terrain_biome nb = BIOME_COUNT;
        int tie_ok = 0;
        for (int j = cj - WIN; j <= cj + WIN; j++)
            for (int k = ci - WIN; k <= ci + WIN; k++) {
                float px, pz;
                terrain_biome cb = terrain_biome_cell(&p, k, j, &px, &pz);
                float d = (fx - px) * (fx - px) + (fz - pz) * (fz - pz);
                if (d < d1) {
                    d2 = d1;
                    d1 = d;
                    nb = cb;
                    tie_ok = 0;
                } else if (d == d1) {
                    d2 = d;
                    tie_ok |= cb == b;
                } else if (d < d2) {
                    d2 = d;
                }
            }
        CHECK(b == nb || tie_ok, "(%d, %d) size %g: biome %d, brute force %d", x, z, biome_size, b, nb);
        float want_edge = sqrtf(d2) - sqrtf(d1);
        CHECK(fabsf(edge - want_edge) <= 1e-3f * (1.0f + want_edge), "(%d, %d): edge %g, brute force %g", x, z, edge, want_edge);
        seen[b]++;
    }
    for (int b = 0; b < BIOME_COUNT; b++)
        CHECK(seen[b] > samples / 10, "biome %d seen %d times of %d", b, seen[b], samples);
    printf("size %g: grassland %d, forest %d, desert %d\n", biome_size, seen[0], seen[1], seen[2]);
}

static int test_biomes_bruteforce(void)
{
    biomes_case(128.0f, 5000);
    biomes_case(20.0f, 5000);
    biomes_case(3.0f, 2000);
    return 0;
}

/* ---- layers ---- */

typedef struct layer_stats {
    int water, snow, trees;
} layer_stats;

static void check_column(const terrain_params *p, const vrg_block *col, int x, int z, layer_stats *st)
{
    int h = terrain_height_at(p, x, z);
    terrain_biome b = terrain_biome_at(p, x, z, NULL);
    CHECK(h >= 1 && h <= 16 * p->height_chunks - 8, "(%d,%d): height %d out of range", x, z, h);
    int shore = b != BIOME_DESERT && h - 1 <= p->sea_level;
    for (int y = 0; y < 16 * p->height_chunks; y++) {
        int depth = h - 1 - y;
        vrg_block got = col[y], want;
        if (y >= h) {
            /* Above ground: no floating terrain; water exactly below sea level. */
            if (y < p->sea_level)
                CHECK(got == VRG_BLOCK_WATER, "(%d,%d,%d): %d where water belongs", x, y, z, got);
            else
                CHECK(got == VRG_BLOCK_AIR || got == VRG_BLOCK_WOOD || got == VRG_BLOCK_LEAVES,
                      "(%d,%d,%d): %d above ground", x, y, z, got);
            st->water += got == VRG_BLOCK_WATER;
            st->trees += got == VRG_BLOCK_WOOD && y == h;
            continue;
        }
        if (b == BIOME_DESERT)
            want = depth < 3 ? VRG_BLOCK_SAND : depth < 6 ? VRG_BLOCK_SANDSTONE : VRG_BLOCK_STONE;
        else if (shore)
            want = depth < 3 ? VRG_BLOCK_SAND : VRG_BLOCK_STONE;
        else if (depth == 0)
            want = (float)y >= p->base_height + 0.75f * p->amplitude ? VRG_BLOCK_SNOW : VRG_BLOCK_GRASS;
        else
            want = depth <= 3 ? VRG_BLOCK_DIRT : VRG_BLOCK_STONE;
        st->snow += got == VRG_BLOCK_SNOW;
        CHECK(got == want, "(%d,%d,%d): biome %d height %d depth %d: %d, want %d", x, y, z, b, h, depth, got, want);
    }
}

static int test_layers(void)
{
    terrain_params p;
    terrain_params_default(&p);
    p.seed = 777;
    static vrg_block chunks[3][VRG_CHUNK_VOXELS];
    vrg_block col[48];
    int columns = 0, biome_cols[BIOME_COUNT] = { 0 };
    layer_stats st = { 0 };
    for (int i = 0; i < 150; i++) {
        int cx = rng_range(-100, 100), cz = rng_range(-100, 100);
        for (int cy = 0; cy < 3; cy++)
            terrain_generate_chunk(&p, cx, cy, cz, chunks[cy]);
        for (int lz = 0; lz < 16; lz++)
            for (int lx = 0; lx < 16; lx++) {
                for (int y = 0; y < 48; y++)
                    col[y] = chunks[y / 16][vrg_chunk_index(lx, y & 15, lz)];
                int x = cx * 16 + lx, z = cz * 16 + lz;
                check_column(&p, col, x, z, &st);
                biome_cols[terrain_biome_at(&p, x, z, NULL)]++;
                columns++;
            }
    }
    for (int b = 0; b < BIOME_COUNT; b++)
        CHECK(biome_cols[b] > 0, "no column of biome %d", b);
    CHECK(st.water > 0 && st.snow > 0 && st.trees > 0, "water %d, snow %d, trees %d: expected some of each", st.water,
          st.snow, st.trees);
    /* Out-of-range cy is air. */
    terrain_generate_chunk(&p, 0, 3, 0, chunks[0]);
    terrain_generate_chunk(&p, 0, -1, 0, chunks[1]);
    for (int i = 0; i < VRG_CHUNK_VOXELS; i++)
        CHECK(chunks[0][i] == VRG_BLOCK_AIR && chunks[1][i] == VRG_BLOCK_AIR, "out-of-range chunk not air");

    /* No cliffs at biome borders: neighbouring heights near a border differ
     * by little more than anywhere else. */
    int border_max = 0, border_samples = 0;
    for (int i = 0; i < 200000 && border_samples < 3000; i++) {
        int x = rng_range(-3000, 3000), z = rng_range(-3000, 3000);
        float edge;
        terrain_biome_at(&p, x, z, &edge);
        if (edge > 2.0f)
            continue;
        int h = terrain_height_at(&p, x, z);
        int dx = abs(terrain_height_at(&p, x + 1, z) - h), dz = abs(terrain_height_at(&p, x, z + 1) - h);
        border_max = dx > border_max ? dx : border_max;
        border_max = dz > border_max ? dz : border_max;
        border_samples++;
    }
    CHECK(border_samples > 100, "too few border samples");
    CHECK(border_max <= 3, "height step of %d at a biome border", border_max);
    printf("%d columns (grassland %d, forest %d, desert %d): %d water blocks, %d snow, %d trees; max step at "
           "borders %d over %d samples\n",
           columns, biome_cols[0], biome_cols[1], biome_cols[2], st.water, st.snow, st.trees, border_max, border_samples);
    return 0;
}

/* ---- streaming ---- */

enum { ST_R = 3, ST_HYST = 1, ST_H = 3, ST_MIN = -20, ST_MAX = 20, ST_SPAN = ST_MAX - ST_MIN + 1 };

/* Integration pretends to upload: each chunk takes at least UPLOAD_MS, so a
 * call with a budget of BUDGET_MS can integrate at most MAX_PER_CALL (the
 * budget is checked before every chunk after the first). */
#define UPLOAD_MS 0.25
#define BUDGET_MS 1.0
enum { MAX_PER_CALL = 4 };

typedef struct tracker {
    unsigned char loaded[ST_SPAN][ST_SPAN][ST_H];
    int errors, integrated, dropped, most_per_call;
    double times[4096];
    int ntimes;
} tracker;

/* Stamps each chunk with its coordinates so integration can verify them. */
static void stamp_gen(void *user, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS])
{
    (void)user;
    memset(out, 0, VRG_CHUNK_VOXELS);
    out[0] = (vrg_block)cx;
    out[1] = (vrg_block)cy;
    out[2] = (vrg_block)cz;
    out[VRG_CHUNK_VOXELS - 1] = 0xa5;
}

static int in_box(int cx, int cy, int cz)
{
    return cx >= ST_MIN && cx <= ST_MAX && cz >= ST_MIN && cz <= ST_MAX && cy >= 0 && cy < ST_H;
}

static void st_integrate(void *user, int cx, int cy, int cz, const vrg_block *b)
{
    tracker *t = user;
    if (!in_box(cx, cy, cz) || b[0] != (vrg_block)cx || b[1] != (vrg_block)cy || b[2] != (vrg_block)cz ||
        b[VRG_CHUNK_VOXELS - 1] != 0xa5) {
        t->errors++;
        return;
    }
    unsigned char *l = &t->loaded[cx - ST_MIN][cz - ST_MIN][cy];
    t->errors += *l; /* integrated twice without a drop */
    *l = 1;
    t->integrated++;
    sleep_ms(UPLOAD_MS);
}

static void st_drop(void *user, int cx, int cy, int cz)
{
    tracker *t = user;
    if (!in_box(cx, cy, cz) || !t->loaded[cx - ST_MIN][cz - ST_MIN][cy]) {
        t->errors++;
        return;
    }
    t->loaded[cx - ST_MIN][cz - ST_MIN][cy] = 0;
    t->dropped++;
}

/* Frames of update + integrate until nothing is pending. */
static void st_run(stream *s, tracker *t, int cx, int cz)
{
    for (;;) {
        double spent;
        stream_update(s, cx, cz, st_drop, t);
        int n = stream_integrate(s, BUDGET_MS, st_integrate, t, &spent);
        t->most_per_call = n > t->most_per_call ? n : t->most_per_call;
        if (n > 0 && t->ntimes < (int)(sizeof t->times / sizeof *t->times))
            t->times[t->ntimes++] = spent;
        if (!stream_pending(s))
            return;
        if (!n)
            sleep_ms(0.5); /* the next frame */
    }
}

/* The model: after settling at (cx, cz), loaded = wanted ∪ (loaded ∩ kept). */
static void model_step(unsigned char m[ST_SPAN][ST_SPAN][ST_H], int cx, int cz)
{
    for (int x = ST_MIN; x <= ST_MAX; x++)
        for (int z = ST_MIN; z <= ST_MAX; z++)
            for (int y = 0; y < ST_H; y++) {
                int dx = abs(x - cx), dz = abs(z - cz);
                unsigned char *v = &m[x - ST_MIN][z - ST_MIN][y];
                if (dx <= ST_R && dz <= ST_R)
                    *v = 1;
                else if (dx > ST_R + ST_HYST || dz > ST_R + ST_HYST)
                    *v = 0;
            }
}

static int count_loaded(unsigned char m[ST_SPAN][ST_SPAN][ST_H])
{
    int n = 0;
    for (int i = 0; i < ST_SPAN * ST_SPAN * ST_H; i++)
        n += (&m[0][0][0])[i];
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int test_streaming(void)
{
    static tracker t;
    static unsigned char model[ST_SPAN][ST_SPAN][ST_H];
    stream_desc d = { .threads = 2, .radius = ST_R, .hysteresis = ST_HYST, .height_chunks = ST_H, .generate = stamp_gen };
    stream *s = stream_create(&d);
    if (!CHECK(s, "stream_create"))
        return 1;

    st_run(s, &t, 0, 0);
    model_step(model, 0, 0);
    CHECK(!t.errors, "%d bad callbacks", t.errors);
    CHECK(!memcmp(t.loaded, model, sizeof model) && count_loaded(t.loaded) == 7 * 7 * 3, "start set wrong (%d loaded)",
          count_loaded(t.loaded));

    for (int step = 1; step <= 5; step++) {
        st_run(s, &t, step, 0);
        model_step(model, step, 0);
        CHECK(!t.errors, "step %d: %d bad callbacks", step, t.errors);
        CHECK(!memcmp(t.loaded, model, sizeof model), "step %d: loaded set differs from the model", step);
    }
    /* Exactly x in [1, 8] (x = 1 held by hysteresis), z in [-3, 3]. */
    for (int x = ST_MIN; x <= ST_MAX; x++)
        for (int z = ST_MIN; z <= ST_MAX; z++)
            for (int y = 0; y < ST_H; y++) {
                int want = x >= 1 && x <= 8 && z >= -3 && z <= 3;
                CHECK(t.loaded[x - ST_MIN][z - ST_MIN][y] == want, "chunk (%d,%d,%d) loaded %d", x, y, z, !want);
            }
    CHECK(t.dropped == 4 * 7 * 3 && t.integrated == 7 * 7 * 3 + 5 * 7 * 3, "dropped %d, integrated %d", t.dropped,
          t.integrated);
    CHECK(stream_pending(s) == 0, "pending after settling");
    CHECK(t.most_per_call >= 2 && t.most_per_call <= MAX_PER_CALL, "budget not kept: %d chunks in one call",
          t.most_per_call);

    /* Jump away and back before anything settles (in-flight chunks get
     * discarded), then back to the origin: dropped chunks come back. */
    stream_update(s, 15, 15, st_drop, &t);
    stream_update(s, 0, 0, st_drop, &t);
    model_step(model, 15, 15);
    model_step(model, 0, 0);
    st_run(s, &t, 0, 0);
    CHECK(!t.errors, "jumps: %d bad callbacks", t.errors);
    CHECK(!memcmp(t.loaded, model, sizeof model), "after jumps: loaded set differs from the model");
    stream_destroy(s);

    /* Shutdown with work in flight, with one worker. */
    d.threads = 1;
    d.radius = 12;
    s = stream_create(&d);
    if (!CHECK(s, "stream_create"))
        return 1;
    stream_update(s, 3, -2, NULL, NULL);
    CHECK(stream_pending(s) > 0, "nothing pending");
    stream_destroy(s);

    qsort(t.times, (size_t)t.ntimes, sizeof *t.times, cmp_double);
    printf("integrate calls %d (budget %.2f ms, >= %.2f ms per chunk, at most %d per call): median %.3f ms, max %.3f ms\n",
           t.ntimes, BUDGET_MS, UPLOAD_MS, t.most_per_call, t.times[t.ntimes / 2], t.times[t.ntimes - 1]);
    return 0;
}

/* ---- perf ---- */

typedef struct sink {
    int n;
    uint64_t h;
} sink;

static void sink_integrate(void *user, int cx, int cy, int cz, const vrg_block *blocks)
{
    (void)cx, (void)cy, (void)cz;
    sink *k = user;
    k->n++;
    k->h ^= fnv1a64(FNV_OFFSET, blocks, VRG_CHUNK_VOXELS);
}

static int test_perf(void)
{
    terrain_params p;
    terrain_params_default(&p);
    enum { R = 13 };
    const int total = (2 * R + 1) * (2 * R + 1) * 3;
    static vrg_block buf[VRG_CHUNK_VOXELS];
    uint64_t direct_hash = 0;
    double t0 = now_ms();
    for (int cx = -R; cx <= R; cx++)
        for (int cz = -R; cz <= R; cz++)
            for (int cy = 0; cy < 3; cy++) {
                terrain_generate_chunk(&p, cx, cy, cz, buf);
                direct_hash ^= fnv1a64(FNV_OFFSET, buf, sizeof buf);
            }
    double single = now_ms() - t0;
    printf("%d chunks, 1 thread (direct): %.1f ms (%.1f us/chunk)\n", total, single, 1e3 * single / total);

    for (int threads = 1; threads <= 2; threads++) {
        stream_desc d = { .threads = threads, .radius = R, .hysteresis = 0, .height_chunks = 3, .generate = generate_cb, .user = &p };
        stream *s = stream_create(&d);
        if (!CHECK(s, "stream_create"))
        return 1;
        sink k = { 0 };
        t0 = now_ms();
        stream_update(s, 0, 0, NULL, NULL);
        stream_wait_idle(s);
        double gen = now_ms() - t0;
        while (stream_pending(s))
            stream_integrate(s, 1e9, sink_integrate, &k, NULL);
        stream_destroy(s);
        CHECK(k.n == total && k.h == direct_hash, "streamed %d chunks, hash %s", k.n, k.h == direct_hash ? "same" : "differs");
        printf("%d chunks, %d thread(s) (stream): %.1f ms\n", total, threads, gen);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(void);
    } cases[] = {
        { "noise", test_noise },
        { "determinism", test_determinism },
        { "trees_across_borders", test_trees_across_borders },
        { "biomes_bruteforce", test_biomes_bruteforce },
        { "streaming", test_streaming },
        { "layers", test_layers },
        { "perf", test_perf },
    };
    if (argc != 2) {
        fprintf(stderr, "usage: test_terrain CASE\n");
        return 2;
    }
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        if (!strcmp(argv[1], cases[i].name)) {
            if (cases[i].fn() || failures) {
                fprintf(stderr, "%s: FAILED (%d checks)\n", cases[i].name, failures);
                return 1;
            }
            printf("%s: ok\n", cases[i].name);
            return 0;
        }
    fprintf(stderr, "unknown case %s\n", argv[1]);
    return 2;
}
