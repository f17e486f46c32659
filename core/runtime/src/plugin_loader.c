/* Plugins are found by name on one search path; the first folder holding
 * NAME.so or NAME.comp (a shader-only pass, shader_pass.c) wins. In a
 * folder holding both, NAME.so is the pass: a C plugin's shader is often
 * NAME.comp beside it (`voxrg check` prints the file each plugin came from):
 *   1. built-in: <exe>/plugins (the build tree; tests also the build's
 *      plugin folder), 2. installed: voxrg/plugins beside libvoxrg's own
 *      file (PREFIX/lib/voxrg/plugins, wherever the prefix was moved),
 *   3. $VOXRG_PLUGIN_PATH (':'-separated): the user's own,
 *   4. the graph's `[graph] plugin_path` (':'-separated, relative to the
 *      graph file).
 * Built-in and installed plugins come first and are never shadowed, and a
 * graph's own folder is searched only when the graph names it: opening a
 * downloaded graph cannot swap a shipped pass for code that came with it,
 * and `voxrg check` prints the file every plugin came from.
 *
 * A plugin is never run from the user's file: it is read once, checked as
 * an ELF shared object of this machine whose segments lie inside the file (a
 * truncated build would otherwise die of SIGBUS inside dlopen), copied to a
 * private file, loaded from there and the copy unlinked. A build that
 * overwrites the .so in place cannot change code that runs, and every load
 * of a rebuilt file is a new image (dlopen hands back the old one for a path
 * it knows). In the copy, $ORIGIN in the plugin's RUNPATH would name the
 * copy's temporary folder: the libraries it needs are first looked up the
 * way ld.so would for the original file ($ORIGIN = the original's folder)
 * and opened from there, so that an installed plugin finds the voxrg
 * libraries beside it (PREFIX/lib, its RUNPATH $ORIGIN/../..) whatever the
 * host has loaded. */
#define _GNU_SOURCE
#include <ctype.h>
#include <dirent.h>
#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>
#include "internal.h"
#include "plugin_loader.h"
#include "shader_pass.h"

#if UINTPTR_MAX > 0xffffffffu
typedef Elf64_Ehdr elf_ehdr;
typedef Elf64_Phdr elf_phdr;
typedef Elf64_Dyn elf_dyn;
#else
typedef Elf32_Ehdr elf_ehdr;
typedef Elf32_Phdr elf_phdr;
typedef Elf32_Dyn elf_dyn;
#endif
#define PLUGIN_MAX_BYTES (1u << 30) /* larger is no plugin: refuse before reading it */

/* Slots stay put (graphs hold pointers to them); an unloaded version's slot
 * is emptied (name "") and reused. */
static _vrg_plugin loaded[VRG_MAX_PLUGINS];
static int loaded_count;
static unsigned last_generation;

/* The current version of the plugin built from `key` (a source file), or of
 * the plugin named `key` when !by_source. */
static _vrg_plugin *newest(const char *key, int by_source)
{
    _vrg_plugin *best = NULL;
    for (int i = 0; i < loaded_count; i++)
        if (loaded[i].name[0] && strcmp(by_source ? loaded[i].source : loaded[i].name, key) == 0 &&
            (!best || loaded[i].generation > best->generation))
            best = &loaded[i];
    return best;
}

static _vrg_plugin *free_slot(int claim)
{
    for (int i = 0; i < loaded_count; i++)
        if (!loaded[i].name[0])
            return &loaded[i];
    if (loaded_count == VRG_MAX_PLUGINS)
        return NULL;
    return claim ? &loaded[loaded_count++] : &loaded[loaded_count];
}

void _vrg_plugin_acquire(const _vrg_plugin *p) { ((_vrg_plugin *)p)->users++; }

/* The plugin first (it uses them), then its libraries, last opened first. */
static void unload(_vrg_plugin *p)
{
    _vrg_shader_pass_free(p);
    if (p->handle)
        dlclose(p->handle);
    while (p->lib_count > 0)
        dlclose(p->libs[--p->lib_count]);
    free(p->libs);
    if (p->keep_fd >= 0)
        close(p->keep_fd);
    p->handle = NULL;
    p->libs = NULL;
    p->keep_fd = -1;
}

void _vrg_plugin_release(const _vrg_plugin *cp)
{
    _vrg_plugin *p = (_vrg_plugin *)cp;
    if (--p->users > 0 || newest(p->source, 1) == p)
        return; /* in use, or the current version (kept loaded: a cache) */
    unload(p);
    memset(p, 0, sizeof *p);
}

/* An error at a graph line, or without one (line 0: a reload, a listing). */
static void fail(_vrg_diag *d, int line, _vrg_diag_code code, const char *hint, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static void fail(_vrg_diag *d, int line, _vrg_diag_code code, const char *hint, const char *fmt, ...)
{
    char msg[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        _vrg_error_at(d, line, code, hint, "%s", msg);
    else if (hint)
        _vrg_error_hint(d, code, hint, "%s", msg);
    else
        _vrg_error(d, code, "%s", msg);
}

/* ---- the search path ---- */

typedef enum { DIR_BUILTIN, DIR_INSTALLED, DIR_ENV, DIR_GRAPH } dir_origin;
static const char *const origin_names[] = {"built-in", "installed", "VOXRG_PLUGIN_PATH", "the graph's plugin_path"};

typedef struct search_path {
    struct {
        char path[VRG_PATH_MAX];
        dir_origin origin;
    } *dirs;
    int count, cap, failed;
} search_path;

static void add_dir(search_path *s, dir_origin origin, const char *dir, size_t len)
{
    if (!len || len >= VRG_PATH_MAX)
        return; /* an empty entry of a ':'-list; longer ones cannot name a folder */
    for (int i = 0; i < s->count; i++)
        if (strlen(s->dirs[i].path) == len && strncmp(s->dirs[i].path, dir, len) == 0)
            return;
    if (s->count == s->cap) {
        int cap = s->cap ? 2 * s->cap : 8;
        void *grown = realloc(s->dirs, (size_t)cap * sizeof *s->dirs);
        if (!grown) {
            s->failed = 1; /* out of memory: reported by the caller, not a folder dropped */
            return;
        }
        s->dirs = grown, s->cap = cap;
    }
    snprintf(s->dirs[s->count].path, VRG_PATH_MAX, "%.*s", (int)len, dir);
    s->dirs[s->count++].origin = origin;
}

/* Entry p (len bytes) of a ':'-list as a folder in dir: a relative one
 * under base (NULL: as written). Its length, or -1 if it does not fit. */
static int list_entry_dir(const char *base, const char *p, size_t len, char *dir, size_t cap)
{
    int n = base && p[0] != '/' ? snprintf(dir, cap, "%s/%.*s", base, (int)len, p) : snprintf(dir, cap, "%.*s", (int)len, p);
    return n >= 0 && (size_t)n < cap ? n : -1;
}

static void add_list(search_path *s, dir_origin origin, const char *base, const char *list)
{
    for (const char *p = list; p && *p;) {
        const char *c = strchr(p, ':');
        size_t len = c ? (size_t)(c - p) : strlen(p);
        char dir[VRG_PATH_MAX];
        int n = len ? list_entry_dir(base, p, len, dir, sizeof dir) : -1;
        if (n > 0)
            add_dir(s, origin, dir, (size_t)n);
        p = c ? c + 1 : p + len;
    }
}

/* The folder of a file ("." for a bare name) in `out`. */
static void folder_of(const char *path, char *out, size_t cap)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(out, cap, ".");
    else
        snprintf(out, cap, "%.*s", slash == path ? 1 : (int)(slash - path), path);
}

int _vrg_plugin_path_check(const char *graph_path, const char *plugin_path, _vrg_diag *d, int line)
{
    static const char *hint = "folders separated by ':', relative to the graph file";
    char base[VRG_PATH_MAX], dir[VRG_PATH_MAX];
    folder_of(graph_path ? graph_path : ".", base, sizeof base);
    int errors = d->errors;
    for (const char *p = plugin_path; *p;) {
        const char *c = strchr(p, ':');
        size_t len = c ? (size_t)(c - p) : strlen(p);
        struct stat st;
        if (len == 0)
            _vrg_error_at(d, line, VRG_E_BAD_PLUGIN_PATH, hint, "'plugin_path' has an empty entry");
        else if (list_entry_dir(base, p, len, dir, sizeof dir) < 0)
            _vrg_error_at(d, line, VRG_E_BAD_PLUGIN_PATH, hint, "plugin_path: '%.*s' is longer than %d characters under the graph's folder", (int)len, p, VRG_PATH_MAX - 1);
        else if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
            _vrg_error_at(d, line, VRG_E_BAD_PLUGIN_PATH, hint, "plugin_path: '%.*s' (%s) is not a folder", (int)len, p, dir);
        p = c ? c + 1 : p + len;
    }
    return d->errors > errors ? -1 : 0;
}

static void search_path_build(search_path *s, const char *graph_path, const char *plugin_path)
{
    memset(s, 0, sizeof *s);
    char exe[VRG_PATH_MAX], dir[VRG_PATH_MAX + 32];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash)
            *slash = '\0';
        add_dir(s, DIR_BUILTIN, dir, (size_t)snprintf(dir, sizeof dir, "%s/plugins", exe));
        /* tests and fuzzers run from other folders of the build; an
         * installed voxrg never searches the folder it was built in */
        const char *built = _vrg_build_plugin_dir();
        add_dir(s, DIR_BUILTIN, built, strlen(built));
    }
    if (*_vrg_lib_dir())
        add_dir(s, DIR_INSTALLED, dir, (size_t)snprintf(dir, sizeof dir, "%s/voxrg/plugins", _vrg_lib_dir()));
    add_list(s, DIR_ENV, NULL, getenv("VOXRG_PLUGIN_PATH"));
    if (graph_path && plugin_path) {
        char base[VRG_PATH_MAX];
        folder_of(graph_path, base, sizeof base);
        add_list(s, DIR_GRAPH, base, plugin_path);
    }
}

static int is_regular(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* Index of the first folder holding NAME.so or NAME.comp, -1 if none; its
 * path in `file` (NAME.so where both are). */
static int search_path_find(const search_path *s, const char *name, int from, char *file, size_t cap)
{
    for (int i = from; i < s->count; i++) {
        for (int k = 1; k >= 0; k--) {
            int n = snprintf(file, cap, "%s/%s.%s", s->dirs[i].path, name, k ? "comp" : "so");
            if (n > 0 && n < (int)cap && access(file, F_OK) == 0) {
                if (k) { /* NAME.so beside it is the pass */
                    char so[VRG_PATH_MAX + VRG_NAME_MAX + 8];
                    n = snprintf(so, sizeof so, "%s/%s.so", s->dirs[i].path, name);
                    if (n > 0 && n < (int)sizeof so && access(so, F_OK) == 0)
                        snprintf(file, cap, "%s", so);
                }
                return i;
            }
        }
    }
    return -1;
}

/* Whether folder i holds both NAME.so and NAME.comp. */
static int ambiguous(const search_path *s, int i, const char *name)
{
    char f[VRG_PATH_MAX + VRG_NAME_MAX + 8];
    int both = 1;
    for (int k = 0; k < 2 && both; k++) {
        int n = snprintf(f, sizeof f, "%s/%s.%s", s->dirs[i].path, name, k ? "comp" : "so");
        both = n > 0 && n < (int)sizeof f && access(f, F_OK) == 0;
    }
    return both;
}

static int is_shader_file(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && strcmp(path + n - 5, ".comp") == 0;
}

static void search_path_hint(const search_path *s, char *hint, size_t cap)
{
    size_t n = (size_t)snprintf(hint, cap, "searched:");
    for (int i = 0; i < s->count && n < cap; i++)
        n += (size_t)snprintf(hint + n, cap - n, "%s %s (%s)", i ? "," : "", s->dirs[i].path, origin_names[s->dirs[i].origin]);
    if (n < cap)
        snprintf(hint + n, cap - n, "; the first match wins. Set VOXRG_PLUGIN_PATH or the graph's [graph] plugin_path; `voxrg plugins` lists what exists");
}

/* ---- reading, checking and loading one file ---- */

static int read_whole(const char *path, unsigned char **data, size_t *size, char *why, size_t cap)
{
    /* a FIFO named like a plugin must not block the open (vrg_open_regular) */
    int fd = vrg_open_regular(path, O_RDONLY);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        int err = errno;
        if (err == EINVAL || err == EISDIR)
            snprintf(why, cap, "it is not a regular file");
        else
            snprintf(why, cap, "cannot read it: %s", strerror(err));
        if (fd >= 0)
            close(fd);
        return -1;
    }
    if (st.st_size > PLUGIN_MAX_BYTES) {
        snprintf(why, cap, "it is larger than 1 GiB");
        close(fd);
        return -1;
    }
    *size = (size_t)st.st_size;
    *data = malloc(*size ? *size : 1);
    size_t got = 0;
    ssize_t r = 1;
    while (*data && got < *size && (r = read(fd, *data + got, *size - got)) > 0)
        got += (size_t)r;
    int err = errno;
    close(fd);
    if (!*data || got != *size) {
        snprintf(why, cap, "cannot read it: %s", !*data ? "out of memory" : r < 0 ? strerror(err) : "it shrank while being read");
        free(*data);
        *data = NULL;
        return -1;
    }
    return 0;
}

/* This process's own ELF class, byte order and machine: a plugin must match. */
static int host_elf(unsigned char ident[EI_NIDENT], uint16_t *machine)
{
    static elf_ehdr self;
    static int known = -1;
    if (known < 0) {
        int fd = open("/proc/self/exe", O_RDONLY | O_CLOEXEC);
        known = fd >= 0 && read(fd, &self, sizeof self) == (ssize_t)sizeof self && memcmp(self.e_ident, ELFMAG, SELFMAG) == 0;
        if (fd >= 0)
            close(fd);
    }
    if (known) {
        memcpy(ident, self.e_ident, EI_NIDENT);
        *machine = self.e_machine;
    }
    return known;
}

/* Why `b` (n bytes) is not a shared object dlopen can map safely, or NULL. */
static const char *elf_problem(const unsigned char *b, size_t n, char *why, size_t cap)
{
    unsigned char ident[EI_NIDENT];
    uint16_t machine = 0;
    int host = host_elf(ident, &machine);
    if (n < SELFMAG || memcmp(b, ELFMAG, SELFMAG) != 0)
        return snprintf(why, cap, "not an ELF file (%zu bytes; no ELF magic)", n), why;
    if (n < sizeof(elf_ehdr))
        return snprintf(why, cap, "truncated: %zu bytes, shorter than an ELF header (%zu)", n, sizeof(elf_ehdr)), why;
    elf_ehdr e;
    memcpy(&e, b, sizeof e);
    if (host && (e.e_ident[EI_CLASS] != ident[EI_CLASS] || e.e_ident[EI_DATA] != ident[EI_DATA]))
        return snprintf(why, cap, "built for another kind of machine (ELF class %u, byte order %u; this voxrg is %u, %u)",
                        e.e_ident[EI_CLASS], e.e_ident[EI_DATA], ident[EI_CLASS], ident[EI_DATA]), why;
    if (e.e_type != ET_DYN)
        return snprintf(why, cap, "not a shared object (ELF type %u; build it with -shared -fPIC)", e.e_type), why;
    if (host && e.e_machine != machine)
        return snprintf(why, cap, "built for another machine (ELF machine %u, this one is %u)", e.e_machine, machine), why;
    if (e.e_phentsize != sizeof(elf_phdr) || e.e_phnum == 0 || e.e_phnum == 0xffff)
        return snprintf(why, cap, "malformed ELF program header table (%u entries of %u bytes)", e.e_phnum, e.e_phentsize), why;
    /* offsets compared before adding: a huge e_phoff must not wrap around */
    if (e.e_phoff > n || e.e_phnum > (n - e.e_phoff) / sizeof(elf_phdr))
        return snprintf(why, cap, "truncated: %zu bytes, its program headers (%u at byte %llu) do not fit", n, e.e_phnum,
                        (unsigned long long)e.e_phoff), why;
    if (e.e_shoff && (e.e_shoff > n || (e.e_shentsize && e.e_shnum > (n - e.e_shoff) / e.e_shentsize)))
        return snprintf(why, cap, "truncated: %zu bytes, its section headers (%u at byte %llu) do not fit", n, e.e_shnum,
                        (unsigned long long)e.e_shoff), why;
    for (unsigned i = 0; i < e.e_phnum; i++) {
        elf_phdr ph;
        memcpy(&ph, b + e.e_phoff + (size_t)i * sizeof ph, sizeof ph);
        uint64_t end = (uint64_t)ph.p_offset + ph.p_filesz;
        if (ph.p_offset > n || ph.p_filesz > n - ph.p_offset)
            return snprintf(why, cap, "truncated: %zu bytes, segment %u (type %u) ends at byte %llu", n, i, ph.p_type, (unsigned long long)end), why;
    }
    return NULL;
}

static void *dlopen_checked(const _vrg_plugin *p, const char *file, char *why, size_t cap)
{
    _vrg_running before = _vrg_running_enter("loading (dlopen and the plugin's constructors)", NULL, p);
    void *handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    _vrg_running_leave(before);
    if (!handle)
        snprintf(why, cap, "%s", dlerror());
    return handle;
}

/* ---- the libraries a plugin needs, found from its original file ---- */

/* The file offset of virtual address `vaddr` (in a PT_LOAD segment's file
 * bytes), or -1. The program headers were checked by elf_problem. */
static int64_t vaddr_offset(const unsigned char *b, const elf_ehdr *e, uint64_t vaddr)
{
    for (unsigned i = 0; i < e->e_phnum; i++) {
        elf_phdr ph;
        memcpy(&ph, b + e->e_phoff + (size_t)i * sizeof ph, sizeof ph);
        if (ph.p_type == PT_LOAD && vaddr >= ph.p_vaddr && vaddr - ph.p_vaddr < ph.p_filesz)
            return (int64_t)(ph.p_offset + (vaddr - ph.p_vaddr));
    }
    return -1;
}

/* The dynamic section's strings: DT_NEEDED names, DT_RUNPATH or DT_RPATH. */
typedef struct elf_dynamic {
    const unsigned char *dyn; /* elf_dyn entries, maybe unaligned in the buffer: read with memcpy */
    size_t count;
    const char *strtab;
    size_t strsz;
} elf_dynamic;

static int elf_dynamic_find(const unsigned char *b, size_t n, elf_dynamic *out)
{
    elf_ehdr e;
    memcpy(&e, b, sizeof e);
    memset(out, 0, sizeof *out);
    uint64_t strtab = 0, strsz = 0;
    for (unsigned i = 0; i < e.e_phnum && !out->dyn; i++) {
        elf_phdr ph;
        memcpy(&ph, b + e.e_phoff + (size_t)i * sizeof ph, sizeof ph);
        if (ph.p_type == PT_DYNAMIC)
            out->dyn = b + ph.p_offset, out->count = ph.p_filesz / sizeof(elf_dyn);
    }
    for (size_t i = 0; i < out->count; i++) {
        elf_dyn d;
        memcpy(&d, out->dyn + i * sizeof d, sizeof d);
        if (d.d_tag == DT_NULL)
            break;
        if (d.d_tag == DT_STRTAB)
            strtab = d.d_un.d_ptr;
        else if (d.d_tag == DT_STRSZ)
            strsz = d.d_un.d_val;
    }
    int64_t at = out->dyn && strtab ? vaddr_offset(b, &e, strtab) : -1;
    if (at < 0)
        return -1; /* no dynamic strings: nothing to look up, dlopen judges the rest */
    out->strtab = (const char *)b + at;
    out->strsz = strsz < n - (size_t)at ? (size_t)strsz : n - (size_t)at;
    return 0;
}

/* The string at `off` of the dynamic string table, NULL if it does not end inside it. */
static const char *elf_dynamic_string(const elf_dynamic *dyn, uint64_t off)
{
    if (off >= dyn->strsz || !memchr(dyn->strtab + off, '\0', dyn->strsz - off))
        return NULL;
    return dyn->strtab + off;
}

/* The first value of `tag`, or NULL. */
static const char *elf_dynamic_value(const elf_dynamic *dyn, int64_t tag)
{
    for (size_t i = 0; i < dyn->count; i++) {
        elf_dyn d;
        memcpy(&d, dyn->dyn + i * sizeof d, sizeof d);
        if (d.d_tag == DT_NULL)
            break;
        if (d.d_tag == tag)
            return elf_dynamic_string(dyn, d.d_un.d_val);
    }
    return NULL;
}

/* Folder `entry` (len bytes) of a search list with $ORIGIN / ${ORIGIN}
 * replaced by `origin`, into dir; 0, or -1 if it holds another token
 * ($LIB, $PLATFORM: left to ld.so) or does not fit. */
static int expand_origin(const char *entry, size_t len, const char *origin, char *dir, size_t cap)
{
    size_t o = 0;
    for (size_t i = 0; i < len;) {
        size_t skip = 0;
        if (entry[i] == '$') {
            if (len - i >= 7 && strncmp(entry + i, "$ORIGIN", 7) == 0)
                skip = 7;
            else if (len - i >= 9 && strncmp(entry + i, "${ORIGIN}", 9) == 0)
                skip = 9;
            else
                return -1;
        }
        const char *piece = skip ? origin : entry + i;
        size_t plen = skip ? strlen(origin) : 1;
        if (o + plen >= cap)
            return -1;
        memcpy(dir + o, piece, plen);
        o += plen, i += skip ? skip : 1;
    }
    dir[o] = '\0';
    return 0;
}

/* Where `lib` lies on the ':'-separated `list` (each entry expanded with
 * `origin`; NULL: not expanded) as ld.so looks: the first folder holding it,
 * empty entries skipped. 1 with the file in `file`, 0 if none, -1 if an
 * entry cannot be expanded here (ld.so decides). */
static int find_on_list(const char *list, const char *origin, const char *lib, char *file, size_t cap)
{
    for (const char *p = list; p && *p;) {
        const char *c = strchr(p, ':');
        size_t len = c ? (size_t)(c - p) : strlen(p);
        char dir[VRG_PATH_MAX];
        if (len) {
            if (origin ? expand_origin(p, len, origin, dir, sizeof dir) != 0 : list_entry_dir(NULL, p, len, dir, sizeof dir) < 0)
                return -1;
            int n = snprintf(file, cap, "%s/%s", dir, lib);
            if (n > 0 && (size_t)n < cap && access(file, R_OK) == 0)
                return 1;
        }
        p = c ? c + 1 : p + len;
    }
    return 0;
}

static int keep_lib(_vrg_plugin *p, void *handle)
{
    void **grown = realloc(p->libs, (size_t)(p->lib_count + 1) * sizeof *grown);
    if (!grown)
        return -1;
    p->libs = grown;
    p->libs[p->lib_count++] = handle;
    return 0;
}

/* Opens, from where the original file's RUNPATH (or RPATH) points, each
 * library the plugin needs that ld.so would take from there: not one the
 * process has loaded already (by SONAME), nor, for RUNPATH, one that
 * LD_LIBRARY_PATH holds (searched first). The copy then binds to these.
 * A library found nowhere is left to dlopen's own search (and its error).
 * The handles stay with the plugin (closed by unload). */
static int open_needed_libs(_vrg_plugin *p, const unsigned char *data, size_t size, char *why, size_t cap)
{
    elf_dynamic dyn;
    if (elf_dynamic_find(data, size, &dyn) != 0)
        return 0;
    const char *runpath = elf_dynamic_value(&dyn, DT_RUNPATH);
    const char *list = runpath ? runpath : elf_dynamic_value(&dyn, DT_RPATH);
    if (!list)
        return 0;
    char origin[VRG_PATH_MAX], file[2 * VRG_PATH_MAX];
    folder_of(p->source, origin, sizeof origin);
    for (size_t i = 0; i < dyn.count; i++) {
        elf_dyn d;
        memcpy(&d, dyn.dyn + i * sizeof d, sizeof d);
        if (d.d_tag == DT_NULL)
            break;
        const char *lib = d.d_tag == DT_NEEDED ? elf_dynamic_string(&dyn, d.d_un.d_val) : NULL;
        if (!lib || !lib[0] || strchr(lib, '/'))
            continue; /* a path is opened as written, from the copy as from the original */
        void *loaded_already = dlopen(lib, RTLD_LAZY | RTLD_NOLOAD);
        if (loaded_already) {
            dlclose(loaded_already);
            continue;
        }
        (void)dlerror(); /* the failed lookup's message is no error */
        if (runpath && find_on_list(getenv("LD_LIBRARY_PATH"), NULL, lib, file, sizeof file) != 0)
            continue;
        if (find_on_list(list, origin, lib, file, sizeof file) != 1)
            continue;
        char err[768];
        void *handle = dlopen_checked(p, file, err, sizeof err);
        if (!handle) {
            snprintf(why, cap, "it needs %s, found through its %s at %s, which does not load: %s", lib, runpath ? "RUNPATH" : "RPATH", file, err);
            return -1;
        }
        if (keep_lib(p, handle) != 0) {
            dlclose(handle);
            snprintf(why, cap, "out of memory for the handles of its libraries");
            return -1;
        }
    }
    return 0;
}

static int write_all(int fd, const unsigned char *data, size_t size)
{
    for (size_t put = 0; put < size;) {
        ssize_t w = write(fd, data + put, size - put);
        if (w <= 0)
            return -1;
        put += (size_t)w;
    }
    return 0;
}

/* Where $TMPDIR is mounted noexec no copy there can be mapped: the copy is
 * an anonymous memory file instead, opened through /proc/self/fd. Its
 * descriptor stays open while the plugin is loaded (*keep_fd), so no other
 * load gets the same /proc path, which dlopen would take for this one. */
static void *open_memfd(const _vrg_plugin *p, const unsigned char *data, size_t size, int *keep_fd, char *why, size_t cap)
{
    int fd = memfd_create(p->name, MFD_CLOEXEC);
    if (fd < 0 || write_all(fd, data, size) != 0) {
        snprintf(why, cap, "cannot write its private copy in memory: %s", strerror(errno));
        if (fd >= 0)
            close(fd);
        return NULL;
    }
    char file[64];
    snprintf(file, sizeof file, "/proc/self/fd/%d", fd);
    void *handle = dlopen_checked(p, file, why, cap);
    if (handle)
        *keep_fd = fd;
    else
        close(fd);
    return handle;
}

/* A private copy of `data`, dlopen'ed; the copy is unlinked right after
 * (the mapping stays), and removed by the crash handler if dlopen or the
 * plugin's constructors die. */
static void *open_private(const _vrg_plugin *p, const unsigned char *data, size_t size, int *keep_fd, char *why, size_t cap)
{
    const char *tmp = getenv("TMPDIR");
    tmp = tmp && tmp[0] ? tmp : "/tmp";
    struct statvfs fs;
    if (statvfs(tmp, &fs) == 0 && (fs.f_flag & ST_NOEXEC))
        return open_memfd(p, data, size, keep_fd, why, cap);
    char dir[VRG_PATH_MAX], file[VRG_PATH_MAX + VRG_NAME_MAX + 8];
    snprintf(dir, sizeof dir, "%s/voxrg-plugin-XXXXXX", tmp);
    if (!mkdtemp(dir)) {
        snprintf(why, cap, "cannot make a private folder for its copy (%s): %s", dir, strerror(errno));
        return NULL;
    }
    snprintf(file, sizeof file, "%s/%s.so", dir, p->name);
    _vrg_crash_cleanup_set(dir, file);
    int fd = open(file, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0500);
    void *handle = NULL;
    if (fd < 0 || write_all(fd, data, size) != 0 || close(fd) != 0) {
        snprintf(why, cap, "cannot write its private copy %s: %s", file, strerror(errno));
        if (fd >= 0)
            close(fd);
    } else
        handle = dlopen_checked(p, file, why, cap);
    unlink(file);
    rmdir(dir);
    _vrg_crash_cleanup_set(NULL, NULL);
    return handle;
}

/* The plugin's descriptor at this runtime's size: a shorter one (older
 * headers) gets zeros for the fields it lacks, a longer one (newer
 * headers) is refused if it sets any field this runtime does not know. */
static int copy_desc(_vrg_plugin *p, uint32_t size, _vrg_diag *d, int line)
{
    const unsigned char *bytes = (const unsigned char *)p->desc;
    size_t known = sizeof(vrg_plugin_desc);
    if (size < offsetof(vrg_plugin_desc, execute) + sizeof p->desc->execute) {
        fail(d, line, VRG_E_PLUGIN_ABI, "rebuild the plugin against this voxrg's headers", "plugin '%s' (%s): its descriptor is %u bytes, too short to hold execute",
             p->name, p->source, size);
        return 0;
    }
    for (size_t i = known; i < size; i++)
        if (bytes[i]) {
            fail(d, line, VRG_E_PLUGIN_ABI, "update voxrg, or rebuild the plugin against this voxrg's headers",
                 "plugin '%s' (%s): its descriptor (%u bytes) sets fields this voxrg (%zu bytes) does not know", p->name, p->source, size, known);
            return 0;
        }
    memset(&p->desc_copy, 0, sizeof p->desc_copy);
    memcpy(&p->desc_copy, bytes, size < known ? size : known);
    p->desc = &p->desc_copy;
    return 1;
}

/* Loads p->source into *p: read, ELF check, private copy, entry point, ABI
 * and descriptor checks. Reports at `line` (0: none) and returns -1 on any
 * failure, with nothing left loaded. */
/* Code that anyone on the machine can replace: a plugin file others may
 * write, or one in a folder where others may rename files (world-writable
 * without the sticky bit, which /tmp has). Said, not refused: a folder
 * shared on purpose is the user's choice, and the warning names it. */
static void warn_if_writable(const _vrg_plugin *p, _vrg_diag *d, int line)
{
    struct stat st;
    char dir[VRG_PATH_MAX];
    folder_of(p->source, dir, sizeof dir);
    if (stat(p->source, &st) == 0 && (st.st_mode & S_IWOTH))
        _vrg_warning_at(d, line, VRG_W_PLUGIN_WRITABLE, "plugin '%s' (%s) is writable by every user: anyone on this machine can change the code it runs "
                        "(chmod o-w it)", p->name, p->source);
    else if (stat(dir, &st) == 0 && (st.st_mode & S_IWOTH) && !(st.st_mode & S_ISVTX))
        _vrg_warning_at(d, line, VRG_W_PLUGIN_WRITABLE, "plugin '%s' (%s): its folder %s is writable by every user: anyone on this machine can replace "
                        "the plugin (chmod o-w the folder)", p->name, p->source, dir);
}

static int check_desc(const vrg_plugin_desc *desc, const char *name, const char *path, _vrg_diag *d, int line, int needs_execute);

static int load_file(_vrg_plugin *p, _vrg_diag *d, int line)
{
    if (is_shader_file(p->source)) { /* no code of its own: the same trust warning, then its interface */
        warn_if_writable(p, d, line);
        if (_vrg_shader_pass_load(p, d, line) != 0)
            return -1;
        if (check_desc(p->desc, p->name, p->source, d, line, 0) == 0)
            return 0;
        _vrg_shader_pass_free(p);
        p->desc = NULL;
        return -1;
    }
    char why[1024];
    unsigned char *data = NULL;
    size_t size = 0;
    const char *problem = NULL;
    if (read_whole(p->source, &data, &size, why, sizeof why) != 0)
        problem = why;
    else
        problem = elf_problem(data, size, why, sizeof why);
    if (!problem && open_needed_libs(p, data, size, why, sizeof why) != 0)
        problem = why;
    if (!problem && !(p->handle = open_private(p, data, size, &p->keep_fd, why, sizeof why)))
        problem = why;
    free(data);
    if (!problem)
        warn_if_writable(p, d, line);
    if (problem) {
        unload(p);
        /* dlerror's words for a library it needs that no search found */
        const char *hint = strstr(problem, "cannot open shared object file")
                               ? "a library it needs is on neither its RUNPATH ($ORIGIN: the plugin's folder) nor the system's search path"
                               : "is it a plugin built for this machine? a build still writing it is picked up when it finishes";
        fail(d, line, VRG_E_PLUGIN_LOAD_FAILED, hint, "cannot load plugin '%s' from %s: %s", p->name, p->source, problem);
        return -1;
    }
    vrg_plugin_entry_fn entry = (vrg_plugin_entry_fn)dlsym(p->handle, VRG_PLUGIN_ENTRY_SYMBOL);
    if (!entry)
        fail(d, line, VRG_E_PLUGIN_NO_ENTRY, "a plugin's source ends with VRG_PLUGIN(desc)", "plugin '%s' (%s) does not export %s", p->name, p->source,
                     VRG_PLUGIN_ENTRY_SYMBOL);
    else {
        _vrg_running before = _vrg_running_enter(VRG_PLUGIN_ENTRY_SYMBOL, NULL, p);
        p->desc = entry(VRG_ABI_VERSION);
        _vrg_running_leave(before);
        /* plugins built before the size was exported have this runtime's layout */
        const uint32_t *size = (const uint32_t *)dlsym(p->handle, VRG_PLUGIN_DESC_SIZE_SYMBOL);
        if (!p->desc)
            fail(d, line, VRG_E_PLUGIN_NO_ENTRY, NULL, "plugin '%s' (%s): %s returned NULL", p->name, p->source, VRG_PLUGIN_ENTRY_SYMBOL);
        else if (p->desc->abi_version != VRG_ABI_VERSION)
            fail(d, line, VRG_E_PLUGIN_ABI, "rebuild the plugin against this voxrg's headers", "plugin '%s' (%s) has ABI version %u, this voxrg expects ABI version %u",
                         p->name, p->source, p->desc->abi_version, VRG_ABI_VERSION);
        else if (copy_desc(p, size ? *size : (uint32_t)sizeof(vrg_plugin_desc), d, line) &&
                 _vrg_plugin_check_desc(p->desc, p->name, p->source, d, line) == 0)
            return 0;
    }
    unload(p);
    p->desc = NULL;
    return -1;
}

static const _vrg_plugin *keep(const _vrg_plugin *p)
{
    _vrg_plugin *slot = free_slot(1);
    *slot = *p;
    slot->desc = &slot->desc_copy;
    if (slot->shader_pass)
        slot->desc_copy.name = slot->name; /* made from the shader: its name is the plugin's */
    slot->generation = ++last_generation;
    slot->users = 0;
    return slot;
}

/* ---- descriptors ---- */

/* A name a graph can write: the key's text after "PASS." (no '=', ';', '#',
 * '[', ']', white space or control characters), below VRG_NAME_MAX. */
static int valid_name(const char *s)
{
    size_t n = s ? strlen(s) : 0;
    if (n == 0 || n >= VRG_NAME_MAX)
        return 0;
    for (; *s; s++)
        if ((unsigned char)*s <= ' ' || strchr("=;#[]", *s))
            return 0;
    return 1;
}

/* needs_execute: a plugin's own; a shader-only pass has none (dispatch.c records it) */
static int check_desc(const vrg_plugin_desc *desc, const char *name, const char *path, _vrg_diag *d, int line, int needs_execute)
{
    const char *why = NULL;
    char buf[512];
    if (!desc->name || strcmp(desc->name, name) != 0)
        why = "its descriptor's name differs from its file name";
    else if (desc->kind != VRG_PLUGIN_PASS && desc->kind != VRG_PLUGIN_SCENE)
        why = "kind is neither VRG_PLUGIN_PASS nor VRG_PLUGIN_SCENE";
    else if (needs_execute && !desc->execute && (desc->kind == VRG_PLUGIN_SCENE || !desc->dispatch_count))
        why = desc->kind == VRG_PLUGIN_SCENE ? "execute callback is NULL" : "execute callback is NULL and it lists no dispatches for the runtime to record";
    else if (desc->slot_count > VRG_MAX_SLOTS || (desc->slot_count && !desc->slots))
        why = desc->slot_count > VRG_MAX_SLOTS ? (snprintf(buf, sizeof buf, "%u slots, more than the %d a plugin may have", desc->slot_count, VRG_MAX_SLOTS), buf)
                                               : "slot_count is set but slots is NULL";
    else if (desc->param_count > VRG_MAX_PARAMS || (desc->param_count && !desc->params))
        why = desc->param_count > VRG_MAX_PARAMS ? (snprintf(buf, sizeof buf, "%u parameters, more than the %d a plugin may have", desc->param_count, VRG_MAX_PARAMS), buf)
                                                 : "param_count is set but params is NULL";
    else if (desc->dispatch_count > VRG_MAX_DISPATCHES || (desc->dispatch_count && !desc->dispatches))
        why = desc->dispatch_count > VRG_MAX_DISPATCHES
                  ? (snprintf(buf, sizeof buf, "%u listed dispatches, more than the %d a plugin may list", desc->dispatch_count, VRG_MAX_DISPATCHES), buf)
                  : "dispatch_count is set but dispatches is NULL";
    for (uint32_t i = 0; !why && i < desc->dispatch_count; i++)
        if (!desc->dispatches[i].shader)
            why = (snprintf(buf, sizeof buf, "listed dispatch %u names no shader", i), buf);
    if (why) {
        fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): %s", name, path, why);
        return -1;
    }
    for (uint32_t i = 0; i < desc->param_count; i++) {
        const vrg_param_desc *pd = &desc->params[i];
        if (!valid_name(pd->name)) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, "names are 1-63 characters without spaces, '=', ';', '#', '[' or ']'",
                         "plugin '%s' (%s): parameter %u has %s name", name, path, i, pd->name ? "an invalid" : "a NULL");
            return -1;
        }
        if (strcmp(pd->name, "plugin") == 0 || strcmp(pd->name, "output_scale") == 0 || strncmp(pd->name, "in.", 3) == 0 ||
            strncmp(pd->name, "out.", 4) == 0) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, "plugin, output_scale, in.* and out.* are the graph's keys in a [pass] section",
                 "plugin '%s' (%s): parameter '%s' has a name the graph file keeps for itself", name, path, pd->name);
            return -1;
        }
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(desc->params[j].name, pd->name) == 0) {
                fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): two parameters named '%s' (%u and %u)", name, path, pd->name, j, i);
                return -1;
            }
        if ((why = _vrg_param_problem(pd, buf, sizeof buf))) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): parameter '%s' %s", name, path, pd->name, why);
            return -1;
        }
        const char *choices = _vrg_param_choices(desc, i);
        if (choices && (why = _vrg_choices_problem(pd, choices, buf, sizeof buf))) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): parameter '%s' %s", name, path, pd->name, why);
            return -1;
        }
    }
    for (uint32_t i = 0; i < desc->slot_count; i++) {
        const vrg_slot_desc *s = &desc->slots[i];
        if (!valid_name(s->name) || (s->dir != VRG_IN && s->dir != VRG_OUT) || s->kind < VRG_IMAGE || s->kind > VRG_ACCEL ||
            s->access < VRG_ACCESS_SAMPLED || s->access > VRG_ACCESS_TEXEL_READ) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): slot %u is malformed (name, dir, kind, access)", name, path, i);
            return -1;
        }
        int as_access = s->access == VRG_ACCESS_AS_BUILD || s->access == VRG_ACCESS_RAY_QUERY;
        if ((s->access == VRG_ACCESS_SAMPLED && s->kind != VRG_IMAGE) || ((s->access == VRG_ACCESS_UNIFORM || s->access == VRG_ACCESS_TEXEL_READ) && s->kind != VRG_BUFFER) ||
            as_access != (s->kind == VRG_ACCEL)) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): slot '%s': %s access does not fit a%s", name, path, s->name, _vrg_access_name(s->access),
                         s->kind == VRG_IMAGE ? "n image" : s->kind == VRG_BUFFER ? " buffer" : "n acceleration structure");
            return -1;
        }
        /* a buffer's format is the texel format of its TEXEL_READ views */
        int texel_format = s->format == VK_FORMAT_R32_UINT || s->format == VK_FORMAT_R32G32_UINT || s->format == VK_FORMAT_R32G32B32A32_UINT;
        if (s->kind == VRG_BUFFER && s->format && !texel_format) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): slot '%s': a buffer's format is the texel format of its TEXEL_READ views: r32ui, rg32ui or rgba32ui, not %s",
                         name, path, s->name, _vrg_format_name(s->format));
            return -1;
        }
        if (s->kind == VRG_BUFFER && s->format && s->dir == VRG_IN && s->access != VRG_ACCESS_TEXEL_READ) {
            fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): slot '%s': a %s input names a texel format; only texel-read inputs (VRG_ACCESS_TEXEL_READ) and outputs do",
                         name, path, s->name, _vrg_access_name(s->access));
            return -1;
        }
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(desc->slots[j].name, s->name) == 0 && desc->slots[j].dir == s->dir) {
                fail(d, line, VRG_E_PLUGIN_BAD_DESC, NULL, "plugin '%s' (%s): two %s slots named '%s'", name, path, s->dir == VRG_IN ? "input" : "output", s->name);
                return -1;
            }
    }
    return 0;
}

int _vrg_plugin_check_desc(const vrg_plugin_desc *desc, const char *name, const char *path, _vrg_diag *d, int line)
{
    return check_desc(desc, name, path, d, line, 1);
}

/* ---- the entry points ---- */

const _vrg_plugin *_vrg_plugin_load(const char *name, const char *graph_path, const char *plugin_path, _vrg_diag *d, int line)
{
    if (!name[0] || strchr(name, '/') || strlen(name) >= VRG_NAME_MAX) {
        fail(d, line, VRG_E_UNKNOWN_PLUGIN, "a plugin is named by its file name without .so or .comp (at most 63 characters)", "unknown plugin '%s'", name);
        return NULL;
    }
    search_path s;
    search_path_build(&s, graph_path, plugin_path);
    if (s.failed) {
        fail(d, line, VRG_E_OUT_OF_MEMORY, NULL, "cannot load plugin '%s': out of memory for the search path", name);
        free(s.dirs);
        return NULL;
    }
    char file[VRG_PATH_MAX + VRG_NAME_MAX + 8], real[VRG_PATH_MAX];
    int at = search_path_find(&s, name, 0, file, sizeof file);
    const _vrg_plugin *result = NULL;
    if (at < 0) {
        char hint[8192];
        search_path_hint(&s, hint, sizeof hint);
        if (graph_path) {
            char base[VRG_PATH_MAX], beside[VRG_PATH_MAX + 2 * VRG_NAME_MAX];
            folder_of(graph_path, base, sizeof base);
            for (int k = 0; k < 4 && !plugin_path; k++) {
                snprintf(beside, sizeof beside, "%s/%s%s.%s", base, k & 1 ? "plugins/" : "", name, k & 2 ? "comp" : "so");
                if (access(beside, F_OK) == 0)
                    snprintf(hint, sizeof hint, "%s is beside the graph, but a graph's folder is searched only when the graph names it: add "
                             "'plugin_path = %s' to [graph]", beside, k & 1 ? "plugins" : ".");
            }
        }
        fail(d, line, VRG_E_UNKNOWN_PLUGIN, hint, "unknown plugin '%s'", name);
        goto done;
    }
    if (!realpath(file, real))
        snprintf(real, sizeof real, "%s", file);
    /* never shadowed: say so when a later folder of the user's has the name */
    char other[sizeof file];
    for (int k = at + 1; s.dirs[at].origin <= DIR_INSTALLED && (k = search_path_find(&s, name, k, other, sizeof other)) >= 0; k++)
        if (s.dirs[k].origin > DIR_INSTALLED)
            _vrg_warning_at(d, line, VRG_W_PLUGIN_SHADOWED, "%s (%s) is not used: the %s plugin %s comes first; built-in and installed plugins are never shadowed, "
                        "so give yours another name", other, origin_names[s.dirs[k].origin], origin_names[s.dirs[at].origin], real);
    if ((result = newest(real, 1)))
        goto done; /* this file is loaded already: the newest version of it */
    if (!is_regular(real)) {
        fail(d, line, VRG_E_PLUGIN_LOAD_FAILED, NULL, "cannot load plugin '%s' from %s: it is not a regular file", name, real);
        goto done;
    }
    if (!free_slot(0)) {
        fail(d, line, VRG_E_TOO_MANY_PLUGINS, "fewer plugins per process, or fewer rebuilds kept alive by running graphs",
                     "cannot load plugin '%s': %d plugin versions are loaded, the most a process holds", name, VRG_MAX_PLUGINS);
        goto done;
    }
    _vrg_plugin p = {.keep_fd = -1};
    snprintf(p.name, sizeof p.name, "%s", name);
    snprintf(p.source, sizeof p.source, "%s", real);
    snprintf(p.path, sizeof p.path, "%s", real);
    if (load_file(&p, d, line) == 0)
        result = keep(&p);
done:
    free(s.dirs);
    return result;
}

/* Hot reload of a rebuilt plugin file (one a loaded plugin came from): it
 * is loaded like any plugin, from a private copy, and becomes the newest
 * version of that file (graphs loaded from now on use it); the old version
 * stays loaded while graphs still run it, and is unloaded with its last user. */
int _vrg_plugin_reload(const char *path, _vrg_diag *d)
{
    _vrg_plugin *old = newest(path, 1);
    if (!old) {
        _vrg_error(d, VRG_E_NOT_A_LOADED_PLUGIN, "plugin %s: not a loaded plugin", path);
        return -1;
    }
    if (!free_slot(0)) {
        _vrg_error(d, VRG_E_TOO_MANY_PLUGINS, "plugin %s: %d plugin versions are loaded, the most a process holds", path, VRG_MAX_PLUGINS);
        return -1;
    }
    _vrg_plugin p = {.keep_fd = -1};
    snprintf(p.name, sizeof p.name, "%s", old->name);
    snprintf(p.source, sizeof p.source, "%s", path);
    snprintf(p.path, sizeof p.path, "%s", path);
    if (load_file(&p, d, 0) != 0)
        return -1;
    keep(&p);
    if (old->users == 0) { /* superseded with no pass running it: unload now */
        old->users = 1;
        _vrg_plugin_release(old);
    }
    return 0;
}

/* Whether a .comp's own text names a slot: a word in_NAME or out_NAME
 * outside comments. A listing skips one that names none: it is a C
 * plugin's helper shader (say NAME_pass2.comp beside NAME.so), which only
 * compiles with the defines its plugin dispatches it with, not a pass
 * (docs/plugin-abi.md, "A pass in one file"). A graph that names it
 * still loads it, and says what is wrong. Unreadable: 1 (listed, so the
 * failure is said). */
static int names_a_slot(const char *file)
{
    FILE *f = fopen(file, "r");
    if (!f)
        return 1;
    int c, prev = '\n', found = 0;
    size_t w = 0; /* characters of the current word so far */
    char word[5];
    enum { CODE, LINE_COMMENT, BLOCK_COMMENT } state = CODE;
    while (!found && (c = fgetc(f)) != EOF) {
        if (state == LINE_COMMENT)
            state = c == '\n' ? CODE : state;
        else if (state == BLOCK_COMMENT) {
            if (prev == '*' && c == '/')
                state = CODE, c = ' ';
        } else if (prev == '/' && (c == '/' || c == '*')) {
            state = c == '/' ? LINE_COMMENT : BLOCK_COMMENT;
            c = ' ';
        } else if (isalnum(c) || c == '_') {
            if (w < sizeof word)
                word[w] = (char)c;
            w++;
            /* a character after "in_" or "out_" at the word's start */
            found = (w > 3 && strncmp(word, "in_", 3) == 0) || (w > 4 && strncmp(word, "out_", 4) == 0);
        } else
            w = 0;
        prev = c;
    }
    fclose(f);
    return found;
}

static int by_name(const void *a, const void *b)
{
    return strcmp((*(const _vrg_plugin *const *)a)->name, (*(const _vrg_plugin *const *)b)->name);
}

int _vrg_plugin_list(const _vrg_plugin **out, int max, FILE *problems, int *failed)
{
    search_path s;
    search_path_build(&s, NULL, NULL);
    *failed = 0;
    if (s.failed) {
        _vrg_diag shown = {.out = problems ? problems : stderr, .file = "plugins"};
        _vrg_error(&shown, VRG_E_OUT_OF_MEMORY, "out of memory for the plugin search path: the listing is incomplete");
        *failed = 1;
    }
    FILE *devnull = problems ? NULL : fopen("/dev/null", "w");
    _vrg_diag diag = {.out = problems ? problems : devnull ? devnull : stderr, .file = "plugins"};
    for (int i = 0; i < s.count; i++) {
        DIR *dir = opendir(s.dirs[i].path);
        struct dirent *e;
        while (dir && (e = readdir(dir))) {
            size_t len = strlen(e->d_name);
            size_t ext = len >= 4 && strcmp(e->d_name + len - 3, ".so") == 0 ? 3 : len >= 6 && strcmp(e->d_name + len - 5, ".comp") == 0 ? 5 : 0;
            if (!ext)
                continue;
            char name[VRG_NAME_MAX];
            if (len - ext >= VRG_NAME_MAX) {
                _vrg_error(&diag, VRG_E_PLUGIN_NAME_TOO_LONG, "%s/%s: the name is longer than %d characters, so no graph can name it", s.dirs[i].path, e->d_name, VRG_NAME_MAX - 1);
                continue;
            }
            snprintf(name, sizeof name, "%.*s", (int)(len - ext), e->d_name);
            char file[VRG_PATH_MAX + VRG_NAME_MAX + 8];
            /* only the file the search order picks for this name, once
             * (a folder holding both: the .so) */
            if (search_path_find(&s, name, 0, file, sizeof file) == i && (ext == 3 || (!ambiguous(&s, i, name) && names_a_slot(file))))
                _vrg_plugin_load(name, NULL, NULL, &diag, 0);
        }
        if (dir)
            closedir(dir);
    }
    free(s.dirs);
    if (devnull)
        fclose(devnull);
    *failed += diag.errors;
    int n = 0;
    for (int i = 0; i < loaded_count; i++)
        if (loaded[i].name[0] && newest(loaded[i].source, 1) == &loaded[i]) { /* current versions only */
            if (n < max)
                out[n] = &loaded[i];
            n++;
        }
    qsort(out, (size_t)(n < max ? n : max), sizeof *out, by_name);
    return n;
}

int vrg_list_plugins(const vrg_plugin_desc **descs, const char **paths, int max, FILE *problems, int *failed)
{
    const _vrg_plugin *list[VRG_MAX_PLUGINS];
    int refused;
    int n = _vrg_plugin_list(list, VRG_MAX_PLUGINS, problems, &refused);
    if (failed)
        *failed = refused;
    for (int i = 0; i < n && i < max && i < VRG_MAX_PLUGINS; i++) {
        descs[i] = list[i]->desc;
        paths[i] = list[i]->source;
    }
    return n;
}

int vrg_find_plugin(const char *name, FILE *diag, const vrg_plugin_desc **desc, const char **path)
{
    _vrg_diag d = {.out = diag ? diag : stderr, .file = "plugins"};
    /* a graph's own plugin_path is that graph's: this answers for the
     * search path every graph shares */
    const _vrg_plugin *p = _vrg_plugin_load(name, NULL, NULL, &d, 0);
    if (!p)
        return -1;
    *desc = p->desc;
    *path = p->source;
    return 0;
}
