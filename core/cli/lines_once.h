#ifndef VOXRG_CLI_LINES_ONCE_H
#define VOXRG_CLI_LINES_ONCE_H
/* A stream that passes each line written to it on to `out` the first time
 * only: a command that loads the same graph many times (compare: once per
 * case and candidate) shows the graph's warnings once. Unbuffered, so
 * that a line is passed on as soon as its newline is written; a last line
 * without one is passed on at fclose, which also frees what it holds.
 * NULL when it cannot be made (out of memory). */
#include <stdio.h>
FILE *vrg_cli_lines_once(FILE *out);
#endif
