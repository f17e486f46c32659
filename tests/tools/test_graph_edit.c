#define _GNU_SOURCE /* mkdtemp */
/* The graph-file rewriter behind `voxrg run`'s panel save
 * (voxrg/graph_edit.h): only the edited values' text changes (comments,
 * blank lines, odd spacing, inline comments and CRLF line ends stay), a
 * missing key is added after its section's last key, a missing section is
 * an error naming the file, and the file is replaced whole; a FIFO in its
 * place is refused without blocking. No device.
 * Usage: test_graph_edit CASE (run in a writable folder). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "voxrg/graph_edit.h"
#include "check.h"

static int failures;

/* The text after one edit; NULL on error (the message in err). */
static char *edit(const char *text, const char *section, const char *key, const char *value, char *err, size_t cap)
{
    vrg_graph_edit e = {section, key, value};
    FILE *diag = fmemopen(err, cap, "w");
    char *out = vrg_graph_edit_text("g.ini", text, &e, 1, diag);
    fclose(diag);
    return out;
}

static void expect(const char *what, const char *text, const char *section, const char *key, const char *value, const char *want)
{
    char err[512] = "";
    char *got = edit(text, section, key, value, err, sizeof err);
    CHECK(got && strcmp(got, want) == 0, "%s:\n--- got\n%s\n--- want\n%s\n(%s)", what, got ? got : "(null)", want, err);
    free(got);
}

static const char *graph =
    "; a comment = with an equals sign\n"
    "[graph]\n"
    "name = g\n"
    "\n"
    "[scene]\n"
    "plugin=blocks\n"
    "  time_of_day   =  10   ; noon-ish\n"
    "# exposure = 3 (commented out)\n"
    "\n"
    "[pass  view ]\n"
    "plugin    = world_debug\n"
    "exposure\t=\t0.35\n"
    "\n"
    "; trailing comment\n";

static void case_values(void)
{
    expect("inline comment and odd spacing kept", graph, "scene", "time_of_day", "18.5",
           "; a comment = with an equals sign\n[graph]\nname = g\n\n[scene]\nplugin=blocks\n  time_of_day   =  18.5   ; noon-ish\n"
           "# exposure = 3 (commented out)\n\n[pass  view ]\nplugin    = world_debug\nexposure\t=\t0.35\n\n; trailing comment\n");
    expect("tabs kept; header with odd blanks matched", graph, "pass view", "exposure", "1.5",
           "; a comment = with an equals sign\n[graph]\nname = g\n\n[scene]\nplugin=blocks\n  time_of_day   =  10   ; noon-ish\n"
           "# exposure = 3 (commented out)\n\n[pass  view ]\nplugin    = world_debug\nexposure\t=\t1.5\n\n; trailing comment\n");
    expect("a commented-out key is not the key", graph, "scene", "exposure", "3",
           "; a comment = with an equals sign\n[graph]\nname = g\n\n[scene]\nplugin=blocks\n  time_of_day   =  10   ; noon-ish\nexposure = 3\n"
           "# exposure = 3 (commented out)\n\n[pass  view ]\nplugin    = world_debug\nexposure\t=\t0.35\n\n; trailing comment\n");
    expect("the last of a repeated key", "[s]\na = 1\na = 2\n", "s", "a", "9", "[s]\na = 1\na = 9\n");
    expect("an empty value", "[s]\na =\nb=\n", "s", "b", "4", "[s]\na =\nb= 4\n");
    expect("key ends at ':' too", "[s]\na: 1\n", "s", "a", "2", "[s]\na: 2\n");
    expect("a semicolon without a blank before it is part of the value", "[s]\na = x;y\n", "s", "a", "z", "[s]\na = z\n");
}

static void case_crlf(void)
{
    expect("CRLF kept", "[scene]\r\ntime_of_day = 10\r\n\r\n[pass a]\r\nk = 1\r\n", "pass a", "k", "2",
           "[scene]\r\ntime_of_day = 10\r\n\r\n[pass a]\r\nk = 2\r\n");
    expect("CRLF key added with CRLF", "[scene]\r\ntime_of_day = 10\r\n\r\n[pass a]\r\nk = 1\r\n", "scene", "day_length", "0",
           "[scene]\r\ntime_of_day = 10\r\nday_length = 0\r\n\r\n[pass a]\r\nk = 1\r\n");
    expect("no line end at the end", "[s]\r\na = 1", "s", "a", "2", "[s]\r\na = 2");
}

static void case_missing(void)
{
    expect("missing key after the section's last key", graph, "pass view", "mode", "2",
           "; a comment = with an equals sign\n[graph]\nname = g\n\n[scene]\nplugin=blocks\n  time_of_day   =  10   ; noon-ish\n"
           "# exposure = 3 (commented out)\n\n[pass  view ]\nplugin    = world_debug\nexposure\t=\t0.35\nmode = 2\n\n; trailing comment\n");
    expect("missing key, last line without an end", "[s]\na = 1", "s", "b", "2", "[s]\na = 1\nb = 2");
    expect("missing key in an empty section", "[s]\n[t]\n", "s", "b", "2", "[s]\nb = 2\n[t]\n");
    char err[512] = "";
    char *got = edit(graph, "pass nope", "k", "1", err, sizeof err);
    CHECK(!got, "a missing section was edited: %s", got);
    CHECK(strstr(err, "g.ini") && strstr(err, "[pass nope]"), "the message names the file and section: %s", err);
    free(got);
}

/* The file itself: replaced with the edits applied, and no temporary file
 * left beside it; a failed edit leaves it as it was. */
static void case_file(void)
{
    char dir[] = "graph_edit_XXXXXX";
    CHECK(mkdtemp(dir), "mkdtemp failed");
    char path[64];
    snprintf(path, sizeof path, "%s/g.ini", dir);
    FILE *f = fopen(path, "w");
    fputs(graph, f);
    fclose(f);
    vrg_graph_edit e[2] = {{"scene", "time_of_day", "12"}, {"pass view", "exposure", "0.5"}};
    CHECK(vrg_graph_edit_file(path, e, 2, stderr) == 0, "edit failed");
    char buf[2048] = "";
    f = fopen(path, "rb");
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    CHECK(strstr(buf, "  time_of_day   =  12   ; noon-ish\n") && strstr(buf, "exposure\t=\t0.5\n") && n == strlen(graph) - 1, /* "0.35" became "0.5" */
          "both values replaced, nothing else: %s", buf);
    vrg_graph_edit bad = {"nope", "k", "1"};
    char err[512] = "";
    FILE *diag = fmemopen(err, sizeof err, "w");
    CHECK(vrg_graph_edit_file(path, &bad, 1, diag) != 0, "a missing section was accepted");
    fclose(diag);
    CHECK(strstr(err, path), "the message names the file: %s", err);
    char again[2048] = "";
    f = fopen(path, "rb");
    again[fread(again, 1, sizeof again - 1, f)] = '\0';
    fclose(f);
    CHECK(strcmp(again, buf) == 0, "a failed edit changed the file");
    char missing[80];
    snprintf(missing, sizeof missing, "%s/none.ini", dir);
    err[0] = '\0';
    diag = fmemopen(err, sizeof err, "w");
    CHECK(vrg_graph_edit_file(missing, e, 1, diag) != 0 && (fflush(diag), strstr(err, missing)), "a missing file: %s", err);
    fclose(diag);
    unlink(path);
    CHECK(rmdir(dir) == 0, "files left beside the graph (a temporary file?)");
}

/* A graph file replaced by a FIFO before the panel saves: an error naming
 * it, at once (an open that blocked would wait for a writer for ever, and
 * the window with it: the alarm fails the case instead). */
static void case_fifo(void)
{
    char dir[] = "graph_edit_XXXXXX";
    CHECK(mkdtemp(dir), "mkdtemp failed");
    char path[64], err[512] = "";
    snprintf(path, sizeof path, "%s/g.ini", dir);
    CHECK(mkfifo(path, 0644) == 0, "mkfifo failed");
    vrg_graph_edit e = {"scene", "time_of_day", "12"};
    FILE *diag = fmemopen(err, sizeof err, "w");
    alarm(30);
    CHECK(vrg_graph_edit_file(path, &e, 1, diag) != 0, "a FIFO was edited");
    alarm(0);
    fclose(diag);
    CHECK(strstr(err, path) && strstr(err, "not a regular file"), "the message: %s", err);
    unlink(path);
    CHECK(rmdir(dir) == 0, "files left beside the graph");
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*fn)(void);
    } cases[] = {{"values", case_values}, {"crlf", case_crlf}, {"missing", case_missing}, {"file", case_file}, {"fifo", case_fifo}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (argc > 1 && strcmp(argv[1], cases[i].name) == 0) {
            cases[i].fn();
            return failures ? 1 : 0;
        }
    fprintf(stderr, "usage: test_graph_edit values|crlf|missing|file|fifo\n");
    return 2;
}
