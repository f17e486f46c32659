/* What `voxrg check` shows: schedule, culled passes, resources with their
 * lifetimes and memory placement, the barriers of a steady-state frame, and
 * memory savings. Also the Graphviz view. */
#include <stdlib.h>
#include <string.h>
#include "internal.h"

static const char *layout_name(VkImageLayout l)
{
    switch (l) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST";
    default: return "OTHER";
    }
}

static void flags_name(char *out, size_t cap, uint64_t v, const uint64_t *bits, const char *const *names, int n, const char *none)
{
    out[0] = '\0';
    for (int i = 0; i < n; i++)
        if (v & bits[i]) {
            if (out[0])
                strncat(out, "|", cap - strlen(out) - 1);
            strncat(out, names[i], cap - strlen(out) - 1);
        }
    if (!out[0])
        snprintf(out, cap, "%s", none);
}

static void stage_name(char *out, size_t cap, VkPipelineStageFlags2 s)
{
    static const uint64_t bits[] = {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                    VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR};
    static const char *const names[] = {"COMPUTE", "TRANSFER", "HOST", "AS_BUILD"};
    flags_name(out, cap, s, bits, names, 4, "NONE");
}

static void access_name(char *out, size_t cap, VkAccessFlags2 a)
{
    static const uint64_t bits[] = {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                    VK_ACCESS_2_UNIFORM_READ_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR};
    static const char *const names[] = {"SAMPLED_READ", "STORAGE_READ", "STORAGE_WRITE", "UNIFORM_READ", "TRANSFER_READ", "TRANSFER_WRITE", "AS_READ", "AS_WRITE"};
    flags_name(out, cap, a, bits, names, 8, "0");
}

static void print_barrier(const vrg_graph *g, const _vrg_barrier_rec *b, FILE *f)
{
    const _vrg_resource *r = &g->res[b->res];
    char ss[64], sa[96], ds[64], da[96];
    stage_name(ss, sizeof ss, b->src_stage);
    access_name(sa, sizeof sa, b->src_access);
    stage_name(ds, sizeof ds, b->dst_stage);
    access_name(da, sizeof da, b->dst_access);
    fprintf(f, "      %-22s %s/%s -> %s/%s", r->name, ss, sa, ds, da);
    if (r->kind == VRG_IMAGE)
        fprintf(f, "  %s -> %s", layout_name(b->old_layout), layout_name(b->new_layout));
    if (r->history)
        fprintf(f, "  [copy %d]", b->copy);
    if (b->aliasing)
        fprintf(f, "  (aliased memory)");
    fputc('\n', f);
}

/* Runs the barrier tracker over one frame without recording anything. */
static void simulate_frame(vrg_graph *g, FILE *f)
{
    /* a pass's slots and any number of internal resources; the readback: any resource */
    _vrg_barrier_rec b[VRG_MAX_SLOTS + VRG_MAX_RESOURCES];
    for (int i = 0; i < g->res_count; i++)
        g->res[i].touched[0] = g->res[i].touched[1] = 0;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        int n = _vrg_pass_barriers(g, p, b, VRG_MAX_SLOTS);
        for (int ri = 0; ri < g->res_count; ri++)
            if (g->res[ri].internal_owner == g->schedule[k] && _vrg_resource_barrier(g, ri, 0, g->res[ri].internal_first_access, &b[n]))
                n++;
        if (f) {
            fprintf(f, "  %-12s %d barrier%s\n", p->name, n, n == 1 ? "" : "s");
            for (int i = 0; i < n; i++)
                print_barrier(g, &b[i], f);
        }
    }
    int n = 0;
    for (int i = 0; i < g->res_count; i++)
        if (g->res[i].first_use >= 0 && (g->res[i].is_output || g->res[i].readback) &&
            _vrg_resource_barrier(g, i, _vrg_copy_of(g, i, 0), VRG_ACCESS_TRANSFER_SRC, &b[n]))
            n++;
    if (f) {
        fprintf(f, "  %-12s %d barrier%s\n", "(readback)", n, n == 1 ? "" : "s");
        for (int i = 0; i < n; i++)
            print_barrier(g, &b[i], f);
    }
    g->frame.frame_index++;
}

static void print_barriers(const vrg_graph *cg, FILE *f)
{
    /* Work on a copy: the live graph's tracked state must not change. */
    vrg_graph *g = malloc(sizeof *g);
    memcpy(g, cg, sizeof *g);
    for (int i = 0; i < g->res_count; i++)
        memset(g->res[i].sync, 0, sizeof g->res[i].sync);
    g->frame.frame_index = 0;
    simulate_frame(g, NULL);
    fprintf(f, "barriers (steady-state frame; a pass's barriers are one vkCmdPipelineBarrier2):\n");
    simulate_frame(g, f);
    free(g);
}

static void human(char *out, size_t cap, uint64_t bytes)
{
    if (bytes >= (1u << 20))
        snprintf(out, cap, "%.2f MiB", (double)bytes / (1 << 20));
    else
        snprintf(out, cap, "%.1f KiB", (double)bytes / 1024);
}

void vrg_graph_report(const vrg_graph *g, FILE *f)
{
    int culled = 0;
    for (int i = 0; i < g->pass_count; i++)
        culled += g->passes[i].culled;
    fprintf(f, "graph '%s' (%s): %ux%u, output '%s', %d passes scheduled, %d culled\n", g->name, g->path, g->width, g->height, g->output_name,
            g->schedule_count, culled);
    fprintf(f, "schedule:\n");
    for (int k = 0; k < g->schedule_count; k++) {
        const vrg_pass *p = &g->passes[g->schedule[k]];
        fprintf(f, "  %2d. %-12s plugin %-14s (line %d)  %s\n", k, p->name, p->plugin->name, p->line, p->plugin->path);
    }
    fprintf(f, "culled passes:%s\n", culled ? "" : " none");
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].culled)
            fprintf(f, "  %-12s (line %d): its outputs reach neither the output nor a history resource\n", g->passes[i].name, g->passes[i].line);
    fprintf(f, "resources:\n");
    for (int i = 0; i < g->res_count; i++) {
        const _vrg_resource *r = &g->res[i];
        if (r->first_use < 0)
            continue;
        char what[64], mem[96], sz[32];
        if (r->kind == VRG_IMAGE)
            snprintf(what, sizeof what, "image %-8s %ux%u", _vrg_format_name(r->format), r->width, r->height);
        else if (r->kind == VRG_ACCEL)
            snprintf(what, sizeof what, r->size ? "accel, %llu instances" : "accel, not built", (unsigned long long)r->size);
        else
            snprintf(what, sizeof what, "buffer %llu B", (unsigned long long)r->size);
        human(sz, sizeof sz, r->req.size);
        if (r->block >= 0)
            snprintf(mem, sizeof mem, "block %d @ %llu, %s%s", r->block, (unsigned long long)r->offset, sz, r->overlap_count ? ", aliased" : "");
        else
            snprintf(mem, sizeof mem, "own memory, %s%s", sz, r->history ? " x2 (history)" : r->dummy ? (r->writer >= 0 ? " (unread optional output)" : " (unconnected input)") : " (persistent)");
        const char *role = r->internal_owner >= 0 ? " internal" : r->history ? " @prev" : "";
        fprintf(f, "  %-22s %-28s lifetime %d..%d%s%s  [%s]\n", r->name, what, r->first_use, r->last_use, role, r->is_output ? " output" : "", mem);
    }
    print_barriers(g, f);
    char naive[32], aliased[32], hist[32];
    human(naive, sizeof naive, g->naive_bytes);
    human(aliased, sizeof aliased, g->aliased_bytes);
    human(hist, sizeof hist, g->history_bytes);
    double saved = g->naive_bytes ? 100.0 * (double)(g->naive_bytes - g->aliased_bytes) / (double)g->naive_bytes : 0.0;
    fprintf(f, "memory: transient naive %s, aliased %s, saved %.1f%%; history/persistent %s\n", naive, aliased, saved, hist);
}

/* A Graphviz string body: quotes and backslashes escaped. */
static const char *dot_str(const char *s, char *buf, size_t cap)
{
    size_t n = 0;
    for (; *s && n + 2 < cap; s++) {
        if (*s == '"' || *s == '\\')
            buf[n++] = '\\';
        buf[n++] = *s;
    }
    buf[n] = '\0';
    return buf;
}

void vrg_graph_write_dot(const vrg_graph *g, FILE *f)
{
    char esc[2 * VRG_NAME_MAX + 8];
    fprintf(f, "digraph \"%s\" {\n  rankdir=LR;\n  node [fontname=\"sans\"];\n", dot_str(g->name, esc, sizeof esc));
    for (int i = 0; i < g->pass_count; i++) {
        const vrg_pass *p = &g->passes[i];
        fprintf(f, "  \"pass:%s\" [shape=box, label=\"%s\\n(%s)\"%s];\n", p->name, p->name, p->plugin ? p->plugin->name : "?",
                p->culled ? ", style=dashed, color=gray" : "");
    }
    for (int i = 0; i < g->res_count; i++) {
        const _vrg_resource *r = &g->res[i];
        if (r->internal_owner >= 0 || r->dummy)
            continue;
        fprintf(f, "  \"res:%s\" [shape=%s, label=\"%s\\n%s\"%s];\n", r->name, r->kind == VRG_IMAGE ? "ellipse" : "cylinder", r->name,
                r->kind == VRG_IMAGE ? _vrg_format_name(r->format) : "buffer", r->is_output ? ", penwidth=2" : "");
        if (r->writer >= 0)
            fprintf(f, "  \"pass:%s\" -> \"res:%s\";\n", g->passes[r->writer].name, r->name);
    }
    for (int i = 0; i < g->pass_count; i++) {
        const vrg_pass *p = &g->passes[i];
        for (int s = 0; p->plugin && s < (int)p->plugin->desc->slot_count; s++) {
            const _vrg_binding_ref *b = &p->slots[s];
            if (vrg_slot(p, s)->dir != VRG_IN || b->res < 0 || b->dummy)
                continue;
            fprintf(f, "  \"res:%s\" -> \"pass:%s\" [label=\"%s%s\"%s];\n", g->res[b->res].name, p->name, vrg_slot(p, s)->name,
                    b->prev ? " @prev" : "", b->prev ? ", style=dashed, constraint=false" : "");
        }
    }
    fprintf(f, "}\n");
}
