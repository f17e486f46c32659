/* Chunk streaming around a moving camera: a pthread worker pool generates
 * the chunks near the camera, nearest first, and the main thread integrates
 * finished chunks under a time budget and drops far ones.
 *
 * Regions, around the camera chunk column (cam_cx, cam_cz):
 *   wanted: |dx| <= radius && |dz| <= radius, every cy in [0, height_chunks)
 *   kept:   |dx| <= radius + hysteresis && |dz| <= radius + hysteresis
 * Chunks leave the queue, and finished-but-not-integrated chunks are
 * discarded, as soon as they leave the wanted region; only loaded
 * (integrated) chunks enjoy the hysteresis and are dropped once they leave
 * the kept region. A dropped chunk is requested again when it is wanted.
 *
 * stream_update, stream_integrate and stream_pending are for one (main)
 * thread; the generate callback runs on the workers, concurrently. */
#ifndef VOXRG_TERRAIN_STREAM_H
#define VOXRG_TERRAIN_STREAM_H

#include "voxrg/world.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef void (*stream_generate_fn)(void *user, int cx, int cy, int cz, vrg_block out[VRG_CHUNK_VOXELS]);

typedef struct stream_desc {
    int threads;       /* workers; 0 or 1 both mean one */
    int radius;        /* >= 0 */
    int hysteresis;    /* >= 0 */
    int height_chunks; /* >= 1 */
    stream_generate_fn generate;
    void *user;        /* passed to generate */
} stream_desc;

typedef struct stream stream;

/* NULL on invalid desc or out of memory. */
stream *stream_create(const stream_desc *d);
/* Joins the workers (each finishes the chunk it is generating) and frees
 * every chunk not yet integrated. NULL is ignored. */
void stream_destroy(stream *s);

/* Once per frame with the camera's chunk column: queues missing wanted
 * chunks nearest first (by horizontal chunk distance; ties by cy, then dx,
 * then dz), cancels queued ones no longer wanted, and calls drop (if not
 * NULL) for loaded chunks outside the kept region. Cheap when the camera
 * stayed in the same column. */
void stream_update(stream *s, int cam_cx, int cam_cz, void (*drop)(void *user, int cx, int cy, int cz), void *user);

/* Hands finished chunks to integrate(), nearest first, until budget_ms of
 * wall time has been spent (at least one per call if any is ready). The
 * blocks are only valid during the call. Returns the number integrated;
 * *spent_ms (if not NULL) gets the time spent. */
int stream_integrate(stream *s, double budget_ms,
                     void (*integrate)(void *user, int cx, int cy, int cz, const vrg_block *blocks), void *user,
                     double *spent_ms);

/* Queued + generating + finished-not-integrated. */
int stream_pending(const stream *s);
/* Blocks until nothing is queued or generating. */
void stream_wait_idle(stream *s);

#ifdef __cplusplus
}
#endif
#endif
