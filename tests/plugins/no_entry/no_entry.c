/* Test plugin that loads as a shared object but exports no vrg_plugin_entry:
 * the loader must say which symbol is missing. It exports another function
 * so the .so is not empty and dlopen succeeds. */
#include "voxrg/plugin.h"

VRG_EXPORT int vrg_not_a_plugin_entry(void);

VRG_EXPORT int vrg_not_a_plugin_entry(void)
{
    return 42;
}
