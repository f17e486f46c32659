/* One-bounce diffuse indirect light: `rays` cosine-weighted rays per pixel
 * around the face normal n, from position + n * 1e-3, traced through the
 * world (DDA, or ray queries when the scene built a TLAS). Each ray brings
 * back the radiance L_in arriving along it:
 *   miss (nothing within max_distance):  L_in = frame_sky(d)
 *   hit block b, face normal n2, at x2:  L_in = albedo(b, n2) * (sun_radiance * max(n2.L, 0) * V + ambient + e(b))
 * L = sun_dir; V = 1 if the shadow ray from x2 + n2 * 1e-3 toward L travels
 * max_distance unoccluded (else 0; always 1 with shadow = 0; not traced when
 * n2.L <= 0 or the sun is below the horizon). The "albedo x (sun
 * radiance x N.L x one shadow ray) plus sky" reads "plus sky" as the sky's
 * ambient term: frame.ambient (the cosine-weighted mean sky radiance, what a
 * white up-facing unoccluded surface reflects), times the albedo, unoccluded
 * and the same for every face orientation. sun_radiance and ambient are
 * already reflected (outgoing) radiance of a white Lambertian surface, so
 * the bracket times albedo is the hit's outgoing radiance, with no 1/pi.
 * e(b) is the block's emissive scale (world.glsl's material_emissive, 0 for
 * blocks that do not emit): an emitting block sends albedo * e(b) (the
 * emitters' light reaches a surface in one bounce: docs/world.md).
 * albedo(b, n2): material_albedo(b), or, with the atlas connected and
 * textures = 1, the mean of the face's atlas tile (mip level 4: one texel per
 * tile; differs from the material's for grass sides and bottoms).
 * Directions: from the pixel's random stream, or with stratified = 1 from
 * random.glsl's stratified points (docs/lighting.md, "Sampling").
 *
 * young_rays (adaptive sampling of new history): a pixel whose history is
 * young takes young_rays rays instead of rays. Young: last frame's
 * history length (in.history_length, a temporal pass's length@prev) at
 * the pixel it came from (p - motion, the nearest) was below
 * young_history frames, or it came from off screen. Where a surface
 * newly shows through a moving edge, last frame's pixel held another
 * surface, whose length counts: the temporal pass restarts the history
 * there, and the pixel is young from the next frame on. A fast turn, a
 * descent and a disocclusion are where a temporal filter has few frames
 * to average. The extra rays cost where histories are young: there, and
 * everywhere for young_history frames after the history starts over and
 * while a moving sun keeps histories short (README.md).
 *
 * Output, rgb (a = 1): irradiance = (1/rays) * sum of L_in, the mean incoming
 * radiance over cosine-weighted directions (pdf cos/pi). That estimates
 * E / pi, E = the irradiance integral of L_in cos over the hemisphere, so a
 * Lambertian surface of albedo A reflects A * irradiance (no further 1/pi).
 * Sky pixels (position.w == 0): 0, no rays. */
#include "voxrg/plugin.h"

static const vrg_param_desc params[] = {
    {"rays", VRG_PARAM_INT, 4, 1, 64, "indirect rays per pixel"},
    {"max_distance", VRG_PARAM_FLOAT, 64, 1, 16384, "indirect and secondary shadow ray length, blocks"},
    {"shadow", VRG_PARAM_BOOL, 1, 0, 1, "trace a shadow ray toward the sun at each secondary hit (0: assume lit)"},
    {"textures", VRG_PARAM_BOOL, 1, 0, 1, "with the atlas connected, use its per-face tile means instead of material albedos"},
    {"stratified", VRG_PARAM_BOOL, 0, 0, 1,
     "directions from a sequence that covers the hemisphere evenly over each 4x4 tile of pixels and over the frames (0: independent random numbers)"},
    {"young_rays", VRG_PARAM_INT, 0, 0, 64, "rays for a pixel whose history is young (in.history_length, in.motion); 0: every pixel takes `rays`"},
    {"young_history", VRG_PARAM_FLOAT, 4, 1, 1000, "a pixel is young when its history had fewer frames than this last frame (or it was off screen)"},
};

static const vrg_slot_desc slots[] = {
    {.name = "world", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_TEXEL_READ, .format = VK_FORMAT_R32G32B32A32_UINT,
     .help = "the scene's world (world.glsl reads 16-byte texels)"},
    {.name = "frame", .dir = VRG_IN, .kind = VRG_BUFFER, .access = VRG_ACCESS_UNIFORM, .help = "the scene's per-frame uniforms"},
    {.name = "position", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
     .help = "gbuffer position: world hit point, w = 1 on a hit, 0 on sky"},
    {.name = "normal", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_READ, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "gbuffer normal: the face normal"},
    {.name = "atlas", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "block textures: per-face albedo at secondary hits (else material albedos)"},
    {.name = "irradiance", .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT,
     .help = "mean incoming radiance over cosine-weighted directions (= irradiance / pi); 0 on sky"},
    {.name = "history_length", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "with young_rays: last frame's history length in frames (clamped_reproject's length@prev), the size of irradiance"},
    {.name = "motion", .dir = VRG_IN, .kind = VRG_IMAGE, .access = VRG_ACCESS_SAMPLED, .flags = VRG_SLOT_OPTIONAL,
     .help = "with young_rays: the G-buffer's motion (pixels) at the size of irradiance"},
    /* last: bound only when the scene built it, so the slots before it
     * keep their bindings (indirect.comp) */
    {.name = "tlas", .dir = VRG_IN, .kind = VRG_ACCEL, .access = VRG_ACCESS_RAY_QUERY, .flags = VRG_SLOT_OPTIONAL,
     .help = "the scene's TLAS: trace with ray queries (traversal = rayquery)"},
};

static int check(vrg_pass *pass)
{
    if (vrg_param_int(pass, "young_rays") > 0 &&
        (!vrg_res_connected(vrg_pass_res(pass, "history_length")) || !vrg_res_connected(vrg_pass_res(pass, "motion"))))
        return vrg_pass_error(pass, "young_rays = %d reads last frame's history: connect in.history_length (a temporal pass's length@prev) and in.motion",
                              vrg_param_int(pass, "young_rays"));
    return 0;
}

/* every dispatch execute() records: checked by `voxrg check`; its push
 * constants are the parameters by name, and textured */
static const vrg_dispatch_desc dispatches[] = {
    {.shader = "indirect.comp", .pixel_loop = 1},
};

static void execute(vrg_pass *pass, VkCommandBuffer cmd)
{
    if (vrg_param_int(pass, "young_rays") > 0) {
        static const char *same[] = {"in.history_length", "in.motion"};
        if (vrg_pass_require_same_size(pass, "out.irradiance", same, 2) != 0)
            return;
    }
    vrg_push_int(pass, "textured", vrg_param_int(pass, "textures") && vrg_res_connected(vrg_pass_res(pass, "atlas")));
    (void)vrg_dispatch(pass, cmd, &dispatches[0]);
}

static const vrg_plugin_desc desc = {
    .abi_version = VRG_ABI_VERSION,
    .name = "indirect",
    .kind = VRG_PLUGIN_PASS,
    .help = "one-bounce diffuse indirect light: cosine-weighted rays, sun (with a shadow ray), ambient sky and emission at the hit, sky on a miss",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .slots = slots,
    .slot_count = sizeof slots / sizeof slots[0],
    .check = check,
    .execute = execute,
    .dispatches = dispatches,
    .dispatch_count = sizeof dispatches / sizeof dispatches[0],
};

VRG_PLUGIN(desc)
