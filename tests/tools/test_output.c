#define _GNU_SOURCE /* mkdtemp, RLIMIT_FSIZE */
/* The writer of output files (vrg_output_*, and PNGs through it): a write
 * that fails (a full disk, simulated with the file size limit) leaves the
 * old file as it was and nothing else behind, with the system's reason in
 * the message; a commit replaces the file whole; an abort leaves nothing.
 * No device. Usage: test_output CASE (run in a writable folder). */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include "voxrg/voxrg.h"
#include "voxrg/output.h"
#include "voxrg/png.h"
#include "check.h"

static int failures;

static char dir[64];

static void put(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
}

/* the whole file (static buffer), "" if missing */
static const char *get(const char *name)
{
    static char buf[65536];
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f)
        fclose(f);
    buf[n] = '\0';
    return buf;
}

/* the folder's entries, sorted names joined with spaces */
static const char *entries(void)
{
    static char list[4096];
    struct dirent **names;
    int n = scandir(dir, &names, NULL, alphasort);
    list[0] = '\0';
    for (int i = 0; i < n; i++) {
        if (strcmp(names[i]->d_name, ".") && strcmp(names[i]->d_name, ".."))
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? " " : "", names[i]->d_name);
        free(names[i]);
    }
    free(names);
    return list;
}

/* stderr while fn runs, in a static buffer */
static char captured[4096];
static int capture_stderr(int (*fn)(void))
{
    fflush(stderr);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    int rc = fn();
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(tmp);
    size_t n = fread(captured, 1, sizeof captured - 1, tmp);
    captured[n] = '\0';
    fclose(tmp);
    return rc;
}

static char big[20000];
static int write_big(void)
{
    char path[256];
    snprintf(path, sizeof path, "%s/out.bin", dir);
    return vrg_output_write(path, big, sizeof big);
}

/* a noisy image: its PNG is larger than the limit below */
static int write_png(void)
{
    enum { W = 64, H = 64 };
    static uint8_t rgb[W * H * 3];
    uint32_t s = 1;
    for (size_t i = 0; i < sizeof rgb; i++)
        rgb[i] = (uint8_t)((s = s * 1664525u + 1013904223u) >> 24);
    char path[256];
    snprintf(path, sizeof path, "%s/out.png", dir);
    return vrg_png_write_rgb8(path, rgb, W, H);
}

static void set_file_limit(rlim_t bytes)
{
    struct rlimit r;
    getrlimit(RLIMIT_FSIZE, &r);
    r.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &r);
}

/* past the file size limit, as on a full disk: the old file stays */
static int test_full_disk(void)
{
    signal(SIGXFSZ, SIG_IGN); /* a failed write, not the end of the process */
    memset(big, 'x', sizeof big);
    put("out.bin", "old data\n");
    put("out.png", "old image\n");
    set_file_limit(4096);
    int rc = capture_stderr(write_big);
    set_file_limit(RLIM_INFINITY);
    CHECK(rc == -1, "rc %d", rc);
    CHECK(strstr(captured, "out.bin") && strstr(captured, strerror(EFBIG)), "message: %s", captured);
    CHECK(!strcmp(get("out.bin"), "old data\n"), "out.bin now: %.40s", get("out.bin"));
    set_file_limit(4096);
    rc = capture_stderr(write_png);
    set_file_limit(RLIM_INFINITY);
    CHECK(rc == -1, "rc %d", rc);
    CHECK(strstr(captured, "out.png") && strstr(captured, strerror(EFBIG)), "message: %s", captured);
    CHECK(!strcmp(get("out.png"), "old image\n"), "out.png now: %.40s", get("out.png"));
    CHECK(!strcmp(entries(), "out.bin out.png"), "left in the folder: %s", entries());
    /* and without the limit both are written */
    CHECK(write_big() == 0 && strlen(get("out.bin")) == sizeof big, "out.bin: %zu bytes", strlen(get("out.bin")));
    CHECK(write_png() == 0 && !memcmp(get("out.png"), "\x89PNG", 4), "out.png is no PNG");
    CHECK(!strcmp(entries(), "out.bin out.png"), "left in the folder: %s", entries());
    return 0;
}

/* a commit replaces the file whole (a new inode: a reader of the old one
 * keeps reading it), with the usual permissions; a symbolic link is
 * followed, the link kept; an abort leaves nothing */
static int test_commit(void)
{
    char path[256], link_path[256];
    snprintf(path, sizeof path, "%s/a.txt", dir);
    put("a.txt", "old\n");
    FILE *reader = fopen(path, "r");
    vrg_output *out = vrg_output_open(path);
    CHECK(out != NULL, "open");
    fputs("new\n", vrg_output_stream(out));
    CHECK(!strcmp(get("a.txt"), "old\n"), "before the commit: %s", get("a.txt"));
    CHECK(vrg_output_commit(out) == 0, "commit");
    CHECK(!strcmp(get("a.txt"), "new\n"), "after the commit: %s", get("a.txt"));
    char old[8] = "";
    CHECK(fgets(old, sizeof old, reader) && !strcmp(old, "old\n"), "the reader saw '%s'", old);
    fclose(reader);
    mode_t mask = umask(022);
    snprintf(path, sizeof path, "%s/b.txt", dir);
    CHECK(vrg_output_write(path, "b", 1) == 0, "new file");
    umask(mask);
    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644, "mode %o", (unsigned)(st.st_mode & 0777));
    snprintf(link_path, sizeof link_path, "%s/link.txt", dir);
    CHECK(symlink("b.txt", link_path) == 0, "symlink: %s", strerror(errno));
    CHECK(vrg_output_write(link_path, "via link", 8) == 0, "write through the link");
    CHECK(lstat(link_path, &st) == 0 && S_ISLNK(st.st_mode), "the link was replaced");
    CHECK(!strcmp(get("b.txt"), "via link"), "b.txt: %s", get("b.txt"));
    snprintf(path, sizeof path, "%s/c.txt", dir);
    out = vrg_output_open(path);
    fputs("never", vrg_output_stream(out));
    vrg_output_abort(out);
    CHECK(!strcmp(entries(), "a.txt b.txt link.txt"), "left in the folder: %s", entries());
    return 0;
}

/* a file replaced keeps its mode (0600 stays private, 0755 executable);
 * a new one gets the umask's */
static int test_mode(void)
{
    static const mode_t modes[] = {0600, 0755, 0640};
    char path[256];
    struct stat st;
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++) {
        snprintf(path, sizeof path, "%s/m%zu.txt", dir, i);
        put(path + strlen(dir) + 1, "old\n");
        CHECK(chmod(path, modes[i]) == 0, "chmod: %s", strerror(errno));
        CHECK(vrg_output_write(path, "new\n", 4) == 0, "replace %s", path);
        CHECK(stat(path, &st) == 0 && (st.st_mode & 07777) == modes[i], "%04o became %04o", (unsigned)modes[i], (unsigned)(st.st_mode & 07777));
        CHECK(!strcmp(get(path + strlen(dir) + 1), "new\n"), "%s: %s", path, get(path + strlen(dir) + 1));
    }
    mode_t mask = umask(077);
    snprintf(path, sizeof path, "%s/new.txt", dir);
    CHECK(vrg_output_write(path, "n", 1) == 0, "new file");
    umask(mask);
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0600, "a new file under umask 077: %04o", (unsigned)(st.st_mode & 0777));
    return 0;
}

static const char *probed;
static int probe(void) { return vrg_output_dir_check(probed); }

/* the folder check: a file or a missing folder is an error with the reason;
 * a good folder passes and keeps nothing */
static int test_dir_check(void)
{
    char path[256];
    put("file", "x");
    snprintf(path, sizeof path, "%s/file", dir);
    probed = path;
    CHECK(capture_stderr(probe) == -1, "a file as folder");
    CHECK(strstr(captured, path) && strstr(captured, strerror(ENOTDIR)), "message: %s", captured);
    snprintf(path, sizeof path, "%s/missing", dir);
    CHECK(capture_stderr(probe) == -1, "a missing folder");
    CHECK(strstr(captured, path) && strstr(captured, strerror(ENOENT)), "message: %s", captured);
    probed = dir;
    CHECK(probe() == 0, "the test folder");
    snprintf(path, sizeof path, "%s/missing/x.png", dir);
    CHECK(vrg_output_write(path, "x", 1) == -1, "a file in a missing folder");
    CHECK(!strcmp(entries(), "file"), "left in the folder: %s", entries());
    return 0;
}

static void remove_dir(void)
{
    struct dirent **names;
    int n = scandir(dir, &names, NULL, NULL);
    for (int i = 0; i < n; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]->d_name);
        if (strcmp(names[i]->d_name, ".") && strcmp(names[i]->d_name, ".."))
            unlink(path);
        free(names[i]);
    }
    free(names);
    rmdir(dir);
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(void);
    } cases[] = {{"full_disk", test_full_disk}, {"commit", test_commit}, {"dir_check", test_dir_check}, {"mode", test_mode}};
    for (size_t i = 0; argc == 2 && i < sizeof cases / sizeof cases[0]; i++)
        if (!strcmp(argv[1], cases[i].name)) {
            snprintf(dir, sizeof dir, "output-%s-XXXXXX", cases[i].name);
            if (!mkdtemp(dir)) {
                perror("mkdtemp");
                return 1;
            }
            cases[i].fn();
            if (failures == 0)
                remove_dir(); /* kept for a look when something failed */
            printf("%s: %s\n", cases[i].name, failures ? "FAILED" : "ok");
            return failures != 0;
        }
    fprintf(stderr, "usage: test_output full_disk|commit|dir_check|mode\n");
    return 2;
}
