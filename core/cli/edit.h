/* voxrg run's block editing: the block under the cursor (a CPU pick along
 * the camera ray through the cursor's pixel), removed by a left click,
 * placed against the face hit by a right click, undone and redone, each
 * through the graph's edit journal (voxrg/edits.h) when its scene keeps one
 * (docs/world.md, "Edits"). */
#ifndef VOXRG_CLI_EDIT_H
#define VOXRG_CLI_EDIT_H
#include <stddef.h>
#include "overlay.h"
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/world.h"
typedef struct vrg_cli_edit {
    vrg_block type;   /* what a right click places: E / Q cycle */
    char status[VRG_CLI_PATH + 512]; /* the last edit's result or error, whole (the overlay clips it, the terminal has it all) */
} vrg_cli_edit;
typedef enum vrg_cli_edit_action { VRG_CLI_EDIT_REMOVE, VRG_CLI_EDIT_PLACE, VRG_CLI_EDIT_UNDO, VRG_CLI_EDIT_REDO } vrg_cli_edit_action;
/* The block shown at framebuffer pixel (fx, fy) of an fb_w x fb_h window
 * that shows g's output stretched over it: 1 and *hit, 0 when none (no
 * world, or nothing along the ray). */
int vrg_cli_edit_pick(const vrg_graph *g, double fx, double fy, int fb_w, int fb_h, vrg_world_hit *hit);
/* Removes the block hit or places e->type against its face; undo and redo
 * ignore hit. The result (or why nothing changed) goes to e->status and
 * stderr. */
void vrg_cli_edit_apply(vrg_cli_edit *e, vrg_graph *g, vrg_cli_edit_action action, const vrg_world_hit *hit);
/* The next (dir 1) or previous (-1) solid block type of g's world. */
void vrg_cli_edit_cycle(vrg_cli_edit *e, const vrg_graph *g, int dir);
/* The hit block's 12 edges, projected with g's camera, drawn into the layer. */
void vrg_cli_edit_outline(const vrg_graph *g, const vrg_world_hit *hit, vrg_overlay_layer *l);
/* The overlay's line: the type placed, the block under the cursor, the status. */
void vrg_cli_edit_describe(const vrg_cli_edit *e, const vrg_graph *g, const vrg_world_hit *hover, char *line, size_t size);
#endif
