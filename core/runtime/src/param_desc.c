/* The rules a parameter's descriptor follows: plugin_loader.c checks a
 * plugin's table with them, shader_pass.c a shader's @param annotations
 * (at the member's line); and a string parameter's choices, which the
 * loader checks, validation holds a value to and dispatch.c packs as an
 * index. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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


/* ---- a string parameter's choices: "a,b,c" (vrg_plugin_desc.param_choices) ---- */

const char *_vrg_param_choices(const vrg_plugin_desc *desc, uint32_t i)
{
    return desc->param_choices && i < desc->param_count ? desc->param_choices[i] : NULL;
}

int _vrg_choice_index(const char *choices, const char *value)
{
    size_t n = strlen(value);
    int k = 0;
    for (const char *c = choices; c && *c; k++) {
        const char *comma = strchr(c, ',');
        size_t len = comma ? (size_t)(comma - c) : strlen(c);
        if (len == n && strncmp(c, value, n) == 0)
            return k;
        if (!comma)
            break;
        c = comma + 1;
    }
    return -1;
}

int _vrg_choice_count(const char *choices)
{
    int k = choices && *choices ? 1 : 0;
    for (const char *c = choices; c && *c; c++)
        k += *c == ',';
    return k;
}

/* "a, b or c": the names for a message; each comma becomes at most " or " */
char *_vrg_choice_words(const char *choices)
{
    int count = _vrg_choice_count(choices), k = 0;
    size_t o = 0, cap = (choices ? strlen(choices) : 0) + 3 * (size_t)(count > 0 ? count - 1 : 0) + 1;
    char *out = malloc(cap);
    if (!out)
        return NULL;
    out[0] = '\0';
    for (const char *c = choices; c && *c && o < cap; k++) {
        const char *comma = strchr(c, ',');
        int len = comma ? (int)(comma - c) : (int)strlen(c);
        int w = snprintf(out + o, cap - o, "%s%.*s", k == 0 ? "" : k == count - 1 ? " or " : ", ", len, c);
        o += w > 0 ? (size_t)w : 0;
        if (!comma)
            break;
        c = comma + 1;
    }
    return out;
}

const char *_vrg_choices_problem(const vrg_param_desc *pd, const char *choices, char *why, size_t cap)
{
    if (pd->type != VRG_PARAM_STRING || (pd->flags & VRG_PARAM_REPEATABLE))
        return "has choices but is not a single string (VRG_PARAM_STRING, not repeatable)";
    int count = _vrg_choice_count(choices);
    if (count < 1)
        return "has an empty list of choices";
    /* every entry, the one after a trailing comma too: an empty one would
     * be a choice of its own (_vrg_choice_count counts the commas) */
    int k = 0;
    for (const char *c = choices;; k++) {
        const char *comma = strchr(c, ',');
        size_t len = comma ? (size_t)(comma - c) : strlen(c);
        if (len == 0 || len >= VRG_NAME_MAX)
            return snprintf(why, cap, "choice %d of '%s' is %s", k, choices, len ? "too long" : "empty"), why;
        for (size_t j = 0; j < len; j++)
            if ((unsigned char)c[j] <= ' ' || strchr("=;#[]\"", c[j]))
                return snprintf(why, cap, "choice '%.*s' holds a space or one of = ; # [ ] \"", (int)len, c), why;
        char name[VRG_NAME_MAX];
        snprintf(name, sizeof name, "%.*s", (int)len, c);
        if (_vrg_choice_index(choices, name) != k)
            return snprintf(why, cap, "names choice '%s' twice", name), why;
        if (!comma)
            break;
        c = comma + 1;
    }
    if (!pd->default_string || _vrg_choice_index(choices, pd->default_string) < 0)
        return snprintf(why, cap, "has default '%s', which is none of its choices %s", pd->default_string ? pd->default_string : "(none)", choices), why;
    return NULL;
}
