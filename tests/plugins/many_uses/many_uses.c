/* Test plugin for the runtime's tables: any number of internal images, of
 * resources in one vrg_pass_use and of figures (vrg_pass_stat). The last
 * `written` internal images are brought to TRANSFER_DST in one vrg_pass_use
 * and cleared (a dropped barrier leaves one in the wrong layout: validation
 * fails); the others stay untouched, so only the last ones have accesses a
 * later resource in the same memory must wait for. The output is cleared to
 * the number of images. */
#include <stdio.h>
#include <stdlib.h>
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"images", VRG_PARAM_INT, 70, 1, 200, "internal images"},
    {"figures", VRG_PARAM_INT, 20, 0, 200, "figures recorded with vrg_pass_stat"},
    {"written", VRG_PARAM_INT, 200, 0, 200, "the last this many images are cleared (at most all)"},
    {"scale", VRG_PARAM_FLOAT, 0.125, 0.01, 1.0, "internal images' scale"},
};

static const vrg_slot_desc slots[] = {
    {.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_TRANSFER_DST,
     .format = VK_FORMAT_R32_SFLOAT, .scale = 1.0f, .help = "cleared to the number of images"},
};

typedef struct state {
    int count;
    vrg_res images[];
} state;

static int create(vrg_pass *pass)
{
    int n = vrg_param_int(pass, "images");
    state *s = malloc(sizeof *s + (size_t)n * sizeof s->images[0]);
    if (!s)
        return vrg_pass_error(pass, "out of memory");
    s->count = n;
    vrg_pass_set_user(pass, s);
    for (int i = 0; i < n; i++) {
        char name[32];
        snprintf(name, sizeof name, "t%d", i);
        s->images[i] = vrg_pass_request_image(pass, name, VK_FORMAT_R32_SFLOAT, (float)vrg_param(pass, "scale"), VRG_ACCESS_TRANSFER_DST);
        if (s->images[i].id < 0)
            return -1;
    }
    return 0;
}

static void destroy(vrg_pass *pass) { free(vrg_pass_user(pass)); }

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    const state *s = vrg_pass_user(pass);
    int figures = vrg_param_int(pass, "figures");
    for (int i = 0; i < figures; i++) {
        char name[96];
        snprintf(name, sizeof name, "figure_named_at_length_beyond_thirty_one_characters_%d", i);
        vrg_pass_stat(pass, name, i);
    }
    int written = vrg_param_int(pass, "written");
    int first = written < s->count ? s->count - written : 0;
    vrg_use *uses = malloc((size_t)s->count * sizeof *uses);
    if (!uses) {
        vrg_pass_error(pass, "out of memory");
        return;
    }
    for (int i = first; i < s->count; i++)
        uses[i - first] = (vrg_use){s->images[i], VRG_ACCESS_TRANSFER_DST};
    vrg_pass_use(pass, cmd, uses, (uint32_t)(s->count - first));
    free(uses);
    VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (int i = first; i < s->count; i++) {
        VkClearColorValue v = {.float32 = {(float)i}};
        vkCmdClearColorImage(cmd, vrg_res_image(pass, s->images[i]), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
    }
    VkClearColorValue out = {.float32 = {(float)s->count}};
    vkCmdClearColorImage(cmd, vrg_res_image(pass, vrg_pass_res(pass, "color")), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &out, 1, &range);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "many_uses",
    .kind = VRG_PLUGIN_PASS,
    .help = "test: many internal images in one vrg_pass_use, many figures",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .create = create,
    .destroy = destroy,
    .execute = execute,
};

VRG_PLUGIN(desc)
