/* The edit journal (voxrg/edits.h). File layout, little-endian:
 *   header: "VRGEDIT1", u32 key length, key bytes, u32 CRC-32 of all before
 *   records, 20 bytes each: u8 kind ('E' edit, 'U' undo, 'R' redo), u8 old,
 *     u8 new, u8 0, i32 x, y, z, u32 CRC-32 of the 16 bytes before
 * The header is written once, to a temporary file that is synced and
 * renamed into place (then the folder is synced): a journal either has its
 * whole header or does not exist. Records are appended with one write()
 * each and synced before the world changes. Appending beats rewriting the
 * file per edit: an edit costs 20 bytes and one sync however long the
 * history is. A kill or power loss can only tear the last record, which
 * opening drops; a damaged record with records after it is corruption,
 * reported, never skipped. A record outside the world, or naming a block
 * without a material, is refused as well: the world could not show it.
 *
 * The journal's bytes are also kept in memory: when the file is deleted or
 * moved away while edits go on (an append would land in a file nobody will
 * read), the next append writes it again at its path, whole, as the header
 * is written. A different file found at the path is left alone: the edit
 * is refused. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdarg.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "voxrg/edits.h"

#define MAGIC "VRGEDIT1"
#define RECORD 20

typedef struct change { /* the block the edits leave at a position */
    int x, y, z;
    vrg_block block;
} change;

typedef struct op { /* an edit record, for undo and redo */
    int x, y, z;
    vrg_block old, now;
} op;

struct vrg_edits {
    char path[4096];
    char key[VRG_EDITS_KEY_MAX];
    int fd;            /* open for appending once the file exists; -1 before */
    dev_t dev;         /* the file fd is (or is to be) opened on, to notice */
    ino_t ino;         /* another one, or none, at the path */
    uint8_t *bytes;    /* the header and the whole records: the file as it should be */
    size_t bytes_cap;
    long valid_bytes;  /* bytes used: a torn tail beyond is cut before appending */
    long dropped;
    int height;        /* blocks: y in [0, height) */
    int materials;     /* block ids below it have a material */
    int records;
    change *changes;   /* sorted by chunk, then position (apply_chunk finds a chunk's range) */
    int change_count, change_cap;
    op *done, *undone; /* the undo and redo stacks */
    int done_count, done_cap, undone_count, undone_cap;
};

static uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = c >> 1 ^ (0xedb88320u & (0u - (c & 1)));
    }
    return ~c;
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> 8 * i);
}
static uint32_t get32(const uint8_t *p) { return p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

static int chunk_order(const change *a, int x, int y, int z)
{
    int ca[3] = {vrg_floor_div16(a->y), vrg_floor_div16(a->z), vrg_floor_div16(a->x)};
    int cb[3] = {vrg_floor_div16(y), vrg_floor_div16(z), vrg_floor_div16(x)};
    const int pa[3] = {a->y, a->z, a->x}, pb[3] = {y, z, x};
    for (int i = 0; i < 3; i++)
        if (ca[i] != cb[i])
            return ca[i] < cb[i] ? -1 : 1;
    for (int i = 0; i < 3; i++)
        if (pa[i] != pb[i])
            return pa[i] < pb[i] ? -1 : 1;
    return 0;
}

/* The first change not ordered before (x, y, z). */
static int lower_bound(const vrg_edits *e, int x, int y, int z)
{
    int lo = 0, hi = e->change_count;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (chunk_order(&e->changes[mid], x, y, z) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static int grow(void **p, int *cap, int need, size_t item)
{
    if (need <= *cap)
        return 0;
    int n = *cap ? 2 * *cap : 64;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, (size_t)n * item);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

static int set_change(vrg_edits *e, int x, int y, int z, vrg_block b)
{
    int i = lower_bound(e, x, y, z);
    if (i < e->change_count && chunk_order(&e->changes[i], x, y, z) == 0) {
        e->changes[i].block = b;
        return 0;
    }
    if (grow((void **)&e->changes, &e->change_cap, e->change_count + 1, sizeof *e->changes) != 0)
        return -1;
    memmove(e->changes + i + 1, e->changes + i, (size_t)(e->change_count - i) * sizeof *e->changes);
    e->changes[i] = (change){x, y, z, b};
    e->change_count++;
    return 0;
}

static int push(op **stack, int *count, int *cap, op o)
{
    if (grow((void **)stack, cap, *count + 1, sizeof **stack) != 0)
        return -1;
    (*stack)[(*count)++] = o;
    return 0;
}

/* What a record does to the state; 1 when it makes no sense (an undo with
 * nothing done), -1 out of memory. */
static int replay(vrg_edits *e, int kind, op o)
{
    switch (kind) {
    case 'E':
        e->undone_count = 0;
        return push(&e->done, &e->done_count, &e->done_cap, o) || set_change(e, o.x, o.y, o.z, o.now) ? -1 : 0;
    case 'U':
        if (!e->done_count)
            return 1;
        o = e->done[--e->done_count];
        return push(&e->undone, &e->undone_count, &e->undone_cap, o) || set_change(e, o.x, o.y, o.z, o.old) ? -1 : 0;
    case 'R':
        if (!e->undone_count)
            return 1;
        o = e->undone[--e->undone_count];
        return push(&e->done, &e->done_count, &e->done_cap, o) || set_change(e, o.x, o.y, o.z, o.now) ? -1 : 0;
    }
    return 1;
}

static int failf(char *err, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int failf(char *err, size_t n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, n, fmt, ap);
    va_end(ap);
    return -1;
}

static size_t header_bytes(const vrg_edits *e) { return 8 + 4 + strlen(e->key) + 4; }

/* 0 when the world can hold block b at (x, y, z), else -1 with why. Within
 * VRG_WORLD_LIMIT block coordinates and their chunks fit an int. */
static int check_edit(const vrg_edits *e, int x, int y, int z, int b, char *why, size_t n)
{
    const int limit = (int)VRG_WORLD_LIMIT;
    if (x < -limit || x >= limit || z < -limit || z >= limit || y < 0 || y >= e->height)
        return failf(why, n, "block %d %d %d is outside the world (x and z in [%d, %d), y in [0, %d))", x, y, z, -limit, limit, e->height);
    if (b >= e->materials)
        return failf(why, n, "block id %d has no material (this world's ids are 0 to %d)", b, e->materials - 1);
    return 0;
}

static int load(vrg_edits *e, const uint8_t *d, size_t size, char *err, size_t n)
{
    size_t klen = strlen(e->key);
    if (size < 12 || memcmp(d, MAGIC, 8) != 0)
        return failf(err, n, "%s: not an edit journal (it does not start with '" MAGIC "')", e->path);
    uint32_t flen = get32(d + 8);
    if (flen >= VRG_EDITS_KEY_MAX || 12 + (size_t)flen + 4 > size || crc32(d, 12 + flen) != get32(d + 12 + flen))
        return failf(err, n, "%s: the header is damaged (its checksum does not match)", e->path);
    if (flen != klen || memcmp(d + 12, e->key, klen) != 0) {
        char theirs[4 * VRG_EDITS_KEY_MAX], ours[4 * VRG_EDITS_KEY_MAX]; /* the file's bytes, quoted as text */
        return failf(err, n, "%s: these edits belong to another world ('%s'), this scene is '%s': move the file away or set the scene's edits parameter",
                     e->path, vrg_escape(theirs, sizeof theirs, (const char *)(d + 12), flen), vrg_escape(ours, sizeof ours, e->key, klen));
    }
    size_t pos = header_bytes(e);
    for (; pos + RECORD <= size; pos += RECORD) {
        const uint8_t *r = d + pos;
        if (crc32(r, 16) != get32(r + 16)) {
            if (pos + RECORD < size)
                return failf(err, n, "%s: record at byte %zu is damaged and records follow it (not a torn last write)", e->path, pos);
            break; /* the last record, torn */
        }
        op o = {(int32_t)get32(r + 4), (int32_t)get32(r + 8), (int32_t)get32(r + 12), r[1], r[2]};
        char why[160];
        if (check_edit(e, o.x, o.y, o.z, o.old > o.now ? o.old : o.now, why, sizeof why) != 0)
            return failf(err, n, "%s: record at byte %zu: %s", e->path, pos, why);
        int rc = replay(e, r[0], o);
        if (rc < 0)
            return failf(err, n, "%s: out of memory", e->path);
        if (rc > 0)
            return failf(err, n, "%s: record at byte %zu is '%c', which nothing before it allows", e->path, pos, r[0] >= 32 && r[0] < 127 ? r[0] : '?');
        e->records++;
    }
    e->valid_bytes = (long)pos;
    e->dropped = (long)(size - pos);
    return 0;
}

static int read_file(vrg_edits *e, char *err, size_t n)
{
    int fd = vrg_open_regular(e->path, O_RDONLY); /* a FIFO must not block the open */
    if (fd < 0) {
        if (errno == ENOENT)
            return 0; /* no edits yet */
        return failf(err, n, "%s: cannot open: %s", e->path, vrg_open_strerror(errno));
    }
    struct stat st;
    uint8_t *d = NULL;
    int rc = -1;
    if (fstat(fd, &st) != 0)
        failf(err, n, "%s: cannot open: %s", e->path, strerror(errno));
    else if (!(d = malloc(st.st_size ? (size_t)st.st_size : 1)))
        failf(err, n, "%s: out of memory for %lld bytes", e->path, (long long)st.st_size);
    else {
        size_t got = 0;
        while (got < (size_t)st.st_size) {
            ssize_t k = read(fd, d + got, (size_t)st.st_size - got);
            if (k <= 0)
                break;
            got += (size_t)k;
        }
        rc = got == (size_t)st.st_size ? load(e, d, got, err, n) : failf(err, n, "%s: read failed", e->path);
    }
    close(fd);
    if (rc != 0) {
        free(d);
        return rc;
    }
    e->bytes = d; /* the journal as read, less a torn tail (valid_bytes) */
    e->bytes_cap = st.st_size ? (size_t)st.st_size : 1;
    e->dev = st.st_dev;
    e->ino = st.st_ino;
    e->fd = -2; /* exists: opened for appending at the first edit */
    return 0;
}

/* Room for `more` bytes after the valid ones. */
static int reserve(vrg_edits *e, size_t more)
{
    size_t need = (size_t)e->valid_bytes + more;
    if (need <= e->bytes_cap)
        return 0;
    size_t cap = e->bytes_cap ? 2 * e->bytes_cap : 4096;
    while (cap < need)
        cap *= 2;
    uint8_t *b = realloc(e->bytes, cap);
    if (!b)
        return -1;
    e->bytes = b;
    e->bytes_cap = cap;
    return 0;
}

/* A journal not written yet: its header. */
static int start_bytes(vrg_edits *e)
{
    size_t klen = strlen(e->key);
    if (reserve(e, header_bytes(e)) != 0)
        return -1;
    uint8_t *h = e->bytes;
    memcpy(h, MAGIC, 8);
    put32(h + 8, (uint32_t)klen);
    memcpy(h + 12, e->key, klen);
    put32(h + 12 + klen, crc32(h, 12 + klen));
    e->valid_bytes = (long)header_bytes(e);
    return 0;
}

vrg_edits *vrg_edits_open(const char *path, const char *key, const vrg_world *w, char *err, size_t err_size)
{
    vrg_edits *e = calloc(1, sizeof *e);
    if (!e) {
        failf(err, err_size, "%s: out of memory", path);
        return NULL;
    }
    e->fd = -1;
    if (strlen(path) >= sizeof e->path || strlen(key) >= sizeof e->key) {
        failf(err, err_size, "%s: path or world key too long", path);
        free(e);
        return NULL;
    }
    strcpy(e->path, path);
    strcpy(e->key, key);
    int dims[3];
    vrg_world_grid(w, dims);
    e->height = dims[1] * VRG_CHUNK_SIZE;
    e->materials = vrg_world_material_count(w);
    int rc = read_file(e, err, err_size);
    if (rc == 0 && !e->bytes && start_bytes(e) != 0)
        rc = failf(err, err_size, "%s: out of memory", path);
    if (rc != 0) {
        vrg_edits_close(e);
        return NULL;
    }
    return e;
}

void vrg_edits_close(vrg_edits *e)
{
    if (!e)
        return;
    if (e->fd >= 0)
        close(e->fd);
    free(e->bytes);
    free(e->changes);
    free(e->done);
    free(e->undone);
    free(e);
}

int vrg_edits_records(const vrg_edits *e) { return e->records; }
long vrg_edits_dropped_bytes(const vrg_edits *e) { return e->dropped; }
const char *vrg_edits_path(const vrg_edits *e) { return e->path; }

static int sync_folder(const char *path)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *(slash == dir ? slash + 1 : slash) = '\0';
    else
        strcpy(dir, ".");
    int fd = open(dir, O_RDONLY | O_DIRECTORY);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

/* The journal's bytes as the file at its path, atomically: a temporary
 * file, synced, renamed, the folder synced. */
static int create_file(vrg_edits *e, char *err, size_t n)
{
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", e->path, (long)getpid());
    unlink(tmp); /* a stale one; O_EXCL then opens nothing else (a FIFO would block) */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    int ok = fd >= 0 && write(fd, e->bytes, (size_t)e->valid_bytes) == (ssize_t)e->valid_bytes && fsync(fd) == 0;
    if (fd >= 0)
        close(fd);
    if (!ok || rename(tmp, e->path) != 0 || sync_folder(e->path) != 0) {
        int code = errno;
        unlink(tmp);
        return failf(err, n, "%s: cannot create: %s", e->path, strerror(code));
    }
    e->dropped = 0; /* a torn tail was not written again */
    return 0;
}

static int replaced(const vrg_edits *e, char *err, size_t n)
{
    return failf(err, n, "%s: another file took the journal's place since it was opened: the edit is not written (move that file away to go on)",
                 e->path);
}

/* Opens for appending, cutting a torn tail first (records go after whole
 * ones). Another file at the path than the one read is refused. */
static int open_append(vrg_edits *e, char *err, size_t n)
{
    if (e->fd >= 0)
        return 0;
    int created = e->fd == -1;
    if (created && create_file(e, err, n) != 0)
        return -1;
    e->fd = vrg_open_regular(e->path, O_WRONLY | O_APPEND);
    struct stat st;
    if (e->fd < 0 || fstat(e->fd, &st) != 0) {
        int code = errno;
        if (e->fd >= 0)
            close(e->fd);
        e->fd = -2;
        return failf(err, n, "%s: cannot open for writing: %s", e->path, vrg_open_strerror(code));
    }
    if (!created && (st.st_dev != e->dev || st.st_ino != e->ino)) {
        close(e->fd);
        e->fd = -2;
        return replaced(e, err, n);
    }
    e->dev = st.st_dev;
    e->ino = st.st_ino;
    if (e->dropped && (ftruncate(e->fd, e->valid_bytes) != 0 || fsync(e->fd) != 0)) {
        close(e->fd);
        e->fd = -2;
        return failf(err, n, "%s: cannot cut the torn last record: %s", e->path, strerror(errno));
    }
    e->dropped = 0;
    return 0;
}

/* Whether the journal read or written is still at its path: 0 yes, 1 no
 * file is there (it was deleted or moved away: appending to it would save
 * nothing anyone reads), -1 another file is. */
static int journal_moved(const vrg_edits *e)
{
    struct stat st;
    if (e->fd == -1) /* not created yet */
        return 0;
    if (stat(e->path, &st) != 0)
        return errno == ENOENT;
    return st.st_dev == e->dev && st.st_ino == e->ino ? 0 : -1;
}

static int append(vrg_edits *e, int kind, op o, char *err, size_t n)
{
    uint8_t r[RECORD] = {(uint8_t)kind, o.old, o.now, 0};
    put32(r + 4, (uint32_t)o.x);
    put32(r + 8, (uint32_t)o.y);
    put32(r + 12, (uint32_t)o.z);
    put32(r + 16, crc32(r, 16));
    if (reserve(e, RECORD) != 0)
        return failf(err, n, "%s: out of memory", e->path);
    int moved = journal_moved(e), rewritten = moved == 1;
    if (moved && e->fd >= 0)
        close(e->fd);
    if (moved)
        e->fd = rewritten ? -1 : -2;
    if (moved < 0)
        return replaced(e, err, n);
    if (open_append(e, err, n) != 0)
        return -1;
    if (write(e->fd, r, RECORD) != RECORD || fdatasync(e->fd) != 0) {
        int code = errno;
        /* a partial record would sit before the next one: cut it */
        if (ftruncate(e->fd, e->valid_bytes) != 0) {
            close(e->fd);
            e->fd = -2;
        }
        return failf(err, n, "%s: cannot write an edit: %s", e->path, strerror(code));
    }
    memcpy(e->bytes + e->valid_bytes, r, RECORD);
    e->valid_bytes += RECORD;
    e->records++;
    if (rewritten)
        snprintf(err, n, "%s was deleted or moved away: written again with all %d records", e->path, e->records);
    return 0;
}

int vrg_edits_block(const vrg_edits *e, int x, int y, int z, vrg_block *b)
{
    int i = lower_bound(e, x, y, z);
    if (i < e->change_count && chunk_order(&e->changes[i], x, y, z) == 0) {
        *b = e->changes[i].block;
        return 1;
    }
    return 0;
}

int vrg_edits_apply_chunk(const vrg_edits *e, int cx, int cy, int cz, vrg_block *blocks)
{
    int n = 0;
    for (int i = lower_bound(e, cx * 16, cy * 16, cz * 16); i < e->change_count; i++, n++) {
        const change *c = &e->changes[i];
        if (vrg_floor_div16(c->x) != cx || vrg_floor_div16(c->y) != cy || vrg_floor_div16(c->z) != cz)
            break;
        blocks[vrg_chunk_index(c->x & 15, c->y & 15, c->z & 15)] = c->block;
    }
    return n;
}

int vrg_edits_apply_world(const vrg_edits *e, vrg_world *w)
{
    int n = 0;
    for (int i = 0; i < e->change_count; i++)
        n += vrg_world_set_block(w, e->changes[i].x, e->changes[i].y, e->changes[i].z, e->changes[i].block) == 0;
    return n;
}

static int record(vrg_edits *e, vrg_world *w, int kind, op o, char *err, size_t n)
{
    if (n)
        err[0] = '\0';
    if (append(e, kind, o, err, n) != 0)
        return -1;
    if (replay(e, kind, o) < 0)
        return failf(err, n, "%s: out of memory", e->path);
    vrg_block b;
    if (vrg_edits_block(e, o.x, o.y, o.z, &b) == 1 && w)
        vrg_world_set_block(w, o.x, o.y, o.z, b);
    return 0;
}

int vrg_edits_set(vrg_edits *e, vrg_world *w, int x, int y, int z, vrg_block b, char *err, size_t n)
{
    op o = {x, y, z, w ? vrg_world_block(w, x, y, z) : VRG_BLOCK_AIR, b};
    char why[160];
    if (check_edit(e, x, y, z, b, why, sizeof why) != 0)
        return failf(err, n, "%s: not written: %s", e->path, why);
    return record(e, w, 'E', o, err, n);
}

int vrg_edits_undo(vrg_edits *e, vrg_world *w, char *err, size_t n)
{
    if (!e->done_count)
        return 1;
    return record(e, w, 'U', e->done[e->done_count - 1], err, n);
}

int vrg_edits_redo(vrg_edits *e, vrg_world *w, char *err, size_t n)
{
    if (!e->undone_count)
        return 1;
    return record(e, w, 'R', e->undone[e->undone_count - 1], err, n);
}

vrg_edits *vrg_graph_edits(const vrg_graph *g) { return vrg_graph_shared(g, VRG_EDITS_SHARED_NAME); }
