#ifndef VOXRG_CLI_WARNINGS_ONCE_H
#define VOXRG_CLI_WARNINGS_ONCE_H
/* A stream for a graph's diagnostics that passes each warning on to `out`
 * the first time only: a command that loads the same graph many times
 * (compare: once per case and candidate) shows the graph's warnings once.
 * A warning is a line naming warning[VRG-...] (before any error[VRG-...])
 * with the indented lines after it (its hint); a repeat has the same
 * first line.
 * Every other line is passed on each time: an error's text may repeat
 * with a new cause (a message without FILE:LINE says nothing of which
 * graph or case it came from). Unbuffered, so that a line is passed on as
 * soon as its newline is written; a last line without one is passed on at
 * fclose, which also frees what it holds. NULL when it cannot be made
 * (out of memory). */
#include <stdio.h>
FILE *vrg_cli_warnings_once(FILE *out);
#endif
