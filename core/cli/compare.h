#ifndef VOXRG_CLI_COMPARE_H
#define VOXRG_CLI_COMPARE_H
/* `voxrg compare`: candidates against a converged reference. What it
 * measures (compare_result.h) the HTML report (report.h) shows. */

/* `voxrg compare ARGS`; returns the exit status. */
int vrg_cli_compare(int argc, char **argv);
extern const char *const vrg_cli_compare_usage;
#endif
