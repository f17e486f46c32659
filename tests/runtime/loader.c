#define _POSIX_C_SOURCE 200809L
/* The plugin loader's errors, checked without a device.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"

/* Loader errors: each names the plugin path and what was expected. */
static int load_text_errors(const char *text, const char *want1, const char *want2)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *diag = open_memstream(&buf, &len);
    vrg_graph_desc d = {.path = TEST_DIR "/graphs/loader.ini", .text = text, .diag = diag};
    vrg_graph *g = NULL;
    int rc = vrg_graph_load(NULL, &d, &g);
    fclose(diag);
    int ok = rc != 0 && strstr(buf, want1) && (!want2 || strstr(buf, want2));
    if (!ok)
        fprintf(stderr, "loader message lacks '%s'/'%s':\n%s\n", want1, want2 ? want2 : "", buf);
    free(buf);
    vrg_graph_destroy(g);
    return ok;
}

static void test_loader(void)
{
    char abi[256];
    snprintf(abi, sizeof abi, "ABI version %u", VRG_ABI_VERSION);
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = bad_abi\n", "bad_abi.so", "has ABI version 999"), "ABI mismatch");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = bad_abi\n", "loader.ini:4:", abi), "ABI mismatch line/expected");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = no_entry\n", "no_entry.so", "vrg_plugin_entry"), "missing entry point");
    CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = not_there\n", "unknown plugin 'not_there'", "searched:"), "missing file");
    /* a file that is not a shared object: dlopen's own error, with the path */
    const char *dir = getenv("VOXRG_PLUGIN_PATH");
    CHECK(dir != NULL, "VOXRG_PLUGIN_PATH is not set for this test");
    if (dir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/garbage.so", dir);
        FILE *f = fopen(path, "w");
        CHECK(f != NULL, "cannot write %s", path);
        if (f) {
            fputs("this is not an ELF file\n", f);
            fclose(f);
            CHECK(load_text_errors("[graph]\noutput=x\n[pass a]\nplugin = garbage\n", "cannot load plugin 'garbage'", "garbage.so"), "dlopen error");
        }
    }
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"loader", test_loader, 0},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
