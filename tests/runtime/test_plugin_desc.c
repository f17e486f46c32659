/* The loader's descriptor checks, case by case: every malformed parameter or
 * slot table is refused with a message naming the plugin's file and what is
 * wrong, and well-formed ones pass. No device, no files: the descriptors are
 * built here and handed to the check the loader runs on every plugin. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "internal.h"
#include "plugin_loader.h"

static int failures;

static void noop(vrg_pass *p, VkCommandBuffer c) { (void)p, (void)c; }

/* Runs the check; `want` NULL: must pass, else must fail with `want` in the message. */
static void expect(const char *what, const vrg_plugin_desc *desc, const char *want)
{
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    _vrg_diag d = {.out = mem, .file = "t.ini"};
    int rc = _vrg_plugin_check_desc(desc, "p", "/plugins/p.so", &d, 3);
    fclose(mem);
    int ok = want ? rc != 0 && strstr(text, want) && strstr(text, "/plugins/p.so") && strstr(text, "t.ini:3:") : rc == 0 && len == 0;
    CHECK(ok, "%s: rc %d, want %s '%s', got:\n%s", what, rc, want ? "an error with" : "no error", want ? want : "", text);
    free(text);
}

#define PARAMS(...)                                                                                  \
    (const vrg_param_desc[]){__VA_ARGS__}, sizeof((const vrg_param_desc[]){__VA_ARGS__}) / sizeof(vrg_param_desc)

static void with_params(const char *what, const vrg_param_desc *params, uint32_t count, const char *want)
{
    vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = "p", .kind = VRG_PLUGIN_PASS, .execute = noop, .params = params, .param_count = count};
    expect(what, &desc, want);
}

int main(void)
{
    with_params("good", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .default_value = 0.5, .max = 1}, {.name = "b", .type = VRG_PARAM_INT, .default_value = 3},
                               {.name = "c", .type = VRG_PARAM_BOOL, .default_value = 1, .max = 1},
                               {.name = "d", .type = VRG_PARAM_STRING, .flags = VRG_PARAM_REPEATABLE}), NULL);
    with_params("NULL name", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT}, {.name = NULL, .type = VRG_PARAM_FLOAT}), "parameter 1 has a NULL name");
    with_params("empty name", PARAMS({.name = "", .type = VRG_PARAM_FLOAT}), "parameter 0 has an invalid name");
    with_params("name with '='", PARAMS({.name = "a=b", .type = VRG_PARAM_FLOAT}), "parameter 0 has an invalid name");
    with_params("name with a space", PARAMS({.name = "a b", .type = VRG_PARAM_FLOAT}), "parameter 0 has an invalid name");
    with_params("64-char name", PARAMS({.name = "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", .type = VRG_PARAM_FLOAT}),
                "parameter 0 has an invalid name");
    with_params("duplicate", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT}, {.name = "a", .type = VRG_PARAM_INT}), "two parameters named 'a' (0 and 1)");
    with_params("named plugin", PARAMS({.name = "plugin", .type = VRG_PARAM_FLOAT}), "parameter 'plugin' has a name the graph file keeps for itself");
    with_params("named output_scale", PARAMS({.name = "output_scale", .type = VRG_PARAM_FLOAT}), "parameter 'output_scale' has a name the graph file keeps");
    with_params("named in.x", PARAMS({.name = "in.x", .type = VRG_PARAM_FLOAT}), "parameter 'in.x' has a name the graph file keeps");
    with_params("named out.x", PARAMS({.name = "out.x", .type = VRG_PARAM_FLOAT}), "parameter 'out.x' has a name the graph file keeps");
    with_params("min > max", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .default_value = 1, .min = 2, .max = 1}), "parameter 'a' min 2 is greater than max 1");
    with_params("unknown type", PARAMS({.name = "a", .type = (vrg_param_type)9}), "parameter 'a' type 9 is none of");
    with_params("type 0", PARAMS({.name = "a"}), "parameter 'a' type 0 is none of");
    with_params("default above max", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .default_value = 5, .max = 1}), "default 5 lies outside [0, 1]");
    with_params("default below min", PARAMS({.name = "a", .type = VRG_PARAM_INT, .default_value = -1, .min = 0, .max = 4}), "default -1 lies outside [0, 4]");
    with_params("NaN default", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .default_value = NAN}), "must be finite numbers");
    with_params("infinite max", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .max = INFINITY}), "must be finite numbers");
    with_params("fractional int", PARAMS({.name = "a", .type = VRG_PARAM_INT, .default_value = 1.5, .max = 4}), "whole-number default, min and max");
    with_params("bool default 2", PARAMS({.name = "a", .type = VRG_PARAM_BOOL, .default_value = 2}), "a bool's default is 0 or 1");
    with_params("repeatable float", PARAMS({.name = "a", .type = VRG_PARAM_FLOAT, .flags = VRG_PARAM_REPEATABLE}), "is repeatable but not a string");
    with_params("unknown flag", PARAMS({.name = "a", .type = VRG_PARAM_STRING, .flags = 1u << 7}), "has unknown flags 0x80");
    with_params("NULL table", NULL, 2, "param_count is set but params is NULL");
    static vrg_param_desc many[VRG_MAX_PARAMS + 1];
    with_params("too many", many, VRG_MAX_PARAMS + 1, "65 parameters, more than the 64");

    vrg_slot_desc slot_null = {.name = NULL, .dir = VRG_OUT, .kind = VRG_IMAGE, .access = VRG_ACCESS_STORAGE_WRITE};
    vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = "p", .kind = VRG_PLUGIN_PASS, .execute = noop, .slots = &slot_null, .slot_count = 1};
    expect("slot with a NULL name", &desc, "slot 0 is malformed");
    desc.slot_count = VRG_MAX_SLOTS + 1;
    expect("too many slots", &desc, "33 slots, more than the 32");
    desc = (vrg_plugin_desc){.abi_version = VRG_ABI_VERSION, .name = "p", .kind = VRG_PLUGIN_PASS, .execute = noop, .dispatch_count = 2};
    expect("listed dispatches NULL", &desc, "dispatch_count is set but dispatches is NULL");
    const vrg_dispatch_desc listed[] = {{.shader = "a.comp"}, {.shader = NULL}};
    desc.dispatches = listed;
    expect("a listed dispatch without a shader", &desc, "listed dispatch 1 names no shader");
    desc.dispatch_count = 1;
    expect("listed dispatches", &desc, NULL);
    desc.dispatch_count = VRG_MAX_DISPATCHES + 1;
    expect("too many listed dispatches", &desc, "257 listed dispatches, more than the 256");
    desc = (vrg_plugin_desc){.abi_version = VRG_ABI_VERSION, .name = "q", .kind = VRG_PLUGIN_PASS, .execute = noop};
    expect("name differs from the file's", &desc, "its descriptor's name differs from its file name");
    desc.name = NULL;
    expect("NULL plugin name", &desc, "its descriptor's name differs from its file name");
    printf("plugin_desc: %s\n", failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
