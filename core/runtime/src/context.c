/* Vulkan context: instance (with validation + synchronization validation on
 * request), device choice (a real GPU first, lavapipe otherwise), features
 * the plugins can ask about, and debug names for everything we create. */
#define _GNU_SOURCE
#include <ctype.h>
#include <dlfcn.h>
#include <link.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <time.h>
#include <string.h>
#include "internal.h"

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
                                                    const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)type;
    vrg_context *ctx = user;
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
        return VK_FALSE;
    ctx->validation_errors++;
    fprintf(stderr, "validation %s: %s\n", severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
            data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

static int has_layer(const char *name)
{
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, NULL);
    VkLayerProperties *props = calloc(n ? n : 1, sizeof *props);
    vkEnumerateInstanceLayerProperties(&n, props);
    int found = 0;
    for (uint32_t i = 0; i < n; i++)
        found |= strcmp(props[i].layerName, name) == 0;
    free(props);
    return found;
}

static int has_device_ext(VkPhysicalDevice pd, const char *name)
{
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL);
    VkExtensionProperties *props = calloc(n ? n : 1, sizeof *props);
    vkEnumerateDeviceExtensionProperties(pd, NULL, &n, props);
    int found = 0;
    for (uint32_t i = 0; i < n; i++)
        found |= strcmp(props[i].extensionName, name) == 0;
    free(props);
    return found;
}

static int create_instance(vrg_context *ctx, const vrg_context_desc *desc)
{
    const char *layers[1] = {"VK_LAYER_KHRONOS_validation"};
    const char *exts[17] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    uint32_t next = 1;
    for (uint32_t i = 0; i < desc->instance_extension_count && next < 17; i++)
        exts[next++] = desc->instance_extensions[i];
    if (desc->validate && !has_layer(layers[0])) {
        fprintf(stderr, "error: validation (vrg_context_desc.validate) needs VK_LAYER_KHRONOS_validation (Debian package vulkan-validationlayers; run scripts/setup.sh)\n");
        return -1;
    }
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .pNext = desc->validate ? &features : NULL,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation,
        .pUserData = ctx,
    };
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "voxrg",
        .pEngineName = "voxrg",
        .apiVersion = VK_API_VERSION_1_3,
    };
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = &messenger,
        .pApplicationInfo = &app,
        .enabledLayerCount = desc->validate ? 1 : 0,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = next,
        .ppEnabledExtensionNames = exts,
    };
    VkResult res = vkCreateInstance(&info, NULL, &ctx->dev.instance);
    if (res != VK_SUCCESS) {
        fprintf(stderr, "error: vkCreateInstance failed (%d): is a Vulkan driver installed? (run scripts/setup.sh for lavapipe)\n", res);
        return -1;
    }
    PFN_vkCreateDebugUtilsMessengerEXT create =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->dev.instance, "vkCreateDebugUtilsMessengerEXT");
    messenger.pNext = NULL;
    if (create)
        create(ctx->dev.instance, &messenger, NULL, &ctx->messenger);
    ctx->set_name = (PFN_vkSetDebugUtilsObjectNameEXT)vkGetInstanceProcAddr(ctx->dev.instance, "vkSetDebugUtilsObjectNameEXT");
    return 0;
}

static int device_usable(VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    return p.apiVersion >= VK_API_VERSION_1_3 && has_device_ext(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
}

static int device_score(VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    switch (p.deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    default: return 1;
    }
}

static int contains_nocase(const char *hay, const char *needle)
{
    for (; *hay; hay++) {
        size_t i = 0;
        while (needle[i] && hay[i] && tolower((unsigned char)hay[i]) == tolower((unsigned char)needle[i]))
            i++;
        if (!needle[i])
            return 1;
    }
    return 0;
}

static int pick_device(vrg_context *ctx, const vrg_context_desc *desc)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(ctx->dev.instance, &n, NULL);
    if (n == 0) {
        fprintf(stderr, "error: no Vulkan device found (run scripts/setup.sh to install lavapipe)\n");
        return -1;
    }
    VkPhysicalDevice *pds = calloc(n, sizeof *pds);
    vkEnumeratePhysicalDevices(ctx->dev.instance, &n, pds);
    int pick = -1;
    if (desc->device) {
        char *end;
        long idx = strtol(desc->device, &end, 10);
        for (uint32_t i = 0; i < n && pick < 0; i++) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pds[i], &p);
            if ((*end == '\0' && idx == (long)i) || (*end != '\0' && contains_nocase(p.deviceName, desc->device)))
                pick = (int)i;
        }
        if (pick < 0) {
            fprintf(stderr, "error: device '%s' (vrg_context_desc.device) matches no device; devices:\n", desc->device);
            for (uint32_t i = 0; i < n; i++) {
                VkPhysicalDeviceProperties p;
                vkGetPhysicalDeviceProperties(pds[i], &p);
                fprintf(stderr, "  %u: %s\n", i, p.deviceName);
            }
        } else if (!device_usable(pds[pick])) {
            fprintf(stderr, "error: device '%s' lacks Vulkan 1.3 or VK_KHR_push_descriptor\n", desc->device);
            pick = -1;
        }
    } else {
        for (uint32_t i = 0; i < n; i++)
            if (device_usable(pds[i]) && (pick < 0 || device_score(pds[i]) > device_score(pds[pick])))
                pick = (int)i;
        if (pick < 0)
            fprintf(stderr, "error: no device with Vulkan 1.3 and VK_KHR_push_descriptor\n");
    }
    if (pick >= 0)
        ctx->dev.physical_device = pds[pick];
    free(pds);
    return pick >= 0 ? 0 : -1;
}

static int create_device(vrg_context *ctx)
{
    VkPhysicalDevice pd = ctx->dev.physical_device;
    vkGetPhysicalDeviceProperties(pd, &ctx->props);
    vkGetPhysicalDeviceMemoryProperties(pd, &ctx->mem_props);
    snprintf(ctx->device_name, sizeof ctx->device_name, "%s", ctx->props.deviceName);
    ctx->dev.name = ctx->device_name;

    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, NULL);
    VkQueueFamilyProperties *qf = calloc(nq ? nq : 1, sizeof *qf);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, qf);
    int family = -1;
    for (uint32_t i = 0; i < nq && family < 0; i++)
        if ((qf[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
            family = (int)i;
    for (uint32_t i = 0; i < nq && family < 0; i++)
        if (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT)
            family = (int)i;
    int ts_bits = family >= 0 ? (int)qf[family].timestampValidBits : 0;
    free(qf);
    if (family < 0) {
        fprintf(stderr, "error: device '%s' has no compute queue\n", ctx->device_name);
        return -1;
    }
    ctx->dev.queue_family = (uint32_t)family;

    /* Ask what exists, then enable what we use of it. */
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    VkPhysicalDeviceRayQueryFeaturesKHR rq = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR, .pNext = &rtp};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    VkPhysicalDeviceVulkan13Features v13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features v12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, .pNext = &v13};
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &v12};
    int has_rq = has_device_ext(pd, VK_KHR_RAY_QUERY_EXTENSION_NAME);
    int has_as = has_device_ext(pd, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                 has_device_ext(pd, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
    int has_rtp = has_device_ext(pd, VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
    if (has_as) {
        v13.pNext = &as;
        as.pNext = &rq; /* rq chains on to rtp; unknown structs are ignored by drivers lacking them */
    }
    vkGetPhysicalDeviceFeatures2(pd, &f2);
    if (!v13.synchronization2) {
        fprintf(stderr, "error: device '%s' lacks synchronization2\n", ctx->device_name);
        return -1;
    }
    has_as = has_as && as.accelerationStructure && v12.bufferDeviceAddress;
    has_rq = has_rq && has_as && rq.rayQuery;
    has_rtp = has_rtp && has_as && rtp.rayTracingPipeline;

    VkPhysicalDeviceFeatures2 en = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features en12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features en13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR en_as = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    VkPhysicalDeviceRayQueryFeaturesKHR en_rq = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR en_rtp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    en.pNext = &en12;
    en12.pNext = &en13;
    en.features.shaderStorageImageWriteWithoutFormat = f2.features.shaderStorageImageWriteWithoutFormat;
    en.features.shaderStorageImageReadWithoutFormat = f2.features.shaderStorageImageReadWithoutFormat;
    ctx->read_without_format = f2.features.shaderStorageImageReadWithoutFormat;
    en.features.shaderInt64 = f2.features.shaderInt64;
    en12.bufferDeviceAddress = v12.bufferDeviceAddress;
    en12.scalarBlockLayout = v12.scalarBlockLayout;
    en12.shaderInt8 = v12.shaderInt8;
    en12.storageBuffer8BitAccess = v12.storageBuffer8BitAccess;
    en12.uniformAndStorageBuffer8BitAccess = v12.uniformAndStorageBuffer8BitAccess;
    en12.hostQueryReset = v12.hostQueryReset;
    en13.synchronization2 = VK_TRUE;
    en13.maintenance4 = v13.maintenance4;
    const char *exts[12];
    uint32_t next = 0;
    exts[next++] = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    if (ctx->want_swapchain) {
        if (!has_device_ext(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) {
            fprintf(stderr, "error: device '%s' cannot present to a window (no VK_KHR_swapchain): use `voxrg render`\n", ctx->device_name);
            return -1;
        }
        exts[next++] = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    }
    if (has_as) {
        en13.pNext = &en_as;
        en_as.accelerationStructure = VK_TRUE;
        exts[next++] = VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME;
        exts[next++] = VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME;
        void **tail = &en_as.pNext;
        if (has_rq) {
            *tail = &en_rq;
            tail = &en_rq.pNext;
            en_rq.rayQuery = VK_TRUE;
            exts[next++] = VK_KHR_RAY_QUERY_EXTENSION_NAME;
        }
        if (has_rtp) {
            *tail = &en_rtp;
            en_rtp.rayTracingPipeline = VK_TRUE;
            exts[next++] = VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME;
        }
    }
    float prio = 1.0f;
    VkDeviceQueueCreateInfo qi = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = (uint32_t)family, .queueCount = 1, .pQueuePriorities = &prio};
    VkDeviceCreateInfo di = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &en,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &qi,
        .enabledExtensionCount = next,
        .ppEnabledExtensionNames = exts,
    };
    VkResult res = vkCreateDevice(pd, &di, NULL, &ctx->dev.device);
    if (res != VK_SUCCESS) {
        fprintf(stderr, "error: vkCreateDevice failed on '%s' (%d)\n", ctx->device_name, res);
        return -1;
    }
    vkGetDeviceQueue(ctx->dev.device, (uint32_t)family, 0, &ctx->dev.queue);
    ctx->push_descriptor = (PFN_vkCmdPushDescriptorSetKHR)vkGetDeviceProcAddr(ctx->dev.device, "vkCmdPushDescriptorSetKHR");
    if (has_as) {
        VkDevice d = ctx->dev.device;
        ctx->as.create = (PFN_vkCreateAccelerationStructureKHR)vkGetDeviceProcAddr(d, "vkCreateAccelerationStructureKHR");
        ctx->as.destroy = (PFN_vkDestroyAccelerationStructureKHR)vkGetDeviceProcAddr(d, "vkDestroyAccelerationStructureKHR");
        ctx->as.sizes = (PFN_vkGetAccelerationStructureBuildSizesKHR)vkGetDeviceProcAddr(d, "vkGetAccelerationStructureBuildSizesKHR");
        ctx->as.build = (PFN_vkCmdBuildAccelerationStructuresKHR)vkGetDeviceProcAddr(d, "vkCmdBuildAccelerationStructuresKHR");
        ctx->as.address = (PFN_vkGetAccelerationStructureDeviceAddressKHR)vkGetDeviceProcAddr(d, "vkGetAccelerationStructureDeviceAddressKHR");
    }

    vrg_features *f = &ctx->dev.features;
    f->ray_query = has_rq;
    f->acceleration_structure = has_as;
    f->ray_tracing_pipeline = has_rtp;
    f->timestamps = ts_bits > 0 && ctx->props.limits.timestampComputeAndGraphics;
    f->timestamp_period_ns = ctx->props.limits.timestampPeriod;
    VkPhysicalDeviceSubgroupProperties sg = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &sg};
    vkGetPhysicalDeviceProperties2(pd, &p2);
    f->subgroup_size = sg.subgroupSize;
    f->max_texel_buffer_texels = ctx->props.limits.maxTexelBufferElements;
    int cpu = ctx->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    ctx->group_size[0] = cpu && sg.subgroupSize >= 4 && sg.subgroupSize <= 64 ? sg.subgroupSize : 8;
    ctx->group_size[1] = cpu ? 1 : 8;
    /* the pixels of a group: as square as its invocations allow (4x2 for 8) */
    uint32_t lanes = ctx->group_size[0] * ctx->group_size[1], th = 1;
    while ((th * 2) * (th * 2) <= lanes)
        th *= 2;
    ctx->pixel_tile[0] = lanes / th;
    ctx->pixel_tile[1] = th;
    ctx->pixel_rows = cpu ? 32 : 1; /* tile rows per invocation: shader.c */
    return 0;
}

#ifdef VRG_SANITIZE_BUILD
/* Leak reports from inside the Vulkan driver and layers can only be matched
 * by the suppressions in tests/lsan.supp while those libraries are still
 * mapped; the loader unloads them at vkDestroyInstance, so pin them. */
static int pin_library(struct dl_phdr_info *info, size_t size, void *user)
{
    (void)size;
    (void)user;
    const char *n = info->dlpi_name;
    if (n && (strstr(n, "libvulkan_") || strstr(n, "VkLayer_") || strstr(n, "libLLVM") || strstr(n, "libgallium")))
        dlopen(n, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    return 0;
}
#endif

/* The one place the GPU timeout's default is resolved: the desc, then the
 * environment, then VRG_GPU_TIMEOUT_DEFAULT_S. */
static int resolve_gpu_timeout(const vrg_context_desc *desc, double *out)
{
    if (!(desc->gpu_timeout_s >= 0) || !isfinite(desc->gpu_timeout_s)) {
        fprintf(stderr, "error: vrg_context_desc.gpu_timeout_s = %g: expected seconds > 0 (0: the default)\n", desc->gpu_timeout_s);
        return -1;
    }
    *out = VRG_GPU_TIMEOUT_DEFAULT_S;
    const char *env = getenv("VOXRG_GPU_TIMEOUT");
    if (desc->gpu_timeout_s > 0)
        *out = desc->gpu_timeout_s;
    else if (env && *env) {
        char *end;
        double v = strtod(env, &end);
        if (*end || strpbrk(env, "xX") || !(v > 0) || !isfinite(v)) {
            fprintf(stderr, "error: VOXRG_GPU_TIMEOUT='%s': expected seconds > 0, e.g. 30\n", env);
            return -1;
        }
        *out = v;
    }
    return 0;
}

static volatile sig_atomic_t interrupt_requested;
void vrg_interrupt(void) { interrupt_requested = 1; }
int vrg_context_gpu_busy(const vrg_context *ctx) { return ctx && ctx->gpu_busy; }

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

_vrg_wait_result _vrg_wait_fence(vrg_context *ctx, VkFence fence, double *waited_s)
{
    /* slices short enough that an interrupt is seen at once */
    const uint64_t slice_ns = 50u * 1000u * 1000u;
    double start = seconds_now(), interrupted_at = -1;
    for (;;) {
        VkResult r = vkWaitForFences(ctx->dev.device, 1, &fence, VK_TRUE, slice_ns);
        double now = seconds_now();
        *waited_s = now - start;
        if (r == VK_SUCCESS)
            return VRG_WAIT_DONE;
        if (r != VK_TIMEOUT)
            return VRG_WAIT_FAILED;
        if (interrupt_requested && interrupted_at < 0)
            interrupted_at = now;
        int interrupted = interrupted_at >= 0 && now - interrupted_at >= VRG_INTERRUPT_GRACE_S;
        if (interrupted || *waited_s >= ctx->gpu_timeout_s) {
            ctx->gpu_busy = 1;
            return interrupted ? VRG_WAIT_INTERRUPTED : VRG_WAIT_TIMEOUT;
        }
    }
}

int vrg_context_create(const vrg_context_desc *desc, vrg_context **out)
{
    vrg_context_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    *out = NULL;
    double timeout;
    if (resolve_gpu_timeout(desc, &timeout) != 0)
        return -1;
    vrg_context *ctx = calloc(1, sizeof *ctx);
    ctx->gpu_timeout_s = timeout;
    ctx->validate = desc->validate;
    ctx->want_swapchain = desc->swapchain;
    *out = NULL;
    if (create_instance(ctx, desc) != 0 || pick_device(ctx, desc) != 0 || create_device(ctx) != 0) {
        vrg_context_destroy(ctx);
        return -1;
    }
#ifdef VRG_SANITIZE_BUILD
    dl_iterate_phdr(pin_library, NULL);
#endif
    VkCommandPoolCreateInfo pi = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = ctx->dev.queue_family,
    };
    vkCreateCommandPool(ctx->dev.device, &pi, NULL, &ctx->cmd_pool);
    VkSamplerCreateInfo si = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_LINEAR,
        .minFilter = VK_FILTER_LINEAR,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
    };
    vkCreateSampler(ctx->dev.device, &si, NULL, &ctx->sampler_linear);
    _vrg_name_object(ctx, VK_OBJECT_TYPE_SAMPLER, (uint64_t)ctx->sampler_linear, "voxrg linear clamp sampler");
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.maxLod = VK_LOD_CLAMP_NONE;
    vkCreateSampler(ctx->dev.device, &si, NULL, &ctx->sampler_mips);
    _vrg_name_object(ctx, VK_OBJECT_TYPE_SAMPLER, (uint64_t)ctx->sampler_mips, "voxrg nearest-texel trilinear-mip sampler");
    if (!desc->quiet) {
        const vrg_features *f = &ctx->dev.features;
        fprintf(stderr, "voxrg: device %s (ray query %s, acceleration structures %s, timestamps %s)%s\n", ctx->device_name,
                f->ray_query ? "yes" : "no", f->acceleration_structure ? "yes" : "no", f->timestamps ? "yes" : "no",
                desc->validate ? ", validation + synchronization validation on" : "");
        if (!f->ray_query)
            fprintf(stderr, "voxrg: note: no VK_KHR_ray_query on this device: shaders cannot trace acceleration structures\n");
    }
    *out = ctx;
    return 0;
}

void vrg_context_destroy(vrg_context *ctx)
{
    /* the device still runs work that may never end: waiting would block */
    if (!ctx || ctx->gpu_busy)
        return;
    if (ctx->dev.device) {
        vkDeviceWaitIdle(ctx->dev.device);
        vkDestroySampler(ctx->dev.device, ctx->sampler_linear, NULL);
        vkDestroySampler(ctx->dev.device, ctx->sampler_mips, NULL);
        vkDestroyCommandPool(ctx->dev.device, ctx->cmd_pool, NULL);
        vkDestroyDevice(ctx->dev.device, NULL);
    }
    if (ctx->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(ctx->dev.instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy)
            destroy(ctx->dev.instance, ctx->messenger, NULL);
    }
    if (ctx->dev.instance)
        vkDestroyInstance(ctx->dev.instance, NULL);
    free(ctx);
}

const vrg_device *vrg_context_device(const vrg_context *ctx) { return &ctx->dev; }
uint32_t vrg_context_validation_errors(const vrg_context *ctx) { return ctx->validation_errors; }

void _vrg_name_object(vrg_context *ctx, VkObjectType type, uint64_t handle, const char *fmt, ...)
{
    if (!ctx->set_name || !handle)
        return;
    char name[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(name, sizeof name, fmt, ap);
    va_end(ap);
    VkDebugUtilsObjectNameInfoEXT info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT, .objectType = type, .objectHandle = handle, .pObjectName = name};
    ctx->set_name(ctx->dev.device, &info);
}

int _vrg_find_memory_type(const vrg_context *ctx, uint32_t bits, VkMemoryPropertyFlags want)
{
    for (uint32_t i = 0; i < ctx->mem_props.memoryTypeCount; i++)
        if ((bits & (1u << i)) && (ctx->mem_props.memoryTypes[i].propertyFlags & want) == want)
            return (int)i;
    return -1;
}
