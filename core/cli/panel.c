/* voxrg run's parameter panel (panel.h). Its own small widget on the
 * overlay's text renderer: Debian packages no C immediate-mode UI (Nuklear
 * is not packaged; libimgui-dev is C++ and would bring its own Vulkan
 * renderer), and a list of numbers with a highlighted row needs no more. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "panel.h"
#include "voxrg/graph_edit.h"

typedef struct row {
    uint32_t pass;
    const vrg_param_desc *pd;
} row;

/* The graph's parameters in pass order; *more when they did not all fit. */
static int list_rows(vrg_graph *g, row *rows, int *more)
{
    int n = 0;
    *more = 0;
    for (uint32_t i = 0; i < vrg_graph_pass_count(g); i++) {
        const vrg_plugin_desc *d = vrg_graph_pass_plugin(g, i);
        for (uint32_t j = 0; d && j < d->param_count; j++) {
            if (n == VRG_PANEL_ROWS) {
                *more = 1;
                return n;
            }
            rows[n++] = (row){i, &d->params[j]};
        }
    }
    return n;
}

static void key_of(vrg_graph *g, const row *r, char *key, size_t cap) { snprintf(key, cap, "%s.%s", vrg_graph_pass_name(g, r->pass), r->pd->name); }

static int needs_reload(const vrg_param_desc *pd) { return pd->type == VRG_PARAM_STRING || (pd->flags & VRG_PARAM_RELOAD); }

static vrg_panel_change *change_of(vrg_panel *p, const char *key)
{
    for (int i = 0; i < p->change_count[p->side]; i++)
        if (strcmp(p->changes[p->side][i].key, key) == 0)
            return &p->changes[p->side][i];
    return NULL;
}

/* The value shown: an unsaved reload-only change, else the one in effect. */
static double value_of(vrg_panel *p, vrg_graph *g, const row *r)
{
    char key[160];
    key_of(g, r, key, sizeof key);
    const vrg_panel_change *c = change_of(p, key);
    double v = 0;
    if (c)
        return c->value;
    (void)vrg_graph_get_param(g, key, &v);
    return v;
}

/* What the file will hold: floats to 6 significant digits, so that the value
 * applied live is the one the saved file parses to. */
static double as_saved(const vrg_param_desc *pd, double v)
{
    char text[64];
    snprintf(text, sizeof text, pd->type == VRG_PARAM_FLOAT ? "%.6g" : "%.0f", v);
    return strtod(text, NULL);
}

static void apply(vrg_panel *p, vrg_graph *g, const row *r, double v)
{
    const vrg_param_desc *pd = r->pd;
    if (pd->min != 0 || pd->max != 0)
        v = v < pd->min ? pd->min : v > pd->max ? pd->max : v;
    v = as_saved(pd, v);
    char key[160];
    key_of(g, r, key, sizeof key);
    vrg_panel_change *c = change_of(p, key);
    if (!c && p->change_count[p->side] == VRG_PANEL_CHANGES) {
        snprintf(p->status, sizeof p->status, "%d unsaved changes: save (ctrl+s) before more", VRG_PANEL_CHANGES);
        return;
    }
    if (!needs_reload(pd) && vrg_graph_set_param(g, key, v) != 0) {
        snprintf(p->status, sizeof p->status, "%s = %g refused (see the terminal)", key, v);
        return;
    }
    if (!c) {
        c = &p->changes[p->side][p->change_count[p->side]++];
        snprintf(c->key, sizeof c->key, "%s", key);
    }
    c->value = v;
    c->reload = needs_reload(pd);
    snprintf(p->status, sizeof p->status, "%s = %g%s", key, v, c->reload ? " (applies on save: reload)" : "");
}

/* A float's step: a tenth of its size, or of its range near zero. */
static double step_of(const vrg_param_desc *pd, double v)
{
    if (pd->type != VRG_PARAM_FLOAT)
        return 1;
    double range = pd->max - pd->min;
    double s = fabs(v) > 0 ? fabs(v) * 0.1 : range > 0 ? range * 0.01 : 0.1;
    return pow(10, floor(log10(s))); /* round steps: 0.1 + 0.1 stays readable */
}

void vrg_panel_select(vrg_panel *p, vrg_graph *g, int delta)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(g, rows, &more);
    if (n)
        p->selected = ((p->selected + delta) % n + n) % n;
}

void vrg_panel_step(vrg_panel *p, vrg_graph *g, int dir, int fine)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(g, rows, &more);
    if (p->selected >= n)
        return;
    const row *r = &rows[p->selected];
    if (r->pd->type == VRG_PARAM_STRING) {
        snprintf(p->status, sizeof p->status, "%s is text: edit the graph file (it reloads)", r->pd->name);
        return;
    }
    double v = value_of(p, g, r);
    if (r->pd->type == VRG_PARAM_BOOL)
        v = v != 0 ? 0 : 1;
    else
        v += dir * step_of(r->pd, v) * (fine && r->pd->type == VRG_PARAM_FLOAT ? 0.1 : 1);
    apply(p, g, r, v);
}

int vrg_panel_contains(const vrg_panel *p, double x, double y)
{
    return p->open && x >= p->x && x < p->x + p->w && y >= p->y && y < p->y + p->lines * VRG_OVERLAY_LINE_H + 2 * VRG_OVERLAY_PAD;
}

int vrg_panel_press(vrg_panel *p, vrg_graph *g, double x, double y)
{
    if (!vrg_panel_contains(p, x, y))
        return 0;
    int line = (int)((y - p->y - VRG_OVERLAY_PAD) / VRG_OVERLAY_LINE_H);
    if (line >= 0 && line < p->lines && p->line_row[line] >= 0) {
        static row rows[VRG_PANEL_ROWS];
        int more;
        p->selected = p->line_row[line];
        if (p->selected < list_rows(g, rows, &more) && rows[p->selected].pd->type != VRG_PARAM_STRING) {
            p->dragging = 1;
            p->drag_x = x;
            p->drag_value = value_of(p, g, &rows[p->selected]);
        }
    }
    return 1;
}

void vrg_panel_drag(vrg_panel *p, vrg_graph *g, double x, int fine)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(g, rows, &more);
    if (!p->dragging || p->selected >= n || x == p->drag_x)
        return;
    const row *r = &rows[p->selected];
    /* a step per 10 pixels (booleans: dragged right on, left off) */
    double v = r->pd->type == VRG_PARAM_BOOL ? (x > p->drag_x ? 1 : 0)
                                             : p->drag_value + round((x - p->drag_x) / 10) * step_of(r->pd, p->drag_value) * (fine ? 0.1 : 1);
    if (v != value_of(p, g, r))
        apply(p, g, r, v);
}

static void row_text(vrg_panel *p, vrg_graph *g, const row *r, char *line, size_t cap)
{
    char key[160], value[32], range[48] = "";
    key_of(g, r, key, sizeof key);
    const vrg_panel_change *c = change_of(p, key);
    const vrg_param_desc *pd = r->pd;
    if (pd->type == VRG_PARAM_STRING)
        snprintf(value, sizeof value, "(text)");
    else
        snprintf(value, sizeof value, pd->type == VRG_PARAM_FLOAT ? "%.6g" : "%.0f", value_of(p, g, r));
    if (pd->type != VRG_PARAM_STRING && pd->type != VRG_PARAM_BOOL && (pd->min != 0 || pd->max != 0))
        snprintf(range, sizeof range, "[%g..%g]", pd->min, pd->max);
    snprintf(line, cap, " %c %-16s %10s %-14s%s", c ? '*' : ' ', pd->name, value, range,
             pd->type == VRG_PARAM_STRING ? " edit the file" : needs_reload(pd) ? " reload" : "");
}

void vrg_panel_draw(vrg_panel *p, vrg_graph *g, const char *file, vrg_overlay_layer *l)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(g, rows, &more);
    if (p->selected >= n)
        p->selected = n ? n - 1 : 0;
    vrg_overlay ov;
    char line[160];
    vrg_overlay_clear(&ov);
    snprintf(line, sizeof line, "%s: %s%s", p->side ? "B" : "A", file, p->change_count[p->side] ? "  (unsaved: ctrl+s)" : "");
    vrg_overlay_line(&ov, line);
    p->line_row[0] = -1;
    /* the rows that fit, scrolled to keep the selected one in view (4 lines
     * go to the title, help, status and a "more" note) */
    int fit = ((int)l->height - 8 - 2 * VRG_OVERLAY_PAD) / VRG_OVERLAY_LINE_H - 4;
    fit = fit > VRG_OVERLAY_LINES - 4 ? VRG_OVERLAY_LINES - 4 : fit;
    /* a third of the rows above the selected one: with a title each, it still fits */
    int first = p->selected - fit / 3 > 0 ? p->selected - fit / 3 : 0;
    int highlight = -1;
    for (int i = 0, shown_pass = -1; i < n && ov.lines < fit + 1; i++) {
        if (i < first)
            continue;
        if ((int)rows[i].pass != shown_pass) { /* the pass's title */
            shown_pass = (int)rows[i].pass;
            snprintf(line, sizeof line, "%s (%s)", vrg_graph_pass_name(g, rows[i].pass), vrg_graph_pass_plugin(g, rows[i].pass)->name);
            p->line_row[ov.lines] = -1;
            vrg_overlay_line(&ov, line);
            if (ov.lines >= fit + 1)
                break;
        }
        row_text(p, g, &rows[i], line, sizeof line);
        if (i == p->selected)
            highlight = ov.lines;
        p->line_row[ov.lines] = i;
        vrg_overlay_line(&ov, line);
    }
    if (more) {
        p->line_row[ov.lines] = -1;
        vrg_overlay_line(&ov, "(more parameters than the panel lists)");
    }
    if (p->selected < n) {
        snprintf(line, sizeof line, "%.150s", rows[p->selected].pd->help ? rows[p->selected].pd->help : "");
        p->line_row[ov.lines] = -1;
        vrg_overlay_line(&ov, line);
    }
    p->line_row[ov.lines] = -1;
    vrg_overlay_line(&ov, p->status[0] ? p->status : "up/down, click: select. left/right, drag: change (shift: fine)");
    int longest = 0;
    for (int i = 0; i < ov.lines; i++)
        longest = vrg_overlay_text_width(ov.text[i]) > longest ? vrg_overlay_text_width(ov.text[i]) : longest;
    p->w = longest + 2 * VRG_OVERLAY_PAD;
    p->x = (int)l->width - p->w - 4;
    p->x = p->x < 0 ? 0 : p->x;
    p->y = 4;
    p->lines = ov.lines;
    int w, h;
    vrg_overlay_draw(&ov, l, p->x, p->y, highlight, &w, &h);
}

int vrg_panel_save(vrg_panel *p, vrg_graph *g, const char *file)
{
    int n = p->change_count[p->side];
    if (!n) {
        snprintf(p->status, sizeof p->status, "nothing changed to save");
        return 0;
    }
    vrg_graph_edit edits[VRG_PANEL_CHANGES];
    char sections[VRG_PANEL_CHANGES][96], values[VRG_PANEL_CHANGES][48];
    for (int i = 0; i < n; i++) {
        const vrg_panel_change *c = &p->changes[p->side][i];
        const char *dot = strchr(c->key, '.');
        const vrg_param_desc *pd = NULL;
        const vrg_plugin_desc *d = NULL;
        for (uint32_t k = 0; k < vrg_graph_pass_count(g) && !d; k++)
            if (strlen(vrg_graph_pass_name(g, k)) == (size_t)(dot - c->key) && !strncmp(vrg_graph_pass_name(g, k), c->key, (size_t)(dot - c->key)))
                d = vrg_graph_pass_plugin(g, k);
        for (uint32_t k = 0; d && k < d->param_count && !pd; k++)
            pd = strcmp(d->params[k].name, dot + 1) == 0 ? &d->params[k] : NULL;
        if (!pd) { /* a reload since the change took the pass away */
            fprintf(stderr, "error: save %s: the graph has no parameter %s any more\n", file, c->key);
            snprintf(p->status, sizeof p->status, "save failed: %s is gone (see the terminal)", c->key);
            return -1;
        }
        if (d->kind == VRG_PLUGIN_SCENE)
            snprintf(sections[i], sizeof sections[i], "scene");
        else
            snprintf(sections[i], sizeof sections[i], "pass %.*s", (int)(dot - c->key), c->key);
        snprintf(values[i], sizeof values[i], pd->type == VRG_PARAM_FLOAT ? "%.6g" : "%.0f", c->value);
        edits[i] = (vrg_graph_edit){sections[i], dot + 1, values[i]};
    }
    if (vrg_graph_edit_file(file, edits, n, stderr) != 0) {
        snprintf(p->status, sizeof p->status, "save failed (see the terminal)");
        return -1;
    }
    fprintf(stderr, "saved %d value%s to %s\n", n, n == 1 ? "" : "s", file);
    snprintf(p->status, sizeof p->status, "saved %d value%s: reloading", n, n == 1 ? "" : "s");
    p->change_count[p->side] = 0;
    return 0;
}
