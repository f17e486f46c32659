/* A reader for MagicaVoxel .vox files: models (SIZE/XYZI), the palette
 * (RGBA, or the default one), materials (MATL), and the scene graph
 * (nTRN/nGRP/nSHP/LAYR) flattened into instances. Pure C on a byte buffer:
 * no Vulkan, no files, so tests and the fuzzer feed it memory.
 *
 * Every size the file states is checked against the bytes that hold it
 * before anything is allocated, so no input allocates more than a small
 * multiple of its own length. */
#ifndef VOX_READ_H
#define VOX_READ_H

#include <stddef.h>
#include <stdint.h>

#define VOX_MAX_DIM 256 /* a model's side: voxel coordinates are bytes */
/* The most a MATL _emit material may emit, _emit x (1 + _flux): more is an
 * error (the scene multiplies it by 4, VRG_MATERIAL_EMISSIVE_MAX). */
#define VOX_EMIT_MAX 25

typedef struct vox_model {
    int size[3];           /* x, y, z (z up), each 1..VOX_MAX_DIM */
    int count;             /* voxels */
    const uint8_t *xyzi;   /* count x (x, y, z, palette index 1..255): points into the file's bytes */
} vox_model;

/* A model placed in MagicaVoxel's space (z up): voxel v of the model lands
 * at rot * (2v + 1 - size) / 2 + t, floored (the model's centre at t). */
typedef struct vox_instance {
    int model;
    int rot[3][3]; /* a signed permutation matrix */
    int t[3];
} vox_instance;

typedef struct vox_scene {
    uint32_t palette[256];  /* index i: R | G << 8 | B << 16 | A << 24; index 0 unused */
    float emissive[256];    /* MATL _type _emit: _emit (else _weight) x (1 + _flux), in 0..VOX_EMIT_MAX; else 0 */
    int model_count;
    vox_model *models;
    int instance_count;
    vox_instance *instances;
} vox_scene;

/* Parses data (size bytes; it must outlive the scene: models point into
 * it). name is the file's name for messages. Returns 0, or -1 with a
 * message "NAME: chunk 'ID' at byte OFFSET: what is wrong" in err. */
int vox_read(const uint8_t *data, size_t size, const char *name, vox_scene *out, char *err, size_t err_size);
void vox_free(vox_scene *s);

/* The palette MagicaVoxel uses when a file has no RGBA chunk. */
extern const uint32_t vox_default_palette[256];

#endif
