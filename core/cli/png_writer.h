#ifndef VOXRG_CLI_PNG_WRITER_H
#define VOXRG_CLI_PNG_WRITER_H
/* PNG files written by a thread of their own, so that encoding frame k
 * overlaps the GPU's work on frame k + 1 (`render --sequence`). A bounded
 * queue: a push waits while `depth` images are queued, so memory stays
 * bounded when encoding is slower than rendering. Each file is written
 * whole or not at all (vrg_write_png goes through vrg_output). */
#include "voxrg/voxrg.h"

typedef struct vrg_cli_png_writer vrg_cli_png_writer;
/* NULL after printing why (no thread). */
vrg_cli_png_writer *vrg_cli_png_writer_start(int depth);
/* Queues img for path; the writer frees img->pixels. -1 once any earlier
 * write failed (its message is printed): the caller stops rendering. */
int vrg_cli_png_writer_push(vrg_cli_png_writer *w, const char *path, vrg_image_data *img);
/* Writes what is queued, ends the thread and frees w: 0, or -1 if any
 * write failed. NULL is fine. */
int vrg_cli_png_writer_finish(vrg_cli_png_writer *w);
#endif
