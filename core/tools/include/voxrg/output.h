/* Crash-safe output files (tools layer). */
#ifndef VOXRG_OUTPUT_H
#define VOXRG_OUTPUT_H
#include <stddef.h>
#include <stdio.h>
#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_tools (built with
 * -fvisibility=hidden). */
#pragma GCC visibility push(default)

/* Output files written whole or not at all: the data goes to a temporary
 * file in the target's folder (unnamed where the file system allows it, so a
 * killed process leaves nothing behind), is flushed, synced and checked, and
 * then renamed over the target. A failed write leaves the old file as it was.
 * Errors are printed to stderr with the path and the system's reason. */
typedef struct vrg_output vrg_output;
/* NULL (after the message) if the folder cannot take a new file. */
vrg_output *vrg_output_open(const char *path);
/* Where to write the data. */
FILE *vrg_output_stream(vrg_output *out);
/* Puts the file in place: 0, or -1 after the message (the target unchanged,
 * the temporary file gone). Frees out either way. */
int vrg_output_commit(vrg_output *out);
/* Drops the temporary file, the target unchanged. Frees out; NULL is fine. */
void vrg_output_abort(vrg_output *out);
/* size bytes of data as the whole file at path, as above. */
int vrg_output_write(const char *path, const void *data, size_t size);
/* 0 if the existing folder dir can take new files (a temporary file is
 * created and dropped), else -1 after a message naming dir and the reason. */
int vrg_output_dir_check(const char *dir);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif
