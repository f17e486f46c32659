/* The ray-query backend's data: one bottom-level acceleration structure per
 * chunk, built from the faces between solid blocks and air, and a top-level
 * one with an instance per chunk. See voxrg/world.h. */
#include <stdlib.h>
#include <string.h>
#include "voxel_internal.h"

typedef struct chunk_blas {
    VkAccelerationStructureKHR as;
    VkBuffer buffer;
    VkDeviceMemory memory;
    VkDeviceAddress address;
    int quads;
    int chunk[3];
} chunk_blas;

/* The BLASes of a world's chunks. Their memory is their own, not a pass's:
 * the backends of the graph instances a hot reload keeps the world across
 * share them (reference-counted), and the last to go frees them. */
typedef struct blas_set {
    int refs;
    vrg_world *world;
    int slots;
    chunk_blas *blas; /* per slot */
    VkDevice device;
    VkPhysicalDeviceMemoryProperties memory;
    /* VK_KHR_acceleration_structure's commands, from the pass's device */
    PFN_vkCreateAccelerationStructureKHR create_as;
    PFN_vkDestroyAccelerationStructureKHR destroy_as;
    PFN_vkGetAccelerationStructureBuildSizesKHR build_sizes;
    PFN_vkCmdBuildAccelerationStructuresKHR cmd_build;
    PFN_vkGetAccelerationStructureDeviceAddressKHR as_address;
} blas_set;

/* One graph instance's backend: what it builds with, per frame. */
struct vrg_world_accel {
    vrg_pass *pass;
    blas_set *set;
    int *changed;
    /* per-frame host data, rings (earlier frames may still build from
     * theirs): triangle vertices of rebuilt chunks, instances */
    vrg_ring *vertices, *instances;
    VkBuffer scratch;
    VkDeviceAddress scratch_address;
    uint64_t scratch_bytes;
    VkDeviceSize scratch_align;
};

static void *buffer(vrg_world_accel *a, const char *name, uint64_t size, VkBufferUsageFlags usage, int host, VkBuffer *b, VkDeviceAddress *addr)
{
    vrg_buffer_desc d = {.name = name, .size = size, .usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, .host_visible = host};
    return vrg_pass_buffer(a->pass, &d, b, addr);
}

/* A BLAS and its storage, destroyed at once (the GPU is idle) or once no
 * frame in flight traces it. */
typedef struct retired_blas {
    PFN_vkDestroyAccelerationStructureKHR destroy;
    VkDevice device;
    chunk_blas blas;
} retired_blas;

static void destroy_blas(PFN_vkDestroyAccelerationStructureKHR destroy, VkDevice device, const chunk_blas *b)
{
    if (b->as)
        destroy(device, b->as, NULL);
    vkDestroyBuffer(device, b->buffer, NULL);
    vkFreeMemory(device, b->memory, NULL);
}

static void destroy_retired_blas(void *user)
{
    retired_blas *r = user;
    destroy_blas(r->destroy, r->device, &r->blas);
    free(r);
}

static blas_set *blas_set_create(const vrg_device *dev, vrg_world *world)
{
    blas_set *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    t->refs = 1;
    t->device = dev->device;
    vkGetPhysicalDeviceMemoryProperties(dev->physical_device, &t->memory);
    t->create_as = (PFN_vkCreateAccelerationStructureKHR)vkGetDeviceProcAddr(dev->device, "vkCreateAccelerationStructureKHR");
    t->destroy_as = (PFN_vkDestroyAccelerationStructureKHR)vkGetDeviceProcAddr(dev->device, "vkDestroyAccelerationStructureKHR");
    t->build_sizes = (PFN_vkGetAccelerationStructureBuildSizesKHR)vkGetDeviceProcAddr(dev->device, "vkGetAccelerationStructureBuildSizesKHR");
    t->cmd_build = (PFN_vkCmdBuildAccelerationStructuresKHR)vkGetDeviceProcAddr(dev->device, "vkCmdBuildAccelerationStructuresKHR");
    t->as_address = (PFN_vkGetAccelerationStructureDeviceAddressKHR)vkGetDeviceProcAddr(dev->device, "vkGetAccelerationStructureDeviceAddressKHR");
    t->world = world;
    t->slots = vrg_world_slot_count(world);
    t->blas = calloc((size_t)t->slots, sizeof *t->blas);
    if (!t->blas) {
        free(t);
        return NULL;
    }
    return t;
}

/* The last user's destroy(): the graph waited for the GPU before it. */
static void blas_set_release(blas_set *t)
{
    if (!t || --t->refs > 0)
        return;
    for (int s = 0; s < t->slots; s++)
        destroy_blas(t->destroy_as, t->device, &t->blas[s]);
    free(t->blas);
    free(t);
}

/* A backend of `pass` building into `set` (whose reference it takes over). */
static vrg_world_accel *accel_for(vrg_pass *pass, blas_set *set)
{
    const vrg_device *dev = vrg_pass_device(pass);
    vrg_world_accel *a = calloc(1, sizeof *a);
    if (!a) {
        blas_set_release(set);
        vrg_pass_error(pass, "out of memory for the ray-query backend");
        return NULL;
    }
    a->pass = pass;
    a->set = set;
    a->changed = calloc((size_t)set->slots, sizeof *a->changed);
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &asp};
    vkGetPhysicalDeviceProperties2(dev->physical_device, &p2);
    a->scratch_align = asp.minAccelerationStructureScratchOffsetAlignment ? asp.minAccelerationStructureScratchOffsetAlignment : 256;
    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    a->instances = vrg_pass_host_ring(pass, "tlas instances", (uint64_t)set->slots * sizeof(VkAccelerationStructureInstanceKHR), input);
    a->vertices = a->instances ? vrg_pass_host_ring(pass, "blas vertices", 16, input) : NULL; /* grows with the first frame's chunks */
    if (!a->vertices || !a->changed) {
        vrg_world_accel_destroy(a);
        return NULL;
    }
    return a;
}

vrg_world_accel *vrg_world_accel_create(vrg_pass *pass, vrg_world *world)
{
    const vrg_device *dev = vrg_pass_device(pass);
    if (!dev || !dev->features.acceleration_structure || !dev->features.ray_query) {
        vrg_pass_error(pass, "the ray-query backend needs VK_KHR_acceleration_structure and VK_KHR_ray_query, which '%s' lacks",
                       dev ? dev->name : "(no device)");
        return NULL;
    }
    blas_set *set = blas_set_create(dev, world);
    if (!set) {
        vrg_pass_error(pass, "out of memory for the ray-query backend");
        return NULL;
    }
    return accel_for(pass, set);
}

vrg_world_accel *_vrg_world_accel_share(vrg_pass *pass, vrg_world_accel *previous)
{
    previous->set->refs++;
    return accel_for(pass, previous->set);
}

void vrg_world_accel_destroy(vrg_world_accel *a)
{
    if (!a)
        return;
    /* the rings and scratch belong to the pass: the runtime frees them with it */
    blas_set_release(a->set);
    free(a->changed);
    free(a);
}

/* Storage for a BLAS: device-local, with a device address. */
static int blas_storage(vrg_world_accel *a, VkDeviceSize bytes, chunk_blas *b, const char *name)
{
    blas_set *t = a->set;
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                             .size = bytes,
                             .usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT};
    if (vkCreateBuffer(t->device, &bi, NULL, &b->buffer) != VK_SUCCESS)
        return vrg_pass_error(a->pass, "cannot create the buffer of %s (%llu bytes)", name, (unsigned long long)bytes);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(t->device, b->buffer, &req);
    int type = -1;
    for (uint32_t i = 0; i < t->memory.memoryTypeCount && type < 0; i++)
        if ((req.memoryTypeBits >> i & 1) && (t->memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = (int)i;
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO, .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .pNext = &flags, .allocationSize = req.size, .memoryTypeIndex = (uint32_t)type};
    if (type < 0 || vkAllocateMemory(t->device, &ai, NULL, &b->memory) != VK_SUCCESS || vkBindBufferMemory(t->device, b->buffer, b->memory, 0) != VK_SUCCESS)
        return vrg_pass_error(a->pass, "out of device memory for %s (%llu bytes)", name, (unsigned long long)bytes);
    vrg_pass_name_object(a->pass, VK_OBJECT_TYPE_BUFFER, (uint64_t)b->buffer, name);
    return 0;
}

/* Morton order of a voxel inside its chunk (4 bits per axis). */
static uint32_t morton16(int x, int y, int z)
{
    uint32_t m = 0;
    for (int b = 0; b < 4; b++)
        m |= ((uint32_t)(x >> b & 1) << (3 * b)) | ((uint32_t)(y >> b & 1) << (3 * b + 1)) | ((uint32_t)(z >> b & 1) << (3 * b + 2));
    return m;
}

static int by_key(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

static const int face_dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

/* Exposed faces of a chunk as quad keys: morton << 3 | face, sorted. */
static int chunk_quads(const vrg_world *w, const int c[3], uint32_t *keys)
{
    const vrg_block *blocks = vrg_world_chunk(w, c[0], c[1], c[2]);
    int n = 0;
    for (int y = 0; y < 16; y++)
        for (int z = 0; z < 16; z++)
            for (int x = 0; x < 16; x++) {
                if (blocks[vrg_chunk_index(x, y, z)] == VRG_BLOCK_AIR)
                    continue;
                for (int f = 0; f < 6; f++) {
                    int nx = x + face_dir[f][0], ny = y + face_dir[f][1], nz = z + face_dir[f][2];
                    vrg_block nb = (nx | ny | nz) & ~15 ? vrg_world_block(w, c[0] * 16 + nx, c[1] * 16 + ny, c[2] * 16 + nz)
                                                       : blocks[vrg_chunk_index(nx, ny, nz)];
                    if (nb == VRG_BLOCK_AIR)
                        keys[n++] = morton16(x, y, z) << 3 | (uint32_t)f;
                }
            }
    qsort(keys, (size_t)n, sizeof *keys, by_key);
    return n;
}

/* Two triangles of a face, chunk-local coordinates, 18 floats. */
static void quad_vertices(uint32_t key, float *out)
{
    int f = key & 7, x = 0, y = 0, z = 0;
    uint32_t m = key >> 3;
    for (int b = 0; b < 4; b++) {
        x |= (int)((m >> (3 * b)) & 1) << b;
        y |= (int)((m >> (3 * b + 1)) & 1) << b;
        z |= (int)((m >> (3 * b + 2)) & 1) << b;
    }
    int axis = f / 2, positive = f % 2 == 0;
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    float corner[4][3];
    for (int k = 0; k < 4; k++) {
        float p[3] = {(float)x, (float)y, (float)z};
        p[axis] += positive ? 1.0f : 0.0f;
        p[u] += (k == 1 || k == 2) ? 1.0f : 0.0f;
        p[v] += (k >= 2) ? 1.0f : 0.0f;
        memcpy(corner[k], p, sizeof p);
    }
    static const int tri[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++)
        memcpy(out + 3 * i, corner[tri[i]], 3 * sizeof(float));
}

static VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

int vrg_world_accel_record(vrg_world_accel *a, VkCommandBuffer cmd, const char *tlas_slot)
{
    blas_set *t = a->set;
    VkDevice dev = t->device;
    int nchanged = vrg_world_take_mesh_changes(t->world, a->changed, t->slots);
    size_t cap = nchanged > 0 ? (size_t)nchanged : 1;
    uint32_t *keys = malloc(16 * 16 * 16 * 6 * sizeof *keys);

    /* 1. meshes of changed chunks: count, then write into this frame's vertex memory */
    int *quads = calloc(cap, sizeof *quads);
    uint64_t total = 0;
    for (int i = 0; i < nchanged; i++) {
        int c[3];
        quads[i] = vrg_world_slot_chunk(t->world, a->changed[i], c) ? chunk_quads(t->world, c, keys) : 0;
        total += (uint64_t)quads[i];
    }
    uint64_t vbytes = total * 18 * sizeof(float);
    vrg_ring_slice vslice = vrg_pass_ring_slice(a->pass, a->vertices, vbytes);
    vrg_ring_slice islice = vrg_pass_ring_slice(a->pass, a->instances, (uint64_t)t->slots * sizeof(VkAccelerationStructureInstanceKHR));
    if (!vslice.map || !islice.map) {
        free(keys);
        free(quads);
        return -1;
    }
    /* 2. one BLAS per changed chunk with faces */
    VkAccelerationStructureGeometryKHR *geoms = calloc(cap, sizeof *geoms);
    VkAccelerationStructureBuildGeometryInfoKHR *infos = calloc(cap, sizeof *infos);
    VkAccelerationStructureBuildRangeInfoKHR *ranges = calloc(cap, sizeof *ranges);
    const VkAccelerationStructureBuildRangeInfoKHR **range_ptrs = calloc(cap, sizeof *range_ptrs);
    VkDeviceSize *scratch_offsets = calloc(cap + 1, sizeof *scratch_offsets);
    uint64_t voff = 0;
    VkDeviceSize scratch_total = 0;
    int nbuild = 0, rc = 0;
    for (int i = 0; i < nchanged && rc == 0; i++) {
        int s = a->changed[i];
        chunk_blas *b = &t->blas[s];
        if (b->as || b->buffer) { /* earlier frames in flight may still trace it */
            retired_blas *r = malloc(sizeof *r); /* before anything is freed: a failure leaves the BLAS whole */
            if (!r) {
                rc = vrg_pass_error(a->pass, "out of memory retiring the BLAS of chunk slot %d", s);
                break;
            }
            *r = (retired_blas){t->destroy_as, dev, *b};
            if (vrg_pass_defer(a->pass, destroy_retired_blas, r) != 0) {
                free(r);
                rc = -1;
                break;
            }
            memset(b, 0, sizeof *b);
        }
        int c[3];
        if (!quads[i] || !vrg_world_slot_chunk(t->world, s, c))
            continue;
        int n = chunk_quads(t->world, c, keys);
        float *v = (float *)vslice.map + voff / sizeof(float);
        for (int q = 0; q < n; q++)
            quad_vertices(keys[q], v + 18 * q);
        VkAccelerationStructureGeometryKHR *g = &geoms[nbuild];
        *g = (VkAccelerationStructureGeometryKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
            .geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR,
            .flags = VK_GEOMETRY_OPAQUE_BIT_KHR,
            .geometry.triangles = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
                                   .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
                                   .vertexData.deviceAddress = vslice.address + voff,
                                   .vertexStride = 3 * sizeof(float),
                                   .maxVertex = (uint32_t)(6 * n - 1),
                                   .indexType = VK_INDEX_TYPE_NONE_KHR},
        };
        VkAccelerationStructureBuildGeometryInfoKHR *info = &infos[nbuild];
        *info = (VkAccelerationStructureBuildGeometryInfoKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
            .type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
            .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
            .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
            .geometryCount = 1,
            .pGeometries = g,
        };
        uint32_t tris = (uint32_t)(2 * n);
        VkAccelerationStructureBuildSizesInfoKHR sizes = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
        t->build_sizes(dev, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, info, &tris, &sizes);
        char name[64];
        snprintf(name, sizeof name, "blas %d %d %d", c[0], c[1], c[2]);
        if (blas_storage(a, sizes.accelerationStructureSize, b, name) != 0) {
            rc = -1;
            break;
        }
        VkAccelerationStructureCreateInfoKHR ci = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
                                                   .buffer = b->buffer,
                                                   .size = sizes.accelerationStructureSize,
                                                   .type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR};
        if (t->create_as(dev, &ci, NULL, &b->as) != VK_SUCCESS) {
            rc = vrg_pass_error(a->pass, "cannot create the BLAS of chunk %d %d %d", c[0], c[1], c[2]);
            break;
        }
        vrg_pass_name_object(a->pass, VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, (uint64_t)b->as, name);
        VkAccelerationStructureDeviceAddressInfoKHR ai = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR, .accelerationStructure = b->as};
        b->address = t->as_address(dev, &ai);
        b->quads = n;
        memcpy(b->chunk, c, sizeof c);
        info->dstAccelerationStructure = b->as;
        scratch_offsets[nbuild] = scratch_total;
        scratch_total = align_up(scratch_total + sizes.buildScratchSize, a->scratch_align);
        ranges[nbuild] = (VkAccelerationStructureBuildRangeInfoKHR){.primitiveCount = tris};
        range_ptrs[nbuild] = &ranges[nbuild];
        voff += (uint64_t)n * 18 * sizeof(float);
        nbuild++;
    }

    /* 3. TLAS: every slot with a BLAS, translated to its chunk */
    uint32_t ninst = 0;
    for (int s = 0; s < t->slots; s++) {
        chunk_blas *b = &t->blas[s];
        if (!b->as)
            continue;
        VkAccelerationStructureInstanceKHR *in = (VkAccelerationStructureInstanceKHR *)islice.map + ninst++;
        memset(in, 0, sizeof *in);
        in->transform.matrix[0][0] = in->transform.matrix[1][1] = in->transform.matrix[2][2] = 1.0f;
        in->transform.matrix[0][3] = (float)(b->chunk[0] * 16);
        in->transform.matrix[1][3] = (float)(b->chunk[1] * 16);
        in->transform.matrix[2][3] = (float)(b->chunk[2] * 16);
        in->instanceCustomIndex = (uint32_t)s;
        in->mask = 0xff;
        in->flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR | VK_GEOMETRY_INSTANCE_FORCE_OPAQUE_BIT_KHR;
        in->accelerationStructureReference = b->address;
    }
    VkAccelerationStructureGeometryKHR tgeom = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .geometry.instances = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR, .data.deviceAddress = islice.address},
    };
    VkAccelerationStructureBuildGeometryInfoKHR tinfo = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .dstAccelerationStructure = vrg_res_accel(a->pass, vrg_pass_res(a->pass, tlas_slot)),
        .geometryCount = 1,
        .pGeometries = &tgeom,
    };
    VkAccelerationStructureBuildSizesInfoKHR tsizes = {.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    uint32_t max_inst = (uint32_t)t->slots;
    t->build_sizes(dev, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &tinfo, &max_inst, &tsizes);
    VkDeviceSize tlas_scratch = 0;
    VkDeviceSize need = align_up(scratch_total, a->scratch_align) + tsizes.buildScratchSize + a->scratch_align;
    if (rc == 0 && need > a->scratch_bytes) {
        if (a->scratch)
            vrg_pass_free_buffer(a->pass, a->scratch);
        a->scratch_bytes = need + need / 4;
        if (!buffer(a, "as scratch", a->scratch_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 0, &a->scratch, &a->scratch_address))
            rc = -1;
    }
    if (rc == 0 && tinfo.dstAccelerationStructure) {
        VkDeviceAddress base = align_up(a->scratch_address, a->scratch_align);
        /* last frame's builds used the same scratch: order them before these */
        VkMemoryBarrier2 reuse = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                  .srcStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                  .srcAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                                  .dstStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                  .dstAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR};
        VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &reuse};
        vkCmdPipelineBarrier2(cmd, &dep);
        if (nbuild) {
            for (int i = 0; i < nbuild; i++)
                infos[i].scratchData.deviceAddress = base + scratch_offsets[i];
            t->cmd_build(cmd, (uint32_t)nbuild, infos, range_ptrs);
            /* the TLAS build reads the BLASes just written */
            vkCmdPipelineBarrier2(cmd, &dep);
        }
        tlas_scratch = align_up(scratch_total, a->scratch_align);
        tinfo.scratchData.deviceAddress = base + tlas_scratch;
        VkAccelerationStructureBuildRangeInfoKHR trange = {.primitiveCount = ninst};
        const VkAccelerationStructureBuildRangeInfoKHR *tr = &trange;
        t->cmd_build(cmd, 1, &tinfo, &tr);
    }
    free(keys);
    free(quads);
    free(geoms);
    free(infos);
    free(ranges);
    free(range_ptrs);
    free(scratch_offsets);
    vrg_pass_stat(a->pass, "blas_built", nbuild);
    vrg_pass_stat(a->pass, "tlas_instances", ninst);
    double all = 0;
    for (int s2 = 0; s2 < t->slots; s2++)
        all += t->blas[s2].quads;
    vrg_pass_stat(a->pass, "blas_quads", all);
    return rc;
}
