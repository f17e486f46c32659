/* Defaults, resolved in one place per descriptor kind (as sokol_gfx's
 * _sg_*_desc_defaults): a descriptor's zero fields mean "the default", and
 * the code after these functions reads only resolved values. The zeros of
 * the plugin's own descriptor keep their meaning where they state a
 * requirement ("any format" for a slot), so callers keep the original to
 * check against and use the resolved copy for what they create. */
#include "internal.h"

/* The resource a slot (or a pass's internal request) creates. */
vrg_slot_desc _vrg_slot_desc_defaults(const vrg_slot_desc *sd)
{
    vrg_slot_desc d = *sd;
    if (!d.format) /* buffers: the texel format of their TEXEL_READ views */
        d.format = d.kind == VRG_BUFFER ? VK_FORMAT_R32_UINT : VK_FORMAT_R16G16B16A16_SFLOAT;
    if (!(d.scale > 0))
        d.scale = 1.0f;
    return d;
}

/* groups_x = 0 derives every group count from the domain (dispatch.c);
 * otherwise an unset y or z is one group. */
vrg_dispatch_desc _vrg_dispatch_desc_defaults(const vrg_dispatch_desc *desc)
{
    vrg_dispatch_desc d = *desc;
    if (!d.groups_y)
        d.groups_y = 1;
    if (!d.groups_z)
        d.groups_z = 1;
    return d;
}
