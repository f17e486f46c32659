/* Block edits of a world, kept in a journal file beside the graph (voxel
 * layer; docs/world.md, "Edits"). An edit is (x, y, z, old block, new
 * block); undo and redo are records too. The journal is append-only, one
 * checksummed record per change, each synced before the world changes: a
 * process killed at any instant leaves every record it finished, and a torn
 * last record is dropped when the journal is opened again. The header names
 * the world the edits belong to (the scene and its world parameters), so a
 * journal of another world is refused. A journal deleted or moved away
 * while edits go on is written again at its path, whole, with the next
 * edit. */
#ifndef VOXRG_EDITS_H
#define VOXRG_EDITS_H

#include <stddef.h>
#include "voxrg/world.h"

#ifdef __cplusplus
extern "C" {
#endif
#pragma GCC visibility push(default)

typedef struct vrg_edits vrg_edits;

/* Reads the journal at path if it exists (created with the first edit
 * otherwise). key names the world (at most VRG_EDITS_KEY_MAX - 1 bytes); w
 * is that world, with its materials: what a record may hold. NULL with a
 * message naming the file (and byte offset) in err when it is not a
 * regular file or cannot be read, belongs to another key, holds a damaged
 * record that is not the last one, or a record outside the world (its
 * height, VRG_WORLD_LIMIT across) or naming a block id without a material. */
#define VRG_EDITS_KEY_MAX 1024
vrg_edits *vrg_edits_open(const char *path, const char *key, const vrg_world *w, char *err, size_t err_size);
void vrg_edits_close(vrg_edits *e);
/* Records read or written, and the bytes of a torn last record dropped when opened. */
int vrg_edits_records(const vrg_edits *e);
long vrg_edits_dropped_bytes(const vrg_edits *e);
/* The journal's path, as opened. */
const char *vrg_edits_path(const vrg_edits *e);
/* The block the edits leave at (x, y, z): 1 and *b, or 0 when unchanged. */
int vrg_edits_block(const vrg_edits *e, int x, int y, int z, vrg_block *b);
/* Writes the edited blocks of chunk (cx, cy, cz) into blocks (a chunk being
 * generated or placed); returns how many. */
int vrg_edits_apply_chunk(const vrg_edits *e, int cx, int cy, int cz, vrg_block *blocks);
/* Applies every edit to the world's loaded chunks (scene start). */
int vrg_edits_apply_world(const vrg_edits *e, vrg_world *w);
/* An edit: (x, y, z) becomes b (its old block is the world's). The record
 * is written and synced first, then the world's chunk changes (only that
 * chunk is uploaded again; not loaded: it gets the edit when it is). 0
 * (err holds a notice, "" without one: the journal was written again), or
 * -1 with err when the journal cannot be written or the edit is outside
 * the world or names a block without a material (the world unchanged). */
int vrg_edits_set(vrg_edits *e, vrg_world *w, int x, int y, int z, vrg_block b, char *err, size_t err_size);
/* Undo the last edit, redo the last undone one: 0 done (err as for
 * vrg_edits_set), 1 nothing to do, -1 with err when the journal cannot be
 * written. */
int vrg_edits_undo(vrg_edits *e, vrg_world *w, char *err, size_t err_size);
int vrg_edits_redo(vrg_edits *e, vrg_world *w, char *err, size_t err_size);

/* The name a scene shares its journal under (vrg_pass_share), and the
 * graph's journal (NULL without one): what an editing host writes to. */
#define VRG_EDITS_SHARED_NAME "vrg_edits"
vrg_edits *vrg_graph_edits(const vrg_graph *g);

#pragma GCC visibility pop
#ifdef __cplusplus
}
#endif
#endif
