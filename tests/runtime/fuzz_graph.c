/* libFuzzer target: graph text → parse + validate + compile + aliasing plan,
 * without a device (memory sizes estimated). Plugins come from the build's
 * plugins/ folder. Any crash, leak or sanitizer report is a bug. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/voxrg.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 16384)
        return 0;
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    /* no --set: an override naming a pass the input lacks would stop every
     * such input before compile */
    vrg_graph_desc desc = {.path = "fuzz.ini", .text = text, .diag = devnull};
    vrg_graph *g = NULL;
    if (vrg_graph_load(NULL, &desc, &g) == 0) {
        vrg_graph_report(g, devnull);
        vrg_graph_write_dot(g, devnull);
        vrg_graph_destroy(g);
    }
    free(text);
    return 0;
}
