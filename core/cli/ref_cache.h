/* The reference frames' cache of voxrg compare: a folder, on this machine
 * or shared (NFS) by many processes and machines at once, of
 * content-addressed entries, each written whole under a unique temporary
 * name and renamed into place, and verified when read (docs/compare.md,
 * "The reference cache"). */
#ifndef VRG_CLI_REF_CACHE_H
#define VRG_CLI_REF_CACHE_H
#include <stddef.h>
#include <stdint.h>
#include "util.h"
#include "voxrg/camera.h"
#include "voxrg/plugin.h"
#include "voxrg/voxrg.h"

#define VRG_REF_HASH 32                  /* SHA-256 */
#define VRG_REF_KEY_HEX (2 * VRG_REF_HASH + 1) /* a key as hex, with its NUL */

typedef struct vrg_ref_file_hash vrg_ref_file_hash;

typedef struct vrg_ref_cache {
    char dir[VRG_CLI_PATH];
    uint8_t base[VRG_REF_HASH]; /* the hash of everything that decides every frame */
    vrg_ref_file_hash *files;   /* files hashed so far: the key's, then the entries' shaders */
    int file_count, key_files;  /* key_files: the first ones, hashed into base */
} vrg_ref_cache;

/* The folder: `given` (--cache), else $XDG_CACHE_HOME/voxrg/reference,
 * else ~/.cache/voxrg/reference. */
const char *vrg_ref_cache_dir(const char *given, char *buf, size_t cap);

/* The key's part shared by every frame: voxrg's version, the device and
 * its driver, the reference graph's text and its overrides, the size, and
 * the content of the runtime's and voxel layer's libraries and of every
 * file the graph (loaded, without a device: graph file, plugins, the
 * scene's data files) is built from. g is that graph. 0, or -1 after the
 * message. */
int vrg_ref_cache_open(vrg_ref_cache *c, const char *dir, const char *graph_path, const vrg_graph *g, const char *const *sets, int set_count,
                       const vrg_device *device, uint32_t width, uint32_t height);
void vrg_ref_cache_close(vrg_ref_cache *c);

/* A frame's key: the shared part, the path's frame number and time, and
 * the camera there. */
void vrg_ref_cache_key(const vrg_ref_cache *c, uint32_t frame, double seconds, const vrg_camera *cam, char key[VRG_REF_KEY_HEX]);

/* The entry of key: 0 with *rgb (width x height, RGB8) when it is whole,
 * this key's, its pixels match their checksum and the shaders it was
 * rendered with are unchanged; 1 when there is none or it must be
 * rendered again (a damaged or foreign entry is named in a warning);
 * -1 after an error (something that is not a regular file in its place). */
int vrg_ref_cache_read(vrg_ref_cache *c, const char *key, uint32_t width, uint32_t height, uint8_t **rgb);

/* Writes the entry of key, rendered by g (its shaders are recorded), whole
 * or not at all. One that cannot be written is only not cached (a warning). */
void vrg_ref_cache_write(vrg_ref_cache *c, const char *key, const vrg_graph *g, const uint8_t *rgb, uint32_t width, uint32_t height);

#endif
