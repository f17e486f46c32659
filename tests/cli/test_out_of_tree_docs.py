#!/usr/bin/env python3
"""docs/out-of-tree.md run as printed: every ```sh block of the page, in
order, in one shell state (what a block exports holds for the next), with
HOME a scratch folder, so that the page's prefix $HOME/voxrg and pass folder
~/fog are in it, and an environment cleared of everything else. A drift
between the page and the program fails here.

Two blocks are not run quite as a user runs them:
- Install: its first line configures and builds the tree, which is the
  build under test (ctest runs after it); `cmake -S . -B build` and
  `cmake --build build` are checked to name the folder `build` that
  `cmake --install build` then installs from, which is this build.
- Hot reload: the renderer runs in the background while this script does
  what the page says a user does: saves an edited fog.comp (the image must
  change), rebuilds an edited fog.c with the page's `cmake --build` (the
  reload is reported, timed from the new fog.so), saves a broken fog.comp
  (reported at fog.comp:LINE, the last good version keeps running) and
  breaks fog.c (the build fails, the running version stays). SIGTERM then
  ends it with exit 0: no validation message. The files are put back and
  rebuilt before the compare block.
Usage: test_out_of_tree_docs.py BUILD_DIR SOURCE_DIR OUT_DIR"""
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_pixels  # noqa: E402

BUILD, SRC, OUT = (os.path.abspath(a) for a in sys.argv[1:4])
PAGE = os.path.join(SRC, "docs", "out-of-tree.md")
HOME = os.path.join(OUT, "home")
STATE = os.path.join(OUT, "state.sh")  # the shell's exports between blocks
BOUND = 10     # frames from a save or rebuild to the first frame showing it
WAIT_S = 300   # wall-clock limit of any wait (the sanitizer build is slow)
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def blocks():
    """The page's fenced blocks as (heading, language, text), in order."""
    out, heading, lang, lines = [], "", None, []
    for line in open(PAGE):
        if lang is None and line.startswith("## "):
            heading = line[3:].strip()
        elif line.startswith("```"):
            if lang is None:
                lang, lines = line[3:].strip(), []
            else:
                out.append((heading, lang, "".join(lines)))
                lang = None
        elif lang is not None:
            lines.append(line)
    return out


def environment():
    """What a user's shell has, plus the sanitizers' settings of the
    sanitizer build."""
    env = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": HOME}
    for k in ("ASAN_OPTIONS", "LSAN_OPTIONS", "UBSAN_OPTIONS"):
        if k in os.environ:
            env[k] = os.environ[k]
    return env


# The install block's first line is this build (see the docstring): cmake
# on the tree's `build` folder is this build, and only the install runs.
INSTALL_SHIM = r"""cmake() {
    case "$1 $2 $3 $4" in
        "-S . -B build") return 0 ;;
        "--build build "*) return 0 ;;
        "--install build "*) shift 2; command cmake --install %s "$@" ;;
        *) echo "the install block runs cmake $*, which this test does not know" >&2; return 1 ;;
    esac
}
""" % shlex.quote(BUILD)


def script(text, shim=""):
    """A block as a bash script: the state of the blocks before, the block
    (stopping at its first failing command), then its exports saved."""
    return "set -e\n. %s\n%s%s\nexport -p > %s\n" % (shlex.quote(STATE), shim, text, shlex.quote(STATE))


def run_block(heading, text, cwd, shim=""):
    log = os.path.join(OUT, "block-%s.log" % re.sub(r"\W+", "-", heading.lower()))
    with open(log, "w") as f:
        rc = subprocess.run(["bash", "-c", script(text, shim)], cwd=cwd, env=environment(), stdout=f, stderr=subprocess.STDOUT).returncode
    if not check(rc == 0, "block '%s' exits %d:\n%s\n--- output:\n%s" % (heading, rc, text, open(log).read()[-4000:])):
        raise RuntimeError("block '%s' failed" % heading)
    return open(log).read()


def fog(name):
    return os.path.join(HOME, "fog", name)


def save(path, text):
    with open(path, "w") as f:  # written in place and closed, as editors do
        f.write(text)


class Watch:
    """The hot-reload block's renderer, run in the background."""

    def __init__(self, text):
        self.err_path = os.path.join(OUT, "watch-stderr.txt")
        self.err = open(self.err_path, "w")
        # exec: the signal reaches voxrg itself
        self.proc = subprocess.Popen(["bash", "-c", ". %s\nexec %s" % (shlex.quote(STATE), text.strip())], cwd=HOME,
                                     env=environment(), stdout=subprocess.DEVNULL, stderr=self.err)

    def path(self, k):
        return fog("out/ldr-%05d.png" % k)

    def latest(self):
        ks = [int(m.group(1)) for m in (re.match(r"ldr-(\d{5})\.png$", n) for n in os.listdir(fog("out"))) if m]
        return max(ks, default=-1)

    def frame(self, k):
        """Frame k as its pixel function, waiting for it."""
        end = time.time() + WAIT_S
        while not os.path.exists(self.path(k)):
            if self.proc.poll() is not None or time.time() > end:
                raise RuntimeError("hot reload: frame %d never came (exit %s); stderr:\n%s" % (k, self.proc.poll(), self.stderr()[-3000:]))
            time.sleep(0.02)
        return png_pixels.load(self.path(k))

    def stderr(self):
        if not self.err.closed:
            self.err.flush()
        with open(self.err_path) as f:
            return f.read()

    def reloads(self):
        return [int(ms) for ms in re.findall(r"reloaded, (\d+) ms from save to frame", self.stderr())]

    def wait_stderr(self, pattern, count):
        end = time.time() + WAIT_S
        while len(re.findall(pattern, self.stderr())) < count:
            if self.proc.poll() is not None or time.time() > end:
                return False
            time.sleep(0.05)
        return True

    def settle(self, frames=2):
        k = max(self.latest(), 0)
        self.frame(k + frames)
        return self.latest()

    def first(self, after, want):
        """The first frame after `after` (at most BOUND on) that satisfies want."""
        for k in range(after + 1, after + BOUND + 1):
            if want(self.frame(k)):
                return k
        return None

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            rc = self.proc.wait(WAIT_S)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        self.err.close()
        check(rc == 0, "hot reload: exit %s after SIGTERM, want 0 (under --validate); stderr:\n%s" % (rc, self.stderr()[-3000:]))


def samples(image):
    """Corners, middle and a quarter point of a frame: enough to tell a
    uniform image from the terrain."""
    w, h, pixel = image
    return [pixel(x, y) for x, y in ((1, 1), (w - 2, 1), (1, h - 2), (w - 2, h - 2), (w // 2, h // 2), (w // 4, h // 3))]


def uniform(image, order):
    """Every sample the same colour, its channels ordered by `order`."""
    s = samples(image)
    r, g, b = s[0]
    return all(max(abs(a - c) for a, c in zip(p, s[0])) <= 1 for p in s) and order(r, g, b)


def warm_red(r, g, b):
    return r > g > b


def grey(r, g, b):
    return max(r, g, b) - min(r, g, b) <= 1 and r > 0


def cmake_build():
    """The page's rebuild command, as the Build with CMake block has it."""
    build = next(line for _, lang, text in blocks() if lang == "sh" for line in text.splitlines()
                 if line.startswith("cmake --build ~/fog/build"))
    return subprocess.run(["bash", "-c", ". %s\n%s" % (shlex.quote(STATE), build)], cwd=HOME, env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def hot_reload(text):
    originals = {n: open(fog(n)).read() for n in ("fog.c", "fog.comp")}
    store = "imageStore(out_tinted, p, vec4(c.rgb * tint, c.a));"
    # the C pass pushes its parameters by name: the edit sets strength itself
    strength = "    (void)vrg_dispatch(pass, cmd, &dispatches[0]);"
    if not (check(store in originals["fog.comp"], "fog.comp has no line '%s' to edit" % store) and
            check(strength in originals["fog.c"], "fog.c has no line '%s' to edit" % strength)):
        return
    w = Watch(text)
    try:
        check(not uniform(w.frame(1), lambda *c: True), "hot reload: the scaffolded pass's first frames are uniform, not the terrain")

        # the shader: the tint alone, so every pixel is the tint (1, 0.68, 0.44)
        k = w.settle()
        save(fog("fog.comp"), originals["fog.comp"].replace(store, "imageStore(out_tinted, p, vec4(tint, 1.0));"))
        check(w.first(k, lambda im: uniform(im, warm_red)) is not None,
              "hot reload: the edited fog.comp (the tint alone) did not show within %d frames of frame %d" % (BOUND, k))

        # the plugin: strength 0 makes the tint white; the reload is timed
        # from the new fog.so, not from the graph file (an hour old here)
        k = w.settle()
        os.utime(fog("fog.ini"), (time.time() - 3600, time.time() - 3600))
        before = len(w.reloads())
        save(fog("fog.c"), originals["fog.c"].replace(strength, '    vrg_push_float(pass, "strength", 0.0f);\n' + strength))
        started = time.time()
        built = cmake_build()
        check(built.returncode == 0, "hot reload: cmake --build of the edited fog.c failed:\n%s" % built.stdout[-3000:])
        check(w.wait_stderr(r"reloaded, \d+ ms from save to frame", before + 1), "hot reload: the rebuilt fog.so was not reported as reloaded")
        took = (time.time() - started) * 1000
        ms = w.reloads()[-1] if len(w.reloads()) > before else -1
        check(0 <= ms <= took + 1000, "hot reload: the reload took %d ms from save to frame, but the build began only %.0f ms ago: "
              "not timed from fog.so" % (ms, took))
        check(w.first(w.latest(), lambda im: uniform(im, grey)) is not None, "hot reload: the rebuilt fog.c (strength 0) did not show")

        # a broken shader: reported at its line, the last good version runs on
        k = w.settle()
        broken = originals["fog.comp"].replace(store, "this is not glsl;")
        line = broken.splitlines().index("    this is not glsl;") + 1
        save(fog("fog.comp"), broken)
        check(w.wait_stderr(re.escape(fog("fog.comp")) + r":%d: error\[VRG-E063\]" % line, 1),
              "hot reload: the broken fog.comp was not reported at fog.comp:%d" % line)
        k = w.latest()
        check(all(uniform(w.frame(j), grey) for j in range(k + 1, k + 4)), "hot reload: the last good version stopped after the broken shader")

        # a build that fails: no new fog.so, the running version stays
        save(fog("fog.c"), originals["fog.c"].replace(strength, '    vrg_push_float(pass, "strength", );\n' + strength))
        check(cmake_build().returncode != 0, "hot reload: fog.c with a syntax error built")
        k = w.latest()
        check(all(uniform(w.frame(j), grey) for j in range(k + 1, k + 4)), "hot reload: the running version changed after a failed build")
        check(w.proc.poll() is None, "hot reload: voxrg stopped")
    finally:
        w.stop()
        for name, body in originals.items():
            save(fog(name), body)
    check(cmake_build().returncode == 0, "the restored fog.c does not build")


def compared_graph(out):
    """The compare block compares a graph that runs the new pass: fog is in
    raw-fog's timed passes (culled passes are not), its frames differ from
    raw's, and no pass was culled (the warning every command prints)."""
    csv = open(fog("compare/metrics.csv")).read()
    check(",raw-fog," in csv or "\nraw-fog," in csv, "compare: no raw-fog rows in metrics.csv:\n" + csv[:2000])
    check(os.path.exists(fog("compare/report.html")), "compare: no report.html")
    check("VRG-W008" not in out and "is culled" not in out, "compare: a pass is culled:\n" + out[-3000:])
    cands = {c["name"]: c for c in json.load(open(fog("compare/metrics.json")))["candidates"]}
    if not check("raw-fog" in cands and "raw" in cands, "compare: candidates %s, want raw-fog and raw" % sorted(cands)):
        return
    check("fog" in [p["name"] for p in cands["raw-fog"]["passes"]],
          "compare: raw-fog ran no pass 'fog' (culled?): passes %s" % [p["name"] for p in cands["raw-fog"]["passes"]])
    check(cands["raw-fog"]["summary"]["psnr"] != cands["raw"]["summary"]["psnr"],
          "compare: raw-fog scores as raw does (PSNR %s): the fog pass changed nothing" % cands["raw"]["summary"]["psnr"])


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(HOME)
    save(STATE, "")
    found = blocks()
    sh = [(h, t) for h, lang, t in found if lang == "sh"]
    headings = [h for h, _ in sh]
    for want in ("Install", "Scaffold", "Build with CMake", "Build with pkg-config", "Run", "Hot reload",
                 "Compare against the shipped passes"):
        check(want in headings, "docs/out-of-tree.md has no sh block under '## %s'" % want)
    try:
        for heading, text in sh:
            print("--", heading, flush=True)
            if heading == "Install":
                run_block(heading, text, SRC, INSTALL_SHIM)
            elif heading == "Hot reload":
                hot_reload(text)
            else:
                out = run_block(heading, text, HOME)
            if heading == "Scaffold":
                # the CMake block the page shows is what new-pass wrote
                shown = next(t for h, lang, t in found if lang == "cmake")
                written = open(fog("CMakeLists.txt")).read()
                for line in shown.splitlines():
                    check(line in written.splitlines(), "the page's CMakeLists.txt line '%s' is not in the scaffold's" % line)
            if heading == "Run":
                check("file: %s" % fog("build/fog.so") in out, "voxrg plugins fog did not find ~/fog/build/fog.so:\n" + out)
                check(os.path.getsize(fog("out/ldr.png")) > 0, "voxrg render wrote no ~/fog/out/ldr.png")
            if heading.startswith("Compare"):
                compared_graph(out)
    except (RuntimeError, OSError, StopIteration) as e:
        check(False, str(e))
    print("out-of-tree docs: %s" % ("FAILED (%d)" % len(failures) if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
