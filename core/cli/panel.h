/* voxrg run's parameter panel: every pass's parameters, from their
 * descriptors, changed live with vrg_graph_set_param and saved into the
 * graph file (voxrg/graph_edit.h). Drawn with the overlay's text. */
#ifndef VOXRG_CLI_PANEL_H
#define VOXRG_CLI_PANEL_H
#include "overlay.h"
#include "voxrg/voxrg.h"
#define VRG_PANEL_CHANGES 64 /* unsaved changes per graph: more are refused, not dropped */
#define VRG_PANEL_ROWS 512   /* parameters listed: the panel says when a graph has more */
typedef struct vrg_panel_change {
    char key[160]; /* PASS.PARAM */
    double value;
    int reload; /* not applied live: the save's reload applies it */
} vrg_panel_change;
typedef struct vrg_panel {
    int open;
    int side;     /* the graph edited: 0 A, 1 B (--ab) */
    int selected; /* among the parameter rows */
    vrg_panel_change changes[2][VRG_PANEL_CHANGES];
    int change_count[2];
    char status[160]; /* the last action's result */
    /* where the lines were drawn, for the mouse: line i's row (-1: a title) */
    int x, y, w, lines, line_row[VRG_OVERLAY_LINES];
    int dragging;
    double drag_x, drag_value;
} vrg_panel;
/* Up (-1) or down (+1) a parameter. */
void vrg_panel_select(vrg_panel *p, vrg_graph *g, int delta);
/* The selected parameter a step down (-1) or up (+1), a tenth of one when
 * fine; booleans flip. */
void vrg_panel_step(vrg_panel *p, vrg_graph *g, int dir, int fine);
/* Whether (x, y), framebuffer pixels, lies on the open panel. */
int vrg_panel_contains(const vrg_panel *p, double x, double y);
/* A press of the left button at (x, y): 1 if it fell on the panel (the row
 * under it is selected and a drag starts), else 0. */
int vrg_panel_press(vrg_panel *p, vrg_graph *g, double x, double y);
/* The button held at x: the dragged value follows (fine: ten times slower). */
void vrg_panel_drag(vrg_panel *p, vrg_graph *g, double x, int fine);
/* Lines for graph g (file: its path) at the window's right edge. */
void vrg_panel_draw(vrg_panel *p, vrg_graph *g, const char *file, vrg_overlay_layer *l);
/* Writes the side's changed values into its graph file: 0, or -1 (the
 * message on stderr, the file unchanged). */
int vrg_panel_save(vrg_panel *p, vrg_graph *g, const char *file);
#endif
