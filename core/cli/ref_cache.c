/* The reference frames' cache (ref_cache.h).
 *
 * An entry is KEY.frame, KEY the SHA-256 (hex) of every input that
 * decides the frame's pixels. The file is a text header, then the pixels:
 *
 *   voxrg reference frame 1
 *   key KEY
 *   size W H
 *   pixels SHA-256 of the W*H*3 bytes that follow
 *   shader SHA-256 PATH        (each shader file the frame was rendered with)
 *   end
 *   W*H*3 bytes, RGB8, rows top to bottom
 *
 * The shaders are not in the key: which ones a graph compiles is known
 * only after a frame. They are checked when the entry is read instead, by
 * content, so an edited shader renders the reference again.
 *
 * Many writers may share the folder (a cluster's jobs over NFS): each
 * writes a temporary file of a name no other writer uses (voxrg/output.h:
 * host, process, counter and random bits), syncs it and renames it over
 * KEY.frame. Two writers of one key both rename; the last one stays, and
 * both wrote the same valid entry. A reader sees a whole entry or none,
 * and checks the header, the key and the pixels' checksum anyway: a file
 * copied over an entry, cut short by a full disk or damaged is named in a
 * warning and rendered again, never used. */
#define _GNU_SOURCE /* dladdr */
#include "ref_cache.h"
#include <dlfcn.h>
#include <errno.h>
#include <openssl/evp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "voxrg/edits.h"
#include "voxrg/output.h"
#include "voxrg/plugin.h"
#include "voxrg/png.h"

#define FORMAT_LINE "voxrg reference frame 1"
#define HEADER_MAX (1 << 20) /* the header's lines: a few hundred shaders at most */

struct vrg_ref_file_hash {
    char *path;
    int absent;
    uint8_t hash[VRG_REF_HASH];
};

static void hex(const uint8_t *h, char *out)
{
    for (int i = 0; i < VRG_REF_HASH; i++)
        sprintf(out + 2 * i, "%02x", h[i]);
}

/* SHA-256 of a file's content: 0, 1 when it does not exist, -1 when it
 * cannot be read. */
static int hash_file(const char *path, uint8_t out[VRG_REF_HASH])
{
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f)
        return errno == ENOENT ? 1 : -1;
    EVP_MD_CTX *md = EVP_MD_CTX_new();
    int ok = md && EVP_DigestInit_ex(md, EVP_sha256(), NULL);
    unsigned char buf[65536];
    size_t n;
    while (ok && (n = fread(buf, 1, sizeof buf, f)) > 0)
        ok = EVP_DigestUpdate(md, buf, n);
    ok = ok && !ferror(f) && EVP_DigestFinal_ex(md, out, NULL);
    EVP_MD_CTX_free(md);
    fclose(f);
    return ok ? 0 : -1;
}

/* A file's hash, each file read once per run; NULL when it cannot be read. */
static const vrg_ref_file_hash *file_hash(vrg_ref_cache *c, const char *path)
{
    for (int i = 0; i < c->file_count; i++)
        if (strcmp(c->files[i].path, path) == 0)
            return &c->files[i];
    vrg_ref_file_hash h = {0};
    int rc = hash_file(path, h.hash);
    if (rc < 0)
        return NULL;
    vrg_ref_file_hash *grown = realloc(c->files, sizeof *grown * (size_t)(c->file_count + 1));
    if (!grown || !(h.path = strdup(path))) {
        if (grown)
            c->files = grown;
        return NULL;
    }
    c->files = grown;
    h.absent = rc == 1;
    c->files[c->file_count] = h;
    return &c->files[c->file_count++];
}

const char *vrg_ref_cache_dir(const char *given, char *buf, size_t cap)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (given)
        snprintf(buf, cap, "%s", given);
    else if (xdg && *xdg)
        snprintf(buf, cap, "%s/voxrg/reference", xdg);
    else
        snprintf(buf, cap, "%s/.cache/voxrg/reference", home && *home ? home : "/tmp");
    return buf;
}

static void add_text(EVP_MD_CTX *md, const char *label, const char *text, size_t len)
{
    char head[96];
    int n = snprintf(head, sizeof head, "%s %zu\n", label, len); /* length first: no two inputs read alike */
    EVP_DigestUpdate(md, head, (size_t)n);
    EVP_DigestUpdate(md, text, len);
}

typedef struct collect {
    vrg_ref_cache *c;
    EVP_MD_CTX *md;
    const char *failed; /* a file that could not be read */
} collect;

/* Each source's content, by content alone: the same checkout in another
 * folder (another node of a cluster) finds the same entries. */
static void add_source(void *user, const char *path)
{
    collect *k = user;
    const vrg_ref_file_hash *h = k->failed ? NULL : file_hash(k->c, path);
    if (!h) {
        k->failed = k->failed ? k->failed : path;
        return;
    }
    char text[2 * VRG_REF_HASH + 1];
    hex(h->hash, text);
    add_text(k->md, "file", h->absent ? "absent" : text, h->absent ? 6 : 2 * VRG_REF_HASH);
}

/* The device and its driver's version: lavapipe and a GPU, or two drivers
 * of one GPU, render slightly different references. */
static void add_device(EVP_MD_CTX *md, const vrg_device *d)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d->physical_device, &p);
    char text[512];
    int n = snprintf(text, sizeof text, "%s vendor %x device %x driver %u api %u", d->name, p.vendorID, p.deviceID, p.driverVersion, p.apiVersion);
    add_text(md, "device", text, (size_t)n);
}

/* The runtime's, the voxel layer's and the tools' libraries, as loaded:
 * they render (and the tools turn the output into 8-bit RGB) as much as
 * the plugins do. */
static void add_libraries(collect *k)
{
    const void *symbols[] = {(const void *)vrg_version, (const void *)vrg_edits_open, (const void *)vrg_image_rgb8};
    for (int i = 0; i < 3; i++) {
        Dl_info info;
        if (dladdr(symbols[i], &info) && info.dli_fname)
            add_source(k, info.dli_fname);
        else
            k->failed = k->failed ? k->failed : "the voxrg libraries (dladdr)";
    }
}

int vrg_ref_cache_open(vrg_ref_cache *c, const char *dir, const char *graph_path, const vrg_graph *g, const char *const *sets, int set_count,
                       const vrg_device *device, uint32_t width, uint32_t height)
{
    memset(c, 0, sizeof *c);
    snprintf(c->dir, sizeof c->dir, "%s", dir);
    char *text = vrg_cli_read_text(graph_path);
    if (!text) {
        fprintf(stderr, "error: cannot read %s: %s\n", graph_path, vrg_open_strerror(errno));
        return -1;
    }
    EVP_MD_CTX *md = EVP_MD_CTX_new();
    if (!md || !EVP_DigestInit_ex(md, EVP_sha256(), NULL)) {
        free(text);
        EVP_MD_CTX_free(md);
        fprintf(stderr, "error: the reference cache: cannot start a SHA-256\n");
        return -1;
    }
    add_text(md, "cache", FORMAT_LINE, strlen(FORMAT_LINE));
    add_text(md, "version", vrg_version(), strlen(vrg_version()));
    add_device(md, device);
    add_text(md, "graph", text, strlen(text));
    free(text);
    for (int i = 0; i < set_count; i++)
        add_text(md, "set", sets[i], strlen(sets[i]));
    char size[64];
    add_text(md, "size", size, (size_t)snprintf(size, sizeof size, "%ux%u", width, height));
    collect k = {.c = c, .md = md};
    add_libraries(&k);
    vrg_graph_sources(g, add_source, &k);
    c->key_files = c->file_count;
    int ok = EVP_DigestFinal_ex(md, c->base, NULL);
    EVP_MD_CTX_free(md);
    if (k.failed || !ok) {
        fprintf(stderr, "error: the reference cache: cannot read %s, which the reference is built from\n", k.failed ? k.failed : "(SHA-256)");
        vrg_ref_cache_close(c);
        return -1;
    }
    return 0;
}

void vrg_ref_cache_close(vrg_ref_cache *c)
{
    for (int i = 0; i < c->file_count; i++)
        free(c->files[i].path);
    free(c->files);
    c->files = NULL;
    c->file_count = c->key_files = 0;
}

void vrg_ref_cache_key(const vrg_ref_cache *c, uint32_t frame, double seconds, const vrg_camera *cam, char key[VRG_REF_KEY_HEX])
{
    /* %a: every float exactly, the same text on every machine */
    char text[512];
    int n = snprintf(text, sizeof text, "frame %u time %a camera %a %a %a yaw %a pitch %a fov %a near %a far %a", frame, seconds,
                     (double)cam->position[0], (double)cam->position[1], (double)cam->position[2], (double)cam->yaw, (double)cam->pitch,
                     (double)cam->fov_y, (double)cam->near_plane, (double)cam->far_plane);
    uint8_t h[VRG_REF_HASH];
    EVP_MD_CTX *md = EVP_MD_CTX_new();
    EVP_DigestInit_ex(md, EVP_sha256(), NULL);
    EVP_DigestUpdate(md, c->base, sizeof c->base);
    EVP_DigestUpdate(md, text, (size_t)n);
    EVP_DigestFinal_ex(md, h, NULL);
    EVP_MD_CTX_free(md);
    hex(h, key);
}

static void entry_path(const vrg_ref_cache *c, const char *key, char *out, size_t cap) { snprintf(out, cap, "%s/%s.frame", c->dir, key); }

/* Anything but a regular file under an entry's name (a FIFO would block
 * the reader, and the writer, for ever) is an error naming it. */
static int entry_ok(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return 0;
    fprintf(stderr, "error: the reference cache's %s is not a regular file: remove it\n", path);
    return -1;
}

static void pixels_hash(const uint8_t *rgb, size_t n, char out[VRG_REF_KEY_HEX])
{
    uint8_t h[VRG_REF_HASH];
    unsigned len;
    EVP_Digest(rgb, n, h, &len, EVP_sha256(), NULL);
    hex(h, out);
}

/* The next header line, NUL-terminated in place; NULL at the header's end
 * or when it is cut short. */
static char *next_line(char **at, char *end)
{
    char *line = *at, *nl = memchr(line, '\n', (size_t)(end - line));
    if (!nl)
        return NULL;
    *nl = '\0';
    *at = nl + 1;
    return line;
}

/* Why the entry at path (its whole content in data) cannot be used, or
 * NULL; *stale: it is sound but a shader changed since (no warning). */
static const char *entry_fault(vrg_ref_cache *c, char *data, size_t size, const char *key, uint32_t w, uint32_t h, char *why, size_t cap,
                               int *stale, const uint8_t **pixels)
{
    char *at = data, *end = data + size, *line = next_line(&at, end);
    if (!line || strcmp(line, FORMAT_LINE) != 0)
        return "is not a reference frame of this voxrg (its first line is not '" FORMAT_LINE "')";
    char word[16], value[VRG_REF_KEY_HEX + 8], sum[VRG_REF_KEY_HEX + 8];
    unsigned ew, eh;
    if (!(line = next_line(&at, end)) || sscanf(line, "key %72s", value) != 1)
        return "is cut short in its header";
    if (strcmp(value, key) != 0)
        return snprintf(why, cap, "holds another frame (key %.72s): a file copied or renamed over it", value), why;
    if (!(line = next_line(&at, end)) || sscanf(line, "size %u %u", &ew, &eh) != 2)
        return "is cut short in its header";
    if (ew != w || eh != h)
        return snprintf(why, cap, "is %ux%u, its key's frames %ux%u: damaged", ew, eh, w, h), why;
    if (!(line = next_line(&at, end)) || sscanf(line, "pixels %72s", sum) != 1)
        return "is cut short in its header";
    while ((line = next_line(&at, end)) && strcmp(line, "end") != 0) {
        char *path = line + strlen("shader ") + 2 * VRG_REF_HASH + 1;
        if (sscanf(line, "%15s %72s", word, value) != 2 || strcmp(word, "shader") != 0 || strlen(value) != 2 * VRG_REF_HASH ||
            strlen(line) <= (size_t)(path - line))
            return "has a damaged header line";
        const vrg_ref_file_hash *fh = file_hash(c, path);
        char now[VRG_REF_KEY_HEX];
        if (fh && !fh->absent)
            hex(fh->hash, now);
        *stale |= !fh || fh->absent || strcmp(now, value) != 0;
    }
    if (!line)
        return "is cut short in its header";
    size_t want = (size_t)w * h * 3, have = (size_t)(end - at);
    if (have < want)
        return snprintf(why, cap, "is truncated: %zu of its %zu pixel bytes", have, want), why;
    if (have > want)
        return snprintf(why, cap, "has %zu bytes after its pixels: damaged", have - want), why;
    char got[VRG_REF_KEY_HEX];
    pixels_hash((const uint8_t *)at, want, got);
    if (strcmp(got, sum) != 0)
        return "has pixels that do not match their checksum: damaged or altered";
    *pixels = (const uint8_t *)at;
    return NULL;
}

int vrg_ref_cache_read(vrg_ref_cache *c, const char *key, uint32_t width, uint32_t height, uint8_t **rgb)
{
    char path[VRG_CLI_PATH + VRG_REF_KEY_HEX + 8];
    entry_path(c, key, path, sizeof path);
    *rgb = NULL;
    if (entry_ok(path) != 0)
        return -1;
    FILE *f = vrg_fopen_regular(path, "rb");
    if (!f)
        return 1;
    size_t cap = HEADER_MAX + (size_t)width * height * 3 + 1, size = 0;
    char *data = malloc(cap), why[256];
    if (data)
        size = fread(data, 1, cap, f);
    int read_failed = !data || ferror(f);
    fclose(f);
    if (read_failed) {
        fprintf(stderr, "\nwarning: cannot read the reference cache's %s: rendering the frame again\n", path);
        free(data);
        return 1;
    }
    int stale = 0;
    const uint8_t *pixels = NULL;
    const char *fault = size == cap ? "is larger than any frame of its size: damaged" :
                                      entry_fault(c, data, size, key, width, height, why, sizeof why, &stale, &pixels);
    if (fault)
        fprintf(stderr, "\nwarning: the reference cache's %s %s: rendering the frame again\n", path, fault);
    else if (!stale && (*rgb = malloc((size_t)width * height * 3)))
        memcpy(*rgb, pixels, (size_t)width * height * 3);
    free(data);
    return *rgb ? 0 : 1;
}

typedef struct shader_list {
    vrg_ref_cache *c;
    FILE *f;
    char **seen;
    int count, failed;
} shader_list;

/* Each file the graph was built from that the key does not cover: the
 * shaders and their #includes, once each. */
static void add_shader(void *user, const char *path)
{
    shader_list *s = user;
    for (int i = 0; i < s->c->key_files; i++)
        if (strcmp(s->c->files[i].path, path) == 0)
            return;
    for (int i = 0; i < s->count; i++)
        if (strcmp(s->seen[i], path) == 0)
            return;
    const vrg_ref_file_hash *h = file_hash(s->c, path);
    char **grown = realloc(s->seen, sizeof *grown * (size_t)(s->count + 1));
    if (grown)
        s->seen = grown;
    if (!h || h->absent || !grown || strchr(path, '\n')) { /* not recorded: the entry could not be checked */
        s->failed = 1;
        return;
    }
    s->seen[s->count++] = (char *)path;
    char text[VRG_REF_KEY_HEX];
    hex(h->hash, text);
    fprintf(s->f, "shader %s %s\n", text, path);
}

void vrg_ref_cache_write(vrg_ref_cache *c, const char *key, const vrg_graph *g, const uint8_t *rgb, uint32_t width, uint32_t height)
{
    char path[VRG_CLI_PATH + VRG_REF_KEY_HEX + 8], sum[VRG_REF_KEY_HEX];
    entry_path(c, key, path, sizeof path);
    vrg_output *out = vrg_output_open(path); /* says why it cannot */
    if (!out)
        return;
    FILE *f = vrg_output_stream(out);
    size_t n = (size_t)width * height * 3;
    pixels_hash(rgb, n, sum);
    fprintf(f, FORMAT_LINE "\nkey %s\nsize %u %u\npixels %s\n", key, width, height, sum);
    shader_list s = {.c = c, .f = f};
    vrg_graph_sources(g, add_shader, &s);
    free(s.seen);
    fprintf(f, "end\n");
    fwrite(rgb, 1, n, f);
    if (s.failed) {
        fprintf(stderr, "\nwarning: the reference cache: a shader of the reference could not be read: %s not written\n", path);
        vrg_output_abort(out);
    } else
        vrg_output_commit(out); /* a failure is reported; the frame is only not cached */
}
