#!/usr/bin/env python3
"""Scripted hot reload through `voxrg render --watch`, the way a user's script
drives it: the renderer runs until interrupted (--frames 0), paced
(--interval) and writing every frame (--sequence), while this script edits a
shader, the graph file and a plugin's source (rebuilt with cc) and reads the
frames that follow. Each change must show within BOUND frames of the save; a
broken shader, graph or plugin must be reported (FILE:LINE, or the plugin's
path) while the process keeps running with the last good version; SIGTERM
ends it with exit 0, which under --validate also means no validation message.
Usage: test_watch.py VOXRG TESTS_DIR INCLUDE_DIR OUT_DIR"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_pixels  # noqa: E402

VOXRG, TESTS, INCLUDE, OUT = sys.argv[1:5]
BOUND = 10          # frames from a save to the first frame showing it
WAIT_S = 180        # wall-clock limit of any wait (ASan builds JIT slowly)
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def save(path, text):
    with open(path, "w") as f:  # written in place and closed, as editors do
        f.write(text)


def linear(byte):
    """Inverse of the PNG writer's sRGB encoding of a linear value."""
    c = byte / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


class Render:
    """One `voxrg render --watch` process and the frames it writes."""

    def __init__(self, name, graph, output, env):
        self.dir = os.path.join(OUT, name)
        os.makedirs(self.dir)
        self.output = output
        self.err_path = os.path.join(self.dir, "stderr.txt")
        self.err = open(self.err_path, "w")
        self.proc = subprocess.Popen(
            [VOXRG, "render", graph, "--watch", "--validate", "--frames", "0", "--interval", "30",
             "--sequence", "--out", self.dir], stdout=subprocess.DEVNULL, stderr=self.err,
            env=dict(os.environ, **env))

    def path(self, k):
        return os.path.join(self.dir, "%s-%05d.png" % (self.output, k))

    def latest(self):
        """The last frame written so far (-1 before the first)."""
        pat = re.compile(re.escape(self.output) + r"-(\d{5})\.png$")
        ks = [int(m.group(1)) for m in map(pat.match, os.listdir(self.dir)) if m]
        return max(ks, default=-1)

    def alive(self):
        return self.proc.poll() is None

    def frame(self, k):
        """Frame k as (width, height, pixel(1, 1)), waiting for it."""
        end = time.time() + WAIT_S
        while not os.path.exists(self.path(k)):
            if not self.alive() or time.time() > end:
                raise RuntimeError("%s: frame %d never came (exit %s); stderr:\n%s"
                                   % (self.dir, k, self.proc.poll(), self.stderr()))
            time.sleep(0.01)
        w, h, pixel = png_pixels.load(self.path(k))
        return w, h, pixel(1, 1)

    def stderr(self):
        if not self.err.closed:
            self.err.flush()
        with open(self.err_path) as f:
            return f.read()

    def wait_stderr(self, pattern, count=1):
        """Waits until `pattern` occurs `count` times in stderr."""
        end = time.time() + WAIT_S
        while len(re.findall(pattern, self.stderr())) < count:
            if not self.alive() or time.time() > end:
                return False
            time.sleep(0.02)
        return True

    def first(self, after, want):
        """The first frame after `after` whose (w, h, rgb) satisfies want,
        looking at most BOUND frames ahead; None if none does."""
        for k in range(after + 1, after + BOUND + 1):
            if want(*self.frame(k)):
                return k
        return None

    def stop(self, what):
        self.proc.send_signal(signal.SIGTERM)
        try:
            rc = self.proc.wait(WAIT_S)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        self.err.close()
        text = self.stderr()
        check(rc == 0, "%s: exit %s after SIGTERM, want 0; stderr:\n%s" % (what, rc, text[-3000:]))
        check("interrupted after" in text, "%s: no 'interrupted after' line" % what)
        check(os.path.exists(os.path.join(self.dir, self.output + ".png")), "%s: no final %s.png" % (what, self.output))


def settle(r, frames=3):
    """Lets a few frames pass; returns the last one written."""
    k = r.latest()
    r.frame(k + frames)
    return r.latest()


# --- a shader (user.comp on $VOXRG_SHADER_PATH) ---------------------------------
def shader_case(tmp):
    shader = os.path.join(tmp, "user.comp")
    body = ("#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
            "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
            "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), vec4(%s, 1.0)); }\n")
    save(shader, body % "0.25, 0.5, 0.75")
    r = Render("shader", os.path.join(TESTS, "graphs", "shader_file.ini"), "color", {"VOXRG_SHADER_PATH": tmp})
    _, _, rgb = r.frame(2)
    check(rgb == (137, 188, 225), "shader: first version gives %s, want (137, 188, 225)" % (rgb,))

    k = settle(r)
    save(shader, body % "1.0, 0.0, 0.0")
    red = r.first(k, lambda w, h, c: c == (255, 0, 0))
    check(red is not None, "shader: the constant red did not show within %d frames of frame %d" % (BOUND, k))

    k = settle(r)
    save(shader, "#version 450\nlayout(local_size_x = 8) in;\nvoid main() { this is not glsl }\n")
    check(r.wait_stderr(r"user\.comp:3: error\[VRG-E063\]"), "shader: the syntax error was not reported at user.comp:3")
    check(r.alive(), "shader: the process stopped on a broken shader")
    k = r.latest()
    for j in range(k + 1, k + BOUND):
        c = r.frame(j)[2]
        if not check(c == (255, 0, 0), "shader: frame %d after the broken save is %s, not the last good red" % (j, c)):
            break

    # valid GLSL that disagrees with the slot (rgba32f for rgba16f): the
    # reflection check fails the reload like a compile error does
    save(shader, body.replace("rgba16f", "rgba32f") % "0.0, 0.0, 1.0")
    check(r.wait_stderr(r"user\.comp:3: error\[VRG-E066\]: binding 0 'dst' is rgba32f, but slot 'out.color' of pass 'user' \(plugin shader_file\) is rgba16f"),
          "shader: the format mismatch was not reported at user.comp:3")
    check(r.alive(), "shader: the process stopped on a mismatching shader")
    k = r.latest()
    for j in range(k + 1, k + BOUND):
        c = r.frame(j)[2]
        if not check(c == (255, 0, 0), "shader: frame %d after the mismatching save is %s, not the last good red" % (j, c)):
            break

    k = settle(r)
    save(shader, body % "0.0, 1.0, 0.0")
    check(r.first(k, lambda w, h, c: c == (0, 255, 0)) is not None, "shader: the fixed shader did not show")
    r.stop("shader")


# --- the graph file -------------------------------------------------------------
GRAPH = """[graph]
output = count
width  = 8
height = 8

[pass counter]
plugin    = counter
in.prev   = count@prev
out.count = count
step      = {step}
{extra}"""


def graph_case(tmp):
    path = os.path.join(tmp, "watch.ini")
    save(path, GRAPH.format(step=0.01, extra=""))
    r = Render("graph", path, "count", {})
    value = lambda k: linear(r.frame(k)[2][0])  # noqa: E731
    check(abs(value(4) - 0.05) < 0.004, "graph: frame 4 counts %.4f, want 0.05" % value(4))
    reloads = 0

    # parameters only: the count goes on from where it was, by the new step
    k = settle(r)
    save(path, GRAPH.format(step=0.02, extra=""))
    reloads += 1
    kp = next((j for j in range(k + 1, k + BOUND + 1) if abs(value(j) - value(j - 1) - 0.02) < 0.006), None)
    if check(kp is not None, "graph: the new step did not show within %d frames of frame %d" % (BOUND, k)):
        check(all(value(j) > value(j - 1) for j in range(k + 1, kp + 1)),
              "graph: the count dropped after a parameter change: history was not kept")
    check(r.wait_stderr(r"reloaded, \d+ ms from save to frame", reloads), "graph: no 'reloaded' line")

    # structural, every history resource unchanged: an unrelated pass added
    k = settle(r)
    save(path, GRAPH.format(step=0.02, extra="\n[pass other]\nplugin = counter\nout.count = other\n"))
    reloads += 1
    check(r.wait_stderr(r"reloaded, \d+ ms from save to frame", reloads), "graph: the added pass was not reloaded")
    k2 = settle(r)
    check(all(abs(value(j) - value(j - 1) - 0.02) < 0.006 for j in range(k + 1, k2 + 1)),
          "graph: the count did not go on across a pass being added: %s" % [round(value(j), 3) for j in range(k, k2 + 1)])

    # structural, the history resource resized: it starts anew
    k = settle(r)
    save(path, GRAPH.format(step=0.02, extra="\n[resource count]\nscale = 0.5\n"))
    reloads += 1
    kr = r.first(k, lambda w, h, c: w == 4)
    if check(kr is not None, "graph: the resized count did not show within %d frames of frame %d" % (BOUND, k)):
        check(abs(value(kr) - 0.02) < 0.004, "graph: the resized count starts at %.4f, want 0.02 (history anew)" % value(kr))

    # broken: reported at FILE:LINE, the running graph goes on counting
    k = settle(r)
    save(path, GRAPH.format(step=0.05, extra="\nthis line is not ini\n"))
    check(r.wait_stderr(r"watch\.ini:12: error"), "graph: the broken graph was not reported at watch.ini:12")
    check(r.alive(), "graph: the process stopped on a broken graph")
    k = r.latest()
    k2 = settle(r, 5)
    check(all(r.frame(j)[0] == 4 and abs(value(j) - value(j - 1) - 0.02) < 0.006 for j in range(k + 1, k2 + 1)),
          "graph: the last good graph did not keep running after a broken save")
    r.stop("graph")


# --- a plugin rebuilt -------------------------------------------------------------
PLUGIN = r"""#include "voxrg/plugin.h"
static const vrg_slot_desc slots[] = {{.name = "color", .dir = VRG_OUT, .kind = VRG_IMAGE,
    .access = VRG_ACCESS_STORAGE_WRITE, .format = VK_FORMAT_R16G16B16A16_SFLOAT}};
static void execute(vrg_pass *p, VkCommandBuffer cmd) {
    float pc[4] = {VERSION == 1, VERSION == 2, 0, 1};
    (void)vrg_dispatch(p, cmd, &(vrg_dispatch_desc){.shader = "paint.comp", .push = pc, .push_size = sizeof pc});
}
static const vrg_plugin_desc desc = {.abi_version = ABI, .name = "paint", .kind = VRG_PLUGIN_PASS,
    .help = "test: painted by version", .shader_dir = DIR, .slots = slots, .slot_count = 1, .execute = execute};
VRG_PLUGIN(desc)
"""


def compile_plugin(tmp, version, abi="VRG_ABI_VERSION"):
    """paint.so of this version, compiled beside it (before the renderer runs:
    compile time on a busy machine would count against the frame bound)."""
    src, out = os.path.join(tmp, "paint.c"), os.path.join(tmp, "paint-v%d-%s.so" % (version, abi))
    save(src, PLUGIN)
    subprocess.run(["cc", "-std=c11", "-shared", "-fPIC", "-I" + INCLUDE, "-DVERSION=%d" % version, "-DABI=" + abi,
                    '-DDIR="%s"' % tmp, src, "-o", out], check=True)
    return out


def build_plugin(tmp, version, abi="VRG_ABI_VERSION"):
    """Installs paint.so the way a build system does: a new file renamed over the old."""
    so = os.path.join(tmp, "paint.so")
    shutil.copy(os.path.join(tmp, "paint-v%d-%s.so" % (version, abi)), so + ".new")
    os.rename(so + ".new", so)
    return so


def plugin_case(tmp):
    save(os.path.join(tmp, "paint.comp"),
         "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
         "layout(binding = 0, rgba16f) uniform writeonly image2D dst;\n"
         "layout(push_constant) uniform P { vec4 c; } pc;\n"
         "void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), pc.c); }\n")
    for version, abi in ((1, "VRG_ABI_VERSION"), (2, "VRG_ABI_VERSION"), (1, "999")):
        compile_plugin(tmp, version, abi)
    so = build_plugin(tmp, 1)
    graph = os.path.join(tmp, "paint.ini")
    save(graph, "[graph]\noutput = color\nwidth = 8\nheight = 8\n[pass p]\nplugin = paint\nout.color = color\n")
    r = Render("plugin", graph, "color", {"VOXRG_PLUGIN_PATH": tmp})
    check(r.frame(2)[2] == (255, 0, 0), "plugin: version 1 is not red: %s" % (r.frame(2)[2],))

    k = settle(r)
    build_plugin(tmp, 2)
    check(r.first(k, lambda w, h, c: c == (0, 255, 0)) is not None,
          "plugin: the rebuilt version did not show within %d frames of frame %d" % (BOUND, k))

    k = settle(r)
    build_plugin(tmp, 1, abi="999")
    check(r.wait_stderr(re.escape(so) + r".*ABI version 999"), "plugin: the refused rebuild was not reported with its path")
    check(r.alive(), "plugin: the process stopped on a refused plugin")
    k = r.latest()
    k2 = settle(r, 5)
    check(all(r.frame(j)[2] == (0, 255, 0) for j in range(k + 1, k2 + 1)), "plugin: the running version did not keep going")
    r.stop("plugin")


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    for name, case in (("shader", shader_case), ("graph", graph_case), ("plugin", plugin_case)):
        tmp = os.path.join(OUT, name + "-src")
        os.makedirs(tmp)
        try:
            case(tmp)
        except (RuntimeError, subprocess.CalledProcessError) as e:
            check(False, "%s: %s" % (name, e))
        print("%s: %s" % (name, "done"), flush=True)
    print("watch: %s" % ("FAILED (%d)" % len(failures) if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
