#ifndef VOXRG_CLI_COMPARE_SHARD_H
#define VOXRG_CLI_COMPARE_SHARD_H
/* Shards of `voxrg compare` (docs/compare.md, "On a cluster"): `--shard
 * I/N` runs a slice of the (case, candidate) tasks and writes OUT/shard.txt,
 * its results as exact numbers; `--merge OUT DIR...` reads the shards back
 * and writes the one report (compare_files.c writes its files). */
#include <stdio.h>
#include "compare_result.h"

#define VRG_CMP_SHARD_FILE "shard.txt"

/* One unit of a run's work: a candidate on a case. A run's tasks are
 * numbered case by case, candidate by candidate. */
typedef struct vrg_cmp_task {
    int case_index, candidate;
} vrg_cmp_task;

/* The tasks of shard `shard` of `shards` out of `count`: a contiguous
 * block, so that a shard loads the reference frames of as few cases as
 * the split allows. Sets *first and *n. */
void vrg_cmp_shard_tasks(int count, int shard, int shards, int *first, int *n);

/* The shown frames' FLIP maps of the candidates of case r that this
 * process rendered, as FRAMES_DIR/NAME-NNNNN.flip (raw floats), for the
 * merge's report. 0 or -1. */
int vrg_cmp_shard_write_maps(const char *frames_dir, const vrg_cmp_result *r);

/* DIR/shard.txt: the run's settings, this shard's device and the results
 * of tasks[0..n), numbers as %.17g. 0 or -1. */
int vrg_cmp_shard_write(const char *dir, const vrg_cmp_run *run, int shard, int shards, const char *device, const vrg_cmp_task *tasks,
                        int n);

/* `voxrg compare --merge OUT DIR...`; returns the exit status. usage:
 * compare's, printed after an error in the arguments. */
int vrg_cmp_merge(int argc, char **argv, const char *usage);
#endif
