/* Phase 3, compile: cull, order, lifetimes. Nothing here touches Vulkan
 * objects, so `check` without a device and the fuzzer run exactly this
 * code; memory placement (aliasing) is alias.c's, which allocate calls
 * once the sizes are known. */
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "phases.h"

/* ---- cull ---- */

static void mark_alive(vrg_graph *g, int pi, int *alive)
{
    if (pi < 0 || alive[pi])
        return;
    alive[pi] = 1;
    vrg_pass *p = &g->passes[pi];
    for (int s = 0; p->plugin && s < (int)p->plugin->desc->slot_count; s++)
        if (vrg_slot(p, s)->dir == VRG_IN && p->slots[s].res >= 0)
            mark_alive(g, g->res[p->slots[s].res].writer, alive);
}

/* Appends 'name' to a list of names in out (cap bytes), "..." once full. */
static void list_name(char *out, size_t cap, const char *name)
{
    size_t n = strlen(out);
    if (n + strlen(name) + 8 >= cap) {
        if (!strstr(out, "..."))
            snprintf(out + n, cap - n, ", ...");
        return;
    }
    snprintf(out + n, cap - n, "%s'%s'", n ? ", " : "", name);
}

/* A culled pass is not created or run: as good as not written. Says so
 * at the pass's line, and why: nothing reads what it writes, or only
 * passes culled themselves do. */
static void warn_culled(vrg_graph *g, const vrg_pass *p)
{
    char outputs[256] = "", readers[256] = "";
    for (int s = 0; s < (int)p->plugin->desc->slot_count; s++)
        if (vrg_slot(p, s)->dir == VRG_OUT && p->slots[s].res >= 0)
            list_name(outputs, sizeof outputs, g->res[p->slots[s].res].name);
    for (int i = 0; i < g->pass_count; i++) {
        const vrg_pass *q = &g->passes[i];
        int reads = 0;
        for (int t = 0; t < (int)q->plugin->desc->slot_count && !reads; t++)
            reads = vrg_slot(q, t)->dir == VRG_IN && q->slots[t].res >= 0 && g->res[q->slots[t].res].writer == p - g->passes;
        if (reads)
            list_name(readers, sizeof readers, q->name);
    }
    if (readers[0])
        _vrg_warning_at(&g->diag, p->line, VRG_W_PASS_CULLED,
                        "pass '%s' is culled (not run): its outputs (%s) are read only by passes culled themselves (%s); connect one of them to "
                        "what reaches the output '%s', or remove them", p->name, outputs, readers, g->output_name);
    else
        _vrg_warning_at(&g->diag, p->line, VRG_W_PASS_CULLED,
                        "pass '%s' is culled (not run): no pass reads its outputs (%s), and none is the output '%s'; connect one to a pass "
                        "that is run (in.SLOT = NAME), or remove the pass", p->name, outputs[0] ? outputs : "none", g->output_name);
}

static void cull(vrg_graph *g)
{
    int alive[VRG_MAX_PASSES] = {0};
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->is_output || r->readback || r->history)
            mark_alive(g, r->writer, alive);
    }
    for (int i = 0; i < g->pass_count; i++)
        if (g->passes[i].is_scene)
            mark_alive(g, i, alive);
    for (int i = 0; i < g->pass_count; i++) {
        if (!alive[i] && !g->passes[i].culled) /* once: compile runs again after create */
            warn_culled(g, &g->passes[i]);
        g->passes[i].culled = !alive[i];
    }
}

/* ---- order: Kahn's algorithm, ties broken by file order, scene first ---- */

static int schedule(vrg_graph *g)
{
    int indeg[VRG_MAX_PASSES] = {0}, done[VRG_MAX_PASSES] = {0};
    for (int i = 0; i < g->pass_count; i++) {
        vrg_pass *p = &g->passes[i];
        p->order = -1;
        if (p->culled)
            continue;
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
            _vrg_binding_ref *b = &p->slots[s];
            if (vrg_slot(p, s)->dir == VRG_IN && b->res >= 0 && !b->prev && g->res[b->res].writer >= 0)
                indeg[i]++;
        }
    }
    g->schedule_count = 0;
    for (;;) {
        int pick = -1;
        for (int i = 0; i < g->pass_count; i++) {
            if (g->passes[i].culled || done[i] || indeg[i] > 0)
                continue;
            if (pick < 0 || (g->passes[i].is_scene && !g->passes[pick].is_scene))
                pick = i;
        }
        if (pick < 0)
            break;
        done[pick] = 1;
        g->passes[pick].order = g->schedule_count;
        g->schedule[g->schedule_count++] = pick;
        /* release readers of everything pick writes */
        for (int i = 0; i < g->pass_count; i++) {
            vrg_pass *p = &g->passes[i];
            if (p->culled || done[i])
                continue;
            for (int s = 0; s < (int)p->plugin->desc->slot_count; s++) {
                _vrg_binding_ref *b = &p->slots[s];
                if (vrg_slot(p, s)->dir == VRG_IN && b->res >= 0 && !b->prev && g->res[b->res].writer == pick)
                    indeg[i]--;
            }
        }
    }
    for (int i = 0; i < g->pass_count; i++)
        if (!g->passes[i].culled && !done[i]) {
            _vrg_error_at(&g->diag, g->passes[i].line, VRG_E_CYCLE, NULL, "pass '%s' cannot be scheduled (cycle)", g->passes[i].name);
            return -1;
        }
    return 0;
}

/* ---- lifetimes, in schedule order ---- */

static void use_at(_vrg_resource *r, int order)
{
    if (r->first_use < 0 || order < r->first_use)
        r->first_use = order;
    if (order > r->last_use)
        r->last_use = order;
}

static void lifetimes(vrg_graph *g)
{
    for (int i = 0; i < g->res_count; i++)
        g->res[i].first_use = g->res[i].last_use = -1;
    for (int k = 0; k < g->schedule_count; k++) {
        vrg_pass *p = &g->passes[g->schedule[k]];
        for (int s = 0; s < (int)p->plugin->desc->slot_count; s++)
            if (p->slots[s].res >= 0)
                use_at(&g->res[p->slots[s].res], k);
    }
    for (int i = 0; i < g->res_count; i++)
        if (g->res[i].internal_owner >= 0 && g->passes[g->res[i].internal_owner].order >= 0)
            use_at(&g->res[i], g->passes[g->res[i].internal_owner].order);
    for (int i = 0; i < g->res_count; i++) {
        _vrg_resource *r = &g->res[i];
        if (r->first_use < 0)
            continue;
        /* read back after the last pass; kept resources live all frame; a
         * viewer's graph keeps every image to the end */
        if (r->is_output || r->readback || (g->desc.keep_images && r->kind == VRG_IMAGE))
            r->last_use = g->schedule_count;
        if (_vrg_resource_kept(r)) {
            r->first_use = 0;
            r->last_use = g->schedule_count;
        }
    }
}

int _vrg_compile(vrg_graph *g)
{
    cull(g);
    if (schedule(g) != 0)
        return -1;
    lifetimes(g);
    return 0;
}
