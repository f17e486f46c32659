#ifndef VOXRG_CLI_REPORT_H
#define VOXRG_CLI_REPORT_H
/* The HTML report of `voxrg compare`. */
#include <stdio.h>
#include "compare_result.h"

/* Writes one case's part of the report (settings, summary, plots, GPU
 * time, frames) to f, so that its frames can be freed before the next
 * case runs. 0 or -1. */
int vrg_cmp_report_case(FILE *f, const vrg_cmp_result *r);

/* Writes report.html (self-contained): the verdict over the cases, then
 * the cases' parts, `sections` as vrg_cmp_report_case wrote them. 0 or -1. */
int vrg_cmp_write_report(const char *path, const vrg_cmp_run *run, FILE *sections);
#endif
