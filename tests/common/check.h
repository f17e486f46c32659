/* CHECK for every C test: a failed condition is reported with its file,
 * line and text plus a printf-style explanation, and counted in the
 * program's `failures` (which the including file provides). */
#ifndef VRG_TEST_CHECK_H
#define VRG_TEST_CHECK_H

#include <stdio.h>

#define CHECK(cond, ...)                                                  \
    do {                                                                  \
        if (!(cond)) {                                                    \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                 \
            fputc('\n', stderr);                                          \
            failures++;                                                   \
        }                                                                 \
    } while (0)

#endif
