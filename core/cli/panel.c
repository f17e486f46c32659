/* voxrg run's parameter panel (panel.h). Its own small widget on the
 * overlay's text renderer: Debian packages no C immediate-mode UI (Nuklear
 * is not packaged; libimgui-dev is C++ and would bring its own Vulkan
 * renderer), and a list of numbers with a highlighted row needs no more. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "panel.h"
#include "util.h"
#include "voxrg/graph_edit.h"
#include "voxrg/output.h"

typedef struct row {
    uint32_t pass;
    const vrg_param_desc *pd;
} row;

static void key_of(vrg_graph *g, uint32_t pass, const vrg_param_desc *pd, char *key, size_t cap)
{
    snprintf(key, cap, "%s.%s", vrg_graph_pass_name(g, pass), pd->name);
}

/* Whether key holds the filter, any case. */
static int passes_filter(const char *key, const char *filter)
{
    size_t n = strlen(filter);
    for (const char *k = key; *k; k++)
        if (strncasecmp(k, filter, n) == 0)
            return 1;
    return n == 0;
}

/* The graph's parameters that pass the filter, in pass order; *more when
 * they did not all fit. */
static int list_rows(const vrg_panel *p, vrg_graph *g, row *rows, int *more)
{
    int n = 0;
    *more = 0;
    for (uint32_t i = 0; i < vrg_graph_pass_count(g); i++) {
        const vrg_plugin_desc *d = vrg_graph_pass_plugin(g, i);
        for (uint32_t j = 0; d && j < d->param_count; j++) {
            char key[160];
            key_of(g, i, &d->params[j], key, sizeof key);
            if (!passes_filter(key, p->filter))
                continue;
            if (n == VRG_PANEL_ROWS) {
                *more = 1;
                return n;
            }
            rows[n++] = (row){i, &d->params[j]};
        }
    }
    return n;
}

static int needs_reload(const vrg_param_desc *pd) { return pd->type == VRG_PARAM_STRING || (pd->flags & VRG_PARAM_RELOAD); }

static vrg_panel_change *change_of(vrg_panel *p, const char *key)
{
    for (int i = 0; i < p->change_count[p->side]; i++)
        if (strcmp(p->changes[p->side][i].key, key) == 0)
            return &p->changes[p->side][i];
    return NULL;
}

/* The value in effect: the graph's (the file's, a --set's or the default). */
static double value_in_effect(vrg_graph *g, const char *key)
{
    double v = 0;
    (void)vrg_graph_get_param(g, key, &v);
    return v;
}

/* The value shown: an unsaved reload-only change, else the one in effect. */
static double value_of(vrg_panel *p, vrg_graph *g, const row *r)
{
    char key[160];
    key_of(g, r->pass, r->pd, key, sizeof key);
    const vrg_panel_change *c = change_of(p, key);
    return c ? c->value : value_in_effect(g, key);
}

/* What the file will hold: floats to 6 significant digits, so that the value
 * applied live is the one the saved file parses to. */
static double as_saved(const vrg_param_desc *pd, double v)
{
    char text[64];
    snprintf(text, sizeof text, pd->type == VRG_PARAM_FLOAT ? "%.6g" : "%.0f", v);
    return strtod(text, NULL);
}

static void drop_change(vrg_panel *p, vrg_panel_change *c)
{
    vrg_panel_change *end = &p->changes[p->side][--p->change_count[p->side]];
    memmove(c, c + 1, (size_t)(end - c) * sizeof *c);
}

static void apply(vrg_panel *p, vrg_graph *g, const row *r, double v)
{
    const vrg_param_desc *pd = r->pd;
    if (pd->min != 0 || pd->max != 0)
        v = v < pd->min ? pd->min : v > pd->max ? pd->max : v;
    v = as_saved(pd, v);
    char key[160];
    key_of(g, r->pass, pd, key, sizeof key);
    vrg_panel_change *c = change_of(p, key);
    if (!c && p->change_count[p->side] == VRG_PANEL_CHANGES) {
        snprintf(p->status, sizeof p->status, "%d unsaved changes: save (ctrl+s) before more", VRG_PANEL_CHANGES);
        return;
    }
    double original = c ? c->original : as_saved(pd, value_in_effect(g, key));
    if (!needs_reload(pd) && vrg_graph_set_param(g, key, v) != 0) {
        snprintf(p->status, sizeof p->status, "%s = %g refused (see the terminal)", key, v);
        return;
    }
    if (v == original) { /* set back: nothing to save */
        if (c)
            drop_change(p, c);
        snprintf(p->status, sizeof p->status, "%s = %g (as before: not saved)", key, v);
        return;
    }
    if (!c) {
        c = &p->changes[p->side][p->change_count[p->side]++];
        snprintf(c->key, sizeof c->key, "%s", key);
        c->original = original;
    }
    c->value = v;
    c->reload = needs_reload(pd);
    snprintf(p->status, sizeof p->status, "%s = %g%s", key, v, c->reload ? " (applies on save: reload)" : "");
}

/* The largest of 1, 2 or 5 times a power of ten not above s: steps that add up readably. */
static double round_step(double s)
{
    double unit = pow(10, floor(log10(s)));
    return s >= 5 * unit ? 5 * unit : s >= 2 * unit ? 2 * unit : unit;
}

double vrg_panel_step_size(const vrg_param_desc *pd, int fine)
{
    double range = pd->max - pd->min, scale = fabs(pd->default_value);
    int bounded = pd->min != 0 || pd->max != 0;
    double s = bounded && range > 0 && !(scale > 0 && range > 100 * scale) ? range / 20 : scale > 0 ? scale / 5 : 0.1;
    s = round_step(s) * (fine ? 0.1 : 1);
    return pd->type == VRG_PARAM_FLOAT ? s : s < 1 ? 1 : round(s);
}

void vrg_panel_select(vrg_panel *p, vrg_graph *g, int delta)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(p, g, rows, &more);
    if (n)
        p->selected = ((p->selected + delta) % n + n) % n;
}

void vrg_panel_jump(vrg_panel *p, vrg_graph *g, int dir)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(p, g, rows, &more);
    if (!n)
        return;
    int i = p->selected < n ? p->selected : 0;
    uint32_t pass = rows[i].pass;
    if (dir > 0) { /* past this pass's rows, wrapping to the first pass */
        while (i < n && rows[i].pass == pass)
            i++;
        i = i == n ? 0 : i;
    } else { /* this pass's first row, then the previous pass's (the last pass's before the first) */
        while (i > 0 && rows[i - 1].pass == rows[i].pass)
            i--;
        i = i == 0 ? n - 1 : i - 1;
        while (i > 0 && rows[i - 1].pass == rows[i].pass)
            i--;
    }
    p->selected = i;
    snprintf(p->status, sizeof p->status, "%s", vrg_graph_pass_name(g, rows[i].pass));
}

void vrg_panel_step(vrg_panel *p, vrg_graph *g, int dir, int fine)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(p, g, rows, &more);
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
        v += dir * vrg_panel_step_size(r->pd, fine);
    apply(p, g, r, v);
}

void vrg_panel_filter_begin(vrg_panel *p)
{
    p->typing = VRG_PANEL_TYPING_FILTER;
    p->filter[0] = '\0';
    p->selected = 0;
}

void vrg_panel_save_as_begin(vrg_panel *p, const char *name)
{
    p->typing = VRG_PANEL_TYPING_SAVE_AS;
    snprintf(p->save_name, sizeof p->save_name, "%s", name);
}

static char *typed_text(vrg_panel *p, size_t *cap)
{
    *cap = p->typing == VRG_PANEL_TYPING_FILTER ? sizeof p->filter : sizeof p->save_name;
    return p->typing == VRG_PANEL_TYPING_FILTER ? p->filter : p->typing == VRG_PANEL_TYPING_SAVE_AS ? p->save_name : NULL;
}

void vrg_panel_type(vrg_panel *p, unsigned codepoint)
{
    size_t cap;
    char *text = typed_text(p, &cap);
    size_t n = text ? strlen(text) : 0;
    if (!text || codepoint < 32 || codepoint > 126 || n + 1 >= cap)
        return;
    text[n] = (char)codepoint, text[n + 1] = '\0';
    p->selected = p->typing == VRG_PANEL_TYPING_FILTER ? 0 : p->selected;
}

void vrg_panel_backspace(vrg_panel *p)
{
    size_t cap;
    char *text = typed_text(p, &cap);
    if (text && text[0])
        text[strlen(text) - 1] = '\0';
}

int vrg_panel_type_end(vrg_panel *p, int accept)
{
    int save = accept && p->typing == VRG_PANEL_TYPING_SAVE_AS;
    if (!accept && p->typing == VRG_PANEL_TYPING_FILTER)
        p->filter[0] = '\0';
    if (!accept && p->typing == VRG_PANEL_TYPING_SAVE_AS)
        snprintf(p->status, sizeof p->status, "save as: cancelled");
    p->typing = VRG_PANEL_TYPING_NONE;
    return save;
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
        if (p->selected < list_rows(p, g, rows, &more) && rows[p->selected].pd->type != VRG_PARAM_STRING) {
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
    int more, n = list_rows(p, g, rows, &more);
    if (!p->dragging || p->selected >= n || x == p->drag_x)
        return;
    const row *r = &rows[p->selected];
    /* a step per 10 pixels (booleans: dragged right on, left off) */
    double v = r->pd->type == VRG_PARAM_BOOL ? (x > p->drag_x ? 1 : 0) : p->drag_value + round((x - p->drag_x) / 10) * vrg_panel_step_size(r->pd, fine);
    if (v != value_of(p, g, r))
        apply(p, g, r, v);
}

/* "a|b|c: edit the file" into out: the names a choice takes, cut after the
 * last whole name that fits the panel's line and marked "..." when they
 * do not all fit. */
static void choices_text(const char *choices, char *out, size_t cap)
{
    static const char tail[] = ": edit the file", cut[] = "...";
    size_t len = strlen(choices), keep = len;
    if (cap < sizeof tail + sizeof cut) {
        snprintf(out, cap, "%s", cap > sizeof cut ? cut : "");
        return;
    }
    if (len + sizeof tail > cap) { /* up to and with the last '|' that leaves room for the mark */
        keep = cap - sizeof tail - (sizeof cut - 1);
        while (keep > 0 && choices[keep - 1] != ',')
            keep--;
    }
    for (size_t i = 0; i < keep; i++)
        out[i] = choices[i] == ',' ? '|' : choices[i];
    snprintf(out + keep, cap - keep, "%s%s", keep < len ? cut : "", tail);
}

static void row_text(vrg_panel *p, vrg_graph *g, const row *r, char *line, size_t cap)
{
    char key[160], value[32], range[48] = "";
    key_of(g, r->pass, r->pd, key, sizeof key);
    const vrg_panel_change *c = change_of(p, key);
    const vrg_param_desc *pd = r->pd;
    if (pd->type == VRG_PARAM_STRING)
        snprintf(value, sizeof value, "(text)");
    else
        snprintf(value, sizeof value, pd->type == VRG_PARAM_FLOAT ? "%.6g" : "%.0f", value_of(p, g, r));
    if (pd->type != VRG_PARAM_STRING && pd->type != VRG_PARAM_BOOL && (pd->min != 0 || pd->max != 0))
        snprintf(range, sizeof range, "[%g..%g]", pd->min, pd->max);
    /* the range, or what to do instead, after the value: no padding after it, the panel is as wide as its longest line */
    int n = snprintf(line, cap, " %c %-16s %10s ", c ? '*' : ' ', pd->name, value);
    size_t o = n < 0 ? 0 : (size_t)n < cap ? (size_t)n : cap - 1;
    if (pd->type != VRG_PARAM_STRING) {
        snprintf(line + o, cap - o, "%s%s", range, needs_reload(pd) ? " reload" : "");
        return;
    }
    /* a string with choices: the names it takes (the file holds which) */
    const vrg_plugin_desc *d = vrg_graph_pass_plugin(g, r->pass);
    const char *choices = d && d->param_choices ? d->param_choices[r->pd - d->params] : NULL;
    if (choices)
        choices_text(choices, line + o, cap - o);
    else
        snprintf(line + o, cap - o, "edit the file");
}

void vrg_panel_draw(vrg_panel *p, vrg_graph *g, const char *file, vrg_overlay_layer *l)
{
    static row rows[VRG_PANEL_ROWS];
    int more, n = list_rows(p, g, rows, &more);
    if (p->selected >= n)
        p->selected = n ? n - 1 : 0;
    vrg_overlay ov;
    char line[160];
    vrg_overlay_clear(&ov);
    snprintf(line, sizeof line, "%s: %.90s%s", p->side ? "B" : "A", file, p->change_count[p->side] ? "  (unsaved: ctrl+s)" : "");
    vrg_overlay_line(&ov, line);
    p->line_row[0] = -1;
    if (p->filter[0] || p->typing == VRG_PANEL_TYPING_FILTER) { /* the filter's line, with the cursor while typing */
        snprintf(line, sizeof line, "/%s%s  %d match%s%s", p->filter, p->typing == VRG_PANEL_TYPING_FILTER ? "_" : "", n, n == 1 ? "" : "es",
                 p->typing == VRG_PANEL_TYPING_FILTER ? " (enter: keep, esc: clear)" : "");
        p->line_row[ov.lines] = -1;
        vrg_overlay_line(&ov, line);
    }
    /* the rows that fit, scrolled to keep the selected one in view (5 lines
     * go to the title, filter, help, status and a "more" note) */
    int fit = ((int)l->height - 8 - 2 * VRG_OVERLAY_PAD) / VRG_OVERLAY_LINE_H - 5;
    fit = fit > VRG_OVERLAY_LINES - 4 ? VRG_OVERLAY_LINES - 4 : fit;
    /* a third of the rows above the selected one: with a title each, it still fits */
    int first = p->selected - fit / 3 > 0 ? p->selected - fit / 3 : 0;
    int highlight = -1;
    int top = ov.lines;
    for (int i = 0, shown_pass = -1; i < n && ov.lines < fit + top; i++) {
        if (i < first)
            continue;
        if ((int)rows[i].pass != shown_pass) { /* the pass's title */
            shown_pass = (int)rows[i].pass;
            snprintf(line, sizeof line, "%s (%s)", vrg_graph_pass_name(g, rows[i].pass), vrg_graph_pass_plugin(g, rows[i].pass)->name);
            p->line_row[ov.lines] = -1;
            vrg_overlay_line(&ov, line);
            if (ov.lines >= fit + top)
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
    if (p->typing == VRG_PANEL_TYPING_SAVE_AS)
        snprintf(line, sizeof line, "save as: %.100s_ (enter: write, esc: cancel)", p->save_name);
    else
        snprintf(line, sizeof line, "%s", p->status[0] ? p->status : "up/down pgup/pgdn /: find. left/right: change (shift: fine)");
    vrg_overlay_line(&ov, line);
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

/* The side's changes as graph edits (sections and values in the arrays
 * given): their count, or -1 after a message (a reload took a pass away). */
static int collect_edits(vrg_panel *p, vrg_graph *g, const char *file, vrg_graph_edit *edits, char (*sections)[96], char (*values)[48])
{
    int n = p->change_count[p->side];
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
    return n;
}

/* Whether the graph file may be replaced by the save: -1 after the message
 * when it has no write permission (the rename would replace it all the
 * same); a file with other hard links is said to be split from them. */
static int check_in_place(vrg_panel *p, const char *file)
{
    struct stat st;
    if (stat(file, &st) != 0) {
        fprintf(stderr, "error: save %s: %s\n", file, strerror(errno));
        snprintf(p->status, sizeof p->status, "save failed: %.60s: %.60s", file, strerror(errno));
        return -1;
    }
    /* the mode bits as well as access(): root may write to a 0444 file, but its owner meant it to stay */
    if (access(file, W_OK) != 0 || !(st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH))) {
        fprintf(stderr, "error: save %s: the file is read-only (mode %04o): not replaced; save a copy with ctrl+shift+s\n", file,
                (unsigned)(st.st_mode & 07777));
        snprintf(p->status, sizeof p->status, "save refused: read-only file (ctrl+shift+s: save as)");
        return -1;
    }
    if (st.st_nlink > 1)
        fprintf(stderr, "warning: save %s: the file has %lu other hard link%s: it is replaced under this name only, the other names keep the old text\n",
                file, (unsigned long)st.st_nlink - 1, st.st_nlink == 2 ? "" : "s");
    return 0;
}

int vrg_panel_save(vrg_panel *p, vrg_graph *g, const char *file)
{
    vrg_graph_edit edits[VRG_PANEL_CHANGES];
    char sections[VRG_PANEL_CHANGES][96], values[VRG_PANEL_CHANGES][48];
    int n = collect_edits(p, g, file, edits, sections, values);
    if (n == 0) {
        snprintf(p->status, sizeof p->status, "nothing changed to save");
        return 0;
    }
    if (n < 0 || check_in_place(p, file) != 0)
        return -1;
    if (vrg_graph_edit_file(file, edits, n, stderr) != 0) {
        snprintf(p->status, sizeof p->status, "save failed (see the terminal)");
        return -1;
    }
    fprintf(stderr, "saved %d value%s to %s\n", n, n == 1 ? "" : "s", file);
    snprintf(p->status, sizeof p->status, "saved %d value%s: reloading", n, n == 1 ? "" : "s");
    p->change_count[p->side] = 0;
    return 0;
}

int vrg_panel_save_as(vrg_panel *p, vrg_graph *g, const char *file, const char *to)
{
    vrg_graph_edit edits[VRG_PANEL_CHANGES];
    char sections[VRG_PANEL_CHANGES][96], values[VRG_PANEL_CHANGES][48];
    int n = collect_edits(p, g, file, edits, sections, values);
    if (n < 0)
        return -1;
    int exists = to[0] && access(to, F_OK) == 0;
    if (!to[0] || exists) { /* a save-as makes a new file: one that exists may be anyone's */
        fprintf(stderr, "error: save as '%s': %s: not written (type another name)\n", to, exists ? "the file exists" : "no name given");
        snprintf(p->status, sizeof p->status, "save as refused: %.80s", exists ? "the file exists" : "no name given");
        return -1;
    }
    char *text = vrg_cli_read_text(file);
    char *edited = text ? vrg_graph_edit_text(file, text, edits, n, stderr) : NULL;
    int rc = edited && vrg_output_write(to, edited, strlen(edited)) == 0 ? 0 : -1;
    if (!text)
        fprintf(stderr, "error: save as: cannot read %s: %s\n", file, strerror(errno));
    free(text);
    free(edited);
    if (rc != 0) {
        snprintf(p->status, sizeof p->status, "save as failed (see the terminal)");
        return -1;
    }
    fprintf(stderr, "saved %d value%s to %s (a copy of %s, which stays as it is)\n", n, n == 1 ? "" : "s", to, file);
    snprintf(p->status, sizeof p->status, "wrote %.100s (%d value%s)", to, n, n == 1 ? "" : "s");
    return 0;
}

void vrg_panel_save_as_name(const char *file, char *name, size_t cap)
{
    size_t n = strlen(file);
    size_t stem = n > 4 && strcmp(file + n - 4, ".ini") == 0 ? n - 4 : n;
    snprintf(name, cap, "%.*s-edited.ini", (int)stem, file);
}
