#ifndef VOXRG_CLI_BENCH_H
#define VOXRG_CLI_BENCH_H
#include "voxrg/voxrg.h"
/* `voxrg bench`; returns the exit status. */
int vrg_cli_bench(const char *suite, const char *json, int runs, const char *device);
/* The source tree (graphs/paths), compiled in. */
const char *vrg_source_dir(void);
#endif
