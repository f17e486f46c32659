#!/usr/bin/env python3
"""Files that are not what voxrg expects, where a user can put them:
- a FIFO where a file is read (a vox model, an edit journal, a cached
  reference frame): an error naming it and a non-zero exit, at once (each
  run has a time limit: an open that blocks fails the case instead of
  hanging the suite);
- compare at a size below SSIM's window: refused, naming --size and the
  minimum (no -1 reported as a score);
- compare with a cache folder it cannot write: one error, before any work;
- compare whose frame cannot be written: the write is the error, naming the
  file and the reason, not a "failed to render";
- voxrg run (under Xvfb, driven with xdotool; skipped without them): the
  edit journal deleted while editing, the graph file a FIFO when saved.
Usage: test_hostile_files.py VOXRG TESTS_DIR OUT_DIR CASE"""
import os
import re
import shutil
import subprocess
import sys
import time

VOXRG, TESTS, OUT, CASE = sys.argv[1:5]
LIMIT_S = 120
failures = []

GRAPH = """[graph]
name   = {name}
output = view
width  = {width}
height = 18

[scene]
{scene}

[pass view]
plugin    = world_debug
in.world  = world
in.frame  = frame
out.color = view
"""


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def voxrg(*args):
    """rc, stderr; rc None when the run did not end within LIMIT_S."""
    try:
        p = subprocess.run([VOXRG, *args], cwd=OUT, capture_output=True, text=True, timeout=LIMIT_S)
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        return None, ""


def refused(what, rc, stderr, *patterns):
    check(rc is not None, f"{what}: blocked ({LIMIT_S} s)")
    check(rc not in (None, 0), f"{what}: exit {rc}")
    for p in patterns:
        check(re.search(p, stderr), f"{what}: no '{p}' in:\n{stderr}")


def write(name, text):
    with open(os.path.join(OUT, name), "w") as f:
        f.write(text)


def fifo(name):
    os.mkfifo(os.path.join(OUT, name))


def fifo_vox():
    write("vox.ini", GRAPH.format(name="fifo_vox", width=32, scene="plugin = vox\nfile   = model.vox"))
    fifo("model.vox")
    rc, err = voxrg("check", "--no-device", "vox.ini")
    refused("a FIFO as the vox file", rc, err, r"vox\.ini:\d+: error.*model\.vox: not a regular file")


def fifo_journal():
    write("terrain.ini", GRAPH.format(name="fifo_journal", width=32, scene="plugin  = terrain\nseed    = 7\nradius  = 1\nthreads = 1"))
    fifo("terrain.ini.edits")
    rc, err = voxrg("check", "terrain.ini")
    refused("a FIFO as the edit journal", rc, err, r"terrain\.ini\.edits: cannot open: not a regular file")


def compare(*args, cache="cache", out="out"):
    shutil.copy(os.path.join(TESTS, "graphs", "blocks_wall.ini"), OUT)
    return voxrg("compare", "blocks_wall.ini", "--reference", "blocks_wall.ini", "--frames", "2", "--out", out, "--cache", cache, *args)


def fifo_reference():
    rc, err = compare("--size", "32x18")
    check(rc == 0, f"the first compare (filling the cache): exit {rc}\n{err}")
    frames = sorted(f for f in os.listdir(os.path.join(OUT, "cache")) if f.endswith(".frame"))
    check(len(frames) == 2, f"cached frames: {frames}")
    entry = os.path.join("cache", frames[0])
    os.unlink(os.path.join(OUT, entry))
    fifo(entry)
    rc, err = compare("--size", "32x18")
    refused("a FIFO as a cached reference frame", rc, err, re.escape(entry) + r" is not a regular file")


def compare_size():
    rc, err = compare("--size", "10x18")
    refused("--size 10x18", rc, err, r"--size 10x18: compare needs at least 11x11 pixels")
    check(rc == 2, f"--size 10x18 is a usage error: exit {rc}")
    write("narrow.ini", GRAPH.format(name="narrow", width=8, scene="plugin = blocks\nbox    = 0 0 0 7 0 7 white"))
    rc, err = voxrg("compare", "narrow.ini", "--reference", "narrow.ini", "--frames", "2", "--out", "out", "--cache", "cache")
    refused("a graph 8 pixels wide", rc, err, r"render 8x18: compare needs at least 11x11 pixels.*set --size")
    check(not os.path.exists(os.path.join(OUT, "out", "metrics.json")), "a report was written")


def compare_cache():
    # a folder no file can be created in, whoever runs the test (root too)
    cache = "/proc/1"
    rc, err = compare("--size", "32x18", cache=cache)
    refused("an unwritable --cache", rc, err, r"error: cannot write in " + re.escape(cache))
    check(len(re.findall(r"error", err)) == 1, f"one error, before any work:\n{err}")


def compare_out_write():
    # the candidate's first frame cannot be written: a folder holds its name
    os.makedirs(os.path.join(OUT, "out", "frames", "blocks_wall-00000.png"))
    rc, err = compare("--size", "32x18")
    refused("a frame that cannot be written", rc, err, r"cannot write out/frames/blocks_wall-00000\.png: Is a directory")
    check("failed to render" not in err, f"a write failure reported as a failed render:\n{err}")


def run_window():
    """voxrg run, driven under Xvfb: the journal deleted while editing (the
    next edit writes it again, whole, and says so), then Ctrl+S after the
    graph file became a FIFO (an error naming it; the window goes on and
    closes on Escape)."""
    if not shutil.which("Xvfb") or not shutil.which("xdotool"):
        print("skip: Xvfb or xdotool not installed (scripts/setup.sh installs them)")
        sys.exit(77)
    write("terrain.ini", GRAPH.format(name="window", width=160, scene="plugin  = terrain\nseed    = 7\nradius  = 1\nthreads = 2")
          .replace("height = 18", "height = 100") + "\n[camera]\nposition = 8 44 8\nyaw      = 30\npitch    = -50\n")
    display = os.path.join(OUT, "xvfb.display")
    with open(display, "w") as f:
        xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(f.fileno()), "-screen", "0", "640x480x24", "-nolisten", "tcp"],
                                pass_fds=(f.fileno(),), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    log = os.path.join(OUT, "run.stderr")
    proc = None
    try:
        for _ in range(100):
            if open(display).read().strip():
                break
            time.sleep(0.1)
        env = dict(os.environ, DISPLAY=":" + open(display).read().split()[0])
        proc = subprocess.Popen([VOXRG, "run", "terrain.ini", "--window", "160x100", "--scale", "1"], cwd=OUT, env=env,
                                stdout=subprocess.DEVNULL, stderr=open(log, "w"))

        def xdo(*args):
            return subprocess.run(["xdotool", *args], env=env, capture_output=True, text=True, timeout=60).stdout

        def said(pattern, count=1, seconds=60):
            """Waits for the count-th match of pattern on voxrg's stderr."""
            end = time.time() + seconds
            while time.time() < end and proc.poll() is None:
                if len(re.findall(pattern, open(log).read())) >= count:
                    return True
                time.sleep(0.1)
            return check(len(re.findall(pattern, open(log).read())) >= count, f"no '{pattern}' x{count} from voxrg run:\n{open(log).read()[-3000:]}")

        wid = xdo("search", "--sync", "--name", "^voxrg").split()[0]
        said(r"device")
        xdo("windowfocus", "--sync", wid)
        xdo("mousemove", "--window", wid, "80", "50")
        journal = os.path.join(OUT, "terrain.ini.edits")
        def click():
            """One click, and its "edit:" line (each waited for: a slow run must not take two clicks as one)."""
            before = open(log).read().count("edit:")
            xdo("click", "1")
            said(r"edit:.*\n", before + 1)
            return open(log).read().split("edit:")[before + 1]

        for _ in range(100):  # until streaming has put a block under the cursor
            if click().startswith(" removed"):
                break
            time.sleep(0.3)
        os.unlink(journal)
        said_again = click()
        check(re.match(r" removed .*; .*terrain\.ini\.edits was deleted or moved away: written again with all 2 records", said_again),
              f"the edit after the journal was deleted:{said_again}")
        data = open(journal, "rb").read() if os.path.exists(journal) else b""
        header = 8 + 4 + int.from_bytes(data[8:12], "little") + 4 if len(data) >= 12 else 0
        check(header and len(data) == header + 2 * 20, f"the journal at its path holds {len(data)} bytes, not its header and 2 records")
        xdo("key", "m", "Down", "Right")
        os.unlink(os.path.join(OUT, "terrain.ini"))
        fifo("terrain.ini")
        xdo("key", "ctrl+s")
        said(r"error: cannot read terrain\.ini: not a regular file")
        xdo("key", "Escape")
        try:
            rc = proc.wait(timeout=LIMIT_S)
            check(rc == 0, f"voxrg run exited {rc}")
        except subprocess.TimeoutExpired:
            check(False, "the window froze: no exit after Escape")
    finally:
        if proc and proc.poll() is None:
            proc.kill()
        xvfb.kill()
        xvfb.wait()


CASES = (fifo_vox, fifo_journal, fifo_reference, compare_size, compare_cache, compare_out_write, run_window)


def main():
    cases = {c.__name__: c for c in CASES}
    if CASE not in cases:
        sys.exit(f"usage: test_hostile_files.py VOXRG TESTS_DIR OUT_DIR {'|'.join(cases)}")
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    cases[CASE]()
    print("FAILED" if failures else "ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
