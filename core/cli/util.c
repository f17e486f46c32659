/* Helpers the CLI commands share (util.h). */
#define _POSIX_C_SOURCE 200809L
#include "util.h"
#include "voxrg/voxrg.h"
#include "voxrg/output.h"
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "voxrg/voxrg.h"

void vrg_cli_exit_if_gpu_busy(const vrg_context *ctx, int rc)
{
    if (!vrg_context_gpu_busy(ctx))
        return;
    fflush(NULL);
    _exit(rc ? rc : 1);
}

int vrg_cli_parse_seconds(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    /* decimal only, as graph files */
    if (end == s || *end || strpbrk(s, "xX") || !(v > 0) || v > 1e9)
        return -1;
    *out = v;
    return 0;
}

double vrg_cli_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

int vrg_cli_parse_size(const char *s, uint32_t *w, uint32_t *h)
{
    char *end;
    if (!isdigit((unsigned char)s[0]))
        return -1;
    long a = strtol(s, &end, 10);
    if (*end != 'x' || !isdigit((unsigned char)end[1]) || a <= 0 || a > VRG_CLI_SIZE_MAX)
        return -1;
    long b = strtol(end + 1, &end, 10);
    if (*end || b <= 0 || b > VRG_CLI_SIZE_MAX)
        return -1;
    *w = (uint32_t)a;
    *h = (uint32_t)b;
    return 0;
}

int vrg_cli_mkdir_p(const char *dir)
{
    if (strlen(dir) > VRG_CLI_DIR_MAX) { /* the files in it must fit VRG_CLI_PATH */
        fprintf(stderr, "error: cannot use folder %.80s...: its path is %zu characters, at most %d\n", dir, strlen(dir), VRG_CLI_DIR_MAX);
        return -1;
    }
    char *buf = strdup(dir);
    if (!buf) {
        fprintf(stderr, "error: cannot create directory %s: out of memory\n", dir);
        return -1;
    }
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(buf, 0777);
            *p = '/';
        }
    int rc = 0;
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "error: cannot create directory %s: %s\n", dir, strerror(errno));
        rc = -1;
    }
    free(buf);
    return rc;
}

int vrg_cli_out_dir(const char *dir)
{
    return vrg_cli_mkdir_p(dir) == 0 && vrg_output_dir_check(dir) == 0 ? 0 : -1;
}

int vrg_cli_out_file_dir(const char *file)
{
    char dir[4096];
    const char *slash = strrchr(file, '/');
    if (!slash)
        return vrg_output_dir_check(".");
    if (slash == file)
        return vrg_output_dir_check("/");
    if ((size_t)(slash - file) >= sizeof dir) {
        fprintf(stderr, "error: cannot write %s: %s\n", file, strerror(ENAMETOOLONG));
        return -1;
    }
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - file), file);
    return vrg_cli_out_dir(dir);
}

const char *vrg_cli_json_str(const char *s, char *buf, size_t cap)
{
    size_t n = 0;
    for (; *s && n + 7 < cap; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            n += (size_t)snprintf(buf + n, cap - n, "\\%c", c);
        else if (c < 0x20)
            n += (size_t)snprintf(buf + n, cap - n, "\\u%04x", c);
        else
            buf[n++] = (char)c;
    }
    buf[n] = '\0';
    return buf;
}

char *vrg_cli_read_text(const char *path)
{
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, len = 0;
    char *t = malloc(cap);
    size_t got;
    while (t && (got = fread(t + len, 1, cap - len - 1, f)) > 0) {
        len += got;
        if (len + 1 == cap) {
            char *grown = realloc(t, cap * 2);
            if (!grown) {
                free(t);
                t = NULL;
                break;
            }
            t = grown, cap *= 2;
        }
    }
    fclose(f);
    if (t)
        t[len] = '\0';
    return t;
}
