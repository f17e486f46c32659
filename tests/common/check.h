/* CHECK for every C test: a failed condition is reported with its file,
 * line and text plus a printf-style explanation, counted in the program's
 * `failures` (which the including file provides), and the test goes on.
 * CHECK is an expression, true when the condition held: where going on
 * makes no sense (a NULL about to be used), `if (!CHECK(p, ...)) return 1;`.
 * Past CHECK_REPORTS failures, further ones are counted but not printed,
 * so that a check inside a loop over many cases does not flood the log. */
#ifndef VRG_TEST_CHECK_H
#define VRG_TEST_CHECK_H

#include <stdarg.h>
#include <stdio.h>

#define CHECK_REPORTS 50

/* Reports failure number failed_before + 1 (unless past CHECK_REPORTS);
 * 0, the value of a CHECK that failed. */
__attribute__((format(printf, 5, 6))) static inline int check_failed(int failed_before, const char *file, int line, const char *cond,
                                                                     const char *fmt, ...)
{
    if (failed_before < CHECK_REPORTS) {
        fprintf(stderr, "%s:%d: check failed: %s: ", file, line, cond);
        va_list ap;
        va_start(ap, fmt);
        vfprintf(stderr, fmt, ap);
        va_end(ap);
        fputc('\n', stderr);
    } else if (failed_before == CHECK_REPORTS) {
        fprintf(stderr, "(more checks failed: counted, not printed)\n");
    }
    return 0;
}

#define CHECK(cond, ...) ((cond) ? 1 : check_failed(failures++, __FILE__, __LINE__, #cond, __VA_ARGS__))

#endif
