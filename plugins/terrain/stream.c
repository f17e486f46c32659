/* Chunk streaming: one mutex guards everything shared with the workers; the
 * generate callback and integrate callbacks run without it. */
#define _POSIX_C_SOURCE 200809L
#include "stream.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Bounds that keep every size computation below far from overflow. */
#define STREAM_MAX_RADIUS 4096
#define STREAM_MAX_HEIGHT 4096
#define STREAM_MAX_THREADS 256

typedef struct chunk_key {
    int cx, cy, cz;
} chunk_key;

enum chunk_state { SLOT_EMPTY, CHUNK_QUEUED, CHUNK_GENERATING, CHUNK_FINISHED, CHUNK_LOADED };

typedef struct slot {
    chunk_key key;
    int state;
    vrg_block *blocks; /* CHUNK_FINISHED only */
} slot;

/* A finished chunk taken out for integration, with its camera-relative key. */
typedef struct ready {
    chunk_key key, rel;
    vrg_block *blocks;
} ready;

struct stream {
    stream_desc desc;
    pthread_mutex_t lock;
    pthread_cond_t work_cv, idle_cv;
    pthread_t *workers;
    int nworkers, shutdown;

    /* Every chunk the stream knows, by key: linear probing, kept at most half
     * full. It never grows: between updates it holds at most the kept region
     * (loaded) plus one chunk per worker being generated outside it, and the
     * capacity is sized for that at creation. */
    slot *slots;
    size_t mask;

    chunk_key *offsets; /* the wanted region relative to the camera, nearest first */
    size_t noffsets;
    /* Queued keys, nearest first; workers take from head. Queued and finished
     * chunks are always in the wanted region, so noffsets bounds both. */
    chunk_key *queue;
    size_t queue_head, queue_len;
    chunk_key *finished;
    size_t nfinished;
    int generating;

    int cam_cx, cam_cz, have_cam;
    int dirty; /* a wanted chunk was lost (out of memory): re-queue next update */

    /* Main-thread scratch: removals in update, the batch in integrate. */
    chunk_key *scratch;
    ready *batch;
};

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* ---- chunk table ---- */

static size_t key_hash(chunk_key k)
{
    uint32_t h = (uint32_t)k.cx * 0x9e3779b1u ^ (uint32_t)k.cz * 0x85ebca77u ^ (uint32_t)k.cy * 0xc2b2ae3du;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return h;
}

static int key_eq(chunk_key a, chunk_key b) { return a.cx == b.cx && a.cy == b.cy && a.cz == b.cz; }

static slot *table_find(stream *s, chunk_key k)
{
    for (size_t i = key_hash(k) & s->mask;; i = (i + 1) & s->mask) {
        if (s->slots[i].state == SLOT_EMPTY)
            return NULL;
        if (key_eq(s->slots[i].key, k))
            return &s->slots[i];
    }
}

/* The slot of k, added as CHUNK_QUEUED if absent. */
static slot *table_find_or_queue(stream *s, chunk_key k)
{
    size_t i = key_hash(k) & s->mask;
    for (; s->slots[i].state != SLOT_EMPTY; i = (i + 1) & s->mask)
        if (key_eq(s->slots[i].key, k))
            return &s->slots[i];
    s->slots[i] = (slot){ .key = k, .state = CHUNK_QUEUED };
    return &s->slots[i];
}

/* Backward-shift deletion: later entries of the probe run move up into the
 * hole when their home position allows, so lookups never need tombstones. */
static void table_remove(stream *s, chunk_key k)
{
    size_t i = key_hash(k) & s->mask;
    while (s->slots[i].state != SLOT_EMPTY && !key_eq(s->slots[i].key, k))
        i = (i + 1) & s->mask;
    if (s->slots[i].state == SLOT_EMPTY)
        return;
    for (size_t j = i;;) {
        s->slots[i].state = SLOT_EMPTY;
        for (;;) {
            j = (j + 1) & s->mask;
            if (s->slots[j].state == SLOT_EMPTY)
                return;
            size_t home = key_hash(s->slots[j].key) & s->mask;
            /* Stay if home lies cyclically in (i, j]. */
            int stays = i <= j ? (home > i && home <= j) : (home > i || home <= j);
            if (!stays)
                break;
        }
        s->slots[i] = s->slots[j];
        i = j;
    }
}

/* ---- ordering and regions ---- */

/* Nearest first by horizontal distance; ties by cy, dx, dz. */
static int rel_cmp(const chunk_key *a, const chunk_key *b)
{
    long long da = (long long)a->cx * a->cx + (long long)a->cz * a->cz;
    long long db = (long long)b->cx * b->cx + (long long)b->cz * b->cz;
    if (da != db)
        return da < db ? -1 : 1;
    if (a->cy != b->cy)
        return a->cy < b->cy ? -1 : 1;
    if (a->cx != b->cx)
        return a->cx < b->cx ? -1 : 1;
    return (a->cz > b->cz) - (a->cz < b->cz);
}

static int offset_cmp(const void *a, const void *b) { return rel_cmp(a, b); }
static int ready_cmp(const void *a, const void *b) { return rel_cmp(&((const ready *)a)->rel, &((const ready *)b)->rel); }

static int within(const stream *s, chunk_key k, int r)
{
    long long dx = (long long)k.cx - s->cam_cx, dz = (long long)k.cz - s->cam_cz;
    return dx >= -r && dx <= r && dz >= -r && dz <= r;
}

/* ---- workers ---- */

static void *worker_main(void *arg)
{
    stream *s = arg;
    pthread_mutex_lock(&s->lock);
    for (;;) {
        while (!s->shutdown && s->queue_head == s->queue_len)
            pthread_cond_wait(&s->work_cv, &s->lock);
        if (s->shutdown)
            break;
        chunk_key k = s->queue[s->queue_head++];
        table_find(s, k)->state = CHUNK_GENERATING;
        s->generating++;
        pthread_mutex_unlock(&s->lock);

        vrg_block *blocks = malloc(VRG_CHUNK_VOXELS);
        if (blocks)
            s->desc.generate(s->desc.user, k.cx, k.cy, k.cz, blocks);

        pthread_mutex_lock(&s->lock);
        s->generating--;
        /* Updates never remove generating chunks, so k is still there; the
         * camera may have moved away meanwhile, and then it is discarded. */
        if (blocks && !s->shutdown && within(s, k, s->desc.radius)) {
            slot *e = table_find(s, k);
            e->state = CHUNK_FINISHED;
            e->blocks = blocks;
            s->finished[s->nfinished++] = k;
            blocks = NULL;
        } else {
            table_remove(s, k);
            if (!blocks)
                s->dirty = 1;
        }
        if (s->queue_head == s->queue_len && s->generating == 0)
            pthread_cond_broadcast(&s->idle_cv);
        if (blocks) {
            pthread_mutex_unlock(&s->lock);
            free(blocks);
            pthread_mutex_lock(&s->lock);
        }
    }
    pthread_mutex_unlock(&s->lock);
    return NULL;
}

/* ---- lifetime ---- */

static void free_all(stream *s)
{
    if (s->slots)
        for (size_t i = 0; i <= s->mask; i++)
            if (s->slots[i].state == CHUNK_FINISHED)
                free(s->slots[i].blocks);
    free(s->slots);
    free(s->offsets);
    free(s->queue);
    free(s->finished);
    free(s->scratch);
    free(s->batch);
    free(s->workers);
    free(s);
}

stream *stream_create(const stream_desc *d)
{
    if (!d || !d->generate || d->radius < 0 || d->radius > STREAM_MAX_RADIUS || d->hysteresis < 0 ||
        d->hysteresis > STREAM_MAX_RADIUS || d->height_chunks < 1 || d->height_chunks > STREAM_MAX_HEIGHT)
        return NULL;
    stream *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->desc = *d;
    int want_workers = d->threads < 1 ? 1 : d->threads > STREAM_MAX_THREADS ? STREAM_MAX_THREADS : d->threads;

    size_t side = 2 * (size_t)d->radius + 1, kept_side = 2 * ((size_t)d->radius + (size_t)d->hysteresis) + 1;
    s->noffsets = side * side * (size_t)d->height_chunks;
    size_t most = kept_side * kept_side * (size_t)d->height_chunks + (size_t)want_workers;
    size_t cap = 16;
    while (cap < 2 * most)
        cap *= 2;
    s->mask = cap - 1;
    s->slots = calloc(cap, sizeof *s->slots);
    s->scratch = malloc(cap * sizeof *s->scratch);
    s->offsets = malloc(s->noffsets * sizeof *s->offsets);
    s->queue = malloc(s->noffsets * sizeof *s->queue);
    s->finished = malloc(s->noffsets * sizeof *s->finished);
    s->batch = malloc(s->noffsets * sizeof *s->batch);
    s->workers = malloc((size_t)want_workers * sizeof *s->workers);
    if (!s->slots || !s->scratch || !s->offsets || !s->queue || !s->finished || !s->batch || !s->workers) {
        free_all(s);
        return NULL;
    }
    size_t n = 0;
    for (int dz = -d->radius; dz <= d->radius; dz++)
        for (int dx = -d->radius; dx <= d->radius; dx++)
            for (int cy = 0; cy < d->height_chunks; cy++)
                s->offsets[n++] = (chunk_key){ dx, cy, dz };
    qsort(s->offsets, n, sizeof *s->offsets, offset_cmp);

    if (pthread_mutex_init(&s->lock, NULL)) {
        free_all(s);
        return NULL;
    }
    if (pthread_cond_init(&s->work_cv, NULL)) {
        pthread_mutex_destroy(&s->lock);
        free_all(s);
        return NULL;
    }
    if (pthread_cond_init(&s->idle_cv, NULL)) {
        pthread_cond_destroy(&s->work_cv);
        pthread_mutex_destroy(&s->lock);
        free_all(s);
        return NULL;
    }
    /* Fewer workers than asked is still a working stream; none is not. */
    for (int i = 0; i < want_workers; i++)
        if (pthread_create(&s->workers[s->nworkers], NULL, worker_main, s) == 0)
            s->nworkers++;
    if (s->nworkers == 0) {
        pthread_cond_destroy(&s->idle_cv);
        pthread_cond_destroy(&s->work_cv);
        pthread_mutex_destroy(&s->lock);
        free_all(s);
        return NULL;
    }
    return s;
}

void stream_destroy(stream *s)
{
    if (!s)
        return;
    pthread_mutex_lock(&s->lock);
    s->shutdown = 1;
    pthread_cond_broadcast(&s->work_cv);
    pthread_cond_broadcast(&s->idle_cv);
    pthread_mutex_unlock(&s->lock);
    for (int i = 0; i < s->nworkers; i++)
        pthread_join(s->workers[i], NULL);
    pthread_cond_destroy(&s->idle_cv);
    pthread_cond_destroy(&s->work_cv);
    pthread_mutex_destroy(&s->lock);
    free_all(s);
}

/* ---- main thread ---- */

void stream_update(stream *s, int cam_cx, int cam_cz, void (*drop)(void *user, int cx, int cy, int cz), void *user)
{
    pthread_mutex_lock(&s->lock);
    if (s->have_cam && !s->dirty && cam_cx == s->cam_cx && cam_cz == s->cam_cz) {
        pthread_mutex_unlock(&s->lock);
        return;
    }
    s->cam_cx = cam_cx;
    s->cam_cz = cam_cz;
    s->have_cam = 1;
    s->dirty = 0;
    const int wanted = s->desc.radius, kept = s->desc.radius + s->desc.hysteresis;

    /* Collect first, remove after: removal shifts entries, which would upset
     * the scan. Drops fill scratch from the front, other removals from the
     * back; together they are at most the table's entries. */
    size_t ndrop = 0, nremove = 0, cap = s->mask + 1;
    for (size_t i = 0; i < cap; i++) {
        slot *e = &s->slots[i];
        if ((e->state == CHUNK_QUEUED || e->state == CHUNK_FINISHED) && !within(s, e->key, wanted)) {
            if (e->state == CHUNK_FINISHED)
                free(e->blocks);
            s->scratch[cap - 1 - nremove++] = e->key;
        } else if (e->state == CHUNK_LOADED && !within(s, e->key, kept)) {
            s->scratch[ndrop++] = e->key;
        }
    }
    for (size_t i = 0; i < ndrop; i++)
        table_remove(s, s->scratch[i]);
    for (size_t i = 0; i < nremove; i++)
        table_remove(s, s->scratch[cap - 1 - i]);
    size_t nf = 0;
    for (size_t i = 0; i < s->nfinished; i++)
        if (within(s, s->finished[i], wanted))
            s->finished[nf++] = s->finished[i];
    s->nfinished = nf;

    /* Rebuild the queue in nearest-first order from the sorted offsets. */
    s->queue_head = s->queue_len = 0;
    for (size_t i = 0; i < s->noffsets; i++) {
        const chunk_key *o = &s->offsets[i];
        chunk_key k = { cam_cx + o->cx, o->cy, cam_cz + o->cz };
        if (table_find_or_queue(s, k)->state == CHUNK_QUEUED)
            s->queue[s->queue_len++] = k;
    }
    if (s->queue_len)
        pthread_cond_broadcast(&s->work_cv);
    pthread_mutex_unlock(&s->lock);

    if (drop)
        for (size_t i = 0; i < ndrop; i++)
            drop(user, s->scratch[i].cx, s->scratch[i].cy, s->scratch[i].cz);
}

int stream_integrate(stream *s, double budget_ms,
                     void (*integrate)(void *user, int cx, int cy, int cz, const vrg_block *blocks), void *user,
                     double *spent_ms)
{
    double t0 = now_ms();
    /* Take every finished chunk out, so the workers can keep finishing others
     * while the callbacks run; the main thread alone moves finished chunks
     * on, so their table entries stay put meanwhile. */
    pthread_mutex_lock(&s->lock);
    size_t n = integrate ? s->nfinished : 0;
    for (size_t i = 0; i < n; i++) {
        chunk_key k = s->finished[i];
        s->batch[i] = (ready){ .key = k, .rel = { k.cx - s->cam_cx, k.cy, k.cz - s->cam_cz }, .blocks = table_find(s, k)->blocks };
    }
    s->nfinished -= n;
    pthread_mutex_unlock(&s->lock);
    qsort(s->batch, n, sizeof *s->batch, ready_cmp);

    size_t done = 0;
    while (done < n && (done == 0 || now_ms() - t0 < budget_ms)) {
        const ready *r = &s->batch[done++];
        integrate(user, r->key.cx, r->key.cy, r->key.cz, r->blocks);
    }

    pthread_mutex_lock(&s->lock);
    for (size_t i = 0; i < done; i++) {
        slot *e = table_find(s, s->batch[i].key);
        e->state = CHUNK_LOADED;
        e->blocks = NULL;
    }
    for (size_t i = done; i < n; i++)
        s->finished[s->nfinished++] = s->batch[i].key;
    pthread_mutex_unlock(&s->lock);
    for (size_t i = 0; i < done; i++)
        free(s->batch[i].blocks);
    if (spent_ms)
        *spent_ms = now_ms() - t0;
    return (int)done;
}

int stream_pending(const stream *s)
{
    /* Locking changes the mutex, not what the stream holds. */
    stream *m = (stream *)s;
    pthread_mutex_lock(&m->lock);
    size_t n = m->queue_len - m->queue_head + (size_t)m->generating + m->nfinished;
    pthread_mutex_unlock(&m->lock);
    return (int)n;
}

void stream_wait_idle(stream *s)
{
    pthread_mutex_lock(&s->lock);
    while (!s->shutdown && (s->queue_head < s->queue_len || s->generating > 0))
        pthread_cond_wait(&s->idle_cv, &s->lock);
    pthread_mutex_unlock(&s->lock);
}
