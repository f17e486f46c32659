/* parse.c: a graph file as written, with line numbers (validate.c gives
 * the keys their meaning). */
#ifndef VRG_PARSE_H
#define VRG_PARSE_H

#include "internal.h"

typedef struct _vrg_key {
    char name[VRG_NAME_MAX];
    char value[256];
    int line;
    int section_index; /* index into _vrg_ast.sections */
} _vrg_key;
typedef struct _vrg_section {
    char name[256]; /* longer than any line that can be read */
    int line;
} _vrg_section;
typedef struct _vrg_ast {
    _vrg_section sections[VRG_MAX_PASSES + 64];
    int section_count;
    _vrg_key keys[VRG_MAX_KEYS];
    int key_count;
    int syntax_error_line; /* inih's first error, 0 if none */
    int fatal;             /* a limit or encoding error: the file was not read whole */
} _vrg_ast;
int _vrg_parse(const char *path, const char *text, _vrg_ast *ast, _vrg_diag *d);
#endif
