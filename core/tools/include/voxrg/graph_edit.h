/* Rewriting values of a graph file in place (tools layer): what a viewer's
 * "save" does with parameters tweaked live, so that the tweak becomes an
 * ordinary graph edit. */
#ifndef VOXRG_GRAPH_EDIT_H
#define VOXRG_GRAPH_EDIT_H
#include <stdio.h>
#ifdef __cplusplus
extern "C" {
#endif
#pragma GCC visibility push(default)

typedef struct vrg_graph_edit {
    const char *section; /* the header's name: "scene", "pass NAME", "graph" */
    const char *key;
    const char *value;   /* the new value's text */
} vrg_graph_edit;

/* The graph text with each edit applied, everything else byte for byte as
 * it was: the section's (last) `key = value` line keeps its key, spacing,
 * inline comment and line end, only the value's text is replaced; a key the
 * section lacks becomes a line "key = value" after the section's last key
 * (with the file's line end). Section names match with blanks around them
 * and runs of blanks inside taken as one. Returns the new text (malloc'd),
 * or NULL after writing "error: PATH: ..." to diag (a section the file
 * lacks, out of memory). path only names the file in messages. */
char *vrg_graph_edit_text(const char *path, const char *text, const vrg_graph_edit *edits, int count, FILE *diag);
/* Reads the file, applies the edits and writes it crash-safely
 * (vrg_output_write: a temporary file, synced, renamed over it). Returns 0,
 * or -1 after a message naming the file; the file is then unchanged. */
int vrg_graph_edit_file(const char *path, const vrg_graph_edit *edits, int count, FILE *diag);

#pragma GCC visibility pop
#ifdef __cplusplus
}
#endif
#endif
