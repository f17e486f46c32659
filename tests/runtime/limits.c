#define _POSIX_C_SOURCE 200809L
/* Tables past their old fixed sizes (history images, uses of a resource,
 * aliases) and how dispatches are sized and limited.
 * Usage: PROGRAM CASE (ctest registers one test per case). */
#include "harness.h"

/* More history images than one barrier batch holds, all cleared in the same
 * frame (the first, and after a reset): every clear gets its barrier (a
 * missing one is a validation error) and every counter counts from 1. */
static void test_history_many(void)
{
    enum { COUNTERS = 70 };
    char *text = NULL, names[COUNTERS][16];
    const char *reads[COUNTERS];
    size_t len = 0;
    append(&text, &len, "[graph]\nname = history_many\noutput = c0\nwidth = 8\nheight = 8\n");
    for (int i = 0; i < COUNTERS; i++) {
        append(&text, &len, "[pass n%d]\nplugin = counter\nalways_read = 1\nin.prev = c%d@prev\nout.count = c%d\n", i, i, i);
        snprintf(names[i], sizeof names[i], "c%d", i);
        reads[i] = names[i];
    }
    vrg_graph *g = load_text(text, reads, COUNTERS);
    free(text);
    if (!g)
        return;
    for (int round = 0; round < 2; round++) {
        if (round)
            vrg_graph_reset_history(g);
        for (int frame = 1; frame <= 2; frame++) {
            CHECK(vrg_graph_frame(g) == 0, "frame failed");
            for (int i = 0; i < COUNTERS; i += COUNTERS - 1) {
                vrg_image_data img;
                CHECK(vrg_graph_read(g, names[i], &img) == 0, "readback of %s failed", names[i]);
                CHECK(px(&img, 7, 7, 0) == (float)frame, "round %d frame %d: %s is %g", round, frame, names[i], px(&img, 7, 7, 0));
                free(img.pixels);
            }
        }
    }
    vrg_graph_destroy(g);
}

/* A pass with more internal images than a barrier batch, all in one
 * vrg_pass_use (a dropped barrier leaves an image in the wrong layout for its
 * clear: a validation error), and more figures than there once was room for,
 * with names longer than 31 characters. */
static void test_many_uses(void)
{
    vrg_graph *g = load_text("[graph]\nname = many_uses\noutput = out\nwidth = 16\nheight = 16\n"
                             "[pass m]\nplugin = many_uses\nimages = 70\nfigures = 20\nout.color = out\n",
                             NULL, 0);
    if (!g)
        return;
    for (int frame = 0; frame < 2; frame++)
        CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, "out", &img) == 0, "readback failed");
    CHECK(px(&img, 3, 3, 0) == 70.0f, "output is %g, not 70", px(&img, 3, 3, 0));
    free(img.pixels);
    for (int i = 0; i < 20; i++) {
        char name[96];
        double v = -1;
        snprintf(name, sizeof name, "figure_named_at_length_beyond_thirty_one_characters_%d", i);
        CHECK(vrg_graph_stat(g, "m", name, &v) == 0 && v == i, "figure %d: %s, %g", i, name, v);
    }
    vrg_graph_destroy(g);
}

/* One image (big) placed over more than 64 earlier ones whose lifetimes
 * ended before it starts; only the last few of them are written. Its first
 * use must wait for those writes (the aliasing barrier), or synchronization
 * validation reports a hazard. */
static void test_alias_many(void)
{
    vrg_graph *g = load_text("[graph]\nname = alias_many\noutput = sum\nwidth = 128\nheight = 128\n"
                             "[pass m]\nplugin = many_uses\nimages = 70\nwritten = 6\nscale = 0.0625\nfigures = 0\nout.color = small\n"
                             "[pass gen]\nplugin = pattern\nout.color = big\n"
                             "[pass s]\nplugin = add\nin.a = small\nin.b = big\nout.sum = sum\n",
                             NULL, 0);
    if (!g)
        return;
    int big_block, block;
    uint64_t big_offset, big_size, offset, size;
    CHECK(vrg_graph_placement(g, "big", &big_block, &big_offset, &big_size) == 0, "no placement of big");
    for (int i = 0; i < 70; i++) {
        char name[32];
        snprintf(name, sizeof name, "m.t%d", i);
        CHECK(vrg_graph_placement(g, name, &block, &offset, &size) == 0 && block == big_block && offset >= big_offset &&
                  offset + size <= big_offset + big_size,
              "%s (block %d, %llu + %llu) is not inside big's memory (block %d, %llu + %llu): the test proves nothing", name, block,
              (unsigned long long)offset, (unsigned long long)size, big_block, (unsigned long long)big_offset, (unsigned long long)big_size);
    }
    CHECK(vrg_graph_frame(g) == 0, "frame failed");
    vrg_image_data img;
    CHECK(vrg_graph_read(g, "sum", &img) == 0, "readback failed");
    CHECK(px(&img, 0, 0, 0) == 70.0f, "sum is %g, not 70 + 0", px(&img, 0, 0, 0));
    free(img.pixels);
    vrg_graph_destroy(g);
}

/* The dispatch helper's limits fail the frame with a message naming them:
 * more bound slots than bindings (the rest were once left unbound), defines
 * longer than it takes (once cut short). */
static void test_dispatch_limits(void)
{
    static const struct {
        const char *set, *want;
    } cases[] = {
        {"m.long_defines=0", "its slots need more than the 16 bindings of a dispatch"},
        {"m.long_defines=1", "defines of 399 characters (at most"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *log = NULL;
        size_t len = 0;
        FILE *diag = open_memstream(&log, &len);
        const char *sets[] = {cases[i].set};
        vrg_graph_desc d = {.path = "limits.ini", .overrides = sets, .override_count = 1, .diag = diag,
                            .text = "[graph]\noutput = out\nwidth = 8\nheight = 8\n[pass m]\nplugin = many_slots\nout.color = out\n"};
        vrg_graph *g = NULL;
        CHECK(vrg_graph_load(ctx, &d, &g) == 0, "cannot load the graph");
        if (g) {
            CHECK(vrg_graph_frame(g) != 0, "%s: the frame did not fail", cases[i].set);
            vrg_graph_destroy(g);
        }
        fclose(diag);
        CHECK(log && strstr(log, cases[i].want), "%s: no '%s' in: %s", cases[i].set, cases[i].want, log ? log : "");
        free(log);
    }
}

/* How a dispatch is sized. A shader's local size is read from the SPIR-V
 * whichever way glslang writes it (an 8x8 shader that does not use
 * gl_WorkGroupSize gets LocalSizeId: it was once read as 1x1 and dispatched
 * 64 times over). A pixel loop covers every pixel with the device's
 * tiles, also where the size is no multiple of them; a pixel loop with
 * another local size is refused with an error naming the shader. */
static void test_dispatch_shape(void)
{
    char dir[] = "/tmp/voxrg-shape-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        return;
    }
    char user[1100];
    snprintf(user, sizeof user, "%s/user.comp", dir);
    setenv("VOXRG_SHADER_PATH", dir, 1);
    static const char *shaders[] = {
        "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\nlayout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(gl_NumWorkGroups.xy, 0.0, 1.0)); }\n",
        "#version 450\n#include \"pixel.glsl\"\nlayout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;\n"
        "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void shade(ivec2 p) { if (all(lessThan(p, imageSize(dst)))) imageStore(dst, p, vec4(p, 1.0, 0.0)); }\n"
        "void main() { for (uint k = 0u; k < VRG_PIXEL_ROWS; k++) shade(vrg_pixel(k)); }\n",
        "#version 450\n#include \"pixel.glsl\"\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
        "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
        "void shade(ivec2 p) { imageStore(dst, p, vec4(1.0)); }\nvoid main() { shade(vrg_pixel(0u)); }\n",
    };
    for (int c = 0; c < 3; c++) {
        save_file(user, shaders[c]);
        char text[512];
        snprintf(text, sizeof text, "[graph]\noutput = color\nwidth = %d\nheight = %d\n[pass user]\nplugin = shader_file\nout.color = color\npixel_loop = %d\n",
                 c ? 13 : 16, c ? 11 : 16, c > 0);
        char *log = NULL;
        size_t len = 0;
        FILE *diag = open_memstream(&log, &len);
        vrg_graph_desc d = {.path = "shape.ini", .text = text, .diag = diag};
        vrg_graph *g = NULL;
        int rc = vrg_graph_load(ctx, &d, &g);
        CHECK(rc == 0, "case %d: load failed", c);
        int frame_rc = rc == 0 ? vrg_graph_frame(g) : -1;
        fclose(diag);
        vrg_image_data img = {0};
        if (c < 2 && frame_rc == 0 && vrg_graph_read(g, "color", &img) == 0) {
            int bad = 0;
            for (uint32_t y = 0; y < img.height; y++)
                for (uint32_t x = 0; x < img.width; x++) {
                    float want[3] = {c ? (float)x : 2.0f, c ? (float)y : 2.0f, c ? 1.0f : 0.0f};
                    int wrong = 0;
                    for (int k = 0; k < 3; k++)
                        wrong |= px(&img, x, y, k) != want[k];
                    if (wrong && !bad++) /* the first wrong pixel */
                        CHECK(0, "case %d: pixel %u,%u is %g %g %g, want %g %g %g", c, x, y, px(&img, x, y, 0), px(&img, x, y, 1), px(&img, x, y, 2),
                              want[0], want[1], want[2]);
                }
            free(img.pixels);
        } else if (c < 2)
            CHECK(0, "case %d: the frame failed:\n%s", c, log ? log : "");
        else
            CHECK(frame_rc != 0 && log && strstr(log, "pixel_loop dispatch of user.comp: local size 8x8x1"), "case 2: no error:\n%s", log ? log : "");
        free(log);
        vrg_graph_destroy(g);
    }
    unsetenv("VOXRG_SHADER_PATH");
    remove(user), rmdir(dir);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"dispatch_shape", test_dispatch_shape, 1},
        {"history_many", test_history_many, 1},
        {"many_uses", test_many_uses, 1},
        {"dispatch_limits", test_dispatch_limits, 1},
        {"alias_many", test_alias_many, 1},
    };
    return run_case(argc, argv, cases, sizeof cases / sizeof cases[0]);
}
