/* Test plugin for internal resources and barriers between dispatches of one
 * pass: src+1 goes into "ping", then iterations-1 dispatches bounce between
 * "ping" and "pong" adding 1 each, and the last one is copied to dst. So
 * dst = src + iterations (all four channels). Any missing barrier between
 * the dispatches shows up as a wrong count or a validation error. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"iterations", VRG_PARAM_INT, 3, 1, 16, "how much is added to src"},
};

static const vrg_slot_desc slots[] = {
    {.name = "src", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .help = "image to add to"},
    {.name = "dst", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE,
     .format = VK_FORMAT_R16G16B16A16_SFLOAT, .scale = 1.0f, .help = "src + iterations"},
};

static int create(vrg_pass *pass)
{
    const char *names[] = {"ping", "pong"};
    for (int i = 0; i < 2; i++)
        if (!vrg_res_connected(vrg_pass_request_image(pass, names[i], VK_FORMAT_R16G16B16A16_SFLOAT, 1.0f,
                                                      VRG_ACCESS_STORAGE_WRITE)))
            return -1; /* the runtime has reported why */
    return 0;
}

/* One dispatch to = from + add. The accesses are spelled out so the runtime
 * puts a barrier between this write and the next dispatch's read. */
static int step(vrg_pass *pass, VkCommandBuffer cmd, const char *from, const char *to, float add)
{
    vrg_dispatch_desc d = {
        .shader = "pingpong.comp",
        .bindings = {{from, VRG_ACCESS_STORAGE_READ}, {to, VRG_ACCESS_STORAGE_WRITE}},
        .push = &add,
        .push_size = sizeof add,
        .domain = to,
    };
    return vrg_dispatch(pass, cmd, &d);
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    int n = vrg_param_int(pass, "iterations");
    const char *cur = "ping", *other = "pong";
    if (step(pass, cmd, "src", cur, 1.0f) != 0)
        return;
    for (int i = 1; i < n; i++) {
        if (step(pass, cmd, cur, other, 1.0f) != 0)
            return;
        const char *t = cur;
        cur = other;
        other = t;
    }
    (void)step(pass, cmd, cur, "dst", 0.0f);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "pingpong",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: dst = src + iterations, through two internal images",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .execute = execute,
};

VRG_PLUGIN(desc)
