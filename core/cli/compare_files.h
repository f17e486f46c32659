#ifndef VOXRG_CLI_COMPARE_FILES_H
#define VOXRG_CLI_COMPARE_FILES_H
/* What a `voxrg compare` run writes and prints, for the run (compare.c)
 * and the merge of its shards (compare_shard.c) alike. */
#include "compare_result.h"

/* metrics.csv and metrics.json in dir, each written whole or not at all. 0 or -1. */
int vrg_cmp_write_metrics(const char *dir, const vrg_cmp_run *run);
/* Each case's summaries, then each candidate's verdict, on stdout. */
void vrg_cmp_print(const vrg_cmp_run *run);
/* Frees the shown frames and FLIP maps of case r (the report has them). */
void vrg_cmp_free_shown(vrg_cmp_result *r);
/* Frees what the run allocated. */
void vrg_cmp_run_free(vrg_cmp_run *run);
#endif
