#ifndef VOXRG_CLI_COMPARE_CASES_H
#define VOXRG_CLI_COMPARE_CASES_H
/* Case files of `voxrg compare --cases FILE`: INI, one [case NAME] section
 * per case, whose keys mirror compare's options (docs/compare.md). */
#include <stdint.h>

typedef struct vrg_cmp_case_spec {
    char name[64];
    char camera[4096];   /* the path file, relative to the case file made relative to the working folder; "" for none */
    uint32_t start, frames, warmup, width, height; /* width 0: the graphs' own size */
    int warmup_given;
    char **scene;        /* "scene.PARAM=VALUE" overrides, [scene_count] */
    int scene_count;
    int line;            /* of the [case NAME] header */
} vrg_cmp_case_spec;

/* Reads FILE into *cases (*count of them). Errors name file:line, with a
 * hint, on stderr; returns 0 or -1. */
int vrg_cmp_cases_load(const char *file, vrg_cmp_case_spec **cases, int *count);
void vrg_cmp_cases_free(vrg_cmp_case_spec *cases, int count);
#endif
