/* A frame of a loaded graph: the host's per-frame state (camera, frame
 * index, history reset), recording and submitting it (record.c) after the
 * saved shaders swap in, waiting for it, and capturing its commands for a
 * benchmark's replay (capture.c keeps them). */
#define _POSIX_C_SOURCE 200809L
#include <time.h>
#include "internal.h"
#include "phases.h"
#include "capture.h"

int vrg_graph_frame(vrg_graph *g)
{
    if (!g->ctx || !g->allocated) {
        _vrg_error(&g->diag, VRG_E_NO_DEVICE, "graph '%s' has no device resources (loaded without a context, or its last resize failed)", g->name);
        return -1;
    }
    if (g->ctx->gpu_busy) { /* the command buffer may still be executing */
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "graph '%s': the GPU is still busy with a frame that timed out or was interrupted", g->name);
        return -1;
    }
    (void)vrg_graph_poll_changes(g); /* saved shaders swap in before recording */
    int rc = _vrg_record_frame(g);
    /* this frame used the change: the save-to-frame time ends when it has
     * ended on the GPU (the wait drains the frames in flight, once) */
    if (rc == 0 && g->pending_since > 0)
        rc = vrg_graph_wait(g);
    if (g->pending_since > 0) {
        struct timespec now;
        clock_gettime(CLOCK_REALTIME, &now);
        g->reload_ms = ((double)now.tv_sec + 1e-9 * (double)now.tv_nsec - g->pending_since) * 1e3;
        g->pending_since = 0;
    }
    return rc;
}

/* The runtime's barriers and dispatches of one frame, kept as data (capture.c). */
vrg_capture *vrg_graph_capture_frame(vrg_graph *g)
{
    vrg_capture *c = _vrg_capture_new(g->ctx->push_descriptor);
    if (!c)
        return NULL;
    g->capture = c;
    int rc = vrg_graph_frame(g);
    g->capture = NULL;
    /* the captured commands replay after this frame, which must have ended */
    if (rc == 0)
        rc = vrg_graph_wait(g);
    if (rc != 0) {
        vrg_capture_free(c);
        return NULL;
    }
    return c;
}

int vrg_graph_wait(vrg_graph *g)
{
    if (g->ctx && g->ctx->gpu_busy) {
        _vrg_error(&g->diag, VRG_E_GPU_BUSY, "graph '%s': the GPU is still busy with a frame that timed out or was interrupted", g->name);
        return -1;
    }
    if (g->ctx && _vrg_wait_frames(g) != 0)
        return -1;
    return _vrg_finite_failed(g);
}

void vrg_graph_reset_history(vrg_graph *g) { g->history_reset = 1; }

void vrg_graph_set_frame_index(vrg_graph *g, uint64_t index)
{
    g->frame.frame_index = index;
    g->history_reset = 1; /* the @prev copy is picked by the index's parity */
}

int vrg_graph_set_camera(vrg_graph *g, const vrg_camera *c)
{
    if (!vrg_camera_position_in_world(c->position)) {
        _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "vrg_graph_set_camera: camera->position (%g, %g, %g) is outside the world: each coordinate lies in [%g, %g] (VRG_WORLD_LIMIT)",
                  c->position[0], c->position[1], c->position[2], -VRG_WORLD_LIMIT, VRG_WORLD_LIMIT);
        return -1;
    }
    g->camera = *c;
    return 0;
}

const vrg_camera *vrg_graph_camera(const vrg_graph *g) { return &g->camera; }

double vrg_graph_frame_seconds(const vrg_graph *g) { return 1.0 / g->fps; }

int64_t vrg_graph_timed_frame(const vrg_graph *g) { return g->timed_frame; }

uint32_t vrg_graph_frames_in_flight(const vrg_graph *g) { return g->frames_in_flight; }
