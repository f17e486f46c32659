/* `voxrg new-pass`: scaffolds an out-of-tree pass (new_pass.c). */
#ifndef VOXRG_CLI_NEW_PASS_H
#define VOXRG_CLI_NEW_PASS_H
/* Writes NAME.c, NAME.comp, CMakeLists.txt and NAME.ini into dir (created
 * if missing; its parent must exist). Returns the exit status: 0, 1 after
 * an error (a file exists, a write failed), 2 for a NAME that cannot be
 * used (not a C identifier, a target name CMake keeps, a plugin already on
 * the search path). */
/* shader: a one-file pass instead (NAME.comp, NAME.ini, README.md), no build. */
int vrg_cli_new_pass(const char *name, const char *dir, int shader);
#endif
