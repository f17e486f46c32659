/* voxrg run's block editing (edit.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "edit.h"
#include "voxrg/edits.h"
#include "voxrg/voxrg.h"

/* The camera sees no farther: a pick beyond would select what is not drawn. */
static float reach(const vrg_camera *c)
{
    float near = c->near_plane > 0 ? c->near_plane : 0.05f;
    return c->far_plane > near ? c->far_plane : c->far_plane > 0 ? near * 2 : 1000.0f;
}

int vrg_cli_edit_pick(const vrg_graph *g, double fx, double fy, int fb_w, int fb_h, vrg_world_hit *hit)
{
    const vrg_world *w = vrg_graph_world(g);
    uint32_t rw, rh;
    vrg_graph_size(g, &rw, &rh);
    if (!w || fb_w <= 0 || fb_h <= 0 || fx < 0 || fy < 0 || fx >= fb_w || fy >= fb_h)
        return 0;
    /* display.comp's mapping: window pixel centres onto render pixel centres */
    float px = (float)((fx + 0.5) * rw / fb_w - 0.5), py = (float)((fy + 0.5) * rh / fb_h - 0.5);
    const vrg_camera *cam = vrg_graph_camera(g);
    float dir[3];
    vrg_camera_ray(cam, rw, rh, px, py, dir);
    return vrg_world_pick(w, cam->position, dir, reach(cam), hit);
}

static const char *type_name(const vrg_world *w, vrg_block b)
{
    const char *name = (int)b < vrg_world_material_count(w) ? vrg_world_materials(w)[b].name : NULL;
    return name ? name : "?";
}

/* Without a journal (a graph from text, or edits = none) the world changes
 * in memory only: nothing to undo, nothing kept. */
static void set_in_memory(vrg_cli_edit *e, vrg_world *w, const int at[3], vrg_block b, vrg_block shown)
{
    if (vrg_world_set_block(w, at[0], at[1], at[2], b) != 0)
        snprintf(e->status, sizeof e->status, "%d %d %d is not in a loaded chunk: nothing changed", at[0], at[1], at[2]);
    else
        snprintf(e->status, sizeof e->status, "%s %s at %d %d %d (no journal: in memory only, no undo)", b ? "placed" : "removed",
                 type_name(w, shown), at[0], at[1], at[2]);
}

static void set_block(vrg_cli_edit *e, vrg_graph *g, const int at[3], vrg_block b, vrg_block shown)
{
    vrg_world *w = vrg_graph_world(g);
    vrg_edits *journal = vrg_graph_edits(g);
    char err[VRG_CLI_PATH + 256] = "";
    if (!journal)
        set_in_memory(e, w, at, b, shown);
    else if (vrg_edits_set(journal, w, at[0], at[1], at[2], b, err, sizeof err) != 0)
        snprintf(e->status, sizeof e->status, "edit failed: %s", err);
    else /* a notice (the journal written again) is news the user needs */
        snprintf(e->status, sizeof e->status, "%s %s at %d %d %d%s%s", b ? "placed" : "removed", type_name(w, shown), at[0], at[1], at[2],
                 err[0] ? "; " : "", err);
}

static void undo_redo(vrg_cli_edit *e, vrg_graph *g, int redo)
{
    vrg_edits *journal = vrg_graph_edits(g);
    char err[VRG_CLI_PATH + 256] = "";
    if (!journal) {
        snprintf(e->status, sizeof e->status, "no journal (a graph from text, or edits = none): nothing to %s", redo ? "redo" : "undo");
        return;
    }
    int r = redo ? vrg_edits_redo(journal, vrg_graph_world(g), err, sizeof err) : vrg_edits_undo(journal, vrg_graph_world(g), err, sizeof err);
    if (r < 0)
        snprintf(e->status, sizeof e->status, "%s failed: %s", redo ? "redo" : "undo", err);
    else if (r)
        snprintf(e->status, sizeof e->status, "nothing to %s", redo ? "redo" : "undo");
    else
        snprintf(e->status, sizeof e->status, "%s done%s%s", redo ? "redo" : "undo", err[0] ? "; " : "", err);
}

void vrg_cli_edit_apply(vrg_cli_edit *e, vrg_graph *g, vrg_cli_edit_action action, const vrg_world_hit *hit)
{
    if (!vrg_graph_world(g))
        snprintf(e->status, sizeof e->status, "the graph has no voxel world to edit");
    else if (action == VRG_CLI_EDIT_UNDO || action == VRG_CLI_EDIT_REDO)
        undo_redo(e, g, action == VRG_CLI_EDIT_REDO);
    else if (!hit)
        snprintf(e->status, sizeof e->status, "no block under the cursor");
    else if (action == VRG_CLI_EDIT_REMOVE)
        set_block(e, g, hit->block, VRG_BLOCK_AIR, hit->id);
    else if (!hit->normal[0] && !hit->normal[1] && !hit->normal[2])
        snprintf(e->status, sizeof e->status, "the camera is inside a block: no face to place against");
    else {
        int at[3] = {hit->block[0] + hit->normal[0], hit->block[1] + hit->normal[1], hit->block[2] + hit->normal[2]};
        set_block(e, g, at, e->type, e->type);
    }
    fprintf(stderr, "edit: %s\n", e->status);
}

void vrg_cli_edit_cycle(vrg_cli_edit *e, const vrg_graph *g, int dir)
{
    const vrg_world *w = vrg_graph_world(g);
    int solid = w ? vrg_world_material_count(w) - 1 : 0; /* ids 1..solid; 0 is air */
    if (solid < 1)
        return;
    int t = e->type >= 1 && e->type <= solid ? e->type : 1;
    e->type = (vrg_block)((t - 1 + dir + solid) % solid + 1);
    snprintf(e->status, sizeof e->status, "type: %s", type_name(w, e->type));
}

/* Clip-space point of world position p. */
static void to_clip(const float m[16], const float p[3], double out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* One edge: the part in front of the camera, to window pixels. */
static void edge(vrg_overlay_layer *l, const double a_in[4], const double b_in[4], const uint8_t rgba[4])
{
    const double near_w = 1e-3;
    double a[4], b[4];
    memcpy(a, a_in, sizeof a), memcpy(b, b_in, sizeof b);
    if (a[3] < near_w && b[3] < near_w)
        return;
    if (a[3] < near_w || b[3] < near_w) { /* cut at the near side: a projection through w = 0 flips */
        double *behind = a[3] < near_w ? a : b, *front = a[3] < near_w ? b : a;
        double t = (front[3] - near_w) / (front[3] - behind[3]);
        for (int i = 0; i < 4; i++)
            behind[i] = front[i] + t * (behind[i] - front[i]);
    }
    /* NDC y points down, as the window's rows */
    double x0 = (a[0] / a[3] * 0.5 + 0.5) * l->width, y0 = (a[1] / a[3] * 0.5 + 0.5) * l->height;
    double x1 = (b[0] / b[3] * 0.5 + 0.5) * l->width, y1 = (b[1] / b[3] * 0.5 + 0.5) * l->height;
    vrg_overlay_segment(l, x0, y0, x1, y1, 2, rgba);
}

void vrg_cli_edit_outline(const vrg_graph *g, const vrg_world_hit *hit, vrg_overlay_layer *l)
{
    static const uint8_t colour[4] = {255, 230, 60, 255};
    uint32_t rw, rh;
    vrg_graph_size(g, &rw, &rh);
    float m[16];
    vrg_camera_view_projection(vrg_graph_camera(g), (float)rw / (float)(rh ? rh : 1), m);
    double corner[8][4];
    for (int i = 0; i < 8; i++) {
        float p[3] = {(float)(hit->block[0] + (i & 1)), (float)(hit->block[1] + (i >> 1 & 1)), (float)(hit->block[2] + (i >> 2 & 1))};
        to_clip(m, p, corner[i]);
    }
    /* corners differing in one bit share an edge */
    for (int i = 0; i < 8; i++)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit))
                edge(l, corner[i], corner[i | bit], colour);
}

void vrg_cli_edit_describe(const vrg_cli_edit *e, const vrg_graph *g, const vrg_world_hit *hover, char *line, size_t size)
{
    const vrg_world *w = vrg_graph_world(g);
    int n = snprintf(line, size, "place: %s (e q)", type_name(w, e->type));
    if (hover && n > 0 && (size_t)n < size)
        n += snprintf(line + n, size - (size_t)n, "  cursor: %s %d %d %d", type_name(w, hover->id), hover->block[0], hover->block[1],
                      hover->block[2]);
    if (e->status[0] && n > 0 && (size_t)n < size)
        snprintf(line + n, size - (size_t)n, "  %s", e->status);
}
