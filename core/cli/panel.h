/* voxrg run's parameter panel: every pass's parameters, from their
 * descriptors, changed live with vrg_graph_set_param and saved into the
 * graph file or a copy of it (voxrg/graph_edit.h). Drawn with the overlay's
 * text. */
#ifndef VOXRG_CLI_PANEL_H
#define VOXRG_CLI_PANEL_H
#include "overlay.h"
#include "voxrg/voxrg.h"
#define VRG_PANEL_CHANGES 64 /* unsaved changes per graph: more are refused, not dropped */
#define VRG_PANEL_ROWS 512   /* parameters listed: the panel says when a graph has more */
typedef struct vrg_panel_change {
    char key[160]; /* PASS.PARAM */
    double value;
    double original; /* the value in effect before the first change: set back to it, the change is gone */
    int reload;      /* not applied live: the save's reload applies it */
} vrg_panel_change;
/* What keys typed go to: nothing (keys are commands), the filter, or the
 * name a save-as writes. */
typedef enum vrg_panel_typing { VRG_PANEL_TYPING_NONE, VRG_PANEL_TYPING_FILTER, VRG_PANEL_TYPING_SAVE_AS } vrg_panel_typing;
typedef struct vrg_panel {
    int open;
    int side;     /* the graph edited: 0 A, 1 B (--ab) */
    int selected; /* among the rows the filter lets through */
    vrg_panel_change changes[2][VRG_PANEL_CHANGES];
    int change_count[2];
    char status[160]; /* the last action's result */
    vrg_panel_typing typing;
    char filter[64];     /* rows whose PASS.PARAM holds it (any case); "" lists all */
    char save_name[512]; /* the file a save-as writes, as typed */
    /* where the lines were drawn, for the mouse: line i's row (-1: a title) */
    int x, y, w, lines, line_row[VRG_OVERLAY_LINES];
    int dragging;
    double drag_x, drag_value;
} vrg_panel;
/* Up (-1) or down (+1) a parameter. */
void vrg_panel_select(vrg_panel *p, vrg_graph *g, int delta);
/* The first parameter of the next (+1) or previous (-1) pass. */
void vrg_panel_jump(vrg_panel *p, vrg_graph *g, int dir);
/* The selected parameter a step down (-1) or up (+1): a fixed fraction of
 * its range (vrg_panel_step_size), a tenth of that when fine; booleans flip. */
void vrg_panel_step(vrg_panel *p, vrg_graph *g, int dir, int fine);
/* The step of a parameter: a twentieth of its range, rounded down to 1, 2
 * or 5 times a power of ten; where the range is more than a hundred times
 * the default (a bound, not a scale: exposure 0..1e6) or there is none, a
 * fifth of the default (0.1 for a default of 0); whole numbers at least 1.
 * fine: a tenth of it (whole numbers: 1). */
double vrg_panel_step_size(const vrg_param_desc *pd, int fine);
/* Typing: the filter (emptied) or the save-as name (start: the default)
 * receives the characters typed, until vrg_panel_type_end. */
void vrg_panel_filter_begin(vrg_panel *p);
void vrg_panel_save_as_begin(vrg_panel *p, const char *name);
/* A character typed (printable ASCII; others are ignored), or the last one
 * taken back (backspace). */
void vrg_panel_type(vrg_panel *p, unsigned codepoint);
void vrg_panel_backspace(vrg_panel *p);
/* Typing ends: accepted (Enter: the filter stays; returns 1 for a save-as
 * to write p->save_name) or cancelled (Esc: the filter is emptied, the
 * save-as dropped); 0. */
int vrg_panel_type_end(vrg_panel *p, int accept);
/* Whether (x, y), framebuffer pixels, lies on the open panel. */
int vrg_panel_contains(const vrg_panel *p, double x, double y);
/* A press of the left button at (x, y): 1 if it fell on the panel (the row
 * under it is selected and a drag starts), else 0. */
int vrg_panel_press(vrg_panel *p, vrg_graph *g, double x, double y);
/* The button held at x: the dragged value follows, a step per 10 pixels
 * (fine: a tenth of a step). */
void vrg_panel_drag(vrg_panel *p, vrg_graph *g, double x, int fine);
/* Lines for graph g (file: its path) at the window's right edge. */
void vrg_panel_draw(vrg_panel *p, vrg_graph *g, const char *file, vrg_overlay_layer *l);
/* Writes the side's changed values (those that differ from the value they
 * had before) into its graph file, in place, keeping the file's mode: 0, or
 * -1 (the message on stderr and in the status, the file unchanged). A file
 * without write permission is refused (save-as writes elsewhere); one with
 * other hard links is replaced under this name only, and the message says
 * that the other names keep the old text. The changes are then gone: the
 * reload applies them. */
int vrg_panel_save(vrg_panel *p, vrg_graph *g, const char *file);
/* The graph file with the changed values, written as the new file `to`
 * (an existing one is refused); the graph running and its file stay as
 * they are, and so do the changes. 0, or -1 after the message. */
int vrg_panel_save_as(vrg_panel *p, vrg_graph *g, const char *file, const char *to);
/* The save-as default for a graph file: "DIR/NAME-edited.ini" beside it. */
void vrg_panel_save_as_name(const char *file, char *name, size_t cap);
#endif
