/* The functions a plugin calls on its vrg_pass. */
#define _DEFAULT_SOURCE
#include <stdlib.h>
#include <string.h>
#include "internal.h"

const vrg_device *vrg_pass_device(const vrg_pass *p) { return p->graph->ctx ? &p->graph->ctx->dev : NULL; }
const vrg_frame_info *vrg_pass_frame(const vrg_pass *p) { return &p->graph->frame; }
const char *vrg_pass_name(const vrg_pass *p) { return p->name; }
void *vrg_pass_user(const vrg_pass *p) { return p->user; }
void vrg_pass_set_user(vrg_pass *p, void *user) { p->user = user; }

/* A plugin's message as long as it is (a list of choices, a path), as the
 * graph's diagnostics keep it (diag.c); NULL without memory. Free it. */
static char *format_message(const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    char *msg = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (msg)
        vsnprintf(msg, (size_t)n + 1, fmt, ap);
    return msg;
}
static const char *const no_memory_for_message = "(out of memory formatting the pass's message)";

static int pass_vfail(vrg_pass *p, _vrg_diag_code code, const char *fmt, va_list ap)
{
    char *msg = format_message(fmt, ap);
    _vrg_error_at(&p->graph->diag, p->line, code, NULL, "pass '%s' (plugin %s): %s", p->name, p->plugin ? p->plugin->path : "?",
                  msg ? msg : no_memory_for_message);
    free(msg);
    p->failed = 1;
    return -1;
}

static int pass_vfail_at(vrg_pass *p, int line, _vrg_diag_code code, const char *fmt, va_list ap)
{
    char *msg = format_message(fmt, ap);
    const char *text = msg ? msg : no_memory_for_message;
    if (line > 0)
        _vrg_error_at(&p->graph->diag, line, code, NULL, "%s", text);
    else
        _vrg_error(&p->graph->diag, code, "pass '%s': %s", p->name, text);
    free(msg);
    p->failed = 1;
    return -1;
}

static int pass_fail_at(vrg_pass *p, int line, _vrg_diag_code code, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static int pass_fail_at(vrg_pass *p, int line, _vrg_diag_code code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = pass_vfail_at(p, line, code, fmt, ap);
    va_end(ap);
    return rc;
}

/* What a plugin reports: its own words under one code. */
int vrg_pass_error(vrg_pass *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = pass_vfail(p, VRG_E_PASS_FAILED, fmt, ap);
    va_end(ap);
    return rc;
}

/* What the runtime finds wrong with a pass: the code names the problem. */
int _vrg_pass_fail(vrg_pass *p, _vrg_diag_code code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = pass_vfail(p, code, fmt, ap);
    va_end(ap);
    return rc;
}

vrg_pass *vrg_pass_previous_instance(const vrg_pass *p)
{
    vrg_graph *old = p->graph->predecessor;
    for (int i = 0; old && i < old->pass_count; i++) {
        vrg_pass *q = &old->passes[i];
        if (strcmp(q->name, p->name) == 0)
            return q->plugin == p->plugin && q->created ? q : NULL;
    }
    return NULL;
}

double vrg_pass_gpu_ms(const vrg_pass *p, const char *other)
{
    const vrg_graph *g = p->graph;
    if (!other)
        return g->pass_ms[p - g->passes];
    for (int i = 0; i < g->pass_count; i++)
        if (strcmp(g->passes[i].name, other) == 0)
            return g->pass_ms[i];
    return -1;
}

static int param_index(const vrg_pass *p, const char *name)
{
    for (uint32_t i = 0; i < p->plugin->desc->param_count; i++)
        if (strcmp(p->plugin->desc->params[i].name, name) == 0)
            return (int)i;
    return -1;
}

double vrg_param(const vrg_pass *p, const char *name)
{
    int i = param_index(p, name);
    if (i < 0) {
        /* A plugin asking for a parameter it never declared is a plugin bug. */
        fprintf(stderr, "voxrg: plugin %s asked for undeclared parameter '%s'\n", p->plugin->name, name);
        abort();
    }
    return p->params[i];
}

int vrg_param_int(const vrg_pass *p, const char *name) { return (int)vrg_param(p, name); }

int _vrg_pass_add_string(vrg_pass *p, int param, const char *value, int line, int replace)
{
    if (replace) {
        int k = 0;
        for (int i = 0; i < p->string_count; i++) {
            if (p->strings[i].param == param)
                free(p->strings[i].value);
            else
                p->strings[k++] = p->strings[i];
        }
        p->string_count = k;
    }
    p->strings = realloc(p->strings, (size_t)(p->string_count + 1) * sizeof *p->strings);
    p->strings[p->string_count++] = (_vrg_param_value){param, strdup(value), line};
    return 0;
}

void _vrg_pass_free_params(vrg_pass *p)
{
    for (int i = 0; i < p->string_count; i++)
        free(p->strings[i].value);
    free(p->strings);
    p->strings = NULL;
    p->string_count = 0;
    for (int i = 0; i < p->input_count; i++)
        free(p->inputs[i]);
    free(p->inputs);
    p->inputs = NULL;
    p->input_count = 0;
    free(p->push_values);
    p->push_values = NULL;
    p->push_count = p->push_cap = 0;
}

static int string_param(const vrg_pass *p, const char *name)
{
    int i = param_index(p, name);
    if (i < 0 || p->plugin->desc->params[i].type != VRG_PARAM_STRING) {
        fprintf(stderr, "voxrg: plugin %s asked for undeclared string parameter '%s'\n", p->plugin->name, name);
        abort();
    }
    return i;
}

const char *vrg_param_string(const vrg_pass *p, const char *name)
{
    int idx = string_param(p, name);
    const char *v = p->plugin->desc->params[idx].default_string;
    for (int i = 0; i < p->string_count; i++)
        if (p->strings[i].param == idx)
            v = p->strings[i].value;
    return v ? v : "";
}

int vrg_param_count(const vrg_pass *p, const char *name)
{
    int idx = string_param(p, name), n = 0;
    for (int i = 0; i < p->string_count; i++)
        n += p->strings[i].param == idx;
    return n;
}

const char *vrg_param_item(const vrg_pass *p, const char *name, int k, int *line)
{
    int idx = string_param(p, name);
    for (int i = 0; i < p->string_count; i++)
        if (p->strings[i].param == idx && k-- == 0) {
            if (line)
                *line = p->strings[i].line;
            return p->strings[i].value;
        }
    return NULL;
}

int vrg_param_line(const vrg_pass *p, const char *name)
{
    int line = 0, n = vrg_param_count(p, name);
    if (n > 0)
        vrg_param_item(p, name, n - 1, &line);
    return line;
}

/* The index of parameter i's value in the descriptor's list for it
 * (param_choices), or -1 after VRG-E047 at the value's line. */
static int descriptor_choice(vrg_pass *p, uint32_t i)
{
    const vrg_plugin_desc *d = p->plugin->desc;
    const char *choices = _vrg_param_choices(d, i), *v = vrg_param_string(p, d->params[i].name);
    int k = _vrg_choice_index(choices, v);
    if (k >= 0)
        return k;
    char *list = _vrg_choice_words(choices);
    pass_fail_at(p, vrg_param_line(p, d->params[i].name), VRG_E_NOT_A_CHOICE, "%s = '%s': expected %s", d->params[i].name, v,
                 list ? list : choices); /* no memory for the words: the list as written */
    free(list);
    return -1;
}

int vrg_param_choice(vrg_pass *p, const char *name, const char *const *choices, int count)
{
    const char *v = vrg_param_string(p, name);
    if (!choices) { /* the descriptor's list (param_choices), which the runtime checked the value against */
        const vrg_plugin_desc *d = p->plugin->desc;
        for (uint32_t i = 0; i < d->param_count; i++)
            if (strcmp(d->params[i].name, name) == 0 && _vrg_param_choices(d, i))
                return descriptor_choice(p, i);
        return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_param_choice('%s', NULL): the plugin lists no choices for it (param_choices)", name);
    }
    for (int i = 0; i < count; i++)
        if (strcmp(v, choices[i]) == 0)
            return i;
    /* "a, b or c", each name whole however many */
    size_t cap = 1;
    for (int i = 0; i < count; i++)
        cap += strlen(choices[i]) + 4;
    char *list = malloc(cap);
    if (list)
        list[0] = '\0';
    for (int i = 0, o = 0; list && i < count; i++)
        o += snprintf(list + o, cap - (size_t)o, "%s%s", i == 0 ? "" : i == count - 1 ? " or " : ", ", choices[i]);
    pass_fail_at(p, vrg_param_line(p, name), VRG_E_NOT_A_CHOICE, "%s = '%s': expected %s", name, v, list ? list : "one of its choices (out of memory listing them)");
    free(list);
    return -1;
}

/* The descriptor's choices (param_choices): each such string parameter's
 * value is one of them, else VRG-E047 at its line, as vrg_param_choice
 * says it for a C pass that checks its own. */
int _vrg_pass_check_choices(vrg_pass *p)
{
    const vrg_plugin_desc *d = p->plugin->desc;
    int rc = 0;
    for (uint32_t i = 0; i < d->param_count; i++)
        if (_vrg_param_choices(d, i) && descriptor_choice(p, i) < 0)
            rc = -1;
    return rc;
}

int _vrg_pass_choice(const vrg_pass *p, uint32_t param)
{
    const char *choices = _vrg_param_choices(p->plugin->desc, param);
    return choices ? _vrg_choice_index(choices, vrg_param_string(p, p->plugin->desc->params[param].name)) : -1;
}

int vrg_pass_error_at(vrg_pass *p, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = pass_vfail_at(p, line, VRG_E_PASS_FAILED, fmt, ap);
    va_end(ap);
    return rc;
}

void vrg_pass_warn_at(vrg_pass *p, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *msg = format_message(fmt, ap);
    va_end(ap);
    const char *text = msg ? msg : no_memory_for_message;
    if (line > 0)
        _vrg_warning_at(&p->graph->diag, line, VRG_W_PASS_WARNING, "%s", text);
    else
        _vrg_warning_at(&p->graph->diag, p->line, VRG_W_PASS_WARNING, "pass '%s': %s", p->name, text);
    free(msg);
}

const char *vrg_pass_graph_path(const vrg_pass *p) { return p->graph->loaded_from_file ? p->graph->path : ""; }

int vrg_pass_input_file(vrg_pass *p, const char *path)
{
    char **grown = realloc(p->inputs, sizeof *grown * (size_t)(p->input_count + 1));
    char *copy = strdup(path);
    if (grown)
        p->inputs = grown;
    if (!grown || !copy) {
        free(copy);
        return _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "out of memory naming its input file %s", path);
    }
    p->inputs[p->input_count++] = copy;
    return 0;
}

int vrg_pass_set_buffer_size(vrg_pass *p, const char *slot, uint64_t bytes)
{
    const vrg_plugin_desc *d = p->plugin->desc;
    for (uint32_t s = 0; s < d->slot_count; s++)
        if (d->slots[s].dir == VRG_OUT && d->slots[s].kind != VRG_IMAGE && strcmp(d->slots[s].name, slot) == 0) {
            if (p->graph->allocated)
                return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "buffer size of '%s' set after allocation", slot);
            p->buffer_size[s] = bytes;
            if (p->slots[s].res >= 0)
                p->graph->res[p->slots[s].res].size = bytes;
            return 0;
        }
    return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_set_buffer_size: no buffer output '%s'", slot);
}

static const _vrg_resource *res_of(const vrg_pass *p, vrg_res h, int *copy);

static void free_one(VkDevice dev, _vrg_host_buffer *hb)
{
    if (hb->map)
        vkUnmapMemory(dev, hb->memory);
    vkDestroyBuffer(dev, hb->buffer, NULL);
    vkFreeMemory(dev, hb->memory, NULL);
    free(hb);
}

void *vrg_pass_buffer(vrg_pass *p, const vrg_buffer_desc *d, VkBuffer *buffer, VkDeviceAddress *address)
{
    vrg_context *ctx = p->graph->ctx;
    *buffer = VK_NULL_HANDLE;
    if (address)
        *address = 0;
    if (!ctx) {
        _vrg_pass_fail(p, VRG_E_NO_DEVICE, "buffer '%s' needs a device", d->name);
        return NULL;
    }
    VkDevice dev = ctx->dev.device;
    int wants_address = (d->usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
    _vrg_host_buffer *hb = calloc(1, sizeof *hb);
    snprintf(hb->name, sizeof hb->name, "%s", d->name);
    hb->host_visible = d->host_visible;
    VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = d->size ? d->size : 16, .usage = d->usage};
    VkMemoryRequirements req = {0};
    int type = -1;
    if (vkCreateBuffer(dev, &ci, NULL, &hb->buffer) == VK_SUCCESS) {
        vkGetBufferMemoryRequirements(dev, hb->buffer, &req);
        VkMemoryPropertyFlags want = d->host_visible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                                     : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        type = _vrg_find_memory_type(ctx, req.memoryTypeBits, want);
    }
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO, .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .pNext = wants_address ? &flags : NULL,
                               .allocationSize = req.size, .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(dev, &ai, NULL, &hb->memory) != VK_SUCCESS || vkBindBufferMemory(dev, hb->buffer, hb->memory, 0) != VK_SUCCESS ||
        (d->host_visible && vkMapMemory(dev, hb->memory, 0, VK_WHOLE_SIZE, 0, &hb->map) != VK_SUCCESS)) {
        free_one(dev, hb);
        _vrg_pass_fail(p, VRG_E_VULKAN_FAILED, "cannot allocate %llu bytes of %s memory for '%s'", (unsigned long long)d->size, d->host_visible ? "host-visible" : "device",
                       d->name);
        return NULL;
    }
    _vrg_name_object(ctx, VK_OBJECT_TYPE_BUFFER, (uint64_t)hb->buffer, "%s/%s.%s", p->graph->name, p->name, d->name);
    hb->size = ci.size;
    if (wants_address) {
        VkBufferDeviceAddressInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = hb->buffer};
        hb->address = vkGetBufferDeviceAddress(dev, &info);
    }
    if (address)
        *address = hb->address;
    hb->next = p->host_buffers;
    p->host_buffers = hb;
    *buffer = hb->buffer;
    return hb->map ? hb->map : (void *)hb;
}

void *vrg_pass_host_buffer(vrg_pass *p, const char *name, uint64_t bytes, VkBuffer *buffer)
{
    vrg_buffer_desc d = {.name = name, .size = bytes, .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT, .host_visible = 1};
    return vrg_pass_buffer(p, &d, buffer, NULL);
}

static void retire(vrg_graph *g, _vrg_host_buffer *hb, void (*fn)(void *), void *user)
{
    _vrg_retired *r = calloc(1, sizeof *r);
    if (!r) { /* cannot defer: wait for the GPU instead */
        vkDeviceWaitIdle(g->ctx->dev.device);
        if (hb)
            free_one(g->ctx->dev.device, hb);
        if (fn)
            fn(user);
        return;
    }
    *r = (_vrg_retired){.serial = g->submitted + 1, .buffer = hb, .fn = fn, .user = user, .next = g->retired};
    g->retired = r;
}

void _vrg_retire(vrg_graph *g, void (*fn)(void *user), void *user) { retire(g, NULL, fn, user); }

int vrg_pass_defer(vrg_pass *p, void (*fn)(void *user), void *user)
{
    if (!fn)
        return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_defer: no function");
    if (!p->graph->ctx)
        fn(user); /* no device: nothing in flight */
    else
        retire(p->graph, NULL, fn, user);
    return 0;
}

void _vrg_free_retired(vrg_graph *g, int all)
{
    for (_vrg_retired **at = &g->retired; *at;) {
        _vrg_retired *r = *at;
        if (!all && r->serial > g->finished) {
            at = &r->next;
            continue;
        }
        *at = r->next;
        if (r->fn)
            r->fn(r->user);
        if (r->buffer)
            free_one(g->ctx->dev.device, r->buffer);
        free(r);
    }
}

void vrg_pass_free_buffer(vrg_pass *p, VkBuffer buffer)
{
    for (_vrg_host_buffer **at = &p->host_buffers; *at; at = &(*at)->next)
        if ((*at)->buffer == buffer) {
            _vrg_host_buffer *hb = *at;
            *at = hb->next;
            retire(p->graph, hb, NULL, NULL); /* frames in flight may still read it */
            return;
        }
}

/* A buffer for one slice: made like vrg_pass_buffer's, but owned by the ring. */
static _vrg_host_buffer *ring_buffer(vrg_pass *p, const vrg_ring *ring, uint32_t slot, uint64_t bytes)
{
    char name[VRG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s[%u]", ring->name, slot);
    VkBuffer buffer;
    vrg_buffer_desc d = {.name = name, .size = bytes, .usage = ring->usage, .host_visible = 1};
    if (!vrg_pass_buffer(p, &d, &buffer, NULL))
        return NULL;
    _vrg_host_buffer *hb = p->host_buffers; /* just added first: take it off the pass's list */
    p->host_buffers = hb->next;
    hb->next = NULL;
    return hb;
}

vrg_ring *vrg_pass_host_ring(vrg_pass *p, const char *name, uint64_t bytes, VkBufferUsageFlags usage)
{
    vrg_ring *ring = calloc(1, sizeof *ring);
    if (!ring) {
        _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "out of memory for ring '%s'", name);
        return NULL;
    }
    snprintf(ring->name, sizeof ring->name, "%s", name);
    ring->usage = usage ? usage : VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    ring->next = p->rings;
    p->rings = ring;
    for (uint32_t s = 0; s < p->graph->frames_in_flight; s++)
        if (!(ring->slice[s] = ring_buffer(p, ring, s, bytes)))
            return NULL;
    return ring;
}

vrg_ring_slice vrg_pass_ring_slice(vrg_pass *p, vrg_ring *ring, uint64_t min_bytes)
{
    vrg_graph *g = p->graph;
    uint32_t slot = g->frame.frame_slot;
    if (!p->cmd) { /* another slot may be in use by the GPU right now */
        _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_ring_slice('%s') is for execute() only", ring->name);
        return (vrg_ring_slice){0};
    }
    _vrg_host_buffer *hb = ring->slice[slot];
    if (!hb || hb->size < min_bytes) {
        /* grown by a quarter more, so that slow growth reallocates rarely */
        _vrg_host_buffer *grown = ring_buffer(p, ring, slot, min_bytes + min_bytes / 4);
        if (!grown)
            return (vrg_ring_slice){0};
        if (hb)
            retire(g, hb, NULL, NULL);
        ring->slice[slot] = hb = grown;
    }
    return (vrg_ring_slice){.map = hb->map, .buffer = hb->buffer, .size = hb->size, .address = hb->address};
}

VkAccelerationStructureKHR vrg_res_accel(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->accel : VK_NULL_HANDLE;
}

void _vrg_pass_free_host_buffers(vrg_pass *p)
{
    while (p->rings) {
        vrg_ring *ring = p->rings;
        p->rings = ring->next;
        for (int s = 0; s < VRG_MAX_FRAMES_IN_FLIGHT; s++)
            if (ring->slice[s])
                free_one(p->graph->ctx->dev.device, ring->slice[s]);
        free(ring);
    }
    while (p->host_buffers) {
        _vrg_host_buffer *hb = p->host_buffers;
        p->host_buffers = hb->next;
        free_one(p->graph->ctx->dev.device, hb);
    }
}

/* A name that is no slot (nor internal resource) of the pass: a misspelt
 * name must not pass for an unconnected optional slot. */
static int names_no_slot(const vrg_pass *p, const char *name)
{
    int res, prev, slot = -1;
    return _vrg_pass_lookup(p, name, &res, &prev, &slot) != 0 && slot < 0;
}

int vrg_pass_require_same_size(vrg_pass *p, const char *ref, const char *const *names, int count)
{
    if (names_no_slot(p, ref) || !vrg_res_connected(vrg_pass_res(p, ref)))
        return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_require_same_size: '%s' names no connected slot of this pass", ref);
    VkExtent2D want = vrg_res_extent(p, vrg_pass_res(p, ref));
    for (int i = 0; i < count; i++) {
        if (names_no_slot(p, names[i]))
            return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_require_same_size: '%s' names no slot of this pass", names[i]);
        vrg_res r = vrg_pass_res(p, names[i]);
        if (!vrg_res_connected(r))
            continue; /* an optional slot's stand-in */
        VkExtent2D e = vrg_res_extent(p, r);
        if (e.width != want.width || e.height != want.height)
            return _vrg_pass_fail(p, VRG_E_SIZE_MISMATCH, "input '%s' is %ux%u, '%s' %ux%u: this pass needs them at one size", names[i], e.width, e.height, ref,
                                  want.width, want.height);
    }
    return 0;
}

void vrg_pass_set_subframes(vrg_pass *p, uint32_t n)
{
    if (n > p->graph->subframes)
        p->graph->subframes = n;
}

static vrg_res request(vrg_pass *p, const char *name, vrg_resource_kind kind)
{
    vrg_graph *g = p->graph;
    char full[2 * VRG_NAME_MAX + 2];
    snprintf(full, sizeof full, "%s.%s", p->name, name);
    if (p->created) {
        _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "internal resource '%s' requested outside create()", name);
        return (vrg_res){-1};
    }
    int before = g->res_count;
    int r = _vrg_graph_add_resource(g, full);
    if (r >= 0 && r < before) {
        if (g->res[r].internal_owner == (int)(p - g->passes))
            _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "internal resource '%s' requested twice", name);
        else
            _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "cannot add internal resource '%s': the graph has a resource named '%s'", name, full);
        return (vrg_res){-1};
    }
    if (r < 0) {
        _vrg_pass_fail(p, VRG_E_TOO_MANY, "cannot add internal resource '%s': too many resources (at most %d in a graph)", name, VRG_MAX_RESOURCES);
        return (vrg_res){-1};
    }
    _vrg_resource *res = &g->res[r];
    res->kind = kind;
    res->internal_owner = (int)(p - g->passes);
    res->line = p->line;
    return (vrg_res){r << 1};
}

vrg_res vrg_pass_request_image(vrg_pass *p, const char *name, VkFormat format, float scale, vrg_access first_access)
{
    vrg_res h = request(p, name, VRG_IMAGE);
    if (h.id >= 0) {
        _vrg_resource *r = &p->graph->res[h.id >> 1];
        const vrg_slot_desc def = _vrg_slot_desc_defaults(&(vrg_slot_desc){.kind = VRG_IMAGE, .format = format, .scale = scale});
        r->format = def.format;
        /* a pass's output_scale sizes its scratch images as its outputs */
        r->scale = def.scale * (p->output_scale > 0 ? p->output_scale : 1.0f);
        r->internal_first_access = first_access ? first_access : VRG_ACCESS_STORAGE_WRITE;
    }
    return h;
}

vrg_res vrg_pass_request_buffer(vrg_pass *p, const char *name, uint64_t size)
{
    vrg_res h = request(p, name, VRG_BUFFER);
    if (h.id >= 0) {
        _vrg_resource *r = &p->graph->res[h.id >> 1];
        r->size = size ? size : 16;
        r->internal_first_access = VRG_ACCESS_STORAGE_WRITE;
    }
    return h;
}

/* Slot (or internal resource) by name, dummies included: what the dispatch helper binds. */
int _vrg_pass_lookup(const vrg_pass *p, const char *name, int *res, int *prev, int *slot)
{
    const vrg_plugin_desc *d = p->plugin->desc;
    /* "in.color" / "out.color" pick a direction; a bare name takes the first
     * slot declared with it. */
    int dir = 0;
    if (strncmp(name, "in.", 3) == 0)
        dir = VRG_IN, name += 3;
    else if (strncmp(name, "out.", 4) == 0)
        dir = VRG_OUT, name += 4;
    for (uint32_t s = 0; s < d->slot_count; s++)
        if (strcmp(d->slots[s].name, name) == 0 && (!dir || (int)d->slots[s].dir == dir)) {
            *res = p->slots[s].res;
            *prev = p->slots[s].prev;
            *slot = (int)s;
            return *res >= 0 ? 0 : -1;
        }
    size_t n = strlen(p->name);
    const vrg_graph *g = p->graph;
    for (int i = 0; i < g->res_count; i++) {
        const char *full = g->res[i].name;
        if (g->res[i].internal_owner == (int)(p - g->passes) && strncmp(full, p->name, n) == 0 && full[n] == '.' &&
            strcmp(full + n + 1, name) == 0) {
            *res = i;
            *prev = 0;
            *slot = -1;
            return 0;
        }
    }
    return -1;
}

int vrg_pass_slot_line(const vrg_pass *p, const char *slot)
{
    for (uint32_t s = 0; s < p->plugin->desc->slot_count; s++)
        if (!strcmp(vrg_slot(p, (int)s)->name, slot))
            return p->slots[s].dummy ? 0 : p->slots[s].line;
    return 0;
}

vrg_res vrg_pass_res(const vrg_pass *p, const char *name)
{
    int res, prev, slot;
    if (_vrg_pass_lookup(p, name, &res, &prev, &slot) != 0 || (slot >= 0 && p->slots[slot].dummy))
        return (vrg_res){-1};
    return (vrg_res){(res << 1) | prev};
}

int vrg_res_connected(vrg_res res) { return res.id >= 0; }

int vrg_res_history_valid(const vrg_pass *p, vrg_res h)
{
    if (h.id < 0 || (h.id >> 1) >= p->graph->res_count)
        return 0;
    const _vrg_resource *r = &p->graph->res[h.id >> 1];
    return r->history ? !r->history_cleared : p->graph->frame.history_valid;
}

int vrg_res_fresh(const vrg_pass *p, vrg_res h)
{
    if (h.id < 0 || (h.id >> 1) >= p->graph->res_count)
        return 0;
    return p->graph->res[h.id >> 1].fresh;
}

/* Only a request: the new instance's resources exist only after every
 * create(), and the hand-over happens once the reload can no longer fail
 * (reload.c: keep_resources). */
int vrg_pass_keep_resource(vrg_pass *p, const char *slot)
{
    const vrg_plugin_desc *d = p->plugin->desc;
    if (p->created)
        return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_keep_resource('%s') outside create()", slot);
    for (uint32_t s = 0; s < d->slot_count; s++) {
        if (strcmp(d->slots[s].name, slot) != 0 || d->slots[s].dir != VRG_OUT)
            continue;
        if (!(d->slots[s].flags & VRG_SLOT_PERSISTENT) || d->slots[s].kind == VRG_ACCEL)
            return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_keep_resource: output '%s' is not a persistent buffer or image", slot);
        if (p->graph->predecessor)
            p->keep_slots |= 1u << s;
        return 0;
    }
    return _vrg_pass_fail(p, VRG_E_PASS_API_MISUSE, "vrg_pass_keep_resource: no output '%s'", slot);
}

static const _vrg_resource *res_of(const vrg_pass *p, vrg_res h, int *copy)
{
    if (h.id < 0 || (h.id >> 1) >= p->graph->res_count)
        return NULL;
    *copy = _vrg_copy_of(p->graph, h.id >> 1, h.id & 1);
    return &p->graph->res[h.id >> 1];
}

VkImage vrg_res_image(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->image[c] : VK_NULL_HANDLE;
}

VkImageView vrg_res_view(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->view[c] : VK_NULL_HANDLE;
}

VkBuffer vrg_res_buffer(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->buffer[c] : VK_NULL_HANDLE;
}

VkExtent2D vrg_res_extent(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? (VkExtent2D){r->width, r->height} : (VkExtent2D){0, 0};
}

VkFormat vrg_res_format(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->format : VK_FORMAT_UNDEFINED;
}

uint32_t vrg_res_mips(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->mips : 0;
}

uint64_t vrg_res_size(const vrg_pass *p, vrg_res h)
{
    int c;
    const _vrg_resource *r = res_of(p, h, &c);
    return r ? r->size : 0;
}

void vrg_pass_use(vrg_pass *p, VkCommandBuffer cmd, const vrg_use *uses, uint32_t count)
{
    /* in batches: a plugin may name any number of resources */
    _vrg_barrier_rec b[64];
    int n = 0;
    for (uint32_t i = 0; i < count; i++) {
        if (uses[i].res.id < 0 || (uses[i].res.id >> 1) >= p->graph->res_count)
            continue;
        int res = uses[i].res.id >> 1;
        if (_vrg_resource_barrier(p->graph, res, _vrg_copy_of(p->graph, res, uses[i].res.id & 1), uses[i].access, &b[n]))
            n++;
        if (n == (int)(sizeof b / sizeof b[0])) {
            _vrg_emit_barriers(p->graph, cmd, b, n);
            n = 0;
        }
    }
    _vrg_emit_barriers(p->graph, cmd, b, n);
}

void vrg_pass_stat(vrg_pass *p, const char *name, double value)
{
    for (int i = 0; i < p->stat_count; i++)
        if (strcmp(p->stats[i].name, name) == 0) {
            p->stats[i].value = value;
            return;
        }
    if (p->stat_count == p->stat_cap) {
        int cap = p->stat_cap ? 2 * p->stat_cap : 16;
        _vrg_pass_figure *grown = realloc(p->stats, (size_t)cap * sizeof *grown);
        if (!grown) {
            _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "vrg_pass_stat('%s'): out of memory", name);
            return;
        }
        p->stats = grown;
        p->stat_cap = cap;
    }
    char *copy = strdup(name);
    if (!copy) {
        _vrg_pass_fail(p, VRG_E_OUT_OF_MEMORY, "vrg_pass_stat('%s'): out of memory", name);
        return;
    }
    p->stats[p->stat_count++] = (_vrg_pass_figure){copy, value};
}

void _vrg_pass_clear_stats(vrg_pass *p, int free_table)
{
    for (int i = 0; i < p->stat_count; i++)
        free(p->stats[i].name);
    p->stat_count = 0;
    if (free_table) {
        free(p->stats);
        p->stats = NULL;
        p->stat_cap = 0;
    }
}
