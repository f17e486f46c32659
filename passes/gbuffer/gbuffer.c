/* G-buffer: one primary ray per pixel through the world (DDA, or ray
 * queries when the scene built a TLAS), writing what the lighting passes and
 * the denoiser need. On a miss: sky radiance in albedo, zero normal, w = 0
 * in position, ids 0. emission: the emissive scale of the block hit
 * (world.glsl's material_emissive), 0 on a miss; modulate adds albedo x
 * emission to the pixel. depth, ids, motion and emission are optional
 * outputs, written only where some pass reads them (or the graph dumps or
 * reads them back): each is an image store per pixel, and the depth and
 * motion arithmetic, that a graph which does not read them should not pay
 * for (docs/benchmarks.md). */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"max_distance", VRG_PARAM_FLOAT, 1024, 1, 16384, "primary ray length, blocks"},
    {"textures", VRG_PARAM_BOOL, 1, 0, 1, "sample the block atlas (mip from the pixel footprint) instead of mean albedos"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the scene's world (world.glsl reads 16-byte texels)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms"},
    {.name = "atlas", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "block textures (else mean albedos)"},
    {.name = "position", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "world position of the hit; w = 1 on a hit, 0 on sky"},
    {.name = "depth", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "linear view depth (blocks along the view axis); 0 on sky (written only when read)"},
    {.name = "normal", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "face normal (an axis unit vector); 0 on sky"},
    {.name = "albedo", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "surface albedo; sky radiance on a miss"},
    {.name = "ids", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R32G32_UINT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "block id, chunk (object) id + 1; 0 0 on sky (written only when read)"},
    {.name = "motion", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16_SFLOAT,
     .flags = VRG_SLOT_OPTIONAL,
     .help = "pixels from where the surface was last frame to where it is now (about 1e4 when it was behind the previous camera; written only when read)"},
    {.name = "emission", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16_SFLOAT, .flags = VRG_SLOT_OPTIONAL,
     .help = "emitted radiance scale e of the block hit (it emits albedo x e); 0 on sky and where nothing emits (written only when read)"},
    /* the acceleration structure stays last: an absent one is not bound */
    {.name = "tlas", .dir = VRG_IN, .kind = VRG_ACCEL, .access = VRG_ACCESS_RAY_QUERY, .flags = VRG_SLOT_OPTIONAL,
     .help = "the scene's TLAS: trace with ray queries (traversal = rayquery)"},
};

/* the one dispatch execute() records: checked by `voxrg check`; its push
 * constants are max_distance by name, textured and writes */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "gbuffer.comp", .pixel_loop = 1},
};

/* gbuffer.comp's WRITE_* bits, in order */
static const char *const optional_outputs[] = {"depth", "ids", "motion", "emission"};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    vrg_push_int(pass, "textured", vrg_param_int(pass, "textures") && vrg_res_connected(vrg_pass_res(pass, "atlas")));
    /* an unread optional output is a 1x1 stand-in the shader does not write */
    uint32_t writes = 0;
    for (uint32_t i = 0; i < sizeof optional_outputs / sizeof optional_outputs[0]; i++)
        writes |= vrg_res_connected(vrg_pass_res(pass, optional_outputs[i])) ? 1u << i : 0u;
    vrg_push_uint(pass, "writes", writes);
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "gbuffer",
    .kind = VRG_PLUGIN_PASS,
    .help = "primary rays: position, depth, normal, albedo (textured), ids, motion vectors, emission; sky on a miss",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
