#!/usr/bin/env python3
"""Plugins as a hostile world hands them over: graph-local plugins that try
to shadow shipped ones, plugins anyone may replace (a warning), truncated builds, garbage, a FIFO named like a
plugin, a pass that crashes, and hot-reload faults while `render --watch`
runs (a good build copied over the loaded file in place, a truncated build,
garbage, the graph deleted, a half-written graph). None may crash voxrg;
each must be reported with the file's path; under --watch the last good
version keeps running and SIGTERM still ends the run cleanly. No private
plugin copy may be left behind in $TMPDIR.
Usage: test_plugin_faults.py VOXRG INCLUDE_DIR OUT_DIR"""
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_pixels  # noqa: E402

VOXRG, INCLUDE, OUT = sys.argv[1:4]
WAIT_S = 180   # wall-clock limit of any wait (ASan builds JIT slowly)
BOUND = 10     # frames from a change to the first frame showing it
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def save(path, text):
    with open(path, "w") as f:
        f.write(text)


TMPDIR = os.path.join(OUT, "tmp")
ENV = dict(os.environ, TMPDIR=TMPDIR)


def run(args, env=None, timeout=120):
    p = subprocess.run([VOXRG] + args, capture_output=True, text=True, timeout=timeout, env=dict(ENV, **(env or {})))
    return p.returncode, p.stdout, p.stderr


PAINT = r"""#include "voxrg/plugin.h"
static const vrg_slot_desc slots[] = {{.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE,
    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};
static void execute(vrg_pass *p, VkCommandBuffer cmd) {
    float pc[4] = {VERSION == 1, VERSION == 2, 0, 1};
    (void)vrg_dispatch(p, cmd, &(vrg_dispatch_desc){.shader = "paint.comp", .push = pc, .push_size = sizeof pc});
}
static const vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = "paint", .kind = VRG_PLUGIN_PASS,
    .help = "test: painted by version", .shader_dir = DIR, .slots = slots, .slot_count = 1, .execute = execute};
VRG_PLUGIN(desc)
"""
PAINT_COMP = ("#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
              "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
              "layout(push_constant) uniform P { vec4 c; } pc;\n"
              "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n")
# A plugin named like a shipped one whose constructor leaves a mark: it
# must never be loaded from a graph's folder.
IMPOSTOR = r"""#include <stdio.h>
#include "voxrg/plugin.h"
__attribute__((constructor)) static void mark(void) { FILE *f = fopen(MARKER, "w"); if (f) fclose(f); }
static void execute(vrg_pass *p, VkCommandBuffer cmd) { (void)p; (void)cmd; }
static const vrg_slot_desc slots[] = {{.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE,
    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};
static const vrg_plugin_desc desc = {.abi_version = VRG_ABI_VERSION, .name = "pattern", .kind = VRG_PLUGIN_PASS,
    .slots = slots, .slot_count = 1, .execute = execute};
VRG_PLUGIN(desc)
"""
GRAPH = "[graph]\noutput = color\nwidth = 8\nheight = 8\n%s[pass p]\nplugin = %s\nout.color = color\n"


def build(src_text, out, defines):
    src = out + ".c"
    save(src, src_text)
    subprocess.run(["cc", "-std=c11", "-shared", "-fPIC", "-I" + INCLUDE] + ["-D" + d for d in defines] + [src, "-o", out], check=True)


def leftovers():
    return [n for n in os.listdir(TMPDIR) if n.startswith("voxrg-plugin-")]


# --- the search policy -----------------------------------------------------------
def policy_case(d):
    marker = os.path.join(d, "impostor-ran")
    os.makedirs(os.path.join(d, "plugins"))
    build(IMPOSTOR, os.path.join(d, "plugins", "pattern.so"), ['MARKER="%s"' % marker])
    shutil.copy(os.path.join(d, "plugins", "pattern.so"), os.path.join(d, "pattern.so"))
    graph = os.path.join(d, "innocent.ini")
    for extra in ("", "plugin_path = plugins\n"):
        save(graph, GRAPH % (extra, "pattern"))
        rc, out, err = run(["check", graph, "--no-device"])
        check(rc == 0, "policy: check of a graph beside an impostor: exit %d\n%s" % (rc, err))
        check(not os.path.exists(marker), "policy: the graph's own pattern.so was loaded (%s)" % (extra or "no plugin_path"))
        check(re.search(r"plugin pattern .*/plugins/pattern\.so", out) and os.path.join(d, "plugins") not in out,
              "policy: check does not show the shipped pattern's file:\n%s" % out)
    check("is not used" in err and "never shadowed" in err, "policy: no note that the graph's pattern.so is ignored:\n%s" % err)

    # a plugin of the user's own beside the graph: only with plugin_path
    os.makedirs(os.path.join(d, "mine", "plugins"))
    build(PAINT, os.path.join(d, "mine", "plugins", "paint.so"), ["VERSION=1", 'DIR="%s"' % d])
    graph = os.path.join(d, "mine", "paint.ini")
    save(graph, GRAPH % ("", "paint"))
    rc, out, err = run(["check", graph, "--no-device"])
    check(rc == 1 and "unknown plugin 'paint'" in err and "plugin_path = plugins" in err,
          "policy: a graph-local plugin without plugin_path: exit %d, want 1 with a hint\n%s" % (rc, err))
    save(graph, GRAPH % ("plugin_path = plugins\n", "paint"))
    rc, out, err = run(["check", graph, "--no-device"])
    check(rc == 0 and re.search(r"plugin paint .*mine/plugins/paint\.so", out),
          "policy: with plugin_path = plugins: exit %d\n%s%s" % (rc, out, err))
    rc, out, err = run(["plugins", "nonesuch"])
    check(rc == 1 and "searched:" in err and "(built-in)" in err, "policy: plugins NAME does not say where it looked:\n%s" % err)


# --- code anyone may replace ---------------------------------------------------------
def writable_case(d):
    """A plugin file others may write, or one in a folder others may write
    (without the sticky bit), loads with a warning naming the path."""
    folder = os.path.join(d, "ww")
    os.makedirs(folder)
    so = os.path.join(folder, "paint.so")
    build(PAINT, so, ["VERSION=1", 'DIR="%s"' % d])
    graph = os.path.join(d, "paint.ini")
    save(graph, GRAPH % ("plugin_path = ww\n", "paint"))
    for folder_mode, file_mode, named in ((0o755, 0o755, None), (0o777, 0o755, "its folder %s is writable by every user" % folder),
                                          (0o1777, 0o755, None), (0o755, 0o666, "(%s) is writable by every user" % so)):
        os.chmod(folder, folder_mode)
        os.chmod(so, file_mode)
        rc, out, err = run(["check", graph, "--no-device"])
        what = "writable: folder %o, file %o" % (folder_mode, file_mode)
        check(rc == 0, "%s: exit %d, want 0 (a warning, not an error)\n%s" % (what, rc, err))
        if named:
            check(re.search(r"paint\.ini:7: warning\[VRG-W007\]: plugin 'paint' .*" + re.escape(named), err), "%s: no warning naming it:\n%s" % (what, err))
        else:
            check("VRG-W007" not in err, "%s: a warning where none is due:\n%s" % (what, err))
    os.chmod(folder, 0o755)


# --- files that are no plugin ------------------------------------------------------
def broken_files_case(d):
    good = os.path.join(d, "good.so")
    build(PAINT, good, ["VERSION=1", 'DIR="%s"' % d])
    lib = os.path.join(d, "lib")
    os.makedirs(lib)
    graph = os.path.join(d, "paint.ini")
    save(graph, GRAPH % ("", "paint"))
    blob = open(good, "rb").read()
    # e_phoff (bytes 32-39 of an ELF64 header) near 2^64: the sum with the
    # table's size wraps; the check must not read before its buffer
    wrapped = blob[:32] + (2 ** 64 - 16).to_bytes(8, "little") + blob[40:]
    for what, data, want in (("truncated", blob[:3000], "truncated: 3000 bytes"), ("garbage", b"garbage\n" * 100, "not an ELF file"),
                             ("empty", b"", "not an ELF file"), ("wrapping e_phoff", wrapped, "program headers")):
        with open(os.path.join(lib, "paint.so"), "wb") as f:
            f.write(data)
        for args in (["plugins", "paint"], ["check", graph, "--no-device"], ["render", graph, "--frames", "1", "--out", os.path.join(d, "o")]):
            rc, out, err = run(args, {"VOXRG_PLUGIN_PATH": lib})
            check(rc == 1 and want in err and os.path.join(lib, "paint.so") in err,
                  "%s plugin, voxrg %s: exit %d, want 1 with '%s' and the path\n%s" % (what, args[0], rc, want, err))
    os.remove(os.path.join(lib, "paint.so"))
    os.mkfifo(os.path.join(lib, "paint.so"))
    rc, out, err = run(["plugins", "paint"], {"VOXRG_PLUGIN_PATH": lib}, timeout=60)
    check(rc == 1 and "not a regular file" in err, "FIFO plugin: exit %d\n%s" % (rc, err))
    rc, out, err = run(["plugins"], {"VOXRG_PLUGIN_PATH": lib}, timeout=60)
    check(rc == 1 and "paint.so" in err and "not a regular file" in err and re.search(r"^pattern +pass", out, re.M),
          "FIFO plugin in the listing: exit %d, want 1 with the rest listed\n%s" % (rc, err))


# --- descriptors of other sizes (headers older or newer than voxrg's) ---
SIZED = r"""#include <stddef.h>
#include "voxrg/plugin.h"
static void execute(vrg_pass *p, VkCommandBuffer cmd) { (void)p; (void)cmd; }
static const vrg_slot_desc slots[] = {{.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE,
    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};
static const vrg_param_desc params[] = {{.name = "curve", .type = VRG_PARAM_STRING, .help = "a choice", .default_string = "aces"}};
static const char *const choices[] = {LIST};
static const struct { vrg_plugin_desc d; unsigned long long newer; } desc = {{.abi_version = VRG_ABI_VERSION, .name = "sized",
    .kind = VRG_PLUGIN_PASS, .help = "test: descriptor size", .slots = slots, .slot_count = 1, .execute = EXECUTE,
    .params = params, .param_count = 1, .param_choices = CHOICES}, NEWER};
VRG_EXPORT const vrg_plugin_desc *vrg_plugin_entry(uint32_t host_abi) { (void)host_abi; return &desc.d; }
VRG_EXPORT const uint32_t vrg_plugin_desc_size = SIZE;
"""


def desc_size_case(d):
    old = ["EXECUTE=execute", "CHOICES=NULL", "LIST=NULL"]
    for what, size, newer, want_rc, want, more in (
            ("older headers (no check field)", "offsetof(vrg_plugin_desc, check)", "0", 0, "test: descriptor size", old),
            ("newer headers, new field unset", "sizeof desc", "0", 0, "test: descriptor size", old),
            ("newer headers, new field set", "sizeof desc", "1", 1, "sets fields this voxrg", old),
            ("too short for execute", "8", "0", 1, "too short to hold execute", old),
            # a pass without execute lists the dispatches the runtime records in its stead
            ("no execute and no dispatches", "sizeof desc", "0", 1, "execute callback is NULL and it lists no dispatches",
             ["EXECUTE=NULL", "CHOICES=NULL", "LIST=NULL"]),
            # param_choices: the default among them, names a graph can write, each once
            ("choices without the default", "sizeof desc", "0", 1, "parameter 'curve' has default 'aces', which is none of its choices linear,reinhard",
             ["EXECUTE=execute", "CHOICES=choices", 'LIST="linear,reinhard"']),
            ("a choice named twice", "sizeof desc", "0", 1, "parameter 'curve' names choice 'aces' twice",
             ["EXECUTE=execute", "CHOICES=choices", 'LIST="aces,linear,aces"']),
            ("choices listed", "sizeof desc", "0", 0, "aces|linear", ["EXECUTE=execute", "CHOICES=choices", 'LIST="aces,linear"'])):
        lib = os.path.join(d, what.replace(" ", "_").replace(",", "").replace("(", "").replace(")", ""))
        os.makedirs(lib)
        build(SIZED, os.path.join(lib, "sized.so"), ["SIZE=" + size, "NEWER=" + newer] + more)
        rc, out, err = run(["plugins", "sized"], {"VOXRG_PLUGIN_PATH": lib})
        check(rc == want_rc and want in out + err, "descriptor size, %s: exit %d, want %d with '%s'\n%s%s" % (what, rc, want_rc, want, out, err))


# --- a pass that crashes ------------------------------------------------------------
def crash_case(d):
    graph = os.path.join(d, "crash.ini")
    save(graph, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass boom]\nplugin = crashes\nout.color = color\n")
    rc, out, err = run(["render", graph, "--frames", "3", "--out", os.path.join(d, "o")])
    check(rc != 0 and re.search(r"voxrg: SIGSEGV .* in pass 'boom' \(plugin 'crashes', .*/crashes\.so\) during execute", err),
          "crash: exit %d, want a line naming pass, plugin, file and callback:\n%s" % (rc, err[-2000:]))


# --- hot-reload faults --------------------------------------------------------------
def frame_color(path):
    end = time.time() + WAIT_S
    while not os.path.exists(path):
        if time.time() > end:
            raise RuntimeError("no frame %s" % path)
        time.sleep(0.01)
    return png_pixels.load(path)[2](1, 1)


def watch_case(d):
    save(os.path.join(d, "paint.comp"), PAINT_COMP)
    builds = {}
    for v in (1, 2):
        builds[v] = os.path.join(d, "v%d.so" % v)
        build(PAINT, builds[v], ["VERSION=%d" % v, 'DIR="%s"' % d])
    so = os.path.join(d, "paint.so")
    shutil.copy(builds[1], so)
    graph = os.path.join(d, "paint.ini")
    save(graph, GRAPH % ("", "paint"))
    frames = os.path.join(d, "frames")
    os.makedirs(frames)
    err_path = os.path.join(d, "stderr.txt")
    err = open(err_path, "w")
    proc = subprocess.Popen([VOXRG, "render", graph, "--watch", "--validate", "--frames", "0", "--interval", "30", "--sequence",
                             "--out", frames], stdout=subprocess.DEVNULL, stderr=err, env=dict(ENV, VOXRG_PLUGIN_PATH=d))

    def latest():
        ks = [int(m.group(1)) for m in (re.match(r"color-(\d{5})\.png$", n) for n in os.listdir(frames)) if m]
        return max(ks, default=-1)

    def settle(n=3):
        k = latest()
        frame_color(os.path.join(frames, "color-%05d.png" % (k + n)))
        return latest()

    def shows(after, rgb):
        for k in range(after + 1, after + BOUND + 1):
            if frame_color(os.path.join(frames, "color-%05d.png" % k)) == rgb:
                return True
        return False

    def stderr_has(pattern, count):
        end = time.time() + WAIT_S
        while len(re.findall(pattern, open(err_path).read())) < count:
            if proc.poll() is not None or time.time() > end:
                return False
            time.sleep(0.02)
        return True

    try:
        check(frame_color(os.path.join(frames, "color-00002.png")) == (255, 0, 0), "watch: version 1 is not red")
        # a good build copied over the loaded file, same inode (cp): the
        # running code is a private copy, so this is just a reload
        k = settle()
        ino = os.stat(so).st_ino
        with open(so, "r+b") as f:
            f.truncate(0)
            f.write(open(builds[2], "rb").read())
        check(os.stat(so).st_ino == ino, "watch: the overwrite made a new file")
        check(shows(k, (0, 255, 0)), "watch: version 2 written in place did not show within %d frames" % BOUND)
        # broken builds in place: reported, the last good version keeps going
        errors = 0
        for what, data, want in (("truncated", open(builds[1], "rb").read()[:3000], "truncated: 3000 bytes"),
                                 ("garbage", b"\x7fELF garbage", "truncated")):
            k = settle()
            with open(so, "r+b") as f:
                f.truncate(0)
                f.write(data)
            errors += 1
            check(stderr_has(re.escape(so) + ".*" + re.escape(want), 1), "watch: the %s build was not reported with its path" % what)
            check(proc.poll() is None, "watch: the process stopped on a %s plugin" % what)
            check(not shows(k, (255, 0, 0)) and shows(settle(), (0, 255, 0)), "watch: version 2 stopped after a %s build" % what)
        k = settle()
        shutil.copy(builds[1], so + ".new")
        os.rename(so + ".new", so)
        check(shows(k, (255, 0, 0)), "watch: a good build after broken ones did not show")
        # the graph deleted (nothing to reload), then written half, then whole
        os.remove(graph)
        settle(5)
        check(proc.poll() is None, "watch: the process stopped when the graph was deleted")
        text = GRAPH % ("", "paint")
        save(graph, text[: text.index("out.color") + 5])
        check(stderr_has(r"paint\.ini:\d+: error", 1), "watch: the half-written graph was not reported with file:line")
        check(shows(settle(), (255, 0, 0)), "watch: the last good graph stopped after a half-written save")
        reloads = len(re.findall("reloaded,", open(err_path).read()))
        save(graph, text)
        check(stderr_has("reloaded,", reloads + 1), "watch: the graph written whole again did not reload")
        check(shows(settle(), (255, 0, 0)), "watch: version 1 stopped after the graph was reloaded")
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            rc = proc.wait(WAIT_S)
        except subprocess.TimeoutExpired:
            proc.kill()
            rc = proc.wait()
        err.close()
    text = open(err_path).read()
    check(rc == 0, "watch: exit %s after SIGTERM, want 0 (under --validate: no validation message); stderr:\n%s" % (rc, text[-3000:]))


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(TMPDIR)
    for name, case in (("policy", policy_case), ("broken_files", broken_files_case), ("desc_size", desc_size_case), ("writable", writable_case), ("crash", crash_case), ("watch", watch_case)):
        d = os.path.join(OUT, name)
        os.makedirs(d)
        try:
            case(d)
        except (RuntimeError, subprocess.CalledProcessError, subprocess.TimeoutExpired) as e:
            check(False, "%s: %s" % (name, e))
        print("%s: done" % name, flush=True)
    check(not leftovers(), "private plugin copies left in $TMPDIR: %s" % leftovers())
    print("plugin_faults: %s" % ("FAILED (%d)" % len(failures) if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
