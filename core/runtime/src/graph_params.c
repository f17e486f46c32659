/* A pass's numeric parameters as a host reads and sets them between
 * frames ("pass.param"), with the plugin's range checks. */
#include <math.h>
#include <string.h>
#include "internal.h"

/* "pass.param": the pass and the parameter's index, or -1 after an error */
static int find_param(vrg_graph *g, const char *pass_param, vrg_pass **out)
{
    const char *dot = strchr(pass_param, '.');
    vrg_pass *p = NULL;
    for (int i = 0; dot && i < g->pass_count && !p; i++)
        if (strlen(g->passes[i].name) == (size_t)(dot - pass_param) && strncmp(g->passes[i].name, pass_param, (size_t)(dot - pass_param)) == 0)
            p = &g->passes[i];
    if (!p) {
        _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "%s: no pass of that name (PASS.PARAM)", pass_param);
        return -1;
    }
    *out = p;
    const vrg_plugin_desc *d = p->plugin->desc;
    for (uint32_t i = 0; i < d->param_count; i++)
        if (strcmp(d->params[i].name, dot + 1) == 0)
            return (int)i;
    _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "%s: pass '%s' (plugin %s) has no parameter '%s'", pass_param, p->name, p->plugin->name, dot + 1);
    return -1;
}

int vrg_graph_get_param(vrg_graph *g, const char *pass_param, double *value)
{
    vrg_pass *p;
    int i = find_param(g, pass_param, &p);
    if (i < 0)
        return -1;
    *value = p->params[i];
    return 0;
}

int vrg_graph_set_param(vrg_graph *g, const char *pass_param, double value)
{
    vrg_pass *p;
    int i = find_param(g, pass_param, &p);
    if (i >= 0) {
        const vrg_param_desc *pd = &p->plugin->desc->params[i];
        if (pd->type == VRG_PARAM_STRING || (pd->flags & VRG_PARAM_RELOAD)) {
            _vrg_error(&g->diag, VRG_E_PARAM_NOT_SETTABLE, "set %s: %s; edit the graph file (it reloads)", pass_param,
                       pd->type == VRG_PARAM_STRING ? "a string parameter" : "read only when the pass is created");
            return -1;
        }
        if (value != value || (pd->type != VRG_PARAM_FLOAT && value != floor(value)) || ((pd->min != 0 || pd->max != 0) && (value < pd->min || value > pd->max))) {
            _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "set %s = %g: %s takes %s in [%g, %g]", pass_param, value, pd->name, pd->type == VRG_PARAM_FLOAT ? "a number" : "an integer",
                      pd->min, pd->max);
            return -1;
        }
        if (p->params[i] != value) {
            p->params[i] = value;
            g->params_changed = 1; /* accumulations restart; history stays */
        }
        return 0;
    }
    return -1;
}
