/* libFuzzer target: plugin descriptors built from the input bytes (names
 * from a small pool that includes NULL, empty, too long and malformed ones;
 * every numeric field free) through the loader's descriptor check. Whatever
 * the check accepts must keep the promises later phases rely on: names
 * valid and unique, ranges ordered and finite, defaults inside them. A
 * crash, a sanitizer report or a broken promise is a bug. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"
#include "plugin_loader.h"

typedef struct bytes {
    const uint8_t *p;
    size_t n;
} bytes;

static uint8_t take8(bytes *b)
{
    if (!b->n)
        return 0;
    b->n--;
    return *b->p++;
}

static double take_double(bytes *b)
{
    /* mostly small whole numbers and halves, sometimes any bit pattern */
    uint8_t mode = take8(b);
    if (mode < 200)
        return (double)((int)take8(b) - 128) / (mode & 1 ? 2.0 : 1.0);
    uint64_t bits = 0;
    for (int i = 0; i < 8; i++)
        bits = bits << 8 | take8(b);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

static const char *const names[] = {NULL, "", "a", "b", "gain", "a b", "x=y", "[s]", "semi;colon", "tab\tname",
                                    "a_name_that_is_exactly_sixty_three_characters_long_0123456789ab",
                                    "a_name_that_is_exactly_sixty_four_characters_long_0123456789abc"};
#define NAMES (sizeof names / sizeof names[0])

static void noop(vrg_pass *p, VkCommandBuffer c) { (void)p, (void)c; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    vrg_param_desc params[VRG_MAX_PARAMS + 2];
    vrg_slot_desc slots[VRG_MAX_SLOTS + 2];
    uint32_t np = take8(&b) % (VRG_MAX_PARAMS + 2), ns = take8(&b) % (VRG_MAX_SLOTS + 2);
    for (uint32_t i = 0; i < np; i++)
        params[i] = (vrg_param_desc){.name = names[take8(&b) % NAMES], .type = (vrg_param_type)(take8(&b) % 6), .default_value = take_double(&b),
                                     .min = take_double(&b), .max = take_double(&b), .flags = take8(&b) % 4};
    for (uint32_t i = 0; i < ns; i++)
        slots[i] = (vrg_slot_desc){.name = names[take8(&b) % NAMES], .dir = (vrg_slot_dir)(take8(&b) % 4), .kind = (vrg_resource_kind)(take8(&b) % 5),
                                   .access = (vrg_access)(take8(&b) % 16), .format = (VkFormat)(take8(&b) % 110)};
    uint8_t flags = take8(&b);
    vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = flags & 1 ? "p" : names[flags % NAMES], .kind = (vrg_plugin_kind)(flags >> 1 & 3),
                            .execute = flags & 8 ? NULL : noop, .params = flags & 16 ? NULL : params, .param_count = np,
                            .slots = flags & 32 ? NULL : slots, .slot_count = ns};
    _vrg_diag d = {.out = devnull, .file = "fuzz.ini"};
    if (_vrg_plugin_check_desc(&desc, "p", "/fuzz/p.so", &d, 1) != 0)
        return 0;
    for (uint32_t i = 0; i < desc.param_count; i++) {
        const vrg_param_desc *pd = &desc.params[i];
        if (!pd->name || !pd->name[0] || strlen(pd->name) >= VRG_NAME_MAX || strpbrk(pd->name, " \t=;#[]"))
            abort();
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(desc.params[j].name, pd->name) == 0)
                abort();
        if (pd->type < VRG_PARAM_FLOAT || pd->type > VRG_PARAM_STRING)
            abort();
        if (pd->type != VRG_PARAM_STRING &&
            (!isfinite(pd->default_value) || !isfinite(pd->min) || !isfinite(pd->max) || pd->min > pd->max ||
             ((pd->min != 0 || pd->max != 0) && (pd->default_value < pd->min || pd->default_value > pd->max))))
            abort();
    }
    for (uint32_t i = 0; i < desc.slot_count; i++)
        if (!desc.slots[i].name || !desc.slots[i].name[0])
            abort();
    return 0;
}
