/* The rules a parameter's descriptor follows: plugin_loader.c checks a
 * plugin's table with them, shader_pass.c a shader's @param annotations
 * (at the member's line). */
#include <math.h>
#include <stdio.h>
#include "internal.h"

const char *_vrg_param_problem(const vrg_param_desc *pd, char *why, size_t cap)
{
    if (pd->type < VRG_PARAM_FLOAT || pd->type > VRG_PARAM_STRING)
        return snprintf(why, cap, "type %d is none of VRG_PARAM_FLOAT, _INT, _BOOL, _STRING", (int)pd->type), why;
    if ((pd->flags & VRG_PARAM_REPEATABLE) && pd->type != VRG_PARAM_STRING)
        return "is repeatable but not a string";
    const uint32_t known = VRG_PARAM_REPEATABLE | VRG_PARAM_RELOAD;
    if (pd->flags & ~known)
        return snprintf(why, cap, "has unknown flags 0x%x", pd->flags & ~known), why;
    if (pd->type == VRG_PARAM_STRING)
        return NULL;
    if (!isfinite(pd->default_value) || !isfinite(pd->min) || !isfinite(pd->max))
        return "default, min and max must be finite numbers";
    if (pd->min > pd->max)
        return snprintf(why, cap, "min %g is greater than max %g", pd->min, pd->max), why;
    if ((pd->min != 0 || pd->max != 0) && (pd->default_value < pd->min || pd->default_value > pd->max))
        return snprintf(why, cap, "default %g lies outside [%g, %g]", pd->default_value, pd->min, pd->max), why;
    if (pd->type != VRG_PARAM_FLOAT && (pd->default_value != floor(pd->default_value) || pd->min != floor(pd->min) || pd->max != floor(pd->max)))
        return snprintf(why, cap, "an %s parameter needs whole-number default, min and max", pd->type == VRG_PARAM_INT ? "int" : "bool"), why;
    if (pd->type == VRG_PARAM_BOOL && pd->default_value != 0 && pd->default_value != 1)
        return snprintf(why, cap, "a bool's default is 0 or 1, not %g", pd->default_value), why;
    return NULL;
}

