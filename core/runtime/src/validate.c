#define _DEFAULT_SOURCE
/* Phase 2, validate: give the parsed keys meaning. Loads plugins, resolves
 * slots to resources, and runs every check, collecting all errors (each with
 * file:line and a hint) instead of stopping at the first. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "phases.h"
#include "parse.h"
#include "plugin_loader.h"
#include "shader_pass.h"

/* ---- numbers ---- */

static int parse_double(const char *s, double *out)
{
    char *end;
    while (isspace((unsigned char)*s))
        s++;
    if (!*s)
        return -1;
    /* decimal only: strtod would also take hex ("0x10") and "infinity" */
    for (const char *c = s; *c; c++)
        if (*c == 'x' || *c == 'X')
            return -1;
    double v = strtod(s, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || isnan(v) || isinf(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_int(const char *s, long *out)
{
    double v;
    /* up to 2^32 - 1: seeds and masks are unsigned 32-bit */
    if (parse_double(s, &v) != 0 || v != floor(v) || v < -2147483648.0 || v > 4294967295.0)
        return -1;
    *out = (long)v;
    return 0;
}

static int parse_bool(const char *s, double *out)
{
    static const char *yes[] = {"1", "true", "yes", "on"}, *no[] = {"0", "false", "no", "off"};
    for (int i = 0; i < 4; i++) {
        if (strcasecmp(s, yes[i]) == 0) { *out = 1; return 0; }
        if (strcasecmp(s, no[i]) == 0) { *out = 0; return 0; }
    }
    return -1;
}

static int positive_int(_vrg_diag *d, const _vrg_key *k, uint32_t max, uint32_t *out)
{
    long v;
    if (parse_int(k->value, &v) != 0 || v <= 0 || v > (long)max) {
        char hint[96];
        snprintf(hint, sizeof hint, "a whole number from 1 to %u", max);
        _vrg_error_at(d, k->line, VRG_E_NOT_A_NUMBER, hint, "'%s = %s' must be a positive integer", k->name, k->value);
        return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

/* ---- resources ---- */

static int valid_name(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-' && *s != '.')
            return 0;
    return 1;
}

/* Names longer than the tables hold are an error of their own (not "not
 * valid", and never cut short). Returns 1 after reporting. */
static int name_too_long(vrg_graph *g, int line, const char *what, const char *name, size_t len)
{
    if (len < VRG_NAME_MAX)
        return 0;
    _vrg_error_at(&g->diag, line, VRG_E_TOO_LONG, NULL, "%s name '%.*s' is longer than %d characters", what, (int)len, name, VRG_NAME_MAX - 1);
    return 1;
}

/* A slot by name and direction (in.color and out.color may both exist);
 * with no slot of that direction, one of the other so the error can say so. */
static int find_slot(const vrg_plugin_desc *desc, const char *name, vrg_slot_dir dir)
{
    int other = -1;
    for (uint32_t i = 0; i < desc->slot_count; i++)
        if (strcmp(desc->slots[i].name, name) == 0) {
            if (desc->slots[i].dir == dir)
                return (int)i;
            other = (int)i;
        }
    return other;
}

static int find_param(const vrg_plugin_desc *desc, const char *name)
{
    for (uint32_t i = 0; i < desc->param_count; i++)
        if (strcmp(desc->params[i].name, name) == 0)
            return (int)i;
    return -1;
}

/* Checks and stores one parameter value; `where` is the line, or 0 for --set. */
static int set_param(vrg_graph *g, vrg_pass *p, int idx, const char *value, int line, const char *what)
{
    const vrg_param_desc *pd = &p->plugin->desc->params[idx];
    if (pd->type == VRG_PARAM_STRING) {
        /* a list grows by file lines; --set replaces it */
        _vrg_pass_add_string(p, idx, value, line, !line || !(pd->flags & VRG_PARAM_REPEATABLE));
        (void)g;
        (void)what;
        return 0;
    }
    double v = 0;
    long iv = 0;
    int bad;
    const char *hint = pd->help;
    if (pd->type == VRG_PARAM_BOOL)
        bad = parse_bool(value, &v);
    else if (pd->type == VRG_PARAM_INT)
        bad = parse_int(value, &iv), v = (double)iv;
    else
        bad = parse_double(value, &v);
    if (bad) {
        const char *kind = pd->type == VRG_PARAM_BOOL ? "true or false" : pd->type == VRG_PARAM_INT ? "an integer" : "a finite number";
        if (line)
            _vrg_error_at(&g->diag, line, VRG_E_NOT_A_NUMBER, hint, "%s = '%s' is not a number of the right kind: %s expects %s", what, value, pd->name, kind);
        else
            _vrg_error(&g->diag, VRG_E_NOT_A_NUMBER, "override %s=%s: not a number of the right kind (%s expects %s)", what, value, pd->name, kind);
        return -1;
    }
    if ((pd->min != 0 || pd->max != 0) && (v < pd->min || v > pd->max)) {
        char h[256];
        snprintf(h, sizeof h, "%s lies in [%g, %g]%s%s", pd->name, pd->min, pd->max, hint ? ": " : "", hint ? hint : "");
        if (line)
            _vrg_error_at(&g->diag, line, VRG_E_OUT_OF_RANGE, h, "%s = %s is out of range", what, value);
        else
            _vrg_error(&g->diag, VRG_E_OUT_OF_RANGE, "override %s=%s is out of range (%s)", what, value, h);
        return -1;
    }
    p->params[idx] = v;
    return 0;
}

/* ---- sections ---- */

/* A key given twice in one section is a mistake, not an override. */
static int repeated_key(vrg_graph *g, const _vrg_ast *a, int ki)
{
    const _vrg_key *k = &a->keys[ki];
    for (int i = 0; i < ki; i++)
        if (a->keys[i].section_index == k->section_index && strcmp(a->keys[i].name, k->name) == 0) {
            char h[64];
            snprintf(h, sizeof h, "first given at line %d", a->keys[i].line);
            _vrg_error_at(&g->diag, k->line, VRG_E_DUPLICATE_KEY, h, "duplicate key '%s' in [%s]", k->name, a->sections[k->section_index].name);
            return 1;
        }
    return 0;
}

typedef enum { SEC_GRAPH, SEC_SCENE, SEC_PASS, SEC_RESOURCE, SEC_CAMERA, SEC_UNKNOWN } sec_kind;

static sec_kind section_kind(const char *name, const char **arg)
{
    *arg = NULL;
    if (strcmp(name, "graph") == 0)
        return SEC_GRAPH;
    if (strcmp(name, "scene") == 0)
        return SEC_SCENE;
    if (strcmp(name, "camera") == 0)
        return SEC_CAMERA;
    if (strncmp(name, "pass ", 5) == 0 || strncmp(name, "resource ", 9) == 0) {
        const char *a = name + (name[0] == 'p' ? 5 : 9);
        while (*a == ' ')
            a++;
        *arg = a;
        return name[0] == 'p' ? SEC_PASS : SEC_RESOURCE;
    }
    return SEC_UNKNOWN;
}

static void graph_section(vrg_graph *g, const _vrg_ast *a, int si, const char *graph_path)
{
    static const char *known = "name, output, width, height, seed, fps, frames_in_flight, plugin_path";
    for (int i = 0; i < a->key_count; i++) {
        const _vrg_key *k = &a->keys[i];
        if (k->section_index != si || repeated_key(g, a, i))
            continue;
        double v;
        if (strcmp(k->name, "name") == 0) {
            if (!name_too_long(g, k->line, "graph", k->value, strlen(k->value)))
                snprintf(g->name, sizeof g->name, "%s", k->value);
        } else if (strcmp(k->name, "output") == 0) {
            if (!name_too_long(g, k->line, "resource", k->value, strlen(k->value)))
                snprintf(g->output_name, sizeof g->output_name, "%s", k->value);
            g->output_line = k->line;
        } else if (strcmp(k->name, "width") == 0)
            positive_int(&g->diag, k, 16384, &g->width);
        else if (strcmp(k->name, "height") == 0)
            positive_int(&g->diag, k, 16384, &g->height);
        else if (strcmp(k->name, "seed") == 0) {
            double d;
            if (parse_double(k->value, &d) != 0 || d < 0 || d > 4294967295.0 || d != floor(d))
                _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "a whole number from 0 to 4294967295", "'seed = %s' must be a non-negative integer", k->value);
            else
                g->seed = (uint32_t)d;
        } else if (strcmp(k->name, "fps") == 0) {
            if (parse_double(k->value, &v) != 0)
                _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "frames per second of simulated time", "'fps = %s' is not a number", k->value);
            else if (v <= 0)
                _vrg_error_at(&g->diag, k->line, VRG_E_OUT_OF_RANGE, "frames per second of simulated time", "'fps = %s' must be > 0", k->value);
            else
                g->fps = v;
        } else if (strcmp(k->name, "frames_in_flight") == 0) {
            long n;
            if (parse_int(k->value, &n) != 0 || n < 1 || n > VRG_MAX_FRAMES_IN_FLIGHT)
                _vrg_error_at(&g->diag, k->line, parse_int(k->value, &n) != 0 ? VRG_E_NOT_A_NUMBER : VRG_E_OUT_OF_RANGE, "1: the CPU waits for each frame; 2 (the default): it records the next while the GPU runs one",
                              "'frames_in_flight = %s' must be a whole number from 1 to %d", k->value, VRG_MAX_FRAMES_IN_FLIGHT);
            else
                g->frames_in_flight = (uint32_t)n;
        } else if (strcmp(k->name, "plugin_path") == 0)
            _vrg_plugin_path_check(graph_path, k->value, &g->diag, k->line); /* a typo: not "unknown plugin" per pass */
        else
            _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_KEY, known, "unknown key '%s' in [graph]", k->name);
    }
}

/* Three decimal numbers (parse_double's rules) within the world. */
static void camera_position(vrg_graph *g, const _vrg_key *k, float out[3])
{
    char buf[sizeof k->value], *save = NULL;
    snprintf(buf, sizeof buf, "%s", k->value);
    double d[3];
    int n = 0;
    for (char *tok = strtok_r(buf, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save), n++)
        if (n >= 3 || parse_double(tok, &d[n]) != 0) {
            n = -1;
            break;
        }
    if (n != 3) {
        _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "three decimal numbers: X Y Z in blocks", "'position = %s' is not a position", k->value);
        return;
    }
    /* checked as doubles: one beyond float's range must not be converted */
    if (!(fabs(d[0]) <= VRG_WORLD_LIMIT && fabs(d[1]) <= VRG_WORLD_LIMIT && fabs(d[2]) <= VRG_WORLD_LIMIT)) {
        char hint[96];
        snprintf(hint, sizeof hint, "X, Y and Z lie in [%.0f, %.0f] blocks (VRG_WORLD_LIMIT)", -VRG_WORLD_LIMIT, VRG_WORLD_LIMIT);
        _vrg_error_at(&g->diag, k->line, VRG_E_OUT_OF_RANGE, hint, "'position = %s' is outside the world", k->value);
        return;
    }
    for (int a = 0; a < 3; a++)
        out[a] = (float)d[a];
}

/* [camera]: where a still camera stands (--camera PATH or the host moves it). */
static void camera_section(vrg_graph *g, const _vrg_ast *a, int si)
{
    static const char *known = "position = X Y Z, yaw, pitch, fov (degrees)";
    vrg_camera *c = &g->camera;
    for (int i = 0; i < a->key_count; i++) {
        const _vrg_key *k = &a->keys[i];
        if (k->section_index != si || repeated_key(g, a, i))
            continue;
        double v;
        if (strcmp(k->name, "position") == 0)
            camera_position(g, k, c->position);
        else if (strcmp(k->name, "yaw") == 0 || strcmp(k->name, "pitch") == 0 || strcmp(k->name, "fov") == 0) {
            int is_pitch = k->name[0] == 'p', is_fov = k->name[0] == 'f';
            double lo, hi;
            vrg_camera_angle_range(k->name, &lo, &hi); /* the camera paths' too */
            char hint[64];
            snprintf(hint, sizeof hint, "degrees in [%g, %g]", lo, hi);
            if (parse_double(k->value, &v) != 0)
                _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, hint, "'%s = %s' is not a number", k->name, k->value);
            else if (v < lo || v > hi)
                _vrg_error_at(&g->diag, k->line, VRG_E_OUT_OF_RANGE, hint, "'%s = %s' is out of range", k->name, k->value);
            else if (is_fov)
                c->fov_y = (float)v;
            else if (is_pitch)
                c->pitch = (float)v;
            else
                c->yaw = (float)v;
        } else
            _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_KEY, known, "unknown key '%s' in [camera]", k->name);
    }
}

static void param_hint(const vrg_plugin_desc *desc, char *out, size_t cap)
{
    size_t n = (size_t)snprintf(out, cap, "plugin '%s' takes: plugin, in.*/out.* slots", desc->name);
    for (uint32_t i = 0; i < desc->slot_count && n < cap; i++)
        n += (size_t)snprintf(out + n, cap - n, " %s.%s", desc->slots[i].dir == VRG_IN ? "in" : "out", desc->slots[i].name);
    if (n < cap)
        n += (size_t)snprintf(out + n, cap - n, "; parameters:");
    for (uint32_t i = 0; i < desc->param_count && n < cap; i++)
        n += (size_t)snprintf(out + n, cap - n, " %s", desc->params[i].name);
    if (desc->param_count == 0 && n < cap)
        snprintf(out + n, cap - n, " none");
}

static void bind_slot(vrg_graph *g, vrg_pass *p, const _vrg_key *k, const char *slot_name, vrg_slot_dir dir)
{
    const vrg_plugin_desc *desc = p->plugin->desc;
    char hint[1024];
    int s = find_slot(desc, slot_name, dir);
    if (s < 0) {
        param_hint(desc, hint, sizeof hint);
        _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_SLOT, hint, "plugin '%s' has no slot '%s'", desc->name, slot_name);
        return;
    }
    const vrg_slot_desc *sd = &desc->slots[s];
    if (sd->dir != dir) {
        _vrg_error_at(&g->diag, k->line, VRG_E_SLOT_DIRECTION, dir == VRG_IN ? "connect it as out.<slot>" : "connect it as in.<slot>",
                     "slot '%s' of plugin '%s' is an %s", slot_name, desc->name, sd->dir == VRG_IN ? "input" : "output");
        return;
    }
    if (p->slots[s].line) {
        _vrg_error_at(&g->diag, k->line, VRG_E_SLOT_CONNECTED_TWICE, NULL, "slot '%s' is connected twice (first at line %d)", slot_name, p->slots[s].line);
        return;
    }
    /* From here on errors concern the value: the slot counts as connected
     * so it is not also reported as missing. */
    p->slots[s].bad = 1;
    p->slots[s].line = k->line;
    if (name_too_long(g, k->line, "resource", k->value, strcspn(k->value, "@")))
        return;
    char name[VRG_NAME_MAX + 8];
    snprintf(name, sizeof name, "%s", k->value);
    char *at = strchr(name, '@');
    int prev = 0;
    if (at) {
        if (strcmp(at, "@prev") != 0 || dir == VRG_OUT) {
            _vrg_error_at(&g->diag, k->line, VRG_E_BAD_PREV, "'@prev' on an input names last frame's value of a resource",
                         "'%s' is not a resource name%s", k->value, dir == VRG_OUT ? " an output can write" : "");
            return;
        }
        *at = '\0';
        prev = 1;
    }
    if (!valid_name(name) || strlen(name) >= VRG_NAME_MAX) {
        _vrg_error_at(&g->diag, k->line, VRG_E_INVALID_NAME, "resource names use letters, digits, '_', '-' and '.'", "'%s' is not a valid resource name", k->value);
        return;
    }
    int r = _vrg_graph_add_resource(g, name);
    if (r < 0) {
        _vrg_error_at(&g->diag, k->line, VRG_E_TOO_MANY, NULL, "too many resources (at most %d)", VRG_MAX_RESOURCES);
        return;
    }
    _vrg_resource *res = &g->res[r];
    if (!res->line)
        res->line = k->line;
    p->slots[s] = (_vrg_binding_ref){.res = r, .prev = prev, .line = k->line};
    if (dir == VRG_OUT && res->writer >= 0)
        p->slots[s].bad = 1;
    if (dir == VRG_OUT) {
        if (res->writer >= 0) {
            char h[128];
            snprintf(h, sizeof h, "pass '%s' already writes it at line %d; give one of them another name", g->passes[res->writer].name,
                     res->writer_line);
            _vrg_error_at(&g->diag, k->line, VRG_E_TWO_WRITERS, h, "resource '%s' has two writers", name);
            return;
        }
        res->writer = (int)(p - g->passes);
        res->writer_slot = s;
        res->writer_line = k->line;
    } else if (prev)
        res->history = 1;
}

/* Falcor's per-pass output size: the pass's image outputs that are sized
 * relative to the graph get this factor (a [resource] section still wins),
 * e.g. lighting at half resolution without a section per output. */
static void output_scale(vrg_graph *g, vrg_pass *p, const _vrg_key *k)
{
    double v;
    if (parse_double(k->value, &v) != 0) {
        _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "a factor of the outputs' size, e.g. 0.5", "'output_scale = %s' is not a number", k->value);
        return;
    }
    if (!(v > 0) || v > 16) {
        _vrg_error_at(&g->diag, k->line, VRG_E_OUT_OF_RANGE, "a factor in (0, 16]", "'output_scale = %s' must be > 0 (and at most 16)", k->value);
        return;
    }
    p->output_scale = (float)v;
    const vrg_plugin_desc *desc = p->plugin->desc;
    for (uint32_t i = 0; i < desc->slot_count; i++)
        if (desc->slots[i].dir == VRG_OUT && desc->slots[i].kind == VRG_IMAGE && !desc->slots[i].width)
            return;
    _vrg_error_at(&g->diag, k->line, VRG_E_KEY_WRONG_KIND, "it scales image outputs sized relative to the graph", "pass '%s' (plugin '%s') has no image output that output_scale could scale",
                 p->name, desc->name);
}

static void pass_section(vrg_graph *g, const _vrg_ast *a, int si, vrg_pass *p)
{
    char hint[1024];
    for (int i = 0; i < a->key_count; i++) {
        const _vrg_key *k = &a->keys[i];
        if (k->section_index != si || strcmp(k->name, "plugin") == 0)
            continue;
        int list = p->plugin && find_param(p->plugin->desc, k->name) >= 0 &&
                   (p->plugin->desc->params[find_param(p->plugin->desc, k->name)].flags & VRG_PARAM_REPEATABLE);
        if (!list && repeated_key(g, a, i))
            continue;
        if (!p->plugin) {
            /* Its plugin failed to load (already reported). Remember what it
             * would write so readers get no follow-on "never written". */
            if (strncmp(k->name, "out.", 4) == 0 && valid_name(k->value)) {
                int r = _vrg_graph_add_resource(g, k->value);
                if (r >= 0)
                    g->res[r].writer_unknown = 1;
            }
            continue;
        }
        const vrg_plugin_desc *desc = p->plugin->desc;
        if (strcmp(k->name, "output_scale") == 0)
            output_scale(g, p, k);
        else if (strncmp(k->name, "in.", 3) == 0)
            bind_slot(g, p, k, k->name + 3, VRG_IN);
        else if (strncmp(k->name, "out.", 4) == 0)
            bind_slot(g, p, k, k->name + 4, VRG_OUT);
        else {
            int pi = find_param(desc, k->name);
            if (pi < 0) {
                param_hint(desc, hint, sizeof hint);
                _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_KEY, hint, "unknown key '%s' in [%s]", k->name, a->sections[si].name);
            } else
                set_param(g, p, pi, k->value, k->line, k->name);
        }
    }
}

static void resource_section(vrg_graph *g, const _vrg_ast *a, int si, const char *name)
{
    if (name_too_long(g, a->sections[si].line, "resource", name, strlen(name)))
        return;
    int ri = _vrg_graph_find_resource(g, name);
    if (ri < 0) {
        _vrg_warning_at(&g->diag, a->sections[si].line, VRG_W_UNUSED_RESOURCE, "[resource %s] is not used by any pass", name);
        return;
    }
    _vrg_resource *r = &g->res[ri];
    r->line = a->sections[si].line;
    for (int i = 0; i < a->key_count; i++) {
        const _vrg_key *k = &a->keys[i];
        if (k->section_index != si || repeated_key(g, a, i))
            continue;
        double v;
        if (strcmp(k->name, "format") == 0) {
            VkFormat f = _vrg_format_parse(k->value);
            if (f == VK_FORMAT_UNDEFINED)
                _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_FORMAT, _vrg_format_list(), "unknown format '%s'", k->value);
            else
                r->format = f, r->format_line = k->line;
        } else if (strcmp(k->name, "scale") == 0) {
            if (parse_double(k->value, &v) != 0)
                _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "a fraction of the graph size, e.g. 0.5", "'scale = %s' is not a number", k->value);
            else if (v <= 0 || v > 16)
                _vrg_error_at(&g->diag, k->line, VRG_E_OUT_OF_RANGE, "a fraction of the graph size in (0, 16]", "'scale = %s' must be > 0 (and at most 16)", k->value);
            else
                r->scale = (float)v, r->size_line = r->extent_line = k->line;
        } else if (strcmp(k->name, "width") == 0) {
            if (positive_int(&g->diag, k, 16384, &r->abs_width) == 0)
                r->size_line = r->extent_line = k->line;
        } else if (strcmp(k->name, "height") == 0) {
            if (positive_int(&g->diag, k, 16384, &r->abs_height) == 0)
                r->size_line = r->extent_line = k->line;
        } else if (strcmp(k->name, "size") == 0) {
            long s;
            if (parse_int(k->value, &s) != 0 || s <= 0)
                _vrg_error_at(&g->diag, k->line, VRG_E_NOT_A_NUMBER, "buffer size in bytes", "'size = %s' must be a positive integer", k->value);
            else
                r->size = (uint64_t)s, r->size_line = r->bytes_line = k->line;
        } else
            _vrg_error_at(&g->diag, k->line, VRG_E_UNKNOWN_KEY, "format, scale, width, height (images) or size (buffers)", "unknown key '%s' in [resource %s]", k->name, name);
    }
    if ((r->abs_width != 0) != (r->abs_height != 0))
        _vrg_error_at(&g->diag, r->line, VRG_E_SIZE_KEYS, "give both width and height, or scale", "[resource %s] sets only one of width and height", name);
    if (r->abs_width && r->scale > 0)
        _vrg_error_at(&g->diag, r->line, VRG_E_SIZE_KEYS, "give width and height, or scale, not both", "[resource %s] sets both a scale and a size", name);
}

static int find_pass(const vrg_graph *g, const char *name)
{
    for (int i = 0; i < g->pass_count; i++)
        if (strcmp(g->passes[i].name, name) == 0)
            return i;
    return -1;
}

/* [graph] plugin_path: needed before any plugin loads, so read here. */
static const char *graph_plugin_path(const _vrg_ast *a)
{
    for (int i = 0; i < a->key_count; i++)
        if (strcmp(a->keys[i].name, "plugin_path") == 0 && strcmp(a->sections[a->keys[i].section_index].name, "graph") == 0)
            return a->keys[i].value;
    return NULL;
}

/* First pass: the sections themselves, plugins, and pass identities. */
static void collect_sections(vrg_graph *g, const _vrg_ast *a, const char *graph_path, int *graph_si, int *camera_si)
{
    int scene_si = -1;
    *graph_si = -1;
    *camera_si = -1;
    for (int si = 0; si < a->section_count; si++) {
        const _vrg_section *sec = &a->sections[si];
        const char *arg;
        sec_kind kind = section_kind(sec->name, &arg);
        if (kind == SEC_UNKNOWN) {
            _vrg_error_at(&g->diag, sec->line, VRG_E_UNKNOWN_SECTION, "sections are [graph], [camera], [scene], [pass NAME] and [resource NAME]", "unknown section '[%s]'",
                         sec->name);
            continue;
        }
        if (kind == SEC_CAMERA) {
            if (*camera_si >= 0)
                _vrg_error_at(&g->diag, sec->line, VRG_E_DUPLICATE_SECTION, NULL, "duplicate section [camera] (first at line %d)", a->sections[*camera_si].line);
            else
                *camera_si = si;
            continue;
        }
        if (kind == SEC_GRAPH || kind == SEC_SCENE) {
            int *seen = kind == SEC_GRAPH ? graph_si : &scene_si;
            if (*seen >= 0)
                _vrg_error_at(&g->diag, sec->line, VRG_E_DUPLICATE_SECTION, NULL, "duplicate section [%s] (first at line %d)", sec->name, a->sections[*seen].line);
            else
                *seen = si;
            if (kind == SEC_GRAPH)
                continue;
        }
        if (kind == SEC_RESOURCE) {
            for (int o = 0; o < si; o++)
                if (strcmp(a->sections[o].name, sec->name) == 0) {
                    _vrg_error_at(&g->diag, sec->line, VRG_E_DUPLICATE_SECTION, NULL, "duplicate section [%s] (first at line %d)", sec->name, a->sections[o].line);
                    break;
                }
            continue;
        }
        if (kind == SEC_SCENE && *(&scene_si) != si)
            continue;
        /* a pass or the scene */
        const char *pname = kind == SEC_SCENE ? "scene" : arg;
        if (kind == SEC_PASS && name_too_long(g, sec->line, "pass", pname, strlen(pname)))
            continue;
        if (kind == SEC_PASS && !valid_name(pname)) {
            _vrg_error_at(&g->diag, sec->line, VRG_E_INVALID_NAME, "pass names use letters, digits, '_', '-' and '.'", "'%s' is not a valid pass name", pname);
            continue;
        }
        if (kind == SEC_PASS && (strcmp(pname, "scene") == 0 || find_pass(g, pname) >= 0)) {
            int first = find_pass(g, pname);
            char h[96];
            snprintf(h, sizeof h, "the first [pass %s] is at line %d; pass names must be unique", pname, first >= 0 ? g->passes[first].line : 0);
            _vrg_error_at(&g->diag, sec->line, VRG_E_DUPLICATE_PASS, h, "duplicate pass name '%s'", pname);
            continue;
        }
        if (g->pass_count >= VRG_MAX_PASSES) {
            _vrg_error_at(&g->diag, sec->line, VRG_E_TOO_MANY, NULL, "too many passes (at most %d)", VRG_MAX_PASSES);
            continue;
        }
        vrg_pass *p = &g->passes[g->pass_count++];
        memset(p, 0, sizeof *p);
        snprintf(p->name, sizeof p->name, "%s", pname);
        p->line = sec->line;
        p->is_scene = kind == SEC_SCENE;
        p->graph = g;
        p->order = -1;
        for (int s = 0; s < VRG_MAX_SLOTS; s++)
            p->slots[s].res = -1;
        const _vrg_key *plugin_key = NULL;
        for (int i = 0; i < a->key_count; i++)
            if (a->keys[i].section_index == si && strcmp(a->keys[i].name, "plugin") == 0) {
                if (plugin_key)
                    _vrg_error_at(&g->diag, a->keys[i].line, VRG_E_DUPLICATE_KEY, NULL, "duplicate key 'plugin' in [%s] (first at line %d)", sec->name, plugin_key->line);
                else
                    plugin_key = &a->keys[i];
            }
        if (!plugin_key) {
            _vrg_error_at(&g->diag, sec->line, VRG_E_NO_PLUGIN, "add 'plugin = NAME' (`voxrg plugins` lists them)", "[%s] has no plugin", sec->name);
            continue;
        }
        const _vrg_plugin *pl = _vrg_plugin_load(plugin_key->value, graph_path, graph_plugin_path(a), &g->diag, plugin_key->line);
        if (!pl)
            continue;
        if (kind == SEC_PASS && pl->desc->kind == VRG_PLUGIN_SCENE) {
            _vrg_error_at(&g->diag, plugin_key->line, VRG_E_PLUGIN_KIND, "use it in the [scene] section", "plugin '%s' is a scene plugin, not a pass", pl->name);
            continue;
        }
        if (kind == SEC_SCENE && pl->desc->kind != VRG_PLUGIN_SCENE) {
            _vrg_error_at(&g->diag, plugin_key->line, VRG_E_PLUGIN_KIND, "use it in a [pass NAME] section", "plugin '%s' is a pass plugin, not a scene plugin", pl->name);
            continue;
        }
        p->plugin = pl;
        _vrg_plugin_acquire(pl); /* released by vrg_graph_destroy */
        for (uint32_t i = 0; i < pl->desc->param_count; i++)
            p->params[i] = pl->desc->params[i].default_value;
    }
}

static void apply_overrides(vrg_graph *g, const vrg_graph_desc *desc)
{
    for (uint32_t i = 0; i < desc->override_count; i++) {
        const char *o = desc->overrides[i];
        const char *dot = strchr(o, '.'), *eq = strchr(o, '=');
        if (!dot || !eq || dot > eq) {
            _vrg_error(&g->diag, VRG_E_BAD_OVERRIDE, "override '%s': expected PASS.PARAM=VALUE", o);
            continue;
        }
        char pass[VRG_NAME_MAX] = {0}, param[VRG_NAME_MAX] = {0};
        snprintf(pass, sizeof pass, "%.*s", (int)(dot - o), o);
        snprintf(param, sizeof param, "%.*s", (int)(eq - dot - 1), dot + 1);
        int pi = find_pass(g, pass);
        if (pi < 0) {
            _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "override '%s': the graph has no pass '%s'", o, pass);
            continue;
        }
        vrg_pass *p = &g->passes[pi];
        if (!p->plugin)
            continue;
        int idx = find_param(p->plugin->desc, param);
        if (idx < 0) {
            char hint[1024];
            param_hint(p->plugin->desc, hint, sizeof hint);
            _vrg_error(&g->diag, VRG_E_UNKNOWN_PARAMETER, "override '%s': pass '%s' has no parameter '%s' (%s)", o, pass, param, hint);
            continue;
        }
        char what[2 * VRG_NAME_MAX + 2];
        snprintf(what, sizeof what, "%s.%s", pass, param);
        set_param(g, p, idx, eq + 1, 0, what);
    }
}

/* Resolve each resource's kind, format and size from its writer and the
 * [resource] overrides; then check every reader against it. */
/* A persistent resource (a scene's world, an acceleration structure) is
 * kept up to date in place, one copy: an @prev read of it would give it a
 * second copy that its writer updates only every other frame, so frames
 * would alternate between the world and an empty buffer. An error, not a
 * silent alternation. */
static void check_prev_of_persistent(vrg_graph *g)
{
    for (int pi = 0; pi < g->pass_count; pi++) {
        const vrg_pass *p = &g->passes[pi];
        for (int s = 0; p->plugin && s < (int)p->plugin->desc->slot_count; s++) {
            const _vrg_binding_ref *b = &p->slots[s];
            if (b->res < 0 || !b->prev || !g->res[b->res].persistent || g->res[b->res].writer < 0)
                continue;
            const _vrg_resource *r = &g->res[b->res];
            char h[160];
            snprintf(h, sizeof h, "pass '%s' keeps it up to date in place (line %d): read '%s' without @prev", g->passes[r->writer].name,
                     r->writer_line, r->name);
            _vrg_error_at(&g->diag, b->line, VRG_E_PREV_OF_PERSISTENT, h, "'%s@prev': resource '%s' is persistent and has no last frame's copy", r->name, r->name);
        }
    }
}

/* 1 when a pass or the scene has an out.SLOT key naming `name` (with or
 * without an '@' suffix) that wrote nothing: the pass, its plugin or the
 * binding was refused, and that error is the cause to read. "Never
 * written" would only follow from it, and print before it when its line
 * comes first. */
static int write_refused(const vrg_graph *g, const _vrg_ast *a, const char *name)
{
    if (!g->diag.errors)
        return 0;
    for (int i = 0; i < a->key_count; i++) {
        const _vrg_key *k = &a->keys[i];
        const char *arg;
        sec_kind kind = section_kind(a->sections[k->section_index].name, &arg);
        size_t len = strcspn(k->value, "@");
        if ((kind == SEC_PASS || kind == SEC_SCENE) && strncmp(k->name, "out.", 4) == 0 && len == strlen(name) && strncmp(k->value, name, len) == 0)
            return 1;
    }
    return 0;
}

static void resolve_resources(vrg_graph *g, const _vrg_ast *a)
{
    for (int ri = 0; ri < g->res_count; ri++) {
        _vrg_resource *r = &g->res[ri];
        if (r->writer < 0)
            continue;
        const vrg_slot_desc *sd = vrg_slot(&g->passes[r->writer], r->writer_slot);
        const vrg_slot_desc def = _vrg_slot_desc_defaults(sd);
        r->kind = sd->kind;
        if (sd->kind == VRG_BUFFER || !r->format_line)
            r->format = def.format;
        if (!r->size_line) {
            const vrg_pass *w = &g->passes[r->writer];
            r->scale = def.scale * (sd->kind == VRG_IMAGE && !sd->width && w->output_scale > 0 ? w->output_scale : 1.0f);
            r->abs_width = sd->width;
            r->abs_height = sd->height;
            if (sd->kind != VRG_IMAGE)
                r->size = g->passes[r->writer].buffer_size[r->writer_slot] ? g->passes[r->writer].buffer_size[r->writer_slot] : sd->size;
        }
        if (sd->kind == VRG_ACCEL && (r->format_line || r->extent_line))
            _vrg_error_at(&g->diag, r->format_line ? r->format_line : r->extent_line, VRG_E_KEY_WRONG_KIND, "acceleration structures take size = INSTANCES",
                         "resource '%s' is an acceleration structure", r->name);
        if (sd->kind == VRG_BUFFER && r->size == 0)
            _vrg_error_at(&g->diag, r->writer_line, VRG_E_BUFFER_SIZE, "give the buffer a size in a [resource] section", "buffer '%s' has size 0", r->name);
        else if (sd->kind == VRG_BUFFER && r->size % _vrg_format_bytes(r->format)) {
            char h[160];
            snprintf(h, sizeof h, "pass '%s' declares %s texels for it (its slot '%s')", g->passes[r->writer].name, _vrg_format_name(r->format), sd->name);
            _vrg_error_at(&g->diag, r->size_line ? r->size_line : r->writer_line, VRG_E_BUFFER_SIZE, h, "buffer '%s' of %llu bytes is not a whole number of %llu-byte texels", r->name,
                         (unsigned long long)r->size, (unsigned long long)_vrg_format_bytes(r->format));
        }
        /* A shader writes a storage image through a format qualifier: the
         * image must have that format. Sampled and transfer writers adapt. */
        int storage = sd->access == VRG_ACCESS_STORAGE_WRITE || sd->access == VRG_ACCESS_STORAGE_READ_WRITE;
        if (sd->kind == VRG_IMAGE && r->format_line && storage && sd->format && sd->format != r->format) {
            char h[160];
            snprintf(h, sizeof h, "pass '%s' writes it as a storage image of format %s", g->passes[r->writer].name, _vrg_format_name(sd->format));
            _vrg_error_at(&g->diag, r->format_line, VRG_E_FORMAT_MISMATCH, h, "format mismatch: resource '%s' cannot be %s", r->name, _vrg_format_name(r->format));
        }
        if (sd->kind == VRG_BUFFER && r->format_line)
            _vrg_error_at(&g->diag, r->format_line, VRG_E_KEY_WRONG_KIND, "format applies to images", "resource '%s' is a buffer", r->name);
        /* an acceleration structure is rebuilt from scene data, never aliased */
        r->persistent = (sd->flags & VRG_SLOT_PERSISTENT) != 0 || sd->kind == VRG_ACCEL;
        r->mip_request = sd->mip_levels;
        if (sd->kind != VRG_BUFFER && sd->kind != VRG_ACCEL && r->bytes_line)
            _vrg_error_at(&g->diag, r->bytes_line, VRG_E_KEY_WRONG_KIND, "size = applies to buffers; images take scale or width/height", "resource '%s' is an image", r->name);
        if (sd->kind == VRG_BUFFER && r->extent_line)
            _vrg_error_at(&g->diag, r->extent_line, VRG_E_KEY_WRONG_KIND, "buffers take size = BYTES", "resource '%s' is a buffer", r->name);
    }
    for (int pi = 0; pi < g->pass_count; pi++) {
        vrg_pass *p = &g->passes[pi];
        if (!p->plugin)
            continue;
        for (uint32_t s = 0; s < p->plugin->desc->slot_count; s++) {
            const vrg_slot_desc *sd = vrg_slot(p, (int)s);
            _vrg_binding_ref *b = &p->slots[s];
            if (sd->dir != VRG_IN)
                continue;
            if (b->bad && b->res < 0)
                continue; /* its error is already reported */
            if (b->res < 0 && (sd->flags & VRG_SLOT_OPTIONAL) && sd->kind == VRG_ACCEL)
                continue; /* no stand-in can exist: shaders compile without it (vrg_res_connected) */
            if (b->res < 0 && (sd->flags & VRG_SLOT_OPTIONAL)) {
                /* Shaders still declare the binding: give them a 1x1 stand-in. */
                char name[2 * VRG_NAME_MAX + 16];
                snprintf(name, sizeof name, "%s.%s(unconnected)", p->name, sd->name);
                int r = _vrg_graph_add_resource(g, name);
                if (r >= 0) {
                    _vrg_resource *res = &g->res[r];
                    res->kind = sd->kind;
                    res->format = _vrg_slot_desc_defaults(sd).format;
                    res->abs_width = res->abs_height = 1;
                    res->size = sd->size > 16 ? sd->size : 16;
                    res->persistent = res->dummy = 1;
                    res->line = p->line;
                    *b = (_vrg_binding_ref){.res = r, .dummy = 1, .line = p->line};
                }
                continue;
            }
            if (b->res < 0) {
                if (!(sd->flags & VRG_SLOT_OPTIONAL)) {
                    char h[160];
                    snprintf(h, sizeof h, "add 'in.%s = RESOURCE' to [%s%s]", sd->name, p->is_scene ? "scene" : "pass ", p->is_scene ? "" : p->name);
                    _vrg_error_at(&g->diag, p->line, VRG_E_INPUT_NOT_CONNECTED, h, "required input '%s' of pass '%s' is not connected", sd->name, p->name);
                }
                continue;
            }
            _vrg_resource *r = &g->res[b->res];
            if (r->writer < 0 && (r->writer_unknown || write_refused(g, a, r->name)))
                continue;
            if (r->writer < 0) {
                _vrg_error_at(&g->diag, b->line, VRG_E_NEVER_WRITTEN, "some pass must write it (out.SLOT = NAME), or fix the name",
                             "resource '%s' is read but never written", r->name);
                continue;
            }
            if (r->kind != sd->kind) {
                static const char *kinds[] = {"?", "an image", "a buffer", "an acceleration structure"};
                const char *decl = _vrg_shader_pass_slot_where(p->plugin, sd);
                _vrg_error_at(&g->diag, b->line, VRG_E_KIND_MISMATCH, NULL, "kind mismatch: resource '%s' is %s, slot '%s' of pass '%s' takes %s%s%s", r->name,
                             kinds[r->kind], sd->name, p->name, kinds[sd->kind], decl ? ", declared at " : "", decl ? decl : "");
                continue;
            }
            if (sd->kind == VRG_IMAGE && sd->format && sd->format != r->format) {
                char h[256];
                snprintf(h, sizeof h, "'%s' is written by pass '%s' (line %d)%s", r->name, g->passes[r->writer].name, r->writer_line,
                         r->format_line ? "; see its [resource] format" : "");
                const char *decl = _vrg_shader_pass_slot_where(p->plugin, sd);
                _vrg_error_at(&g->diag, b->line, VRG_E_FORMAT_MISMATCH, h, "format mismatch: resource '%s' is %s, slot '%s' of pass '%s' needs %s%s%s", r->name,
                             _vrg_format_name(r->format), sd->name, p->name, _vrg_format_name(sd->format), decl ? ", declared at " : "", decl ? decl : "");
            }
            if (sd->kind == VRG_BUFFER && sd->format && sd->format != r->format) {
                const vrg_slot_desc *wd = vrg_slot(&g->passes[r->writer], r->writer_slot);
                char h[256];
                snprintf(h, sizeof h, "'%s' is written by pass '%s' (line %d), whose slot '%s' %s", r->name, g->passes[r->writer].name, r->writer_line,
                         wd->name, wd->format ? "names that texel format" : "names no texel format (r32ui)");
                _vrg_error_at(&g->diag, b->line, VRG_E_FORMAT_MISMATCH, h, "texel format mismatch: buffer '%s' has %s texels, slot '%s' of pass '%s' reads %s", r->name,
                             _vrg_format_name(r->format), sd->name, p->name, _vrg_format_name(sd->format));
            }
            if (sd->kind == VRG_IMAGE && (sd->scale > 0 || sd->width)) {
                int same = sd->width ? (r->abs_width == sd->width && r->abs_height == sd->height)
                                     : (!r->abs_width && fabsf(r->scale - sd->scale) < 1e-6f);
                if (!same) {
                    char have[64], need[64];
                    if (r->abs_width)
                        snprintf(have, sizeof have, "%ux%u", r->abs_width, r->abs_height);
                    else
                        snprintf(have, sizeof have, "scale %g", r->scale);
                    if (sd->width)
                        snprintf(need, sizeof need, "%ux%u", sd->width, sd->height);
                    else
                        snprintf(need, sizeof need, "scale %g", sd->scale);
                    _vrg_error_at(&g->diag, b->line, VRG_E_SIZE_MISMATCH, "check the [resource] size or the writer's slot", "size mismatch: resource '%s' is %s, slot '%s' of pass '%s' needs %s",
                                 r->name, have, sd->name, p->name, need);
                }
            }
            if (sd->kind == VRG_BUFFER && sd->size > r->size)
                _vrg_error_at(&g->diag, b->line, VRG_E_SIZE_MISMATCH, NULL, "size mismatch: buffer '%s' has %llu bytes, slot '%s' of pass '%s' needs at least %llu", r->name,
                             (unsigned long long)r->size, sd->name, p->name, (unsigned long long)sd->size);
        }
    }
}

/* Outputs nobody named are still written by the shader: each gets a private
 * resource "pass.slot" (a scene's: the slot name), made before the
 * [resource] sections are read so those can configure it. */
static void default_outputs(vrg_graph *g)
{
    for (int pi = 0; pi < g->pass_count; pi++) {
        vrg_pass *p = &g->passes[pi];
        if (!p->plugin)
            continue;
        /* Outputs nobody named still get written by the shader: give them a private resource. */
        for (uint32_t s = 0; s < p->plugin->desc->slot_count; s++) {
            const vrg_slot_desc *sd = vrg_slot(p, (int)s);
            if (sd->dir != VRG_OUT || p->slots[s].res >= 0 || p->slots[s].bad)
                continue;
            char name[2 * VRG_NAME_MAX + 2];
            if (p->is_scene)
                snprintf(name, sizeof name, "%s", sd->name);
            else
                snprintf(name, sizeof name, "%s.%s", p->name, sd->name);
            if (_vrg_graph_find_resource(g, name) >= 0 && g->res[_vrg_graph_find_resource(g, name)].writer >= 0) {
                _vrg_error_at(&g->diag, p->line, VRG_E_TWO_WRITERS, NULL, "resource '%s' (the default for unconnected out.%s) has two writers", name, sd->name);
                continue;
            }
            int r = _vrg_graph_add_resource(g, name);
            if (r < 0)
                continue;
            _vrg_resource *res = &g->res[r];
            /* a reader may already have asked for it (scene outputs by slot name) */
            if (!res->line)
                res->line = p->line;
            res->writer = pi;
            res->writer_slot = (int)s;
            res->writer_line = p->line;
            p->slots[s] = (_vrg_binding_ref){.res = r, .prev = 0, .line = p->line};
        }
    }
}

/* One pass may read a resource through two slots only if both want the same
 * image layout: a descriptor cannot see two layouts at once. */
static void check_conflicting_uses(vrg_graph *g)
{
    for (int pi = 0; pi < g->pass_count; pi++) {
        vrg_pass *p = &g->passes[pi];
        if (!p->plugin)
            continue;
        for (int a = 0; a < (int)p->plugin->desc->slot_count; a++)
            for (int b = a + 1; b < (int)p->plugin->desc->slot_count; b++) {
                const _vrg_binding_ref *x = &p->slots[a], *y = &p->slots[b];
                if (x->res < 0 || x->res != y->res || x->prev != y->prev || x->dummy || g->res[x->res].kind != VRG_IMAGE ||
                    vrg_slot(p, a)->dir == VRG_OUT || vrg_slot(p, b)->dir == VRG_OUT) /* read + write: reported as a cycle */
                    continue;
                _vrg_access_info ia = _vrg_access_info_of(vrg_slot(p, a)->access, VRG_IMAGE);
                _vrg_access_info ib = _vrg_access_info_of(vrg_slot(p, b)->access, VRG_IMAGE);
                if (ia.layout != ib.layout)
                    _vrg_error_at(&g->diag, y->line, VRG_E_LAYOUT_CONFLICT, "read it through one slot, or give the plugin matching accesses",
                                 "resource '%s' is bound to slots '%s' (%s) and '%s' (%s) of pass '%s', which need different layouts",
                                 g->res[x->res].name, vrg_slot(p, a)->name, _vrg_access_name(vrg_slot(p, a)->access), vrg_slot(p, b)->name,
                                 _vrg_access_name(vrg_slot(p, b)->access), p->name);
            }
    }
}

/* Cycles through same-frame reads (an @prev read breaks the cycle). */
static int cycle_dfs(vrg_graph *g, int pi, int *state, int *stack, int depth)
{
    state[pi] = 1;
    stack[depth] = pi;
    vrg_pass *p = &g->passes[pi];
    for (int s = 0; p->plugin && s < (int)p->plugin->desc->slot_count; s++) {
        _vrg_binding_ref *b = &p->slots[s];
        if (vrg_slot(p, s)->dir != VRG_IN || b->res < 0 || b->prev)
            continue;
        int w = g->res[b->res].writer;
        if (w < 0)
            continue;
        if (state[w] == 1) {
            /* every pass of the cycle, however many: sized, not cut short */
            size_t cap = (size_t)(depth + 2) * (VRG_NAME_MAX + 4), used = 0;
            char *path = malloc(cap);
            int start = depth;
            while (start > 0 && stack[start] != w)
                start--;
            int first = w;
            for (int i = start; path && i <= depth; i++) {
                if (g->passes[stack[i]].line < g->passes[first].line)
                    first = stack[i];
                used += (size_t)snprintf(path + used, cap - used, "%s -> ", g->passes[stack[i]].name);
            }
            if (path)
                snprintf(path + used, cap - used, "%s", g->passes[w].name);
            _vrg_error_at(&g->diag, g->passes[first].line, VRG_E_CYCLE, "read last frame's value with NAME@prev to break the cycle",
                         "cycle between passes: %s", path ? path : "(out of memory listing them)");
            free(path);
            return 1;
        }
        if (state[w] == 0 && cycle_dfs(g, w, state, stack, depth + 1))
            return 1;
    }
    state[pi] = 2;
    return 0;
}

static void check_cycles(vrg_graph *g)
{
    int state[VRG_MAX_PASSES] = {0}, stack[VRG_MAX_PASSES];
    for (int i = 0; i < g->pass_count; i++)
        if (state[i] == 0 && cycle_dfs(g, i, state, stack, 0))
            return; /* one cycle report is enough; the rest usually repeat it */
}

/* An optional output that no pass reads, that is not the graph's output and
 * not read back costs its pass nothing: it gets a 1x1 stand-in and the slot
 * reports unconnected (vrg_res_connected), so the pass can skip computing it.
 * Run after every reader, the output and the readbacks are known. */
static void unread_optional_outputs(vrg_graph *g)
{
    for (int pi = 0; pi < g->pass_count; pi++) {
        vrg_pass *p = &g->passes[pi];
        for (uint32_t s = 0; p->plugin && s < p->plugin->desc->slot_count; s++) {
            const vrg_slot_desc *sd = vrg_slot(p, (int)s);
            int ri = p->slots[s].res;
            if (sd->dir != VRG_OUT || !(sd->flags & VRG_SLOT_OPTIONAL) || sd->kind != VRG_IMAGE || ri < 0 || p->slots[s].bad)
                continue;
            _vrg_resource *r = &g->res[ri];
            int read = r->is_output || r->readback || r->history;
            for (int qi = 0; qi < g->pass_count && !read; qi++) {
                const vrg_pass *q = &g->passes[qi];
                for (uint32_t t = 0; q->plugin && t < q->plugin->desc->slot_count && !read; t++)
                    read = vrg_slot(q, (int)t)->dir == VRG_IN && q->slots[t].res == ri;
            }
            if (read)
                continue;
            r->abs_width = r->abs_height = 1;
            r->persistent = r->dummy = 1;
            p->slots[s].dummy = 1;
        }
    }
}

int _vrg_validate(vrg_graph *g, const _vrg_ast *ast, const vrg_graph_desc *desc)
{
    int graph_si, camera_si;
    g->fps = 60;
    collect_sections(g, ast, desc->path, &graph_si, &camera_si);
    if (camera_si >= 0)
        camera_section(g, ast, camera_si);
    if (graph_si >= 0)
        graph_section(g, ast, graph_si, desc->path);
    else
        _vrg_error_at(&g->diag, 1, VRG_E_NO_GRAPH_SECTION, "start the file with [graph] and 'output = RESOURCE'", "the graph has no [graph] section, so no output");
    for (int si = 0; si < ast->section_count; si++) {
        const char *arg;
        sec_kind kind = section_kind(ast->sections[si].name, &arg);
        if (kind != SEC_PASS && kind != SEC_SCENE)
            continue;
        const char *pname = kind == SEC_SCENE ? "scene" : arg;
        int pi = find_pass(g, pname);
        if (pi >= 0 && g->passes[pi].line == ast->sections[si].line)
            pass_section(g, ast, si, &g->passes[pi]);
    }
    apply_overrides(g, desc);
    for (int i = 0; i < g->pass_count; i++) {
        vrg_pass *p = &g->passes[i];
        if (p->plugin && p->plugin->desc->param_choices && _vrg_pass_check_choices(p) != 0)
            continue; /* its check() would read a value it does not take */
        if (!p->plugin || !p->plugin->desc->check)
            continue;
        _vrg_running before = _vrg_running_enter("check", p->name, p->plugin);
        int rc = p->plugin->desc->check(p);
        _vrg_running_leave(before);
        if (rc != 0 && !p->failed)
            _vrg_pass_fail(p, VRG_E_CALLBACK_FAILED, "its check() failed");
    }
    default_outputs(g);
    for (int si = 0; si < ast->section_count; si++) {
        const char *arg;
        if (section_kind(ast->sections[si].name, &arg) == SEC_RESOURCE)
            resource_section(g, ast, si, arg);
    }
    resolve_resources(g, ast);
    check_prev_of_persistent(g);
    check_conflicting_uses(g);
    if (graph_si >= 0) {
        if (!g->output_name[0]) {
            if (!g->output_line) /* else given, but not usable: already reported */
                _vrg_error_at(&g->diag, ast->sections[graph_si].line, VRG_E_NO_OUTPUT, "add 'output = RESOURCE' to [graph]", "the graph has no output");
        } else {
            g->output = _vrg_graph_find_resource(g, g->output_name);
            if ((g->output >= 0 && g->res[g->output].writer_unknown) || write_refused(g, ast, g->output_name))
                ; /* its writer, its writer's plugin or the binding was refused: already reported */
            else if (g->output < 0 || g->res[g->output].writer < 0)
                _vrg_error_at(&g->diag, g->output_line, VRG_E_OUTPUT_NEVER_WRITTEN, "name a resource some pass writes", "output resource '%s' is never written",
                             g->output_name);
            else if (g->res[g->output].kind != VRG_IMAGE)
                _vrg_error_at(&g->diag, g->output_line, VRG_E_OUTPUT_NOT_IMAGE, "the output is shown and written as PNG", "output resource '%s' is a buffer, not an image",
                             g->output_name);
            else
                g->res[g->output].is_output = 1;
        }
        if (!g->width || !g->height)
            if (!desc->width && !g->diag.errors)
                _vrg_error_at(&g->diag, ast->sections[graph_si].line, VRG_E_NO_SIZE, "add 'width = ' and 'height = ' to [graph] (or load it with a size)",
                             "the graph has no size");
    }
    if (desc->width && desc->height)
        g->width = desc->width, g->height = desc->height;
    for (uint32_t i = 0; i < desc->readback_count; i++) {
        int r = _vrg_graph_find_resource(g, desc->readback[i]);
        if (r < 0 || g->res[r].writer < 0)
            _vrg_error(&g->diag, VRG_E_UNKNOWN_RESOURCE, "readback '%s': the graph writes no resource of that name", desc->readback[i]);
        else
            g->res[r].readback = 1;
    }
    unread_optional_outputs(g);
    check_cycles(g);
    return g->diag.errors ? -1 : 0;
}
