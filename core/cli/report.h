#ifndef VOXRG_CLI_REPORT_H
#define VOXRG_CLI_REPORT_H
/* The HTML report of `voxrg compare`. */
#include "compare_result.h"

/* Writes report.html (self-contained). 0 or -1. */
int vrg_cmp_write_report(const char *path, const vrg_cmp_result *r);
#endif
