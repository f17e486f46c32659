/* The phases, which only the graph object runs: load (graph.c) runs
 * validate, compile and allocate in order, a frame (graph_frame.c)
 * records; and the load a reload (reload.c) runs. */
#ifndef VRG_PHASES_H
#define VRG_PHASES_H

#include "internal.h"
#include "parse.h"

/* validate.c: AST → graph (plugins loaded, slots resolved, every check). */
int _vrg_validate(vrg_graph *g, const _vrg_ast *ast, const vrg_graph_desc *desc);
/* compile.c: cull, order, lifetimes. */
int _vrg_compile(vrg_graph *g);
/* allocate.c */
int _vrg_allocate(vrg_graph *g);
void _vrg_free_resources(vrg_graph *g);
/* record.c */
int _vrg_record_frame(vrg_graph *g);
/* Waits for every submitted frame (reading their timestamps); -1 after
 * reporting a GPU timeout, interrupt or device loss. */
int _vrg_wait_frames(vrg_graph *g);
/* vrg_graph_load for a reload (graph.c): passes may look at `predecessor`'s
 * (vrg_pass_previous_instance) until the reload ends. */
int _vrg_graph_load_replacing(vrg_context *ctx, const vrg_graph_desc *desc, vrg_graph *predecessor, vrg_graph **out);
#endif
