/* tiles: up to 9 images side by side in a grid, each remapped to display
 * values, as NRD's validation layer shows its views: the debug outputs of
 * the temporal passes next to the image they explain (graphs/debug-*.ini).
 * Tile i shows input t<i> (tiles fill rows left to right, top to bottom;
 * `columns` of them a row, 0: the fewest columns that make a square-ish
 * grid of the connected inputs, ceil(sqrt(last connected + 1))). Each tile
 * is W / columns x H / rows pixels (what the division leaves over, at the
 * right and bottom, is black) and shows its input scaled to that size
 * (nearest texel), remapped:
 *   ti_channel  rgb: the three channels; r, g, b, a, luma: one, as grey
 *   v' = clamp((v - ti_min) / (ti_max - ti_min), 0, 1)
 *   ti_heat     one channel as a false-colour ramp (black, blue, cyan,
 *               green, yellow, red, white) instead of grey
 * A value that is NaN or infinite in a shown channel is magenta; an
 * unconnected tile is black. No tone curve: the remapped value is the
 * display value, written into an UNORM image (make it the graph's output).
 * Integer images cannot be sampled as floats: connecting one is an error. */
#include <stdio.h>
#include "voxrg/plugin.h"

#define TILES 9

#define TILE_PARAMS(i)                                                                                                                           \
    {.name = "t" #i "_channel", .type = VRG_PARAM_STRING, .default_string = "rgb",                                                               \
     .help = "what tile " #i " shows: rgb, or one channel as grey: r, g, b, a or luma"},                                                          \
        {.name = "t" #i "_min", .type = VRG_PARAM_FLOAT, .default_value = 0, .min = -1e30, .max = 1e30,                                         \
         .help = "tile " #i ": the value shown black"},                                                                                          \
        {.name = "t" #i "_max", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = -1e30, .max = 1e30,                                         \
         .help = "tile " #i ": the value shown white (full colour)"},                                                                            \
        {.name = "t" #i "_heat", .type = VRG_PARAM_BOOL, .default_value = 0, .min = 0, .max = 1,                                                 \
         .help = "tile " #i ": one channel as a false-colour ramp instead of grey"}

static const vrg_param_desc params[] = {
    {.name = "columns", .type = VRG_PARAM_INT, .default_value = 0, .min = 0, .max = TILES,
     .help = "tiles per row (0: ceil(sqrt(last connected input + 1)))"},
    TILE_PARAMS(0), TILE_PARAMS(1), TILE_PARAMS(2), TILE_PARAMS(3), TILE_PARAMS(4),
    TILE_PARAMS(5), TILE_PARAMS(6), TILE_PARAMS(7), TILE_PARAMS(8),
};

/* the names each t<i>_channel takes (the runtime checks the graph's
 * values; vrg_param_choice(pass, name, NULL, 0) is the index), in the
 * order of TILE_PARAMS; tiles.comp's modes: their indices */
#define TILE_CHOICES "rgb,r,g,b,a,luma", NULL, NULL, NULL
static const char *const param_choices[] = {
    NULL, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES, TILE_CHOICES,
};
_Static_assert(sizeof param_choices / sizeof param_choices[0] == sizeof params / sizeof params[0], "a choice list (or NULL) per parameter");

#define TILE_SLOT(i)                                                                                                                             \
    {.name = "t" #i, .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,                                \
     .help = "tile " #i "'s image: any float or UNORM format, any size"}

static const vrg_slot_desc slots[] = {
    TILE_SLOT(0), TILE_SLOT(1), TILE_SLOT(2), TILE_SLOT(3), TILE_SLOT(4), TILE_SLOT(5), TILE_SLOT(6), TILE_SLOT(7), TILE_SLOT(8),
    {.name = "view", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R8G8B8A8_UNORM,
     .help = "the tiles, display values"},
};

static int check(vrg_pass *pass)
{
    int bad = 0;
    for (int i = 0; i < TILES; i++) {
        char lo[32], hi[32];
        snprintf(lo, sizeof lo, "t%d_min", i);
        snprintf(hi, sizeof hi, "t%d_max", i);
        if (!(vrg_param(pass, lo) < vrg_param(pass, hi)))
            bad |= vrg_pass_error_at(pass, vrg_param_line(pass, hi) ? vrg_param_line(pass, hi) : vrg_param_line(pass, lo),
                                     "%s = %g is not above %s = %g: the range needs a width", hi, vrg_param(pass, hi), lo, vrg_param(pass, lo)) != 0;
    }
    return bad ? -1 : 0;
}

/* the one dispatch execute() records (every slot, in order): checked by
 * `voxrg check`. Its push constants, all computed here and set by name:
 * columns and rows of the grid, connected (bit i: t<i> is connected),
 * modes (4 bits a tile, tiles 0-7 then 8: the channel, 0 rgb .. 5 luma,
 * +8: heat) and each tile's range lo, hi */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "tiles.comp", .pixel_loop = 1},
};

static int integer_format(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R8_UINT: case VK_FORMAT_R8_SINT: case VK_FORMAT_R8G8_UINT: case VK_FORMAT_R8G8_SINT: case VK_FORMAT_R8G8B8A8_UINT:
    case VK_FORMAT_R8G8B8A8_SINT: case VK_FORMAT_R16_UINT: case VK_FORMAT_R16_SINT: case VK_FORMAT_R16G16_UINT: case VK_FORMAT_R16G16_SINT:
    case VK_FORMAT_R16G16B16A16_UINT: case VK_FORMAT_R16G16B16A16_SINT: case VK_FORMAT_R32_UINT: case VK_FORMAT_R32_SINT:
    case VK_FORMAT_R32G32_UINT: case VK_FORMAT_R32G32_SINT: case VK_FORMAT_R32G32B32A32_UINT: case VK_FORMAT_R32G32B32A32_SINT:
        return 1;
    default:
        return 0;
    }
}

/* Formats are known from here on (not yet in check()): an integer input
 * fails the load at its in.tN line, before any frame. */
static int create(vrg_pass *pass)
{
    int bad = 0;
    for (int i = 0; i < TILES; i++) {
        char name[32];
        snprintf(name, sizeof name, "t%d", i);
        vrg_res r = vrg_pass_res(pass, name);
        if (vrg_res_connected(r) && integer_format(vrg_res_format(pass, r)))
            bad |= vrg_pass_error_at(pass, vrg_pass_slot_line(pass, name),
                                     "in.t%d: an integer image cannot be shown (sampled as floats): connect a float or UNORM image", i) != 0;
    }
    return bad ? -1 : 0;
}

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    uint32_t connected = 0, modes[2] = {0, 0};
    float lo[TILES] = {0}, hi[TILES] = {0};
    int last = -1;
    for (int i = 0; i < TILES; i++) {
        char name[32];
        snprintf(name, sizeof name, "t%d", i);
        vrg_res r = vrg_pass_res(pass, name);
        if (!vrg_res_connected(r))
            continue;
        connected |= 1u << i;
        last = i;
        snprintf(name, sizeof name, "t%d_channel", i);
        uint32_t mode = (uint32_t)vrg_param_choice(pass, name, NULL, 0);
        snprintf(name, sizeof name, "t%d_heat", i);
        mode |= vrg_param_int(pass, name) ? 8u : 0u;
        modes[i / 8] |= mode << (4 * (i % 8));
        snprintf(name, sizeof name, "t%d_min", i);
        lo[i] = (float)vrg_param(pass, name);
        snprintf(name, sizeof name, "t%d_max", i);
        hi[i] = (float)vrg_param(pass, name);
    }
    int n = last + 1, columns = vrg_param_int(pass, "columns");
    if (columns == 0)
        while (columns * columns < n)
            columns++;
    if (columns == 0)
        columns = 1;
    vrg_push_int(pass, "columns", columns);
    vrg_push_int(pass, "rows", n > 0 ? (n + columns - 1) / columns : 1);
    vrg_push_uint(pass, "connected", connected);
    vrg_push_uints(pass, "modes", modes, 2);
    vrg_push_floats(pass, "lo", lo, TILES);
    vrg_push_floats(pass, "hi", hi, TILES);
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "tiles",
    .kind = VRG_PLUGIN_PASS,
    .help = "up to 9 images side by side in a grid, each remapped to display values (channel, range, false colour)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .create = create,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
    .param_choices = param_choices,
};

VRG_PLUGIN(desc)
