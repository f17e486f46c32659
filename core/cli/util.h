#ifndef VOXRG_CLI_UTIL_H
#define VOXRG_CLI_UTIL_H
/* Helpers the CLI commands share. */
#include <stddef.h>
#include <stdint.h>

/* Monotonic milliseconds. */
double vrg_cli_now_ms(void);
/* The largest --size side: as a graph file's width and height. */
#define VRG_CLI_SIZE_MAX 16384
/* Paths the CLI builds: an output folder of at most VRG_CLI_DIR_MAX
 * characters (checked when it is created) plus a file name. */
#define VRG_CLI_DIR_MAX 3839
#define VRG_CLI_PATH 4352
#define VRG_CLI_STR_(x) #x
#define VRG_CLI_STR(x) VRG_CLI_STR_(x)
#define VRG_CLI_SIZE_RANGE "W and H whole numbers from 1 to " VRG_CLI_STR(VRG_CLI_SIZE_MAX)
/* "WxH" (each 1..VRG_CLI_SIZE_MAX) -> 0, else -1. */
int vrg_cli_parse_size(const char *s, uint32_t *w, uint32_t *h);
/* mkdir -p; prints the error and returns -1 on failure. */
int vrg_cli_mkdir_p(const char *dir);
/* An output folder checked before any work: created if missing, then
 * probed with a temporary file; prints the path and the reason, -1. */
int vrg_cli_out_dir(const char *dir);
/* The same for the folder FILE goes to. */
int vrg_cli_out_file_dir(const char *file);
/* A JSON string body in buf: quotes, backslashes and control characters escaped. */
const char *vrg_cli_json_str(const char *s, char *buf, size_t cap);
/* The whole file, NUL-terminated (malloc'd), or NULL. */
char *vrg_cli_read_text(const char *path);
/* After a GPU wait gave up (vrg_context_gpu_busy): flushes every stream
 * and ends the process with rc (1 if 0) without exit's handlers, which could
 * block on or touch the busy driver. Returns otherwise. */
struct vrg_context;
void vrg_cli_exit_if_gpu_busy(const struct vrg_context *ctx, int rc);
/* --gpu-timeout SECONDS -> 0, else -1. */
int vrg_cli_parse_seconds(const char *s, double *out);
#endif
