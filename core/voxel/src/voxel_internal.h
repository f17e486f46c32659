/* What libvoxrg_voxel's sources share and do not export (the library is
 * built with -fvisibility=hidden: only world.h's block is public). */
#ifndef VOXRG_VOXEL_INTERNAL_H
#define VOXRG_VOXEL_INTERNAL_H

#include "voxrg/world.h"

/* In create(): a backend for `pass` that builds into the BLASes of
 * `previous` (the backend of the instance a hot reload replaces, on the
 * same world) instead of its own: no chunk is built again. Each backend's
 * vrg_world_accel_destroy releases its share. NULL after an error. */
vrg_world_accel *_vrg_world_accel_share(vrg_pass *pass, vrg_world_accel *previous);

#endif
